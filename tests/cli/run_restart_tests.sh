#!/usr/bin/env bash
# Checkpoint and restart: a run stopped by a signal and resumed gives the
# same rows and values as an uninterrupted run (bit-identical on the same
# number of ranks, to solver tolerance on another), a resumed run may go to
# a later End time, the CSV files have every step once, and a bad checkpoint
# gets one clear message, exit status 1 and changes no file.
# Usage: run_restart_tests.sh path/to/fidus
set -u
fidus="$1"
work="$(mktemp -d)"
# FIDUS_KEEP=1 keeps the work folder for inspection.
[ -z "${FIDUS_KEEP:-}" ] && trap 'rm -rf "$work"' EXIT
cd "$work"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mpirun_cmd=(mpirun -np 2 --oversubscribe)
failures=0
passes=0

pass() { passes=$((passes + 1)); echo "ok: $1"; }
fail() { failures=$((failures + 1)); echo "FAILED: $1"; }

# scene OUT END [Output lines] [further sections]: the paper's 2D pair
# (gluey) at level 5, 0.1 per step; the multiplier warm start and skipped
# remeshes are in play.
scene() {
  cat <<EOF2
${4:-}
set Dimension = 2
set Output directory = $work/$1
subsection Fluid
  set Rigidity tolerance = 1e-3
  set Rigidity measure = box
  set Maximum Uzawa iterations = 4
end
subsection Particles
  set Radius = 0.05
  set Positions = 0.451, 0.51; 0.549, 0.49
end
subsection Contact
  set Model = gluey
end
subsection Time stepping
  set End time = $2
  set Time step = 0.1
end
subsection Mesh refinement
  set Maximum level = 5
end
subsection Output
  set Particle output interval = 5
  set Verbosity = quiet
$3
end
EOF2
}

rows() { echo $(($(wc -l < "$1") - 1)); }

# Same rows and values, wall clock (column 12 of statistics.csv) excepted.
# The stress columns (particles.csv 14-19, statistics.csv 17-25) to 1e-10
# relative to the row's largest stress: a checkpoint does not hold the
# pressure's constant mode of the last solve, and the normal stresses carry
# it at the level of rounding (the mean pressure cancels between them in
# exact arithmetic, doc/restart.md).
same_stress() {
  paste -d, <(cut -d, -f"$3" "$1") <(cut -d, -f"$3" "$2") | awk -F, '
    NR > 1 { n = NF / 2; s = 0; d = 0
             for (c = 1; c <= n; ++c) {
               a = $c; if (a < 0) a = -a; if (a > s) s = a
               e = $c - $(c + n); if (e < 0) e = -e; if (e > d) d = e }
             if (d > 1e-10 * s) bad = 1 }
    END { exit bad }'
}
same_output() {
  cmp -s <(cut -d, -f1-13 "$1/particles.csv") \
         <(cut -d, -f1-13 "$2/particles.csv") &&
    cmp -s <(cut -d, -f1-11,13-16 "$1/statistics.csv") \
           <(cut -d, -f1-11,13-16 "$2/statistics.csv") &&
    same_stress "$1/particles.csv" "$2/particles.csv" 14-19 &&
    same_stress "$1/statistics.csv" "$2/statistics.csv" 17-25
}

# Which part of same_output() differs, and its first differing lines: a
# failure on a fresh machine is then readable from the CI log alone.
explain_difference() {
  cmp -s <(cut -d, -f1-13 "$1/particles.csv") <(cut -d, -f1-13 "$2/particles.csv") ||
    { echo "  particles.csv, columns 1-13:"; diff <(cut -d, -f1-13 "$1/particles.csv") \
        <(cut -d, -f1-13 "$2/particles.csv") | head -4; }
  cmp -s <(cut -d, -f1-11,13-16 "$1/statistics.csv") <(cut -d, -f1-11,13-16 "$2/statistics.csv") ||
    { echo "  statistics.csv, columns 1-11, 13-16:"; diff <(cut -d, -f1-11,13-16 "$1/statistics.csv") \
        <(cut -d, -f1-11,13-16 "$2/statistics.csv") | head -4; }
  same_stress "$1/particles.csv" "$2/particles.csv" 14-19 ||
    echo "  particles.csv stresslets (14-19) beyond 1e-10"
  same_stress "$1/statistics.csv" "$2/statistics.csv" 17-25 ||
    echo "  statistics.csv stresses (17-25) beyond 1e-10"
  no_duplicate_steps "$2" || echo "  $2/statistics.csv repeats or skips a step"
}

