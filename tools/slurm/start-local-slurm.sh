#!/usr/bin/env bash
# A single-node Slurm on this machine, for tests (tests/slurm/slurm_test.sh) and trying the job
# script (docs/slurm.md): munged, slurmctld and slurmd as root, without systemd and without
# cgroups, every file in one folder.
#
#   tools/slurm/start-local-slurm.sh [DIR]     # prints DIR; then: . DIR/env.sh; sbatch ...
#   tools/slurm/stop-local-slurm.sh DIR        # stops the three daemons and removes DIR
#
# DIR (default: a new mktemp -d folder) gets:
#   munge/       munge.key (mungekey), munged's socket, pid, log and seed file
#   slurm.conf   one node, this machine's name and CPUs, NodeAddr 127.0.0.1, one partition `debug`;
#                ProctrackType=proctrack/linuxproc, TaskPlugin=task/none, select/cons_tres with
#                CR_CPU, no accounting database (jobcomp/filetxt writes DIR/jobcomp.txt: one line
#                per finished job with its state and exit code), ports chosen free on 127.0.0.1
#   state/ spool/ log/ run/   slurmctld's state, slurmd's spool, the daemons' logs and pid files
#   env.sh       `export SLURM_CONF=DIR/slurm.conf` for sbatch, srun, squeue, scancel, sinfo
#   node         the node's name
# Returns when `sinfo` shows the node idle (exit 0), or stops what it started, prints the logs'
# last lines and exits 1. Exit 77 (skip) when slurmctld, slurmd, munged or mungekey is missing or
# not run as root. Everything talks over 127.0.0.1.
# Environment: CRASHLINK_SLURM_CPUS (the node's CPUs, default `nproc`), CRASHLINK_SLURM_WAIT_S
# (how long to wait for the idle node, default 90).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
for p in munged mungekey slurmctld slurmd sinfo scontrol; do
  if ! command -v "$p" >/dev/null 2>&1 && [ ! -x "/usr/sbin/$p" ]; then
    echo "start-local-slurm: $p not found (Debian: apt-get install slurmctld slurmd slurm-client munge;" \
      "tools/install-deps.sh installs them)" >&2
    exit 77
  fi
done
if [ "$(id -u)" -ne 0 ]; then
  echo "start-local-slurm: must run as root (slurmd starts jobs as their users; munged's key)" >&2
  exit 77
fi
PATH="$PATH:/usr/sbin:/sbin"

dir="${1:-}"
if [ -z "$dir" ]; then
  dir="$(mktemp -d "${TMPDIR:-/tmp}/crashlink-slurm.XXXXXX")"
else
  mkdir -p "$dir"
fi
dir="$(cd "$dir" && pwd)"
chmod 0755 "$dir"
mkdir -p "$dir/munge" "$dir/state" "$dir/spool" "$dir/log" "$dir/run" "$dir/tmp"
chmod 0700 "$dir/munge" "$dir/state"
chmod 1777 "$dir/tmp"
sock="$dir/munge/munge.socket"
if [ "${#sock}" -gt 100 ]; then
  echo "start-local-slurm: $sock is too long for a Unix socket; use a shorter DIR" >&2
  exit 1
fi

fail() {
  echo "start-local-slurm: $*" >&2
  for f in "$dir/munge/munged.log" "$dir/log/slurmctld.log" "$dir/log/slurmd.log"; do
    [ -f "$f" ] && { echo "--- last lines of $f" >&2; tail -n 15 "$f" >&2; }
  done
  "$here/stop-local-slurm.sh" --keep "$dir" >&2 || true
  exit 1
}

# munge: a key of our own and a socket in DIR
mungekey --create --keyfile="$dir/munge/munge.key" --force >/dev/null
chmod 0600 "$dir/munge/munge.key"
munged --force --socket="$sock" --key-file="$dir/munge/munge.key" \
  --pid-file="$dir/munge/munged.pid" --log-file="$dir/munge/munged.log" \
  --seed-file="$dir/munge/munged.seed" ||
  fail "munged did not start"
for _ in $(seq 50); do [ -S "$sock" ] && break; sleep 0.1; done
[ -S "$sock" ] || fail "munged's socket $sock did not appear"

# two free tcp ports on 127.0.0.1 (slurmctld, slurmd)
read -r ctld_port slurmd_port < <(/usr/bin/python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*[x.getsockname()[1] for x in s])')

node="$(hostname -s)"
cpus="${CRASHLINK_SLURM_CPUS:-$(nproc)}"
mem_mb=$(( $(awk '/^MemTotal:/ {print $2}' /proc/meminfo) / 1024 * 9 / 10 ))
: >"$dir/plugstack.conf"
cat >"$dir/slurm.conf" <<EOF
# Written by tools/slurm/start-local-slurm.sh: a single-node Slurm for tests, in $dir.
ClusterName=crashlinktest
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$sock
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool/slurmd-%n
SlurmctldPidFile=$dir/run/slurmctld.pid
SlurmdPidFile=$dir/run/slurmd-%n.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
TmpFS=$dir/tmp
PlugStackConfig=$dir/plugstack.conf
MailProg=/bin/true
# no cgroups, no systemd: processes tracked through their parents, no binding
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$dir/jobcomp.txt
MpiDefault=none
SwitchType=switch/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SlurmdParameters=config_overrides
ReturnToService=2
# a cancelled job's processes get SIGTERM, then SIGKILL KillWait seconds later
KillWait=30
MinJobAge=600
MessageTimeout=30
SlurmctldTimeout=60
SlurmdTimeout=120
InactiveLimit=0
NodeName=$node NodeAddr=127.0.0.1 NodeHostname=$node CPUs=$cpus RealMemory=$mem_mb State=UNKNOWN
PartitionName=debug Nodes=$node Default=YES MaxTime=INFINITE State=UP OverSubscribe=NO
EOF
echo "export SLURM_CONF=$dir/slurm.conf" >"$dir/env.sh"
echo "$node" >"$dir/node"
export SLURM_CONF="$dir/slurm.conf"

slurmctld -f "$dir/slurm.conf" -i || fail "slurmctld did not start"
slurmd -f "$dir/slurm.conf" -N "$node" || fail "slurmd did not start"

wait_s="${CRASHLINK_SLURM_WAIT_S:-90}"
state=""
for _ in $(seq $((wait_s * 2))); do
  state="$(sinfo -h -n "$node" -o '%t' 2>/dev/null || true)"
  case "$state" in idle) break ;; esac
  sleep 0.5
done
[ "$state" = idle ] || fail "node $node not idle after ${wait_s} s (sinfo: '${state:-no answer}')"
echo "$dir"
