#!/usr/bin/env bash
# FGMRES iterations of the cut finite element's iterative solver
# (CutSaddlePointSolver) against the mesh level and the gap, on fixed
# configurations (one rank; prints markdown tables; not a test):
#   2D: two discs a = 0.1 held on the compressional axis of the shear,
#       levels LEVELS_2D at gaps GAPS_2D (in a), one gap cell;
#   3D: one sphere a = 0.2 off the centre (the exact inclusion), levels
#       LEVELS_SPHERE, uniform mesh;
#   3D: two spheres a = 0.15 held on the compressional axis, level 3, gaps
#       GAPS_3D, one gap cell.
# Usage: contrib/benchmarks/cut_iterations.sh [2d] [sphere] [pair3d]
#   (default: all three)
# Env: FIDUS_CUT_INCLUSION (the binary; default: built with
#   contrib/build.sh fidus_cut_inclusion), ITERATIVE_TOLERANCE (default
#   the solver's, 1e-10), LEVELS_2D ("4 5 6"), GAPS_2D ("0.5 0.1 0.02 0.005
#   0.001"), LEVELS_SPHERE ("3 4"), GAPS_3D ("0.5 0.1 0.02"),
#   GAP_LAPLACIAN (the thin gaps' pressure Laplacian's weight; 0 for the
#   pressure mass alone), GAP_THRESHOLD (its region, in reduced radii),
#   PAIR_ANGLE (the held pairs' line of centres, degrees below the x axis;
#   default 45), NITSCHE (the Nitsche parameter; default the solver's,
#   100), SMOOTHER_DEGREE (the velocity multigrid's products per
#   smoothing; default 2), SEPARATE_COMPONENTS (0: the multigrid's levels
#   from the full velocity block, 1: from its components separated;
#   default: separated in 3D, full in 2D),
#   DEAL_II_NUM_THREADS (the binary takes the machine's cores as threads,
#   as fidus's cut element does on its one rank; 1 for a single thread).
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
bin="${FIDUS_CUT_INCLUSION:-}"
if [ -z "$bin" ]; then
  "$top/contrib/build.sh" fidus_cut_inclusion >/dev/null
  bin="$top/build-release/fidus_cut_inclusion"
fi
export LINEAR_SOLVER=iterative GAP_CELLS=1
parts="${*:-2d sphere pair3d}"
for part in $parts; do
  case "$part" in
    2d)
      echo "2D held pair (a = 0.1):"
      "$bin" held 0.1 "${LEVELS_2D:-4 5 6}" \
        "${GAPS_2D:-0.5 0.1 0.02 0.005 0.001}" 0 | cut -d'|' -f2,3,5,6,9,10,11
      ;;
    sphere)
      echo "3D sphere (a = 0.2, exact inclusion):"
      echo "| level | max omega error | unknowns | wall s | FGMRES |"
      echo "|---|---|---|---|---|"
      "$bin" 3 0.2 "${LEVELS_SPHERE:-3 4}" 1 0 | tail -n +3 |
        cut -d'|' -f1,2,4,10,12,14,16
      ;;
    pair3d)
      echo "3D held pair (a = 0.15, level 3):"
      "$bin" held3d 0.15 3 "${GAPS_3D:-0.5 0.1 0.02}" 0 | cut -d'|' -f2,3,4,7,8,9,11
      ;;
    *)
      echo "unknown part '$part' (allowed: 2d, sphere, pair3d)" >&2
      exit 2
      ;;
  esac
done
