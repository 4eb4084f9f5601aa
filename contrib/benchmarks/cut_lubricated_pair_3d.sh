#!/usr/bin/env bash
# The sub-grid lubrication inside the 3D cut element against the cut element
# that resolves the gap (doc/theory/lubrication.md, "With the cut finite
# element"). Two spheres of radius 0.15 in the middle of the unit box, their
# line of centres at 135 degrees from the flow in the shear plane, at a gap
# of GAP (relative to a), one step of 1e-4:
#   - sheared: linear shear of rate 1 (the compressional axis), force-free;
#   - pushed: the box at rest, a force of 1 on each sphere along the line.
# Each variant is "minimum gap, correction": the fluid resolves every gap
# down to the minimum gap (Fluid/Cut minimum gap) and, with the correction,
# the bonds add the resistance between it and the true gap. The reference
# is "1e-4 false" (the gap resolved). Prints per variant and case: the
# closing speed, the pair's stresslet xy (the fluid's and the bonds'), each
# over the reference's, fidus's wall seconds and peak memory.
# Env: GAP (default 0.01), LEVEL (Initial global refinement, default 3:
#   a/h = 1.2 away from the particles), GAP_CELLS (Cut gap cells, default 1),
#   CASES (default "sheared pushed"), WORK (keep the runs there), FIDUS.
# Usage: contrib/benchmarks/cut_lubricated_pair_3d.sh \
#          ["1e-4 false" "0.02 true" ...]   (defaults: the table's rows)
# The resolved pair at 0.01 a takes about 9 minutes and 17 GB.
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
[ -n "${FIDUS:-}" ] || "$top/contrib/build.sh" fidus >/dev/null
fidus="${FIDUS:-$top/build-release/fidus}"
work="${WORK:-$(mktemp -d)}"
mkdir -p "$work"
gap="${GAP:-0.01}"
level="${LEVEL:-3}"
if [ $# -eq 0 ]; then
  set -- "1e-4 false" "0.02 true" "0.05 true" "0.1 true" "0.1 false"
fi
variants=("$@")
a=0.15
# centre 1/2, line at 135 degrees, centres 2a + gap a apart
read -r x0 y0 x1 y1 forces < <(python3 -c "
import math
a = $a; d = a + 0.5 * $gap * a; t = math.radians(135.)
c, s = math.cos(t), math.sin(t)
print('%.17g %.17g %.17g %.17g' % (0.5 - d * c, 0.5 - d * s, 0.5 + d * c, 0.5 + d * s),
      '%.17g, %.17g, 0; %.17g, %.17g, 0' % (c, s, -c, -s))")

run() { # case minimum_gap corrected -> "closing stresslet seconds peak"
  local case="$1" hs="$2" corrected="$3" name="${1}_${2}_${3}"
  local shear=1 force=""
  if [ "$case" = pushed ]; then
    shear=0
    force="  set External force = $forces"
  fi
  cat > "$work/$name.prm" <<PRM
set Dimension = 3
set Output directory = $work/$name
subsection Domain
  set Lower left = 0, 0, 0
  set Upper right = 1, 1, 1
  set Boundary condition = linear shear
  set Shear rate = $shear
end
subsection Fluid
  set Model = cut finite element
  set Cut minimum gap = $hs
  set Cut gap cells = ${GAP_CELLS:-1}
  set Lubrication correction = $corrected
end
subsection Particles
  set Radius = $a
  set Positions = $x0, $y0, 0.5; $x1, $y1, 0.5
$force
end
subsection Contact
  set Model = none
  set Walls = true
  set Roughness = 1e-4
end
subsection Time stepping
  set End time = 1e-4
  set Time step = 1e-4
end
subsection Mesh refinement
  set Initial global refinement = $level
  set Minimum level = $level
  set Maximum level = $((level + 2))
end
PRM
  "$fidus" "$work/$name.prm" > "$work/$name.log" 2>&1 ||
    { echo "FAILED: $name (see $work/$name.log)" >&2; return 1; }
  python3 - "$work/$name" "$a" <<'PY'
import csv, math, re, sys
d, a = sys.argv[1], float(sys.argv[2])
rows = list(csv.DictReader(open(d + '/particles.csv')))
def gap(r0, r1):
    return math.dist([float(r0[k]) for k in 'xyz'], [float(r1[k]) for k in 'xyz']) - 2 * a
closing = (gap(rows[0], rows[1]) - gap(rows[2], rows[3])) / 1e-4
stresslet = sum(float(r['stresslet_xy']) + float(r.get('lubrication_stresslet_xy') or 0)
                for r in rows[:2])
print(closing, stresslet)
PY
}
echo "3D pair, a = $a, gap $gap a, level $level, gap cells ${GAP_CELLS:-1}:"
echo "| case | minimum gap | correction | closing / resolved | stresslet xy / resolved | s | peak GB |"
echo "|---|---|---|---|---|---|---|"
for case in ${CASES:-sheared pushed}; do
  ref=""
  for v in "${variants[@]}"; do
    set -- $v
    start=$(date +%s.%N)
    read -r closing stresslet < <(run "$case" "$1" "$2")
    seconds=$(python3 -c "print('%.0f' % ($(date +%s.%N) - $start))")
    peak=$(grep -o "peak memory per rank: [0-9.]* [GMk]B" "$work/${case}_${1}_${2}.log" | awk '{print $5, $6}')
    [ -n "$ref" ] || ref="$closing $stresslet"
    read -r rc rs <<< "$ref"
    python3 -c "
c, s, rc, rs = $closing, $stresslet, $rc, $rs
sr = '%.3f' % (s / rs) if abs(rs) > 1e-12 else '-'
print('| $case | $1 | $2 | %.3f | %s | $seconds | $peak |' % (c / rc, sr))"
  done
done
