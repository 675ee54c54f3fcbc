#!/usr/bin/env bash
# cmake --install into a throwaway root, then: every program, unit, setting, migration and
# document is where Debian expects it; the installed programs run; and systemd itself
# (`systemd-analyze verify`, against that root) accepts every unit, with no warning.
#
#   tests/install/install_test.sh BUILD_DIR     (ctest: install.layout_and_units)
set -euo pipefail
build=$(realpath "$1")
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

DESTDIR=$stage cmake --install "$build" --prefix /usr >"$stage.log" 2>&1 || { cat "$stage.log"; fail "cmake --install failed"; }
rm -f "$stage.log"

for f in usr/bin/dtmf-agent usr/bin/dtmf-server usr/bin/dtmfctl usr/bin/dtmf-migrate usr/bin/dtmf-room \
         usr/bin/dtmf-console usr/bin/dtmf-ros-bridge usr/share/dtmf-teleop/console/index.html \
         usr/share/dtmf-teleop/console/vendor/uplot/LICENSE usr/share/doc/dtmf-teleop/console.md \
         usr/share/doc/dtmf-teleop/ros.md usr/share/dtmf-teleop/ros/localhost.sh \
         usr/share/dtmf-teleop/ros/fastdds-localhost.xml usr/share/dtmf-teleop/ros/cyclonedds-localhost.xml \
         usr/lib/systemd/system/dtmf-agent.service usr/lib/systemd/system/dtmf-server.service \
         usr/lib/systemd/system/dtmf-console.service usr/lib/systemd/system/dtmf-ros-bridge.service \
         etc/default/dtmf-agent etc/default/dtmf-server etc/default/dtmf-console etc/default/dtmf-ros-bridge \
         usr/share/dtmf-teleop/migrations/001_schema.sql usr/share/doc/dtmf-teleop/README.md \
         usr/share/doc/dtmf-teleop/protocol.md usr/share/doc/dtmf-teleop/seed.md; do
  [ -e "$stage/$f" ] || fail "not installed: /$f"
done
[ -x "$stage/usr/bin/dtmf-agent" ] || fail "/usr/bin/dtmf-agent is not executable"

# The installed programs run from where they were installed.
grep -q -- "--stop-robot" <<<"$("$stage/usr/bin/dtmf-agent" --help)" || fail "dtmf-agent --help does not offer --stop-robot"
"$stage/usr/bin/dtmf-server" --help >/dev/null || fail "dtmf-server --help failed"
grep -q -- "/usr/share/dtmf-teleop/console" <<<"$("$stage/usr/bin/dtmf-console" --help)" ||
  fail "the installed dtmf-console does not look for its page in /usr/share/dtmf-teleop/console"
[ "$("$stage/usr/bin/dtmfctl" encode --json --word 2861 | grep -o '"frame":"[01]*"')" = '"frame":"1011001011011101"' ] ||
  fail "the installed dtmfctl encodes word 2861 wrongly"

# systemd's own check needs the units the services depend on (sysinit.target, ...): the
# host's, copied beside ours.
cp -rn /usr/lib/systemd/system/. "$stage/usr/lib/systemd/system/"
for unit in dtmf-agent.service dtmf-server.service dtmf-console.service dtmf-ros-bridge.service; do
  out=$(systemd-analyze verify --root="$stage" --recursive-errors=no "$stage/usr/lib/systemd/system/$unit" 2>&1) ||
    fail "systemd-analyze verify $unit: $out"
  [ -z "$out" ] || fail "systemd-analyze verify $unit warns: $out"
  # Every setting of the unit comes from the programs' own environment variables.
  grep -q "^EnvironmentFile=-/etc/default/${unit%.service}$" "$stage/usr/lib/systemd/system/$unit" ||
    fail "$unit does not read /etc/default/${unit%.service}"
  echo "$unit: verified; $(systemd-analyze security --offline=yes --root="$stage" \
    "$stage/usr/lib/systemd/system/$unit" 2>/dev/null | tail -n 1)"
done
grep -q '^ExecStopPost=-/usr/bin/dtmf-agent --stop-robot$' "$stage/usr/lib/systemd/system/dtmf-agent.service" ||
  fail "dtmf-agent.service does not stop the robot after the agent ends"
# Each variable the settings files name is one a program reads.
# (The help is read whole first: `--help | grep -q` under pipefail failed once the help grew
# past one 4 KiB write, as grep -q left at its first match and the program's next write met
# a closed pipe.)
for pair in agent:dtmf-agent server:dtmf-server console:dtmf-console ros_bridge:dtmf-ros-bridge; do
  program=${pair#*:}
  help=$("$stage/usr/bin/$program" --help)
  for var in $(sed -n 's/^#\{0,1\}\(DTMF_[A-Z_]*\)=.*/\1/p' "$stage/etc/default/$program"); do
    grep -q "$var" <<<"$help" || fail "/etc/default/$program names $var, which $program does not read"
  done
done
echo "PASS"
