"""Measure the data layer: study import time and single-save latency of do_save_response.

Prints figures, asserts nothing. Uses a throwaway test database on whatever
DATABASE_URL points at (SQLite by default):

    .venv/bin/python bench/bench_responses.py
    DATABASE_URL=postgres://postgres@127.0.0.1:5432/signstudy \\
        .venv/bin/python bench/bench_responses.py
"""

import os
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
os.environ.setdefault("DJANGO_SETTINGS_MODULE", "studyplatform.settings")

import django

django.setup()

from database import throwaway_database  # noqa: E402
from django.contrib.auth import get_user_model  # noqa: E402  (needs django.setup())
from django.db import connection  # noqa: E402

PARTICIPANTS = 50


def percentile(values: list[float], fraction: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(fraction * len(ordered)))]


def main() -> None:
    from studyplatform.actions import (
        Answer,
        do_enroll_participant,
        do_import_study,
        do_save_response,
    )
    from studyplatform.demo import fingerspelling_timing_study
    from studyplatform.lib.exchange import export_study

    owner = get_user_model().objects.create_user("bench")
    started = time.perf_counter()
    study = do_import_study(fingerspelling_timing_study(), owner=owner).study
    import_ms = (time.perf_counter() - started) * 1000
    started = time.perf_counter()
    export_study(study)
    export_ms = (time.perf_counter() - started) * 1000

    trials = [
        (trial, trial.questions.get())
        for trial in study.trials.filter(kind="pairwise").prefetch_related("questions")
    ]
    new_ms, repeat_ms = [], []
    for number in range(PARTICIPANTS):
        participant = do_enroll_participant(study)
        for trial, question in trials:
            answer = Answer(choice_position=1 + number % 2, rt_ms=1000)
            started = time.perf_counter()
            do_save_response(participant, trial, question, answer)
            new_ms.append((time.perf_counter() - started) * 1000)
            started = time.perf_counter()
            do_save_response(participant, trial, question, answer)
            repeat_ms.append((time.perf_counter() - started) * 1000)

    print(f"database: {connection.vendor}")
    print(f"import demo study (51 trials): {import_ms:.1f} ms; export: {export_ms:.1f} ms")
    for label, values in (("first save", new_ms), ("repeated save", repeat_ms)):
        print(
            f"{label}: n={len(values)} median {statistics.median(values):.2f} ms, "
            f"p95 {percentile(values, 0.95):.2f} ms, "
            f"throughput {1000 / statistics.mean(values):.0f} saves/s (one client)"
        )


if __name__ == "__main__":
    with throwaway_database():
        main()
