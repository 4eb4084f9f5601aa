#!/usr/bin/env bash
# Where 'Fluid/Cut linear solver = auto' should switch from the direct
# solver to the iterative one in 3D: one solve of each scene with each
# solver, one rank, its cores as threads. Scenes (Maximum level in
# brackets, Minimum level 2), from small to large:
#   sphere   one sphere a = 0.2 off the centre in linear shear [3, 4];
#   pair     two spheres a = 0.15 in linear shear, those of cli.cut_ranks
#            [3];
#   small    one sphere a = 0.1 off the centre in linear shear [4, 5].
# Prints the unknowns, the seconds of the solve stage and of the whole
# solve, and the peak memory, per solver.
# Env: CASES (default "sphere,3 pair,3 sphere,4 small,4 small,5"), FIDUS,
# WORK (keep the runs there).
# Usage: contrib/benchmarks/cut_solver_choice.sh
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
[ -n "${FIDUS:-}" ] || "$top/contrib/build.sh" fidus >/dev/null
fidus="${FIDUS:-$top/build-release/fidus}"
cases="${CASES:-sphere,3 pair,3 sphere,4 small,4 small,5}"
if [ -n "${WORK:-}" ]; then mkdir -p "$WORK"; work="$(cd "$WORK" && pwd)"
else work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT; fi

# scene_prm NAME LEVEL SOLVER OUT
scene_prm() {
  local radius positions
  case "$1" in
    sphere) radius=0.2; positions="0.47, 0.53, 0.51" ;;
    pair) radius=0.15; positions="0.3, 0.45, 0.5; 0.7, 0.55, 0.5" ;;
    small) radius=0.1; positions="0.43, 0.56, 0.52" ;;
    *) echo "cut_solver_choice.sh: unknown scene '$1'; allowed: sphere pair small" >&2; exit 1 ;;
  esac
  cat <<PRM
set Dimension        = 3
set Output directory = $4
subsection Domain
  set Lower left         = 0, 0, 0
  set Upper right        = 1, 1, 1
  set Boundary condition = linear shear
end
subsection Fluid
  set Model             = cut finite element
  set Cut linear solver = $3
end
subsection Particles
  set Radius    = $radius
  set Positions = $positions
end
subsection Time stepping
  set End time = 0
end
subsection Mesh refinement
  set Initial global refinement = 2
  set Minimum level             = 2
  set Maximum level             = $2
end
subsection Output
  set Verbosity = verbose
end
PRM
}

echo "| scene | Maximum level | solver | unknowns | FGMRES | solve s | all s | peak |"
echo "|---|---|---|---|---|---|---|---|"
for c in $cases; do
  scene="${c%%,*}"; level="${c#*,}"
  for solver in direct iterative; do
    run="$work/${scene}_${level}_$solver"
    scene_prm "$scene" "$level" "$solver" "$run" > "$run.prm"
    if ! "$fidus" "$run.prm" > "$run.log" 2>&1; then
      echo "| $scene | $level | $solver | run failed: $(tail -1 "$run.log" | cut -c1-160) |"; continue
    fi
    /usr/bin/python3 - "$run.log" "$scene" "$level" "$solver" <<'PY'
import re, sys
log, scene, level, solver = sys.argv[1:]
text = open(log).read()
line = [l for l in text.splitlines() if "cut element:" in l][0]
fgmres = re.search(r"FGMRES (\d+)", line)
peak = re.search(r"peak memory per rank: ([0-9.]+ [KMG]B)", text)
print("| %s | %s | %s | %s | %s | %.2f | %.2f | %s |" % (
    scene, level, solver, re.search(r"(\d+) unknowns", line).group(1),
    fgmres.group(1) if fgmres else "", float(re.search(r"solve ([0-9.e+-]+)", line).group(1)),
    float(re.search(r"all ([0-9.e+-]+)", line).group(1)), peak.group(1) if peak else "?"))
PY
  done
done
