#!/usr/bin/env bash
# Two real processes and one output folder. (1) Two `aerobox fly ... --out cc` started together:
# one owns the folder, the other stops at once with exit 2 naming the owner; the folder then
# holds one complete run (pandas reads its telemetry; its summary has the owner's seed).
# (2) A video run, then a --no-video run into the same folder: no video.mp4 of the first run
# is left beside the second's telemetry. Usage: shared_folder_test.sh AEROBOX_BINARY SOURCE_DIR
set -euo pipefail
aerobox=$1
top=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scenario=$top/scenes/empty/scenario.toml

"$aerobox" fly "$scenario" --no-video --quiet --seed 1 --out "$work/cc" > "$work/a.out" 2> "$work/a.err" &
a=$!
"$aerobox" fly "$scenario" --no-video --quiet --seed 2 --out "$work/cc" > "$work/b.out" 2> "$work/b.err" &
b=$!
set +e
wait "$a"; code_a=$?
wait "$b"; code_b=$?
set -e
echo "exit codes: $code_a $code_b"
if [ "$code_a" -eq 0 ] && [ "$code_b" -eq 2 ]; then winner=1; loser=b
elif [ "$code_a" -eq 2 ] && [ "$code_b" -eq 0 ]; then winner=2; loser=a
elif [ "$code_a" -eq 0 ] && [ "$code_b" -eq 0 ]; then winner=0  # one finished before the other began
else echo "FAIL: exit codes $code_a and $code_b"; cat "$work/a.err" "$work/b.err"; exit 1; fi
if [ "$winner" -ne 0 ]; then
  grep -q "another aerobox run (process [0-9]*) is writing into this folder" "$work/$loser.err" ||
    { echo "FAIL: the second run did not name the first"; cat "$work/$loser.err"; exit 1; }
  seed=$(/usr/bin/python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['seed'])" "$work/cc/summary.json")
  [ "$seed" -eq "$winner" ] || { echo "FAIL: summary of seed $seed, the owner was $winner"; exit 1; }
fi
/usr/bin/python3 -c "import pandas,sys; t = pandas.read_csv(sys.argv[1]); assert len(t) > 100 and t['t'].is_monotonic_increasing" "$work/cc/telemetry.csv" ||
  { echo "FAIL: telemetry.csv does not parse as one run"; exit 1; }
[ -z "$(find "$work/cc" -name '*.partial' -o -name '.aerobox.lock')" ] || { echo "FAIL: leftovers"; ls -a "$work/cc"; exit 1; }

# (2) stale files
"$aerobox" fly "$scenario" --size 160x120 --quiet --out "$work/reuse" > /dev/null
[ -f "$work/reuse/video.mp4" ] || { echo "FAIL: no video in the first run"; exit 1; }
"$aerobox" fly "$scenario" --no-video --quiet --out "$work/reuse" > /dev/null
[ ! -e "$work/reuse/video.mp4" ] || { echo "FAIL: the first run's video.mp4 survived"; exit 1; }
for name in path.csv trajectory.csv telemetry.csv summary.json overview.png; do
  [ -f "$work/reuse/$name" ] || { echo "FAIL: $name missing"; exit 1; }
done
echo "shared folder: one owner, the other exit 2 naming it; no stale video after a --no-video run"
