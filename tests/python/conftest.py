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

import pytest

from dtmf_teleop import Client, TeleopError

BIN = Path(os.environ.get("DTMF_BIN_DIR", "build/bin"))
REPO = Path(__file__).resolve().parent.parent.parent
EXAMPLES = REPO / "clients" / "python" / "examples"


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_serving(address: str, process: subprocess.Popen, log: Path) -> None:
    with Client(address, timeout_s=1) as client:
        for _ in range(100):
            if process.poll() is not None:
                pytest.fail(f"{process.args[0]} exited with {process.returncode}: {log.read_text()}")
            try:
                if client.health() == "SERVING":
                    return
            except TeleopError:
                time.sleep(0.1)
    pytest.fail(f"no server at {address}: {log.read_text()}")


class LiveSystem:
    def __init__(self, folder: Path):
        self.folder = folder
        self.processes: list[subprocess.Popen] = []
        db = os.environ.get("DTMF_DB_URL", "none")
        self.start("agent", [BIN / "dtmf-agent", "--audio", "default", "--ack-out", "default", "--cmd-vel", "sim",
                             "--db", db, "--spill-file", folder / "agent.spill"])
        self.address = f"127.0.0.1:{free_port()}"
        server = self.start("server", [BIN / "dtmf-server", "--address", "127.0.0.1", "--port",
                                       self.address.split(":")[1], "--db", db, "--spill-file", folder / "server.spill"])
        self.deaf_address = f"127.0.0.1:{free_port()}"
        deaf = self.start("deaf", [BIN / "dtmf-server", "--address", "127.0.0.1", "--port",
                                   self.deaf_address.split(":")[1], "--audio-out", f"wav:{folder / 'deaf.wav'}",
                                   "--audio-in", "none", "--db", "none"])
        wait_serving(self.address, server, folder / "server.log")
        wait_serving(self.deaf_address, deaf, folder / "deaf.log")
        time.sleep(3)  # new PulseAudio streams deliver their first seconds irregularly (tests/e2e)

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
