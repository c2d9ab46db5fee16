"""The standing hostile-input harness: every endpoint that takes a file, a zip, a
definition or a technique parameter, fed generated malformed inputs (issue 51).

The endpoints are found from the URLconf and the admin (:func:`file_accepting`): a view
of the project whose own code reads ``request.FILES`` or ``request.body``, and the admin
add and change pages of every model (or inline) with a file field or technique
parameters. :data:`HARNESS` holds an entry for each, and
:func:`test_every_file_accepting_endpoint_has_an_entry` fails when a new one has none.

Each entry sends what its kind of input can be, made hostile: issue 51's named cases,
then Hypothesis's damage to good files (tests/hostile.py) — glTF/VRM JSON and binary
chunks, BVH, ``.pose``, videos, zips and manifests, definitions, parameters, and the
language code the JavaScript catalogue takes in its URL. Every
answer must be a 4xx or an accepted object, never ≥ 500, within its CPU time (the wall
clock only guards against a hang) and with the web process's Python allocations under
64 MB (parsers run confined, outside it); what a victim researcher had saved must be
unchanged after all of it. Seeded and quick here (``HOSTILE_EXAMPLES`` examples an
endpoint); ``-m release`` runs 25 times as many.
"""

import copy
import inspect
import json
import os
import re
import time
import tracemalloc
from collections import Counter, defaultdict
from collections.abc import Callable
from dataclasses import dataclass
from html.parser import HTMLParser
from urllib.parse import quote

import numpy as np
import pytest
from django.conf import settings as django_settings
from django.core.files.uploadedfile import SimpleUploadedFile
from django.db import models
from django.test import Client
from django.urls import URLResolver, get_resolver, reverse
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from studyplatform.lib.exchange import export_study
from studyplatform.models import Avatar, Condition, Recording, Study, UploadedClip
from synthesis.capture import format_pose, from_hand_motion
from synthesis.fingerspelling.spelling import spell
from synthesis.rigs.hand import HandModel
from synthesis.skeleton.bvh import format_bvh
from synthesis.timing import simulate_recording
from tests.conftest import as_draft, tiny_webm
from tests.hostile import (
    GLTF_CASES,
    corrupt_deflate_zip,
    damaged_bytes,
    damaged_glb,
    damaged_text,
    encrypted_member_zip,
    with_animation,
    zip_of,
)
from tests.studyplatform.test_fuzz import _mutate, _raw_json
from tests.synthesis.humanoids import humanoid_glb

pytestmark = pytest.mark.django_db

QUICK = int(os.environ.get("HOSTILE_EXAMPLES", "6"))
MAX_PEAK_BYTES = 64 * 1024**2
# The study's own upload pages answer a script in JSON: 400 naming the problem, or saved
# (a browser's post is redirected back to the page with the message instead).
JSON = {"Accept": "application/json"}
STATUSES: dict[str, Counter] = defaultdict(Counter)  # by endpoint, for the summary
WORST: dict[str, list[float]] = defaultdict(lambda: [0.0, 0.0])  # CPU seconds, peak MB
WALL_MARGIN = 4
# An endpoint's first request also pays for what later ones find ready (imports, template
# compilation, the engine's identity digest): 20.7 s of CPU once on a study page whose
# later requests took under 5 s. It gets this many times the budget.
COLD_MARGIN = 3
WARMED: set[str] = set()
JOBS: Counter = Counter()  # the background jobs' outcomes in this entry, by status

# --- finding the endpoints ---------------------------------------------------------------

READS_INPUT = re.compile(r"request\.FILES|request\.body")


def _routes(patterns=None, prefix: str = ""):
    for pattern in get_resolver().url_patterns if patterns is None else patterns:
        if isinstance(pattern, URLResolver):
            yield from _routes(pattern.url_patterns, prefix + str(pattern.pattern))
        else:
            yield prefix + str(pattern.pattern), pattern.name, pattern.callback


def _takes_files(admin_class, model) -> set[str]:
    """Return the file and technique-parameter fields an admin (or inline) of *model*
    edits: the model's, less what its declared fields leave out and its read-only ones."""
    takes = {
        field.name
        for field in model._meta.get_fields()
        if isinstance(field, models.FileField)
        or (isinstance(field, models.JSONField) and field.name == "parameters")
    }
    declared = admin_class.fields
    if declared is None and admin_class.fieldsets:
        declared = [name for _, options in admin_class.fieldsets for name in options["fields"]]
    if declared is not None:
        takes &= set(declared)
    return takes - set(admin_class.readonly_fields or ())


