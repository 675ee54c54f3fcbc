#!/usr/bin/env bash
# A room of several robots inside the test air (scripts/lib/room_air.sh, "A room of several
# robots"), as `scripts/quickstart --robots N` builds it: every station plays into room_air,
# and each microphone (fleet_sender_ear, robot1_ear .. robotN_ear) hears it through the
# measured room by a bridge of its own. tests/e2e/fleet_e2e_test.cpp starts and stops it.
#
#   fleet_fixture.sh start AIR_DIR DTMF_ROOM RIR N   load the sinks, start the silent streams and bridges
#   fleet_fixture.sh stop AIR_DIR                    stop them and unload the sinks
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/lib/room_air.sh

action=${1:?start or stop}
air=$(realpath -m -- "${2:?the directory of the air}")
state=$air/fleet
export PULSE_SERVER=unix:$air/native

alive() { [ -f "$1" ] && kill -0 "$(cat "$1")" 2>/dev/null; }
stop_all() {
  local pid
  for pid in "$state"/*.pid; do
    [ -e "$pid" ] || continue
    alive "$pid" && kill -TERM -- "-$(cat "$pid")" 2>/dev/null || true
    rm -f "$pid"
  done
}

case $action in
  stop)
    stop_all
    [ -S "$air/native" ] && room_unload_sinks $(fleet_sinks 7)
    exit 0 ;;
  start) ;;
  *) echo "fleet_fixture.sh: start or stop, not '$action'" >&2; exit 2 ;;
esac

dtmf_room=${3:?the dtmf-room program}
rir=$(realpath -- "${4:?a room impulse response (WAV)}")
robots=${5:?how many robots}
[ -S "$air/native" ] || { echo "fleet_fixture.sh: no air in $air (ctest fixture air first)" >&2; exit 1; }
mkdir -p "$state"
stop_all

start() {
  setsid bash -c "$2" > "$state/$1.log" 2>&1 < /dev/null &
  echo $! > "$state/$1.pid"
}

mapfile -t sinks < <(fleet_sinks "$robots")
room_load_sinks "${sinks[@]}"
for sink in "${sinks[@]}"; do start "silence-$sink" "$(room_silence_command "$sink")"; done
for _ in $(seq 100); do room_settled $((${#sinks[@]} + 1)) && break; sleep 0.1; done
room_settled $((${#sinks[@]} + 1)) || { echo "fleet_fixture.sh: the sinks did not settle within 10 s" >&2; exit 1; }
room=(--rir "$rir" --distance-m 1)
start to-sender "$(room_bridge_command to-sender room_air fleet_sender_ear "$dtmf_room" "${room[@]}" --seed 100)"
for k in $(seq "$robots"); do
  start "to-robot$k" "$(room_bridge_command "to-robot$k" room_air "robot${k}_ear" "$dtmf_room" "${room[@]}" --seed "$k")"
done
sleep 1
for pid in "$state"/*.pid; do
  alive "$pid" || { echo "fleet_fixture.sh: $(basename "$pid" .pid) died:" >&2; cat "${pid%.pid}.log" >&2; stop_all; exit 1; }
done
echo "fleet room: $rir, $robots robots and the sender, every loudspeaker into every microphone"
