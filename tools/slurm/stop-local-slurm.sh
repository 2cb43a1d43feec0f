#!/usr/bin/env bash
# Stops the single-node Slurm of tools/slurm/start-local-slurm.sh and removes its folder.
#
#   tools/slurm/stop-local-slurm.sh [--keep] DIR
#
# Cancels the jobs left (scancel: SIGTERM to their processes) and waits up to 10 s for them; then
# SIGKILL to whatever of them is left: slurmstepd and job processes whose environment names
# SLURM_CONF=DIR/slurm.conf. Then stops slurmd, slurmctld and munged by the pids in DIR's pid
# files (SIGTERM, SIGKILL 10 s later) and removes DIR (--keep: leaves it, e.g. to read its logs).
# Nothing is found by name alone. Exit 0 when none of it runs any more, 1 otherwise.
set -uo pipefail
keep=0
if [ "${1:-}" = --keep ]; then keep=1; shift; fi
dir="${1:?usage: stop-local-slurm.sh [--keep] DIR}"
[ -d "$dir" ] || { echo "stop-local-slurm: $dir is not a folder" >&2; exit 1; }
dir="$(cd "$dir" && pwd)"
[ -f "$dir/slurm.conf" ] || [ -d "$dir/munge" ] ||
  { echo "stop-local-slurm: $dir is not a folder of start-local-slurm.sh" >&2; exit 1; }
PATH="$PATH:/usr/sbin:/sbin"
export SLURM_CONF="$dir/slurm.conf"

# the jobs first (their processes get SIGTERM as scancel gives it)
if [ -f "$dir/slurm.conf" ] && [ -f "$dir/run/slurmctld.pid" ]; then
  timeout 10 scancel --quiet --user=root >/dev/null 2>&1 || true
fi

alive() { [ -n "$1" ] && kill -0 "$1" 2>/dev/null; }
pid_of() { [ -f "$1" ] && tr -dc '0-9' <"$1" || true; }

# this Slurm's leftovers: slurmstepd processes and job processes (SLURM_JOB_ID set) whose
# environment has SLURM_CONF=DIR/slurm.conf (slurmd passes its environment on to slurmstepd, and
# sbatch the submitter's to the job); nothing else is matched
job_pids() {
  local p env
  for p in /proc/[0-9]*; do
    p="${p#/proc/}"
    [ "$p" = "$$" ] && continue
    env="$(tr '\0' '\n' 2>/dev/null <"/proc/$p/environ")" || continue
    grep -qxF "SLURM_CONF=$dir/slurm.conf" <<<"$env" || continue
    if grep -q '^SLURM_JOB_ID=' <<<"$env" ||
       tr '\0' ' ' 2>/dev/null <"/proc/$p/cmdline" | grep -q '^slurmstepd'; then
      echo "$p"
    fi
  done
}

stop_pid() {  # NAME PID
  local name="$1" pid="$2"
  alive "$pid" || return 0
  kill -TERM "$pid" 2>/dev/null || true
  for _ in $(seq 100); do alive "$pid" || return 0; sleep 0.1; done
  echo "stop-local-slurm: $name ($pid) still running after 10 s: SIGKILL" >&2
  kill -KILL "$pid" 2>/dev/null || true
  sleep 0.2
}

pids=()
for f in "$dir"/run/slurmd-*.pid; do [ -f "$f" ] && pids+=("slurmd:$(pid_of "$f")"); done
pids+=("slurmctld:$(pid_of "$dir/run/slurmctld.pid")")
pids+=("munged:$(pid_of "$dir/munge/munged.pid")")
# wait for the jobs' processes to end (scancel's SIGTERM) before stopping slurmd, then SIGKILL
for _ in $(seq 100); do [ -z "$(job_pids)" ] && break; sleep 0.1; done
leftover="$(job_pids)"
if [ -n "$leftover" ]; then
  # shellcheck disable=SC2086  # one pid a word
  echo "stop-local-slurm: job processes still running 10 s after scancel, SIGKILL:" $leftover >&2
  # shellcheck disable=SC2086
  kill -KILL $leftover 2>/dev/null || true
fi
# slurmd and slurmctld together (each takes 1-2 s to save its state and go), munged last
for np in "${pids[@]}"; do
  case "$np" in munged:*) ;; *) kill -TERM "${np#*:}" 2>/dev/null || true ;; esac
done
for np in "${pids[@]}"; do stop_pid "${np%%:*}" "${np#*:}"; done

left=0
for np in "${pids[@]}"; do
  if alive "${np#*:}"; then echo "stop-local-slurm: ${np%%:*} (${np#*:}) is still running" >&2; left=1; fi
done
if [ "$keep" -eq 0 ] && [ "$left" -eq 0 ]; then
  rm -rf "$dir"
fi
exit "$left"
