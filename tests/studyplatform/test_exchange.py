"""Test study definitions: export → import round trips, and bad files that change nothing."""

import copy
import io
import json

import pytest
from django.core.files.base import ContentFile
from django.core.files.storage import default_storage
from django.core.files.uploadedfile import SimpleUploadedFile
from django.core.management import call_command
from django.urls import reverse

from studyplatform.actions import StudyImportError, do_duplicate_study, do_import_study
from studyplatform.lib.bundle import read_bundle, write_bundle
from studyplatform.lib.exchange import export_study
from studyplatform.models import AslVideo, Participant, Question, Study, Trial
from tests.conftest import tiny_webm

pytestmark = pytest.mark.django_db


def _without_slug(data):
    data = copy.deepcopy(data)
    data["study"].pop("slug")
    return data


def test_export_import_export_is_identical(fingerspelling, bob):
    exported = export_study(fingerspelling)
    imported = do_import_study(json.loads(json.dumps(exported)), owner=bob).study
    assert imported.pk != fingerspelling.pk
    assert imported.owner == bob
    assert _without_slug(export_study(imported)) == _without_slug(exported)


def test_reimport_after_delete_gives_byte_identical_definition(alice):
    from studyplatform.demo import spine_study

    study = do_import_study(spine_study(), owner=alice).study
    before = json.dumps(export_study(study), sort_keys=True)
    study.delete()
    again = do_import_study(json.loads(before), owner=alice).study
    assert json.dumps(export_study(again), sort_keys=True) == before


def test_export_keeps_every_part_of_the_demo(fingerspelling):
    data = export_study(fingerspelling)
    assert len(data["conditions"]) == 4
    assert len(data["items"]) == 9
    assert len([t for t in data["trials"] if t["kind"] == "pairwise"]) == 49  # 48 + practice
    mocap = next(c for c in data["conditions"] if c["key"] == "mocap")
    assert mocap["is_simulated"] is True
    age = next(q for q in data["questions"] if q["key"] == "age")
    assert [o["label"] for o in age["options"]][-1] == "66+"


def test_asl_videos_travel_with_the_definition(fingerspelling, alice, settings, tmp_path):
    settings.MEDIA_ROOT = tmp_path
    question = fingerspelling.questions.get(key="most-natural")
    name = default_storage.save("asl/most-natural.webm", ContentFile(tiny_webm()))
    AslVideo.objects.create(target=question, field_name="text", video=name)
    AslVideo.objects.create(target=fingerspelling, field_name="consent_text", video=name)
    exported = export_study(fingerspelling)
    imported = do_import_study(exported, owner=alice).study  # her own files: shared
    assert imported.asl_videos.get().field_name == "consent_text"
    copied = imported.questions.get(key="most-natural").asl_videos.get()
    assert copied.video.name == name
    assert _without_slug(export_study(imported)) == _without_slug(exported)


def test_an_import_may_not_name_another_researchers_file(fingerspelling, bob, settings, tmp_path):
    """Issue 19: an import could name any media file, which replacing it then deleted."""
    settings.MEDIA_ROOT = tmp_path
    name = default_storage.save("asl/consent.webm", ContentFile(tiny_webm()))
    AslVideo.objects.create(target=fingerspelling, field_name="consent_text", video=name)
    exported = export_study(fingerspelling)
    studies = Study.objects.count()
    # Another researcher's file reads as one that is not there (issue 33: the two messages
    # told whether a file of that name existed): left out, with the same warning.
    result = do_import_study(exported, owner=bob)
    assert result.warnings == (
        "asl_videos[0]: video file 'asl/consent.webm' is not in media; left out.",
    )
    assert not result.study.asl_videos.exists() and AslVideo.objects.count() == 1
    result.study.delete()
    assert Study.objects.count() == studies
    # The bundle brings a copy of the file, stored under a name made from its content.
    buffer = io.BytesIO()
    write_bundle(exported, buffer)
    definition, files = read_bundle(buffer.getvalue())
    assert name in files and len(files) == 1
    imported = do_import_study(definition, owner=bob, files=files).study
    video = imported.asl_videos.get()
    assert video.video.name != name and video.video.read() == tiny_webm()
    again = do_import_study(definition, owner=bob, files=files).study  # same content, one file
    assert again.asl_videos.get().video.name == video.video.name


