#!/usr/bin/env python3
"""Convergence study for one fidus setting.

Runs a fidus scene for a sequence of values of one setting (mesh level, time
step, tolerances, penalty factor, ...), compares the particle trajectories of
successive runs, estimates observed orders and Richardson extrapolations of
the scene's scalar results, and prints a Markdown table with a verdict.
See doc/convergence.md and --help.

Standard library only; matplotlib is used for the figure when it is
installed, and the figure is skipped with a message when it is not.
"""

import argparse
import concurrent.futures
import csv
import difflib
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import threading
import time

# Reading the runs and the numerical analysis live next to this script.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from convergence_analysis import (  # noqa: E402
    EXACT_LINE,
    Trajectory,
    assess_known_limit,
    assess_sequence,
    load_results,
    max_trajectory_difference,
    pair_scalars,
    pair_series,
    parse_prm,
    read_text,
    run_scalars,
)

PROG = "convergence_study.py"
REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# Entries whose values are mesh levels: one level halves the cell size, so
# the refinement ratio of a step is 2 per level rather than a value ratio.
LEVEL_ENTRIES = {"Maximum level", "Minimum level", "Initial global refinement"}

# Set in every variant before the user's --set overrides.
DRIVER_SETTINGS = [
    ("Output/Verbosity", "quiet"),
    ("Output/Particle output interval", "0"),
    ("Output/Field output interval", "0"),
    ("Output/Checkpoint interval", "0"),
    ("Output/Checkpoint wall interval", "0"),
]

# The quantities of the exact-inclusion line that the study follows, with
# their key in the line and the name used in tables and CSV files.
EXACT_QUANTITIES = [
    ("L2 error of u (fluid)", "l2_error", "L2 error u"),
    ("H1 error of u (fluid)", "h1_error", "H1 error u"),
    ("relative omega error", "omega_error", "ω error"),
]

EPILOG = """\
The setting to vary:
  --vary "Subsection/Entry=v1,v2,v3,..."
      Values separated by commas, ordered from coarse/loose to fine/tight.
      Nested subsections are separated by '/', e.g.
      "Fluid/Linear solver/Tolerance=1e-4,1e-6,1e-8"; a top-level entry has
      no '/'. Several entries that take the same value are joined by '+':
      "Mesh refinement/Initial global refinement+Mesh refinement/Minimum
      level+Mesh refinement/Maximum level=3,4,5" (uniform refinement).
  Refinement ratio r of a step: 2 per level for 'Maximum level',
  'Minimum level' and 'Initial global refinement'; otherwise the ratio of
  the two values, taken >= 1 (0.2 -> 0.1 gives 2, 100 -> 1000 gives 10).

What is run:
  For each value, <work>/run_<value>/run.prm: a copy of PRM followed by the
  driver's output settings (Verbosity quiet, no field/particle output, no
  checkpoints), the --set overrides, the value, and the Output directory
  <work>/run_<value>/output. fidus's screen goes to stdout.txt and
  stderr.txt there, its exit status to exit_status.

What is printed (stdout; progress and failures go to stderr):
  A Markdown table, one row per value: cells and DoFs of the last step,
  wall seconds, FGMRES iterations (sum), max |dX|/a against the next run,
  d_min, final offset, glued time (exact-inclusion scenes: the error norms),
  then observed orders with Richardson extrapolations or 'not asymptotic',
  and a verdict naming the cheapest value whose trajectories are within
  --target of 2a of the next finer run.

What is compared (successive successful runs k and k+1):
  max |dX|/a   largest distance between a particle's centres in the two
               runs over particles and over the times both runs cover
               (linear interpolation in time when the steps differ; the
               minimum image in x, and z in 3D, for 'sliding walls')
  d_min        min over time of d(t) = |X1 - X0| / (a0 + a1), particles 0, 1
  offset       |y1 - y0| / (a0 + a1) at the last time all runs reached
  glued time   sum of dt over the steps with glued_contacts > 0
  Orders: from three successive values of a scalar,
  p = log(|q_k - q_k+1| / |q_k+1 - q_k+2|) / log(r) and the extrapolation
  q_k+2 + (q_k+2 - q_k+1) / (r^p - 1), shown only when the differences
  decrease monotonically, keep their sign, and the orders of consecutive
  triples differ by at most 50 %; otherwise 'not asymptotic'. Errors of
  the exact rigid inclusion (and max |dX|/a, whose limit is 0):
  p = log(e_k / e_k+1) / log(r), plus a least-squares fit over all runs.

Exit status: 0 when every run succeeded, 1 for bad input (nothing run),
  2 when a fidus run failed (the others are still compared).

Examples:
  contrib/convergence_study.py prm/two_particles_2d.prm \\
      --vary "Mesh refinement/Maximum level=4,5,6" --set "Time stepping/End time=3"
  contrib/convergence_study.py prm/two_particles_2d.prm \\
      --vary "Time stepping/Time step=0.2,0.1,0.05" --set "Time stepping/End time=3" \\
      --work /tmp/dt_study --reuse --csv /tmp/dt_study/table.csv
  contrib/convergence_study.py prm/exact_rigid_inclusion_2d.prm --vary \\
      "Mesh refinement/Initial global refinement+Mesh refinement/Minimum level+Mesh refinement/Maximum level=3,4,5,6"
  contrib/convergence_study.py prm/two_particles_2d.prm --vary "Fluid/Penalty factor=1e2,1e3,1e4" --dry-run
"""


