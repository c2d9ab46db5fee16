"""Automated spine and shoulder motion from the hand targets (seed 003 §3.1–3.3, spec 03).

The torso bends toward where the hands reach, twists with their lateral and one-sided
forward reach, and the clavicles raise and come forward with the arms, so that an avatar
reaching with its arms is not a "pole with arms". Everything here works in seed 003's
torso frame: x to the signer's right, y forward, z up, metres; angles in radians.

Two readings of §3.1, chosen by ``SpineParams.formula``:

- ``"seed"`` (the default): the equations as printed. The bend is
  ``c0·smoothstep(|V_reach|/L_arm)`` about ``Z × V_reach`` (no bend only for an exactly
  vertical reach), and the twist ``c1·smoothstep(V_w·V_twist/(2 L_arm))`` is clamped at
  zero by the smoothstep, so it turns one way only. The torso leans about 11° over hands
  in front of the chest and 15° (c0 = 16°) over arms at rest; a hand the sign library
  places on the head or chest goes with it (synthesis.signing.keys).
- ``"comfort"`` (this project's variant, a named option): the paper's text says hands in
  the proximal signing space have "very little effect", which the printed bend
  contradicts. The variant bends by the reach's horizontal part beyond a comfort radius,
  ``x = (|V_xy| − r) / (L_arm − r)``, and twists both ways, ``sign(x)·smoothstep(|x|)``,
  since the text's two arms "cancel" and "amplify" each other. Every condition's
  description says which formula it uses.

Where the paper leaves a choice open, this module decides and says so:

- *Clavicle raise* follows the vertical component of the reach (spec 03 notes the
  paper's ``V.x`` misprint); raise and forward are clamped at zero as printed, so a
  hanging arm does not pull its shoulder down.
- *Spine weights* split bend and twist over the lower, middle and upper spine joints in
  proportion to regional ranges of motion after White & Panjabi, *Clinical Biomechanics
  of the Spine* (2nd ed., 1990): lateral bending is shared by the lumbar and thoracic
  spine, axial rotation is mostly thoracic (about 10° lumbar against 35° thoracic).
"""

from dataclasses import dataclass

import numpy as np

FORMULAS = ("seed", "comfort")


def smoothstep(x: np.ndarray) -> np.ndarray:
    """Return ``3x² − 2x³`` with x clamped to [0, 1] (seed 003 §3.1)."""
    x = np.clip(x, 0.0, 1.0)
    return x * x * (3.0 - 2.0 * x)


def signed_smoothstep(x: np.ndarray) -> np.ndarray:
    """Return ``sign(x) · smoothstep(|x|)``: the ease in both directions."""
    return np.sign(x) * smoothstep(np.abs(x))


@dataclass(frozen=True)
class SpineParams:
    """Tuning of the spine and shoulder extension (seed 003's c0–c3, V_w, weights).

    Angles in degrees (the study's editable numbers); the seed gives no values, so the
    defaults are this project's, chosen so that a full reach bends the torso visibly
    but well inside the spine's range.
    """

    bend_deg: float = 16.0  # c0
    twist_deg: float = 20.0  # c1
    clavicle_raise_deg: float = 12.0  # c2
    clavicle_forward_deg: float = 12.0  # c3
    twist_weights: tuple[float, float] = (-2.5, 2.5)  # V_w = (X_w, Y_w)
    # lower, middle, upper spine; each triple sums to 1
    bend_split: tuple[float, float, float] = (0.40, 0.35, 0.25)
    twist_split: tuple[float, float, float] = (0.15, 0.30, 0.55)
    arm_length_m: float = 0.55  # L_arm, shoulder to wrist at full reach
    comfort_m: float = 0.25  # r, used by the "comfort" formula only
    formula: str = "seed"  # "comfort" (the variant) or "seed" (§3.1 as printed)

    def __post_init__(self) -> None:
        for name in ("bend_split", "twist_split"):
            if abs(sum(getattr(self, name)) - 1.0) > 1e-9:
                raise ValueError(f"SpineParams.{name} must sum to 1, not {getattr(self, name)}.")
        if self.formula not in FORMULAS:
            raise ValueError(
                f"SpineParams.formula must be one of {FORMULAS}, not {self.formula!r}."
            )
        if not 0 <= self.comfort_m < self.arm_length_m:
            raise ValueError("SpineParams.comfort_m must be at least 0 and below the arm length.")


