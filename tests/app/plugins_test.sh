#!/usr/bin/env bash
# The example plug-ins in examples/plugins (built in through AEROBOX_PLUGINS) fly with
# `aerobox fly` and take their own keys from [controller] and [planner]: the keys change what
# they do, bad values are refused naming the key and its range, `aerobox keys` lists them, and
# no file under src/ names them.
# Usage: plugins_test.sh AEROBOX_BINARY SOURCE_DIR
set -euo pipefail
aerobox=$1
top=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

scenario() {  # scenario FILE [EXTRA CONTROLLER LINE] [EXTRA PLANNER LINE]
  cat > "$1" << TOML
name = "plugins"
map = "$top/scenes/pillar/map.json"
start = [-5.0, 0.0, 1.0]
goal = [5.0, 0.0, 1.0]
[controller]
kind = "example_pd"
${2:-}
[planner]
kind = "example_detour"
${3:-}
TOML
}

# they fly, with their own keys
scenario "$work/a.toml" "position_gain = 5.0" "step = 0.5"
"$aerobox" fly "$work/a.toml" --no-video --quiet --out "$work/a" > "$work/a.txt"
grep -q '"controller": "example_pd"' "$work/a/summary.json" || { cat "$work/a/summary.json"; exit 1; }
grep -q '"status": "reached goal"' "$work/a/summary.json" || { cat "$work/a.txt"; exit 1; }
# the planner's step decides how far aside the detour goes: 0.5 m, then 1.5 m
detour() { sed -n 3p "$1/path.csv" | cut -d, -f2; }
scenario "$work/b.toml" "" "step = 1.5"
"$aerobox" fly "$work/b.toml" --no-video --quiet --out "$work/b" > /dev/null
a=$(detour "$work/a")
b=$(detour "$work/b")
/usr/bin/python3 -c "import sys; a, b = abs(float('$a')), abs(float('$b')); sys.exit(0 if abs(a - 0.5) < 1e-9 and abs(b - 1.5) < 1e-9 else 1)" ||
  { echo "FAIL: the detours are $a and $b m aside, expected 0.5 and 1.5"; exit 1; }
# the controller's gains change the flight
scenario "$work/c.toml" "position_gain = 2.0" "step = 0.5"
"$aerobox" fly "$work/c.toml" --no-video --quiet --out "$work/c" > /dev/null || true
if cmp -s "$work/a/telemetry.csv" "$work/c/telemetry.csv"; then
  echo "FAIL: position_gain changed nothing"
  exit 1
fi
# --controller NAME is controller.kind in other words: set before the table is read, so the
# named controller's own keys can follow with --set
sed 's/kind = "example_pd"/kind = "cascade"/' "$work/c.toml" | grep -v position_gain > "$work/d.toml"
"$aerobox" fly "$work/d.toml" --controller example_pd --set controller.position_gain=2.0 \
  --no-video --quiet --out "$work/d" > /dev/null || true
cmp -s "$work/c/telemetry.csv" "$work/d/telemetry.csv" ||
  { echo "FAIL: --controller example_pd --set controller.position_gain=2.0 flew otherwise"; exit 1; }

# their keys are checked like every other: the range, and the key list
scenario "$work/bad.toml" "" "step = 50"
set +e
"$aerobox" fly "$work/bad.toml" --no-video --out "$work/bad" > /dev/null 2> "$work/bad.err"
code=$?
set -e
[ "$code" = 2 ] || { echo "FAIL: a step of 50 m exits $code, expected 2"; exit 1; }
grep -q "bad.toml:10: planner.step: expected a number from 0.01 to 10" "$work/bad.err" ||
  { cat "$work/bad.err"; exit 1; }
[ ! -e "$work/bad" ] || { echo "FAIL: a refused run left its folder"; exit 1; }
scenario "$work/typo.toml" "position_gian = 5" ""
set +e
"$aerobox" check "$work/typo.toml" > /dev/null 2> "$work/typo.err"
code=$?
set -e
[ "$code" = 2 ] || { echo "FAIL: a misspelt key exits $code, expected 2"; exit 1; }
grep -q "controller.position_gian: unknown key (expected .*position_gain, velocity_gain)" \
  "$work/typo.err" || { cat "$work/typo.err"; exit 1; }

# the reference lists them; nothing under src/ names them
"$aerobox" keys > "$work/keys.md"
grep -q '^## \[controller\] kind = "example_pd"' "$work/keys.md" || exit 1
grep -q '^| `max_offset` | m | 5 | 0.01 to 1000 |' "$work/keys.md" || { cat "$work/keys.md"; exit 1; }
if grep -rlE "example_pd|example_detour|PdParams|DetourParams" "$top/src"; then
  echo "FAIL: a file under src/ names the example plug-ins"
  exit 1
fi
echo "plugins: example_pd and example_detour fly with their own keys; src/ does not name them"
