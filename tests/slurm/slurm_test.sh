#!/usr/bin/env bash
# The Slurm test (docs/slurm.md): the job script tools/slurm/crashlink.sbatch on a single-node
# Slurm that this test starts (tools/slurm/start-local-slurm.sh) and stops again.
#
#   tests/slurm/slurm_test.sh BUILD_DIR [WORK_DIR]      (WORK_DIR default: BUILD_DIR/slurm-test)
#
# 1. starts munged, slurmctld and slurmd in a temporary folder (the node with 4 CPUs on any
#    machine, so that two tasks of 2 CPUs fit: each daemon then runs 2 threads);
# 2. runs the CI scene (scenarios/head_impact_small.yaml) on this machine with
#    `crashlink run --mode multi` (ipc, shared-memory lanes);
# 3. submits the same scene twice with sbatch and the job script and waits for each:
#    A  --ntasks=2 --cpus-per-task=1: tcp on 127.0.0.1, lanes daemon to daemon, --threads 1;
#    B  --ntasks=2 --cpus-per-task=2 and --curve: CURVE keys made by the job (`crashlink keygen`),
#       the vectors through the coordinator, --threads 2 (taken from SLURM_CPUS_PER_TASK);
#    each job must exit 0 with every piece 0, each daemon must have run with the job's CPUs per
#    task as threads (/timing/<domain> of its file), and each gathered result.h5 must equal the
#    local one to the bit (tests/docker/compare_results.py, tolerance 0);
# 4. stops a longer run (the scene with end_time 1 s) once both daemons compute, three ways:
#    `scancel JOB` (SIGTERM to every process of the job, as a user cancels: job CANCELLED),
#    `scancel --signal=TERM JOB` (the job steps only: job FAILED with exit code 7), and
#    `scancel --batch --signal=TERM JOB` (the job script only, which passes it on to its steps);
#    every piece (coordinator, wiper, body) must have exited 7 (DIR/slurm/exit-codes, written by
#    the job script from what each task recorded), the job script 7 (Slurm's ExitCode 7:0), gather
#    0, and none of the pieces' processes may be left;
# 5. stops Slurm (always: trap) and removes its folder; no slurm or munge daemon is left.
#
# Exit 0 passed, 1 failed, 77 skipped (not root, or no slurmctld / slurmd / munged / sbatch:
# `apt-get install slurmctld slurmd slurm-client munge`, as tools/install-deps.sh does). Prints
# `[measured]` lines with the time of each step.
set -euo pipefail
SKIP=77
skip() { echo "SKIPPED: $*"; exit "$SKIP"; }
fail() { echo "FAILED: $*"; exit 1; }
here="$(cd "$(dirname "$0")" && pwd)"
src="$(cd "$here/../.." && pwd)"
build="${1:?usage: slurm_test.sh BUILD_DIR [WORK_DIR]}"
build="$(cd "$build" && pwd)"
work="${2:-$build/slurm-test}"
apps="$build/apps"
scenario="$src/scenarios/head_impact_small.yaml"
job_script="$src/tools/slurm/crashlink.sbatch"
PATH="$PATH:/usr/sbin:/sbin"

[ "$(id -u)" -eq 0 ] || skip "the local Slurm needs root (munged, slurmd)"
for p in munged mungekey slurmctld slurmd sbatch srun scancel scontrol sinfo; do
  command -v "$p" >/dev/null ||
    skip "$p not found (apt-get install slurmctld slurmd slurm-client munge; tools/install-deps.sh)"
done
for p in crashlink crashlink-coordinator crashlink-solver; do
  [ -x "$apps/$p" ] || fail "$apps/$p missing (build first)"
done
/usr/bin/python3 -c 'import h5py' 2>/dev/null || fail "/usr/bin/python3 has no h5py (python3-h5py)"

now() { date +%s.%N; }
took() { awk -v a="$1" -v b="${2:-$(now)}" 'BEGIN { printf "%.2f", b - a }'; }

