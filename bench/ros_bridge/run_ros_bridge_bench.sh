#!/usr/bin/env bash
# dtmf-ros-bridge's benchmark (issue 62's targets): scripts/quickstart with one robot through
# the seminar room both ways, keyed and then without a key, each time with the bridge it
# starts, on ports and a ROS domain of their own; dtmf-bench-ros-bridge drives the bridge over
# DDS as ROS 2's tools do (ros/localhost.sh) and writes OUT_DIR/ros_bridge_{keyed,unkeyed}.json.
#   run_ros_bridge_bench.sh SOURCE_DIR BIN_DIR WORK_DIR OUT_DIR [dtmf-bench-ros-bridge arguments...]
# DTMF_ROS_BRIDGE_BENCH_VARIANTS: which to run ("keyed unkeyed"; the suite's smoke test: keyed).
set -uo pipefail
src=$1
bin=$2
dir=$3
out=$4
shift 4
[ -n "$dir" ] && [ "$dir" != / ] || { echo "FAIL: no work directory"; exit 1; }
export DTMF_QUICKSTART_BIN=$bin DTMF_QUICKSTART_DIR=$dir
export DTMF_QUICKSTART_PORT=25480 DTMF_QUICKSTART_PG_PORT=25481 DTMF_QUICKSTART_CONSOLE_PORT=25482
export ROS_DOMAIN_ID=58
unset DTMF_AUDIO_DEVICE CYCLONEDDS_URI
quickstart() { "$src/scripts/quickstart" "$@"; }
clean() {
  quickstart down >/dev/null 2>&1
  "$src/scripts/pg" destroy "$dir/pg" >/dev/null 2>&1
}
trap clean EXIT
mkdir -p "$out"
status=0
for variant in ${DTMF_ROS_BRIDGE_BENCH_VARIANTS:-keyed unkeyed}; do
  clean
  rm -rf "$dir"
  flags=(--no-sequence)
  [ "$variant" = keyed ] || flags+=(--no-key)
  quickstart "${flags[@]}" > "$out/ros_bridge_$variant.quickstart.log" 2>&1 ||
    { echo "FAIL: scripts/quickstart ${flags[*]} (see $out/ros_bridge_$variant.quickstart.log)"; status=1; continue; }
  # The bench's own DDS endpoints set up as a user's ROS 2 tools (README).
  (source "$src/clients/ros_bridge/ros/localhost.sh"
   "$bin/dtmf-bench-ros-bridge" --state-dir "$dir" --domain "$ROS_DOMAIN_ID" --server "localhost:$DTMF_QUICKSTART_PORT" \
     --fastdds-publisher "$bin/fastdds_twist_publisher" --dtmfctl "$bin/dtmfctl" \
     --keyed "$([ "$variant" = keyed ] && echo true || echo false)" --json "$out/ros_bridge_$variant.json" "$@") ||
    { echo "FAIL: dtmf-bench-ros-bridge ($variant)"; status=1; }
done
exit "$status"
