"""Client.teleop without dtmf-server: the status dataclass; the stream's requests,
repetition, close and error mapping against a fake gRPC call, then over real gRPC against a
stand-in server (teleop_helpers.py); the keyboard example's keys, status line, refusal
without a terminal, and the example in a pseudo-terminal. (The live stream: test_client.py.)"""

import importlib.util
import queue
import subprocess
import sys
import threading
import time

import grpc
import pytest

from dtmf_teleop import BadRequest, Client, FrameEvent, NotConfirmed, TeleopError, TeleopStatus
from dtmf_teleop._stubs.dtmf.v1 import teleop_pb2 as pb
from dtmf_teleop.teleop import TeleopStream

from conftest import EXAMPLES, wait_until
from teleop_helpers import KeyboardInTerminal, start_stand_in


def load_example(name):
    spec = importlib.util.spec_from_file_location(name.removesuffix(".py"), EXAMPLES / name)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


keyboard = load_example("teleop_keyboard.py")
BURGER = keyboard.MODELS["burger"]


def response(linear=0.0, angular=0.0, event=pb.FRAME_EVENT_QUEUED, **fields):
    return pb.TeleopResponse(progress=pb.Progress(event=event, profile="fast"), target_linear_mps=linear,
                             target_angular_radps=angular, **fields)


class FakeRpcError(grpc.RpcError):
    def __init__(self, code, details):
        self._code, self._details = code, details

    def code(self):
        return self._code

    def details(self):
        return self._details


class FakeCall:
    """A Teleop call as grpcio makes it: it consumes the request iterator on its own thread
    and yields what the test (or answer()) puts in its response queue."""

    def __init__(self, requests, answer=None):
        self.requests = []  # (time.monotonic(), TeleopRequest)
        self.half_closed = threading.Event()
        self.cancelled = False
        self.responses = queue.Queue()
        self._answer = answer or (lambda call, request: call.responses.put(response(request.linear_mps,
                                                                                     request.angular_radps)))
        threading.Thread(target=self._consume, args=(requests,), daemon=True).start()

    def _consume(self, requests):
        for request in requests:
            self.requests.append((time.monotonic(), request))
            if len(self.requests) == 1 or request.linear_mps != self.requests[-2][1].linear_mps:
                self._answer(self, request)
        self.half_closed.set()
        self.responses.put(None)  # the server ends the call OK once the client half-closed

    def __iter__(self):
        while (item := self.responses.get()) is not None:
            if isinstance(item, Exception):
                raise item
            yield item

    def cancel(self):
        self.cancelled = True
        self.responses.put(FakeRpcError(grpc.StatusCode.CANCELLED, "Locally cancelled by application!"))


def open_stream(answer=None, stop_robot=None, **options):
    calls, stops = [], []
    settings = dict(linear_mps=0.0, angular_radps=0.0, lease_s=1.0, profile="fast", accept_timeout_s=5,
                    target="test:1")
    settings.update(options)
    stream = TeleopStream(lambda requests: calls.append(FakeCall(requests, answer)) or calls[-1],
                          stop_robot or (lambda: stops.append(time.monotonic())), **settings)
    return stream, calls[0], stops


# --- TeleopStatus ----------------------------------------------------------------------------

def test_status_converts_every_field_and_the_progress():
    r = response(0.1, 0.5, pb.FRAME_EVENT_ACK, confirmed=True, confirmed_linear_mps=0.0999,
                 confirmed_angular_radps=0.49, response_time_ms=82.5, link_quality=0.75, frames_in_window=4, link_window_s=3, lease_s=1.0,
                 lease_left_s=0.6)
    s = TeleopStatus.from_proto(r)
    assert (s.target, s.velocity) == ((0.1, 0.5), (0.0999, 0.49))
    assert (s.response_time_ms, s.link_quality, s.frames_in_window, s.link_window_s) == (82.5, 0.75, 4, 3.0)
    assert (s.lease_s, s.lease_left_s) == (1.0, 0.6)
    assert s.progress.event == FrameEvent.ACK and s.progress.profile == "fast"


