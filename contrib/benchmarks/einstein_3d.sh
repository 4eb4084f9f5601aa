#!/usr/bin/env bash
# Einstein's dilute limit in 3D: one sphere of radius a in a cube of side
# H = 1 between sliding walls (periodic in x and z), one time step. Prints
# (eta_r - 1) / (5/2 phi), phi = 4/3 pi a^3, for each radius and maximum
# level, with and without Fluid/Solid retraction = 0.3, the first-order
# extrapolation in h between successive levels, and the run's wall seconds.
# The sphere sits off the mesh's symmetry at (0.513, 0.493, 0.507).
# Usage: contrib/benchmarks/einstein_3d.sh ["a:L1,L2,..." ...]
#        (default: "0.2:4,5,6" "0.1:5,6,7")
# RETRACTIONS="0.3" (default "0 0.3") chooses the Solid retraction values;
# NP=2 runs each case on that many MPI ranks (default 1).
# SETTINGS=defaults leaves the rigidity and linear tolerances and the
# coarse mesh at fidus's defaults (what a user who sets only the sphere and
# the walls gets); the default, tight, solves them to 1e-4 (box measure)
# and 1e-9 on a coarse mesh of level 2.
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
[ -n "${FIDUS:-}" ] || "$top/contrib/build.sh" fidus >/dev/null
fidus="${FIDUS:-$top/build-release/fidus}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

cases=("$@")
[ ${#cases[@]} -gt 0 ] || cases=("0.2:4,5,6" "0.1:5,6,7")

fluid_settings="  set Rigidity tolerance = 1e-4
  set Rigidity measure = box
  subsection Linear solver
    set Tolerance = 1e-9
  end"
mesh_settings="  set Initial global refinement = 2
  set Minimum level = 2"
case "${SETTINGS:-tight}" in
  tight) ;;
  defaults) fluid_settings=""; mesh_settings="" ;;
  *) echo "SETTINGS must be tight or defaults, not '$SETTINGS'" >&2; exit 1 ;;
esac

echo "| H/a | retraction | max level | h/a | cells | (eta_r - 1)/(2.5 phi) | first-order extrapolation | wall s |"
echo "|---|---|---|---|---|---|---|---|"
for c in "${cases[@]}"; do
  a=${c%%:*}
  IFS=',' read -r -a levels <<< "${c#*:}"
  for retraction in ${RETRACTIONS:-0 0.3}; do
    previous=""
    for level in "${levels[@]}"; do
      out="$work/run_${a}_${retraction}_$level"
      cat > "$work/run.prm" <<PRM
set Dimension = 3
set Output directory = $out
subsection Domain
  set Lower left = 0, 0, 0
  set Upper right = 1, 1, 1
  set Boundary condition = sliding walls
end
subsection Fluid
$fluid_settings
  set Solid retraction = $retraction
end
subsection Particles
  set Radius = $a
  set Positions = 0.513, 0.493, 0.507
end
subsection Time stepping
  set End time = 0
end
subsection Mesh refinement
$mesh_settings
  set Maximum level = $level
end
subsection Output
  set Verbosity = quiet
  set Field output interval = 0
  set Particle output interval = 0
  set Checkpoint wall interval = 0
end
PRM
      start=$(date +%s.%N)
      launch=()
      [ "${NP:-1}" -gt 1 ] && launch=(mpirun -np "$NP" --oversubscribe)
      if ! "${launch[@]}" "$fidus" "$work/run.prm" > "$work/log" 2>&1; then
        echo "| a = $a, level $level: run failed |"; tail -3 "$work/log"; continue
      fi
      wall=$(echo "$(date +%s.%N) - $start" | bc)
      line=$(/usr/bin/python3 - "$out/statistics.csv" "$a" "$level" "$retraction" "$wall" "$previous" <<'PY'
import csv, math, sys
path, a, level, retraction, wall, previous = sys.argv[1:7]
a, level = float(a), int(level)
row = list(csv.DictReader(open(path)))[-1]
phi = 4. / 3. * math.pi * a ** 3
c = (float(row["relative_viscosity"]) - 1.) / (2.5 * phi)
h = 1. / 2 ** level
extrapolated = "%.4f" % (2. * c - float(previous)) if previous else ""
print("| %g | %s | %d | %.3f | %s | %.4f | %s | %.0f |%.10g" % (
    1. / a, retraction, level, h / a, row["cells"], c, extrapolated,
    float(wall), c))
PY
)
      echo "${line%|*}|"
      previous=${line##*|}
    done
  done
done
