"""Test non-manual signals: spans in a sentence's text, tracks in time, the face technique."""

import numpy as np
import pytest

from synthesis.rigs.face import is_face_dof
from synthesis.signing.nonmanual import (
    HEAD_DOFS,
    Marker,
    NonmanualError,
    Track,
    envelope,
    parse_spans,
)
from synthesis.signing.sentence import SentenceOptions, synthesize
from synthesis.signing.signs import SignError, parse_library
from synthesis.signing.stories import SPINE_STORY
from synthesis.techniques import ClipRequest, build_motion

QUIET = {"liveliness": None}


def test_spans_nest_and_phrase_boundaries_follow_punctuation():
    plain, spans, boundaries = parse_spans("[top [q:0.5 HAVE C-A-R]], I LOST [rhq WHERE].")
    assert plain == "HAVE C-A-R , I LOST WHERE ."
    assert [(s.marker, s.first, s.last, s.intensity) for s in spans] == [
        ("q", 0, 1, 0.5),
        ("top", 0, 1, 1.0),
        ("rhq", 4, 4, 1.0),
    ]
    assert boundaries == {1, 4}
    # A dash between glosses ends a phrase; a hyphenated gloss does not.
    assert parse_spans("GIVE-ME — SAD!")[2] == {0, 1}


@pytest.mark.parametrize(
    "text, message",
    [
        ("I [q LOST", "not closed"),
        ("I LOST]", "closes no"),
        ("I [q] LOST", "holds no signs"),
        ("I [Q! LOST]", "not a non-manual marker"),
        ("I [", "must be followed"),
    ],
)
def test_malformed_spans_are_refused_naming_the_problem(text, message):
    with pytest.raises(NonmanualError, match=message):
        parse_spans(text)
    with pytest.raises(SignError, match=message):
        synthesize(text)


@pytest.mark.parametrize("face", ["on", "neutral", "off"])
def test_an_unknown_marker_is_refused_naming_it_and_the_known_ones(face):
    with pytest.raises(SignError, match=r"'shrug'.*known: .*whq"):
        synthesize("I [shrug LOST]", SentenceOptions(face=face))


def test_the_envelope_rises_before_the_span_holds_and_falls_after():
    marker = Marker("q", "question", onset_ms=200, offset_ms=100)
    track = Track("q", 1000, 2000, 0.8)
    at = np.array([700, 800, 900, 1000, 1500, 2000, 2050, 2100, 2200])
    np.testing.assert_allclose(
        envelope(at, track, marker), [0, 0, 0.4, 0.8, 0.8, 0.8, 0.4, 0, 0], atol=1e-12
    )


def _channel(sentence, name: str) -> np.ndarray:
    return np.degrees(sentence.dofs_rad[:, sentence.body.dof_names.index(name)])


def _frames(sentence, start_ms: float, end_ms: float) -> slice:
    return slice(
        int(np.ceil(start_ms / 1000 * sentence.rate_hz)),
        int(np.floor(end_ms / 1000 * sentence.rate_hz)) + 1,
    )


def test_a_yes_no_question_raises_the_brows_over_its_span_only():
    sentence = synthesize("I LOST, [q HAVE C-A-R]?", SentenceOptions(**QUIET))
    (track,) = sentence.tracks
    assert track.marker == "q"
    brow = _channel(sentence, "right_brow_raise")
    assert brow[_frames(sentence, track.start_ms, track.end_ms)].min() > 6.0
    assert np.abs(brow[_frames(sentence, 0, track.start_ms - 250)]).max() < 1e-9
    head = _channel(sentence, "head_flexion")
    assert head[_frames(sentence, track.start_ms, track.end_ms)].min() > 5.0


def test_the_story_marks_a_rhetorical_question_a_negation_and_a_mouth_morpheme():
    sentence = synthesize(SPINE_STORY[1], SentenceOptions(**QUIET))
    by_name = {track.marker: track for track in sentence.tracks}
    assert {"rhq", "neg", "sad"} <= set(by_name)
    rhq = by_name["rhq"]
    brow = _channel(sentence, "left_brow_raise")
    assert brow[_frames(sentence, rhq.start_ms, rhq.end_ms)].min() > 6.0
    # The negation shakes the head: it swings both ways over CAN'T FIND.
    neg = by_name["neg"]
    shake = _channel(sentence, "head_rotation")[_frames(sentence, neg.start_ms, neg.end_ms)]
    assert shake.max() > 5.0 and shake.min() < -5.0
    # BIG carries CHA: the jaw drops over the sign.
    big = synthesize(SPINE_STORY[2], SentenceOptions(**QUIET))
    cha = next(track for track in big.tracks if track.marker == "cha")
    assert _channel(big, "jaw_open")[_frames(big, cha.start_ms, cha.end_ms)].min() > 10.0


