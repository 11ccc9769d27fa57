#!/usr/bin/env bash
# Set-up, configure and build as needed (each step does nothing when it is already done).
# Usage: tools/build.sh [extra cmake -D options...]   Build folder: build/ (or $AEROBOX_BUILD_DIR).
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
build=${AEROBOX_BUILD_DIR:-$top/build}

"$top/tools/setup.sh"
if [ ! -f "$build/CMakeCache.txt" ] || [ $# -gt 0 ]; then
  cmake -S "$top" -B "$build" -DCMAKE_BUILD_TYPE=Release "$@"
fi
cmake --build "$build" --parallel "$(nproc)"