class UsageError(Exception):
    """Bad input: reported in one line with exit status 1, before any run."""


class ArgumentParser(argparse.ArgumentParser):
    """argparse with the driver's convention for bad input.

    argparse prints the whole usage and exits with 2; the driver promises
    one clear line and exit status 1 for every kind of bad input.
    """

    def error(self, message):
        """Raise instead of printing usage, so main() reports it in one line."""
        raise UsageError(message + " (see --help)")


# ---------------------------------------------------------------------------
# Parameter files
# ---------------------------------------------------------------------------


def overrides_text(pairs):
    """Return prm text for a list of (key, value), one block per subsection run.

    Consecutive entries of the same subsection share one block, so that a
    variant stays readable; the order of the entries is kept.
    """
    groups = []
    for key, value in pairs:
        parent = key.split("/")[:-1]
        if groups and groups[-1][0] == parent:
            groups[-1][1].append((key, value))
        else:
            groups.append((parent, [(key, value)]))
    text = ""
    for parent, items in groups:
        depth = len(parent)
        text += "".join("  " * d + f"subsection {sub}\n" for d, sub in enumerate(parent))
        text += "".join("  " * depth + f"set {key.split('/')[-1]} = {value}\n"
                        for key, value in items)
        text += "".join("  " * d + "end\n" for d in reversed(range(depth)))
    return text


def normalise_key(text):
    """Turn ' Mesh refinement / Maximum level ' into 'Mesh refinement/Maximum level'."""
    return "/".join(" ".join(part.split()) for part in text.split("/"))


def check_key(key, known, option):
    """Raise UsageError unless key names an entry that fidus declares."""
    if not key or any(not part for part in key.split("/")):
        raise UsageError(f"{option}: '{key}' is not of the form 'Subsection/Entry'")
    if known is not None and key not in known:
        hint = difflib.get_close_matches(key, sorted(known), n=3, cutoff=0.6)
        if not hint:
            # Maybe only the subsection was forgotten or misspelt.
            leaf = key.split("/")[-1]
            hint = sorted(k for k in known if k.split("/")[-1] == leaf)
        message = f"{option}: fidus has no entry '{key}'"
        if hint:
            message += "; did you mean " + " or ".join(f"'{h}'" for h in hint) + "?"
        raise UsageError(message)


def parse_vary(spec, known):
    """Parse 'Key[+Key...]=v1,v2,...' into (keys, value strings, numbers)."""
    if "=" not in spec:
        raise UsageError(f"--vary '{spec}': expected 'Subsection/Entry=v1,v2,...'")
    names, values_text = spec.split("=", 1)
    keys = [normalise_key(n) for n in names.split("+")]
    for key in keys:
        check_key(key, known, "--vary")
    if len(set(keys)) != len(keys):
        raise UsageError(f"--vary '{spec}': an entry is named twice")
    values = [v.strip() for v in values_text.split(",")]
    if any(not v for v in values):
        raise UsageError(f"--vary '{spec}': an empty value in the list '{values_text}'")
    numbers = []
    for v in values:
        try:
            x = float(v)
        except ValueError:
            raise UsageError(f"--vary '{spec}': value '{v}' is not a number") from None
        if not math.isfinite(x):
            raise UsageError(f"--vary '{spec}': value '{v}' is not a finite number")
        numbers.append(x)
    if len(values) < 2:
        raise UsageError(f"--vary '{spec}': give at least two values (three for orders)")
    if is_level(keys):
        if any(x != int(x) for x in numbers):
            raise UsageError(f"--vary '{spec}': mesh levels must be whole numbers")
    elif any(x <= 0 for x in numbers):
        # The refinement ratio is a ratio of values: it needs positive ones.
        raise UsageError(f"--vary '{spec}': values must be > 0 "
                         "(the ratio of two values is the refinement ratio)")
    steps = [b - a for a, b in zip(numbers, numbers[1:])]
    if not (all(s > 0 for s in steps) or all(s < 0 for s in steps)):
        raise UsageError(
            f"--vary '{spec}': values must be distinct and ordered (from coarse/loose to fine/tight)")
    return keys, values, numbers


