#!/usr/bin/env python3
"""The sub-grid correction's stress against a resolved reference, one
configuration at a time, over an ensemble of sheared configurations.

A time-averaged stress does not separate a method's error from the noise:
two runs' configurations part after a few steps, and N1 and the particle
pressure of a dense suspension swing by more than their mean over a strain
unit. Here every method sees the same positions:

1. A source run: the fictitious-domain prm with `Fluid/Lubrication
   correction = true` sheared to the last strain of --strains; its
   positions at each strain of --strains (nearest step) are the ensemble,
   configurations with the microstructure that shear builds.
2. At each configuration, one step of --dt (a strain small enough that the
   positions hardly move) of the reference prm (the cut finite element,
   every gap resolved) and of the fictitious domain on uniform meshes at
   each of --levels with the correction, for each --variant.
3. The last row of each run's statistics.csv (the step's corrected
   stress), against the reference at the same configuration: the mean
   error (bias) and its scatter (standard deviation over the ensemble) of
   eta_r (relative), N1, in 3D N2, and the particle pressure Pi (over
   eta_f gamma).
   "mesh alone" is the first row of the first variant (the fictitious
   domain's solve at the configuration, before any correction; not shown
   for a cut-element prm, which solves its correction with the flow).

    contrib/benchmarks/dense_configurations.py prm/rheology_steady_shear_2d.prm \\
        prm/rheology_steady_shear_2d_cut.prm --levels 6,7,8 \\
        --variant "no tangential=Fluid/Lubrication tangential terms=false" \\
        --work /tmp/dense_configurations

--variant "name=Key=value;Key=value" adds a set of overrides (repeat it;
the default variant, the prm's own settings, always runs). --from WORK
takes the configurations and references of an earlier run, so that a
second fluid (for example the cut element with the correction:
the reference prm first, with --set entries) sees the same ones. --set
"Key=value" overrides every run, the source included (for example
"Particles/Generator/Fraction=0.5"). --reuse keeps runs that finished. --np N runs the source and the
fictitious domain on N ranks (the cut element runs on one).
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

PROG = "dense_configurations.py"
QUANTITIES = (("relative_viscosity", "η_r"), ("normal_stress_difference_1", "N1"),
              ("particle_pressure", "Π"))
# In 3D N2 is not -N1/2 (the 2D plane-strain rule), so it is shown too.
QUANTITIES_3D = QUANTITIES[:2] + (("normal_stress_difference_2", "N2"),) + QUANTITIES[2:]


def run(fidus, prm_text, overrides, folder, reuse, np_ranks=1):
    """Run fidus in folder (run_in_folder()); the rows of its
    statistics.csv."""
    run_in_folder(fidus, prm_text, overrides, folder, reuse, PROG, os.path.basename(folder), np_ranks)
    with open(os.path.join(folder, "output", "statistics.csv"), newline="") as f:
        return list(csv.DictReader(f))


def write_configurations(particles_csv, steps, work, dim, walls):
    """One positions file per step ('x y [z] radius' per particle). A
    particle that the contact model holds on a wall (gap zero to round-off)
    is moved inside by 1e-8 of its radius: fidus refuses a particle that
    cuts the box."""
    rows = {}
    with open(particles_csv, newline="") as f:
        for r in csv.DictReader(f):
            if int(r["step"]) in steps:
                rows.setdefault(int(r["step"]), []).append(r)
    files = []
    for step in steps:
        path = os.path.abspath(os.path.join(work, f"configuration_{step}.txt"))
        with open(path, "w") as f:
            for r in rows[step]:
                a = float(r["radius"])
                y = min(max(float(r["y"]), walls[0] + a * (1. + 1e-8)), walls[1] - a * (1. + 1e-8))
                coords = [r["x"], repr(y), r["z"]][:dim]
                f.write(" ".join(coords + [r["radius"]]) + "\n")
        files.append(path)
    return files


def particles(folder, step):
    """{id: row} of one step of a run's particles.csv."""
    with open(os.path.join(folder, "output", "particles.csv"), newline="") as f:
        return {r["id"]: r for r in csv.DictReader(f) if int(r["step"]) == step}


