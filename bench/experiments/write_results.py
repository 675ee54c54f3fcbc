#!/usr/bin/env python3
"""Writes docs/results.md (and a PNG per condition) from the runs of scripts/experiments.

    python3 bench/experiments/write_results.py --runs build/experiments/runs --out docs/results.md \\
        --machine "$(uname -srm)" --date "..." --minutes 10 --rt60-s 0.3 --bridge-buffers-ms 20 60 \\
        --conditions reference general noise 4m 7m 10m

Each condition's directory holds what scripts/experiments saved: report.json (a row of
run_report()), frames.json (run_frames()) and condition.json. Our figures come only from
those files; the seed's are typed once below, from its section 10.1 and Appendix A. Needs
Python 3 and matplotlib (Debian: python3-matplotlib), nothing else.
"""

import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")  # files only; no display needed
import matplotlib.pyplot as plt  # noqa: E402

# The seed's tables (shared/seed, section 10.1 "Test Results – general" and Appendix A),
# None where it says N/A. Keys are run_report() columns.
SEED = {
    "general": dict(transmissions_sent=65, transmissions_received=65, successfully_matched=65, dropped=0,
                    false_positives=0, false_positive_rate_pct=0.00, success_rate_pct=100, sender_confirmed_rate_pct=100,
                    crc_accepted=65, crc_rejected=0, negative_confirmations_sent=0, error_catch_rate_pct=None,
                    response_time_avg_ms=887.26, response_time_min_ms=874, response_time_max_ms=1424,
                    latency_avg_ms=198.83, latency_min_ms=139, latency_max_ms=758),
    "noise": dict(transmissions_sent=65, transmissions_received=69, successfully_matched=64, dropped=1,
                  false_positives=1, false_positive_rate_pct=1.54, success_rate_pct=98.46, sender_confirmed_rate_pct=43.08,
                  crc_accepted=65, crc_rejected=4, negative_confirmations_sent=4, error_catch_rate_pct=80,
                  response_time_avg_ms=982.85, response_time_min_ms=926, response_time_max_ms=2711,
                  latency_avg_ms=278.78, latency_min_ms=222, latency_max_ms=496),
    "4m": dict(transmissions_sent=65, transmissions_received=65, successfully_matched=65, dropped=0,
               false_positives=0, false_positive_rate_pct=0.00, success_rate_pct=100, sender_confirmed_rate_pct=100,
               crc_accepted=65, crc_rejected=0, negative_confirmations_sent=0, error_catch_rate_pct=None,
               response_time_avg_ms=883.25, response_time_min_ms=867, response_time_max_ms=1344,
               latency_avg_ms=169.37, latency_min_ms=125, latency_max_ms=628),
    "7m": dict(transmissions_sent=65, transmissions_received=66, successfully_matched=65, dropped=0,
               false_positives=0, false_positive_rate_pct=0, success_rate_pct=100, sender_confirmed_rate_pct=100,
               crc_accepted=65, crc_rejected=1, negative_confirmations_sent=1, error_catch_rate_pct=100,
               response_time_avg_ms=886.31, response_time_min_ms=873, response_time_max_ms=1359,
               latency_avg_ms=134.83, latency_min_ms=82, latency_max_ms=643),
    "10m": dict(transmissions_sent=65, transmissions_received=77, successfully_matched=64, dropped=1,
                false_positives=0, false_positive_rate_pct=0, success_rate_pct=98.46, sender_confirmed_rate_pct=95.38,
                crc_accepted=64, crc_rejected=13, negative_confirmations_sent=13, error_catch_rate_pct=100,
                response_time_avg_ms=888.02, response_time_min_ms=876, response_time_max_ms=1350,
                latency_avg_ms=None, latency_min_ms=None, latency_max_ms=None),
}

SHORT = {"reference": "reference (air)", "general": "general (1 m)", "noise": "noise polluted",
         "4m": "4 m", "7m": "7 m", "10m": "10 m"}

TITLES = {
    "reference": "Reference: the plain air, no room",
    "general": "General (1 m), seed §10.1",
    "noise": "Noise polluted (1 m, white noise), seed §10.2",
    "4m": "4 meters, seed §10.3",
    "7m": "7 meters, seed §10.3",
    "10m": "10 meters, seed §10.3",
}

