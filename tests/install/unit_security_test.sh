#!/usr/bin/env bash
# systemd's own judgement of the units' sandboxes: `systemd-analyze security --offline=true`
# (systemd 250 and later) on each unit file as shipped, whose overall exposure level (0.0
# safest, 10.0 unsafe) must be 2.0 or less. Offline, the settings are read from the file, so no
# running systemd, no installation and no build is needed. The units must also keep what the
# programs need: the sound card, real-time priority, and a private state directory.
#
#   tests/install/unit_security_test.sh SOURCE_DIR     (ctest: install.unit_exposure)
set -euo pipefail
source_dir=$(realpath "$1")
fail() { echo "FAIL: $*" >&2; exit 1; }
command -v systemd-analyze >/dev/null || fail "systemd-analyze is missing (apt-get install systemd)"

for unit in robot_agent/systemd/dtmf-agent.service server/systemd/dtmf-server.service; do
  file=$source_dir/$unit
  name=$(basename "$unit")
  report=$(systemd-analyze security --offline=true "$file" 2>&1) || fail "systemd-analyze security $name: $report"
  score=$(printf '%s\n' "$report" | sed -n "s/.*Overall exposure level for $name: \([0-9][0-9.]*\).*/\1/p")
  [ -n "$score" ] || fail "systemd-analyze security $name gave no overall exposure level: $report"
  awk -v s="$score" 'BEGIN { exit !(s <= 2.0) }' ||
    fail "$name: exposure level $score, above 2.0; what systemd counts against it:
$(printf '%s\n' "$report" | grep '✗')"
  # What the sandbox must leave the programs.
  for setting in 'StateDirectoryMode=0700' 'DeviceAllow=char-alsa rw' 'LimitRTPRIO=4' \
                 'SystemCallFilter=@system-service' 'SystemCallFilter=~@privileged'; do
    grep -qx "$setting" "$file" || fail "$name lacks $setting"
  done
  # Real time is raised with sched_setscheduler / setpriority (@resources): neither may be filtered.
  ! grep -Eq '^(RestrictRealtime=(yes|true)|SystemCallFilter=~.*@resources)' "$file" ||
    fail "$name forbids real-time scheduling, which the audio threads need (protocol/physical/realtime_priority.cpp)"
  ! grep -Eq '^PrivateDevices=(yes|true)' "$file" || fail "$name hides the sound card (PrivateDevices=yes)"
  echo "$name: exposure level $score"
done
# The console and the ROS 2 bridge touch no device and need no real time: only their
# exposure is judged.
for unit in clients/console/systemd/dtmf-console.service clients/ros_bridge/systemd/dtmf-ros-bridge.service; do
  file=$source_dir/$unit
  name=$(basename "$unit")
  report=$(systemd-analyze security --offline=true "$file" 2>&1) || fail "systemd-analyze security $name: $report"
  score=$(printf '%s\n' "$report" | sed -n "s/.*Overall exposure level for $name: \([0-9][0-9.]*\).*/\1/p")
  [ -n "$score" ] || fail "systemd-analyze security $name gave no overall exposure level: $report"
  awk -v s="$score" 'BEGIN { exit !(s <= 2.0) }' || fail "$name: exposure level $score, above 2.0:
$(printf '%s\n' "$report" | grep '✗')"
  echo "$name: exposure level $score"
done
echo "PASS"
