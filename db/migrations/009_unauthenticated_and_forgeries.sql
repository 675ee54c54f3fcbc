-- 009: what a keyed sender and a keyed robot must not hide (docs/security.md).
--
-- sender_confirmed_unauthenticated: transmissions confirmed by an untagged ACK — the answer
-- to a frame without a MAC (the seed profile's, or any frame of a sender without a key), a
-- fixed chord that anyone within earshot can play. A keyed sender sends such frames only
-- with --allow-unauthenticated-commands; this column keeps them apart from keyed
-- confirmations.
-- refused_authentication_peak_per_minute: the most frames refused for authentication in any
-- 60 s of the run: a burst of forgeries, or a sender under another key. The robot also logs
-- a warning once a burst reaches 10 a minute.
-- run_report() is the one of 007 with these two columns added at the end.

ALTER TYPE run_report_row
  ADD ATTRIBUTE sender_confirmed_unauthenticated bigint,
  ADD ATTRIBUTE refused_authentication_peak_per_minute bigint;

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
    (SELECT count(*) FROM heard WHERE crc_ok AND event = 'refused' AND reason = 'authentication') AS refused_auth,
    (SELECT count(DISTINCT (command_id, position)) FROM attempts
      WHERE answer = 'ack' AND NOT authenticated) AS confirmed_untagged,
    (SELECT coalesce(max(n), 0) FROM (
       SELECT count(*) OVER (ORDER BY heard_at RANGE BETWEEN interval '60 seconds' PRECEDING AND CURRENT ROW) AS n
       FROM heard WHERE crc_ok AND event = 'refused' AND reason = 'authentication') w) AS refused_auth_peak
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
  c.refused_auth_peak
FROM the_run, counts c, response, latency
$$;
