#!/usr/bin/env bash
# scripts/lib/apt_sources.sh against apt configurations written here: deb822 and one-line
# sources, disabled entries, options in brackets, suites that merely start with the one
# asked, and none at all. Prints PASS when every case holds.
set -uo pipefail
source "$1/scripts/lib/apt_sources.sh"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
failed=0
expect() {  # expect WANT SUITE: debian_mirror SUITE prints WANT (or fails when WANT is "FAIL")
  local got
  got=$(APT_SOURCES_DIR=$dir debian_mirror "$2" 2>/dev/null) || got=FAIL
  if [ "$got" != "$1" ]; then echo "FAIL: ${3:-}: wanted '$1' for $2, got '$got'"; failed=1; fi
}
mkdir -p "$dir/sources.list.d"

cat >"$dir/sources.list.d/debian.sources" <<'SRC'
Types: deb
URIs: http://disabled.example/debian
Suites: bookworm
Components: main
Enabled: no

Types: deb-src
URIs: http://sources-only.example/debian
Suites: bookworm
Components: main

# a comment between paragraphs
Types: deb
URIs: http://updates.example/debian
Suites: bookworm-updates
Components: main

Types: deb deb-src
URIs: http://mirror.local/debian/ http://second.example/debian
Suites: bookworm bookworm-updates
Components: main
SRC
expect http://mirror.local/debian bookworm "deb822: the first enabled deb source offering the suite"
expect http://updates.example/debian bookworm-updates "deb822: another suite"
expect FAIL trixie "no source offers it"

rm "$dir/sources.list.d/debian.sources"
printf 'deb-src http://src.example/debian bookworm main\n# deb http://commented.example/debian bookworm main\n' \
  >"$dir/sources.list"
printf 'deb [arch=amd64 signed-by=/k.gpg] http://proxy.local:3142/debian bookworm main\n' \
  >"$dir/sources.list.d/local.list"
expect http://proxy.local:3142/debian bookworm "one-line, options in brackets, comments and deb-src skipped"

rm -rf "$dir/sources.list.d" "$dir/sources.list"
expect FAIL bookworm "no apt sources at all"

[ $failed -eq 0 ] && echo PASS
