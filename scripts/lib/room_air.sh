# A room in the PulseAudio air: four more null sinks and two bridges through dtmf-room, so
# that what the sender's loudspeaker plays reaches the robot's microphone through a room,
# and the robot's answer comes back through the same room. Shared by scripts/quickstart
# and scripts/experiments. Source it after `eval "$(scripts/air start DIR)"`; it defines
# functions and constants only.
#
#   sender:  plays into `speaker`,        listens to `sender_ear.monitor`
#   robot:   plays into `robot_speaker`,  listens to `robot_ear.monitor`
#   bridges: speaker.monitor -> dtmf-room -> robot_ear, robot_speaker.monitor -> dtmf-room -> sender_ear

ROOM_SINKS=(speaker robot_ear robot_speaker sender_ear)
ROOM_RAW=(--raw --format=float32le --rate=48000 --channels=1)
# The bridges' buffers: with less, pacat underruns now and then on a busy machine, each time
# playing a few ms of silence into a chord and adding as much to the delay for good.
ROOM_BRIDGE_IN_MS=20   # parec
ROOM_BRIDGE_OUT_MS=60  # pacat
ROOM_BRIDGE_MAX_LAG_MS=50  # dtmf-room: what a pipe may hold before it is dropped
# The measured room the demo and the experiments use unless told otherwise (bench/rirs/README.md).
ROOM_DEFAULT_RIR=bench/rirs/seminar_room_clap.wav

# A room of several robots (scripts/quickstart --robots N): every station plays into one sink,
# `room_air`, and each microphone hears it through the room by a bridge of its own:
#
#   sender:   plays into `room_air`, listens to `fleet_sender_ear.monitor`
#   robot k:  plays into `room_air`, listens to `robot<k>_ear.monitor`
#   bridges:  room_air.monitor -> dtmf-room (its own seed) -> each ear
#
# So every microphone hears the sum of every loudspeaker, its own and the other robots'
# answers included, through the measured room: N + 1 bridges where a path per loudspeaker
# and microphone would take N (N + 1) (12 for three robots, each bridge about 7 % of a core
# here). The price: every path has the response's own distance, and a station's own
# loudspeaker sounds as loud as the others (beside its microphone it is louder: the
# benchmarks model that, `dtmf-bench-roundtrip`).
fleet_sinks() {
  local k
  printf "%s\n" room_air fleet_sender_ear
  for k in $(seq "$1"); do echo "robot${k}_ear"; done
}

# room_load_sinks [SINK...]: the sinks (default the four of the one-robot room); a no-op for
# those already there.
room_load_sinks() {
  local sink sinks=("$@")
  [ ${#sinks[@]} -gt 0 ] || sinks=("${ROOM_SINKS[@]}")
  for sink in "${sinks[@]}"; do
    # awk reads the whole list (grep -q would stop early, and under pipefail the listing's
    # SIGPIPE would read as "not there" and load the sink twice).
    LC_ALL=C timeout 5 pactl list short sinks | awk -v s="$sink" '$2 == s { found = 1 } END { exit !found }' && continue
    LC_ALL=C timeout 5 pactl load-module module-null-sink "sink_name=$sink" rate=48000 channels=1 format=float32le >/dev/null
  done
}

# room_unload_sinks SINK...: unloads the null sinks of these names (a no-op for those not there),
# so that the air is as the tests without a room know it (PulseAudio keeps rendering an idle
# null sink).
room_unload_sinks() {
  LC_ALL=C timeout 5 pactl list short modules | awk -v sinks=" $* " \
    '$2 == "module-null-sink" && match($0, /sink_name=[^ \t]+/) &&
     index(sinks, " " substr($0, RSTART + 10, RLENGTH - 10) " ") { print $1 }' |
    while read -r module; do LC_ALL=C timeout 5 pactl unload-module "$module"; done
}

# room_silence_command SINK: a silent low-latency stream that keeps SINK rendering in small
# blocks (as scripts/air does for `air`); without it a null sink plays in 2 s blocks.
room_silence_command() {
  echo "exec pacat --playback -d $1 ${ROOM_RAW[*]} --latency-msec=20 --client-name=silence-$1 </dev/zero"
}

# room_settled [COUNT]: every sink with less than 50 ms queued, and at least COUNT sinks
# (default: the air and the one-robot room's four).
room_settled() {
  LC_ALL=C timeout 5 pactl list sinks | sed -n 's/^\s*Latency: \([0-9]*\) usec.*/\1/p' |
    awk -v want="${1:-$((${#ROOM_SINKS[@]} + 1))}" 'BEGIN { ok = 1; n = 0 } { n++; if ($1 >= 50000) ok = 0 } END { exit !(ok && n >= want) }'
}

# room_bridge_command NAME FROM TO DTMF_ROOM [ROOM ARGS...]: the pipeline (bash text) that
# plays what FROM's loudspeaker plays into TO, through `DTMF_ROOM ROOM ARGS`.
room_bridge_command() {
  local name=$1 from=$2 to=$3 room=$4
  shift 4
  # --max-lag-ms: sound queued in a pipe is late for good (both ends keep the same pace), so
  # the filter drops what waits longer (tools/room/lag_keeper.h); without it the delay
  # through a bridge grew from 370 to 870 ms within one 70 s run.
  printf 'parec -d %s.monitor %s --latency-msec=%s --client-name=%s-in | %q --max-lag-ms %s' "$from" "${ROOM_RAW[*]}" \
    "$ROOM_BRIDGE_IN_MS" "$name" "$room" "$ROOM_BRIDGE_MAX_LAG_MS"
  # No ROOM ARGS: print none (printf with a format and no arguments still prints it once: '').
  [ $# -eq 0 ] || printf ' %q' "$@"
  printf ' | pacat --playback -d %s %s --latency-msec=%s --client-name=%s-out\n' "$to" "${ROOM_RAW[*]}" \
    "$ROOM_BRIDGE_OUT_MS" "$name"
}
