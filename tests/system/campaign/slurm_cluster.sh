#!/bin/bash
# A one-node Slurm cluster on localhost for the tests of jobs/campaigns/slurm_*.sh
# (real_slurm_test.sh): Debian's munge and slurm-wlm, every file in one folder, ports free now.
#
#   slurm_cluster.sh available           exit 0 if the commands are installed and this is root, else
#                                        says why not
#   slurm_cluster.sh start DIR OWNER_PID starts munged, slurmctld and slurmd with DIR/slurm.conf and
#                                        a guard that stops them when OWNER_PID ends (also when the
#                                        test is killed with SIGKILL and its traps never run)
#   slurm_cluster.sh stop DIR            stops the daemons and every process of the jobs
#
# The jobs and the daemons carry SLURM_CONF=DIR/slurm.conf in their environment: `stop` ends every
# process that has it (the job scripts, srun, the ranks, slurmstepd), each by its pid, and nothing
# else. Every wait is bounded.
set -u
commands=(munged mungekey slurmctld slurmd sbatch scontrol squeue scancel sinfo srun)

# The pids of the processes whose environment holds SLURM_CONF=$1, but for this script and its
# ancestors (the test that calls `stop` has it too).
cluster_processes() {
  local p mine=" $BASHPID " up=$$
  while [[ $up -gt 1 ]]; do
    mine+="$up "
    up=$(awk '/^PPid:/ {print $2}' "/proc/$up/status" 2> /dev/null) || break
  done
  # shellcheck disable=SC2013  # paths without blanks
  for p in $(grep -lzxF "SLURM_CONF=$1" /proc/[0-9]*/environ 2> /dev/null); do
    p=${p#/proc/} p=${p%/environ}
    [[ $mine == *" $p "* ]] || echo "$p"
  done
}

# Two TCP ports nothing listens on now (the kernel's choice).
free_ports() {
  /usr/bin/python3 - <<'PY'
import socket
held = [socket.socket() for _ in range(2)]
for s in held:
    s.bind(("127.0.0.1", 0))
print(" ".join(str(s.getsockname()[1]) for s in held))
PY
}

write_config() {  # DIR CTLD_PORT SLURMD_PORT
  local dir=$1 host
  host=$(hostname -s)
  # cred_expire: a requeued job waits this long before it may start again (default 120 s).
  # sched_interval: the main scheduler looks at pending jobs every second (a requeued job becomes
  # eligible by the clock, not by an event).
  cat > "$dir/slurm.conf" <<EOF
ClusterName=raceway-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$2
SlurmdPort=$3
SlurmUser=$(id -un)
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/munge.sock,cred_expire=10
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/pgid
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/builtin
SchedulerParameters=sched_interval=1
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
SlurmdParameters=config_overrides
KillWait=5
MinJobAge=600
MessageTimeout=20
NodeName=$host NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=main Nodes=$host Default=YES MaxTime=INFINITE State=UP
PartitionName=other Nodes=$host Default=NO MaxTime=INFINITE State=UP
EOF
}

start() {  # DIR OWNER_PID
  local dir=$1 owner=$2 ports
  mkdir -p "$dir/munge" "$dir/state" "$dir/spool" || return 1
  # munged refuses a socket in a folder that not everyone may enter (the test's scratch folder is
  # the parent).
  chmod 755 "$(dirname "$dir")" "$dir" "$dir/munge"
  ports=$(free_ports) || return 1
  # shellcheck disable=SC2086  # two words
  write_config "$dir" $ports
  export SLURM_CONF=$dir/slurm.conf
  mungekey --create --keyfile="$dir/munge/munge.key" || return 1
  setsid munged --foreground --socket="$dir/munge/munge.sock" --key-file="$dir/munge/munge.key" \
    --pid-file="$dir/munge/munged.pid" --log-file="$dir/munge/munged.log" --seed-file="$dir/munge/munged.seed" \
    < /dev/null > "$dir/munged.out" 2>&1 &
  echo $! > "$dir/pids"
  # The guard, in a session of its own: it outlives a test killed by ctest's timeout.
  env -u SLURM_CONF setsid "$0" guard "$dir" "$owner" < /dev/null > /dev/null 2>&1 &
  for _ in $(seq 1 100); do [[ -S "$dir/munge/munge.sock" ]] && break; sleep 0.1; done
  [[ -S "$dir/munge/munge.sock" ]] || { echo "munged did not start: $(cat "$dir/munged.out")"; return 1; }
  setsid slurmctld -D -i -f "$SLURM_CONF" < /dev/null > "$dir/slurmctld.out" 2>&1 &
  echo $! >> "$dir/pids"
  setsid slurmd -D -f "$SLURM_CONF" < /dev/null > "$dir/slurmd.out" 2>&1 &
  echo $! >> "$dir/pids"
  for _ in $(seq 1 300); do
    [[ $(timeout 10 sinfo -h -o %T 2> /dev/null) == idle ]] && return 0
    sleep 0.1
  done
  echo "the node did not become idle within 30 s: $(timeout 10 sinfo 2>&1)"
  tail -5 "$dir/slurmctld.log" "$dir/slurmd.log" 2>&1
  return 1
}

# Which of the pids are alive (a zombie, ended but not yet reaped by init, is not).
alive() {
  local p
  for p in "$@"; do
    [[ $(awk '/^State:/ {print $2}' "/proc/$p/status" 2> /dev/null) =~ ^[^Z] ]] && echo "$p"
  done
}

stop() {  # DIR
  local dir=$1 conf=$1/slurm.conf left
  [[ -f "$dir/pids" ]] || return 0
  # No scancel: the jobs' processes (slurmstepd, the job scripts, srun, the ranks) end with the
  # daemons.
  # slurmstepd outlives SIGTERM: SIGKILL after 2 s.
  # shellcheck disable=SC2046  # pids
  left=$(alive $(cluster_processes "$conf") $(cat "$dir/pids"))
  for signal in TERM KILL; do
    [[ -n $left ]] || break
    # shellcheck disable=SC2086
    kill -$signal $left 2> /dev/null
    for _ in $(seq 1 20); do
      # shellcheck disable=SC2086
      left=$(alive $left)
      [[ -n $left ]] || break
      sleep 0.1
    done
  done
  # What a dying step may still have started.
  # shellcheck disable=SC2046
  kill -KILL $(cluster_processes "$conf") 2> /dev/null
  rm -f "$dir/pids"
}

guard() {  # DIR OWNER_PID
  while kill -0 "$2" 2> /dev/null; do sleep 1; done
  stop "$1"
  rm -rf "$1"
}

case ${1:-} in
available)
  missing=()
  for c in "${commands[@]}"; do command -v "$c" > /dev/null || missing+=("$c"); done
  (( ${#missing[@]} == 0 )) || { echo "not installed: ${missing[*]} (Debian: apt-get install slurm-wlm munge)"; exit 1; }
  # slurmd starts each job as its user.
  [[ $(id -u) == 0 ]] || { echo "slurmd needs root, this is $(id -un)"; exit 1; }
  ;;
start) start "$2" "$3" ;;
stop) stop "$2" ;;
guard) guard "$2" "$3" ;;
*) echo "usage: slurm_cluster.sh available | start DIR OWNER_PID | stop DIR"; exit 2 ;;
esac
