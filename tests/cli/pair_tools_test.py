#!/usr/bin/env python3
"""contrib/benchmarks/pair_invariant.py and pair_rates.py against Batchelor &
Green's exact passage: a run's particles.csv and statistics.csv written from
the exact relative motion of the paper's 3D pair (centres (0.3, 0.525, 0.5)
and (0.7, 0.475, 0.5), a = 0.05, shear rate 1; RK4 on the exact equations of
batchelor_green.py, steps of 0.01, a row every 0.1), then read by the tools.

Known answers: along an exact trajectory the first integral y_inf^2 is
constant (its value at the start 0.99036, whose closest approach is the
documented 7.37e-3 a), and the exact velocities' closing rate at each step's
start is the exact rate there (ratio 1, to the digits printed). The rate over a step of 0.1 is the
mean over the step, compared at the step's middle: within 2 %.

Usage: pair_tools_test.py SOURCE_DIR
"""
import csv
import math
import os
import subprocess
import sys
import tempfile

source = sys.argv[1]
bench = os.path.join(source, "contrib", "benchmarks")
sys.path.insert(0, bench)
from batchelor_green import Mobility, rhs_t, rk4_t  # noqa: E402

A = 0.05
failures = 0


def check(what, ok):
    global failures
    print("%s: %s" % (what, "OK" if ok else "FAILED"))
    failures += 0 if ok else 1


def write_exact_run(folder):
    """particles.csv and statistics.csv of the exact passage, t = 0 .. 16."""
    mob = Mobility()
    rel = (0.4 / A, -0.05 / A)  # sphere 1 from sphere 0, in radii
    y = (math.log(math.hypot(*rel) - 2.), math.atan2(rel[1], rel[0]))
    with open(os.path.join(folder, "particles.csv"), "w", newline="") as f, \
            open(os.path.join(folder, "statistics.csv"), "w", newline="") as g:
        p = csv.writer(f)
        s = csv.writer(g)
        p.writerow(["step", "time", "id", "x", "y", "z", "ux", "uy", "uz"])
        s.writerow(["step", "time", "lubrication_pairs", "active_contacts"])
        for n in range(1601):
            if n % 10 == 0:
                step, t = n // 10, 0.01 * n
                r, th = 2. + math.exp(y[0]), y[1]
                drho, dth = rhs_t(mob, y)
                dr = drho * (r - 2.)
                d = (A * r * math.cos(th), A * r * math.sin(th))
                v = (A * (dr * math.cos(th) - r * dth * math.sin(th)),
                     A * (dr * math.sin(th) + r * dth * math.cos(th)))
                for i, sign in ((0, -0.5), (1, 0.5)):
                    p.writerow([step, "%.10g" % t, i,
                                "%.15g" % (0.5 + sign * d[0]),
                                "%.15g" % (0.5 + sign * d[1]), 0.5,
                                "%.15g" % (sign * v[0]),
                                "%.15g" % (sign * v[1]), 0.])
                s.writerow([step, "%.10g" % t, 0, 0])
            y = rk4_t(mob, y, 0.01)


def table(command):
    """The Markdown table rows a tool prints, as lists of cells."""
    out = subprocess.run(command, capture_output=True, text=True, check=True)
    rows = []
    for line in out.stdout.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if line.startswith("|") and cells and cells[0][:1].isdigit():
            rows.append(cells)
    return rows


with tempfile.TemporaryDirectory() as folder:
    write_exact_run(folder)
    rows = table([sys.executable, os.path.join(bench, "pair_invariant.py"),
                  folder, str(A)])
    invariants = [float(r[3]) for r in rows]
    closest = [float(r[4]) for r in rows]
    check("pair_invariant.py: %d rows, y_inf^2 at the start 0.99036 to 1e-4"
          % len(rows), len(rows) > 40 and abs(invariants[0] - 0.99036) < 1e-4)
    check("pair_invariant.py: y_inf^2 constant along the exact passage to 1e-4",
          max(invariants) - min(invariants) < 1e-4)
    check("pair_invariant.py: its closest approach 7.37e-3 a to 1 %",
          all(abs(c / 7.37e-3 - 1.) < 0.01 for c in closest))

    rows = table([sys.executable, os.path.join(bench, "pair_rates.py"),
                  folder, str(A), "1e-3", "2"])
    solved = [float(r[8]) for r in rows if float(r[7]) != 0.]
    over_step = [float(r[5]) for r in rows if abs(float(r[4])) > 1e-3]
    check("pair_rates.py: %d steps, the solved closing rate over exact 1 to "
          "its three printed digits" % len(rows),
          len(rows) > 20 and all(abs(x - 1.) < 5e-4 for x in solved))
    check("pair_rates.py: the closing rate over each step within 2 % of exact "
          "at its middle", all(abs(x - 1.) < 0.02 for x in over_step))

sys.exit(1 if failures else 0)
