#!/usr/bin/python3
"""Work-precision benchmark: error against wall time for fidus's numerical
settings, each swept on its own while the others stay at a base value.

Cases
  a2, a3  rigid inclusion with the exact solution on the box (Boundary
          condition = exact rigid inclusion, End time = 0, one particle of
          radius 0.15 (2D) / 0.2 (3D), or --radius-2d/--radius-3d, at the
          centre of the unit box, as in
          contrib/benchmarks/rigid_inclusion.sh). Error: relative L2 error of
          u on the fluid part (also: H1 error, relative omega error).
  b       the seed paper's 2D scene, contact model gluey
          (prm/two_particles_2d.prm). Error: max over time of
          |d(t) - d_ref(t)|, d = |X1 - X0| / (a0 + a1), against a reference
          run at the finest settings of all sweeps (linear interpolation in
          time when the time steps differ); also the final cross-stream
          offset |y1 - y0| and its deviation from the reference.

Sweeps
  uniform     Initial global refinement = Minimum level = Maximum level = L
              (case a only)
  adaptive    Maximum level = L, Initial global refinement = Minimum level =
              --coarse-level (2)
  penalty     Fluid/Penalty factor
  rigidity    Fluid/Rigidity tolerance (with Maximum Uzawa iterations = 30)
  linear_tol  Fluid/Linear solver/Tolerance
  dt          Time stepping/Time step (case b only)

For every run: cells, DoFs, Uzawa and FGMRES iterations (statistics.csv,
summed over the steps for case b, whose cells/DoFs are the maximum over the
steps), wall seconds of the fidus process, error(s). Prints one Markdown
table per case, its Pareto-optimal rows (no other run has both a smaller
error and a smaller time) and, for case a, the wall time to reach 1 %
relative L2 error with uniform and with adaptive refinement. Draws
<out>/work_precision_<case>.png (error against time, log-log).

Usage:
  contrib/benchmarks/work_precision.py [--case a2|a3|b ...] [--quick]
      [--out DIR] [--csv FILE] [--end-time T] [--uniform-2d 3:7] ...
  FIDUS=build/fidus nice -n 10 contrib/benchmarks/work_precision.py --quick --out /tmp

The executable is $FIDUS, default build-release/fidus (built with
contrib/build.sh fidus when missing). Runs go to a temporary directory that
is removed at the end. Run with --help for every option.
"""
import argparse
import copy
import csv
import math
import os
import re
import subprocess
import sys
import tempfile
import time

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

TOP = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# Sweep values (default and --quick).
PENALTIES = [1e2, 1e3, 1e4, 1e6]
RIGIDITY_TOLS = [1e-2, 1e-3, 5e-4, 1e-4]
LINEAR_TOLS = [1e-4, 1e-6, 1e-8, 1e-10]
TIME_STEPS = [0.2, 0.1, 0.05]
QUICK_PENALTIES = [1e3, 1e4]
QUICK_RIGIDITY_TOLS = [1e-2, 1e-3]
QUICK_LINEAR_TOLS = [1e-4, 1e-8]
QUICK_TIME_STEPS = [0.2, 0.1]
UZAWA_FOR_RIGIDITY_SWEEP = 30

SWEEP_LABELS = {
    "uniform": "uniform refinement (level)",
    "adaptive": "adaptive refinement (max level)",
    "penalty": "penalty factor",
    "rigidity": "rigidity tolerance",
    "linear_tol": "FGMRES tolerance",
    "dt": "time step",
}
STYLE = {  # marker, colour
    "uniform": ("s", "tab:blue"),
    "adaptive": ("o", "tab:orange"),
    "penalty": ("^", "tab:green"),
    "rigidity": ("v", "tab:red"),
    "linear_tol": ("D", "tab:purple"),
    "dt": ("P", "tab:brown"),
}
NUM = r"([-+]?(?:\d+\.?\d*(?:[eE][-+]?\d+)?|nan|inf|-nan))"


