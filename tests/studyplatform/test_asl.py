"""Test the study's ASL videos page: which texts are signed, uploading and replacing."""

import pytest
from django.contrib.contenttypes.models import ContentType
from django.core.files.uploadedfile import SimpleUploadedFile
from django.urls import reverse

from studyplatform.lib.asl import study_prompts
from studyplatform.models import AslVideo, Question, SignedTemplate
from tests.conftest import tiny_webm

pytestmark = pytest.mark.django_db
WEBM = tiny_webm()


@pytest.fixture
def media(settings, tmp_path):
    settings.MEDIA_ROOT = tmp_path
    return tmp_path


def _post(client, study, obj, field_name, name="consent.webm", data=WEBM):
    url = reverse("admin:studyplatform_study_asl", args=[study.pk])
    return client.post(
        url,
        {
            "content_type": ContentType.objects.get_for_model(obj).pk,
            "object_id": obj.pk,
            "field_name": field_name,
            "video": SimpleUploadedFile(name, data, "video/webm"),
        },
        follow=True,
    )


def test_every_text_participants_read_is_listed(spine):
    prompts = study_prompts(spine)
    where = {(p.obj._meta.model_name, p.field_name) for p in prompts}
    assert {
        ("study", "consent_text"),
        ("question", "text"),
        ("answeroption", "label"),
        ("study", "thank_you_text"),
    } <= where
    assert ("block", "title") not in where  # headings: the signed intro carries them
    assert all(p.text for p in prompts)  # empty texts need no video
    assert not any(p.video for p in prompts)


def test_a_researcher_uploads_and_replaces_a_prompt_video(client, alice, fingerspelling, media):
    client.force_login(alice)
    page = client.get(reverse("admin:studyplatform_study_asl", args=[fingerspelling.pk]))
    total = len(study_prompts(fingerspelling))
    assert f"0 of {total}" in page.text
    assert page.text.count('<strong class="missing">') == total
    saved = _post(client, fingerspelling, fingerspelling, "consent_text")
    assert "ASL video saved." in saved.text and f"1 of {total}" in saved.text
    first = AslVideo.objects.get()
    _post(client, fingerspelling, fingerspelling, "consent_text", name="again.webm")
    replaced = AslVideo.objects.get()
    assert replaced.pk == first.pk and replaced.video.name != first.video.name
    question = Question.objects.get(study=fingerspelling, key="age")
    _post(client, fingerspelling, question, "text", name="age.mp4")
    assert AslVideo.objects.count() == 2


def test_replacing_a_video_deletes_the_old_file_unless_a_copy_still_uses_it(
    alice, fingerspelling, media, django_capture_on_commit_callbacks
):
    """Regression (issue 19): after "Duplicate", replacing the copy's video deleted the
    original study's file, which the copy had shared."""
    from studyplatform.actions import do_attach_asl_video, do_duplicate_study

    kind = ContentType.objects.get_for_model(fingerspelling).pk

    def attach(study, name):
        with django_capture_on_commit_callbacks(execute=True):
            return do_attach_asl_video(
                study, kind, study.pk, "consent_text", SimpleUploadedFile(name, WEBM, "video/webm")
            )

    original = attach(fingerspelling, "consent.webm")
    with django_capture_on_commit_callbacks(execute=True):
        copy = do_duplicate_study(fingerspelling, owner=alice)
    shared = AslVideo.objects.get(object_id=copy.pk, content_type_id=kind)
    assert shared.video.name == original.video.name  # the copy points at the same file
    replaced = attach(copy, "new.webm")
    assert (media / original.video.name).exists()  # the original's video is intact
    assert (media / replaced.video.name).exists()
    again = attach(copy, "newer.webm")  # the copy's own file: nobody else uses it
    assert not (media / replaced.video.name).exists() and (media / again.video.name).exists()


