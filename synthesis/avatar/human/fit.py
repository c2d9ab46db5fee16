"""Put MakeHuman's mesh on the engine's skeleton: a bind pose, then a warp.

The engine's rig stays the one that moves (its arm lengths, hand and IK are what the
alphabet's contacts and the signs' locations were solved on). First the rig is posed
like MakeHuman's rest pose (arms down and out, fingers relaxed): its arm and hand DOFs
are fitted so that each segment points where MakeHuman's counterpart does and each palm
faces the same way (bounded least squares within the joint limits, the arm first, then
each digit). Then every vertex is moved by its bones' transforms blended with
MakeHuman's skin weights (:mod:`synthesis.avatar.human.warp`).

A digit is matched as a whole chain: MakeHuman's finger joints sit unevenly along its
short fingers (the proximal phalanx shorter than the distal one), so the engine's
joints are matched to the points at the same share of the chain's length from the
knuckle (or the thumb's base) to the tip.
"""

from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares

from synthesis.avatar.human.skeleton import SIDE_SUFFIX, MakeHumanSkeleton
from synthesis.rigs.body import SIDES, BodyModel
from synthesis.rigs.landmarks import LANDMARK_JOINTS

DIGITS = {"thumb": 1, "index": 2, "middle": 3, "ring": 4, "pinky": 5}


def unit(vectors: np.ndarray) -> np.ndarray:
    """Return *vectors* (..., 3) scaled to length one."""
    return vectors / np.linalg.norm(vectors, axis=-1, keepdims=True)


def digit_joints(digit: str) -> tuple[str, ...]:
    """Return a digit's engine joints from its base to its tip (without the side): its
    four MediaPipe landmarks' joints."""
    start = 1 + 4 * list(DIGITS).index(digit)
    return LANDMARK_JOINTS[start : start + 4]


def _bone_skin(skeleton: MakeHumanSkeleton, vertices_m: np.ndarray, weights: dict, bone: str):
    """Return a bone's head (3,), unit axis (3,) and its skin's offsets from the head
    (the vertices it weighs over one half)."""
    head = skeleton.head(bone)
    axis = unit(skeleton.tail(bone) - head)
    owned = np.array([index for index, weight in weights[bone] if weight > 0.5])
    return head, axis, vertices_m[owned] - head


def fingertip(
    skeleton: MakeHumanSkeleton, vertices_m: np.ndarray, weights: dict, bone: str
) -> np.ndarray:
    """Return a digit's tip: the farthest point of its distal bone's skin along the bone."""
    head, axis, offsets = _bone_skin(skeleton, vertices_m, weights, bone)
    return head + axis * float((offsets @ axis).max())


def cross_section_centre(
    skeleton: MakeHumanSkeleton, vertices_m: np.ndarray, weights: dict, bone: str
) -> np.ndarray:
    """Return how far (3,) the middle of a bone's skin lies from the bone, across it: the
    centre of the skin's extent (5th to 95th percentile) along its two principal
    directions across the bone (a finger's pad has more vertices than its back)."""
    _, axis, offsets = _bone_skin(skeleton, vertices_m, weights, bone)
    across = offsets - np.outer(offsets @ axis, axis)
    _, _, directions = np.linalg.svd(across - across.mean(axis=0), full_matrices=False)
    spread = across @ directions[:2].T
    middle = (np.percentile(spread, 5, axis=0) + np.percentile(spread, 95, axis=0)) / 2
    return middle @ directions[:2]


def along_chain(points: np.ndarray, shares) -> np.ndarray:
    """Return the points at *shares* (0 at the first point, 1 at the last) of a polyline's
    length."""
    at = chain_shares(points)
    return np.column_stack([np.interp(shares, at, points[:, k]) for k in range(3)])


def chain_shares(points: np.ndarray) -> np.ndarray:
    """Return each point's share of a polyline's length from its first point."""
    lengths = np.linalg.norm(np.diff(points, axis=0), axis=1)
    return np.concatenate([[0.0], np.cumsum(lengths)]) / lengths.sum()


@dataclass(frozen=True)
class Correspondence:
    """Where the engine's joints of one side are on MakeHuman's mesh (metres, its frame):
    each arm joint's point and, per digit, MakeHuman's chain (base, the joints between,
    tip) and the points at the engine's joints' shares of it."""

    arm: dict
    chains: dict
    digit_points: dict


