#!/usr/bin/env python3
"""bench/experiments/write_results.py on made-up runs: our figures beside the seed's, a PNG per
condition, and the false-positive paragraph that follows the runs (ctest: bench.results_writer).

    /usr/bin/python3 tests/bench/results_writer_test.py   (Debian's, with python3-matplotlib)
"""

import json
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

WRITER = Path(__file__).resolve().parents[2] / "bench" / "experiments" / "write_results.py"


def report(label, false_positives):
    """A run_report() row for 3 chords, all matched and ACKed."""
    return dict(run_id=f"id-{label}", run_number=1, label=label, profile="seed", transmissions_sent=3,
                frame_attempts=3, transmissions_received=3 + false_positives, successfully_matched=3, dropped=0,
                false_positives=false_positives, false_positive_rate_pct=round(100 * false_positives / 3, 2),
                duplicates=0, success_rate_pct=100.0, sender_confirmed_rate_pct=100.0, crc_accepted=3 + false_positives,
                crc_rejected=0, negative_confirmations_sent=0, error_catch_rate_pct=None, response_time_avg_ms=300.0,
                response_time_min_ms=250.0, response_time_max_ms=350.0, latency_avg_ms=150.0 + false_positives,
                latency_min_ms=100.0, latency_max_ms=200.0)


def write_run(runs, name, false_positives, distance_m, noise_dbfs=None):
    folder = runs / name
    folder.mkdir(parents=True)
    frames = [dict(attempt=1 if i < 2 else 2, response_time_ms=300.0 + i, latency_ms=None if i == 1 else 150.0 + i)
              for i in range(3)]
    (folder / "report.json").write_text(json.dumps(report(name, false_positives)))
    (folder / "frames.json").write_text(json.dumps(frames))
    (folder / "condition.json").write_text(json.dumps(dict(name=name, distance_m=distance_m, noise_dbfs=noise_dbfs,
                                                           seconds=70)))


def generate(folder, conditions):
    out = folder / "docs" / "results.md"
    out.parent.mkdir()
    subprocess.run([sys.executable, str(WRITER), "--runs", str(folder / "runs"), "--out", str(out), "--machine", "test",
                    "--date", "today", "--minutes", "1", "--rt60-s", "0.3", "--bridge-buffers-ms", "20", "60",
                    "--conditions", *conditions], check=True, capture_output=True)
    return out.read_text(), out.parent / "results"


class ResultsWriter(unittest.TestCase):
    def test_each_condition_stands_beside_the_seeds_figures_with_its_plot(self):
        with tempfile.TemporaryDirectory() as tmp:
            folder = Path(tmp)
            write_run(folder / "runs", "reference", 0, None)
            write_run(folder / "runs", "general", 0, 1)
            write_run(folder / "runs", "noise", 0, 1, noise_dbfs=-11)
            text, pngs = generate(folder, ["reference", "general", "noise"])
            # Summary cells are "seed / ours"; the seed's general run: 887.26 ms, ours 300.
            self.assertIn("| 65 / 3 | – / 3 | 65 / 3 | 100.00 / 100.00 % | 0 / 0 | 0 / 0 | 887.26 / 300.00 | 198.83 / 150.00 |",
                          text)
            self.assertIn("| Sender confirmed rate | 43.08 % | 100.00 % |", text)  # noise polluted, seed §10.2
            self.assertIn("| Average latency | – | 150.00 ms |", text)  # the reference has no seed figure
            self.assertIn("−11 dBFS RMS", text)
            self.assertIn("No condition heard a false positive.", text)
            for name in ("reference", "general", "noise"):
                self.assertIn(f"(results/{name}.png)", text)
                self.assertEqual((pngs / f"{name}.png").read_bytes()[:8], b"\x89PNG\r\n\x1a\n")

    def test_false_positives_are_named_by_condition(self):
        with tempfile.TemporaryDirectory() as tmp:
            folder = Path(tmp)
            write_run(folder / "runs", "general", 1, 1)
            write_run(folder / "runs", "4m", 0, 4)
            text, _ = generate(folder, ["general", "4m"])
            self.assertIn("| False positives | 0 | 1 |", text)
            self.assertIn("False positives in these runs: General (1 m), seed §10.1 1.", text)
            self.assertNotIn("No condition heard a false positive.", text)
            self.assertNotIn("The noise level", text)  # no noise condition, no noise paragraph


if __name__ == "__main__":
    unittest.main(verbosity=2)
