"""Test BVH reading and writing: exact round trips on varied files, clear errors, fuzzing."""

import contextlib
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from synthesis import BvhError, Joint, Motion, Skeleton, format_bvh, parse_bvh, read_bvh, write_bvh
from synthesis.skeleton.skeleton import CHANNEL_NAMES, ROTATION_CHANNELS

DATA = Path(__file__).parent / "data"
FILES = sorted(DATA.glob("*.bvh"))


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.name)
def test_sample_files_round_trip_exactly(path, tmp_path):
    motion = read_bvh(path)
    write_bvh(motion, tmp_path / "again.bvh")
    again = read_bvh(tmp_path / "again.bvh", length_unit=motion.skeleton.length_unit)
    assert again == motion
    assert format_bvh(again) == format_bvh(motion)


def test_seed_004_sample_reads_as_published():
    # Seed 004 Fig. B.1, with its two typos fixed (see test_seed_004_typos_are_reported).
    motion = read_bvh(DATA / "seed004_figure_b1.bvh")
    assert motion.skeleton.names == [
        "Hips",
        "Chest",
        "LeftArm",
        "LeftHand",
        "LeftHand_End",
        "RightArm",
        "RightHand",
        "RightHand_End",
    ]
    assert motion.skeleton.joints[0].channels[3:] == ("Zrotation", "Xrotation", "Yrotation")
    assert motion.skeleton.joints[1].rotation_order == "ZXY"
    assert (motion.n_frames, motion.frame_time_s, motion.skeleton.length_unit) == (2, 0.05, "cm")
    assert motion.joint_values("RightHand")[1].tolist() == [0.0, -135.0, 0.0]


def test_seed_004_typos_are_reported():
    text = (DATA / "seed004_figure_b1.bvh").read_text()
    with pytest.raises(BvhError, match=r"fig\.bvh, line 40: '}' closes nothing"):
        parse_bvh(text.replace("}\n\nMOTION", "}\n}\n\nMOTION"), "fig.bvh")
    short = text.replace("0.00 " * 20 + "0.00\n", "0.00 " * 19 + "0.00\n", 1)
    with pytest.raises(BvhError, match=r"line 44: 20 values, expected 21"):
        parse_bvh(short, "fig.bvh")


def test_units_are_detected_and_positions_in_metres():
    seed = read_bvh(DATA / "seed004_figure_b1.bvh")
    metres = read_bvh(DATA / "xyz_metres_one_frame.bvh")
    assert (seed.skeleton.length_unit, metres.skeleton.length_unit) == ("cm", "m")
    assert seed.local_translations_m()[0, 1].tolist() == pytest.approx([0, 0.08, 0])
    assert metres.local_translations_m()[0, 0].tolist() == pytest.approx([0.01, 1.9, -0.02])


def test_varied_syntax_is_understood():
    metres = read_bvh(DATA / "xyz_metres_one_frame.bvh")
    assert metres.skeleton.names[1] == "Left Upper Arm"  # names may contain spaces
    assert metres.skeleton.joints[1].rotation_order == "YXZ"
    assert metres.skeleton.joints[2].channels[:3] == ("Xposition", "Yposition", "Zposition")
    assert metres.values[0, 3] == 15.0  # 1.5e1
    blender = read_bvh(DATA / "blender_two_roots.bvh")
    assert [j.parent for j in blender.skeleton.joints] == [-1, 0, 1, 2, -1]
    assert blender.skeleton.joints[2].channels == ()


def test_empty_and_long_clips_round_trip():
    skeleton = read_bvh(DATA / "seed004_figure_b1.bvh").skeleton
    rng = np.random.default_rng(4)
    for frames in (0, 1, 5000):
        motion = Motion(skeleton, rng.uniform(-180, 180, (frames, 21)).round(6), 1 / 120)
        assert parse_bvh(format_bvh(motion), length_unit="cm") == motion


@pytest.mark.parametrize(
    "change, message",
    [
        (lambda t: t.replace("HIERARCHY", "HIERARCHIES"), r"line 1: expected HIERARCHY"),
        (
            lambda t: t.replace("OFFSET 0.00 8.00 0.00", "OFFSET 0.00 eight 0.00"),
            r"line 8: OFFSET value: other text \(5 characters\) is not a number",
        ),
        (
            lambda t: t.replace("CHANNELS 3 Zrotation", "CHANNELS 3 Wrotation", 1),
            r"line 9: unknown channel other text \(9 characters\)",
        ),
        (
            lambda t: t.replace("JOINT LeftArm", "JOINT Chest"),
            r"line 10: a second joint has a name already taken",
        ),
        (lambda t: t.replace("Frames: 2", "Frames: 3"), r"'Frames: 3' but the file has 2 frame"),
        (
            lambda t: t.replace("Frame Time: 0.05", "Frame Time: -1"),
            r"line 43: frame time must be positive",
        ),
        (lambda t: t.replace("-135.00", "nan"), r"line 45: values must be finite"),
        (
            lambda t: t.replace("-135.00", "x"),
            r"line 45: other text \(1 character\) is not a number",
        ),
        (lambda t: t.split("MOTION")[0], r"end of file: MOTION section missing"),
        (
            lambda t: t[: t.index("JOINT RightArm")],
            r"end of file: file ends inside the joint of line 2",
        ),
        (lambda t: "", r"end of file: file ends early; expected HIERARCHY"),
    ],
)
def test_malformed_files_name_the_line(change, message):
    text = (DATA / "seed004_figure_b1.bvh").read_text()
    with pytest.raises(BvhError, match=message):
        parse_bvh(change(text), "bad.bvh")


