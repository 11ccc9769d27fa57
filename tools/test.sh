#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test (CTest). Extra arguments go to ctest,
# e.g. tools/test.sh -R map   or   tools/test.sh -L scenario
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
build=${AEROBOX_BUILD_DIR:-$top/build}

"$top/tools/build.sh"
cd "$build"
ctest --output-on-failure --parallel "$(nproc)" "$@"
