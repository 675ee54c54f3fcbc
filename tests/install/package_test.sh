#!/usr/bin/env bash
# The Debian packages as a user gets them: scripts/package builds the three from the test
# build tree (cpack, dpkg-shlibdeps, lintian with no error or warning), then each is
# unpacked into a fresh root (dpkg -x) with its computed dependencies checked against this
# machine's dpkg database, and the programs run from that root: every --help, --version,
# and `dtmfctl encode --word 2861`.
#
#   tests/install/package_test.sh SOURCE_DIR BUILD_DIR     (ctest: install.debian_packages)
set -euo pipefail
source_dir=$(realpath "$1")
build=$(realpath "$2")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

"$source_dir/scripts/package" --from "$build" --out "$work/dist" >"$work/package.log" 2>&1 ||
  { cat "$work/package.log"; fail "scripts/package failed"; }
declare -A deb
for name in agent server cli; do
  deb[$name]=$(ls "$work"/dist/dtmf-teleop-${name}_*.deb 2>/dev/null) || fail "no dtmf-teleop-$name package"
  grep -qx "${deb[$name]}" "$work/package.log" || fail "scripts/package did not list ${deb[$name]}"
done

# One "Depends" alternative is met when dpkg has the package installed at that version.
satisfied() {
  local alt name op version installed
  IFS='|' read -ra alts <<<"$1"
  for alt in "${alts[@]}"; do
    read -r name op version <<<"$(sed -E 's/^ *([^ (]+) *(\(([<>=]+) *([^)]+)\))? *$/\1 \3 \4/' <<<"$alt")"
    name=${name%:any}
    installed=$(dpkg-query -W -f='${Status} ${Version}' "$name" 2>/dev/null | sed -n 's/^install ok installed //p')
    # A virtual package (libspdlog1.10-fmt9) is met by an installed package that provides it.
    if [ -z "$installed" ] && [ -z "$op" ] && grep -qx "$name" "$work/provided"; then return 0; fi
    [ -n "$installed" ] || continue
    [ -z "$op" ] && return 0
    case $op in '>=') op=ge ;; '<=') op=le ;; '=') op=eq ;; '>>') op=gt ;; '<<') op=lt ;; esac
    dpkg --compare-versions "$installed" "$op" "$version" && return 0
  done
  return 1
}

root=$work/root
dpkg-query -W -f='${db:Status-Abbrev} ${Provides}\n' | sed -n 's/^ii  *//p' | tr ',' '\n' |
  sed -E 's/^ *([^ ]+).*/\1/; s/:any$//' | grep -v '^$' | sort -u >"$work/provided"
for name in agent server cli; do
  depends=$(dpkg-deb -f "${deb[$name]}" Depends)
  # Computed by dpkg-shlibdeps from the programs' libraries, so the C++ runtime is there.
  grep -q "libstdc++6" <<<"$depends" || fail "dtmf-teleop-$name: Depends was not computed: '$depends'"
  IFS=',' read -ra entries <<<"$depends"
  for entry in "${entries[@]}"; do
    satisfied "$entry" || fail "dtmf-teleop-$name needs '$entry', which this machine lacks"
  done
  echo "dtmf-teleop-$name: Depends: $depends"
  dpkg -x "${deb[$name]}" "$root"
  dpkg-deb --ctrl-tarfile "${deb[$name]}" | tar -x -O ./conffiles 2>/dev/null >"$work/conffiles" || true
  for doc in copyright changelog.Debian.gz; do
    [ -f "$root/usr/share/doc/dtmf-teleop-$name/$doc" ] || fail "dtmf-teleop-$name has no /usr/share/doc/dtmf-teleop-$name/$doc"
  done
  case $name in
    agent | server)
      grep -qx "/etc/default/dtmf-$name" "$work/conffiles" || fail "dtmf-teleop-$name: /etc/default/dtmf-$name is no conffile"
      [ -f "$root/lib/systemd/system/dtmf-$name.service" ] || [ -f "$root/usr/lib/systemd/system/dtmf-$name.service" ] ||
        fail "dtmf-teleop-$name has no systemd unit" ;;
  esac
done
grep -q "libddsc" <<<"$(dpkg-deb -f "${deb[agent]}" Depends)" || fail "the agent's package does not depend on CycloneDDS"
grep -q "libgrpc++" <<<"$(dpkg-deb -f "${deb[server]}" Depends)" || fail "the server's package does not depend on gRPC"
# dtmf-ros-bridge links CycloneDDS too (computed as the agent's: nothing in packaging.cmake names it).
if grep -q '/usr/bin/dtmf-ros-bridge$' <<<"$(dpkg-deb -c "${deb[server]}")"; then
  grep -q "libddsc" <<<"$(dpkg-deb -f "${deb[server]}" Depends)" ||
    fail "the server's package holds dtmf-ros-bridge but does not depend on CycloneDDS"
fi

# The programs, from the unpacked root.
for program in dtmf-agent dtmf-server dtmf-migrate dtmfctl dtmf-room; do
  [ -x "$root/usr/bin/$program" ] || fail "no /usr/bin/$program in the packages"
  "$root/usr/bin/$program" --help >/dev/null || fail "$program --help failed from the package"
  [ "$("$root/usr/bin/$program" --version)" = "$program $(dpkg-deb -f "${deb[cli]}" Version | sed 's/-[^-]*$//')" ] ||
    fail "$program --version: '$("$root/usr/bin/$program" --version)'"
  [ -f "$root/usr/share/man/man1/$program.1.gz" ] || fail "no manual page for $program"
done
[ "$("$root/usr/bin/dtmfctl" encode --json --word 2861 | grep -o '"frame":"[01]*"')" = '"frame":"1011001011011101"' ] ||
  fail "the packaged dtmfctl encodes word 2861 wrongly"
file "$root/usr/bin/dtmf-agent" | grep -q "stripped" && ! file "$root/usr/bin/dtmf-agent" | grep -q "not stripped" ||
  fail "the packaged dtmf-agent is not stripped"
echo "PASS"
