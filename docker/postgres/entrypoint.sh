#!/usr/bin/env bash
# docker/postgres's entry point, after the official image's: on an empty data directory it
# makes a cluster whose superuser is POSTGRES_USER (default postgres) with POSTGRES_PASSWORD,
# and the database POSTGRES_DB (default: the user's name); then it runs the server as the
# user postgres, listening on every interface of the container. Password authentication
# (scram-sha-256) over TCP, trust on the container's own unix socket (pg_isready, psql).
#   docker-entrypoint.sh postgres [-c name=value ...]    anything else: run as given
set -euo pipefail

if [ "${1:-postgres}" != postgres ] && [ "${1:0:1}" != - ]; then exec "$@"; fi
[ "${1:-}" = postgres ] && shift

user=${POSTGRES_USER:-postgres}
db=${POSTGRES_DB:-$user}
as_postgres() { setpriv --reuid=postgres --regid=postgres --init-groups -- "$@"; }

if [ "$(id -u)" = 0 ]; then
  install -d -o postgres -g postgres -m 700 "$PGDATA"
  chown postgres:postgres "$PGDATA"   # a fresh volume may come owned by root
  install -d -o postgres -g postgres -m 2775 /var/run/postgresql
else
  as_postgres() { "$@"; }
fi

if [ ! -s "$PGDATA/PG_VERSION" ]; then
  if [ -z "${POSTGRES_PASSWORD:-}" ]; then
    echo "postgres: POSTGRES_PASSWORD is empty; set it (the database is reachable over the network)" >&2
    exit 1
  fi
  echo "postgres: a new cluster in $PGDATA (superuser $user, database $db)" >&2
  pwfile=$(mktemp)
  printf '%s\n' "$POSTGRES_PASSWORD" >"$pwfile"
  chown postgres "$pwfile"
  as_postgres initdb -D "$PGDATA" --username="$user" --pwfile="$pwfile" \
    --auth-host=scram-sha-256 --auth-local=trust >/dev/null
  rm -f "$pwfile"
  echo "host all all all scram-sha-256" >>"$PGDATA/pg_hba.conf"
  # The database, with the server on its unix socket only (nothing can connect meanwhile).
  as_postgres pg_ctl -D "$PGDATA" -o "-c listen_addresses=''" -w start >/dev/null
  if [ "$db" != postgres ]; then
    as_postgres psql -v ON_ERROR_STOP=1 -q -U "$user" -d postgres \
      -c "CREATE DATABASE \"${db//\"/\"\"}\"" >/dev/null
  fi
  as_postgres pg_ctl -D "$PGDATA" -m fast -w stop >/dev/null
  echo "postgres: cluster ready" >&2
fi

if [ "$(id -u)" = 0 ]; then
  exec setpriv --reuid=postgres --regid=postgres --init-groups -- postgres -D "$PGDATA" -c listen_addresses='*' "$@"
fi
exec postgres -D "$PGDATA" -c listen_addresses='*' "$@"
