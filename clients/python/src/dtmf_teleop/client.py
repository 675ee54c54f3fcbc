"""Client: the dtmf-teleop gRPC API (dtmf.v1.TeleopService) as plain Python.

    from dtmf_teleop import Client
    with Client("localhost:50051") as robot:
        for step in robot.drive(speed=50, duration=2):   # typed Progress events
            print(step.event.name, step.frame_bits)
        robot.turn(rotation=-40, duration=1).result()     # or just wait for the end
        print(robot.report()["success_rate_pct"])

Each command call starts at once and returns a CommandCall: iterate it for progress events,
or call result() for the final one; teleop() opens a live-driving stream (teleop.py). A
command that ends unconfirmed, a bad value or an unreachable server raise TeleopError
subclasses (errors.py) carrying the gRPC status.
"""

from __future__ import annotations

from typing import Any, Callable, Iterator, Optional

import grpc

from . import errors
from ._stubs.dtmf.v1 import teleop_pb2 as pb
from ._stubs.dtmf.v1 import teleop_pb2_grpc
from ._stubs.grpc.health.v1 import health_pb2, health_pb2_grpc
from .events import Decision, FrameEvent, Progress, SequenceProgress, TeleopStatus, Unconfirmed
from .records import message_to_dict
from .teleop import REPEAT_S, TeleopStream
from .watch import AirWatch

DEFAULT_TARGET = "localhost:50051"


class CommandCall:
    """A command under way. Iterating yields its events (Progress or SequenceProgress) as
    they come; result() waits for the last. Failures raise when reached."""

    def __init__(self, client: "Client", call: Any, convert: Callable[[Any], Any]):
        self._client = client
        self._call = call
        self._convert = convert
        self.last: Optional[Any] = None

    def __iter__(self) -> Iterator[Any]:
        try:
            for response in self._call:
                self.last = self._convert(response)
                yield self.last
        except grpc.RpcError as e:
            raise errors.from_rpc_error(e, self._client.target) from None

    def result(self) -> Any:
        """The final event (CONFIRMED, CONTINUED, or SENT for a stop to every robot); raises if
        the command failed."""
        for _ in self:
            pass
        return self.last

    def decide(self, decision: Decision) -> None:
        """Answer an AWAITING_DECISION event of this command."""
        progress = self.last.progress if isinstance(self.last, SequenceProgress) else self.last
        if progress is None:
            raise RuntimeError("nothing to decide yet: wait for FrameEvent.AWAITING_DECISION")
        self._client.decide(progress.command_id, decision)

    def cancel(self) -> None:
        """Withdraw the command; frames not yet on air never play."""
        self._call.cancel()


