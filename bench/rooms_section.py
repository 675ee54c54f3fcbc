"""The rooms section of docs/benchmarks.md: dtmf-bench-rooms' table and its plot.

Kept apart from write_benchmarks.py (which imports it) so that each file stays readable.
The room targets are issue 15's, typed once here (targets_section.py judges them); every figure
comes from BUILD/bench/PROFILE/rooms.json.
"""

import os

import matplotlib.pyplot as plt

# (what, which cases, the least success each must reach; None: judged on its own figures).
# bench/rirs, as bench/frames/channel_case.h names them.
MEASURED_ROOMS = ("studio_live_room", "seminar_room_clap", "smoking_room", "st_margarets_church", "st_andrews_church",
                  "monument_chamber", "concert_hall", "typing_room", "club_hall")

TARGETS = [
    ("measured rooms (1 and 3 m)", lambda c: c.startswith(MEASURED_ROOMS) and "ppm" not in c, 0.999),
    ("image-source rooms, RT60 ≤ 1.0 s, 1–5 m", lambda c: c.startswith("image-source") and rt60(c) <= 1.0, 0.999),
    ("image-source rooms, RT60 1.5 s", lambda c: c.startswith("image-source") and rt60(c) > 1.0, 0.99),
    ("clock offset ±2000 ppm (< 0.1 % lost)", lambda c: "ppm" in c, 0.999),
    ("a whine 6 dB over a tone (< 1 % lost)", lambda c: c.startswith("whine"), 0.99),
]


def rt60(case):
    return float(case.split("RT60 ")[1].split(" ")[0])


def plot_rooms(docs, png_dir):
    cases = [c["case"] for c in next(iter(docs.values()))["cases"]]
    fig, ax = plt.subplots(figsize=(9, 0.28 * len(cases) + 1.5))
    height = 0.8 / max(len(docs), 1)
    for i, (p, d) in enumerate(docs.items()):
        lost = {c["case"]: 100 * (1 - c["success_rate"]) for c in d["cases"]}
        ys = [k + i * height for k in range(len(cases))]
        ax.barh(ys, [max(lost.get(c, 0), 0.01) for c in cases], height=height, label=p)
    ax.set_yticks([k + 0.4 - height / 2 for k in range(len(cases))])
    ax.set_yticklabels(cases, fontsize=7)
    ax.invert_yaxis()
    ax.set_xscale("log")
    ax.axvline(0.1, color="k", lw=0.8, ls="--")
    ax.axvline(1, color="k", lw=0.8, ls=":")
    ax.set_xlabel("frames lost (%, log; bars at 0.01 % mean none lost)")
    ax.set_title("Rooms: frames lost per case (dashed 0.1 %, dotted 1 %)")
    ax.grid(alpha=0.3, axis="x")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(png_dir, "rooms_lost.png"), dpi=100)
    plt.close(fig)


def rooms_section(w, data, profiles, stem, png_dir, ok):
    w("## Rooms")
    w("")
    docs = {p: data[p]["rooms"] for p in profiles if ok(data[p]["rooms"])}
    if not docs:
        w("Not run: " + "; ".join(f"{p}: {data[p]['rooms']['error']}" for p in profiles))
        w("")
        return
    first = next(iter(docs.values()))
    w("`dtmf-bench-rooms`: random frames through measured rooms (`bench/rirs/`: their direct sound 1/d from 1 m, "
      "their reverberation as loud at every distance), image-source rooms 6 × 8 × 3 m tuned to an RT60 (a hard "
      "floor, the microphone 5 cm above it, the loudspeaker at the distance towards the far corner and up to 0.75 m "
      "higher), clock offsets and steady whines 6 dB over one of the profile's tones as heard at 1 m; pink noise at "
      "−50 dBFS everywhere. "
      f"{first['frames_per_case']} frames a case, in streams of 100 that each begin with {first['lead_in_s']:g} s of the "
      "channel alone (a robot listens long before it is spoken to). Columns as in the sweeps.")
    w("")
    plot_rooms(docs, png_dir)
    w("![frames lost per case](" + stem + "/rooms_lost.png)")
    w("")
    w("| case | " + " | ".join(f"{p}: success | {p}: twice | {p}: wrong | {p}: NACKed" for p in docs) + " |")
    w("|---|" + "---|---|---|---|" * len(docs))
    by_case = {p: {c["case"]: c for c in d["cases"]} for p, d in docs.items()}
    for c in first["cases"]:
        cells = []
        for p in docs:
            r = by_case[p].get(c["case"])
            if r is None:
                cells += ["–"] * 4
                continue
            lo, hi = r["success_rate_ci95"]
            cells += [f"{100 * r['success_rate']:.2f} % of {r['frames']} [{100 * lo:.2f}, {100 * hi:.2f}]",
                      str(r["duplicated"]), str(r["wrong_accepts"]), str(r["check_failed"])]
        w(f"| {c['case']} | " + " | ".join(cells) + " |")
    w("")
    w("The targets are judged on these rows in the section *Targets (issue 15)* at the end.")
    w("")
