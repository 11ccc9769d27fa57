#!/usr/bin/env bash
# `pip install .` from the source tree into a fresh venv (Debian's python3, its numpy through
# the system site packages) builds the C++ core through scikit-build-core (pyproject.toml);
# `import aerobox` then works from anywhere with no PYTHONPATH and flies the window map. Then
# `pip install -e .`: the Python half is the source tree's own.
# Usage: pip_install_test.sh SOURCE_DIR BUILD_DIR   (the CMake build of pip goes into
# BUILD_DIR/pip-build, kept between runs so that a second run only rebuilds what changed)
set -euo pipefail
top=$(cd "$1" && pwd)
build=$(cd "$2" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

/usr/bin/python3 -m venv --system-site-packages "$work/venv"
python=$work/venv/bin/python
# no sanitizer runtime for this one: pip builds its own, uninstrumented, extension
unset LD_PRELOAD PYTHONPATH
"$python" -m pip install --quiet --disable-pip-version-check "$top" \
  --config-settings=build-dir="$build/pip-build" > "$work/pip.log" 2>&1 ||
  fail "pip install . failed: $(tail -n 30 "$work/pip.log")"

cd "$work"
"$python" - "$top" "$work/venv" << 'PY'
import os, sys
top, venv = sys.argv[1], sys.argv[2]
import aerobox
assert aerobox.__file__.startswith(venv), f"aerobox from {aerobox.__file__}, not the venv"
scenario = aerobox.load_scenario(os.path.join(top, "scenes", "window", "scenario.toml"))
path = aerobox.plan(scenario, seed=1)
trajectory = aerobox.min_snap(scenario, path)
result = aerobox.Simulator(scenario).run("cascade", trajectory)
assert result["status"] == "reached goal" and result["collisions"] == 0, result["status"]
print(f"pip install .: the window map flown, {result['flight_time']:.2f} s, "
      f"tracking RMS {100 * result['tracking_rms']:.1f} cm")
PY

"$python" -m pip install --quiet --disable-pip-version-check -e "$top" \
  --config-settings=build-dir="$build/pip-build" > "$work/pip.log" 2>&1 ||
  fail "pip install -e . failed: $(tail -n 30 "$work/pip.log")"
"$python" -c "
import aerobox, os, sys
source = os.path.join(sys.argv[1], 'src', 'python', 'aerobox', '__init__.py')
assert os.path.samefile(aerobox.__file__, source), aerobox.__file__
print('pip install -e .: the Python half is the source tree\'s')
" "$top"
