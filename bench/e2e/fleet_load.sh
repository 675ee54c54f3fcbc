#!/usr/bin/env bash
# The fleet's database under load (issue 37): AGENTS dtmf-agent and SERVERS dtmf-server
# processes, all real, on one private PulseAudio air and one private PostgreSQL, for SECONDS,
# the database stopped for OUTAGE seconds in the middle. Each server drives two robots
# (addresses 2s-1 and 2s) with Drives at random from a dtmfctl loop; the agents take the
# addresses in turn, so several agents hear and log each robot's frames. The servers share
# the air, listening before they talk; what collisions remain are counted (frames that
# overlapped another sender's, how many of those and of the others went unanswered, and
# frames started into another sender's exchange it could have heard begin). Afterwards, every row any program wrote is in
# the database once:
#   - each agent's receptions: as many rows as frames it logged (its log's frame lines);
#   - each server's commands: every command dtmfctl saw start (its command ids) has a row,
#     finished (no 'queued' or 'transmitting' left), with at least one frame attempt;
#   - no two receptions of one agent heard at the same moment with the same frame;
#   - the per-robot reports of each sender's commands add up to the room's;
#   - every frame a robot executed was sent to its address by some sender (0 executions by
#     the wrong robot, 0 of frames no sender sent);
# and every program did its part: each server answered health checks and confirmed commands,
# each agent logged frames. The CPU each agent used is printed: a decoder that spins (as one
# at real-time priority once did, physical/capture_thread.h) shows there.
#
#   bench/e2e/fleet_load.sh [--agents 20] [--servers 3] [--seconds 600] [--outage-s 10]
#                           [--bin build/bin] [--json PATH]      (--outage-s 0: no restart)
# Exit 0 when every check holds, 1 naming each that failed. scripts/bench runs it for 10
# minutes; the suite (bench.FleetLoad) for 40 s with 6 agents and 2 servers.
set -euo pipefail
cd "$(dirname "$0")/../.."

agents=20 servers=3 seconds=600 outage_s=10 bin=build/bin json=""
while [ $# -gt 0 ]; do
  case $1 in
    --agents) agents=$2; shift ;;
    --servers) servers=$2; shift ;;
    --seconds) seconds=$2; shift ;;
    --outage-s) outage_s=$2; shift ;;
    --bin) bin=$2; shift ;;
    --json) json=$2; shift ;;
    *) echo "fleet_load: unknown argument '$1'" >&2; exit 2 ;;
  esac
  shift
done
[ "$servers" -ge 1 ] && [ "$servers" -le 3 ] || { echo "fleet_load: 1 to 3 servers (two robots each, addresses 1-6)" >&2; exit 2; }
[ "$agents" -ge "$((2 * servers))" ] || { echo "fleet_load: at least two agents a server (one per robot)" >&2; exit 2; }
[ "$outage_s" -ge 0 ] && [ "$seconds" -gt "$((outage_s + 10))" ] || { echo "fleet_load: --seconds must exceed the outage by 10 s" >&2; exit 2; }
bin=$(realpath "$bin")
dir=$(mktemp -d /tmp/dtmf-fleet-load-XXXXXX)
chmod o+x "$dir"  # PostgreSQL runs as postgres when this runs as root (scripts/pg)
pids=()
cleanup() {
  local p
  for p in "${pids[@]}"; do kill -TERM "$p" 2>/dev/null || true; done
  for p in "${pids[@]}"; do wait "$p" 2>/dev/null || true; done
  scripts/pg destroy "$dir/pg" >/dev/null 2>&1 || true
  scripts/air stop "$dir/air" >/dev/null 2>&1 || true
  rm -rf "$dir"
}
trap cleanup EXIT

eval "$(scripts/air start "$dir/air")"
pg_port=$((26000 + RANDOM % 4000))
eval "$(scripts/pg start "$dir/pg" "$pg_port")"
"$bin/dtmf-migrate" --db "$DTMF_DB_URL" >/dev/null

