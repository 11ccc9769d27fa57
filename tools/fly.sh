#!/usr/bin/env bash
# Installs what is missing, builds, flies the default scene (the window map) and plots the
# telemetry: video, overview, report.html, telemetry, summary and plots land in renders/<scenario>/.
# Extra arguments go to `aerobox fly` (e.g. --camera overview, --quality pretty, --no-video).
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
build=${AEROBOX_BUILD_DIR:-$top/build}

"$top/tools/build.sh"
cd "$top"
code=0
"$build/aerobox" fly scenes/window/scenario.toml "$@" || code=$?
if [ -f renders/window/telemetry.csv ]; then
  /usr/bin/python3 tools/plot_telemetry.py renders/window/telemetry.csv renders/window/plots.png
fi
exit "$code"
