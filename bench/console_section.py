"""The web console's section of docs/benchmarks.md (issue 61): what one page costs the sender,
how late it draws the air and marks a frame's answer, and what it weighs. Figures from
BUILD/bench/console/console.json, written by bench/console/console_bench.py."""

import json
import os

COLUMN_TARGET_MS = (250.0, 400.0)  # median, p95: air → spectrogram column drawn
MARK_TARGET_MS = 250.0  # median: the answer heard → its mark drawn
EXTRA_CPU_TARGET_PCT = 5.0  # of one core, the sender's
WEIGHT_TARGET_KB = 500.0


def met(ok):
    return "met" if ok else "missed"


def console_section(w, directory):
    path = os.path.join(directory, "console", "console.json")
    w("## The web console")
    w("")
    if not os.path.exists(path):
        error = os.path.join(directory, "console", "console.error")
        w(f"Not run{': ' + open(error).read().strip().splitlines()[-1] if os.path.exists(error) else ''}.")
        w("")
        return
    d = json.load(open(path))
    col, mark = d["column_delay_ms"], d["mark_delay_ms"]
    w("The whole system as `scripts/quickstart` starts it (one keyed robot through the seminar room, the server, "
      "`dtmf-console`), and Debian's Chromium, headless, on the console's page. The CPU of `dtmf-server` and "
      "`dtmf-console` over "
      f"{d['seconds_per_phase']:.0f} s with no page, then {d['seconds_per_phase']:.0f} s with the page open (its "
      f"spectrogram at 25 columns a second of 160 bins); then {d['drives']} Drives clicked in the page. Delays run "
      "from the sender's wall time of a column (when its last sample reached the sender, the audio queued behind it "
      "taken off) or of an answer heard, to the page drawing it (`bench/console/console_bench.py`, "
      f"measured {d.get('measured_utc', 'with the rest')}).")
    w("")
    w("| what | figure | target |")
    w("|---|---|---|")
    w(f"| air → spectrogram column drawn | median {col['median']:.0f} ms, p95 {col['p95']:.0f} ms ({col['count']} "
      f"columns) | ≤ {COLUMN_TARGET_MS[0]:.0f} / {COLUMN_TARGET_MS[1]:.0f} ms: "
      f"{met(col['median'] <= COLUMN_TARGET_MS[0] and col['p95'] <= COLUMN_TARGET_MS[1])} |")
    if mark:
        w(f"| a frame's answer heard → its mark drawn | median {mark['median']:.0f} ms, p95 {mark['p95']:.0f} ms "
          f"({mark['count']} answers) | median ≤ {MARK_TARGET_MS:.0f} ms: {met(mark['median'] <= MARK_TARGET_MS)} |")
    else:
        w(f"| a frame's answer heard → its mark drawn | no answer marked | median ≤ {MARK_TARGET_MS:.0f} ms: missed |")
    extra, before, after = d["extra_cpu_pct_core"], d["cpu_unwatched_pct_core"], d["cpu_watched_pct_core"]
    parts = ", ".join(f"{name} {before[name]:.1f} → {after[name]:.1f} %" for name in sorted(after))
    w(f"| the console's extra CPU on the sender with one page | {extra:+.2f} % of a core ({parts}) | "
      f"≤ {EXTRA_CPU_TARGET_PCT:.0f} %: {met(extra <= EXTRA_CPU_TARGET_PCT)} |")
    kb = d["page_weight_bytes"] / 1024
    w(f"| the page's weight at load | {kb:.0f} kB, all from the console | ≤ {WEIGHT_TARGET_KB:.0f} kB: "
      f"{met(kb <= WEIGHT_TARGET_KB)} |")
    w("")
