#!/usr/bin/env bash
# Rewrites the generated MJCF kept in git: models/tello.xml and scenes/*/scene.xml. Run it after
# changing QuadParams or the scene writer; the tests fail while these files are stale.
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
build=${AEROBOX_BUILD_DIR:-$top/build}

"$top/tools/build.sh"
cd "$top"
"$build/aerobox" model -o models/tello.xml
for scenario in scenes/*/scenario.toml; do
  "$build/aerobox" scene "$scenario" -o "$(dirname "$scenario")/scene.xml"
done
echo "regenerated models/tello.xml and $(ls scenes/*/scenario.toml | wc -l) scenes"
