# The clients scripts/quickstart starts once the server answers, for one robot or several:
# the web console and the ROS 2 bridge. Sourced by scripts/quickstart; uses its variables
# (state, bin, port, console_port) and its function alive.

# DDS on this machine only (loopback), for the agents' cmd_vel and the bridge's: the
# quickstart's CYCLONEDDS_URI, unless the user has set one. The bridge's own default
# (clients/ros_bridge/bridge_setup.cpp, kLoopbackOnly): discovery as ROS 2's
# ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST has it, up to 33 DDS processes on this machine
# (Cyclone's default is 10: seven robots, the bridge and three ROS 2 tools would be 11).
QUICKSTART_LOOPBACK_DDS='<General><Interfaces><NetworkInterface name="lo"/></Interfaces><AllowMulticast>false</AllowMulticast></General><Discovery><ParticipantIndex>auto</ParticipantIndex><MaxAutoParticipantIndex>32</MaxAutoParticipantIndex><Peers><Peer address="localhost"/></Peers></Discovery><Internal><MaxSampleSize>65536B</MaxSampleSize></Internal>'

# start_console: the web console, on loopback, relaying to the server; prints its address.
start_console() {
  if ! alive console; then
    rm -f "$state/console.out"
    "$bin/dtmf-console" --server "localhost:$port" --port "$console_port" > "$state/console.out" 2> "$state/console.log" &
    echo $! > "$state/console.pid"
  fi
  for _ in $(seq 100); do grep -q "^console at " "$state/console.out" 2>/dev/null && break; alive console || break; sleep 0.1; done
  if ! alive console; then
    tail -n 3 "$state/console.log" >&2
    echo "quickstart: the web console stopped (above; $state/console.log); is port $console_port taken?" \
      "(DTMF_QUICKSTART_CONSOLE_PORT=...)" >&2
    exit 1
  fi
  echo "web console: $(sed -n 's/^console at //p' "$state/console.out" | head -n 1) (open it in a browser on this machine)"
}

# How to drive through the bridge, for the closing "Try:" list; what went wrong, when it did.
ros_bridge_try="(no ROS 2 bridge: see above)"

# start_ros_bridge ROBOTS: dtmf-ros-bridge, taking cmd_vel from ROS 2 on the domain the agents
# publish theirs on (ROS_DOMAIN_ID, else 0: what ros2 in this shell uses too), and prints how
# to drive with it. The agents' own cmd_vel it recognises and never takes (dds_inputs.h). Not
# built (a build without DTMF_BUILD_ROS_BRIDGE), it is said and the quickstart goes on; built
# and not starting, the quickstart stops, as for the console: what it prints would be untrue.
start_ros_bridge() {
  local robots=$1 line domain reach remap=""
  if [ ! -x "$bin/dtmf-ros-bridge" ]; then
    echo "ROS 2 bridge: not built ($bin/dtmf-ros-bridge is missing); going on without it"
    ros_bridge_try="(no ROS 2 bridge: dtmf-ros-bridge is not built)"
    return 0
  fi
  if ! alive ros-bridge; then
    rm -f "$state/ros-bridge.out"
    "$bin/dtmf-ros-bridge" --server "localhost:$port" --domain "${ROS_DOMAIN_ID:-0}" \
      > "$state/ros-bridge.out" 2> "$state/ros-bridge.log" &
    echo $! > "$state/ros-bridge.pid"
  fi
  for _ in $(seq 100); do
    grep -q "^ros bridge on domain " "$state/ros-bridge.out" 2>/dev/null && break
    alive ros-bridge || break
    sleep 0.1
  done
  line=$(grep -m 1 "^ros bridge on domain " "$state/ros-bridge.out" 2>/dev/null || true)
  if [ -z "$line" ]; then
    tail -n 3 "$state/ros-bridge.log" >&2
    if alive ros-bridge; then
      echo "quickstart: the ROS 2 bridge did not say it was ready within 10 s (above; $state/ros-bridge.log)" >&2
    else
      echo "quickstart: the ROS 2 bridge stopped (above; $state/ros-bridge.log); is ROS_DOMAIN_ID a domain (0-232)?" >&2
    fi
    exit 1
  fi
  domain=$(sed -n 's/^ros bridge on domain \([0-9]*\):.*/\1/p' <<<"$line")
  # The bridge keeps to loopback unless CYCLONEDDS_URI says otherwise (the user's, not ours).
  reach="this machine only"
  [ "${CYCLONEDDS_URI:-}" = "$QUICKSTART_LOOPBACK_DDS" ] || reach="DDS as CYCLONEDDS_URI sets it"
  # Several robots: one cmd_vel each, under its name (bridge_topics.h); the keyboard drives robot1.
  [ "$robots" -gt 1 ] && remap="-r cmd_vel:=robot1/cmd_vel "
  # repeat_rate: the keyboard repeats its last twist 10 times a second; without it the bridge
  # stops the robot half a second after each key press (its --timeout-s, as twist_mux's).
  # localhost.sh: the ROS 2 tools on loopback too, where the bridge can reach them (docs/ros.md).
  ros_bridge_try="source clients/ros_bridge/ros/localhost.sh; ros2 run teleop_twist_keyboard teleop_twist_keyboard --ros-args ${remap}-p repeat_rate:=10.0"
  echo "ROS 2 bridge: ${line#ros bridge on } (log: $state/ros-bridge.log)"
  if [ "$robots" -gt 1 ]; then
    echo "ROS 2: robot<k>/cmd_vel on domain $domain ($reach): $ros_bridge_try"
  else
    echo "ROS 2: cmd_vel on domain $domain ($reach): $ros_bridge_try"
  fi
}
