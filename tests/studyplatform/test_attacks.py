"""Replay issue 33's attacks against a live server and check that each one now fails.

Each test sends what a hostile second researcher or participant sent on loopback (raw
HTTP through :mod:`tests.studyplatform.attack`), on SQLite and, in the PostgreSQL run,
on PostgreSQL; the numbers in the names are the issue's.
"""

import hashlib
import json
import subprocess
import tracemalloc
import zipfile
from io import BytesIO

import pytest
from django.contrib.auth import get_user_model
from django.contrib.sessions.models import Session
from django.core.management import call_command

from studyplatform.actions import do_withdraw_participant
from studyplatform.actions.uploads import partial_directory
from studyplatform.lib.exchange import export_study
from studyplatform.models import MediaEvent, Participant, Response, Study, Withdrawal
from tests.conftest import as_draft, tiny_webm, video_frames
from tests.studyplatform.attack import Attacker, bundle
from tests.studyplatform.test_app_server import server  # noqa: F401 (the gunicorn fixture)

pytestmark = pytest.mark.django_db(transaction=True)

IMPORT = "/admin/studyplatform/study/import/"
SCRIPT = b"fetch('/admin/auth/user/add/');document.title='PWNED';"


@pytest.fixture
def media(settings, tmp_path):
    settings.MEDIA_ROOT = tmp_path / "media"
    settings.MEDIA_ROOT.mkdir()
    return settings.MEDIA_ROOT


def _definition(study, asl_videos) -> dict:
    definition = export_study(study)
    definition["study"]["slug"] = "planted"
    definition["asl_videos"] = asl_videos
    return definition


def test_1_a_bundle_cannot_plant_a_page_or_a_script(live_server, fingerspelling, bob, media):
    """A zip whose ASL "video" is HTML and "poster" is JavaScript is refused, whatever names."""
    js_name = hashlib.sha256(SCRIPT).hexdigest()[:32]
    html = f'<script src="/media/asl/{js_name}.js"></script>'.encode()
    definition = _definition(
        fingerspelling,
        [
            {
                "target": ["study", None],
                "field_name": "description",
                "video": "asl/consent.html",
                "poster": "asl/consent.js",
            }
        ],
    )
    researcher = Attacker(live_server.url)
    assert researcher.sign_in("bob", "pw-bob").status == 302
    researcher.get(IMPORT)
    for video in ("asl/consent.html", "asl/consent.webm"):  # by name, then by content
        definition["asl_videos"][0]["video"] = video
        zipped = bundle(definition, {video: html, "asl/consent.js": SCRIPT})
        refused = researcher.post_file(IMPORT, {"slug": ""}, "definition", "s.zip", zipped)
        assert refused.status == 400 and "is not a video file" in refused.text
    assert not Study.objects.filter(slug__startswith="planted").exists()
    assert not list(media.rglob("*.js")) and not list(media.rglob("*.html"))


def test_1_a_planted_page_never_runs_for_a_superuser_in_chromium(
    server,  # noqa: F811 (the fixture imported above)
    browser,
    settings,
    fingerspelling,
):
    """Files put in media by any other way: not served (.html, .js), or served as what their
    extension says with a sandbox (a page saved as .webm), so no script runs.

    Served by gunicorn as deployed (Django's live test server answers /media/ itself)."""
    settings.PASSWORD_HASHERS = ["django.contrib.auth.hashers.PBKDF2PasswordHasher"]
    get_user_model().objects.create_superuser("root", "root@example.org", "pw-root-1234")
    media = server.media_root
    (media / "asl").mkdir(parents=True)
    page_bytes = b"<html><body><script>" + SCRIPT + b"</script>planted</body></html>"
    for name in ("evil.html", "evil.js", "evil.svg", "evil.webm"):
        (media / "asl" / name).write_bytes(page_bytes)
    users = get_user_model().objects.count()
    context = browser.new_context()  # the site's own policies, not bypassed
    try:
        page = context.new_page()
        page.goto(f"{server.url}/admin/login/")
        page.get_by_label("Username").fill("root")
        page.get_by_label("Password").fill("pw-root-1234")
        page.get_by_role("button", name="Log in").click()
        page.wait_for_url("**/admin/")
        for name in ("evil.html", "evil.js", "evil.svg"):
            assert page.goto(f"{server.url}/media/asl/{name}").status == 404
        served = page.goto(f"{server.url}/media/asl/evil.webm")
        assert served.headers["content-type"] == "video/webm"
        assert served.headers["x-content-type-options"] == "nosniff"
        assert "sandbox" in served.headers["content-security-policy"]
        # The planted script sends its request and sets the title in one run, before the
        # page's load (which goto waited for): an unchanged title means it never ran.
        assert page.title() != "PWNED"
    finally:
        context.close()
    assert get_user_model().objects.count() == users


