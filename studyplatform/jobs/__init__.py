"""Send the platform's background jobs: queued by name once the write commits, to Celery
with a broker, else to one background process.

The jobs themselves are :mod:`studyplatform.tasks` (Celery finds them by that name).
"""
