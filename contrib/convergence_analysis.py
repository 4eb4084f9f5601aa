"""Reading and analysing the runs of a convergence study (used by
convergence_study.py): parameter files, particle trajectories, the
differences between successive runs, observed orders and Richardson
extrapolation. Standard library only.
"""

import bisect
import csv
import math
import os
import subprocess
import sys
import time

# Two consecutive observed orders count as consistent when the larger is at
# most this factor times the smaller ("differ by no more than 50 %").
ORDER_CONSISTENCY = 1.5

EXACT_LINE = "exact rigid inclusion:"


# ---------------------------------------------------------------------------
# Parameter files and output
# ---------------------------------------------------------------------------


def logical_lines(text):
    """Yield the lines of a deal.II parameter file without comments.

    Follows ParameterHandler: '#' starts a comment, a trailing backslash
    joins the next line.
    """
    pending = ""
    for raw in text.splitlines():
        line = raw.split("#", 1)[0].rstrip()
        if line.endswith("\\"):
            pending += line[:-1] + " "
            continue
        line = (pending + line).strip()
        pending = ""
        if line:
            yield line
    if pending.strip():
        yield pending.strip()


def parse_prm(text):
    """Return {'Sub/Sub/Entry': value} of a parameter file, the last set winning.

    This mirrors what ParameterHandler does with repeated 'set' lines, which
    is how the variants override the original file.
    """
    values = {}
    path = []
    for line in logical_lines(text):
        words = line.split(None, 1)
        keyword = words[0]
        if keyword == "subsection" and len(words) == 2:
            path.append(" ".join(words[1].split()))
        elif keyword == "end":
            if path:
                path.pop()
        elif keyword == "set" and len(words) == 2 and "=" in words[1]:
            name, value = words[1].split("=", 1)
            key = "/".join(path + [" ".join(name.split())])
            values[key] = value.strip()
    return values


# Set by the benchmark drivers in every run before their --set overrides:
# quiet, no field output, no checkpoints.
QUIET_RUN = [("Output/Verbosity", "quiet"), ("Output/Field output interval", "0"),
             ("Output/Checkpoint interval", "0"), ("Output/Checkpoint wall interval", "0")]


def prm_with(prm_text, overrides, output):
    """The prm followed by 'subsection ... set ... end' blocks of the
    (key, value) pairs in overrides and the Output directory: fidus, like
    parse_prm(), takes the last value set."""
    lines = [prm_text, "", "set Output directory = " + output]
    for key, value in overrides:
        parts = key.split("/")
        lines += ["subsection " + p for p in parts[:-1]]
        lines.append(f"set {parts[-1]} = {value}")
        lines += ["end"] * (len(parts) - 1)
    return "\n".join(lines) + "\n"


def run_in_folder(fidus, prm_text, overrides, folder, reuse, prog, label, np_ranks=1):
    """Run fidus on the prm with the overrides (prm_with()) in folder:
    run.prm, stderr.txt and exit_status there, output in folder/output;
    "<prog>: running <label>" on stderr first. With reuse, a run whose
    exit_status is 0 is not run again. Returns the wall seconds of the
    run, or None if it was reused; exits with one message naming the label
    if fidus fails."""
    done = os.path.join(folder, "exit_status")
    if reuse and os.path.exists(done) and open(done).read().strip() == "0":
        return None
    os.makedirs(folder, exist_ok=True)
    print(f"{prog}: running {label}", file=sys.stderr)
    prm = os.path.join(folder, "run.prm")
    with open(prm, "w") as f:
        f.write(prm_with(prm_text, overrides, os.path.abspath(os.path.join(folder, "output"))))
    command = [fidus, prm]
    if np_ranks > 1:
        command = ["mpirun", "-np", str(np_ranks)] + command
    start = time.time()
    with open(os.path.join(folder, "stderr.txt"), "w") as err:
        status = subprocess.call(command, stdout=subprocess.DEVNULL, stderr=err)
    seconds = time.time() - start
    with open(done, "w") as f:
        f.write(f"{status}\n")
    if status != 0:
        sys.exit(f"{prog}: fidus failed for {label} (exit status {status}); see {folder}/stderr.txt")
    return seconds


def parse_overrides(items, prog):
    """(key, value) pairs of --set 'Subsection/Entry=value' items; exits
    with one message naming the bad item otherwise."""
    pairs = []
    for item in items:
        if "=" not in item:
            raise SystemExit(f"{prog}: --set '{item}': allowed: Subsection/Entry=value")
        k, v = item.split("=", 1)
        pairs.append((k.strip(), v.strip()))
    return pairs


