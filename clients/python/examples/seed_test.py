#!/usr/bin/env python3
"""Run the seed's test sequence (27 commands, 65 frames) as a labelled test run, show each
frame as it is answered, then print the run's report (the seed's Appendix A figures).

    python3 examples/seed_test.py --label general
"""

import argparse
import sys

from dtmf_teleop import FrameEvent, TeleopError
from dtmf_teleop.arguments import add_connection_arguments, client_from_arguments

ROWS = [("transmissions sent", "transmissions_sent", ""), ("received", "transmissions_received", ""),
        ("successfully matched", "successfully_matched", ""), ("dropped", "dropped", ""),
        ("false positives", "false_positives", ""), ("false positive rate", "false_positive_rate_pct", "%"),
        ("success rate", "success_rate_pct", "%"), ("confirmed by the robot", "sender_confirmed_rate_pct", "%"),
        ("error catch rate", "error_catch_rate_pct", "%"), ("response time avg", "response_time_avg_ms", " ms"),
        ("latency avg", "latency_avg_ms", " ms")]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_connection_arguments(parser)
    parser.add_argument("--label", default="general", help="the run's label (default %(default)s)")
    parser.add_argument("--notes", default="", help="free text stored with the run")
    args = parser.parse_args()
    try:
        with client_from_arguments(args) as robot:
            run_id = None
            for step in robot.run_sequence(args.label, args.notes):
                run_id = step.run_id
                p = step.progress
                if p.event == FrameEvent.WAITING_FOR_AIR:  # another's sound, or turn-taking, holds the frame
                    print(f"[{step.frames_done:2}/{step.frames_total}] {p.waiting_for_air}", flush=True)
                if p.event in (FrameEvent.ACK, FrameEvent.NACK, FrameEvent.NO_ANSWER):
                    answer = f"{p.event.name} after {p.response_time_ms:.0f} ms" if p.response_time_ms else p.event.name
                    print(f"[{step.frames_done:2}/{step.frames_total}] {p.frame_bits}  {answer}", flush=True)
            report = robot.report(run_id)
    except TeleopError as e:
        print(f"seed_test: {e}", file=sys.stderr)
        return 1
    print(f"\nrun {report['run']['number']} '{report['run']['label']}'")
    for title, key, unit in ROWS:
        value = report[key]
        shown = "N/A" if value is None else (f"{value:.2f}{unit}" if isinstance(value, float) else f"{value}{unit}")
        print(f"  {title:<24} {shown}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