# --------------------------------------------------------------------------
# Parameter files: a flat {"Subsection/Sub/Entry": value} dict, in order.
# --------------------------------------------------------------------------
def parse_prm(text):
    entries, stack = {}, []
    for raw in text.splitlines():
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        if line.startswith("subsection "):
            stack.append(line[len("subsection "):].strip())
        elif line == "end":
            stack.pop()
        elif line.startswith("set "):
            key, value = line[4:].split("=", 1)
            entries["/".join(stack + [key.strip()])] = value.strip()
    return entries


def write_prm(entries, path):
    tree = {}
    for key, value in entries.items():
        node, parts = tree, key.split("/")
        for p in parts[:-1]:
            node = node.setdefault(p, {})
        node[parts[-1]] = value
    lines = []

    def emit(node, indent):
        for k, v in node.items():
            if not isinstance(v, dict):
                lines.append(f"{indent}set {k} = {v}")
        for k, v in node.items():
            if isinstance(v, dict):
                lines.append(f"{indent}subsection {k}")
                emit(v, indent + "  ")
                lines.append(f"{indent}end")

    emit(tree, "")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def fmt(v):
    return f"{v:g}" if isinstance(v, float) else str(v)


# --------------------------------------------------------------------------
# Sweeps: name -> function(entries, value, opts) changing the entries.
# --------------------------------------------------------------------------
def set_uniform(e, level, opts):
    for k in ("Initial global refinement", "Minimum level", "Maximum level"):
        e["Mesh refinement/" + k] = str(level)


def set_adaptive(e, level, opts):
    e["Mesh refinement/Initial global refinement"] = str(opts.coarse_level)
    e["Mesh refinement/Minimum level"] = str(opts.coarse_level)
    e["Mesh refinement/Maximum level"] = str(level)


def set_penalty(e, r, opts):
    e["Fluid/Penalty factor"] = fmt(r)


def set_rigidity(e, tol, opts):
    e["Fluid/Rigidity tolerance"] = fmt(tol)
    e["Fluid/Maximum Uzawa iterations"] = str(UZAWA_FOR_RIGIDITY_SWEEP)


def set_linear_tol(e, tol, opts):
    e["Fluid/Linear solver/Tolerance"] = fmt(tol)


def set_dt(e, dt, opts):
    e["Time stepping/Time step"] = fmt(dt)


APPLY = {
    "uniform": set_uniform,
    "adaptive": set_adaptive,
    "penalty": set_penalty,
    "rigidity": set_rigidity,
    "linear_tol": set_linear_tol,
    "dt": set_dt,
}


def level_range(text):
    """'3:7' -> [3, 4, 5, 6, 7]; '3,5,7' -> [3, 5, 7]; '4' -> [4]."""
    if ":" in text:
        lo, hi = (int(x) for x in text.split(":"))
        return list(range(lo, hi + 1))
    return [int(x) for x in text.split(",")]


# --------------------------------------------------------------------------
# Cases
# --------------------------------------------------------------------------
def case_a(dim, opts):
    box_lo, box_hi = ", ".join(["0"] * dim), ", ".join(["1"] * dim)
    base = {
        "Dimension": str(dim),
        "Domain/Lower left": box_lo,
        "Domain/Upper right": box_hi,
        "Domain/Boundary condition": "exact rigid inclusion",
        "Domain/Shear rate": "1",
        "Fluid/Penalty factor": "1000",
        # Rigidity and FGMRES tolerances at the Pareto point chosen with
        # this script (doc/performance.md), in the box measure it used.
        "Fluid/Rigidity tolerance": "1e-3",
        "Fluid/Rigidity measure": "box",
        "Fluid/Maximum Uzawa iterations": "30",
        "Fluid/Linear solver/Tolerance": "1e-6",
        "Particles/Radius": fmt(opts.radius_2d if dim == 2 else opts.radius_3d),
        "Particles/Positions": ", ".join(["0.5"] * dim),
        "Time stepping/End time": "0",
        "Output/Field output interval": "0",
        "Output/Particle output interval": "0",
    }
    set_adaptive(base, opts.base_level_2d if dim == 2 else opts.base_level_3d, opts)
    q = opts.quick
    a = opts.radius_2d if dim == 2 else opts.radius_3d
    sweeps = [
        ("uniform", opts.uniform_2d if dim == 2 else opts.uniform_3d),
        ("adaptive", opts.adaptive_2d if dim == 2 else opts.adaptive_3d),
        ("penalty", QUICK_PENALTIES if q else PENALTIES),
        ("rigidity", QUICK_RIGIDITY_TOLS if q else RIGIDITY_TOLS),
        ("linear_tol", QUICK_LINEAR_TOLS if q else LINEAR_TOLS),
    ]
    sweeps = [(n, v) for n, v in sweeps if not opts.sweeps or n in opts.sweeps]
    return {"name": f"a{dim}", "dim": dim, "base": base, "sweeps": sweeps,
            "title": f"{dim}D rigid inclusion (a = {a:g}), exact solution on the box"}


