#!/usr/bin/env python3
"""The console's benchmark, small (ctest: bench.console): bench/console/console_bench.py once
on the whole system with a page for 2 s and 2 Drives, its JSON holding every figure the report
needs; then bench/console_section.py judging that run, and made-up runs that miss each target,
which it must say it missed.

    /usr/bin/python3 tests/bench/console_bench_test.py SOURCE_DIR BIN_DIR WORK_DIR
"""

import json
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(SOURCE / "bench"))
import console_section  # noqa: E402

ARGS = sys.argv[1:4]


def delays(median, p95):
    return {"median": median, "p95": p95, "max": p95, "count": 100}


def made_up(column=(8, 15), mark=(8, 15), extra_cpu=2.0, weight=100_000):
    return {"measured_utc": "2026-12-07 20:35 UTC", "seconds_per_phase": 60, "drives": 20,
            "cpu_unwatched_pct_core": {"server": 5.0, "console": 0.0},
            "cpu_watched_pct_core": {"server": 5.0 + extra_cpu / 2, "console": extra_cpu / 2},
            "extra_cpu_pct_core": extra_cpu, "column_delay_ms": delays(*column),
            "mark_delay_ms": delays(*mark) if mark else None, "columns_drawn": 100, "page_weight_bytes": weight}


def rows(doc):
    with tempfile.TemporaryDirectory() as directory:
        Path(directory, "console").mkdir()
        Path(directory, "console", "console.json").write_text(json.dumps(doc))
        lines = []
        console_section.console_section(lines.append, directory)
    return [line for line in lines if line.startswith("| ") and not line.startswith("| what")]


class ConsoleSection(unittest.TestCase):
    def test_a_run_within_every_target_meets_all_four(self):
        judged = rows(made_up())
        self.assertEqual(len(judged), 4, judged)
        self.assertTrue(all(row.rstrip(" |").endswith("met") for row in judged), judged)

    def test_each_target_missed_is_said_missed(self):
        for name, doc in {"column median": made_up(column=(260, 300)), "column p95": made_up(column=(100, 450)),
                          "mark": made_up(mark=(300, 400)), "no mark": made_up(mark=None),
                          "cpu": made_up(extra_cpu=5.5), "weight": made_up(weight=600 * 1024)}.items():
            missed = [row for row in rows(doc) if row.rstrip(" |").endswith("missed")]
            self.assertEqual(len(missed), 1, (name, rows(doc)))


class ConsoleBench(unittest.TestCase):
    def test_a_short_run_measures_every_figure(self):
        source, bin_dir, work = ARGS
        out = Path(work, "console.json")
        out.unlink(missing_ok=True)
        run = subprocess.run(["/usr/bin/python3", str(SOURCE / "bench/console/console_bench.py"), source, bin_dir,
                              str(Path(work, "system")), str(out), "--seconds", "2", "--drives", "2"],
                             capture_output=True, text=True, timeout=300)
        self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
        doc = json.loads(out.read_text())
        self.assertGreaterEqual(doc["column_delay_ms"]["count"], 25, doc)  # 25 columns a second, 2 s and more
        self.assertGreaterEqual(doc["mark_delay_ms"]["count"], 2, doc)  # each Drive's frames answered
        self.assertEqual(set(doc["cpu_watched_pct_core"]), {"server", "console"}, doc)  # both processes read
        self.assertTrue(20_000 < doc["page_weight_bytes"] < 500 * 1024, doc)
        self.assertEqual(len(rows(doc)), 4)


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0], "-v"])
