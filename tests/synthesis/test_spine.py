"""Test the automated spine and shoulder formulas (seed 003 §3.1–3.3, spec 03).

The seed's formulas are checked against the equations printed in seed 003 §3.1 (bend
``c0·smoothstep(|V_reach|/L_arm)``, twist ``c1·smoothstep(V_w·V_twist/(2 L_arm))``);
the comfort-radius variant against its own definition in ``synthesis.signing.spine``.
"""

import numpy as np
import pytest

from synthesis.signing.spine import SpineParams, smoothstep, spine_motion

SEED = SpineParams()
PARAMS = SpineParams(formula="comfort")
RIGHT_SHOULDER = np.array([0.175, 0.0, 0.0])
LEFT_SHOULDER = np.array([-0.175, 0.0, 0.0])


def _motion(v_right, v_left, params=PARAMS):
    """Return the extension for displacement vectors from each shoulder (torso frame)."""
    return spine_motion(
        RIGHT_SHOULDER + np.atleast_2d(v_right),
        LEFT_SHOULDER + np.atleast_2d(v_left),
        RIGHT_SHOULDER,
        LEFT_SHOULDER,
        params,
    )


def test_smoothstep_is_the_papers_cubic_clamped():
    x = np.array([-0.5, 0.0, 0.25, 0.5, 1.0, 2.0])
    assert np.allclose(smoothstep(x), [0, 0, 3 / 16 - 2 / 64, 0.5, 1, 1])


def test_no_bend_inside_the_comfort_zone_near_the_body():
    for angle in np.linspace(0, 2 * np.pi, 9):
        near = 0.95 * PARAMS.comfort_m * np.array([np.cos(angle), np.sin(angle), -0.3])
        motion = _motion(near, near)
        assert motion.bend_rad[0] == 0.0


def test_bend_saturates_smoothly_at_full_reach():
    c0 = np.radians(PARAMS.bend_deg)
    reach = np.linspace(0.0, 0.8, 161)
    bends = np.array([_motion([0, r, 0], [0, r, 0]).bend_rad[0] for r in reach])
    assert np.all(np.diff(bends) >= -1e-15)  # never decreases with reach
    assert np.allclose(bends[reach >= PARAMS.arm_length_m], c0)
    # C¹ at the ends of the ramp: the slope fades to zero at both.
    slope = np.gradient(bends, reach)
    assert slope[np.argmin(np.abs(reach - PARAMS.arm_length_m))] < 0.05 * slope.max()
    assert slope[np.argmin(np.abs(reach - PARAMS.comfort_m))] < 0.05 * slope.max()


def test_bends_add_for_two_arms_reaching_the_same_way():
    one = _motion([0.45, 0.35, 0.0], [0.0, 0.0, 0.0])
    two = _motion([0.45, 0.35, 0.0], [0.45, 0.35, 0.0])
    assert two.bend_rad[0] > one.bend_rad[0] > 0
    assert np.allclose(two.bend_axis, one.bend_axis)  # both bend toward the reach
    # The bend axis is Z × V_reach: reaching forward tips the torso forward (about −x).
    forward = _motion([0, 0.5, 0], [0, 0.5, 0])
    assert np.allclose(forward.bend_axis[0], [-1, 0, 0])
    angles = forward.spine_angles(PARAMS)
    assert sum(a[0, 0] for a in angles.values()) == pytest.approx(forward.bend_rad[0])


def test_twists_cancel_for_symmetric_forward_reach_and_add_laterally():
    assert _motion([0, 0.5, 0], [0, 0.5, 0]).twist_rad[0] == 0.0
    right_forward = _motion([0, 0.5, 0], [0, 0, 0]).twist_rad[0]
    left_forward = _motion([0, 0, 0], [0, 0.5, 0]).twist_rad[0]
    assert right_forward > 0 and left_forward == pytest.approx(-right_forward)
    # Both hands moving to the signer's right turn the torso that way (negative), more
    # than one hand; hands moving apart cancel.
    one = _motion([0.3, 0, 0], [0, 0, 0]).twist_rad[0]
    both = _motion([0.3, 0, 0], [0.3, 0, 0]).twist_rad[0]
    assert both < one < 0
    assert _motion([0.3, 0, 0], [-0.3, 0, 0]).twist_rad[0] == 0.0