def read_text(path):
    """Return the content of a file, or None if it cannot be read."""
    try:
        with open(path) as f:
            return f.read()
    except OSError:
        return None


# ---------------------------------------------------------------------------
# Reading the output
# ---------------------------------------------------------------------------


class Trajectory:
    """Time series of one particle's centre, with its radius."""

    def __init__(self, radius):
        """An empty trajectory of a particle of the given radius."""
        self.radius = radius
        self.t = []
        self.x = []     # list of [x, y, z]

    def at(self, t):
        """Centre at time t by linear interpolation (t within the series)."""
        i = bisect.bisect_left(self.t, t)
        if i < len(self.t) and self.t[i] == t:
            return self.x[i]
        if i == 0 or i == len(self.t):
            raise ValueError(f"time {t} outside [{self.t[0]}, {self.t[-1]}]")
        t0, t1 = self.t[i - 1], self.t[i]
        w = (t - t0) / (t1 - t0)
        return [a + w * (b - a) for a, b in zip(self.x[i - 1], self.x[i])]


class Geometry:
    """What the comparison needs from the scene: periodic directions, box, dimension."""

    def __init__(self, used):
        """Read the geometry from the {key: value} of used_parameters.prm."""
        self.dim = int(float(used.get("Dimension", "2")))
        lower = [float(s) for s in used.get("Domain/Lower left", "0,0,0").split(",")]
        upper = [float(s) for s in used.get("Domain/Upper right", "1,1,1").split(",")]
        self.length = [u - l for u, l in zip(upper, lower)]
        condition = used.get("Domain/Boundary condition", "")
        # 'sliding walls' is periodic in x, and in z in 3D.
        self.periodic = []
        if condition == "sliding walls":
            self.periodic = [0] + ([2] if self.dim == 3 else [])

    def difference(self, a, b):
        """b - a with the minimum image in the periodic directions."""
        d = [q - p for p, q in zip(a, b)]
        for c in self.periodic:
            d[c] -= self.length[c] * round(d[c] / self.length[c])
        return d

    def distance(self, a, b):
        """|b - a| with the minimum image."""
        return math.sqrt(sum(c * c for c in self.difference(a, b)))

    def unwrap(self, traj):
        """Make a trajectory continuous across periodic faces.

        A particle that leaves through x = 1 reappears at x = 0; linear
        interpolation in time across that jump would be meaningless.
        """
        for c in self.periodic:
            shift = 0.0
            previous = None
            for point in traj.x:
                raw = point[c]
                if previous is not None:
                    jump = raw - previous
                    shift -= self.length[c] * round(jump / self.length[c])
                previous = raw
                point[c] = raw + shift


def read_csv_rows(path):
    """Rows of a CSV file as dicts (columns by name)."""
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def read_particles(path):
    """Return {id: Trajectory} from particles.csv, one point per step."""
    by_step = {}
    for row in read_csv_rows(path):
        # A resumed run rewrites its steps: keep the last row of a step.
        by_step[(int(row["step"]), int(row["id"]))] = row
    trajectories = {}
    for (step, pid), row in sorted(by_step.items()):
        traj = trajectories.setdefault(pid, Trajectory(float(row["radius"])))
        t = float(row["time"])
        if traj.t and t <= traj.t[-1]:
            continue
        traj.t.append(t)
        traj.x.append([float(row["x"]), float(row["y"]), float(row["z"])])
    return trajectories


def parse_exact_line(stdout):
    """Return {name: number} from the 'exact rigid inclusion:' screen line."""
    for line in stdout.splitlines():
        if line.startswith(EXACT_LINE):
            result = {}
            for item in line[len(EXACT_LINE):].split(","):
                words = item.split()
                if len(words) >= 2:
                    try:
                        result[" ".join(words[:-1])] = float(words[-1])
                    except ValueError:
                        pass
            return result
    return {}


