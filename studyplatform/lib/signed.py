"""Signed (webcam) answers in the exports: each file's SHA-256, its download path, its bytes.

The tidy CSV names each signed answer by the SHA-256 of its file and gives the path its
researchers download it from; the "everything" zip carries the files under
``signed_answers/<sha256><extension>``, so a row finds its video by that column alone.
"""

import hashlib
import os
from collections.abc import Iterator
from dataclasses import dataclass

from django.urls import reverse

from studyplatform.models import Response, Study

ZIP_FOLDER = "signed_answers"


def video_digest(response: Response) -> str:
    """Return the SHA-256 of *response*'s video: as checked on upload, or read now."""
    if response.video_sha256:
        return response.video_sha256
    digest = hashlib.sha256()
    with response.video.open("rb") as video:
        for block in iter(lambda: video.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def signed_cells(response: Response) -> dict[str, str]:
    """Return the CSV cells naming *response*'s signed answer (empty without one)."""
    if not response.video:
        return {"video_sha256": "", "video_url": ""}
    return {
        "video_sha256": video_digest(response),
        "video_url": reverse("private_media", args=[response.video.name]),
    }


@dataclass(frozen=True)
class SignedVideo:
    """One signed answer's file: where it is stored, its name in the zip, its size."""

    path: str
    archive_name: str
    size: int


def _on_disk(study: Study) -> Iterator[tuple[Response, str, int]]:
    """Yield each signed answer of *study* whose file is on disk: response, path, size."""
    responses = Response.objects.filter(participant__study=study).exclude(video="")
    for response in responses.order_by("pk").iterator():
        try:
            path = response.video.path
            yield response, path, os.path.getsize(path)
        except (FileNotFoundError, NotImplementedError):
            continue


def signed_videos(study: Study) -> Iterator[SignedVideo]:
    """Yield every signed answer of *study*'s participants that is on disk (once per file)."""
    seen = set()
    for response, path, size in _on_disk(study):
        digest = video_digest(response)
        if digest in seen:
            continue
        seen.add(digest)
        extension = os.path.splitext(response.video.name)[1]
        yield SignedVideo(path, f"{ZIP_FOLDER}/{digest}{extension}", size)


def signed_summary(study: Study) -> tuple[int, int]:
    """Return how many signed answers the study has on disk and their bytes, without
    reading the files (the zip leaves out a file identical to another, if any)."""
    found = [size for _, _, size in _on_disk(study)]
    return len(found), sum(found)
