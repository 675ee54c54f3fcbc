"""Typed views of what the server streams: a command's progress frame by frame, the test
sequence's progress and a Teleop stream's status, as frozen dataclasses with Python enums
(no protobuf needed)."""

from __future__ import annotations

import enum
from dataclasses import dataclass, field
from typing import Optional

from ._stubs.dtmf.v1 import teleop_pb2 as pb


class FrameEvent(enum.Enum):
    QUEUED = pb.FRAME_EVENT_QUEUED
    TRANSMITTING = pb.FRAME_EVENT_TRANSMITTING
    ACK = pb.FRAME_EVENT_ACK
    NACK = pb.FRAME_EVENT_NACK
    NO_ANSWER = pb.FRAME_EVENT_NO_ANSWER
    RETRANSMITTING = pb.FRAME_EVENT_RETRANSMITTING
    AWAITING_DECISION = pb.FRAME_EVENT_AWAITING_DECISION
    CONFIRMED = pb.FRAME_EVENT_CONFIRMED
    CONTINUED = pb.FRAME_EVENT_CONTINUED
    FAILED = pb.FRAME_EVENT_FAILED
    SENT = pb.FRAME_EVENT_SENT  # a stop for every robot played whole: no robot answers it
    # The frame waits for the air (the server listens before it talks): Progress.air_wait_reason says why.
    WAITING_FOR_AIR = pb.FRAME_EVENT_WAITING_FOR_AIR
    UNSPECIFIED = pb.FRAME_EVENT_UNSPECIFIED

    @classmethod
    def _missing_(cls, value):
        # An event of a newer server than this package: UNSPECIFIED, not an error mid-command.
        return cls.UNSPECIFIED

    @property
    def is_final(self) -> bool:
        return self in (FrameEvent.CONFIRMED, FrameEvent.CONTINUED, FrameEvent.FAILED, FrameEvent.SENT)


class Decision(enum.Enum):
    """The answer to FrameEvent.AWAITING_DECISION (the seed's continue / retransmit / abort)."""
    CONTINUE = pb.DECISION_CONTINUE
    RETRANSMIT = pb.DECISION_RETRANSMIT
    ABORT = pb.DECISION_ABORT


class Unconfirmed(enum.Enum):
    """What the server does with a frame still unconfirmed after its automatic retransmission."""
    ASK = pb.UNCONFIRMED_POLICY_ASK  # stream AWAITING_DECISION and wait for decide()
    CONTINUE = pb.UNCONFIRMED_POLICY_CONTINUE
    FAIL = pb.UNCONFIRMED_POLICY_FAIL


@dataclass(frozen=True)
class Progress:
    """One step of a command: a frame queued, on air, answered, or the command's end."""
    event: FrameEvent
    command_id: str
    command: str                  # e.g. "drive_for_duration speed=50.0% duration=2.06s"
    frame_index: int              # from 0
    frame_count: int
    attempt: int                  # 1 = first transmission
    word: Optional[int]           # seed frames; None for fast frames (a whole command each)
    frame_bits: str               # "1011001011011101" (50 bits under the fast profile)
    tones_hz: tuple[float, ...] = field(default_factory=tuple)
    response_time_ms: float = 0.0  # with ACK / NACK: chord start to the answer
    detail: str = ""
    queue_position: int = 0
    time_unix_ms: int = 0
    profile: str = ""              # "seed" or "fast"
    sequence: Optional[int] = None  # fast: the number the frame's ACK names
    authenticated: bool = False     # the frame carries a MAC (fast, with a key on the server)
    synchronisation: bool = False   # a counter synchronisation ahead of the command (authenticated)
    # ACK, CONFIRMED: the answer spelled the frame's tag under the key. False: an untagged
    # ACK, which anyone within earshot can play (never a keyed confirmation).
    answer_authenticated: bool = False
    robot: str = ""                 # the robot the command is for (its name on the server)
    # WAITING_FOR_AIR: why ("sound 14 dB over the room's floor", "yielding to another sender")
    # and the longest it may still wait; TRANSMITTING / RETRANSMITTING: how long it waited.
    air_wait_reason: str = ""
    air_wait_left_ms: float = 0.0
    air_wait_ms: float = 0.0

    @property
    def waiting_for_air(self) -> str:
        """What dtmfctl shows for WAITING_FOR_AIR: "waiting for the air: <why>"; "" otherwise."""
        return f"waiting for the air: {self.air_wait_reason}" if self.event == FrameEvent.WAITING_FOR_AIR else ""

    @classmethod
    def from_proto(cls, p: pb.Progress) -> "Progress":
        return cls(event=FrameEvent(p.event), command_id=p.command_id, command=p.command,
                   frame_index=p.frame_index, frame_count=p.frame_count, attempt=p.attempt,
                   word=p.word if p.HasField("word") else None,
                   frame_bits=p.frame_bits, tones_hz=tuple(p.tones_hz), response_time_ms=p.response_time_ms,
                   detail=p.detail, queue_position=p.queue_position, time_unix_ms=p.time_unix_ms,
                   profile=p.profile, sequence=p.sequence if p.HasField("sequence") else None,
                   authenticated=p.authenticated, synchronisation=p.synchronisation,
                   answer_authenticated=p.answer_authenticated, robot=p.robot,
                   air_wait_reason=p.air_wait_reason, air_wait_left_ms=p.air_wait_left_ms,
                   air_wait_ms=p.air_wait_ms)


