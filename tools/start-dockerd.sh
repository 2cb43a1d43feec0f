#!/usr/bin/env bash
# Starts a docker engine for the docker test (DEVELOPERS.md "Docker") on a machine or container
# without one: installs docker.io, docker-compose and debootstrap from Debian's archive if
# missing, then runs dockerd in the background (as root) with the settings that work inside a
# container: vfs storage (no overlay mounts needed), no iptables rules, no default bridge
# (containers use the user-defined network of docker/compose.yaml; builds use --network host).
#
#   tools/start-dockerd.sh          # returns once the engine answers; log in $CRASHLINK_DOCKERD_LOG
#
# Does nothing if an engine already answers. The engine keeps running after the script; stop it
# with: kill "$(cat /var/run/docker.pid)".
set -euo pipefail
log="${CRASHLINK_DOCKERD_LOG:-/var/log/crashlink-dockerd.log}"
if docker info >/dev/null 2>&1; then
  echo "start-dockerd.sh: an engine is already running"
  exit 0
fi
if [ "$(id -u)" -ne 0 ]; then
  echo "start-dockerd.sh: dockerd needs root" >&2
  exit 2
fi
need=()
command -v dockerd >/dev/null || need+=(docker.io)
command -v docker-compose >/dev/null || docker compose version >/dev/null 2>&1 || need+=(docker-compose)
command -v debootstrap >/dev/null || need+=(debootstrap)
if [ "${#need[@]}" -gt 0 ]; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -q
  apt-get install -y -q "${need[@]}"
fi
nohup dockerd --storage-driver=vfs --iptables=false --bridge=none >"$log" 2>&1 &
for _ in $(seq 60); do
  if docker info >/dev/null 2>&1; then
    echo "start-dockerd.sh: engine up (pid $!, log $log)"
    exit 0
  fi
  sleep 0.5
done
echo "start-dockerd.sh: the engine did not answer within 30 s; end of $log:" >&2
tail -n 20 "$log" >&2
exit 1
