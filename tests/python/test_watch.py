"""Client.watch() against the live system (conftest.py): the air as the server sees it."""

import threading
import time

import pytest

from dtmf_teleop import BadRequest


def test_watch_shows_a_frame_its_answer_and_its_end(robot):
    events = []
    watching = threading.Event()
    # A column a second: the first tells the watch is open before anything is sent.
    with robot.watch(spectrum=True, columns_per_s=1) as air:
        def read():
            for event in air:
                watching.set()
                if event["kind"] != "spectrum":
                    events.append(event)
                if event["kind"] == "command_ended":
                    return
        reader = threading.Thread(target=read)
        reader.start()
        assert watching.wait(timeout=10)
        drive = robot.drive(speed=30, duration=1, profile="fast").result()
        reader.join(timeout=10)
    assert not reader.is_alive()
    kinds = [e["kind"] for e in events]
    assert "frame_played" in kinds and "frame_answered" in kinds and kinds[-1] == "command_ended"
    played = next(e for e in events if e["kind"] == "frame_played")
    assert played["frame_played"]["command_id"] == drive.command_id
    assert played["frame_played"]["profile"] == "fast"
    assert played["frame_played"]["sequence"] == drive.sequence
    answered = next(e for e in events if e["kind"] == "frame_answered")
    assert answered["frame_answered"]["answer"] == "ack"
    assert answered["audio_ms"] >= played["audio_ms"]
    assert events[-1]["command_ended"]["outcome"] == "confirmed"
    assert all(e["dropped_events"] == 0 for e in events)


def test_watch_spectrum_columns_have_the_bins_asked(robot):
    with robot.watch(spectrum=True, columns_per_s=20, bins=32) as air:
        columns = []
        for event in air:
            if event["kind"] == "spectrum":
                columns.append(event["spectrum"])
            if len(columns) == 5:
                break
    assert all(len(c["level_dbfs"]) == 32 and c["low_hz"] == 1000 for c in columns)


def test_watch_refuses_a_rate_over_its_cap(robot):
    with pytest.raises(BadRequest) as raised:
        list(robot.watch(spectrum=True, columns_per_s=500))
    assert "columns_per_s" in raised.value.details


def test_receptions_list_what_the_robot_heard_and_did(robot):
    drive = robot.drive(speed=25, duration=1, profile="fast").result()
    assert drive.command_id
    deadline = time.monotonic() + 10
    while True:  # the robot's row reaches the database through its store's queue
        heard = list(robot.receptions(limit=5))
        if any(r["event"] == "command" and r["command"].startswith("drive_for_duration speed=25") for r in heard):
            break
        assert time.monotonic() < deadline, heard
        time.sleep(0.2)
    executed = next(r for r in heard if r["command"].startswith("drive_for_duration speed=25"))
    assert executed["intact"] and executed["reply"] == "ack" and executed["profile"] == "fast"
    assert [r["stored"] for r in heard] == sorted(r["stored"] for r in heard)
