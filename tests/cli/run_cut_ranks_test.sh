#!/usr/bin/env bash
# The cut finite element on 1, 2 and 3 MPI ranks: every rank builds the
# whole cut mesh, the ranks assemble shares of the cells and faces and sum
# them, and MUMPS factorises over the ranks; the answers must agree to
# round-off (tests/cli/check_cut_ranks.py does the checks):
#  1. 2D, three discs between sliding walls (the walls' stress is summed
#     over the ranks' shares too), field output: particles.csv within 1e-9
#     of each column's largest value, statistics.csv's stresses within
#     1e-9, and the .pvtu's pieces, one per rank, together the one rank's
#     fields;
#  2. 2D, two discs in linear shear, one pushed by an external force (added
#     once, after the shares are summed): the same agreement, and the
#     pushed disc moves along the force;
#  3. 3D, two spheres in linear shear, the direct solver (set by hand,
#     where 'auto' would iterate to its tolerance): 1 against 2 ranks;
#  4. the same spheres with the iterative solver (the velocity block and
#     its multigrid split among the ranks) at the tolerance 1e-11: 2 and 3
#     ranks against 1 within 1e-8, and 1 rank against the direct solver
#     within 1e-7;
#     and between sliding walls (periodic faces, the walls' stress from
#     rows summed over the ranks' shares): 2 ranks against 1 within 1e-8;
#  5. 3D with 'auto' on 2 ranks of one machine (which iterates, where one
#     rank with the cores as threads is as fast) is warned about, once;
#     with 'direct' set, not;
#  6. the matrix entries fidus reports (verbose) are the whole system's on
#     2 ranks as on 1, between sliding walls with the iterative solver,
#     although each rank builds K's entries of its own rows only (and the
#     walls' rows whole).
# Usage: run_cut_ranks_test.sh path/to/fidus path/to/repo
. "$(dirname "${BASH_SOURCE[0]}")/driver_test_lib.sh" "$1" "$2"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1

scene() {  # scene NAME DIMENSION BOUNDARY RADIUS POSITIONS FORCE LEVELS
  local upper="1, 1" && [ "$2" = 3 ] && upper="1, 1, 1"
  local lower="0, 0" && [ "$2" = 3 ] && lower="0, 0, 0"
  cat <<PRM
set Dimension = $2
set Output directory = $work/$1
subsection Domain
  set Lower left = $lower
  set Upper right = $upper
  set Boundary condition = $3
end
subsection Fluid
  set Model = cut finite element
  set Cut minimum gap = 1e-3
end
subsection Particles
  set Radius = $4
  set Positions = $5
  set External force = $6
end
subsection Contact
  set Model = inelastic
end
subsection Time stepping
  set End time = 0.4
  set Time step = 0.2
end
subsection Mesh refinement
  set Initial global refinement = ${7%,*}
  set Minimum level = ${7%,*}
  set Maximum level = ${7#*,}
end
subsection Output
  set Field output interval = 1
  set Verbosity = quiet
end
PRM
}

run() {  # run NAME RANKS: fidus on NAME.prm into NAME-RANKS/
  sed "s|$work/$1\$|$work/$1-$2|" "$1.prm" > "$1-$2.prm"
  check "fidus runs $1.prm on $2 rank(s)" \
    mpirun -np "$2" "$fidus" "$1-$2.prm"
}

scene walls 2 "sliding walls" 0.06 "0.7, 0.8; 0.45, 0.5; 0.25, 0.3" "" 3,5 \
  > walls.prm
scene forced 2 "linear shear" 0.06 "0.35, 0.5; 0.65, 0.55" \
  "0.5, -1; 0, 0" 3,5 > forced.prm
scene spheres 3 "linear shear" 0.15 "0.3, 0.45, 0.5; 0.7, 0.55, 0.5" \
  "" 2,3 | sed 's/set Cut minimum gap = 1e-3/&\n  set Cut linear solver = direct/' \
  > spheres.prm
for ranks in 1 2 3; do
  run walls $ranks
  run forced $ranks
done
sed -e 's/set Cut linear solver = direct/set Cut linear solver = iterative\n  set Cut linear tolerance = 1e-11/' \
  -e "s|$work/spheres\$|$work/spheres_iterative|" spheres.prm \
  > spheres_iterative.prm
for ranks in 1 2; do
  run spheres $ranks
done
for ranks in 1 2 3; do
  run spheres_iterative $ranks
done
scene walls3d 3 "sliding walls" 0.15 "0.3, 0.45, 0.5; 0.7, 0.6, 0.5" "" 2,3 |
  sed -e 's/set Cut minimum gap = 1e-3/&\n  set Cut linear solver = iterative\n  set Cut linear tolerance = 1e-11/' \
      -e 's/End time = 0.4/End time = 0.2/' > walls3d.prm
for ranks in 1 2; do
  run walls3d $ranks
done
check "the ranks agree (check_cut_ranks.py)" \
  "$python" "$repo/tests/cli/check_cut_ranks.py" "$work"

# 5. 'auto' in 3D on more than one rank iterates, every rank holding the
#    whole system: said once. One step of one small sphere.
scene sphere 3 "linear shear" 0.15 "0.45, 0.55, 0.5" "" 2,3 |
  sed 's/End time = 0.4/End time = 0.2/' > sphere.prm
mpirun -np 2 "$fidus" sphere.prm > sphere-auto.log 2>&1
status=$?
check "3D 'auto' on 2 ranks runs" [ $status -eq 0 ]
check "and warns once that one rank would be faster" \
  [ "$(grep -c "warning: the cut element runs on 2 MPI ranks of one machine: its iterative solve splits" sphere-auto.log)" = 1 ]
sed 's/set Cut minimum gap = 1e-3/&\n  set Cut linear solver = direct/' \
  sphere.prm > sphere-direct.prm
mpirun -np 2 "$fidus" sphere-direct.prm > sphere-direct.log 2>&1
status=$?
check "3D 'direct' on 2 ranks runs" [ $status -eq 0 ]
check "and does not warn" \
  [ "$(grep -c "warning: the cut element runs on" sphere-direct.log)" = 0 ]

# 6. The entries reported, solve by solve, on 1 and 2 ranks.
for ranks in 1 2; do
  sed -e 's/set Verbosity = quiet/set Verbosity = verbose/' \
      -e "s|$work/walls3d\$|$work/entries-$ranks|" walls3d.prm > entries-$ranks.prm
  mpirun -np $ranks "$fidus" entries-$ranks.prm > entries-$ranks.log 2>&1
  grep -o '([0-9]* matrix entries)' entries-$ranks.log > entries-$ranks.txt
done
check "the whole system's entries on 2 ranks as on 1: $(head -1 entries-1.txt | tr -d '()')" \
  bash -c '[ -s entries-1.txt ] && cmp -s entries-1.txt entries-2.txt'

echo "$passes passed, $failures failed"
[ $failures -eq 0 ]
