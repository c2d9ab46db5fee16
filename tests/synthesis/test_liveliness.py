"""Test the liveliness noise: small, smooth, distal-fast, larger on the weak side."""

import numpy as np

from synthesis.rigs.body import BodyModel
from synthesis.signing.liveliness import DEFAULT_GROUPS, Liveliness, joint_group

BODY = BodyModel()
RATE = 60.0


def _noise(seed=0, n=1200, body=BODY):
    return Liveliness().sample(body, n, RATE, np.random.default_rng(seed))


def test_below_one_degree_at_the_fingers_and_weak_side_larger():
    noise = np.degrees(_noise())
    names = BODY.dof_names
    fingers = [i for i, n in enumerate(names) if joint_group(n) == "fingers"]
    assert np.abs(noise[:, fingers]).max() < 1.0
    right = names.index("right_index_mcp_flexion")
    left = names.index("left_index_mcp_flexion")
    assert np.abs(noise[:, left]).max() > 1.5 * np.abs(noise[:, right]).max()
    assert np.abs(noise[:, right]).max() == np.float64(DEFAULT_GROUPS["fingers"][0])


def test_no_visible_jitter_and_distal_joints_vary_faster():
    noise = np.degrees(_noise())
    # Frame-to-frame angular acceleration at 60 fps: at most 0.03° per frame² (110°/s²)
    # anywhere, a tremor far below what the eye picks out at this amplitude.
    assert np.abs(np.diff(noise, 2, axis=0)).max() < 0.03
    names = BODY.dof_names

    def mean_frequency(column):
        power = np.abs(np.fft.rfft(noise[:, column])) ** 2
        freqs = np.fft.rfftfreq(len(noise), 1 / RATE)
        return float((power * freqs).sum() / power.sum())

    spine = mean_frequency(names.index("spine_lower_flexion"))
    finger = mean_frequency(names.index("right_index_pip_flexion"))
    assert finger > 2 * spine


def test_deterministic_by_seed():
    assert np.array_equal(_noise(3, 300), _noise(3, 300))
    assert not np.array_equal(_noise(3, 300), _noise(4, 300))