def _source(view, depth: int = 2) -> str:
    """Return *view*'s source with that of the methods of its own class it calls."""
    text = inspect.getsource(view)
    owner = getattr(view, "__self__", None)
    if owner is None or depth == 0:
        return text
    for name in sorted(set(re.findall(r"self\.(\w+)\(", text))):
        method = getattr(owner, name, None)
        if inspect.ismethod(method) and method.__module__.startswith("studyplatform"):
            text += _source(method, depth - 1)
    return text


def file_accepting(routes=None) -> dict[str, str]:
    """Return each URL name whose view takes a file, a zip, a definition or technique
    parameters, with why it is counted."""
    found = {}
    for _, name, callback in _routes() if routes is None else routes:
        view = inspect.unwrap(callback)
        owner = getattr(view, "__self__", None)
        module = getattr(view, "__module__", "") or ""
        ours = name and module.startswith(("studyplatform", "tests"))
        if ours and READS_INPUT.search(_source(view)):
            found[name] = "its code reads the request's files or body"
        if name and hasattr(owner, "model") and name.endswith(("_add", "_change")):
            admins = [(owner, owner.model), *((inline, inline.model) for inline in owner.inlines)]
            fields = sorted({field for each in admins for field in _takes_files(*each)})
            if fields:
                found[name] = f"its admin form edits {', '.join(fields)}"
    return found


# --- what the harness sends --------------------------------------------------------------


@dataclass
class Ctx:
    """The attacker (bob, signed in), his studies, and the victim's (alice's) study."""

    client: Client
    words: Study  # bob's fingerspelling study: words take recordings
    spine: Study  # bob's spine study, one condition of uploaded clips
    victim: Study


@dataclass(frozen=True)
class Entry:
    """How to send one endpoint one hostile input, and how to draw one."""

    kind: str
    send: Callable[[Ctx, object], object]
    draw: Callable[[st.DataObject], object]
    cases: Callable[[], tuple] = tuple  # issue 51's named inputs, made when sent
    seconds: float = 20.0


class _Form(HTMLParser):
    """The fields of an admin page's form, as a browser would post them."""

    def __init__(self):
        super().__init__()
        self.fields, self._select, self._textarea = {}, None, None

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        name = a.get("name")
        if tag == "input" and name and a.get("type") not in ("submit", "button", "file"):
            if a.get("type") in ("checkbox", "radio") and "checked" not in a:
                return
            self.fields[name] = a.get("value", "on")
        elif tag == "select" and name:
            self._select = name
            self.fields.setdefault(name, "")
        elif tag == "option" and self._select and "selected" in a:
            self.fields[self._select] = a.get("value", "")
        elif tag == "textarea" and name:
            self._textarea = name
            self.fields[name] = ""

    def handle_endtag(self, tag):
        if tag == "select":
            self._select = None
        elif tag == "textarea":
            self._textarea = None

    def handle_data(self, data):
        if self._textarea:
            self.fields[self._textarea] += data


def form_of(client: Client, url: str) -> dict:
    parser = _Form()
    parser.feed(client.get(url).content.decode())
    return parser.fields


def _glb_input(data: st.DataObject) -> bytes:
    good = data.draw(st.sampled_from(["plain", "vrm", "animated"]))
    base = {
        "plain": GOOD_GLB,
        "vrm": GOOD_VRM,
        "animated": with_animation(GOOD_GLB, [0.0, 0.5, 1.0]),
    }[good]
    return data.draw(damaged_glb(base))


def _send_avatar(ctx: Ctx, data: bytes):
    upload = SimpleUploadedFile("hostile.vrm", data)
    fields = {"upload": upload, "name": "h", "licence": "CC0", "source": ""}
    return ctx.client.post(reverse("admin:studyplatform_avatar_add"), fields)


def _send_avatar_mapping(ctx: Ctx, bones):
    avatar = Avatar.objects.filter(owner__username="bob").first()
    url = reverse("admin:studyplatform_avatar_change", args=[avatar.pk])
    fields = form_of(ctx.client, url)
    fields["bone_mapping"] = bones if isinstance(bones, str) else json.dumps(bones)
    return ctx.client.post(url, fields)


