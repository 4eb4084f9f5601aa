#!/usr/bin/env bash
# Rigid inclusion with the exact solution on the box (validation.md case 3b):
# cells, DoFs, Uzawa and FGMRES iterations, solve time, L2 velocity error on
# the fluid part and omega error, for increasing maximum level and for
# penalty factors 1e2, 1e3, 1e4, 1e6, in 2D and 3D.
# Usage: contrib/benchmarks/rigid_inclusion.sh [2|3|both] [max 2D level] [max 3D level]
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
[ -n "${FIDUS:-}" ] || "$top/contrib/build.sh" fidus >/dev/null
fidus="${FIDUS:-$top/build-release/fidus}"
which="${1:-both}"; max2="${2:-8}"; max3="${3:-5}"
work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT

run_case() { # dim level penalty
  local dim=$1 level=$2 r=$3
  local box="0, 0"; local hi="1, 1"; local pos="0.5, 0.5"; local a=0.15; local init=2
  if [ "$dim" = 3 ]; then box="0, 0, 0"; hi="1, 1, 1"; pos="0.5, 0.5, 0.5"; a=0.2; fi
  cat > "$work/c.prm" <<EOF2
set Dimension = $dim
set Output directory = $work/out
subsection Domain
  set Lower left = $box
  set Upper right = $hi
  set Boundary condition = exact rigid inclusion
end
subsection Fluid
  set Penalty factor = $r
  set Rigidity tolerance = 5e-4
  set Rigidity measure = box
  set Maximum Uzawa iterations = 30
end
subsection Particles
  set Radius = $a
  set Positions = $pos
end
subsection Time stepping
  set End time = 0
end
subsection Mesh refinement
  set Initial global refinement = $init
  set Minimum level = $init
  set Maximum level = $level
end
EOF2
  local start end line stat
  start=$(date +%s.%N)
  line=$("$fidus" "$work/c.prm" 2>/dev/null | grep "exact rigid inclusion:" || true)
  end=$(date +%s.%N)
  stat=$(tail -1 "$work/out/statistics.csv")
  local cells dofs uz lin
  IFS=, read -r _ _ _ cells dofs uz lin _ <<< "$stat"
  local eu ew
  eu=$(sed -E 's/.*L2 error of u \(fluid\) ([^,]*),.*/\1/' <<< "$line")
  ew=$(sed -E 's/.*relative omega error ([^,]*),.*/\1/' <<< "$line")
  printf "| %dD | %2d | %8s | %7d | %8d | %5d | %6d | %8.2f | %10.3e | %10.3e |\n" \
    "$dim" "$level" "$r" "$cells" "$dofs" "$uz" "$lin" "$(awk "BEGIN{print $end - $start}")" "$eu" "$ew"
}

echo "| dim | level | penalty | cells | DoFs | Uzawa | FGMRES | seconds | L2 error u | omega error |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for dim in 2 3; do
  [ "$which" != both ] && [ "$which" != "$dim" ] && continue
  if [ $dim = 2 ]; then levels=$(seq 5 "$max2"); else levels=$(seq 3 "$max3"); fi
  for l in $levels; do run_case $dim "$l" 1000; done
  mid=$([ $dim = 2 ] && echo 7 || echo 4)
  for r in 100 10000 1000000; do run_case $dim $mid $r; done
done
