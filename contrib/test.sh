#!/usr/bin/env bash
# Install what is missing, build fidus (Release) and run the whole test suite
# with ctest. Extra arguments go to ctest (e.g. -R contact).
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
"$top/contrib/build.sh" fidus fidus_core fidus_contact
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cd "$top/build-release"
ctest -j"$(nproc)" --output-on-failure "$@"