def _video(seconds: int = 4) -> bytes:
    import imageio_ffmpeg

    command = [
        imageio_ffmpeg.get_ffmpeg_exe(),
        "-v",
        "error",
        "-f",
        "lavfi",
        "-i",
        f"testsrc=size=320x240:rate=25:duration={seconds}",
        "-c:v",
        "libvpx",
        "-b:v",
        "800k",
        "-f",
        "webm",
        "pipe:1",
    ]
    return subprocess.run(command, capture_output=True, check=True).stdout


def _signed_page(participant) -> int:
    return next(i for i, e in enumerate(participant.schedule, 1) if e["trial"] == "comments")


def _send(who: Attacker, token, number, take, data, offset, final=False, sha=None):
    headers = {
        "Content-Type": "application/octet-stream",
        "Accept": "application/json",
        "X-Upload-Take": take,
        "X-Upload-Offset": str(offset),
        "X-Upload-Final": "1" if final else "0",
    }
    if final:
        headers["X-Upload-Sha256"] = sha or hashlib.sha256(data).hexdigest()
    return who.request("POST", f"/p/{token}/{number}/signed/comments/", data, headers)


@pytest.fixture
def at_signed_answer(live_server, spine, media):
    participant_http = Attacker(live_server.url)
    token = participant_http.enroll(spine.slug)
    participant = Participant.objects.get(token=token)
    participant.reached = len(participant.schedule)
    participant.save()
    return participant_http, participant, _signed_page(participant)


TAKE_1 = "11111111-1111-4111-8111-111111111111"
TAKE_2 = "22222222-2222-4222-8222-222222222222"


def test_2_a_resumed_upload_never_splices_a_discarded_take(at_signed_answer):
    who, participant, number = at_signed_answer
    take_1, take_2 = _video(4), _video(3)
    assert len(take_1) > 40_000 and len(take_2) > 40_000
    token = participant.token
    assert _send(who, token, number, TAKE_1, take_1[:40_000], 0).json()["offset"] == 40_000
    # The participant records again; take 2's first chunk is lost; the client asks where
    # take 2 stands: nowhere. Sending take 2 from byte 40,000 is refused.
    where = who.get(
        f"/p/{token}/{number}/signed/comments/?take={TAKE_2}", Accept="application/json"
    )
    assert where.json() == {"offset": 0}
    spliced = _send(
        who,
        token,
        number,
        TAKE_2,
        take_2[40_000:],
        40_000,
        final=True,
        sha=hashlib.sha256(take_2).hexdigest(),
    )
    assert spliced.status == 409 and spliced.json()["offset"] == 0
    # Under take 1's id, take 2's tail does not match what the browser says it sent.
    forged = _send(
        who,
        token,
        number,
        TAKE_1,
        take_2[40_000:],
        40_000,
        final=True,
        sha=hashlib.sha256(take_2).hexdigest(),
    )
    assert forged.status == 400 and "checksum" in forged.json()["error"]
    assert not Response.objects.filter(participant=participant).exclude(video="").exists()
    # Take 2 sent whole is saved as itself, and leaves no part behind.
    assert _send(who, token, number, TAKE_2, take_2, 0, final=True).json()["saved"]
    saved = Response.objects.get(participant=participant)
    assert video_frames(saved.video.read()) == video_frames(take_2)  # stored remuxed
    assert not list(partial_directory().glob(f"{participant.pk}-*"))


