"""The clinic's archive on PostgreSQL: its schema, roles and grants (``archive init``).

Append-only by the server, not by convention: the group role ``pdcp_fitter`` may insert
entries and read, ``pdcp_reader`` only read; neither may update or delete an entry, and a
trigger refuses UPDATE, DELETE and TRUNCATE of entries to every role, the owner too. The
insert trigger (run with the owner's rights) takes the archive's advisory lock, refuses an
entry that does not follow the last one (id + 1, its hash as previous hash: no fork), refuses
an operator other than the signed-in role (its full name from ``pdcp.operators`` where
given) and moves the head record. Logins are roles the clinic's administrator makes members
of one group (``CREATE ROLE anna LOGIN PASSWORD '…' IN ROLE pdcp_fitter``).
"""

from __future__ import annotations

#: The advisory lock every append holds (session-wide key; "pdcp" in ASCII).
APPEND_LOCK = 0x70646370

SCHEMA = "pdcp"
FITTER = "pdcp_fitter"
READER = "pdcp_reader"

#: Statements of ``archive init``, run in one transaction; each can run again.
INIT_SQL: tuple[str, ...] = (
    f"""DO $$ BEGIN
  IF NOT EXISTS (SELECT FROM pg_roles WHERE rolname = '{READER}') THEN
    CREATE ROLE {READER} NOLOGIN;
  END IF;
  IF NOT EXISTS (SELECT FROM pg_roles WHERE rolname = '{FITTER}') THEN
    CREATE ROLE {FITTER} NOLOGIN IN ROLE {READER};
  END IF;
END $$""",
    f"GRANT {READER} TO {FITTER}",  # a fitter reads too (roles made before init included)
    f"CREATE SCHEMA IF NOT EXISTS {SCHEMA}",
    f"""CREATE TABLE IF NOT EXISTS {SCHEMA}.entries (
  id bigint PRIMARY KEY,
  previous_hash text NOT NULL,
  hash text NOT NULL UNIQUE,
  body text NOT NULL,
  patient text GENERATED ALWAYS AS ((body::jsonb) ->> 'patient') STORED,
  devices jsonb GENERATED ALWAYS AS ((body::jsonb) -> 'devices') STORED,
  origin_hash text GENERATED ALWAYS AS ((body::jsonb) -> 'origin' ->> 'hash') STORED,
  recorded_by name NOT NULL DEFAULT session_user,
  recorded_at timestamptz NOT NULL DEFAULT now()
)""",
    f"CREATE INDEX IF NOT EXISTS entries_patient ON {SCHEMA}.entries (patient)",
    f"CREATE INDEX IF NOT EXISTS entries_devices ON {SCHEMA}.entries "
    "USING gin (devices jsonb_path_ops)",
    f"CREATE INDEX IF NOT EXISTS entries_origin ON {SCHEMA}.entries (origin_hash)",
    f"""CREATE TABLE IF NOT EXISTS {SCHEMA}.head (
  one int PRIMARY KEY CHECK (one = 1),
  last_id bigint NOT NULL,
  last_hash text NOT NULL
)""",
    f"""CREATE TABLE IF NOT EXISTS {SCHEMA}.pending (
  token text PRIMARY KEY,
  pid int NOT NULL,
  host text NOT NULL,
  backend int NOT NULL DEFAULT pg_backend_pid(),
  role name NOT NULL DEFAULT session_user,
  created timestamptz NOT NULL DEFAULT now(),
  body text NOT NULL
)""",
    f"""CREATE TABLE IF NOT EXISTS {SCHEMA}.operators (
  role name PRIMARY KEY,
  full_name text NOT NULL
)""",
    f"""CREATE OR REPLACE FUNCTION {SCHEMA}.refuse_change() RETURNS trigger
LANGUAGE plpgsql AS $$
BEGIN
  RAISE EXCEPTION 'the fitting history is append-only: % of an entry is refused', TG_OP
    USING ERRCODE = 'insufficient_privilege';
END $$""",
    f"""CREATE OR REPLACE FUNCTION {SCHEMA}.entries_insert() RETURNS trigger
LANGUAGE plpgsql SECURITY DEFINER SET search_path = pg_catalog, {SCHEMA} AS $$
DECLARE
  last_id bigint;
  last_hash text;
  doc jsonb := NEW.body::jsonb;
  who text := coalesce((SELECT full_name FROM {SCHEMA}.operators
                        WHERE role = session_user), session_user::text);
BEGIN
  PERFORM pg_advisory_xact_lock({APPEND_LOCK});
  SELECT e.id, e.hash INTO last_id, last_hash FROM {SCHEMA}.entries e
    ORDER BY e.id DESC LIMIT 1;
  IF NEW.id <> coalesce(last_id, 0) + 1
     OR NEW.previous_hash <> coalesce(last_hash, repeat('0', 64)) THEN
    RAISE EXCEPTION 'entry % does not follow entry % of the fitting history (a fork is refused)',
      NEW.id, coalesce(last_id, 0) USING ERRCODE = 'serialization_failure';
  END IF;
  IF jsonb_typeof(doc -> 'origin') = 'object' THEN
    IF doc -> 'origin' ->> 'imported_by' IS DISTINCT FROM session_user::text THEN
      RAISE EXCEPTION 'an imported entry must name the signed-in role % as its importer',
        session_user USING ERRCODE = 'insufficient_privilege';
    END IF;
  ELSIF doc ->> 'signed_in' IS DISTINCT FROM session_user::text
        OR doc ->> 'operator' IS DISTINCT FROM who THEN
    RAISE EXCEPTION 'the operator recorded must be the signed-in role % (%)', session_user, who
      USING ERRCODE = 'insufficient_privilege';
  END IF;
  NEW.recorded_by := session_user;
  NEW.recorded_at := now();
  INSERT INTO {SCHEMA}.head (one, last_id, last_hash) VALUES (1, NEW.id, NEW.hash)
    ON CONFLICT (one) DO UPDATE SET last_id = EXCLUDED.last_id, last_hash = EXCLUDED.last_hash;
  RETURN NEW;
END $$""",
    f"DROP TRIGGER IF EXISTS entries_append_only ON {SCHEMA}.entries",
    f"""CREATE TRIGGER entries_append_only BEFORE UPDATE OR DELETE ON {SCHEMA}.entries
FOR EACH ROW EXECUTE FUNCTION {SCHEMA}.refuse_change()""",
    f"DROP TRIGGER IF EXISTS entries_no_truncate ON {SCHEMA}.entries",
    f"""CREATE TRIGGER entries_no_truncate BEFORE TRUNCATE ON {SCHEMA}.entries
FOR EACH STATEMENT EXECUTE FUNCTION {SCHEMA}.refuse_change()""",
    f"DROP TRIGGER IF EXISTS entries_chain ON {SCHEMA}.entries",
    f"""CREATE TRIGGER entries_chain BEFORE INSERT ON {SCHEMA}.entries
FOR EACH ROW EXECUTE FUNCTION {SCHEMA}.entries_insert()""",
    f"REVOKE ALL ON ALL TABLES IN SCHEMA {SCHEMA} FROM PUBLIC",
    f"REVOKE ALL ON FUNCTION {SCHEMA}.entries_insert() FROM PUBLIC",
    f"GRANT USAGE ON SCHEMA {SCHEMA} TO {READER}",
    f"GRANT SELECT ON {SCHEMA}.entries, {SCHEMA}.head, {SCHEMA}.operators TO {READER}",
    f"GRANT INSERT ON {SCHEMA}.entries TO {FITTER}",
    f"GRANT SELECT, INSERT, DELETE ON {SCHEMA}.pending TO {FITTER}",
)