def _recording_input(data: st.DataObject) -> tuple[str, bytes]:
    kind = data.draw(st.sampled_from([".bvh", ".pose", ".glb", ".mp4"]))
    if kind == ".bvh":
        return "hostile.bvh", data.draw(damaged_text(GOOD_BVH))
    if kind == ".pose":
        return "hostile.pose", data.draw(damaged_bytes(GOOD_POSE))
    if kind == ".glb":
        return "hostile.glb", data.draw(damaged_glb(with_animation(GOOD_GLB, [0.0, 1.0])))
    return "hostile.webm", data.draw(damaged_bytes(GOOD_VIDEO))


def _send_recording(ctx: Ctx, named: tuple[str, bytes]):
    name, data = named
    word = ctx.words.items.filter(kind="word").first()
    url = reverse("admin:studyplatform_study_recordings", args=[ctx.words.pk])
    fields = {"item": word.pk, "recording": SimpleUploadedFile(name, data)}
    return _then_jobs(ctx.client.post(url, fields, headers=JSON))


def _then_jobs(response):
    """Run the background jobs a taken upload queued (the test's transaction never
    commits, so they did not run): a recording's preparation, a clip's conversion. Each
    must end in a status, a hostile file's being failed; their outcomes are counted."""
    from studyplatform.models import ClipUpload
    from studyplatform.tasks import prepare_clips_now, prepare_now

    for recording in Recording.objects.filter(status="capturing").exclude(upload=""):
        if not recording.is_video:  # MediaPipe's capture is the recordings tests' part
            JOBS[f"recording {prepare_now(recording.pk)}"] += 1
    for job in ClipUpload.objects.filter(status="queued"):
        JOBS[f"clip upload {prepare_clips_now(job.pk)}"] += 1
    return response


def _send_clip(ctx: Ctx, data: bytes):
    condition = ctx.spine.conditions.get(source="uploaded")
    item = ctx.spine.items.first()
    url = reverse("admin:studyplatform_study_uploads", args=[ctx.spine.pk])
    fields = {"condition": condition.pk, "item": item.pk}
    clip = SimpleUploadedFile("clip.mp4", data)
    return _then_jobs(ctx.client.post(url, {**fields, "clip": clip}, headers=JSON))


def _manifest(rows: list[list[str]]) -> bytes:
    return "\n".join(",".join(row) for row in [["item", "condition", "file"], *rows]).encode()


def _clips_zip_input(data: st.DataObject) -> bytes:
    name = data.draw(st.sampled_from(["a.mp4", "../a.mp4", "/etc/passwd", "a\x00.mp4", "d/a.mp4"]))
    field = data.draw(st.sampled_from(["S1", "spine-off", "x" * 200_000, '"', "a,b", "\x00"]))
    member = data.draw(st.sampled_from([GOOD_VIDEO, b"", b"#EXTM3U\nhttp://x/\n"]))
    rows = [[field, "spine-off", name]] * data.draw(st.integers(1, 3))
    return zip_of({"manifest.csv": _manifest(rows), name.lstrip("/"): member})


def _uploads_input(data: st.DataObject) -> bytes:
    return _clips_zip_input(data) if data.draw(st.booleans()) else _video_input(data)


def _send_clips_zip(ctx: Ctx, data: bytes):
    url = reverse("admin:studyplatform_study_uploads", args=[ctx.spine.pk])
    archive = SimpleUploadedFile("clips.zip", data)
    return _then_jobs(ctx.client.post(url, {"archive": archive}, headers=JSON))


def _clips_zip_cases() -> tuple:
    manifest = _manifest([["S1", "spine-off", "a.mp4"]])
    return (
        zip_of({"manifest.csv": _manifest([["x" * 200_000, "spine-off", "a.mp4"]])}),
        encrypted_member_zip("manifest.csv", manifest),
        corrupt_deflate_zip("manifest.csv", manifest * 50),
        zip_of({"manifest.csv": manifest, **{f"f{k}.mp4": b"" for k in range(2001)}}),
        zip_of({"manifest.csv": _manifest([["S1", "spine-off", "../../var/secret_key"]])}),
    )