# largest_change REF OUT FIRST LAST: the largest difference between the
# two runs' particles.csv over the columns FIRST..LAST, every row, over the
# radius 0.05.
largest_change() {
  paste -d, "$1/particles.csv" "$2/particles.csv" | awk -F, -v first="$3" -v last="$4" \
    -v nc="$(head -1 "$1/particles.csv" | awk -F, '{ print NF }')" '
    NR > 1 { for (c = first; c <= last; ++c) { d = $c - $(c + nc); if (d < 0) d = -d; if (d > m) m = d } }
    END { printf "%.3e", m / 0.05 }'
}

# Every step once, in order.
no_duplicate_steps() {
  tail -n +2 "$1/statistics.csv" | cut -d, -f1 |
    awk 'NR > 1 && $1 != prev + 1 { bad = 1 } { prev = $1 } END { exit bad }'
}

# run_and_signal OUT PRM SIGNAL LAUNCHER...: start the run, send SIGNAL once
# 8 steps are written, wait; prints the exit status.
run_and_signal() {
  local out="$1" prm="$2" sig="$3"
  shift 3
  "$@" "$fidus" "$prm" > "$out.stdout" 2> "$out.stderr" &
  local pid=$!
  for _ in $(seq 1 600); do
    [ -f "$work/$out/statistics.csv" ] && [ "$(rows "$work/$out/statistics.csv")" -ge 9 ] && break
    sleep 0.05
  done
  if [ "$#" -gt 0 ]; then
    # mpirun answers SIGTERM by killing the ranks: signal the ranks
    # themselves, as a batch system does.
    pkill "-$sig" -P "$pid"
  else
    kill "-$sig" "$pid"
  fi
  wait "$pid"
  echo $?
}

# --- 1. stopped by SIGTERM, resumed: same numbers, 1 and 2 ranks ---------
scene ref1 3 "" > ref1.prm
"$fidus" ref1.prm > /dev/null 2>&1 || fail "reference run (1 rank)"
scene stop1 3 "  set Checkpoint interval = 4" > stop1.prm
status=$(run_and_signal stop1 stop1.prm TERM)
if [ "$status" = 143 ] && grep -q "SIGTERM received: stopped after step" stop1.stderr \
   && [ "$(ls -d stop1/checkpoint-* | wc -l)" = 1 ] \
   && [ "$(rows stop1/statistics.csv)" -lt 31 ]; then
  pass "SIGTERM: exit 143, message, one checkpoint ($(ls -d stop1/checkpoint-*)) before the end"
else
  fail "SIGTERM on 1 rank: status $status, $(cat stop1.stderr)"
fi
# A run killed while writing a row leaves a partial last line: it must go.
printf '3' >> stop1/particles.csv
printf '3,0.3,0' >> stop1/statistics.csv
"$fidus" --resume stop1.prm > stop1.resume.stdout 2>&1 || fail "resume on 1 rank"
if same_output ref1 stop1 && no_duplicate_steps stop1 && [ "$(rows stop1/statistics.csv)" = 31 ]; then
  pass "1 rank: stopped and resumed run bit-identical to the uninterrupted one, every step once (partial last rows dropped)"
else
  fail "1 rank: resumed output differs from the uninterrupted run"
  explain_difference ref1 stop1
fi
if [ "$(grep -c DataSet stop1/particles.pvd)" = 7 ]; then
  pass "particles.pvd lists each of the 7 outputs once"
else
  fail "particles.pvd: $(grep -c DataSet stop1/particles.pvd) entries, expected 7"
