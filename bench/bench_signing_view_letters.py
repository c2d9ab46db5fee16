"""Read the 26 letters off signing-view renders with MediaPipe Hands (issue 36 acceptance).

    .venv/bin/python bench/bench_signing_view_letters.py [--size 1280x720] [--avatar human]

Each letter is held as fingerspelling holds it (synthesis.rigs.posture) and rendered in
the signing view, full frame; MediaPipe Hands (0.10.x, static images) finds the hand and
its 21 landmarks. The landmarks are classified among spoken-to-signed's human letters
(a test dependency) by the orientation-free features of issue 16
(synthesis.capture.features), three ways:

- as seen: the image-plane landmarks' features, directly;
- fitted, seen as humans see: our hand model fitted to MediaPipe's landmarks with their
  depth, then turned and projected as the human recording of that letter shows its
  hand (synthesis.capture.fidelity.seen_as, as bench_alphabet_fidelity.py does with our
  alphabet's own DOFs, which score 20 of 26 there);
- fitted in the image plane, then seen as humans see (the human letters' own pipeline);

and, for scale, the alphabet's own DOFs seen as humans see, with no render or detector.

Look-alikes (G/Q, K/P, H/U, I/J) count as one. Target: hand found 26/26, at least 20 of
26 read right.
"""

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from synthesis.avatar.looks import Look, avatar_for
from synthesis.capture import fit_hand, read_pose
from synthesis.capture.features import handshape_features
from synthesis.capture.fidelity import score_handshapes, seen_as, view_of
from synthesis.capture.handfit import calibrate_scale
from synthesis.capture.lexicon import human_letter_files
from synthesis.fingerspelling import letter_pose
from synthesis.render.renderer import Renderer
from synthesis.render.scene import project_px, signing_view
from synthesis.rigs.hand import HandModel
from synthesis.rigs.posture import hand_motion_on


def mediapipe_hand(model, image: np.ndarray, near_px: np.ndarray) -> np.ndarray | None:
    """Return the 21 landmarks (x, y, z in pixels; z as MediaPipe scales it, by the
    width) of the hand found nearest to *near_px*, or None when no hand is found."""
    result = model.process(image)
    if not result.multi_hand_landmarks:
        return None
    height, width = image.shape[:2]
    hands = [
        np.array([(p.x * width, p.y * height, p.z * width) for p in found.landmark])
        for found in result.multi_hand_landmarks
    ]
    return min(hands, key=lambda marks: np.linalg.norm(marks[0, :2] - near_px))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", default="1280x720")
    parser.add_argument("--avatar", default="human", choices=["human", "simple"])
    arguments = parser.parse_args()
    from mediapipe.python import solutions

    width, height = (int(value) for value in arguments.size.split("x"))
    started = time.perf_counter()
    model = HandModel()
    views = {
        k: view_of(model, *read_pose(p).hand("right")) for k, p in human_letter_files().items()
    }
    human = {k: view.features for k, view in views.items()}
    avatar = avatar_for("upper-body", "right", Look(avatar=arguments.avatar))
    camera = signing_view("right", width, height)
    wrist = avatar.rig.skeleton.index("right_wrist")
    seen, fitted, planar, missing = {}, {}, {}, []
    hands = solutions.hands.Hands(static_image_mode=True, max_num_hands=2)
    with Renderer(avatar, camera, width, height) as renderer, hands:
        for k in views:
            dofs = hand_motion_on(avatar.rig, "right", letter_pose(k, "right")[None])[0]
            near = project_px(camera, avatar.rig.pose(dofs).positions_m[0, wrist], width, height)
            marks = mediapipe_hand(hands, renderer.frame(dofs), near)
            if marks is None:
                missing.append(k)
                continue
            confidence = np.ones((1, 21))
            seen[k] = handshape_features(marks * [1, 1, 0])
            scale = calibrate_scale(model, marks[None], confidence)
            fitted[k] = seen_as(
                model, fit_hand(model, marks[None], confidence, scale).dofs_rad[0], views[k]
            )
            flat = marks[None] * [1, 1, 0]
            scale = calibrate_scale(model, flat, confidence, planar=True)
            planar[k] = seen_as(
                model, fit_hand(model, flat, confidence, scale).dofs_rad[0], views[k]
            )
    not_found = f" (not {''.join(missing)})" if missing else ""
    print(
        f"{arguments.avatar} avatar, signing view {width}×{height}: hand found in "
        f"{len(views) - len(missing)} of {len(views)}{not_found}"
    )
    # The reading with no detector at all, for scale: what the renders could reach if
    # MediaPipe read them perfectly (tests/synthesis/test_fidelity.py pins it at 20).
    alphabet = {k: seen_as(model, letter_pose(k, "right"), views[k]) for k in views}
    ways = {
        "as seen": seen,
        "fitted, seen as humans see": fitted,
        "fitted in the image plane, seen as humans see": planar,
        "our alphabet's DOFs, no render or detector, seen as humans see": alphabet,
    }
    for name, candidates in ways.items():
        score = score_handshapes(candidates, human)
        wrong = ", ".join(f"{k}→{v}" for k, v in score.taken.items() if k not in score.agreeing)
        print(f"  {name}: {len(score.agreeing)} of {len(views)} read right (wrong: {wrong})")
    print(f"({time.perf_counter() - started:.0f} s)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