def case_b(opts):
    with open(opts.scene_b) as f:
        base = parse_prm(f.read())
    base["Contact/Model"] = "gluey"
    # The box measure, in which the case-b tables of doc/performance.md were
    # measured (the prm states its tolerance per particle).
    base["Fluid/Rigidity measure"] = "box"
    base["Fluid/Rigidity tolerance"] = "1e-3"
    base["Output/Field output interval"] = "0"
    base["Output/Particle output interval"] = "0"
    base["Output/Progress interval"] = "1000000"
    if opts.end_time is not None:
        base["Time stepping/End time"] = fmt(opts.end_time)
    if opts.base_level_b is not None:
        base["Mesh refinement/Maximum level"] = str(opts.base_level_b)
    q = opts.quick
    sweeps = [
        ("adaptive", opts.adaptive_b),
        ("penalty", QUICK_PENALTIES if q else PENALTIES),
        ("rigidity", QUICK_RIGIDITY_TOLS if q else RIGIDITY_TOLS),
        ("linear_tol", QUICK_LINEAR_TOLS if q else LINEAR_TOLS),
        ("dt", QUICK_TIME_STEPS if q else TIME_STEPS),
    ]
    return {"name": "b", "dim": int(base.get("Dimension", "2")), "base": base,
            "sweeps": sweeps,
            "title": f"{os.path.basename(opts.scene_b)}, gluey, "
                     f"t <= {base.get('Time stepping/End time')}"}


def reference_entries(case, opts):
    """Case b: every sweep at its finest value at once (largest maximum level
    and penalty factor, smallest tolerances and time step), unless
    overridden by --reference NAME=VALUE."""
    e = copy.deepcopy(case["base"])
    finest = {}
    for name, values in case["sweeps"]:
        finest[name] = max(values) if name in ("adaptive", "uniform", "penalty") else min(values)
    for item in opts.reference:
        name, value = item.split("=", 1)
        if name not in finest:
            sys.exit(f"--reference {item}: unknown sweep '{name}' (one of {', '.join(finest)})")
        finest[name] = int(value) if name in ("adaptive", "uniform") else float(value)
    for name, value in finest.items():
        if name == "adaptive":
            # Only the maximum level: the scene's own Initial global
            # refinement / Minimum level (3) is kept, finer than --coarse-level.
            e["Mesh refinement/Maximum level"] = str(value)
        else:
            APPLY[name](e, value, opts)
    e["Fluid/Maximum Uzawa iterations"] = str(UZAWA_FOR_RIGIDITY_SWEEP)
    return e, finest


# --------------------------------------------------------------------------
# Running fidus and reading its output
# --------------------------------------------------------------------------
def run_fidus(fidus, entries, workdir, tag, timeout):
    outdir = os.path.join(workdir, tag)
    os.makedirs(outdir, exist_ok=True)
    e = dict(entries)
    e["Output directory"] = outdir
    prm = os.path.join(workdir, tag + ".prm")
    write_prm(e, prm)
    res = {"outdir": outdir}
    t0 = time.perf_counter()
    try:
        p = subprocess.run([fidus, prm], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                           text=True, timeout=timeout)
        res["seconds"] = time.perf_counter() - t0
        res["exit"] = p.returncode
        res["stdout"], res["stderr"] = p.stdout, p.stderr
    except OSError as ex:  # e.g. the executable vanished during a rebuild
        res["seconds"] = time.perf_counter() - t0
        res["exit"] = f"cannot start: {ex.strerror}"
        res["stdout"], res["stderr"] = "", str(ex)
    except subprocess.TimeoutExpired as ex:
        res["seconds"] = time.perf_counter() - t0
        res["exit"] = "timeout"
        res["stdout"] = ex.stdout.decode() if isinstance(ex.stdout, bytes) else (ex.stdout or "")
        res["stderr"] = ex.stderr.decode() if isinstance(ex.stderr, bytes) else (ex.stderr or "")
    res["warnings"] = sum(1 for l in res["stderr"].splitlines() if "warning" in l.lower())
    return res


