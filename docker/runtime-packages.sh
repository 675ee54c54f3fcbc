#!/usr/bin/env bash
# Runs in docker/Dockerfile's build stage: checks that a runtime image's package list holds
# every library its programs link, as Debian's own packaging computes it (dpkg-shlibdeps on
# the binaries, which maps each NEEDED library to the package that ships it).
#   runtime-packages IMAGE "PACKAGES" PATH...
# PATH: a program, or a directory searched for ELF files. A needed package is satisfied when
# PACKAGES names it (or names a package that provides it, e.g. a virtual spdlog name), or
# when the bare base image has it (/base-packages, written by the build stage's first step).
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
  [ $ok = 1 ] || missing+=("$(echo "${alternatives[*]}" | sed 's/ / or /g')")
done

echo "runtime-packages: $image (${#binaries[@]} ELF files) links: ${needed[*]}"
if [ ${#missing[@]} -gt 0 ]; then
  echo "runtime-packages: FAIL: the $image image would lack ${missing[*]}:" \
    "add it to ${image^^}_PACKAGES at the top of docker/Dockerfile" >&2
  exit 1
fi
