#!/usr/bin/env bash
# Install what is missing, build fidus (Release) and run the whole test suite
# with ctest. Extra arguments go to ctest (e.g. -R contact).
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
"$top/contrib/build.sh" fidus fidus_core fidus_contact
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# Tests on 3 ranks (name.mpirun=3.output) must run on 2-core machines too:
# OpenMPI refuses more ranks than cores unless told to oversubscribe.
export OMPI_MCA_rmaps_base_oversubscribe=1
cd "$top/build-release"
ctest -j"$(nproc)" --output-on-failure "$@"