agent_pids=()
for a in $(seq "$agents"); do
  address=$(( (a - 1) % (2 * servers) + 1 ))
  "$bin/dtmf-agent" --audio default --ack-out default --profile fast --address "$address" --host "agent$a" \
    --cmd-vel log --db "$DTMF_DB_URL" --spill-file "$dir/agent$a.spill" \
    > /dev/null 2> "$dir/agent$a.log" &
  pids+=($!) agent_pids+=($!)
  # One at a time: a real robot has a sound server of its own, and this air's one PulseAudio,
  # asked by 20 agents within 50 ms, left some unanswered ("PulseAudio server ... did not
  # answer", or a device that would not take mono), and those agents logged no frame.
  for _ in $(seq 100); do
    grep -q "listening to" "$dir/agent$a.log" 2>/dev/null && break
    kill -0 "$!" 2>/dev/null || break
    sleep 0.1
  done
done
ports=()
for s in $(seq "$servers"); do
  echo "[{\"name\": \"s${s}a\", \"address\": $((2 * s - 1))}, {\"name\": \"s${s}b\", \"address\": $((2 * s))}]" \
    > "$dir/robots$s.json"
  port=$((pg_port + 100 + s))
  ports+=("$port")
  "$bin/dtmf-server" --robots "$dir/robots$s.json" --host "sender$s" --port "$port" --audio-out default \
    --audio-in default --db "$DTMF_DB_URL" --spill-file "$dir/server$s.spill" \
    > /dev/null 2> "$dir/server$s.log" &
  pids+=($!)
done
failures=()
started_at=$(date +%s.%N)
for s in $(seq "$servers"); do
  up=no
  for _ in $(seq 300); do
    "$bin/dtmfctl" health --server "localhost:${ports[s - 1]}" >/dev/null 2>&1 && { up=yes; break; }
    sleep 0.1
  done
  [ $up = yes ] || failures+=("sender$s did not answer health checks within 30 s: $(tail -1 "$dir/server$s.log")")
