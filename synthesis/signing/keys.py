"""Solve a sentence's key postures: the keyed trunk, seed 003's automated spine and
clavicles from the hand targets, then the arms by analytic IK (synthesis.rigs.ik).

Hand keys are written in seed 003's torso frame (x right, y forward, z up, metres from
the sternal notch); a key placed on the head or chest (``HandKey.body``) goes with that
part where the automated spine moves it.
"""

from dataclasses import dataclass

import numpy as np

from synthesis.rigs.body import BodyModel
from synthesis.rigs.face import gaze_degrees
from synthesis.rigs.ik import hand_frame, solve_arm_turning
from synthesis.signing.signs import BODY_PARTS
from synthesis.signing.spine import SpineParams, spine_motion

SPINE_JOINTS = ("spine_lower", "spine_middle", "spine_upper")
# Body parts whose keys turn with them (a hand at the face tilts as the head does).
TURNING_PARTS = ("head",)
# The eyes turn this share of a keyed head turn or nod, ahead of the head (gaze leads).
GAZE_SHARE = 0.5
# Seed 003's torso frame (x right, y forward, z up) in the engine's world (x to the
# viewer's right = the signer's left, y up, z toward the viewer).
TORSO_TO_WORLD = np.array([[-1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]])


@dataclass
class Key:
    """One key posture of a sentence at *ms*: both hands (``HandKey``), keyed spine and
    head angles (degrees)."""

    ms: float
    hands: dict
    spine_deg: dict
    head_deg: dict


