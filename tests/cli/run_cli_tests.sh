#!/usr/bin/env bash
# Command-line behaviour of fidus: every bad input gets one clear message that
# names the entry and what is allowed, a non-zero exit status, and nothing is
# written; repeated warnings are written once (rank 0), ten in full, then
# summarised. Usage: run_cli_tests.sh path/to/fidus path/to/this/folder
set -u
fidus="$1"
here="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$work"
failures=0
passes=0

base() {
  cat <<EOF2
set Dimension = 2
set Output directory = $work/out
subsection Particles
  set Radius = 0.05
  set Positions = 0.451, 0.51; 0.549, 0.49
end
subsection Time stepping
  set End time = 0
end
EOF2
}

# expect_error NAME PATTERN PRM-TEXT: the run must fail, print PATTERN on
# stderr, and write no output directory.
expect_error() {
  local name="$1" pattern="$2" text="$3"
  rm -rf "$work/out"
  printf '%s\n' "$text" > case.prm
  "$fidus" case.prm > stdout.txt 2> stderr.txt
  local status=$?
  if [ $status -ne 0 ] && grep -q -- "$pattern" stderr.txt && [ ! -e "$work/out" ] \
     && [ "$(grep -c . stderr.txt)" -le 2 ]; then
    passes=$((passes + 1))
  else
    failures=$((failures + 1))
    echo "FAILED: $name (status $status)"; cat stderr.txt
  fi
}

cut_fluid() { printf 'subsection Fluid\n  set Model = cut finite element\n%s\nend\n' "$1"; }
expect_error "cut element in the cavity" "Domain/Boundary condition' is not 'linear shear' or 'sliding walls' with 'Fluid/Model = cut finite element'; allowed: 'linear shear' or 'sliding walls'" \
  "$(base; cut_fluid ''; printf 'subsection Domain\n  set Boundary condition = cavity\nend\n')"
expect_error "cut element minimum gap 0" "Fluid/Cut minimum gap' has the value '0'; allowed: auto or a value > 0" \
  "$(base; cut_fluid '  set Cut minimum gap = 0')"
expect_error "cut element Nitsche parameter 0" "Fluid/Cut Nitsche parameter' has the value 0; allowed: a value > 0" \
  "$(base; cut_fluid '  set Cut Nitsche parameter = 0')"
expect_error "cut element started from zero with the direct solver" "Fluid/Cut initial guess' has the value 'zero' with the direct solver ('Fluid/Cut linear solver = auto' in 2D), which does not read it; allowed: its default, or 'Fluid/Cut linear solver = iterative'" \
  "$(base; cut_fluid '  set Cut initial guess = zero')"
expect_error "cut element tolerance 1" "Fluid/Cut linear tolerance' has the value 1; allowed: a value in (0, 1)" \
  "$(base; cut_fluid '  set Cut linear solver = iterative
  set Cut linear tolerance = 1')"
expect_error "cut element tolerance with the direct solver" "Fluid/Cut linear tolerance' has the value 1e-06 with the direct solver ('Fluid/Cut linear solver = direct' in 2D), which does not read it; allowed: its default, or 'Fluid/Cut linear solver = iterative'" \
  "$(base; cut_fluid '  set Cut linear solver = direct
  set Cut linear tolerance = 1e-6')"
expect_error "cut entry with the fictitious domain" "Fluid/Cut velocity ghost penalty' is set with 'Fluid/Model = fictitious domain', which does not read it; allowed: its default, or 'Fluid/Model = cut finite element'" \
  "$(base; printf 'subsection Fluid\n  set Cut velocity ghost penalty = 1e-2\nend\n')"
expect_error "cut element with a lubrication range" "Fluid/Lubrication range' is set with 'Fluid/Model = cut finite element' and 'Fluid/Lubrication correction'; allowed: auto" \
  "$(base; cut_fluid '  set Lubrication correction = true
  set Lubrication range = 0.5')"
expect_error "cut element with the lubrication's step mean" "Fluid/Lubrication gap in time' is not 'start' with 'Fluid/Model = cut finite element'.*allowed: start" \
  "$(base; cut_fluid '  set Lubrication correction = true
  set Lubrication gap in time = step mean')"
