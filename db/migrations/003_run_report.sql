-- 003: the seed's test report (its section 10 and Appendix A) for one test run.
--
--   SELECT * FROM run_report(3);          -- by run number
--   SELECT * FROM run_report('…'::uuid);  -- by id
--   SELECT * FROM runs;                   -- what there is
--
-- Every figure is defined in docs/database.md ("The report"). In short: a transmission is a
-- frame of a command as the sender meant it (retransmissions included in it); a reception
-- is matched to the latest attempt of the same frame bits whose chord started no more than
-- clock_skew_ms after it was heard and ended no more than after_chord_ms before it, each
-- attempt taking its first reception only. Receptions belong to the run when heard between
-- its start (less the skew) and its end (plus after_chord_ms).

CREATE TYPE run_report_row AS (
  run_id                       uuid,
  run_number                   bigint,
  label                        text,
  profile                      text,
  started_at                   timestamptz,
  ended_at                     timestamptz,
  transmissions_sent           bigint,
  frame_attempts               bigint,
  transmissions_received       bigint,
  successfully_matched         bigint,
  dropped                      bigint,
  false_positives              bigint,
  false_positive_rate_pct      numeric,
  duplicates                   bigint,
  successful_transmissions     bigint,
  success_rate_pct             numeric,
  sender_confirmed             bigint,
  sender_confirmed_rate_pct    numeric,
  crc_accepted                 bigint,
  crc_rejected                 bigint,
  negative_confirmations_sent  bigint,
  error_catch_rate_pct         numeric,
  response_time_avg_ms         numeric,
  response_time_min_ms         numeric,
  response_time_max_ms         numeric,
  latency_avg_ms               numeric,
  latency_min_ms               numeric,
  latency_max_ms               numeric
);

CREATE FUNCTION run_report(run uuid,
                           clock_skew_ms double precision DEFAULT 200,
                           after_chord_ms double precision DEFAULT 1000)
RETURNS SETOF run_report_row
LANGUAGE sql STABLE
AS $$
WITH the_run AS (
  SELECT * FROM test_runs WHERE id = run
),
slack AS (
  SELECT make_interval(secs => clock_skew_ms / 1000) AS early,
         make_interval(secs => after_chord_ms / 1000) AS late
),
attempts AS (
  SELECT a.* FROM frame_attempts a WHERE a.run_id = run
),
heard AS (
  SELECT r.* FROM receptions r, the_run, slack
  WHERE r.heard_at BETWEEN the_run.started_at - slack.early
                       AND coalesce(the_run.ended_at, now()) + slack.late
),
candidate AS (  -- each intact reception to the latest attempt it can belong to
  SELECT DISTINCT ON (h.id) h.id AS reception_id, h.heard_at, a.id AS attempt_id,
         a.command_id, a.position, a.chord_started_at
  FROM heard h JOIN attempts a ON h.crc_ok AND h.frame = a.frame
  CROSS JOIN slack
  WHERE h.heard_at >= a.chord_started_at - slack.early
    AND h.heard_at <= coalesce(a.chord_ended_at, a.chord_started_at) + slack.late
  ORDER BY h.id, a.chord_started_at DESC
),
matched AS (  -- each attempt keeps its first reception
  SELECT DISTINCT ON (attempt_id) * FROM candidate ORDER BY attempt_id, heard_at
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

CREATE FUNCTION run_report(run_number bigint,
                           clock_skew_ms double precision DEFAULT 200,
                           after_chord_ms double precision DEFAULT 1000)
RETURNS SETOF run_report_row
LANGUAGE sql STABLE
AS $$ SELECT * FROM run_report((SELECT id FROM test_runs WHERE number = run_number),
                               clock_skew_ms, after_chord_ms) $$;

CREATE VIEW runs AS
SELECT r.number, r.id, r.label, r.profile, r.started_at, r.ended_at, r.host,
       (SELECT count(*) FROM commands c WHERE c.run_id = r.id) AS commands,
       (SELECT count(DISTINCT (a.command_id, a.position)) FROM frame_attempts a
         WHERE a.run_id = r.id) AS transmissions_sent
FROM test_runs r
ORDER BY r.number;
