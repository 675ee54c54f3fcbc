"""The console in Debian's Chromium, headless, through Selenium, against the system that
run_browser_tests.sh started with scripts/quickstart --robots 3 (robot1..robot3 in one room).
Helpers to open pages, wait for what a test means, read the simulated robots' pose logs and
keep screenshots."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
from selenium import webdriver
from selenium.webdriver.common.by import By

CONSOLE_URL = os.environ.get("DTMF_CONSOLE_URL", "http://127.0.0.1:25462/")
SERVER = os.environ.get("DTMF_SERVER", "localhost:25460")
SOURCE = Path(os.environ.get("DTMF_SOURCE_DIR", Path(__file__).resolve().parents[3]))
QUICKSTART_DIR = Path(os.environ.get("DTMF_QUICKSTART_DIR", "build/console-browser"))
ARTEFACTS = Path(os.environ.get("DTMF_CONSOLE_ARTEFACTS", QUICKSTART_DIR / "screenshots"))

sys.path.insert(0, str(SOURCE / "scripts" / "lib"))
from headless_chromium import new_browser as _new_browser, wait_until  # noqa: E402,F401 (the tests' wait_until)


def driven_m(robot: str) -> float:
    """How far the simulated TurtleBot3 `robot` has driven, by its agent's newest pose line."""
    log = (QUICKSTART_DIR / f"agent{robot[-1]}.log").read_text(errors="replace")
    found = re.findall(r"sim: (\w+) at t=[\d.]+ s: .*?([\d.]+) m driven", log)
    return float(found[-1][1]) if found else 0.0


def pose_lines(robot: str) -> list[str]:
    """The robot's pose log lines, oldest first."""
    log = (QUICKSTART_DIR / f"agent{robot[-1]}.log").read_text(errors="replace")
    return [line for line in log.splitlines() if "sim: " in line]


def last_pose_word(robot: str) -> str:
    """'moving' or 'stopped', as the robot's pose log last said (none yet: 'stopped')."""
    log = (QUICKSTART_DIR / f"agent{robot[-1]}.log").read_text(errors="replace")
    found = re.findall(r"sim: (\w+) at t=", log)
    return found[-1] if found else "stopped"


def quickstart(*args: str) -> str:
    run = subprocess.run([str(SOURCE / "scripts" / "quickstart"), *args], capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, f"scripts/quickstart {' '.join(args)}: {run.stdout}{run.stderr}"
    return run.stdout


def new_browser() -> webdriver.Chrome:
    """The tests' browser logs every request: the page must make none that leaves the machine."""
    return _new_browser(log_network=True)


class ConsolePage:
    """One browser on the console's page."""

    def __init__(self, browser: webdriver.Chrome):
        self.browser = browser
        browser.get(CONSOLE_URL)
        assert wait_until(lambda: self.state() == "connected", 20), f"the page never went live: {self.badge()}"
        assert wait_until(lambda: self.robot_names(), 15), "the robots were never listed"

    def js(self, script: str, *args):
        return self.browser.execute_script(script, *args)

    def state(self) -> str:
        return self.browser.find_element(By.ID, "connection").get_attribute("data-state")

    def badge(self) -> str:
        return self.browser.find_element(By.ID, "connection").text

    def robot_names(self) -> list[str]:
        return [o.get_attribute("value") for o in self.browser.find_elements(By.CSS_SELECTOR, "#robot-picker option")]

    def pick(self, robot: str) -> None:
        self.js("const p = document.getElementById('robot-picker'); p.value = arguments[0];"
                "p.dispatchEvent(new Event('change'));", robot)

    def stats(self) -> dict:
        return self.js("return window.dtmfConsole.spectrogram.stats;")

    def commands(self) -> list[tuple[str, str | None]]:
        """Each command listed, newest first: its text and outcome, read at one instant (read
        apart, a text read before the last progress and an outcome read after it disagree)."""
        rows = self.js("return [...document.querySelectorAll('#commands li')]"
                       ".map((li) => [li.textContent, li.dataset.outcome || null]);")
        return [(text, outcome) for text, outcome in rows]

    def screenshot(self, name: str) -> Path:
        ARTEFACTS.mkdir(parents=True, exist_ok=True)
        path = ARTEFACTS / f"{name}.png"
        self.browser.save_screenshot(str(path))
        return path


@pytest.fixture
def browser():
    b = new_browser()
    yield b
    b.quit()


@pytest.fixture
def page(browser) -> ConsolePage:
    return ConsolePage(browser)
