"""Take researchers' own avatars: check a GLB/VRM upload, store it, map its bones, and
render its preview stills in the background."""

import base64
import json

from django.core.exceptions import ValidationError
from django.core.files.base import ContentFile
from django.db import transaction

from studyplatform.actions.media import delete_unused_files_on_commit
from studyplatform.confine import ConfinedError, run_task
from studyplatform.files.storage import PRIVATE_STORAGE
from studyplatform.jobs.queue import PREPARE_AVATAR, queue_job_on_commit
from studyplatform.models import Avatar

MAX_AVATAR_BYTES = 200 * 1024**2


class AvatarRejected(ValidationError):
    """A file that cannot be an avatar, or a mapping that cannot be saved; nothing
    changed."""


def _inspected(data: bytes, name: str) -> dict:
    """Return the engine's report on avatar *data*, read confined
    (:mod:`studyplatform.confine`); AvatarRejected names what is wrong."""
    try:
        return run_task("avatar", data, name)
    except ConfinedError as error:
        raise AvatarRejected(str(error)) from None


def _store(avatar: Avatar, data: bytes) -> None:
    """Save *data* as the avatar's file, named by its SHA-256, and queue its stills."""
    import hashlib

    sha256 = hashlib.sha256(data).hexdigest()
    old = avatar.file.name if avatar.file else ""
    name = f"avatars/{sha256}.glb"
    if not PRIVATE_STORAGE.exists(name):
        name = PRIVATE_STORAGE.save(name, ContentFile(data, name=name))
    avatar.file.name, avatar.sha256 = name, sha256
    avatar.status, avatar.error = Avatar.Status.PREPARING, ""
    avatar.save()
    if old and old != name:
        delete_unused_files_on_commit(PRIVATE_STORAGE, [old])
    queue_job_on_commit(PREPARE_AVATAR, avatar.pk)


def check_avatar_file(upload) -> tuple[bytes, dict]:
    """Return an uploaded avatar's bytes and the engine's report on it.

    Raise AvatarRejected for a file over 200 MB, one that is not glTF 2.0 binary (by
    content), a truncated or damaged one, one without a skin, or a skeleton whose
    joints the engine cannot map (fewer than four).
    """
    if (getattr(upload, "size", 0) or 0) > MAX_AVATAR_BYTES:
        raise AvatarRejected(f"The avatar is larger than {MAX_AVATAR_BYTES // 1024**2} MB.")
    upload.seek(0)
    data = upload.read()
    original = getattr(upload, "name", "") or "avatar.glb"
    if data[:4] != b"glTF":
        raise AvatarRejected(
            f"“{original}” is not a GLB or VRM file (glTF 2.0 binary), judged by its content."
        )
    return data, _inspected(data, original)


def check_bone_mapping(avatar: Avatar, bones) -> None:
    """Raise AvatarRejected unless *bones* maps joints the avatar has to joints the
    engine has (or to "", to unmap one)."""
    from synthesis.rigs.body import BodyModel

    if not isinstance(bones, dict):
        raise AvatarRejected("The bone mapping is an object: avatar joint → engine joint.")
    engine = set(BodyModel("right").skeleton.names)
    known = set(avatar.report.get("mapped", {})) | set(avatar.report.get("unmapped", []))
    for joint, target in bones.items():
        if not isinstance(target, str):
            raise AvatarRejected(f"The mapping of {str(joint)[:60]!r} is not a joint name (text).")
        if joint not in known:
            raise AvatarRejected(f"The avatar has no joint {joint!r}.")
        if target and target not in engine:
            raise AvatarRejected(
                f"The engine has no joint {target!r} (its joints: "
                f"{', '.join(sorted(engine)[:8])}, …)."
            )


def do_upload_avatar(owner, upload, name: str, licence: str, source: str = "") -> Avatar:
    """Store a GLB or VRM *upload* as *owner*'s avatar and queue its preview stills;
    AvatarRejected (:func:`check_avatar_file`) stores nothing."""
    data, report = check_avatar_file(upload)
    original = getattr(upload, "name", "") or "avatar.glb"
    with transaction.atomic():
        avatar = Avatar(
            owner=owner,
            name=name or report["meta"].get("name") or original,
            licence=licence,
            source=source,
            original_name=original[:255],
            report=report,
        )
        _store(avatar, data)
    return avatar


def do_map_avatar_bones(avatar: Avatar, bones: dict[str, str]) -> Avatar:
    """Save *bones* (avatar joint → engine joint, "" to unmap) in the avatar's file and
    report; the file's new SHA-256 renders new clips. AvatarRejected names a joint the
    avatar or the engine does not have."""
    check_bone_mapping(avatar, bones)
    with avatar.file.open("rb") as handle:
        data = handle.read()
    try:
        mapped = run_task("mapped_avatar", data, avatar.original_name, json.dumps(bones))
    except ConfinedError as error:
        raise AvatarRejected(str(error)) from None
    data, report = base64.b64decode(mapped["data"]), mapped["report"]
    with transaction.atomic():
        avatar.bone_mapping, avatar.report = bones, report
        _store(avatar, data)
    return avatar


def do_finish_avatar_previews(avatar: Avatar, stills: dict[str, bytes]) -> None:
    """Save the avatar's preview stills (PNG bytes by name) and mark it ready."""
    with transaction.atomic(durable=True):
        old = [avatar.still_rest.name, avatar.still_letter.name, avatar.still_face.name]
        for name, data in stills.items():
            field = getattr(avatar, f"still_{name}")
            field.save(f"{avatar.sha256[:32]}-{name}.png", ContentFile(data), save=False)
        avatar.status, avatar.error = Avatar.Status.READY, ""
        avatar.save()
        delete_unused_files_on_commit(PRIVATE_STORAGE, old)


def do_fail_avatar_previews(avatar: Avatar, error: Exception) -> str:
    """Record why the stills could not be rendered; return the avatar's status."""
    Avatar.objects.filter(pk=avatar.pk).update(
        status=Avatar.Status.FAILED, error=f"{type(error).__name__}: {error}"
    )
    return Avatar.Status.FAILED
