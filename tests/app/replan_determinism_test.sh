#!/usr/bin/env bash
# Replanning around boxes found in flight repeats by seed, however loaded the machine: each
# scene with unknown boxes flies once on a quiet machine and once while busy processes keep
# every core occupied, and path.csv, trajectory.csv, telemetry.csv and every number of
# summary.json but wall times must match byte for byte; no search (the path's or a replan's)
# may report that the wall-time cap cut it.
# Usage: replan_determinism_test.sh AEROBOX_BINARY SOURCE_DIR
set -euo pipefail
aerobox=$1
top=$2
work=$(mktemp -d)
spinners=()
cleanup() {
  for pid in "${spinners[@]}"; do kill "$pid" 2> /dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT

# the forest with 30 % of its trees unknown: the most replans of the benchmark's maps
cat > "$work/forest_unknown.toml" << TOML
name = "forest_unknown"
map = "$top/scenes/forest/map.json"
unknown_fraction = 0.3
TOML

run() {  # run NAME SCENARIO SEED
  "$aerobox" fly "$2" --no-video --quiet --seed "$3" --out "$work/$1" > /dev/null ||
    [[ $? == 5 ]] # a flight that ends in contact is still a flight to compare
  grep -v -E '"(planning_time_s|trajectory_time_s|flight_wall_time_s|solve_time_s|latency_s)"' \
    "$work/$1/summary.json" > "$work/$1/summary.numbers"
  if grep -q '_capped": true' "$work/$1/summary.json"; then
    echo "FAIL: $1: a search was cut by the wall-time cap"
    exit 1
  fi
}
cases=("$top/scenes/maze_unknown/scenario.toml 4" "$top/scenes/maze_unknown/scenario.toml 9"
  "$work/forest_unknown.toml 7" "$work/forest_unknown.toml 3")
for i in "${!cases[@]}"; do
  read -r scenario seed <<< "${cases[$i]}"
  run "quiet$i" "$scenario" "$seed"
done
cores=$(nproc)
for ((k = 0; k < 2 * cores; ++k)); do
  (while :; do :; done) &
  spinners+=($!)
done
replans=0
for i in "${!cases[@]}"; do
  read -r scenario seed <<< "${cases[$i]}"
  run "busy$i" "$scenario" "$seed"
  for name in path.csv trajectory.csv telemetry.csv summary.numbers; do
    cmp "$work/quiet$i/$name" "$work/busy$i/$name" ||
      { echo "FAIL: $scenario seed $seed: $name differs under load"; exit 1; }
  done
  replans=$((replans + $(grep -c '"t_s"' "$work/quiet$i/summary.json" || true)))
done
if ((replans == 0)); then
  echo "FAIL: no flight replanned: the test tests nothing"
  exit 1
fi
echo "replanning: ${#cases[@]} flights, $replans replans, byte-identical with $((2 * cores)) busy processes on $cores cores"
