"""Every Client call against the live system (conftest.py)."""

import time

import grpc
import pytest

from dtmf_teleop import (BadRequest, Client, Decision, FrameEvent, NotConfirmed, NotFound, Progress,
                         ServerUnreachable, TeleopError, Unconfirmed)

# A Velocity frame's steps (docs/protocol.md §10) for a Burger (dtmf-server --robot's default).
LINEAR_STEP_MPS = 0.22 / 2047
ANGULAR_STEP_RADPS = 2.84 / 127


def test_health_is_serving(robot):
    assert robot.health() == "SERVING"


def test_drive_yields_typed_events_frame_by_frame(robot):
    events = list(robot.drive(speed=50, duration=1))
    assert all(isinstance(e, Progress) for e in events)
    assert [e.event for e in events] == [FrameEvent.QUEUED] + [FrameEvent.TRANSMITTING, FrameEvent.ACK] * 3 + [
        FrameEvent.CONFIRMED]
    acks = [e for e in events if e.event == FrameEvent.ACK]
    assert [e.frame_index for e in acks] == [0, 1, 2]
    assert all(e.frame_count == 3 and len(e.frame_bits) == 16 and len(e.tones_hz) == 4 for e in acks)
    assert all(0 < e.response_time_ms < 1500 for e in acks)
    assert events[-1].command == "drive_for_duration speed=50.0% duration=1.03s"
    assert events[-1].event.is_final


def test_turn_stop_and_reset_end_confirmed(robot):
    assert robot.turn(rotation=-40, duration=0.5).result().event == FrameEvent.CONFIRMED
    assert robot.turn(rotation=30).result().command.startswith("turn ")
    stop = robot.stop().result()
    assert (stop.event, stop.frame_count) == (FrameEvent.CONFIRMED, 2)
    assert robot.reset().result().frame_count == 1
    drive = robot.drive(speed=20).result()  # until the next command
    assert drive.command.startswith("drive_forward")
    robot.stop().result()


def test_the_fast_profile_sends_a_whole_command_in_one_named_frame(robot):
    events = list(robot.drive(speed=30, duration=1, profile="fast"))
    assert [e.event for e in events] == [FrameEvent.QUEUED, FrameEvent.TRANSMITTING, FrameEvent.ACK,
                                         FrameEvent.CONFIRMED]
    ack = events[2]
    assert (ack.profile, ack.word, ack.frame_count, len(ack.frame_bits), len(ack.tones_hz)) == ("fast", None, 1, 50, 16)
    assert ack.sequence is not None and 0 < ack.response_time_ms < 500
    assert robot.reset().result().profile == "seed"  # the server's default
    with pytest.raises(BadRequest) as raised:
        robot.stop(profile="slow").result()
    assert "options.profile" in raised.value.details


def test_a_bad_value_raises_bad_request_naming_the_field(robot):
    with pytest.raises(BadRequest) as raised:
        robot.drive(speed=150, duration=1).result()
    assert "speed_percent" in raised.value.details
    assert raised.value.code.name == "INVALID_ARGUMENT"
    with pytest.raises(BadRequest, match="duration_s"):
        robot.turn(rotation=10, duration=9).result()


def test_robots_lists_the_servers_robot_and_a_client_names_its_robot(system, robot):
    robots = robot.robots()
    assert [(r["name"], r["address"], r["model"], r["key_id"]) for r in robots] == [("robot", 0, "burger", "")]
    assert robots[0]["last_answered_unix_ms"] > 0  # the system's readiness Stop was answered
    with Client(system.address, robot="robot") as named:
        assert named.reset().result().robot == "robot"
    with Client(system.address, robot="nobody") as unknown:
        with pytest.raises(BadRequest, match="options.robot: no robot called \"nobody\": this server drives robot"):
            unknown.reset().result()


def test_a_stop_for_every_robot_is_sent_twice_and_answered_by_none(system):
    # A client bound to its robot still stops every robot: the name is left out.
    with Client(system.address, robot="robot") as named:
        events = list(named.stop(all_robots=True))
    assert [e.event for e in events] == [FrameEvent.QUEUED] + [FrameEvent.TRANSMITTING] * 2 + [FrameEvent.SENT]
    assert events[-1].event.is_final
    assert (events[-1].command, events[-1].robot, events[-1].profile) == ("stop every_robot", "", "fast")
    with Client(system.address) as client:
        with pytest.raises(BadRequest, match="options.profile: profile seed names no robot"):
            client.stop(all_robots=True, profile="seed").result()


def test_an_unreachable_server_raises_server_unreachable():
    with Client("127.0.0.1:1", timeout_s=2) as nowhere:
        with pytest.raises(ServerUnreachable, match="cannot reach dtmf-server at 127.0.0.1:1"):
            nowhere.health()
        with pytest.raises(ServerUnreachable):
            nowhere.stop().result()