def parse_set(spec, known):
    """Parse one --set 'Key=value' into (key, value)."""
    if "=" not in spec:
        raise UsageError(f"--set '{spec}': expected 'Subsection/Entry=value'")
    name, value = spec.split("=", 1)
    key = normalise_key(name)
    check_key(key, known, "--set")
    if key == "Output directory":
        raise UsageError("--set: the driver chooses 'Output directory' (use --work)")
    return key, value.strip()


def is_level(keys):
    """True when the varied entries are mesh levels (ratio 2 per level)."""
    return any(k.split("/")[-1] in LEVEL_ENTRIES for k in keys)


def step_ratio(v0, v1, level):
    """Refinement ratio r >= 1 of the step from value v0 to value v1."""
    if level:
        return 2.0 ** abs(v1 - v0)
    # Taken >= 1 so that entries refined by growing (penalty factor) and by
    # shrinking (time step, tolerances) are treated alike.
    return max(v0 / v1, v1 / v0)


def fidus_entries(fidus):
    """Return the {key: default} of every entry fidus declares."""
    try:
        out = subprocess.run([fidus, "--print-parameters"], capture_output=True,
                             text=True, timeout=120)
    except OSError as e:
        raise UsageError(f"cannot run fidus '{fidus}': {e.strerror}") from None
    if out.returncode != 0 or "set " not in out.stdout:
        tail = out.stderr.strip().splitlines()[-1:] or ["no output"]
        raise UsageError(f"'{fidus} --print-parameters' failed "
                         f"(exit status {out.returncode}): {tail[0]}")
    return parse_prm(out.stdout)


def slug(value):
    """Folder-name friendly version of a value string."""
    return re.sub(r"[^A-Za-z0-9._+-]", "_", value)


class Variant:
    """One value of the sequence: its folder, its prm text, and the run's results."""

    def __init__(self, index, value, number, folder):
        """A variant for value (its string and its number) run in folder."""
        self.index = index
        self.value = value          # as given on the command line
        self.number = number        # as a float, for ratios and axes
        self.folder = folder
        self.prm_path = os.path.join(folder, "run.prm")
        self.output = os.path.join(folder, "output")
        self.prm_text = ""
        self.exact = False          # exact-rigid-inclusion scene
        # Filled after the run.
        self.status = None          # fidus exit status (0: success)
        self.reused = False
        self.seconds = None         # elapsed seconds measured by the driver
        self.stderr_tail = []
        self.stats = None           # list of dicts from statistics.csv
        self.particles = None       # {id: Trajectory}
        self.exact_values = {}      # from the exact-inclusion line
        self.geometry = None
        self.problem = ""           # why a finished run cannot be used

    @property
    def ok(self):
        """True when the run finished and its output could be read."""
        return self.status == 0 and not self.problem


