#!/usr/bin/env python3
"""The relative viscosity, N1 and the particle pressure against the fraction.

Runs one steady-shear scene (a prm with a particle generator) at several
values of Particles/Generator/Fraction, one run at a time, and prints a
Markdown table of the means over a window of strain with their standard
errors (batch means over five consecutive batches of rows), the contact and
lubrication parts, the value at step 0 (the hydrodynamic start, before any
contact or lubrication acts) and the dilute limit 1 + 2 phi (discs) or
1 + 2.5 phi (spheres) for orientation. See doc/rheology.md, "The viscosity
against the area fraction".

    contrib/benchmarks/viscosity_curve.py prm/rheology_steady_shear_2d.prm \\
        --fractions 0.1,0.2,0.3,0.4,0.5 \\
        --set "Fluid/Lubrication correction=true" --work /tmp/vc

--set "Subsection/Entry=value" overrides any entry in every run (repeat it).
--window "0.5,1.5" is the strain window (the time at shear rate 1).
--reuse keeps runs that finished before. --np N runs each on N MPI ranks.
"""

import argparse
import csv
import math
import os
import statistics
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(REPO, "contrib"))
from convergence_analysis import QUIET_RUN, parse_overrides, parse_prm, prm_with, run_in_folder  # noqa: E402


def mean_and_error(values, batches=5):
    """Mean, and its standard error from the means of consecutive batches.

    The rows of one run are correlated over a strain of order one; batch
    means of a fifth of the window each are closer to independent than the
    rows are. With fewer than two rows per batch the error is NaN.
    """
    m = statistics.mean(values)
    size = len(values) // batches
    if size < 2:
        return m, math.nan
    means = [statistics.mean(values[k * size:(k + 1) * size]) for k in range(batches)]
    return m, statistics.stdev(means) / math.sqrt(batches)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("prm")
    p.add_argument("--fractions", default="0.1,0.2,0.3,0.4", help="values of Particles/Generator/Fraction")
    p.add_argument("--window", default="0.5,1.5", help="strain window of the means: first,last")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE")
    p.add_argument("--work", default="viscosity_curve_runs")
    p.add_argument("--reuse", action="store_true")
    p.add_argument("--np", type=int, default=1, help="MPI ranks per run")
    p.add_argument("--fidus", default=os.environ.get("FIDUS", os.path.join(REPO, "build-release", "fidus")))
    args = p.parse_args()

    common = QUIET_RUN + parse_overrides(args.set, "viscosity_curve.py")
    try:
        fractions = [float(x) for x in args.fractions.split(",")]
        first, last = (float(x) for x in args.window.split(","))
    except ValueError:
        sys.exit(f"viscosity_curve.py: --fractions '{args.fractions}' and --window '{args.window}' "
                 "must be comma-separated numbers")
    if not all(0. < f < 1. for f in fractions) or not first < last:
        sys.exit("viscosity_curve.py: fractions must lie in (0, 1) and the window must be first < last")

    with open(args.prm) as f:
        prm_text = f.read()
    dim = int(parse_prm(prm_text + "\n" + prm_with("", common, "x")).get("Dimension", "2"))
    rows = []
    for phi in fractions:
        folder = os.path.join(args.work, f"fraction_{phi:g}")
        output = os.path.join(folder, "output")
        seconds = run_in_folder(args.fidus, prm_text, common + [("Particles/Generator/Fraction", f"{phi:g}")],
                                folder, args.reuse, "viscosity_curve.py", f"fraction {phi:g}", args.np)
        with open(os.path.join(output, "statistics.csv"), newline="") as f:
            stats = list(csv.DictReader(f))
        with open(os.path.join(output, "particles.csv"), newline="") as f:
            first_step = [r for r in csv.DictReader(f) if r["step"] == "0"]
        window = [s for s in stats if first - 1e-9 <= float(s["time"]) <= last + 1e-9]
        if len(window) < 2:
            sys.exit(f"viscosity_curve.py: fraction {phi:g} has {len(window)} rows in the window "
                     f"{first:g}–{last:g}; is End time long enough?")

        def col(name):
            return [float(s[name]) for s in window]

        a_min = min(float(r["radius"]) for r in first_step)
        rows.append({
            "phi": phi, "n": len(first_step), "steps": len(stats) - 1, "rows": len(window),
            "eta": mean_and_error(col("relative_viscosity")),
            "contact": statistics.mean(col("contact_relative_viscosity")),
            "lubrication": statistics.mean(col("lubrication_relative_viscosity")),
            "n1": mean_and_error(col("normal_stress_difference_1")),
            "pi": mean_and_error(col("particle_pressure")),
            "start": float(stats[0]["relative_viscosity"]),
            "gap": min(float(s["min_gap"]) for s in stats) / a_min,
            "uzawa": max(int(float(s["uzawa_iterations"])) for s in stats),
            "wall": seconds if seconds is not None else float(stats[-1]["wall_seconds"]),
        })

    dilute = 2. if dim == 2 else 2.5
    print(f"Means over strain {first:g}–{last:g}, over η_f γ̇, ± the standard error of five batch means.\n")
    print(f"| fraction | particles | steps (rows) | η_r | contact part | lubrication part | N1 | Π "
          f"| η_r at step 0 | 1 + {dilute:g}φ | smallest gap / a_min | Uzawa max | wall s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        def pm(v):
            return f"{v[0]:.3f} ± {v[1]:.3f}"
        print(f"| {r['phi']:g} | {r['n']} | {r['steps']} ({r['rows']}) | {pm(r['eta'])} | {r['contact']:.3f} "
              f"| {r['lubrication']:.3f} | {pm(r['n1'])} | {pm(r['pi'])} | {r['start']:.3f} "
              f"| {1 + dilute * r['phi']:.3f} | {r['gap']:.2g} | {r['uzawa']} | {r['wall']:.0f} |")


if __name__ == "__main__":
    main()