@dataclass(frozen=True)
class SpineMotion:
    """The extension's angles per frame (radians), shapes (n,) unless noted.

    *bend_rad* about the horizontal axis ``a_bend`` (n, 3) toward the reach; *twist_rad*
    about the vertical, positive turning the right shoulder forward; per side the
    clavicle's raise and forward angles.
    """

    bend_rad: np.ndarray
    bend_axis: np.ndarray
    twist_rad: np.ndarray
    clavicle_raise_rad: dict
    clavicle_forward_rad: dict

    def spine_angles(self, params: SpineParams) -> dict[str, np.ndarray]:
        """Return per spine joint its (flexion, side bend, rotation) angles (n, 3).

        The bend about ``a_bend`` becomes forward flexion (about −x) and side bend (about
        y, positive to the signer's left); small-angle Euler extraction is exact enough
        for the ≤ 15° of the extension and keeps the split across joints linear.
        """
        flexion = -self.bend_axis[:, 0] * self.bend_rad
        lean_right = self.bend_axis[:, 1] * self.bend_rad
        out = {}
        joints = ("spine_lower", "spine_middle", "spine_upper")
        splits = zip(joints, params.bend_split, params.twist_split, strict=True)
        for joint, w_bend, w_twist in splits:
            out[joint] = np.stack(
                [w_bend * flexion, -w_bend * lean_right, w_twist * self.twist_rad], axis=1
            )
        return out


def spine_motion(
    right_target_m: np.ndarray,
    left_target_m: np.ndarray,
    right_shoulder_m: np.ndarray,
    left_shoulder_m: np.ndarray,
    params: SpineParams | None = None,
) -> SpineMotion:
    """Return the automated spine and clavicle motion for hand targets (n, 3), torso frame.

    Seed 003 §3.1: ``V_R = A_R − S_R``, ``V_L = A_L − S_L``, ``V_reach = (V_R + V_L)/2``;
    ``θ_bend = c0·smoothstep(|V_reach|/L_arm)`` about ``Z × V_reach``; ``θ_twist =
    c1·smoothstep(V_w·V_twist/(2 L_arm))`` with ``V_twist = (V_R.x + V_L.x, V_R.y − V_L.y,
    0)``; §3.3: ``θ_raise = c2·smoothstep(V.z/L_arm)``, ``θ_forward =
    c3·smoothstep(V.y/L_arm)`` per side. The ``comfort`` formula's bend and twist as in
    the module's notes.
    """
    params = params or SpineParams()
    v_right = np.atleast_2d(right_target_m) - right_shoulder_m
    v_left = np.atleast_2d(left_target_m) - left_shoulder_m
    reach = (v_right + v_left) / 2.0
    length = params.arm_length_m
    bend = np.radians(params.bend_deg) * smoothstep(_bend_x(reach, params))
    # a_bend = Z × V_reach: no bend for a purely vertical reach.
    axis = np.stack([-reach[:, 1], reach[:, 0], np.zeros(len(reach))], axis=1)
    norm = np.linalg.norm(axis, axis=1, keepdims=True)
    axis = np.divide(axis, norm, out=np.zeros_like(axis), where=norm > 1e-9)
    bend = np.where(norm[:, 0] > 1e-9, bend, 0.0)
    v_twist = np.stack([v_right[:, 0] + v_left[:, 0], v_right[:, 1] - v_left[:, 1]], axis=1)
    twist_x = v_twist @ np.asarray(params.twist_weights) / (2.0 * length)
    ease = smoothstep if params.formula == "seed" else signed_smoothstep
    twist = np.radians(params.twist_deg) * ease(twist_x)
    raise_, forward = {}, {}
    for side, v in (("right", v_right), ("left", v_left)):
        raise_[side] = np.radians(params.clavicle_raise_deg) * smoothstep(v[:, 2] / length)
        forward[side] = np.radians(params.clavicle_forward_deg) * smoothstep(v[:, 1] / length)
    return SpineMotion(bend, axis, twist, raise_, forward)


def _bend_x(reach: np.ndarray, params: SpineParams) -> np.ndarray:
    """Return the bend's smoothstep argument: the printed |V_reach|/L_arm, or the
    horizontal reach beyond the comfort radius."""
    if params.formula == "seed":
        return np.linalg.norm(reach, axis=1) / params.arm_length_m
    horizontal = np.linalg.norm(reach[:, :2], axis=1)
    return (horizontal - params.comfort_m) / (params.arm_length_m - params.comfort_m)
