#!/usr/bin/env bash
# Ctrl-C stops every command within a second, not only a flight: plan (in a long RRT* search),
# compare and bench. Each exits 130 and leaves no temporary file. (The bound checked is 3 s:
# the one-second grace plus room for a loaded machine.)
# Usage: interrupt_everywhere_test.sh AEROBOX_BINARY SOURCE_DIR
set -euo pipefail
aerobox=$1
top=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# a search that would run a minute: no path, no fallback, a huge budget
cp "$top/scenes/impossible/map.json" "$work/closed.json"
cat > "$work/slow.toml" <<'TOML'
map = "closed.json"
[planner]
max_search_iterations = 100000000
time_budget = 60
lattice_fallback = false
TOML

check() {  # check NAME COMMAND...
  local name=$1
  shift
  "$@" > "$work/$name.out" 2> "$work/$name.err" &
  local pid=$!
  sleep 0.7
  local begin
  begin=$(date +%s.%N)
  kill -INT "$pid"
  set +e
  wait "$pid"
  local code=$?
  set -e
  local took
  took=$(awk -v a="$begin" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }')
  [ "$code" -eq 130 ] || { echo "FAIL: $name exited $code after Ctrl-C"; cat "$work/$name.err"; exit 1; }
  if awk -v t="$took" 'BEGIN { exit !(t > 3) }'; then
    echo "FAIL: $name took $took s to stop"
    exit 1
  fi
  leftovers=$(find "$work" -name '*.partial')
  [ -z "$leftovers" ] || { echo "FAIL: $name left $leftovers"; exit 1; }
  echo "$name: exit 130 after $took s"
}

check plan "$aerobox" plan "$work/slow.toml" --out "$work/plan"
[ ! -e "$work/plan/path.csv" ] || { echo "FAIL: plan wrote path.csv after Ctrl-C"; exit 1; }
check compare "$aerobox" compare "$top/scenes/window/scenario.toml" "$top/scenes/forest/scenario.toml" --out "$work/compare"
check bench "$aerobox" bench --sections planning --scenes "$top/scenes" --maps window --seeds 50 --seconds 1
echo "interrupt: every command stopped with exit 130, nothing partial"
