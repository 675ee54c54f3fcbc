"""Helpers of the Teleop tests: a stand-in TeleopService in Python that keeps dtmf-server's
Teleop rules without sound (real gRPC, so the client's bidirectional stream is exercised
without the C++ server), and a pseudo-terminal to type keys into the keyboard example.

The stand-in answers with dtmf-server's status codes, not its words: its messages say they
come from the stand-in, and tests of it assert on codes. The real server's wording is tested
against the real server (tests/server/server_teleop_test.cpp; live, test_client.py)."""

from __future__ import annotations

import fcntl
import itertools
import os
import pty
import queue
import re
import subprocess
import sys
import termios
import threading
import time
from concurrent import futures

import grpc
import pytest

from dtmf_teleop._stubs.dtmf.v1 import teleop_pb2 as pb
from dtmf_teleop._stubs.dtmf.v1 import teleop_pb2_grpc

from conftest import EXAMPLES, wait_until


class StandInTeleop(teleop_pb2_grpc.TeleopServiceServicer):
    """Teleop and Stop as server/teleop_rpc.cpp has them: profile fast only, one stream at a
    time, a status for each new target (confirmed at once), OK when the client half-closes,
    ABORTED when a Stop overtakes."""

    def __init__(self):
        self.lock = threading.Lock()
        self.driving: threading.Event | None = None  # set: a Stop overtook the stream
        self.requests: list[tuple[float, pb.TeleopRequest]] = []
        self.stops = 0
        self.half_closed = threading.Event()

    def Teleop(self, request_iterator, context):
        first = next(request_iterator, None)
        if first is None:
            return
        if first.options.profile != "fast":
            context.abort(grpc.StatusCode.INVALID_ARGUMENT, "stand-in: profile fast only")
        halted = threading.Event()
        with self.lock:
            if self.driving is not None:
                context.abort(grpc.StatusCode.FAILED_PRECONDITION, "stand-in: a stream drives already")
            self.driving = halted
        targets: queue.Queue = queue.Queue()
        threading.Thread(target=self._read, args=(first, request_iterator, targets), daemon=True).start()
        try:
            sent = None
            while True:
                if halted.is_set():
                    context.abort(grpc.StatusCode.ABORTED, "stand-in: a Stop overtook the stream")
                try:
                    request = targets.get(timeout=0.02)
                except queue.Empty:
                    continue
                if request is None:
                    return
                target = (request.linear_mps, request.angular_radps)
                if target != sent:
                    sent = target
                    yield self._status(request)
        finally:
            with self.lock:
                self.driving = None

    def Stop(self, request, context):
        with self.lock:
            self.stops += 1
            if self.driving is not None:
                self.driving.set()
        yield pb.StopResponse(progress=pb.Progress(event=pb.FRAME_EVENT_CONFIRMED, command="stop",
                                                   profile=request.options.profile))

    def _read(self, first, request_iterator, targets):
        try:
            for request in itertools.chain([first], request_iterator):  # as they come, not all at the end
                self.requests.append((time.monotonic(), request))
                targets.put(request)
            self.half_closed.set()
        except grpc.RpcError:  # the call ended first (the stand-in aborted it, or the client cancelled)
            pass
        targets.put(None)

    @staticmethod
    def _status(r: pb.TeleopRequest) -> pb.TeleopResponse:
        return pb.TeleopResponse(progress=pb.Progress(event=pb.FRAME_EVENT_ACK, profile="fast", response_time_ms=80),
                                 target_linear_mps=r.linear_mps, target_angular_radps=r.angular_radps, confirmed=True,
                                 confirmed_linear_mps=r.linear_mps, confirmed_angular_radps=r.angular_radps,
                                 response_time_ms=80, link_quality=1.0, frames_in_window=1, link_window_s=3,
                                 lease_s=r.lease_s or 1.0, lease_left_s=r.lease_s or 1.0)


def start_stand_in() -> tuple[grpc.Server, StandInTeleop, str]:
    servicer = StandInTeleop()
    server = grpc.server(futures.ThreadPoolExecutor(max_workers=8))
    teleop_pb2_grpc.add_TeleopServiceServicer_to_server(servicer, server)
    port = server.add_insecure_port("127.0.0.1:0")
    server.start()
    return server, servicer, f"127.0.0.1:{port}"


class KeyboardInTerminal:
    """examples/teleop_keyboard.py in a pseudo-terminal: type keys, wait for what it shows."""

    def __init__(self, server: str):
        self.terminal, child_side = pty.openpty()
        # A session of its own with the pseudo-terminal as its controlling terminal, as a shell
        # gives it: Ctrl-C typed there is then a SIGINT for it, as at a real terminal.
        self.process = subprocess.Popen([sys.executable, str(EXAMPLES / "teleop_keyboard.py"), "--server", server],
                                        stdin=child_side, stdout=child_side, stderr=child_side, env=os.environ,
                                        start_new_session=True,
                                        preexec_fn=lambda: fcntl.ioctl(0, termios.TIOCSCTTY, 0))
        os.close(child_side)
        self.screen = bytearray()
        self.reader = threading.Thread(target=self._read, daemon=True)  # drained all along, or the example
        self.reader.start()                                             # would block writing its status

    def _read(self) -> None:
        while True:
            try:
                data = os.read(self.terminal, 4096)
            except OSError:  # EIO: the example has gone
                return
            if not data:
                return
            self.screen.extend(data)

    @property
    def text(self) -> str:
        return self.screen.decode(errors="replace")

    def press(self, keys: bytes, then_shown: str, within_s: float = 15) -> None:
        """Types keys, then waits for a line matching then_shown that came after them."""
        since = len(self.screen)
        os.write(self.terminal, keys)

        def shown() -> bool:
            return re.search(then_shown, self.screen[since:].decode(errors="replace")) is not None

        wait_until(lambda: shown() or self.process.poll() is not None, within_s, poll_s=0.05)
        if not shown():
            pytest.fail(f"{then_shown!r} never shown after {keys!r}:\n{self.text}")

    def quit(self, key: bytes = b"q") -> int:
        os.write(self.terminal, key)
        try:
            return self.process.wait(timeout=30)
        finally:
            self.close()

    def close(self) -> None:
        if self.process.poll() is None:
            self.process.kill()
            self.process.wait()
        self.reader.join(timeout=5)
        if self.terminal >= 0:
            os.close(self.terminal)
            self.terminal = -1
