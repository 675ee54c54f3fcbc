#!/usr/bin/env bash
# docker.compose: the suite runs no Docker engine (scripts/compose-check builds and runs
# the images for real, outside it), so check offline what would otherwise rot unnoticed in
# docker/: compose accepts the file, each Dockerfile and stage it names exists, the images
# run as a non-root user, ports and health checks are where the services rely on them, the
# binaries copied are real CMake targets, and the air's socket, sink and volumes line up
# between compose, docker/air.sh and scripts/air.
# Then what a build in the image would miss: every library the CMake files the build stage
# copies look for (find_package, pkg_check_modules, find_library, find_program; REQUIRED
# ones, outside if(BUILD_TESTING)) must come from a package the build stage installs. A
# scratch CMake project makes those very calls on this machine, and dpkg names the package
# of each file they found; the build stage installs it when it names it in apt-get install,
# or names a package that depends on it (--no-install-recommends: Depends only), or it is
# Essential (in every Debian base image). And the postgres service's image stays
# selectable: ${DTMF_POSTGRES_IMAGE:-postgres:15}, with docker/postgres the stand-in.
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
status=0
/usr/bin/python3 "$(dirname "$0")/compose_check.py" "$repo" "$tmp/resolved.yaml" "$tmp/packages" || status=1

# The postgres service's image: the official one by default, another through the variable.
DTMF_POSTGRES_IMAGE=stand-in:1 env -i PATH="$PATH" HOME="${HOME:-/tmp}" DTMF_POSTGRES_IMAGE=stand-in:1 \
  docker-compose --env-file "$tmp/empty.env" -f "$compose" config >"$tmp/resolved-stand-in.yaml" ||
  fail "docker-compose config with DTMF_POSTGRES_IMAGE set failed"

# The build stage's libraries (see the header), and the postgres image's variable.
/usr/bin/python3 "$(dirname "$0")/build_stage_check.py" "$repo" "$compose" "$tmp" || status=1
exit $status
