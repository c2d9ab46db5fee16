"""Measure the researcher's new pages: design builder, summary, identical-clip check,
and the tidy export with per-trial quality data.

Issue 20 names no target; the figures say whether the pages stay interactive at the size
of seed 000's study (4 conditions × 8 words, 48 comparisons + practice + a check) and
what the quality columns add to an export of many participants' media events. Prints
figures, asserts nothing. Uses a throwaway test database (SQLite unless DATABASE_URL):

    .venv/bin/python bench/bench_design.py [--participants 100]
"""

import argparse
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
from machine import timed_ms  # noqa: E402

WORDS = ("GUITAR", "HEAVEN", "ARREST", "ELEPHANT", "PSYCHIATRY", "DAVID", "MICHAEL", "VICTOR")


def _events(participant, study) -> list:
    """Return what a careful participant's browser logs: per page shown, two clips played
    to their end (one replayed), about 7 events a page, on the browser's clock."""
    from studyplatform.models import MediaEvent, Trial

    trials = {t.key: t for t in Trial.objects.filter(study=study)}
    events, clock = [], 1_700_000_000_000
    for entry in participant.schedule:
        trial = trials[entry["trial"]]
        rows = [("page_shown", None), ("play", 1), ("ended", 1), ("play", 2), ("ended", 2)]
        if trial.condition_b_id:
            rows += [("play", 1), ("ended", 1)]
        for kind, clip in rows:
            clock += 1500
            events.append(
                MediaEvent(
                    participant=participant,
                    trial=trial,
                    kind=kind,
                    clip_position=clip,
                    client_time_ms=clock,
                    detail={"width": 1280, "height": 800},
                )
            )
    return events


def main(participants: int) -> None:
    from stimuli.plan import Design, DesignSpec
    from studyplatform.actions import (
        Answer,
        do_enroll_participant,
        do_import_study,
        do_save_response,
    )
    from studyplatform.actions.design import do_build_design
    from studyplatform.demo import fingerspelling_timing_study
    from studyplatform.lib.design import summarize_design
    from studyplatform.lib.export import tidy_csv
    from studyplatform.lib.quality import study_quality
    from studyplatform.lib.stimuli import identical_clips
    from studyplatform.models import MediaEvent, Study

    owner = get_user_model().objects.create_user("bench")
    study = do_import_study(fingerspelling_timing_study(), owner=owner, status="draft").study
    # The builder makes the comparisons and practice the demo definition spells out.
    study.trials.filter(block__key__in=["comparisons", "practice"]).delete()
    study.blocks.filter(key__in=["comparisons", "practice"]).delete()
    conditions = tuple(study.conditions.values_list("key", flat=True))
    questions = list(study.questions.filter(key="most-natural"))
    example = study.items.get(is_practice=True).key  # the demo's practice word
    spec = DesignSpec(Design.BALANCED_PAIRS, conditions, WORDS, practice_items=(example,), seed=1)
    build_ms, built = timed_ms(lambda: do_build_design(study, spec, questions))
    study.refresh_from_db()
    summary_ms, summary = timed_ms(lambda: summarize_design(study))
    identical_ms, _ = timed_ms(lambda: identical_clips(study))
    print(f"database: {connection.vendor}")
    print(
        f"design builder, {built.pages} pages (4 conditions × 8 words, balanced): "
        f"{build_ms:.0f} ms (median of 5 rebuilds)"
    )
    print(f"design summary ({summary.pages} pages a participant): {summary_ms:.0f} ms")
    print(f"identical-clip check (32 clip specifications): {identical_ms:.0f} ms")

    Study.objects.filter(pk=study.pk).update(status="open")
    study.refresh_from_db()
    started = time.perf_counter()
    for number in range(participants):
        participant = do_enroll_participant(study, consented=True)
        for trial in study.trials.filter(kind="pairwise").prefetch_related("questions"):
            for question in trial.questions.all():
                do_save_response(
                    participant, trial, question, Answer(choice_position=1 + number % 2, rt_ms=9000)
                )
        MediaEvent.objects.bulk_create(_events(participant, study), batch_size=2000)
    setup_s = time.perf_counter() - started
    events = MediaEvent.objects.filter(participant__study=study).count()
    quality_ms, _ = timed_ms(lambda: study_quality(study), repeat=3)
    export_ms, text = timed_ms(lambda: tidy_csv(study), repeat=3)
    rows = text.count("\n") - 1
    print(
        f"{participants} participants, {rows} answer rows, {events} media events "
        f"(set up in {setup_s:.0f} s)"
    )
    print(
        f"tidy CSV with quality columns: {export_ms:.0f} ms "
        f"({1000 * rows / export_ms:.0f} rows/s); of which the quality data "
        f"{quality_ms:.0f} ms ({100 * quality_ms / export_ms:.0f} %, "
        f"{1000 * events / quality_ms:.0f} events/s)"
    )


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--participants", type=int, default=100)
    arguments = parser.parse_args()
    with throwaway_database():
        main(arguments.participants)
