#!/usr/bin/env python3
"""
pair_invariant.py -- where a fidus run of two equal spheres in simple shear
(rate 1, flow along x, gradient along y, both centres in one shear plane)
leaves Batchelor & Green's family of exact trajectories.

Two free spheres in unbounded simple shear keep a first integral of their
relative motion (batchelor_green.py, FirstIntegral): with r the centre
distance over a and s the square of the sine of the angle of the line of
centres from the flow,

    q(r) s - J(r) = y_inf^2,

y_inf the offset (over a) far upstream. Each trajectory has its own y_inf
and its own closest approach r_min(y_inf). This script prints, along the
run, the y_inf^2 of the trajectory through each step's configuration and
the smallest gap that exact trajectory reaches. On an exact passage both
stay constant; where they drift, that part of the run (the far field, the
box's walls, the time step near contact) moves the pair onto another
trajectory, and the smallest gap it will reach moves with it.

Usage:  python3 pair_invariant.py OUTPUT_DIR [RADIUS [INTERVAL]]
        (defaults: radius 0.05; a row every INTERVAL = 0.5 time units, and
        every step whose gap is below 0.6 a). Standard library only.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from batchelor_green import FirstIntegral, Mobility  # noqa: E402
from pair_rates import pair_steps  # noqa: E402


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        sys.exit(1)
    out = sys.argv[1]
    a = float(sys.argv[2]) if len(sys.argv) > 2 else 0.05
    interval = float(sys.argv[3]) if len(sys.argv) > 3 else 0.5
    first_integral = FirstIntegral(Mobility(), N=4000)
    print("| t | gap / a | angle ° | y_inf² | closest approach of that "
          "trajectory, gap / a |")
    print("|---|---|---|---|---|")
    next_time = 0.
    for p in pair_steps(out).values():
        x = [[float(p[i][k]) for k in "xyz"] for i in (0, 1)]
        d = [x[1][k] - x[0][k] for k in range(3)]
        r = math.sqrt(sum(c * c for c in d)) / a
        in_plane = math.hypot(d[0], d[1])
        s = (d[1] / in_plane) ** 2
        t = float(p[0]["time"])
        if t + 1e-9 < next_time and r - 2 > 0.6:
            continue
        next_time = max(next_time, math.floor(t / interval + 1e-9) * interval
                        + interval)
        invariant = first_integral.invariant(r, s)
        closest = (first_integral.rmin(invariant) - 2 if invariant > 0
                   else float("nan"))
        print("| %.3f | %.4g | %.1f | %.5f | %.3e |"
              % (t, r - 2, math.degrees(math.atan2(d[1], d[0])), invariant,
                 closest))


if __name__ == "__main__":
    main()
