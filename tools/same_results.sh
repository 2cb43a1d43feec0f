#!/bin/bash
# Records or checks a matrix of runs for a refactor that must not change a bit:
#   tools/same_results.sh record DIR [--full]   run the matrix with build/apps/crashlink into DIR
#   tools/same_results.sh check DIR [--full]    run it again into DIR.new and compare each
#                                               result.h5 with tests/docker/compare_results.py
# The matrix: the CI scene (head_impact_small) mono, split layer/paper, multi layer over tcp, ipc
# and inproc, multi paper (its guard stops it: exit 1 recorded and checked too), multi variable
# steps, multi without lanes; --full adds the full head impact mono and multi.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
bin=${CRASHLINK_BIN:-$here/build/apps/crashlink}
action=${1:?record|check}
dir=${2:?DIR}
full=${3:-}
small=$here/scenarios/head_impact_small.yaml
big=$here/scenarios/head_impact.yaml
runs=(
  "mono|$small|--mode mono"
  "split_layer|$small|--mode split"
  "split_paper|$small|--mode split --coupling paper"
  "multi_tcp|$small|--mode multi --transport tcp"
  "multi_ipc|$small|--mode multi --transport ipc"
  "multi_inproc|$small|--mode multi --transport inproc"
  "multi_paper|$small|--mode multi --coupling paper --transport ipc"
  "multi_variable|$small|--mode multi --variable-steps --transport ipc"
  "multi_nolanes|$small|--mode multi --no-lanes --transport tcp"
)
if [ "$full" = "--full" ]; then
  runs+=("full_mono|$big|--mode mono" "full_multi|$big|--mode multi --transport ipc")
fi
out=$dir
[ "$action" = check ] && out=$dir.new
mkdir -p "$out"
fail=0
for r in "${runs[@]}"; do
  IFS='|' read -r name scene opts <<<"$r"
  rm -rf "${out:?}/$name"
  # shellcheck disable=SC2086
  code=0
  "$bin" run "$scene" --out "$out/$name" --quiet $opts >"$out/$name.log" 2>&1 || code=$?
  echo "$code" >"$out/$name.exit"
  if [ ! -f "$out/$name/result.h5" ]; then
    echo "$name: no result.h5 (exit $code, log $out/$name.log)"; fail=1; continue
  fi
  if [ "$action" = check ]; then
    if [ "$code" != "$(cat "$dir/$name.exit")" ]; then
      echo "$name: exit $code, recorded $(cat "$dir/$name.exit")"; fail=1
    fi
    if /usr/bin/python3 "$here/tests/docker/compare_results.py" "$dir/$name/result.h5" \
        "$out/$name/result.h5" >"$out/$name.compare" 2>&1; then
      echo "$name: same"
    else
      echo "$name: DIFFERS"; cat "$out/$name.compare"; fail=1
    fi
  else
    echo "$name: recorded (exit $code)"
  fi
done
exit $fail
