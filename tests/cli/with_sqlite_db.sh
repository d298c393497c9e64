#!/bin/sh
# with_sqlite_db.sh FILE [--fresh] -- CMD ARGS...: runs CMD with SRP_DB=FILE, the SQLite
# side of the command-line tests that run on both backends (srp_pg_sandbox --cluster is the
# PostgreSQL side). --fresh removes the file (and its -wal/-shm) first.
db=$1
shift
if [ "${1:-}" = "--fresh" ]; then
  rm -f "$db" "$db-wal" "$db-shm" "$db-journal"
  shift
fi
[ "${1:-}" = "--" ] && shift
SRP_DB=$db
export SRP_DB
exec "$@"