fi

scene ref2 3 "" > ref2.prm
"${mpirun_cmd[@]}" "$fidus" ref2.prm > /dev/null 2>&1 || fail "reference run (2 ranks)"
scene stop2 3 "  set Checkpoint interval = 4" > stop2.prm
status=$(run_and_signal stop2 stop2.prm TERM "${mpirun_cmd[@]}")
if grep -q "SIGTERM received: stopped after step" stop2.stderr && [ "$(rows stop2/statistics.csv)" -lt 31 ]; then
  pass "SIGTERM to both ranks: stopped before the end with a checkpoint"
else
  fail "SIGTERM on 2 ranks: status $status, $(cat stop2.stderr)"
fi
"${mpirun_cmd[@]}" "$fidus" --resume stop2.prm > stop2.resume.stdout 2>&1 || fail "resume on 2 ranks"
# Resumed after a signal on 2 ranks, the run matched the uninterrupted one
# bit for bit on an idle machine, but not always under load (velocities
# 1e-15 apart from the first step after the checkpoint, seen in CI and
# reproduced with both cores busy); stops at a fixed step are bit-identical
# on 2 ranks, loaded or not (below). So the signal path is checked to
# round-off here, and bit-identity on 2 ranks with a deterministic stop
# (where the machine allows it: below).
largest=$(largest_change ref2 stop2 4 9)
if no_duplicate_steps stop2 && [ "$(rows stop2/statistics.csv)" = 31 ] \
   && awk -v m="$largest" 'BEGIN { exit !(m <= 1e-12) }'; then
  pass "2 ranks: stopped by SIGTERM and resumed: largest |dX|, |dU| over a = $largest <= 1e-12 against the uninterrupted run"
else
  fail "2 ranks: resumed after SIGTERM differs from the uninterrupted run by $largest a"
  explain_difference ref2 stop2
fi
scene later2 0.8 "  set Checkpoint interval = 4" > later2.prm
"${mpirun_cmd[@]}" "$fidus" later2.prm > /dev/null 2>&1 || fail "run to t = 0.8 (2 ranks)"
scene later2 3 "  set Checkpoint interval = 4" > later2_3.prm
"${mpirun_cmd[@]}" "$fidus" --resume later2_3.prm > /dev/null 2>&1 || fail "resume to t = 3 (2 ranks)"
# Bit-identical on an idle machine; under load a clean-clone CI run saw the
# two uninterrupted starts differ already in step 0 (the rows before any
# checkpoint), so what a 2-rank run repeats to the last bit is not a
# property of restart. Then the round-off bound of the signal path above.
largest=$(largest_change ref2 later2 4 9)
if same_output ref2 later2 && no_duplicate_steps later2; then
  pass "2 ranks: run to t = 0.8, resumed to t = 3: bit-identical to one run to t = 3"
elif no_duplicate_steps later2 && [ "$(rows later2/statistics.csv)" = 31 ] \
     && awk -v m="$largest" 'BEGIN { exit !(m <= 1e-12) }'; then
  pass "2 ranks: run to t = 0.8, resumed to t = 3: largest |dX|, |dU| over a = $largest <= 1e-12 against one run to t = 3 (not bit-identical: loaded machine)"
else
  fail "2 ranks: stopped at t = 0.8 and resumed: output differs from one run to t = 3 by $largest a"
  explain_difference ref2 later2
fi

# --- 2. resumed on another number of ranks: same to solver tolerance -----
scene other 3 "  set Checkpoint interval = 4" > other.prm
status=$(run_and_signal other other.prm INT)
"${mpirun_cmd[@]}" "$fidus" --resume other.prm > other.resume.stdout 2>&1 || fail "resume 1 -> 2 ranks"
largest=$(largest_change ref1 other 4 5)
if [ "$status" = 130 ] && no_duplicate_steps other && [ "$(rows other/statistics.csv)" = 31 ] \
   && awk -v m="$largest" 'BEGIN { exit !(m <= 1e-4) }'; then
  pass "SIGINT on 1 rank, resumed on 2: largest |dX|/a = $largest <= 1e-4 against the 1-rank run"
