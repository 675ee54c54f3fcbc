"""The examples, run end to end as a user would: the seed test, its plot, a square, and
the keyboard teleop in a pseudo-terminal."""

import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.image  # noqa: E402

from conftest import EXAMPLES  # noqa: E402
from teleop_helpers import KeyboardInTerminal  # noqa: E402


def run_example(name, *args, server):
    result = subprocess.run([sys.executable, str(EXAMPLES / name), "--server", server, *args],
                            capture_output=True, text=True, timeout=600, env=os.environ)
    assert result.returncode == 0, result.stdout + result.stderr
    return result.stdout


def test_seed_test_then_plot_the_run(system, tmp_path):
    out = run_example("seed_test.py", "--label", "python-example", server=system.address)
    assert out.count("ACK after") == 65, out
    assert "transmissions sent       65" in out
    assert "successfully matched     65" in out
    assert "success rate             100.00%" in out

    png = tmp_path / "run.png"
    printed = run_example("plot_run.py", "--out", str(png), server=system.address)
    assert printed.strip() == f"wrote {png}: 65 frames"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    image = matplotlib.image.imread(png)
    assert image.shape[:2] == (600, 1000)
    assert image[..., :3].std() > 0.05  # not a blank page: two curves, axes, labels


def test_drive_square_confirms_all_eight_commands(system):
    out = run_example("drive_square.py", "--side-s", "0.5", "--speed", "30", server=system.address)
    lines = out.strip().splitlines()
    assert len(lines) == 8, out
    assert all(line.endswith(": confirmed") for line in lines), out
    assert lines[0].startswith("side 1: drive_for_duration") and lines[1].startswith("turn 1: turn_for_duration")


def test_teleop_keyboard_steps_the_robot_from_a_terminal_and_stops_on_q(system):
    keyboard = KeyboardInTerminal(system.address)
    try:
        keyboard.press(b"", r"target \+0\.00 m/s \+0\.00 rad/s")  # the stream is open
        keyboard.press(b"wwwww", r"target \+0\.05 m/s \+0\.00 rad/s \| robot \+0\.05 m/s")
        keyboard.press(b"a ", r"target \+0\.00 m/s \+0\.00 rad/s \| robot \+0\.00 m/s \+0\.00 rad/s")
        assert keyboard.quit() == 0, keyboard.text
    finally:
        keyboard.close()
    assert "stopping" in keyboard.text
