-- 015: what robots heard, as a feed (ListReceptions, dtmfctl heard; issue 60).
--
-- Each reception gets the order it was stored in (stored), so that a reader that follows the
-- feed takes every row once, a row replayed from a spill file after an outage too (its
-- heard_at lies in the past: an order by it would skip it). Each insert is announced on the
-- channel dtmf_receptions with its stored number: a follower LISTENs and reads what is new,
-- rather than asking again and again. An upsert that changes a row already stored (a newer
-- revision) is no new reception, and is not announced.

ALTER TABLE receptions ADD COLUMN stored bigint GENERATED ALWAYS AS IDENTITY;
CREATE UNIQUE INDEX receptions_stored ON receptions (stored);

CREATE FUNCTION announce_reception() RETURNS trigger
LANGUAGE plpgsql
AS $$
BEGIN
  PERFORM pg_notify('dtmf_receptions', NEW.stored::text);
  RETURN NULL;
END
$$;

CREATE TRIGGER receptions_announced AFTER INSERT ON receptions
  FOR EACH ROW EXECUTE FUNCTION announce_reception();