def test_a_purely_vertical_reach_moves_no_spine():
    for height in (0.5, -0.5):
        motion = _motion([0, 0, height], [0, 0, height])
        assert motion.bend_rad[0] == 0.0 and motion.twist_rad[0] == 0.0
        assert not np.any([a for a in motion.spine_angles(PARAMS).values()])
    raised = _motion([0, 0, 0.4], [0, 0, 0])
    assert raised.clavicle_raise_rad["right"][0] > 0 == raised.clavicle_raise_rad["left"][0]
    assert _motion([0, 0, -0.4], [0, 0, -0.4]).clavicle_raise_rad["right"][0] == 0.0
    assert _motion([0, 0.4, 0], [0, 0, 0]).clavicle_forward_rad["right"][0] > 0


def test_twist_is_spread_mostly_over_the_thoracic_spine():
    motion = _motion([0, 0.5, 0], [0, 0, 0])
    angles = motion.spine_angles(PARAMS)
    twist = [angles[j][0, 2] for j in ("spine_lower", "spine_middle", "spine_upper")]
    assert twist[0] < twist[1] < twist[2]
    assert sum(twist) == pytest.approx(motion.twist_rad[0])


def test_the_seed_formula_is_the_printed_bend():
    assert SEED.formula == "seed"  # the default: seed 003 as printed (issue 53)
    c0 = np.radians(SEED.bend_deg)
    for v in ([0.1, 0.2, -0.3], [0.3, 0.1, 0.0], [-0.2, 0.05, 0.4], [0.6, 0.3, 0.1]):
        reach = np.asarray(v)
        expected = c0 * smoothstep(np.linalg.norm(reach) / SEED.arm_length_m)
        motion = _motion(reach, reach, SEED)
        assert motion.bend_rad[0] == pytest.approx(expected)
        axis = np.cross([0, 0, 1], reach)
        assert np.allclose(motion.bend_axis[0], axis / np.linalg.norm(axis))
    # Hands resting in front of the chest already bend the torso (what the variant avoids).
    resting = _motion([0.05, 0.2, -0.3], [-0.05, 0.2, -0.3], SEED).bend_rad[0]
    assert resting > 0.5 * c0
    assert _motion([0.05, 0.2, -0.3], [-0.05, 0.2, -0.3]).bend_rad[0] == 0.0


def test_the_seeds_printed_twist_turns_one_way_only():
    c1 = np.radians(SEED.twist_deg)
    v_right, v_left = np.array([0.0, 0.4, 0.0]), np.array([0.0, 0.1, 0.0])
    x = np.dot(SEED.twist_weights, [v_right[0] + v_left[0], v_right[1] - v_left[1]])
    expected = c1 * smoothstep(x / (2 * SEED.arm_length_m))
    assert expected > 0
    assert _motion(v_right, v_left, SEED).twist_rad[0] == pytest.approx(expected)
    # The mirror image would twist the other way; the printed smoothstep clamps it to 0.
    assert _motion(v_left, v_right, SEED).twist_rad[0] == 0.0
    assert _motion(v_left, v_right).twist_rad[0] < 0


def test_parameters_are_checked():
    with pytest.raises(ValueError, match="bend_split must sum to 1"):
        SpineParams(bend_split=(0.5, 0.5, 0.5))
    with pytest.raises(ValueError, match="comfort_m"):
        SpineParams(comfort_m=0.9)
    with pytest.raises(ValueError, match="formula must be one of"):
        SpineParams(formula="curvy")


def test_a_study_sets_c0_to_c3_and_v_w_per_condition():
    """Spec 03: the tuning constants are parameters editable per study. With V_w = 0 the
    torso never twists; with c0 = 0 it never bends."""
    from synthesis.techniques import ClipRequest, build_motion

    def automated(parameters):
        build = build_motion(ClipRequest("sentence", "ME BLUE", parameters))
        sentence = build.result
        names = sentence.body.dof_names
        return {
            angle: np.abs(
                sentence.automated_rad[
                    :,
                    [
                        names.index(f"{j}_{angle}")
                        for j in ("spine_lower", "spine_middle", "spine_upper")
                    ],
                ]
            ).max()
            for angle in ("flexion", "side_bend", "rotation")
        }

    default = automated({})
    assert default["rotation"] > 0.01 and max(default["flexion"], default["side_bend"]) > 0.01
    still = automated({"spine_twist_weight_x": 0.0, "spine_twist_weight_y": 0.0})
    assert still["rotation"] == 0.0 and still["flexion"] == default["flexion"]
    upright = automated({"spine_bend_deg": 0.0})
    assert upright["flexion"] == upright["side_bend"] == 0.0
    assert upright["rotation"] == default["rotation"]
