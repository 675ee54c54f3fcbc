#!/usr/bin/env python3
"""Plot a test run frame by frame: the sender's response time (chord start to ACK/NACK)
and the robot's latency (chord start to its reception), like the seed's Fig. 14 and 16.

    python3 examples/plot_run.py            # the latest run, to run-<number>.png
    python3 examples/plot_run.py 3 --out general.png
"""

import argparse
import sys

import matplotlib

matplotlib.use("Agg")  # files only; no display needed
import matplotlib.pyplot as plt  # noqa: E402

from dtmf_teleop import TeleopError  # noqa: E402
from dtmf_teleop.arguments import add_connection_arguments, client_from_arguments  # noqa: E402


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_connection_arguments(parser)
    parser.add_argument("run", nargs="?", help="run number or id (default: the latest)")
    parser.add_argument("--out", help="PNG file to write (default run-<number>.png)")
    args = parser.parse_args()
    run = int(args.run) if args.run and args.run.isdigit() else args.run
    try:
        with client_from_arguments(args) as robot:
            report = robot.report(run, frames=True)
    except TeleopError as e:
        print(f"plot_run: {e}", file=sys.stderr)
        return 1
    frames = report["frames"]
    if not frames:
        print(f"plot_run: run {report['run']['number']} has no frames to plot", file=sys.stderr)
        return 1
    out = args.out or f"run-{report['run']['number']}.png"

    index = list(range(1, len(frames) + 1))
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(10, 6), sharex=True)
    for axis, key, name, colour in ((top, "response_time_ms", "response time", "tab:blue"),
                                    (bottom, "latency_ms", "latency", "tab:orange")):
        measured = [(i, f[key]) for i, f in zip(index, frames) if f[key] is not None]
        missing = [i for i, f in zip(index, frames) if f[key] is None]
        axis.plot([i for i, _ in measured], [v for _, v in measured], "o-", color=colour, markersize=3, label=name)
        if missing:
            axis.plot(missing, [0] * len(missing), "x", color="tab:red", label="none")
        retries = [(i, f[key]) for i, f in zip(index, frames) if f["attempt"] > 1 and f[key] is not None]
        if retries:
            axis.plot([i for i, _ in retries], [v for _, v in retries], "s", color="tab:green", fillstyle="none",
                      label="retransmission")
        axis.set_ylabel(f"{name} (ms)")
        axis.grid(alpha=0.3)
        axis.legend(loc="upper right")
    bottom.set_xlabel("frame (in the order played)")
    rate = report["success_rate_pct"]
    top.set_title(f"run {report['run']['number']} '{report['run']['label']}' ({report['run']['profile']} profile): "
                  f"{len(frames)} chords, success {'N/A' if rate is None else f'{rate:.2f} %'}")
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    print(f"wrote {out}: {len(frames)} frames")
    return 0


if __name__ == "__main__":
    sys.exit(main())