done
healthy_s=$(awk -v a="$started_at" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')

# Each server's driver: Drives at random to its two robots until told to stop.
drive_loop() {
  local s=$1 port=$2 robot
  while [ ! -e "$dir/stop-driving" ]; do
    robot=s${s}$( ((RANDOM % 2)) && echo a || echo b)
    "$bin/dtmfctl" --server "localhost:$port" --robot "$robot" --json drive --speed $((10 + RANDOM % 80)) \
      --duration 0.5 --on-unconfirmed continue < /dev/null >> "$dir/driver$s.jsonl" 2>> "$dir/driver$s.err" || true
  done
}
drivers=()
for s in $(seq "$servers"); do drive_loop "$s" "${ports[s - 1]}" & drivers+=($!); done

ticks() { awk '{ print $14 + $15 }' "/proc/$1/stat" 2>/dev/null || echo 0; }
declare -A cpu_before
for p in "${agent_pids[@]}"; do cpu_before[$p]=$(ticks "$p"); done
measured_from=$(date +%s.%N)
half=$(( seconds / 2 ))
sleep "$half"
if [ "$outage_s" -gt 0 ]; then
  echo "fleet_load: the database stops for ${outage_s} s"
  scripts/pg stop "$dir/pg" >/dev/null
  sleep "$outage_s"
  eval "$(scripts/pg start "$dir/pg" "$pg_port")"
fi
sleep $(( seconds - half - outage_s ))
touch "$dir/stop-driving"
for d in "${drivers[@]}"; do wait "$d" || true; done
# The CPU share each agent used while the servers drove (a spinning decoder shows here).
elapsed=$(awk -v a="$measured_from" -v b="$(date +%s.%N)" 'BEGIN { print b - a }')
hz=$(getconf CLK_TCK)
cpu_pcts=()
for p in "${agent_pids[@]}"; do
  cpu_pcts+=("$(awk -v t="$(( $(ticks "$p") - ${cpu_before[$p]} ))" -v hz="$hz" -v s="$elapsed" \
    'BEGIN { printf "%.1f", 100 * t / hz / s }')")
done
cpu_mean=$(printf '%s\n' "${cpu_pcts[@]}" | awk '{ s += $1 } END { printf "%.1f", s / NR }')
cpu_max=$(printf '%s\n' "${cpu_pcts[@]}" | sort -n | tail -1)
# Stopped with SIGTERM, as systemd stops them: each flushes what it holds.
for p in "${pids[@]}"; do kill -TERM "$p" 2>/dev/null || true; done
for p in "${pids[@]}"; do wait "$p" 2>/dev/null || true; done
pids=()

q() { psql "$DTMF_DB_URL" -XAtc "$1"; }
logged_total=0 stored_total=0
for a in $(seq "$agents"); do
  logged=$(grep -cE 't=[0-9.]+s fast frame' "$dir/agent$a.log" || true)
  stored=$(q "SELECT count(*) FROM receptions WHERE host = 'agent$a'")
  logged_total=$((logged_total + logged)); stored_total=$((stored_total + stored))
  [ "$logged" -gt 0 ] || failures+=("agent$a logged no frame: $(tail -1 "$dir/agent$a.log")")
  [ "$logged" = "$stored" ] || failures+=("agent$a logged $logged frames, the database holds $stored")
done
dupes=$(q "SELECT count(*) FROM (SELECT host, heard_at, frame FROM receptions GROUP BY 1, 2, 3 HAVING count(*) > 1) d")
[ "$dupes" = 0 ] || failures+=("$dupes receptions stored twice")
commands_total=0 confirmed_total=0
for s in $(seq "$servers"); do
  started=$(grep -o '"command_id":"[0-9a-f-]*"' "$dir/driver$s.jsonl" 2>/dev/null | sort -u | wc -l)
  stored=$(q "SELECT count(*) FROM commands WHERE host = 'sender$s'")
  confirmed=$(q "SELECT count(*) FROM commands WHERE host = 'sender$s' AND outcome = 'confirmed'")
  commands_total=$((commands_total + stored)) confirmed_total=$((confirmed_total + confirmed))
  [ "$confirmed" -gt 0 ] || failures+=("sender$s confirmed no command: $(tail -1 "$dir/driver$s.err" 2>/dev/null)")
  [ "$started" = "$stored" ] || failures+=("sender$s started $started commands, the database holds $stored")
  unfinished=$(q "SELECT count(*) FROM commands WHERE host = 'sender$s' AND outcome IN ('queued', 'transmitting')")
  [ "$unfinished" = 0 ] || failures+=("sender$s: $unfinished commands never finished in the database")
  bare=$(q "SELECT count(*) FROM commands c WHERE host = 'sender$s' AND NOT EXISTS
            (SELECT 1 FROM frame_attempts a WHERE a.command_id = c.id)")
  [ "$bare" = 0 ] || failures+=("sender$s: $bare commands without a frame attempt")
done
# The reports: one run per sender over all its commands, whose robots must add up to it.
q "INSERT INTO test_runs (id, label, profile, started_at, ended_at, host, revision)
   SELECT gen_random_uuid(), 'load ' || host, 'fast', min(requested_at), max(finished_at), host, 1
   FROM commands GROUP BY host" >/dev/null
q "UPDATE commands c SET run_id = r.id FROM test_runs r WHERE r.host = c.host" >/dev/null
q "UPDATE frame_attempts a SET run_id = c.run_id FROM commands c WHERE c.id = a.command_id" >/dev/null
mismatch=$(q "SELECT count(*) FROM test_runs r, run_report(r.id) room
              WHERE room.transmissions_sent <> (SELECT sum(x.transmissions_sent)
                FROM (SELECT DISTINCT robot FROM commands WHERE run_id = r.id) n, LATERAL run_report(r.id, n.robot) x)
                 OR room.successfully_matched <> (SELECT sum(x.successfully_matched)
                FROM (SELECT DISTINCT robot FROM commands WHERE run_id = r.id) n, LATERAL run_report(r.id, n.robot) x)")
[ "$mismatch" = 0 ] || failures+=("$mismatch senders whose robots' reports do not add up to the room's")
# The air shared: frames that overlapped another sender's, and what each kind lost; and frames
# started inside another sender's exchange (its frame's start until its answer, or its 500 ms
# wait), classed as tests/server/listen_before_talk_test.cpp classes them:
#   - into an exchange: one that began at least 100 ms (two slots) before, while this sender
#     listened; listening before talking must prevent these;
#   - masked: one that began under this sender's own exchange (from 100 ms before its frame
#     until 100 ms after its answer, or after its frame if none came): its microphone, beside
#     its loudspeaker, takes what it hears then for its own, so it cannot hear that start. After
#     two frames start together, the winner's next frames fall into the loser's wait so;
#   - together: one that began less than 100 ms before (neither could hear the other coming);
#   - hidden: one that began within 100 ms of a third sender's exchange, whose answer came
#     before this start: the sender heard one stretch of sound end in an answer it could read,
#     and took the exchange for over (reliability/air_access.h, the short quiet after an
#     answer read). The other, started with it, was mostly lost, and waits for an answer that
#     will not come.
IFS='|' read -r attempts overlapped overlapped_lost clear_lost first_time into_exchange masked together hidden < <(q "
  WITH a AS (SELECT f.id, c.host, f.chord_started_at s, f.chord_ended_at e, f.answer, f.answered_at,
                    coalesce(f.answered_at, f.chord_started_at + interval '500 milliseconds') x_end,
                    coalesce(f.answered_at, f.chord_ended_at) + interval '100 milliseconds' own_end
             FROM frame_attempts f JOIN commands c ON c.id = f.command_id WHERE f.chord_ended_at IS NOT NULL),
       inside AS (SELECT a.id, b.s <= a.s - interval '100 milliseconds' heard_start,
                         EXISTS (SELECT 1 FROM a m WHERE m.host = a.host AND m.s < b.s + interval '100 milliseconds'
                                                     AND b.s <= m.own_end) under_own,
                         EXISTS (SELECT 1 FROM a c WHERE c.host NOT IN (a.host, b.host) AND c.answered_at <= a.s
                                                     AND c.s > b.s - interval '100 milliseconds'
                                                     AND c.s < b.s + interval '100 milliseconds') hidden
                  FROM a JOIN a b ON b.host <> a.host AND b.s <= a.s AND a.s < b.x_end),
       x AS (SELECT a.*, EXISTS (SELECT 1 FROM a b WHERE b.host <> a.host AND b.s < a.e AND a.s < b.e) o,
                    EXISTS (SELECT 1 FROM inside n WHERE n.id = a.id AND n.heard_start AND NOT n.under_own
                                                     AND NOT n.hidden) i,
                    EXISTS (SELECT 1 FROM inside n WHERE n.id = a.id AND n.heard_start AND n.under_own) m,
                    EXISTS (SELECT 1 FROM inside n WHERE n.id = a.id AND n.heard_start AND n.hidden) h,
                    EXISTS (SELECT 1 FROM inside n WHERE n.id = a.id) t FROM a)
  SELECT count(*), count(*) FILTER (WHERE o), count(*) FILTER (WHERE o AND answer IS DISTINCT FROM 'ack'),
         count(*) FILTER (WHERE NOT o AND answer IS DISTINCT FROM 'ack'),
         (SELECT count(*) FROM commands c WHERE outcome = 'confirmed'
            AND NOT EXISTS (SELECT 1 FROM frame_attempts f WHERE f.command_id = c.id AND f.attempt > 1)),
         count(*) FILTER (WHERE i), count(*) FILTER (WHERE m AND NOT i),
         count(*) FILTER (WHERE t AND NOT m AND NOT i AND NOT h), count(*) FILTER (WHERE h AND NOT m AND NOT i)
  FROM x")
# Executions (bench/e2e/fleet_executions.sql): every frame a robot executed was sent to its
# address by some sender. Targets: 0 executions by the wrong robot, 0 of frames no one sent.
IFS='|' read -r executed wrong_robot wrong_frame < <(q "$(cat bench/e2e/fleet_executions.sql)")
[ "$wrong_robot" = 0 ] || failures+=("$wrong_robot frames executed by a robot they were not sent to")
[ "$wrong_frame" = 0 ] || failures+=("$wrong_frame frames executed that no sender sent")
spilled=$(find "$dir" -maxdepth 1 -name '*.spill*' -exec cat {} + | wc -l)
[ "$spilled" = 0 ] || failures+=("$spilled rows left in spill files after a clean stop")

echo "fleet_load: $agents agents, $servers servers, ${seconds} s, the database down ${outage_s} s in the middle"
echo "fleet_load: servers healthy after ${healthy_s} s; agents' CPU mean ${cpu_mean} %, most ${cpu_max} % of a core"
echo "fleet_load: receptions logged $logged_total, stored $stored_total; commands stored $commands_total," \
  "confirmed $confirmed_total ($first_time at the first try); spill lines left $spilled"
echo "fleet_load: frames sent $attempts, $overlapped overlapped another sender's ($overlapped_lost of them" \
  "unanswered); unanswered without an overlap $clear_lost; started into another's exchange $into_exchange," \
  "into one that began under its own $masked, within 100 ms of another's start $together, into one hidden" \
  "by a third's answered exchange that began with it $hidden"
echo "fleet_load: frames executed $executed; by a robot they were not sent to $wrong_robot; sent by no sender $wrong_frame"
if [ -n "$json" ]; then
  python3 - "$json" "${failures[@]}" <<EOF
import json, sys
json.dump({"agents": $agents, "servers": $servers, "seconds": $seconds, "outage_s": $outage_s,
           "healthy_s": $healthy_s, "agent_cpu_mean_pct": $cpu_mean, "agent_cpu_max_pct": $cpu_max,
           "receptions_logged": $logged_total, "receptions_stored": $stored_total, "commands": $commands_total,
           "confirmed": $confirmed_total, "confirmed_first_try": $first_time, "duplicates": $dupes,
           "spill_left": $spilled, "frames": $attempts, "frames_overlapped": $overlapped,
           "frames_overlapped_unanswered": $overlapped_lost, "frames_clear_unanswered": $clear_lost,
           "frames_into_exchange": $into_exchange, "frames_into_masked_exchange": $masked,
           "frames_started_together": $together, "frames_into_hidden_exchange": $hidden, "executed": $executed,
           "executed_by_wrong_robot": $wrong_robot, "executed_unsent": $wrong_frame,
           "measured_utc": "$(date -u '+%Y-%m-%d %H:%M UTC')", "failures": sys.argv[2:]}, open(sys.argv[1], "w"))
EOF
fi
if [ ${#failures[@]} -gt 0 ]; then
  # What the programs said about their database, and what was left behind: the why of a lost row.
  grep -H -iE 'database|spill|rejected|lost' "$dir"/*.log | tail -40 >&2 || true
  find "$dir" -maxdepth 1 -name '*.spill*' -exec sh -c 'echo "== $1"; head -c 2000 "$1"; echo' _ {} \; >&2
  printf 'fleet_load: FAILED: %s\n' "${failures[@]}" >&2
  exit 1
fi
echo "fleet_load: every row once, every report adds up"
