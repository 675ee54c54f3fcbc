-- 013: a joint renewal counts as sent only once it went on air (docs/protocol.md §10,
-- "Renewing leases together").
--
-- A renewal's commands row is written before it goes on air, so that nothing sounds that the
-- log would not show. One that waits for the air when a Teleop stream it renews ends is now
-- cancelled (server/transmitter_renewal.cpp): its row ends 'cancelled', with no frame attempt,
-- and counted among renewals_sent it showed a renewal the robots never heard. renewals_sent
-- now counts the renewals with a frame attempt, as the transmissions are counted.
-- Old rows stay readable: every renewal that went on air has its attempt, and every other
-- figure is computed as in 012.

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
  c.renewals_not_taken
FROM the_run, counts c, response, latency
$$;
