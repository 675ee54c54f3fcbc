#!/usr/bin/env python3
"""The ROS 2 bridge's benchmark, small (ctest: bench.ros_bridge): run_ros_bridge_bench.sh once,
keyed, with 2 changes, 2 stops and 3 s of a 20 Hz stream, its JSON holding every figure the
report needs; then bench/ros_bridge_section.py judging made-up runs that miss each target,
which it must say it missed.

    /usr/bin/python3 tests/bench/ros_bridge_bench_test.py SOURCE_DIR BIN_DIR WORK_DIR
"""

import json
import os
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(SOURCE / "bench"))
import ros_bridge_section  # noqa: E402

ARGS = sys.argv[1:4]


def made_up(keyed=True, change=(150, 250), stops=(700, 750), per_s=2.5, lapses=0):
    return {"keyed": keyed, "timeout_ms": 500, "lease_ms": 1000, "measured_utc": "2026-12-08 01:00 UTC",
            "changes": {"median": change[0], "p95": change[1], "max": change[1], "count": 40, "opening_ms": 500},
            "stops": [{"kind": "silent", "ms": stops[0]}, {"kind": "killed -9 (Fast DDS)", "ms": stops[1]}],
            "nav2": {"seconds": 30, "frames": int(per_s * 30), "frames_per_s": per_s, "lapses": lapses}}


def rows(*docs):
    with tempfile.TemporaryDirectory() as directory:
        Path(directory, "ros_bridge").mkdir()
        for doc in docs:
            name = "keyed" if doc["keyed"] else "unkeyed"
            Path(directory, "ros_bridge", f"ros_bridge_{name}.json").write_text(json.dumps(doc))
        lines = []
        ros_bridge_section.ros_bridge_section(lines.append, directory)
    return [line for line in lines if line.startswith("| ") and not line.startswith("| what")]


class RosBridgeSection(unittest.TestCase):
    def test_runs_within_every_target_meet_all_six(self):
        judged = rows(made_up(keyed=False), made_up(keyed=True))
        self.assertEqual(len(judged), 6, judged)
        self.assertTrue(all(row.rstrip(" |").endswith("met") for row in judged), judged)

    def test_each_target_missed_is_said_missed(self):
        cases = {"unkeyed median": made_up(keyed=False, change=(210, 300)),
                 "keyed p95": made_up(change=(200, 410)), "a stop too slow": made_up(stops=(700, 1701)),
                 "too few frames": made_up(per_s=1.9), "a lapse": made_up(lapses=1)}
        for name, doc in cases.items():
            missed = [row for row in rows(doc) if row.rstrip(" |").endswith("missed")]
            self.assertEqual(len(missed), 1, (name, rows(doc)))

    def test_the_keyed_target_is_looser_than_the_unkeyed(self):
        keyed, unkeyed = rows(made_up(keyed=True, change=(240, 390))), rows(made_up(keyed=False, change=(240, 390)))
        self.assertTrue(keyed[0].rstrip(" |").endswith("met"), keyed)
        self.assertTrue(unkeyed[0].rstrip(" |").endswith("missed"), unkeyed)


class RosBridgeBench(unittest.TestCase):
    def test_a_short_run_measures_every_figure(self):
        source, bin_dir, work = ARGS
        out = Path(work, "out")
        Path(out, "ros_bridge_keyed.json").unlink(missing_ok=True)
        run = subprocess.run([str(SOURCE / "bench/ros_bridge/run_ros_bridge_bench.sh"), source, bin_dir,
                              str(Path(work, "system")), str(out), "--changes", "2", "--stops", "2", "--nav2-s", "3"],
                             capture_output=True, text=True, timeout=400,
                             env={**os.environ, "DTMF_ROS_BRIDGE_BENCH_VARIANTS": "keyed"})
        self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
        doc = json.loads(Path(out, "ros_bridge_keyed.json").read_text())
        self.assertTrue(doc["keyed"])
        self.assertEqual(doc["changes"]["count"], 2, doc)
        self.assertLess(doc["changes"]["max"], 2000, doc)  # every change reached the robot
        self.assertEqual([t["kind"] for t in doc["stops"]], ["silent", "killed -9 (Fast DDS)"], doc)
        self.assertTrue(all(t["ms"] < 5000 for t in doc["stops"]), doc)  # both stops seen
        self.assertGreater(doc["nav2"]["frames"], 0, doc)  # dtmfctl watch saw the stream's frames
        self.assertEqual(len(rows(doc)), 3)


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0], "-v"])