def test_missing_asl_video_file_is_left_out_with_a_warning(fingerspelling, bob, settings, tmp_path):
    settings.MEDIA_ROOT = tmp_path
    data = export_study(fingerspelling)
    data["asl_videos"] = [
        {
            "target": ["study", None],
            "field_name": "consent_text",
            "transcript": "",
            "video": "asl/not-here.mp4",
            "poster": "",
        }
    ]
    result = do_import_study(data, owner=bob)
    assert result.warnings == (
        "asl_videos[0]: video file 'asl/not-here.mp4' is not in media; left out.",
    )
    assert not result.study.asl_videos.exists()


def test_slug_taken_gets_a_free_variant(fingerspelling, bob):
    copy_one = do_import_study(export_study(fingerspelling), owner=bob).study
    copy_two = do_import_study(export_study(fingerspelling), owner=bob).study
    assert copy_one.slug == "fingerspelling-timing-2"
    assert copy_two.slug == "fingerspelling-timing-3"


def test_explicit_slug_taken_is_an_error(fingerspelling, bob):
    with pytest.raises(StudyImportError, match=r"study: slug: Study with this Slug already exists"):
        do_import_study(export_study(fingerspelling), owner=bob, slug=fingerspelling.slug)


def test_duplicate_is_a_draft_copy_owned_by_who_asked(fingerspelling, bob):
    Participant.objects.create(study=fingerspelling)
    copy_ = do_duplicate_study(fingerspelling, owner=bob)
    assert copy_.status == Study.Status.DRAFT
    assert copy_.owner == bob
    assert copy_.slug == "fingerspelling-timing-copy"
    assert copy_.title == "ASL fingerspelling timing (demo) (copy)"
    assert copy_.trials.count() == fingerspelling.trials.count()
    assert not copy_.participants.exists()


BAD_DEFINITIONS = [
    (lambda d: d.update(format="something-else"), "Not a study definition"),
    (lambda d: d.update(version=99), "Unsupported study definition version 99"),
    (lambda d: d["study"].update(colour="red"), r"study: unknown field\(s\) colour"),
    (
        lambda d: d["study"].update(status="maybe"),
        "study: status: Value 'maybe' is not a valid choice",
    ),
    (
        lambda d: d["conditions"].append(dict(d["conditions"][0])),
        r"conditions\[4\]: __all__: .*already exists",
    ),
    (  # the study's own key is not looked up, but a key used twice in it is refused
        lambda d: d["trials"].append(dict(d["trials"][5])),
        r"trials\[\d+\]: __all__: .*already exists",
    ),
    (
        lambda d: d["trials"][5].update(condition_a="telepathy"),
        r"trials\[5\].condition_a: unknown condition 'telepathy'",
    ),
    (
        lambda d: d["trials"][5].update(questions=["age"]),
        r"trials\[5\].questions: A pairwise forced choice trial cannot ask age",
    ),
    (
        lambda d: d["trials"][5].update(condition_b=None),
        r"trials\[5\]: condition_b: A comparison needs",
    ),
    (
        lambda d: d["trials"][5].update(block="nowhere"),
        r"trials\[5\].block: unknown block 'nowhere'",
    ),
    (
        lambda d: d["questions"][0]["options"].append({"value": 1, "label": "again"}),
        r"questions\[0\].options\[6\]",
    ),
    (lambda d: d.update(items="GUITAR"), "items: expected a list"),
    (  # issue 19: was a server error
        lambda d: d["questions"].append(
            {"key": "years", "kind": "number", "text": "Years?", "min_value": "x"}
        ),
        r"questions\[11\]: min_value must be a number, not str",
    ),
]


