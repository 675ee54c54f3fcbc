"""The Fleet section of docs/benchmarks.md (issue 37): a room of robots.

dtmf-bench-room-stop's figures (the stop for every robot, heard by three robots at 1, 2 and
3 m in each measured room), dtmf-bench-fleet-teleop's, bench/e2e/fleet_load.sh's (the fleet's
database under load, DIRECTORY/fleet/load.json), and every Fleet target of issue 37, met or
with its figure or the reason it has none yet.
"""

import json
import os

STOP_TARGET_PCT = 99.9
STOP_TARGET_ROOM = "seminar_room_clap"


def _stop_rows(w, data, shown):
    w("| profile | room | all 3 robots in time | robot 1 m | robot 2 m | robot 3 m "
      "| decision after the first copy (median / p95 / most) | other commands | answers |")
    w("|---|---|---|---|---|---|---|---|---|")
    for p in shown:
        d = data[p]["room_stop"]
        for c in d["cases"]:
            robots = " | ".join(f"{100.0 * r['in_time'] / d['stops']:.2f} %" for r in c["robots"])
            w(f"| `{p}` | {c['room']} | {c['all_in_time_pct']:.2f} % ({c['all_in_time']} of {d['stops']}) | {robots} "
              f"| {c['decision_median_ms']:.0f} / {c['decision_p95_ms']:.0f} / {c['decision_max_ms']:.0f} ms "
              f"| {c['other_commands']} | {c['answered']} |")
    w("")


def _stop_target(data, profiles):
    """(figure, met) of the broadcast-stop target, keyed (`fast+key`) where it ran, else unkeyed."""
    for p in sorted(profiles, key=lambda name: not name.endswith("+key")):
        d = data[p].get("room_stop")
        if not d or "error" in d:
            continue
        for c in d["cases"]:
            if c["room"] == STOP_TARGET_ROOM:
                met = c["all_in_time_pct"] >= STOP_TARGET_PCT and c["other_commands"] == 0 and c["answered"] == 0
                return (f"`{p}`: {c['all_in_time_pct']:.2f} % of {d['stops']}, decided at most "
                        f"{c['decision_max_ms']:.0f} ms after the first copy began", met)
    return ("not run", False)


TWO_SENDERS_CONFIRMED_PCT = 99.0


def load_fleet_load(directory, name="load"):
    """bench/e2e/fleet_load.sh's figures (run NAME), {"error": ...} when it failed, or None when not run."""
    path = os.path.join(directory, "fleet", name + ".json")
    if os.path.exists(path):
        with open(path) as f:
            return json.load(f)
    err = os.path.join(directory, "fleet", name + ".error")
    if os.path.exists(err):
        with open(err) as f:
            lines = [line.strip() for line in f if line.strip()]
        return {"error": lines[-1] if lines else "failed"}
    return None


