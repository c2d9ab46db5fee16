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