def test_unreadable_and_binary_files(tmp_path):
    with pytest.raises(BvhError, match="cannot read the file"):
        read_bvh(tmp_path / "missing.bvh")
    (tmp_path / "binary.bvh").write_bytes(b"\x00\x01HIERARCHY")
    with pytest.raises(BvhError, match="not a text file"):
        read_bvh(tmp_path / "binary.bvh")


# --- Property-based round trips and fuzzing --------------------------------------

finite = st.floats(-1e4, 1e4, allow_nan=False, allow_infinity=False, width=64)
names = st.text(
    "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_.:-", min_size=1, max_size=12
)


@st.composite
def skeletons(draw) -> Skeleton:
    count = draw(st.integers(1, 12))
    joints: list[Joint] = []
    used = set()
    for number in range(count):
        name = draw(names.filter(lambda n: n not in used and not n.endswith("_End")))
        used.add(name)
        parent = -1 if number == 0 else draw(st.integers(0, number - 1))
        if parent >= 0 and joints[parent].is_end_site:
            parent = joints[parent].parent
        end_site = parent >= 0 and draw(st.booleans()) and draw(st.booleans())
        channels = ()
        if not end_site:
            pool = list(CHANNEL_NAMES if parent < 0 else ROTATION_CHANNELS + CHANNEL_NAMES[:3])
            channels = tuple(
                draw(st.permutations(pool))[: draw(st.integers(3 if parent < 0 else 0, len(pool)))]
            )
        if end_site:
            name = f"{joints[parent].name}_End"
            while name in used:
                name += "_"
            used.add(name)
        joints.append(
            Joint(name, parent, tuple(draw(finite) for _ in range(3)), channels, end_site)
        )
    # Writers list a joint's children after it: order joints depth-first like a file.
    skeleton = Skeleton(tuple(joints), length_unit="cm")
    return parse_bvh(
        format_bvh(Motion(skeleton, np.zeros((0, skeleton.channel_count)), 0.01)), length_unit="cm"
    ).skeleton


@st.composite
def motions(draw) -> Motion:
    skeleton = draw(skeletons())
    frames = draw(st.integers(0, 6))
    values = np.array(
        [[draw(finite) for _ in range(skeleton.channel_count)] for _ in range(frames)],
        dtype=np.float64,
    ).reshape(frames, skeleton.channel_count)
    frame_time = draw(st.floats(1e-4, 1.0, allow_nan=False))
    return Motion(skeleton, values, frame_time)


@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(motions())
def test_any_motion_round_trips_exactly(motion):
    text = format_bvh(motion)
    again = parse_bvh(text, length_unit="cm")
    assert again == motion
    assert format_bvh(again) == text


@settings(max_examples=300, deadline=None)
@given(
    st.data(),
    st.sampled_from(["delete_line", "swap_lines", "replace_token", "insert_text", "truncate"]),
)
def test_mutated_files_never_raise_anything_but_bvh_error(data, how):
    lines = (DATA / "seed004_figure_b1.bvh").read_text().splitlines()
    index = data.draw(st.integers(0, len(lines) - 1))
    if how == "delete_line":
        del lines[index]
    elif how == "swap_lines":
        other = data.draw(st.integers(0, len(lines) - 1))
        lines[index], lines[other] = lines[other], lines[index]
    elif how == "replace_token":
        words = lines[index].split() or [""]
        position = data.draw(st.integers(0, len(words) - 1))
        words[position] = data.draw(
            st.sampled_from(
                [
                    "{",
                    "}",
                    "JOINT",
                    "End",
                    "Site",
                    "CHANNELS",
                    "-1",
                    "3",
                    "1e400",
                    "nan",
                    "MOTION",
                    "ROOT",
                    "x",
                ]
            )
            | st.text(max_size=5)
        )
        lines[index] = " ".join(words)
    elif how == "insert_text":
        lines.insert(index, data.draw(st.text(max_size=30)))
    else:
        lines = lines[:index]
    text = "\n".join(lines)
    try:
        motion = parse_bvh(text, "fuzz.bvh")
    except BvhError as error:
        assert str(error).startswith("fuzz.bvh")
    else:
        assert isinstance(motion, Motion)


@settings(max_examples=200, deadline=None)
@given(st.text(max_size=400))
def test_arbitrary_text_never_raises_anything_but_bvh_error(text):
    with contextlib.suppress(BvhError):
        parse_bvh(text, "random.bvh")
