#!/bin/bash
# Mono on 1 and on N threads, in alternation, and the ratios (issue 24, docs/threads.md "Measured"):
#   tools/bench_threads.sh [SCENARIO] [N] [PAIRS]
# defaults: scenarios/head_impact.yaml, 2 threads, 3 pairs. Per run: cycles, CPU [s] (the process's,
# every thread), wall [s], HIC15; then the medians, the wall-clock speed-up (1 thread / N threads)
# and the CPU per cycle of N threads against 1 thread's. Runs in a temporary folder.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
bin=${CRASHLINK_BIN:-$here/build/apps/crashlink}
scene=${1:-$here/scenarios/head_impact.yaml}
n=${2:-2}
pairs=${3:-3}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
printf '%-8s %8s %10s %10s %10s %10s\n' threads run cycles "CPU [s]" "wall [s]" HIC15
for p in $(seq 1 "$pairs"); do
  for t in 1 "$n"; do
    log=$tmp/run_${t}_$p.log
    "$bin" run "$scene" --mode mono --quiet --threads "$t" --out "$tmp/out_$t" >"$log" 2>&1
    cycles=$(awk '$1 == "model" {print $3}' "$log")
    cpu=$(awk '$1 == "model" {print $5}' "$log")
    wall=$(sed -n 's/.*; wall \([0-9.]*\) s;.*/\1/p' "$log")
    hic=$(sed -n 's/^HIC15 = \([0-9.]*\).*/\1/p' "$log" | head -1)
    printf '%-8s %8s %10s %10s %10s %10s\n' "$t" "$p" "$cycles" "$cpu" "$wall" "${hic:--}"
    echo "$t $cycles $cpu $wall" >>"$tmp/rows"
  done
done
/usr/bin/python3 - "$tmp/rows" "$n" <<'PY'
import statistics, sys
rows = [l.split() for l in open(sys.argv[1])]
n = sys.argv[2]
def med(t, k):
    return statistics.median(float(r[k]) for r in rows if r[0] == t)
c1, cn = med("1", 2) / med("1", 1), med(n, 2) / med(n, 1)
w1, wn = med("1", 3), med(n, 3)
print(f"median wall: 1 thread {w1:.2f} s, {n} threads {wn:.2f} s: speed-up {w1 / wn:.3f}")
print(f"median CPU per cycle: 1 thread {1e6 * c1:.1f} us, {n} threads {1e6 * cn:.1f} us: "
      f"{n} threads / 1 = {cn / c1:.3f}")
PY