rm -rf "$work"
mkdir -p "$work"
work="$(cd "$work" && pwd)"
# short path: munged's socket lives in it
slurm_dir="$(mktemp -d /tmp/crashlink-slurm-test.XXXXXX)"
cleanup() {
  local rc=$?
  set +e
  if [ -d "$slurm_dir/log" ]; then cp -r "$slurm_dir/log" "$work/slurm-daemon-logs" 2>/dev/null; fi
  [ -f "$slurm_dir/jobcomp.txt" ] && cp "$slurm_dir/jobcomp.txt" "$work/" 2>/dev/null
  "$src/tools/slurm/stop-local-slurm.sh" "$slurm_dir" || { echo "FAILED: Slurm did not stop"; rc=1; }
  exit "$rc"
}
trap cleanup EXIT
t_all=$(now)

# 1. Slurm
t=$(now)
CRASHLINK_SLURM_CPUS=4 "$src/tools/slurm/start-local-slurm.sh" "$slurm_dir" >/dev/null ||
  fail "the local Slurm did not start"
export SLURM_CONF="$slurm_dir/slurm.conf"
echo "[measured] local Slurm started (munged, slurmctld, slurmd; node idle): $(took "$t") s"
sinfo

# 2. the local run
t=$(now)
(cd "$src" && "$apps/crashlink" run "$scenario" --mode multi --out "$work/local" --quiet) \
  >"$work/local.log" 2>&1 || { cat "$work/local.log"; fail "local run"; }
echo "[measured] local run (crashlink run --mode multi, ipc): $(took "$t") s"

