# scripts/quickstart --robots N: one sender and N simulated TurtleBot3s in one measured room
# (room_air.sh, "A room of several robots"). Sourced by scripts/quickstart, after the air and
# PostgreSQL are up; uses its variables (state, fleet, bin, port, rir, keyed, sequence) and
# functions (start_room_process, stop_process, alive, robot_paired; start_console and
# start_ros_bridge of quickstart_clients.sh).
#
#   robot k (1..N): dtmf-agent --address k --host robot<k> --topic /robot<k>/cmd_vel, its own
#                   key robot<k>.key and the room key room.key, state in agent<k>-state/
#   the sender:     dtmf-server --robots robots.json (robot1..robotN, each with its key) and
#                   --room-key room.key, so that `dtmfctl stop --all` stops them all
# Keys, counters and the roster live in $fleet (build/quickstart/fleet), apart from the
# one-robot set-up's, so that pairing either never touches the other's; logs and PIDs in
# $state as the one robot's. Without --no-key every frame is authenticated under its robot's
# key; the stop for every robot under the room key (docs/security.md, "The room key").

fleet_up() {
  local n=$1 k sinks
  mapfile -t sinks < <(fleet_sinks "$n")
  room_load_sinks "${sinks[@]}"
  for sink in "${sinks[@]}"; do start_room_process "silence-$sink" "$(room_silence_command "$sink")"; done
  for _ in $(seq 100); do room_settled $((${#sinks[@]} + 1)) && break; sleep 0.1; done
  local room=()
  [ "$rir" = none ] || room=(--rir "$(realpath "$rir")" --distance-m 1)
  start_room_process to-sender "$(room_bridge_command to-sender room_air fleet_sender_ear "$bin/dtmf-room" "${room[@]}" --seed 100)"
  for k in $(seq "$n"); do
    start_room_process "to-robot$k" \
      "$(room_bridge_command "to-robot$k" room_air "robot${k}_ear" "$bin/dtmf-room" "${room[@]}" --seed "$k")"
  done
  echo "audio: the PulseAudio air through the room of ${rir}: every loudspeaker into every microphone (${n} robots)"

  eval "$(scripts/pg start "$state/pg" "$pg_port")"
  echo "database: $DTMF_DB_URL"
  export CYCLONEDDS_URI=${CYCLONEDDS_URI:-$QUICKSTART_LOOPBACK_DDS}

  # Keys: one per robot, and the room key every robot and the sender hold. A robot keeps its
  # key while it has its counter state for it; without, that robot is paired afresh with a new
  # key (a robot told --new-key must never get a key it used), and the server, which reads the
  # keys at its start, is restarted with it. The room key needs no --new-key: a robot starts
  # its counters by itself (docs/security.md, "The room key").
  local roster=$fleet/robots.json entries=() new_key=() repaired=0
  mkdir -p "$fleet"
  if [ "$keyed" = 1 ] && [ ! -f "$fleet/room.key" ]; then
    "$bin/dtmfctl" keygen "$fleet/room.key" >/dev/null
    repaired=1
  fi
  for k in $(seq "$n"); do
    new_key[k]=0
    local key_field=""
    if [ "$keyed" = 1 ]; then
      if ! alive "agent$k" && ! robot_paired "$fleet/robot$k.key" "$fleet/agent$k-state"; then
        rm -rf "$fleet/agent$k-state" "$fleet/robot$k.key"
        "$bin/dtmfctl" keygen "$fleet/robot$k.key" >/dev/null
        new_key[k]=1
        repaired=1
      fi
      key_field=", \"key\": \"$(realpath "$fleet/robot$k.key")\""
    fi
    entries+=("{\"name\": \"robot$k\", \"address\": $k, \"model\": \"burger\"$key_field}")
  done
  (IFS=,; echo "[${entries[*]}]") > "$roster"
  [ "$repaired" = 0 ] || stop_process server
  [ "$keyed" = 1 ] && echo "keys: robot1..robot$n each their own key, and the room key $fleet/room.key for stop --all"

  for k in $(seq "$n"); do
    alive "agent$k" && continue
    local keys=()
    if [ "$keyed" = 1 ]; then
      keys=(--key "$fleet/robot$k.key" --room-key "$fleet/room.key" --state-dir "$fleet/agent$k-state")
      [ "${new_key[k]}" = 0 ] || keys+=(--new-key)
    fi
    env PULSE_SINK=room_air PULSE_SOURCE="robot${k}_ear.monitor" "$bin/dtmf-agent" --audio default --ack-out default \
      --address "$k" --host "robot$k" --topic "/robot$k/cmd_vel" --cmd-vel sim,dds --db "$DTMF_DB_URL" "${keys[@]}" \
      --spill-file "$state/agent$k.spill" > "$state/agent$k.out" 2> "$state/agent$k.log" &
    echo $! > "$state/agent$k.pid"
  done
  sleep 1
  for k in $(seq "$n"); do
    alive "agent$k" && continue
    tail -n 3 "$state/agent$k.log" >&2
    echo "quickstart: robot$k's agent stopped (above; $state/agent$k.log). If it refuses its counter state," \
      "pair it afresh: scripts/quickstart down; rm -r $fleet/agent$k-state" >&2
    exit 1
  done
  echo "robots robot1..robot$n started at addresses 1..$n (logs: $state/agent<k>.log; cmd_vel on /robot<k>/cmd_vel)"

  if ! alive server; then
    local server_keys=()
    [ "$keyed" = 1 ] && server_keys=(--room-key "$fleet/room.key" --state-dir "$fleet/server-state")
    env PULSE_SINK=room_air PULSE_SOURCE=fleet_sender_ear.monitor "$bin/dtmf-server" --port "$port" --audio-out default \
      --audio-in default --db "$DTMF_DB_URL" --robots "$roster" "${server_keys[@]}" \
      --spill-file "$state/server.spill" > /dev/null 2> "$state/server.log" &
    echo $! > "$state/server.pid"
    echo "server started on port $port, driving robot1..robot$n (log: $state/server.log)"
  fi
  for _ in $(seq 100); do "$bin/dtmfctl" health --server "localhost:$port" >/dev/null 2>&1 && break; sleep 0.1; done
  "$bin/dtmfctl" health --server "localhost:$port" || { echo "quickstart: the server did not come up; see $state/server.log" >&2; exit 1; }
  start_console
  start_ros_bridge "$n"

  local ctl=("$bin/dtmfctl" --server "localhost:$port")
  echo
  "${ctl[@]}" robots
  if [ "$sequence" = 1 ]; then
    echo
    echo "== robot2 drives, the others stand still; then a stop for every robot"
    "${ctl[@]}" --robot robot2 drive --speed 40 --duration 2 < /dev/null
    "${ctl[@]}" stop --all < /dev/null
  fi
  cat <<MSG

$n robots are running in one room. Try:
  open $(sed -n 's/^console at //p' "$state/console.out" | head -n 1) in a browser: the air, every robot, a picker, STOP EVERY ROBOT
  $bin/dtmfctl --server localhost:$port robots
  $bin/dtmfctl --server localhost:$port --robot robot1 teleop      # one terminal per robot: all drive at once
  $bin/dtmfctl --server localhost:$port --robot robot3 turn --rotation 50 --duration 1
  $bin/dtmfctl --server localhost:$port stop --all                 # every robot, one frame (e in teleop)
  grep sim: $state/agent2.log | tail -3                                  # where robot2 is
  $ros_bridge_try    # robot1 from ROS 2 (robot<k>/cmd_vel)
Stop it all with: scripts/quickstart down
MSG
}
