#!/usr/bin/env bash
# Builds a Debian 12 base image without a registry: debootstrap (minbase) from the Debian
# archive, then `docker import`. Stands in for debian:bookworm and debian:bookworm-slim when no
# registry can be reached (docker/Dockerfile takes them as --build-arg BASE/RUNTIME_BASE).
#
#   docker/build-base-image.sh [IMAGE]      # default crashlink/debian:bookworm
#
# Tags IMAGE and IMAGE-slim (the same image: minbase is already small). Needs root, debootstrap
# (apt-get install debootstrap), a running docker engine and the Debian mirror
# (CRASHLINK_DEBIAN_MIRROR, default http://deb.debian.org/debian). About 2 min (measured 1 min
# 53 s for debootstrap, 8 s for the import; docs in DEVELOPERS.md "Docker").
set -euo pipefail
image="${1:-crashlink/debian:bookworm}"
mirror="${CRASHLINK_DEBIAN_MIRROR:-http://deb.debian.org/debian}"
security="${CRASHLINK_DEBIAN_SECURITY_MIRROR:-http://deb.debian.org/debian-security}"
if [ "$(id -u)" -ne 0 ]; then
  echo "build-base-image.sh: debootstrap needs root" >&2
  exit 2
fi
command -v debootstrap >/dev/null || {
  echo "build-base-image.sh: debootstrap missing: apt-get install -y debootstrap" >&2
  exit 2
}
rootfs="$(mktemp -d "${TMPDIR:-/tmp}/crashlink-rootfs.XXXXXX")"
trap 'rm -rf "$rootfs"' EXIT
chmod 755 "$rootfs"   # mktemp's 0700 would become the image's / (no one but root gets in)
start=$(date +%s)
debootstrap --variant=minbase bookworm "$rootfs" "$mirror"
# The same sources as the official debian:bookworm image (point-release updates and security),
# so that the build stage gets the same compiler and libraries as an up-to-date Debian 12 host.
cat >"$rootfs/etc/apt/sources.list" <<EOF
deb $mirror bookworm main
deb $mirror bookworm-updates main
deb $security bookworm-security main
EOF
# Like the official image: no package lists or downloaded .debs in the layer.
# (files only: the partial/ folders keep their owner _apt, or apt warns about its sandbox).
find "$rootfs/var/lib/apt/lists" "$rootfs/var/cache/apt" -type f -delete
mid=$(date +%s)
# `docker import` sets no environment: PATH as in the official image (or programs are not found).
tar -C "$rootfs" -c . | docker import \
  --change 'ENV PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin' \
  --change 'CMD ["/bin/bash"]' - "$image"
docker tag "$image" "$image-slim"
end=$(date +%s)
echo "build-base-image.sh: $image and $image-slim: debootstrap $((mid - start)) s, import $((end - mid)) s"
