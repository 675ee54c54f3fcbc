#!/usr/bin/env python3
"""bench/targets_section.py on made-up benchmark figures: a met target says "met" with its
figure, a missed one "**missed**" with its figure and its typed reason, a miss without a typed
reason says so, a target that does not bind a profile shows only the figure, and a benchmark
that did not run is named (ctest: bench.targets_section).

    /usr/bin/python3 tests/bench/targets_section_test.py
"""

import sys
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bench"))
import targets_section  # noqa: E402


def ok(doc):
    return "error" not in doc


def profile_data(rooms_worst=1.0, e2e_bps=300.0, snr_10=1.0, wrong=0, decoder=6000.0, e2e_ms=120.0, heard=1.0,
                 frame_ms=102.5, false_confirmations=0):
    cases = [dict(case="seminar_room_clap 1 m", frames=1000, success_rate=rooms_worst, duplicated=0, wrong_accepts=wrong),
             dict(case="clock -2000 ppm", frames=1000, success_rate=1.0, duplicated=0, wrong_accepts=0)]
    points = [dict(snr_db=-10.0, frames=10000, success_rate=snr_10, wrong_accepts=0),
              dict(snr_db=-12.0, frames=1000, success_rate=0.5, wrong_accepts=0)]
    talk = dict(accepted=0, hours=1.0, false_confirmations=false_confirmations)
    answers = dict(frame_ms=frame_ms, cases=[dict(case="smoking_room 1 m", answers=1000, heard_rate=heard, wrong=0),
                                             dict(case="studio_live_room 1 m", answers=1000, heard_rate=1.0, wrong=0)])
    return dict(rooms=dict(cases=cases), snr=dict(points=points), distance=dict(points=[]),
                distance_loud=dict(points=[]),
                e2e_room=dict(latency_ms_median=e2e_ms, throughput_bps=e2e_bps, retransmissions=3, commands=100),
                answers=answers,
                talkoff_speech=talk, talkoff_music=talk, talkoff_noise=talk, decoder=dict(factor=decoder))


def table(data, profiles=("seed", "fast")):
    out = []
    targets_section.targets_section(out.append, data, list(profiles), ok, lambda d, signal: d["factor"])
    rows = {}
    for line in out:
        cells = [c.strip() for c in line.strip("|").split("|")]
        if line.startswith("| ") and len(cells) == 2 + len(profiles):
            rows[cells[0]] = dict(zip(profiles, cells[2:]))
    return rows


