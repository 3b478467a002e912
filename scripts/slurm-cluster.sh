#!/usr/bin/env bash
# Starts or stops a one-node Slurm cluster on localhost whose whole state lives in DIR, for testing farm
# submission without a real cluster. Usage:
#   scripts/slurm-cluster.sh start DIR   # then: export SLURM_CONF=DIR/slurm.conf
#   scripts/slurm-cluster.sh stop DIR
# Needs slurmctld, slurmd and slurm-client (CLIPBLUR_SLURM=1 scripts/setup.sh installs them). Runs as root
# or as the invoking user (SlurmUser is whoever starts it). No munge: auth/none and cred/none.
# Environment: CLIPBLUR_SLURM_PORT (controller port, default 6817; slurmd uses the next one),
# CLIPBLUR_SLURM_WAIT (seconds to wait for the node to become idle, default 60).
set -euo pipefail

usage() { echo "usage: $0 start|stop DIR" >&2; exit 2; }
[ $# -eq 2 ] || usage
action=$1
dir=$(mkdir -p "$2" && cd "$2" && pwd)
conf=$dir/slurm.conf
export SLURM_CONF=$conf

print_logs() {
  for log in "$dir"/log/slurmctld.log "$dir"/log/slurmd.log; do
    echo "---- $log" >&2
    if [ -f "$log" ]; then tail -n 60 "$log" >&2; else echo "(missing)" >&2; fi
  done
}

write_conf() {
  local port=${CLIPBLUR_SLURM_PORT:-6817}
  local user cpus memory
  user=$(id -un)
  # slurmd -C reports what this machine has; declaring more makes slurmd drain the node.
  cpus=$(slurmd -C | sed -n 's/.*CPUs=\([0-9]*\).*/\1/p' | head -n1)
  memory=$(slurmd -C | sed -n 's/.*RealMemory=\([0-9]*\).*/\1/p' | head -n1)
  [ -n "$cpus" ] && [ -n "$memory" ] || { echo "slurm-cluster: cannot read slurmd -C" >&2; exit 1; }
  mkdir -p "$dir/state" "$dir/spool" "$dir/log" "$dir/run"
  cat >"$conf" <<EOF
ClusterName=clipblur
SlurmctldHost=localhost
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/none
CredType=cred/none
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/run/slurmctld.pid
SlurmdPidFile=$dir/run/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
DependencyParameters=kill_invalid_depend
MailProg=/bin/true
SwitchType=switch/none
MaxArraySize=100001
SlurmctldTimeout=30
SlurmdTimeout=60
InactiveLimit=0
MinJobAge=300
KillWait=5
Waittime=0
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$memory State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
}

node_state() { sinfo -h -N -o '%T' 2>/dev/null | head -n1; }

start() {
  if [ -f "$dir/run/slurmctld.pid" ] && kill -0 "$(cat "$dir/run/slurmctld.pid")" 2>/dev/null; then
    echo "slurm-cluster: already running in $dir" >&2
    exit 1
  fi
  write_conf
  # -i ignores state from a previous run so a stale node or job list cannot block this one.
  slurmctld -f "$conf" -i || { echo "slurm-cluster: slurmctld failed to start" >&2; print_logs; exit 1; }
  slurmd -f "$conf" -N localhost || { echo "slurm-cluster: slurmd failed to start" >&2; print_logs; stop_daemons; exit 1; }
  local wait=${CLIPBLUR_SLURM_WAIT:-60} state=""
  for ((i = 0; i < wait * 2; i++)); do
    state=$(node_state)
    case "$state" in
      idle) echo "slurm-cluster: node idle; export SLURM_CONF=$conf"; return 0 ;;
    esac
    sleep 0.5
  done
  echo "slurm-cluster: node did not become idle within ${wait}s (state: ${state:-none})" >&2
  scontrol -a show node localhost >&2 2>&1 || true
  print_logs
  stop_daemons
  exit 1
}

# Kills only the daemons whose pid files this cluster wrote, after asking politely.
stop_daemons() {
  scontrol shutdown >/dev/null 2>&1 || true
  for name in slurmctld slurmd; do
    local pidfile=$dir/run/$name.pid
    [ -f "$pidfile" ] || continue
    local pid
    pid=$(cat "$pidfile")
    for ((i = 0; i < 40; i++)); do
      kill -0 "$pid" 2>/dev/null || break
      sleep 0.25
    done
    if kill -0 "$pid" 2>/dev/null; then kill -TERM "$pid" 2>/dev/null || true; sleep 1; fi
    if kill -0 "$pid" 2>/dev/null; then kill -KILL "$pid" 2>/dev/null || true; fi
    rm -f "$pidfile"
  done
}

case "$action" in
  start) start ;;
  stop)
    [ -f "$conf" ] || { echo "slurm-cluster: no cluster in $dir" >&2; exit 1; }
    stop_daemons
    echo "slurm-cluster: stopped" ;;
  *) usage ;;
esac