expect_error "lubrication gap in time without the correction" "Fluid/Lubrication gap in time' is set without 'Fluid/Lubrication correction = true'.*allowed: start, or the correction on" \
  "$(base; printf 'subsection Fluid\n  set Lubrication gap in time = closing mean\nend\n')"
expect_error "cut element with the correction after the solve" "Fluid/Lubrication coupling' has the value 'after the solve' with 'Fluid/Model = cut finite element'.*allowed: auto, with the flow" \
  "$(base; cut_fluid '  set Lubrication correction = true
  set Lubrication coupling = after the solve')"
expect_error "lubrication coupling without the correction" "Fluid/Lubrication coupling' is set without 'Fluid/Lubrication correction = true'.*allowed: auto, or the correction on" \
  "$(base; printf 'subsection Fluid\n  set Lubrication coupling = with the flow\nend\n')"
expect_error "lubrication coupled with no flow" "Fluid/Lubrication coupling' has the value 'with the flow' with 'Fluid/Model = undisturbed shear', which solves no flow; allowed: auto, after the solve" \
  "$(base; printf 'subsection Fluid\n  set Model = undisturbed shear\n  set Lubrication correction = true\n  set Lubrication coupling = with the flow\nend\n')"
expect_error "coupling tolerance that nothing uses" "Fluid/Lubrication coupling tolerance' has the value 0.01, which only 'Fluid/Model = fictitious domain' with 'Fluid/Lubrication coupling = with the flow' uses" \
  "$(base; printf 'subsection Fluid\n  set Lubrication correction = true\n  set Lubrication coupling = after the solve\n  set Lubrication coupling tolerance = 1e-2\nend\n')"
expect_error "coupled lubrication with the step mean" "Fluid/Lubrication gap in time' is not 'start' with 'Fluid/Lubrication coupling = with the flow'.*allowed: start" \
  "$(base; printf 'subsection Fluid\n  set Lubrication correction = true\n  set Lubrication coupling = with the flow\n  set Lubrication gap in time = step mean\nend\n')"
expect_error "cut element lubricated below the roughness" "Fluid/Cut minimum gap' has the value 0.001 with 'Fluid/Lubrication correction' and 'Contact/Roughness = 0.005'; allowed: a gap above the roughness" \
  "$(base; cut_fluid '  set Lubrication correction = true
  set Cut minimum gap = 1e-3')"
expect_error "overlapping particles" "particles 0 and 1 overlap" \
  "$(base | sed 's/0.451, 0.51; 0.549, 0.49/0.45, 0.5; 0.5, 0.5/')"
expect_error "overlap across a periodic face" "particles 0 and 1 overlap by 0.06.*(nearest periodic image" \
  "$(base | sed 's/0.451, 0.51; 0.549, 0.49/0.02, 0.5; 0.98, 0.5/'; printf 'subsection Domain\n  set Boundary condition = sliding walls\nend\n')"
expect_error "particle outside the box" "cuts or lies outside the box face x = 1" \
  "$(base | sed 's/0.549, 0.49/0.98, 0.49/')"
expect_error "radius <= 0" "Particles/Radius.*allowed: a radius > 0" \
  "$(base | sed 's/Radius = 0.05/Radius = -0.05/')"
expect_error "GMG with Velocity degree 4" "Preconditioner' has the value 'GMG' with 'Fluid/Velocity degree' = 4; allowed: GMG with Velocity degree 2 or 3" \
  "$(base; printf 'subsection Fluid\n  set Velocity degree = 4\n  subsection Linear solver\n    set Preconditioner = GMG\n  end\nend\n')"
expect_error "rigidity tolerance out of range" "Fluid/Rigidity tolerance' has the value '2'; allowed: auto or a number in (0, 1)" \
  "$(base; printf 'subsection Fluid\n  set Rigidity tolerance = 2\nend\n')"
expect_error "rigidity tolerance not a number" "Fluid/Rigidity tolerance' has the value 'tight'; allowed: auto or a number in (0, 1)" \
  "$(base; printf 'subsection Fluid\n  set Rigidity tolerance = tight\nend\n')"
expect_error "unknown time scheme" "value RK4 for the entry named Scheme does not match.*AB2|trapezoidal" \
  "$(base; printf 'subsection Time stepping\n  set Scheme = RK4\nend\n')"
