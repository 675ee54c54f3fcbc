"""dtmf_teleop: drive a TurtleBot3 by sound through dtmf-server's gRPC API.

Client is the friendly layer (client.py), teleop.py its live-driving stream; events.py holds
the typed progress events, errors.py the exceptions. The raw generated stubs are in
dtmf_teleop._stubs (made by the package's build from proto/, never edited by hand).
"""

from .client import DEFAULT_TARGET, Client, CommandCall
from .errors import (BadRequest, Cancelled, NotConfirmed, NotFound, QueueFull, ServerUnreachable, TeleopError,
                     Unauthenticated)
from .events import Decision, FrameEvent, Progress, SequenceProgress, TeleopStatus, Unconfirmed
from .teleop import TeleopStream
from .watch import AirWatch

__all__ = ["AirWatch", "Client", "CommandCall", "DEFAULT_TARGET", "BadRequest", "Cancelled", "NotConfirmed", "NotFound",
           "QueueFull", "ServerUnreachable", "TeleopError", "Unauthenticated", "Decision", "FrameEvent", "Progress",
           "SequenceProgress", "TeleopStatus", "TeleopStream", "Unconfirmed"]
