#!/usr/bin/env bash
# The geometric multigrid's hierarchy in 3D has one level per refinement
# level of the mesh, not the two levels that limited the ML AMG (a fine
# level and one coarse aggregate level): the 3D exact rigid inclusion
# (a = 0.2, off-centre) at Maximum level 3 and 4 with Preconditioner = GMG
# and Verbosity = verbose, whose screen prints "multigrid: N levels" at
# every set-up. Checks N >= 3, N(level 4) = N(level 3) + 1, and that the
# FGMRES count per Uzawa solve stays within 30 at both levels.
# Usage: run_multigrid_levels_test.sh path/to/fidus
set -u
fidus="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$work"
failures=0
passes=0

check() {  # check NAME COMMAND...: run COMMAND, report ok/FAILED
  local name="$1"; shift
  if "$@"; then
    passes=$((passes + 1)); echo "ok: $name"
  else
    failures=$((failures + 1)); echo "FAILED: $name"
  fi
}

# run LEVEL: writes level-LEVEL.log and out-LEVEL/statistics.csv
run() {
  cat > "level-$1.prm" <<PRM
set Dimension = 3
set Output directory = $work/out-$1
subsection Domain
  set Lower left = 0, 0, 0
  set Upper right = 1, 1, 1
  set Boundary condition = exact rigid inclusion
end
subsection Fluid
  subsection Linear solver
    set Preconditioner = GMG
  end
end
subsection Particles
  set Radius = 0.2
  set Positions = 0.53, 0.48, 0.51
end
subsection Time stepping
  set End time = 0
end
subsection Mesh refinement
  set Initial global refinement = 2
  set Minimum level = 2
  set Maximum level = $1
end
subsection Output
  set Verbosity = verbose
end
PRM
  "$fidus" "level-$1.prm" > "level-$1.log" 2>&1
}

levels_of() {  # the number of levels of the first multigrid set-up
  grep -o 'multigrid: [0-9]* levels' "level-$1.log" | head -1 | awk '{print $2}'
}

per_solve() {  # FGMRES per Uzawa solve of step 0, from statistics.csv
  python3 - "$work/out-$1/statistics.csv" <<'PY'
import csv, sys
row = next(csv.DictReader(open(sys.argv[1])))
print("%.1f" % (float(row["linear_iterations"]) / float(row["uzawa_iterations"])))
PY
}

for level in 3 4; do
  check "3D level $level runs" run "$level"
done
n3=$(levels_of 3); n4=$(levels_of 4)
echo "multigrid levels: $n3 at Maximum level 3, $n4 at Maximum level 4"
check "3D hierarchy has more than two levels" [ "${n3:-0}" -ge 3 ]
check "one more mesh level gives one more multigrid level" [ "${n4:-0}" -eq $(( ${n3:-0} + 1 )) ]
for level in 3 4; do
  s=$(per_solve "$level")
  echo "FGMRES per Uzawa solve at Maximum level $level: $s"
  check "FGMRES per solve at level $level <= 30" python3 -c "import sys; sys.exit(0 if $s <= 30 else 1)"
done

echo "$passes passed, $failures failed"
[ "$failures" -eq 0 ]