def _load_rows(w, runs):
    """The load runs that ran, one row each; `runs` maps a title to its figures."""
    w("`bench/e2e/fleet_load.sh`: real `dtmf-agent` and `dtmf-server` processes on one PulseAudio air (every "
      "loudspeaker straight into every microphone, no room) and one PostgreSQL. Each server drives two robots "
      "(addresses 2s−1, 2s) with Drives at random from a `dtmfctl` loop, the agents take the addresses in turn, and "
      "PostgreSQL is stopped for a while in the middle. Every frame an agent logged must be a row, once; every "
      "command a client saw start must be a row, finished, with its frame attempts; each sender's per-robot "
      "reports must add up to its room's; nothing may be left in a spill file. *Agent CPU*: each agent's share of "
      "a core while the servers drove (a reader spinning in the sound library shows here: docs/protocol.md §7, "
      "scheduling). *Overlapped*: frames that were on air while another sender's frame was, and how many of them "
      "went unanswered, next to the unanswered frames that overlapped nothing; *into an exchange*: frames started "
      "while another sender's exchange (its frame's start until its answer, or its 500 ms wait) that had begun "
      "100 ms or more before was under way, and had begun while this sender listened, which listening before "
      "talking must prevent; counted apart, those started into an exchange that began under the sender's own "
      "(from 100 ms before its frame until 100 ms after its answer: its microphone, beside its loudspeaker, takes "
      "what it hears then for its own) and those started within 100 ms of another's start (neither could hear the "
      "other coming), as `tests/server/listen_before_talk_test.cpp` counts them; and, with three senders or more, "
      "those started into an exchange *hidden* by a third sender's that began within 100 ms of it and whose answer "
      "came before this start (the sender heard one stretch of sound end in an answer and took the exchange for "
      "over; the hidden one, started with it, was mostly lost). Runs from before 2026-11-30 did not "
      "count them, and their senders did not listen; runs before 2026-11-30 16:00 UTC counted all three as into an "
      "exchange but those that started within 100 ms, and runs before 2026-11-30 19:30 UTC counted hidden ones as "
      "into an exchange. *Executed (wrong robot; unsent)*: frames "
      "the robots executed, those a sender had sent to another address, and those no sender sent "
      "(`bench/e2e/fleet_executions.sql`; runs from before 2026-11-30 did not count them).")
    w("")
    w("| run | agents | servers | time | database down | servers up after | agent CPU (mean / most) "
      "| receptions logged / stored | commands stored (confirmed; at the first try) | stored twice "
      "| left in spill files | frames sent | overlapped (unanswered) | unanswered, no overlap "
      "| into an exchange (under its own; together; hidden) "
      "| executed (wrong robot; unsent) | failures | measured |")
    w("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for title, load in runs.items():
        if "error" in load:
            w(f"| {title} | | | | | | | | | | | | | | | | failed: {load['error']} | |")
            continue
        w(f"| {title} | {load['agents']} | {load['servers']} | {load['seconds']} s | {load['outage_s']} s "
          f"| {load['healthy_s']:.1f} s | {load['agent_cpu_mean_pct']:.1f} / {load['agent_cpu_max_pct']:.1f} % "
          f"| {load['receptions_logged']} / {load['receptions_stored']} | {load['commands']} ({load['confirmed']}; "
          f"{load.get('confirmed_first_try', '–')}) | {load['duplicates']} | {load['spill_left']} "
          f"| {load.get('frames', '–')} | {load.get('frames_overlapped', '–')} "
          f"({load.get('frames_overlapped_unanswered', '–')}) | {load.get('frames_clear_unanswered', '–')} "
          f"| {_into_exchange(load)} | {_executions(load)} | {len(load['failures'])} "
          f"| {load.get('measured_utc', '')} |")
    w("")
    failures = [f"- {title}: {failure}" for title, load in runs.items() for failure in load.get("failures", [])]
    for line in failures:
        w(line)
    if failures:
        w("")


def _into_exchange(load):
    """Frames started into another's exchange, and apart those under the sender's own, together and hidden."""
    if "frames_into_masked_exchange" not in load:
        return str(load.get("frames_into_exchange", "–"))
    return (f"{load['frames_into_exchange']} ({load['frames_into_masked_exchange']}; "
            f"{load['frames_started_together']}; {load.get('frames_into_hidden_exchange', '–')})")


def _executions(load):
    """Frames executed, and of them by a robot they were not sent to and sent by no sender."""
    if "executed" not in load:
        return "–"
    return f"{load['executed']} ({load['executed_by_wrong_robot']}; {load['executed_unsent']})"


def _air_share(profile, robots, _first):
    """The share of the air one sender used for its robots' Teleop streams (all of them)."""
    own_ms = 215.0 if profile.endswith("+key") else 153.75
    joint_ms = 153.75 if profile.endswith("+key") else 102.5
    own = sum(r["renewals_per_s"] - r.get("joint_renewals_per_s", 0.0) for r in robots)
    joint = max(r.get("joint_renewals_per_s", 0.0) for r in robots)
    return f"{(own * own_ms + joint * joint_ms) / 10:.0f} % ({own:.1f} own, {joint:.1f} joint a second)"


def _two_senders_target(w, run):
    target = ("two senders, 2 robots each, one air, Drives at random for 10 min: confirmed without a manual retry "
              f"| ≥ {TWO_SENDERS_CONFIRMED_PCT:.0f} %, the share lost to collisions reported, 0 wrong executions")
    if run is None or "error" in run:
        w(f"| {target} | {'not run' if run is None else 'failed: ' + run['error']} | no |")
        return
    confirmed = 100.0 * run["confirmed"] / max(run["commands"], 1)
    overlapped = 100.0 * run["frames_overlapped"] / max(run["frames"], 1)
    lost = 100.0 * run["frames_overlapped_unanswered"] / max(run["frames"], 1)
    full = run["servers"] == 2 and run["seconds"] >= 600
    counted = "executed" in run
    wrong = run.get("executed_by_wrong_robot", 0) + run.get("executed_unsent", 0)
    confirmed_met = full and confirmed >= TWO_SENDERS_CONFIRMED_PCT and not run["failures"]
    if counted:
        executions = (f"; of {run['executed']} frames executed, {run['executed_by_wrong_robot']} by a robot they were "
                      f"not sent to and {run['executed_unsent']} that no sender sent")
        verdict = "yes" if confirmed_met and wrong == 0 else "no"
    else:
        executions = ("; wrong executions are not counted in this run (dtmf-bench-fleet-teleop and the FleetE2E test "
                      "count them: 0)")
        verdict = "the confirmed share: yes; wrong executions: not counted" if confirmed_met else "no"
    w(f"| {target} | {confirmed:.2f} % of {run['commands']} confirmed (the sender's own retransmissions "
      f"included); {overlapped:.1f} % of frames overlapped the other sender's and {lost:.1f} % were lost to it"
      f"{_into_exchange_text(run)}"
      f"{executions}{'' if full else '; a shorter run'} | {verdict} |")


def _into_exchange_text(run):
    if "frames_into_exchange" not in run:
        return " (before the senders listened)"
    text = f"; {run['frames_into_exchange']} started into an exchange of the other it could hear begin"
    if "frames_into_masked_exchange" in run:
        text += (f", {run['frames_into_masked_exchange']} into one that began under its own and "
                 f"{run['frames_started_together']} within 100 ms of the other's start")
    if run.get("frames_into_hidden_exchange"):
        text += (f", {run['frames_into_hidden_exchange']} into one hidden by a third sender's answered exchange "
                 "that began with it")
    return text


def _load_target(w, load):
    if load is None:
        w("| fleet database: 20 agents and 3 servers, 10 min, a database restart in the middle | no row lost or "
          "duplicated, every report adds up | not run | no |")
        return
    if "error" in load and "agents" not in load:
        w(f"| fleet database: 20 agents and 3 servers, 10 min, a database restart in the middle | no row lost or "
          f"duplicated, every report adds up | failed: {load['error']} | no |")
        return
    full = load["agents"] >= 20 and load["servers"] >= 3 and load["seconds"] >= 600
    met = full and not load["failures"]
    figure = (f"{load['agents']} agents, {load['servers']} servers, {load['seconds']} s, down {load['outage_s']} s: "
              f"{load['receptions_stored']} of {load['receptions_logged']} receptions, {load['commands']} commands, "
              f"{load['duplicates']} twice, {len(load['failures'])} failures"
              + ("" if full else " (a shorter run than the target's)"))
    w(f"| fleet database: 20 agents and 3 servers, 10 min, a database restart in the middle | no row lost or "
      f"duplicated, every report adds up | {figure} | {'yes' if met else 'no'} |")


def _teleop_targets(w, run, keys):
    """The three Teleop rows of the Fleet targets for one fleet_teleop run (`keys`: keyed or unkeyed)."""
    robots = run["robots"]
    slowest = min(r["renewals_per_s"] for r in robots)
    ms = run["press_to_cmd_vel_ms"]
    lapses = sum(r["lapses"] for r in robots)
    wrong = sum(r["wrong"] for r in robots)
    air = ("; the sender sends one frame at a time, and the joint renewals did not keep up"
           if slowest < 2 else "")
    w(f"| one sender, 3 robots, 3 Teleop streams, {keys}, seminar room: renewals per robot | ≥ 2 a second "
      f"| slowest robot {slowest:.2f} a second{air} | {'yes' if slowest >= 2 else 'no'} |")
    press_met = ms["median"] <= 300 and ms["p95"] <= 600
    w(f"| the same: key press → that robot's cmd_vel | median ≤ 300 ms, p95 ≤ 600 ms | {ms['median']:.0f} / "
      f"{ms['p95']:.0f} ms{'' if press_met else ': a press waits for the frames queued ahead of it, one per robot'}"
      f" | {'yes' if press_met else 'no'} |")
    # Whether a lapse was a wait for the air: runs before 2026-11-30 20:30 UTC did not count it.
    waited = (f"; the sender deferred {run['air_deferred']} frames to another's sound (heard in "
              f"{run['air_busy_blocks']} blocks)" if lapses and "air_deferred" in run else "")
    w(f"| the same: lapses while a key is held; frames executed by the wrong robot | 0; 0 | {lapses}; {wrong}"
      f"{waited} | {'yes' if lapses == 0 and wrong == 0 else 'no'} |")


def fleet_section(w, data, profiles, ok, directory):
    w("## Fleet: a room of robots")
    w("")
    shown = [p for p in profiles if ok(data[p].get("room_stop", {"error": "not run"}))]
    w("`dtmf-bench-room-stop`: a stream of stops for every robot (`dtmfctl stop --all`: the profile's two copies "
      "back to back, keyed under the room key, one stop a second), heard by three robots at 1, 2 and 3 m from the "
      "sender's loudspeaker, each through the measured room at its distance with pink noise at −50 dBFS; each robot "
      "has its own key and the room key. A robot counts a stop when it executes one of its copies within 300 ms of "
      "the first copy's start (the agent publishes the stop on cmd_vel the moment it decides). *Other commands*: "
      "anything a robot executed that was not the stop (must be 0); *answers*: what the robots played back "
      "(must be 0: no robot answers a stop for every robot).")
    w("")
    if shown:
        when = sorted({data[p]["room_stop"].get("measured_utc", "") for p in shown})
        w(f"Measured {', '.join(when)}, {data[shown[0]]['room_stop']['stops']} stops a room.")
        w("")
        _stop_rows(w, data, shown)
    else:
        w("Not run: " + "; ".join(f"{p}: {data[p].get('room_stop', {}).get('error', 'not run')}" for p in profiles))
        w("")
    teleop_shown = [p for p in profiles if ok(data[p].get("fleet_teleop", {"error": "not run"}))]
    if teleop_shown:
        w("`dtmf-bench-fleet-teleop`: one sender drives robot1..robot3 (addresses 1–3, 1, 2 and 3 m from its "
          "loudspeaker) through the seminar room both ways, one Teleop stream each, as `dtmfctl teleop` drives, in "
          "real time; a key press (±0.01 m/s) every second on average, the robots in turn. *Renewals*: velocities "
          "each robot executed per second, each renewing its lease: its stream's VELOCITY frames and the "
          "joint renewals (one unanswered frame for all three: docs/protocol.md §10, \"Renewing leases together\"), "
          "which *joint* counts apart; *lapses*: standstills while its stream held a non-zero target; "
          "*wrong*: velocities a robot executed from another robot's range. *Air*: the share of the air the sender "
          "used, its own frames at 215 ms each (a keyed frame and its tag chord; 153.75 ms unkeyed with its "
          "answer under it) and the joint renewals at 153.75 ms keyed, 102.5 ms unkeyed.")
        w("")
        when = sorted({data[p]["fleet_teleop"].get("measured_utc", "at an unknown time") for p in teleop_shown})
        w(f"Measured {', '.join(when)}, {data[teleop_shown[0]]['fleet_teleop']['seconds']:.0f} s each.")
        w("")
        w("| profile | robot | renewals a second (joint) | press → cmd_vel (median / p95 / max) | presses reached "
          "| lapses | wrong | air |")
        w("|---|---|---|---|---|---|---|---|")
        for p in teleop_shown:
            robots = data[p]["fleet_teleop"]["robots"]
            for r in robots:
                ms = r["press_to_cmd_vel_ms"]
                joint = r.get("joint_renewals_per_s", 0.0)
                w(f"| `{p}` | {r['robot']} | {r['renewals_per_s']:.2f} ({joint:.2f}) | {ms['median']:.0f} / "
                  f"{ms['p95']:.0f} / {ms['max']:.0f} ms | {r['presses'] - r['missed']} of {r['presses']} "
                  f"| {r['lapses']} | {r['wrong']} | {_air_share(p, robots, r) if r is robots[0] else ''} |")
        w("")
    load = load_fleet_load(directory)
    two_senders = load_fleet_load(directory, "two_senders")
    runs = {title: run for title, run in (("load", load), ("two senders", two_senders)) if run is not None}
    if runs:
        _load_rows(w, runs)
    figure, met = _stop_target(data, profiles)
    w("| Fleet target (issue 37) | target | figure | met |")
    w("|---|---|---|---|")
    w(f"| stop for every robot, 3 robots, seminar room, keyed | ≥ {STOP_TARGET_PCT} % of 1000 heard by all three, "
      f"each within 300 ms, none answered | {figure} | {'yes' if met else 'no'} |")
    keyed = next((data[p]["fleet_teleop"] for p in teleop_shown if p.endswith("+key")), None)
    if keyed:
        _teleop_targets(w, keyed, "keyed")
    else:
        w("| one sender, 3 robots, 3 Teleop streams, keyed | renewals ≥ 2 a second, press → cmd_vel median ≤ 300 ms "
          "and p95 ≤ 600 ms, no lapse, 0 wrong | not run | no |")
    # The target names keys; the same figures without them, against the same bars.
    unkeyed = next((data[p]["fleet_teleop"] for p in teleop_shown if not p.endswith("+key")), None)
    if unkeyed:
        _teleop_targets(w, unkeyed, "unkeyed")
    _two_senders_target(w, two_senders)
    _load_target(w, load)
    w("")
