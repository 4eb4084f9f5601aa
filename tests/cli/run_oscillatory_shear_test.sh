#!/usr/bin/env bash
# contrib/oscillatory_shear.py against known answers, with two discs
# (radius 0.04, centres 0.1 apart in x and 0.02 in y) in undisturbed shear,
# which under the strain g meet when g = 1.127:
#  1. amplitude 0.5: they never touch, the affine motion comes back exactly
#     each cycle (the midpoint shear rates of a cycle sum to zero): no
#     particle is counted, largest |dX| below 1e-9 a, for both models;
#  2. amplitude 2: the inelastic pair is pushed off its streamlines in the
#     first cycle (both particles counted) onto the ones that just graze at
#     the largest strain (distance 2a there, 1e-3), and then comes back
#     exactly (an absorbing state: none counted, |dX| below 1e-9 a); the
#     gluey pair comes back every cycle (none counted, |dX| below 1 % of a);
#  3. the table's fractions equal returns.csv, recomputed here from
#     particles.csv; bad input gives one message and exit status 1.
# Usage: run_oscillatory_shear_test.sh path/to/fidus path/to/repo
# FIDUS_KEEP=1 keeps the temporary folder; PYTHON picks the interpreter.
. "$(dirname "${BASH_SOURCE[0]}")/driver_test_lib.sh" "$1" "$2"
driver="$repo/contrib/oscillatory_shear.py"

cat > pair.prm <<'PRM'
set Dimension = 2
subsection Domain
  set Lower left = -1, 0
  set Upper right = 2, 1
  set Boundary condition = linear shear
end
subsection Fluid
  set Model = undisturbed shear
end
subsection Particles
  set Radius = 0.04
  set Positions = 0.45, 0.51; 0.55, 0.49
end
PRM

"$python" "$driver" pair.prm --fidus "$fidus" --amplitudes 0.5,2 \
  --models inelastic,gluey --cycles 3 --out osc > table.txt 2> err.txt
check "driver runs" test $? -eq 0

# returns.csv: model,amplitude,cycle,not_returned_fraction,mean,max
value() {  # value MODEL AMPLITUDE CYCLE COLUMN
  awk -F, -v m="$1" -v g="$2" -v k="$3" -v c="$4" \
    '$1 == m && $2 == g && $3 == k { print $c }' osc/returns.csv
}
below() { awk -v x="$1" -v y="$2" 'BEGIN { exit !(x < y) }'; }
for m in inelastic gluey; do
  for k in 1 2 3; do
    check "$m, amplitude 0.5, cycle $k: nobody counted" test "$(value $m 0.5 $k 4)" = 0
    check "$m, amplitude 0.5, cycle $k: max |dX| < 1e-9 a" below "$(value $m 0.5 $k 6)" 1e-9
  done
done
check "inelastic, amplitude 2, cycle 1: both counted" test "$(value inelastic 2 1 4)" = 1
for k in 2 3; do
  check "inelastic, amplitude 2, cycle $k: nobody counted" test "$(value inelastic 2 $k 4)" = 0
  check "inelastic, amplitude 2, cycle $k: max |dX| < 1e-9 a" below "$(value inelastic 2 $k 6)" 1e-9
done
grazing=$("$python" - osc/inelastic_g2/output/particles.csv <<'PY'
import csv, math, sys
rows = [r for r in csv.DictReader(open(sys.argv[1]))]
steps = sorted({int(r["step"]) for r in rows})
p = {r["id"]: (float(r["x"]), float(r["y"])) for r in rows if int(r["step"]) == steps[1]}
dx, dy = p["1"][0] - p["0"][0], p["1"][1] - p["0"][1]
print(abs(math.hypot(dx + 2 * dy, dy) / 0.08 - 1))
PY
)
check "inelastic, amplitude 2: after cycle 1 the pair grazes at strain 2 (1e-3)" below "$grazing" 1e-3
for k in 1 2 3; do
  check "gluey, amplitude 2, cycle $k: nobody counted" test "$(value gluey 2 $k 4)" = 0
  check "gluey, amplitude 2, cycle $k: max |dX| < 0.01 a" below "$(value gluey 2 $k 6)" 0.01
done

# Recompute the inelastic amplitude-2 fraction of cycle 2 from particles.csv.
recomputed=$("$python" - osc/inelastic_g2/output/particles.csv <<'PY'
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
steps = sorted({int(r["step"]) for r in rows})
at = {s: {r["id"]: (float(r["x"]), float(r["y"]), float(r["radius"]))
          for r in rows if int(r["step"]) == s} for s in steps}
a, b = at[steps[1]], at[steps[2]]
moved = sum(math.hypot(b[i][0] - a[i][0], b[i][1] - a[i][1]) / a[i][2] > 0.01 for i in a)
print(f"{moved / len(a):g}")
PY
)
check "cycle 2 fraction recomputed from particles.csv" test "$recomputed" = "$(value inelastic 2 2 4)"
check "table lists both models" grep -q "| gluey | 2 |" table.txt

bad() {  # bad PATTERN ARGS...: exit status 1 and one stderr line matching PATTERN
  local pattern="$1"; shift
  "$python" "$driver" --fidus "$fidus" "$@" > bad.out 2> bad.err
  local status=$?
  [ $status -eq 1 ] && [ "$(wc -l < bad.err)" -eq 1 ] && grep -q -- "$pattern" bad.err
}
check "negative amplitude" bad "amplitudes.*allowed: numbers > 0" pair.prm --amplitudes -1
check "unknown model" bad "models.*allowed: none, inelastic, gluey" pair.prm --models sticky
check "one cycle" bad "cycles.*allowed: an integer >= 2" pair.prm --cycles 1
check "missing prm" bad "cannot read the parameter file" missing.prm
check "bad --set" bad "set.*allowed: Section/Entry=value" pair.prm --set Model=none

echo "$failures failure(s)"
[ $failures -eq 0 ]