class TargetsSection(unittest.TestCase):
    def test_met_missed_with_and_without_a_reason(self):
        rows = table({"seed": profile_data(), "fast": profile_data(rooms_worst=0.99, e2e_bps=180.0, snr_10=0.998)})
        measured = rows["measured rooms (1 and 3 m)"]
        self.assertEqual(measured["seed"], "met: worst 100.00 % (seminar_room_clap 1 m)")
        self.assertTrue(measured["fast"].startswith("**missed**: worst 99.00 % (seminar_room_clap 1 m) — "))
        self.assertIn("reason not yet analysed", measured["fast"])  # no reason typed for this one
        bps = rows["end to end through the seminar room both ways: net throughput"]
        self.assertEqual(bps["seed"], "300 bit/s, 3 retransmissions in 100 commands")  # binds fast only
        self.assertIn("**missed**: 180 bit/s", bps["fast"])
        self.assertIn("does not pipeline yet", bps["fast"])  # its typed reason
        self.assertIn("**missed**: 99.80 % of 10000", rows["frame success at −10 dB SNR"]["fast"])
        self.assertEqual(rows["decoder speed, one core (noise / frames)"]["fast"], "met: 6 000 × / 6 000 ×")

    def test_a_wrong_accept_anywhere_misses_the_target(self):
        rows = table({"seed": profile_data(wrong=1), "fast": profile_data()})
        self.assertTrue(rows["zero wrong accepts"]["seed"].startswith("**missed**: 1 in 13 000 frames"))
        self.assertEqual(rows["zero wrong accepts"]["fast"], "met: 0 in 13 000 frames")

    def test_a_benchmark_that_did_not_run_is_named(self):
        fast = profile_data()
        fast["snr"] = dict(error="not built")
        rows = table({"seed": profile_data(), "fast": fast})
        self.assertEqual(rows["frame success at −10 dB SNR"]["fast"], "not run")
        self.assertEqual(rows["zero wrong accepts"]["fast"], "snr not run")

    def test_the_keyed_column_is_judged_on_the_targets_of_authenticated_frames(self):
        profiles = ("seed", "fast", "fast+key")
        rows = table({"seed": profile_data(), "fast": profile_data(),
                      "fast+key": profile_data(e2e_ms=250.0, heard=0.99, frame_ms=153.75, false_confirmations=1)},
                     profiles)
        self.assertEqual(rows["one authenticated frame on air"]["fast+key"], "met: 153.75 ms")
        self.assertEqual(rows["one authenticated frame on air"]["fast"], "102.50 ms")  # binds the keyed column only
        drive = rows["authenticated Drive through the seminar room both ways: RPC → confirmed, median"]
        self.assertTrue(drive["fast+key"].startswith("**missed**: 250 ms"))
        heard = rows["answer path: answers heard, every room, own loudspeaker at 0.1 m or not"]
        self.assertEqual(heard["fast"], "met: worst 100.00 % of 1000 (smoking_room 1 m)")
        self.assertTrue(heard["fast+key"].startswith("**missed**: worst 99.00 % of 1000 (smoking_room 1 m)"))
        confirmations = rows["talk-off: false confirmations per hour (with a key: a forged tag; without, anyone may ACK)"]
        self.assertTrue(confirmations["fast+key"].startswith("**missed**: 3 in 3 h"))
        self.assertEqual(rows["measured rooms (1 and 3 m)"]["fast+key"], "met: worst 100.00 % (seminar_room_clap 1 m)")

    def test_teleop_rows_judge_the_median_press_and_every_stop_against_its_bound(self):
        def teleop(press_median=150.0, kill_max=1100.0, moved=0, not_reached=0):
            def stops(worst):
                return dict(median=worst - 100, p95=worst, max=worst, all=[worst - 100, worst])
            return dict(presses=100, presses_not_reached=not_reached, stop_bound_ms=1230.0,
                        press_to_cmd_vel_ms=dict(median=press_median, p95=190.0, max=300.0, all=[press_median]),
                        kills=2, kills_not_stopped=0, kills_moved_after=moved, kill_to_stop_ms=stops(kill_max),
                        losses=2, losses_not_stopped=0, losses_moved_after=0, loss_to_stop_ms=stops(1000.0))
        fast, keyed = profile_data(), profile_data()
        fast["teleop"], keyed["teleop"] = teleop(), teleop(press_median=230.0, kill_max=1300.0)
        rows = table({"seed": profile_data(), "fast": fast, "fast+key": keyed}, ("seed", "fast", "fast+key"))
        press = rows["teleop through the seminar room both ways: key press → cmd_vel, median"]
        self.assertEqual(press["seed"], "not run")
        self.assertEqual(press["fast"], "met: 150 ms, 0 of 100 presses not reached")
        self.assertTrue(press["fast+key"].startswith("**missed**: 230 ms"))
        kill = rows["teleop: the client killed with -9 → the robot stopped"]
        self.assertEqual(kill["fast"], "met: max 1100 ms of 2 (bound 1230 ms), 0 not stopped, 0 moved again")
        self.assertTrue(kill["fast+key"].startswith("**missed**: max 1300 ms"))
        fast["teleop"] = teleop(moved=1)
        rows = table({"seed": profile_data(), "fast": fast})
        self.assertTrue(rows["teleop: the client killed with -9 → the robot stopped"]["fast"].startswith("**missed**"))

    def test_every_typed_reason_belongs_to_a_target(self):
        keys = {key for key, _, _, _ in targets_section.targets(lambda d, s: 0)}
        for key, profile in targets_section.REASONS:
            self.assertIn(key, keys)
            self.assertIn(profile, ("seed", "fast", "fast+key"))


if __name__ == "__main__":
    unittest.main()