def load_results(v):
    """Read the output of a successful run into v; set v.problem if unusable."""
    try:
        v.stats = read_csv_rows(os.path.join(v.output, "statistics.csv"))
        v.particles = read_particles(os.path.join(v.output, "particles.csv"))
        used = parse_prm(read_text(os.path.join(v.output, "used_parameters.prm")) or "")
        v.geometry = Geometry(used)
        for traj in v.particles.values():
            v.geometry.unwrap(traj)
    except (OSError, KeyError, ValueError) as e:
        v.problem = f"output cannot be read: {e}"
        return
    if not v.stats:
        v.problem = "statistics.csv has no rows"
    if v.exact:
        v.exact_values = parse_exact_line(read_text(os.path.join(v.folder, "stdout.txt")) or "")
        if not v.exact_values:
            v.problem = "no 'exact rigid inclusion:' line on the screen"


# ---------------------------------------------------------------------------
# Comparisons
# ---------------------------------------------------------------------------


def common_times(a, b):
    """Union of the sample times of two series, within the span both cover.

    The difference of two piecewise-linear curves is piecewise linear with
    breaks at either grid, so its maximum is attained on this union.
    """
    lo = max(a[0], b[0])
    hi = min(a[-1], b[-1])
    return sorted({t for t in a + b if lo <= t <= hi})


def max_trajectory_difference(coarse, fine):
    """Largest |X_coarse - X_fine| / a over common times and particles.

    Returns (value, particle id, time), or None when no particle and time
    are common to both runs.
    """
    best = None
    for pid, tc in coarse.particles.items():
        tf = fine.particles.get(pid)
        if tf is None:
            continue
        for t in common_times(tc.t, tf.t):
            d = coarse.geometry.distance(tc.at(t), tf.at(t)) / tc.radius
            if best is None or d > best[0]:
                best = (d, pid, t)
    return best


def pair_series(v):
    """Times and d(t) = |X1 - X0| / (a0 + a1) of particles 0 and 1 of a run."""
    p0, p1 = v.particles.get(0), v.particles.get(1)
    if p0 is None or p1 is None:
        return [], []
    a = p0.radius + p1.radius
    times = [t for t in p0.t if p1.t[0] <= t <= p1.t[-1]]
    return times, [v.geometry.distance(p0.at(t), p1.at(t)) / a for t in times]


def pair_scalars(v, t_end):
    """d_min, final offset and glued time of a run, up to the common time t_end."""
    result = {}
    times, d = pair_series(v)
    kept = [x for t, x in zip(times, d) if t <= t_end + 1e-12]
    if kept:
        result["d_min"] = min(kept)
        p0, p1 = v.particles[0], v.particles[1]
        # y is bounded by walls in every boundary condition: no image needed.
        result["offset"] = abs(p1.at(t_end)[1] - p0.at(t_end)[1]) / (p0.radius + p1.radius)
    if v.stats and "glued_contacts" in v.stats[0]:
        result["glued_time"] = sum(
            float(r["dt"]) for r in v.stats
            if float(r["time"]) <= t_end + 1e-12 and float(r["glued_contacts"]) > 0)
    return result


def run_scalars(v):
    """Cells, DoFs, wall seconds and FGMRES sum of a run (from statistics.csv)."""
    last = v.stats[-1]
    return {
        "cells": int(float(last["cells"])),
        "dofs": int(float(last["dofs"])),
        "wall_seconds": float(last["wall_seconds"]),
        "fgmres": int(sum(float(r["linear_iterations"]) for r in v.stats)),
    }


# ---------------------------------------------------------------------------
# Orders and extrapolation
# ---------------------------------------------------------------------------


def triple_order(d1, d2, r1, r2):
    """Observed order p from two successive differences and their ratios.

    With q(h) = q* + C h^p and h shrinking by r1 then r2:
    d1/d2 = r2^p (r1^p - 1) / (r2^p - 1). For r1 = r2 = r this is r^p, i.e.
    p = log(|d1|/|d2|) / log(r), returned even when it is <= 0 (growing
    differences), for the report. With unequal ratios, returns None when no
    p > 0 fits.
    """
    ratio = abs(d1) / abs(d2)
    if abs(r1 - r2) <= 1e-9 * r2:
        return math.log(ratio) / math.log(r2)

    def model(p):
        """d1/d2 predicted for order p (inf where the powers overflow)."""
        try:
            return r2 ** p * (r1 ** p - 1) / (r2 ** p - 1)
        except OverflowError:
            return math.inf

    # model(p) grows with p from log(r1)/log(r2) at p -> 0: bisection.
    lo, hi = 1e-9, 1.0
    if ratio <= model(lo):
        return None
    while model(hi) < ratio:
        hi *= 2
        if hi > 100:
            return None
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if model(mid) < ratio:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def orders_consistent(p, q):
    """True when two observed orders differ by no more than 50 %."""
    return p > 0 and q > 0 and max(p, q) <= ORDER_CONSISTENCY * min(p, q)


