#!/usr/bin/env bash
# tools/plot_telemetry.py on a real flight's telemetry writes a PNG; bad input exits 2 and
# writes nothing. Usage: plot_telemetry_test.sh AEROBOX_BINARY SOURCE_DIR
set -euo pipefail
aerobox=$1
top=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$aerobox" fly "$top/scenes/empty/scenario.toml" --no-video --quiet --out "$work/empty" > /dev/null
/usr/bin/python3 "$top/tools/plot_telemetry.py" "$work/empty/telemetry.csv" "$work/plots.png"
[ "$(head -c 8 "$work/plots.png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] ||
  { echo "FAIL: plots.png is not a PNG"; exit 1; }

printf 'a,b\n1,2\n' > "$work/bad.csv"
set +e
/usr/bin/python3 "$top/tools/plot_telemetry.py" "$work/bad.csv" "$work/bad.png" 2> "$work/err.txt"
code=$?
set -e
[ "$code" -eq 2 ] || { echo "FAIL: bad telemetry exited $code"; exit 1; }
grep -q "not an aerobox telemetry file" "$work/err.txt" || { cat "$work/err.txt"; exit 1; }
[ ! -e "$work/bad.png" ] || { echo "FAIL: a PNG was written for bad input"; exit 1; }
echo "plot_telemetry: PNG written; bad input exits 2"
