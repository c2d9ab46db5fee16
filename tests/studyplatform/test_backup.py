"""Back up everything, restore it into an empty installation, and verify (issue 19)."""

import io
import tarfile

import pytest
from django.core.management import call_command
from django.core.management.base import CommandError

from studyplatform.models import Participant, PersonalAnswer, Response, Study
from tests.conftest import tiny_webm
from tests.studyplatform.test_participate import _chunk, _save

pytestmark = pytest.mark.django_db(transaction=True)


def _snapshot() -> dict:
    return {
        "studies": sorted(Study.objects.values_list("slug", flat=True)),
        "participants": sorted(Participant.objects.values_list("token", flat=True)),
        "answers": sorted(
            Response.objects.values_list("participant__token", "question__key", "text", "video")
        ),
        "personal": sorted(PersonalAnswer.objects.values_list("value", flat=True)),
    }


def test_backup_and_restore_give_back_every_row_and_file(
    client, at_comments, fingerspelling, tmp_path, settings
):
    participant, number = at_comments
    assert _chunk(client, participant, number, tiny_webm(), 0, final=True).json()["saved"]
    _save(
        client,
        participant,
        page=1,
        trial=participant.schedule[0]["trial"],
        question="age",
        value="2",
    )
    stimulus = tmp_path / "stimuli" / "clip.mp4"  # at_comments put MEDIA_ROOT at tmp_path
    stimulus.parent.mkdir()
    stimulus.write_bytes(b"a public clip")
    video = Response.objects.exclude(video="").get().video
    recorded = video.read()
    before = _snapshot()

    archive = tmp_path.parent / "backup.tar.gz"
    call_command("backup", str(archive))
    with pytest.raises(CommandError, match="not empty"):
        call_command("restore", str(archive))

    call_command("flush", interactive=False, verbosity=0)  # the installation is lost …
    stimulus.unlink()
    video.storage.delete(video.name)
    call_command("restore", str(archive))  # … and comes back
    assert _snapshot() == before
    assert stimulus.read_bytes() == b"a public clip"
    assert Response.objects.exclude(video="").get().video.read() == recorded
    assert Study.objects.get(slug=fingerspelling.slug).owner.username == "alice"


def test_a_damaged_archive_is_refused(client, fingerspelling, tmp_path, settings):
    settings.MEDIA_ROOT = tmp_path / "media"
    (tmp_path / "media").mkdir()
    (tmp_path / "media" / "a.txt").write_bytes(b"original")
    good = tmp_path / "good.tar.gz"
    call_command("backup", str(good))
    damaged = tmp_path / "damaged.tar.gz"
    with tarfile.open(good) as source, tarfile.open(damaged, "w:gz") as target:
        for member in source.getmembers():
            data = source.extractfile(member).read()
            if member.name == "media/a.txt":
                data = b"tampered"
                member.size = len(data)
            target.addfile(member, io.BytesIO(data))
    with pytest.raises(CommandError, match=r"media/a\.txt does not match its checksum"):
        call_command("restore", str(damaged), "--replace")
    assert Study.objects.get(slug=fingerspelling.slug)  # nothing was deleted
    with pytest.raises(CommandError, match="There is no archive"):
        call_command("restore", str(tmp_path / "missing.tar.gz"))