def _definition_input(data: st.DataObject) -> bytes:
    seed = data.draw(st.integers(0, 2**32 - 1))
    import random

    rng = random.Random(seed)
    return _raw_json(rng, _mutate(rng, copy.deepcopy(SPINE_DEFINITION)))


def _send_definition(ctx: Ctx, data: bytes):
    name = "d.zip" if data[:2] == b"PK" else "d.json"
    upload = SimpleUploadedFile(name, data)
    return ctx.client.post(reverse("admin:studyplatform_study_import"), {"definition": upload})


def _definition_cases() -> tuple:
    cases = []
    for study in (-1, "x", [], None, {"title": ["x"]}):
        cases.append(json.dumps({**SPINE_DEFINITION, "study": study}).encode())
    for parameters in (
        {"source": "recording", "recording": "/proc/self/environ"},
        {"avatar_file": "../../var/secret_key"},
        {"hand_database": "/etc/passwd"},
        {"recording": {"$ref": "x"}},
    ):
        definition = copy.deepcopy(SPINE_DEFINITION)
        definition["study"]["slug"] = "hostile-parameters"
        definition["conditions"][0]["parameters"] = parameters
        cases.append(json.dumps(definition).encode())
    definition = json.dumps(SPINE_DEFINITION).encode()
    cases += [
        encrypted_member_zip("study.json", definition),
        corrupt_deflate_zip("study.json", definition),
        zip_of({"study.json": definition, "files/../../x": b"x"}),
    ]
    return tuple(cases)


def _asl_input(data: st.DataObject) -> bytes:
    return data.draw(damaged_bytes(GOOD_VIDEO))


def _send_asl(ctx: Ctx, data: bytes):
    from django.contrib.contenttypes.models import ContentType

    url = reverse("admin:studyplatform_study_asl", args=[ctx.spine.pk])
    fields = {
        "content_type": ContentType.objects.get_for_model(Study).pk,
        "object_id": ctx.spine.pk,
        "field_name": "description",
        "video": SimpleUploadedFile("asl.webm", data),
    }
    return ctx.client.post(url, fields, headers=JSON)


def _send_template(ctx: Ctx, data: bytes):
    url = reverse("admin:studyplatform_signedtemplate_add")
    fields = {"name": "t", "kind": form_of(ctx.client, url).get("kind", ""), "transcript": "t"}
    return ctx.client.post(url, {**fields, "video": SimpleUploadedFile("t.webm", data)})


def _send_template_change(ctx: Ctx, data: bytes):
    from studyplatform.models import SignedTemplate

    template = SignedTemplate.objects.filter(owner__username="bob").first()
    if template is None:
        return _send_template(ctx, data)
    url = reverse("admin:studyplatform_signedtemplate_change", args=[template.pk])
    fields = form_of(ctx.client, url)
    return ctx.client.post(url, {**fields, "video": SimpleUploadedFile("t.webm", data)})


PARAMETER_VALUES = st.one_of(
    st.sampled_from(
        [
            "/proc/self/environ",
            "../../var/secret_key",
            "recording:1",
            "avatar:1",
            "recording:99999999999999999999",
            "file:///etc/passwd",
            "x" * 5000,
            "\x00",
            "libras",
            "../alphabets/asl",
        ]
    ),
    st.integers(-(2**70), 2**70),
    st.floats(),
    st.booleans(),
    st.none(),
    st.lists(st.text(max_size=5), max_size=3),
    st.dictionaries(st.text(max_size=5), st.none()),
)
PARAMETER_NAMES = st.sampled_from(
    [
        "recording",
        "avatar_file",
        "hand_database",
        "transition_db",
        "library",
        "lexicon",
        "model",
        "timing_file",
        "source",
        "alphabet",
        "timing",
        "rate_hz",
        "seed",
        "width",
        "x",
    ]
)


def _parameters_input(data: st.DataObject) -> dict:
    return data.draw(st.dictionaries(PARAMETER_NAMES, PARAMETER_VALUES, max_size=3))


def _send_condition(ctx: Ctx, parameters: dict, change: bool = False):
    condition = ctx.spine.conditions.exclude(source="uploaded").first()
    url = (
        reverse("admin:studyplatform_condition_change", args=[condition.pk])
        if change
        else reverse("admin:studyplatform_condition_add")
    )
    fields = form_of(ctx.client, url)
    fields.update({"study": str(ctx.spine.pk), "key": fields.get("key") or "hostile"})
    fields["label"] = fields.get("label") or "Hostile"
    for name, value in parameters.items():
        if f"technique_{name}" in fields and not isinstance(value, dict | list):
            fields[f"technique_{name}"] = str(value)
    fields["parameters"] = json.dumps(parameters, default=str)
    return ctx.client.post(url, fields)


