-- 008: velocity commands (live teleop, docs/protocol.md §10 "Velocity and its lease").
--
-- A teleop session sends one command per frame: kind 'velocity', with the fractions of the
-- robot's limits and the lease it asked for in parameters, e.g.
-- {"linear_fraction": 0.5, "angular_fraction": -0.1, "lease_s": 1.0}. Each is a command of
-- one frame like any other, so run_report() counts a teleop session's frames unchanged.

ALTER TABLE commands
  DROP CONSTRAINT commands_kind_check,
  ADD CONSTRAINT commands_kind_check CHECK (kind IN ('reset', 'drive_for_duration', 'turn_for_duration',
                                                     'drive_forward', 'turn', 'stop', 'word', 'velocity'));
