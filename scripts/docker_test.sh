#!/usr/bin/env bash
# Builds the Docker image and checks it as a user would meet it
# (docs/install.md, "Docker"):
#
#   scripts/docker_test.sh            # builds plcrun:test, runs it, removes the container
#
# Checks: the image builds; a container of it runs `plcrun serve` as the
# user plcrun and becomes healthy (its HEALTHCHECK, `plcrun health` on the
# web monitor); the monitor answers on the published port; `docker stop`
# (SIGTERM) ends it with exit status 0 and the retain file saved. Prints
# the image's size. Says so and exits 0 where docker or its daemon is
# missing (a build needs Docker Hub's rust and debian images).
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v docker >/dev/null 2>&1; then
    echo "docker test: skipped: docker is not installed"
    exit 0
fi
if ! docker info >/dev/null 2>&1; then
    echo "docker test: skipped: no docker daemon answers"
    exit 0
fi
image=plcrun:test
name=plcrun-test-$$
state=$(mktemp -d)
chmod 777 "$state"
cleanup() {
    docker rm -f "$name" >/dev/null 2>&1 || true
    rm -rf "$state"
}
trap cleanup EXIT
docker build -t "$image" .
# A free port of the host for the monitor.
port=$(python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
docker run -d --name "$name" -p "127.0.0.1:$port:8080" -v "$state:/var/lib/plcrun" "$image" >/dev/null
user=$(docker exec "$name" id -un)
[ "$user" = plcrun ] || { echo "docker test: runs as $user, not plcrun" >&2; exit 1; }
# Healthy within the start period and two checks (interval 30 s).
health=starting
for _ in $(seq 1 90); do
    health=$(docker inspect --format '{{.State.Health.Status}}' "$name")
    [ "$health" = healthy ] && break
    [ "$health" = unhealthy ] && break
    sleep 1
done
if [ "$health" != healthy ]; then
    docker logs "$name" >&2
    echo "docker test: the container is $health" >&2
    exit 1
fi
# The monitor answers from the host on the published port.
target/release/plcrun health "127.0.0.1:$port" 2>/dev/null \
    || docker exec "$name" plcrun health 127.0.0.1:8080
docker stop -t 10 "$name" >/dev/null
code=$(docker inspect --format '{{.State.ExitCode}}' "$name")
[ "$code" = 0 ] || { docker logs "$name" >&2; echo "docker test: exit status $code" >&2; exit 1; }
[ -s "$state/plcrun.retain" ] || { echo "docker test: no retain file saved" >&2; exit 1; }
size=$(docker image inspect --format '{{.Size}}' "$image")
echo "docker ok: healthy as plcrun, stopped cleanly, retain saved; image $((size / 1000000)) MB"
