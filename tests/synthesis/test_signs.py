"""Test the sign library format and the shipped library."""

import pytest
import yaml

from synthesis.signing.sentence import parse_glosses
from synthesis.signing.signs import SignError, default_library, parse_library, read_library
from synthesis.signing.stories import SPINE_STORY


def test_the_shipped_library_has_every_sign_of_the_story():
    library = default_library()
    for text in SPINE_STORY:
        for token in parse_glosses(text):
            if "-" in token and all(len(p) == 1 for p in token.split("-")):
                continue  # fingerspelled
            assert library.sign(token)


def _library(signs, **extra):
    return {
        "format": "signstudy.sign-library",
        "version": 1,
        "signs": signs,
        "locations": {"neutral": [0.1, 0.3, -0.2]},
        **extra,
    }


def test_a_left_hand_is_written_as_a_right_hand_and_mirrored():
    library = parse_library(
        _library(
            {
                "X": {
                    "keys": [
                        {
                            "ms": 0,
                            "right": {"at": "neutral", "palm": "in"},
                            "left": {"at": "neutral", "palm": "in"},
                        }
                    ]
                }
            }
        )
    )
    key = library.sign("x")[0]
    assert key.hands["right"].at_m[0] == 0.1 and key.hands["left"].at_m[0] == -0.1
    assert key.hands["right"].palm[0] == -1 and key.hands["left"].palm[0] == 1


@pytest.mark.parametrize(
    ("signs", "message"),
    [
        ({"X": {"keys": [{"ms": 0, "right": {"at": "nowhere"}}]}}, "X key 1: unknown or malformed"),
        ({"X": {"keys": [{"ms": 0, "right": {"at": "neutral", "shape": "7"}}]}}, "handshape '7'"),
        (
            {"X": {"keys": [{"ms": 0, "right": {"at": "neutral", "palm": "sideways"}}]}},
            "unknown direction 'sideways'",
        ),
        ({"X": {"keys": [{"ms": 50}, {"ms": 0}]}}, "X: keys must be in time order"),
        ({"X": {"keys": []}}, "X: a sign needs at least one key"),
        ({"X": {"keys": [{"ms": 0, "spine": {"lean": 4}}]}}, "unknown spine angle 'lean'"),
        (
            {"X": {"keys": [{"ms": 0, "left": {"at": "neutral", "bdy": "chest"}}]}},
            "X key 1: a hand key has no field 'bdy'",
        ),
        # YAML reads an unquoted "on: chest" as {True: "chest"} (six left-hand keys of
        # HAVE, SAD, SURPRISE and GIVE-ME, read as no body part until issue 52).
        (
            {"X": {"keys": [{"ms": 0, "left": {"at": "neutral", True: "chest"}}]}},
            r"no field True \(YAML's on, off, yes or no\)",
        ),
    ],
)
def test_malformed_libraries_are_clear_errors(signs, message):
    with pytest.raises(SignError, match=message):
        parse_library(_library(signs))


def test_reading_a_file(tmp_path):
    path = tmp_path / "signs.yaml"
    path.write_text(yaml.safe_dump(_library({"HI": {"keys": [{"ms": 0}]}})), encoding="utf-8")
    assert read_library(path).sign("HI")
    path.write_text("format: [", encoding="utf-8")
    with pytest.raises(SignError, match="not YAML"):
        read_library(path)
    with pytest.raises(SignError, match="Not a sign library"):
        parse_library({"format": "other"})
