#!/usr/bin/env bash
# The examples run, so that the README's snippets never name what does not exist: the README's
# Python block is examples/python/fly_mine.py, which flies the window map through the package
# and, as a module, through `aerobox fly --controller`; examples/sweep.toml runs as a sweep.
# Usage: examples_test.sh AEROBOX_BINARY SOURCE_DIR PYTHON_PACKAGE_DIR
set -euo pipefail
aerobox=$1
top=$2
package=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$top"

# the README shows the file as it is
/usr/bin/python3 - "$top" << 'PY'
import pathlib, sys
top = pathlib.Path(sys.argv[1])
readme = (top / "README.md").read_text(encoding="utf-8")
example = (top / "examples/python/fly_mine.py").read_text(encoding="utf-8")
if "```python\n" + example + "```\n" not in readme:
    sys.exit("FAIL: README.md's Python block is not examples/python/fly_mine.py")
PY

# (a sanitizer build: python3 needs the sanitizers' runtime first, tests/CMakeLists.txt)
LD_PRELOAD="${AEROBOX_PYTHON_PRELOAD:-}" PYTHONPATH=$package PYTHONDONTWRITEBYTECODE=1 \
  /usr/bin/python3 examples/python/fly_mine.py \
  "$work/mine" > "$work/mine.txt"
grep -q "^reached goal " "$work/mine.txt" || { cat "$work/mine.txt"; exit 1; }
[ -s "$work/mine/summary.json" ] && [ -s "$work/mine/video.mp4" ] ||
  { ls "$work/mine"; echo "FAIL: write_outputs wrote no summary or video"; exit 1; }

# the same class through the command, with no PYTHONPATH: the module's `import aerobox` finds
# the package beside the binary
env -u PYTHONPATH "$aerobox" fly scenes/window/scenario.toml --no-video --quiet \
  --controller examples/python/fly_mine.py:MyController --out "$work/fly" > /dev/null
grep -q '"status": "reached goal"' "$work/fly/summary.json" || exit 1

"$aerobox" sweep examples/sweep.toml --out "$work/sweep" -j 2 --quiet > /dev/null 2>&1
runs=$(wc -l < "$work/sweep/results.jsonl")
[ "$runs" = 4 ] || { echo "FAIL: the example sweep ran $runs runs, expected 4"; exit 1; }
echo "examples: the README's Python example, the controller through aerobox fly, the sweep"
