"""A live system for the Python package's tests: dtmf-agent (simulated TurtleBot3) and
dtmf-server over the PulseAudio air, logging to the test PostgreSQL cluster, plus a "deaf"
server whose chords nobody answers. run_tests.sh installs the package and sets
DTMF_BIN_DIR, and ctest's fixtures give the air (PULSE_SERVER) and DTMF_DB_URL."""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import time
from pathlib import Path
from typing import Callable

import pytest

from dtmf_teleop import Client, TeleopError

BIN = Path(os.environ.get("DTMF_BIN_DIR", "build/bin"))
REPO = Path(__file__).resolve().parent.parent.parent
EXAMPLES = REPO / "clients" / "python" / "examples"


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_until(predicate: Callable[[], bool], timeout_s: float, poll_s: float = 0.01) -> bool:
    """Polls predicate until it holds or timeout_s has passed; whether it held (tried once
    more at the deadline). Wait for what a test means, not for a time that usually suffices:
    a sleep is right only where the time is the behaviour under test, and says so."""
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if predicate():
            return True
        time.sleep(poll_s)
    return bool(predicate())


def wait_serving(address: str, process: subprocess.Popen, log: Path) -> None:
    with Client(address, timeout_s=1) as client:
        def serving() -> bool:
            if process.poll() is not None:
                pytest.fail(f"{process.args[0]} exited with {process.returncode}: {log.read_text()}")
            try:
                return client.health() == "SERVING"
            except TeleopError:
                return False

        if not wait_until(serving, timeout_s=15, poll_s=0.1):
            pytest.fail(f"no server at {address}: {log.read_text()}")


def wait_robot_answers(address: str, timeout_s: float = 60) -> bool:
    """Until the robot confirms a Stop sent through the air: the live system is ready (rather
    than a fixed wait for new PulseAudio streams to settle: in their first seconds they once
    delivered sound irregularly). The Stop is outside any run: no report counts it."""
    with Client(address, timeout_s=30) as client:
        def confirmed() -> bool:
            try:
                client.stop().result()
                return True
            except TeleopError:
                return False

        return wait_until(confirmed, timeout_s, poll_s=0.1)


class LiveSystem:
    def __init__(self, folder: Path):
        self.folder = folder
        self.processes: list[subprocess.Popen] = []
        db = os.environ.get("DTMF_DB_URL", "none")
        try:
            self.start("agent", [BIN / "dtmf-agent", "--audio", "default", "--ack-out", "default", "--cmd-vel", "sim",
                                 "--db", db, "--spill-file", folder / "agent.spill"])
            self.address = f"127.0.0.1:{free_port()}"
            server = self.start("server", [BIN / "dtmf-server", "--address", "127.0.0.1", "--port",
                                           self.address.split(":")[1], "--db", db, "--spill-file",
                                           folder / "server.spill"])
            self.deaf_address = f"127.0.0.1:{free_port()}"
            deaf = self.start("deaf", [BIN / "dtmf-server", "--address", "127.0.0.1", "--port",
                                       self.deaf_address.split(":")[1], "--audio-out", f"wav:{folder / 'deaf.wav'}",
                                       "--audio-in", "none", "--db", "none"])
            wait_serving(self.address, server, folder / "server.log")
            wait_serving(self.deaf_address, deaf, folder / "deaf.log")
            if not wait_robot_answers(self.address):
                pytest.fail(f"the robot never confirmed a Stop: {(folder / 'agent.log').read_text()}")
        except BaseException:  # pytest.fail's too: no process outlives a system that did not start
            self.stop()
            raise

    def start(self, name: str, command: list) -> subprocess.Popen:
        log = open(self.folder / f"{name}.log", "w")
        process = subprocess.Popen([str(c) for c in command], stdout=subprocess.DEVNULL, stderr=log)
        self.processes.append(process)
        return process

    def stop(self) -> None:
        """Every process gone before the next test suite starts its own: two agents on one
        air would both hear every chord."""
        for p in self.processes:
            p.send_signal(signal.SIGTERM)
        for p in self.processes:
            try:
                p.wait(timeout=10)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()


@pytest.fixture(scope="session")
def system(tmp_path_factory) -> LiveSystem:
    live = LiveSystem(tmp_path_factory.mktemp("live"))
    yield live
    live.stop()


@pytest.fixture
def robot(system) -> Client:
    with Client(system.address) as client:
        yield client


@pytest.fixture
def deaf(system) -> Client:
    with Client(system.deaf_address) as client:
        yield client