@pytest.mark.parametrize("break_it, message", BAD_DEFINITIONS)
def test_bad_definition_names_the_problem_and_saves_nothing(alice, break_it, message):
    from studyplatform.demo import fingerspelling_timing_study

    data = fingerspelling_timing_study()
    break_it(data)
    counts = (Study.objects.count(), Trial.objects.count(), Question.objects.count())
    with pytest.raises(StudyImportError, match=message):
        do_import_study(data, owner=alice)
    assert (Study.objects.count(), Trial.objects.count(), Question.objects.count()) == counts


def test_not_an_object_is_rejected(alice):
    with pytest.raises(StudyImportError, match="must be a JSON object"):
        do_import_study(["a", "list"], owner=alice)


@pytest.mark.parametrize(
    ("field", "name"), [("video", "../db.sqlite3"), ("poster", "asl/../../x.png"), ("video", 7)]
)
def test_an_asl_video_pointing_out_of_its_folder_is_refused(fingerspelling, bob, field, name):
    data = export_study(fingerspelling)
    row = {
        "target": ["study", None],
        "field_name": "consent_text",
        "transcript": "",
        "video": "asl/fine.mp4",
        "poster": "",
    }
    data["asl_videos"] = [{**row, field: name}]
    with pytest.raises(StudyImportError, match=rf"asl_videos\[0\]\.{field}: .* is not an ASL"):
        do_import_study(data, owner=bob, slug="elsewhere")
    assert not Study.objects.filter(slug="elsewhere").exists()


def test_an_asl_video_with_a_malformed_target_is_refused(fingerspelling, bob):
    """Regression (issue 19): a list where the model's name belongs was a server error."""
    data = export_study(fingerspelling)
    data["asl_videos"] = [
        {
            "target": [["study"], None],
            "field_name": "consent_text",
            "transcript": "",
            "video": "asl/fine.mp4",
            "poster": "",
        }
    ]
    with pytest.raises(StudyImportError, match=r"asl_videos\[0\]\.target: unknown model"):
        do_import_study(data, owner=bob, slug="elsewhere")
    assert not Study.objects.filter(slug="elsewhere").exists()


def test_a_bundle_travels_by_the_admin_and_the_shell(
    client, fingerspelling, alice, bob, settings, tmp_path
):
    settings.MEDIA_ROOT = tmp_path
    name = default_storage.save("asl/consent.webm", ContentFile(tiny_webm()))
    AslVideo.objects.create(target=fingerspelling, field_name="consent_text", video=name)
    client.force_login(alice)
    url = reverse("admin:studyplatform_study_export", args=[fingerspelling.pk])
    bundle = client.get(url, {"media": "1"})
    assert bundle["Content-Type"] == "application/zip"
    client.force_login(bob)
    upload = SimpleUploadedFile("fs.study.zip", bundle.content, "application/zip")
    imported = client.post(reverse("admin:studyplatform_study_import"), {"definition": upload})
    assert imported.status_code == 302
    study = Study.objects.filter(owner=bob).get()
    assert study.asl_videos.get().video.read() == tiny_webm()
    path = tmp_path / "bundle.zip"
    call_command("export_study", fingerspelling.slug, "--out", str(path), "--with-media")
    call_command("import_study", str(path), "--owner", "bob", "--slug", "from-the-shell")
    assert Study.objects.get(slug="from-the-shell").asl_videos.get().video.read() == tiny_webm()
    broken = SimpleUploadedFile("x.zip", b"PK\x03\x04broken")
    plain = client.post(reverse("admin:studyplatform_study_import"), {"definition": broken})
    assert "not a zip file" in plain.text


