#!/usr/bin/env bash
# Ctrl-C stops every command cooperatively within 0.2 s: plan (in RRT*), compare, fly without and
# with video (while planning, solving and flying), bench and sweep. Each command is interrupted
# while it is known to be working: once it has reported that phase on stderr, and with work made
# long by its own options, so the test does not depend on the machine's speed. Each exits 130,
# says what it was doing, never needs the watchdog, and leaves no temporary file; a folder that
# held a finished run holds it byte for byte (also after a Python controller raised).
# Usage: interrupt_everywhere_test.sh AEROBOX_BINARY SOURCE_DIR [ROUNDS [BUSY]]
#   ROUNDS: repeat everything (default 1); BUSY=1: two busy loops keep both cores loaded.
set -euo pipefail
aerobox=$1
top=$(cd "$2" && pwd)
rounds=${3:-1}
busy=${4:-0}
limit=0.2  # [s] from SIGINT to the process's end
work=$(mktemp -d)
busy_pids=()
cleanup() {
  for p in "${busy_pids[@]}"; do kill "$p" 2> /dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT
fail() { echo "FAIL: $*"; exit 1; }
window=$top/scenes/window/scenario.toml
forest=$top/scenes/forest/scenario.toml

# a search that would run a minute: no path, no fallback, a huge budget
cp "$top/scenes/impossible/map.json" "$work/closed.json"
cat > "$work/slow.toml" << 'TOML'
map = "closed.json"
[planner]
max_search_iterations = 100000000
time_budget = 60
lattice_fallback = false
TOML
# a given path of 300 waypoints: its trajectory takes seconds to solve
/usr/bin/python3 - "$top/scenes/empty/map.json" > "$work/helix.toml" << 'PY'
import math, sys
points = ", ".join("[%.3f, %.3f, %.3f]" % (2.25 + 1.5 * math.cos(0.5 * i),
                   3.25 + 1.5 * math.sin(0.5 * i), 1 + 0.05 * (i % 20)) for i in range(300))
print('map = "%s"\nstart = [2.25, 3.25, 0.5]\ngoal = [2.25, 3.25, 2.5]' % sys.argv[1])
print('[planner]\nkind = "waypoints"\nwaypoints = [%s]' % points)
PY
# a sweep whose runs fly for a minute each
cat > "$work/slow_sweep.toml" << TOML
scenarios = ["$window"]
seeds = 4
[grid]
"trajectory.max_speed" = [0.1]
TOML
cat > "$work/raising.py" << 'PY'
class Raising:
    def __init__(self, quad_params):
        pass

    def update(self, t, state, flat_output):
        raise RuntimeError("this controller always fails")
PY

snapshot() { (cd "$1" && find . -type f | sort | xargs md5sum); }

# check NAME PHASE COMMAND...: runs COMMAND, interrupts it once its stderr (or a file in the
# folder $watch, when set) matches PHASE. In a sanitizer build (AEROBOX_SANITIZED=1) each
# command runs twice: once with leak detection, AddressSanitizer's defaults and no time limit
# (the interrupted paths leak nothing and touch no freed memory), once timed without leak
# detection and with an 8 MB quarantine of freed memory instead of 256 MB, since both are the
# sanitizer's time at exit, not the command's: LeakSanitizer's scan of the heap takes 0.3 to
# 0.7 s, and the kernel's teardown of the quarantine's pages 80 to 100 ms after exit_group
# (measured with strace: fly stopped 43 ms after SIGINT and its process ended 81 ms later).
check() {
  if [ "${AEROBOX_SANITIZED:-0}" = 1 ]; then
    limit=1000 check_once "$@"
    ASAN_OPTIONS="${ASAN_OPTIONS:-}:detect_leaks=0:quarantine_size_mb=8" check_once "$@"
  else
    check_once "$@"
  fi
}
check_once() {
  local name=$1 phase=$2
  shift 2
  # an earlier round's files would match at once, before this command has even started
  rm -f "$work/$name.out" "$work/$name.err"
  "$@" > "$work/$name.out" 2> "$work/$name.err" &
  local pid=$!
  local waited=0
  until grep -rqs -- "$phase" "$work/$name.err" ${watch:+"$watch"}; do
    kill -0 "$pid" 2> /dev/null || fail "$name ended before '$phase': $(cat "$work/$name.err")"
    sleep 0.02
    waited=$((waited + 1))
    [ "$waited" -lt 6000 ] || fail "$name: no '$phase' within 2 minutes"
  done
  sleep 0.1  # well inside that phase
  local begin end code=0
  begin=$(date +%s.%N)
  kill -INT "$pid"
  wait "$pid" || code=$?
  end=$(date +%s.%N)
  local took
  took=$(awk -v a="$begin" -v b="$end" 'BEGIN { printf "%.3f", b - a }')
  [ "$code" -eq 130 ] || fail "$name exited $code after Ctrl-C: $(cat "$work/$name.err")"
  ! grep -q "watchdog" "$work/$name.err" || fail "$name needed the watchdog: $(cat "$work/$name.err")"
  grep -q "interrupted" "$work/$name.err" || fail "$name said nothing: $(cat "$work/$name.err")"
  awk -v t="$took" -v l="$limit" 'BEGIN { exit !(t <= l) }' || fail "$name took $took s to stop"
  local leftovers
  leftovers=$(find "$work" -name '*.partial' -o -name '.aerobox-staging.*')
  [ -z "$leftovers" ] || fail "$name left $leftovers"
  echo "$name: exit 130 after $took s ($(grep -o 'interrupted while [^;]*' "$work/$name.err" | head -n 1))"
}

if [ "$busy" = 1 ]; then
  for _ in 1 2; do
    (while :; do :; done) &
    busy_pids+=($!)
  done
fi

# a finished run, which every interrupted or failed run into its folder must leave as it is
"$aerobox" fly "$window" --no-video --quiet --out "$work/kept" > /dev/null
before=$(snapshot "$work/kept")
unchanged() { [ "$(snapshot "$work/kept")" = "$before" ] || fail "$1 changed the finished run"; }

for round in $(seq 1 "$rounds"); do
  [ "$rounds" -eq 1 ] || echo "round $round of $rounds"
  check plan "planning" "$aerobox" plan "$work/slow.toml" --out "$work/plan"
  [ ! -e "$work/plan" ] || fail "plan left $work/plan behind"
  check compare "compare: forest" "$aerobox" compare "$window" "$forest" "$forest" --out "$work/compare"
  [ ! -e "$work/compare" ] || fail "compare left $work/compare behind"
  check fly_planning "planning" "$aerobox" fly "$work/slow.toml" --no-video --out "$work/kept"
  unchanged "fly interrupted while planning"
  check fly_solving "planning" "$aerobox" fly "$work/helix.toml" --no-video --out "$work/kept"
  grep -q "interrupted while .*trajectory\|interrupted while allocating" "$work/fly_solving.err" ||
    fail "fly_solving was not solving: $(cat "$work/fly_solving.err")"
  unchanged "fly interrupted while solving"
  check fly_flying "flying" "$aerobox" fly "$window" --max-speed 0.1 --seed 5 --no-video --out "$work/kept"
  unchanged "fly interrupted while flying"
  check fly_video "flying" "$aerobox" fly "$window" --max-speed 0.1 --seed 5 --out "$work/kept"
  unchanged "fly with video interrupted while flying"
  check bench "run 1/" "$aerobox" bench --sections planning --scenes "$top/scenes" --maps window --seeds 50 --seconds 1
  watch=$work/sweep.out check sweep "to run" "$aerobox" sweep "$work/slow_sweep.toml" --out "$work/sweep" -j 2 --quiet
  rm -rf "$work/sweep"
  # a Python controller that raises: exit 2, and the finished run stays
  code=0
  "$aerobox" fly "$window" --no-video --quiet --controller "$work/raising.py:Raising" \
    --out "$work/kept" > /dev/null 2> "$work/raising.err" || code=$?
  [ "$code" -eq 2 ] || fail "a raising controller: exit $code"
  unchanged "a raising Python controller"
done
echo "interrupt: every command stopped within $limit s with exit 130, the finished run intact"
