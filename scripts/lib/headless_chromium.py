"""Debian's Chromium, headless, through Selenium and Debian's chromedriver, as the console's
browser tests (tests/console/browser), its bench (bench/console) and scripts/compose-check
open it; and waiting for what a check means instead of for a time."""

from __future__ import annotations

import time
from typing import Callable

from selenium import webdriver
from selenium.webdriver.chrome.service import Service

# No first-run pages, no sync, no updates: nothing but the page under test talks to the network.
ARGUMENTS = ("--headless=new", "--no-sandbox", "--disable-gpu", "--window-size=1500,1300", "--disable-dev-shm-usage",
             "--no-first-run", "--disable-background-networking", "--disable-component-update", "--disable-sync",
             "--disable-default-apps")


def new_browser(log_network: bool = False) -> webdriver.Chrome:
    """A fresh headless Chromium; with log_network, its performance log keeps every request."""
    options = webdriver.ChromeOptions()
    for argument in ARGUMENTS:
        options.add_argument(argument)
    if log_network:
        options.set_capability("goog:loggingPrefs", {"performance": "ALL", "browser": "ALL"})
    return webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)


def wait_until(predicate: Callable[[], object], timeout_s: float, poll_s: float = 0.05):
    """Polls predicate until it gives a true value or timeout_s has passed; that value (tried
    once more at the deadline)."""
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        value = predicate()
        if value:
            return value
        time.sleep(poll_s)
    return predicate()
