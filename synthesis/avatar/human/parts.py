"""The human avatar's features besides its skin: eyeballs, brows, lashes, hair, teeth.

Eyeballs are spheres made here, their pupil and iris edges on rings of their own so
that the colours change sharply, turned by the rig's eye joints (gaze). Brows and a
close-cropped hair cap are shells lifted a little off the skin over regions chosen
around the eyes, carrying the skin's weights and blendshapes so that they move with it
(a brow raise moves the brows). Lashes, teeth and tongue are MakeHuman's helper meshes,
which its face targets move (a blink closes the lashes, the jaw takes the lower teeth).
"""

import numpy as np

# Latitudes (degrees from the eye's forward axis) of the eyeball's rings; pupil and iris
# edges appear twice, one ring for each colour.
PUPIL_DEG, IRIS_DEG = 11.0, 31.0
_RINGS_DEG = (
    0.0,
    5.0,
    PUPIL_DEG,
    PUPIL_DEG,
    17.0,
    24.0,
    IRIS_DEG,
    IRIS_DEG,
    40.0,
    55.0,
    75.0,
    100.0,
    130.0,
    160.0,
    180.0,
)
_SEGMENTS = 32


def sphere_fit(points_m: np.ndarray) -> tuple[np.ndarray, float]:
    """Return the centre (3,) and radius of the sphere through *points_m* (least squares)."""
    a = np.column_stack([2 * points_m, np.ones(len(points_m))])
    b = (points_m**2).sum(axis=1)
    solution, *_ = np.linalg.lstsq(a, b, rcond=None)
    centre = solution[:3]
    return centre, float(np.sqrt(solution[3] + centre @ centre))


def eyeball(centre_m, radius_m: float, forward, sclera_rgb, iris_rgb, pupil_rgb):
    """Return an eyeball's vertices, faces and colours: rings about *forward*."""
    forward = np.asarray(forward, dtype=np.float64)
    side = np.cross(forward, [0.0, 1.0, 0.0])
    side /= np.linalg.norm(side)
    up = np.cross(side, forward)
    vertices, colours = [], []
    angles = np.linspace(0.0, 2 * np.pi, _SEGMENTS, endpoint=False)
    seen_pupil = seen_iris = False
    for latitude in _RINGS_DEG:
        theta = np.radians(latitude)
        if latitude < PUPIL_DEG or (latitude == PUPIL_DEG and not seen_pupil):
            colour = pupil_rgb
            seen_pupil |= latitude == PUPIL_DEG
        elif latitude < IRIS_DEG or (latitude == IRIS_DEG and not seen_iris):
            colour = iris_rgb
            seen_iris |= latitude == IRIS_DEG
        else:
            colour = sclera_rgb
        ring = np.cos(theta) * forward[None] + np.sin(theta) * (
            np.cos(angles)[:, None] * side[None] + np.sin(angles)[:, None] * up[None]
        )
        vertices.append(np.asarray(centre_m) + radius_m * ring)
        colours.append(np.broadcast_to(colour, (_SEGMENTS, 3)))
    vertices, colours = np.concatenate(vertices), np.concatenate(colours)
    faces = []
    for ring in range(len(_RINGS_DEG) - 1):
        a, b = ring * _SEGMENTS, (ring + 1) * _SEGMENTS
        for k in range(_SEGMENTS):
            k1 = (k + 1) % _SEGMENTS
            faces += [(a + k, b + k1, b + k), (a + k, a + k1, b + k1)]
    return vertices, np.array(faces, dtype=np.int64), colours


def shell(
    vertices_m: np.ndarray,
    normals: np.ndarray,
    faces: np.ndarray,
    chosen: np.ndarray,
    lift_m: float,
):
    """Return a shell over the *chosen* faces (a face mask): its vertices (their corners
    lifted along their normals), faces, and for each of its vertices the skin vertex it
    came from."""
    used = np.unique(faces[chosen])
    renumber = np.full(len(vertices_m), -1)
    renumber[used] = np.arange(len(used))
    return vertices_m[used] + lift_m * normals[used], renumber[faces[chosen]], used


