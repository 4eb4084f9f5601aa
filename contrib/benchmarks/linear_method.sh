#!/usr/bin/env bash
# The fictitious domain's two ways of solving its Stokes system
# (Fluid/Linear solver/Method = iterative | direct), on the same scenes, one
# run at a time, and one Markdown table:
#   - the rigid inclusion with the exact solution on the box: 2D, a = 0.15,
#     uniform meshes at the levels LEVELS_2D (default "6 7 8"); 3D, a = 0.1,
#     adaptive meshes (3 to the levels LEVELS_3D, default "4 5");
#   - the seed paper's 2D scene (prm/two_particles_2d.prm) and the converged
#     one (prm/two_particles_2d_converged.prm), to End time END (default
#     14); SCENES="" leaves them out.
# Columns: unknowns (last solve), steps, Uzawa iterations and FGMRES
# iterations (summed), fidus's "fluid" seconds and wall seconds, peak
# memory (max RSS), and the answer: the inclusion's omega error, or for a
# scene the largest distance between the two methods' particle centres
# over the run, relative to the radius.
# Usage: [LEVELS_2D=...] [LEVELS_3D=...] [END=...] \
#        contrib/benchmarks/linear_method.sh
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
[ -n "${FIDUS:-}" ] || "$top/contrib/build.sh" fidus >/dev/null
fidus="${FIDUS:-$top/build-release/fidus}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
work="$(mktemp -d)"
levels_2d="${LEVELS_2D-6 7 8}"
levels_3d="${LEVELS_3D-4 5}"
scenes="${SCENES-two_particles_2d two_particles_2d_converged}"
end="${END:-14}"

inclusion_prm() { # dim level method
  local dim=$1 level=$2 method=$3 lo=$level
  [ "$dim" = 3 ] && lo=3
  cat <<EOF
set Dimension = $dim
set Output directory = $work/inclusion_${dim}d_${level}_$method
subsection Domain
  set Lower left = $([ "$dim" = 2 ] && echo "0, 0" || echo "0, 0, 0")
  set Upper right = $([ "$dim" = 2 ] && echo "1, 1" || echo "1, 1, 1")
  set Boundary condition = exact rigid inclusion
end
subsection Fluid
  subsection Linear solver
    set Method = $method
  end
end
subsection Particles
  set Radius = $([ "$dim" = 2 ] && echo 0.15 || echo 0.1)
  set Positions = $([ "$dim" = 2 ] && echo "0.503, 0.488" || echo "0.503, 0.488, 0.51")
end
subsection Time stepping
  set End time = 0
end
subsection Mesh refinement
  set Initial global refinement = $lo
  set Minimum level = $lo
  set Maximum level = $level
end
EOF
}

scene_prm() { # scene method
  sed -e "s#^set Output directory.*#set Output directory = $work/$1_$2#" \
    -e "s#^\( *set End time *=\).*#\1 $end#" "$top/prm/$1.prm"
  printf 'subsection Fluid\n  subsection Linear solver\n    set Method = %s\n  end\nend\n' "$2"
}

# One run: prints "| case | method | unknowns | steps | Uzawa | FGMRES |
# fluid s | wall s | max RSS MB |" and leaves the output directory.
run() { # case method prm-file output-directory
  local log="$work/$1_$2.log"
  /usr/bin/time -f "%e %M" -o "$work/time" "$fidus" "$3" >"$log" 2>&1 ||
    { echo "| $1 | $2 | failed (exit status $?; $log) |"; return; }
  /usr/bin/python3 - "$1" "$2" "$4" "$log" "$work/time" <<'PY'
import csv, re, sys
case, method, out, log, timing = sys.argv[1:6]
rows = list(csv.DictReader(open(out + "/statistics.csv")))
fluid = re.search(r"\| fluid\s*\|\s*\d+\s*\|\s*([0-9.e+-]+)(m?s)", open(log).read())
fluid_s = float(fluid.group(1)) * (1e-3 if fluid.group(2) == "ms" else 1) if fluid else float("nan")
wall, rss = open(timing).read().split()
print("| %s | %s | %s | %d | %d | %d | %.2f | %.2f | %.0f |" % (
    case, method, rows[-1]["dofs"], len(rows) - 1,
    sum(int(r["uzawa_iterations"]) for r in rows),
    sum(int(r["linear_iterations"]) for r in rows), fluid_s, float(wall),
    int(rss) / 1024.), end="")
PY
}

echo "| case | method | unknowns | steps | Uzawa | FGMRES | fluid s | wall s | max RSS MB | answer |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for dim_levels in "2:$levels_2d" "3:$levels_3d"; do
  dim=${dim_levels%%:*}
  for level in ${dim_levels#*:}; do
    for method in iterative direct; do
      prm="$work/inclusion_${dim}d_${level}_$method.prm"
      inclusion_prm "$dim" "$level" "$method" >"$prm"
      run "inclusion ${dim}D level $level" "$method" "$prm" \
        "$work/inclusion_${dim}d_${level}_$method"
      omega=$(grep -o 'relative omega error [0-9.e+-]*' \
        "$work/inclusion ${dim}D level ${level}_$method.log" | awk '{print $4}')
      echo " omega error ${omega:-?} |"
    done
  done
done
for scene in $scenes; do
  for method in iterative direct; do
    scene_prm "$scene" "$method" >"$work/${scene}_$method.prm"
    run "$scene" "$method" "$work/${scene}_$method.prm" "$work/${scene}_$method"
    if [ "$method" = direct ]; then
      /usr/bin/python3 - "$work/${scene}_iterative/particles.csv" \
        "$work/${scene}_direct/particles.csv" <<'PY'
import csv, math, sys
def load(p):
    return {(r["time"], r["id"]): [float(r[k]) for k in ("x", "y", "z", "radius")]
            for r in csv.DictReader(open(p))}
a, b = load(sys.argv[1]), load(sys.argv[2])
d = max((math.dist(a[k][:3], b[k][:3]) / a[k][3] for k in a if k in b), default=float("nan"))
print(" max distance / a %.2e from iterative |" % d)
PY
    else
      echo " |"
    fi
  done
done
echo
echo "(one run at a time; runs kept in $work)"
