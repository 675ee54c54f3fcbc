#!/usr/bin/env bash
# dtmf-ros-bridge end to end (ctest ros_bridge.e2e): scripts/quickstart --robots 3 starts the
# whole system as a user starts it (air, database, three keyed simulated TurtleBot3s publishing
# their cmd_vel over DDS, the server, the console, the ROS 2 bridge), on ports and a ROS
# domain of its own, then bridge_e2e_tests publishes cmd_vel as ROS 2's tools do and watches
# the robots' cmd_vel, poses and /diagnostics (bridge_e2e_test.cpp).
#   run_bridge_e2e.sh SOURCE_DIR BIN_DIR WORK_DIR TEST_BINARY [gtest arguments...]
set -uo pipefail
src=$1
bin=$2
dir=$3
tests=$4
shift 4
[ -n "$dir" ] && [ "$dir" != / ] || { echo "FAIL: no work directory"; exit 1; }
export DTMF_QUICKSTART_BIN=$bin DTMF_QUICKSTART_DIR=$dir
export DTMF_QUICKSTART_PORT=25490 DTMF_QUICKSTART_PG_PORT=25491 DTMF_QUICKSTART_CONSOLE_PORT=25492
# A domain of its own: no other test's DDS endpoints (domain 0) are seen, nor a user's.
export ROS_DOMAIN_ID=57
unset DTMF_AUDIO_DEVICE CYCLONEDDS_URI
quickstart() { "$src/scripts/quickstart" "$@"; }
clean() {
  quickstart down >/dev/null 2>&1
  "$src/scripts/pg" destroy "$dir/pg" >/dev/null 2>&1
}
clean
rm -rf "$dir"
trap clean EXIT
quickstart --robots 3 --no-sequence || { echo "FAIL: scripts/quickstart --robots 3 --no-sequence"; exit 1; }
# The test's publishers and subscribers set up as the README has a user's ROS 2 tools: on
# loopback, Fast DDS and CycloneDDS alike (the files the package installs).
source "$src/clients/ros_bridge/ros/localhost.sh"
DTMF_E2E_STATE=$dir DTMF_SERVER=localhost:$DTMF_QUICKSTART_PORT "$tests" "$@"