class KeySolver:
    """Key postures → body DOFs, and the automated spine motion for them."""

    def __init__(self, body: BodyModel, params: SpineParams):
        self.body, self.params = body, params
        pose = body.pose(body.neutral()).positions_m[0]
        index = body.skeleton.index
        self.origin = (pose[index("right_clavicle")] + pose[index("left_clavicle")]) / 2
        self.shoulders = {
            side: TORSO_TO_WORLD.T @ (pose[index(f"{side}_shoulder")] - self.origin)
            for side in ("right", "left")
        }
        self.names = body.dof_names
        wrist, tip = index("right_wrist"), index("right_middle_tip")
        self.hand_length_m = float(np.linalg.norm(pose[tip] - pose[wrist]))

    def world(self, torso_m: np.ndarray) -> np.ndarray:
        return self.origin + TORSO_TO_WORLD @ torso_m

    def trunk(self, spine_deg: dict, head_deg: dict) -> np.ndarray:
        """Return the keyed trunk pose: spine angles split over the spine joints."""
        dofs = self.body.neutral()
        p = self.params
        for name, value in spine_deg.items():
            split = p.twist_split if name == "rotation" else p.bend_split
            for joint, weight in zip(SPINE_JOINTS, split, strict=True):
                dofs[self.names.index(f"{joint}_{name}")] += np.radians(value) * weight
        for name, value in head_deg.items():
            dofs[self.names.index(f"head_{name}")] += np.radians(value)
        gaze = gaze_degrees(
            GAZE_SHARE * head_deg.get("rotation", 0.0), GAZE_SHARE * head_deg.get("flexion", 0.0)
        )
        for name, value in gaze.items():
            dofs[self.names.index(name)] += np.radians(value)
        return dofs

    def keys(self, keys: list[Key], automated: np.ndarray, lead=None) -> np.ndarray:
        """Return the body DOFs (n_keys, n_dofs) of the keys: the keyed trunk plus the
        *automated* spine and clavicle DOFs, then the arms by IK from there.

        *lead*, when the trunk leads the arms (the stagger), maps key DOFs to the trunk
        as it stands at the keys' times; the arms reach their targets from that trunk.
        """
        lead = lead or (lambda dofs: dofs)
        trunk = self.trunks(keys)
        dofs = trunk + automated
        posed = lead(dofs)
        solved = posed
        placed = self.placed(keys, lead(trunk), posed)
        for side, (targets, palms, fingers) in placed.items():
            hands = [k.hands[side] for k in keys]
            rotations = np.stack([hand_frame(p, f) for p, f in zip(palms, fingers, strict=True)])
            swivels = np.array([h.swivel_rad for h in hands])
            solved = solve_arm_turning(self.body, solved, side, targets, rotations, swivels)
            solved = self.body.with_hand(
                solved, side, np.stack([h.shape_rad for h in hands]), digits_only=True
            )
        return dofs + (solved - posed)

    def trunks(self, keys: list[Key]) -> np.ndarray:
        """Return the keys' keyed trunk poses (n_keys, n_dofs)."""
        return np.stack([self.trunk(k.spine_deg, k.head_deg) for k in keys])

    def placed(self, keys: list[Key], before: np.ndarray, after: np.ndarray) -> dict:
        """Return per side the hand's wrist targets and palm and finger directions, each
        (n_keys, 3), world frame, on the trunk *after* (DOFs), the keys being written for
        the trunk *before* (without the automated spine).

        A hand key placed at a body part (``HandKey.body``) goes where the automated
        spine takes the part: the hand moves as the point of the part nearest it does
        (the point of the wrist-to-fingertip line closest to the part's joint); a hand at
        the head turns with it too (``TURNING_PARTS``), one at the chest keeps its turn
        (the body's turn, up to 12°, would take the wrist past its limits there), so a
        sign made on the chest or the face keeps its contact. Keys in the signing space
        stay where the sign puts them, in both spine conditions.
        """
        carried = self._carried(before, after)
        out = {}
        for side in ("right", "left"):
            hands = [k.hands[side] for k in keys]
            turns, moves, joints = (
                np.stack([carried[h.body][part][k] for k, h in enumerate(hands)])
                for part in range(3)
            )
            places = np.stack([self.world(h.at_m) for h in hands])
            palms = np.stack([TORSO_TO_WORLD @ h.palm for h in hands])
            fingers = np.stack([TORSO_TO_WORLD @ h.fingers for h in hands])
            along = np.einsum("ij,ij->i", joints - places, fingers)
            near = places + np.clip(along, 0.0, self.hand_length_m)[:, None] * fingers
            shift = (turns @ near[..., None])[..., 0] + moves - near
            turned = np.array([h.body in TURNING_PARTS for h in hands])[:, None]
            palms = np.where(turned, (turns @ palms[..., None])[..., 0], palms)
            fingers = np.where(turned, (turns @ fingers[..., None])[..., 0], fingers)
            out[side] = (places + shift, palms, fingers)
        return out

    def _carried(self, before: np.ndarray, after: np.ndarray) -> dict:
        """Return per body part (``BODY_PARTS``, and "" for the signing space) the rigid
        motion that takes the part from its pose in *before* to its pose in *after*
        (DOFs, n × n_dofs): rotation (n, 3, 3), translation (n, 3) and the part's joint
        before (n, 3), world frame."""
        n = len(before)
        still = (np.broadcast_to(np.eye(3), (n, 3, 3)), np.zeros((n, 3)), np.zeros((n, 3)))
        if np.array_equal(before, after):
            # No automated motion (spine off): nothing moves, no need to pose the body.
            return {"": still, **dict.fromkeys(BODY_PARTS, still)}
        pose_before, pose_after = self.body.pose(before), self.body.pose(after)
        carried = {"": still}
        for part, joint in BODY_PARTS.items():
            j = self.body.skeleton.index(joint)
            turn = pose_after.rotations[:, j] @ np.swapaxes(pose_before.rotations[:, j], 1, 2)
            start, end = pose_before.positions_m[:, j], pose_after.positions_m[:, j]
            carried[part] = (turn, end - (turn @ start[..., None])[..., 0], start)
        return carried

    def automated(self, keys: list[Key]) -> np.ndarray:
        """Return the automated spine and clavicle DOFs (n_keys, n_dofs) from the targets."""
        right = np.stack([k.hands["right"].at_m for k in keys])
        left = np.stack([k.hands["left"].at_m for k in keys])
        motion = spine_motion(
            right, left, self.shoulders["right"], self.shoulders["left"], self.params
        )
        out = np.zeros((len(keys), len(self.names)))
        for joint, angles in motion.spine_angles(self.params).items():
            for column, name in enumerate(("flexion", "side_bend", "rotation")):
                out[:, self.names.index(f"{joint}_{name}")] = angles[:, column]
        for side in ("right", "left"):
            out[:, self.names.index(f"{side}_clavicle_raise")] = motion.clavicle_raise_rad[side]
            out[:, self.names.index(f"{side}_clavicle_forward")] = motion.clavicle_forward_rad[side]
        return out
