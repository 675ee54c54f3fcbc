"""AirWatch: the air as dtmf-server puts it there and hears it (WatchAir), as plain dicts.

    with Client() as robot, robot.watch() as air:
        for event in air:
            if event["kind"] == "frame_played":
                print(event["audio_ms"], event["frame_played"]["command"])

Each event is a dict: "kind" (frame_played, frame_answered, answer_heard, air_waiting,
air_busy, command_ended, spectrum), "audio_ms" (the microphone's clock), "time_unix_ms",
"dropped_events" and "dropped_columns" (lost just before it, because this watcher read too
slowly: the server never waits for it), and the event's fields under its kind.
"""

from __future__ import annotations

from typing import Any, Callable, Iterator, Optional

import grpc

from . import errors
from .records import message_to_dict

KINDS = ("frame_played", "frame_answered", "answer_heard", "air_waiting", "air_busy", "command_ended", "spectrum")


def watch_event(message: Any) -> dict[str, Any]:
    """A WatchAirResponse as a dict with only its own event's fields."""
    kind = message.WhichOneof("event")
    event = {"kind": kind, "audio_ms": message.audio_ms, "time_unix_ms": message.time_unix_ms,
             "dropped_events": message.dropped_events, "dropped_columns": message.dropped_columns}
    if kind:
        event[kind] = message_to_dict(getattr(message, kind))
    return event


class AirWatch:
    """A server stream (WatchAir, or ListReceptions with its own `convert`): iterate it for
    dicts; cancel() (or leaving a with block) ends it."""

    def __init__(self, call: Any, target: str, convert: Optional[Callable[[Any], dict[str, Any]]] = None):
        self._call = call
        self._target = target
        self._convert = convert or watch_event
        self._cancelled = False

    def __iter__(self) -> Iterator[dict[str, Any]]:
        try:
            for message in self._call:
                yield self._convert(message)
        except grpc.RpcError as e:
            if self._cancelled and e.code() == grpc.StatusCode.CANCELLED:
                return
            raise errors.from_rpc_error(e, self._target) from None

    def cancel(self) -> None:
        self._cancelled = True
        self._call.cancel()

    def __enter__(self) -> "AirWatch":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.cancel()
