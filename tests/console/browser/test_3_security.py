"""A console on loopback must not be drivable by another web site open in the same browser
(docs/security.md, "The web console"). The attacks: a socket opened from another origin, one
without the page's token, a cross-site POST, and DNS rebinding (a name of the attacker's that
resolves to 127.0.0.1). Each is tried on the wire and, where a browser is the attacker's tool,
from a real page of another origin."""

from __future__ import annotations

import base64
import http.client
import http.server
import os
import re
import threading
from urllib.parse import urlparse

import pytest
from selenium.webdriver.common.by import By

from conftest import CONSOLE_URL, ConsolePage, new_browser, wait_until

CONSOLE = urlparse(CONSOLE_URL)
ORIGIN = f"http://{CONSOLE.hostname}:{CONSOLE.port}"


def request(method: str, path: str, headers: dict[str, str]) -> tuple[int, str]:
    connection = http.client.HTTPConnection(CONSOLE.hostname, CONSOLE.port, timeout=5)
    connection.putrequest(method, path, skip_host=True, skip_accept_encoding=True)
    for name, value in headers.items():
        connection.putheader(name, value)
    connection.endheaders()
    response = connection.getresponse()
    body = response.read().decode(errors="replace") if response.status != 101 else ""
    connection.close()
    return response.status, body


def page_token() -> str:
    status, body = request("GET", "/", {"Host": f"{CONSOLE.hostname}:{CONSOLE.port}"})
    assert status == 200
    return re.search(r'name="dtmf-page-token" content="([0-9a-f]{64})"', body).group(1)


def handshake(origin: str | None, token: str | None) -> tuple[int, str]:
    headers = {"Host": f"{CONSOLE.hostname}:{CONSOLE.port}", "Upgrade": "websocket", "Connection": "Upgrade",
               "Sec-WebSocket-Version": "13", "Sec-WebSocket-Key": base64.b64encode(os.urandom(16)).decode()}
    if origin is not None:
        headers["Origin"] = origin
    return request("GET", "/socket" + (f"?token={token}" if token is not None else ""), headers)


def test_only_the_consoles_own_origin_with_the_pages_token_opens_the_socket():
    token = page_token()
    assert handshake(ORIGIN, token)[0] == 101, "the page's own handshake must work, or the refusals prove nothing"
    for origin, with_token, why in [("http://evil.example", token, "another origin"),
                                    (None, token, "no Origin"), ("null", token, "a sandboxed frame"),
                                    (ORIGIN, None, "no token"), (ORIGIN, "0" * 64, "a guessed token"),
                                    (ORIGIN, token[:-1], "a token one digit short")]:
        status, body = handshake(origin, with_token)
        assert status == 403, f"{why}: {status} {body}"


def test_a_rebinding_host_gets_no_page_and_no_token():
    for host in ("evil.example:%d" % CONSOLE.port, "127.0.0.1.nip.io:%d" % CONSOLE.port, "127.0.0.1"):
        status, body = request("GET", "/", {"Host": host})
        assert status == 421, (host, status)
        assert "dtmf-page-token" not in body and not re.search(r"[0-9a-f]{64}", body), body


def test_nothing_but_get_is_answered_and_no_answer_allows_another_origin():
    status, body = request("POST", "/", {"Host": f"{CONSOLE.hostname}:{CONSOLE.port}", "Origin": "http://evil.example",
                                          "Content-Type": "application/x-www-form-urlencoded", "Content-Length": "0"})
    assert status == 405, body
    connection = http.client.HTTPConnection(CONSOLE.hostname, CONSOLE.port, timeout=5)
    connection.request("GET", "/", headers={"Origin": "http://evil.example"})
    response = connection.getresponse()
    assert response.getheader("Access-Control-Allow-Origin") is None
    assert "frame-ancestors 'none'" in response.getheader("Content-Security-Policy", "")
    connection.close()


class EvilSite:
    """Another web site on this machine: a page that tries to drive the robots through the
    console, as one open in another tab of the user's browser could."""

    PAGE = """<!doctype html><title>evil</title><script>
      window.result = {};
      const target = "%(console)s";
      const socket = new WebSocket(target.replace("http", "ws") + "socket?token=" + "0".repeat(64));
      socket.onopen = () => { window.result.socket = "open"; };
      socket.onerror = () => { window.result.socket = "refused"; };
      const tokenless = new WebSocket(target.replace("http", "ws") + "socket");
      tokenless.onopen = () => { window.result.tokenless = "open"; };
      tokenless.onerror = () => { window.result.tokenless = "refused"; };
      fetch(target).then(r => r.text()).then(t => { window.result.read = t.slice(0, 200); })
        .catch(() => { window.result.read = "blocked"; });
      fetch(target, {method: "POST", mode: "no-cors", body: "stop"})
        .then(r => { window.result.post = r.type; }).catch(() => { window.result.post = "failed"; });
    </script>"""

    def __init__(self):
        page = (self.PAGE % {"console": CONSOLE_URL}).encode()

        class Handler(http.server.BaseHTTPRequestHandler):
            def do_GET(self):
                self.send_response(200)
                self.send_header("Content-Type", "text/html")
                self.end_headers()
                self.wfile.write(page)

            def log_message(self, *args):
                pass

        self.server = http.server.HTTPServer(("127.0.0.1", 0), Handler)
        threading.Thread(target=self.server.serve_forever, daemon=True).start()
        self.url = f"http://localhost:{self.server.server_address[1]}/"

    def close(self):
        self.server.shutdown()


def test_a_page_of_another_site_in_the_same_browser_cannot_drive_or_read_the_console():
    evil = EvilSite()
    browser = new_browser()
    try:
        browser.get(evil.url)
        result = wait_until(lambda: browser.execute_script(
            "const r = window.result; return r.socket && r.tokenless && r.read && r.post ? r : null;"), 10)
        assert result, browser.execute_script("return window.result")
        assert result["socket"] == "refused" and result["tokenless"] == "refused", result
        assert result["read"] == "blocked", "the other site read the console's page (and its token)"
        assert result["post"] in ("opaque", "failed"), result
    finally:
        browser.quit()
        evil.close()


def test_a_rebinding_name_in_the_browser_finds_no_console():
    """The browser itself resolves rebind.test to 127.0.0.1, as DNS rebinding makes it."""
    browser = new_browser_mapping("rebind.test")
    try:
        browser.get(f"http://rebind.test:{CONSOLE.port}/")
        body = browser.find_element(By.TAG_NAME, "body").text
        assert "answers to" in body and "DNS rebinding" in body, body
        assert not browser.find_elements(By.ID, "spectrogram")
    finally:
        browser.quit()


def new_browser_mapping(name: str):
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service
    options = webdriver.ChromeOptions()
    for argument in ("--headless=new", "--no-sandbox", "--disable-gpu", f"--host-resolver-rules=MAP {name} 127.0.0.1"):
        options.add_argument(argument)
    return webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)
