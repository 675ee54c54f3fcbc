-- 006: frames of any width up to 62 bits (docs/protocol.md §10).
--
-- The fast profile's frame grew from 48 to 50 bits (a robot address before the sequence
-- number), and its reserve holds frame kinds of other sizes. 005 allowed exactly 16 or 48;
-- a 50-bit row was refused by PostgreSQL and ended in the spill's .rejected file. The bound
-- is what a bigint holds with frame < 2^frame_width still computable: 62 bits.

ALTER TABLE frame_attempts
  DROP CONSTRAINT frame_attempts_frame_width_check,
  ADD CONSTRAINT frame_attempts_frame_width_check CHECK (frame_width BETWEEN 1 AND 62);

ALTER TABLE receptions
  DROP CONSTRAINT receptions_frame_width_check,
  ADD CONSTRAINT receptions_frame_width_check CHECK (frame_width BETWEEN 1 AND 62);
