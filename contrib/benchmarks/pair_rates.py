#!/usr/bin/env python3
"""
pair_rates.py -- a fidus run of two equal spheres in simple shear (rate 1,
flow along x, gradient along y, both centres in one shear plane), step by
step against Batchelor & Green's exact relative motion at the same
configuration (batchelor_green.py):

    dr/dt  = r (1 - A(r)) sin th cos th,   dth/dt = -(sin^2 th + B(r)/2 cos 2th)

For each step whose gap lies between GAP_MIN and GAP_MAX (in radii), it
prints the gap and the angle at the middle of the step, fidus's closing and
turning rates over the step (from the positions in particles.csv, so every
stage of the step is in them: extrapolation, lubrication, contacts), the
exact rates there and their ratios, and the step's lubricated and active
contact pairs from statistics.csv. A ratio of the closing rate above 1
brings the pair closer than the exact passage; the trajectory's own error
(a lag in time, the box's walls) does not enter, since each step is
compared at its own configuration.

The columns "solved" give the closing rate of the velocities the fluid
solve returned at the step's start (particles.csv's ux, uy, uz), against
the exact one at that configuration: the hydrodynamics alone, before the
time scheme (AB2's extrapolation, the step's chord) and the contact
projection act. Where "over the step" and "solved" differ, the time
step is the error; where both differ alike, the flow solve is.

Usage:  python3 pair_rates.py OUTPUT_DIR [RADIUS [GAP_MIN [GAP_MAX]]]
        (defaults: radius 0.05, gaps 1e-3 .. 0.5). Standard library only.
"""
import csv
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from batchelor_green import Mobility  # noqa: E402


def pair_steps(out):
    """The rows of particles.csv in @p out by step, {step: {id: row}}, for
    the steps that hold both spheres (0 and 1), in order of the step."""
    by_step = {}
    for r in csv.DictReader(open(os.path.join(out, "particles.csv"))):
        by_step.setdefault(int(r["step"]), {})[int(r["id"])] = r
    return {s: by_step[s] for s in sorted(by_step)
            if 0 in by_step[s] and 1 in by_step[s]}


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        sys.exit(1)
    out = sys.argv[1]
    a = float(sys.argv[2]) if len(sys.argv) > 2 else 0.05
    gap_min = float(sys.argv[3]) if len(sys.argv) > 3 else 1e-3
    gap_max = float(sys.argv[4]) if len(sys.argv) > 4 else 0.5
    stats = {int(r["step"]): r for r in
             csv.DictReader(open(os.path.join(out, "statistics.csv")))}
    by_step = pair_steps(out)
    steps = list(by_step)
    if len(steps) < 2:
        sys.exit("pair_rates.py: %s has fewer than two steps with both "
                 "particles (set 'Particle output interval = 1')" % out)

    def geometry(s):
        p = by_step[s]
        x = [[float(p[i][k]) for k in "xyz"] for i in (0, 1)]
        return (math.dist(x[0], x[1]) / a,
                math.atan2(x[1][1] - x[0][1], x[1][0] - x[0][0]),
                float(p[0]["time"]))

    def solved_closing(s):
        """(u1 - u0) . e / a at step s's start, e from sphere 0 to 1."""
        p = by_step[s]
        x = [[float(p[i][k]) for k in "xyz"] for i in (0, 1)]
        u = [[float(p[i][k]) for k in ("ux", "uy", "uz")] for i in (0, 1)]
        d = [x[1][k] - x[0][k] for k in range(3)]
        n = math.sqrt(sum(c * c for c in d))
        return sum((u[1][k] - u[0][k]) * d[k] for k in range(3)) / (n * a)

    mob = Mobility()
    print("| t | gap / a | angle ° | closing rate over the step | exact | "
          "ratio | solved at the start | exact | ratio | "
          "turning rate | exact | ratio | lubricated pairs | active contacts |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    closing_ratios, solved_ratios = [], []
    for s0, s1 in zip(steps, steps[1:]):
        r0, th0, t0 = geometry(s0)
        r1, th1, t1 = geometry(s1)
        if t1 <= t0:
            continue
        r, th = 0.5 * (r0 + r1), 0.5 * (th0 + th1)
        if not gap_min <= r - 2 <= gap_max:
            continue
        A, B = mob.AB(r)
        exact_r = r * (1 - A) * math.sin(th) * math.cos(th)
        exact_th = -(math.sin(th) ** 2 + 0.5 * B * math.cos(2 * th))
        rate_r = (r1 - r0) / (t1 - t0)
        dth = math.remainder(th1 - th0, 2 * math.pi)
        rate_th = dth / (t1 - t0)
        A0, _ = mob.AB(r0)
        exact_0 = r0 * (1 - A0) * math.sin(th0) * math.cos(th0)
        solved_0 = solved_closing(s0)
        st = stats.get(s0, {})
        ratio_r = rate_r / exact_r if exact_r != 0 else float("nan")
        ratio_0 = solved_0 / exact_0 if exact_0 != 0 else float("nan")
        if exact_r < 0 and int(st.get("active_contacts", 0) or 0) == 0:
            closing_ratios.append(ratio_r)
            if exact_0 < 0:
                solved_ratios.append(ratio_0)
        print("| %.3f | %.4g | %.1f | %.4g | %.4g | %.3f | %.4g | %.4g | %.3f "
              "| %.4g | %.4g | %.3f | %s | %s |"
              % (t0, r - 2, math.degrees(th), rate_r, exact_r, ratio_r,
                 solved_0, exact_0, ratio_0, rate_th, exact_th,
                 rate_th / exact_th, st.get("lubrication_pairs", "-"),
                 st.get("active_contacts", "-")))
    if closing_ratios:
        closing_ratios.sort()
        print("\nclosing steps without a contact: %d, closing-rate ratio "
              "median %.3f, range %.3f .. %.3f"
              % (len(closing_ratios), closing_ratios[len(closing_ratios) // 2],
                 closing_ratios[0], closing_ratios[-1]))
    if solved_ratios:
        solved_ratios.sort()
        print("solved closing rate at the steps' starts: ratio median %.3f, "
              "range %.3f .. %.3f"
              % (solved_ratios[len(solved_ratios) // 2], solved_ratios[0],
                 solved_ratios[-1]))


if __name__ == "__main__":
    main()
