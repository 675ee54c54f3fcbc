"""When things go wrong, the page says so: another page holds the robot (told who; Stop always
works), the database is down (the live view goes on, the reports say they cannot be read), the
server or the console goes away and comes back (the page says it, keeps what it showed, and
reconnects by itself). These stop and start parts of the running system: they come last."""

from __future__ import annotations

import os
import signal
import subprocess

from selenium.webdriver.common.action_chains import ActionChains
from selenium.webdriver.common.by import By

from conftest import QUICKSTART_DIR, SOURCE, ConsolePage, new_browser, quickstart, wait_until


def stop_process(name: str) -> None:
    pid = int((QUICKSTART_DIR / f"{name}.pid").read_text())
    os.kill(pid, signal.SIGTERM)
    assert wait_until(lambda: not alive(pid), 10), f"{name} did not stop"


def alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
        return True
    except ProcessLookupError:
        return False


def test_a_second_page_is_told_who_drives_the_robot_and_its_stop_still_works(browser):
    first = ConsolePage(browser)
    second_browser = new_browser()
    try:
        second = ConsolePage(second_browser)
        first.pick("robot3")
        first.browser.find_element(By.ID, "teleop-button").click()
        ActionChains(first.browser).send_keys("www").perform()
        assert wait_until(lambda: "m/s" in first.browser.find_element(By.ID, "teleop-confirmed").text, 5)
        second.pick("robot3")
        second.browser.find_element(By.ID, "teleop-button").click()
        told = wait_until(lambda: second.browser.find_element(By.ID, "teleop-message").text
                          if "held by" in second.browser.find_element(By.ID, "teleop-message").text else "", 5)
        assert told and "dtmf-console page" in told, second.browser.find_element(By.ID, "teleop-message").text
        second.screenshot("second-page-told-who-drives")
        second.browser.find_element(By.ID, "stop-button").click()
        assert wait_until(lambda: "overtook" in first.browser.find_element(By.ID, "teleop-message").text, 5), \
            first.browser.find_element(By.ID, "teleop-message").text
        assert wait_until(lambda: any("Stop" in t and o == "ok" for t, o in second.commands()), 5)
    finally:
        second_browser.quit()


def test_with_the_database_down_the_air_goes_on_and_the_report_says_it_cannot_be_read(page):
    subprocess.run([str(SOURCE / "scripts" / "pg"), "stop", str(QUICKSTART_DIR / "pg")], check=True,
                   capture_output=True)
    try:
        columns = page.stats()["columns"]
        page.browser.find_element(By.ID, "report-refresh").click()
        message = wait_until(lambda: page.browser.find_element(By.ID, "report-message").text, 15)
        assert "cannot be read" in message, message
        assert wait_until(lambda: page.stats()["columns"] > columns + 25, 5), "the live view stopped with the database"
        page.pick("robot1")
        page.browser.find_element(By.ID, "drive-button").click()
        assert wait_until(lambda: [c for c in page.commands() if c[1]], 10), page.commands()[:1]
        page.screenshot("database-down")
    finally:
        subprocess.run([str(SOURCE / "scripts" / "pg"), "start", str(QUICKSTART_DIR / "pg")], check=True,
                       capture_output=True)


def test_the_page_says_the_server_is_gone_keeps_what_it_showed_and_reconnects(page):
    page.pick("robot1")
    page.browser.find_element(By.ID, "drive-button").click()
    assert wait_until(lambda: page.browser.find_elements(By.CSS_SELECTOR, "#air-log li[data-kind=ack]"), 10)
    shown = len(page.browser.find_elements(By.CSS_SELECTOR, "#air-log li"))
    stop_process("server")
    assert wait_until(lambda: page.state() == "server-down", 10), page.badge()
    assert "does not answer" in page.badge()
    assert len(page.browser.find_elements(By.CSS_SELECTOR, "#air-log li")) >= shown, "the page forgot what it showed"
    page.screenshot("server-down")
    quickstart("--robots", "3", "--no-sequence")  # starts what is not running: the server
    assert wait_until(lambda: page.state() == "connected", 30), page.badge()
    columns = page.stats()["columns"]
    assert wait_until(lambda: page.stats()["columns"] > columns + 10, 5), "the air did not come back"


def test_the_page_reconnects_to_a_restarted_console_by_itself(page):
    shown = len(page.browser.find_elements(By.CSS_SELECTOR, "#air-log li"))
    stop_process("console")
    assert wait_until(lambda: page.state() == "console-down", 10), page.badge()
    quickstart("--robots", "3", "--no-sequence")  # the console again, with a new page token
    assert wait_until(lambda: page.state() == "connected", 30), page.badge()
    assert len(page.browser.find_elements(By.CSS_SELECTOR, "#air-log li")) >= shown
    columns = page.stats()["columns"]
    assert wait_until(lambda: page.stats()["columns"] > columns + 10, 5)