@dataclass(frozen=True)
class SequenceProgress:
    """One step of the seed's test sequence: where it is, and the current command's step."""
    run_id: str
    command_index: int
    command_count: int
    frames_done: int
    frames_total: int
    progress: Progress

    @classmethod
    def from_proto(cls, r: pb.RunTestSequenceResponse) -> "SequenceProgress":
        return cls(run_id=r.run_id, command_index=r.command_index, command_count=r.command_count,
                   frames_done=r.frames_done, frames_total=r.frames_total, progress=Progress.from_proto(r.progress))


@dataclass(frozen=True)
class TeleopStatus:
    """A Teleop stream after one frame's event: the target the server holds, the velocity
    the robot last confirmed, and how well the link carries (Client.teleop)."""
    target_linear_mps: float         # the newest target the server holds
    target_angular_radps: float
    confirmed: bool                  # the robot has confirmed a frame of this stream
    confirmed_linear_mps: float      # the last velocity it confirmed, as it executes it (0 before)
    confirmed_angular_radps: float
    response_time_ms: float          # the last confirmed frame's chord start to its ACK
    link_quality: float              # answers heard per frame sent over the last link_window_s (0..1)
    frames_in_window: int
    link_window_s: float
    lease_s: float                   # the lease each frame carries (as the frame encodes it)
    lease_left_s: float              # until the lease of the last frame sent ends, if the robot heard it
    progress: Optional[Progress] = None  # the frame's event, as drive() yields it

    @property
    def target(self) -> tuple[float, float]:
        """(linear m/s, angular rad/s) the server is sending."""
        return (self.target_linear_mps, self.target_angular_radps)

    @property
    def velocity(self) -> Optional[tuple[float, float]]:
        """(linear m/s, angular rad/s) the robot confirmed last; None before its first ACK."""
        return (self.confirmed_linear_mps, self.confirmed_angular_radps) if self.confirmed else None

    @classmethod
    def from_proto(cls, r: pb.TeleopResponse) -> "TeleopStatus":
        return cls(target_linear_mps=r.target_linear_mps, target_angular_radps=r.target_angular_radps,
                   confirmed=r.confirmed, confirmed_linear_mps=r.confirmed_linear_mps,
                   confirmed_angular_radps=r.confirmed_angular_radps, response_time_ms=r.response_time_ms,
                   link_quality=r.link_quality, frames_in_window=r.frames_in_window, link_window_s=r.link_window_s,
                   lease_s=r.lease_s, lease_left_s=r.lease_left_s,
                   progress=Progress.from_proto(r.progress) if r.HasField("progress") else None)