def test_status_before_a_confirmation_has_no_velocity_and_may_lack_progress():
    s = TeleopStatus.from_proto(pb.TeleopResponse(target_linear_mps=0.2))
    assert (s.confirmed, s.velocity, s.progress, s.target) == (False, None, None, (0.2, 0.0))


# --- the stream against a fake call --------------------------------------------------------------

def test_the_first_request_carries_profile_and_lease_and_the_target_is_repeated_every_100_ms():
    stream, call, _ = open_stream(linear_mps=0.05, lease_s=0.5)
    time.sleep(0.65)  # kept: the repetition's pace is the test; its requests are counted over 0.65 s
    stream.close(stop_robot=False)
    requests = [r for _, r in call.requests]
    assert requests[0].options.profile == "fast" and requests[0].lease_s == 0.5
    assert all(not r.HasField("options") for r in requests[1:])
    assert all((r.linear_mps, r.angular_radps, r.lease_s) == (0.05, 0.0, 0.5) for r in requests)
    gaps = [b - a for (a, _), (b, _) in zip(call.requests, call.requests[1:])]
    assert 3 <= len(requests) <= 8, gaps
    assert all(0.09 < gap < 0.5 for gap in gaps), gaps  # ~0.1 s; the server wants one a second
    assert call.half_closed.is_set()


def test_a_new_target_goes_out_at_once_and_status_and_updates_follow_the_server():
    seen = []
    stream, call, _ = open_stream(on_status=seen.append)
    assert stream.status().target == (0.0, 0.0)
    time.sleep(0.03)  # kept: the new target comes between two repetitions, 70 ms before the next is due
    stream.set(linear_mps=0.1, angular_radps=0.5)
    sent = time.monotonic()
    stream.set(angular_radps=-0.3)  # None keeps the linear part
    assert stream.target == (0.1, -0.3)
    statuses = list(stream.updates(timeout_s=0.5))
    assert statuses[-1].target == (0.1, 0.5) or statuses[-1].target == (0.1, -0.3)
    first_new = next(t for t, r in call.requests if r.linear_mps == 0.1)
    assert first_new - sent < 0.05  # not after the next repetition
    stream.stop()
    assert wait_until(lambda: call.requests[-1][1].linear_mps == 0.0, timeout_s=2), "the stop target never went out"
    stream.close(stop_robot=False)
    assert seen[0].target == (0.0, 0.0) and len(seen) >= 2


def test_leaving_the_block_half_closes_then_sends_a_stop_unless_told_not_to():
    stream, call, stops = open_stream()
    with stream:
        stream.set(0.1, 0.0)
    assert call.half_closed.wait(1) and len(stops) == 1
    with pytest.raises(RuntimeError, match="has ended"):
        stream.set(0.2)

    quiet, call, stops = open_stream(stop_on_exit=False)
    with quiet:
        pass
    assert call.half_closed.is_set() and stops == []
    quiet.close()  # twice: nothing more
    assert stops == []


# The fake call's messages are the test's own: the client passes on whatever the server says.
# The real server's words are tested against it (tests/server/server_teleop_test.cpp).

def test_a_refused_stream_raises_its_error_class_with_the_server_message():
    def refuse(code, details):
        return lambda call, request: call.responses.put(FakeRpcError(code, details))

    with pytest.raises(TeleopError) as raised:
        open_stream(refuse(grpc.StatusCode.FAILED_PRECONDITION, "fake: refused"))
    assert raised.value.code == grpc.StatusCode.FAILED_PRECONDITION
    assert raised.value.details == "fake: refused"
    with pytest.raises(BadRequest) as raised:
        open_stream(refuse(grpc.StatusCode.INVALID_ARGUMENT, "fake: a bad profile"))
    assert raised.value.code == grpc.StatusCode.INVALID_ARGUMENT and raised.value.details == "fake: a bad profile"


