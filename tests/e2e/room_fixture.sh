#!/usr/bin/env bash
# ctest fixture "room": a measured room inside the test air (scripts/lib/room_air.sh), both
# ways, as scripts/quickstart builds it. The end-to-end tests play and listen through it:
#
#   sender: PULSE_SINK=speaker       PULSE_SOURCE=sender_ear.monitor
#   robot:  PULSE_SINK=robot_speaker PULSE_SOURCE=robot_ear.monitor
#
#   room_fixture.sh start AIR_DIR DTMF_ROOM RIR   load the sinks, start the silent streams
#                                                 and the two bridges (1 m through RIR)
#   room_fixture.sh stop AIR_DIR                  stop them and unload the sinks
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/lib/room_air.sh

action=${1:?start or stop}
air=$(realpath -m -- "${2:?the directory of the air}")
state=$air/room
export PULSE_SERVER=unix:$air/native

alive() { [ -f "$state/$1.pid" ] && kill -0 "$(cat "$state/$1.pid")" 2>/dev/null; }
processes=(to-robot to-sender "${ROOM_SINKS[@]/#/silence-}")

stop_all() {
  local p
  for p in "${processes[@]}"; do
    alive "$p" && kill -TERM -- "-$(cat "$state/$p.pid")" 2>/dev/null || true
    rm -f "$state/$p.pid"
  done
}

case $action in
  stop)
    stop_all
    # The sinks too: the air is as the tests without the room know it.
    [ -S "$air/native" ] && room_unload_sinks "${ROOM_SINKS[@]}"
    exit 0 ;;
  start) ;;
  *) echo "room_fixture.sh: start or stop, not '$action'" >&2; exit 2 ;;
esac

dtmf_room=${3:?the dtmf-room program}
rir=$(realpath -- "${4:?a room impulse response (WAV)}")
[ -S "$air/native" ] || { echo "room_fixture.sh: no air in $air (ctest fixture air first)" >&2; exit 1; }
mkdir -p "$state"
stop_all  # a former run's bridges, if a test run was interrupted

# start NAME COMMAND: COMMAND (bash text) in its own session, so that stop ends the whole pipeline.
start() {
  setsid bash -c "$2" > "$state/$1.log" 2>&1 < /dev/null &
  echo $! > "$state/$1.pid"
}

room_load_sinks
for sink in "${ROOM_SINKS[@]}"; do start "silence-$sink" "$(room_silence_command "$sink")"; done
for _ in $(seq 100); do room_settled && break; sleep 0.1; done
room_settled || { echo "room_fixture.sh: the room's sinks did not settle within 10 s" >&2; exit 1; }
room=(--rir "$rir" --distance-m 1)
start to-robot "$(room_bridge_command to-robot speaker robot_ear "$dtmf_room" "${room[@]}" --seed 1)"
start to-sender "$(room_bridge_command to-sender robot_speaker sender_ear "$dtmf_room" "${room[@]}" --seed 2)"
sleep 1
for p in "${processes[@]}"; do
  alive "$p" || { echo "room_fixture.sh: $p died:" >&2; cat "$state/$p.log" >&2; stop_all; exit 1; }
done
echo "room: $rir at 1 m, both ways (bridges to-robot and to-sender running)"
