#!/usr/bin/env python3
"""Writes docs/benchmarks.md and its plots (docs/benchmarks/*.png) from scripts/bench's JSON.

    python3 bench/write_benchmarks.py --in build/bench --out docs/benchmarks.md --profiles seed fast \\
        --machine "..." --date "..." --minutes 9 --build-type Release --talkoff-s 3600

Each profile's directory holds one JSON file per benchmark (decoder, snr, distance,
distance_loud, rooms, talkoff_speech, talkoff_music, talkoff_noise, e2e, teleop...) or NAME.error when the
benchmark could not run for that profile. Every figure of ours comes from those files; the
seed report's figures and the issue's targets for the fast profile are typed once below.
Needs Python 3 and matplotlib (Debian: python3-matplotlib).
"""

import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")  # files only
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rooms_section import rooms_section  # noqa: E402
from answers_section import answers_section  # noqa: E402
from targets_section import targets_section  # noqa: E402
from teleop_section import teleop_section  # noqa: E402
from fleet_section import fleet_section  # noqa: E402
from robot_section import robot_section  # noqa: E402
from watch_section import watch_section  # noqa: E402
from console_section import console_section  # noqa: E402
from ros_bridge_section import ros_bridge_section  # noqa: E402
from round_trip_rooms_section import load_rooms, round_trip_rooms_section, round_trip_targets_section  # noqa: E402

BENCHES = ["decoder", "snr", "distance", "distance_loud", "rooms", "answers", "talkoff_speech", "talkoff_music",
           "talkoff_noise", "roundtrip", "roundtrip_room", "e2e", "e2e_room", "teleop"]
# Run only where they apply (dtmf-bench-lost: hopped frames without a key; dtmf-bench-room-stop:
# profiles whose frames name robots): listed under "not run" only when they failed.
OPTIONAL_BENCHES = ["lost", "room_stop", "fleet_teleop"]
# A frame heard that reads as a joint renewal forges one with at most 3 slots in each of 4 readings,
# each 2^-18 (docs/security.md, "Joint renewals": kMacChecksPerFrame, kRenewalMacBits).
RENEWAL_FORGERY_PER_FRAME = 12 * 2.0**-18
TALKOFF = [("speech", "speech (espeak-ng)"), ("music", "music-like (sox synth)"), ("noise", "noise (white, pink, brown)")]


def lost_section(w, profile, d):
    """Why frames are lost at one SNR, frame by frame (dtmf-bench-lost)."""
    lost = d["frames"] - d["accepted"]
    read = lost - d["lost_no_reading"]
    misread = d["misread_tones"]

    def pct(n, of):
        return f"{100 * n / of:.0f} %" if of else "–"

    def count(n):
        return f"{n:,}".replace(",", " ")
    snr = f"{d['snr_db']:g}".replace("-", "−")
    at_most = 100 * (d["accepted"] + d["oracle_erasure_decodes"]) / d["frames"]
    w(f"`{profile}` at {snr} dB, frame by frame (`dtmf-bench-lost`: {count(d['frames'])} frames, each alone in its "
      f"noise): {100 * d['success_rate']:.2f} % accepted. Of the {count(lost)} lost, {count(d['lost_no_reading'])} "
      f"never made a reading at the gate and {count(read)} were read with errors (the best of the grid's readings "
      f"and the whole-chord re-reads): {count(misread)} heard tones "
      f"misread besides the unheard; the tone sent was the band's runner-up for "
      f"{pct(d['misread_runner_up_right'], misread)} of them (what the runner-up swaps can mend) and "
      f"{pct(d['misread_among_doubted'], misread)} were among the {d['doubted_tones']} least certain. An oracle "
      f"erasing exactly the misread and unheard tones, at most {d['oracle_max_erasures']} as the plain tries, would "
      f"decode {count(d['oracle_erasure_decodes'])} of them: "
      f"{at_most:.2f} % at most from these readings.")
    w("")


def load(directory, profiles):
    data = {}
    for p in profiles:
        data[p] = {}
        for b in BENCHES + OPTIONAL_BENCHES:
            path = os.path.join(directory, p, b + ".json")
            err = os.path.join(directory, p, b + ".error")
            if os.path.exists(path):
                with open(path) as f:
                    data[p][b] = json.load(f)
            elif os.path.exists(err):
                with open(err) as f:
                    lines = [line.strip() for line in f if line.strip()]
                data[p][b] = {"error": lines[-1] if lines else "failed"}
            else:
                data[p][b] = {"error": "not run"}
    return data


