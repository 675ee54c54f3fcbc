-- 010: a room of robots (docs/protocol.md §9; docs/database.md, "A fleet on one database").
--
-- Every row names its robot and its sender, so that several senders and robots share one
-- database and a report can be read per robot or for the whole room:
--   commands.robot, commands.robot_address: the robot a command was for, by the name its
--     sender gives it (ListRobots) and the address its frames carry; NULL in rows from
--     before 010, and for a stop for every robot;
--   commands.every_robot: a stop for every robot in the room (dtmfctl stop --all). No robot
--     answers it, so it ends 'sent', neither confirmed nor failed;
--   commands.host, test_runs.host: the sender (dtmf-server --host; before, always the
--     machine's name), as before;
--   receptions.host: the robot that heard the frame (dtmf-agent --host), as before, and
--     receptions.robot_address its address (dtmf-agent --address).
-- Old rows stay readable: the new columns are NULL (false) in them, and every report below
-- reads them as the one robot of a room.
--
--   SELECT * FROM run_report(3);            -- the whole room, as before
--   SELECT * FROM run_report(3, 'alpha');   -- one robot: its commands, and what robots at its address heard

ALTER TABLE commands
  ADD COLUMN robot text,
  ADD COLUMN robot_address smallint CHECK (robot_address BETWEEN 0 AND 7),
  ADD COLUMN every_robot boolean NOT NULL DEFAULT false,
  DROP CONSTRAINT commands_outcome_check,
  ADD CONSTRAINT commands_outcome_check CHECK (outcome IN ('queued', 'transmitting', 'confirmed', 'continued',
                                                           'failed', 'cancelled', 'sent'));
CREATE INDEX commands_robot ON commands (run_id, robot);

ALTER TABLE receptions
  ADD COLUMN robot_address smallint CHECK (robot_address BETWEEN 0 AND 7);

-- The report's rows say which robot they cover (NULL: the whole room), and count the stops
-- for every robot apart: no robot answers them, so they are no transmissions to confirm,
-- and every robot that hears one executes it.
ALTER TYPE run_report_row
  ADD ATTRIBUTE robot text,
  ADD ATTRIBUTE every_robot_stops_sent bigint,
  ADD ATTRIBUTE every_robot_stops_executed bigint;

-- The report of 009 over one robot's commands (robot_name) or the whole room's (NULL).
-- Receptions count for a robot when heard at its address; for the room, when heard at any
-- address the run's commands went to (a run from before 010, whose commands name no address,
-- keeps every reception, as before). Another sender's robots in the same room are so left
-- out of this run's figures.
CREATE FUNCTION robot_report(run uuid, robot_name text,
                             clock_skew_ms double precision DEFAULT 200,
                             after_chord_ms double precision DEFAULT 1000)
