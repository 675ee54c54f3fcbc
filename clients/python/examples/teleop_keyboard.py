#!/usr/bin/env python3
"""Drive the robot from the keyboard over a Teleop stream, with turtlebot3_teleop_key's keys:

            w
       a    s    d
            x

    w / x      linear velocity +/- 0.01 m/s (Burger up to 0.22, Waffle 0.26)
    a / d      angular velocity +/- 0.1 rad/s, left positive (Burger up to 2.84, Waffle 1.82)
    s, space   stop: both to zero (the stream stays open)
    q, Ctrl-C  quit: the stream ends and a Stop makes the robot stop at once

    python3 examples/teleop_keyboard.py --model burger --lease-s 1

It reads single keys, so it needs a terminal. A status line follows the server's updates:
the target, the velocity the robot confirmed and how fast, the link's quality, the lease left.
"""

import argparse
import os
import select
import sys
import termios
import threading
import tty
from typing import Optional

from dtmf_teleop import Client, TeleopError, TeleopStatus
from dtmf_teleop.arguments import add_connection_arguments, client_from_arguments

# TurtleBot3 limits (m/s, rad/s), as dtmf-server --robot and turtlebot3_teleop know them.
MODELS = {"burger": (0.22, 2.84), "waffle": (0.26, 1.82), "waffle_pi": (0.26, 1.82)}
LINEAR_STEP_MPS = 0.01
ANGULAR_STEP_RADPS = 0.1
QUIT_KEYS = ("q", "\x03")  # Ctrl-C also arrives as a key if the terminal passes it through


STEPS = {"w": (LINEAR_STEP_MPS, 0.0), "x": (-LINEAR_STEP_MPS, 0.0),
         "a": (0.0, ANGULAR_STEP_RADPS), "d": (0.0, -ANGULAR_STEP_RADPS)}


def next_target(key: str, linear: float, angular: float, limits: tuple[float, float]) -> Optional[tuple[float, float]]:
    """The target (m/s, rad/s) after a key, within the robot's limits (m/s, rad/s); None for
    a key that does not steer."""
    if key in ("s", " "):
        return (0.0, 0.0)
    if key not in STEPS:
        return None
    step_linear, step_angular = STEPS[key]
    return (_within(linear + step_linear, limits[0]), _within(angular + step_angular, limits[1]))


def _within(value: float, limit: float) -> float:
    # rounded so that ten steps of 0.01 make 0.1, not 0.09999999999999999
    return min(max(round(value, 3), -limit), limit)


def status_line(s: TeleopStatus) -> str:
    robot = (f"robot {s.confirmed_linear_mps:+.2f} m/s {s.confirmed_angular_radps:+.2f} rad/s "
             f"({s.response_time_ms:.0f} ms)" if s.confirmed else "robot: nothing confirmed yet")
    return (f"target {s.target_linear_mps:+.2f} m/s {s.target_angular_radps:+.2f} rad/s | {robot} | "
            f"link {s.link_quality:.0%} of {s.frames_in_window} frames | lease {s.lease_left_s:.1f} s left")


def drive(robot: Client, limits: tuple[float, float], lease_s: float) -> None:
    """Reads keys until q or Ctrl-C (or the stream's end) with the terminal in cbreak mode."""
    printing = threading.Lock()

    def show(status: TeleopStatus) -> None:
        with printing:
            print(f"\r{status_line(status)}\x1b[K", end="", flush=True)

    fd = sys.stdin.fileno()
    saved = termios.tcgetattr(fd)
    try:
        tty.setcbreak(fd)
        with robot.teleop(lease_s=lease_s, on_status=show) as stream:
            linear, angular = stream.target
            try:
                while not stream.ended:
                    if not select.select([fd], [], [], 0.1)[0]:
                        continue
                    key = os.read(fd, 1).decode(errors="replace")  # unbuffered: select() sees the rest
                    if key in QUIT_KEYS:
                        break
                    target = next_target(key, linear, angular, limits)
                    if target is not None:
                        linear, angular = target
                        stream.set(linear, angular)
            except KeyboardInterrupt:
                pass
            with printing:
                print("\nstopping", flush=True)
    finally:
        termios.tcsetattr(fd, termios.TCSADRAIN, saved)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_connection_arguments(parser)
    parser.add_argument("--model", choices=sorted(MODELS), default="burger",
                        help="the TurtleBot3 model, for its limits (as dtmf-server --robot; default %(default)s)")
    parser.add_argument("--lease-s", type=float, default=1.0,
                        help="how long the robot holds a target without renewal, 0.3..2 (default %(default)s)")
    args = parser.parse_args()
    if not sys.stdin.isatty():
        print("teleop_keyboard: standard input is not a terminal: it reads single keys, so run it in an "
              "interactive terminal (not through a pipe or a redirection)", file=sys.stderr)
        return 2
    print("\n\n".join(__doc__.split("\n\n")[1:3]), flush=True)  # the keys
    try:
        with client_from_arguments(args) as robot:
            drive(robot, MODELS[args.model], args.lease_s)
    except TeleopError as e:
        print(f"\nteleop_keyboard: {e}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:  # before the stream was open, or while it closed
        return 130
    return 0


if __name__ == "__main__":
    sys.exit(main())