def build_variants(keys, values, numbers, overrides, prm_text, prm_path, work, defaults):
    """Make the Variant objects and the full text of their prm files."""
    prm_dir = os.path.dirname(os.path.abspath(prm_path))
    original = parse_prm(prm_text)
    variants = []
    for index, (value, number) in enumerate(zip(values, numbers)):
        folder = os.path.join(work, "run_" + slug(value))
        v = Variant(index, value, number, folder)
        parts = [prm_text.rstrip("\n") + "\n",
                 "\n# ---- added by contrib/convergence_study.py ----\n",
                 "# Short screens and no field/particle/checkpoint files: the\n",
                 "# study reads only the CSV files (and the exact-inclusion line).\n"]
        # An older fidus may lack some of these entries: set only known ones.
        parts.append(overrides_text([(key, val) for key, val in DRIVER_SETTINGS
                                     if not defaults or key in defaults]))
        # fidus reads a relative 'Positions file' next to the prm file;
        # the variant lives elsewhere, so make the path absolute.
        positions = original.get("Particles/Positions file", "")
        if positions and not os.path.isabs(positions):
            parts.append(overrides_text([("Particles/Positions file",
                                          os.path.join(prm_dir, positions))]))
        fixed = []
        for key, val in overrides:
            if key == "Particles/Positions file" and val and not os.path.isabs(val):
                val = os.path.abspath(val)  # typed relative to the caller
            fixed.append((key, val))
        parts.append(overrides_text(fixed))
        parts.append(overrides_text([(key, value) for key in keys]))
        text = "".join(parts)
        effective = dict(defaults)
        effective.update(parse_prm(text))
        v.exact = effective.get("Domain/Boundary condition", "") == "exact rigid inclusion"
        if v.exact and effective.get("Output/Verbosity", "normal") == "quiet":
            # The exact-inclusion errors are printed on the screen only, and
            # 'quiet' suppresses that line.
            text += ("# The exact-inclusion errors are a screen line that 'quiet' hides.\n"
                     + overrides_text([("Output/Verbosity", "normal")]))
        text += f"set Output directory = {v.output}\n"
        v.prm_text = text
        variants.append(v)
    return variants


# ---------------------------------------------------------------------------
# Running fidus
# ---------------------------------------------------------------------------


def complete_run(v):
    """True when v.folder holds a finished successful run of exactly v.prm_text."""
    if read_text(v.prm_path) != v.prm_text:
        return False
    if (read_text(os.path.join(v.folder, "exit_status")) or "").strip() != "0":
        return False
    for name in ("statistics.csv", "particles.csv", "used_parameters.prm"):
        if not os.path.isfile(os.path.join(v.output, name)):
            return False
    if v.exact and EXACT_LINE not in (read_text(os.path.join(v.folder, "stdout.txt")) or ""):
        return False
    return True


def tail_lines(path, n=8):
    """Return the last n non-empty lines of a file."""
    text = read_text(path) or ""
    return [line for line in text.splitlines() if line.strip()][-n:]


def run_variant(v, fidus, reuse, log):
    """Run fidus on v (or reuse a complete earlier run) and record the status."""
    if reuse and complete_run(v):
        v.status, v.reused = 0, True
        log(f"  {v.value}: reused {v.folder}")
        return v
    os.makedirs(v.folder, exist_ok=True)
    # Stale files of an earlier run must not be mistaken for this run's.
    if os.path.isdir(v.output):
        shutil.rmtree(v.output)
    for name in ("exit_status", "stdout.txt", "stderr.txt"):
        if os.path.exists(os.path.join(v.folder, name)):
            os.remove(os.path.join(v.folder, name))
    with open(v.prm_path, "w") as f:
        f.write(v.prm_text)
    log(f"  {v.value}: running")
    start = time.monotonic()
    with open(os.path.join(v.folder, "stdout.txt"), "w") as out, \
            open(os.path.join(v.folder, "stderr.txt"), "w") as err:
        try:
            status = subprocess.run([fidus, v.prm_path], stdout=out, stderr=err,
                                    stdin=subprocess.DEVNULL, cwd=v.folder).returncode
        except OSError as e:
            err.write(f"cannot start {fidus}: {e.strerror}\n")
            status = 127
    v.seconds = time.monotonic() - start
    v.status = status
    with open(os.path.join(v.folder, "exit_status"), "w") as f:
        f.write(f"{status}\n")
    if status == 0:
        log(f"  {v.value}: done in {v.seconds:.1f} s")
    else:
        v.stderr_tail = tail_lines(os.path.join(v.folder, "stderr.txt"))
    return v


def describe_status(status):
    """Human-readable exit status, naming the signal for a killed process."""
    if status is not None and status < 0:
        return f"killed by signal {-status}"
    return f"exit status {status}"


def validate_variants(variants, fidus, jobs):
    """Let fidus --validate every variant; raise UsageError with its message.

    A value fidus rejects (out of range, wrong kind) is bad input, reported
    before anything runs rather than as N identical failed runs.
    """
    scratch = tempfile.mkdtemp(prefix="convergence_validate_")
    try:
        def check(v):
            """Run fidus --validate on the text of variant v."""
            path = os.path.join(scratch, f"{v.index}.prm")
            with open(path, "w") as f:
                f.write(v.prm_text)
            out = subprocess.run([fidus, "--validate", path], capture_output=True, text=True)
            return v, out

        with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
            for v, out in pool.map(check, variants):
                if out.returncode != 0:
                    lines = [line for line in out.stderr.splitlines() if line.strip()]
                    message = lines[0] if lines else describe_status(out.returncode)
                    raise UsageError(f"fidus rejects the variant for value {v.value}: {message}")
    finally:
        shutil.rmtree(scratch, ignore_errors=True)


