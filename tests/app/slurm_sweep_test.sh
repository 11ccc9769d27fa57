#!/usr/bin/env bash
# A real Slurm: a single-node cluster on localhost (tools/slurm_local.sh, its files in the build
# folder), a 4-task array sweep submitted through the script `aerobox sweep slurm` writes, its
# merge job waited for, and every run's result equal to the same run done locally (all but wall
# times and the host). When the daemons cannot start, the test fails with their logs.
# Usage: slurm_sweep_test.sh AEROBOX_BINARY SOURCE_DIR CLUSTER_DIR
set -euo pipefail
aerobox=$1
top=$2
cluster=$3
work=$(mktemp -d)
fail() { echo "FAIL: $*"; "$top/tools/slurm_local.sh" logs "$cluster" || true; exit 1; }
trap '"$top/tools/slurm_local.sh" stop "$cluster"; rm -rf "$work"' EXIT

"$top/tools/slurm_local.sh" start "$cluster"
export SLURM_CONF=$cluster/slurm.conf

cat > "$work/speeds.toml" <<TOML
scenarios = ["$top/scenes/window/scenario.toml"]
seeds = 4
[grid]
"trajectory.max_speed" = [2.0, 4.0]
TOML
"$aerobox" sweep "$work/speeds.toml" --out "$work/local" -j 2 --quiet > /dev/null
"$aerobox" sweep slurm "$work/speeds.toml" --array 4 --cpus 1 --out "$work/slurm" --submit --wait \
  > "$work/submit.out" || fail "submission: $(cat "$work/submit.out")"
cat "$work/submit.out"
[ -x "$work/slurm/sweep.sbatch" ] || fail "no sweep.sbatch"
grep -q '^#SBATCH --array=0-3$' "$work/slurm/sweep.sbatch" || fail "not a 4-task array"
for task in 0 1 2 3; do
  [ -s "$work/slurm/results.shard-$task-of-4.jsonl" ] || fail "task $task wrote no results"
done
[ "$(ls "$work"/slurm/logs/task-*.log | wc -l)" -eq 4 ] || fail "4 task logs expected"
grep -q "merge: 8 of 8 runs" "$work"/slurm/logs/merge-*.log || fail "merge: $(cat "$work"/slurm/logs/merge-*.log)"
/usr/bin/python3 "$top/tests/app/sweep_results_equal.py" "$work/local/results.jsonl" \
  "$work/slurm/results.jsonl" || fail "Slurm's results differ from the local ones"
cmp "$work/local/report.md" "$work/slurm/report.md" || fail "the reports differ"
# the queue is empty again
[ -z "$(squeue -h)" ] || fail "jobs left in the queue: $(squeue)"
echo "slurm sweep: ok"
