#!/usr/bin/env python3
"""Drive a square: four times, drive one side, then turn a quarter turn on the spot.

    python3 examples/drive_square.py --side-s 2 --speed 50

The quarter turn's duration comes from the robot's top turn rate (TurtleBot3 Burger:
2.84 rad/s; Waffle: 1.82 rad/s) at the chosen rotation percent. A new command replaces the
one under way, so each is given its time before the next is sent.
"""

import argparse
import math
import sys
import time

from dtmf_teleop import TeleopError
from dtmf_teleop.arguments import add_connection_arguments, client_from_arguments


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_connection_arguments(parser)
    parser.add_argument("--speed", type=float, default=50, help="percent of top speed (default %(default)s)")
    parser.add_argument("--side-s", type=float, default=2, help="seconds per side (default %(default)s)")
    parser.add_argument("--rotation", type=float, default=50, help="turn rate, percent, left (default %(default)s)")
    parser.add_argument("--max-turn-rate-rps", type=float, default=2.84,
                        help="the robot's top turn rate in rad/s (default: Burger, %(default)s)")
    args = parser.parse_args()
    turn_s = (math.pi / 2) / (args.max_turn_rate_rps * args.rotation / 100)
    if not 0 < turn_s <= 8:
        parser.error(f"a quarter turn at {args.rotation}% takes {turn_s:.2f} s; commands last at most 8 s")
    try:
        with client_from_arguments(args) as robot:
            for side in range(1, 5):
                for name, call, seconds in (
                        (f"side {side}", lambda: robot.drive(speed=args.speed, duration=args.side_s), args.side_s),
                        (f"turn {side}", lambda: robot.turn(rotation=args.rotation, duration=turn_s), turn_s)):
                    final = call().result()
                    print(f"{name}: {final.command}: {final.event.name.lower()}", flush=True)
                    time.sleep(seconds)
    except TeleopError as e:
        print(f"drive_square: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
