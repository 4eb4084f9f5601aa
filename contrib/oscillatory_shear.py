#!/usr/bin/env python3
"""Oscillatory shear of a fidus scene: which particles come back each cycle.

For each contact model and strain amplitude g0 this runs the scene under the
shear rate g0 w cos(w t), w = 2 pi / T (strain g0 sin(w t)), for a number of
cycles, and compares every particle's position at the end of each cycle with
its position one cycle earlier (minimum image in the periodic directions of
'sliding walls'). A particle "does not return" when it moved by more than
--threshold times its radius. This is the measure of Pine et al. (Nature
2005) and Corte et al. (Nat. Phys. 2008): below a threshold amplitude the
non-returning fraction decays to zero (an absorbing state), above it stays
finite. Prints a Markdown table (fraction per cycle and amplitude) and draws
a PNG. See doc/rheology.md.

Standard library only; matplotlib draws the figure when it is installed.

Example (contact only, 'undisturbed shear', cheap):
  contrib/oscillatory_shear.py prm/rheology_oscillatory_shear_2d.prm \\
      --amplitudes 0.2,0.5,1,2 --models inelastic,gluey --cycles 20 \\
      --set "Fluid/Model=undisturbed shear" --out osc
"""

import argparse
import concurrent.futures
import csv
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from convergence_analysis import parse_prm, read_text  # noqa: E402

PROG = "oscillatory_shear.py"
REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def fail(message):
    """One message naming the problem, exit status 1."""
    sys.stderr.write(f"{PROG}: error: {message}\n")
    sys.exit(1)


def numbers(text, name, positive=True):
    """Comma-separated floats of option --name, all > 0 if positive."""
    try:
        values = [float(v) for v in text.split(",") if v.strip()]
    except ValueError:
        fail(f"--{name} has the value '{text}'; allowed: comma-separated numbers")
    if not values or (positive and any(not v > 0 for v in values)):
        fail(f"--{name} has the value '{text}'; allowed: numbers > 0")
    return values


def prm_block(entry, value):
    """'A/B/Entry', value -> nested subsection blocks setting it."""
    parts = entry.split("/")
    lines = [f"subsection {p}" for p in parts[:-1]]
    lines.append(f"set {parts[-1]} = {value}")
    lines += ["end"] * (len(parts) - 1)
    return "\n".join(lines) + "\n"


def periods_of(prm):
    """Box periods of a 'sliding walls' scene (x, and z in 3D), else 0."""
    values = parse_prm(prm)
    if values.get("Domain/Boundary condition", "").strip() != "sliding walls":
        return [0.0, 0.0, 0.0]
    lo = [float(v) for v in values.get("Domain/Lower left", "0, 0").split(",")]
    hi = [float(v) for v in values.get("Domain/Upper right", "1, 1").split(",")]
    p = [hi[0] - lo[0], 0.0, 0.0]
    if len(lo) == 3 and len(hi) == 3:
        p[2] = hi[2] - lo[2]
    return p


def read_cycles(folder, steps_per_cycle):
    """{step: {id: ((x, y, z), radius)}} of the cycle ends in particles.csv.

    Streams the file: only the rows of steps that end a cycle are kept, so a
    particles.csv written every step does not have to fit in memory.
    """
    path = os.path.join(folder, "particles.csv")
    rows = {}
    try:
        with open(path) as f:
            reader = csv.reader(f)
            header = next(reader)
            col = {name: k for k, name in enumerate(header)}
            ks, ki = col["step"], col["id"]
            kx, ky, kz, ka = col["x"], col["y"], col["z"], col["radius"]
            for r in reader:
                step = int(float(r[ks]))
                if step % steps_per_cycle:
                    continue
                rows.setdefault(step, {})[int(float(r[ki]))] = (
                    (float(r[kx]), float(r[ky]), float(r[kz])), float(r[ka]))
    except (OSError, KeyError, ValueError, StopIteration) as e:
        fail(f"cannot read {path}: {e}")
    return rows


def returns(cycles, steps_per_cycle, periods, threshold):
    """Per cycle k >= 1: (fraction not returned, mean |dX|/a, max |dX|/a)."""
    out = []
    k = 1
    while k * steps_per_cycle in cycles and (k - 1) * steps_per_cycle in cycles:
        now, before = cycles[k * steps_per_cycle], cycles[(k - 1) * steps_per_cycle]
        moved, total, largest = 0, 0.0, 0.0
        for i, (x, a) in now.items():
            y = before[i][0]
            d2 = 0.0
            for c in range(3):
                dx = x[c] - y[c]
                if periods[c] > 0:
                    dx -= periods[c] * round(dx / periods[c])
                d2 += dx * dx
            d = math.sqrt(d2) / a
            total += d
            largest = max(largest, d)
            moved += d > threshold
        out.append((moved / len(now), total / len(now), largest))
        k += 1
    return out


