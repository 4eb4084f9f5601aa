#!/usr/bin/env python3
"""Plot the rheology columns of fidus's statistics.csv against strain.

Usage: contrib/plot_rheology.py OUTPUT_DIR [--shear-rate G] [--png FILE]
           [--skip STRAIN]

Panels: relative viscosity, its contact part and (when the sub-grid
lubrication correction is on) its lubrication part; N1, N2 and the particle
pressure, each divided by eta_f |G| (G the shear rate of the run, default 1;
the viscosity is read from used_parameters.prm). Prints the means over the
strain after --skip (default 0: all rows except step 0). Definitions:
doc/rheology.md.
"""
import argparse
import csv
import math
import os
import sys


def viscosity_of(folder):
    path = os.path.join(folder, "used_parameters.prm")
    try:
        section = []
        for line in open(path):
            words = line.split()
            if not words:
                continue
            if words[0] == "subsection":
                section.append(" ".join(words[1:]))
            elif words[0] == "end":
                section.pop()
            elif section == ["Fluid"] and line.strip().startswith("set Viscosity"):
                return float(line.split("=")[1])
    except OSError:
        pass
    return 1.0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder")
    parser.add_argument("--shear-rate", type=float, default=1.0)
    parser.add_argument("--png", default=None)
    parser.add_argument("--skip", type=float, default=0.0)
    args = parser.parse_args()
    if args.shear_rate == 0:
        sys.exit("plot_rheology.py: --shear-rate must not be 0")
    path = os.path.join(args.folder, "statistics.csv")
    try:
        rows = list(csv.DictReader(open(path)))
    except OSError as e:
        sys.exit("plot_rheology.py: cannot read %s: %s" % (path, e))
    if not rows or "relative_viscosity" not in rows[0]:
        sys.exit("plot_rheology.py: %s has no stress columns" % path)
    eta = viscosity_of(args.folder)
    scale = 1.0 / (eta * abs(args.shear_rate))
    rows = [r for r in rows if int(r["step"]) > 0]
    strain = [abs(args.shear_rate) * float(r["time"]) for r in rows]
    series = {
        "relative viscosity": [float(r["relative_viscosity"]) for r in rows],
        "contact part": [float(r["contact_relative_viscosity"]) for r in rows],
        "lubrication part": [float(r.get("lubrication_relative_viscosity", 0) or 0)
                             for r in rows],
        "N1 / (eta |G|)": [scale * float(r["normal_stress_difference_1"]) for r in rows],
        "N2 / (eta |G|)": [scale * float(r["normal_stress_difference_2"]) for r in rows],
        "particle pressure / (eta |G|)": [scale * float(r["particle_pressure"]) for r in rows],
    }
    kept = [i for i, s in enumerate(strain) if s >= args.skip]
    print("| quantity | mean over strain >= %g (%d rows) |" % (args.skip, len(kept)))
    print("|---|---|")
    for name, values in series.items():
        v = [values[i] for i in kept if math.isfinite(values[i])]
        print("| %s | %.4g |" % (name, sum(v) / len(v) if v else float("nan")))

    png = args.png or os.path.join(args.folder, "rheology.png")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 7), sharex=True)
    top.plot(strain, series["relative viscosity"], label="relative viscosity")
    top.plot(strain, series["contact part"], label="contact part")
    # Runs without the sub-grid lubrication correction have a zero column.
    if any(v != 0 for v in series["lubrication part"]):
        top.plot(strain, series["lubrication part"], label="lubrication part")
    top.set_ylabel("eta_r")
    top.legend()
    for name in ("N1 / (eta |G|)", "N2 / (eta |G|)", "particle pressure / (eta |G|)"):
        bottom.plot(strain, series[name], label=name)
    bottom.set_xlabel("strain |G| t")
    bottom.legend()
    fig.tight_layout()
    fig.savefig(png, dpi=120)
    print("figure: %s" % png)


if __name__ == "__main__":
    main()
