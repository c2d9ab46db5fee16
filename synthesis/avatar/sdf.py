"""Signed distance fields of body parts and their smooth union, meshed by marching cubes.

An avatar's skin is one implicit surface: every bone contributes a primitive (a round
cone along the bone, or a rounded plate for the palm), primitives are merged with a
polynomial smooth minimum so joints blend like flesh instead of meeting like a robot's
capsules, and marching cubes (scikit-image) turns the zero level set into a single
watertight triangle mesh at the rest pose (spec 01 "Avatar").

Distances are in metres; negative inside. :func:`simplify` then decimates the mesh,
keeping it watertight.
"""

from dataclasses import dataclass

import numpy as np
import trimesh


@dataclass(frozen=True)
class RoundCone:
    """A round cone from *start_m* to *end_m*, radii at both ends, moved by *joint*.

    ``flatten`` < 1 squashes the cross-section along *normal* (a forearm, a finger's pad),
    which keeps the zero set smooth while the distance becomes a bound.
    """

    joint: str
    start_m: tuple[float, float, float]
    end_m: tuple[float, float, float]
    radius_start_m: float
    radius_end_m: float
    blend_m: float = 0.0
    flatten: float = 1.0
    normal: tuple[float, float, float] = (0.0, 0.0, 1.0)

    def distance(self, points_m: np.ndarray) -> np.ndarray:
        """Return the signed distance of points (..., 3) to the surface, metres."""
        a = np.asarray(self.start_m)
        relative = points_m - a
        if self.flatten != 1.0:
            normal = np.asarray(self.normal) / np.linalg.norm(self.normal)
            along = relative @ normal
            relative = relative + np.multiply.outer(along, normal) * (1.0 / self.flatten - 1.0)
        distance = _round_cone(
            relative, np.asarray(self.end_m) - a, self.radius_start_m, self.radius_end_m
        )
        return distance * min(self.flatten, 1.0)

    def axis_distance(self, points_m: np.ndarray) -> np.ndarray:
        """Return the distance of points (..., 3) to the bone's axis segment, metres."""
        return self._axis(points_m)[0]

    def relative_axis_distance(self, points_m: np.ndarray) -> np.ndarray:
        """Return the axis distance in units of the cone's radius where it is nearest."""
        distance, t = self._axis(points_m)
        return distance / (self.radius_start_m + t * (self.radius_end_m - self.radius_start_m))

    def _axis(self, points_m: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        a, b = np.asarray(self.start_m), np.asarray(self.end_m)
        ab = b - a
        t = np.clip(((points_m - a) @ ab) / (ab @ ab), 0.0, 1.0)
        return np.linalg.norm(points_m - a - np.multiply.outer(t, ab), axis=-1), t

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """Return the axis-aligned box (low, high) that holds the primitive."""
        radius = max(self.radius_start_m, self.radius_end_m)
        ends = np.array([self.start_m, self.end_m])
        return ends.min(axis=0) - radius, ends.max(axis=0) + radius


def _round_cone(p: np.ndarray, ba: np.ndarray, r1: float, r2: float) -> np.ndarray:
    """Return the exact distance to a round cone from the origin to *ba* (radii r1, r2)."""
    l2 = float(ba @ ba)
    rr = r1 - r2
    a2 = l2 - rr * rr
    y = p @ ba
    z = y - l2
    x2 = np.sum((p * l2 - np.multiply.outer(y, ba)) ** 2, axis=-1)
    y2, z2 = y * y * l2, z * z * l2
    k = np.sign(rr) * rr * rr * x2
    at_end = np.sign(z) * a2 * z2 > k
    at_start = np.sign(y) * a2 * y2 < k
    side = (np.sqrt(np.maximum(x2 * a2 / l2, 0.0)) + y * rr) / l2 - r1
    end = np.sqrt(x2 + z2) / l2 - r2
    start = np.sqrt(x2 + y2) / l2 - r1
    return np.where(at_end, end, np.where(at_start, start, side))


@dataclass(frozen=True)
class RoundedPlate:
    """A flat convex polygon thickened to *half_thickness_m* with rounded rims (the palm).

    The polygon lies in the plane through *centre_m* spanned by *u* and *v*; its corners
    are given in that plane's coordinates (metres), counter-clockwise.
    """

    joint: str
    centre_m: tuple[float, float, float]
    u: tuple[float, float, float]
    v: tuple[float, float, float]
    corners_m: tuple[tuple[float, float], ...]
    half_thickness_m: float
    blend_m: float = 0.0

    def _plane(self, points_m: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        u, v = np.asarray(self.u), np.asarray(self.v)
        n = np.cross(u, v)
        relative = points_m - np.asarray(self.centre_m)
        return np.stack((relative @ u, relative @ v), axis=-1), relative @ n

    def axis_distance(self, points_m: np.ndarray) -> np.ndarray:
        """Return the distance of points (..., 3) to the polygon itself, metres."""
        in_plane, height = self._plane(points_m)
        outside = _polygon_distance(in_plane, np.asarray(self.corners_m))
        return np.hypot(np.maximum(outside, 0.0), height)

    def relative_axis_distance(self, points_m: np.ndarray) -> np.ndarray:
        """Return the distance to the polygon in units of the plate's half thickness."""
        return self.axis_distance(points_m) / self.half_thickness_m

    def distance(self, points_m: np.ndarray) -> np.ndarray:
        """Return the signed distance of points (..., 3) to the plate's surface, metres."""
        in_plane, height = self._plane(points_m)
        outside = _polygon_distance(in_plane, np.asarray(self.corners_m))
        inside = np.maximum(outside, 0.0)
        return np.where(
            outside > 0,
            np.hypot(inside, height) - self.half_thickness_m,
            np.maximum(np.abs(height) - self.half_thickness_m, outside - self.half_thickness_m),
        )

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """Return the axis-aligned box (low, high) that holds the primitive."""
        u, v = np.asarray(self.u), np.asarray(self.v)
        corners = np.asarray(self.centre_m) + np.asarray(self.corners_m) @ np.stack((u, v))
        return corners.min(axis=0) - self.half_thickness_m, corners.max(
            axis=0
        ) + self.half_thickness_m


def _polygon_distance(points: np.ndarray, corners: np.ndarray) -> np.ndarray:
    """Return the signed 2-D distance to a convex counter-clockwise polygon (negative inside)."""
    starts, ends = corners, np.roll(corners, -1, axis=0)
    edges = ends - starts
    relative = points[..., None, :] - starts
    t = np.clip(np.sum(relative * edges, axis=-1) / np.sum(edges * edges, axis=-1), 0.0, 1.0)
    nearest = np.linalg.norm(relative - t[..., None] * edges, axis=-1).min(axis=-1)
    cross = edges[:, 0] * relative[..., 1] - edges[:, 1] * relative[..., 0]
    inside = np.all(cross >= 0, axis=-1)
    return np.where(inside, -nearest, nearest)


Primitive = RoundCone | RoundedPlate


def smooth_min(a: np.ndarray, b: np.ndarray, blend_m: float) -> np.ndarray:
    """Return the polynomial smooth minimum of two distances (Quílez); min where apart > k."""
    if blend_m <= 0:
        return np.minimum(a, b)
    h = np.maximum(blend_m - np.abs(a - b), 0.0) / blend_m
    return np.minimum(a, b) - h * h * blend_m * 0.25


def union_distance(primitives: tuple[Primitive, ...], points_m: np.ndarray) -> np.ndarray:
    """Return the smooth union's distance at points (..., 3): primitives merged in order.

    Each primitive blends into everything before it with its own ``blend_m``: a finger's
    phalanges blend into each other tightly, the whole finger into the palm more softly.
    """
    result = np.full(points_m.shape[:-1], np.inf)
    for primitive in primitives:
        result = smooth_min(result, primitive.distance(points_m), primitive.blend_m)
    return result


def sample_grid(
    primitives: tuple[Primitive, ...], voxel_m: float, block: int = 24
) -> tuple[np.ndarray, np.ndarray]:
    """Return the union's distances on a grid (nx, ny, nz) and the grid's origin (3,), m.

    Only blocks near the surface are evaluated in full, and only with the primitives
    that can reach them: a primitive further than its blend width beyond the nearest one
    leaves a smooth minimum unchanged, so skipping it is exact.
    """
    lows, highs = zip(*(p.bounds() for p in primitives), strict=True)
    margin = 3 * voxel_m + max(p.blend_m for p in primitives)
    # An odd fraction of a voxel off the round numbers of the primitives: a surface through
    # a grid point exactly would give marching cubes degenerate, zero-area triangles.
    origin = np.min(lows, axis=0) - margin + voxel_m * np.array([0.2137, 0.3161, 0.4271])
    shape = np.ceil((np.max(highs, axis=0) + margin - origin) / voxel_m).astype(int) + 1
    far = 4 * voxel_m
    volume = np.full(tuple(shape), far, dtype=np.float32)
    half_diagonal = 0.5 * np.sqrt(3.0) * block * voxel_m
    blend = max(p.blend_m for p in primitives)
    starts = [np.arange(0, n, block) for n in shape]
    grid = np.stack(np.meshgrid(*starts, indexing="ij"), axis=-1).reshape(-1, 3)
    centres = origin + (grid + 0.5 * block) * voxel_m
    at_centres = np.stack([p.distance(centres) for p in primitives], axis=1)
    nearest = at_centres.min(axis=1)
    for corner, distances, best in zip(grid, at_centres, nearest, strict=True):
        if best > half_diagonal + far:
            continue
        useful = tuple(
            p
            for p, d in zip(primitives, distances, strict=True)
            if d - half_diagonal <= best + half_diagonal + blend
        )
        stop = np.minimum(corner + block, shape)
        axes = [origin[k] + np.arange(corner[k], stop[k]) * voxel_m for k in range(3)]
        points = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1)
        values = union_distance(useful, points)
        volume[corner[0] : stop[0], corner[1] : stop[1], corner[2] : stop[2]] = np.minimum(
            values, far
        )
    return volume, origin


def mesh_primitives(
    primitives: tuple[Primitive, ...], voxel_m: float
) -> tuple[np.ndarray, np.ndarray]:
    """Return a watertight mesh of the union: vertices (n, 3) m, faces (m, 3) wound outward."""
    from skimage.measure import marching_cubes

    volume, origin = sample_grid(primitives, voxel_m)
    # No sample may sit exactly on the level (same reason as the grid's offset).
    volume[volume == 0.0] = np.float32(1e-9)
    vertices, faces, _, _ = marching_cubes(volume, level=0.0, spacing=(voxel_m,) * 3)
    # scikit-image's default "descent" winding faces outward for negative-inside fields.
    return vertices + origin, faces


def simplify(vertices, faces, target_faces: int):
    """Return the mesh decimated to about *target_faces* (quadric error, fast-simplification).

    Aggressive decimation can leave an edge shared by more than two triangles; the skin
    must stay watertight, so gentler settings are tried in turn, and the full mesh is
    kept if none holds.
    """
    if len(faces) <= target_faces:
        return vertices, faces
    import fast_simplification

    for aggressiveness in (7.0, 4.0, 2.0, 1.0):
        fewer_vertices, fewer_faces = fast_simplification.simplify(
            np.asarray(vertices, dtype=np.float32),
            np.asarray(faces, dtype=np.int32),
            target_count=target_faces,
            agg=aggressiveness,
        )
        if trimesh.Trimesh(fewer_vertices, fewer_faces, process=False).is_watertight:
            return fewer_vertices, fewer_faces
    return vertices, faces
