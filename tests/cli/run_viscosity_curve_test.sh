#!/usr/bin/env bash
# contrib/benchmarks/viscosity_curve.py against known answers, with the
# 'undisturbed shear' fluid and no contact model, where the suspension's
# stress is the fluid's alone (free-draining particles carry none):
#  1. at fractions 0.1 and 0.2, eta_r = 1 exactly in every row, so its mean
#     is 1.000 with standard error 0.000, as are the lubrication and contact
#     parts 0.000; the dilute column is 1 + 2 phi;
#  2. the number of discs and of steps and rows in the window are those of
#     the runs' CSV files, recounted here;
#  3. --reuse prints the same table without running fidus again;
#  4. bad input (a fraction outside (0, 1), a bad --set, an empty window)
#     gives one message and a non-zero exit status.
# Usage: run_viscosity_curve_test.sh path/to/fidus path/to/repo
. "$(dirname "${BASH_SOURCE[0]}")/driver_test_lib.sh" "$1" "$2"
driver="$repo/contrib/benchmarks/viscosity_curve.py"

cat > scene.prm <<'PRM'
set Dimension = 2
subsection Domain
  set Boundary condition = sliding walls
  set Shear rate = 1
end
subsection Fluid
  set Model = undisturbed shear
end
subsection Particles
  subsection Generator
    set Fraction = 0.3
    set Radii = 0.04
    set Minimum separation = 0.02
  end
end
subsection Contact
  set Model = none
end
subsection Time stepping
  set End time = 0.4
  set Time step = 0.02
end
PRM

"$python" "$driver" scene.prm --fidus "$fidus" --fractions 0.1,0.2 \
  --window 0,0.4 --work runs > table.txt 2> err.txt
check "driver runs" test $? -eq 0

row() {  # row FRACTION: the table's row of that fraction
  grep "^| $1 |" table.txt
}
column() {  # column FRACTION N: the N-th cell of that row
  row "$1" | awk -F'|' -v n="$(($2 + 1))" '{ gsub(/^ +| +$/, "", $n); print $n }'
}
for phi in 0.1 0.2; do
  check "fraction $phi: eta_r 1.000 +- 0.000" test "$(column $phi 4)" = "1.000 ± 0.000"
  check "fraction $phi: contact and lubrication parts 0" \
    test "$(column $phi 5)/$(column $phi 6)" = "0.000/0.000"
  check "fraction $phi: eta_r at step 0 is 1" test "$(column $phi 9)" = "1.000"
  discs=$(awk -F, 'NR > 1 && $1 == 0' runs/fraction_$phi/output/particles.csv | wc -l)
  check "fraction $phi: $discs discs, as in particles.csv" test "$(column $phi 2)" = "$discs"
  check "fraction $phi: 20 steps, 21 rows in the window" test "$(column $phi 3)" = "20 (21)"
done
check "dilute column 1 + 2 phi" test "$(column 0.1 10)/$(column 0.2 10)" = "1.200/1.400"

"$python" "$driver" scene.prm --fidus /nonexistent/fidus --fractions 0.1,0.2 \
  --window 0,0.4 --work runs --reuse > again.txt 2> /dev/null
check "--reuse: the same table, fidus not run" \
  test "$(cut -d'|' -f1-11 again.txt)" = "$(cut -d'|' -f1-11 table.txt)"

bad() {  # bad PATTERN ARGS...: a non-zero exit and one message matching
  # PATTERN on stderr (besides the lines that announce each run)
  local pattern="$1"; shift
  "$python" "$driver" --fidus "$fidus" --work bad "$@" > bad.out 2> bad.err
  local status=$?
  grep -v ": running fraction" bad.err > message.txt
  [ $status -ne 0 ] && [ "$(wc -l < message.txt)" -eq 1 ] && grep -q -- "$pattern" message.txt
}
check "fraction 1.5" bad "fractions must lie in (0, 1)" scene.prm --fractions 1.5
check "bad --set" bad "allowed: Subsection/Entry=value" scene.prm --set Model
check "window after the End time" bad "rows in the window" scene.prm --fractions 0.1 --window 1,2

echo "$failures failure(s)"
[ $failures -eq 0 ]