# (label, run_report column, kind); kind: n count, pct, ms. Columns the seed did not report
# show "–" in its column.
ROWS = [
    ("Total transmissions sent", "transmissions_sent", "n"),
    ("Chords played (retransmissions included)", "frame_attempts", "n"),
    ("Total transmissions received", "transmissions_received", "n"),
    ("Successfully matched", "successfully_matched", "n"),
    ("Dropped", "dropped", "n"),
    ("False positives", "false_positives", "n"),
    ("False positive rate", "false_positive_rate_pct", "pct"),
    ("Duplicates (a retransmission executed twice)", "duplicates", "n"),
    ("Success rate", "success_rate_pct", "pct"),
    ("Sender confirmed rate", "sender_confirmed_rate_pct", "pct"),
    ("CRC accepted", "crc_accepted", "n"),
    ("CRC rejected", "crc_rejected", "n"),
    ("Negative confirmations (NACKs) sent", "negative_confirmations_sent", "n"),
    ("Error catch rate", "error_catch_rate_pct", "pct"),
    ("Average response time", "response_time_avg_ms", "ms"),
    ("Min response time", "response_time_min_ms", "ms"),
    ("Max response time", "response_time_max_ms", "ms"),
    ("Average latency", "latency_avg_ms", "ms"),
    ("Min latency", "latency_min_ms", "ms"),
    ("Max latency", "latency_max_ms", "ms"),
]


DEFAULT_NOISE_DBFS = -11  # scripts/experiments' default


def minus(x) -> str:
    """A number with a typographic minus sign, as in the rest of the text."""
    return f"{x:g}".replace("-", "−")


def fmt(value, kind):
    if value is None:
        return "N/A"
    if kind == "n":
        return str(int(value))
    if kind == "pct":
        return f"{float(value):.2f} %"
    return f"{float(value):.2f} ms"


def load(runs_dir, name):
    directory = os.path.join(runs_dir, name)
    with open(os.path.join(directory, "report.json")) as f:
        report = json.load(f)
    with open(os.path.join(directory, "frames.json")) as f:
        frames = json.load(f)
    with open(os.path.join(directory, "condition.json")) as f:
        condition = json.load(f)
    return report, frames, condition


