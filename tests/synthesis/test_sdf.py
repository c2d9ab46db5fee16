"""Test the skin's distance fields and their meshing (synthesis.avatar.sdf)."""

import numpy as np
import trimesh

from synthesis.avatar.sdf import (
    RoundCone,
    RoundedPlate,
    mesh_primitives,
    sample_grid,
    smooth_min,
    union_distance,
)


def test_round_cone_distance_is_exact_for_a_capsule():
    capsule = RoundCone("j", (0, 0, 0), (0, 0.1, 0), 0.02, 0.02)
    points = np.array([[0.05, 0.05, 0], [0, 0.15, 0], [0, -0.03, 0], [0, 0.05, 0]])
    expected = [0.03, 0.03, 0.01, -0.02]
    assert np.allclose(capsule.distance(points), expected, atol=1e-12)


def test_round_cone_tapers_between_its_radii():
    cone = RoundCone("j", (0, 0, 0), (0, 0.1, 0), 0.02, 0.01)
    # Surface points at both ends and the side (the side is slanted, so measure normal to it).
    assert abs(cone.distance(np.array([0, -0.02, 0]))) < 1e-12
    assert abs(cone.distance(np.array([0, 0.11, 0]))) < 1e-12
    assert cone.distance(np.array([0.0, 0.05, 0.0])) < 0  # inside on the axis


def test_flattened_cone_is_thinner_along_its_normal():
    cone = RoundCone("j", (0, 0, 0), (0, 0.1, 0), 0.02, 0.02, flatten=0.5, normal=(0, 0, 1))
    assert cone.distance(np.array([0.0, 0.05, 0.011])) > 0  # beyond 0.5 · 20 mm
    assert cone.distance(np.array([0.019, 0.05, 0.0])) < 0  # full width across


def test_plate_distance_inside_outside_and_rim():
    plate = RoundedPlate(
        "p",
        (0, 0, 0),
        (1, 0, 0),
        (0, 1, 0),
        ((-0.04, -0.04), (0.04, -0.04), (0.04, 0.04), (-0.04, 0.04)),
        0.01,
    )
    points = np.array([[0, 0, 0], [0, 0, 0.02], [0.06, 0, 0], [0.039, 0, 0]])
    assert np.allclose(plate.distance(points), [-0.01, 0.01, 0.01, -0.01], atol=1e-12)


def test_smooth_min_never_exceeds_min_and_equals_it_when_apart():
    a = np.linspace(-0.05, 0.05, 101)
    b = np.zeros_like(a)
    blended = smooth_min(a, b, 0.01)
    assert np.all(blended <= np.minimum(a, b) + 1e-15)
    apart = np.abs(a - b) >= 0.01
    assert np.allclose(blended[apart], np.minimum(a, b)[apart])
    assert np.all(blended[~apart] < np.minimum(a, b)[~apart] + 1e-15)


def test_block_sampling_matches_full_evaluation_near_the_surface():
    shapes = (
        RoundCone("a", (0, 0, 0), (0, 0.08, 0), 0.02, 0.015),
        RoundCone("b", (0, 0.08, 0), (0.05, 0.12, 0), 0.015, 0.01, blend_m=0.01),
        RoundCone("c", (0.2, 0, 0), (0.2, 0.05, 0), 0.01, 0.01, blend_m=0.002),
    )
    volume, origin = sample_grid(shapes, 0.003, block=8)
    index = np.indices(volume.shape).reshape(3, -1).T
    points = origin + index * 0.003
    exact = union_distance(shapes, points).reshape(volume.shape)
    near = np.abs(exact) < 0.006
    assert np.allclose(volume[near], exact[near], atol=1e-6)
    assert np.all(np.sign(volume[~near]) == np.sign(exact[~near]))


def test_mesh_is_watertight_outward_and_close_to_the_analytic_volume():
    capsule = RoundCone("j", (0, 0, 0), (0, 0.1, 0), 0.02, 0.02)
    vertices, faces = mesh_primitives((capsule,), 0.001)
    mesh = trimesh.Trimesh(vertices, faces)
    analytic = np.pi * 0.02**2 * 0.1 + 4 / 3 * np.pi * 0.02**3
    assert mesh.is_watertight and mesh.body_count == 1
    assert mesh.volume > 0  # faces wound outward
    assert abs(mesh.volume - analytic) / analytic < 0.02
