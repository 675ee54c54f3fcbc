"""The sender's watchers section of docs/benchmarks.md (issue 60): what one watcher of the air
at the full spectrum (WatchAir, 50 columns a second of 512 bins) costs the sender, and how soon
it reads a frame. Figures from BUILD/bench/sender/watch.json, written by dtmf-bench-watch."""

import json
import os

EXTRA_CPU_TARGET_PCT = 2.0  # of one core
LATENCY_TARGET_MS = 100.0  # median, a frame's chord start to the watcher reading it


def watch_section(w, directory):
    path = os.path.join(directory, "sender", "watch.json")
    w("## Watching the air")
    w("")
    if not os.path.exists(path):
        error = os.path.join(directory, "sender", "watch.error")
        w(f"Not run{': ' + open(error).read().strip().splitlines()[-1] if os.path.exists(error) else ''}.")
        w("")
        return
    d = json.load(open(path))
    lat = d["latency_ms"]
    w("One watcher reads the air through `WatchAir` at the full spectrum, in a process of its own, while the "
      "sender drives a `fast` command every half second; phases with and without it alternate "
      f"({d['phases']} × {d['seconds_per_phase']:.0f} s each; the robot's agent and the simulated room run in the "
      "measured process too, alike in both). `dtmf-bench-watch`.")
    w("")
    w("| what | figure | target |")
    w("|---|---|---|")
    extra = d["extra_cpu_pct_core"]
    w(f"| the sender's extra CPU | {extra:+.2f} % of a core ({d['cpu_unwatched_pct_core']:.1f} → "
      f"{d['cpu_watched_pct_core']:.1f} %) | ≤ {EXTRA_CPU_TARGET_PCT:.0f} %: "
      f"{'met' if extra <= EXTRA_CPU_TARGET_PCT else 'missed'} |")
    w(f"| a frame's chord start to the watcher | median {lat['median']:.0f} ms, p95 {lat['p95']:.0f} ms, max "
      f"{lat['max']:.0f} ms ({lat['count']} frames) | median ≤ {LATENCY_TARGET_MS:.0f} ms: "
      f"{'met' if lat['median'] <= LATENCY_TARGET_MS else 'missed'} |")
    w(f"| spectrum columns read | {d['columns_per_s']:.1f} a second; {d['dropped_columns']} columns and "
      f"{d['dropped_events']} events lost | 50 a second, none lost |")
    w(f"| commands confirmed meanwhile | {d['commands_confirmed']} | all |")
    w("")
