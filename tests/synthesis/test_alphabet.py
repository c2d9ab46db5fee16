"""Test the ASL alphabet data: every letter valid, contacts holding, handshape features."""

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from synthesis.fingerspelling.alphabet import (
    LETTERS,
    AlphabetError,
    alphabet,
    contact_gaps_m,
    letter,
    letter_pose,
)
from synthesis.rigs.hand import HandModel
from synthesis.rigs.landmarks import LANDMARK_NAMES, landmarks

ROOT = Path(__file__).resolve().parents[2]
MODEL = HandModel()


@pytest.fixture(scope="module")
def points():
    return {key: landmarks(MODEL, value.dofs_rad) for key, value in alphabet().items()}


def test_all_26_letters_within_limits():
    low, high = MODEL.limits_rad
    for key, value in alphabet().items():
        assert value.dofs_rad.shape == (len(MODEL.dofs),), key
        assert np.all(value.dofs_rad >= low - 1e-9) and np.all(value.dofs_rad <= high + 1e-9), key


@pytest.mark.parametrize("key", [k for k in LETTERS if letter(k).contacts])
def test_contacts_hold_within_a_millimetre(key):
    value = letter(key)
    gaps = contact_gaps_m(MODEL, value.dofs_rad, value.contacts)
    assert max(abs(g) for g in gaps) < 0.001, (key, gaps)


def test_contact_letters_named_by_the_spec_have_contacts():
    # Spec 01: D, F, O, E, M, N, T, R, U/V are defined by contacts.
    for key in "DFOEMNTU":
        assert letter(key).contacts, key


def _curled(p, finger: str) -> bool:
    """Whether a finger is bent: its tip is nearer the wrist than 85 % of its full reach."""
    base = {"index": 5, "middle": 9, "ring": 13, "pinky": 17}[finger]
    reach = np.linalg.norm(p[base] - p[0]) + sum(
        np.linalg.norm(p[base + k + 1] - p[base + k]) for k in range(3)
    )
    return np.linalg.norm(p[base + 3] - p[0]) < 0.85 * reach


@pytest.mark.parametrize(
    "key, extended",
    [
        ("A", ""),
        ("S", ""),
        ("E", ""),
        ("B", "index middle ring pinky"),
        ("D", "index"),
        ("F", "middle ring pinky"),
        ("I", "pinky"),
        ("L", "index"),
        ("U", "index middle"),
        ("V", "index middle"),
        ("W", "index middle ring"),
        ("Y", "pinky"),
        ("R", "index middle"),
    ],
)
def test_extended_and_curled_fingers(points, key, extended):
    p = points[key]
    for finger in ("index", "middle", "ring", "pinky"):
        assert _curled(p, finger) == (finger not in extended.split()), (key, finger)


def test_u_together_v_spread_r_crossed(points):
    gap = {k: np.linalg.norm(points[k][8] - points[k][12]) for k in "UVR"}
    assert gap["U"] < 0.02 < gap["V"]
    # R: the index tip lies on the ulnar (pinky) side of the middle tip; x grows to the thumb.
    assert points["R"][8][0] < points["R"][12][0]
    assert points["U"][8][0] > points["U"][12][0]


def test_orientations(points):
    # G and H point sideways (along x); P and Q point down (+y is down in MediaPipe axes).
    for key in "GH":
        direction = points[key][8] - points[key][5]
        assert abs(direction[0]) > abs(direction[1]), key
    for key in "PQ":
        assert points[key][8][1] > points[key][5][1], key


def test_j_and_z_are_motion_paths():
    for key in "JZ":
        value = letter(key)
        assert (
            value.path_rad.shape[0] >= 3 and value.path_times[0] == 0 and value.path_times[-1] == 1
        )
        assert np.ptp(value.path_rad, axis=0).max() > np.radians(10)


@pytest.mark.parametrize("bad", ["1", "AB", "Ä", "", " "])
def test_unknown_letters_are_named(bad):
    with pytest.raises(AlphabetError, match="is not a letter of the ASL manual alphabet"):
        letter_pose(bad)


def test_landmarks_have_mediapipe_layout(points):
    assert len(LANDMARK_NAMES) == 21 and LANDMARK_NAMES[8] == "INDEX_FINGER_TIP"
    p = points["B"]
    assert p.shape == (21, 3)
    assert np.allclose(p[[0, 5, 9, 13, 17]].mean(axis=0), 0, atol=1e-12)  # palm centre origin
    assert p[12][1] < p[0][1]  # fingertips above the wrist: y points down
    assert 0.17 < np.linalg.norm(p[12] - p[0]) < 0.20  # a 19 cm hand


def test_left_hand_letters_mirror_the_right():
    right = landmarks(HandModel("right"), letter_pose("K", "right"))
    left = landmarks(HandModel("left"), letter_pose("K", "left"))
    assert np.allclose(left * [-1, 1, 1], right, atol=1e-6)


def test_command_line_prints_landmark_json():
    result = subprocess.run(
        [sys.executable, "-m", "synthesis", "landmarks", "AbC"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=True,
    )
    data = json.loads(result.stdout)
    assert list(data) == ["A", "B", "C"]
    assert np.array(data["C"]).shape == (21, 3)


def test_command_line_rejects_unknown_letters():
    result = subprocess.run(
        [sys.executable, "-m", "synthesis", "landmarks", "A1"],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    assert result.returncode == 2
    assert result.stderr.strip() == "error: '1' is not a letter of the ASL manual alphabet (A–Z)."
