#!/usr/bin/env bash
# The same seed gives byte-identical path.csv, trajectory.csv, telemetry.csv and the same
# numbers in summary.json (all but wall times), across runs and across thread counts of the
# numerical libraries (OpenMP, OpenBLAS). Usage: determinism_test.sh AEROBOX_BINARY SOURCE_DIR
set -euo pipefail
aerobox=$1
top=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scenario=$top/scenes/forest/scenario.toml

run() {  # run NAME THREADS [SCENARIO]
  OMP_NUM_THREADS=$2 OPENBLAS_NUM_THREADS=$2 \
    "$aerobox" fly "${3:-$scenario}" --no-video --quiet --seed 7 --out "$work/$1" > /dev/null
  # wall-clock fields differ by nature; everything else must not
  grep -v -E '"(planning_time_s|trajectory_time_s|flight_wall_time_s)"' "$work/$1/summary.json" \
    > "$work/$1/summary.numbers"
}
run a 1
run b 1
run c 2
run d 8
for other in b c d; do
  for name in path.csv trajectory.csv telemetry.csv summary.numbers; do
    cmp "$work/a/$name" "$work/$other/$name" || { echo "FAIL: $name differs ($other)"; exit 1; }
  done
done
# wind, turbulence and sensor noise repeat byte for byte too; another seed changes them
windy=$top/scenes/windy_window/scenario.toml
run w1 1 "$windy"
run w2 2 "$windy"
for name in path.csv trajectory.csv telemetry.csv summary.numbers; do
  cmp "$work/w1/$name" "$work/w2/$name" || { echo "FAIL: windy $name differs"; exit 1; }
done
"$aerobox" fly "$windy" --no-video --quiet --seed 8 --out "$work/w3" > /dev/null
if cmp -s "$work/w1/telemetry.csv" "$work/w3/telemetry.csv"; then
  echo "FAIL: seeds 7 and 8 flew the same windy flight"
  exit 1
fi
echo "determinism: 4 runs (1, 1, 2, 8 threads) byte-identical; wind and sensors too"
