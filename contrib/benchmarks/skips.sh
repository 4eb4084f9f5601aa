#!/usr/bin/env bash
# "Skip what a scene does not need", measured: the 2D paper scene (gluey,
# fictitious domain) to t = T with
#   default          remeshing skipped while particles moved less than half
#                    the refined band; no VTU output;
#   remesh always    'Mesh refinement/Remesh fraction = 0' (the refinement
#                    is recomputed every step; a changed mesh also loses the
#                    warm start of the Uzawa multiplier);
#   VTU every step   'Output/Field output interval = 1'.
# Prints the stage timing table (wall seconds) and the summed FGMRES
# iterations of each run.
# Usage: contrib/benchmarks/skips.sh [end time, default 3] [max level, default 6]
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
[ -n "${FIDUS:-}" ] || "$top/contrib/build.sh" fidus >/dev/null
fidus="${FIDUS:-$top/build-release/fidus}"
end="${1:-3}"; level="${2:-6}"
work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT

run() { # name, extra prm lines (mesh), extra prm lines (output)
  local name=$1 mesh=$2 out=$3
  sed -e "s#^set Output directory.*#set Output directory = $work/$name#" \
      -e "s#^  set End time .*#  set End time = $end#" \
      -e "s#^  set Maximum level .*#  set Maximum level = $level\n$mesh#" \
      -e "s#^  set Field output interval .*#  set Field output interval = $out#" \
      "$top/prm/two_particles_2d.prm" > "$work/$name.prm"
  "$fidus" "$work/$name.prm" > "$work/$name.log" 2>&1
  local its remeshes
  its=$(awk -F, 'NR>1{s+=$7}END{print s}' "$work/$name/statistics.csv")
  remeshes=$(awk -F, 'NR>1{s+=$13}END{print s}' "$work/$name/statistics.csv")
  printf "| %-15s | %s | %s |" "$name" "$its" "$remeshes"
  for stage in total fluid mesh "rigid motion" contact output; do
    if [ "$stage" = total ]; then
      v=$(grep "Total wallclock" "$work/$name.log" | awk -F'|' '{print $3}')
    else
      v=$(grep "^| $stage " "$work/$name.log" | awk -F'|' '{print $4}')
    fi
    printf " %s |" "$(echo $v)"
  done
  echo
}

echo "2D paper scene, gluey, t <= $end, maximum level $level"
echo
echo "| run | FGMRES (sum) | remeshes | total | fluid | mesh | rigid motion | contact | output |"
echo "|---|---|---|---|---|---|---|---|---|"
run default "" 0
run remesh_always "  set Remesh fraction = 0" 0
run vtu_every_step "" 1
