-- 014: waits for the air (docs/protocol.md §9, "sharing the air"; issue 59).
--
-- The sender listens before it talks: another's sound, or its own turn-taking, may hold a
-- frame before its chord. How long each attempt waited is now logged with it (air_wait_ms, 0
-- when it went at once) and why (air_wait_reason, as the operator was told: "sound 14 dB over
-- the room's floor", "yielding to another sender", ...; NULL when it did not wait). A
-- command's waits, its frames and retransmissions together, stay within 8.7 s
-- (reliability::kMaxDeferToUnknownMs): a sound that never leaves the air held one for good.
--
-- The report counts them for the commands it covers (stops for every robot never wait, and
-- renewals count for the robots they name): air_waits, the frames (a command's frame, its
-- retransmissions together) that waited at all; air_wait_total_ms, all their waits;
-- air_wait_max_ms, the longest any one command waited, its frames together (NULL when none
-- waited). Old rows stay readable: their air_wait_ms is NULL, counted as no wait, and every
-- other figure is computed as in 013.

ALTER TABLE frame_attempts
  ADD COLUMN air_wait_ms double precision CHECK (air_wait_ms >= 0),
  ADD COLUMN air_wait_reason text;

ALTER TYPE run_report_row
  ADD ATTRIBUTE air_waits bigint,
  ADD ATTRIBUTE air_wait_total_ms numeric,
  ADD ATTRIBUTE air_wait_max_ms numeric;

CREATE OR REPLACE FUNCTION robot_report(run uuid, robot_name text,
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
  WHERE NOT c.every_robot AND c.kind <> 'renewal' AND (robot_name IS NULL OR c.robot = robot_name)
),
in_room AS (
  SELECT h.* FROM run_receptions(run, clock_skew_ms, after_chord_ms) h
  WHERE h.robot_address IN (SELECT robot_address FROM addresses)
     OR (robot_name IS NULL AND (h.robot_address IS NULL OR NOT EXISTS (SELECT 1 FROM addresses)))
),
renewal_frames AS (
  SELECT a.frame, a.frame_width FROM frame_attempts a JOIN run_commands c ON c.id = a.command_id
  WHERE c.kind = 'renewal'
),
-- A joint renewal's frame heard, whatever the robot made of it.
renewals_heard AS (
  SELECT * FROM in_room h
  WHERE h.event = 'renewal'
     OR (h.crc_ok AND EXISTS (SELECT 1 FROM renewal_frames f WHERE f.frame = h.frame AND f.frame_width = h.frame_width))
),
heard AS (
  SELECT * FROM in_room WHERE command IS DISTINCT FROM 'stop every_robot'
                          AND id NOT IN (SELECT id FROM renewals_heard)
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
    (SELECT count(*) FROM in_room WHERE command = 'stop every_robot' AND event = 'command') AS stops_executed,
    (SELECT count(*) FROM run_commands c
      WHERE kind = 'renewal' AND (robot_name IS NULL OR parameters->'robots' ? robot_name)
        AND EXISTS (SELECT 1 FROM frame_attempts a WHERE a.command_id = c.id)) AS renewals_sent,
    (SELECT count(*) FROM in_room WHERE event = 'renewal') AS renewals_executed,
    (SELECT count(*) FROM renewals_heard WHERE event IS DISTINCT FROM 'renewal') AS renewals_not_taken
),
-- Every frame the sender played for the commands covered, for its waits for the air.
air_attempts AS (
  SELECT a.* FROM frame_attempts a JOIN run_commands c ON c.id = a.command_id
  WHERE robot_name IS NULL OR c.robot = robot_name
     OR (c.kind = 'renewal' AND c.parameters->'robots' ? robot_name)
),
air AS (
  SELECT
    (SELECT count(DISTINCT (command_id, position)) FROM air_attempts WHERE air_wait_ms > 0) AS frames,
    (SELECT coalesce(sum(air_wait_ms), 0) FROM air_attempts) AS total_ms,
    (SELECT max(ms) FROM (SELECT sum(air_wait_ms) AS ms FROM air_attempts WHERE air_wait_ms > 0
                          GROUP BY command_id) w) AS max_ms
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
  c.stops_executed,
  c.renewals_sent,
  c.renewals_executed,
  c.renewals_not_taken,
  air.frames,
  round(air.total_ms::numeric, 2),
  round(air.max_ms::numeric, 2)
FROM the_run, counts c, response, latency, air
$$;
