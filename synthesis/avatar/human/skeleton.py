"""MakeHuman's skeleton on a shaped base mesh, and how its bones map onto the engine's.

A MakeHuman bone's head and tail are placed from the mesh (rig.default.json): the mean of
a joint cube's vertices (CUBE), one vertex (VERTEX) or the mean of a few (MEAN), so they
follow the body's shape targets. :data:`ENGINE_JOINT` names, for every bone, the engine
joint whose rotation moves the skin it weighs (the engine's skeleton has fewer bones: the
spine's five become three, the metacarpals go with the wrist, the face's many with the
head, whose expressions are blendshapes here).
"""

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class MakeHumanSkeleton:
    """Bone names, parents, and each bone's head and tail (n, 3), metres, mesh frame."""

    names: tuple[str, ...]
    parents: dict
    heads_m: np.ndarray
    tails_m: np.ndarray

    def head(self, name: str) -> np.ndarray:
        return self.heads_m[self.names.index(name)]

    def tail(self, name: str) -> np.ndarray:
        return self.tails_m[self.names.index(name)]


def _place(rule: dict, vertices_m: np.ndarray, group) -> np.ndarray:
    strategy = rule["strategy"]
    if strategy == "CUBE":
        return vertices_m[group(rule["cube_name"])].mean(axis=0)
    if strategy == "VERTEX":
        return vertices_m[rule["vertex_index"]]
    if strategy == "MEAN":
        return vertices_m[rule["vertex_indices"]].mean(axis=0)
    raise ValueError(f"Unknown MakeHuman joint strategy {strategy!r}.")


def place_skeleton(rig: dict, vertices_m: np.ndarray, group) -> MakeHumanSkeleton:
    """Return the skeleton of MakeHuman's *rig* placed on shaped *vertices_m*.

    *group(name)* returns a vertex group's indices (the joint cubes).
    """
    names = tuple(sorted(rig))
    heads = np.array([_place(rig[n]["head"], vertices_m, group) for n in names])
    tails = np.array([_place(rig[n]["tail"], vertices_m, group) for n in names])
    return MakeHumanSkeleton(names, {n: rig[n]["parent"] for n in names}, heads, tails)


_FINGERS = {2: "index", 3: "middle", 4: "ring", 5: "pinky"}
_THUMB = {1: "thumb_cmc", 2: "thumb_mcp", 3: "thumb_ip"}
_PHALANGES = {1: "mcp", 2: "pip", 3: "dip"}
_TRUNK = {
    "root": "hips",
    "spine05": "hips",
    "spine04": "spine_lower",
    "spine03": "spine_lower",
    "spine02": "spine_middle",
    "spine01": "spine_upper",
    "neck01": "neck",
    "neck02": "neck",
    "neck03": "neck",
}
_SIDED = {
    "clavicle": "clavicle",
    "shoulder01": "clavicle",
    "breast": "@spine_upper",
    "upperarm01": "shoulder",
    "upperarm02": "shoulder",
    "lowerarm01": "elbow",
    "lowerarm02": "forearm",
    "wrist": "wrist",
    "eye": "eye",
}
SIDE_SUFFIX = {"right": ".R", "left": ".L"}


def engine_joint(bone: str) -> str:
    """Return the engine joint that carries the skin MakeHuman's *bone* weighs."""
    if bone in _TRUNK:
        return _TRUNK[bone]
    base, dot, suffix = bone.partition(".")
    side = {"R": "right_", "L": "left_"}.get(suffix, "")
    if dot and side:
        if base in _SIDED:
            joint = _SIDED[base]
            return joint[1:] if joint.startswith("@") else side + joint
        if base.startswith("metacarpal"):
            return side + "wrist"
        if base.startswith("finger"):
            digit, _, phalanx = base[len("finger") :].partition("-")
            if digit == "1":
                return side + _THUMB[int(phalanx)]
            return side + f"{_FINGERS[int(digit)]}_{_PHALANGES[int(phalanx)]}"
        if base.startswith(("pelvis", "upperleg", "lowerleg", "foot", "toe")):
            return "hips"
    # The face's bones, the jaw and the tongue: their expressions are blendshapes.
    return "head"
