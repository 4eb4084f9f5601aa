#!/usr/bin/env bash
# The cut element's peak memory and time per solve, for one or more fidus
# binaries side by side (before and after a change, in one run). Per scene
# and binary: unknowns, matrix entries, FGMRES iterations, seconds of the
# solve and of the whole step (mean over the solves), the process's peak
# resident memory (/usr/bin/time -v) and bytes per matrix entry, and the
# largest difference from the first binary's particle velocities and
# stresses (walls' and particles' shear stress, N1, N2, Pi), each over its
# column's largest.
# Scenes:
#   sphere3d   one sphere a = 0.1 off the centre in shear, maximum level 5
#              (a/h = 3.2), two steps of 0.2;
#   dense3d    the 37 spheres of prm/rheology_steady_shear_3d.prm (phi =
#              0.3, sliding walls) at their generated start, a/h = 2, the
#              sub-grid correction below REACH a (default 0.4; 0.2 needs
#              about 8 GB before this change), no gap cells, one step.
# Env: SCENES (default "sphere3d dense3d"), BINARIES (default
# "build-release/fidus"; several: "label=path label=path"), REACH, WORK
# (keep the runs there).
# Usage: BINARIES="before=/tmp/fidus_old after=build-release/fidus" \
#          contrib/benchmarks/cut_memory.sh
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
scenes="${SCENES:-sphere3d dense3d}"
binaries="${BINARIES:-build-release/fidus}"
reach="${REACH:-0.4}"
if [ -n "${WORK:-}" ]; then mkdir -p "$WORK"; work="$(cd "$WORK" && pwd)"
else work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT; fi

# box_prm OUT BOUNDARY: the 3D unit box's lines, output in OUT.
box_prm() {
  cat <<PRM
set Dimension        = 3
set Output directory = $1
subsection Domain
  set Lower left         = 0, 0, 0
  set Upper right        = 1, 1, 1
  set Boundary condition = $2
end
subsection Output
  set Verbosity                = verbose
  set Particle output interval = 1
end
PRM
}

# scene_prm NAME OUT: print the scene's prm, its output in OUT.
scene_prm() {
  case "$1" in
    sphere3d) box_prm "$2" "linear shear"; cat <<PRM
subsection Fluid
  set Model = cut finite element
end
subsection Particles
  set Radius    = 0.1
  set Positions = 0.43, 0.56, 0.52
end
subsection Time stepping
  set End time  = 0.4
  set Time step = 0.2
end
subsection Mesh refinement
  set Initial global refinement = 2
  set Minimum level             = 2
  set Maximum level             = 5
end
PRM
    ;;
    dense3d) box_prm "$2" "sliding walls"; cat <<PRM
subsection Fluid
  set Model                  = cut finite element
  set Cut minimum gap        = $reach
  set Cut gap cells          = 0
  set Lubrication correction = true
end
subsection Particles
  subsection Generator
    set Fraction           = 0.3
    set Radii              = 0.125
    set Minimum separation = 0.01
    set Seed               = 1
  end
end
subsection Contact
  set Model = gluey
end
subsection Time stepping
  set End time  = 0.002
  set Time step = 0.002
end
subsection Mesh refinement
  set Initial global refinement = 4
  set Minimum level             = 4
  set Maximum level             = 4
end
PRM
    ;;
    *) echo "cut_memory.sh: unknown scene '$1'; allowed: sphere3d dense3d" >&2; exit 1 ;;
  esac
}

echo "| scene | binary | unknowns | entries | FGMRES | solve s | step s | peak GB | B per entry | velocity difference | stress difference |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for scene in $scenes; do
  runs=()
  for pair in $binaries; do
    label="${pair%%=*}"; binary="${pair#*=}"
    [ "$label" = "$pair" ] && label=fidus
    run="$work/${scene}_$label"
    scene_prm "$scene" "$run" > "$run.prm"
    if ! /usr/bin/time -v "$binary" "$run.prm" > "$run.log" 2>&1; then
      echo "| $scene | $label | run failed: $run.log |"; continue
    fi
    runs+=("$label=$run")
  done
  [ "${#runs[@]}" -gt 0 ] || continue
  /usr/bin/python3 - "$scene" "${runs[@]}" <<'PY'
import csv, glob, re, statistics, sys
scene, runs = sys.argv[1], [r.split("=", 1) for r in sys.argv[2:]]
def solves(log):
    rows = []
    for line in open(log):
        if "cut element:" in line:
            rows.append(dict(
                unknowns=int(re.search(r"(\d+) unknowns", line).group(1)),
                entries=int(re.search(r"\((\d+) matrix entries", line).group(1)),
                fgmres=int(re.search(r"FGMRES (\d+)", line).group(1)),
                solve=float(re.search(r"solve ([0-9.e+-]+)", line).group(1)),
                step=float(re.search(r"all ([0-9.e+-]+)", line).group(1))))
    return rows
def peak(log):
    for line in open(log):
        if "Maximum resident set size" in line:
            return int(line.split()[-1]) * 1024
def column(run, name):
    for path in (run + "/particles.csv", run + "/statistics.csv"):
        rows = list(csv.DictReader(open(path)))
        if rows and name in rows[0]:
            return [float(r[name]) for r in rows if r[name] not in ("", "nan")]
    return []
def difference(a_run, b_run, names):
    """Largest difference over the names, each over its column's largest."""
    worst = None
    for name in names:
        a, b = column(a_run, name), column(b_run, name)
        scale = max([abs(x) for x in a] + [0.0])
        if a and len(a) == len(b) and scale > 0:
            d = max(abs(x - y) for x, y in zip(a, b)) / scale
            worst = d if worst is None else max(worst, d)
    return "" if worst is None else "%.1e" % worst
velocity = ["ux", "uy", "uz"]
stress = ["wall_shear_stress", "shear_stress", "normal_stress_difference_1",
          "normal_stress_difference_2", "particle_pressure"]
first = runs[0][1]
for label, run in runs:
    rows = solves(run + ".log")
    mean = lambda k: statistics.mean(r[k] for r in rows)
    p = peak(run + ".log")
    diffs = [difference(first, run, names) if run != first else ""
             for names in (velocity, stress)]
    print("| %s | %s | %.0f | %.1f M | %.1f | %.2f | %.2f | %.2f | %.1f | %s | %s |" % (
        scene, label, mean("unknowns"), mean("entries") / 1e6, mean("fgmres"),
        mean("solve"), mean("step"), p / 1e9, p / max(r["entries"] for r in rows),
        diffs[0], diffs[1]))
PY
done
