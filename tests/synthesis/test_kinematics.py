"""Test forward kinematics against seed 004 §4.2.1 and a naive per-frame implementation."""

from pathlib import Path

import numpy as np
import pytest

from synthesis import Joint, Motion, Skeleton, forward_kinematics, read_bvh

DATA = Path(__file__).parent / "data"


def seed_004_local(z_deg: float, x_deg: float, y_deg: float) -> np.ndarray:
    """L = Lz · Lx · Ly with the matrices printed in seed 004 §4.2.1."""
    z, x, y = np.radians([z_deg, x_deg, y_deg])
    lz = np.array([[np.cos(z), -np.sin(z), 0], [np.sin(z), np.cos(z), 0], [0, 0, 1]])
    lx = np.array([[1, 0, 0], [0, np.cos(x), -np.sin(x)], [0, np.sin(x), np.cos(x)]])
    ly = np.array([[np.cos(y), 0, np.sin(y)], [0, 1, 0], [-np.sin(y), 0, np.cos(y)]])
    return lz @ lx @ ly


def test_local_rotation_is_seed_004_zxy_product():
    motion = read_bvh(DATA / "seed004_figure_b1.bvh")
    local = motion.local_rotations()
    z, x, y = motion.joint_values("LeftArm")[1]  # 45 0 0 in the file
    assert np.allclose(local[1, motion.skeleton.index("LeftArm")], seed_004_local(z, x, y))
    rng = np.random.default_rng(1)
    angles = rng.uniform(-180, 180, (4, 21))
    random_motion = motion.with_values(angles)
    chest = random_motion.local_rotations()[:, 1]
    for frame in range(4):
        assert np.allclose(chest[frame], seed_004_local(*angles[frame, 6:9]), atol=1e-12)


def naive_fk(motion: Motion):
    """Frame by frame, joint by joint: the textbook recursion, as an independent check."""
    local_r = motion.local_rotations()
    local_t = motion.local_translations_m()
    parents = motion.skeleton.parents
    rotations = np.zeros_like(local_r)
    positions = np.zeros_like(local_t)
    for f in range(motion.n_frames):
        for j, parent in enumerate(parents):
            if parent < 0:
                rotations[f, j], positions[f, j] = local_r[f, j], local_t[f, j]
            else:
                rotations[f, j] = rotations[f, parent] @ local_r[f, j]
                positions[f, j] = positions[f, parent] + rotations[f, parent] @ local_t[f, j]
    return rotations, positions


@pytest.mark.parametrize("path", sorted(DATA.glob("*.bvh")), ids=lambda p: p.name)
def test_batched_fk_equals_naive_recursion(path):
    motion = read_bvh(path)
    rng = np.random.default_rng(7)
    motion = motion.with_values(rng.uniform(-170, 170, (9, motion.skeleton.channel_count)))
    pose = forward_kinematics(motion)
    rotations, positions = naive_fk(motion)
    assert np.allclose(pose.rotations, rotations, atol=1e-12)
    assert np.allclose(pose.positions_m, positions, atol=1e-12)


def test_bent_elbow_puts_the_hand_where_geometry_says():
    # Shoulder at the origin, upper arm 30 cm along +x, forearm 25 cm along +x.
    skeleton = Skeleton(
        (
            Joint("shoulder", -1, (0, 0, 0), ("Zrotation", "Xrotation", "Yrotation")),
            Joint("elbow", 0, (30, 0, 0), ("Zrotation", "Xrotation", "Yrotation")),
            Joint("wrist", 1, (25, 0, 0), (), is_end_site=True),
        ),
        length_unit="cm",
    )
    motion = Motion(skeleton, np.array([[0, 0, 0, 90, 0, 0], [90, 0, 0, 90, 0, 0]]), 1 / 60)
    positions = forward_kinematics(motion).positions_m
    assert np.allclose(positions[0, 2], [0.30, 0.25, 0])  # elbow bent 90° about z
    assert np.allclose(positions[1, 2], [-0.25, 0.30, 0])  # and the shoulder turned 90°


def test_root_position_channels_move_the_whole_skeleton():
    motion = read_bvh(DATA / "seed004_figure_b1.bvh")
    values = np.zeros((2, 21))
    values[1, :3] = [10, 20, 30]  # cm
    pose = forward_kinematics(motion.with_values(values))
    assert np.allclose(pose.positions_m[1] - pose.positions_m[0], [0.1, 0.2, 0.3])
