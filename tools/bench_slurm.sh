#!/usr/bin/env bash
# The sweep benchmark through Slurm: the 100-run sweep of `aerobox bench --sections sweep` (the
# window, 20 seeds x 5 speed limits, no video) run locally with -j 2, then as a 2-task job array
# (1 CPU each) on a single-node cluster started on this machine (tools/slurm_local.sh), merge
# included; prints both wall times, their ratio and the scheduler's overhead.
# Usage: tools/bench_slurm.sh [BUILD_DIR]   (default: build; needs root and slurm-wlm, munge)
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
build=$(realpath "${1:-$top/build}")
aerobox=$build/aerobox
[ -x "$aerobox" ] || { echo "bench_slurm: $aerobox is missing: run tools/build.sh" >&2; exit 2; }
work=$(mktemp -d)
cluster=$work/cluster
trap '"$top/tools/slurm_local.sh" stop "$cluster"; rm -rf "$work"' EXIT
"$top/tools/slurm_local.sh" start "$cluster" > /dev/null
export SLURM_CONF=$cluster/slurm.conf
cat > "$work/speeds.toml" <<TOML
scenarios = ["$top/scenes/window/scenario.toml"]
seeds = 20
[grid]
"trajectory.max_speed" = [1.0, 2.0, 3.0, 4.0, 5.0]
TOML
begin=$EPOCHREALTIME
"$aerobox" sweep "$work/speeds.toml" --out "$work/local" -j 2 --quiet > /dev/null
local_s=$(/usr/bin/python3 -c "print($EPOCHREALTIME - $begin)")
begin=$EPOCHREALTIME
"$aerobox" sweep slurm "$work/speeds.toml" --array 2 --cpus 1 --out "$work/slurm" --submit --wait \
  > /dev/null
slurm_s=$(/usr/bin/python3 -c "print($EPOCHREALTIME - $begin)")
/usr/bin/python3 "$top/tests/app/sweep_results_equal.py" "$work/local/results.jsonl" \
  "$work/slurm/results.jsonl" > /dev/null
runs=$(wc -l < "$work/slurm/results.jsonl")
/usr/bin/python3 - "$local_s" "$slurm_s" "$runs" <<'PY'
import sys
local, slurm, runs = float(sys.argv[1]), float(sys.argv[2]), int(sys.argv[3])
print("| how | wall time [s] | runs per second |")
print("|---|---|---|")
print(f"| local, -j 2 | {local:.2f} | {runs / local:.2f} |")
print(f"| Slurm, a 2-task array (1 CPU each) and its merge job | {slurm:.2f} | {runs / slurm:.2f} |")
print()
print(f"Slurm's throughput against local -j 2: {local / slurm:.2f}x; the scheduler's overhead "
      f"(submission, start of the tasks, the merge job): {slurm - local:.1f} s for {runs} runs; "
      "the results are the same run for run")
PY