def read_statistics(outdir):
    path = os.path.join(outdir, "statistics.csv")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        return None
    return {
        "cells": max(int(float(r["cells"])) for r in rows),
        "dofs": max(int(float(r["dofs"])) for r in rows),
        "uzawa": sum(int(float(r["uzawa_iterations"])) for r in rows),
        "fgmres": sum(int(float(r["linear_iterations"])) for r in rows),
        "steps": len(rows) - 1,
    }


def compute_seconds(stdout):
    """fidus's own 'Total wallclock time elapsed since start' (from after
    MPI initialisation to the end of the run): the wall time without the
    fixed process start (MPI singleton start, shared libraries), about
    0.6 s on the CI machine, which no mesh or solver setting can change."""
    m = re.search(r"Total wallclock time elapsed since start\s*\|\s*([0-9.eE+-]+)(s|min|h)", stdout)
    if not m:
        return None
    return float(m.group(1)) * {"s": 1.0, "min": 60.0, "h": 3600.0}[m.group(2)]


def parse_exact_line(stdout):
    """Fields of the 'exact rigid inclusion: ...' line, found by name."""
    line = next((l for l in stdout.splitlines() if "exact rigid inclusion:" in l), None)
    if line is None:
        return None
    names = {
        "cells": r"cells",
        "dofs": r"dofs",
        "l2_error": r"L2 error of u \(fluid\)",
        "l2_norm": r"L2 norm of exact u \(fluid\)",
        "h1_error": r"H1 error of u \(fluid\)",
        "omega_error": r"relative omega error",
        "translation_error": r"\|U\|/\(g a\)",
    }
    out = {}
    for key, pat in names.items():
        m = re.search(pat + r"\s+" + NUM, line)
        if m:
            out[key] = float(m.group(1))
    return out


def pair_history(outdir):
    """Times, normalised distances and offsets |y1 - y0| of particles 0, 1."""
    path = os.path.join(outdir, "particles.csv")
    if not os.path.exists(path):
        return None
    by_step = {}
    with open(path) as f:
        for r in csv.DictReader(f):
            by_step.setdefault(int(r["step"]), {})[int(r["id"])] = r
    t, d, off = [], [], []
    for s in sorted(by_step):
        p = by_step[s]
        if 0 not in p or 1 not in p:
            continue
        x0 = np.array([float(p[0][c]) for c in "xyz"])
        x1 = np.array([float(p[1][c]) for c in "xyz"])
        a = float(p[0]["radius"]) + float(p[1]["radius"])
        t.append(float(p[0]["time"]))
        d.append(np.linalg.norm(x1 - x0) / a)
        off.append(abs(x1[1] - x0[1]))
    if not t:
        return None
    return np.array(t), np.array(d), np.array(off)