expect_error "no trapezoidal pass" "value 0 for the entry named Trapezoidal iterations does not match.*1...20" \
  "$(base; printf 'subsection Time stepping\n  set Trapezoidal iterations = 0\nend\n')"
expect_error "unknown preconditioner" "Preconditioner" \
  "$(base; printf 'subsection Fluid\n  subsection Linear solver\n    set Preconditioner = ILU\n  end\nend\n')"
expect_error "GMRES restart 0" "value 0 for the entry named GMRES restart does not match.*1...2147483647" \
  "$(base; printf 'subsection Fluid\n  subsection Linear solver\n    set GMRES restart = 0\n  end\nend\n')"
expect_error "solid retraction leaves no solid" "Fluid/Solid retraction' has the value 0.8, which leaves particle 0 (radius 0.01) no solid.*allowed: values below" \
  "$(base | sed 's/Radius = 0.05/Radius = 0.01/'; printf 'subsection Fluid\n  set Solid retraction = 0.8\nend\nsubsection Mesh refinement\n  set Maximum level = 6\nend\n')"
expect_error "external force count" "Particles/External force' has 3 forces for 2 particles; allowed: one force for all particles or one per particle" \
  "$(base | sed 's/  set Radius = 0.05/  set Radius = 0.05\n  set External force = 1, 0; 0, 1; 1, 1/')"
expect_error "external force coordinates" "Particles/External force' has the value '1, 0, 0' with 3 coordinates; allowed: exactly 2" \
  "$(base | sed 's/  set Radius = 0.05/  set Radius = 0.05\n  set External force = 1, 0, 0/')"
expect_error "external force on the exact inclusion" "Particles/External force' is set with 'Domain/Boundary condition = exact rigid inclusion'; allowed: external forces with any other boundary condition" \
  "$(base; printf 'subsection Particles\n  set Positions = 0.5, 0.5\n  set External force = 0, -1\nend\nsubsection Domain\n  set Boundary condition = exact rigid inclusion\nend\n')"
expect_error "lubrication range 0" "Fluid/Lubrication range' has the value 0.*allowed: a gap in finest cell sizes > 0" \
  "$(base; printf 'subsection Fluid\n  set Lubrication correction = true\n  set Lubrication range = 0\nend\n')"
expect_error "lubrication wall range 0" "Fluid/Lubrication range' has the value 0.*allowed: a gap in finest cell sizes > 0" \
  "$(base; printf 'subsection Fluid\n  set Lubrication correction = true\n  set Lubrication range = 0.3, 0\nend\n')"
expect_error "lubrication range three numbers" "Fluid/Lubrication range' has the value '1, 2, 3'; allowed: auto, one gap" \
  "$(base; printf 'subsection Fluid\n  set Lubrication correction = true\n  set Lubrication range = 1, 2, 3\nend\n')"
expect_error "lubrication flow range 0" "Fluid/Lubrication flow range' has the value 0.*allowed: a gap in finest cell sizes > 0" \
  "$(base; printf 'subsection Fluid\n  set Lubrication correction = true\n  set Lubrication flow range = 0\nend\n')"
expect_error "lubrication flow edge below the flow range" "Fluid/Lubrication flow edge' has the value 0.3, below 'Fluid/Lubrication flow range' = 0.5; allowed: a gap in finest cell sizes >= the flow range" \
  "$(base; printf 'subsection Fluid\n  set Lubrication correction = true\n  set Lubrication flow range = 0.5\n  set Lubrication flow edge = 0.3\nend\n')"
expect_error "lubrication wall tangential range 0" "Fluid/Lubrication tangential range' has the value 0.*allowed: a gap in finest cell sizes > 0" \
  "$(base; printf 'subsection Fluid\n  set Lubrication correction = true\n  set Lubrication tangential range = 1, 0\nend\n')"
expect_error "negative roughness" "Roughness" \
  "$(base; printf 'subsection Contact\n  set Roughness = -1\nend\n')"
expect_error "negative drag coefficient" "Drag coefficient" \
  "$(base; printf 'subsection Contact\n  set Drag coefficient = -1\nend\n')"
expect_error "negative friction coefficient" "Friction coefficient" \
  "$(base; printf 'subsection Contact\n  set Friction coefficient = -0.5\nend\n')"
