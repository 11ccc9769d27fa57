#!/usr/bin/env bash
# Installs what is missing, builds, and flies the default scene (the window map), writing the
# video, telemetry and summary under renders/<scenario>/. Extra arguments go to `aerobox fly`.
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
build=${AEROBOX_BUILD_DIR:-$top/build}

"$top/tools/build.sh"
cd "$top"
exec "$build/aerobox" fly scenes/window/scenario.toml "$@"
