#!/usr/bin/env bash
# contrib/benchmarks/dense_configurations.py against known answers. The
# scene (discs at area fraction 0.3 with the lubrication correction on a
# uniform level-5 mesh) is given as both the fluid and the reference, at
# its own level, so that every fictitious-domain run repeats its reference
# run exactly:
#  1. every error is zero (η_r +0.0 % ± 0.0, N1 and Π +0.000 ± 0.000), N1
#     is followed with slope and correlation 1.00, the close pairs' closing
#     speed is 1.00 of the reference's;
#  2. the configurations are the source run's positions at the requested
#     strains, recounted here from its particles.csv;
#  3. --from another work takes its configurations and references and
#     prints the same row;
#  4. bad input (strains out of order, a bad --variant) gives one message
#     and a non-zero exit status.
# Usage: run_dense_configurations_test.sh path/to/fidus path/to/repo
. "$(dirname "${BASH_SOURCE[0]}")/driver_test_lib.sh" "$1" "$2"
driver="$repo/contrib/benchmarks/dense_configurations.py"

cat > scene.prm <<'PRM'
set Dimension = 2
subsection Domain
  set Boundary condition = sliding walls
  set Shear rate = 1
end
subsection Fluid
  set Shared cells = fluid
  set Lubrication correction = true
end
subsection Particles
  subsection Generator
    set Fraction = 0.3
    set Radii = 0.05
    set Minimum separation = 0.01
  end
end
subsection Contact
  set Model = gluey
end
subsection Time stepping
  set Time step = 0.02
end
subsection Mesh refinement
  set Initial global refinement = 5
  set Minimum level = 5
  set Maximum level = 5
end
PRM

"$python" "$driver" scene.prm scene.prm --fidus "$fidus" --levels 5 \
  --strains 0.04,0.08,0.02 --pair-gap 0.5 --work runs > table.txt 2> err.txt
status=$?
check "driver runs" test $status -eq 0
# What failed, if it did (the driver names the run; fidus's own message is
# in that run's stderr.txt).
if [ $status -ne 0 ]; then
  cat err.txt
  cat runs/*/stderr.txt runs/*/*/stderr.txt 2> /dev/null | tail -20
fi

cell() {  # cell N: the N-th cell of the row of the prm's settings
  grep "^| prm's settings | 5 |" table.txt |
    awk -F'|' -v n="$(($1 + 1))" '{ gsub(/^ +| +$/, "", $n); print $n }'
}
check "eta_r error zero" test "$(cell 3)" = "+0.0 % ± 0.0"
check "N1 and Pi errors zero" test "$(cell 4)/$(cell 5)" = "+0.000 ± 0.000/+0.000 ± 0.000"
check "N1 followed with slope 1" test "$(cell 6)" = "1.00 (1.00)"
check "closing speed 1 of the reference's" test "$(cell 8)" = "1.00"
check "three configurations" grep -q "^3 configurations" table.txt
# The positions of the source run at strain 0.06 (step 3), recounted.
expected=$(awk -F, 'NR > 1 && $1 == 3 { n++ } END { print n }' runs/source/output/particles.csv)
check "configuration of step 3 holds the source's $expected discs" \
  test "$(wc -l < runs/configuration_3.txt)" -eq "$expected"
check "its first disc at the source's position" test \
  "$(head -1 runs/configuration_3.txt | cut -d' ' -f1)" = \
  "$(awk -F, 'NR > 1 && $1 == 3 { print $4; exit }' runs/source/output/particles.csv)"

"$python" "$driver" scene.prm scene.prm --fidus "$fidus" --levels 5 \
  --strains 0.04,0.08,0.02 --pair-gap 0.5 --from runs --work second > second.txt 2> /dev/null
check "--from: the same row" test \
  "$(grep "^| prm's settings" second.txt)" = "$(grep "^| prm's settings" table.txt)"
check "--from: no source run of its own" test ! -e second/source

bad() {  # bad PATTERN ARGS...: a non-zero exit and one message matching
  # PATTERN on stderr
  local pattern="$1"; shift
  "$python" "$driver" --fidus "$fidus" --work bad "$@" > bad.out 2> message.txt
  local status=$?
  [ $status -ne 0 ] && [ "$(wc -l < message.txt)" -eq 1 ] && grep -q -- "$pattern" message.txt
}
check "strains out of order" bad "needs 0 < first <= last" scene.prm scene.prm --strains 0.5,0.1,0.1
check "bad --variant" bad "allowed: name=Key=value" scene.prm scene.prm --variant nothing

echo "$failures failure(s)"
[ $failures -eq 0 ]
