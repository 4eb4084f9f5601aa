#!/usr/bin/env python3
"""Fixed time steps against the gap step (Time stepping/Gap step fraction).

Runs one scene with fixed steps and with gap steps (a large base step cut
by the gaps), one run at a time, and compares every run with the run at
the smallest fixed step: largest |dX|/a over particles and common times
(linear interpolation in time), the smallest and the median gap, the
number of steps, the range of dt and the wall time. Prints a Markdown
table. See doc/results.md, "A step that follows the gaps".

    contrib/benchmarks/gap_step.py prm/two_particles_2d_cut.prm \\
        --fixed 0.05,0.025 --gap 0.4,0.2 --base 0.2 --floor 1e-4 --work /tmp/gs

--set "Subsection/Entry=value" overrides any entry in every run (repeat it).
--reuse keeps runs that finished before.
"""

import argparse
import csv
import os
import statistics
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(REPO, "contrib"))
from convergence_analysis import (  # noqa: E402
    QUIET_RUN, Geometry, max_trajectory_difference, parse_overrides, parse_prm, read_particles, read_text,
    run_in_folder)


class Run:
    """One fidus run of the comparison, and what it wrote."""

    def __init__(self, label, overrides, folder):
        self.label = label
        self.overrides = overrides
        self.folder = folder
        self.output = os.path.join(folder, "output")

    def load(self):
        self.particles = read_particles(os.path.join(self.output, "particles.csv"))
        self.geometry = Geometry(parse_prm(read_text(os.path.join(self.output, "used_parameters.prm"))))
        for t in self.particles.values():
            self.geometry.unwrap(t)
        with open(os.path.join(self.output, "statistics.csv"), newline="") as f:
            self.stats = list(csv.DictReader(f))[1:]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("prm")
    p.add_argument("--fixed", default="0.05,0.025", help="fixed steps; the smallest is the reference")
    p.add_argument("--gap", default="0.4,0.2", help="gap step fractions")
    p.add_argument("--base", default="0.2", help="Time step of the gap-step runs")
    p.add_argument("--floor", default="1e-3", help="Gap step floor of the gap-step runs")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE")
    p.add_argument("--work", default="gap_step_runs")
    p.add_argument("--reuse", action="store_true")
    p.add_argument("--fidus", default=os.environ.get("FIDUS", os.path.join(REPO, "build-release", "fidus")))
    args = p.parse_args()

    common = QUIET_RUN + parse_overrides(args.set, "gap_step.py")
    fixed = sorted((float(x) for x in args.fixed.split(",")), reverse=True)
    runs = [Run(f"fixed {dt:g}", common + [("Time stepping/Time step", f"{dt:g}"),
                                           ("Time stepping/Gap step fraction", "0")],
                os.path.join(args.work, f"fixed_{dt:g}")) for dt in fixed]
    runs += [Run(f"Δt {args.base}, gap step f = {f}, floor {args.floor}",
                 common + [("Time stepping/Time step", args.base),
                           ("Time stepping/Gap step fraction", f),
                           ("Time stepping/Gap step floor", args.floor)],
                 os.path.join(args.work, f"gap_{f}")) for f in args.gap.split(",")]

    with open(args.prm) as f:
        prm_text = f.read()
    for r in runs:
        run_in_folder(args.fidus, prm_text, r.overrides, r.folder, args.reuse, "gap_step.py", r.label)

    for r in runs:
        r.load()
    ref = runs[len(fixed) - 1]
    a = min(t.radius for t in ref.particles.values())
    print(f"Reference: {ref.label}. Gaps over the smallest radius a = {a:g}.\n")
    print("| run | steps | Δt min / mean / max | gap / a, min / median | max \\|ΔX\\|/a from the reference | wall s |")
    print("|---|---|---|---|---|---|")
    for r in runs:
        dts = [float(s["dt"]) for s in r.stats]
        gaps = [float(s["min_gap"]) / a for s in r.stats]
        d = max_trajectory_difference(r, ref) if r is not ref else None
        diff = "–" if d is None else f"{d[0]:.4f}"
        print(f"| {r.label} | {len(dts)} | {min(dts):.3g} / {statistics.mean(dts):.3g} / {max(dts):.3g} "
              f"| {min(gaps):.3g} / {statistics.median(gaps):.3g} | {diff} | {float(r.stats[-1]['wall_seconds']):.0f} |")


if __name__ == "__main__":
    main()
