#!/usr/bin/env bash
# scripts/quickstart as a new user runs it, in the README's order (issue 59): one robot, down,
# --robots 3, down, one robot again. Pairing the fleet used to remove the one robot's counter
# state, and its agent then stopped at start ("no counter state for key ..."). Every start
# here must leave every agent running, reuse that set-up's own keys, and drive: one command
# to each robot confirmed, so both sides hold the same key. Then the one robot loses its
# state while its server runs: both sides are paired afresh (a new key, still driving); and
# the fleet, started again, still has its own keys. The real pairing, programs, air and
# database; left out are only the install and build (DTMF_QUICKSTART_BIN) and the seed's
# sequence (--no-sequence). Prints PASS when every check holds.
#   quickstart_order_test.sh SOURCE_DIR BIN_DIR WORK_DIR
set -uo pipefail
src=$1
bin=$2
dir=$3
[ -n "$dir" ] && [ "$dir" != / ] || { echo "FAIL: no work directory"; exit 1; }
export DTMF_QUICKSTART_BIN=$bin DTMF_QUICKSTART_DIR=$dir
# Ports of its own: the user's quickstart may be running on 50051 and 55433 meanwhile.
export DTMF_QUICKSTART_PORT=25440 DTMF_QUICKSTART_PG_PORT=25441 DTMF_QUICKSTART_CONSOLE_PORT=25442
unset DTMF_AUDIO_DEVICE
server=localhost:$DTMF_QUICKSTART_PORT

quickstart() { "$src/scripts/quickstart" "$@"; }
# Whatever a failed run left: its processes, its cluster (owned by postgres), its files.
clean() {
  quickstart down >/dev/null 2>&1
  "$src/scripts/pg" destroy "$dir/pg" >/dev/null 2>&1
  rm -rf "$dir"
}
clean
trap 'quickstart down >/dev/null 2>&1; "$src/scripts/pg" destroy "$dir/pg" >/dev/null 2>&1' EXIT

fail() {
  echo "FAIL: $*"
  local log
  for log in "$dir"/agent*.log "$dir/server.log"; do
    [ -f "$log" ] && { echo "--- last lines of $log"; tail -n 5 "$log"; }
  done
  exit 1
}

pid_of() { cat "$dir/$1.pid" 2>/dev/null; }
running() { local pid; pid=$(pid_of "$1") && [ -n "$pid" ] && kill -0 "$pid" 2>/dev/null; }
# agent_key AGENT: the id of the key the agent runs with, as its log says (not its room key's).
agent_key() { grep -v "room key" "$dir/$1.log" | sed -n 's/.* key \([0-9a-f]\{8\}\) from .*/\1/p' | head -n 1; }

# up WHAT ARGS...: the quickstart started, and two seconds later every agent of it still running.
up() {
  local what=$1 out agent
  shift
  out=$(quickstart "$@" --no-sequence 2>&1) || fail "$what: scripts/quickstart${*:+ $*} failed:"$'\n'"$out"
  sleep 2
  for agent in $agents; do
    running "$agent" || fail "$what: $agent did not stay up"
    ! grep -q "no counter state" "$dir/$agent.log" || fail "$what: $agent has no counter state for its key"
  done
}

# drives WHAT [ROBOT...]: one command to each robot (none named: the only one) confirmed.
drives() {
  local what=$1 robot out
  shift
  for robot in "${@:-}"; do
    out=$("$bin/dtmfctl" --server "$server" ${robot:+--robot "$robot"} drive --speed 20 --duration 0.5 \
      --on-unconfirmed fail </dev/null 2>&1) || fail "$what: a drive${robot:+ of $robot} was not confirmed:"$'\n'"$out"
  done
}

down() {
  quickstart down >/dev/null 2>&1 || fail "$1: scripts/quickstart down failed"
  for agent in server $agents; do ! running "$agent" || fail "$1: $agent still running after down"; done
}

agents=agent
up "the first one-robot start"
single_key=$(agent_key agent)
[ -n "$single_key" ] || fail "the first one-robot start: the agent runs with no key"
drives "the first one-robot start"
down "the first one-robot start"
echo "ok: one robot started, paired with key $single_key and drove"

agents="agent1 agent2 agent3"
up "the fleet's first start" --robots 3
fleet_keys=$(for k in 1 2 3; do agent_key "agent$k"; done | paste -sd ' ')
[ "$(wc -w <<<"$fleet_keys")" = 3 ] || fail "the fleet's first start: not every agent runs with a key ($fleet_keys)"
drives "the fleet's first start" robot1 robot2 robot3
down "the fleet's first start"
echo "ok: three robots started, paired with keys $fleet_keys and each drove"

agents=agent
up "the one robot again, after the fleet"
[ "$(agent_key agent)" = "$single_key" ] || fail "the one robot was paired afresh, not its key reused"
drives "the one robot again, after the fleet"
echo "ok: one robot started again with its key $single_key and drove"

# Its counter state lost while the server runs on: the quickstart pairs both sides afresh,
# never the robot alone (its server would hold the old key and nothing would be confirmed).
old_server=$(pid_of server)
kill "$(pid_of agent)"
for _ in $(seq 50); do running agent || break; sleep 0.1; done
rm -rf "$dir/single/agent-state"
up "the one robot without its counter state"
new_key=$(agent_key agent)
[ -n "$new_key" ] && [ "$new_key" != "$single_key" ] || fail "a robot without its state was not given a new key"
[ "$(pid_of server)" != "$old_server" ] || fail "the server kept running with the old key"
drives "the one robot without its counter state"
down "the one robot without its counter state"
echo "ok: one robot without its state paired afresh on both sides, key $new_key, and drove"

agents="agent1 agent2 agent3"
up "the fleet again, after the one robot" --robots 3
[ "$(for k in 1 2 3; do agent_key "agent$k"; done | paste -sd ' ')" = "$fleet_keys" ] ||
  fail "the fleet was paired afresh, not its keys reused"
drives "the fleet again, after the one robot" robot1 robot2 robot3
down "the fleet again, after the one robot"
echo "ok: three robots started again with their keys and each drove"

"$src/scripts/pg" destroy "$dir/pg" >/dev/null 2>&1
rm -rf "$dir"
echo "PASS: the quickstart in the README's order, every agent up and paired each time"