def ok(doc):
    return doc is not None and "error" not in doc


def num(x, digits=0, unit=""):
    if x is None:
        return "–"
    s = f"{x:,.{digits}f}".replace(",", " ") + unit
    return s.replace("-", "−")


def pct(x, digits=2):
    return "–" if x is None else f"{100 * x:.{digits}f} %"


def db(x):
    return "none" if x is None else f"{x:+g} dB".replace("-", "−")


def point_at(doc, key, value):
    for p in doc["points"]:
        if abs(p[key] - value) < 1e-9:
            return p
    return None


def decoder_factor(doc, signal):
    for s in doc["signals"]:
        if s["signal"] == signal:
            return s["realtime_factor"]
    return None


def summary_rows(d):
    """(figure, seed report, fast target, function(profile data) -> text)."""
    def e2e(key, digits=0, unit=""):
        return lambda p: num(p["e2e"][key], digits, unit) if ok(p["e2e"]) else "not run"

    def snr_at(x):
        def f(p):
            if not ok(p["snr"]):
                return "not run"
            pt = point_at(p["snr"], "snr_db", x)
            return "–" if pt is None else f"{pct(pt['success_rate'])} ({pt['frames']} frames)"
        return f

    def snr_key(key):
        return lambda p: db(p["snr"][key]) if ok(p["snr"]) else "not run"

    def wrong(bench):
        def f(p):
            if not ok(p[bench]):
                return "not run"
            frames = sum(pt["frames"] for pt in p[bench]["points"])
            return f"{sum(pt['wrong_accepts'] for pt in p[bench]['points'])} in {frames:,}".replace(",", " ")
        return f

    def slipped(p):
        if not ok(p["snr"]):
            return "not run"
        w = sum(pt["wrong_accepts"] for pt in p["snr"]["points"])
        c = sum(pt["check_failed"] for pt in p["snr"]["points"])
        return "–" if w + c == 0 else f"1 in {(w + c) / w:.0f} ({w} of {w + c})" if w else f"0 of {c}"

    def talk(kind, key):
        b = "talkoff_" + kind
        return lambda p: num(p[b][key], 2) if ok(p[b]) else "not run"

    def dec(signal):
        return lambda p: num(decoder_factor(p["decoder"], signal), 0, " ×") if ok(p["decoder"]) else "not run"

    def farthest(bench):
        return lambda p: ("none" if p[bench]["farthest_m_99"] is None else f"{p[bench]['farthest_m_99']:g} m") \
            if ok(p[bench]) else "not run"

    def response(p):
        if not ok(p["e2e"]) or not p["e2e"]["response_times_ms"]:
            return "not run"
        v = sorted(p["e2e"]["response_times_ms"])
        return num(v[len(v) // 2], 0, " ms")

    def trip(f):
        return lambda p: f(p["roundtrip"]) if ok(p["roundtrip"]) else "not run"

    rows = [
        ("Response time (chord start → ACK heard), median", "about 883 ms (avg. 883–888)", "–", response),
        # The targets are the RPC's (end to end, below); the link round trip shows what the
        # link alone takes, without gRPC, queues and threads.
        ("Command handed over → confirmed, link round trip in a simulated room, median", "–", "–",
         trip(lambda d: num(d["latency_ms"]["median"], 0, " ms"))),
        ("Link round trip: p95 / max", "–", "–",
         trip(lambda d: f"{num(d['latency_ms']['p95'], 0)} / {num(d['latency_ms']['max'], 0)} ms")),
        ("Net payload throughput, link round trip (stop and wait)", "16–18 bit/s (gross)", "–",
         trip(lambda d: num(d["throughput_bps"], 1, " bit/s"))),
        ("Drive command: RPC call → confirmed, median", "–", "≤ 150 ms", e2e("latency_ms_median", 0, " ms")),
        ("Drive command: p95 / max", "–", "–",
         lambda p: f"{num(p['e2e']['latency_ms_p95'], 0)} / {num(p['e2e']['latency_ms_max'], 0)} ms" if ok(p["e2e"]) else "not run"),
        ("Net payload throughput (end to end)", "16–18 bit/s (gross)", "≥ 250 bit/s", e2e("throughput_bps", 1, " bit/s")),
        ("Frames ACKed at the first attempt (end to end)", "100 % (general, 1 m)", "–",
         lambda p: pct(p["e2e"]["frame_success_rate"]) if ok(p["e2e"]) else "not run"),
        ("Frame success at −10 dB SNR", "–", "≥ 99.9 %", snr_at(-10)),
        ("Lowest SNR with ≥ 99 % success (and all above)", "–", "–", snr_key("lowest_snr_db_99")),
        ("Lowest SNR with ≥ 99.9 % success (and all above)", "–", "–", snr_key("lowest_snr_db_99_9")),
        ("Wrong accepts, SNR sweep", "–", "0", wrong("snr")),
        ("Corrupted frames passing the check (SNR sweep)", "CRC-4: 1 in 15 two-tone errors", "–", slipped),
        ("Farthest distance with ≥ 99 % (pink −50 dBFS)", "10 m tested (98.5 %)", "–", farthest("distance")),
        ("Farthest distance with ≥ 99 % (pink −40 dBFS)", "–", "–", farthest("distance_loud")),
        ("Wrong accepts, distance sweeps", "–", "0",
         lambda p: " / ".join(wrong(b)(p) for b in ("distance", "distance_loud"))),
    ]
    for kind, label in TALKOFF:
        rows.append((f"Accepted frames per hour of {label}", "–", "0", talk(kind, "accepted_per_hour")))
    for kind, label in TALKOFF:
        rows.append((f"False ACK + NACK per hour of {kind} (sender)", "–", "–",
                     lambda p, k=kind: num(p["talkoff_" + k]["acks_per_hour"] + p["talkoff_" + k]["nacks_per_hour"], 2)
                     if ok(p["talkoff_" + k]) else "not run"))
    rows += [
        ("Decoder speed, noise only (one core)", "–", "≥ 5000 ×", dec("noise")),
        ("Decoder speed, back-to-back frames", "–", "≥ 5000 ×", dec("frames")),
    ]
    return rows


def plot_snr(data, profiles, png_dir):
    fig, ax = plt.subplots(figsize=(8, 4.5))
    fig2, ax2 = plt.subplots(figsize=(8, 4.5))
    for p in profiles:
        doc = data[p]["snr"]
        if not ok(doc):
            continue
        x = [pt["snr_db"] for pt in doc["points"]]
        ax.plot(x, [100 * pt["success_rate"] for pt in doc["points"]], "o-", markersize=3, label=p)
        ax2.plot(x, [pt["wrong_accepts"] for pt in doc["points"]], "o-", markersize=3,
                 label=f"{p} ({doc['frames_per_point']}–{doc['topup_frames']} frames a point)")
    for a, ylabel in ((ax, "frame success (%)"), (ax2, "wrong accepts (count)")):
        a.axvline(-10, color="grey", linestyle=":", linewidth=1)
        a.set_xlabel("SNR (dB): chord power / white noise power over 0..fs/2")
        a.set_ylabel(ylabel)
        a.grid(alpha=0.3)
        a.legend(fontsize=8)
    ax.axhline(99.9, color="grey", linestyle="--", linewidth=1)
    ax.set_title("Frame success against SNR (dotted: −10 dB; dashed: 99.9 %)")
    ax2.set_title("Wrong accepts against SNR")
    ax2.set_ylim(bottom=-0.5)
    for f, name in ((fig, "snr_success.png"), (fig2, "snr_wrong_accepts.png")):
        f.tight_layout()
        f.savefig(os.path.join(png_dir, name), dpi=100)
        plt.close(f)


def plot_distance(data, profiles, png_dir):
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for p in profiles:
        for bench, style in (("distance", "o-"), ("distance_loud", "s--")):
            doc = data[p][bench]
            if not ok(doc):
                continue
            ax.plot([pt["distance_m"] for pt in doc["points"]], [100 * pt["success_rate"] for pt in doc["points"]],
                    style, markersize=3, label=f"{p}, pink noise {doc['noise_dbfs']:g} dBFS".replace("-", "−"))
    ax.set_xlabel("distance (m)")
    ax.set_ylabel("frame success (%)")
    ax.set_title("Frame success against distance (room RT60 0.3 s)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(png_dir, "distance_success.png"), dpi=100)
    plt.close(fig)


def plot_latency(data, profiles, png_dir, bench="e2e", title="End-to-end command latency",
                 xlabel="Drive: RPC call → confirmed (ms)", name="e2e_latency.png"):
    fig, (hist, cdf) = plt.subplots(1, 2, figsize=(10, 4))
    for p in profiles:
        doc = data[p][bench]
        if not ok(doc) or not doc["latencies_ms"]:
            continue
        v = sorted(doc["latencies_ms"])
        hist.hist(v, bins=20, alpha=0.6, label=p)
        cdf.step(v, [(i + 1) / len(v) for i in range(len(v))], where="post", label=p)
    hist.set_xlabel(xlabel)
    hist.set_ylabel("commands")
    cdf.set_xlabel(xlabel)
    cdf.set_ylabel("fraction of commands")
    for a in (hist, cdf):
        a.grid(alpha=0.3)
        a.legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(os.path.join(png_dir, name), dpi=100)
    plt.close(fig)


def sweep_table(w, data, profiles, bench, key, label, unit):
    docs = {p: data[p][bench] for p in profiles if ok(data[p][bench])}
    if not docs:
        w(f"No profile could run this benchmark: " + "; ".join(f"{p}: {data[p][bench]['error']}" for p in profiles))
        w("")
        return
    xs = sorted({pt[key] for d in docs.values() for pt in d["points"]})
    w("| " + label + " | " + " | ".join(f"{p}: success | {p}: heard twice | {p}: wrong accepts | {p}: check failed" for p in docs) + " |")
    w("|---|" + "---|---|---|---|" * len(docs))
    for x in xs:
        cells = []
        for p, d in docs.items():
            pt = point_at(d, key, x)
            if pt is None:
                cells += ["–", "–", "–", "–"]
            else:
                lo, hi = pt["success_rate_ci95"]
                cells += [f"{pct(pt['success_rate'])} of {pt['frames']} [{100 * lo:.2f}, {100 * hi:.2f}]",
                          str(pt["duplicated"]), str(pt["wrong_accepts"]), str(pt["check_failed"])]
        w(f"| {num(x, 0 if float(x).is_integer() else 1)}{unit} | " + " | ".join(cells) + " |")
    w("")
    for p in profiles:
        if p not in docs:
            w(f"`{p}`: not run ({data[p][bench]['error']}).")
            w("")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--in", dest="directory", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--profiles", nargs="+", required=True)
    parser.add_argument("--machine", required=True)
    parser.add_argument("--date", required=True)
    parser.add_argument("--minutes", type=int, required=True)
    parser.add_argument("--build-type", required=True)
    parser.add_argument("--talkoff-s", type=float, required=True)
    args = parser.parse_args()

    profiles = args.profiles
    data = load(args.directory, profiles)
    stem = os.path.splitext(os.path.basename(args.out))[0]
    png_dir = os.path.join(os.path.dirname(os.path.abspath(args.out)), stem)
    os.makedirs(png_dir, exist_ok=True)
    plot_snr(data, profiles, png_dir)
    plot_distance(data, profiles, png_dir)
    plot_latency(data, profiles, png_dir)
    plot_latency(data, profiles, png_dir, "roundtrip", "Link round trip in a simulated room",
                 "command handed over → confirmed (ms)", "roundtrip_latency.png")

    out = []
    w = out.append
    w("# Benchmarks")
    w("")
    w(f"Generated by `scripts/bench` on {args.date}, on `{args.machine}`, in about {args.minutes} min "
      f"(build type {args.build_type}). Do not edit: run the script again. Every figure in the "
      "profile columns comes from the JSON files the benchmark programs wrote (`BUILD/bench/PROFILE/`); "
      "the seed report's figures (`shared/seed`, §3.3, §10, §11.3) and the issue's targets for the "
      "`fast` profile are typed into `bench/write_benchmarks.py`.")
    w("")
    w("## Summary")
    w("")
    w("| figure | seed report | target (`fast`) | " + " | ".join(f"`{p}`" for p in profiles) + " |")
    w("|---|---|---|" + "---|" * len(profiles))
    for label, seed, target, f in summary_rows(data):
        w(f"| {label} | {seed} | {target} | " + " | ".join(f(data[p]) for p in profiles) + " |")
    w("")
    for p in profiles:
        missing = [b for b in BENCHES if not ok(data[p][b])]
        missing += [b for b in OPTIONAL_BENCHES if data[p][b].get("error", "not run") != "not run"]
        if missing:
            w(f"`{p}`: not run — " + "; ".join(f"{b}: {data[p][b]['error']}" for b in missing) + ".")
            w("")

    w("## Definitions")
    w("")
    w("| term | definition |")
    w("|---|---|")
    w("| SNR | mean power of the transmitted signal over its non-silent part (the chords, measured from 256 random "
      "frames: −11.0 dBFS RMS for `seed`) divided by the power of the added white Gaussian noise over the full "
      "band 0..fs/2, in dB. The signal stays at its nominal level and the noise is scaled, with no clipping "
      "(at −30 dB the noise is far above full scale): the detectors' noise gate is absolute (−60 dBFS), so "
      "results depend on the level as well as on the ratio. |")
    w("| stream | frames at their normal spacing (chord + gap, one *slot* each), random contents (seeded: "
      "the JSON's `seed`), noise over the whole stream, the receiver fed in blocks of 1024 samples as a "
      "device would, one extra slot without a frame at the end; streams of 500 frames, each with a fresh "
      "receiver and its own seeds |")
    w("| slot of an accepted frame | the slot in which it started: its start time (the centre of the first "
      "analysis window that heard it) plus half an analysis window, divided by the slot length |")
    w("| frame success | the frame sent in a slot was accepted exactly once with the right bits |")
    w("| heard twice | the frame sent in a slot was accepted more than once (a reverberant tail heard as a "
      "second frame: docs/protocol.md §6); not a success |")
    w("| wrong accept | an accepted (check-passing) frame whose bits were not sent in its slot (also one "
      "heard in the empty last slot) |")
    w("| check failed | a frame heard that fails the check (CRC): a robot would NACK it; not an error of the "
      "link, the check did its job |")
    w("| frames per point | 1000; points whose success is in [90 %, 99.99 %) after those are topped up to "
      "10 000. Brackets give the 95 % Wilson interval |")
    w("| distance | `physical::AcousticChannel`: delay, 1/d spreading, air absorption (ISO 9613-1 fit), "
      "Schroeder room RT60 0.3 s (wet 0.3), background pink noise at −50 dBFS RMS (a quiet room; the "
      "chords are −11 dBFS RMS at 1 m) and again at −40 dBFS; 1000 frames per point, 1..20 m |")
    w(f"| talk-off | {args.talkoff_s / 3600:.3g} h of each signal, streamed through pipes (never stored), at the "
      "profile's sample rate, into the robot's receiver and the sender's reply listener: *speech* — espeak-ng "
      "reading the texts of /usr/share/common-licenses paragraph by paragraph, each paragraph in the next of "
      "12 voices (English accents, female and male variants, German, French, Spanish, Italian, Dutch), 5 "
      "speeds (110–260 words/min) and 5 pitches, through sox to 48 kHz; *music-like* — seeded sox synth "
      "phrases: four-note chords with tremolo, sweeps up to 16 kHz, plucked arpeggios, square and sawtooth "
      "melodies, the tempo changing each phrase; *noise* — white, pink and brown noise, 20 min each |")
    w("| decoder speed | seconds of audio the robot's receive path (everything up to the check) decodes per "
      "second of one core's CPU time, fed in 1024-sample blocks: 60 s of pink noise at −30 dBFS, and "
      "random frames back to back in pink noise at −40 dBFS (all must be accepted) |")
    w("| end to end | the whole system in one process (`tests/server/live_system.h`: server transmitter and "
      "robot agent through a real-time simulated room, 1 m, white noise −70 dBFS), a real gRPC client "
      "sending Drive commands (random speed and duration) one after another. Latency: from the RPC call "
      "until the client reads FRAME_EVENT_CONFIRMED. Payload bits: the data bits of every frame of each "
      "confirmed command, check bits excluded and a retransmission not counted twice (`seed`: RESET, mode "
      "and parameter words, 3 × 12 = 36 bits per Drive); throughput = payload bits / time from the first "
      "call to the last confirmation. Frame success: frames ACKed at their first transmission. The seed "
      "report's 16–18 bit/s counted gross bits (16 per frame incl. CRC) per second of sound |")
    w("")

    w("## Frame success against SNR")
    w("")
    w("![frame success against SNR](" + stem + "/snr_success.png)")
    w("")
    w("![wrong accepts against SNR](" + stem + "/snr_wrong_accepts.png)")
    w("")
    sweep_table(w, data, profiles, "snr", "snr_db", "SNR", " dB")
    for p in profiles:
        d = data[p]["snr"]
        if ok(d):
            topped = [pt["snr_db"] for pt in d["points"] if pt["frames"] > d["frames_per_point"]]
            w(f"`{p}`: {d['total_frames']:,} frames in {d['wall_s']:.0f} s on {d['threads']} threads; "
              f"topped up to {d['topup_frames']:,}: {', '.join(f'{x:g}' for x in topped) or 'none'} dB.".replace(",", " ")
              .replace("-", "−"))
            w("")
    for p in profiles:
        if ok(data[p].get("lost")):
            lost_section(w, p, data[p]["lost"])

    w("## Frame success against distance")
    w("")
    w("![frame success against distance](" + stem + "/distance_success.png)")
    w("")
    w("Background pink noise at −50 dBFS RMS:")
    w("")
    sweep_table(w, data, profiles, "distance", "distance_m", "distance", " m")
    w("Background pink noise at −40 dBFS RMS:")
    w("")
    sweep_table(w, data, profiles, "distance_loud", "distance_m", "distance", " m")

    rooms_section(w, data, profiles, stem, png_dir, ok)
    answers_section(w, data, profiles, ok)

    w("## Talk-off")
    w("")
    w("A false confirmation is an ACK the sender would take for the frame it waits for (a new random frame every "
      "ACK timeout; with a key, a tag chord reading with 9 of 16 bands of its tag, `protocol/link/answer_wait.h`).")
    w("")
    w("A frame that passes its check but not the robot's other tests (its MAC, with a key) is *intact, refused*. With a "
      "key, only such a frame could pass for a joint renewal: the robot reads a renewal's slots only in an intact "
      "frame, and a slot naming it holds by chance with 2⁻¹⁸, at most 12 × 2⁻¹⁸ = 4.6 × 10⁻⁵ a frame heard "
      "(docs/security.md, *Joint renewals*). Talk-off gives the robot no velocity to renew, so the chance is "
      "counted, not tried: the last column is the intact frames an hour times that bound, and with none heard, the 3 an "
      "hour that an hour without one still allows at 95 % (the rule of three).")
    w("")
    w("| signal | profile | hours | RMS | accepted frames (/h) | check-failing frames (/h) | intact, refused (/h) "
      "| false ACK (/h) | false NACK (/h) | false confirmations (/h) | renewals forged by chance (/h, bound) |")
    w("|---|---|---|---|---|---|---|---|---|---|---|")
    for kind, label in TALKOFF:
        for p in profiles:
            d = data[p]["talkoff_" + kind]
            if not ok(d):
                w(f"| {label} | `{p}` | not run: {d['error']} | | | | | | | | |")
                continue
            # None seen in the hours heard still bounds the rate, at 95 %, by 3 over the hours (the rule of three).
            intact_per_hour = max(d["refused"], 3) / d["hours"] if d["hours"] else float("nan")
            renewal_bound = (f"< {intact_per_hour * RENEWAL_FORGERY_PER_FRAME:.1e}" if d.get("authenticated")
                             else "no renewals")
            w(f"| {label} | `{p}` | {d['hours']:.2f} | {num(d['rms_dbfs'], 1)} dBFS | {d['accepted']} ({d['accepted_per_hour']:.2f}) "
              f"| {d['check_failed']} ({d['check_failed_per_hour']:.2f}) "
              f"| {d['refused']} ({d['refused_per_hour']:.2f}) | {d['acks']} ({d['acks_per_hour']:.2f}) "
              f"| {d['nacks']} ({d['nacks_per_hour']:.2f}) "
              f"| {d.get('false_confirmations', 0)} ({d.get('false_confirmations_per_hour', 0):.2f}) | {renewal_bound} |")
    w("")

    w("## Decoder speed")
    w("")
    w("| profile | signal | audio | CPU | × real time | frames accepted |")
    w("|---|---|---|---|---|---|")
    for p in profiles:
        d = data[p]["decoder"]
        if not ok(d):
            w(f"| `{p}` | not run: {d['error']} | | | | |")
            continue
        for s in d["signals"]:
            w(f"| `{p}` | {s['signal']} | {s['audio_s']:.0f} s | {s['cpu_s']:.3f} s | {s['realtime_factor']:,.0f} "
              f"| {s['frames_accepted']} of {s['frames_expected']} |".replace(",", " "))
    w("")

    w("## Link round trip")
    w("")
    w("`dtmf-bench-roundtrip`: the sender's own core (server/core/sender_core.h, what dtmf-server runs: its queue, "
      "listen before talk, retries and answer matching) and the robot 1 m apart in a simulated room (both ways: "
      "delay, spreading, air absorption, RT60 0.3 s, pink noise at −50 dBFS), both working in 5 ms audio blocks in "
      "simulated time; the sender hears 1 s of its room first, as a server that starts. "
      "A command's latency runs from being handed to the sender (the moment the previous one ended) to its "
      "confirmation; throughput is the confirmed commands' payload bits over the run's audio time. No server, "
      "no gRPC: the link's own share of a command's latency.")
    w("")
    w("![link round trip](" + stem + "/roundtrip_latency.png)")
    w("")
    w("| profile | room | commands confirmed | median | p95 | max | payload | audio time | throughput "
      "| frames answered first time | retransmissions |")
    w("|---|---|---|---|---|---|---|---|---|---|---|")
    for p, bench in [(p, b) for p in profiles for b in ("roundtrip", "roundtrip_room")]:
        d = data[p][bench]
        room = "simulated, RT60 0.3 s" if bench == "roundtrip" else "seminar room (measured) both ways"
        if not ok(d):
            w(f"| `{p}` | {room} | not run: {d['error']} | | | | | | | | |")
            continue
        w(f"| `{p}` | {room} | {d['confirmed']} of {d['commands']} | {d['latency_ms']['median']:.0f} ms | {d['latency_ms']['p95']:.0f} ms "
          f"| {d['latency_ms']['max']:.0f} ms | {d['payload_bits']} bits | {d['run_s']:.1f} s | {d['throughput_bps']:.1f} bit/s "
          f"| {d['frames_first_time']} of {d['frames_sent']} | {d['retransmissions']} |")
    w("")

    w("## End to end")
    w("")
    w("![end-to-end latency](" + stem + "/e2e_latency.png)")
    w("")
    w("| profile | air | commands confirmed | median | p95 | max | payload | time | throughput | frames ACKed first time | retransmissions |")
    w("|---|---|---|---|---|---|---|---|---|---|---|")
    for p, bench in [(p, b) for p in profiles for b in ("e2e", "e2e_room")]:
        d = data[p][bench]
        air = "free field 1 m, white −70 dBFS" if bench == "e2e" else "seminar room (measured) both ways, pink −50 dBFS"
        if not ok(d):
            w(f"| `{p}` | {air} | not run: {d['error']} | | | | | | | | |")
            continue
        w(f"| `{p}` | {air} | {d['confirmed']} of {d['commands']} | {d['latency_ms_median']:.0f} ms | {d['latency_ms_p95']:.0f} ms "
          f"| {d['latency_ms_max']:.0f} ms | {d['payload_bits']} bits | {d['wall_s']:.1f} s | {d['throughput_bps']:.2f} bit/s "
          f"| {d['frames_acked_first_attempt']} of {d['frames_first_attempt']} | {d['retransmissions']} |")
    w("")
    rooms_round_trip = load_rooms(args.directory, profiles)
    round_trip_rooms_section(w, rooms_round_trip, profiles)
    teleop_section(w, data, profiles, ok)
    fleet_section(w, data, profiles, ok, args.directory)
    robot_section(w, args.directory)
    watch_section(w, args.directory)
    console_section(w, args.directory)
    ros_bridge_section(w, args.directory)
    targets_section(w, data, profiles, ok, decoder_factor)
    round_trip_targets_section(w, rooms_round_trip, profiles)
    with open(args.out, "w") as f:
        f.write("\n".join(out))
    print(f"wrote {args.out} and its plots in {png_dir}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