expect_error "friction without contacts" "entry 'Contact/Friction coefficient' has the value 0.500000 with 'Contact/Model = none', which has no contacts; allowed: 0, or the model 'inelastic' or 'gluey'" \
  "$(base; printf 'subsection Contact\n  set Model = none\n  set Friction coefficient = 0.5\nend\n')"
expect_error "rough contact without contacts" "entry 'Contact/Rough contact' is true with 'Contact/Model = none', which has no contacts; allowed: false, or the model 'inelastic' or 'gluey'" \
  "$(base; printf 'subsection Contact\n  set Model = none\n  set Rough contact = true\nend\n')"
expect_error "contact iterations without contacts" "entry 'Contact/Maximum iterations' has the value 50 with 'Contact/Model = none', which projects nothing; allowed: the default 100000, or the model 'inelastic' or 'gluey'" \
  "$(base; printf 'subsection Contact\n  set Model = none\n  set Maximum iterations = 50\nend\n')"
expect_error "no contact iterations" "Maximum iterations" \
  "$(base; printf 'subsection Contact\n  set Maximum iterations = 0\nend\n')"
expect_error "penalty factor <= 1" "Penalty factor.*allowed: a value > 1" \
  "$(base; printf 'subsection Fluid\n  set Penalty factor = 1\nend\n')"
expect_error "wrong number of coordinates" "Particles/Positions.*allowed: exactly 2 coordinates" \
  "$(base | sed 's/0.549, 0.49/0.549, 0.49, 0.5/')"
expect_error "unreadable positions file" "Positions file.*cannot be read" \
  "$(base | sed 's/set Positions = .*/set Positions file = missing.txt/')"
expect_error "unknown entry" "No entry with name <Colour>" \
  "$(base; printf 'set Colour = red\n')"
expect_error "value out of range" "Dimension" \
  "$(base | sed 's/Dimension = 2/Dimension = 4/')"
expect_error "bad shear rate" "Shear rate.*not a valid expression" \
  "$(base; printf 'subsection Domain\n  set Shear rate = t <\nend\n')"
expect_error "exact inclusion with two particles" "exactly one particle" \
  "$(base; printf 'subsection Domain\n  set Boundary condition = exact rigid inclusion\nend\n')"
expect_error "generator and positions both set" "entries 'Particles/Generator' and 'Particles/Positions' are both set" \
  "$(base; printf 'subsection Particles\n  subsection Generator\n    set Fraction = 0.3\n  end\nend\n')"
expect_error "generator fraction beyond the densest packing" "entry 'Particles/Generator'.*0.95" \
  "$(base | sed 's/set Positions = .*//'; printf 'subsection Particles\n  subsection Generator\n    set Fraction = 0.95\n  end\nend\n')"

# The generator: a bidisperse 2D suspension at area fraction 0.6 between
# sliding walls passes the scene check (inside the box, no overlap with the
# nearest periodic image), and the same seed gives the same particles.
generator_prm() {
  base | sed 's/set Positions = .*//'
  printf 'subsection Domain\n  set Boundary condition = sliding walls\nend\n'
  printf 'subsection Particles\n  subsection Generator\n    set Fraction = 0.6\n    set Radii = 0.02, 0.028\n    set Seed = %s\n  end\nend\n' "$1"
}
generator_prm 3 > gen.prm
"$fidus" --validate gen.prm > stdout.txt 2> stderr.txt
status=$?
count=$(sed -n 's/.*(2D, \([0-9]*\) particles).*/\1/p' stdout.txt)
# 0.6 / (pi (0.02^2 + 0.028^2) / 2) = 322.5 discs in the unit box.
if [ $status -eq 0 ] && [ -n "$count" ] && [ "$count" -ge 320 ] && [ "$count" -le 325 ]; then
  passes=$((passes + 1))
else
  failures=$((failures + 1)); echo "FAILED: generator at area fraction 0.6 (status $status)"; cat stdout.txt stderr.txt
fi
# One particle is named in the singular.
base | sed 's/set Positions = .*/set Positions = 0.5, 0.5/' > one.prm
if "$fidus" --validate one.prm | grep -q "(2D, 1 particle)$"; then
  passes=$((passes + 1))
else
  failures=$((failures + 1)); echo "FAILED: --validate names one particle"