RETURNS SETOF run_report_row
LANGUAGE sql STABLE
AS $$
WITH the_run AS (
  SELECT * FROM test_runs WHERE id = run
),
run_commands AS (
  SELECT * FROM commands c WHERE c.run_id = run
),
addresses AS (
  SELECT DISTINCT robot_address FROM run_commands
  WHERE robot_address IS NOT NULL AND (robot_name IS NULL OR robot = robot_name)
),
attempts AS (
  SELECT a.* FROM frame_attempts a JOIN run_commands c ON c.id = a.command_id
  WHERE NOT c.every_robot AND (robot_name IS NULL OR c.robot = robot_name)
),
in_room AS (
  SELECT h.* FROM run_receptions(run, clock_skew_ms, after_chord_ms) h
  WHERE h.robot_address IN (SELECT robot_address FROM addresses)
     OR (robot_name IS NULL AND (h.robot_address IS NULL OR NOT EXISTS (SELECT 1 FROM addresses)))
),
heard AS (
  SELECT * FROM in_room WHERE command IS DISTINCT FROM 'stop every_robot'
),
matched AS (
  SELECT m.* FROM run_matches(run, clock_skew_ms, after_chord_ms) m
  WHERE m.attempt_id IN (SELECT id FROM attempts) AND m.reception_id IN (SELECT id FROM heard)
),
counts AS (
  SELECT
    (SELECT count(DISTINCT (command_id, position)) FROM attempts) AS sent,
    (SELECT count(*) FROM attempts) AS attempt_count,
    (SELECT count(*) FROM heard) AS received,
    (SELECT count(*) FROM heard WHERE crc_ok AND event IS DISTINCT FROM 'refused') AS accepted,
    (SELECT count(*) FROM heard WHERE NOT crc_ok) AS rejected,
    (SELECT count(*) FROM heard WHERE reply = 'nack') AS nacks,
    (SELECT count(*) FROM matched) AS matched_receptions,
    (SELECT count(DISTINCT (command_id, position)) FROM matched) AS matched_transmissions,
    (SELECT count(DISTINCT (command_id, position)) FROM attempts WHERE answer = 'ack') AS confirmed,
    (SELECT count(*) FROM heard WHERE crc_ok AND event = 'refused') AS refused,
    (SELECT count(*) FROM heard WHERE crc_ok AND event = 'refused' AND reason = 'authentication') AS refused_auth,
    (SELECT count(DISTINCT (command_id, position)) FROM attempts
      WHERE answer = 'ack' AND NOT authenticated) AS confirmed_untagged,
    (SELECT coalesce(max(n), 0) FROM (
       SELECT count(*) OVER (ORDER BY heard_at RANGE BETWEEN interval '60 seconds' PRECEDING AND CURRENT ROW) AS n
       FROM heard WHERE crc_ok AND event = 'refused' AND reason = 'authentication') w) AS refused_auth_peak,
    (SELECT count(*) FROM run_commands WHERE every_robot) AS stops_sent,
    (SELECT count(*) FROM in_room WHERE command = 'stop every_robot' AND event = 'command') AS stops_executed
),
response AS (
  SELECT avg(ms) AS avg_ms, min(ms) AS min_ms, max(ms) AS max_ms
  FROM (SELECT extract(epoch FROM answered_at - chord_started_at) * 1000 AS ms
        FROM attempts WHERE answer IN ('ack', 'nack') AND answered_at IS NOT NULL) t
),
latency AS (
  SELECT avg(ms) AS avg_ms, min(ms) AS min_ms, max(ms) AS max_ms
  FROM (SELECT extract(epoch FROM heard_at - chord_started_at) * 1000 AS ms FROM matched) t
)
SELECT
  the_run.id, the_run.number, the_run.label, the_run.profile, the_run.started_at, the_run.ended_at,
  c.sent,
  c.attempt_count,
  c.received,
  c.matched_transmissions,
  c.sent - c.matched_transmissions,
  c.accepted - c.matched_receptions,
  round(100.0 * (c.accepted - c.matched_receptions) / nullif(c.sent, 0), 2),
  c.matched_receptions - c.matched_transmissions,
  c.matched_transmissions,
  round(100.0 * c.matched_transmissions / nullif(c.sent, 0), 2),
  c.confirmed,
  round(100.0 * c.confirmed / nullif(c.sent, 0), 2),
  c.accepted,
  c.rejected,
  c.nacks,
  round(100.0 * c.rejected / nullif(c.rejected + c.accepted - c.matched_receptions, 0), 2),
  round(response.avg_ms, 2), round(response.min_ms, 2), round(response.max_ms, 2),
  round(latency.avg_ms, 2), round(latency.min_ms, 2), round(latency.max_ms, 2),
  c.refused,
  c.refused_auth,
  c.confirmed_untagged,
  c.refused_auth_peak,
  robot_name,
  c.stops_sent,
  c.stops_executed
FROM the_run, counts c, response, latency
$$;

CREATE OR REPLACE FUNCTION run_report(run uuid,
                                      clock_skew_ms double precision DEFAULT 200,
                                      after_chord_ms double precision DEFAULT 1000)
RETURNS SETOF run_report_row
LANGUAGE sql STABLE
AS $$ SELECT * FROM robot_report(run, NULL, clock_skew_ms, after_chord_ms) $$;

CREATE FUNCTION run_report(run uuid, robot_name text,
                           clock_skew_ms double precision DEFAULT 200,
                           after_chord_ms double precision DEFAULT 1000)
RETURNS SETOF run_report_row
LANGUAGE sql STABLE
AS $$ SELECT * FROM robot_report(run, robot_name, clock_skew_ms, after_chord_ms) $$;

CREATE FUNCTION run_report(run_number bigint, robot_name text,
                           clock_skew_ms double precision DEFAULT 200,
                           after_chord_ms double precision DEFAULT 1000)
RETURNS SETOF run_report_row
LANGUAGE sql STABLE
AS $$ SELECT * FROM robot_report((SELECT id FROM test_runs WHERE number = run_number), robot_name,
                                 clock_skew_ms, after_chord_ms) $$;

-- As in 003, with the robots a run's commands named (by name); its transmissions, as the
-- report's, leave out the stops for every robot.
CREATE OR REPLACE VIEW runs AS
SELECT r.number, r.id, r.label, r.profile, r.started_at, r.ended_at, r.host,
       (SELECT count(*) FROM commands c WHERE c.run_id = r.id) AS commands,
       (SELECT count(DISTINCT (a.command_id, a.position)) FROM frame_attempts a JOIN commands c ON c.id = a.command_id
         WHERE a.run_id = r.id AND NOT c.every_robot) AS transmissions_sent,
       ARRAY(SELECT DISTINCT c.robot FROM commands c WHERE c.run_id = r.id AND c.robot IS NOT NULL
             ORDER BY c.robot) AS robots
FROM test_runs r
ORDER BY r.number;