def run_case(case, opts, fidus, workdir, log):
    rows = []
    name = case["name"]

    done = {}  # parameters -> row: a run shared by several sweeps (the base) runs once

    def one(sweep, value, entries, tag):
        key = tuple(sorted(entries.items()))
        if key in done:
            row = copy.copy(done[key])
            first = f"{row['sweep']} {row['setting']}" if row["sweep"] != "reference" else "the reference"
            row.update({"sweep": sweep, "setting": fmt(value), "reused": True,
                        "note": "same parameters as " + first + ", not rerun"})
            log(f"[{name}] {sweep} = {fmt(value)}: same parameters as {first}")
            return row
        log(f"[{name}] {sweep} = {fmt(value)} ...")
        res = run_fidus(fidus, entries, workdir, tag, opts.timeout)
        row = {"case": name, "sweep": sweep, "setting": fmt(value), "seconds": res["seconds"],
               "compute_seconds": compute_seconds(res["stdout"]),
               "exit": res["exit"], "warnings": res["warnings"], "status": "ok", "note": ""}
        stats = read_statistics(res["outdir"])
        if stats:
            row.update(stats)
        if res["exit"] != 0:
            row["status"] = "timeout" if res["exit"] == "timeout" else (
                f"failed ({res['exit']})" if isinstance(res["exit"], str) else f"failed (exit {res['exit']})")
            last = [l for l in res["stderr"].splitlines() if l.strip()]
            row["note"] = last[-1][:120] if last else ""
        elif name.startswith("a"):
            ex = parse_exact_line(res["stdout"])
            if ex is None or "l2_error" not in ex:
                row["status"] = "failed (no 'exact rigid inclusion:' line)"
            else:
                row.update({k: v for k, v in ex.items() if k not in ("cells", "dofs")})
                row.setdefault("cells", int(ex.get("cells", 0)))
                row.setdefault("dofs", int(ex.get("dofs", 0)))
                if "l2_norm" in ex and ex["l2_norm"] > 0:
                    row["l2_norm_source"] = "fidus"
                else:
                    # Older fidus without 'L2 norm of exact u (fluid)': use the
                    # L2 norm of the undisturbed linear shear u = (y - 1/2) e_x
                    # (shear rate 1) on the whole unit box, sqrt(1/12) in 2D
                    # and, the other coordinates integrating to 1, sqrt(1/12)
                    # in 3D too. It ignores the particle's disturbance and the
                    # hole of the solid, so it is an approximation only: in
                    # 2D (a = 0.15) fidus reports 0.2695, sqrt(1/12) = 0.2887,
                    # i.e. relative errors about 7 % too small.
                    row["l2_norm"] = math.sqrt(1.0 / 12.0)
                    row["l2_norm_source"] = "fallback sqrt(1/12)"
                row["error"] = row["l2_error"] / row["l2_norm"]
        else:
            hist = pair_history(res["outdir"])
            if hist is None:
                row["status"] = "failed (no particles.csv)"
            else:
                row["history"] = hist
                row["final_offset"] = float(hist[2][-1])
                row["final_time"] = float(hist[0][-1])
        if res["warnings"]:
            row["note"] = (row["note"] + "; " if row["note"] else "") + f"{res['warnings']} warning(s) on stderr"
        s = row["status"] if row["status"] != "ok" else f"{row['seconds']:.1f} s"
        log(f"[{name}] {sweep} = {fmt(value)}: {s}")
        done[key] = row
        return row

    k = 0
    if name == "b":
        ref_e, finest = reference_entries(case, opts)
        desc = ", ".join(f"{n}={fmt(v)}" for n, v in finest.items())
        ref = one("reference", desc, ref_e, "reference")
        ref["setting"] = desc
        rows.append(ref)
    for sweep, values in case["sweeps"]:
        for v in values:
            e = copy.deepcopy(case["base"])
            APPLY[sweep](e, v, opts)
            k += 1
            rows.append(one(sweep, v, e, f"run{k:03d}"))

    if name == "b":
        ref = rows[0]
        for r in rows[1:]:
            if r["status"] != "ok":
                continue
            if ref["status"] != "ok":
                r["note"] = (r["note"] + "; " if r["note"] else "") + "no reference"
                continue
            t, d, off = r["history"]
            tr, dr, offr = ref["history"]
            # d_ref interpolated (linearly) at this run's times, within the
            # reference's time range.
            inside = t <= tr[-1] * (1 + 1e-12)
            r["error"] = float(np.max(np.abs(d[inside] - np.interp(t[inside], tr, dr))))
            r["offset_error"] = abs(r["final_offset"] - ref["final_offset"])
            if r["error"] == 0 and not r.get("reused"):
                r["note"] = (r["note"] + "; " if r["note"] else "") + "same trajectory as the reference"
            if abs(r["final_time"] - ref["final_time"]) > 1e-9 * max(1, ref["final_time"]):
                r["note"] = (r["note"] + "; " if r["note"] else "") + \
                    f"ends at t={r['final_time']:g}, reference at {ref['final_time']:g}"
    return rows


