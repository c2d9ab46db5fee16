"""Measure how far a hand goes into the body or the head: skin through skin.

Signs touch the body (ME, the chin of MOTHER, the chest of LIKE), so contact is not a
fault; a hand that sinks through the skin is. Each hand is its joints and the middles of
its bones, each a ball of the finger's or the palm's half thickness; the body is the
skin of every joint outside the arms, kept in that joint's bind frame, where a k-d tree
finds the nearest skin vertex to a hand point carried into the same frame. The signed
distance to the skin is the offset along that vertex's normal (negative inside), which
holds near the surface, where the question is asked: a point more than
:data:`REACH_M` from every body vertex is outside. Where the skin folds inward (the
human signer's eye and mouth openings) a point pushed in may find a vertex whose normal
faces it and read as outside: the check can miss a finger through an eye, never invent
one (tests/synthesis/test_quality.py measures the trunk, where it holds to 1 cm).
"""

from dataclasses import dataclass
from functools import cached_property, lru_cache

import numpy as np
from scipy.spatial import cKDTree

from synthesis.avatar.model import Avatar
from synthesis.avatar.skinning import skin_transforms
from synthesis.render.framing import HAND_JOINTS
from synthesis.skeleton.kinematics import Pose

# Half the thickness of a finger (the phalanx capsules of synthesis.rigs.collisions) and
# of the palm at the knuckles and wrist (about 3 cm thick).
FINGER_RADIUS_M, PALM_RADIUS_M = 0.009, 0.015
# Farther than this from the nearest skin vertex a point is outside: the trunk's half
# depth, so no point inside the body is ever that far from its skin.
REACH_M = 0.15
_ARM = ("clavicle", "shoulder", "elbow", "forearm", *HAND_JOINTS)


def _is_arm(name: str) -> bool:
    return any(name == joint or name.endswith("_" + joint) for joint in _ARM)


@dataclass(frozen=True, eq=False)
class BodySurface:
    """The skin of an avatar's body and head outside the arms, joint by joint, at bind."""

    avatar: Avatar

    @staticmethod
    @lru_cache(maxsize=8)
    def of(avatar: Avatar) -> "BodySurface":
        """Return the surface of *avatar*, built once a process (avatars are too)."""
        return BodySurface(avatar)

    @cached_property
    def _joints(self) -> list[tuple[int, cKDTree, np.ndarray, np.ndarray]]:
        """Return (joint, tree of its skin vertices, vertices, normals) per body joint."""
        names = self.avatar.rig.skeleton.names
        body = [j for j, name in enumerate(names) if not _is_arm(name) and name != "head_top"]
        parts = [part for part in self.avatar.parts if part.casts_shadow]
        owners = np.concatenate([part.weights.main_joints() for part in parts])
        vertices = np.concatenate([part.vertices_m for part in parts])
        normals = np.concatenate([part.normals for part in parts])
        joints = []
        for j in body:
            mine = owners == j
            if mine.sum() >= 4:
                joints.append((j, cKDTree(vertices[mine]), vertices[mine], normals[mine]))
        return joints

    def signed_distance_m(self, pose: Pose, points_m: np.ndarray) -> np.ndarray:
        """Return each point's distance (n_frames, n) to the body's skin, negative inside;
        *points_m* (n_frames, n, 3) are world positions at the frames of *pose*."""
        transforms = skin_transforms(pose, self.avatar.bind_pose)
        best = np.full(points_m.shape[:2], np.inf)
        signed = np.full(points_m.shape[:2], np.inf)
        for j, tree, vertices, normals in self._joints:
            linear, shift = transforms[:, j, :, :3], transforms[:, j, :, 3]
            # The skin transform G·B⁻¹ carries bind to world; its inverse, world to bind.
            local = np.einsum("fji,fnj->fni", linear, points_m - shift[:, None, :])
            distance, index = tree.query(local, distance_upper_bound=REACH_M)
            found = np.isfinite(distance)
            along = np.einsum(
                "fnk,fnk->fn",
                local - vertices[np.minimum(index, len(vertices) - 1)],
                normals[np.minimum(index, len(normals) - 1)],
            )
            closer = found & (distance < best)
            best = np.where(closer, distance, best)
            signed = np.where(closer, along, signed)
        return signed


def hand_points(pose: Pose, names, side: str) -> tuple[np.ndarray, np.ndarray]:
    """Return a hand's sample points (n_frames, n, 3) m, its joints and bones' middles,
    and their radii (n,) m, for the hand of *side* ("" for a lone hand)."""
    prefix = f"{side}_" if side else ""
    index = {name: k for k, name in enumerate(names)}
    joints = [index[prefix + j] for j in HAND_JOINTS if prefix + j in index]
    positions = pose.positions_m[:, joints]
    if not joints:  # a rig without this hand (an imported avatar's may name none)
        return positions, np.zeros(0)
    middles, radii = [], []
    for name in HAND_JOINTS[1:]:
        digit, joint = name.split("_")
        parent = prefix + ("wrist" if joint in ("cmc", "mcp") else _before(digit, joint))
        if prefix + name in index and parent in index:
            middles.append((index[prefix + name], index[parent]))
            radii.append(PALM_RADIUS_M if joint in ("cmc", "mcp") else FINGER_RADIUS_M)
    both = np.concatenate(
        [
            positions,
            np.stack(
                [(pose.positions_m[:, a] + pose.positions_m[:, b]) / 2 for a, b in middles], axis=1
            ),
        ],
        axis=1,
    )
    joint_radii = [
        PALM_RADIUS_M if HAND_JOINTS[k].endswith(("wrist", "cmc", "mcp")) else FINGER_RADIUS_M
        for k in range(len(joints))
    ]
    return both, np.array(joint_radii + radii)


_CHAIN = {"thumb": ("cmc", "mcp", "ip", "tip")}
_FINGER_CHAIN = ("mcp", "pip", "dip", "tip")


def _before(digit: str, joint: str) -> str:
    """Return the joint before *joint* along *digit* (its bone's other end)."""
    chain = _CHAIN.get(digit, _FINGER_CHAIN)
    return f"{digit}_{chain[chain.index(joint) - 1]}"


def penetration_m(surface: BodySurface, pose: Pose, sides) -> np.ndarray:
    """Return, per frame and hand, how deep the hand's skin is in the body's (m, ≥ 0)."""
    names = surface.avatar.rig.skeleton.names
    depths = []
    for side in sides:
        points, radii = hand_points(pose, names, side)
        if not len(radii):
            depths.append(np.zeros(len(points)))
            continue
        signed = surface.signed_distance_m(pose, points)
        depths.append(np.maximum(radii[None, :] - signed, 0.0).max(axis=1))
    return np.stack(depths, axis=1)