# ---------------------------------------------------------------------------
# Reporting
# ---------------------------------------------------------------------------


def fmt(x, digits=5):
    """Format a number for the Markdown table ('–' when missing)."""
    if x is None:
        return "–"
    if isinstance(x, int):
        return str(x)
    return f"{x:.{digits}g}"


def analyse(variants, level):
    """Compute every per-run and per-pair quantity; return the report data."""
    good = [v for v in variants if v.ok]
    rows = {v.index: {} for v in variants}
    for v in good:
        rows[v.index].update(run_scalars(v))
        for key, name, _ in EXACT_QUANTITIES:
            if key in v.exact_values:
                rows[v.index][name] = v.exact_values[key]
    # Successive successful runs are compared; a failed run is skipped.
    ratios = [step_ratio(a.number, b.number, level) for a, b in zip(good, good[1:])]
    for a, b in zip(good, good[1:]):
        best = max_trajectory_difference(a, b)
        if best is not None:
            rows[a.index]["max_dx"] = best[0]
            rows[a.index]["max_dx_particle"] = best[1]
            rows[a.index]["max_dx_time"] = best[2]
            rows[a.index]["next_value"] = b.value
    has_pair = any(0 in v.particles and 1 in v.particles for v in good)
    t_common = None
    if good and has_pair:
        t_common = min(min(v.particles[0].t[-1], v.particles[1].t[-1]) for v in good)
        for v in good:
            rows[v.index].update(pair_scalars(v, t_common))
    moving = any(len(t.t) > 1 for v in good for t in v.particles.values())
    exact = any(v.exact for v in good)

    labels = [v.value for v in good]
    assessments = []
    scalars = []
    if has_pair:
        scalars += [("d_min", "d_min"), ("offset", "offset"), ("glued_time", "glued time")]
    for name, title in scalars:
        qs = [rows[v.index].get(name) for v in good]
        if len(qs) >= 3 and all(q is not None for q in qs):
            assessments.append((title, "sequence", assess_sequence(labels, qs, ratios)))
    if exact:
        for _, name, title in EXACT_QUANTITIES:
            es = [rows[v.index].get(name) for v in good]
            if len(es) >= 2 and all(e is not None for e in es):
                assessments.append((title, "known", assess_known_limit(labels, es, ratios)))
    if moving:
        dx = [rows[a.index].get("max_dx") for a in good[:-1]]
        if len(dx) >= 2 and all(d is not None for d in dx):
            # max|dX| between runs j and j+1 behaves like C h_j^p, so it
            # shrinks like an error with a known limit of 0.
            pair_labels = [f"{a}:{b}" for a, b in zip(labels, labels[1:])]
            assessments.append(("max |ΔX|/a", "known",
                                assess_known_limit(pair_labels, dx, ratios)))
    return {"rows": rows, "good": good, "ratios": ratios, "has_pair": has_pair,
            "moving": moving, "exact": exact, "t_common": t_common,
            "assessments": assessments}


def columns_for(report):
    """The table columns that make sense for this scene: (key, title)."""
    cols = [("cells", "cells"), ("dofs", "DoFs"), ("wall_seconds", "wall s"),
            ("fgmres", "FGMRES")]
    if report["moving"]:
        cols.append(("max_dx", "max \\|ΔX\\|/a vs next"))
    if report["has_pair"]:
        cols += [("d_min", "d_min"), ("offset", "offset"), ("glued_time", "glued time")]
    if report["exact"]:
        cols += [(name, title) for _, name, title in EXACT_QUANTITIES]
    return cols


def assessment_lines(report):
    """Markdown lines with the orders, extrapolations or 'not asymptotic'."""
    lines = []
    for title, kind, a in report["assessments"]:
        if kind == "sequence":
            parts = []
            for t in a["triples"]:
                seq = "→".join(t["labels"])
                if t["p"] is None:
                    continue
                if a["asymptotic"]:
                    parts.append(f"{seq}: p = {t['p']:.3g}, extrapolated {t['extrapolated']:.6g}")
                else:
                    parts.append(f"{seq}: p = {t['p']:.3g}")
            verdict = "" if a["asymptotic"] else f" — not asymptotic ({a['reason']}), no extrapolation"
        else:
            parts = [f"{'→'.join(p['labels'])}: p = {fmt(p['p'], 3)}" for p in a["pairs"]]
            if a["fit"] is not None:
                parts.append(f"least-squares fit over all runs: p = {a['fit']:.3g}")
            verdict = "" if a["asymptotic"] else f" — not asymptotic ({a['reason']})"
        if a.get("constant"):
            lines.append(f"- {title}: the same value in every run")
        elif parts:
            lines.append(f"- {title}: " + "; ".join(parts) + verdict)
        else:
            lines.append(f"- {title}: not asymptotic ({a['reason']})")
    return lines


