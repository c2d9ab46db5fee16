"""The avatar's face: eyeballs, eyelids with lashes, brows, lips, mouth and tongue.

Each feature is a small mesh of its own, skinned to the face's bones
(:mod:`synthesis.rigs.face`), on the skin of :mod:`synthesis.avatar.body_mesh`:
eyeballs (sclera, iris, pupil) turn about their centres; each eyelid is half a shell
just outside the eyeball, turning about the same centre to blink, squint or open
wide, the upper lid's edge dark with lashes; brows are flat strips lying on the
forehead; the lips are two tubes along the mouth line whose ends follow the mouth
corners and whose middles follow the upper lip and the jaw, with the mouth's inside
(dark, upper teeth at its top) stretched between them. The chin's skin goes with the
jaw, the forehead's under each brow with it and the cheeks' with their bones
(:func:`face_skin_weights`), so an open mouth drops the chin, a raised brow never sinks
into the skin and puffed cheeks bulge.

Geometry is built at the bind pose, in the head's frame (x the signer's left, y up, z
forward, metres), features laid onto the skin's surface found from its distance field.
"""

from dataclasses import replace

import numpy as np
import trimesh

from synthesis.avatar.model import SKIN_RGB, SkinnedPart, merge_parts
from synthesis.avatar.sdf import union_distance
from synthesis.avatar.skinning import MAX_BONES, SkinWeights
from synthesis.rigs.face import EYE_CENTRE_M, EYE_RADIUS_M, MOUTH_HALF_WIDTH_M, MOUTH_HEIGHT_M
from synthesis.skeleton.rotations import quat_rotate

SCLERA_RGB = (0.90, 0.88, 0.84)
IRIS_RGB = (0.30, 0.19, 0.11)
PUPIL_RGB = (0.03, 0.02, 0.02)
LASH_RGB = (0.05, 0.04, 0.04)
BROW_RGB = (0.16, 0.11, 0.08)
LIP_RGB = (0.62, 0.34, 0.33)
MOUTH_RGB = (0.16, 0.05, 0.06)
TEETH_RGB = (0.86, 0.84, 0.78)
TONGUE_RGB = (0.70, 0.36, 0.38)
IRIS_DEG, PUPIL_DEG = 27.0, 12.0  # half-angles seen from the eye's centre
LID_GAP_M = 0.0011  # a lid's shell outside the eyeball
BROW_CENTRE_M = (-0.033, 0.131)  # x, y of the right brow's middle
UPPER_LID_EDGE_DEG = 20.0  # the open upper lid's edge, above the eye's centre
LOWER_LID_EDGE_DEG = -27.0
SIDES = ("right", "left")
_MIRROR = {"right": 1.0, "left": -1.0}


class _Head:
    """The head's frame at the bind pose and the skin around it."""

    def __init__(self, model, bind_dofs_rad, primitives):
        pose = model.pose(bind_dofs_rad)
        self.index = {name: i for i, name in enumerate(model.skeleton.names)}
        head = self.index["head"]
        self.origin = pose.positions_m[0, head]
        self.rotation = pose.quaternions[0, head]
        self.primitives = tuple(p for p in primitives if p.joint in ("head", "neck"))

    def world(self, local_m: np.ndarray) -> np.ndarray:
        """Return head-frame points (..., 3) in the world."""
        return self.origin + quat_rotate(self.rotation, np.asarray(local_m, dtype=np.float64))

    def local(self, world_m: np.ndarray) -> np.ndarray:
        """Return world points (..., 3) in the head's frame."""
        inverse = self.rotation * np.array([-1.0, -1.0, -1.0, 1.0])
        return quat_rotate(inverse, np.asarray(world_m, dtype=np.float64) - self.origin)

    def surface_z(self, xy_m: np.ndarray) -> np.ndarray:
        """Return the skin's forward z at head-frame (x, y) points (k, 2), by bisection."""
        xy = np.asarray(xy_m, dtype=np.float64)
        low, high = np.full(len(xy), -0.02), np.full(len(xy), 0.16)  # inside, outside
        for _ in range(30):
            middle = (low + high) / 2
            points = self.world(np.column_stack([xy, middle]))
            inside = union_distance(self.primitives, points) < 0
            low, high = np.where(inside, middle, low), np.where(inside, high, middle)
        return (low + high) / 2


