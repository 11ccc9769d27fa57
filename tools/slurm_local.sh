#!/usr/bin/env bash
# A single-node Slurm cluster on this machine, for the sweep's tests and benchmark: munged,
# slurmctld and slurmd on localhost, with every file (key, slurm.conf, state, spool, logs, pid
# files) in one folder. Needs Debian's slurm-wlm and munge (tools/setup.sh), and root.
#
# Usage: tools/slurm_local.sh start DIR    starts the daemons; prints SLURM_CONF=DIR/slurm.conf
#        tools/slurm_local.sh stop DIR     stops them (by their pid files)
#        tools/slurm_local.sh logs DIR     prints their logs
# After start: export SLURM_CONF=DIR/slurm.conf, then sbatch, squeue and sinfo use it.
# When a daemon fails to start or dies right after, start prints the logs and the likely cause,
# stops the others and exits 1.
# SLURM_LOCAL_EXTRA_CONF: lines start appends to slurm.conf (a later setting overrides an earlier
# one), to try an option, or for tests to give the daemons a configuration they refuse.
set -euo pipefail

usage() { awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "$0" >&2; exit 2; }
[ $# -eq 2 ] || usage
action=$1
dir=$(realpath -m "$2")
# in start order, what each daemon printed before it detached (*.out), then its log
log_files=()
for name in munged slurmctld slurmd; do log_files+=("$dir/log/$name.out" "$dir/log/$name.log"); done

logs() {
  for log in "${log_files[@]}"; do
    [ -s "$log" ] || continue
    echo "----- $log (last 40 lines)"
    tail -n 40 "$log"
  done
}

alive() {  # alive PID_FILE: the pid in it runs (a zombie is a daemon that died, not one that runs)
  local pid state
  pid=$(cat "$1" 2>/dev/null) || return 1
  state=$(ps -o stat= -p "$pid" 2>/dev/null) || return 1
  [[ $state != Z* ]]
}

stop_pid_file() {  # stop_pid_file FILE NAME: SIGTERM, then SIGKILL after 10 s
  local file=$1 name=$2 pid
  [ -f "$file" ] || return 0
  pid=$(cat "$file" 2>/dev/null || true)
  if alive "$file"; then
    kill "$pid" 2>/dev/null || true
    # a daemon that exited stays a zombie until init reaps it (a second or two here): it stopped
    for _ in $(seq 100); do alive "$file" || break; sleep 0.1; done
    if alive "$file"; then
      echo "slurm_local: $name ($pid) did not stop: killing it" >&2
      kill -9 "$pid" 2>/dev/null || true
    fi
  fi
  rm -f "$file"
}

stop_all() {
  stop_pid_file "$dir/slurmd.pid" slurmd
  stop_pid_file "$dir/slurmctld.pid" slurmctld
  stop_pid_file "$dir/munge/munged.pid" munged
}

free_port() {
  /usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}

found() {  # found REGEX: the first log line matching REGEX, after its file's name
  local log line
  for log in "${log_files[@]}"; do
    line=$(grep -E -m1 -- "$1" "$log" 2>/dev/null) || continue
    echo "${log##*/}: $line"
    return 0
  done
  return 1
}

causes=0
cause() {  # cause EVIDENCE TEXT
  echo "slurm_local: likely cause: $2"
  echo "slurm_local:   $1"
  causes=$((causes + 1))
}

# Known log lines and what they mean; a fatal line is quoted whatever else matched, since it is
# what stopped the daemon, and is the cause when nothing else is known.
diagnose() {
  local line extra=${SLURM_LOCAL_EXTRA_CONF:+ (SLURM_LOCAL_EXTRA_CONF is at its end)}
  local host no_cgroup port munge resolve
  host=$(hostname -s)
  no_cgroup='No filesystem mounted on /sys/fs/cgroup|cgroup filesystem not mounted'
  no_cgroup+='|Unknown filesystem type mounted on /sys/fs/cgroup'
  port='Address already in use|Unable to bind listen port'
  munge='^munged: Error:|Error: |[Mm]unge (en|de)code failed|auth_g_|Failed to connect to "'
  resolve='Unable to resolve|getaddrinfo|Name or service not known|name resolution'
  resolve+='|Unable to determine this slurmd.s NodeName'
  if line=$(found "$no_cgroup"); then
    cause "$line" "no cgroup tree on /sys/fs/cgroup. Slurm 22.05's slurmd needs one even with\
 proctrack/linuxproc and task/none (CgroupPlugin=disabled came in a later release): mount one\
 (as root with CAP_SYS_ADMIN: mount -t cgroup2 none /sys/fs/cgroup), or give the container the\
 host's (docker run --privileged, or --cgroupns=host -v /sys/fs/cgroup:/sys/fs/cgroup:rw);\
 otherwise slurmd cannot run in this container"
  elif line=$(found 'Hybrid mode is not supported|Unable to initialize cgroup plugin'); then
    cause "$line" "slurmd's cgroup plugin cannot use the cgroup tree on /sys/fs/cgroup"
  fi
  if line=$(found "$port"); then
    cause "$line" "a port in slurm.conf (SlurmctldPort, SlurmdPort: free when start picked them)\
 is taken, by another cluster still running or a race; stop it or start again"
  fi
  if line=$(found "$munge"); then
    cause "$line" "munge: its key or socket ($dir/munge) is refused or unreachable,\
 or munged is not running"
  fi
  if line=$(found "$resolve"); then
    cause "$line" "the host name '$host' does not resolve or is not the node's name in\
 slurm.conf: add '127.0.0.1 $host' to /etc/hosts"
  fi
  if line=$(found '[Pp]ars(e|ing) error'); then
    cause "$line" "a line of slurm.conf does not parse$extra"
  fi
  if line=$(found 'fatal:'); then
    if [ "$causes" -eq 0 ]; then
      cause "$line" "${line%%.*} stopped on this fatal error, often a slurm.conf setting it\
 refuses$extra"
    else
      echo "slurm_local: the fatal line: $line"
    fi
  elif [ "$causes" -eq 0 ]; then
    echo "slurm_local: no known cause in the logs; their last error lines above tell"
  fi
}

fail() {  # fail MESSAGE: the logs and the likely cause; the EXIT trap stops the daemons
  echo "slurm_local: $1; the logs:" >&2
  logs >&2
  diagnose >&2
  exit 1
}

start_daemon() {  # start_daemon NAME PID_FILE COMMAND...: runs it and waits for the detached daemon
  local name=$1 pid_file=$2 status=0
  shift 2
  "$@" > "$dir/log/$name.out" 2>&1 || status=$?
  [ "$status" -eq 0 ] || fail "$name failed to start (exit status $status)"
  # the detached daemon writes its pid file; one that dies first never does
  for _ in $(seq 100); do
    if [ -s "$pid_file" ]; then
      alive "$pid_file" || fail "$name exited right after starting"
      return 0
    fi
    sleep 0.1
  done
  fail "$name wrote no pid file in 10 s: it exited right after starting"
}

check_running() {  # a daemon may die after its pid file is written, while the node comes up
  alive "$dir/munge/munged.pid" || fail "munged exited after starting"
  alive "$dir/slurmctld.pid" || fail "slurmctld exited after starting"
  alive "$dir/slurmd.pid" || fail "slurmd exited after starting"
}

write_conf() {  # write_conf HOST: slurm.conf for one node, HOST, on 127.0.0.1
  local host=$1
  cat > "$dir/slurm.conf" <<EOF
# generated by tools/slurm_local.sh: a single-node cluster on localhost
ClusterName=aerobox
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.sock
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
  if [ -n "${SLURM_LOCAL_EXTRA_CONF:-}" ]; then
    printf '# from SLURM_LOCAL_EXTRA_CONF\n%s\n' "$SLURM_LOCAL_EXTRA_CONF" >> "$dir/slurm.conf"
  fi
}

start() {
  [ "$(id -u)" -eq 0 ] || { echo "slurm_local: the daemons run as root here (SlurmUser=root)" >&2; exit 1; }
  for tool in mungekey munged slurmctld slurmd sinfo; do
    command -v "$tool" > /dev/null || { echo "slurm_local: $tool is missing: run tools/setup.sh" >&2; exit 1; }
  done
  stop_all  # daemons of an earlier run in this folder
  rm -rf "$dir/state" "$dir/spool" "$dir/log"
  mkdir -p "$dir/munge" "$dir/state" "$dir/spool" "$dir/log"
  chmod 700 "$dir/munge"
  # however start ends short of an idle node, it leaves no daemon behind
  trap stop_all EXIT
  mungekey --create --keyfile="$dir/munge/munge.key" --force
  # the origin given, munged does not look up the host name, whose failure (a container without
  # its name in /etc/hosts) printed 'Failed to lookup origin' and looked like the cause of others
  start_daemon munged "$dir/munge/munged.pid" \
    munged --key-file="$dir/munge/munge.key" --socket="$dir/munge/munge.sock" \
    --pid-file="$dir/munge/munged.pid" --log-file="$dir/log/munged.log" \
    --seed-file="$dir/munge/munged.seed" --origin=127.0.0.1 --force
  write_conf "$(hostname -s)"
  export SLURM_CONF="$dir/slurm.conf"
  start_daemon slurmctld "$dir/slurmctld.pid" slurmctld -f "$SLURM_CONF"
  start_daemon slurmd "$dir/slurmd.pid" slurmd -f "$SLURM_CONF"
  local state=
  for _ in $(seq 300); do
    check_running
    state=$(sinfo -h -o %t 2>/dev/null || true)
    if [ "$state" = "idle" ]; then
      trap - EXIT
      echo "SLURM_CONF=$SLURM_CONF"
      exit 0
    fi
    sleep 0.1
  done
  fail "the node is not idle after 30 s (sinfo: '${state:-nothing}')"
}

case "$action" in
  logs) logs ;;
  stop) stop_all ;;
  start) start ;;
  *) usage ;;
esac