def test_a_failure_mid_stream_raises_from_set_and_updates_and_once_at_close():
    stream, call, stops = open_stream()
    call.responses.put(FakeRpcError(grpc.StatusCode.ABORTED, "fake: overtaken"))
    with pytest.raises(NotConfirmed, match="fake: overtaken"):
        list(stream.updates(timeout_s=2))
    assert stream.ended
    with pytest.raises(NotConfirmed):
        stream.set(0.1)
    stream.close()  # raised already: not again; the Stop is still sent
    assert len(stops) == 1

    stream, call, _ = open_stream()
    call.responses.put(FakeRpcError(grpc.StatusCode.UNAVAILABLE, "fake: no device"))
    with pytest.raises(TeleopError, match="fake: no device") as raised:
        with stream:
            assert wait_until(lambda: stream.ended, timeout_s=5), "the failure never ended the stream"
    assert raised.value.code == grpc.StatusCode.UNAVAILABLE


def test_the_stop_that_ends_the_stream_is_not_an_error_but_a_failed_stop_is():
    def stop_aborting_the_stream():
        call.responses.put(FakeRpcError(grpc.StatusCode.ABORTED, "fake: overtaken"))

    stream, call, _ = open_stream(stop_robot=stop_aborting_the_stream)
    stream.close()

    def stop_unconfirmed():
        raise NotConfirmed(grpc.StatusCode.ABORTED, "stop: no answer from the robot")

    stream, call, _ = open_stream(stop_robot=stop_unconfirmed)
    with pytest.raises(NotConfirmed, match="no answer"):
        stream.close()
    stream, call, _ = open_stream(stop_robot=stop_unconfirmed)
    with pytest.raises(KeyError):  # the block's own exception wins over the Stop's
        with stream:
            raise KeyError("x")


def test_a_server_that_never_answers_times_out():
    with pytest.raises(TeleopError, match="did not answer the Teleop stream within 0.2 s") as raised:
        open_stream(answer=lambda call, request: None, accept_timeout_s=0.2)
    assert raised.value.code == grpc.StatusCode.DEADLINE_EXCEEDED


# --- real gRPC against a stand-in server (teleop_helpers.py) -------------------------------------
# The stand-in gives dtmf-server's status codes, not its words: these tests assert on codes.

@pytest.fixture
def stand_in():
    server, servicer, address = start_stand_in()
    yield servicer, address
    server.stop(grace=None)


def test_over_grpc_a_stream_confirms_repeats_refuses_a_second_and_stops_on_exit(stand_in):
    servicer, address = stand_in
    with Client(address, timeout_s=5) as robot:
        with robot.teleop(linear_mps=0.1, angular_radps=0.5, lease_s=0.5) as stream:
            assert stream.status().velocity == (0.1, 0.5) and stream.status().progress.profile == "fast"
            with pytest.raises(TeleopError) as raised:
                robot.teleop(profile="fast")
            assert raised.value.code == grpc.StatusCode.FAILED_PRECONDITION
            assert wait_until(lambda: sum(1 for _, r in servicer.requests if r.linear_mps == 0.1) >= 4, timeout_s=5), \
                "the unchanged target was not repeated"
            stream.set(linear_mps=-0.05)
            assert next(s for s in stream.updates(timeout_s=2) if s.target == (-0.05, 0.5)).velocity == (-0.05, 0.5)
            assert not stream.ended
        assert servicer.half_closed.wait(2) and servicer.stops == 1 and stream.ended
        requests = [r for _, r in servicer.requests]
        assert requests[0].options.profile == "fast" and requests[0].lease_s == 0.5
        assert sum(1 for r in requests if r.linear_mps == 0.1) >= 4  # repeated while unchanged

        with pytest.raises(BadRequest) as raised:
            robot.teleop(profile="seed")
        assert raised.value.code == grpc.StatusCode.INVALID_ARGUMENT
        with robot.teleop(stop_on_exit=False):  # the robot is free again
            pass
        assert servicer.stops == 1


def test_over_grpc_a_stop_from_elsewhere_ends_the_stream_aborted(stand_in):
    servicer, address = stand_in
    with Client(address, timeout_s=5) as robot, Client(address, timeout_s=5) as other:
        stream = robot.teleop(linear_mps=0.1)
        other.stop(profile="fast").result()
        with pytest.raises(NotConfirmed) as raised:
            list(stream.updates(timeout_s=2))
        assert raised.value.code == grpc.StatusCode.ABORTED
        stream.close(stop_robot=False)


