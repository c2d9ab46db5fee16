"""Test that a clip's .pose export lays over the clip (issue 54, item 4).

The export is in the clip's pixels, as MediaPipe Holistic's image landmarks are, so a
researcher can draw it over the video (pose-format's visualiser) and compare it with a
capture of the same clip. The check is the field's own tool: MediaPipe run on the
rendered clip must find the shoulders and hands where the file puts them.
Reference: MediaPipe Holistic's output conventions (image landmarks in the frame's
pixels once scaled by its width and height; pose world landmarks in metres from the
hips' midpoint), and pose-format's Holistic header.
"""

import numpy as np
import pytest

from synthesis.capture import read_pose
from synthesis.capture.armfit import fit_arms
from synthesis.cli import main
from synthesis.rigs.body import BodyModel

SHOULDERS = ("LEFT_SHOULDER", "RIGHT_SHOULDER")


def _export(tmp_path, command: list[str], size: str):
    out, pose = tmp_path / "clip.mp4", tmp_path / "clip.pose"
    arguments = [*command, "--size", size, "--rate", "15", "--out", str(out)]
    assert main([*arguments, "--export-pose", str(pose)]) == 0
    return out, read_pose(pose)


def _median_miss(ours, theirs, frames_seen) -> float:
    """Return the median image distance (px) of found points, frames both have."""
    miss = np.linalg.norm(ours[..., :2] - theirs[..., :2], axis=-1)
    return float(np.median(miss[frames_seen]))


def test_a_sentence_export_lays_over_its_clip(tmp_path, renderable):
    pytest.importorskip("mediapipe")
    from pose_format import Pose

    from synthesis.capture.video import capture_body

    video, ours = _export(tmp_path, ["sentence", "ME HAPPY"], "640x480")
    assert (ours.width, ours.height) == (640, 480)
    header = Pose.read((tmp_path / "clip.pose").read_bytes()).header.dimensions
    assert (header.width, header.height) == (640, 480)
    theirs = capture_body(video)
    n = min(ours.n_frames, theirs.n_frames)
    our_shoulders = ours.component("POSE_LANDMARKS", SHOULDERS)[0][:n]
    their_shoulders, seen = theirs.component("POSE_LANDMARKS", SHOULDERS)
    assert _median_miss(our_shoulders, their_shoulders[:n], seen[:n] > 0.5) < 8  # ~1 % of 640
    for side in ("left", "right"):
        mine, (found, confidence) = ours.hand(side)[0][:n], theirs.hand(side)
        hand_seen = np.repeat(confidence[:n].max(axis=1, keepdims=True) > 0, 21, axis=1)
        assert hand_seen[:, 0].mean() > 0.8
        assert _median_miss(mine, found[:n], hand_seen) < 8
    # The metric pose beside the pixels: the engine's own fit reads it, not the image.
    world = ours.component("POSE_WORLD_LANDMARKS", SHOULDERS)[0]
    assert 0.3 < np.linalg.norm(world[0, 0] - world[0, 1]) < 0.45
    fit = fit_arms(BodyModel(), ours)
    assert fit.depth == "file" and np.nanmax(fit.residual_mm) < 1


def test_a_close_up_export_follows_its_moving_camera(tmp_path, renderable):
    pytest.importorskip("mediapipe")
    from synthesis.capture.video import capture_hands

    video, ours = _export(tmp_path, ["spell", "ABC", "--view", "hand"], "480x360")
    assert (ours.width, ours.height) == (480, 360)
    theirs = capture_hands(video, one_hand="right")
    n = min(ours.n_frames, theirs.n_frames)
    found, confidence = theirs.hand("right")
    seen = np.repeat(confidence[:n].max(axis=1, keepdims=True) > 0, 21, axis=1)
    assert seen[:, 0].mean() > 0.8
    # The camera follows the hand: the file's points move with it, frame by frame.
    assert _median_miss(ours.hand("right")[0][:n], found[:n], seen) < 0.03 * 480
