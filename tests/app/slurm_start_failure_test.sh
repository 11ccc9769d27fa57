#!/usr/bin/env bash
# A Slurm cluster that cannot start says why: tools/slurm_local.sh start, given a slurm.conf line
# slurmd refuses and slurmctld accepts (its spool folder under /dev/null), exits non-zero, prints
# slurmd's log with its fatal line, names a likely cause, and leaves no daemon running.
# Usage: slurm_start_failure_test.sh SOURCE_DIR CLUSTER_DIR
set -euo pipefail
top=$1
cluster=$(realpath -m "$2")
work=$(mktemp -d)
fail() { echo "FAIL: $*"; echo "----- start's stderr:"; cat "$work/stderr"; exit 1; }
trap '"$top/tools/slurm_local.sh" stop "$cluster"; rm -rf "$work"' EXIT

status=0
SLURM_LOCAL_EXTRA_CONF='SlurmdSpoolDir=/dev/null/spool' \
  "$top/tools/slurm_local.sh" start "$cluster" > "$work/stdout" 2> "$work/stderr" || status=$?
[ "$status" -ne 0 ] || fail "start succeeded with a configuration slurmd refuses"
grep -q '^SLURM_CONF=' "$work/stdout" && fail "start printed SLURM_CONF, the cluster not up"
grep -q '^slurm_local: slurmd ' "$work/stderr" || fail "no 'slurm_local: slurmd ...' message"
grep -q "^----- .*/slurmd\.log" "$work/stderr" || fail "slurmd's log is not printed"
grep -q '\] fatal: mkdir(/dev/null/spool)' "$work/stderr" || fail "slurmd's fatal line is not shown"
grep -q '^slurm_local: likely cause: slurmd .*SLURM_LOCAL_EXTRA_CONF' "$work/stderr" \
  || fail "no likely cause named"
grep -q '^slurm_local: .*slurmd\.log: .*fatal: mkdir(/dev/null/spool)' "$work/stderr" \
  || fail "the fatal line is not quoted beside the cause"

# nothing left running: no pid file, and no process of this cluster's (its files are in the
# command lines of all three daemons)
for pid_file in "$cluster/munge/munged.pid" "$cluster/slurmctld.pid" "$cluster/slurmd.pid"; do
  [ ! -e "$pid_file" ] || fail "$pid_file left behind"
done
if left=$(pgrep -a -f -- "$cluster/(slurm\.conf|munge/)"); then
  fail "daemons left running: $left"
fi
echo "slurm start failure: ok"
