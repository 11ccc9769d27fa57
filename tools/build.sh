#!/usr/bin/env bash
# Set-up, configure and build as needed (each step does nothing when it is already done).
# Usage: tools/build.sh [extra cmake -D options...]   Build folder: build/ (or $AEROBOX_BUILD_DIR).
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
build=${AEROBOX_BUILD_DIR:-$top/build}

"$top/tools/setup.sh"
if [ ! -f "$build/CMakeCache.txt" ] || [ $# -gt 0 ]; then
  # Debian's python3 (with numpy), not one a version manager puts first on PATH (DESIGN.md)
  cmake -S "$top" -B "$build" -DCMAKE_BUILD_TYPE=Release -DPython_EXECUTABLE=/usr/bin/python3 "$@"
fi
cmake --build "$build" --parallel "$(nproc)"
