#!/usr/bin/env bash
# The dense 3D suspension through the cut element against the fictitious
# domain with its sub-grid correction, at one configuration: the 37
# spheres (a = 0.125, phi = 0.3) of prm/rheology_steady_shear_3d.prm
# between sliding walls. The fictitious domain runs the prm to its first
# step (strain 0.05) at each level of FD_LEVELS on NP ranks; its step 1
# carries the correction's bonds. The cut element then solves once at the
# positions of that step on the finest of FD_LEVELS' runs, for each
# "level,minimum gap" of CUT_CASES (the sub-grid correction below the
# minimum gap, GAP_CELLS cells across the gaps: Cut gap cells, default 0),
# on one rank.
# Prints eta_r, its lubrication part, N1, N2 and the particle pressure
# (in eta_f gamma_dot), the unknowns and the seconds and peak memory of
# each run. Measured at 0.4 a: 1.5 GB (level 4), 6.3 GB (level 5).
# Env: FD_LEVELS (default "4 5"), CUT_CASES (default "4,0.4 4,0.2 5,0.4";
# "4,0.1": 530 979 unknowns, about 2 minutes and 7.6 GB; "4,0.05":
# 880 935 unknowns, about 4 minutes and 13 GB; "5,0.1": 995 749
# unknowns, 3 minutes and 11.4 GB), NP (default 2), FIDUS, WORK (keep
# the runs there), GAP_CELLS (default 0; 1 at "4,0.2": 1 390 812 unknowns,
# 4 minutes and 17 GB).
# Usage: contrib/benchmarks/cut_dense_3d.sh
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
[ -n "${FIDUS:-}" ] || "$top/contrib/build.sh" fidus >/dev/null
fidus="${FIDUS:-$top/build-release/fidus}"
fd_levels="${FD_LEVELS:-4 5}"; cut_cases="${CUT_CASES:-4,0.4 4,0.2 5,0.4}"
np="${NP:-2}"
if [ -n "${WORK:-}" ]; then mkdir -p "$WORK"; work="$(cd "$WORK" && pwd)"
else work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT; fi
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

row() { # row LABEL RUN STEP
  /usr/bin/python3 - "$@" <<'PY'
import csv, re, sys
label, run, step = sys.argv[1], sys.argv[2], sys.argv[3]
r = [r for r in csv.DictReader(open(run + "/statistics.csv")) if r["step"] == step][0]
log = open(run + ".log").read()
peak = re.search(r"peak memory per rank: ([0-9.]+ [KMG]B)", log)
print("| %s | %s | %.4f | %.4f | %.4f | %.4f | %.4f | %.0f | %s |" % (
    label, r["dofs"], float(r["relative_viscosity"]),
    float(r["lubrication_relative_viscosity"]),
    float(r["normal_stress_difference_1"]), float(r["normal_stress_difference_2"]),
    float(r["particle_pressure"]), float(r["wall_seconds"]),
    peak.group(1) if peak else "?"))
PY
}

echo "| fluid | unknowns | eta_r | lubrication part | N1 | N2 | Pi | run s | peak per rank |"
echo "|---|---|---|---|---|---|---|---|---|"
finest=""
for level in $fd_levels; do
  run="$work/fd_$level"
  sed -e "s#^set Output directory.*#set Output directory = $run#" \
      -e "s/^  set Initial global refinement = 4/  set Initial global refinement = $level/" \
      -e "s/^  set Minimum level             = 4/  set Minimum level             = $level/" \
      -e "s/^  set Maximum level             = 4/  set Maximum level             = $level/" \
      -e 's/^  set End time .*/  set End time  = 0.05/' \
      "$top/prm/rheology_steady_shear_3d.prm" > "$run.prm"
  mpirun -np "$np" --oversubscribe "$fidus" "$run.prm" > "$run.log" 2>&1 \
    || { echo "| fictitious domain, level $level | run failed: $run.log |"; continue; }
  row "fictitious domain, a/h = $(/usr/bin/python3 -c "print(0.125 * 2**$level)"), step 1 (its own positions)" "$run" 1
  finest="$run"
done
[ -n "$finest" ] || exit 1
positions=$(/usr/bin/python3 - "$finest/particles.csv" <<'PY'
import csv, sys
rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["step"] == "1"]
print("; ".join("%.12g, %.12g, %.12g" % (float(r["x"]), float(r["y"]), float(r["z"])) for r in rows))
PY
)
for c in $cut_cases; do
  level="${c%%,*}"; gap="${c#*,}"; run="$work/cut_${level}_$gap"
  cat > "$run.prm" <<PRM
set Dimension        = 3
set Output directory = $run
subsection Domain
  set Lower left         = 0, 0, 0
  set Upper right        = 1, 1, 1
  set Boundary condition = sliding walls
  set Shear rate         = 1
end
subsection Fluid
  set Model                  = cut finite element
  set Cut minimum gap        = $gap
  set Cut gap cells          = ${GAP_CELLS:-0}
  set Lubrication correction = true
end
subsection Particles
  set Radius    = 0.125
  set Positions = $positions
end
subsection Contact
  set Model = gluey
end
subsection Time stepping
  set End time = 0
end
subsection Mesh refinement
  set Initial global refinement = $level
  set Minimum level             = $level
  set Maximum level             = $level
end
PRM
  "$fidus" "$run.prm" > "$run.log" 2>&1 \
    || { echo "| cut element, level $level, correction below $gap a | run failed: $(tail -1 "$run.log" | cut -c1-200) |"; continue; }
  row "cut element, a/h = $(/usr/bin/python3 -c "print(0.125 * 2**$level)"), correction below $gap a (the finest run's step-1 positions)" "$run" 0
done
