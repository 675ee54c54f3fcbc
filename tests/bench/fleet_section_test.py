#!/usr/bin/env python3
"""bench/fleet_section.py's fleet-database rows on made-up load runs: the full run with no
failure meets the target, a failure or a shorter run does not and says why, a run that failed
outright shows its error, and a missing run says "not run" (ctest: bench.fleet_section).

    /usr/bin/python3 tests/bench/fleet_section_test.py
"""

import json
import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bench"))
import fleet_section  # noqa: E402


def load(agents=20, servers=3, seconds=600, failures=(), confirmed=299, into_exchange=None, executions=None):
    extra = {} if into_exchange is None else {"frames_into_exchange": into_exchange}
    if executions is not None:
        extra.update(executed=executions[0], executed_by_wrong_robot=executions[1], executed_unsent=executions[2])
    return dict(**extra,agents=agents, servers=servers, seconds=seconds, outage_s=10, healthy_s=5.2, agent_cpu_mean_pct=5.1,
                agent_cpu_max_pct=5.6, receptions_logged=900, receptions_stored=900, commands=300, confirmed=confirmed,
                confirmed_first_try=280, duplicates=0, spill_left=0, frames=400, frames_overlapped=40,
                frames_overlapped_unanswered=20, frames_clear_unanswered=3, measured_utc="2026-11-29 18:00 UTC",
                failures=list(failures))


def section(load_doc=None, error=None, two_senders=None):
    with tempfile.TemporaryDirectory() as directory:
        fleet = Path(directory) / "fleet"
        fleet.mkdir()
        if load_doc is not None:
            (fleet / "load.json").write_text(json.dumps(load_doc))
        if two_senders is not None:
            (fleet / "two_senders.json").write_text(json.dumps(two_senders))
        if error is not None:
            (fleet / "load.error").write_text("starting\n" + error + "\n")
        out = []
        fleet_section.fleet_section(out.append, {"fast": {}}, ["fast"], lambda d: "error" not in d, directory)
        return "\n".join(out)


def target_row(text, start="| fleet database"):
    return next(line for line in text.splitlines() if line.startswith(start))


class FleetLoadRows(unittest.TestCase):
    def test_the_full_run_without_failures_meets_the_target(self):
        text = section(load())
        self.assertTrue(target_row(text).endswith("| yes |"), target_row(text))
        self.assertIn("| load | 20 | 3 | 600 s | 10 s | 5.2 s | 5.1 / 5.6 % | 900 / 900 | 300 (299; 280) | 0 | 0 | 400 "
                      "| 40 (20) | 3 | – | – | 0 |", text)
        self.assertIn("| 40 (20) | 3 | 2 | 410 (1; 0) | 0 |", section(load(into_exchange=2, executions=(410, 1, 0))))

    def test_starts_under_the_senders_own_exchange_and_together_are_counted_apart(self):
        classed = load(agents=4, servers=2, into_exchange=0)
        classed.update(frames_into_masked_exchange=9, frames_started_together=4)
        text = section(two_senders=classed)
        self.assertIn("| 40 (20) | 3 | 0 (9; 4; –) |", text)
        self.assertIn("0 started into an exchange of the other it could hear begin, 9 into one that began under its "
                      "own and 4 within 100 ms of the other's start;", target_row(text, "| two senders, "))

    def test_starts_into_an_exchange_hidden_by_a_third_senders_are_counted_apart(self):
        classed = load(into_exchange=0)
        classed.update(frames_into_masked_exchange=13, frames_started_together=16, frames_into_hidden_exchange=3)
        self.assertIn("| 40 (20) | 3 | 0 (13; 16; 3) |", section(classed))
        two = load(agents=4, servers=2, into_exchange=0)
        two.update(frames_into_masked_exchange=1, frames_started_together=2, frames_into_hidden_exchange=1)
        self.assertIn("within 100 ms of the other's start, 1 into one hidden by a third sender's answered exchange "
                      "that began with it", target_row(section(two_senders=two), "| two senders, "))

    def test_a_failure_misses_the_target_and_is_listed(self):
        text = section(load(failures=["agent3 logged 12 frames, the database holds 11"]))
        self.assertTrue(target_row(text).endswith("| no |"))
        self.assertIn("- load: agent3 logged 12 frames, the database holds 11", text)

    def test_a_shorter_run_does_not_meet_the_target_and_says_so(self):
        row = target_row(section(load(agents=6, servers=2, seconds=40)))
        self.assertIn("a shorter run than the target's", row)
        self.assertTrue(row.endswith("| no |"))

    def test_a_run_that_failed_shows_its_error(self):
        text = section(error="fleet_load: FAILED: sender2 confirmed no command")
        self.assertIn("| load | | | | | | | | | | | | | | | | failed: fleet_load: FAILED: sender2 confirmed no command", text)
        self.assertIn("failed: fleet_load: FAILED: sender2 confirmed no command | no |", target_row(text))

    def test_no_run_says_not_run(self):
        self.assertIn("| not run | no |", target_row(section()))
        self.assertIn("| not run | no |", target_row(section(), "| two senders, "))

    def test_two_senders_report_the_confirmed_share_and_the_collisions(self):
        row = target_row(section(two_senders=load(agents=4, servers=2)), "| two senders, ")
        self.assertIn("99.67 % of 300 confirmed", row)
        self.assertIn("10.0 % of frames overlapped the other sender's and 5.0 % were lost to it (before the senders "
                      "listened)", row)
        listening = target_row(section(two_senders=load(agents=4, servers=2, into_exchange=0)), "| two senders, ")
        self.assertIn("5.0 % were lost to it; 0 started into an exchange of the other", listening)
        self.assertTrue(row.endswith("| the confirmed share: yes; wrong executions: not counted |"), row)
        missed = target_row(section(two_senders=load(agents=4, servers=2, confirmed=290)), "| two senders, ")
        self.assertTrue(missed.endswith("| no |"), missed)

    def test_two_senders_meet_the_target_only_with_no_wrong_execution(self):
        clean = target_row(section(two_senders=load(agents=4, servers=2, into_exchange=0, executions=(600, 0, 0))),
                           "| two senders, ")
        self.assertIn("of 600 frames executed, 0 by a robot they were not sent to and 0 that no sender sent", clean)
        self.assertTrue(clean.endswith("| yes |"), clean)
        for wrong in ((600, 1, 0), (600, 0, 1)):
            row = target_row(section(two_senders=load(agents=4, servers=2, into_exchange=0, executions=wrong)),
                             "| two senders, ")
            self.assertTrue(row.endswith("| no |"), row)


