"""A clip's stimulus check, kept beside its files: ``<hash>.quality.json``.

The check depends on what the clip's content hash names (its specification and the
engine files it comes from) and on the checking code, which the hash leaves out (a
change to the check must not re-render a clip): the file records the whole engine's
:func:`~synthesis.identity.code_digest`, and a check made by other code is made again.
It is made by whichever comes first — the render, or a check of a whole study before
rendering (``manage.py check_stimuli``) — and read back by both.
"""

import json
from pathlib import Path
from typing import TYPE_CHECKING

from synthesis.identity import code_digest
from synthesis.quality import ClipQuality, Finding, check_request
from synthesis.techniques.request import Build

if TYPE_CHECKING:  # stimuli.clips imports this module
    from stimuli.clips import ClipSpec


def quality_file(directory: Path, content_hash: str) -> Path:
    """Return the file of the check of the clip named *content_hash*."""
    return Path(directory) / f"{content_hash}.quality.json"


def stored_quality(directory: Path, content_hash: str) -> ClipQuality | None:
    """Return the check kept for *content_hash*, or None if none was made (or it is damaged)."""
    path = quality_file(directory, content_hash)
    try:
        data = json.loads(path.read_text())
        if data.get("checked_by") != code_digest():
            return None
        return ClipQuality.from_dict(data)
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        return None


def checked(
    spec: "ClipSpec",
    directory: Path,
    content_hash: str | None = None,
    build: Build | None = None,
    filmed=None,
) -> ClipQuality:
    """Return the check of *spec*: the one kept in *directory*, or made and kept now.

    *build* is the clip's motion and *filmed* its (avatar, camera), where the caller made
    them already (a render).
    """
    name = content_hash or spec.content_hash()
    found = stored_quality(directory, name)
    if found is not None:
        return found
    try:
        quality = check_request(spec, build, filmed)
    except (ValueError, IndexError, KeyError) as error:
        # A check that cannot run says so where its warnings go; the clip still renders.
        message = f"the stimulus check could not run on this clip: {type(error).__name__}: {error}"
        quality = ClipQuality({}, (Finding("check", message, 0),))
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    path = quality_file(directory, name)
    temporary = path.with_suffix(".json.part")
    data = {**quality.to_dict(), "checked_by": code_digest()}
    temporary.write_text(json.dumps(data, indent=1, ensure_ascii=False) + "\n")
    temporary.replace(path)
    return quality
