#!/usr/bin/env bash
# Builds aerobox with the OMPL reference (in build-bench/, apart from the normal build) and runs
# `aerobox bench`. Extra arguments go to `aerobox bench`, e.g. tools/bench.sh --seeds 5
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
build=${AEROBOX_BENCH_DIR:-$top/build-bench}

"$top/tools/setup.sh" --bench
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$top" -B "$build" -DCMAKE_BUILD_TYPE=Release -DAEROBOX_WITH_OMPL=ON \
        -DAEROBOX_BUILD_TESTS=OFF
fi
cmake --build "$build" --parallel "$(nproc)" --target aerobox aerobox-bench
cd "$top"
# the city section reads the FCND map when the shared maps sit beside the repository
city=$top/../shared/maps/fcnd/colliders.csv
extra=()
if [ -f "$city" ]; then extra=(--city "$city"); fi
exec "$build/aerobox" bench "${extra[@]}" "$@"
