#!/usr/bin/env bash
# Reversibility of the seed paper's 2D pair through the fluid: the shear is
# reversed at t = T (Shear rate = t < T ? 1 : -1) and the run ends at 2T,
# where a reversible model is back at its start. Prints, per contact model,
# maximum level and rigidity tolerance: the return error max_i |X_i(2T) -
# X_i(0)| / a, the smallest normalised distance |X_1 - X_0| / (a_0 + a_1)
# over the run, the steps with an active contact, and the wall seconds.
# Usage: contrib/benchmarks/reversibility.sh
#   PRM=prm/two_particles_2d_converged.prm (default) the scene
#   T=3 (default)                 the reversal time
#   MODELS="gluey inelastic none" LEVELS="6 7" TOLERANCES="3e-4 1e-4"
#   (default: MODELS="gluey inelastic", LEVELS and TOLERANCES: the prm's;
#   a tolerance given here is in the box measure)
#   EXTRA="subsection Mesh refinement|set Remesh fraction = 0|end" more prm
#   lines ('|' separates them), LABEL=text a first column naming them
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
[ -n "${FIDUS:-}" ] || "$top/contrib/build.sh" fidus >/dev/null
fidus="${FIDUS:-$top/build-release/fidus}"
prm="$(cd "$(dirname "${PRM:-$top/prm/two_particles_2d_converged.prm}")" && pwd)/$(basename "${PRM:-two_particles_2d_converged.prm}")"
T="${T:-3}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

run() { # model level tolerance
  local model=$1 level=$2 tol=$3
  {
    echo "include $prm"
    echo "set Output directory = $work/out"
    echo "subsection Domain"
    echo "  set Shear rate = t < $T ? 1 : -1"
    echo "end"
    echo "subsection Contact"
    echo "  set Model = $model"
    echo "end"
    echo "subsection Time stepping"
    echo "  set End time = $(echo "2 * $T" | bc -l)"
    echo "end"
    [ "$level" = prm ] || printf "subsection Mesh refinement\n  set Maximum level = %s\nend\n" "$level"
    [ "$tol" = prm ] || printf "subsection Fluid\n  set Rigidity tolerance = %s\n  set Rigidity measure = box\nend\n" "$tol"
    [ -z "${EXTRA:-}" ] || tr '|' '\n' <<< "$EXTRA"
    echo "subsection Output"
    echo "  set Field output interval = 0"
    echo "  set Particle output interval = 0"
    echo "  set Checkpoint interval = 0"
    echo "  set Checkpoint wall interval = 0"
    echo "end"
  } > "$work/run.prm"
  local start end
  start=$(date +%s.%N)
  if ! "$fidus" "$work/run.prm" > "$work/log" 2>&1; then
    echo "| $model | $level | $tol | run failed: $(tail -1 "$work/log") |"
    return
  fi
  end=$(date +%s.%N)
  /usr/bin/python3 - "$work/out" "$model" "$level" "$tol" "$(echo "$end - $start" | bc)" <<'PY'
import csv, math, sys
out, model, level, tol, wall = sys.argv[1:6]
rows = list(csv.DictReader(open(out + "/particles.csv")))
steps = sorted({int(r["step"]) for r in rows})
pos = {}
for r in rows:
    pos.setdefault(int(r["step"]), {})[int(r["id"])] = (
        float(r["x"]), float(r["y"]), float(r["radius"]))
first, last = pos[steps[0]], pos[steps[-1]]
ret = max(math.hypot(last[i][0] - first[i][0], last[i][1] - first[i][1]) / first[i][2]
          for i in first)
dmin = min(math.hypot(p[1][0] - p[0][0], p[1][1] - p[0][1]) / (p[0][2] + p[1][2])
           for p in pos.values() if 0 in p and 1 in p)
stats = list(csv.DictReader(open(out + "/statistics.csv")))
active = sum(1 for s in stats if int(s["active_contacts"]) > 0)
label = __import__("os").environ.get("LABEL", "")
print(("| %s " % label if label else "") + "| %-9s | %5s | %6s | %10.3e | %.5f | %3d | %7.1f |" % (
    model, level, tol, ret, dmin, active, float(wall)))
PY
}

echo "reversal at t = $T, end at t = $(echo "2 * $T" | bc -l), scene $(basename "$prm")"
[ -z "${LABEL:-}" ] || printf "| settings "
echo "| model | level | rigidity tolerance | max \|X(2T) - X(0)\| / a | min distance | steps with contact | wall s |"
[ -z "${LABEL:-}" ] || printf "|---"
echo "|---|---|---|---|---|---|---|"
for model in ${MODELS:-gluey inelastic}; do
  for level in ${LEVELS:-prm}; do
    for tol in ${TOLERANCES:-prm}; do
      run "$model" "$level" "$tol"
    done
  done
done