def test_7_a_truncated_recording_is_refused(at_signed_answer):
    who, participant, number = at_signed_answer
    import imageio_ffmpeg

    command = [
        imageio_ffmpeg.get_ffmpeg_exe(),
        "-v",
        "error",
        "-f",
        "lavfi",
        "-i",
        "testsrc=size=160x120:rate=15:duration=3",
        "-c:v",
        "libx264",
        "-pix_fmt",
        "yuv420p",
        "-movflags",
        "+faststart+frag_keyframe+empty_moov",
        "-f",
        "mp4",
        "pipe:1",
    ]
    mp4 = subprocess.run(command, capture_output=True, check=True).stdout
    for cut in (mp4[: len(mp4) // 3], tiny_webm()[: len(tiny_webm()) // 3]):
        refused = _send(who, participant.token, number, TAKE_1, cut, 0, final=True)
        assert refused.status == 400, refused.text
    assert not Response.objects.filter(participant=participant).exclude(video="").exists()


def test_3_a_withdrawal_leaves_nothing_and_survives_a_restore(at_signed_answer, tmp_path):
    who, participant, number = at_signed_answer
    video = _video(2)
    assert _send(who, participant.token, number, TAKE_1, video, 0, final=True).json()["saved"]
    archive = tmp_path / "before.tar.gz"
    call_command("backup", str(archive))  # made before the withdrawal
    assert _send(who, participant.token, number, TAKE_2, video[:5000], 0).status == 200
    saved = Response.objects.exclude(video="").get(participant=participant).video.path

    withdrawal = do_withdraw_participant(participant)
    assert withdrawal.files == 2  # the saved answer and the unfinished take
    assert not list(partial_directory().glob("*.part"))
    assert not (tmp_path / saved).exists()
    remembered = [s.get_decoded().get("signstudy_participants") for s in Session.objects.all()]
    assert all(participant.token not in (r or {}).values() for r in remembered)
    assert who.get(f"/p/{participant.token}/").status == 404

    call_command("restore", str(archive), "--replace")  # an older backup comes back …
    assert not Participant.objects.filter(token=participant.token).exists()  # … not them
    assert not Response.objects.filter(participant__token=participant.token).exists()
    assert Withdrawal.objects.filter(participant_number=participant.pk).count() == 1
    assert not (tmp_path / saved).exists() and not list(partial_directory().glob("*.part"))


def test_4_an_attacker_cannot_lock_the_owner_out(live_server, alice, settings):
    settings.SIGNSTUDY_TRUSTED_PROXIES = frozenset({"127.0.0.1"})
    owner = Attacker(live_server.url, address="198.51.100.7")
    assert owner.sign_in("alice", "pw-alice").status == 302
    device = owner.cookie("signstudy_device")
    assert device
    # Through the proxy, from many addresses, far past the limit.
    for attempt in range(25):
        Attacker(live_server.url, address=f"203.0.113.{attempt}").sign_in("alice", "wrong")
    assert (
        Attacker(live_server.url, address="203.0.113.99").sign_in("alice", "pw-alice").status == 429
    )
    back = Attacker(live_server.url, address="198.51.100.8")  # the owner's browser, moved
    back.jar.set_cookie(next(c for c in owner.jar if c.name == "signstudy_device"))
    assert back.sign_in("alice", "pw-alice").status == 302


def _zero_member_zip(definition: dict, member: str, size: int) -> bytes:
    buffer = BytesIO()
    with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as archive:
        archive.writestr("study.json", json.dumps(definition))
        info = zipfile.ZipInfo(member)
        info.compress_type = zipfile.ZIP_DEFLATED
        block = bytes(1 << 20)
        with archive.open(info, "w", force_zip64=True) as handle:
            for _ in range(size >> 20):
                handle.write(block)
    return buffer.getvalue()


def test_5_a_zip_bomb_is_refused_with_flat_memory(live_server, fingerspelling, bob, media):
    definition = _definition(
        fingerspelling,
        [
            {
                "target": ["study", None],
                "field_name": "description",
                "video": "asl/bomb.webm",
                "poster": "",
            }
        ],
    )
    bomb = _zero_member_zip(definition, "files/asl/bomb.webm", 1 << 30)
    assert len(bomb) < 2 << 20  # about a megabyte that unpacks to a gigabyte
    unnamed = _zero_member_zip(definition, "files/asl/other.bin", 1 << 20)
    researcher = Attacker(live_server.url)
    researcher.sign_in("bob", "pw-bob")
    researcher.get(IMPORT)
    tracemalloc.start()  # the live server runs in this process: its allocations count
    try:
        refused = researcher.post_file(IMPORT, {"slug": ""}, "definition", "b.zip", bomb)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert refused.status == 400 and "larger than 300 MB unpacked" in refused.text
    assert peak < 64 << 20, f"peak {peak / 2**20:.0f} MiB while refusing the bomb"
    other = researcher.post_file(IMPORT, {"slug": ""}, "definition", "b.zip", unnamed)
    assert other.status == 400 and "does not name" in other.text
    assert not Study.objects.filter(slug__startswith="planted").exists()


NULLABLE_NOT = (
    "description",
    "consent_text",
    "thank_you_text",
    "completion_code",
    "redirect_url",
    "design",
)


def test_6_no_crafted_request_gets_a_server_error(live_server, fingerspelling, bob, media):
    participant_http = Attacker(live_server.url)
    assert participant_http.get("/p/%00/").status == 400
    assert (
        participant_http.request("POST", f"/s/{fingerspelling.slug}/?a=%00", b"consent=yes").status
        == 400
    )
    token = participant_http.enroll(fingerspelling.slug)
    events = f"/p/{token}/events/"
    nul = participant_http.post_json(
        events,
        {
            "events": [
                {"kind": "page_shown", "page": 1, "client_time_ms": 1, "detail": {"a": "\u0000"}}
            ]
        },
    )
    assert nul.status == 400 and "NUL" in nul.json()["error"]
    assert not MediaEvent.objects.exists()
    float_clip = participant_http.post_json(
        events, {"events": [{"kind": "play", "page": 1, "clip": 1.0, "client_time_ms": 2}]}
    )
    assert float_clip.status == 400 and "names clip 1.0" in float_clip.json()["error"]

    researcher = Attacker(live_server.url)
    researcher.sign_in("bob", "pw-bob")
    researcher.get(IMPORT)
    base = export_study(fingerspelling)
    base["study"]["slug"] = "crafted"
    crafted = [(field, None) for field in NULLABLE_NOT]
    crafted += [("title", "A\u0000B"), ("title", ["a", "list"])]
    for field, value in crafted:
        definition = json.loads(json.dumps(base))
        definition["study"][field] = value
        answer = researcher.post_file(
            IMPORT, {}, "definition", "d.json", json.dumps(definition).encode()
        )
        assert answer.status == 400, (field, answer.status)
    for change in (
        lambda d: d["conditions"][0].update(parameters=[1, 2]),
        lambda d: d["conditions"][0]["parameters"].update(rate_hz=int("9" * 4000)),
        lambda d: d["questions"][0]["options"][0].update(value=2**40),
        lambda d: d["questions"][0].update(min_value=5, max_value=1),
    ):
        definition = json.loads(json.dumps(base))
        change(definition)
        text = json.dumps(definition).encode()
        answer = researcher.post_file(IMPORT, {}, "definition", "d.json", text)
        assert answer.status == 400, text[:300]
    assert not Study.objects.filter(slug__startswith="crafted").exists()

    as_draft(fingerspelling)
    roster = f"/admin/studyplatform/study/{fingerspelling.pk}/participants/"
    owner = Attacker(live_server.url)
    owner.sign_in("alice", "pw-alice")
    owner.get(roster)
    review = owner.post_form(roster, {"review": "approved", "participant": "9" * 25})
    assert review.status == 302


def test_7_filters_and_messages_leak_nothing(live_server, fingerspelling, spine, bob, media):
    """Bob's condition list names none of alice's studies; a file name of hers reads as absent."""
    researcher = Attacker(live_server.url)
    researcher.sign_in("bob", "pw-bob")
    conditions = researcher.get("/admin/studyplatform/condition/")
    assert conditions.status == 200 and fingerspelling.title not in conditions.text
    assert spine.title in conditions.text


def test_7_the_asl_page_names_no_python_internals(live_server, fingerspelling, alice, media):
    as_draft(fingerspelling)
    owner = Attacker(live_server.url)
    owner.sign_in("alice", "pw-alice")
    url = f"/admin/studyplatform/study/{fingerspelling.pk}/asl/"
    owner.get(url)
    answer = owner.request(
        "POST",
        url,
        b"content_type=x&object_id=1e9&field_name=text",
        {"Content-Type": "application/x-www-form-urlencoded", "Accept": "application/json"},
    )
    assert answer.status == 400
    assert answer.json()["error"] == "This text is not part of the study."


def test_7_stored_files_are_the_services_alone(settings, media, fingerspelling, tmp_path):
    from django.core.files.base import ContentFile
    from django.core.files.storage import default_storage

    name = default_storage.save("asl/new/consent.webm", ContentFile(tiny_webm()))
    assert (media / name).stat().st_mode & 0o777 == 0o600
    assert (media / "asl" / "new").stat().st_mode & 0o777 == 0o700
    call_command("backup", str(tmp_path / "b.tar.gz"))
    assert (tmp_path / "b.tar.gz").stat().st_mode & 0o077 == 0


def test_7_gunicorn_shares_no_control_socket(monkeypatch):
    from tests.studyplatform.test_settings import ROOT

    values: dict = {}
    exec((ROOT / "deploy" / "gunicorn.conf.py").read_text(), values)
    assert values["control_socket_disable"] is True and "control_socket" not in values
    monkeypatch.setenv("SIGNSTUDY_CONTROL_SOCKET", "/run/signstudy/gunicorn.ctl")
    values = {}
    exec((ROOT / "deploy" / "gunicorn.conf.py").read_text(), values)
    assert values["control_socket"] == "/run/signstudy/gunicorn.ctl"
    assert not values["control_socket_disable"]


def test_6_a_database_outage_answers_503_not_500(rf):
    """bench_load --fault pg-restart: requests during the restart were 500s."""
    from django.db import OperationalError

    from studyplatform.middleware import DatabaseUnavailableMiddleware

    middleware = DatabaseUnavailableMiddleware(lambda request: None)
    refused = OperationalError("connection refused: the database system is starting up")
    answer = middleware.process_exception(rf.get("/s/x/"), refused)
    assert answer.status_code == 503 and answer["Retry-After"] == "5"
    assert middleware.process_exception(rf.get("/"), ValueError("a bug")) is None