class FleetTeleopRows(unittest.TestCase):
    def test_joint_renewals_and_the_senders_share_of_the_air(self):
        robots = [dict(robot=f"robot{k}", renewals_per_s=2.7, joint_renewals_per_s=2.4, presses=10, missed=0, lapses=0,
                       wrong=0, press_to_cmd_vel_ms=dict(median=160, p95=300, max=400, count=10)) for k in (1, 2, 3)]
        teleop = dict(robots=robots, seconds=120, press_to_cmd_vel_ms=dict(median=165, p95=310, max=400, count=30),
                      measured_utc="2026-11-30 00:17 UTC")
        out = []
        fleet_section.fleet_section(out.append, {"fast+key": {"fleet_teleop": teleop}}, ["fast+key"],
                                    lambda d: "error" not in d, tempfile.gettempdir() + "/no-such-bench-dir")
        text = "\n".join(out)
        # 3 × 0.3 own frames a second at 215 ms and 2.4 joint renewals at 153.75 ms: 19 + 37 = 56 %.
        self.assertIn("| `fast+key` | robot1 | 2.70 (2.40) | 160 / 300 / 400 ms | 10 of 10 | 0 | 0 | 56 % (0.9 own, "
                      "2.4 joint a second) |", text)
        self.assertIn("| slowest robot 2.70 a second | yes |", text)
        self.assertIn("| 165 / 310 ms | yes |", text)

    def test_the_unkeyed_run_is_held_to_the_same_targets_with_its_own_air_time(self):
        def run(renewals_per_s, joint_per_s, lapses):
            robots = [dict(robot=f"robot{k}", renewals_per_s=renewals_per_s, joint_renewals_per_s=joint_per_s,
                           presses=10, missed=0, lapses=lapses if k == 3 else 0, wrong=0,
                           press_to_cmd_vel_ms=dict(median=100, p95=200, max=250, count=10)) for k in (1, 2, 3)]
            return dict(robots=robots, seconds=120, press_to_cmd_vel_ms=dict(median=100, p95=200, max=250, count=30))
        out = []
        data = {"fast": {"fleet_teleop": run(1.92, 0.0, 1)}, "fast+key": {"fleet_teleop": run(2.7, 2.4, 0)}}
        fleet_section.fleet_section(out.append, data, ["fast", "fast+key"], lambda d: "error" not in d,
                                    tempfile.gettempdir() + "/no-such-bench-dir")
        text = "\n".join(out)
        self.assertIn("| one sender, 3 robots, 3 Teleop streams, keyed, seminar room: renewals per robot | ≥ 2 a second "
                      "| slowest robot 2.70 a second | yes |", text)
        self.assertIn("| one sender, 3 robots, 3 Teleop streams, unkeyed, seminar room: renewals per robot | ≥ 2 a "
                      "second | slowest robot 1.92 a second; the sender sends one frame at a time, and the joint "
                      "renewals did not keep up | no |", text)
        self.assertIn("| 0; 0 | yes |", text)
        self.assertIn("| 1; 0 | no |", text)
        # With the sender's air counted, a lapse says whether the sender waited for the air.
        counted = run(2.7, 2.4, 3)
        counted.update(air_deferred=0, air_busy_blocks=0)
        out = []
        fleet_section.fleet_section(out.append, {"fast": {"fleet_teleop": counted}}, ["fast"],
                                    lambda d: "error" not in d, tempfile.gettempdir() + "/no-such-bench-dir")
        self.assertIn("| 3; 0; the sender deferred 0 frames to another's sound (heard in 0 blocks) | no |",
                      "\n".join(out))
        # Unkeyed: 3 × 1.92 own frames a second at 153.75 ms, no joint renewal: 89 %.
        self.assertIn("| 89 % (5.8 own, 0.0 joint a second) |", text)
        out = []
        fleet_section.fleet_section(out.append, {"fast": {"fleet_teleop": run(2.8, 2.4, 0)}}, ["fast"],
                                    lambda d: "error" not in d, tempfile.gettempdir() + "/no-such-bench-dir")
        # 3 × 0.4 own frames at 153.75 ms and 2.4 joint renewals at 102.5 ms: 18 + 25 = 43 %.
        self.assertIn("| 43 % (1.2 own, 2.4 joint a second) |", "\n".join(out))


if __name__ == "__main__":
    unittest.main()