# wait_job ID SECONDS: until the job has ended and left squeue (a cancelled job stays there,
# COMPLETING, until its batch script has ended); prints its state and exit code (STATE CODE)
wait_job() {
  local id="$1" limit="$2" line state code
  for _ in $(seq $((limit * 5))); do
    line="$(scontrol show job "$id" -o 2>/dev/null || true)"
    state="$(sed -n 's/.* JobState=\([A-Z_]*\).*/\1/p' <<<"$line")"
    code="$(sed -n 's/.* ExitCode=\([0-9:]*\).*/\1/p' <<<"$line")"
    case "$state" in
      ''|PENDING|RUNNING|CONFIGURING|COMPLETING|SUSPENDED) sleep 0.2 ;;
      *) if [ -n "$(squeue -h -j "$id" -t PD,R,CG,CF,S -o %T 2>/dev/null)" ]; then sleep 0.2; continue; fi
         echo "$state $code"; return 0 ;;
    esac
  done
  echo "TIMEOUT ?"
  return 1
}
# submit NAME SBATCH-OPTIONS... -- JOB-SCRIPT-OPTIONS...: prints the job id
submit() {
  local name="$1"; shift
  local sb=()
  while [ "$1" != -- ]; do sb+=("$1"); shift; done
  shift
  sbatch --parsable --job-name="cl-$name" --chdir="$work" --output="$work/$name.out" "${sb[@]}" \
    "$job_script" --bin "$apps" --out "$work/$name" "$@"
}
show_job() {  # NAME: the job's output and its pieces' logs
  echo "--- $work/$1.out"; cat "$work/$1.out" 2>/dev/null
  for f in "$work/$1"/slurm/logs/*.log; do echo "--- $f"; tail -n 5 "$f"; done
}
threads_of() {  # FILE DOMAIN
  /usr/bin/python3 -c 'import sys, h5py
print(h5py.File(sys.argv[1], "r")["timing"][sys.argv[2]].attrs["threads"])' "$1" "$2"
}

# 3. the scene through sbatch, compared with the local run
for spec in "A 1" "B 2 --curve"; do
  read -r name cpt extra <<<"$spec"
  t=$(now)
  # shellcheck disable=SC2086
  id="$(submit "$name" --ntasks=2 --cpus-per-task="$cpt" -- $extra "$scenario")"
  res="$(wait_job "$id" 600)" || { show_job "$name"; fail "job $name ($id) did not end in 600 s"; }
  echo "[measured] job $name (--ntasks=2 --cpus-per-task=$cpt $extra): sbatch to end $(took "$t") s; Slurm: $res"
  codes="$(cat "$work/$name/slurm/exit-codes" 2>/dev/null || true)"
  echo "$codes" | paste -sd' '
  if [ "$res" != "COMPLETED 0:0" ] || [ "$(grep -vc ' 0$' <<<"$codes")" -ne 0 ] ||
     [ "$(grep -c ' 0$' <<<"$codes")" -ne 5 ]; then
    show_job "$name"; fail "job $name: every piece, gather and the job must exit 0"
  fi
  for d in wiper body; do
    n="$(threads_of "$work/$name/domains/$d.h5" "$d")"
    [ "$n" = "$cpt" ] || fail "job $name: daemon $d ran $n threads, not --cpus-per-task=$cpt"
  done
  echo "job $name: each daemon ran $cpt thread(s) (--cpus-per-task)"
  if [ "$extra" = --curve ]; then
    grep -q -- '--curve-secret-key' "$work/$name/slurm/logs/coordinator.log" ||
      fail "job $name: the coordinator did not get CURVE keys"
    [ "$(stat -c %a "$work/$name/slurm/keys/coordinator.key")" = 600 ] ||
      fail "job $name: the coordinator's secret key is not mode 0600"
  fi
  /usr/bin/python3 "$src/tests/docker/compare_results.py" "$work/local/result.h5" \
    "$work/$name/result.h5" --rtol 0 || fail "job $name: result.h5 differs from the local run"
done

# 4. stop on request: a longer run, stopped three ways
sed 's/^\( *end_time:\).*/\1 1.0/' "$scenario" >"$work/long.yaml"
grep -q '^ *end_time: 1.0$' "$work/long.yaml" || fail "could not make the long scenario"
for spec in "cancel|CANCELLED|" "steps|FAILED|--signal=TERM" "batch|FAILED|--batch --signal=TERM"; do
  IFS='|' read -r name want_state how <<<"$spec"
  name="stop-$name"
  id="$(submit "$name" --ntasks=2 --cpus-per-task=1 -- "$work/long.yaml")"
  # running: the coordinator has sent the Setup, and both daemons have reported progress
  ok=0
  for _ in $(seq 1500); do
    if grep -q 'run, steps:' "$work/$name/slurm/logs/coordinator.log" 2>/dev/null; then ok=1; break; fi
    st="$(scontrol show job "$id" -o 2>/dev/null | sed -n 's/.* JobState=\([A-Z_]*\).*/\1/p')"
    case "$st" in PENDING|RUNNING|CONFIGURING|'') ;; *) break ;; esac
    sleep 0.2
  done
  [ "$ok" -eq 1 ] || { show_job "$name"; fail "job $name ($id) never started computing"; }
  sleep 1
  for d in coordinator wiper body; do
    [ -s "$work/$name/slurm/pids/$d" ] || { show_job "$name"; fail "job $name: no pid of $d"; }
  done
  t=$(now)
  # shellcheck disable=SC2086
  scancel $how "$id"
  res="$(wait_job "$id" 120)" || { show_job "$name"; fail "job $name ($id) did not end 120 s after scancel $how"; }
  t_end=$(now)
  last=0
  for d in coordinator wiper body; do
    m="$(stat -c %.9Y "$work/$name/slurm/exit/$d" 2>/dev/null || echo 0)"
    last="$(awk -v a="$last" -v b="$m" 'BEGIN { print (b > a ? b : a) }')"
  done
  echo "[measured] job $name: scancel $how -> every piece's exit recorded after $(took "$t" "$last") s, job ended after $(took "$t" "$t_end") s; Slurm: $res"
  codes="$(cat "$work/$name/slurm/exit-codes" 2>/dev/null || true)"
  echo "$codes" | paste -sd' '
  expect="$(printf 'coordinator 7\nwiper 7\nbody 7\ngather 0\njob 7')"
  if [ "$codes" != "$expect" ]; then
    show_job "$name"; fail "job $name: expected every piece and the job to exit 7 and gather 0"
  fi
  [ "$res" = "$want_state 7:0" ] ||
    { show_job "$name"; fail "job $name: Slurm says '$res', expected '$want_state 7:0'"; }
  for d in coordinator wiper body; do
    p="$(cat "$work/$name/slurm/pids/$d")"
    if kill -0 "$p" 2>/dev/null; then fail "job $name: $d (pid $p) is still running"; fi
  done
  grep -q 'stopped on request' "$work/$name/slurm/logs/wiper.log" "$work/$name/slurm/logs/body.log" ||
    fail "job $name: no daemon says it was stopped on request"
  [ -f "$work/$name/result.h5" ] || fail "job $name: nothing gathered"
done

echo "[measured] Slurm test total (without stopping Slurm): $(took "$t_all") s"
echo "PASSED"