# --------------------------------------------------------------------------
# Reporting
# --------------------------------------------------------------------------
def pareto(rows):
    ok = [r for r in rows if r["status"] == "ok" and r.get("error") is not None
          and math.isfinite(r["error"]) and r["sweep"] != "reference" and not r.get("reused")]
    front = [r for r in ok
             if not any(o["error"] < r["error"] and o["seconds"] < r["seconds"] for o in ok)]
    return sorted(front, key=lambda r: r["seconds"])


def cell(v, f="{:.3e}"):
    if v is None:
        return "–"
    if isinstance(v, float) and not math.isfinite(v):
        return str(v)
    return f.format(v)


def print_table(case, rows):
    name = case["name"]
    print(f"\n### Case {name}: {case['title']}\n")
    if name.startswith("a"):
        err_head = "rel. L2 error u | H1 error u | omega error"
        nerr = 3
    else:
        err_head = "max abs(d - d_ref) | final offset | abs(offset - ref offset)"
        nerr = 3
    cells_head = "cells | DoFs" if name.startswith("a") else "cells (max) | DoFs (max)"
    it_head = "Uzawa | FGMRES" if name.startswith("a") else "Uzawa (sum) | FGMRES (sum)"
    print(f"| sweep | setting | {cells_head} | {it_head} | seconds | compute s | {err_head} | notes |")
    print("|" + "---|" * (10 + nerr - 1))
    for r in rows:
        head = f"| {r['sweep']} | {r['setting']} | {cell(r.get('cells'), '{}')} | " \
               f"{cell(r.get('dofs'), '{}')} | {cell(r.get('uzawa'), '{}')} | " \
               f"{cell(r.get('fgmres'), '{}')} | {r['seconds']:.2f} | " \
               f"{cell(r.get('compute_seconds'), '{:.2f}')} | "
        if r["status"] != "ok":
            errs = " | ".join([r["status"]] + ["–"] * (nerr - 1))
        elif name.startswith("a"):
            errs = f"{cell(r.get('error'))} | {cell(r.get('h1_error'))} | {cell(r.get('omega_error'))}"
        else:
            e = "0 (reference)" if r["sweep"] == "reference" else cell(r.get("error"))
            errs = f"{e} | {cell(r.get('final_offset'), '{:.5f}')} | {cell(r.get('offset_error'))}"
        print(head + errs + f" | {r.get('note', '')} |")
    if name.startswith("a"):
        src = sorted({r["l2_norm_source"] for r in rows if r.get("l2_norm_source")})
        if "fallback sqrt(1/12)" in src:
            print("\n(relative L2 error divided by sqrt(1/12): this fidus does not print "
                  "'L2 norm of exact u (fluid)')")
    front = pareto(rows)
    print(f"\nPareto-optimal runs of case {name} (no other run both faster and more accurate):\n")
    print("| sweep | setting | seconds | error |")
    print("|---|---|---|---|")
    for r in front:
        print(f"| {r['sweep']} | {r['setting']} | {r['seconds']:.2f} | {r['error']:.3e} |")
    if name.startswith("a"):
        target = 0.01
        tu = time_to_reach([r for r in rows if r["sweep"] == "uniform"], target)
        ta = time_to_reach([r for r in rows if r["sweep"] == "adaptive"], target)
        print("\nWall time to reach 1 % relative L2 error (log-log interpolation):")
        print(f"- uniform refinement:  {tu[1]}")
        print(f"- adaptive refinement: {ta[1]}")
        if tu[0] is not None and ta[0] is not None:
            print(f"- ratio uniform / adaptive: {tu[0] / ta[0]:.2f}")
        else:
            print("- ratio uniform / adaptive: not available")
        # The same without the fixed process start-up, which dominates runs
        # of about a second.
        cu = time_to_reach([r for r in rows if r["sweep"] == "uniform"], target, "compute_seconds")
        ca = time_to_reach([r for r in rows if r["sweep"] == "adaptive"], target, "compute_seconds")
        print("\nCompute time (fidus's own timer, without process start-up) to reach 1 %:")
        print(f"- uniform refinement:  {cu[1]}")
        print(f"- adaptive refinement: {ca[1]}")
        if cu[0] is not None and ca[0] is not None:
            print(f"- ratio uniform / adaptive: {cu[0] / ca[0]:.2f}")
        else:
            print("- ratio uniform / adaptive: not available")


