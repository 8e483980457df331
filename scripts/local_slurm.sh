#!/usr/bin/env bash
# A one-node Slurm cluster on this machine, for trying the workflow's Slurm profile
# (workflow/profiles/slurm, docs/pipeline.md) and for its test: MUNGE and the Slurm controller
# and node daemons of Debian's slurm-wlm and munge, all kept in one folder (its own key, socket,
# ports, state and logs; nothing of the system's configuration is touched).
#
#   scripts/local_slurm.sh start FOLDER     # prints `export SLURM_CONF=FOLDER/slurm.conf`
#   export SLURM_CONF=FOLDER/slurm.conf     # then sbatch, squeue, snakemake --profile ... use it
#   scripts/local_slurm.sh stop FOLDER      # stops the daemons (the folder is left)
#
# FOLDER is a new or empty folder, inside folders that all may enter (MUNGE's socket is there).
# The daemons run as the calling user, which must be root (Slurm's node daemon starts jobs as their
# users). The node has this machine's cores and its memory less 1 GiB; the ports are two free ones
# above 20000. Exit 77 where a program is missing or the user is not root.
set -euo pipefail

usage() { echo "usage: $0 start|stop FOLDER" >&2; exit 2; }
[[ $# -eq 2 ]] || usage
action=$1
folder=$2

stop() {
  if [[ -f "$folder/slurm.conf" ]]; then
    SLURM_CONF="$folder/slurm.conf" scontrol shutdown > /dev/null 2>&1 || true
  fi
  for daemon in slurmd slurmctld munged; do
    if [[ -f "$folder/$daemon.pid" ]]; then
      kill "$(cat "$folder/$daemon.pid")" 2> /dev/null || true
    fi
  done
  # scontrol shutdown returns at once: wait (10 s at most) until the daemons are gone.
  for _ in $(seq 50); do
    alive=0
    for daemon in slurmd slurmctld munged; do
      [[ -f "$folder/$daemon.pid" ]] && kill -0 "$(cat "$folder/$daemon.pid")" 2> /dev/null && alive=1
    done
    [[ $alive == 0 ]] && return 0
    sleep 0.2
  done
  echo "local_slurm.sh: a daemon of $folder did not stop" >&2
  return 1
}

case "$action" in
  stop) stop; exit ;;
  start) ;;
  *) usage ;;
esac

for program in munged mungekey slurmctld slurmd sbatch scontrol sinfo; do
  if ! command -v "$program" > /dev/null && [[ ! -x "/usr/sbin/$program" ]]; then
    echo "local_slurm.sh: $program is not installed (Debian: apt-get install slurm-wlm munge)" >&2
    exit 77
  fi
done
export PATH="$PATH:/usr/sbin"
if [[ "$(id -u)" != 0 ]]; then
  echo "local_slurm.sh: the node daemon runs jobs as their users: start it as root" >&2
  exit 77
fi
if [[ -e "$folder" && -n "$(ls -A "$folder")" ]]; then
  echo "local_slurm.sh: $folder is not empty; give a new folder" >&2
  exit 1
fi
mkdir -p "$folder/state" "$folder/spool"
folder=$(cd "$folder" && pwd)
# MUNGE wants every folder above its socket open to all (execute permission).
chmod go+x "$folder"

mungekey -c -k "$folder/munge.key" > /dev/null
chmod 600 "$folder/munge.key"
munged --key-file="$folder/munge.key" --socket="$folder/munge.socket" \
  --pid-file="$folder/munged.pid" --log-file="$folder/munged.log" --seed-file="$folder/munged.seed"

read -r port_ctld port_d < <(/usr/bin/python3 - <<'EOF'
import random
import socket
ports = []
while len(ports) < 2:
    port = random.randint(20000, 60000)
    with socket.socket() as s:
        try:
            s.bind(("", port))
        except OSError:
            continue
    if port not in ports:
        ports.append(port)
print(*ports)
EOF
)
host=$(hostname)
memory=$(( $(awk '/MemTotal/ {print $2}' /proc/meminfo) / 1024 - 1024 ))
cat > "$folder/slurm.conf" <<EOF
# A one-node cluster on $host for sffcal's workflow (scripts/local_slurm.sh).
ClusterName=sffcal
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$folder/munge.socket
CredType=cred/munge
SlurmctldPort=$port_ctld
SlurmdPort=$port_d
StateSaveLocation=$folder/state
SlurmdSpoolDir=$folder/spool
SlurmctldPidFile=$folder/slurmctld.pid
SlurmdPidFile=$folder/slurmd.pid
SlurmctldLogFile=$folder/slurmctld.log
SlurmdLogFile=$folder/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
MpiDefault=none
ReturnToService=2
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
NodeName=$host CPUs=$(nproc) RealMemory=$memory State=UNKNOWN
PartitionName=local Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF="$folder/slurm.conf"
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF"
# Ready when the node is idle (10 s at most).
for _ in $(seq 50); do
  if [[ "$(sinfo -h -o %t 2> /dev/null)" == idle ]]; then
    echo "export SLURM_CONF=$SLURM_CONF"
    exit 0
  fi
  sleep 0.2
done
echo "local_slurm.sh: the node did not come up; logs in $folder" >&2
stop
exit 1
