# SignStudy: two commands on a fresh machine.
#   make demo   install everything, load the demo studies, render their clips, serve on
#               127.0.0.1:8000 with gunicorn (deploy/gunicorn.conf.py) and WhiteNoise
#   make test   install everything, lint, run the tests (SQLite, then PostgreSQL if it answers)

PY := .venv/bin/python
HOST ?= 127.0.0.1
PORT ?= 8000

.PHONY: demo test install lock clean

install:
	@bash scripts/bootstrap.sh

test: install
	@bash scripts/test.sh

demo: install
	$(PY) manage.py migrate --noinput
	$(PY) manage.py collectstatic --noinput -v0
	$(PY) manage.py seed_demo --render --workers 2 --url http://$(HOST):$(PORT)/
	$(PY) -m gunicorn -c deploy/gunicorn.conf.py --bind $(HOST):$(PORT) studyplatform.wsgi

# Re-pin the whole dependency tree after changing pyproject.toml.
lock: install
	$(PY) -m pip freeze --exclude-editable | grep -v '^signstudy' > requirements/lock.txt

clean:
	rm -rf .venv var .pytest_cache .ruff_cache
