"""Build a full-body-with-hands skeleton and random motion for the benchmarks."""

import numpy as np

from synthesis import Joint, Motion, Skeleton

ZXY = ("Zrotation", "Xrotation", "Yrotation")


def full_body_skeleton() -> Skeleton:
    """Return a 54-joint body: legs, three spine joints, neck, head, arms, 15-joint hands."""
    joints: list[Joint] = [
        Joint("Hips", -1, (0, 95, 0), ("Xposition", "Yposition", "Zposition", *ZXY))
    ]

    def add(name: str, parent: str, offset) -> None:
        index = [j.name for j in joints].index(parent)
        joints.append(Joint(name, index, tuple(float(v) for v in offset), ZXY))

    for side, sign in (("Left", 1), ("Right", -1)):
        add(f"{side}UpLeg", "Hips", (sign * 9, -5, 0))
        add(f"{side}Leg", f"{side}UpLeg", (0, -42, 0))
        add(f"{side}Foot", f"{side}Leg", (0, -40, 0))
        add(f"{side}ToeBase", f"{side}Foot", (0, -6, 12))
    add("Spine", "Hips", (0, 10, 0))
    add("Spine1", "Spine", (0, 12, 0))
    add("Spine2", "Spine1", (0, 12, 0))
    add("Neck", "Spine2", (0, 14, 0))
    add("Head", "Neck", (0, 10, 0))
    for side, sign in (("Left", 1), ("Right", -1)):
        add(f"{side}Shoulder", "Spine2", (sign * 3, 10, 0))
        add(f"{side}Arm", f"{side}Shoulder", (sign * 14, 0, 0))
        add(f"{side}ForeArm", f"{side}Arm", (sign * 28, 0, 0))
        add(f"{side}ForeArmTwist", f"{side}ForeArm", (sign * 12, 0, 0))
        add(f"{side}Hand", f"{side}ForeArmTwist", (sign * 13, 0, 0))
        for digit, spread in (
            ("Thumb", 3),
            ("Index", 2),
            ("Middle", 0),
            ("Ring", -2),
            ("Pinky", -4),
        ):
            parent = f"{side}Hand"
            for number, length in enumerate((5, 3.5, 2.5), start=1):
                name = f"{side}Hand{digit}{number}"
                offset = (sign * (8 if number == 1 else length), 0, spread if number == 1 else 0)
                add(name, parent, offset)
                parent = name
    return Skeleton(tuple(joints), length_unit="cm")


def random_motion(frames: int, rate_hz: float = 60.0, seed: int = 0) -> Motion:
    """Return smooth random motion (sums of sines) on the full-body skeleton."""
    skeleton = full_body_skeleton()
    rng = np.random.default_rng(seed)
    t = np.arange(frames)[:, None] / rate_hz
    frequency = rng.uniform(0.2, 2.0, skeleton.channel_count)
    phase = rng.uniform(0, 2 * np.pi, skeleton.channel_count)
    amplitude = rng.uniform(5, 40, skeleton.channel_count)
    values = (amplitude * np.sin(2 * np.pi * frequency * t + phase)).round(4)
    return Motion(skeleton, values, 1.0 / rate_hz)
