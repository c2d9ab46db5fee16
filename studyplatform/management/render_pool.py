"""Render stimuli in local worker processes when no Celery broker is configured.

Kept free of Django imports at module level: a spawned process imports this module to
find its function before Django is set up.
"""

import os


def setup() -> None:
    """Set Django up in a fresh worker process (the pool's initializer)."""
    os.environ.setdefault("DJANGO_SETTINGS_MODULE", "studyplatform.settings")
    import django

    django.setup()


def render(stimulus_id: int) -> str:
    """Render one stimulus in this process; return its final status."""
    from django.db import connection

    from studyplatform.tasks import render_now

    try:
        return render_now(stimulus_id)
    finally:
        connection.close()


def expected_cost(parameters: dict) -> float:
    """Return a clip's rough rendering cost, for ordering only: its text's length, a
    sentence's character weighing 0.4 of a fingerspelled letter (in the demo a letter
    lasts about 35 frames, a sentence's character about 10, and an upper-body frame
    takes 1.5 times a hand close-up's)."""
    text = str(parameters.get("text", ""))
    return len(text) * (0.4 if parameters.get("kind") == "sentence" else 1.0)


def render_many(stimulus_ids, workers: int, report=None) -> list[str]:
    """Render the stimuli of *stimulus_ids* not ready yet in *workers* processes, longest
    first (a long clip left for last would keep one process busy while the others wait);
    call ``report(number, total, status)`` after each; return their statuses."""
    from concurrent.futures import ProcessPoolExecutor
    from multiprocessing import get_context

    from studyplatform.models import Stimulus

    pending = (
        Stimulus.objects.filter(pk__in=list(stimulus_ids))
        .exclude(status=Stimulus.Status.READY)
        .exclude(condition__source="uploaded")
        .values_list("pk", "parameters")
    )
    order = [pk for pk, _ in sorted(pending, key=lambda row: -expected_cost(row[1]))]
    statuses = []
    if workers <= 1 or len(order) <= 1:
        results = map(render, order)
    else:
        pool = ProcessPoolExecutor(
            min(workers, len(order)), mp_context=get_context("spawn"), initializer=setup
        )
        results = pool.map(render, order)
    try:
        for number, status in enumerate(results, start=1):
            statuses.append(status)
            if report is not None:
                report(number, len(order), status)
    finally:
        if workers > 1 and len(order) > 1:
            pool.shutdown()
    return statuses