KILLED_IMPORT = """
import json, os, signal, sys

import django

django.setup()
from django.contrib.auth import get_user_model
from django.db.models.signals import post_save

from studyplatform.actions import do_import_study
from studyplatform.models import Condition

saved = []


def kill(sender, **kwargs):
    saved.append(1)
    if len(saved) == 300:  # half-way through the conditions, as a killed worker would stop
        os.kill(os.getpid(), signal.SIGKILL)


post_save.connect(kill, sender=Condition)
with open(sys.argv[1], encoding="utf-8") as definition:
    do_import_study(json.load(definition), owner=get_user_model().objects.get(username="bob"))
"""


@pytest.mark.django_db(transaction=True)
def test_a_killed_import_leaves_no_half_imported_study(fingerspelling, bob, tmp_path):
    """Issue 57: the import committed every 200 rows, so a process killed half-way left a
    half-imported draft. It is one transaction now: a worker killed (SIGKILL, in its own
    process on this test's database) at the 300th of 451 conditions leaves nothing."""
    import os
    import subprocess
    import sys

    from django.db import connection

    from studyplatform.models import Condition

    data = export_study(fingerspelling)
    data["study"]["slug"] = "killed-half-way"
    template = data["conditions"][0]
    data["conditions"] += [
        {**template, "key": f"extra-{n}", "label": f"Extra {n}"} for n in range(450)
    ]
    path = tmp_path / "definition.json"
    path.write_text(json.dumps(data), "utf-8")
    database = connection.settings_dict
    if database["ENGINE"].endswith("sqlite3"):
        url = f"sqlite:///{database['NAME']}"
    else:
        url = (
            f"postgres://{database['USER']}@{database['HOST']}:{database['PORT'] or 5432}"
            f"/{database['NAME']}"
        )
    conditions = Condition.objects.count()
    killed = subprocess.run(
        [sys.executable, "-c", KILLED_IMPORT, str(path)],
        env={**os.environ, "DATABASE_URL": url, "DJANGO_SETTINGS_MODULE": "studyplatform.settings"},
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert killed.returncode == -9, killed.stderr[-2000:]
    assert not Study.objects.filter(slug="killed-half-way").exists()
    assert Condition.objects.count() == conditions


def test_every_model_field_is_exported_or_left_out_on_purpose(monkeypatch):
    """Issue 39: do_duplicate_study goes export → import, so a field left off the lists
    would silently vanish from copies and versions. The system check E004 holds it; a
    field planted off both lists, and a stale one, make it fail."""
    from studyplatform.checks import check_exchange_fields
    from studyplatform.lib import exchange

    assert check_exchange_fields() == []
    monkeypatch.setitem(exchange.EXPORTED, "Item", (*exchange.ITEM_FIELDS[1:], "colour"))
    messages = [error.msg for error in check_exchange_fields()]
    assert messages == [
        "Item.key is neither exported nor left out on purpose.",
        "Item.colour is exported or left out but is no field.",
    ]
    assert {error.id for error in check_exchange_fields()} == {"studyplatform.E004"}


def test_a_copy_and_a_version_keep_the_signed_templates_their_owner_may_use(
    alice, bob, spine, settings, tmp_path
):
    settings.MEDIA_ROOT = tmp_path
    from studyplatform.actions import do_create_study_version
    from studyplatform.models import SignedTemplate

    video = SimpleUploadedFile("consent.webm", tiny_webm(), "video/webm")
    mine = SignedTemplate.objects.create(owner=bob, kind="consent", name="Lab", video=video)
    theirs = SignedTemplate.objects.create(owner=alice, kind="next", name="Alice's", video=video)
    spine.signed_templates.add(mine, theirs)
    version = do_create_study_version(spine, owner=bob)
    assert set(version.signed_templates.all()) == {mine}
    copied = do_duplicate_study(spine, owner=alice)
    assert set(copied.signed_templates.all()) == {theirs}
