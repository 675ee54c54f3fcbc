"""The live-driving section of docs/benchmarks.md: dtmf-bench-teleop's figures.

A Teleop stream through the seminar room both ways, driven as dtmfctl teleop drives it: a
key press to the new velocity on the robot's cmd_vel, and how soon the robot stops after its
client is killed with -9 or its link is cut. One row per profile that carries velocity frames.
"""


def _ms(summary):
    return f"{summary['median']:.0f} / {summary['p95']:.0f} / {summary['max']:.0f} ms" if summary["all"] else "–"


def teleop_section(w, data, profiles, ok):
    w("## Live driving (Teleop)")
    w("")
    shown = [p for p in profiles if ok(data[p].get("teleop", {"error": "not run"}))]
    if not shown:
        w("Not run: " + "; ".join(f"{p}: {data[p].get('teleop', {}).get('error', 'not run')}" for p in profiles))
        w("")
        return
    first = data[shown[0]]["teleop"]
    w("`dtmf-bench-teleop`: the whole system in one process (server, robot agent, a real gRPC Teleop stream on "
      "loopback), the seminar room (measured) both ways with pink noise at −50 dBFS, in real time. Presses: one key "
      "of turtlebot3_teleop_key at a time (±0.01 m/s or ±0.1 rad/s) at random moments, timed from the new target "
      "on the stream to the first cmd_vel sample at it. Kills: a client process driving at 0.1 m/s and 0.5 rad/s "
      "killed with -9 at a random moment; losses: the sender's loudspeaker muted at a random moment while driving "
      "(the frame on air cut, none heard after: a dead server, a closed laptop). Both timed from the cut to the "
      f"first zero on cmd_vel. Lease {first['lease_s']:g} s, {first['carried_lease_s']:.2f} s as the frame carries "
      f"it; the bound is that + 0.2 s = {first['stop_bound_ms']:.0f} ms.")
    w("")
    w("| profile | presses reached | press → cmd_vel (median / p95 / max) | kill -9 → stopped (median / p95 / max) "
      "| link lost → stopped (median / p95 / max) | moved again after stopping |")
    w("|---|---|---|---|---|---|")
    for p in shown:
        d = data[p]["teleop"]
        reached = d["presses"] - d["presses_not_reached"]
        w(f"| `{p}` | {reached} of {d['presses']} | {_ms(d['press_to_cmd_vel_ms'])} "
          f"| {_ms(d['kill_to_stop_ms'])} ({d['kills'] - d['kills_not_stopped']} of {d['kills']} stopped) "
          f"| {_ms(d['loss_to_stop_ms'])} ({d['losses'] - d['losses_not_stopped']} of {d['losses']} stopped) "
          f"| {d['kills_moved_after'] + d['losses_moved_after']} |")
    w("")