def _signed_answer_input(data: st.DataObject) -> tuple[dict, bytes]:
    headers = {
        "X-Upload-Take": data.draw(st.sampled_from(["", TAKE, "\x00", "x" * 100])),
        "X-Upload-Offset": data.draw(st.sampled_from(["0", "-1", "1e3", "9" * 20, ""])),
        "X-Upload-Final": data.draw(st.sampled_from(["0", "1"])),
        "X-Upload-Sha256": data.draw(st.sampled_from(["", "0" * 64, "zz"])),
        "X-Upload-Duration-Ms": data.draw(st.sampled_from(["", "NaN", "-5", "1e400", "900"])),
    }
    return headers, data.draw(damaged_bytes(GOOD_VIDEO))


def _send_signed_answer(ctx: Ctx, sent: tuple[dict, bytes]):
    headers, body = sent
    participant, number = SIGNED_PAGE[0]
    url = f"/p/{participant.token}/{number}/signed/comments/"
    return Client().post(url, body, content_type="application/octet-stream", headers=headers)


def _language_input(data: st.DataObject) -> str:
    return data.draw(st.one_of(st.text(min_size=1, max_size=300), st.sampled_from(LANGUAGE_CASES)))


LANGUAGE_CASES = (
    "pt-br",
    "PT-BR",
    "tr\x00",
    "..",
    "%2e%2e%2fsettings",
    "en;rm -rf",
    "x" * 5000,
    "zh-hans",
    "../../locale/tr/LC_MESSAGES/django.po",
)


def _send_language(ctx: Ctx, language: str):
    """Ask for a JavaScript catalogue in a hostile language code (the URL's one part)."""
    response = Client().get(f"/jsi18n/{quote(language, safe='')}/")
    known = {code for code, _ in django_settings.LANGUAGES}
    wanted = (200,) if language in known else range(400, 500)
    assert response.status_code in wanted, (language, response.status_code)
    return response


ASL_PREFIX = "studyplatform-aslvideo-content_type-object_id"


def _inline_asl(model_name: str, view: str):
    """Post a hostile video as a new ASL video row on a design row's admin page."""

    def send(ctx: Ctx, data: bytes):
        from django.apps import apps

        from studyplatform.models import PARTICIPANT_FACING_FIELDS

        model = apps.get_model("studyplatform", model_name)
        lookup = {"answeroption": "question__study", "study": "pk"}.get(model_name, "study")
        row = model.objects.filter(**{lookup: ctx.spine.pk}).first()
        args = [row.pk] if view == "change" else []
        url = reverse(f"admin:studyplatform_{model_name}_{view}", args=args)
        fields = form_of(ctx.client, url)
        if view == "add":
            fields.update({"study": str(ctx.spine.pk), "key": "hostile", "title": "Hostile"})
            fields.update({"slug": "hostile-study"})
            if model_name == "answeroption":
                fields["question"] = str(ctx.spine.questions.first().pk)
        fields[f"{ASL_PREFIX}-TOTAL_FORMS"] = "1"
        fields[f"{ASL_PREFIX}-0-field_name"] = PARTICIPANT_FACING_FIELDS[model_name][0]
        files = {
            f"{ASL_PREFIX}-0-video": SimpleUploadedFile("asl.webm", data),
            f"{ASL_PREFIX}-0-poster": SimpleUploadedFile("asl.png", data[:64]),
        }
        return ctx.client.post(url, {**fields, **files})

    return send


def _video_input(data: st.DataObject) -> bytes:
    return data.draw(damaged_bytes(GOOD_VIDEO))


# --- good files the damage starts from ---------------------------------------------------

GOOD_GLB = humanoid_glb()
GOOD_VRM = humanoid_glb(vrm=True, morphs=("eyeBlinkLeft",), expressions={"blink": 0})
GOOD_VIDEO = tiny_webm()
TAKE = "0b7c6f2e-4a1d-4e8b-9c3f-5d2a1b0e9f81"
SIGNED_PAGE: list = []  # (participant, page number), made per test
SPINE_DEFINITION: dict = {}


