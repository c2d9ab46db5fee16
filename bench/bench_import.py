"""Measure a study import, which is one transaction since issue 57.

On SQLite a transaction holds the one write lock, so a participant's save that arrives
during an import waits for it (up to the 20 s busy timeout, never refused); on
PostgreSQL saves to other rows do not wait. The figures say how long that can be: the
demo's fingerspelling study, then with 1,000 and 5,000 extra conditions. Prints figures,
asserts nothing. Uses a throwaway test database (SQLite unless DATABASE_URL):

    .venv/bin/python bench/bench_import.py
"""

import os
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
sys.path.insert(0, str(Path(__file__).resolve().parent))
os.environ.setdefault("DJANGO_SETTINGS_MODULE", "studyplatform.settings")

import django

django.setup()

from database import throwaway_database  # noqa: E402
from django.contrib.auth import get_user_model  # noqa: E402  (needs django.setup())
from django.db import connection  # noqa: E402
from machine import describe  # noqa: E402


def main() -> None:
    from studyplatform.actions import do_import_study
    from studyplatform.demo import fingerspelling_timing_study

    owner = get_user_model().objects.create_user("bench")
    print(describe())
    print(f"database: {connection.vendor}")
    for extra in (0, 1000, 5000):
        data = fingerspelling_timing_study()
        template = data["conditions"][0]
        data["conditions"] += [
            {**template, "key": f"extra-{n}", "label": f"Extra {n}"} for n in range(extra)
        ]
        rows = sum(len(value) for value in data.values() if isinstance(value, list))
        started = time.perf_counter()
        do_import_study(data, owner=owner, slug=f"bench-{extra}")
        seconds = time.perf_counter() - started
        print(
            f"import of {rows} rows ({len(data['conditions'])} conditions): {seconds:.2f} s "
            f"in one transaction ({rows / seconds:.0f} rows/s)"
        )


if __name__ == "__main__":
    with throwaway_database():
        main()
