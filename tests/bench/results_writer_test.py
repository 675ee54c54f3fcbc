#!/usr/bin/env python3
"""bench/experiments/write_results.py on made-up runs of both profiles: our figures beside the
seed report's, a PNG per profile and condition, the room named from --rir, the 10 m comparison
with the seed's 13 CRC rejects, and the false-positive paragraph that follows the runs
(ctest: bench.results_writer).

    /usr/bin/python3 tests/bench/results_writer_test.py   (Debian's, with python3-matplotlib)
"""

import json
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

WRITER = Path(__file__).resolve().parents[2] / "bench" / "experiments" / "write_results.py"
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def report(profile, label, sent, false_positives=0, crc_rejected=0, response_ms=300.0, latency_ms=150.0):
    """A run_report() row: SENT frames, all matched and ACKed; CRC_REJECTED more receptions, each NACKed."""
    received = sent + false_positives + crc_rejected
    return dict(run_id=f"id-{profile}-{label}", run_number=1, label=label, profile=profile, transmissions_sent=sent,
                frame_attempts=sent, transmissions_received=received, successfully_matched=sent, dropped=0,
                false_positives=false_positives, false_positive_rate_pct=round(100 * false_positives / sent, 2),
                duplicates=0, success_rate_pct=100.0, sender_confirmed_rate_pct=100.0,
                crc_accepted=sent + false_positives, crc_rejected=crc_rejected,
                negative_confirmations_sent=crc_rejected, error_catch_rate_pct=None if not crc_rejected else 100.0,
                response_time_avg_ms=response_ms, response_time_min_ms=250.0, response_time_max_ms=350.0,
                latency_avg_ms=latency_ms + false_positives, latency_min_ms=100.0, latency_max_ms=200.0)


def write_run(runs, profile, name, distance_m, sent, noise_dbfs=None, report_profile=None, **figures):
    folder = runs / profile / name
    folder.mkdir(parents=True)
    frames = [dict(attempt=1 if i < 2 else 2, response_time_ms=300.0 + i, latency_ms=None if i == 1 else 150.0 + i)
              for i in range(sent)]
    (folder / "report.json").write_text(json.dumps(report(report_profile or profile, name, sent, **figures)))
    (folder / "frames.json").write_text(json.dumps(frames))
    (folder / "condition.json").write_text(json.dumps(dict(name=name, profile=profile, distance_m=distance_m,
                                                           noise_dbfs=noise_dbfs, rir="x", seconds=70)))


def run_writer(folder, profiles, conditions, rir="bench/rirs/seminar_room_clap.wav"):
    out = folder / "docs" / "results.md"
    out.parent.mkdir(exist_ok=True)
    return out, subprocess.run(
        [sys.executable, str(WRITER), "--runs", str(folder / "runs"), "--out", str(out), "--machine", "test",
         "--date", "today", "--minutes", "1", "--rir", rir, "--rt60-s", "0.3", "--bridge-buffers-ms", "20", "60",
         "--bridge-max-lag-ms", "35", "--profiles", *profiles, "--conditions", *conditions], capture_output=True, text=True)


def generate(folder, profiles, conditions, **kwargs):
    out, done = run_writer(folder, profiles, conditions, **kwargs)
    if done.returncode != 0:
        raise AssertionError(f"write_results.py failed ({done.returncode}):\n{done.stderr}")
    return out.read_text(), out.parent / "results"


