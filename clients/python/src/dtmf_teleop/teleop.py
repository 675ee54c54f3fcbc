"""TeleopStream: live driving over the Teleop RPC, one bidirectional gRPC stream.

    with robot.teleop(lease_s=1.0) as t:             # profile "fast": the one that carries velocity
        t.set(linear_mps=0.1, angular_radps=0.5)
        for status in t.updates(timeout_s=2):        # typed TeleopStatus, one per frame event
            print(status.target, status.velocity, status.link_quality)
            break
        t.stop()                                     # target (0, 0): the robot halts, the stream stays
    # leaving the block half-closes the stream and sends a Stop RPC: the robot stops at once

The requests come from a generator fed by a thread-safe queue: each new target goes out at
once, and the current one is repeated every repeat_s (0.1 s, as turtlebot3_teleop publishes)
because the server stops renewing the robot's lease after a second without a message. A
thread reads the server's answers: status() is the latest, updates() yields them in turn,
on_status is called with each (on that thread). A failed stream raises the TeleopError
subclass of its gRPC status (errors.py), with the server's message, from Client.teleop(),
set(), updates() or close(): BadRequest for a bad target, lease or profile ("seed" carries no
velocity), NotConfirmed when a Stop from elsewhere overtook the stream (ABORTED), and a plain
TeleopError with code FAILED_PRECONDITION when another stream already drives the robot.
"""

from __future__ import annotations

import collections
import queue
import threading
from typing import Any, Callable, Iterator, Optional

import grpc

from . import errors
from ._stubs.dtmf.v1 import teleop_pb2 as pb
from .events import TeleopStatus

REPEAT_S = 0.1  # how often the current target is sent again (turtlebot3_teleop: 10 Hz)
_END = object()  # queued by close(): the request stream ends (half-close)