@pytest.mark.parametrize("text", SPINE_STORY)
def test_face_off_and_neutral_differ_from_on_only_in_face_channels(text):
    on = synthesize(text, SentenceOptions())
    face = np.array([is_face_dof(name) or name in HEAD_DOFS for name in on.body.dof_names])
    for mode in ("neutral", "off"):
        other = synthesize(text, SentenceOptions(face=mode))
        np.testing.assert_array_equal(other.dofs_rad[:, ~face], on.dofs_rad[:, ~face])
        assert not other.tracks
    assert np.abs(
        on.dofs_rad[:, face] - synthesize(text, SentenceOptions(face="off")).dofs_rad[:, face]
    ).max() > np.radians(5)
    off = synthesize(text, SentenceOptions(face="off"))
    assert not off.dofs_rad[:, [is_face_dof(n) for n in off.body.dof_names]].any()
    neutral = synthesize(text, SentenceOptions(face="neutral"))
    lid = _channel(neutral, "right_upper_lid_close")
    assert neutral.blinks_ms and lid.max() > 40.0  # it blinks at the phrase boundaries
    assert np.abs(_channel(neutral, "right_brow_raise")).max() < 1e-9


def test_gaze_leads_a_keyed_head_turn():
    """LOOKING-BACK turns the head 25° to the signer's right; the eyes turn with it, and
    start earlier (the stagger's eyes_ms)."""
    sentence = synthesize("LOOKING-BACK", SentenceOptions(face="neutral", **QUIET))
    eye = _channel(sentence, "right_eye_turn")
    head = _channel(sentence, "head_rotation")
    assert eye.min() < -10.0
    first_eye = np.argmax(eye < eye.min() * 0.1)
    first_head = np.argmax(head < head.min() * 0.1)
    assert first_eye < first_head


def test_a_left_handed_signer_mirrors_the_signals():
    right = synthesize(SPINE_STORY[1], SentenceOptions(**QUIET))
    left = synthesize(SPINE_STORY[1], SentenceOptions(dominant="left", **QUIET))
    np.testing.assert_allclose(left.dofs_rad, left.body.mirror_pose(right.dofs_rad), atol=1e-12)


def test_the_library_refuses_an_unknown_signal_and_pose_naming_them():
    base = {
        "format": "signstudy.sign-library",
        "version": 1,
        "signs": {"ME": {"keys": [{"right": {"at": [0.1, 0.2, 0.0]}}]}},
    }
    with pytest.raises(SignError, match="ME: unknown non-manual signal 'wow'"):
        parse_library({**base, "signs": {"ME": {**base["signs"]["ME"], "nonmanual": "wow"}}})
    with pytest.raises(SignError, match="unknown face pose or channel 'grin'"):
        parse_library({**base, "nonmanuals": {"x": {"face": {"grin": 1}}}})
    with pytest.raises(SignError, match="unknown head angle 'roll'"):
        parse_library({**base, "nonmanuals": {"x": {"oscillate": {"angle": "roll"}}}})


def test_the_face_technique_is_a_condition_parameter():
    on = build_motion(ClipRequest("sentence", SPINE_STORY[3], {"face": "on"}))
    off = build_motion(ClipRequest("sentence", SPINE_STORY[3], {"face": "off"}))
    names = on.rig.dof_names
    face = np.array([is_face_dof(name) or name in HEAD_DOFS for name in names])
    np.testing.assert_array_equal(np.asarray(on.motion)[:, ~face], np.asarray(off.motion)[:, ~face])
    assert not np.array_equal(np.asarray(on.motion), np.asarray(off.motion))
    assert ClipRequest("sentence", "ME").parameters["face"] == "on"
    with pytest.raises(Exception, match="face"):
        ClipRequest("sentence", "ME", {"face": "smile"})