class Client:
    """A connection to dtmf-server. target: "host:port"; token: the server's bearer token
    (dtmf-server --auth-token-file); tls_ca: PEM file to trust for a TLS server; robot: the
    robot every command of this client drives, by the name the server gives it (robots());
    None: the server's only robot (a server that drives several refuses with BadRequest)."""

    def __init__(self, target: str = DEFAULT_TARGET, *, token: Optional[str] = None,
                 tls_ca: Optional[str] = None, timeout_s: float = 30.0, robot: Optional[str] = None):
        self.target = target
        self.robot = robot
        self.timeout_s = timeout_s
        if tls_ca:
            with open(tls_ca, "rb") as f:
                self._channel = grpc.secure_channel(target, grpc.ssl_channel_credentials(f.read()))
        else:
            self._channel = grpc.insecure_channel(target)
        self._metadata = (("authorization", f"Bearer {token}"),) if token else ()
        self._stub = teleop_pb2_grpc.TeleopServiceStub(self._channel)
        self._health = health_pb2_grpc.HealthStub(self._channel)

    def close(self) -> None:
        self._channel.close()

    def __enter__(self) -> "Client":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    # --- commands: each streams its progress --------------------------------------------

    # Every command takes on_unconfirmed (what to do with a frame left unconfirmed) and
    # profile ("seed" or "fast"; None: the server's default).

    def drive(self, speed: float, duration: Optional[float] = None, *,
              on_unconfirmed: Optional[Unconfirmed] = None, profile: Optional[str] = None) -> CommandCall:
        """Drive forward at speed percent (0..100) for duration seconds (0..8), or until
        the next command when duration is None."""
        request = pb.DriveRequest(speed_percent=speed, options=self._options(on_unconfirmed, profile))
        if duration is not None:
            request.duration_s = duration
        return self._command(self._stub.Drive, request)

    def turn(self, rotation: float, duration: Optional[float] = None, *,
             on_unconfirmed: Optional[Unconfirmed] = None, profile: Optional[str] = None) -> CommandCall:
        """Turn in place at rotation percent (-100..100, positive is left) for duration
        seconds (0..8), or until the next command when duration is None."""
        request = pb.TurnRequest(rotation_percent=rotation, options=self._options(on_unconfirmed, profile))
        if duration is not None:
            request.duration_s = duration
        return self._command(self._stub.Turn, request)

    def stop(self, *, on_unconfirmed: Optional[Unconfirmed] = None, profile: Optional[str] = None,
             all_robots: bool = False) -> CommandCall:
        """Stop this client's robot, ahead of queued commands. all_robots: one stop that every
        robot in the room executes and none answers (its final event SENT); with keyed robots
        it needs the server's room key (else TeleopError, code FAILED_PRECONDITION)."""
        options = self._options(on_unconfirmed, profile)
        if all_robots:
            options.ClearField("robot")
        return self._command(self._stub.Stop, pb.StopRequest(options=options, all_robots=all_robots))

    def reset(self, *, on_unconfirmed: Optional[Unconfirmed] = None, profile: Optional[str] = None) -> CommandCall:
        return self._command(self._stub.Reset, pb.ResetRequest(options=self._options(on_unconfirmed, profile)))

    def run_sequence(self, label: str, notes: str = "", *,
                     on_unconfirmed: Optional[Unconfirmed] = None, profile: Optional[str] = None) -> CommandCall:
        """The seed's test sequence as a labelled test run (65 frames under the seed
        profile, one frame per command under fast); yields SequenceProgress."""
        request = pb.RunTestSequenceRequest(label=label, notes=notes, options=self._options(on_unconfirmed, profile))
        call = self._stub.RunTestSequence(request, metadata=self._metadata)
        return CommandCall(self, call, SequenceProgress.from_proto)

    def teleop(self, linear_mps: float = 0.0, angular_radps: float = 0.0, *, lease_s: float = 1.0,
               profile: str = "fast", on_status: Optional[Callable[[TeleopStatus], None]] = None,
               stop_on_exit: bool = True, repeat_s: float = REPEAT_S) -> TeleopStream:
        """Live driving (teleop.py): opens a Teleop stream starting at this target (m/s, rad/s,
        left positive) and returns once the server has taken it. lease_s (0.3..2): how long
        the robot holds a target without a renewal; profile: one that carries velocity
        ("fast"); on_status: called with each TeleopStatus (on the stream's reader thread). One
        stream drives a robot at a time: a second one to it, and drive(), turn(), reset() or
        run_sequence() for it meanwhile, are refused (FAILED_PRECONDITION); stop() overtakes
        and ends it. Clients naming different robots (Client(robot=...)) drive them at once.

        Use it in a with-block: leaving it half-closes the stream and, unless stop_on_exit is
        False, sends a Stop (with this profile) and waits for the robot to confirm it, so the
        robot stops at once instead of when its lease runs out."""
        def stop_robot() -> None:
            self.stop(on_unconfirmed=Unconfirmed.FAIL, profile=profile).result()

        return TeleopStream(lambda requests: self._stub.Teleop(requests, metadata=self._metadata), stop_robot,
                            linear_mps=linear_mps, angular_radps=angular_radps, lease_s=lease_s, profile=profile,
                            robot=self.robot or "",
                            on_status=on_status, stop_on_exit=stop_on_exit, repeat_s=repeat_s,
                            accept_timeout_s=self.timeout_s, target=self.target)

    def decide(self, command_id: str, decision: Decision) -> None:
        self._unary(self._stub.Decide, pb.DecideRequest(command_id=command_id, decision=decision.value))

    # --- test runs and reports -----------------------------------------------------------

    def start_run(self, label: str, notes: str = "") -> str:
        """Open a test run: the commands sent until end_run() belong to it. Returns its id."""
        return self._unary(self._stub.StartRun, pb.StartRunRequest(label=label, notes=notes)).run_id

    def end_run(self, run_id: str) -> None:
        self._unary(self._stub.EndRun, pb.EndRunRequest(run_id=run_id))

    def runs(self, limit: int = 0) -> list[dict[str, Any]]:
        """Test runs, newest first (limit 0: all)."""
        return [message_to_dict(r) for r in self._unary(self._stub.ListRuns, pb.ListRunsRequest(limit=limit)).runs]

    def report(self, run: Optional[str | int] = None, *, frames: bool = False,
               robot: Optional[str] = None) -> dict[str, Any]:
        """The seed's Appendix A table of a run (id, number, or None for the latest) as a
        dict; rates absent for want of data are None. frames=True adds every chord played,
        with its response time and latency, under "frames". robot: one robot of the run (its
        name, as in runs()[i]["robots"]); None: the whole room."""
        request = pb.GetReportRequest(include_frames=frames, robot=robot or "")
        if isinstance(run, int):
            request.run_number = run
        elif run:
            request.run_id = run
        report = message_to_dict(self._unary(self._stub.GetReport, request))
        if not frames:
            report.pop("frames")
        return report

    def robots(self) -> list[dict[str, Any]]:
        """The robots the server drives: name, address (0..7), key_id (empty without a
        key), model, and last_answered_unix_ms (0: no answer since the server started)."""
        return [message_to_dict(r) for r in self._unary(self._stub.ListRobots, pb.ListRobotsRequest()).robots]

    def watch(self, *, spectrum: bool = False, columns_per_s: float = 0.0, bins: int = 0) -> AirWatch:
        """The air as the server puts it there and hears it, as it happens (WatchAir): frames
        played, answers heard and taken, waits for the air, the air busy, commands ended; with
        spectrum=True, the microphone's spectrum in columns (columns_per_s: 0 is 10, at most 50;
        bins: 0 is 128, at most 512). With Client(robot=...), that robot's events and the
        room's. Iterate the AirWatch for dicts (watch.py); cancel() ends it."""
        request = pb.WatchAirRequest(robot=self.robot or "", spectrum=spectrum, columns_per_s=columns_per_s,
                                     bins=bins)
        return AirWatch(self._stub.WatchAir(request, metadata=self._metadata), self.target)

    def receptions(self, run: Optional[str | int] = None, *, limit: int = 0, follow: bool = False) -> AirWatch:
        """What the robots heard and did, from the database: dicts with robot, address, host,
        profile, heard_unix_ms, intact, event ("command", "repeat", "refused", "renewal",
        "sync", "broken", ...), reason, authenticated, reply, command and the velocity set.
        The newest `limit` (0: 100), oldest first, of this client's robot (Client(robot=...))
        or every robot, within a run (id, number) or any time; with follow=True, then each as
        it is stored, until cancel(). Iterate the returned stream."""
        request = pb.ListReceptionsRequest(robot=self.robot or "", limit=limit, follow=follow)
        if isinstance(run, int):
            request.run_number = run
        elif run:
            request.run_id = run
        return AirWatch(self._stub.ListReceptions(request, metadata=self._metadata), self.target,
                        convert=lambda response: message_to_dict(response.reception))

    def health(self) -> str:
        """The server's health: "SERVING" or "NOT_SERVING" (its audio device is gone)."""
        response = self._unary(self._health.Check, health_pb2.HealthCheckRequest(service=""))
        return health_pb2.HealthCheckResponse.ServingStatus.Name(response.status)

    # --- plumbing ------------------------------------------------------------------------

    def _options(self, on_unconfirmed: Optional[Unconfirmed], profile: Optional[str] = None) -> pb.CommandOptions:
        options = pb.CommandOptions()
        if on_unconfirmed is not None:
            options.on_unconfirmed = on_unconfirmed.value
        if profile is not None:
            options.profile = profile
        if self.robot is not None:
            options.robot = self.robot
        return options

    def _command(self, method: Any, request: Any) -> CommandCall:
        call = method(request, metadata=self._metadata)
        return CommandCall(self, call, lambda response: Progress.from_proto(response.progress))

    def _unary(self, method: Any, request: Any) -> Any:
        try:
            return method(request, metadata=self._metadata, timeout=self.timeout_s)
        except grpc.RpcError as e:
            raise errors.from_rpc_error(e, self.target) from None