class ResultsWriter(unittest.TestCase):
    def test_both_profiles_stand_beside_the_seeds_figures_with_their_plots(self):
        with tempfile.TemporaryDirectory() as tmp:
            folder = Path(tmp)
            runs = folder / "runs"
            for profile, sent in (("seed", 3), ("fast", 2)):
                write_run(runs, profile, "reference", None, sent, response_ms=200.0, latency_ms=100.0)
                write_run(runs, profile, "general", 1, sent)
                write_run(runs, profile, "noise", 1, sent, noise_dbfs=-11)
            conditions = ["reference", "general", "noise"]
            text, pngs = generate(folder, ["seed", "fast"], conditions)
            # Summary cells are "seed report / seed profile / fast profile"; the seed's general run: 887.26 ms.
            self.assertIn("| [general (1 m)](#general-1-m-seed-101) | 65 / 3 / 2 | – / 3 / 2 | 65 / 3 / 2 "
                          "| 100.00 / 100.00 / 100.00 % | 0 / 0 / 0 | 0 / 0 / 0 | 887.26 / 300.00 / 300.00 "
                          "| 198.83 / 150.00 / 150.00 |", text)
            self.assertIn("| figure | seed report | ours, `seed` profile | ours, `fast` profile |", text)
            self.assertIn("| Sender confirmed rate | 43.08 % | 100.00 % | 100.00 % |", text)  # noise, seed §10.2
            self.assertIn("| Average latency | – | 100.00 ms | 100.00 ms |", text)  # the reference: no seed figure
            self.assertIn('- `fast` profile: run "general" (id-fast-general), 1 m both ways through a university '
                          "seminar room", text)
            # The room: named with its RT60 from bench/rirs/README.md; the Schroeder arithmetic is gone.
            self.assertIn("(`bench/rirs/seminar_room_clap.wav`: RT60 0.63 s, direct-to-reverberant ratio −7 dB;", text)
            self.assertIn("the distance adds no delay and no air absorption", text)
            self.assertNotIn("Schroeder", text)
            self.assertNotIn("distance alone costs only margin", text)
            self.assertIn("drops what waits longer than 35 ms", text)  # the bridges' own figure
            # Bridge latency: general's 150 ms less the reference's 100 ms less 0.25 ms; response 300 - 200.
            self.assertIn("what they add on the way to the robot: **50 ms** under `seed` (response time, both ways: "
                          "**100 ms**); **50 ms** under `fast`", text)
            self.assertIn("−11 dBFS RMS", text)
            self.assertNotIn("At 10 m: the seed's room", text)  # no 10 m run, no comparison
            self.assertIn("No run heard a false positive.", text)
            for profile in ("seed", "fast"):
                for name in conditions:
                    self.assertIn(f"(results/{profile}-{name}.png)", text)
                    self.assertEqual((pngs / f"{profile}-{name}.png").read_bytes()[:8], PNG_MAGIC)

    def test_ten_metres_is_compared_with_the_seeds_13_crc_rejects(self):
        with tempfile.TemporaryDirectory() as tmp:
            folder = Path(tmp)
            runs = folder / "runs"
            write_run(runs, "seed", "10m", 10, 65)  # clean: the kind model
            write_run(runs, "fast", "10m", 10, 27, crc_rejected=3)  # 13 in 65 would be 5.4 in 27; 3 is over half
            write_run(runs, "seed", "4m", 4, 65, false_positives=1)
            write_run(runs, "fast", "4m", 4, 27)
            text, pngs = generate(folder, ["seed", "fast"], ["4m", "10m"])
            self.assertIn("The seed's own room at 10 m rejected 13 receptions by CRC", text)
            self.assertIn("- `seed` profile: 0 CRC rejects and 0 NACKs in 65 receptions of 65 frames (0 retransmitted); "
                          "100.00 % matched, 100.00 % confirmed — like the kind model, not the seed's room.", text)
            self.assertIn("- `fast` profile: 3 CRC rejects and 3 NACKs in 30 receptions of 27 frames (0 retransmitted); "
                          "100.00 % matched, 100.00 % confirmed — like the seed's room (its rate would give 5.4 in 27 "
                          "frames).", text)
            self.assertIn("| CRC rejected | 13 | 0 | 3 |", text)
            self.assertIn("(−12 dB at 4 m, −20 dB at 10 m, against 1 m)", text)
            self.assertIn("about −34 dBFS, 26 dB over the seed detectors' −60 dBFS noise gate", text)
            # Only the direct sound falls with distance: the seminar room's −7 dB at 1 m is −27 dB at 10 m.
            self.assertIn("| distance | the direct sound only: amplitude × 1 / distance", text)
            self.assertIn("its direct-to-reverberant ratio, −7 dB at 1 m, is −27 dB there", text)
            self.assertIn("weighs 20 dB more against the direct sound at 10 m than at 1 m", text)
            self.assertNotIn("level alone", text)
            self.assertIn("False positives in these runs: `seed` profile: 4 m 1; `fast` profile: none.", text)
            self.assertIn("a mode word heard twice", text)
            self.assertNotIn("Under `fast`, a frame heard twice", text)
            self.assertNotIn("No run heard a false positive.", text)
            self.assertNotIn("The noise level", text)  # no noise condition, no noise paragraph
            self.assertEqual((pngs / "fast-10m.png").read_bytes()[:8], PNG_MAGIC)

    def test_the_old_reverberator_keeps_its_model_and_arithmetic(self):
        with tempfile.TemporaryDirectory() as tmp:
            folder = Path(tmp)
            write_run(folder / "runs", "fast", "general", 1, 2, false_positives=1)
            text, _ = generate(folder, ["fast"], ["general"], rir="none")
            self.assertIn("| reverberation | a Schroeder room (4 combs, 2 all-passes), RT60 0.3 s", text)
            self.assertIn("So distance alone costs only margin", text)
            self.assertIn("| figure | seed report | ours, `fast` profile |", text)
            self.assertIn("| False positives | 0 | 1 |", text)
            self.assertIn("Under `fast`, a frame heard twice", text)

    def test_an_unknown_room_is_named_by_its_file(self):
        with tempfile.TemporaryDirectory() as tmp:
            folder = Path(tmp)
            write_run(folder / "runs", "seed", "7m", 7, 3)
            text, _ = generate(folder, ["seed"], ["7m"], rir="/elsewhere/my_hall.wav")
            self.assertIn("the measured impulse response of the room of `my_hall.wav`", text)
            self.assertIn("RT60 and direct-to-reverberant ratio not in bench/rirs/README.md", text)

    def test_a_run_of_the_wrong_profile_or_a_missing_run_is_refused(self):
        with tempfile.TemporaryDirectory() as tmp:
            folder = Path(tmp)
            write_run(folder / "runs", "fast", "general", 1, 3, report_profile="seed")
            _, done = run_writer(folder, ["fast"], ["general"])
            self.assertNotEqual(done.returncode, 0)
            self.assertIn("holds a run of profile 'seed', not 'fast'", done.stderr)
            _, done = run_writer(folder, ["seed"], ["general"])  # runs/seed/general was never written
            self.assertNotEqual(done.returncode, 0)
            self.assertIn("no usable run of profile seed, condition general", done.stderr)
            _, done = run_writer(folder, ["slow"], ["general"])
            self.assertNotEqual(done.returncode, 0)
            self.assertIn("invalid choice: 'slow'", done.stderr)


if __name__ == "__main__":
    unittest.main(verbosity=2)