def test_the_keyboard_example_in_a_terminal_steps_and_stops_with_q(stand_in):
    servicer, address = stand_in
    keyboard = KeyboardInTerminal(address)
    try:
        keyboard.press(b"", r"target \+0\.00 m/s \+0\.00 rad/s \| robot \+0\.00")
        keyboard.press(b"www", r"target \+0\.03 m/s \+0\.00 rad/s \| robot \+0\.03 m/s \+0\.00 rad/s")
        keyboard.press(b"dd", r"target \+0\.03 m/s -0\.20 rad/s \| robot \+0\.03 m/s -0\.20 rad/s \(80 ms\) \| "
                              r"link 100%")
        keyboard.press(b"s", r"target \+0\.00 m/s \+0\.00 rad/s")
        assert keyboard.quit() == 0, keyboard.text
    finally:
        keyboard.close()
    assert "stopping" in keyboard.text and servicer.stops == 1
    assert [r.linear_mps for _, r in servicer.requests][-1] == 0.0


def test_the_keyboard_example_quits_with_a_stop_on_ctrl_c(stand_in):
    servicer, address = stand_in
    keyboard = KeyboardInTerminal(address)
    try:
        keyboard.press(b"", r"robot \+0\.00")
        keyboard.press(b"a", r"robot \+0\.00 m/s \+0\.10 rad/s")
        assert keyboard.quit(b"\x03") == 0, keyboard.text  # the terminal makes it SIGINT
    finally:
        keyboard.close()
    assert servicer.stops == 1


# --- the keyboard example ------------------------------------------------------------------------

def test_keys_step_the_target_like_turtlebot3_teleop_key():
    step = keyboard.next_target
    assert step("w", 0.0, 0.0, BURGER) == (0.01, 0.0)
    assert step("x", 0.0, 0.0, BURGER) == (-0.01, 0.0)
    assert step("a", 0.0, 0.0, BURGER) == (0.0, 0.1)
    assert step("d", 0.0, 0.0, BURGER) == (0.0, -0.1)
    assert step("s", 0.1, 0.5, BURGER) == step(" ", 0.1, 0.5, BURGER) == (0.0, 0.0)
    assert step("k", 0.1, 0.5, BURGER) is None and step("q", 0.1, 0.5, BURGER) is None
    target = (0.0, 0.0)
    for _ in range(10):
        target = step("w", *target, BURGER)
    assert target == (0.1, 0.0)  # no drift from adding 0.01 ten times


def test_keys_stop_at_the_robot_limits():
    step = keyboard.next_target
    linear, angular = 0.0, 0.0
    for _ in range(40):
        linear, angular = step("w", linear, angular, BURGER)
        linear, angular = step("a", linear, angular, BURGER)
    assert (linear, angular) == BURGER == (0.22, 2.84)
    for _ in range(80):
        linear, angular = step("x", linear, angular, keyboard.MODELS["waffle"])
    assert linear == -0.26 and angular == 1.82
    assert "q" in keyboard.QUIT_KEYS and "\x03" in keyboard.QUIT_KEYS


def test_the_status_line_shows_target_confirmation_link_and_lease():
    s = TeleopStatus.from_proto(response(0.1, 0.5, pb.FRAME_EVENT_ACK, confirmed=True, confirmed_linear_mps=0.1,
                                         confirmed_angular_radps=0.4976, response_time_ms=81.6, link_quality=0.9,
                                         frames_in_window=10, lease_left_s=0.73))
    assert keyboard.status_line(s) == ("target +0.10 m/s +0.50 rad/s | robot +0.10 m/s +0.50 rad/s (82 ms) | "
                                       "link 90% of 10 frames | lease 0.7 s left")
    assert "nothing confirmed yet" in keyboard.status_line(TeleopStatus.from_proto(response(0.1)))


def test_the_keyboard_example_refuses_without_a_terminal():
    result = subprocess.run([sys.executable, str(EXAMPLES / "teleop_keyboard.py"), "--server", "127.0.0.1:1"],
                            stdin=subprocess.DEVNULL, capture_output=True, text=True, timeout=60)
    assert result.returncode == 2
    assert "standard input is not a terminal" in result.stderr
    assert result.stdout == ""  # refused before the key help, and before connecting
