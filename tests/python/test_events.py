"""Typed progress events without a server: a frame the air holds (issue 59) says why, and an
event of a newer server that this package does not know is UNSPECIFIED, not an error."""

from dtmf_teleop import FrameEvent, Progress
from dtmf_teleop._stubs.dtmf.v1 import teleop_pb2 as pb


def test_a_frame_the_air_holds_says_why_and_for_how_long_at_most():
    p = Progress.from_proto(pb.Progress(event=pb.FRAME_EVENT_WAITING_FOR_AIR,
                                        air_wait_reason="sound 14 dB over the room's floor", air_wait_left_ms=8700))
    assert p.event == FrameEvent.WAITING_FOR_AIR and not p.event.is_final
    assert p.waiting_for_air == "waiting for the air: sound 14 dB over the room's floor"
    assert p.air_wait_left_ms == 8700


def test_a_transmission_says_how_long_it_waited():
    p = Progress.from_proto(pb.Progress(event=pb.FRAME_EVENT_TRANSMITTING, air_wait_ms=8712.5))
    assert p.air_wait_ms == 8712.5 and p.waiting_for_air == ""


def test_an_event_this_package_does_not_know_is_unspecified():
    unknown = pb.Progress()
    unknown.event = 99
    assert Progress.from_proto(unknown).event == FrameEvent.UNSPECIFIED
