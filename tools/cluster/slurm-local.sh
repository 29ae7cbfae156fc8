#!/usr/bin/env bash
# A throw-away single-node Slurm cluster on this machine, for tests and for trying
# tools/cluster/tile-slurm.sh: munged, slurmctld and slurmd run as the current user with every file
# (config, key, sockets, state, logs) under STATE_DIR, on two free local ports; nothing in
# /etc is read or changed. Needs Debian's slurm-wlm and munge (tools/setup installs them).
# usage: tools/cluster/slurm-local.sh start STATE_DIR    then: export SLURM_CONF=STATE_DIR/slurm.conf
#        tools/cluster/slurm-local.sh stop STATE_DIR     (stops the daemons; STATE_DIR is kept)
set -euo pipefail
if [ $# -ne 2 ] || { [ "$1" != start ] && [ "$1" != stop ]; }; then
  sed -n '6,7p' "$0" >&2
  exit 2
fi
dir=$(realpath -m "$2")

# Stops one daemon by its pid file and waits for it to go (SIGKILL after 10 s).
stop_daemon() {
  local pidfile=$1 pid
  [ -s "$pidfile" ] || return 0
  pid=$(cat "$pidfile")
  kill "$pid" 2>/dev/null || { rm -f "$pidfile"; return 0; }
  for _ in $(seq 100); do
    kill -0 "$pid" 2>/dev/null || { rm -f "$pidfile"; return 0; }
    sleep 0.1
  done
  kill -9 "$pid" 2>/dev/null || true
  rm -f "$pidfile"
}

if [ "$1" = stop ]; then
  stop_daemon "$dir/slurmd.pid"
  stop_daemon "$dir/slurmctld.pid"
  stop_daemon "$dir/munged.pid"
  exit 0
fi

for tool in munged slurmctld slurmd sinfo; do
  command -v "$tool" >/dev/null || {
    echo "slurm-local.sh: $tool is not installed (apt-get install slurm-wlm munge)" >&2
    exit 3
  }
done

# A TCP port nobody listens on, from the ephemeral range, for slurmctld and slurmd.
free_port() {
  local port
  for _ in $(seq 50); do
    port=$((20000 + RANDOM % 30000))
    if ! (echo >"/dev/tcp/127.0.0.1/$port") 2>/dev/null; then
      echo "$port"
      return
    fi
  done
  echo "slurm-local.sh: no free port found" >&2
  exit 1
}

mkdir -p "$dir"/{state,spool,munge}
chmod 700 "$dir" "$dir/munge"
user=$(id -un)
host=$(hostname -s)
cpus=$(nproc)
# slurmd refuses a node that claims more memory than it has: ask for 90 % of MemTotal.
mem_mib=$(awk '/^MemTotal:/ { print int($2 / 1024 * 0.9) }' /proc/meminfo)
ctld_port=$(free_port)
slurmd_port=$(free_port)
while [ "$slurmd_port" = "$ctld_port" ]; do slurmd_port=$(free_port); done

head -c 1024 /dev/urandom >"$dir/munge/munge.key"
chmod 400 "$dir/munge/munge.key"
munged --force --key-file="$dir/munge/munge.key" --socket="$dir/munge/munge.socket" \
  --pid-file="$dir/munged.pid" --log-file="$dir/munged.log" --seed-file="$dir/munge/seed"

cat >"$dir/slurm.conf" <<EOF
# Written by tools/cluster/slurm-local.sh: one node, this machine, no cgroups, no accounting.
ClusterName=decimate-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/munge.socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
ReturnToService=2
MailProg=/bin/true
PlugStackConfig=$dir/plugstack.conf
MinJobAge=30
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem_mib State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP DefMemPerCPU=$((mem_mib / cpus))
EOF
: >"$dir/plugstack.conf"

slurmctld -f "$dir/slurm.conf" -i
slurmd -f "$dir/slurm.conf"

# Ready when the node is idle (slurmd registered with slurmctld); 30 s at most.
export SLURM_CONF=$dir/slurm.conf
for _ in $(seq 150); do
  state=$(sinfo -h -n "$host" -o %t 2>/dev/null || true)
  if [ "$state" = idle ]; then
    echo "slurm-local.sh: node $host idle ($cpus CPUs, $mem_mib MiB); export SLURM_CONF=$dir/slurm.conf" >&2
    exit 0
  fi
  sleep 0.2
done
echo "slurm-local.sh: the node did not come up (state '${state:-none}'); logs in $dir:" >&2
tail -n 5 "$dir"/slurmctld.log "$dir"/slurmd.log "$dir"/munged.log >&2 || true
exit 1