def closing_slope(runs, references, periods, dim, gap, moved=True):
    """Least-squares slope of the close pairs' normal relative speeds
    against the reference's: pairs closer than gap (over the smaller
    radius) at the reference's positions, the velocities the particles
    moved with (or, with moved=False, the fluid's own at the
    configuration), minimum images across the periodic lengths."""
    num = den = 0.
    axes = "xyz"[:dim]
    for run_p, ref_p in zip(runs, references):
        ids = sorted(ref_p, key=int)
        pos = {i: [float(ref_p[i][c]) for c in axes] for i in ids}
        for m, i in enumerate(ids):
            for j in ids[m + 1:]:
                d = [pos[j][c] - pos[i][c] for c in range(dim)]
                for c, length in enumerate(periods):
                    if length:
                        d[c] -= length * round(d[c] / length)
                r = math.sqrt(sum(x * x for x in d))
                ai, aj = float(ref_p[i]["radius"]), float(ref_p[j]["radius"])
                if r - ai - aj > gap * min(ai, aj):
                    continue
                n = [x / r for x in d]
                key = "moved_u" if moved else "u"
                v = sum((float(run_p[j][key + c]) - float(run_p[i][key + c])) * n[k] for k, c in enumerate(axes))
                w = sum((float(ref_p[j]["moved_u" + c]) - float(ref_p[i]["moved_u" + c])) * n[k]
                        for k, c in enumerate(axes))
                num += v * w
                den += w * w
    return num / den if den > 0. else math.nan


def n1_slope(runs, reference):
    """Slope and correlation of N1 against the reference's across the
    configurations: how much of N1's change from one configuration to the
    next the method follows."""
    x = [float(r["normal_stress_difference_1"]) for r in reference]
    y = [float(r["normal_stress_difference_1"]) for r in runs]
    mx, my = statistics.mean(x), statistics.mean(y)
    sxy = sum((a - mx) * (b - my) for a, b in zip(x, y))
    sxx = sum((a - mx) ** 2 for a in x)
    syy = sum((b - my) ** 2 for b in y)
    if sxx <= 0. or syy <= 0.:
        return math.nan, math.nan
    return sxy / sxx, sxy / math.sqrt(sxx * syy)


