#!/usr/bin/python3
"""Run one of the seed paper's scenes for the three contact models and draw
its figure: normalised distance |X_1 - X_0| / (a_0 + a_1) against time, and
the cross-stream offset |y_1 - y_0| against time.

Usage: contrib/paper_figure.py prm/two_particles_2d.prm [out.png] [--no-run]
Each model runs in <output directory>_<model>; the PNG goes to out.png
(default: doc/<scene>.png). Prints a table per model: minimum normalised
distance, final offset, time spent glued.
"""
import csv
import os
import re
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

top = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
args = [a for a in sys.argv[1:] if not a.startswith("--")]
prm_file = args[0]
scene = os.path.splitext(os.path.basename(prm_file))[0]
png = args[1] if len(args) > 1 else os.path.join(top, "doc", scene + ".png")
fidus = os.environ.get("FIDUS", os.path.join(top, "build-release", "fidus"))
text = open(prm_file).read()
outdir = re.search(r"set Output directory\s*=\s*(\S+)", text).group(1)

styles = {"none": ("-", "none"), "inelastic": ("--", "inelastic"), "gluey": ("-", "gluey")}
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4))
print("| model | min normalised distance | final offset | time glued | steps |")
print("|---|---|---|---|---|")
for model in ["none", "inelastic", "gluey"]:
    d = f"{outdir}_{model}"
    if "--no-run" not in sys.argv:
        t = re.sub(r"set Output directory\s*=.*", f"set Output directory = {d}", text)
        t = re.sub(r"(subsection Contact\s*\n\s*set Model\s*=)\s*\S+", rf"\1 {model}", t)
        tmp = f"/tmp/fidus_{scene}_{model}.prm"
        open(tmp, "w").write(t)
        subprocess.run([fidus, tmp], stdout=subprocess.DEVNULL)
    rows = list(csv.DictReader(open(os.path.join(d, "particles.csv"))))
    by_step = {}
    for r in rows:
        by_step.setdefault(int(r["step"]), {})[int(r["id"])] = r
    times, dist, offset = [], [], []
    for s in sorted(by_step):
        p = by_step[s]
        if 0 not in p or 1 not in p:
            continue
        x0 = [float(p[0][c]) for c in "xyz"]
        x1 = [float(p[1][c]) for c in "xyz"]
        a = float(p[0]["radius"]) + float(p[1]["radius"])
        times.append(float(p[0]["time"]))
        dist.append(sum((u - v) ** 2 for u, v in zip(x0, x1)) ** 0.5 / a)
        offset.append(abs(x1[1] - x0[1]))
    stats = list(csv.DictReader(open(os.path.join(d, "statistics.csv"))))
    glued = sum(float(r["dt"]) for r in stats if float(r["glued_contacts"]) > 0)
    ls, label = styles[model]
    ax1.plot(times, dist, ls, label=label, lw=2 if model == "gluey" else 1)
    ax2.plot(times, offset, ls, label=label, lw=2 if model == "gluey" else 1)
    print(f"| {model} | {min(dist):.4f} | {offset[-1]:.4f} | {glued:.2f} | {len(times) - 1} |")
ax1.axhline(1, color="grey", lw=0.5)
ax1.set_xlabel("t")
ax1.set_ylabel("normalised distance")
ax2.set_xlabel("t")
ax2.set_ylabel("cross-stream offset |y1 - y0|")
ax1.legend()
ax1.set_title(scene)
fig.tight_layout()
fig.savefig(png, dpi=110)
print("figure:", png)
