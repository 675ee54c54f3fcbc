# scripts/lib/compose_wait.sh: how scripts/compose-check tells that the stack is up, sourced
# by it (its compose, say, fail and elapsed). COMPOSE_SERVICES: every service of
# docker/compose.yaml, for the waits, the logs and the libraries. wait_ready WHAT DEADLINE_S:
# until postgres, air and server are healthy, agent, console and ros-bridge run (ros-bridge
# having said it is ready) and migrate exited 0; fails naming the laggard (with its log) at
# the deadline, or at once when migrate failed.

COMPOSE_SERVICES="postgres air migrate agent server console ros-bridge"

state_of() {  # state_of SERVICE: "status health exit-code", or "absent"
  local id
  id=$(compose ps -q "$1" 2>/dev/null)
  [ -n "$id" ] || { echo absent; return; }
  docker inspect -f '{{.State.Status}} {{if .State.Health}}{{.State.Health.Status}}{{else}}-{{end}} {{.State.ExitCode}}' "$id"
}

# The bridge has no port to ask (its compose health check is off): it is ready once its
# stdout, the service's log, has its `ros bridge on domain N: ...`.
ros_bridge_ready() {
  compose logs --no-color ros-bridge 2>/dev/null | grep -q 'ros bridge on domain '
}

wait_ready() {
  local what=$1 deadline=$(( $(date +%s) + $2 )) service state pending
  while :; do
    pending=""
    for service in $COMPOSE_SERVICES; do
      state=$(state_of "$service")
      case $service:$state in
        migrate:"exited - 0") ;;
        migrate:exited*) fail "migrate exited with status ${state##* }" migrate ;;
        ros-bridge:"running - "*) ros_bridge_ready || pending+=" $service (running, not yet ready)" ;;
        agent:"running - "*|console:"running - "*) ;;
        *:"running healthy "*) ;;
        *) pending+=" $service ($state)" ;;
      esac
    done
    [ -z "$pending" ] && break
    if [ "$(date +%s)" -ge "$deadline" ]; then
      fail "$what: not ready after $2 s:$pending" "$(echo "$pending" | sed 's/ ([^)]*)//g')"
    fi
    sleep 2
  done
  say "$what: postgres, air and server healthy, agent and console running, ros-bridge ready, migrate done ($(elapsed))"
}