def test_an_unanswered_frame_fails_continues_or_asks_as_told(deaf):
    with pytest.raises(NotConfirmed) as raised:
        deaf.reset().result()
    assert raised.value.code.name == "ABORTED"
    assert deaf.reset(on_unconfirmed=Unconfirmed.CONTINUE).result().event == FrameEvent.CONTINUED

    call = deaf.reset(on_unconfirmed=Unconfirmed.ASK)
    seen = []
    for step in call:
        seen.append(step.event)
        if step.event == FrameEvent.AWAITING_DECISION:
            call.decide(Decision.CONTINUE)
    assert seen.count(FrameEvent.TRANSMITTING) == 1 and seen.count(FrameEvent.RETRANSMITTING) == 1
    assert FrameEvent.AWAITING_DECISION in seen
    assert call.last.event == FrameEvent.CONTINUED


def test_a_run_frames_commands_and_reports_them_as_a_dict(robot):
    run_id = robot.start_run("python", notes="pytest")
    robot.stop().result()
    robot.end_run(run_id)

    runs = robot.runs(limit=1)
    assert runs[0]["run_id"] == run_id and runs[0]["label"] == "python"
    assert runs[0]["transmissions_sent"] == 2 and isinstance(runs[0]["number"], int)

    report = robot.report(run_id, frames=True)
    assert report["run"]["label"] == "python"
    assert report["transmissions_sent"] == 2
    assert report["sender_confirmed"] == 2
    assert report["success_rate_pct"] == 100.0
    assert report["error_catch_rate_pct"] is None  # nothing damaged to catch: the seed's N/A
    assert [f["position"] for f in report["frames"]] == [0, 1]
    for frame in report["frames"]:
        assert frame["command"] == "stop" and frame["answer"] == "ack"
        assert 0 < frame["response_time_ms"] < 1500
        assert frame["latency_ms"] is not None and 0 < frame["latency_ms"] < frame["response_time_ms"]

    by_number = robot.report(runs[0]["number"])
    assert by_number["run"]["run_id"] == run_id and "frames" not in by_number
    with pytest.raises(NotFound):
        robot.report(999999)

    # The run's one robot, by name: the same figures as the room's (migration 010).
    assert runs[0]["robots"] == ["robot"]
    own = robot.report(run_id, robot="robot")
    assert (own["robot"], own["transmissions_sent"], own["sender_confirmed"]) == ("robot", 2, 2)
    assert report["robot"] == ""
    with pytest.raises(NotFound, match='no command of run .* named robot "nobody"'):
        robot.report(run_id, robot="nobody")


# --- Teleop: the bidirectional stream of server/teleop_rpc.cpp, live ---------------------------
# Its parts that need no server: test_teleop.py.

def first_confirmed(stream, linear_mps, angular_radps, within_s=10):
    """The first status whose confirmed velocity is the target's, within the frame's steps."""
    deadline = time.monotonic() + within_s
    for status in stream.updates(timeout_s=within_s):
        if (status.confirmed and abs(status.confirmed_linear_mps - linear_mps) <= LINEAR_STEP_MPS
                and abs(status.confirmed_angular_radps - angular_radps) <= ANGULAR_STEP_RADPS):
            return status
        if time.monotonic() > deadline:
            break
    pytest.fail(f"no confirmation of ({linear_mps}, {angular_radps}) within {within_s} s: {stream.status()}")


def test_teleop_drives_at_the_target_one_stream_at_a_time_and_only_with_fast(robot):
    with robot.teleop(linear_mps=0.1, angular_radps=0.5, profile="fast", lease_s=1.0) as stream:
        status = first_confirmed(stream, 0.1, 0.5)
        assert status.target == (0.1, 0.5) and status.velocity is not None
        assert 0 < status.response_time_ms < 500
        assert 0 < status.link_quality <= 1 and status.frames_in_window >= 1 and status.link_window_s > 0
        assert status.lease_s == pytest.approx(1.0, abs=0.15) and 0 <= status.lease_left_s <= status.lease_s
        assert isinstance(status.progress, Progress) and status.progress.profile == "fast"
        assert stream.status().confirmed

        with pytest.raises(TeleopError) as raised:  # one stream drives at a time
            robot.teleop(linear_mps=0.05, profile="fast")
        assert raised.value.code == grpc.StatusCode.FAILED_PRECONDITION and raised.value.details
        with pytest.raises(TeleopError) as raised:  # and no command meanwhile
            robot.drive(speed=20, duration=1, profile="fast").result()
        assert raised.value.code == grpc.StatusCode.FAILED_PRECONDITION

        stream.set(linear_mps=-0.05, angular_radps=0.0)
        assert first_confirmed(stream, -0.05, 0.0).target == (-0.05, 0.0)
    # the block's end sent a Stop the robot confirmed, and freed the robot for commands
    assert stream.ended
    assert robot.drive(speed=30, duration=0.5, profile="fast").result().event == FrameEvent.CONFIRMED

    with pytest.raises(BadRequest) as raised:
        robot.teleop(profile="seed")
    assert raised.value.code == grpc.StatusCode.INVALID_ARGUMENT and "seed" in raised.value.details
