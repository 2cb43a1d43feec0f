#!/usr/bin/env bash
# Cost of a coupled run against mono (docs/processes.md "Measured"): runs SCENARIO RUNS times in
# each of `--mode mono` and `--mode multi` over every transport given, interleaved (mono, ipc,
# tcp, mono, ...) so that the machine's load falls on all alike, and prints the median of each
# figure with its range:
#   mono:  CPU and wall of the single-domain run;
#   multi: total CPU (domains + coordinator), the coordinator's CPU and its share of the total,
#          wall, the sum of the CPU times and wall / sum (1: the pieces took turns; 1/n: n pieces
#          ran at once), and total CPU / mono CPU.
# Every ratio is taken within one run, then the median over the runs.
#
#   bench/bench_multi.sh [-b BUILD_DIR]... [-n RUNS] [-t "ipc tcp"] [-s SCENARIO] [-k]
#     -b  build directory holding apps/crashlink, crashlink-coordinator and crashlink-solver
#         (default: build); give -b twice to compare two builds run by run (before/after)
#     -n  runs per mode (default: 3; quote medians of >= 3 on a loaded machine)
#     -t  transports for multi (default: "ipc tcp"; also inproc)
#     -s  scenario (default: bench/scenarios/multi_block.yaml)
#     -k  keep the run folders (default: removed at the end)
# Needs /usr/bin/python3 (medians). Figures are those `crashlink run` prints (DIR/result.h5
# /timing): CPU per process (wait4-style process CPU, ZeroMQ's I/O thread included), wall of the
# launcher (process start to the last exit).
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
builds=()
runs=3
transports="ipc tcp"
scenario="$here/bench/scenarios/multi_block.yaml"
keep=0
while getopts "b:n:t:s:kh" opt; do
  case "$opt" in
    b) builds+=("$(cd "$OPTARG" && pwd)") ;;
    n) runs="$OPTARG" ;;
    t) transports="$OPTARG" ;;
    s) scenario="$OPTARG" ;;
    k) keep=1 ;;
    *) sed -n '2,20p' "$0"; exit 2 ;;
  esac
done
[[ ${#builds[@]} -gt 0 ]] || builds=("$here/build")
for b in "${builds[@]}"; do
  [[ -x "$b/apps/crashlink" ]] ||
    { echo "bench_multi: $b/apps/crashlink not found (build first, or -b DIR)" >&2; exit 2; }
done
work="$(mktemp -d "${TMPDIR:-/tmp}/bench_multi.XXXXXX")"
[[ "$keep" == 1 ]] || trap 'rm -rf "$work"' EXIT
table="$work/figures.tsv"
: >"$table"

echo "bench_multi: $(basename "$scenario"), $runs run(s) of mono and multi over $transports" \
  "with ${builds[*]}; $(nproc) core(s), load $(cut -d' ' -f1-3 /proc/loadavg)"
for ((i = 1; i <= runs; ++i)); do
  for b in "${builds[@]}"; do
    exe="$b/apps/crashlink"
    label="$(basename "$b")"
    for mode in mono $transports; do
      out="$work/$label-$mode-$i"
      log="$out.log"
      if [[ "$mode" == mono ]]; then
        "$exe" run "$scenario" --mode mono --quiet --out "$out" >"$log" 2>&1 ||
          { echo "bench_multi: $label mono run $i failed:" >&2; tail -5 "$log" >&2; exit 1; }
        # "<domain> elements cycles dt_min CPU ns" then "coordinator: none (one domain); wall W s"
        awk -v run="$i" -v label="$label" '
          /^coordinator: none/ { for (k = 1; k <= NF; ++k) if ($k == "wall") wall = $(k + 1) }
          prev ~ /^domain +elements/ { cpu = $5 }
          { prev = $0 }
          END { printf "%s\tmono\t%s\t%s\t%s\t0\n", label, run, cpu, wall }' "$log" >>"$table"
      else
        "$exe" run "$scenario" --mode multi --transport "$mode" --quiet --out "$out" >"$log" 2>&1 ||
          { echo "bench_multi: $label multi $mode run $i failed:" >&2; tail -5 "$log" >&2; exit 1; }
        # "coordinator: CPU C s = P % of the total CPU T s" and "wall W s vs sum of CPU times S s"
        awk -v run="$i" -v mode="$mode" -v label="$label" '
          /^coordinator: CPU/ { coord = $3; total = $(NF - 1) }
          /^wall .* vs sum of CPU times/ { wall = $2 }
          END { printf "%s\t%s\t%s\t%s\t%s\t%s\n", label, mode, run, total, wall, coord }' \
          "$log" >>"$table"
      fi
      [[ "$keep" == 1 ]] || rm -rf "$out"
      tail -1 "$table" | awk -F'\t' '{ printf "  %s %-6s run %s: CPU %s s, wall %s s%s\n", $1, $2,
        $3, $4, $5, ($2 == "mono" ? "" : ", coordinator " $6 " s") }'
    done
  done
done

/usr/bin/python3 - "$table" <<'PY'
import statistics, sys
runs = {}
for line in open(sys.argv[1]):
    if not line.strip():
        continue
    label, mode, run, cpu, wall, coord = line.rstrip("\n").split("\t")
    runs.setdefault(label, {}).setdefault(mode, {})[int(run)] = (
        float(cpu), float(wall), float(coord))
def fmt(values, unit="", scale=1.0, digits=3):
    v = [x * scale for x in values]
    return f"{statistics.median(v):.{digits}f}{unit} ({min(v):.{digits}f}-{max(v):.{digits}f})"
print("\nmedian (min-max) over the runs; CPU = process CPU times, sum = domains + coordinator")
for label, by in runs.items():
    print(f"{label}:")
    mono = by.pop("mono", {})
    if mono:
        print(f"  mono          CPU {fmt([c for c, _, _ in mono.values()], ' s')}"
              f"  wall {fmt([w for _, w, _ in mono.values()], ' s')}")
    for mode, r in by.items():
        v = r.values()
        print(f"  multi {mode:6s}  sum of CPU {fmt([c for c, _, _ in v], ' s')}"
              f"  coordinator {fmt([k for _, _, k in v], ' s')}"
              f" = {fmt([k / c for c, _, k in v], ' %', 100.0, 2)} of the sum")
        line = (f"                wall {fmt([w for _, w, _ in v], ' s')}"
                f"  wall/sum of CPU {fmt([w / c for c, w, _ in v], '', 1.0, 2)}")
        both = [i for i in r if i in mono]
        if both:
            line += (f"  sum of CPU/mono CPU "
                     f"{fmt([r[i][0] / mono[i][0] for i in both], '', 1.0, 2)}")
        print(line)
PY
