#!/usr/bin/env bash
# docker.compose: there is no Docker engine to build or run the images here, so check
# offline what would otherwise rot unnoticed in docker/: compose accepts the file, each
# Dockerfile and stage it names exists, the images run as a non-root user, ports and health
# checks are where the services rely on them, the binaries copied are real CMake targets,
# and the air's socket, sink and volumes line up between compose, docker/air.sh and scripts/air.
#   tests/docker/compose_test.sh [REPO]      (REPO: the repository root; default: this one)
set -euo pipefail

repo=$(cd "${1:-$(dirname "$0")/../..}" && pwd)
compose=$repo/docker/compose.yaml
fail() { echo "docker.compose: FAIL: $*" >&2; exit 1; }

command -v docker-compose >/dev/null ||
  fail "docker-compose not found; install it: apt-get install docker-compose (it is in DTMF_PACKAGES)"
[[ -f $compose ]] || fail "$compose is missing"

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# Check the defaults, not whatever DTMF_* the caller exported or a docker/.env sets.
touch "$tmp/empty.env"
clean_compose() {
  env -i PATH="$PATH" HOME="${HOME:-/tmp}" docker-compose --env-file "$tmp/empty.env" -f "$compose" "$@"
}
clean_compose config -q || fail "docker-compose rejects $compose (its message is above)"
clean_compose config >"$tmp/resolved.yaml" || fail "docker-compose config failed"
# shellcheck disable=SC1091  # a path known at run time
(source "$repo/scripts/lib/common.sh" && printf '%s\n' "${DTMF_PACKAGES[@]}") >"$tmp/packages"

# PyYAML comes with docker-compose; Debian's python3 has it, a python3 first on PATH may not.
/usr/bin/python3 "$(dirname "$0")/compose_check.py" "$repo" "$tmp/resolved.yaml" "$tmp/packages"
