-- 005: the fast profile's frames (docs/protocol.md §10) in the same tables as the seed's.
--
-- A fast frame is 48 bits (sequence number, command, CRC-16) and carries no 12-bit word, so
-- frame columns widen to bigint, frame_attempts.word may be NULL, and each row says how many
-- bits its frame has (frame_width), for printing it. Receptions still match attempts by
-- equal frame bits (003): a fast frame's sequence number and CRC make equal bits the same frame.

ALTER TABLE frame_attempts
  DROP CONSTRAINT frame_attempts_frame_check,
  ALTER COLUMN frame TYPE bigint,
  ALTER COLUMN word DROP NOT NULL,
  ADD COLUMN frame_width integer NOT NULL DEFAULT 16 CHECK (frame_width IN (16, 48)),
  ADD CONSTRAINT frame_attempts_frame_check CHECK (frame >= 0 AND frame < (1::bigint << frame_width)),
  ADD CONSTRAINT frame_attempts_word_when_seed CHECK ((word IS NOT NULL) = (frame_width = 16));

ALTER TABLE receptions
  DROP CONSTRAINT receptions_frame_check,
  ALTER COLUMN frame TYPE bigint,
  ADD COLUMN frame_width integer NOT NULL DEFAULT 16 CHECK (frame_width IN (16, 48)),
  ADD CONSTRAINT receptions_frame_check CHECK (frame >= 0 AND frame < (1::bigint << frame_width));

-- As in 004, and a frame matches only a frame of its own width.
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
  JOIN frame_attempts a ON a.run_id = run AND h.crc_ok AND h.frame = a.frame AND h.frame_width = a.frame_width
  WHERE h.heard_at >= a.chord_started_at - make_interval(secs => clock_skew_ms / 1000)
    AND h.heard_at <= coalesce(a.chord_ended_at, a.chord_started_at)
                      + make_interval(secs => after_chord_ms / 1000)
  ORDER BY h.id, a.chord_started_at DESC
)
SELECT DISTINCT ON (attempt_id) * FROM candidate ORDER BY attempt_id, heard_at
$$;

-- "0001…1101": `width` bits of a frame.
CREATE FUNCTION frame_bits(frame bigint, width integer) RETURNS text
LANGUAGE sql IMMUTABLE STRICT
AS $$ SELECT right((frame::bit(64))::text, width) $$;

CREATE OR REPLACE FUNCTION run_frames(run uuid,
                           clock_skew_ms double precision DEFAULT 200,
                           after_chord_ms double precision DEFAULT 1000)
RETURNS TABLE (attempt_id uuid, command_id uuid, command_kind text, "position" integer,
               attempt integer, word integer, frame_bits text, tones_hz real[],
               chord_started_at timestamptz, answer text, response_time_ms numeric,
               heard_at timestamptz, latency_ms numeric)
LANGUAGE sql STABLE
AS $$
SELECT a.id, a.command_id, c.kind, a.position, a.attempt, a.word, frame_bits(a.frame, a.frame_width), a.tones_hz,
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