class TeleopStream:
    """An open Teleop stream (Client.teleop() makes it). Use it as a context manager, or
    call close() yourself: until then the robot keeps the last target."""

    def __init__(self, open_call: Callable[[Iterator[pb.TeleopRequest]], Any], stop_robot: Callable[[], Any], *,
                 linear_mps: float, angular_radps: float, lease_s: float, profile: str, robot: str = "",
                 on_status: Optional[Callable[[TeleopStatus], None]] = None, stop_on_exit: bool = True,
                 repeat_s: float = REPEAT_S, accept_timeout_s: float = 30.0, target: str = ""):
        self.profile = profile
        self.robot = robot
        self.lease_s = lease_s
        self.stop_on_exit = stop_on_exit
        self._stop_robot = stop_robot
        self._on_status = on_status
        self._repeat_s = repeat_s
        self._server = target
        self._requests: queue.Queue[Any] = queue.Queue()
        self._changed = threading.Condition()
        self._target = (float(linear_mps), float(angular_radps))
        self._latest: Optional[TeleopStatus] = None
        self._pending: collections.deque[TeleopStatus] = collections.deque(maxlen=1024)
        self._ended = False
        self._closing = False
        self._closed = False
        self._error: Optional[Exception] = None
        self._error_raised = False
        self._requests.put(self._target)
        self._call = open_call(self._request_stream())
        self._reader = threading.Thread(target=self._read, name="dtmf-teleop-status", daemon=True)
        self._reader.start()
        self._await_acceptance(accept_timeout_s)

    # --- driving -------------------------------------------------------------------------

    def set(self, linear_mps: Optional[float] = None, angular_radps: Optional[float] = None) -> None:
        """A new target: linear m/s (forward positive) and angular rad/s (left positive);
        None keeps that part. Sent at once, then repeated until the next."""
        with self._changed:
            self._raise_if_over()
            self._target = (self._target[0] if linear_mps is None else float(linear_mps),
                            self._target[1] if angular_radps is None else float(angular_radps))
            self._requests.put(self._target)

    def stop(self) -> None:
        """Target (0, 0): the robot halts with its next frame; the stream stays open."""
        self.set(0.0, 0.0)

    @property
    def target(self) -> tuple[float, float]:
        """The target this client sends: (linear m/s, angular rad/s)."""
        with self._changed:
            return self._target

    # --- what the server says ------------------------------------------------------------

    def status(self) -> TeleopStatus:
        """The latest status (there is one as soon as the stream is open)."""
        with self._changed:
            assert self._latest is not None
            return self._latest

    @property
    def ended(self) -> bool:
        """The server has ended the stream (close() raises its failure, if any)."""
        with self._changed:
            return self._ended

    def updates(self, timeout_s: Optional[float] = None) -> Iterator[TeleopStatus]:
        """Every status in turn, from the first not yet yielded (the newest 1024 are kept),
        until the stream ends (raising its failure) or, with timeout_s, none came for that
        long. One consumer at a time."""
        while True:
            with self._changed:
                self._changed.wait_for(lambda: self._pending or self._ended, timeout_s)
                if not self._pending:
                    if self._error is not None:
                        self._error_raised = True
                        raise self._error
                    return
                status = self._pending.popleft()
            yield status

    # --- the end -------------------------------------------------------------------------

    def close(self, stop_robot: Optional[bool] = None) -> None:
        """End the stream: half-close it, and (stop_robot, default stop_on_exit) send a Stop
        RPC with the stream's profile and wait for the robot to confirm it, so it stops now
        rather than when its lease runs out (up to lease_s later). Without the Stop the robot
        keeps the last target until then. Raises the stream's failure not yet raised, else the
        Stop's (NotConfirmed: the robot did not confirm the Stop). Closing twice does nothing."""
        if self._closed:
            return
        self._closed = True
        with self._changed:
            self._closing = True  # the Stop ends the stream ABORTED, and a cancel CANCELLED: ours
        self._requests.put(_END)
        stop_error: Optional[errors.TeleopError] = None
        if self.stop_on_exit if stop_robot is None else stop_robot:
            try:
                self._stop_robot()
            except errors.TeleopError as e:
                stop_error = e
        self._reader.join(timeout=max(5.0, 3 * self.lease_s))
        if self._reader.is_alive():
            self._call.cancel()
            self._reader.join()
        with self._changed:
            failure = None if self._error_raised else self._error
            self._error_raised = True
        if failure is not None:
            raise failure
        if stop_error is not None:
            raise stop_error

    def __enter__(self) -> "TeleopStream":
        return self

    def __exit__(self, exc_type: Any, *exc: Any) -> None:
        try:
            self.close()
        except errors.TeleopError:
            if exc_type is None:
                raise  # else the block's own exception goes on

    # --- plumbing ------------------------------------------------------------------------

    def _request_stream(self) -> Iterator[pb.TeleopRequest]:
        """What gRPC sends: the newest target as soon as it is set, else the current one
        again every repeat_s; options (the profile) in the first message only."""
        target: Optional[tuple[float, float]] = None
        while True:
            try:
                items = [self._requests.get(timeout=self._repeat_s)]
            except queue.Empty:
                items = [target]
            while not self._requests.empty():
                items.append(self._requests.get_nowait())
            if any(item is _END for item in items):
                return
            request = pb.TeleopRequest(linear_mps=items[-1][0], angular_radps=items[-1][1], lease_s=self.lease_s)
            if target is None:
                request.options.profile = self.profile
                request.options.robot = self.robot
            target = items[-1]
            yield request

    def _read(self) -> None:
        failure: Optional[Exception] = None
        try:
            for response in self._call:
                status = TeleopStatus.from_proto(response)
                with self._changed:
                    self._latest = status
                    self._pending.append(status)
                    self._changed.notify_all()
                if self._on_status is not None:
                    self._on_status(status)
        except grpc.RpcError as e:
            failure = errors.from_rpc_error(e, self._server)
        except Exception as e:  # on_status failed: the stream ends with its exception
            failure = e
            self._call.cancel()
        with self._changed:
            ours = self._closing and isinstance(failure, errors.TeleopError) and failure.code in (
                grpc.StatusCode.ABORTED, grpc.StatusCode.CANCELLED)
            if failure is not None and not ours:
                self._error = failure
            self._ended = True
            self._changed.notify_all()
        self._requests.put(_END)  # nothing more to send

    def _await_acceptance(self, timeout_s: float) -> None:
        """Waits for the first status: the server took the stream (or refused it)."""
        with self._changed:
            answered = self._changed.wait_for(lambda: self._latest is not None or self._ended, timeout_s)
            if answered and self._latest is not None:
                return
            self._closing = True  # the cancel below is ours
        self._closed = True
        self._requests.put(_END)
        self._call.cancel()
        with self._changed:
            if self._error is None and answered:
                self._error = errors.TeleopError(grpc.StatusCode.UNKNOWN,
                                                 f"dtmf-server at {self._server} ended the Teleop stream at once")
            elif self._error is None:
                self._error = errors.Cancelled(grpc.StatusCode.DEADLINE_EXCEEDED, f"dtmf-server at {self._server} "
                                               f"did not answer the Teleop stream within {timeout_s:g} s")
            self._error_raised = True
            raise self._error

    def _raise_if_over(self) -> None:
        """Called holding self._changed."""
        if self._error is not None:
            self._error_raised = True
            raise self._error
        if self._closed or self._ended:
            raise RuntimeError("the Teleop stream has ended: open a new one with Client.teleop()")
