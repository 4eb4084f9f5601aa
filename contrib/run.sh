#!/usr/bin/env bash
# Install what is missing, build fidus (Release) and run one scene.
# Usage: contrib/run.sh [file.prm] [number of MPI ranks]
# Default: the seed paper's 2D scene, prm/two_particles_2d.prm, on 1 rank.
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
"$top/contrib/build.sh" fidus
prm="${1:-$top/prm/two_particles_2d.prm}"
ranks="${2:-1}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
if [ "$ranks" -gt 1 ]; then
  mpirun -np "$ranks" "$top/build-release/fidus" "$prm"
else
  "$top/build-release/fidus" "$prm"
fi
