#!/usr/bin/env bash
# aerobox sweep end to end: a sweep runs every run once, with a result line each and a report;
# 1, 2 and 4 shards merged give the same results; an interrupted sweep resumes with only what is
# missing; bad sweep files exit 2 naming the line, before any run, and write nothing.
# Usage: sweep_test.sh AEROBOX_BINARY SOURCE_DIR
set -euo pipefail
aerobox=$1
top=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
equal="/usr/bin/python3 $top/tests/app/sweep_results_equal.py"
fail() { echo "FAIL: $*"; exit 1; }

mkdir -p "$work/sweeps"
cat > "$work/sweeps/speeds.toml" <<TOML
scenarios = ["$top/scenes/window/scenario.toml"]
seeds = [1, 2, 3]
[grid]
"trajectory.max_speed" = [2.0, 4.0]
[keep]
video = 1
TOML
# --list: the runs, and nothing run or written
"$aerobox" sweep "$work/sweeps/speeds.toml" --out "$work/listed" --list > "$work/list.out"
[ "$(grep -c 'scenario.toml' "$work/list.out")" -eq 6 ] || fail "--list: $(cat "$work/list.out")"
grep -q "6 runs (1 scenario(s) x 2 grid cell(s) x 3 seed(s))" "$work/list.out" || fail "--list total"
[ ! -e "$work/listed" ] || fail "--list wrote $work/listed"
"$aerobox" sweep "$work/sweeps/speeds.toml" --out "$work/whole" -j 2 --quiet > "$work/whole.out"
[ "$(wc -l < "$work/whole/results.jsonl")" -eq 6 ] || fail "6 result lines expected"
for file in report.md report.csv success.svg tracking.svg sweep.json; do
  [ -s "$work/whole/$file" ] || fail "no $file"
done
grep -q '| 2.0 | 3 | 3/3 (100 %)' "$work/whole/report.md" || fail "report.md: $(cat "$work/whole/report.md")"
[ "$(wc -l < "$work/whole/report.csv")" -eq 3 ] || fail "report.csv: a header and 2 cells"
# one unit for the tracking error in the table, the chart and the page: metres
grep -q 'tracking RMS median / p90 \[m\]' "$work/whole/report.md" || fail "report.md: RMS unit"
grep -q ' m</text>' "$work/whole/tracking.svg" || fail "tracking.svg: not in metres"
! grep -q -e ' cm<' -e '\[cm\]' -e "'cm'" "$work/whole/tracking.svg" "$work/whole/report.html" ||
  fail "a chart in cm"
# the first run alone keeps a video; no run keeps telemetry (the defaults of [keep])
[ "$(find "$work/whole/runs" -name video.mp4 | wc -l)" -eq 1 ] || fail "one video expected"
[ "$(find "$work/whole/runs" -name telemetry.csv | wc -l)" -eq 0 ] || fail "no telemetry expected"
/usr/bin/python3 - "$work/whole/results.jsonl" <<'PY' || fail "a result line lacks a field"
import json, sys
for line in open(sys.argv[1]):
    r = json.loads(line)
    assert r["status"] == "reached goal" and r["exit_code"] == 0, r
    assert r["params"]["trajectory.max_speed"] in (2.0, 4.0)
    assert r["summary"]["trajectory_max_speed_mps"] <= r["params"]["trajectory.max_speed"] + 1e-3
    assert r["wall_time_s"] > 0 and r["host"] and len(r["id"]) == 16
PY

# shards: every run in exactly one, whatever N; merged, the same results and report
for n in 2 4; do
  for ((i = 0; i < n; i++)); do
    "$aerobox" sweep "$work/sweeps/speeds.toml" --out "$work/shards$n" --shard "$i/$n" --quiet \
      > /dev/null
  done
  "$aerobox" sweep merge "$work/shards$n" > /dev/null
  cmp "$work/whole/report.md" "$work/shards$n/report.md" || fail "report.md differs ($n shards)"
done
$equal "$work/whole/results.jsonl" "$work/shards2/results.jsonl" "$work/shards4/results.jsonl"
# the Slurm variables choose the shard when --shard is not given
SLURM_ARRAY_TASK_ID=5 SLURM_ARRAY_TASK_MIN=4 SLURM_ARRAY_TASK_COUNT=3 \
  "$aerobox" sweep "$work/sweeps/speeds.toml" --out "$work/slurmvars" --quiet > /dev/null
[ -s "$work/slurmvars/results.shard-1-of-3.jsonl" ] || fail "SLURM_ARRAY_TASK_* ignored"
# a merge with a shard missing says so and fails
code=0
"$aerobox" sweep merge "$work/slurmvars" > /dev/null 2> "$work/merge.err" || code=$?
[ "$code" -eq 1 ] && grep -q "have no result" "$work/merge.err" || fail "incomplete merge: $code"

