# Sourced by the bulk benchmarks (bulk_solver.sh, bulk_scaling.sh,
# bulk_resolution.sh): prm/rheology_bulk_3d.prm rescaled to another box,
# a uniform mesh and an end time.

# bulk_prm OUT LX LY LZ LEVEL END_TIME [RADIUS]: print the scene with its
# output in OUT, the box LX x LY x LZ, a uniform mesh whose cells are
# those of the unit box's level LEVEL, End time END_TIME and, if given,
# the spheres' radius RADIUS. The coarse mesh has cubes of the box's
# smallest side: one level less per halving keeps the finest cell at
# 1 / 2^LEVEL.
bulk_prm() {
  local out="$1" lx="$2" ly="$3" lz="$4" level="$5" end="$6" radius="${7:-}"
  local top box_level
  top="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
  box_level=$(/usr/bin/python3 -c "import math; print($level + round(math.log2(min($lx, $ly, $lz))))")
  local radius_rule=()
  [ -n "$radius" ] && radius_rule=(-e "s#^    set Radii .*#    set Radii              = $radius#")
  sed -e "s#^set Output directory.*#set Output directory = $out#" \
      -e "s#^  set Upper right .*#  set Upper right        = $lx, $ly, $lz#" \
      "${radius_rule[@]}" \
      -e "s#^  set Initial global refinement.*#  set Initial global refinement = $box_level#" \
      -e "s#^  set Minimum level .*#  set Minimum level             = $box_level#" \
      -e "s#^  set Maximum level .*#  set Maximum level             = $box_level#" \
      -e "s#^  set End time .*#  set End time  = $end#" \
      "$top/prm/rheology_bulk_3d.prm"
}