def _good_bvh() -> str:
    motion, _ = simulate_recording("AB", np.random.default_rng(1), rate_hz=20.0)
    return format_bvh(motion)


def _good_pose() -> bytes:
    _, truth = simulate_recording("AB", np.random.default_rng(1), rate_hz=20.0)
    dofs = spell("AB", "right", 20.0, truth, 250.0)
    return format_pose(from_hand_motion(HandModel(), dofs, 20.0))


GOOD_BVH, GOOD_POSE = _good_bvh(), _good_pose()


def _gltf_cases(reader: str) -> tuple:
    return tuple(
        make(GOOD_VRM if vrm else with_animation(GOOD_GLB, [0.0, 0.5, 1.0]))
        for make, vrm, readers in GLTF_CASES.values()
        if reader in readers
    )


HARNESS: dict[str, Entry] = {
    "studyplatform_study_import": Entry(
        "definition", _send_definition, _definition_input, _definition_cases
    ),
    "studyplatform_avatar_add": Entry(
        "glTF/VRM", _send_avatar, _glb_input, lambda: _gltf_cases("avatar")
    ),
    "studyplatform_avatar_change": Entry(
        "bone mapping",
        _send_avatar_mapping,
        lambda data: data.draw(st.dictionaries(st.text(max_size=12), PARAMETER_VALUES, max_size=4)),
        lambda: ("[1, 2]", '{"Hips": "nonexistent"}', "x" * 100_000, '{"Hips": ["hips"]}'),
    ),
    "studyplatform_study_recordings": Entry(
        "BVH, .pose, glTF, video",
        _send_recording,
        _recording_input,
        lambda: tuple(("motion.glb", data) for data in _gltf_cases("motion")),
    ),
    "studyplatform_study_uploads": Entry(
        "video; zip with manifest",
        lambda ctx, data: (_send_clips_zip if data[:2] == b"PK" else _send_clip)(ctx, data),
        _uploads_input,
        _clips_zip_cases,
        seconds=60.0,
    ),
    "studyplatform_study_asl": Entry("video", _send_asl, _asl_input, seconds=60.0),
    "studyplatform_signedtemplate_add": Entry(
        "video", lambda ctx, data: _send_template(ctx, data), _video_input, seconds=60.0
    ),
    "studyplatform_signedtemplate_change": Entry(
        "video", _send_template_change, _video_input, seconds=60.0
    ),
    "studyplatform_condition_add": Entry(
        "technique parameters", _send_condition, _parameters_input
    ),
    "studyplatform_condition_change": Entry(
        "technique parameters",
        lambda ctx, parameters: _send_condition(ctx, parameters, change=True),
        _parameters_input,
    ),
    "javascript_catalog": Entry(
        "language code", _send_language, _language_input, lambda: LANGUAGE_CASES, seconds=5.0
    ),
    "participant_signed_answer": Entry(
        "signed-answer chunks", _send_signed_answer, _signed_answer_input, seconds=60.0
    ),
    **{
        f"studyplatform_{model}_{view}": Entry(
            "ASL video row", _inline_asl(model, view), _video_input
        )
        for model in ("study", "question", "answeroption", "block", "trial")
        for view in ("add", "change")
    },
}


# --- the tests ---------------------------------------------------------------------------


def test_every_file_accepting_endpoint_has_an_entry():
    found = file_accepting()
    missing = {name: why for name, why in found.items() if name not in HARNESS}
    assert not missing, f"endpoints without a hostile-input harness entry: {missing}"
    names = {name for _, name, _ in _routes()}
    assert not set(HARNESS) - names, "harness entries for endpoints that no longer exist"
    assert len(found) >= 15


def _planted(request):
    return request.FILES.get("x")


def test_the_discovery_finds_a_new_upload_view():
    """A view reading request.FILES that no entry covers is found (and would fail above)."""
    found = file_accepting([("planted/", "planted_upload", _planted)])
    assert found == {"planted_upload": "its code reads the request's files or body"}


