#!/usr/bin/env bash
# The paper's 3D pair under the cut element as shipped
# (prm/two_particles_3d_cut.prm: a = 0.05, the gaps resolved down to 0.05 a,
# the sub-grid correction below), held at gaps GAPS (in radii) on the
# compressional axis of the shear (the line of centres at 135 degrees from
# the flow, in the shear plane, about the box's centre), two steps of 1e-4
# (three solves: the first from zero, the others from the previous one).
# Prints per gap and number of ranks: the unknowns, FGMRES of the first
# solve and of the next ones, seconds per solve (fidus's "all" of each
# solve: mesh, DoFs, assembly, solve, measure), the peak memory per rank,
# and the closing speed the first solve returns against Batchelor &
# Green's exact one at that configuration (batchelor_green.py: unbounded
# shear, so the box's walls, 9 radii away, are part of the difference).
# Env: GAPS (default "0.1 0.01 0.001"), RANKS (default "1 2"; each run with
#   mpirun --bind-to none), FIDUS (the binary; default built with
#   contrib/build.sh), WORK (keep the runs there).
# Usage: contrib/benchmarks/cut_pair_gaps_3d.sh
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
[ -n "${FIDUS:-}" ] || "$top/contrib/build.sh" fidus >/dev/null
fidus="${FIDUS:-$top/build-release/fidus}"
if [ -n "${WORK:-}" ]; then mkdir -p "$WORK"; work="$(cd "$WORK" && pwd)"
else work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT; fi
a=0.05

echo "| gap / a | ranks | unknowns | FGMRES first, next | s per solve | peak per rank | closing speed / exact |"
echo "|---|---|---|---|---|---|---|"
for gap in ${GAPS:-0.1 0.01 0.001}; do
  read -r x0 y0 x1 y1 < <(python3 -c "
import math
d = $a + 0.5 * $gap * $a; t = math.radians(135.)
print('%.17g %.17g %.17g %.17g' % (0.5 - d * math.cos(t), 0.5 - d * math.sin(t),
                                   0.5 + d * math.cos(t), 0.5 + d * math.sin(t)))")
  for ranks in ${RANKS:-1 2}; do
    name="gap_${gap}_ranks_${ranks}"
    sed -e "s#^set Output directory.*#set Output directory = $work/$name#" \
        -e "s#^  set Positions .*#  set Positions = $x0, $y0, 0.5; $x1, $y1, 0.5#" \
        -e 's/^  set End time .*/  set End time          = 2e-4/' \
        -e 's/^  set Time step .*/  set Time step         = 1e-4/' \
        -e 's/^  set Checkpoint wall interval .*/  set Checkpoint wall interval = 0/' \
        -e 's/^subsection Output/subsection Output\n  set Verbosity = verbose/' \
        "$top/prm/two_particles_3d_cut.prm" > "$work/$name.prm"
    if [ "$ranks" -gt 1 ]; then
      mpirun --bind-to none -np "$ranks" "$fidus" "$work/$name.prm" \
        > "$work/$name.log" 2>&1
    else
      "$fidus" "$work/$name.prm" > "$work/$name.log" 2>&1
    fi || { echo "FAILED: $name (see $work/$name.log)" >&2; exit 1; }
    python3 - "$work/$name" "$work/$name.log" "$gap" "$ranks" "$a" \
      "$top/contrib/benchmarks" <<'PY'
import csv, math, os, re, sys
out, log, gap, ranks, a = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], float(sys.argv[5])
sys.path.insert(0, sys.argv[6])
from batchelor_green import Mobility
text = open(log).read()
solves = re.findall(r"cut element: (\d+) unknowns.*?FGMRES (\d+),.*?all ([0-9.e+-]+)", text)
peak = re.search(r"peak memory per rank: ([0-9.]+ [GMk]B)", text).group(1)
rows = [r for r in csv.DictReader(open(out + "/particles.csv")) if r["step"] == "0"]
x = [[float(r[k]) for k in "xyz"] for r in rows]
u = [[float(r["u" + k]) for k in "xyz"] for r in rows]
d = [x[1][k] - x[0][k] for k in range(3)]
dist = math.sqrt(sum(c * c for c in d))
closing = -sum((u[1][k] - u[0][k]) * d[k] for k in range(3)) / dist
r = dist / a
A, _ = Mobility().AB(r)
theta = math.atan2(d[1], d[0])
exact = -a * r * (1.0 - A) * math.sin(theta) * math.cos(theta)
seconds = sum(float(s[2]) for s in solves) / len(solves)
print("| %s | %s | %s | %s, %s | %.2f | %s | %.4f |" % (
    gap, ranks, solves[0][0], solves[0][1],
    ", ".join(s[1] for s in solves[1:]), seconds, peak, closing / exact))
PY
  done
done