def run_one(job):
    """Run fidus on one variant (unless its results are reused)."""
    fidus, folder, prm_text, reuse = job
    os.makedirs(folder, exist_ok=True)
    prm_path = os.path.join(folder, "run.prm")
    done = os.path.join(folder, "done")
    if reuse and os.path.exists(done) and read_text(prm_path) == prm_text:
        return folder, 0
    with open(prm_path, "w") as f:
        f.write(prm_text)
    with open(os.path.join(folder, "log.txt"), "w") as log:
        status = subprocess.run([fidus, prm_path], stdout=log, stderr=subprocess.STDOUT,
                                stdin=subprocess.DEVNULL, cwd=folder).returncode
    if status == 0:
        open(done, "w").close()
    return folder, status


def main():
    p = argparse.ArgumentParser(prog=PROG, description=__doc__.split("\n\n")[0])
    p.add_argument("prm", help="the scene (its Shear rate and End time are replaced)")
    p.add_argument("--amplitudes", default="0.5,1,2", help="strain amplitudes g0")
    p.add_argument("--models", default="inelastic,gluey", help="Contact/Model values")
    p.add_argument("--cycles", type=int, default=10, help="number of cycles, >= 2")
    p.add_argument("--period", type=float, default=4.0, help="period T of a cycle")
    p.add_argument("--steps-per-cycle", type=int, default=100,
                   help="least number of time steps per cycle")
    p.add_argument("--strain-step", type=float, default=0.02,
                   help="largest strain increment g0 w dt of one step: a cycle "
                        "of amplitude g0 gets at least 2 pi g0 / this steps "
                        "(0: --steps-per-cycle for every amplitude)")
    p.add_argument("--threshold", type=float, default=0.01,
                   help="a particle that moved more than this times its radius "
                        "in a cycle has not returned")
    p.add_argument("--set", action="append", default=[], metavar="ENTRY=VALUE",
                   help="override an entry, e.g. 'Fluid/Model=undisturbed shear'")
    p.add_argument("--fidus", default=os.path.join(REPO, "build-release", "fidus"))
    p.add_argument("--jobs", type=int, default=2, help="runs at a time")
    p.add_argument("--reuse", action="store_true",
                   help="keep the results of a run whose parameters did not change")
    p.add_argument("--out", default="oscillatory_shear", help="work and output folder")
    args = p.parse_args()

    amplitudes = numbers(args.amplitudes, "amplitudes")
    models = [m.strip() for m in args.models.split(",") if m.strip()]
    for m in models:
        if m not in ("none", "inelastic", "gluey"):
            fail(f"--models has the value '{m}'; allowed: none, inelastic, gluey")
    if args.cycles < 2:
        fail(f"--cycles has the value {args.cycles}; allowed: an integer >= 2")
    if not args.period > 0 or args.steps_per_cycle < 4:
        fail("--period must be > 0 and --steps-per-cycle >= 4")
    if not args.strain_step >= 0:
        fail(f"--strain-step has the value {args.strain_step}; allowed: >= 0")
    if not args.threshold > 0:
        fail(f"--threshold has the value {args.threshold}; allowed: > 0")
    base = read_text(args.prm)
    if base is None:
        fail(f"cannot read the parameter file '{args.prm}'")
    if not os.access(args.fidus, os.X_OK):
        fail(f"the fidus program '{args.fidus}' does not exist (build it or "
             "give --fidus)")
    overrides = []
    for s in args.set:
        if "=" not in s or "/" not in s.split("=", 1)[0]:
            fail(f"--set has the value '{s}'; allowed: Section/Entry=value")
        overrides.append(tuple(x.strip() for x in s.split("=", 1)))

    omega = 2 * math.pi / args.period
    out = os.path.abspath(args.out)
    jobs, keys = [], []
    for model in models:
        for g0 in amplitudes:
            steps = args.steps_per_cycle
            if args.strain_step > 0:
                steps = max(steps, math.ceil(2 * math.pi * g0 / args.strain_step))
            dt = args.period / steps
            folder = os.path.join(out, f"{model}_g{g0:g}")
            text = f"include {os.path.abspath(args.prm)}\n"
            text += f"set Output directory = {folder}/output\n"
            settings = [
                ("Domain/Shear rate", f"{g0 * omega:.17g} * cos({omega:.17g} * t)"),
                ("Contact/Model", model),
                ("Time stepping/Time step", f"{dt:.17g}"),
                ("Time stepping/End time", f"{args.cycles * args.period:.17g}"),
                ("Time stepping/Adaptive time step", "false"),
                ("Output/Particle output interval", "0"),
                ("Output/Particle CSV interval", str(steps)),
                ("Output/Field output interval", "0"),
                ("Output/Verbosity", "quiet"),
            ] + overrides
            for entry, value in settings:
                text += prm_block(entry, value)
            jobs.append((args.fidus, folder, text, args.reuse))
            keys.append((model, g0, folder, steps))

    with concurrent.futures.ThreadPoolExecutor(max(1, args.jobs)) as pool:
        for folder, status in pool.map(run_one, jobs):
            if status != 0:
                fail(f"fidus failed (exit {status}) in {folder}; see {folder}/log.txt")

    periods = periods_of(base + "".join(prm_block(e, v) for e, v in overrides))
    table = {}
    for model, g0, folder, steps in keys:
        cycles = read_cycles(os.path.join(folder, "output"), steps)
        table[(model, g0)] = returns(cycles, steps, periods, args.threshold)
        if len(table[(model, g0)]) != args.cycles:
            fail(f"{folder}: found {len(table[(model, g0)])} cycles in particles.csv, "
                 f"expected {args.cycles}")

    # The table: the non-returning fraction after each cycle.
    show = sorted({1, 2, 3, 5, args.cycles} | set(range(10, args.cycles, 10)))
    show = [k for k in show if k <= args.cycles]
    print(f"Non-returning fraction (|dX| > {args.threshold:g} a over one cycle); "
          f"T = {args.period:g}")
    print()
    print("| model | g0 | steps per cycle | " + " | ".join(f"cycle {k}" for k in show)
          + " | mean of last 3 | mean |dX|/a, last cycle |")
    print("|---|---|---|" + "---|" * len(show) + "---|---|")
    for model, g0, _, steps in keys:
        rows = table[(model, g0)]
        last = sum(r[0] for r in rows[-3:]) / len(rows[-3:])
        print(f"| {model} | {g0:g} | {steps} | "
              + " | ".join(f"{rows[k - 1][0]:.3f}" for k in show)
              + f" | {last:.3f} | {rows[-1][1]:.2e} |")
    with open(os.path.join(out, "returns.csv"), "w") as f:
        f.write("model,amplitude,cycle,not_returned_fraction,mean_displacement,"
                "max_displacement\n")
        for model, g0, _, _ in keys:
            for k, r in enumerate(table[(model, g0)], start=1):
                f.write(f"{model},{g0:g},{k},{r[0]:.6g},{r[1]:.6g},{r[2]:.6g}\n")

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("\n(matplotlib not installed: no figure)")
        return
    fig, axes = plt.subplots(1, len(models) + 1, figsize=(4.2 * (len(models) + 1), 3.6))
    for ax, model in zip(axes, models):
        for g0 in amplitudes:
            rows = table[(model, g0)]
            ax.plot(range(1, len(rows) + 1), [r[0] for r in rows], "o-", ms=3,
                    label=f"$\\gamma_0$ = {g0:g}")
        ax.set_title(model)
        ax.set_xlabel("cycle")
        ax.set_ylabel("fraction not returned")
        ax.set_ylim(-0.02, 1.02)
        ax.legend(fontsize=8)
    ax = axes[-1]
    for model in models:
        ax.plot(amplitudes,
                [sum(r[0] for r in table[(model, g)][-3:]) / len(table[(model, g)][-3:])
                 for g in amplitudes],
                "s-", label=model)
    ax.set_xscale("log")
    # The amplitudes themselves as ticks: log-axis minor labels overlap.
    ax.set_xticks(amplitudes)
    ax.set_xticklabels([f"{g:g}" for g in amplitudes])
    ax.minorticks_off()
    ax.set_xlabel("strain amplitude $\\gamma_0$")
    ax.set_ylabel("fraction not returned (last 3 cycles)")
    ax.set_ylim(-0.02, 1.02)
    ax.legend(fontsize=8)
    fig.tight_layout()
    png = os.path.join(out, "oscillatory_shear.png")
    fig.savefig(png, dpi=120)
    print(f"\nfigure: {png}")


if __name__ == "__main__":
    main()
