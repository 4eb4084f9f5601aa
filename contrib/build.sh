#!/usr/bin/env bash
# Configure (Release) and build fidus in build-release/. Usage: contrib/build.sh [target...]
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
"$top/contrib/install_dependencies.sh"
build="$top/build-release"
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$top" -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build "$build" -j"$(nproc)" --target "${@:-fidus}"