fi
rm -rf "$work/out"
{ generator_prm 3 | sed 's/End time = 0/End time = 0/'; printf 'subsection Fluid\n  set Model = undisturbed shear\nend\n'; } > gen_a.prm
"$fidus" gen_a.prm > /dev/null 2>&1 && cp out/particles.csv gen_a.csv
rm -rf "$work/out"
"$fidus" gen_a.prm > /dev/null 2>&1 && cp out/particles.csv gen_b.csv
if [ -f gen_a.csv ] && cmp -s gen_a.csv gen_b.csv && [ "$(grep -c . gen_a.csv)" -eq $((count + 1)) ]; then
  passes=$((passes + 1))
else
  failures=$((failures + 1)); echo "FAILED: generator not reproducible or count differs"
fi

# A missing file.
"$fidus" does_not_exist.prm > /dev/null 2> stderr.txt
if [ $? -ne 0 ] && grep -q "cannot read the parameter file" stderr.txt; then
  passes=$((passes + 1)); else failures=$((failures + 1)); echo "FAILED: missing file"; fi

# --validate accepts a good file and writes nothing; rejects a bad one.
base > good.prm
rm -rf "$work/out"
if "$fidus" --validate good.prm > /dev/null 2>&1 && [ ! -e "$work/out" ]; then
  passes=$((passes + 1)); else failures=$((failures + 1)); echo "FAILED: --validate good"; fi
base | sed 's/Radius = 0.05/Radius = 0/' > bad.prm
if ! "$fidus" --validate bad.prm > /dev/null 2>&1; then
  passes=$((passes + 1)); else failures=$((failures + 1)); echo "FAILED: --validate bad"; fi