@pytest.fixture
def ctx(client, fingerspelling, spine, bob, settings, tmp_path):
    from studyplatform.actions import do_import_study
    from studyplatform.demo import fingerspelling_timing_study
    from tests.studyplatform.test_attacks import _signed_page
    from tests.studyplatform.test_participate import _start

    settings.MEDIA_ROOT = tmp_path / "media"
    global SPINE_DEFINITION
    SPINE_DEFINITION = export_study(spine)
    words = do_import_study(fingerspelling_timing_study(), owner=bob, slug="bob-words").study
    as_draft(spine)
    Condition.objects.filter(study=spine, key="spine-off").update(source="uploaded", parameters={})
    from studyplatform.demo import spine_study

    taking = do_import_study(spine_study(), owner=bob, slug="bob-spine-open").study
    participant = _start(Client(), taking)
    participant.reached = len(participant.schedule)
    participant.save()
    SIGNED_PAGE[:] = [(participant, _signed_page(participant))]
    client.force_login(bob)
    client.raise_request_exception = False
    from studyplatform.actions.avatars import do_upload_avatar

    do_upload_avatar(bob, SimpleUploadedFile("good.glb", GOOD_GLB), "good", "CC0")
    return Ctx(client, words, Study.objects.get(pk=spine.pk), fingerspelling)


def _victim_state(victim: Study) -> dict:
    """What no request of bob's may change: alice's study, recordings, avatars, clips."""
    return {
        "study": export_study(Study.objects.get(pk=victim.pk)),
        "recordings": sorted(
            Recording.objects.exclude(item__study__owner__username="bob").values_list(
                "pk", "sha256", "status"
            )
        ),
        "avatars": sorted(
            Avatar.objects.exclude(owner__username="bob").values_list("pk", "sha256")
        ),
        "clips": sorted(
            UploadedClip.objects.exclude(condition__study__owner__username="bob").values_list(
                "pk", "sha256"
            )
        ),
    }


def _cpu_seconds() -> float:
    """Return the CPU time of this process and of its finished children (the confined
    parsers), user and system."""
    return sum(os.times()[:4])


def _send(name: str, ctx: Ctx, entry: Entry, sent) -> None:
    tracemalloc.start()
    started, cpu_started = time.perf_counter(), _cpu_seconds()
    try:
        response = entry.send(ctx, sent)
    finally:
        elapsed = time.perf_counter() - started
        seconds = _cpu_seconds() - cpu_started
        _, peak = tracemalloc.get_traced_memory()
        tracemalloc.stop()
    STATUSES[name][response.status_code] += 1
    worst = WORST[name]
    worst[0], worst[1] = max(worst[0], seconds), max(worst[1], peak / 1024**2)
    assert response.status_code < 500, (name, repr(sent)[:300], response.content[:500])
    # The budget is work done (CPU), which a loaded machine does not stretch; the wall
    # clock only has to show nothing hung, so it gets a margin for waiting on the CPU.
    budget = entry.seconds * (1 if name in WARMED else COLD_MARGIN)
    WARMED.add(name)
    assert seconds < budget, (name, seconds, repr(sent)[:300])
    assert elapsed < WALL_MARGIN * budget, (name, elapsed, repr(sent)[:300])
    assert peak < MAX_PEAK_BYTES, (name, peak, repr(sent)[:300])


def _run_entry(name: str, ctx: Ctx, examples: int) -> None:
    entry = HARNESS[name]
    JOBS.clear()
    before = _victim_state(ctx.victim)
    for case in entry.cases():
        _send(name, ctx, entry, case)

    @settings(
        max_examples=examples,
        derandomize=True,
        database=None,
        deadline=None,
        suppress_health_check=list(HealthCheck),
    )
    @given(data=st.data())
    def generated(data):
        _send(name, ctx, entry, entry.draw(data))

    generated()
    assert _victim_state(ctx.victim) == before
    print(
        f"{name} ({entry.kind}): {sum(STATUSES[name].values())} inputs, "
        f"statuses {dict(sorted(STATUSES[name].items()))}, worst {WORST[name][0]:.2f} CPU s, "
        f"peak {WORST[name][1]:.1f} MB; background jobs {dict(sorted(JOBS.items()))}"
    )


@pytest.mark.parametrize("name", sorted(HARNESS))
def test_hostile_inputs_answer_4xx_or_are_taken(name, ctx):
    _run_entry(name, ctx, QUICK)


@pytest.mark.release
@pytest.mark.parametrize("name", sorted(HARNESS))
def test_hostile_inputs_at_length(name, ctx):
    _run_entry(name, ctx, 25 * QUICK)
