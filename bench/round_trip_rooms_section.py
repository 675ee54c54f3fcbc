"""The round trip in every measured room (issue 35): dtmf-bench-e2e (the whole system, real time)
and dtmf-bench-roundtrip (the link alone, offline) through each room of bench/rirs, both ways,
the sender's own loudspeaker at its microphone; one row per room and profile, and the targets.

scripts/bench writes e2e_rir_ROOM.json and roundtrip_rir_ROOM.json per profile (ROOM: the
file's stem, as MEASURED_ROOMS names them).
"""

import json
import os

from rooms_section import MEASURED_ROOMS

# Broadband RT60 (T20) of each room, bench/rirs/README.md.
RT60_S = {"studio_live_room": 0.22, "seminar_room_clap": 0.63, "smoking_room": 0.74, "st_margarets_church": 1.05,
          "st_andrews_church": 1.35, "monument_chamber": 1.45, "concert_hall": 1.74, "typing_room": 2.08,
          "club_hall": 2.24}


def load_rooms(directory, profiles):
    """{profile: {room: {"e2e": doc, "roundtrip": doc}}} for the files that exist."""
    data = {}
    for p in profiles:
        data[p] = {}
        for room in MEASURED_ROOMS:
            for bench in ("e2e", "roundtrip"):
                path = os.path.join(directory, p, f"{bench}_rir_{room}.json")
                if os.path.exists(path):
                    with open(path) as f:
                        data[p].setdefault(room, {})[bench] = json.load(f)
    return data


def first_attempt(doc):
    """Share of first transmissions answered at once, from either benchmark's JSON."""
    if "frames_first_attempt" in doc:
        return doc["frames_acked_first_attempt"] / max(doc["frames_first_attempt"], 1)
    firsts = doc["frames_sent"] - doc["retransmissions"]
    return doc["frames_first_time"] / max(firsts, 1)


def latency(doc):
    if "latency_ms_median" in doc:
        return doc["latency_ms_median"], doc["latency_ms_p95"]
    return doc["latency_ms"]["median"], doc["latency_ms"]["p95"]


def round_trip_rooms_section(w, rooms, profiles):
    shown = [p for p in profiles if rooms.get(p)]
    w("## The round trip in every measured room")
    w("")
    if not shown:
        w("Not run (`scripts/bench` runs it for the hopped profiles).")
        w("")
        return
    w("Each measured room of bench/rirs both ways (pink noise −50 dBFS, 1 m, the sender's own loudspeaker at 0.1 m "
      "from its microphone): `dtmf-bench-e2e --rir` (the whole system in real time: gRPC, the server's transmitter, "
      "the agent) and `dtmf-bench-roundtrip --rir` (the link alone, offline, 5 ms blocks). First attempts: "
      "transmissions answered without a retransmission. *Yields*: the pauses the sender made to let another sender "
      "in, which it makes only once it has heard one (docs/protocol.md §9, sharing the air): alone in its room it "
      "should make none, and its only pauses are a listening pause per 20 s of frames back to back.")
    w("")
    w("| profile | room | RT60 | e2e: first attempts | e2e: RPC → confirmed, median / p95 | e2e: max | e2e: net "
      "| e2e: yields | offline: first attempts | offline: median / p95 | offline: net |")
    w("|---|---|---|---|---|---|---|---|---|---|---|")
    for p in shown:
        for room in MEASURED_ROOMS:
            docs = rooms[p].get(room)
            if not docs:
                continue
            cells = []
            for bench in ("e2e", "roundtrip"):
                d = docs.get(bench)
                if d is None:
                    cells += ["not run", "–", "–"] + (["–", "–"] if bench == "e2e" else [])
                    continue
                med, p95 = latency(d)
                cells += [f"{100 * first_attempt(d):.1f} %", f"{med:.0f} / {p95:.0f} ms"]
                if bench == "e2e":
                    cells.append(f"{d['latency_ms_max']:.0f} ms" if "latency_ms_max" in d else "–")
                cells.append(f"{d['throughput_bps']:.0f} bit/s")
                if bench == "e2e":
                    cells.append(str(d["air_yields"]) if "air_yields" in d else "–")
            w(f"| `{p}` | {room} | {RT60_S[room]:.2f} s | " + " | ".join(cells) + " |")
    w("")


def _rooms_judge(rt60_from, rt60_to, test, text):
    """judge(profile's rooms) over the e2e rows whose RT60 lies in [rt60_from, rt60_to]."""
    def judge(rooms_of_profile):
        rows = [(room, docs["e2e"]) for room, docs in rooms_of_profile.items()
                if "e2e" in docs and rt60_from <= RT60_S[room] <= rt60_to]
        if not rows:
            return None, "not run"
        failing = [(room, d) for room, d in rows if not test(d)]
        worst_room, worst = failing[0] if failing else min(rows, key=lambda r: first_attempt(r[1]))
        return not failing, f"{len(rows) - len(failing)} of {len(rows)} rooms; " + \
            ("worst" if not failing else "misses") + f" {worst_room}: {text(worst)}"
    return judge


def round_trip_targets(keyed):
    """(target, wanted, judge) rows for the keyed or the unkeyed profile (issue 35)."""
    med_max, p95_max, net_min = (200, 300, 120) if keyed else (150, 250, 150)
    return [
        ("first-attempt ACKs, every measured room with RT60 ≤ 1.5 s (e2e)", "≥ 99 %",
         _rooms_judge(0, 1.5, lambda d: first_attempt(d) >= 0.99, lambda d: f"{100 * first_attempt(d):.1f} %")),
        ("first-attempt ACKs, RT60 1.5–2.5 s (e2e)", "≥ 95 %",
         _rooms_judge(1.5, 2.5, lambda d: first_attempt(d) >= 0.95, lambda d: f"{100 * first_attempt(d):.1f} %")),
        ("RPC → confirmed, median / p95, every room with RT60 ≤ 1.5 s (e2e)", f"≤ {med_max} / {p95_max} ms",
         _rooms_judge(0, 1.5, lambda d: latency(d)[0] <= med_max and latency(d)[1] <= p95_max,
                      lambda d: f"{latency(d)[0]:.0f} / {latency(d)[1]:.0f} ms")),
        ("net payload, every room with RT60 ≤ 1.5 s (e2e)", f"≥ {net_min} bit/s",
         _rooms_judge(0, 1.5, lambda d: d["throughput_bps"] >= net_min, lambda d: f"{d['throughput_bps']:.0f} bit/s")),
    ]


def round_trip_targets_section(w, rooms, profiles):
    w("### Targets of issue 35: the round trip in every room")
    w("")
    w("| target | profile | wanted | figure |")
    w("|---|---|---|---|")
    for p in profiles:
        if p == "seed":
            continue
        for key, wanted, judge in round_trip_targets(keyed=p.endswith("+key")):
            met, figure = judge(rooms.get(p, {}))
            verdict = figure if met is None else (f"met: {figure}" if met else f"**missed**: {figure}")
            w(f"| {key} | `{p}` | {wanted} | {verdict} |")
    w("")