def _rigid(joint_index: int, n: int) -> tuple[np.ndarray, np.ndarray]:
    return np.full((n, 1), joint_index), np.ones((n, 1))


def _eyeballs(head: _Head) -> SkinnedPart:
    sphere = trimesh.creation.icosphere(subdivisions=3, radius=EYE_RADIUS_M)
    angle = np.degrees(np.arccos(np.clip(sphere.vertices[:, 2] / EYE_RADIUS_M, -1, 1)))
    rgb = np.where((angle < PUPIL_DEG)[:, None], PUPIL_RGB, IRIS_RGB)
    eyes = _merge(
        "eyes",
        head,
        [
            (
                sphere.vertices + _sided(EYE_CENTRE_M, side),
                sphere.faces,
                rgb,
                *_rigid(head.index[f"{side}_eye"], len(sphere.vertices)),
            )
            for side in SIDES
        ],
    )
    # The iris's rim is a colour edge, round whatever the triangles (SkinnedPart).
    rim_m = EYE_RADIUS_M * (np.cos(np.radians(angle)) - np.cos(np.radians(IRIS_DEG)))
    return replace(
        eyes,
        edge_m=np.tile(rim_m, 2),
        across_rgb=np.broadcast_to(np.asarray(SCLERA_RGB), (2 * len(angle), 3)),
    )


def _sided(point, side: str) -> np.ndarray:
    """Return a right-side head-frame point for *side* (the left mirrors x)."""
    return np.asarray(point, dtype=np.float64) * [_MIRROR[side], 1.0, 1.0]


def _shell(radius_m: float, from_deg: float, to_deg: float, rows: int = 12, columns: int = 24):
    """Return a band of a sphere about the x axis: elevations *from_deg*…*to_deg* (0 is
    forward, 90 up) all round x, as vertices (k, 3), faces and each vertex's row."""
    # Rows close together at the edge, where the lashes are.
    elevation = np.radians(from_deg + (to_deg - from_deg) * np.linspace(0.0, 1.0, rows) ** 1.6)
    across = np.radians(np.linspace(-84.0, 84.0, columns))
    e, a = np.meshgrid(elevation, across, indexing="ij")
    vertices = radius_m * np.stack(
        [np.sin(a), np.cos(a) * np.sin(e), np.cos(a) * np.cos(e)], axis=-1
    ).reshape(-1, 3)
    faces = _grid_faces(rows, columns)
    return vertices, faces, np.repeat(np.arange(rows), columns)


def _grid_faces(rows: int, columns: int) -> np.ndarray:
    """Return two triangles per cell of a rows × columns vertex grid (row-major)."""
    r, c = np.meshgrid(np.arange(rows - 1), np.arange(columns - 1), indexing="ij")
    a = (r * columns + c).ravel()
    return np.concatenate(
        [
            np.column_stack([a, a + 1, a + columns]),
            np.column_stack([a + 1, a + columns + 1, a + columns]),
        ]
    )


def _facing(vertices: np.ndarray, faces: np.ndarray, outward: np.ndarray) -> np.ndarray:
    """Return *faces* wound so that each faces along *outward* (3,) or (n_faces, 3)."""
    corners = vertices[faces]
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    backward = np.einsum("ij,ij->i", normals, np.broadcast_to(outward, normals.shape)) < 0
    return np.where(backward[:, None], faces[:, ::-1], faces)


