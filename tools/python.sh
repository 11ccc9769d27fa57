#!/usr/bin/env bash
# Debian's python3 with the aerobox package from the build tree (built first when needed), in
# the project environment .venv when tools/setup.sh made it (Debian's python3 seeing its own
# packages, with the pinned PyPI peers: Gymnasium, stable-baselines3, RotorPy):
#   tools/python.sh my_flight.py      tools/python.sh -c "import aerobox; help(aerobox)"
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
build=${AEROBOX_BUILD_DIR:-$top/build}
if [ ! -f "$build/python/aerobox/__init__.py" ] || [ ! -f "$build/CMakeCache.txt" ]; then
  "$top/tools/build.sh" >&2
fi
export PYTHONPATH="$build/python${PYTHONPATH:+:$PYTHONPATH}"
python=/usr/bin/python3
if [ -x "$top/.venv/bin/python" ]; then python=$top/.venv/bin/python; fi
exec "$python" "$@"