# interrupted, then resumed: only the missing runs run, and the result is the whole sweep's
"$aerobox" sweep "$work/sweeps/speeds.toml" --out "$work/cut" -j 1 --quiet > /dev/null &
pid=$!
for _ in $(seq 1200); do  # the first run's result, within a minute even on a loaded machine
  [ -s "$work/cut/results.jsonl" ] && break
  sleep 0.05
done
kill -INT "$pid"
code=0
wait "$pid" || code=$?
[ "$code" -eq 130 ] || fail "interrupted sweep exited $code"
before=$(wc -l < "$work/cut/results.jsonl")
[ "$before" -ge 1 ] && [ "$before" -lt 6 ] || fail "$before results after the interruption"
code=0
"$aerobox" sweep "$work/sweeps/speeds.toml" --out "$work/cut" --quiet > /dev/null 2>&1 || code=$?
[ "$code" -eq 2 ] || fail "a folder with results, without --resume: exit $code"
"$aerobox" sweep "$work/sweeps/speeds.toml" --out "$work/cut" --resume --quiet > "$work/resume.out"
grep -q "$before done before; $((6 - before)) to run" "$work/resume.out" || fail "$(cat "$work/resume.out")"
$equal "$work/whole/results.jsonl" "$work/cut/results.jsonl"

# a depth camera in a sweep: the grid sets the occupancy map's resolution and the camera's
# width; each run's summary has its map at that resolution
cat > "$work/sweeps/depth.toml" <<TOML
scenarios = ["$top/scenes/depth_forest/scenario.toml"]
seeds = [3]
[grid]
"sensing.resolution" = [0.1, 0.2]
"sensing.width" = [160]
TOML
"$aerobox" sweep "$work/sweeps/depth.toml" --out "$work/depth" -j 2 --quiet > /dev/null ||
  fail "depth sweep: exit $?"
/usr/bin/python3 - "$work/depth/results.jsonl" <<'PY' || fail "depth sweep: $(cat "$work/depth/results.jsonl")"
import json, sys
results = [json.loads(line) for line in open(sys.argv[1])]
assert sorted(r["params"]["sensing.resolution"] for r in results) == [0.1, 0.2]
for r in results:
    occupancy = r["summary"]["occupancy"]
    assert occupancy["resolution_m"] == r["params"]["sensing.resolution"], occupancy
    assert occupancy["occupied_cells"] > 0 and occupancy["free_cells"] > 0, occupancy
    assert len(r["summary"]["revealed"]) > 0
PY

# bad sweep files: exit 2, the file and line named, nothing written
bad() {  # bad NAME EXPECTED-MESSAGE, the sweep on standard input
  cat > "$work/sweeps/$1.toml"
  code=0
  "$aerobox" sweep "$work/sweeps/$1.toml" --out "$work/bad_$1" 2> "$work/bad.err" > /dev/null ||
    code=$?
  [ "$code" -eq 2 ] || fail "$1: exit $code"
  grep -q "$1.toml:$2" "$work/bad.err" || fail "$1: $(cat "$work/bad.err")"
  [ ! -e "$work/bad_$1" ] || fail "$1: wrote $work/bad_$1"
}
printf 'scenarios = ["%s"]\nseedz = 3\n' "$top/scenes/window/scenario.toml" |
  bad unknown_key "2: seedz: unknown key"
printf 'scenarios = ["%s"]\n[grid]\n' "$top/scenes/window/scenario.toml" |
  bad empty_grid "2: grid: the grid is empty"
printf 'scenarios = ["nowhere/*/scenario.toml"]\n' | bad bad_glob "1: scenarios: .* matches no file"
printf 'scenarios = ["%s"]\n[grid]\n"trajectory.max_sped" = [1.0]\n' \
  "$top/scenes/window/scenario.toml" | bad unknown_scenario_key "3: trajectory.max_sped"
printf 'scenarios = ["%s"]\n[grid]\n"trajectory.max_speed" = [2.0, 99.0]\n' \
  "$top/scenes/window/scenario.toml" | bad bad_value "3: trajectory.max_speed: .*0.01 to 8"
# fly --set: a refused setting exits 2 naming it, and writes nothing
code=0
"$aerobox" fly "$top/scenes/window/scenario.toml" --no-video --out "$work/set" \
  --set trajectory.max_sped=2 2> "$work/set.err" > /dev/null || code=$?
[ "$code" -eq 2 ] && grep -q "trajectory.max_sped: unknown key" "$work/set.err" ||
  fail "--set: exit $code, $(cat "$work/set.err")"
[ ! -e "$work/set" ] || fail "--set: wrote $work/set"
echo "sweep: ok"
