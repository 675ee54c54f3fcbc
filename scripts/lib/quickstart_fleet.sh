# scripts/quickstart --robots N: one sender and N simulated TurtleBot3s in one measured room
# (room_air.sh, "A room of several robots"). Sourced by scripts/quickstart, after the air and
# PostgreSQL are up; uses its variables (state, port, rir, keyed) and functions
# (start_room_process, alive).
#
#   robot k (1..N): dtmf-agent --address k --host robot<k> --topic /robot<k>/cmd_vel, its own
#                   key robot<k>.key and the room key room.key, state in agent<k>-state/
#   the sender:     dtmf-server --robots robots.json (robot1..robotN, each with its key) and
#                   --room-key room.key, so that `dtmfctl stop --all` stops them all
# Without --no-key every frame is authenticated under its robot's key; the stop for every
# robot under the room key (docs/security.md, "The room key").

fleet_up() {
  local n=$1 k sinks
  mapfile -t sinks < <(fleet_sinks "$n")
  room_load_sinks "${sinks[@]}"
  for sink in "${sinks[@]}"; do start_room_process "silence-$sink" "$(room_silence_command "$sink")"; done
  for _ in $(seq 100); do room_settled $((${#sinks[@]} + 1)) && break; sleep 0.1; done
  local room=()
  [ "$rir" = none ] || room=(--rir "$(realpath "$rir")" --distance-m 1)
  start_room_process to-sender "$(room_bridge_command to-sender room_air fleet_sender_ear build/bin/dtmf-room "${room[@]}" --seed 100)"
  for k in $(seq "$n"); do
    start_room_process "to-robot$k" \
      "$(room_bridge_command "to-robot$k" room_air "robot${k}_ear" build/bin/dtmf-room "${room[@]}" --seed "$k")"
  done
  echo "audio: the PulseAudio air through the room of ${rir}: every loudspeaker into every microphone (${n} robots)"

  eval "$(scripts/pg start "$state/pg" "$pg_port")"
  echo "database: $DTMF_DB_URL"
  export CYCLONEDDS_URI=${CYCLONEDDS_URI:-'<General><Interfaces><NetworkInterface name="lo"/></Interfaces></General>'}

  # Keys: one per robot, and the room key every robot and the sender hold.
  local roster=$state/robots.json entries=() new_keys=0
  if [ "$keyed" = 1 ] && [ ! -f "$state/room.key" ]; then
    # Pairing afresh, every key new: a robot told --new-key must never get a key it used.
    rm -rf "$state"/agent*-state "$state/server-state" "$state"/robot*.key
    build/bin/dtmfctl keygen "$state/room.key" >/dev/null
    new_keys=1
  fi
  for k in $(seq "$n"); do
    local key_field=""
    if [ "$keyed" = 1 ]; then
      [ -f "$state/robot$k.key" ] || build/bin/dtmfctl keygen "$state/robot$k.key" >/dev/null
      key_field=", \"key\": \"$(realpath "$state/robot$k.key")\""
    fi
    entries+=("{\"name\": \"robot$k\", \"address\": $k, \"model\": \"burger\"$key_field}")
  done
  (IFS=,; echo "[${entries[*]}]") > "$roster"
  [ "$keyed" = 1 ] && echo "keys: robot1..robot$n each their own key, and the room key $state/room.key for stop --all"

  for k in $(seq "$n"); do
    alive "agent$k" && continue
    local keys=()
    if [ "$keyed" = 1 ]; then
      keys=(--key "$state/robot$k.key" --room-key "$state/room.key" --state-dir "$state/agent$k-state")
      [ "$new_keys" = 0 ] || keys+=(--new-key)
    fi
    env PULSE_SINK=room_air PULSE_SOURCE="robot${k}_ear.monitor" build/bin/dtmf-agent --audio default --ack-out default \
      --address "$k" --host "robot$k" --topic "/robot$k/cmd_vel" --cmd-vel sim,dds --db "$DTMF_DB_URL" "${keys[@]}" \
      --spill-file "$state/agent$k.spill" > "$state/agent$k.out" 2> "$state/agent$k.log" &
    echo $! > "$state/agent$k.pid"
  done
  sleep 1
  for k in $(seq "$n"); do
    alive "agent$k" || { tail -n 3 "$state/agent$k.log" >&2; echo "quickstart: robot$k's agent stopped (above)" >&2; exit 1; }
  done
  echo "robots robot1..robot$n started at addresses 1..$n (logs: $state/agent<k>.log; cmd_vel on /robot<k>/cmd_vel)"

  if ! alive server; then
    local server_keys=()
    [ "$keyed" = 1 ] && server_keys=(--room-key "$state/room.key" --state-dir "$state/server-state")
    env PULSE_SINK=room_air PULSE_SOURCE=fleet_sender_ear.monitor build/bin/dtmf-server --port "$port" --audio-out default \
      --audio-in default --db "$DTMF_DB_URL" --robots "$roster" "${server_keys[@]}" \
      --spill-file "$state/server.spill" > /dev/null 2> "$state/server.log" &
    echo $! > "$state/server.pid"
    echo "server started on port $port, driving robot1..robot$n (log: $state/server.log)"
  fi
  for _ in $(seq 100); do build/bin/dtmfctl health --server "localhost:$port" >/dev/null 2>&1 && break; sleep 0.1; done
  build/bin/dtmfctl health --server "localhost:$port" || { echo "quickstart: the server did not come up; see $state/server.log" >&2; exit 1; }

  local ctl=(build/bin/dtmfctl --server "localhost:$port")
  echo
  "${ctl[@]}" robots
  echo
  echo "== robot2 drives, the others stand still; then a stop for every robot"
  "${ctl[@]}" --robot robot2 drive --speed 40 --duration 2 < /dev/null
  "${ctl[@]}" stop --all < /dev/null
  cat <<MSG

$n robots are running in one room. Try:
  build/bin/dtmfctl --server localhost:$port robots
  build/bin/dtmfctl --server localhost:$port --robot robot1 teleop      # one terminal per robot: all drive at once
  build/bin/dtmfctl --server localhost:$port --robot robot3 turn --rotation 50 --duration 1
  build/bin/dtmfctl --server localhost:$port stop --all                 # every robot, one frame (e in teleop)
  grep sim: $state/agent2.log | tail -3                                  # where robot2 is
Stop it all with: scripts/quickstart down
MSG
}