else
  fail "1 -> 2 ranks: status $status, largest |dX|/a = $largest"
fi

# --- 3. a later End time on resume ----------------------------------------
# Step 11 remeshes: the loaded mesh must give the numbering of the original.
scene later 1.1 "  set Checkpoint interval = 5" > later.prm
"$fidus" later.prm > /dev/null 2>&1 || fail "run to t = 1.1"
scene later 3 "  set Checkpoint interval = 5" > later3.prm
"$fidus" --resume later3.prm > /dev/null 2>&1 || fail "resume to t = 3"
if same_output ref1 later && no_duplicate_steps later; then
  pass "run to t = 1.1, resumed to t = 3: bit-identical to one run to t = 3"
else
  fail "later End time: output differs from one run to t = 3"
fi

# --- 3b. the same with the trapezoidal scheme ------------------------------
# Its passes solve the fluid within the step and their last solve stands for
# the one after the move: the checkpoint must hold that solve's mesh and
# multiplier, and nothing more.
trapezoidal="subsection Time stepping
  set Scheme = trapezoidal
end"
scene trap_ref 3 "" "$trapezoidal" > trap_ref.prm
"$fidus" trap_ref.prm > /dev/null 2>&1 || fail "trapezoidal run to t = 3"
scene trap 1.1 "  set Checkpoint interval = 5" "$trapezoidal" > trap.prm
"$fidus" trap.prm > /dev/null 2>&1 || fail "trapezoidal run to t = 1.1"
scene trap 3 "  set Checkpoint interval = 5" "$trapezoidal" > trap3.prm
"$fidus" --resume trap3.prm > /dev/null 2>&1 || fail "trapezoidal resume to t = 3"
if same_output trap_ref trap && no_duplicate_steps trap; then
  pass "trapezoidal: run to t = 1.1, resumed to t = 3: bit-identical to one run to t = 3"
else
  fail "trapezoidal, later End time: output differs from one run to t = 3"
fi
if ! cmp -s <(cut -d, -f1-13 "$work/ref1/particles.csv") <(cut -d, -f1-13 "$work/trap_ref/particles.csv"); then
  pass "the trapezoidal run differs from the AB2 one (the scheme is in effect)"
else
  fail "Scheme = trapezoidal gave the AB2 positions"
fi

# --- 3c. a shear reversal that starts on resume ----------------------------
# Sheared at rate 1 to t = 1.1, resumed with 't < 1.1 ? 1 : -1': the
# checkpoint's velocities were solved at rate 1, the file now gives -1 at
# t = 1.1; they are rescaled (Stokes flow is linear in the rate), so the
# run continues as one that reversed at t = 1.1 without stopping (without
# the rescaling it makes one more step forward: 0.1 U off).
reversal() {
  printf 'subsection Domain\n  set Shear rate = %s\nend\n' "$1"
}
scene rev_ref 2 "" "$(reversal 't < 1.1 ? 1 : -1')" > rev_ref.prm
"$fidus" rev_ref.prm > /dev/null 2>&1 || fail "reversal run to t = 2"
scene rev 1.1 "  set Checkpoint interval = 5" "$(reversal 1)" > rev.prm
"$fidus" rev.prm > /dev/null 2>&1 || fail "run at rate 1 to t = 1.1"
scene rev 2 "  set Checkpoint interval = 5" "$(reversal 't < 1.1 ? 1 : -1')" > rev2.prm
"$fidus" --resume rev2.prm > /dev/null 2>&1 || fail "resume with the reversal to t = 2"
largest=$(largest_change rev_ref rev 4 9)
if no_duplicate_steps rev && [ "$(rows rev/statistics.csv)" = 21 ] \
   && awk -v m="$largest" 'BEGIN { exit !(m <= 1e-12) }'; then
  pass "reversal started on resume: largest |dX|, |dU| over a = $largest <= 1e-12 against the run that reversed without stopping"
