"""Test the finger self-intersection check: segment distances and capsule overlaps."""

import numpy as np

from synthesis.rigs.collisions import finger_intersections, segment_distances
from synthesis.rigs.hand import HandModel


def test_segment_distance_against_dense_sampling():
    rng = np.random.default_rng(0)
    p1, q1, p2, q2 = (rng.normal(size=(50, 3)) for _ in range(4))
    exact = segment_distances(p1, q1, p2, q2)
    t = np.linspace(0, 1, 201)
    a = p1[:, None] + t[None, :, None] * (q1 - p1)[:, None]
    b = p2[:, None] + t[None, :, None] * (q2 - p2)[:, None]
    sampled = np.linalg.norm(a[:, :, None] - b[:, None, :], axis=-1).min(axis=(1, 2))
    assert np.all(exact <= sampled + 1e-12)
    assert np.allclose(exact, sampled, atol=0.02)


def test_crossing_and_parallel_segments():
    origin = np.zeros(3)
    crossing = segment_distances(
        np.array([-1.0, 0, 0]), np.array([1.0, 0, 0]), np.array([0, -1.0, 0]), np.array([0, 1.0, 0])
    )
    assert crossing == 0.0
    parallel = segment_distances(
        origin, np.array([1.0, 0, 0]), np.array([0, 0.3, 0]), np.array([1.0, 0.3, 0])
    )
    assert abs(parallel - 0.3) < 1e-12


def test_a_finger_bent_through_its_neighbour_is_caught():
    model = HandModel()
    assert finger_intersections(model, model.neutral()) == []
    # Index spread far toward the middle finger (adduction past the limit of anatomy).
    through = model.neutral()
    through[model.dof_names.index("index_mcp_abduction")] = np.radians(-40)
    hits = finger_intersections(model, through)
    pairs = {(hit.first, hit.second) for hit in hits}
    assert ("index_mcp–index_pip", "middle_mcp–middle_pip") in pairs
    assert all(hit.depth_m > 0.004 for hit in hits)
