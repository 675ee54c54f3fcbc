"""The ROS 2 bridge's section of docs/benchmarks.md (issue 62): a Twist published → the
robot's cmd_vel at it, the publisher stopping or killed → the robot stopped, and a Nav2-like
stream's frames and lapses, keyed and not, through the seminar room both ways. Figures from
BUILD/bench/ros_bridge/ros_bridge_{keyed,unkeyed}.json, written by dtmf-bench-ros-bridge
(bench/ros_bridge/run_ros_bridge_bench.sh)."""

import json
import os
from pathlib import Path

CHANGE_TARGET_MS = {False: (200.0, 350.0), True: (250.0, 400.0)}  # unkeyed, keyed: median, p95
STOP_MARGIN_MS = 200.0  # over the input timeout plus the lease
RENEWALS_PER_S = 2.0


def met(ok):
    return "met" if ok else "missed"


def variant_rows(w, d):
    name = "keyed" if d["keyed"] else "unkeyed"
    median_target, p95_target = CHANGE_TARGET_MS[d["keyed"]]
    c = d["changes"]
    w(f"| {name}: a Twist published → the robot's cmd_vel at it | median {c['median']:.0f} ms, p95 {c['p95']:.0f} ms, "
      f"max {c['max']:.0f} ms ({c['count']} changes; the first, opening the stream, {c['opening_ms']:.0f} ms) | "
      f"≤ {median_target:.0f} / {p95_target:.0f} ms: {met(c['median'] <= median_target and c['p95'] <= p95_target)} |")
    bound = d["timeout_ms"] + d["lease_ms"] + STOP_MARGIN_MS
    stops = [t["ms"] for t in d["stops"]]
    kinds = sorted({t["kind"] for t in d["stops"]})
    w(f"| {name}: the publisher stops or dies → the robot stopped | {min(stops):.0f}–{max(stops):.0f} ms over "
      f"{len(stops)} ({', '.join(kinds)}) | ≤ {bound:.0f} ms every time: {met(max(stops) <= bound)} |")
    n = d["nav2"]
    w(f"| {name}: a Nav2-like 20 Hz stream: frames on air for the robot, lapses | {n['frames_per_s']:.2f} a second "
      f"({n['frames']} in {n['seconds']:.0f} s), {n['lapses']} lapses | ≥ {RENEWALS_PER_S:.0f} a second, 0: "
      f"{met(n['frames_per_s'] >= RENEWALS_PER_S and n['lapses'] == 0)} |")


def ros_bridge_section(w, directory):
    w("## ROS 2 bridge")
    w("")
    paths = [os.path.join(directory, "ros_bridge", f"ros_bridge_{v}.json") for v in ("unkeyed", "keyed")]
    found = [json.loads(Path(p).read_text()) for p in paths if os.path.exists(p)]
    if not found:
        error = os.path.join(directory, "ros_bridge", "ros_bridge.error")
        w(f"Not run{': ' + open(error).read().strip().splitlines()[-1] if os.path.exists(error) else ''}.")
        w("")
        return
    w("`scripts/quickstart` (one robot through the seminar room both ways, the server, `dtmf-ros-bridge`), keyed and "
      "without a key, driven over DDS as ROS 2's tools drive it (`bench/ros_bridge/ros_bridge_bench.cpp`): a "
      "teleop_twist_keyboard-like publisher (Twist, RELIABLE, 10 Hz) changing its velocity, measured from a change's "
      "first message to the robot's cmd_vel (the agent's own DDS writer) at it; stops, every other one by a Fast DDS "
      "publisher killed with -9, from the last message (the kill) to the robot's cmd_vel at zero, against the "
      "bridge's input timeout (0.5 s) plus the lease (1 s) plus 200 ms; a 20 Hz stream at a steady velocity, "
      "counting the frames the sender plays for the robot (`dtmfctl watch`) and the robot's cmd_vel falling to zero "
      f"while it runs (measured {found[0].get('measured_utc', 'with the rest')}).")
    w("")
    w("| what | figure | target |")
    w("|---|---|---|")
    for d in found:
        variant_rows(w, d)
    w("")