else
  fail "reversal started on resume differs from the uninterrupted reversal by $largest a"
fi

# --- 4. bad restart input: one message, exit 1, nothing changed -----------
fingerprint() { find "$1" -type f | sort | xargs md5sum | md5sum; }
expect_refusal() {
  local name="$1" dir="$2" pattern="$3" prm="$4"
  local before
  before=$(fingerprint "$dir")
  "$fidus" --resume "$prm" > bad.stdout 2> bad.stderr
  local status=$?
  if [ $status = 1 ] && grep -q -- "$pattern" bad.stderr && [ "$(grep -c . bad.stderr)" = 1 ] \
     && [ "$before" = "$(fingerprint "$dir")" ]; then
    pass "refused: $name"
  else
    fail "$name: status $status, stderr: $(cat bad.stderr)"
  fi
}
expect_refusal "no checkpoint" ref1 "holds no checkpoint" ref1.prm
scene stop1 3 "" "subsection Domain
  set Lower left = 0, 0, 0
  set Upper right = 1, 1, 1
end" | sed 's/set Dimension = 2/set Dimension = 3/; s/0.451, 0.51;/0.451, 0.51, 0.5;/; s/0.549, 0.49$/0.549, 0.49, 0.5/' > dim3.prm
expect_refusal "another dimension" stop1 "entry 'Dimension' is 3, but the checkpoint" dim3.prm
scene stop1 3 "" | sed 's/0.549, 0.49$/0.549, 0.49; 0.2, 0.2/' > three.prm
expect_refusal "another particle count" stop1 "entry 'Particles/Positions' is 3 particles" three.prm
scene stop1 3 "" "subsection Domain
  set Upper right = 2, 1
end" > box.prm
expect_refusal "another box" stop1 "entry 'Domain/Upper right' is 2,1" box.prm
scene stop1 3 "" "subsection Fluid
  set Model = undisturbed shear
end" > fluid.prm
expect_refusal "another fluid model" stop1 "entry 'Fluid/Model' is 'undisturbed shear'" fluid.prm
scene rest 0.5 "  set Checkpoint interval = 5" "$(reversal 0)" > rest.prm
"$fidus" rest.prm > /dev/null 2>&1 || fail "run at rest to t = 0.5"
scene rest 1 "" "$(reversal 1)" > rest1.prm
expect_refusal "a rate at the checkpoint's time where its velocities were solved at rate 0" rest \
  "entry 'Domain/Shear rate' gives 1 at t = 0.5, where the checkpoint's velocities were solved at the rate 0; allowed: the checkpoint's rate" rest1.prm
cp -r stop1 cut_state && scene cut_state 3 "" > cut_state.prm
state_file=$(ls -d cut_state/checkpoint-*)/state.bin
truncate -s -10 "$state_file"
expect_refusal "truncated state file" cut_state "state.bin' cannot be used: .*truncated" cut_state.prm
cp -r stop1 cut_mesh && scene cut_mesh 3 "" > cut_mesh.prm
mesh_file=$(ls -d cut_mesh/checkpoint-*)/mesh_fixed.data
truncate -s -100 "$mesh_file"
expect_refusal "truncated mesh file" cut_mesh "mesh_fixed.data' has .* bytes, but was written with" cut_mesh.prm

# A new run in the same Output directory removes the old run's checkpoint,
# so that '--resume' cannot continue the old run into the new files.
scene stop1 0.2 "  set Checkpoint interval = 4" > fresh.prm
"$fidus" fresh.prm > /dev/null 2>&1 || fail "fresh run in an old Output directory"
if [ "$(ls -d stop1/checkpoint-* | xargs -n1 basename | tr '\n' ' ')" = "checkpoint-000002 " ]; then
  pass "a new run replaces the old run's checkpoints (only checkpoint-000002 left)"
else
  fail "old checkpoints left: $(ls -d stop1/checkpoint-*)"
fi

echo "restart tests: $passes passed, $failures failed"
[ $failures -eq 0 ]
