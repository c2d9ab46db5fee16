"""An avatar: a rig (hand or upper body) and its skinned mesh parts, posed by DOF vectors."""

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
import trimesh
from scipy import sparse

from synthesis.avatar.skinning import (
    MorphDrive,
    Morphs,
    SkinWeights,
    linear_blend_skinning,
    skin_transforms,
)
from synthesis.skeleton.kinematics import Pose

SKIN_RGB = (0.74, 0.55, 0.45)
NAIL_RGB = (0.82, 0.64, 0.60)
TOP_RGB = (0.11, 0.12, 0.15)


@dataclass(frozen=True, eq=False)
class SkinnedPart:
    """One mesh of the avatar at the bind pose: vertices (n, 3) m, faces, colours, weights.

    A part may carry a sharp colour edge (a neckline, a cuff) that does not follow its
    triangles: *edge_m* (n,) is each vertex's signed distance to the edge; the surface
    shows *colors_rgb* where the distance is ≥ 0 and *across_rgb* (n, 3) where it is
    negative. The distance is interpolated across a triangle and the edge drawn where
    it crosses zero, so a distance linear in position draws a straight edge through
    triangles. A part lying on another's surface (nails, the face's features) need not
    *cast_shadow*: the surface under it casts the shadow, and the shadow pass skips it.
    """

    name: str
    vertices_m: np.ndarray
    faces: np.ndarray
    colors_rgb: np.ndarray
    weights: SkinWeights
    normals: np.ndarray = field(default=None)
    edge_m: np.ndarray | None = None
    across_rgb: np.ndarray | None = None
    casts_shadow: bool = True
    morphs: Morphs | None = None

    def __post_init__(self) -> None:
        if self.normals is None:
            mesh = trimesh.Trimesh(self.vertices_m, self.faces, process=False)
            object.__setattr__(self, "normals", np.asarray(mesh.vertex_normals, dtype=np.float64))

    def vertex_rgb(self) -> np.ndarray:
        """Return the colour (n, 3) the surface shows at each vertex."""
        if self.edge_m is None:
            return np.asarray(self.colors_rgb)
        return np.where((self.edge_m >= 0)[:, None], self.colors_rgb, self.across_rgb)

    def trimesh(self, vertices_m: np.ndarray | None = None) -> trimesh.Trimesh:
        """Return the part as a trimesh (at the bind pose unless *vertices_m* is given)."""
        return trimesh.Trimesh(
            self.vertices_m if vertices_m is None else vertices_m, self.faces, process=False
        )


def merge_parts(name: str, parts, casts_shadow: bool = True) -> SkinnedPart:
    """Return one part made of several (drawn at once: a part is one draw call a pass).

    A part without a colour edge keeps its colours everywhere in the merged one.
    """
    offsets = np.cumsum([0] + [len(part.vertices_m) for part in parts[:-1]])
    edged = any(part.edge_m is not None for part in parts)

    def stack(field, fill=None):
        return np.concatenate(
            [
                np.asarray(getattr(part, field)) if getattr(part, field) is not None else fill(part)
                for part in parts
            ]
        )

    return SkinnedPart(
        name,
        stack("vertices_m"),
        np.concatenate([part.faces + offset for part, offset in zip(parts, offsets, strict=True)]),
        stack("colors_rgb"),
        SkinWeights(
            np.concatenate([part.weights.joints for part in parts]),
            np.concatenate([part.weights.weights for part in parts]),
        ),
        stack("normals"),
        stack("edge_m", lambda part: np.ones(len(part.vertices_m))) if edged else None,
        stack("across_rgb", lambda part: np.asarray(part.colors_rgb)) if edged else None,
        casts_shadow,
        _merge_morphs(parts, offsets),
    )


def _merge_morphs(parts, offsets) -> Morphs | None:
    """Return the blendshapes of merged *parts* (each keeps its own; a part without one
    of the others' has zero offsets in it), or None if no part has any."""
    shaped = [
        (part.morphs, offset)
        for part, offset in zip(parts, offsets, strict=True)
        if part.morphs is not None
    ]
    if not shaped:
        return None
    names = tuple(dict.fromkeys(name for morphs, _ in shaped for name in morphs.names))
    vertices = np.concatenate([morphs.vertices + offset for morphs, offset in shaped])
    offsets_m = np.zeros((len(names), len(vertices), 3))
    normal_offsets = np.zeros_like(offsets_m)
    start = 0
    for morphs, _ in shaped:
        rows = [names.index(name) for name in morphs.names]
        stop = start + len(morphs.vertices)
        offsets_m[rows, start:stop] = morphs.offsets_m
        normal_offsets[rows, start:stop] = morphs.normal_offsets
        start = stop
    return Morphs(names, vertices, offsets_m, normal_offsets)