def correspondence(
    skeleton: MakeHumanSkeleton, vertices_m: np.ndarray, weights: dict, rig: BodyModel, side: str
) -> Correspondence:
    """Return one side's correspondence of the engine's joints on MakeHuman's."""
    s, p = SIDE_SUFFIX[side], side + "_"
    head = skeleton.head
    arm = {
        p + "clavicle": head("clavicle" + s),
        p + "shoulder": head("upperarm01" + s),
        p + "elbow": head("lowerarm01" + s),
        p + "wrist": head("wrist" + s),
    }
    engine = rig.pose(rig.neutral()).positions_m[0]
    index = {name: i for i, name in enumerate(rig.skeleton.names)}
    chains, digit_points = {}, {}
    for digit, number in DIGITS.items():
        bones = [f"finger{number}-{k}{s}" for k in (1, 2, 3)]
        chain = np.array(
            [head(b) for b in bones] + [fingertip(skeleton, vertices_m, weights, bones[-1])]
        )
        # MakeHuman's finger joints lie toward the back of the finger: the engine's turn
        # about the middle of its cross-section, so its chain runs down the middle.
        middles = [cross_section_centre(skeleton, vertices_m, weights, b) for b in bones]
        chain = chain + np.array([*middles, middles[-1]])
        joints = [p + j for j in digit_joints(digit)]
        shares = chain_shares(engine[[index[j] for j in joints]])
        chains[digit] = chain
        digit_points[digit] = dict(zip(joints, along_chain(chain, shares), strict=True))
    return Correspondence(arm, chains, digit_points)


def palm_frame(wrist, index_mcp, pinky_mcp, middle_mcp, side: str) -> np.ndarray:
    """Return a hand's frame (3, 3), columns: across the palm, toward the fingers, out
    of the palm (the left hand's mirrors the right's)."""
    toward = unit(middle_mcp - wrist)
    normal = np.cross(index_mcp - wrist, pinky_mcp - wrist)
    if side == "left":
        normal = -normal
    normal = unit(normal - (normal @ toward) * toward)
    return np.column_stack([np.cross(toward, normal), toward, normal])


def joint_points(match: Correspondence) -> dict:
    """Return every engine joint of the side with its MakeHuman point."""
    points = dict(match.arm)
    for joints in match.digit_points.values():
        points.update(joints)
    return points


def fit_bind_dofs(rig: BodyModel, matches: dict) -> np.ndarray:
    """Return the rig's DOFs (radians) that point each arm and hand segment along
    MakeHuman's and turn each palm as MakeHuman's faces (trunk and face at rest).

    *matches* holds each side's :class:`Correspondence`.
    """
    index = {name: i for i, name in enumerate(rig.skeleton.names)}
    parent = {
        joint.name: rig.skeleton.names[joint.parent]
        for joint in rig.skeleton.joints
        if joint.parent >= 0
    }
    low, high = rig.limits_rad
    dofs = rig.neutral()

    def solve(names: list[str], segments: list[tuple[str, str]], points: dict, palm=None):
        free = np.array([rig.dof_names.index(n) for n in names], dtype=np.intp)
        pairs = np.array([(index[a], index[b]) for a, b in segments])
        wanted = unit(np.array([points[b] - points[a] for a, b in segments]))

        def residuals(values):
            trial = dofs.copy()
            trial[free] = values
            positions = rig.pose(trial).positions_m[0]
            found = [(unit(positions[pairs[:, 1]] - positions[pairs[:, 0]]) - wanted).ravel()]
            if palm is not None:
                side, frame = palm
                p = side + "_"
                mine = palm_frame(
                    *(
                        positions[index[p + n]]
                        for n in ("wrist", "index_mcp", "pinky_mcp", "middle_mcp")
                    ),
                    side,
                )
                found.append(2.0 * (mine - frame).ravel())
            return np.concatenate(found)

        start = np.clip(dofs[free], low[free] + 1e-6, high[free] - 1e-6)
        dofs[free] = least_squares(residuals, start, bounds=(low[free], high[free])).x

    for side in SIDES:
        p, match = side + "_", matches[side]
        points = joint_points(match)
        mh_palm = palm_frame(
            points[p + "wrist"],
            points[p + "index_mcp"],
            points[p + "pinky_mcp"],
            points[p + "middle_mcp"],
            side,
        )
        arm_dofs = [
            d.name
            for d in rig.dofs
            if d.joint in {p + j for j in ("clavicle", "shoulder", "elbow", "forearm", "wrist")}
        ]
        arm_segments = [
            (p + "clavicle", p + "shoulder"),
            (p + "shoulder", p + "elbow"),
            (p + "elbow", p + "wrist"),
        ]
        arm_segments += [(p + "wrist", p + f"{f}_mcp") for f in DIGITS if f != "thumb"]
        solve(arm_dofs, arm_segments, points, palm=(side, mh_palm))
        for digit in DIGITS:
            joints = [p + j for j in digit_joints(digit)]
            names = [d.name for d in rig.dofs if d.joint in joints]
            segments = [(parent[j], j) for j in joints[1:]]
            solve(names, segments, points)
    return dofs
