#!/usr/bin/env bash
# The mesh resolution a dense 3D suspension needs: one configuration of
# the bulk scene (prm/rheology_bulk_3d.prm with its solver settings:
# sliding walls, periodic in x and z, inelastic contact, lubrication
# correction) with spheres of radius RADIUS at phi = 0.3 in a box of
# LX x LY x LZ, solved on uniform meshes of each level of LEVELS (a/h =
# RADIUS * 2^level). The generator places the same spheres whatever the
# level (same seed, same box), so step 0 compares the meshes on one
# configuration; step 1, after a strain of 0.02, adds the lubrication
# correction's bonds.
#
# Printed per level and step: a/h, the unknowns, the relative viscosity
# and its lubrication and contact parts, N1, N2 and the particle pressure
# (in eta gamma_dot), and the wall seconds of the run.
#
# Env: RADIUS (default 0.0625: a/h = 1, 2, 4 at levels 4, 5, 6), LEVELS
# (default "4 5 6"), LX, LY, LZ (default 0.5, 1, 0.5: 73 spheres, walls
# 16 radii apart), NP (ranks, default 2), FIDUS, WORK (keep the runs
# there).
# Usage: contrib/benchmarks/bulk_resolution.sh
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
. "$top/contrib/benchmarks/bulk_scene.sh"
[ -n "${FIDUS:-}" ] || "$top/contrib/build.sh" fidus >/dev/null
fidus="${FIDUS:-$top/build-release/fidus}"
radius="${RADIUS:-0.0625}"; levels="${LEVELS:-4 5 6}"
lx="${LX:-0.5}"; ly="${LY:-1}"; lz="${LZ:-0.5}"; np="${NP:-2}"
if [ -n "${WORK:-}" ]; then mkdir -p "$WORK"; work="$(cd "$WORK" && pwd)"
else work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT; fi
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

echo "| level | a/h | spheres | unknowns | step | eta_r | lubrication part | contact part | N1 | N2 | Pi | run s |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for level in $levels; do
  out="$work/run_$level"
  bulk_prm "$out" "$lx" "$ly" "$lz" "$level" 0.02 "$radius" \
    > "$work/run_$level.prm"
  if ! mpirun -np "$np" --oversubscribe "$fidus" "$work/run_$level.prm" > "$work/log_$level" 2>&1; then
    echo "| $level | run failed |"; tail -3 "$work/log_$level"; continue
  fi
  /usr/bin/python3 - "$out" "$level" "$radius" <<'PY'
import csv, sys
out, level, radius = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
rows = list(csv.DictReader(open(out + "/statistics.csv")))
spheres = len({r["id"] for r in csv.DictReader(open(out + "/particles.csv"))
               if r["step"] == "0"})
for r in rows:
    print("| %d | %.2g | %d | %s | %s | %.4f | %.4f | %.4f | %.4f | %.4f | %.4f | %.0f |" % (
        level, radius * 2**level, spheres, r["dofs"], r["step"],
        float(r["relative_viscosity"]), float(r["lubrication_relative_viscosity"]),
        float(r["contact_relative_viscosity"]), float(r["normal_stress_difference_1"]),
        float(r["normal_stress_difference_2"]), float(r["particle_pressure"]),
        float(rows[-1]["wall_seconds"])))
PY
done