def rigid_part(
    name: str, vertices_m, faces, owners, color_rgb, casts_shadow: bool = True
) -> SkinnedPart:
    """Return a part whose every vertex follows one bone (*owners*: joint index per vertex)."""
    weights = np.zeros((len(owners), 4))
    weights[:, 0] = 1.0
    return SkinnedPart(
        name,
        np.asarray(vertices_m, dtype=np.float64),
        np.asarray(faces, dtype=np.int64),
        np.broadcast_to(np.asarray(color_rgb, dtype=np.float64), (len(owners), 3)),
        SkinWeights(np.repeat(np.asarray(owners)[:, None], 4, axis=1), weights),
        casts_shadow=casts_shadow,
    )


@dataclass(frozen=True, eq=False)
class Avatar:
    """A rig plus skinned parts; ``rig`` has ``skeleton``, ``pose(dofs)`` and ``neutral()``.

    Parts with blendshapes (``morphs``) take their weights from the rig's DOFs through
    *drive* (the face's channels); posed from joint transforms alone they keep their
    bind shape. The bind pose is the rig's at *bind_dofs_rad*, or *bind* for an avatar
    imported with its own (:mod:`synthesis.avatar.imported.humanoid`).
    """

    name: str
    rig: object
    bind_dofs_rad: np.ndarray
    parts: tuple[SkinnedPart, ...]
    drive: MorphDrive | None = None
    bind: Pose | None = None  # an imported avatar's own bind pose, not one of the rig's

    @cached_property
    def bind_pose(self) -> Pose:
        """Return the joints' global transforms at the bind pose (one frame)."""
        return self.bind if self.bind is not None else self.rig.pose(self.bind_dofs_rad)

    @cached_property
    def _weight_matrices(self) -> list[sparse.csr_matrix]:
        n_joints = len(self.rig.skeleton)
        return [part.weights.matrix(n_joints) for part in self.parts]

    def deform(self, dofs_rad: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
        """Return, per part, posed vertices and normals (n_frames, n, 3) for DOF vectors."""
        dofs = np.atleast_2d(dofs_rad)
        weights = None if self.drive is None else self.drive.weights(dofs)
        return self.deform_pose(self.rig.pose(dofs), morph_weights=weights)

    @cached_property
    def _morph_columns(self) -> list[np.ndarray | None]:
        """Return, per part, the drive's column of each of its blendshapes."""
        names = () if self.drive is None else self.drive.names
        return [
            None
            if part.morphs is None
            else np.array([names.index(name) for name in part.morphs.names], dtype=np.intp)
            for part in self.parts
        ]

    def deform_pose(
        self,
        pose: Pose,
        select: list[np.ndarray] | None = None,
        morph_weights: np.ndarray | None = None,
    ) -> list[tuple[np.ndarray, np.ndarray]]:
        """Return, per part, posed vertices and normals for joint transforms (n_frames, …).

        *select*, per part a boolean mask (n,) or indices, poses only those vertices;
        *morph_weights* (n_frames, the drive's blendshapes) shape the parts that have
        blendshapes first.
        """
        transforms = skin_transforms(pose, self.bind_pose)
        select = select if select is not None else [None] * len(self.parts)
        posed = []
        for part, matrix, columns, k in zip(
            self.parts, self._weight_matrices, self._morph_columns, select, strict=True
        ):
            vertices, normals = part.vertices_m, part.normals
            if morph_weights is not None and columns is not None:
                vertices, normals = part.morphs.rest(vertices, normals, morph_weights[:, columns])
            if k is not None:
                vertices, normals, matrix = vertices[..., k, :], normals[..., k, :], matrix[k]
            posed.append(linear_blend_skinning(vertices, normals, matrix, transforms))
        return posed

    @property
    def triangle_count(self) -> int:
        """Return the number of triangles of all parts together."""
        return sum(len(part.faces) for part in self.parts)
