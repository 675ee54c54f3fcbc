#!/usr/bin/env python3
"""bench/round_trip_rooms_section.py on made-up runs: one row per room and profile, and each
issue-35 target judged over the rooms its RT60 range names, a miss naming its room
(ctest: bench.round_trip_rooms).

    /usr/bin/python3 tests/bench/round_trip_rooms_test.py
"""

import json
import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bench"))
from round_trip_rooms_section import load_rooms, round_trip_rooms_section, round_trip_targets_section  # noqa: E402


def e2e(first_acked, median, p95, bps, yields=None):
    extra = {} if yields is None else {"air_yields": yields, "latency_ms_max": 2 * p95}
    return dict(frames_first_attempt=200, frames_acked_first_attempt=first_acked, latency_ms_median=median,
                latency_ms_p95=p95, throughput_bps=bps, **extra)


def roundtrip(first_time, sent, retransmissions):
    return dict(frames_first_time=first_time, frames_sent=sent, retransmissions=retransmissions,
                latency_ms=dict(median=160.0, p95=175.0), throughput_bps=165.0)


class RoundTripRooms(unittest.TestCase):
    def render(self, runs):
        with tempfile.TemporaryDirectory() as d:
            for (profile, name), doc in runs.items():
                (Path(d) / profile).mkdir(exist_ok=True)
                (Path(d) / profile / f"{name}.json").write_text(json.dumps(doc))
            rooms = load_rooms(d, ["seed", "fast", "fast+key"])
        out = []
        round_trip_rooms_section(out.append, rooms, ["seed", "fast", "fast+key"])
        round_trip_targets_section(out.append, rooms, ["seed", "fast", "fast+key"])
        return "\n".join(out)

    def test_a_room_that_misses_is_named_and_the_others_count(self):
        text = self.render({
            ("fast", "e2e_rir_seminar_room_clap"): e2e(200, 140, 180, 170, yields=0),
            ("fast", "roundtrip_rir_seminar_room_clap"): roundtrip(200, 200, 0),
            ("fast", "e2e_rir_smoking_room"): e2e(190, 180, 650, 120),
            ("fast", "e2e_rir_club_hall"): e2e(196, 160, 180, 160),
            ("fast+key", "e2e_rir_typing_room"): e2e(180, 240, 260, 110),
        })
        self.assertIn("| `fast` | seminar_room_clap | 0.63 s | 100.0 % | 140 / 180 ms | 360 ms | 170 bit/s | 0 | 100.0 % "
                      "| 160 / 175 ms | 165 bit/s |", text)
        self.assertIn("| `fast` | smoking_room | 0.74 s | 95.0 % | 180 / 650 ms | – | 120 bit/s | – | not run | – | – |",
                      text)
        self.assertIn("| first-attempt ACKs, every measured room with RT60 ≤ 1.5 s (e2e) | `fast` | ≥ 99 % | "
                      "**missed**: 1 of 2 rooms; misses smoking_room: 95.0 % |", text)
        self.assertIn("| first-attempt ACKs, RT60 1.5–2.5 s (e2e) | `fast` | ≥ 95 % | met: 1 of 1 rooms; "
                      "worst club_hall: 98.0 % |", text)
        self.assertIn("| first-attempt ACKs, RT60 1.5–2.5 s (e2e) | `fast+key` | ≥ 95 % | **missed**: 0 of 1 rooms; "
                      "misses typing_room: 90.0 % |", text)
        self.assertIn("| RPC → confirmed, median / p95, every room with RT60 ≤ 1.5 s (e2e) | `fast+key` | "
                      "≤ 200 / 300 ms | not run |", text)
        self.assertNotIn("`seed` |", text)  # the seed profile has no rows and binds no target here

    def test_nothing_run_says_so(self):
        self.assertIn("Not run", self.render({}))


if __name__ == "__main__":
    unittest.main()
