#!/usr/bin/env bash
# End-to-end docker test (DEVELOPERS.md "Docker"): the CI scene in containers against the same
# scene run on this machine.
#
#   tests/docker/compose_test.sh [--if-enabled] BUILD_DIR [WORK_DIR]
#
# --if-enabled (ctest, tests/CMakeLists.txt): skip unless CRASHLINK_DOCKER_TEST=1.
#
# 1. the base image ($CRASHLINK_DOCKER_BASE, default crashlink/debian:bookworm) is built with
#    docker/build-base-image.sh (debootstrap, no registry) if the engine does not have it;
# 2. the crashlink image is built from this source tree (docker/Dockerfile, tag
#    $CRASHLINK_DOCKER_IMAGE, default crashlink:test);
# 3. docker/compose.yaml runs scenarios/head_impact_small.yaml, mode multi: the coordinator, the
#    wiper and body daemons in their own containers on a user-defined network (tcp by service
#    name), then gather; result.h5 is copied out of the results volume;
# 4. BUILD_DIR/apps/crashlink runs the same scene --mode multi on this machine;
# 5. tests/docker/compare_results.py compares the two result.h5 (every history, state and
#    coupling value; tolerance $CRASHLINK_DOCKER_RTOL, default 0: the image's programs come from
#    the same sources, compiler and flags, so the numbers are bit-identical) and
#    `crashlink compare` prints the HIC of both.
#
# Exit 0 passed, 1 failed, 77 skipped (no engine, no compose, no base image and no way to build
# it: the reason is printed). Prints `[measured]` lines with the time of each step.
set -euo pipefail
SKIP=77
skip() { echo "SKIPPED: $*"; exit "$SKIP"; }
if [ "${1:-}" = --if-enabled ]; then
  shift
  [ "${CRASHLINK_DOCKER_TEST:-0}" = 1 ] ||
    skip "the docker test runs only with CRASHLINK_DOCKER_TEST=1 (minutes; DEVELOPERS.md, Docker)"
fi
here="$(cd "$(dirname "$0")" && pwd)"
src="$(cd "$here/../.." && pwd)"
build="${1:?usage: compose_test.sh [--if-enabled] BUILD_DIR [WORK_DIR]}"
build="$(cd "$build" && pwd)"
work="${2:-$build/docker-test}"
base="${CRASHLINK_DOCKER_BASE:-crashlink/debian:bookworm}"
image="${CRASHLINK_DOCKER_IMAGE:-crashlink:test}"
rtol="${CRASHLINK_DOCKER_RTOL:-0}"
scenario=scenarios/head_impact_small.yaml
run=head_impact_small
project="crashlink-test-$$"

now() { date +%s.%N; }
took() { python3 -c "import sys; print(f'{float(sys.argv[2]) - float(sys.argv[1]):.1f}')" "$1" "$(now)"; }

command -v docker >/dev/null || skip "no docker client"
docker info >/dev/null 2>&1 || skip "no docker engine reachable (start one: tools/start-dockerd.sh)"
if docker compose version >/dev/null 2>&1; then
  compose=(docker compose)
elif command -v docker-compose >/dev/null; then
  compose=(docker-compose)
else
  skip "neither 'docker compose' nor 'docker-compose' (apt-get install docker-compose)"
fi
[ -x "$build/apps/crashlink" ] || { echo "FAILED: $build/apps/crashlink missing"; exit 1; }

rm -rf "$work"
mkdir -p "$work"
t_all=$(now)

# 1. base image
if ! docker image inspect "$base" >/dev/null 2>&1; then
  [ "$(id -u)" -eq 0 ] || skip "base image $base missing and building it needs root"
  command -v debootstrap >/dev/null || skip "base image $base missing and no debootstrap"
  t=$(now)
  "$src/docker/build-base-image.sh" "$base"
  echo "[measured] base image $base built (debootstrap + import): $(took "$t") s"
else
  echo "base image $base present"
fi
# An engine that answers but cannot start containers here (no privileges for its mounts or
# namespaces) is a property of the machine, not of crashlink: skip with its own words.
if ! probe="$(docker run --rm --network none "$base" true 2>&1)"; then
  skip "the engine cannot run a container here: $probe"
fi
runtime_base="$base-slim"
docker image inspect "$runtime_base" >/dev/null 2>&1 || runtime_base="$base"

# 2. the crashlink image (docker's layer cache makes an unchanged tree a few seconds)
t=$(now)
docker build --network host -f "$src/docker/Dockerfile" \
  --build-arg BASE="$base" --build-arg RUNTIME_BASE="$runtime_base" \
  -t "$image" "$src"
echo "[measured] image $image built: $(took "$t") s"

# 3. the scene in containers
export CRASHLINK_IMAGE="$image" CRASHLINK_SCENARIO="$scenario" CRASHLINK_MODE=multi \
  CRASHLINK_RUN="$run"
dc() { "${compose[@]}" -p "$project" -f "$src/docker/compose.yaml" "$@"; }
cleanup() {
  dc down -v --remove-orphans >/dev/null 2>&1 || true
  docker volume rm "${project}_keys" >/dev/null 2>&1 || true
}
trap cleanup EXIT
# CURVE: once the programs have `crashlink keygen` (tcp beyond loopback then needs keys), the keys
# go into the project's keys volume where docker/compose.yaml looks for them.
if docker run --rm "$image" crashlink --help 2>/dev/null | grep -q "^ *keygen"; then
  docker run --rm -v "${project}_keys:/keys" "$image" sh -ec '
    for n in coordinator wiper body; do crashlink keygen --out /keys/$n >/dev/null; done
    cat /keys/wiper.pub /keys/body.pub > /keys/authorized_keys'
  echo "CURVE keys made in volume ${project}_keys"
fi
t=$(now)
timeout 1200 "${compose[@]}" -p "$project" -f "$src/docker/compose.yaml" up --no-color \
  >"$work/compose.log" 2>&1 || true
echo "[measured] compose up (coordinator + 2 daemons + gather): $(took "$t") s"
dc logs --no-color >"$work/services.log" 2>&1 || true
tail -n 25 "$work/services.log"
failed=0
for s in coordinator wiper body gather; do
  id="$(dc ps -aq "$s" | head -n 1)"
  code="$( [ -n "$id" ] && docker inspect -f '{{.State.ExitCode}}' "$id" || echo missing)"
  echo "service $s: exit $code"
  [ "$code" = 0 ] || failed=1
done
if [ "$failed" -ne 0 ]; then
  echo "FAILED: a service did not finish with exit 0 (logs: $work/compose.log, $work/services.log)"
  exit 1
fi
docker cp "$(dc ps -aq gather | head -n 1):/results/$run" "$work/docker"
[ -f "$work/docker/result.h5" ] || { echo "FAILED: no result.h5 in the volume"; exit 1; }

# 4. the same scene on this machine
t=$(now)
(cd "$src" && "$build/apps/crashlink" run "$scenario" --mode multi --out "$work/local" --quiet) \
  >"$work/local.log" 2>&1 || { cat "$work/local.log"; echo "FAILED: local run"; exit 1; }
echo "[measured] local run (multi, ipc): $(took "$t") s"

# 5. compare
"$build/apps/crashlink" compare "$work/local/result.h5" "$work/docker/result.h5" || true
if /usr/bin/python3 "$here/compare_results.py" "$work/local/result.h5" "$work/docker/result.h5" \
  --rtol "$rtol"; then
  echo "[measured] docker test total: $(took "$t_all") s"
  echo "PASSED"
else
  echo "FAILED: the docker run differs from the local run"
  exit 1
fi
