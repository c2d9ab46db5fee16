"""Read untrusted files confined: a child process with limits, no network, few files.

:func:`run_task` runs one of the engine's readers on a file's bytes
(:mod:`studyplatform.confine.worker`); :func:`confined_run` runs a program (ffmpeg) on
files the caller names. Both answer :class:`ConfinedError` for a refused file or a limit
reached. See :mod:`studyplatform.confine.runner`.
"""

from studyplatform.confine.runner import (
    CAPTURE,
    MEDIA,
    PARSE,
    ConfinedError,
    Limits,
    confined_run,
    confinement_status,
    run_task,
)

__all__ = [
    "CAPTURE",
    "MEDIA",
    "PARSE",
    "ConfinedError",
    "Limits",
    "confined_run",
    "confinement_status",
    "run_task",
]
