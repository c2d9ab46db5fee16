"""Retarget a third-party motion onto the hand or body model through a joint mapping.

Each mapped joint copies the source joint's world rotation relative to the source's rest
pose (BVH: all channels zero), applied on top of the model's own rest pose after turning
the model's bone onto the source's rest bone direction; unmapped joints keep their rest
rotation relative to their parent. Bone lengths stay the model's; the root travels as
the source root does, scaled by the two skeletons' sizes.
"""

import numpy as np
from scipy.spatial.transform import Rotation

from synthesis.rigs.rig import Rig
from synthesis.skeleton.kinematics import Pose, forward_kinematics, local_transforms
from synthesis.skeleton.mapping import JointMapping, detect_mapping
from synthesis.skeleton.motion import Motion
from synthesis.skeleton.rotations import quat_conjugate, quat_multiply, quat_rotate


def _between(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Return the shortest-arc quaternion turning direction *a* onto direction *b*."""
    a = a / np.linalg.norm(a)
    b = b / np.linalg.norm(b)
    cross, dot = np.cross(a, b), float(a @ b)
    if dot < -1 + 1e-9:
        # Opposite: any perpendicular axis will do.
        axis = np.cross(a, (1.0, 0.0, 0.0) if abs(a[0]) < 0.9 else (0.0, 1.0, 0.0))
        return np.append(axis / np.linalg.norm(axis), 0.0)
    q = np.append(cross, 1.0 + dot)
    return q / np.linalg.norm(q)


def target_names(mapping: JointMapping, rig: Rig) -> dict[str, str]:
    """Return source joint → rig joint names, adapting sides between hand and body."""
    names = set(rig.skeleton.names)
    result = {}
    single_side = mapping.side()
    for source, canonical in mapping.to_canonical.items():
        candidates = [canonical]
        if "_" in canonical and canonical.split("_", 1)[0] in ("right", "left"):
            side, bare = canonical.split("_", 1)
            if getattr(rig, "side", side) == side or single_side:
                candidates.append(bare)
        else:
            candidates.append(f"{getattr(rig, 'dominant', 'right')}_{canonical}")
        for name in candidates:
            if name in names:
                result[source] = name
                break
    return result


def _height(positions: np.ndarray) -> float:
    return float(np.ptp(positions, axis=0).max())


def _same_skeleton(source, target) -> bool:
    """Return whether *source* is the rig's own skeleton, as a BVH file of it reads back.

    End Sites are compared by place only: the format does not name them.
    """
    if len(source) != len(target) or not np.array_equal(source.parents, target.parents):
        return False
    named = all(
        a.name == b.name or (a.is_end_site and b.is_end_site)
        for a, b in zip(source.joints, target.joints, strict=True)
    )
    return named and np.allclose(
        source.offsets * source.metres_per_unit, target.offsets * target.metres_per_unit, atol=1e-6
    )


def retarget(
    motion: Motion, rig: Rig, mapping: JointMapping | None = None, *, in_place: bool = False
) -> Pose:
    """Return the rig's global transforms, (n_frames, n_joints, …), following *motion*.

    *in_place* films the capture as signing is filmed: turned about the vertical so that
    it faces, on average, as it does at rest (toward the camera), and without the root's
    travel across the floor (its height still follows). Issue 54: CMU 01_01 walks 0.67 m,
    out of the fixed camera by its 50th frame; Boxing_Toes faces away (172° on average).
    """
    source_skeleton = motion.skeleton
    target = rig.skeleton
    if _same_skeleton(source_skeleton, target):
        return forward_kinematics(motion)
    mapping = mapping or detect_mapping(source_skeleton)
    pairs = {
        target.index(t): _turning_joint(source_skeleton, source_skeleton.index(s), mapping)
        for s, t in target_names(mapping, rig).items()
    }
    if not pairs:
        raise ValueError(
            f"No joint of this {mapping.convention} skeleton maps onto the {rig.kind} model."
        )
    rest_values = np.zeros((1, source_skeleton.channel_count))
    source_rest = forward_kinematics(Motion(source_skeleton, rest_values, 1.0))
    source = forward_kinematics(motion)
    if in_place:
        source = _facing_as_at_rest(source, source_rest, _side_pairs(pairs, target.names))
    pose = transfer_pose(
        source,
        source_rest,
        source_skeleton.parents,
        pairs,
        target.parents,
        rig.pose(rig.neutral()),
    )
    if not in_place:
        return pose
    root = int(np.flatnonzero(np.asarray(target.parents) < 0)[0])
    across = pose.positions_m[:, root] - pose.positions_m[:1, root]
    across[:, 1] = 0.0  # the engine's y is up: height stays
    return Pose(quaternions=pose.quaternions, positions_m=pose.positions_m - across[:, None])


# The joints whose left-to-right line says where a body faces (arms swing; these do not).
TRUNK_SIDES = ("clavicle", "shoulder", "hip")


def _side_pairs(pairs: dict[int, int], names) -> list[tuple[int, int]]:
    """Return the source joints (left, right) of the engine's trunk joints mapped on both
    sides, or of every joint mapped on both sides where no trunk pair is."""
    found, trunk = [], []
    for j, name in enumerate(names):
        other = f"right_{name.removeprefix('left_')}" if name.startswith("left_") else None
        if other and j in pairs and names.index(other) in pairs:
            pair = (pairs[j], pairs[names.index(other)])
            found.append(pair)
            if name.removeprefix("left_") in TRUNK_SIDES:
                trunk.append(pair)
    return trunk or found


def _facing_as_at_rest(source: Pose, source_rest: Pose, sides) -> Pose:
    """Return *source* turned about the vertical (y) so that its left-to-right line points,
    on the circular average over its frames, as it does at rest (unchanged with no pair
    of sides mapped)."""
    if not sides:
        return source

    def across(positions: np.ndarray) -> np.ndarray:
        line = sum(positions[..., left, :] - positions[..., right, :] for left, right in sides)
        return np.arctan2(-line[..., 2], line[..., 0])

    turn = across(source.positions_m) - across(source_rest.positions_m)[0]
    mean = float(np.arctan2(np.sin(turn).mean(), np.cos(turn).mean()))
    back = Rotation.from_euler("y", -mean)
    quaternions = (back * Rotation.from_quat(source.quaternions.reshape(-1, 4))).as_quat()
    return Pose(
        quaternions=quaternions.reshape(source.quaternions.shape),
        positions_m=back.apply(source.positions_m.reshape(-1, 3)).reshape(source.positions_m.shape),
    )


def _turning_joint(skeleton, joint: int, mapping: JointMapping) -> int:
    """Return the joint whose rotation turns *joint*'s limb: itself, or, where no mapped
    joint lies below it, an unmapped child at the same place that carries most of the
    limb (CMU's LeftFingerBase, a second frame on the wrist that its fingers hang from;
    issue 54: mapping the hand alone kept the engine's wrist at one angle to the forearm
    in every frame)."""
    mapped = set(mapping.to_canonical)
    names = skeleton.names
    if any(names[c] in mapped for c in _descendants(np.asarray(skeleton.parents), joint)):
        return joint
    while True:
        same_place = [
            c
            for c in range(len(skeleton.names))
            if skeleton.parents[c] == joint
            and skeleton.names[c] not in mapped
            and not skeleton.joints[c].is_end_site
            and np.linalg.norm(skeleton.offsets[c]) < 1e-9
        ]
        if not same_place:
            return joint
        joint = max(same_place, key=lambda c: _reach(skeleton, c))


def _reach(skeleton, joint: int) -> float:
    """Return how far *joint*'s descendants reach from it in the skeleton's rest (units)."""
    offsets = np.asarray(skeleton.offsets, float)
    reach, frontier = 0.0, [(joint, np.zeros(3))]
    while frontier:
        parent, at = frontier.pop()
        for c in range(len(skeleton.names)):
            if skeleton.parents[c] == parent:
                place = at + offsets[c]
                reach = max(reach, float(np.linalg.norm(place)))
                frontier.append((c, place))
    return reach


def transfer_pose(
    source: Pose,
    source_rest: Pose,
    source_parents: np.ndarray,
    pairs: dict[int, int],
    parents: np.ndarray,
    rest: Pose,
) -> Pose:
    """Return a skeleton's global transforms (n_frames, …) following *source*'s.

    *pairs* maps each target joint to its source joint; *source_rest* and *rest* (one
    frame each) are the poses in which the two skeletons stand alike once each mapped
    limb is turned onto the source's (:func:`_alignment`). A mapped joint turns from its
    rest as the source joint turns from the source's rest; an unmapped one keeps its
    rest turn relative to its parent; bone lengths stay the target's, and the root
    travels as the source's root does, scaled by the two skeletons' heights.
    """
    source_rest_q = source_rest.quaternions[0]
    source_rest_p = source_rest.positions_m[0]
    rest_q, rest_p = rest.quaternions[0], rest.positions_m[0]
    local_rest, offsets = (values[0] for values in local_transforms(parents, rest))

    n_frames = len(source.quaternions)
    rotations = np.empty((n_frames, len(parents), 4))
    positions = np.empty((n_frames, len(parents), 3))
    scale = _height(rest_p) / max(_height(source_rest_p), 1e-9)
    for j in range(len(parents)):
        parent = parents[j]
        if j in pairs:
            s = pairs[j]
            align = _alignment(j, s, pairs, (parents, source_parents), rest_p, source_rest_p)
            delta = quat_multiply(source.quaternions[:, s], quat_conjugate(source_rest_q[s]))
            rotations[:, j] = quat_multiply(delta, quat_multiply(align, rest_q[j]))
        elif parent < 0:
            rotations[:, j] = rest_q[j]
        else:
            rotations[:, j] = quat_multiply(rotations[:, parent], local_rest[j])
        if parent < 0:
            positions[:, j] = rest_p[j]
            root_source = pairs.get(j)
            if root_source is not None and source_parents[root_source] < 0:
                travel = source.positions_m[:, root_source] - source.positions_m[:1, root_source]
                positions[:, j] += travel * scale
        else:
            positions[:, j] = positions[:, parent] + quat_rotate(rotations[:, parent], offsets[j])
    return Pose(quaternions=rotations, positions_m=positions)


def _alignment(j, s, pairs, both_parents, neutral_p, source_rest_p) -> np.ndarray:
    """Return the rotation (quaternion) that best turns the model's rest limb onto the source's.

    The limb is the direction to each nearest mapped descendant (a wrist's five digits, the
    upper spine's neck and clavicles), and the rotation the
    least-squares fit of one set onto the other (Wahba's problem, solved by scipy): a
    bone's direction and its roll (where the thumb points, say) both come out of it.
    Where no mapped descendant stands apart from the joint (CMU's hand: its fingers are
    not mapped, and the first of them sits on the wrist), the limb is the direction to
    the middle of all its descendants in each skeleton (issue 54: the hand kept the
    model's own rest direction, at 90° to the forearm in every frame).
    """
    parents = both_parents[0]
    mapped = _nearest_mapped(parents, j, pairs)
    model = np.array([neutral_p[c] - neutral_p[j] for c in mapped]).reshape(-1, 3)
    source = np.array([source_rest_p[pairs[c]] - source_rest_p[s] for c in mapped]).reshape(-1, 3)
    usable = (np.linalg.norm(model, axis=1) > 1e-9) & (np.linalg.norm(source, axis=1) > 1e-9)
    if not usable.any():
        return _centroid_alignment(j, s, both_parents, neutral_p, source_rest_p)
    model = model[usable] / np.linalg.norm(model[usable], axis=1, keepdims=True)
    source = source[usable] / np.linalg.norm(source[usable], axis=1, keepdims=True)
    # With every direction on one line (one descendant, or Biovision's neck and collars
    # all straight above its chest) only the direction is defined, not a roll about it.
    if np.linalg.matrix_rank(model, tol=1e-6) < 2 or np.linalg.matrix_rank(source, tol=1e-6) < 2:
        ours, theirs = model.mean(axis=0), source.mean(axis=0)
        if min(np.linalg.norm(ours), np.linalg.norm(theirs)) < 1e-6:  # opposite, cancelled
            ours, theirs = model[0], source[0]
        return _between(ours, theirs)
    rotation, _ = Rotation.align_vectors(source, model)
    return rotation.as_quat()


def _centroid_alignment(j, s, both_parents, neutral_p, source_rest_p) -> np.ndarray:
    """Return the rotation turning the direction from joint *j* to the middle of its
    descendants in the model onto the same in the source (identity if either has none)."""
    directions = []
    for parents, positions, joint in zip(
        both_parents, (neutral_p, source_rest_p), (j, s), strict=True
    ):
        below = _descendants(parents, joint)
        direction = positions[below].mean(axis=0) - positions[joint] if below else np.zeros(3)
        directions.append(direction)
    if min(np.linalg.norm(d) for d in directions) < 1e-9:
        return np.array([0.0, 0.0, 0.0, 1.0])
    return _between(*directions)


def _descendants(parents: np.ndarray, joint: int) -> list[int]:
    """Return every joint below *joint*."""
    found, frontier = [], [joint]
    while frontier:
        frontier = [c for c in range(len(parents)) if parents[c] in frontier]
        found += frontier
    return found


def _nearest_mapped(parents: np.ndarray, joint: int, pairs: dict) -> list[int]:
    """Return the mapped descendants reached without passing another mapped joint."""
    found, frontier = [], [joint]
    while frontier:
        children = [c for c in range(len(parents)) if parents[c] in frontier]
        found += [c for c in children if c in pairs]
        frontier = [c for c in children if c not in pairs]
    return found


def bone_direction_errors_deg(
    motion: Motion, pose: Pose, rig: Rig, mapping: JointMapping | None = None
) -> dict[str, np.ndarray]:
    """Return, per mapped bone, the angle (degrees, per frame) between its direction in
    the retargeted *pose* and in the source *motion*.

    A bone runs from a mapped joint to each nearest mapped descendant (so the rig's and
    the source's joints in between need not match); bones of zero length in the source
    (CMU's Neck sits on Spine1) have no direction and are left out.
    """
    mapping = mapping or detect_mapping(motion.skeleton)
    target = rig.skeleton
    pairs = {
        target.index(t): motion.skeleton.index(s) for s, t in target_names(mapping, rig).items()
    }
    source = forward_kinematics(motion)
    names = motion.skeleton.names
    errors = {}
    for j, s in pairs.items():
        for c in _nearest_mapped(target.parents, j, pairs):
            wanted = source.positions_m[:, pairs[c]] - source.positions_m[:, s]
            got = pose.positions_m[:, c] - pose.positions_m[:, j]
            length = np.linalg.norm(wanted, axis=1)
            if length.min() < 1e-6:
                continue
            cosine = np.sum(wanted * got, axis=1) / length / np.linalg.norm(got, axis=1)
            angle_deg = np.degrees(np.arccos(np.clip(cosine, -1.0, 1.0)))
            errors[f"{names[s]}→{names[pairs[c]]}"] = angle_deg
    return errors