# Every shipped scene is a valid parameter file (--validate reads it all,
# generates or reads its particles and checks them, and writes nothing).
for shipped in "$here"/../../prm/*.prm; do
  if (cd "$work" && "$fidus" --validate "$shipped" > /dev/null 2> stderr.txt); then
    passes=$((passes + 1))
  else
    failures=$((failures + 1)); echo "FAILED: --validate $(basename "$shipped")"; cat "$work/stderr.txt"
  fi
done

# --print-parameters documents every fixed entry of interface.md.
"$fidus" --print-parameters > params.txt
ok=1
for entry in "Dimension" "Output directory" "Lower left" "Upper right" \
  "Boundary condition" "Shear rate" "Penalty factor" "Velocity degree" \
  "Rigidity tolerance" "Maximum Uzawa iterations" "Radius" "Positions file" \
  "Walls" "End time" "Time step" "Adaptive time step" \
  "Initial global refinement" "Minimum level" "Maximum level" \
  "Interface band" "Field output interval" "Verbosity"; do
  grep -q "set $entry " params.txt || { ok=0; echo "FAILED: --print-parameters lacks '$entry'"; }
done
[ $ok = 1 ] && passes=$((passes + 1)) || failures=$((failures + 1))

# A good run writes used_parameters.prm and both CSV files with headers
# (free-draining particles: no mesh, so that it takes no time).
{ base; printf 'subsection Fluid\n  set Model = undisturbed shear\nend\n'; } > run.prm
"$fidus" run.prm > run_stdout.txt 2>&1
if [ -f out/used_parameters.prm ] && head -1 out/particles.csv | grep -q "^step,time,id,x,y,z,ux,uy,uz,omega_x,omega_y,omega_z,radius,stresslet_xx,stresslet_xy,stresslet_xz,stresslet_yy,stresslet_yz,stresslet_zz,contact_stresslet_xx,contact_stresslet_xy,contact_stresslet_xz,contact_stresslet_yy,contact_stresslet_yz,contact_stresslet_zz,lubrication_stresslet_xx,lubrication_stresslet_xy,lubrication_stresslet_xz,lubrication_stresslet_yy,lubrication_stresslet_yz,lubrication_stresslet_zz,moved_ux,moved_uy,moved_uz,moved_omega_x,moved_omega_y,moved_omega_z,orientation_w,orientation_x,orientation_y,orientation_z$" \
   && head -1 out/statistics.csv | grep -q "^step,time,dt,cells,dofs,uzawa_iterations,linear_iterations,rigidity_residual,min_gap,active_contacts,glued_contacts,wall_seconds,.*,shear_stress,relative_viscosity,normal_stress_difference_1,normal_stress_difference_2,particle_pressure,contact_relative_viscosity,.*,lubrication_relative_viscosity,lubrication_particle_pressure,lubrication_pairs,rigid_velocity_change,particle_rigidity_residual,sliding_contacts$"; then
  passes=$((passes + 1)); else failures=$((failures + 1)); echo "FAILED: output files of a good run"; fi

# The progress line of a sheared box gives the step's relative viscosity,
# the relative_viscosity of statistics.csv to its three decimals.
column=$(head -1 out/statistics.csv | tr ',' '\n' | grep -n -x relative_viscosity | cut -d: -f1)
expected=$(tail -1 out/statistics.csv | cut -d, -f"$column" | xargs printf '%.3f')
shown=$(grep -o 'eta_r [-0-9.]*' run_stdout.txt | tail -1 | cut -d' ' -f2)
if [ -n "$shown" ] && [ "$shown" = "$expected" ]; then
  passes=$((passes + 1)); else failures=$((failures + 1)); echo "FAILED: eta_r on the progress line ('$shown', statistics.csv: '$expected')"; fi

# A particle carried out through an outflow face stops the run with a
# diagnostic (exit status 2), after the rows of the steps before.
{ base | sed 's/0.451, 0.51; 0.549, 0.49/0.9, 0.9/' | sed 's/End time = 0/End time = 2/';
  printf 'subsection Fluid\n  set Model = undisturbed shear\nend\n'; } > leave.prm
rm -rf "$work/out"
"$fidus" leave.prm > /dev/null 2> stderr.txt
status=$?
if [ $status -eq 2 ] && grep -q "particle 0 reached the box face x = 1.*in/outflow face" stderr.txt \
   && [ "$(tail -1 out/statistics.csv | cut -d, -f1)" -ge 10 ]; then
  passes=$((passes + 1)); else failures=$((failures + 1)); echo "FAILED: leaving the box (status $status)"; cat stderr.txt; fi

# Repeated warnings on 2 MPI ranks: one copy only (rank 0); the first ten of
# a kind in full, each naming its step, then one summary line whose count
# is the number of steps and whose worst value and step are those of the
# largest rigidity residual in statistics.csv.
{ base | sed 's/End time = 0/End time = 1.1\n  set Time step = 0.1/';
  printf 'subsection Fluid\n  set Rigidity tolerance = 1e-9\n  set Rigidity measure = box\n  set Maximum Uzawa iterations = 1\nend\n';
  printf 'subsection Mesh refinement\n  set Maximum level = 5\nend\n'; } > warn.prm
rm -rf "$work/out"
OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 \
  mpirun -np 2 "$fidus" warn.prm > /dev/null 2> stderr.txt
status=$?
worst=$(awk -F, 'NR > 1 && (NR == 2 || $8 > w) { w = $8; s = $1 } END { printf "%.6g at step %d", w, s }' out/statistics.csv)
steps=$(($(grep -c . out/statistics.csv) - 1))
full_ok=1
for k in 0 1 2 3 4 5 6 7 8 9; do
  [ "$(grep -c "^fidus: warning: step $k, t = .*the Uzawa loop stopped after 1 iteration " stderr.txt)" -eq 1 ] || full_ok=0
done
if [ $status -eq 0 ] && [ $steps -eq 12 ] && [ $full_ok = 1 ] \
   && [ "$(grep -c "^fidus: warning:" stderr.txt)" -eq 11 ] \
   && grep -q "^fidus: warning: step 9, .*\[10 such warnings (rigidity not reached); further ones are counted" stderr.txt \
   && grep -q "^fidus: warning: 12 warnings (rigidity not reached) in this run, 10 of them written above; the largest value was $worst$" stderr.txt; then
  passes=$((passes + 1)); else failures=$((failures + 1)); echo "FAILED: repeated warnings on 2 ranks (status $status, steps $steps, expected worst $worst)"; cat stderr.txt; fi

# The cut element estimates each solve's memory from its unknowns before
# building its sparsity pattern: under a budget smaller than what the process already
# holds, the run stops at its first solve with one message naming the
# unknowns, the estimate (4 KB per unknown with the 2D direct solver) and
# the entries that would make it fit.
{ base; printf 'subsection Fluid\n  set Model = cut finite element\n  subsection Linear solver\n    set Memory per rank = 0.001\n  end\nend\n'; } > cut_memory.prm
rm -rf "$work/out"
"$fidus" cut_memory.prm > /dev/null 2> stderr.txt
status=$?
unknowns=$(grep -o 'the cut mesh has [0-9]* unknowns' stderr.txt | grep -o '[0-9]*')
if [ $status -ne 0 ] && [ "$(grep -c '^fidus:' stderr.txt)" -eq 1 ] && [ -n "$unknowns" ] \
   && grep -q "its direct solve needs about .* (4 KB per unknown), but this rank has 0 B left ('Fluid/Linear solver/Memory per rank' = .*): raise 'Fluid/Cut minimum gap', lower 'Fluid/Cut gap cells' or 'Mesh refinement/Maximum level'" stderr.txt; then
  passes=$((passes + 1)); else failures=$((failures + 1)); echo "FAILED: cut element over its memory budget (status $status)"; cat stderr.txt; fi

# The iterative solver's peak follows the matrix's entries, which a dense
# suspension has 2-3 times more of per unknown than one sphere: 37 spheres
# at phi = 0.3 (137 000 unknowns, 81 million entries, a 1.8 GB peak) under
# a 1.5 GB budget pass the first estimate (6 KB per unknown) and stop, with
# one message, at the second (20 B per entry), after the pattern and
# before the system is built. (Without the second, such a run was killed
# by the operating system.)
cat > cut_dense_memory.prm <<EOF2
set Dimension = 3
set Output directory = $work/out
subsection Domain
  set Lower left = 0, 0, 0
  set Upper right = 1, 1, 1
  set Boundary condition = sliding walls
end
subsection Fluid
  set Model = cut finite element
  set Cut minimum gap = 0.4
  set Cut gap cells = 0
  set Lubrication correction = true
  subsection Linear solver
    set Memory per rank = 1.5
  end
end
subsection Particles
  subsection Generator
    set Fraction = 0.3
    set Radii = 0.125
    set Minimum separation = 0.01
  end
end
subsection Time stepping
  set End time = 0
end
subsection Mesh refinement
  set Initial global refinement = 4
  set Minimum level = 4
  set Maximum level = 4
end
EOF2
rm -rf "$work/out"
"$fidus" cut_dense_memory.prm > /dev/null 2> stderr.txt
status=$?
if [ $status -ne 0 ] && [ "$(grep -c '^fidus:' stderr.txt)" -eq 1 ] \
   && grep -q "the cut mesh has [0-9]* unknowns and [0-9]* matrix entries; its iterative solve needs about .* (20 B per entry), but this rank has .* left ('Fluid/Linear solver/Memory per rank' = 1.5 GB)" stderr.txt; then
  passes=$((passes + 1)); else failures=$((failures + 1)); echo "FAILED: dense 3D cut element over its memory budget (status $status)"; cat stderr.txt; fi

# A setting that another one switches off is said, not silent: the
# lubrication correction with rigid shared cells (a close pair is one rigid
# doublet, beyond the correction's range) runs with one warning naming both
# entries; with 'Shared cells = auto' it runs without it.
for shared in rigid auto; do
  { base; printf 'subsection Fluid\n  set Lubrication correction = true\n  set Shared cells = %s\nend\nsubsection Mesh refinement\n  set Maximum level = 5\nend\nsubsection Output\n  set Verbosity = quiet\nend\n' "$shared"; } > lub_$shared.prm
  "$fidus" lub_$shared.prm > /dev/null 2> lub_$shared.stderr
  echo $? > lub_$shared.status
done
if [ "$(cat lub_rigid.status)" = 0 ] && [ "$(cat lub_auto.status)" = 0 ] \
   && grep -q "warning: 'Fluid/Lubrication correction' is true with 'Fluid/Shared cells = rigid'" lub_rigid.stderr \
   && ! grep -q "Shared cells = rigid" lub_auto.stderr; then
  passes=$((passes + 1)); else failures=$((failures + 1)); echo "FAILED: lubrication with rigid shared cells not warned"; cat lub_rigid.stderr; fi

echo "$passes passed, $failures failed"
[ $failures -eq 0 ]
