"""Models driven by named DOFs: the hand, the upper body, postures, arm IK, landmarks,
finger collisions, and retargeting recorded motion onto them."""

from synthesis.rigs.body import BodyModel
from synthesis.rigs.hand import HandModel
from synthesis.rigs.retarget import retarget
from synthesis.rigs.rig import Rig

__all__ = ["BodyModel", "HandModel", "Rig", "retarget"]
