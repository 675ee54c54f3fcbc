#!/usr/bin/env bash
# Runs in docker/Dockerfile's build stage, and in the suite's docker.runtime_packages test on
# its own build: checks that a runtime image's package list holds every library its programs
# link, as Debian's own packaging computes it (dpkg-shlibdeps on the binaries, which maps each
# NEEDED library to the package that ships it).
#   runtime-packages IMAGE "PACKAGES" PATH...
# PATH: a program, or a directory searched for ELF files. A needed package is satisfied when
# PACKAGES names it (or names a package that provides it, e.g. a virtual spdlog name), or
# when the bare base image has it (/base-packages, written by the build stage's first step;
# the test, with no image to ask, sets BASE_PACKAGES_FILE to tests/docker/bookworm-slim-packages).
# Prints what IMAGE needs; exits 1 naming each package missing from PACKAGES.
set -euo pipefail

image=$1 declared=$2
shift 2

binaries=()
for path in "$@"; do
  while IFS= read -r -d '' f; do
    # ELF files only (programs and shared objects), by their magic number.
    [ "$(head -c 4 "$f" | od -An -c | tr -d ' ')" = '177ELF' ] && binaries+=("$(realpath "$f")")
  done < <(find "$path" -type f -print0)
done
[ ${#binaries[@]} -gt 0 ] || { echo "runtime-packages: $image: no programs in $*" >&2; exit 1; }

# dpkg-shlibdeps wants to run in a source package: an empty debian/control will do.
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir "$work/debian" && touch "$work/debian/control"
depends=$(cd "$work" && dpkg-shlibdeps -O "${binaries[@]}" 2>"$work/stderr") ||
  { cat "$work/stderr" >&2; echo "runtime-packages: $image: dpkg-shlibdeps failed" >&2; exit 1; }
depends=${depends#shlibs:Depends=}

# Every package a declared one stands for: itself and what it Provides (from dpkg's status:
# the runtime libraries are installed here as dependencies of the -dev packages).
satisfying=" $declared "
for p in $declared; do
  provides=$(dpkg-query -W -f='${Provides}' "$p" 2>/dev/null | sed -e 's/([^)]*)//g' -e 's/,/ /g') || true
  satisfying+="$provides "
done
base=" $(tr '\n' ' ' <"${BASE_PACKAGES_FILE:-/base-packages}") "

# The package to add for a name: itself, or for a virtual one (a library's shlibs file may name
# one: spdlog's is libspdlog1.10-fmt9) the package here that provides it, the name to list.
package_of() {
  local by
  [[ $(dpkg-query -W -f='${db:Status-Abbrev}' "$1" 2>/dev/null) == i* ]] && { echo "$1"; return; }
  by=$(dpkg-query -W -f='${Package}\t${Provides}\n' | sed 's/([^)]*)//g' |
    awk -F'\t' -v n="$1" '{ k = split($2, p, /[ ,]+/); for (i = 1; i <= k; i++) if (p[i] == n) { print $1; exit } }') || true
  echo "${by:-$1}${by:+ (which provides $1)}"
}

needed=() missing=()
IFS=',' read -ra groups <<<"$depends"
for group in "${groups[@]}"; do
  # One dependency, with alternatives (a | b) and versions (>= x) dropped to names.
  names=$(echo "$group" | sed -e 's/([^)]*)//g' -e 's/|/ /g')
  read -ra alternatives <<<"$names"
  [ ${#alternatives[@]} -gt 0 ] || continue
  ok=0
  for name in "${alternatives[@]}"; do
    name=${name%%:*}
    if [[ $satisfying == *" $name "* || $base == *" $name "* ]]; then ok=1; break; fi
  done
  needed+=("${alternatives[0]%%:*}")
  if [ $ok = 0 ]; then
    add=""
    for name in "${alternatives[@]}"; do add+="${add:+ or }$(package_of "${name%%:*}")"; done
    missing+=("$add")
  fi
done

echo "runtime-packages: $image (${#binaries[@]} ELF files) links: ${needed[*]}"
if [ ${#missing[@]} -gt 0 ]; then
  list=$(printf '%s, ' "${missing[@]}")
  echo "runtime-packages: FAIL: the $image image would lack ${list%, }:" \
    "add it to ${image^^}_PACKAGES at the top of docker/Dockerfile" >&2
  exit 1
fi