def assess_sequence(values, qs, ratios):
    """Observed orders and extrapolations of a scalar with unknown limit.

    values: labels, qs: the scalar per run, ratios[j]: refinement ratio from
    run j to run j+1. Returns a dict with 'triples' (one per three successive
    runs: labels, p, extrapolation) and 'asymptotic' / 'reason'.
    """
    diffs = [a - b for a, b in zip(qs, qs[1:])]
    triples = []
    for k in range(len(qs) - 2):
        d1, d2 = diffs[k], diffs[k + 1]
        p = None
        if d1 != 0 and d2 != 0:
            p = triple_order(d1, d2, ratios[k], ratios[k + 1])
        extrapolated = None
        if p is not None and p > 0:
            extrapolated = qs[k + 2] + (qs[k + 2] - qs[k + 1]) / (ratios[k + 1] ** p - 1)
        triples.append({"labels": values[k:k + 3], "p": p, "extrapolated": extrapolated})
    result = {"triples": triples, "asymptotic": False, "reason": ""}
    if not triples:
        result["reason"] = "fewer than three runs"
    elif all(d == 0 for d in diffs):
        result["reason"] = "the same value in every run"
        result["constant"] = True
    elif any(d == 0 for d in diffs):
        # A quantity that stopped changing (a count, a time summed over
        # whole steps) has no order to measure.
        result["reason"] = "a difference is zero: the value stopped changing"
    elif any(abs(b) >= abs(a) for a, b in zip(diffs, diffs[1:])):
        j = next(j for j, (a, b) in enumerate(zip(diffs, diffs[1:])) if abs(b) >= abs(a))
        result["reason"] = (f"differences do not decrease: |{values[j]}-{values[j + 1]}| = "
                            f"{abs(diffs[j]):.3g}, |{values[j + 1]}-{values[j + 2]}| = "
                            f"{abs(diffs[j + 1]):.3g}")
    elif any((a > 0) != (b > 0) for a, b in zip(diffs, diffs[1:])):
        # Oscillating differences: q* is not on the far side of the last
        # value, so the extrapolation formula does not apply.
        result["reason"] = "differences change sign"
    elif any(t["p"] is None or t["p"] <= 0 for t in triples):
        result["reason"] = "no positive order fits the differences"
    elif any(not orders_consistent(a["p"], b["p"]) for a, b in zip(triples, triples[1:])):
        result["reason"] = "orders of consecutive triples differ by more than 50 %"
    else:
        result["asymptotic"] = True
    return result


def assess_known_limit(values, es, ratios):
    """Orders of a quantity whose limit is known to be 0 (an error).

    p_j = log(e_j / e_{j+1}) / log(r_j) for each pair of successive runs.
    """
    pairs = []
    for j in range(len(es) - 1):
        p = None
        if es[j] > 0 and es[j + 1] > 0:
            p = math.log(es[j] / es[j + 1]) / math.log(ratios[j])
        pairs.append({"labels": values[j:j + 2], "p": p})
    result = {"pairs": pairs, "asymptotic": False, "reason": "", "fit": None}
    if len(es) >= 3 and all(e > 0 for e in es):
        # Least-squares slope of log e against log h over all runs: one
        # number that is less sensitive than the pairwise orders to a run
        # whose interface happens to cut the cells favourably.
        log_h = [0.0]
        for r in ratios[:len(es) - 1]:
            log_h.append(log_h[-1] - math.log(r))
        log_e = [math.log(e) for e in es]
        mh, me = sum(log_h) / len(es), sum(log_e) / len(es)
        result["fit"] = (sum((h - mh) * (e - me) for h, e in zip(log_h, log_e))
                         / sum((h - mh) ** 2 for h in log_h))
    if not pairs:
        result["reason"] = "fewer than two runs"
    elif any(p["p"] is None for p in pairs):
        result["reason"] = "a zero error"
    elif any(p["p"] <= 0 for p in pairs):
        result["reason"] = "the error does not decrease"
    elif any(not orders_consistent(a["p"], b["p"]) for a, b in zip(pairs, pairs[1:])):
        result["reason"] = "orders of consecutive steps differ by more than 50 %"
    else:
        result["asymptotic"] = True
    return result
