-- 002: the one entry point the programs write through.
--
-- store_rows takes a JSON array of {"table": name, "row": {column: value, ...}} and upserts
-- each row by its id, only the columns the row names, and only when its revision is newer
-- than the stored one. So a batch can be replayed any number of times, in any order, and
-- the newest state of each row wins: what the store library's spill-and-replay relies on.
-- Returns how many rows were inserted or updated.

CREATE FUNCTION store_rows(batch jsonb) RETURNS integer
LANGUAGE plpgsql
AS $$
DECLARE
  item     jsonb;
  tbl      text;
  cols     text;
  changed  integer := 0;
  n        integer;
BEGIN
  FOR item IN SELECT * FROM jsonb_array_elements(batch) LOOP
    tbl := item->>'table';
    IF tbl IS NULL OR tbl NOT IN ('test_runs', 'commands', 'frame_attempts', 'receptions') THEN
      RAISE EXCEPTION 'store_rows: unknown table %', coalesce(tbl, '(none)');
    END IF;
    IF NOT (item->'row' ? 'id' AND item->'row' ? 'revision') THEN
      RAISE EXCEPTION 'store_rows: a % row needs id and revision', tbl;
    END IF;
    SELECT string_agg(quote_ident(key), ', ' ORDER BY key) INTO cols
      FROM jsonb_object_keys(item->'row') AS key
      WHERE key IN (SELECT column_name FROM information_schema.columns
                    WHERE table_schema = current_schema() AND table_name = tbl);
    EXECUTE format(
      'INSERT INTO %1$I (%2$s) SELECT %2$s FROM jsonb_populate_record(NULL::%1$I, $1) '
      'ON CONFLICT (id) DO UPDATE SET (%2$s) = ROW(%3$s) WHERE %1$I.revision < EXCLUDED.revision',
      tbl, cols,
      (SELECT string_agg('EXCLUDED.' || quote_ident(key), ', ' ORDER BY key)
         FROM jsonb_object_keys(item->'row') AS key
         WHERE key IN (SELECT column_name FROM information_schema.columns
                       WHERE table_schema = current_schema() AND table_name = tbl)))
      USING item->'row';
    GET DIAGNOSTICS n = ROW_COUNT;
    changed := changed + n;
  END LOOP;
  RETURN changed;
END
$$;