def test_bad_uploads_are_refused(client, alice, bob, fingerspelling, spine, media):
    client.force_login(alice)
    not_video = _post(
        client, fingerspelling, fingerspelling, "consent_text", name="notes.txt", data=b"some notes"
    )
    assert "Not saved: “notes.txt” is not a video file (judged by its content)" in not_video.text
    # A page named as a video is judged by what it is, too (issue 33).
    page = _post(
        client,
        fingerspelling,
        fingerspelling,
        "consent_text",
        name="consent.webm",
        data=b"\x1a\x45\xdf\xa3<html><script>alert(1)</script></html>",
    )
    assert "does not decode as a video" in page.text
    wrong_field = _post(client, fingerspelling, fingerspelling, "slug")
    assert "“slug” is not a text participants read" in wrong_field.text
    elsewhere = _post(client, fingerspelling, spine, "consent_text")  # bob's study's text
    assert "This text is not part of the study." in elsewhere.text
    client.force_login(bob)  # alice's study is not there for bob
    url = reverse("admin:studyplatform_study_asl", args=[fingerspelling.pk])
    assert client.get(url).status_code == 404
    assert not AslVideo.objects.exists()


def test_participants_see_the_video_first_on_an_asl_first_study(client, bob, spine, media):
    client.force_login(bob)
    question = Question.objects.get(study=spine, key="clarity")
    _post(client, spine, question, "text")
    _post(client, spine, spine, "consent_text")
    client.logout()
    welcome = client.get(reverse("study_welcome", args=[spine.slug]))
    assert welcome.text.index("<video") < welcome.text.index("This study shows a short signed")
    client.post(reverse("study_welcome", args=[spine.slug]), {"consent": "yes"})
    from studyplatform.models import Participant

    participant = Participant.objects.get()
    number = next(i for i, e in enumerate(participant.schedule, 1) if e["trial"] == "rate-s1")
    participant.reached = number
    participant.save()
    page = client.get(reverse("participant_page", args=[participant.token, number]))
    assert 'aria-label="ASL: Rate the clarity of the sentence."' in page.text
    participant.language = "en"  # English only: no ASL videos
    participant.save()
    page = client.get(reverse("participant_page", args=[participant.token, number]))
    assert "ASL: Rate the clarity" not in page.text


def test_coverage_counts_only_texts_participants_meet(spine):
    unused = Question.objects.create(study=spine, key="unused", kind="likert", text="Never asked")
    texts = {p.text for p in study_prompts(spine)}
    assert "Never asked" not in texts and "Rate the clarity of the sentence." in texts
    preferred = Question.objects.get(study=spine, key="preferred")
    assert not preferred.allow_no_difference
    assert not any(
        p.obj == preferred and p.field_name == "no_difference_label" for p in study_prompts(spine)
    )
    assert unused.pk


def test_a_signed_template_signs_consent_in_every_study_it_is_attached_to(
    client, bob, spine, media
):
    template = SignedTemplate.objects.create(
        owner=bob,
        kind=SignedTemplate.Kind.CONSENT,
        name="Lab consent",
        video=SimpleUploadedFile("consent.webm", WEBM, "video/webm"),
    )
    spine.signed_templates.add(template)
    consent = next(p for p in study_prompts(spine) if p.field_name == "consent_text")
    assert consent.video == template and consent.from_template
    client.force_login(bob)
    page = client.get(reverse("admin:studyplatform_study_asl", args=[spine.pk])).text
    assert "template “Lab consent”" in page
    welcome = client.get(reverse("study_welcome", args=[spine.slug])).text
    assert welcome.index(template.video.url) < welcome.index("This study shows a short signed")


def test_researchers_see_only_their_own_templates(client, alice, bob, media):
    video = SimpleUploadedFile("n.webm", WEBM, "video/webm")
    SignedTemplate.objects.create(owner=bob, kind="next", name="Bob's next", video=video)
    client.force_login(alice)
    page = client.get(reverse("admin:studyplatform_signedtemplate_changelist")).text
    assert "Bob&#x27;s next" not in page and "Bob's next" not in page
    client.force_login(bob)
    assert (
        "Bob&#x27;s next"
        in client.get(reverse("admin:studyplatform_signedtemplate_changelist")).text
    )
