#!/usr/bin/env python3
"""scripts/lib/console_check.py URL: the web console at URL as a user meets it, for
scripts/compose-check. Debian's Chromium, headless, through Selenium: the page goes live and
lists a robot; a Drive clicked in it is confirmed. Then, as another web site's request would
come: a foreign Host (DNS rebinding) and a command socket without the page's token are both
refused. Prints what it saw; exits non-zero naming what failed."""

import sys
import urllib.error
import urllib.request
from urllib.parse import urlsplit

from selenium.webdriver.common.by import By

from headless_chromium import new_browser, wait_until


def status_of(url, headers):
    try:
        with urllib.request.urlopen(urllib.request.Request(url, headers=headers), timeout=10) as answer:
            return answer.status
    except urllib.error.HTTPError as refused:
        return refused.code


def main():
    url = sys.argv[1]
    browser = new_browser()
    try:
        browser.get(url)
        badge = lambda: browser.find_element(By.ID, "connection")  # noqa: E731
        if not wait_until(lambda: badge().get_attribute("data-state") == "connected", 30):
            sys.exit(f"console_check: the page never went live: {badge().text!r}")
        robots = wait_until(lambda: [o.get_attribute("value") for o in
                                     browser.find_elements(By.CSS_SELECTOR, "#robot-picker option")], 20)
        if not robots:
            sys.exit("console_check: the page lists no robot")
        print(f"console_check: the page is live ({badge().text}); robots: {', '.join(robots)}")
        browser.find_element(By.ID, "drive-button").click()
        ended = wait_until(lambda: browser.execute_script(
            "return [...document.querySelectorAll('#commands li')].filter((li) => li.dataset.outcome)"
            ".map((li) => [li.textContent, li.dataset.outcome])[0] || null;"), 20)
        if not ended or ended[1] != "ok":
            sys.exit(f"console_check: the Drive clicked in the page was not confirmed: {ended}")
        print(f"console_check: a Drive clicked in the page: {ended[0]}")
    finally:
        browser.quit()
    rebound = status_of(url, {"Host": "attacker.example:8080"})
    if rebound < 400:
        sys.exit(f"console_check: a request for Host attacker.example was answered {rebound}, not refused")
    parts = urlsplit(url)
    socket = status_of(f"{parts.scheme}://{parts.netloc}/socket", {
        "Connection": "Upgrade", "Upgrade": "websocket", "Sec-WebSocket-Version": "13",
        "Sec-WebSocket-Key": "dGhlIHNhbXBsZSBub25jZQ==", "Origin": f"{parts.scheme}://{parts.netloc}"})
    if socket < 400:
        sys.exit(f"console_check: a socket without the page's token was answered {socket}, not refused")
    print(f"console_check: refused a foreign Host ({rebound}) and a socket without the page's token ({socket})")


if __name__ == "__main__":
    main()
