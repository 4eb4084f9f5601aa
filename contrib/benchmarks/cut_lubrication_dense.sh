#!/usr/bin/env bash
# The sub-grid lubrication inside the cut element against the cut element
# that resolves every gap, on the dense 2D scene
# prm/rheology_steady_shear_2d_cut.prm (138 discs, area fraction 0.4,
# level 6) at its first configuration: step 0 and one step of 0.02.
# Each variant is "minimum gap, gap cells, correction"; the first is the
# reference (the shipped prm). Prints, per variant, the unknowns, the wall
# seconds of the run (two solves and the set-up), eta_r at steps 0 and 1,
# N1 and the particle pressure at step 0, and the correction's part of
# eta_r at step 1 (doc/history/cut_element_lubrication.md).
# Usage: contrib/benchmarks/cut_lubrication_dense.sh \
#          ["1e-4 2 false" "0.02 0 true" ...]   (defaults: the table's rows)
# WORK=<dir> keeps the runs there; JOBS=2 runs two at a time.
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
[ -n "${FIDUS:-}" ] || "$top/contrib/build.sh" fidus >/dev/null
fidus="${FIDUS:-$top/build-release/fidus}"
work="${WORK:-$(mktemp -d)}"
mkdir -p "$work"
if [ $# -eq 0 ]; then
  set -- "1e-4 2 false" "1e-4 0 false" "0.02 0 true" "0.02 1 true" \
         "0.05 0 true" "0.05 1 true" "0.1 0 true"
fi
run_variant() {
  local gap="$1" cells="$2" corrected="$3" name="g${1}_c${2}_${3}"
  sed -e "s#output/rheology_steady_shear_2d_cut#$work/$name#" \
      -e "s/Cut minimum gap = 1e-4/Cut minimum gap = $gap\n  set Lubrication correction = $corrected/" \
      -e "s/Cut gap cells   = 2/Cut gap cells   = $cells/" \
      -e 's/End time  = 1.5/End time  = 0.02/' \
      "$top/prm/rheology_steady_shear_2d_cut.prm" > "$work/$name.prm"
  "$fidus" "$work/$name.prm" > "$work/$name.log" 2>&1 \
    || { echo "FAILED: $name (see $work/$name.log)"; return 1; }
}
pids=()
for v in "$@"; do
  run_variant $v &
  pids+=($!)
  if [ "${#pids[@]}" -ge "${JOBS:-1}" ]; then wait "${pids[0]}"; pids=("${pids[@]:1}"); fi
done
wait
echo "| minimum gap, gap cells, correction | unknowns | wall s | eta_r step 0 | eta_r step 1 | N1 step 0 | Pi step 0 | correction's eta_r, step 1 |"
echo "|---|---|---|---|---|---|---|---|"
for v in "$@"; do
  set -- $v
  /usr/bin/python3 - "$work/g${1}_c${2}_${3}/statistics.csv" "$v" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
s0, s1 = rows[0], rows[1]
print("| %s | %s | %.1f | %.4f | %.4f | %.4f | %.4f | %.3f |" % (
    sys.argv[2], s0["dofs"], float(s1["wall_seconds"]),
    float(s0["relative_viscosity"]), float(s1["relative_viscosity"]),
    float(s0["normal_stress_difference_1"]), float(s0["particle_pressure"]),
    float(s1["lubrication_relative_viscosity"])))
PY
done
