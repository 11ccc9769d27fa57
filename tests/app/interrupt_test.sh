#!/usr/bin/env bash
# Ctrl-C during `aerobox fly` with video: exit 130, and every file in the output folder is
# complete (byte-identical to an uninterrupted run's) or absent; no temporary file is left.
# Usage: interrupt_test.sh AEROBOX_BINARY SOURCE_DIR
set -euo pipefail
aerobox=$1
top=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scenario=$top/scenes/window/scenario.toml

"$aerobox" fly "$scenario" --no-video --quiet --out "$work/whole" > /dev/null
"$aerobox" fly "$scenario" --quiet --out "$work/cut" > /dev/null 2> "$work/err.txt" &
pid=$!
# interrupt once the flight (and its video) is under way: path.csv is written before it starts
for _ in $(seq 1 200); do
  [ -e "$work/cut/trajectory.csv" ] && break
  sleep 0.05
done
sleep 1
kill -INT "$pid"
set +e
wait "$pid"
code=$?
set -e
[ "$code" -eq 130 ] || { echo "FAIL: exit $code after Ctrl-C"; cat "$work/err.txt"; exit 1; }
grep -q "interrupted" "$work/err.txt" || { echo "FAIL: no message"; cat "$work/err.txt"; exit 1; }
leftovers=$(find "$work/cut" -name '*.partial')
[ -z "$leftovers" ] || { echo "FAIL: temporary files left: $leftovers"; exit 1; }
for file in "$work"/cut/*; do
  name=$(basename "$file")
  cmp -s "$file" "$work/whole/$name" || { echo "FAIL: $name is incomplete or differs"; exit 1; }
done
for name in telemetry.csv summary.json video.mp4; do
  [ ! -e "$work/cut/$name" ] || { echo "FAIL: $name written after Ctrl-C"; exit 1; }
done
echo "interrupt: exit 130, kept $(ls "$work/cut" | tr '\n' ' ')(complete), nothing partial"
