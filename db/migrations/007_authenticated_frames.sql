-- 007: authenticated frames (docs/security.md) — frames of up to 128 bits, whether a frame
-- was authenticated, and why the robot refused one.
--
-- The fast profile's authenticated frame has 80 bits: frame columns become numeric (a
-- bigint holds 62 bits with frame < 2^frame_width still computable), and frame_bits() prints
-- any width. A reception the robot refused — intact, but unauthenticated where it has a key,
-- with a MAC that fails, or an old counter (event 'refused', reason 'authentication'), or a
-- payload it does not know (reason 'payload') — is no accepted frame: it matches no
-- attempt and is no false positive; the report counts refusals, and those for
-- authentication on their own.

ALTER TABLE frame_attempts
  DROP CONSTRAINT frame_attempts_frame_check,
  DROP CONSTRAINT frame_attempts_frame_width_check,
  ALTER COLUMN frame TYPE numeric(39, 0),
  ADD CONSTRAINT frame_attempts_frame_width_check CHECK (frame_width BETWEEN 1 AND 128),
  ADD CONSTRAINT frame_attempts_frame_check CHECK (frame >= 0 AND frame < 2::numeric ^ frame_width),
  ADD COLUMN authenticated boolean NOT NULL DEFAULT false;

ALTER TABLE receptions
  DROP CONSTRAINT receptions_frame_check,
  DROP CONSTRAINT receptions_frame_width_check,
  ALTER COLUMN frame TYPE numeric(39, 0),
  ADD CONSTRAINT receptions_frame_width_check CHECK (frame_width BETWEEN 1 AND 128),
  ADD CONSTRAINT receptions_frame_check CHECK (frame >= 0 AND frame < 2::numeric ^ frame_width),
  ADD COLUMN authenticated boolean NOT NULL DEFAULT false,
  ADD COLUMN reason text CHECK (reason IN ('authentication', 'payload'));

DROP FUNCTION frame_bits(bigint, integer);
-- "0001…1101": `width` bits of a frame, most significant first.
CREATE FUNCTION frame_bits(frame numeric, width integer) RETURNS text
LANGUAGE plpgsql IMMUTABLE STRICT
AS $$
DECLARE
  bits text := '';
  v numeric := frame;
BEGIN
  FOR i IN 1..width LOOP
    bits := (v % 2)::integer::text || bits;
    v := trunc(v / 2);
  END LOOP;
  RETURN bits;
END
$$;

-- As in 005, only frames the robot took: a refused frame belongs to no attempt.
CREATE OR REPLACE FUNCTION run_matches(run uuid,
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
  JOIN frame_attempts a ON a.run_id = run AND h.crc_ok AND h.event IS DISTINCT FROM 'refused'
                           AND h.frame = a.frame AND h.frame_width = a.frame_width
  WHERE h.heard_at >= a.chord_started_at - make_interval(secs => clock_skew_ms / 1000)
    AND h.heard_at <= coalesce(a.chord_ended_at, a.chord_started_at)
                      + make_interval(secs => after_chord_ms / 1000)
  ORDER BY h.id, a.chord_started_at DESC
)
SELECT DISTINCT ON (attempt_id) * FROM candidate ORDER BY attempt_id, heard_at
$$;

ALTER TYPE run_report_row
  ADD ATTRIBUTE refused bigint,
  ADD ATTRIBUTE refused_authentication bigint;

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
    (SELECT count(*) FROM heard WHERE crc_ok AND event IS DISTINCT FROM 'refused') AS accepted,
    (SELECT count(*) FROM heard WHERE NOT crc_ok) AS rejected,
    (SELECT count(*) FROM heard WHERE reply = 'nack') AS nacks,
    (SELECT count(*) FROM matched) AS matched_receptions,
    (SELECT count(DISTINCT (command_id, position)) FROM matched) AS matched_transmissions,
    (SELECT count(DISTINCT (command_id, position)) FROM attempts WHERE answer = 'ack') AS confirmed,
    (SELECT count(*) FROM heard WHERE crc_ok AND event = 'refused') AS refused,
    (SELECT count(*) FROM heard WHERE crc_ok AND event = 'refused' AND reason = 'authentication') AS refused_auth
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
  c.refused_auth
FROM the_run, counts c, response, latency
$$;
