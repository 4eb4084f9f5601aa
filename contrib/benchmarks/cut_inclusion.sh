#!/usr/bin/env bash
# The exact rigid inclusion solved with the cut finite element
# (Fidus::CutStokesInclusion, doc/cut_element.md "Fixed particles"): N
# seeded positions of a particle of radius a in the middle of the unit box
# (x, y in [0.4, 0.6]), for each maximum level, the largest and mean
# relative omega error and |U| / (g a) (exact 0), the velocity's L2 error
# over the fluid, the unknowns, the cut cells and the wall seconds of
# one solve (mesh, assembly, linear solve), and the iterative solver's
# FGMRES and setup CG iterations (0 when solved directly). Not a test.
# Usage: contrib/benchmarks/cut_inclusion.sh [a, default 0.1] [levels,
#   default "4 5 6 7 8"] [N, default 12] [band levels, default 2]
# The mesh is the unit box refined to (level - band levels), then band
# levels more around the surface; band 0 is a uniform mesh.
# Env: DIM (2 or 3, default 2), GHOST_VELOCITY, GHOST_PRESSURE (the ghost
# penalties, default 1e-3), NITSCHE (default 40), LINEAR_SOLVER (direct or
# iterative; default: iterative in 3D above 15 000 unknowns),
# VELOCITY_PRECONDITIONER (multigrid, the default, or amg),
# ITERATIVE_TOLERANCE (default 1e-10), FIDUS_CUT_INCLUSION (the
# binary; default: built with contrib/build.sh fidus_cut_inclusion).
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
bin="${FIDUS_CUT_INCLUSION:-}"
if [ -z "$bin" ]; then
  "$top/contrib/build.sh" fidus_cut_inclusion >/dev/null
  bin="$top/build-release/fidus_cut_inclusion"
fi
"$bin" "${DIM:-2}" "${1:-0.1}" "${2:-4 5 6 7 8}" "${3:-12}" "${4:-2}"
