#!/usr/bin/env python3
"""What the web console costs and how late it shows the air (issue 61's targets), measured on
the whole system as scripts/quickstart starts it (one keyed robot through the seminar room, the
server, the console) with Debian's Chromium, headless, as the page's browser:

  - the sender machine's CPU for the console (dtmf-server's and dtmf-console's, from /proc) over
    a phase with no page, then a phase with one page open (its WatchAir at 25 spectrum columns a
    second of 160 bins);
  - air → spectrogram column drawn: the column's wall time at the sender to the page drawing it;
  - a frame's mark: the sender taking a frame's answer to the page drawing its mark, over Drives
    clicked in the page;
  - the page's weight at load (every byte from the console).

  console_bench.py SOURCE_DIR BIN_DIR WORK_DIR OUT_JSON [--seconds S] [--drives N]
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

from selenium.webdriver.common.by import By

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts" / "lib"))
from headless_chromium import new_browser, wait_until  # noqa: E402

PORTS = {"DTMF_QUICKSTART_PORT": "25470", "DTMF_QUICKSTART_PG_PORT": "25471", "DTMF_QUICKSTART_CONSOLE_PORT": "25472"}


def cpu_seconds(pid: int) -> float:
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def cpu_shares(pids: dict, seconds: float) -> dict:
    """Each process's CPU over the same `seconds` of wall time, in percent of one core."""
    start_cpu, start = {name: cpu_seconds(pid) for name, pid in pids.items()}, time.monotonic()
    time.sleep(seconds)  # the phase's length is the measurement
    wall_s = time.monotonic() - start
    return {name: 100 * (cpu_seconds(pid) - start_cpu[name]) / wall_s for name, pid in pids.items()}


def percentile(values, p):
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(round(p / 100 * (len(ordered) - 1))))]


def summary(values):
    return {"median": statistics.median(values), "p95": percentile(values, 95), "max": max(values),
            "count": len(values)} if values else None


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("source")
    parser.add_argument("bin")
    parser.add_argument("work")
    parser.add_argument("out")
    parser.add_argument("--seconds", type=float, default=60)
    parser.add_argument("--drives", type=int, default=20)
    args = parser.parse_args()
    env = dict(os.environ, DTMF_QUICKSTART_BIN=args.bin, DTMF_QUICKSTART_DIR=args.work, **PORTS)
    env.pop("DTMF_AUDIO_DEVICE", None)
    quickstart = [os.path.join(args.source, "scripts", "quickstart")]
    subprocess.run(quickstart + ["down"], env=env, capture_output=True)
    up = subprocess.run(quickstart + ["--no-sequence"], env=env, capture_output=True, text=True)
    if up.returncode != 0:
        sys.exit(f"console_bench: scripts/quickstart failed: {up.stdout}{up.stderr}")
    page = None
    try:
        # The sender machine's share of the console: dtmf-server's extra work for a watcher and
        # dtmf-console's own (the browser is the user's, elsewhere in a real deployment).
        pids = {name: int(Path(args.work, f"{name}.pid").read_text()) for name in ("server", "console")}
        time.sleep(5)  # the system settles: its first seconds are not the sender's steady state
        unwatched = cpu_shares(pids, args.seconds)
        page = new_browser()
        page.get(f"http://127.0.0.1:{PORTS['DTMF_QUICKSTART_CONSOLE_PORT']}/")
        if not wait_until(lambda: page.find_element(By.ID, "connection").get_attribute("data-state") == "connected", 30):
            sys.exit("console_bench: the page never went live")
        weight = page.execute_script(
            "return performance.getEntriesByType('resource').reduce((s, e) => s + e.encodedBodySize, 0)"
            " + performance.getEntriesByType('navigation')[0].encodedBodySize;")
        watched = cpu_shares(pids, args.seconds)
        for _ in range(args.drives):
            before = page.execute_script("return window.dtmfConsole.spectrogram.stats.answersMarked")
            page.find_element(By.ID, "drive-button").click()
            wait_until(lambda: page.execute_script("return window.dtmfConsole.spectrogram.stats.answersMarked") > before, 5)
            time.sleep(1.2)  # the Drive (1 s) ends before the next: one command on the air at a time
        stats = page.execute_script("return window.dtmfConsole.spectrogram.stats")
        result = {
            "measured_utc": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
            "seconds_per_phase": args.seconds,
            "cpu_unwatched_pct_core": unwatched,
            "cpu_watched_pct_core": watched,
            "extra_cpu_pct_core": sum(watched.values()) - sum(unwatched.values()),
            "column_delay_ms": summary(stats["columnDelaysMs"]),
            "mark_delay_ms": summary(stats["markDelaysMs"]),
            "columns_drawn": stats["columns"],
            "drives": args.drives,
            "page_weight_bytes": weight,
        }
        Path(args.out).write_text(json.dumps(result, indent=2))
        print(json.dumps(result, indent=2))
    finally:
        if page:
            page.quit()
        subprocess.run(quickstart + ["down"], env=env, capture_output=True)
        subprocess.run([os.path.join(args.source, "scripts", "pg"), "destroy", os.path.join(args.work, "pg")],
                       capture_output=True)


if __name__ == "__main__":
    main()