def time_to_reach(rows, target, key="seconds"):
    ok = [r for r in rows if r["status"] == "ok" and r.get("error") and r["error"] > 0
          and r.get(key)]
    if not ok:
        return None, "not reached (no successful run)"
    for r0, r1 in zip(ok, ok[1:]):
        e0, e1 = r0["error"], r1["error"]
        if e0 >= target >= e1:
            if e0 == e1:
                t = r1[key]
            else:
                s = (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0))
                t = math.exp(math.log(r0[key]) + s * (math.log(r1[key]) - math.log(r0[key])))
            return t, f"{t:.2f} s (between {r0['sweep']} {r0['setting']} and {r1['setting']})"
    if min(r["error"] for r in ok) > target:
        return None, f"not reached (smallest error {min(r['error'] for r in ok):.3e})"
    return None, (f"not reached (already {ok[0]['error']:.3e} at {ok[0]['setting']}, "
                  "the sweep does not bracket 1 %; start it at a coarser level)")


def plot(case, rows, path):
    fig, ax = plt.subplots(figsize=(7, 5))
    for sweep, _ in case["sweeps"]:
        pts = [r for r in rows if r["sweep"] == sweep and r["status"] == "ok"
               and r.get("error") is not None and r["error"] > 0]
        if not pts:
            continue
        m, c = STYLE[sweep]
        ax.plot([r["seconds"] for r in pts], [r["error"] for r in pts], m, color=c,
                label=SWEEP_LABELS[sweep], ms=7, mfc="none" if sweep == "uniform" else c, alpha=0.85)
        for r in pts:
            ax.annotate(r["setting"], (r["seconds"], r["error"]), fontsize=7,
                        xytext=(4, 3), textcoords="offset points", color=c)
    front = [r for r in pareto(rows) if r["error"] > 0]
    if front:
        ax.plot([r["seconds"] for r in front], [r["error"] for r in front], "-", color="black",
                lw=1, label="Pareto front", zorder=0)
    if case["name"].startswith("a"):
        ax.axhline(0.01, color="grey", lw=0.5, ls=":")
        ax.set_ylabel("relative L2 error of u (fluid)")
    else:
        ax.set_ylabel("max over t of |d - d_ref|, d = |X1 - X0| / (a0 + a1)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time of the run [s]")
    ax.set_title(case["title"], fontsize=10)
    ax.grid(True, which="both", lw=0.3, alpha=0.5)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


CSV_FIELDS = ["case", "sweep", "setting", "status", "exit", "cells", "dofs", "uzawa", "fgmres",
              "steps", "seconds", "compute_seconds", "error", "l2_error", "l2_norm", "l2_norm_source", "h1_error",
              "omega_error", "translation_error", "final_offset", "offset_error", "warnings",
              "note"]


