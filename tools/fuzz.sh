#!/usr/bin/env bash
# Runs one libFuzzer target (docs/fuzzing.md) on its checked-in corpus.
#   tools/fuzz.sh [TARGET] [SECONDS]    TARGET: coordinator (default) | daemon | scenario;
#                                       SECONDS: 600 by default
#   tools/fuzz.sh --merge TARGET        minimises the checked-in corpus with what the runs found
#                                       (-merge=1, then tools/fuzz_trim.py: seeds, regression
#                                       inputs and the 40 finds adding the most edges)
# Configures build-fuzz with clang (libFuzzer, ASan, UBSan: -DCRASHLINK_FUZZ=ON) if needed and
# builds only the target. New inputs go to build-fuzz/corpus/TARGET/ (the checked-in
# tests/fuzz/corpus/TARGET/ is only read), crashes to build-fuzz/crashes/TARGET/; minimise one
# with `build-fuzz/tests/fuzz/fuzz_TARGET -minimize_crash=1 -runs=10000 FILE`, fix the product
# code and keep the minimised input in tests/fuzz/corpus/TARGET/ (Fuzz.<Target>Corpus replays it).
# Extra libFuzzer flags: FUZZ_ARGS="-jobs=2 -workers=2" tools/fuzz.sh daemon 600.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${CRASHLINK_FUZZ_BUILD:-build-fuzz}

merge=0
if [[ ${1:-} == --merge ]]; then
  merge=1
  shift
fi
target=${1:-coordinator}
seconds=${2:-600}
case $target in
  coordinator | daemon) max_len=4096 ;;
  scenario) max_len=8192 ;;
  *)
    echo "usage: tools/fuzz.sh [coordinator|daemon|scenario] [SECONDS] | --merge TARGET" >&2
    exit 2
    ;;
esac

if [[ ! -f $build/build.ninja ]]; then
  CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCRASHLINK_FUZZ=ON
fi
cmake --build "$build" -j2 --target "fuzz_$target"

fuzzer=$build/tests/fuzz/fuzz_$target
checked_in=tests/fuzz/corpus/$target
found=$build/corpus/$target
mkdir -p "$found" "$build/crashes/$target"
dict=(-dict=tests/fuzz/messages.dict)
[[ $target == scenario ]] && dict=(-dict=tests/fuzz/scenario.dict)

if ((merge)); then
  # -merge=1 on edges only (-use_counters=0), then tools/fuzz_trim.py keeps the named inputs
  # (seeds, regression inputs) and the 40 finds that added the most edges: tens of small files.
  fresh=$build/merged/$target
  rm -rf "$fresh" "$build/merged/$target.control" && mkdir -p "$fresh"  # no resumed merge
  "$fuzzer" -merge=1 -use_counters=0 -max_len="$max_len" -timeout=10 -rss_limit_mb=2048 \
    -merge_control_file="$build/merged/$target.control" "$fresh" "$checked_in" "$found"
  python3 tools/fuzz_trim.py "$build/merged/$target.control" "$checked_in" "${FUZZ_KEEP:-40}"
  "$fuzzer" -runs=0 "$checked_in" 2>&1 | grep -E "INITED|DONE" | tail -n 1
  exit 0
fi

# shellcheck disable=SC2086  # FUZZ_ARGS is a list of flags
exec "$fuzzer" "$found" "$checked_in" -max_total_time="$seconds" -timeout=10 \
  -rss_limit_mb=2048 -max_len="$max_len" -print_final_stats=1 "${dict[@]}" \
  -artifact_prefix="$build/crashes/$target/" ${FUZZ_ARGS:-}