def errors(runs, reference, quantities):
    """Per quantity: (bias, standard deviation) of the errors over the
    configurations; eta_r relative, the others absolute."""
    out = []
    for column, _ in quantities:
        e = []
        for row, ref in zip(runs, reference):
            a, b = float(row[column]), float(ref[column])
            e.append((a - b) / b if column == "relative_viscosity" else a - b)
        sd = statistics.stdev(e) if len(e) > 1 else math.nan
        out.append((statistics.mean(e), sd))
    return out


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("prm", help="the fictitious-domain scene (with a particle generator)")
    p.add_argument("reference", help="the same scene with the resolving fluid model (the cut element)")
    p.add_argument("--levels", default="6,7,8", help="uniform mesh levels of the fictitious domain")
    p.add_argument("--strains", default="0.5,1.5,0.1", help="first,last,spacing of the configurations")
    p.add_argument("--dt", type=float, default=0.002, help="the step taken at each configuration")
    p.add_argument("--variant", action="append", default=[], metavar="NAME=KEY=VALUE;KEY=VALUE")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE")
    p.add_argument("--work", default="dense_configurations_runs")
    p.add_argument("--pair-gap", type=float, default=0.1,
                   help="pairs closer than this (over the smaller radius) enter the closing-speed slope")
    p.add_argument("--reuse", action="store_true")
    p.add_argument("--from", dest="from_work", metavar="WORK",
                   help="take the source run and the references from an earlier --work (they must have finished)")
    p.add_argument("--np", type=int, default=1,
                   help="MPI ranks of the fictitious-domain runs (the reference runs on one)")
    p.add_argument("--fidus", default=os.environ.get("FIDUS", os.path.join(REPO, "build-release", "fidus")))
    args = p.parse_args()

    common = QUIET_RUN + parse_overrides(args.set, PROG) + [("Output/Checkpoint wall interval", "0")]
    try:
        levels = [int(x) for x in args.levels.split(",")]
        first, last, spacing = (float(x) for x in args.strains.split(","))
    except ValueError:
        sys.exit(f"{PROG}: --levels '{args.levels}' must be integers and --strains '{args.strains}' "
                 "three numbers first,last,spacing")
    if not (0. < first <= last and spacing > 0. and args.dt > 0.):
        sys.exit(f"{PROG}: --strains '{args.strains}' needs 0 < first <= last and spacing > 0, --dt > 0")
    variants = [("prm's settings", [])]
    for v in args.variant:
        if "=" not in v:
            sys.exit(f"{PROG}: --variant '{v}': allowed: name=Key=value;Key=value")
        name, rest = v.split("=", 1)
        variants.append((name, parse_overrides([s for s in rest.split(";") if s.strip()], PROG)))
    prm_text = open(args.prm).read()
    reference_text = open(args.reference).read()
    correction = [("Fluid/Lubrication correction", "true")]

    # 1. The source run and its configurations (or another work's).
    shared = args.from_work or args.work
    os.makedirs(args.work, exist_ok=True)
    source = run(args.fidus, prm_text, common + correction + [("Time stepping/End time", f"{last:g}")],
                 os.path.join(shared, "source"), args.reuse or shared != args.work, args.np)
    wanted = [first + k * spacing for k in range(int(round((last - first) / spacing)) + 1)]
    steps = sorted({min(source, key=lambda r: abs(float(r["time"]) - s))["step"] for s in wanted}, key=int)
    steps = [int(s) for s in steps]
    values = parse_prm(prm_text + "\n" + prm_with("", common, "x"))
    dim = int(values.get("Dimension", "2"))
    lower = [float(x) for x in values.get("Domain/Lower left", "0,0,0").split(",")]
    upper = [float(x) for x in values.get("Domain/Upper right", "1,1,1").split(",")]
    files = write_configurations(os.path.join(shared, "source", "output", "particles.csv"), steps,
                                 args.work, dim, (lower[1], upper[1]))
    at = [("Particles/Generator/Fraction", "0"), ("Time stepping/End time", f"{args.dt:g}"),
          ("Time stepping/Time step", f"{args.dt:g}")]

    # 2. The reference at each configuration.
    reference, reference_particles = [], []
    for step, path in zip(steps, files):
        rows = run(args.fidus, reference_text, common + at + [("Particles/Positions file", path)],
                   os.path.join(shared, f"reference_{step}"), args.reuse or shared != args.work)
        reference.append(rows[-1])
        reference_particles.append(particles(os.path.join(shared, f"reference_{step}"), len(rows) - 1))
    # Sliding walls and linear shear are periodic in x (and z in 3D).
    periods = [upper[0] - lower[0], 0.] + ([upper[2] - lower[2]] if dim == 3 else [])

    # 3. The fictitious domain at each level and variant.
    print(f"{len(steps)} configurations of the source run (strains {first:g} to {last:g}), one step of "
          f"{args.dt:g} each; errors against the reference at the same configuration: mean (bias) ± "
          "standard deviation over the configurations; η_r relative, the normal stresses and Π over η_f γ̇.\n")
    quantities = QUANTITIES_3D if dim == 3 else QUANTITIES
    means = [statistics.mean(float(r[c]) for r in reference) for c, _ in quantities]
    print("Reference means: " + ", ".join(f"{n} {m:.4f}" for (_, n), m in zip(quantities, means)) + "\n")
    print("| variant | level | " + " | ".join(f"{n} error" for _, n in quantities) +
          " | N1 against the reference across configurations: slope (correlation)"
          f" | lubrication part of η_r | closing speed of pairs within {args.pair_gap:g} a / reference |")
    print("|---|---|" + "---|" * (len(quantities) + 3))
    for level in levels:
        mesh = [("Mesh refinement/Initial global refinement", str(level)),
                ("Mesh refinement/Minimum level", str(level)), ("Mesh refinement/Maximum level", str(level))]
        for k, (name, overrides) in enumerate(variants):
            runs, first_rows, moved, at_start = [], [], [], []
            for step, path in zip(steps, files):
                folder = os.path.join(args.work, f"level_{level}_variant_{k}_{step}")
                rows = run(args.fidus, prm_text,
                           common + correction + at + mesh + overrides + [("Particles/Positions file", path)],
                           folder, args.reuse, args.np)
                runs.append(rows[-1])
                first_rows.append(rows[0])
                moved.append(particles(folder, len(rows) - 1))
                at_start.append(particles(folder, 0))
            # The cut element solves the correction with the flow, so its
            # first solve is not the mesh alone.
            if k == 0 and "cut" not in values.get("Fluid/Model", ""):
                e = errors(first_rows, reference, quantities)
                print(f"| mesh alone | {level} | " + " | ".join(
                    f"{m * 100:+.1f} % ± {s * 100:.1f}" if c == "relative_viscosity" else f"{m:+.3f} ± {s:.3f}"
                    for (c, _), (m, s) in zip(quantities, e)) +
                    " | {:.2f} ({:.2f})".format(*n1_slope(first_rows, reference)) + " | 0 | " +
                    f"{closing_slope(at_start, reference_particles, periods, dim, args.pair_gap, False):.2f} |")
            e = errors(runs, reference, quantities)
            lub = statistics.mean(float(r["lubrication_relative_viscosity"] or 0.) for r in runs)
            print(f"| {name} | {level} | " + " | ".join(
                f"{m * 100:+.1f} % ± {s * 100:.1f}" if c == "relative_viscosity" else f"{m:+.3f} ± {s:.3f}"
                for (c, _), (m, s) in zip(quantities, e)) +
                " | {:.2f} ({:.2f})".format(*n1_slope(runs, reference)) + f" | {lub:.2f} | " +
                f"{closing_slope(moved, reference_particles, periods, dim, args.pair_gap):.2f} |")


if __name__ == "__main__":
    main()
