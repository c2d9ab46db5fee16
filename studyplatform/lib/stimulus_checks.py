"""A study's stimulus checks (:mod:`synthesis.quality`): read for the admin, run by command.

Each rendered condition's clip is checked from its motion once, by content hash, when it
renders or when ``manage.py check_stimuli`` runs; the Generate page shows what the
checks found and how many clips are not checked yet. Nothing is refused: the researcher
reads the warnings and decides.
"""

from collections.abc import Callable
from dataclasses import dataclass

from stimuli.quality import checked, stored_quality
from studyplatform.lib.stimuli import clip_spec, clips_folder, hashed_pairs, needed_pairs
from studyplatform.models import Condition, Item, Study
from synthesis.quality import Finding


@dataclass(frozen=True)
class StudyChecks:
    """How many of a study's rendered clips are checked, and what the checks found."""

    checked: int
    unchecked: int
    warnings: tuple[tuple[Condition, Item, Finding], ...]

    def lines(self) -> list[str]:
        """Return one line per warning: condition × item: what is wrong."""
        return [f"{c.key} × {i.key}: {f.message}" for c, i, f in self.warnings]


def _rendered(study: Study) -> list[tuple[Condition, Item, str]]:
    """Return the study's rendered (not uploaded) clips with their content hashes."""
    return [t for t in hashed_pairs(needed_pairs(study)) if not t[0].is_uploaded]


def stored_checks(hashed: list[tuple[Condition, Item, str]]) -> StudyChecks:
    """Return the checks already made of the rendered clips among *hashed* (none is run)."""
    folder, found, unchecked = clips_folder(), [], 0
    for condition, item, content_hash in hashed:
        if condition.is_uploaded:
            continue
        quality = stored_quality(folder, content_hash)
        if quality is None:
            unchecked += 1
            continue
        found.append((condition, item, quality))
    return _summary(found, unchecked)


def run_checks(study: Study, progress: Callable[[int, int], None] | None = None) -> StudyChecks:
    """Check every rendered clip of *study* not checked yet (from its motion) and return all."""
    folder, found = clips_folder(), []
    clips = _rendered(study)
    for done, (condition, item, content_hash) in enumerate(clips, 1):
        found.append((condition, item, checked(clip_spec(condition, item), folder, content_hash)))
        if progress is not None:
            progress(done, len(clips))
    return _summary(found, 0)


def _summary(found, unchecked: int) -> StudyChecks:
    warnings = tuple((c, i, f) for c, i, quality in found for f in quality.findings)
    return StudyChecks(len(found), unchecked, warnings)