def verdict_line(report, variants, target, label):
    """The cheapest value whose trajectories are within target of 2a of the next run."""
    if not report["moving"]:
        return None
    rows = report["rows"]
    candidates = [v for v in report["good"] if rows[v.index].get("max_dx") is not None]
    if not candidates:
        return "Verdict: no two successful runs to compare."
    within = [v for v in candidates if rows[v.index]["max_dx"] / 2 <= target]
    if not within:
        best = min(candidates, key=lambda v: rows[v.index]["max_dx"])
        r = rows[best.index]
        return (f"Verdict: no value is within {target:g} of 2a of the next finer run "
                f"(smallest max |ΔX|/(2a) = {r['max_dx'] / 2:.3g}, {label} = {best.value} "
                f"against {r['next_value']}).")
    # Cheapest by measured wall time; the sequence order breaks ties.
    best = min(within, key=lambda v: (rows[v.index]["wall_seconds"], v.index))
    r = rows[best.index]
    return (f"Verdict: {label} = {best.value} is the cheapest value within {target:g} of 2a "
            f"of the next finer run (max |ΔX|/(2a) = {r['max_dx'] / 2:.3g} against "
            f"{r['next_value']}; {r['wall_seconds']:.3g} s).")


def markdown(report, variants, label, target):
    """The whole Markdown report as a string."""
    cols = columns_for(report)
    rows = report["rows"]
    lines = ["| " + " | ".join([label] + [t for _, t in cols]) + " |",
             "|" + "---|" * (len(cols) + 1)]
    for v in variants:
        if v.ok:
            cells = [fmt(rows[v.index].get(k)) for k, _ in cols]
            name = v.value + (" (reused)" if v.reused else "")
        else:
            why = describe_status(v.status) if v.status != 0 else v.problem
            cells = ["–"] * len(cols)
            name = f"{v.value} (failed: {why})"
        lines.append("| " + " | ".join([name] + cells) + " |")
    lines.append("")
    if report["t_common"] is not None:
        lines.append(f"d_min, offset and glued time up to t = {report['t_common']:g} "
                     "(the last time all runs reached); max |ΔX|/a over the times both runs cover.")
    if report["ratios"]:
        lines.append("Refinement ratios r between successive runs: "
                     + ", ".join(f"{r:g}" for r in report["ratios"]) + ".")
    lines.append("")
    order_lines = assessment_lines(report)
    if order_lines:
        lines.append("Observed orders (p), Richardson extrapolation where asymptotic:")
        lines.append("")
        lines += order_lines
        lines.append("")
    verdict = verdict_line(report, variants, target, label)
    if verdict:
        lines.append(verdict)
    return "\n".join(lines).rstrip() + "\n"


