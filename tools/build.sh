#!/usr/bin/env bash
# Configures and builds crashlink (Release, -O3 -march=x86-64-v3) into ./build.
# CRASHLINK_WERROR=ON turns warnings into errors (CI sets it).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DCRASHLINK_WERROR="${CRASHLINK_WERROR:-OFF}"
cmake --build build -j"$(nproc)"