def main():
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--case", action="append", choices=["a2", "a3", "b"],
                    help="case to run, repeatable (default: a2 and b)")
    ap.add_argument("--uniform-2d", type=level_range, default=None, metavar="LO:HI",
                    help="uniform levels, case a2 (default 3:7; --quick 3:5)")
    ap.add_argument("--adaptive-2d", type=level_range, default=None, metavar="LO:HI",
                    help="adaptive maximum levels, case a2 (default 3:8; --quick 3:5)")
    ap.add_argument("--uniform-3d", type=level_range, default=None, metavar="LO:HI",
                    help="uniform levels, case a3 (default 2:4; --quick 2:3)")
    ap.add_argument("--adaptive-3d", type=level_range, default=None, metavar="LO:HI",
                    help="adaptive maximum levels, case a3 (default 3:5; --quick 3)")
    ap.add_argument("--adaptive-b", type=level_range, default=None, metavar="LO:HI",
                    help="adaptive maximum levels, case b (default 5:7; --quick 4:5)")
    ap.add_argument("--radius-2d", type=float, default=0.15,
                    help="particle radius of case a2 (default 0.15)")
    ap.add_argument("--radius-3d", type=float, default=0.2,
                    help="particle radius of case a3 (default 0.2)")
    ap.add_argument("--sweeps", type=lambda v: v.split(","), default=None,
                    metavar="NAME,NAME",
                    help="case a: run only these sweeps, e.g. uniform,adaptive (default: all)")
    ap.add_argument("--coarse-level", type=int, default=2,
                    help="Initial global refinement = Minimum level of the adaptive sweeps (default 2)")
    ap.add_argument("--base-level-2d", type=int, default=None,
                    help="Maximum level (adaptive) of the other sweeps, case a2 (default 6; --quick 4)")
    ap.add_argument("--base-level-3d", type=int, default=None,
                    help="Maximum level (adaptive) of the other sweeps, case a3 (default 4; --quick 3)")
    ap.add_argument("--base-level-b", type=int, default=None,
                    help="Maximum level of the other sweeps, case b (default: the scene's; --quick 5)")
    ap.add_argument("--scene-b", default=os.path.join(TOP, "prm", "two_particles_2d.prm"),
                    help="parameter file of case b (default prm/two_particles_2d.prm)")
    ap.add_argument("--end-time", type=float, default=None,
                    help="End time of case b (default: the scene's; --quick 0.4)")
    ap.add_argument("--reference", action="append", default=[], metavar="SWEEP=VALUE",
                    help="case b: override one setting of the reference run, e.g. penalty=1e4 "
                         "(default: the finest value of every sweep)")
    ap.add_argument("--timeout", type=float, default=None,
                    help="seconds after which a run is stopped and reported as 'timeout'")
    ap.add_argument("--quick", action="store_true",
                    help="tiny sweep for smoke testing (about a minute)")
    ap.add_argument("--out", default=os.path.join(TOP, "doc"), help="folder for the PNGs (default doc/)")
    ap.add_argument("--csv", default=None, metavar="FILE", help="save every row to FILE")
    opts = ap.parse_args()

    q = opts.quick
    defaults = {
        "uniform_2d": "3:5" if q else "3:7", "adaptive_2d": "3:5" if q else "3:8",
        "uniform_3d": "2:3" if q else "2:4", "adaptive_3d": "3" if q else "3:5",
        "adaptive_b": "4:5" if q else "5:7",
    }
    for k, v in defaults.items():
        if getattr(opts, k) is None:
            setattr(opts, k, level_range(v))
    if opts.base_level_2d is None:
        opts.base_level_2d = 4 if q else 6
    if opts.base_level_3d is None:
        opts.base_level_3d = 3 if q else 4
    if q and opts.base_level_b is None:
        opts.base_level_b = 5
    if q and opts.end_time is None:
        opts.end_time = 0.4
    cases = opts.case or ["a2", "b"]

    fidus = os.environ.get("FIDUS")
    if not fidus:
        fidus = os.path.join(TOP, "build-release", "fidus")
        if not os.path.exists(fidus):
            subprocess.run([os.path.join(TOP, "contrib", "build.sh"), "fidus"],
                           stdout=subprocess.DEVNULL, check=True)
    if not os.access(fidus, os.X_OK):
        sys.exit(f"work_precision.py: no executable fidus at {fidus}")
    os.makedirs(opts.out, exist_ok=True)

    def log(msg):
        print(msg, file=sys.stderr, flush=True)

    log(f"fidus: {fidus}")
    all_rows = []
    t_start = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="fidus_work_precision_") as workdir:
        for c in cases:
            case = case_a(int(c[1]), opts) if c.startswith("a") else case_b(opts)
            rows = run_case(case, opts, fidus, workdir, log)
            print_table(case, rows)
            png = os.path.join(opts.out, f"work_precision_{case['name']}.png")
            plot(case, rows, png)
            print(f"\nfigure: {png}")
            sys.stdout.flush()
            all_rows += rows
    print(f"\ntotal wall time: {time.perf_counter() - t_start:.1f} s")
    if opts.csv:
        with open(opts.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=CSV_FIELDS, extrasaction="ignore")
            w.writeheader()
            for r in all_rows:
                w.writerow(r)
        print(f"rows: {opts.csv}")


if __name__ == "__main__":
    main()
