#!/usr/bin/env bash
# Where the cut element's FGMRES starts (Fluid/Cut initial guess): from
# zero, or from the previous solve's fields read on the new mesh. Both
# reach the same absolute tolerance, so the answers agree to it; the table
# gives, per scene and start, the solves after the first (the first has no
# previous solve): the mean FGMRES iterations, the mean initial residual
# over the right-hand side's, the mean seconds of FGMRES and of the whole
# solve, and the largest difference of the particles' velocities between
# the two starts over the run (over the largest speed).
# Scenes:
#   pair3d_open   prm/two_particles_3d_cut.prm from its start (gap 6 a),
#                 steps of 0.2, 6 solves;
#   pair3d_close  the same pair 0.1 a apart, line of centres at -60 deg
#                 from the flow, the gap step choosing the step, 6 solves;
#   sphere3d      one sphere a = 0.1 off the centre at maximum level 5
#                 (a/h = 3.2), steps of 0.2, 4 solves.
# Env: SCENES (default "pair3d_open pair3d_close sphere3d"), FIDUS (default
# build-release/fidus), WORK (keep the runs there).
# Usage: contrib/benchmarks/cut_initial_guess.sh
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
scenes="${SCENES:-pair3d_open pair3d_close sphere3d}"
fidus="${FIDUS:-}"
if [ -z "$fidus" ]; then
  "$top/contrib/build.sh" fidus >/dev/null
  fidus="$top/build-release/fidus"
fi
if [ -n "${WORK:-}" ]; then mkdir -p "$WORK"; work="$(cd "$WORK" && pwd)"
else work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT; fi

# scene_prm NAME OUT GUESS: print the scene's prm, its output in OUT.
scene_prm() {
  local common="s#^set Output directory.*#set Output directory = $2#"
  local guess="s/^subsection Fluid/subsection Fluid\n  set Cut initial guess = $3/"
  local verbose='s/^subsection Output/subsection Output\n  set Verbosity = verbose/'
  case "$1" in
    pair3d_open) sed -e "$common" -e "$guess" -e "$verbose" \
                   -e 's/^  set End time .*/  set End time          = 1.0/' \
                   "$top/prm/two_particles_3d_cut.prm" ;;
    # a = 0.05, centres a + 0.05 a / 2 from (0.5, 0.5, 0.5) at -60 deg.
    pair3d_close) sed -e "$common" -e "$guess" -e "$verbose" \
                   -e 's/^  set Positions .*/  set Positions = 0.47375, 0.545466, 0.5; 0.52625, 0.454534, 0.5/' \
                   -e 's/^  set End time .*/  set End time          = 0.25/' \
                   "$top/prm/two_particles_3d_cut.prm" ;;
    sphere3d) cat <<PRM
set Dimension        = 3
set Output directory = $2
subsection Domain
  set Lower left         = 0, 0, 0
  set Upper right        = 1, 1, 1
  set Boundary condition = linear shear
  set Shear rate         = 1
end
subsection Fluid
  set Model             = cut finite element
  set Cut initial guess = $3
end
subsection Particles
  set Radius    = 0.1
  set Positions = 0.43, 0.56, 0.52
end
subsection Time stepping
  set End time  = 0.6
  set Time step = 0.2
end
subsection Mesh refinement
  set Initial global refinement = 2
  set Minimum level             = 2
  set Maximum level             = 5
end
subsection Output
  set Verbosity                = verbose
  set Particle output interval = 1
end
PRM
    ;;
    *) echo "cut_initial_guess.sh: unknown scene '$1'; allowed: pair3d_open pair3d_close sphere3d" >&2; exit 1 ;;
  esac
}

echo "| scene | start | solves | unknowns | FGMRES | initial residual | FGMRES s | solve s | velocity difference |"
echo "|---|---|---|---|---|---|---|---|---|"
for scene in $scenes; do
  for guess in zero "previous solve"; do
    label="${guess// /_}"
    run="$work/${scene}_$label"
    scene_prm "$scene" "$run" "$guess" > "$run.prm"
    if ! "$fidus" "$run.prm" > "$run.log" 2>&1; then
      echo "| $scene | $guess | run failed: $run.log |"; continue
    fi
  done
  /usr/bin/python3 - "$work/${scene}_zero" "$work/${scene}_previous_solve" "$scene" <<'PY'
import csv, re, statistics, sys
zero, warm, scene = sys.argv[1:]
def solves(run):
    rows = []
    for line in open(run + ".log"):
        if "cut element:" not in line:
            continue
        rows.append(dict(
            unknowns=int(re.search(r"(\d+) unknowns", line).group(1)),
            fgmres=int(re.search(r"FGMRES (\d+)", line).group(1)),
            r0=float(re.search(r"relative residual ([0-9.e+-]+)", line).group(1)),
            fgmres_s=float(re.search(r"of which FGMRES ([0-9.e+-]+)", line).group(1)),
            solve_s=float(re.search(r"solve ([0-9.e+-]+)", line).group(1))))
    return rows
def velocities(run):
    rows = list(csv.DictReader(open(run + "/particles.csv")))
    return [[float(r[k]) for k in ("ux", "uy", "uz")] for r in rows]
vz, vw = velocities(zero), velocities(warm)
n = min(len(vz), len(vw))
scale = max(max(abs(x) for x in v) for v in vz[:n])
diff = max(max(abs(a - b) for a, b in zip(p, q)) for p, q in zip(vz[:n], vw[:n])) / scale
for label, run in (("zero", zero), ("previous solve", warm)):
    rows = solves(run)[1:]
    mean = lambda k: statistics.mean(r[k] for r in rows)
    print("| %s | %s | %d | %.0f | %.1f | %.2g | %.2f | %.2f | %s |" % (
        scene, label, len(rows), mean("unknowns"), mean("fgmres"), mean("r0"),
        mean("fgmres_s"), mean("solve_s"),
        "%.1e" % diff if label != "zero" else ""))
PY
done
