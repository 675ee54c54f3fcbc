"""Errors of the dtmf-teleop client: one exception per kind of failure, each carrying the
gRPC status code and the server's message (which names what was wrong and what to do)."""

from __future__ import annotations

import grpc


class TeleopError(Exception):
    """A call failed; `code` is the grpc.StatusCode, `details` the server's explanation."""

    def __init__(self, code: grpc.StatusCode, details: str):
        super().__init__(f"{details} ({code.name})" if details else code.name)
        self.code = code
        self.details = details


class BadRequest(TeleopError):
    """INVALID_ARGUMENT: a value out of range; the message names the field."""


class NotConfirmed(TeleopError):
    """ABORTED: the robot did not confirm a frame and the policy or a Decide said fail."""


class ServerUnreachable(TeleopError):
    """UNAVAILABLE: no server at the address, its audio device is gone, or it is stopping."""


class QueueFull(TeleopError):
    """RESOURCE_EXHAUSTED: too many commands wait for the acoustic channel; retry later."""


class NotFound(TeleopError):
    """NOT_FOUND: no such test run or command."""


class Unauthenticated(TeleopError):
    """UNAUTHENTICATED: the server wants a bearer token (Client(token=...))."""


class Cancelled(TeleopError):
    """CANCELLED or DEADLINE_EXCEEDED: the call was cancelled before its command finished."""


_BY_CODE = {
    grpc.StatusCode.INVALID_ARGUMENT: BadRequest,
    grpc.StatusCode.ABORTED: NotConfirmed,
    grpc.StatusCode.UNAVAILABLE: ServerUnreachable,
    grpc.StatusCode.RESOURCE_EXHAUSTED: QueueFull,
    grpc.StatusCode.NOT_FOUND: NotFound,
    grpc.StatusCode.UNAUTHENTICATED: Unauthenticated,
    grpc.StatusCode.CANCELLED: Cancelled,
    grpc.StatusCode.DEADLINE_EXCEEDED: Cancelled,
}


def from_rpc_error(error: grpc.RpcError, target: str = "") -> TeleopError:
    """The exception for a failed gRPC call; a connection failure says where it looked."""
    code, details = error.code(), error.details() or ""
    if code == grpc.StatusCode.UNAVAILABLE and target and ("connect" in details.lower() or not details):
        details = f"cannot reach dtmf-server at {target}: is it running? ({details})"
    return _BY_CODE.get(code, TeleopError)(code, details)
