#!/usr/bin/env bash
# Lint, then run the test suite on SQLite and, when PostgreSQL answers, its database tests
# (the Chromium ones among them) on PostgreSQL.
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

echo "== types (mypy: the engine's techniques and skeleton, the stimuli, the analysis)"
.venv/bin/mypy

echo "== layers (import-linter: the packages, and the platform's floors)"
.venv/bin/lint-imports

echo "== migrations are up to date"
env -u DATABASE_URL "$PY" manage.py makemigrations --check --dry-run >/dev/null || {
  echo "Models changed without a migration: run 'python manage.py makemigrations'." >&2
  exit 1
}

pg_url=${DATABASE_URL:-}
if [ -z "$pg_url" ] && "$PY" scripts/port_open.py 127.0.0.1 5432; then
  pg_url=$DEFAULT_PG_URL
fi

if [ $# -gt 0 ]; then
  # Arguments choose the tests: they run on SQLite, then on PostgreSQL if it answers.
  echo "== tests on SQLite: $*"
  env -u DATABASE_URL "${PYTEST[@]}" "$@"
  if [ -n "$pg_url" ]; then
    echo "== the same tests on PostgreSQL ($pg_url)"
    DATABASE_URL=$pg_url SIGNSTUDY_EXPECT_POSTGRES=1 "${PYTEST[@]}" "$@"
  fi
elif [ -n "$pg_url" ]; then
  # Every test runs on SQLite (the demo's database) and the platform's database tests
  # again on PostgreSQL (production's); the Chromium tests, which check what a browser
  # sees and sends, run once, against PostgreSQL. Only tests/studyplatform touches a
  # database (synthesis, stimuli and analysis never import Django); tests/conftest.py
  # sets the markers.
  echo "== tests on SQLite, Chromium's apart"
  env -u DATABASE_URL "${PYTEST[@]}" -m "not browser"
  echo "== database and Chromium tests on PostgreSQL ($pg_url)"
  DATABASE_URL=$pg_url SIGNSTUDY_EXPECT_POSTGRES=1 "${PYTEST[@]}" -m "database or browser"
else
  echo "== tests on SQLite"
  env -u DATABASE_URL "${PYTEST[@]}"
  echo "!! PostgreSQL is not answering on 127.0.0.1:5432 and DATABASE_URL is unset:"
  echo "!! the PostgreSQL run is SKIPPED. CI must not skip it."
fi
