-- 004: a run's frames one by one (for plots like the seed's Fig. 14 and 16), matched to
-- receptions by the very same rules as run_report, which now reads its matches from here.
--
--   SELECT * FROM run_frames('…'::uuid);   -- one row per chord the sender played
--   SELECT * FROM run_frames(3);           -- by run number
--
-- run_receptions: the receptions that belong to a run (heard between its start less the
-- clock skew and its end plus after_chord_ms). run_matches: each attempt's first intact
-- reception, each reception given to the latest attempt of the same frame bits whose chord
-- started no more than clock_skew_ms after it was heard and ended no more than
-- after_chord_ms before it (docs/database.md, "The report").

CREATE FUNCTION run_receptions(run uuid,
                               clock_skew_ms double precision DEFAULT 200,
                               after_chord_ms double precision DEFAULT 1000)
RETURNS SETOF receptions
LANGUAGE sql STABLE
AS $$
SELECT r.* FROM receptions r, test_runs t
WHERE t.id = run
  AND r.heard_at BETWEEN t.started_at - make_interval(secs => clock_skew_ms / 1000)
                     AND coalesce(t.ended_at, now()) + make_interval(secs => after_chord_ms / 1000)
$$;

CREATE FUNCTION run_matches(run uuid,
                            clock_skew_ms double precision DEFAULT 200,
                            after_chord_ms double precision DEFAULT 1000)
RETURNS TABLE (attempt_id uuid, reception_id uuid, heard_at timestamptz,
               command_id uuid, "position" integer, chord_started_at timestamptz)
LANGUAGE sql STABLE
AS $$
WITH candidate AS (
  SELECT DISTINCT ON (h.id) a.id AS attempt_id, h.id AS reception_id, h.heard_at,
         a.command_id, a.position, a.chord_started_at
  FROM run_receptions(run, clock_skew_ms, after_chord_ms) h
  JOIN frame_attempts a ON a.run_id = run AND h.crc_ok AND h.frame = a.frame
  WHERE h.heard_at >= a.chord_started_at - make_interval(secs => clock_skew_ms / 1000)
    AND h.heard_at <= coalesce(a.chord_ended_at, a.chord_started_at)
                      + make_interval(secs => after_chord_ms / 1000)
  ORDER BY h.id, a.chord_started_at DESC
)
SELECT DISTINCT ON (attempt_id) * FROM candidate ORDER BY attempt_id, heard_at
$$;

CREATE OR REPLACE FUNCTION run_report(run uuid,
                                      clock_skew_ms double precision DEFAULT 200,
                                      after_chord_ms double precision DEFAULT 1000)
RETURNS SETOF run_report_row
LANGUAGE sql STABLE
AS $$
WITH the_run AS (
  SELECT * FROM test_runs WHERE id = run
),
attempts AS (
  SELECT a.* FROM frame_attempts a WHERE a.run_id = run
),
heard AS (
  SELECT * FROM run_receptions(run, clock_skew_ms, after_chord_ms)
),
matched AS (
  SELECT * FROM run_matches(run, clock_skew_ms, after_chord_ms)
),
counts AS (
  SELECT
    (SELECT count(DISTINCT (command_id, position)) FROM attempts) AS sent,
    (SELECT count(*) FROM attempts) AS attempt_count,
    (SELECT count(*) FROM heard) AS received,
    (SELECT count(*) FROM heard WHERE crc_ok) AS accepted,
    (SELECT count(*) FROM heard WHERE NOT crc_ok) AS rejected,
    (SELECT count(*) FROM heard WHERE reply = 'nack') AS nacks,
    (SELECT count(*) FROM matched) AS matched_receptions,
    (SELECT count(DISTINCT (command_id, position)) FROM matched) AS matched_transmissions,
    (SELECT count(DISTINCT (command_id, position)) FROM attempts WHERE answer = 'ack') AS confirmed
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
  round(latency.avg_ms, 2), round(latency.min_ms, 2), round(latency.max_ms, 2)
FROM the_run, counts c, response, latency
$$;

-- One row per chord the sender played, in the order played. response_time_ms: chord start
-- to the ACK / NACK the sender heard; latency_ms: chord start to the robot's matching
-- reception. Either is NULL when there was none.
CREATE FUNCTION run_frames(run uuid,
                           clock_skew_ms double precision DEFAULT 200,
                           after_chord_ms double precision DEFAULT 1000)
RETURNS TABLE (attempt_id uuid, command_id uuid, command_kind text, "position" integer,
               attempt integer, word integer, frame_bits text, tones_hz real[],
               chord_started_at timestamptz, answer text, response_time_ms numeric,
               heard_at timestamptz, latency_ms numeric)
LANGUAGE sql STABLE
AS $$
SELECT a.id, a.command_id, c.kind, a.position, a.attempt, a.word, frame_bits(a.frame), a.tones_hz,
       a.chord_started_at, a.answer,
       CASE WHEN a.answer IN ('ack', 'nack') AND a.answered_at IS NOT NULL
            THEN round((extract(epoch FROM a.answered_at - a.chord_started_at) * 1000)::numeric, 2) END,
       m.heard_at,
       round((extract(epoch FROM m.heard_at - a.chord_started_at) * 1000)::numeric, 2)
FROM frame_attempts a
LEFT JOIN commands c ON c.id = a.command_id
LEFT JOIN run_matches(run, clock_skew_ms, after_chord_ms) m ON m.attempt_id = a.id
WHERE a.run_id = run
ORDER BY a.chord_started_at, a.attempt
$$;

CREATE FUNCTION run_frames(run_number bigint,
                           clock_skew_ms double precision DEFAULT 200,
                           after_chord_ms double precision DEFAULT 1000)
RETURNS TABLE (attempt_id uuid, command_id uuid, command_kind text, "position" integer,
               attempt integer, word integer, frame_bits text, tones_hz real[],
               chord_started_at timestamptz, answer text, response_time_ms numeric,
               heard_at timestamptz, latency_ms numeric)
LANGUAGE sql STABLE
AS $$ SELECT * FROM run_frames((SELECT id FROM test_runs WHERE number = run_number),
                               clock_skew_ms, after_chord_ms) $$;