def _lids(head: _Head) -> SkinnedPart:
    radius = EYE_RADIUS_M + LID_GAP_M
    pieces = []
    for side in SIDES:
        centre = _sided(EYE_CENTRE_M, side)
        upper, faces, row = _shell(radius, UPPER_LID_EDGE_DEG, UPPER_LID_EDGE_DEG + 175.0)
        # The lid's edge is thick and dark: the lashes.
        upper[row == 0] *= (radius + 0.0009) / radius
        rgb = np.where((row == 0)[:, None], LASH_RGB, SKIN_RGB)
        faces = _facing(upper, faces, upper[faces].mean(axis=1))
        pieces.append(
            (upper + centre, faces, rgb, *_rigid(head.index[f"{side}_upper_lid"], len(upper)))
        )
        lower, faces, row = _shell(radius, LOWER_LID_EDGE_DEG, LOWER_LID_EDGE_DEG - 175.0)
        rgb = np.where((row == 0)[:, None], np.multiply(SKIN_RGB, 0.75), SKIN_RGB)
        faces = _facing(lower, faces, lower[faces].mean(axis=1))
        pieces.append(
            (lower + centre, faces, rgb, *_rigid(head.index[f"{side}_lower_lid"], len(lower)))
        )
    return _merge("eyelids", head, pieces)


def _tube(centres: np.ndarray, radii: np.ndarray, depth_share: float = 1.0, around: int = 10):
    """Return a closed tube along *centres* (k, 3) with radii (k,): vertices, faces and
    each vertex's index along the curve. *depth_share* flattens it along z."""
    tangent = np.gradient(centres, axis=0)
    tangent /= np.linalg.norm(tangent, axis=1, keepdims=True)
    side = np.cross(tangent, [0.0, 0.0, 1.0])
    side /= np.linalg.norm(side, axis=1, keepdims=True)
    up = np.cross(side, tangent)
    angle = np.linspace(0, 2 * np.pi, around, endpoint=False)
    ring = (
        np.cos(angle)[None, :, None] * side[:, None] * 1.0
        + np.sin(angle)[None, :, None] * up[:, None] * depth_share
    )
    vertices = (centres[:, None] + radii[:, None, None] * ring).reshape(-1, 3)
    k = len(centres)
    wrapped = np.concatenate([np.arange(around), [0]])
    faces = []
    for i in range(k - 1):
        for j in range(around):
            a, b = i * around + wrapped[j], i * around + wrapped[j + 1]
            faces += [(a, b + around, b), (a, a + around, b + around)]
    # Caps: a vertex at each end.
    ends = np.array([centres[0], centres[-1]])
    first, last = len(vertices), len(vertices) + 1
    for j in range(around):
        faces.append((first, wrapped[j], wrapped[j + 1]))
        faces.append((last, (k - 1) * around + wrapped[j + 1], (k - 1) * around + wrapped[j]))
    along = np.concatenate([np.repeat(np.arange(k), around), [0, k - 1]])
    return np.vstack([vertices, ends]), np.asarray(faces), along


def _brows(head: _Head) -> SkinnedPart:
    pieces = []
    t = np.linspace(0.0, 1.0, 12)
    for side in SIDES:
        x = -(0.011 + 0.041 * t)  # inner end to outer end, right side
        y = 0.129 + 0.007 * np.sin(np.pi * (t * 0.85 + 0.1)) - 0.004 * t
        xy = np.column_stack([_MIRROR[side] * x, y])
        centres = np.column_stack([xy, head.surface_z(xy) + 0.0015])
        radii = 0.0030 * (1.0 - 0.45 * t) + 0.0006
        vertices, faces, _ = _tube(centres, radii, depth_share=0.35)
        pieces.append(
            (vertices, faces, BROW_RGB, *_rigid(head.index[f"{side}_brow"], len(vertices)))
        )
    return _merge("brows", head, pieces)


def _corner_share(x_m: np.ndarray) -> np.ndarray:
    """Return how much of a point of the mouth follows its side's corner (0 mid, 1 end)."""
    # Late and quick, so that an open mouth is round at the bottom, not a V.
    u = np.clip((np.abs(x_m) / MOUTH_HALF_WIDTH_M - 0.55) / 0.45, 0.0, 1.0)
    return u * u * (3 - 2 * u)


