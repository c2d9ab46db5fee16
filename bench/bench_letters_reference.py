"""Read the 26 letters off signing-view renders against real human hands (issue 52).

    .venv/bin/python bench/bench_letters_reference.py [--sizes 1280x720,640x480]

Each letter is held as fingerspelling holds it (synthesis.rigs.posture) and rendered in
the signing view, full frame, at each size; MediaPipe Hands (static images) finds the
hand, and its landmarks are read against the shared reference of 10,508 human samples
(bench/letter_reference.py: the letter most common among the 15 nearest). Strict: no
look-alikes merged. Target: at least 22 of 26 at 1280×720 and at the demo's clip size.
"""

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import machine
from bench_signing_view_letters import mediapipe_hand
from letter_reference import ReferenceHands, from_mediapipe_px

from synthesis.avatar.looks import Look, avatar_for
from synthesis.fingerspelling import letter_pose
from synthesis.render.renderer import Renderer
from synthesis.render.scene import project_px, signing_view
from synthesis.rigs.posture import hand_motion_on

LETTERS = "ABCDEFGHIJKLMNOPQRSTUVWXYZ"


def read_letters(reference, avatar, width: int, height: int, hands) -> dict[str, str]:
    """Return, per letter, what the reference reads off its render ("-": no hand found)."""
    camera = signing_view("right", width, height)
    wrist = avatar.rig.skeleton.index("right_wrist")
    read = {}
    with Renderer(avatar, camera, width, height) as renderer:
        for k in LETTERS:
            dofs = hand_motion_on(avatar.rig, "right", letter_pose(k, "right")[None])[0]
            near = project_px(camera, avatar.rig.pose(dofs).positions_m[0, wrist], width, height)
            marks = mediapipe_hand(hands, renderer.frame(dofs), near)
            if marks is None:
                read[k] = "-"
                continue
            read[k] = str(reference.read(from_mediapipe_px(marks, width)[None])[0])
    return read


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", default="1280x720,640x480")
    arguments = parser.parse_args()
    from mediapipe.python import solutions

    print(machine.describe())
    started = time.perf_counter()
    reference = ReferenceHands()
    avatar = avatar_for("upper-body", "right", Look())
    hands = solutions.hands.Hands(static_image_mode=True, max_num_hands=2)
    with hands:
        for size in arguments.sizes.split(","):
            width, height = (int(v) for v in size.split("x"))
            read = read_letters(reference, avatar, width, height, hands)
            right = [k for k in LETTERS if read[k] == k]
            wrong = ", ".join(f"{k}→{read[k]}" for k in LETTERS if read[k] != k)
            print(f"signing view {width}×{height}: {len(right)} of 26 read right (wrong: {wrong})")
    print(f"({time.perf_counter() - started:.0f} s)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