def write_csv(path, report, variants):
    """The table at full precision, and the orders in <stem>_orders.csv."""
    rows = report["rows"]
    fields = ["value", "status", "cells", "dofs", "wall_seconds", "fgmres",
              "max_dx_over_a_next", "next_value", "d_min", "offset", "glued_time",
              "l2_error", "h1_error", "omega_error", "run_dir"]
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(fields)
        for v in variants:
            r = rows[v.index]
            status = "ok" if v.ok else (describe_status(v.status) if v.status != 0 else v.problem)

            def cell(key):
                """A table entry at full precision ('' when missing)."""
                x = r.get(key)
                return "" if x is None else repr(x) if isinstance(x, float) else str(x)

            w.writerow([v.value, status, cell("cells"), cell("dofs"), cell("wall_seconds"),
                        cell("fgmres"), cell("max_dx"), cell("next_value"), cell("d_min"),
                        cell("offset"), cell("glued_time"), cell("l2_error"),
                        cell("h1_error"), cell("omega_error"), v.folder])
    stem = path[:-4] if path.endswith(".csv") else path
    with open(stem + "_orders.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["quantity", "values", "order", "extrapolated", "asymptotic", "reason"])
        for title, kind, a in report["assessments"]:
            items = a["triples"] if kind == "sequence" else a["pairs"]
            for item in items:
                extrapolated = item.get("extrapolated") if a["asymptotic"] else None
                w.writerow([title, " ".join(item["labels"]),
                            "" if item["p"] is None else repr(item["p"]),
                            "" if extrapolated is None else repr(extrapolated),
                            "yes" if a["asymptotic"] else "no", a["reason"]])
            if kind == "known" and a["fit"] is not None:
                runs = [items[0]["labels"][0]] + [i["labels"][1] for i in items]
                w.writerow([title, "fit " + " ".join(runs), repr(a["fit"]), "",
                            "yes" if a["asymptotic"] else "no", a["reason"]])
    return stem + "_orders.csv"


def plot(path, report, label, level, log):
    """Draw d(t) per run and max |ΔX|/a against the value; skip without matplotlib."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        import matplotlib.ticker
    except ImportError:
        log(f"matplotlib is not installed: no figure written ({path})")
        return False
    good = report["good"]
    rows = report["rows"]

    def value_axis(ax):
        """Levels are whole numbers on a linear axis; other values span decades."""
        if level:
            ax.xaxis.set_major_locator(matplotlib.ticker.MaxNLocator(integer=True))
        else:
            ax.set_xscale("log")
        ax.set_yscale("log")

    dx = [(v.number, rows[v.index]["max_dx"]) for v in good
          if rows[v.index].get("max_dx", 0) > 0]
    # Nothing moves (e.g. End time 0): the second panel would be empty.
    panels = 2 if dx else 1
    fig, axes = plt.subplots(1, panels, figsize=(5.5 * panels, 4), squeeze=False)
    ax1 = axes[0][0]
    if report["has_pair"]:
        for v in good:
            times, d = pair_series(v)
            ax1.plot(times, d, label=f"{label} = {v.value}")
        ax1.axhline(1, color="grey", lw=0.5)
        ax1.set_xlabel("t")
        ax1.set_ylabel("d(t) = |X1 − X0| / (a0 + a1)")
        ax1.legend(fontsize=8)
    elif report["exact"]:
        # One particle, no motion: show the errors instead of d(t).
        for _, name, title in EXACT_QUANTITIES:
            pts = [(v.number, rows[v.index][name]) for v in good
                   if rows[v.index].get(name, 0) > 0]
            if pts:
                ax1.plot(*zip(*pts), "o-", label=title)
        value_axis(ax1)
        ax1.set_xlabel(label)
        ax1.set_ylabel("error")
        ax1.legend(fontsize=8)
    else:
        ax1.set_axis_off()
    if dx:
        ax2 = axes[0][1]
        ax2.plot(*zip(*dx), "o-")
        value_axis(ax2)
        ax2.set_xlabel(label + " (compared with the next value)")
        ax2.set_ylabel("max |ΔX| / a")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return True


# ---------------------------------------------------------------------------
# Main
# ---------------------------------------------------------------------------


def make_parser():
    """The command-line parser, with --help text and examples."""
    p = ArgumentParser(
        prog=PROG,
        description="Run a fidus scene for a sequence of values of one setting, compare "
                    "successive runs, and estimate observed orders and extrapolations.",
        epilog=EPILOG, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("prm", help="the scene's parameter file")
    p.add_argument("--vary", required=True, metavar="ENTRY[+ENTRY...]=V1,V2,...",
                   help="the setting to vary and its values, coarse/loose to fine/tight")
    p.add_argument("--set", action="append", default=[], metavar="ENTRY=VALUE",
                   help="a fixed override for every run (repeatable)")
    p.add_argument("--jobs", type=int, default=os.cpu_count() or 1, metavar="N",
                   help="runs at a time (default: number of cores, %(default)s here)")
    p.add_argument("--work", metavar="DIR",
                   help="folder for the runs, kept (default: a new temporary folder, kept)")
    p.add_argument("--reuse", action="store_true",
                   help="reuse a run whose folder holds complete output of the same prm")
    p.add_argument("--fidus", metavar="PATH",
                   help="the fidus binary (default: $FIDUS, else <repo>/build-release/fidus)")
    p.add_argument("--target", type=float, default=0.01,
                   help="verdict threshold on max |ΔX|/(2a) (default 0.01)")
    p.add_argument("--png", metavar="FILE", help="figure (default: <work>/convergence.png)")
    p.add_argument("--csv", metavar="FILE",
                   help="also write the table as CSV, and the orders to <FILE stem>_orders.csv")
    p.add_argument("--dry-run", action="store_true",
                   help="print the variant prm files and run nothing")
    return p


def main(argv):
    """Parse the command line, run the study, print the report; return the exit status."""
    parser = make_parser()
    args = parser.parse_args(argv)

    # A single --vary is the whole point of the tool: several would be a
    # grid, which the comparison of successive runs does not cover.
    if sum(1 for a in argv if a == "--vary" or a.startswith("--vary=")) > 1:
        raise UsageError("--vary: give exactly one (join entries that share the values with '+')")
    if args.jobs < 1:
        raise UsageError(f"--jobs: must be at least 1, not {args.jobs}")
    if not (args.target > 0):
        raise UsageError(f"--target: must be > 0, not {args.target}")
    prm_text = read_text(args.prm)
    if prm_text is None:
        raise UsageError(f"cannot read the parameter file '{args.prm}'")
    fidus = args.fidus or os.environ.get("FIDUS") or os.path.join(REPO, "build-release", "fidus")
    fidus = os.path.abspath(fidus)
    have_fidus = os.path.isfile(fidus) and os.access(fidus, os.X_OK)
    if not have_fidus and not args.dry_run:
        raise UsageError(f"no executable fidus at '{fidus}' (build it, or give --fidus or $FIDUS)")

    defaults = fidus_entries(fidus) if have_fidus else {}
    known = set(defaults) if have_fidus else None
    keys, values, numbers = parse_vary(args.vary, known)
    overrides = [parse_set(s, known) for s in args.set]
    clash = sorted({k for k, _ in overrides} & set(keys))
    if clash:
        raise UsageError(f"--set: '{clash[0]}' is also the varied entry")
    level = is_level(keys)
    label = " + ".join(k.split("/")[-1] for k in keys)

    if args.work:
        work = os.path.abspath(args.work)
        if os.path.exists(work) and not os.path.isdir(work):
            raise UsageError(f"--work: '{args.work}' exists and is not a folder")
    elif args.dry_run:
        work = "<temporary folder>"
    else:
        work = tempfile.mkdtemp(prefix="convergence_study_")
    variants = build_variants(keys, values, numbers, overrides, prm_text, args.prm, work,
                              defaults)

    if args.dry_run:
        for v in variants:
            print(f"# ===== {v.prm_path} ({label} = {v.value})")
            print(v.prm_text)
        return 0

    log_lock = threading.Lock()

    def log(message):
        """Progress and failures on stderr, keeping stdout a clean Markdown report.

        Runs report from several threads: one write per line under a lock
        keeps their lines whole.
        """
        with log_lock:
            sys.stderr.write(message + "\n")
            sys.stderr.flush()

    # A run that --reuse will take was validated when it ran.
    try:
        validate_variants([v for v in variants if not (args.reuse and complete_run(v))],
                          fidus, args.jobs)
    except UsageError:
        if not args.work:
            os.rmdir(work)  # the empty temporary folder made above
        raise
    os.makedirs(work, exist_ok=True)
    log(f"convergence study: {len(variants)} runs of {args.prm} in {work}, "
        f"{args.jobs} at a time")
    start = time.monotonic()
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        list(pool.map(lambda v: run_variant(v, fidus, args.reuse, log), variants))
    log(f"all runs finished in {time.monotonic() - start:.1f} s")
    failed = False
    for v in variants:
        if v.status != 0:
            failed = True
            log(f"fidus failed for {label} = {v.value} ({describe_status(v.status)}); "
                f"last lines of {os.path.join(v.folder, 'stderr.txt')}:")
            for line in v.stderr_tail or ["(empty)"]:
                log("    " + line)
            continue
        load_results(v)
        if v.problem:
            failed = True
            log(f"run for {label} = {v.value} is not usable: {v.problem}")

    report = analyse(variants, level)
    print(markdown(report, variants, label, args.target), end="")
    if args.csv:
        orders_csv = write_csv(args.csv, report, variants)
        log(f"table: {args.csv}, orders: {orders_csv}")
    png = args.png or os.path.join(work, "convergence.png")
    if report["good"] and plot(png, report, label, level, log):
        log(f"figure: {png}")
    log(f"runs kept in {work}")
    return 2 if failed else 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except UsageError as e:
        print(f"{PROG}: error: {e}", file=sys.stderr)
        sys.exit(1)
    except KeyboardInterrupt:
        print(f"{PROG}: interrupted", file=sys.stderr)
        sys.exit(130)