def _mouth_weights(head: _Head, x_m: np.ndarray, middle: np.ndarray, middle_share=None):
    """Return weights for mouth points at *x_m*: their corner, and the *middle* joints
    (per point, up to two with *middle_share* the second's) for the rest."""
    corner = _corner_share(x_m)
    side = np.where(x_m < 0, head.index["right_mouth_corner"], head.index["left_mouth_corner"])
    second = np.zeros(len(x_m)) if middle_share is None else middle_share
    joints = np.column_stack([side, middle[:, 0], middle[:, 1]])
    weights = np.column_stack([corner, (1 - corner) * (1 - second), (1 - corner) * second])
    return joints, weights + 1e-12


def _mouth(head: _Head) -> SkinnedPart:
    columns = 25
    x = np.linspace(-1.0, 1.0, columns) * MOUTH_HALF_WIDTH_M
    # The mouth line dips a little at the corners.
    y = MOUTH_HEIGHT_M - 0.0012 * (x / MOUTH_HALF_WIDTH_M) ** 2
    surface = head.surface_z(np.column_stack([x, y]))
    u = x / MOUTH_HALF_WIDTH_M
    pieces = []
    upper_lip, lower_lip = head.index["upper_lip"], head.index["lower_lip"]
    for offset, radius, joint in ((0.0022, 0.0026, upper_lip), (-0.0026, 0.0031, lower_lip)):
        centres = np.column_stack([x, y + offset * (1 - 0.5 * u**2), surface - 0.0006])
        vertices, faces, along = _tube(centres, radius * (1 - 0.55 * u**2) + 0.0004, 0.8)
        joints, weights = _mouth_weights(head, x[along], np.full((len(vertices), 2), joint))
        pieces.append((vertices, faces, LIP_RGB, joints, weights))
    # The inside: rows from under the upper lip (v = 0) to over the lower lip (v = 1),
    # all on the mouth line at rest, stretched open by the jaw.
    rows = 8
    v = np.linspace(0.0, 1.0, rows)
    vv, xx = np.meshgrid(v, x, indexing="ij")
    yy = np.broadcast_to(y, vv.shape)
    zz = np.broadcast_to(surface + 0.001, vv.shape)  # in front of the skin it opens over
    inside = np.stack([xx, yy, zz], axis=-1).reshape(-1, 3)
    teeth = (vv.ravel() < 0.2) & (np.abs(xx.ravel()) < 0.8 * MOUTH_HALF_WIDTH_M)
    rgb = np.where(teeth[:, None], TEETH_RGB, MOUTH_RGB)
    middle = np.tile([upper_lip, lower_lip], (len(inside), 1))
    joints, weights = _mouth_weights(head, inside[:, 0], middle, vv.ravel())
    # Spread a hair's breadth so that its faces have a side (it is flat shut at rest).
    spread = inside - [0.0, 1e-5, 0.0] * vv.reshape(-1, 1)
    faces = _facing(spread, _grid_faces(rows, columns), np.array([0.0, 0.0, 1.0]))
    pieces.append((inside, faces, rgb, joints, weights))
    # The tongue: behind the lips at rest.
    tongue = trimesh.creation.icosphere(subdivisions=2, radius=1.0)
    behind = float(surface[columns // 2]) - 0.019
    vertices = tongue.vertices * [0.011, 0.004, 0.016] + [0.0, MOUTH_HEIGHT_M + 0.0005, behind]
    pieces.append(
        (vertices, tongue.faces, TONGUE_RGB, *_rigid(head.index["tongue"], len(vertices)))
    )
    return _merge("mouth", head, pieces)


def _merge(name: str, head: _Head, pieces) -> SkinnedPart:
    """Return one part from pieces (vertices, faces, rgb, joints, weights), head frame."""
    return merge_parts(name, [_piece(name, head, *piece) for piece in pieces])


def _piece(name: str, head: _Head, local_m, faces, rgb, joints, weights) -> SkinnedPart:
    """Return one piece (head-frame vertices, faces, colours, up to MAX_BONES joints and
    weights per vertex) as a part at the bind pose."""
    vertices, faces = head.world(local_m), np.asarray(faces, dtype=np.int64)
    weights = _pad(np.atleast_2d(weights), fill=0.0)
    normals = np.array(trimesh.Trimesh(vertices, faces, process=False).vertex_normals)
    # The mouth's inside is closed flat at rest: it faces forward.
    flat = np.linalg.norm(normals, axis=1) < 0.5
    normals[flat] = head.world(np.array([0.0, 0.0, 1.0])) - head.world(np.zeros(3))
    colours = np.broadcast_to(np.asarray(rgb, dtype=np.float64), (len(vertices), 3))
    return SkinnedPart(
        name,
        vertices,
        faces,
        np.ascontiguousarray(colours),
        SkinWeights(
            _pad(np.atleast_2d(joints)).astype(np.intp),
            weights / weights.sum(axis=1, keepdims=True),
        ),
        normals=normals,
    )


def _pad(array: np.ndarray, fill=None) -> np.ndarray:
    pad = MAX_BONES - array.shape[1]
    if fill is None:
        return np.pad(array, ((0, 0), (0, pad)), mode="edge")
    return np.pad(array, ((0, 0), (0, pad)), constant_values=fill)


def face_part(model, bind_dofs_rad: np.ndarray, primitives) -> SkinnedPart:
    """Return the face's features at the bind pose as one part: eyes, eyelids, brows,
    mouth (one draw call a pass)."""
    head = _Head(model, bind_dofs_rad, primitives)
    return merge_parts(
        "face", [_eyeballs(head), _lids(head), _brows(head), _mouth(head)], casts_shadow=False
    )


def face_skin_weights(model, bind_dofs_rad, vertices_m, weights: SkinWeights) -> SkinWeights:
    """Return the skin's weights with the chin given to the jaw, the skin under the brows
    to the brows and the cheeks to theirs.

    A vertex's share of the head moves to the jaw below the mouth line at the front of
    the face (over 1 cm, so the chin drops and the skin between the lips stretches), to
    a brow bone in a patch round each brow, and to a cheek bone in a round patch over
    each cheek.
    """
    head = _Head(model, bind_dofs_rad, ())
    local = head.local(vertices_m)
    y, z = local[:, 1], local[:, 2]
    jaw_share = _ramp((MOUTH_HEIGHT_M - y) / 0.010) * _ramp((z - 0.015) / 0.035)
    shares = [("jaw", jaw_share)]
    front = _ramp((z - 0.03) / 0.02)
    for side in SIDES:
        # The forehead's skin under a brow slides with it, so the brow never sinks into
        # the skin it moves over; less so below, over the eyelids.
        x_share = ((local[:, 0] - BROW_CENTRE_M[0] * _MIRROR[side]) / 0.026) ** 2
        y_radius = np.where(y > BROW_CENTRE_M[1], 0.022, 0.008)
        shares.append(
            (f"{side}_brow", front * np.exp(-x_share - ((y - BROW_CENTRE_M[1]) / y_radius) ** 2))
        )
    for side in SIDES:
        centre = np.array([-0.047 * _MIRROR[side], 0.055, 0.052])
        distance = np.linalg.norm((local - centre) * [1.0, 0.8, 1.2], axis=1)
        shares.append((f"{side}_cheek", np.exp(-((distance / 0.020) ** 2)) * (distance < 0.05)))
    joints, weights = weights.joints.copy(), weights.weights.copy()
    head_index = head.index["head"]
    for name, share in shares:
        on_head = joints == head_index
        moved = np.where(on_head, weights, 0.0).sum(axis=1) * share
        changed = moved > 1e-4
        # The new bone takes the weakest slot; that slot's weight goes to the strongest.
        weakest = np.argmin(weights, axis=1)
        rows = np.flatnonzero(changed)
        weights[rows, 0] += weights[rows, weakest[rows]]
        weights[rows, weakest[rows]] = 0.0
        scale = np.where(on_head[rows], 1 - share[rows, None], 1.0)
        weights[rows] *= scale
        joints[rows, weakest[rows]] = head.index[name]
        weights[rows, weakest[rows]] = 1.0 - weights[rows].sum(axis=1)
    return SkinWeights(joints, weights)


def _ramp(x: np.ndarray) -> np.ndarray:
    """Return smoothstep of x clipped to [0, 1]."""
    x = np.clip(x, 0.0, 1.0)
    return x * x * (3 - 2 * x)