def brow_distance(
    vertices_m: np.ndarray, eye_m: np.ndarray, midline_x: float = 0.0, scale: float = 1.0
) -> np.ndarray:
    """Return each point's signed distance (m, about) to one brow, negative on it: an
    arch above the eye *eye_m* (either side), thick at the nose, thin at its tail
    (measured × *scale*). Behind the eye's front the distance is large."""
    outward = np.sign(eye_m[0] - midline_x)
    length = 0.022 * scale
    u = (vertices_m[:, 0] - eye_m[0]) * outward / length  # −1 inner … 1 outer
    height = (vertices_m[:, 1] - eye_m[1]) / scale
    middle = 0.0172 + 0.0032 * (1 - np.clip(u, -1.2, 1.2) ** 2) - 0.0012 * u
    half = 0.0043 - 0.0015 * (np.clip(u, -1.0, 1.1) + 1)
    across = (np.abs(height - middle) - half) * scale
    ends = np.maximum(-1.0 - u, u - 1.1) * length
    behind = np.where(vertices_m[:, 2] < eye_m[2] - 0.01 * scale, 1.0, 0.0)
    return np.maximum(across, ends) + behind


def hair_distance(vertices_m: np.ndarray, eyes_m: np.ndarray, scale: float = 1.0) -> np.ndarray:
    """Return each point's signed height (m) above the hairline, negative in the hair: a
    hairline that runs over the forehead, drops behind the temples and above the ears,
    and goes round the back of the head."""
    eye = eyes_m.mean(axis=0)
    relative = (vertices_m - eye) / scale
    back = np.clip(-relative[:, 2] / 0.11, 0.0, 1.0)  # 0 at the eyes' depth, 1 behind
    side = np.clip((np.abs(relative[:, 0]) - 0.045) / 0.03, 0.0, 1.0)
    hairline = 0.047 - 0.002 * (relative[:, 0] / 0.03) ** 2 - 0.03 * side - 0.06 * back
    return (hairline - relative[:, 1]) * scale


def smoothed(
    vertices_m: np.ndarray, faces: np.ndarray, chosen: np.ndarray, iterations: int = 12
) -> np.ndarray:
    """Return the mesh with the *chosen* vertices smoothed (Taubin's λ|μ filter, which
    keeps the volume; trimesh's): a top's cloth over the chest and belly, not the skin's
    every detail. The other vertices stay."""
    import trimesh

    mesh = trimesh.Trimesh(vertices_m, faces, process=False)
    trimesh.smoothing.filter_taubin(mesh, lamb=0.5, nu=0.53, iterations=iterations)
    return np.where(chosen[:, None], mesh.vertices, vertices_m)


def draped(
    vertices_m: np.ndarray, faces: np.ndarray, weight: np.ndarray, radius_m: float = 0.04
) -> np.ndarray:
    """Return the mesh with each vertex moved toward the mean of the surface within
    *radius_m* of it (Gaussian in distance, each vertex counted by its share of the
    surface's area), by *weight* (n,) from 0 (stays) to 1: cloth over the skin, which does
    not follow details smaller than the radius. Counting by area, not by vertex, keeps
    MakeHuman's dense patches (the chest's, a few millimetres apart) from holding their
    shape: smoothing along the mesh's edges (Taubin's filter) left them."""
    import trimesh
    from scipy.spatial import cKDTree

    mesh = trimesh.Trimesh(vertices_m, faces, process=False)
    area = np.zeros(len(vertices_m))
    np.add.at(area, faces.ravel(), np.repeat(mesh.area_faces / 3.0, 3))
    moved = np.flatnonzero(weight > 0)
    tree = cKDTree(vertices_m)
    out = np.array(vertices_m, dtype=np.float64)
    sigma = radius_m / 2
    for k, neighbours in zip(
        moved, tree.query_ball_point(vertices_m[moved], radius_m), strict=True
    ):
        near = vertices_m[neighbours]
        gauss = area[neighbours] * np.exp(
            -np.sum((near - vertices_m[k]) ** 2, axis=1) / (2 * sigma**2)
        )
        out[k] = vertices_m[k] + weight[k] * (gauss @ near / gauss.sum() - vertices_m[k])
    return out
