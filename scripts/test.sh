#!/usr/bin/env bash
# Lint, then run the test suite on SQLite and, when PostgreSQL answers, its database tests
# on PostgreSQL too.
set -euo pipefail
cd "$(dirname "$0")/.."
PY=.venv/bin/python
DEFAULT_PG_URL=postgres://postgres@127.0.0.1:5432/signstudy
# Tests run in this many processes (pytest-xdist), a file's tests in one of them: the
# browser, worker and render tests spend much of their time waiting, so two processes
# finish in about 60 % of one's time even on two cores. SIGNSTUDY_TEST_WORKERS=0 runs
# everything in this process.
WORKERS=${SIGNSTUDY_TEST_WORKERS:-2}
PYTEST=("$PY" -m pytest --durations=10)
if [ "$WORKERS" != 0 ]; then
  PYTEST+=(-n "$WORKERS" --dist loadfile)
fi

echo "== ruff"
.venv/bin/ruff check .
.venv/bin/ruff format --check .

echo "== migrations are up to date"
env -u DATABASE_URL "$PY" manage.py makemigrations --check --dry-run >/dev/null || {
  echo "Models changed without a migration: run 'python manage.py makemigrations'." >&2
  exit 1
}

pg_url=${DATABASE_URL:-}
if [ -z "$pg_url" ] && "$PY" scripts/port_open.py 127.0.0.1 5432; then
  pg_url=$DEFAULT_PG_URL
fi

echo "== tests on SQLite"
env -u DATABASE_URL "${PYTEST[@]}" "$@"

if [ -n "$pg_url" ]; then
  # Only tests/studyplatform touches a database (synthesis, stimuli and analysis never
  # import Django), so by default only it runs again; arguments choose otherwise.
  targets=("$@")
  [ ${#targets[@]} -eq 0 ] && targets=(tests/studyplatform)
  echo "== database tests on PostgreSQL ($pg_url): ${targets[*]}"
  DATABASE_URL=$pg_url SIGNSTUDY_EXPECT_POSTGRES=1 "${PYTEST[@]}" "${targets[@]}"
else
  echo "!! PostgreSQL is not answering on 127.0.0.1:5432 and DATABASE_URL is unset:"
  echo "!! the PostgreSQL run is SKIPPED. CI must not skip it."
fi
