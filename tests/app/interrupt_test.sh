#!/usr/bin/env bash
# Ctrl-C during `aerobox fly` with video: exit 130, nothing written (a run's files are moved
# into its folder only when it has ended), no temporary file left, and the folder removed again
# when the run made it.
# Usage: interrupt_test.sh AEROBOX_BINARY SOURCE_DIR
set -euo pipefail
aerobox=$1
top=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scenario=$top/scenes/window/scenario.toml

"$aerobox" fly "$scenario" --no-video --quiet --out "$work/whole" > /dev/null
"$aerobox" fly "$scenario" --out "$work/cut" > /dev/null 2> "$work/err.txt" &
pid=$!
# interrupt once the flight (and its video) is under way
for _ in $(seq 1 1200); do
  grep -q "flying" "$work/err.txt" && break
  sleep 0.05
done
sleep 0.5
kill -INT "$pid"
set +e
wait "$pid"
code=$?
set -e
[ "$code" -eq 130 ] || { echo "FAIL: exit $code after Ctrl-C"; cat "$work/err.txt"; exit 1; }
grep -q "interrupted" "$work/err.txt" || { echo "FAIL: no message"; cat "$work/err.txt"; exit 1; }
leftovers=$(find "$work" -name '*.partial' -o -name '.aerobox-staging.*')
[ -z "$leftovers" ] || { echo "FAIL: temporary files left: $leftovers"; exit 1; }
[ ! -e "$work/cut" ] || { echo "FAIL: left $(ls -A "$work/cut")"; exit 1; }

# into a folder holding a finished run: the run is left byte for byte
before=$(cd "$work/whole" && find . -type f | sort | xargs md5sum)
"$aerobox" fly "$scenario" --seed 7 --max-speed 0.5 --out "$work/whole" > /dev/null 2> "$work/err.txt" &
pid=$!
for _ in $(seq 1 1200); do
  grep -q "flying" "$work/err.txt" && break
  sleep 0.05
done
kill -INT "$pid"
code=0
wait "$pid" || code=$?
[ "$code" -eq 130 ] || { echo "FAIL: exit $code after Ctrl-C"; cat "$work/err.txt"; exit 1; }
after=$(cd "$work/whole" && find . -type f | sort | xargs md5sum)
[ "$before" = "$after" ] || { echo "FAIL: the finished run changed"; exit 1; }
echo "interrupt: exit 130, nothing written, nothing partial, the finished run intact"
