#!/usr/bin/env bash
# tools/check_cmake_deps.py fails on each kind of disagreement and passes once they are fixed: a
# throw-away repository with three libraries where `io` includes a header of `contact` it does not
# declare, declares `integration` it does not use, declares spdlog it never includes and includes
# yaml-cpp it does not declare (the findings of issue 23); then the same libraries declared
# honestly.
set -euo pipefail
check="$1/tools/check_cmake_deps.py"
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=expect_findings.sh
. "$here/expect_findings.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
git init -q .
mkdir -p solver/contact solver/integration solver/io
echo 'crashlink_library(contact)' > solver/contact/CMakeLists.txt
echo 'crashlink_library(integration)' > solver/integration/CMakeLists.txt
printf '#pragma once\nint segments();\n' > solver/contact/segments.h
printf '#pragma once\nint solver();\n' > solver/integration/solver.h
cat > solver/io/CMakeLists.txt <<'CM'
crashlink_library(io PUBLIC_DEPS crashlink::integration DEPS spdlog::spdlog)
CM
cat > solver/io/reader.cpp <<'SRC'
#include <yaml-cpp/yaml.h>

#include "solver/contact/segments.h"
int reader() { return segments(); }
SRC
git add -A
expect_findings "$check" "$tmp" "solver/io/reader.cpp:3: library io includes solver/contact/segments.h of crashlink::contact" \
            "library io declares crashlink::integration but includes none of its headers" \
            "library io declares spdlog::spdlog but includes none of its headers" \
            "library io includes yaml-cpp/... but declares no yaml-cpp"
cat > solver/io/CMakeLists.txt <<'CM'
crashlink_library(io PUBLIC_DEPS crashlink::contact DEPS yaml-cpp)
CM
git add -A
/usr/bin/python3 "$check" "$tmp" || { echo "FAIL: honest dependencies refused"; exit 1; }
echo "PASS"
