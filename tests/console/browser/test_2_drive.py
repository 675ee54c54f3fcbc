"""Driving from the page: a Drive clicked, the seed's sequence and the report with its plots
and CSV (before the rest, so that their pages show a run), keyboard teleop and closing the tab,
the robot picker and the stop for every robot."""

from __future__ import annotations

import csv
import io
import time

from selenium.webdriver.common.action_chains import ActionChains
from selenium.webdriver.common.by import By

from conftest import ConsolePage, driven_m, last_pose_word, pose_lines, wait_until

ROBOTS = ("robot1", "robot2", "robot3")


def test_a_drive_clicked_in_the_page_is_confirmed_and_the_page_says_so(page):
    page.pick("robot1")
    page.browser.find_element(By.ID, "drive-button").click()
    done = wait_until(lambda: [c for c in page.commands() if c[1]], 10)
    assert done, f"the Drive never ended: {page.commands()}"
    text, outcome = done[0]
    assert outcome == "ok" and "confirmed" in text and "robot1" in text, text
    page.screenshot("drive-confirmed")


def test_the_seeds_sequence_runs_from_the_page_and_its_reports_plots_draw_and_csv_parses(page):
    page.pick("robot1")
    page.browser.find_element(By.ID, "sequence-button").click()
    done = wait_until(lambda: [c for c in page.commands() if c[1] and "Test sequence" in c[0]], 90)
    assert done and done[0][1] == "ok", page.commands()[:2]
    page.browser.find_element(By.ID, "report-refresh").click()
    assert wait_until(lambda: page.browser.find_elements(By.CSS_SELECTOR, "#report-table tr"), 10), \
        page.browser.find_element(By.ID, "report-message").text
    for plot in ("plot-rates", "plot-histogram", "plot-over-run"):
        assert page.browser.find_elements(By.CSS_SELECTOR, f"#{plot} .uplot canvas"), f"{plot} was not drawn"
    page.browser.find_element(By.ID, "report-csv").click()
    text = wait_until(lambda: page.js("return window.dtmfLastCsv || ''"), 5)
    figures, frames = text.split("\r\n\r\n", 1)
    rows = list(csv.reader(io.StringIO(figures)))
    assert rows[0] == ["figure", "value"] and any(r[0] == "Transmissions sent" for r in rows), rows[:3]
    frame_rows = list(csv.DictReader(io.StringIO(frames)))
    assert frame_rows and all(r["answer"] in ("ack", "nack", "none", "") for r in frame_rows), frame_rows[:3]
    page.screenshot("report")


def test_keyboard_teleop_moves_the_robot_and_closing_the_tab_stops_it(browser):
    page = ConsolePage(browser)
    page.pick("robot2")
    start = driven_m("robot2")
    page.browser.find_element(By.ID, "teleop-button").click()
    ActionChains(page.browser).send_keys("wwwww").perform()  # 0.05 m/s
    assert wait_until(lambda: "0.05 m/s" in page.browser.find_element(By.ID, "teleop-confirmed").text, 5), \
        page.browser.find_element(By.ID, "teleop-confirmed").text
    # The pose log says "moving" when the robot starts, and where it is when it next publishes
    # or stops: a steady velocity may publish nothing new, so the distance is read at the stop.
    assert wait_until(lambda: last_pose_word("robot2") == "moving", 5), \
        ("the pose log shows no drive", pose_lines("robot2")[-4:], page.browser.find_element(By.ID, "teleop-status").text)
    assert "%" in page.browser.find_element(By.ID, "teleop-quality").text
    page.screenshot("keyboard-teleop")
    # Closing the tab: the socket goes, the console cancels the stream, the lease (0.5 s) lapses.
    closed_at = time.monotonic()
    page.browser.quit()
    assert wait_until(lambda: last_pose_word("robot2") == "stopped", 3), "robot2 did not stop after the tab closed"
    print(f"robot2 stopped {time.monotonic() - closed_at:.2f} s after its tab closed (lease 0.5 s)")
    assert driven_m("robot2") > start + 0.02, pose_lines("robot2")[-4:]


def test_the_picker_drives_only_the_chosen_robot_and_one_button_stops_them_all(page):
    before = {r: driven_m(r) for r in ROBOTS}
    page.browser.find_element(By.CSS_SELECTOR, "#drive-form input[name=duration_s]").clear()  # until the next command
    page.pick("robot3")
    page.browser.find_element(By.ID, "drive-button").click()
    assert wait_until(lambda: driven_m("robot3") > before["robot3"] + 0.02, 8), f"robot3 did not drive: {page.commands()}"
    assert driven_m("robot1") == before["robot1"] and driven_m("robot2") == before["robot2"], "another robot moved"
    # All three moving, then one stop for every robot.
    for robot in ("robot1", "robot2"):
        page.pick(robot)
        page.browser.find_element(By.ID, "drive-button").click()
    assert wait_until(lambda: all(last_pose_word(r) == "moving" for r in ROBOTS), 8), \
        ({r: last_pose_word(r) for r in ROBOTS}, page.commands())
    page.screenshot("three-robots-driving")  # the README's picture (docs/console.png)
    page.browser.find_element(By.ID, "stop-every-robot").click()
    assert wait_until(lambda: all(last_pose_word(r) == "stopped" for r in ROBOTS), 5), \
        ({r: last_pose_word(r) for r in ROBOTS}, page.commands())
    assert wait_until(lambda: any("STOP EVERY ROBOT" in t and o == "ok" for t, o in page.commands()), 5), page.commands()
    page.screenshot("stop-every-robot")


def test_the_key_e_stops_every_robot(page):
    page.pick("robot1")
    page.browser.find_element(By.CSS_SELECTOR, "#drive-form input[name=duration_s]").clear()
    page.browser.find_element(By.ID, "drive-button").click()  # no duration: until the next command
    assert wait_until(lambda: last_pose_word("robot1") == "moving", 8)
    page.browser.find_element(By.TAG_NAME, "body").click()
    ActionChains(page.browser).send_keys("e").perform()
    assert wait_until(lambda: last_pose_word("robot1") == "stopped", 5), "e did not stop robot1"
