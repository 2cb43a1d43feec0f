#!/usr/bin/env bash
# Installs crashlink's build and run dependencies on Debian 12 (all from Debian's archive).
set -euo pipefail
pkgs=(build-essential cmake ninja-build pkg-config
      libzmq3-dev cppzmq-dev libprotobuf-dev protobuf-compiler libeigen3-dev libhdf5-dev
      libyaml-cpp-dev libcli11-dev libfmt-dev
      libgtest-dev libgmock-dev libbenchmark-dev clang-format
      python3 python3-numpy python3-matplotlib python3-h5py python3-yaml
      iproute2
      slurmctld slurmd slurm-client munge)  # tests/slurm: a single-node Slurm (docs/slurm.md)
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${pkgs[@]}"