def plot(name, report, frames, path):
    """Response time and latency per chord, like the seed's Fig. 14 / 16 and plot_run.py."""
    seed = SEED.get(name)
    index = list(range(1, len(frames) + 1))
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(10, 6), sharex=True)
    for axis, key, what, colour, seed_key in (
            (top, "response_time_ms", "response time", "tab:blue", "response_time_avg_ms"),
            (bottom, "latency_ms", "latency", "tab:orange", "latency_avg_ms")):
        measured = [(i, float(f[key])) for i, f in zip(index, frames) if f[key] is not None]
        missing = [i for i, f in zip(index, frames) if f[key] is None]
        axis.plot([i for i, _ in measured], [v for _, v in measured], "o-", color=colour, markersize=3, label=what)
        if missing:
            axis.plot(missing, [0] * len(missing), "x", color="tab:red", label="none")
        retries = [(i, float(f[key])) for i, f in zip(index, frames) if f["attempt"] > 1 and f[key] is not None]
        if retries:
            axis.plot([i for i, _ in retries], [v for _, v in retries], "s", color="tab:green", fillstyle="none",
                      label="retransmission")
        if seed and seed[seed_key] is not None:
            axis.axhline(seed[seed_key], color="grey", linestyle="--", linewidth=1, label="seed's average")
        axis.set_ylabel(f"{what} (ms)")
        axis.set_ylim(bottom=0)
        axis.grid(alpha=0.3)
        axis.legend(loc="upper right", fontsize=8)
    bottom.set_xlabel("chord (in the order played)")
    rate = report["success_rate_pct"]
    top.set_title(f"{TITLES[name]}: {len(frames)} chords, "
                  f"success {'N/A' if rate is None else f'{float(rate):.2f} %'}")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", required=True, help="scripts/experiments' runs directory")
    parser.add_argument("--out", required=True, help="the Markdown file to write; PNGs go to results/ beside it")
    parser.add_argument("--conditions", nargs="+", required=True, choices=list(TITLES))
    parser.add_argument("--machine", required=True)
    parser.add_argument("--date", required=True)
    parser.add_argument("--minutes", type=int, required=True)
    parser.add_argument("--rt60-s", type=float, required=True)
    parser.add_argument("--bridge-buffers-ms", type=float, nargs=2, required=True, metavar=("PAREC", "PACAT"))
    args = parser.parse_args()

    png_dir = os.path.join(os.path.dirname(os.path.abspath(args.out)), "results")
    os.makedirs(png_dir, exist_ok=True)
    runs = {name: load(args.runs, name) for name in args.conditions}
    profile = next(iter(runs.values()))[0]["profile"]
    noise_dbfs = runs["noise"][2]["noise_dbfs"] if "noise" in runs else None

    out = []
    w = out.append
    w("# Results: the seed's experiments, repeated")
    w("")
    w(f"Generated by `scripts/experiments` on {args.date}, on `{args.machine}`, in about "
      f"{args.minutes} min (link profile `{profile}`). Do not edit: run the script again. "
      "Our figures come from `run_report()` and `run_frames()` of each run "
      "([docs/database.md](database.md) defines every one); the seed's are its section 10.1 "
      "and Appendix A.")
    w("")
    w("## How")
    w("")
    w("Each condition starts a fresh robot agent (`dtmf-agent --cmd-vel sim`) and server "
      "(`dtmf-server`) and runs the seed's 65-frame test sequence "
      "(`dtmfctl sequence --on-unconfirmed continue`) through them, as the seed ran its test "
      "program. The programs play and record through PulseAudio null sinks (`scripts/air`): "
      "the server plays into `speaker` and listens to `sender_ear`, the agent listens to "
      "`robot_ear` and answers into `robot_speaker`. Between them, in both directions, runs "
      "`parec | dtmf-room | pacat` (`tools/room/`): the simulated acoustic channel of "
      "`protocol/physical/acoustic_channel.h`, the one the tests use, applied to the live "
      "audio stream. Chord and ACK / NACK travel the same distance.")
    w("")
    w("| effect | model |")
    w("|---|---|")
    w("| propagation delay | distance / 343 m/s (2.9 ms at 1 m, 29 ms at 10 m) |")
    w("| spreading | amplitude × 1 / distance; what a program plays is the level heard 1 m away |")
    w("| air absorption | α(f) = 1.8·10⁻⁹ f² dB/m, a fit to ISO 9613-1 at 20 °C, 50 % RH (at 10 m: 1.2 dB at 8 kHz, 4.6 dB at 16 kHz) |")
    w(f"| reverberation | a Schroeder room (4 combs, 2 all-passes), RT60 {args.rt60_s:g} s, wet level 0.3 |")
    if noise_dbfs is not None:
        w(f"| noise (\"noise polluted\" only) | uniform white noise at {minus(noise_dbfs)} dBFS RMS played into the "
          "sender's loudspeaker (`speaker`, so the robot hears it through the room with the chords) and "
          "into the sender's microphone (`sender_ear`: it sits beside the loudspeakers that play it) |")
    w("| not modelled | loudspeaker and microphone responses, their distortion and automatic gain, "
      "background noise in the other conditions, clock offset between the two sides |")
    w("")
    w("So distance alone costs only margin: at 10 m the model takes 24.6 dB off a 16 kHz tone (20 dB "
      "spreading, 4.6 dB absorption), which leaves it at −39 dBFS, still 21 dB over the detectors' "
      "−60 dBFS noise gate, with nothing else in the room to mask it. The seed's room at 10 m had its "
      "own noise and its hardware's limits.")
    w("")
    if noise_dbfs is not None:
        level = ("the default, as loud as the chords themselves" if noise_dbfs == DEFAULT_NOISE_DBFS
                 else f"set with `--noise-dbfs`; the default, {minus(DEFAULT_NOISE_DBFS)} dBFS, is as loud as the chords")
        w(f"**The noise level.** The seed gives none: \"continuous white noise was played through the "
          "sender's speakers\", the same loudspeakers as the chords, both at full volume. Here it is "
          f"{minus(noise_dbfs)} dBFS RMS ({level}: four tones of amplitude 0.2 make −11 dBFS RMS; an ACK, two "
          "tones, −14 dBFS). A chord's tone stands 25–35 dB over this noise in its FFT bin, yet the seed's "
          "rule (exactly one plan tone per band among the 10 loudest peaks between 4 and 17 kHz) refuses "
          "most windows at this level: six of the ten peaks are noise, and each lands within ±25 Hz of some "
          "plan tone about 30 % of the time (docs/protocol.md §1). Under that rule this script's runs of "
          "2026-11-22 confirmed 94 % of frames here. The robot now asks instead that a band's tone stand "
          "8 dB above the band's other plan tones (`dominance_db`, docs/protocol.md §5), which noise peaks "
          "25 dB down never do; the sender's ACK / NACK test follows the same rule.")
        w("")
    if "reference" in runs and "general" in runs:
        ref, gen = runs["reference"][0], runs["general"][0]
        if ref["latency_avg_ms"] is not None and gen["latency_avg_ms"] is not None:
            added = float(gen["latency_avg_ms"]) - float(ref["latency_avg_ms"]) - 1000 / 343
            added_rt = (float(gen["response_time_avg_ms"]) - float(ref["response_time_avg_ms"])
                        if ref["response_time_avg_ms"] is not None and gen["response_time_avg_ms"] is not None
                        else None)
            w("**Bridge latency.** Each direction passes through `parec` and `pacat` (buffers of "
              f"{args.bridge_buffers_ms[0]:g} and {args.bridge_buffers_ms[1]:g} ms) and two more null sinks. "
              "When `pacat` runs dry on a busy machine it plays a few ms of silence and the delay grows by as "
              "much for the rest of the run: a step in a latency plot (smaller buffers made that frequent). "
              "The reference run, "
              "on the plain air without a room, measures it: general's average latency less the "
              f"reference's less the 2.9 ms of flight is **{added:.0f} ms** added on the way to the "
              "robot" + (f", and the response time (both ways) grows by **{added_rt:.0f} ms**." if added_rt is not None else ".")
              + " Latency and response time here are therefore a little longer than the programs "
              "alone would give, and neither is comparable in absolute terms with the seed's: its "
              "figures include its loudspeakers', sound cards' and Python program's delays (its "
              "response time waited for each chord to end).")
            w("")
    w("## Summary")
    w("")
    w("Each cell: the seed / ours.")
    w("")
    w("| condition | sent | chords played | matched | sender confirmed | CRC rejected | false positives "
      "| avg response time (ms) | avg latency (ms) |")
    w("|---|---|---|---|---|---|---|---|---|")

    def pair(name, key, kind):
        seed = SEED.get(name)
        ours = fmt(runs[name][0][key], kind)
        theirs = "–" if seed is None or key not in seed else fmt(seed[key], kind)
        for unit in (" ms", " %"):
            ours, theirs = ours.replace(unit, ""), theirs.replace(unit, "")
        return f"{theirs} / {ours}"

    for name in args.conditions:
        w(f"| [{SHORT[name]}](#{anchor(TITLES[name])}) | {pair(name, 'transmissions_sent', 'n')} "
          f"| {pair(name, 'frame_attempts', 'n')} | {pair(name, 'successfully_matched', 'n')} "
          f"| {pair(name, 'sender_confirmed_rate_pct', 'pct')} % "
          f"| {pair(name, 'crc_rejected', 'n')} | {pair(name, 'false_positives', 'n')} "
          f"| {pair(name, 'response_time_avg_ms', 'ms')} | {pair(name, 'latency_avg_ms', 'ms')} |")
    w("")

    for name in args.conditions:
        report, frames, condition = runs[name]
        seed = SEED.get(name)
        png = os.path.join(png_dir, f"{name}.png")
        plot(name, report, frames, png)
        w(f"## {TITLES[name]}")
        w("")
        where = ("the plain air: both programs on one null sink, no room, no bridge" if condition["distance_m"] is None
                 else f"{condition['distance_m']:g} m both ways")
        w(f"Run \"{report['label']}\" ({report['run_id']}), {where}; "
          f"{len(frames)} chords in {condition['seconds']} s including start and stop.")
        w("")
        w("| figure | seed | ours |")
        w("|---|---|---|")
        for text, key, kind in ROWS:
            theirs = "–" if seed is None else (fmt(seed[key], kind) if key in seed else "–")
            w(f"| {text} | {theirs} | {fmt(report[key], kind)} |")
        w("")
        w(f"![{TITLES[name]}: response time and latency per chord](results/{name}.png)")
        w("")
    w("Response time: the chord's start to the ACK / NACK heard by the sender. Latency: the "
      "chord's start to the robot's reception of it. A red × is a chord without one; a green "
      "square a retransmission; the dashed line the seed's average.")
    w("")
    noisy = {name: runs[name][0]["false_positives"] for name in args.conditions if runs[name][0]["false_positives"]}
    if noisy:
        w("False positives in these runs: " + ", ".join(f"{TITLES[n]} {c}" for n, c in noisy.items()) + ". "
          "The agent's log (`build/experiments/logs/`) shows each reception. A chord heard twice can cost a "
          "command although every chord was ACKed and matched: a mode word heard twice is taken for the "
          "parameter word (\"ignored (parameter word ... has no valid ... field)\"), and the real parameter "
          "word that follows is then ignored, the failure the seed describes in its §11.3.")
    else:
        w("No condition heard a false positive. Before the debouncer's tail rule (docs/protocol.md §6), runs "
          "without noise now and then heard a chord a second time from its own reverberant tail, 850 ms "
          "after the first, once the 800 ms lockout had ended.")
    w("")
    with open(args.out, "w") as f:
        f.write("\n".join(out))
    print(f"wrote {args.out} and {len(args.conditions)} PNGs in {png_dir}")
    return 0


def anchor(title: str) -> str:
    """GitHub's heading anchor: lower case, punctuation dropped, spaces to hyphens."""
    keep = "".join(c for c in title.lower() if c.isalnum() or c in " -")
    return keep.replace(" ", "-")


if __name__ == "__main__":
    sys.exit(main())
