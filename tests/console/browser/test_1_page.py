"""The page itself: it loads from this machine alone and within its weight, and its picture of
the air moves and marks each frame and its answer."""

from __future__ import annotations

import json
from urllib.parse import urlparse

from selenium.webdriver.common.by import By

from conftest import CONSOLE_URL, ConsolePage, wait_until

KB = 1024


def requests_made(browser) -> list[str]:
    """Every URL the browser asked for, from its DevTools log (not only what the page lists)."""
    urls = []
    for entry in browser.get_log("performance"):
        message = json.loads(entry["message"])["message"]
        if message["method"] == "Network.requestWillBeSent":
            urls.append(message["params"]["request"]["url"])
    return urls


def test_the_page_loads_from_this_machine_alone_and_weighs_under_500_kb(browser):
    page = ConsolePage(browser)
    console = urlparse(CONSOLE_URL)
    urls = requests_made(browser)
    assert urls, "the DevTools log saw no request at all"
    for url in urls:
        u = urlparse(url)
        local = u.scheme in ("http", "ws") and u.hostname == console.hostname and u.port == console.port
        assert local or u.scheme in ("data", "blob"), f"a request that leaves the console: {url}"
    weight = page.js("return performance.getEntriesByType('resource').reduce((s, e) => s + e.encodedBodySize, 0)"
                     " + performance.getEntriesByType('navigation')[0].encodedBodySize;")
    assert 0 < weight <= 500 * KB, f"page weight {weight} bytes"
    print(f"page weight at load: {weight / KB:.1f} kB over {len(urls)} requests")
    page.screenshot("page-loaded")


def test_the_spectrogram_moves_and_marks_a_frame_and_its_answer_within_a_second(page):
    first = page.stats()["columns"]
    assert wait_until(lambda: page.stats()["columns"] > first + 20, 5), "no spectrum columns came"
    page.pick("robot1")
    before = page.stats()
    page.browser.find_element(By.ID, "drive-button").click()
    assert wait_until(lambda: page.stats()["framesMarked"] > before["framesMarked"], 5), "no frame was marked"
    assert wait_until(lambda: page.stats()["answersMarked"] > before["answersMarked"], 5), "no answer was marked"
    # Within a second of the frame: the answer's mark was drawn less than a second after the
    # sender heard it, and the columns arrive as fast.
    stats = page.stats()
    assert stats["markDelaysMs"][-1] < 1000, stats["markDelaysMs"][-5:]
    assert sorted(stats["columnDelaysMs"])[len(stats["columnDelaysMs"]) // 2] < 1000
    kinds = [li.get_attribute("data-kind") for li in page.browser.find_elements(By.CSS_SELECTOR, "#air-log li")]
    assert "frame" in kinds and "ack" in kinds, kinds[:10]
    text = page.browser.find_element(By.ID, "air-log").text
    assert "robot1" in text and "(auth)" in text, "the frame is marked with its robot and as authenticated"
    # The marks are drawn on the picture: some of the marks canvas is no longer transparent.
    painted = page.js("const c = document.getElementById('marks'); const d = c.getContext('2d')"
                      ".getImageData(0, 0, c.width, c.height).data; let n = 0;"
                      "for (let i = 3; i < d.length; i += 4) if (d[i]) n++; return n;")
    assert painted > 100, "no mark is drawn over the spectrogram"
    page.screenshot("air-with-a-frame-and-its-answer")
