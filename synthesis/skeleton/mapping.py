"""Joint-name mapping: recognise third-party skeletons and name their joints our way.

Motion capture arrives from Vicon Blade, Xsens MVN, Rokoko, Mixamo, Blender and the CMU
database's BVH conversions, each with
its own joint names (spec 01 "Motion data"). A table maps each convention's names to the
engine's canonical names: the upper-body model's (``spine_lower``, ``right_shoulder``,
``right_index_pip``…), which for one hand alone drop the side (``index_pip``). Names are
compared without case, separators or a namespace prefix (``mixamorig:``), so
``RightHandIndex1``, ``right_hand_index_1`` and ``mixamorig:RightHandIndex1`` all match.
"""

import re
from collections.abc import Collection
from dataclasses import dataclass

from synthesis.skeleton.skeleton import Skeleton

_DIGITS_FINGERS = ("index", "middle", "ring", "pinky")
_FINGER_JOINTS = ("mcp", "pip", "dip", "tip")
_THUMB_JOINTS = ("cmc", "mcp", "ip", "tip")


def _side_names(side: str, cap: str, short: str) -> dict[str, dict[str, str]]:
    """Return, per convention, the name of each canonical joint of one side."""
    s = side + "_"
    tables: dict[str, dict[str, str]] = {
        # Autodesk HumanIK naming, shared by Mixamo, Rokoko and Vicon Blade exports.
        "humanik": {
            s + "clavicle": f"{cap}Shoulder",
            s + "shoulder": f"{cap}Arm",
            s + "elbow": f"{cap}ForeArm",
            s + "wrist": f"{cap}Hand",
        },
        "xsens": {
            s + "clavicle": f"{cap}Shoulder",
            s + "shoulder": f"{cap}UpperArm",
            s + "elbow": f"{cap}ForeArm",
            s + "wrist": f"{cap}Hand",
        },
        "blender": {
            s + "clavicle": f"shoulder.{short}",
            s + "shoulder": f"upper_arm.{short}",
            s + "elbow": f"forearm.{short}",
            s + "wrist": f"hand.{short}",
        },
    }
    digit_names = {
        "humanik": {
            "thumb": "Thumb",
            "index": "Index",
            "middle": "Middle",
            "ring": "Ring",
            "pinky": "Pinky",
        },
        "xsens": {
            "thumb": "First",
            "index": "Second",
            "middle": "Third",
            "ring": "Fourth",
            "pinky": "Fifth",
        },
        "blender": {
            "thumb": "thumb",
            "index": "f_index",
            "middle": "f_middle",
            "ring": "f_ring",
            "pinky": "f_pinky",
        },
    }
    xsens_segments = {"thumb": ("CMC", "MCP", "IP", "Tip"), "finger": ("MCP", "PIP", "DIP", "Tip")}
    for digit in ("thumb", *_DIGITS_FINGERS):
        joints = _THUMB_JOINTS if digit == "thumb" else _FINGER_JOINTS
        for k, joint in enumerate(joints):
            canonical = f"{s}{digit}_{joint}"
            # HumanIK numbers a digit's joints 1–4 from the hand (4 is the end site).
            tables["humanik"][canonical] = f"{cap}Hand{digit_names['humanik'][digit]}{k + 1}"
            segment = xsens_segments["thumb" if digit == "thumb" else "finger"][k]
            tables["xsens"][canonical] = f"{cap}{digit_names['xsens'][digit]}{segment}"
            if k < 3:
                tables["blender"][canonical] = f"{digit_names['blender'][digit]}.0{k + 1}.{short}"
    return tables


def _tables() -> dict[str, dict[str, str]]:
    trunk = {
        "humanik": {
            "hips": "Hips",
            "spine_lower": "Spine",
            "spine_middle": "Spine1",
            "spine_upper": "Spine2",
            "neck": "Neck",
            "head": "Head",
        },
        "xsens": {
            "hips": "Pelvis",
            "spine_lower": "L3",
            "spine_middle": "T12",
            "spine_upper": "T8",
            "neck": "Neck",
            "head": "Head",
        },
        "blender": {
            "hips": "spine",
            "spine_lower": "spine.001",
            "spine_middle": "spine.002",
            "spine_upper": "spine.003",
            "neck": "spine.004",
            "head": "spine.006",
        },
    }
    for side, cap, short in (("right", "Right", "R"), ("left", "Left", "L")):
        for convention, names in _side_names(side, cap, short).items():
            trunk[convention].update(names)
    # The CMU database's ASF/AMC converted to BVH: HumanIK's arms, but a spine of
    # LowerBack, Spine, Spine1 and a neck of Neck (on Spine1, zero length) and Neck1.
    trunk["cmu"] = {
        "hips": "Hips",
        "spine_lower": "LowerBack",
        "spine_middle": "Spine",
        "spine_upper": "Spine1",
        "neck": "Neck1",
        "head": "Head",
        **{
            k: v
            for k, v in trunk["humanik"].items()
            if k.endswith(("clavicle", "shoulder", "elbow", "wrist"))
        },
    }
    # Biovision's and MotionBuilder's classic BVH names (Boxing_Toes.bvh in Debian's
    # assimp-testmodels): Ab and Chest for the spine, a Collar for the clavicle, and a
    # Shoulder that is the upper arm's joint (issue 54: only 9 joints matched, no spine).
    trunk["biovision"] = {
        "hips": "Hips",
        "spine_lower": "Ab",
        "spine_upper": "Chest",
        "neck": "Neck",
        "head": "Head",
        **{
            f"{side}_{joint}": f"{cap}{theirs}"
            for side, cap in (("right", "Right"), ("left", "Left"))
            for joint, theirs in (
                ("clavicle", "Collar"),
                ("shoulder", "Shoulder"),
                ("elbow", "Elbow"),
                ("wrist", "Wrist"),
            )
        },
    }
    # Our own BVH files use the canonical names themselves; a hand alone drops the side.
    trunk["signstudy"] = {name: name for name in trunk["humanik"]}
    trunk["signstudy-hand"] = {
        name.removeprefix("right_"): name.removeprefix("right_")
        for name in trunk["humanik"]
        if name.startswith("right_") and not name.endswith(("clavicle", "shoulder", "elbow"))
    }
    return trunk


JOINT_NAME_TABLES: dict[str, dict[str, str]] = _tables()


def normalise(name: str) -> str:
    """Return a joint name without namespace, case or separators, for matching."""
    name = name.rsplit(":", 1)[-1]
    return re.sub(r"[\s_.\-]", "", name).lower()


@dataclass(frozen=True)
class JointMapping:
    """Which convention a skeleton follows and its joint → canonical-name pairs."""

    convention: str
    to_canonical: dict[str, str]

    @property
    def is_single_hand(self) -> bool:
        """Return True when the skeleton is one hand (no trunk, one side)."""
        return not any(
            c.startswith(("hips", "spine", "neck", "head")) for c in self.to_canonical.values()
        )

    def unmapped_parts(self) -> list[str]:
        """Return a body's parts none of whose joints is mapped (the spine, an arm, a
        hand's fingers): retargeted, they stay at rest. A hand alone has only its fingers."""
        mapped = set(self.to_canonical.values())
        digits = ("thumb", *_DIGITS_FINGERS)

        def has(prefixes: tuple[str, ...]) -> bool:
            return any(name.startswith(prefixes) for name in mapped)

        if self.is_single_hand:
            return [] if has(digits) else ["fingers"]
        missing = [] if has(("spine",)) else ["spine"]
        for side in ("left", "right"):
            if not {f"{side}_{joint}" for joint in ("shoulder", "elbow", "wrist")} & mapped:
                missing.append(f"{side} arm")
            if not has(tuple(f"{side}_{digit}" for digit in digits)):
                missing.append(f"{side} hand's fingers")
        return missing

    def at_rest_warning(self, source: str, parts: Collection[str] | None = None) -> str | None:
        """Return the warning naming what this mapping leaves at rest in *source*'s motion
        (of *parts* only, if given), or None when nothing is."""
        unmapped = [p for p in self.unmapped_parts() if parts is None or p in parts]
        if not unmapped:
            return None
        return f"{source}: not mapped, so at rest: {', '.join(unmapped)}"

    def side(self) -> str | None:
        """Return the only side this mapping covers, or None for both or neither."""
        sides = {c.split("_", 1)[0] for c in self.to_canonical.values()} & {"right", "left"}
        return sides.pop() if len(sides) == 1 else None


def _tip_of(canonical: str) -> str | None:
    """Return the fingertip beyond a finger's last joint (``index_dip`` → ``index_tip``)."""
    if canonical.endswith(("_dip", "thumb_ip")):
        return canonical[: canonical.rindex("_") + 1] + "tip"
    return None


def _with_fingertips(skeleton: Skeleton, matched: dict[str, str]) -> dict[str, str]:
    """Return *matched* with unnamed fingertips added: a BVH End Site after a finger's last
    joint is its tip, whatever the site is called (the format gives End Sites no name)."""
    result = dict(matched)
    taken = set(matched.values())
    for joint in skeleton.joints:
        parent = skeleton.joints[joint.parent].name if joint.parent >= 0 else None
        tip = _tip_of(matched.get(parent, "")) if parent else None
        if joint.is_end_site and joint.name not in result and tip and tip not in taken:
            result[joint.name] = tip
            taken.add(tip)
    return result


def detect_mapping(skeleton: Skeleton, minimum: int = 4) -> JointMapping:
    """Return the convention whose names match most of *skeleton*'s joints.

    Raises ValueError naming the best candidates when fewer than *minimum* joints match,
    so that a wrong file fails loudly instead of animating nothing.
    """
    ours = {normalise(name): name for name in skeleton.names}
    scores = []
    for convention, table in JOINT_NAME_TABLES.items():
        matched = {
            ours[normalise(theirs)]: canonical
            for canonical, theirs in table.items()
            if normalise(theirs) in ours
        }
        scores.append((len(matched), convention, matched))
    scores.sort(key=lambda s: -s[0])
    count, convention, matched = scores[0]
    matched = _with_fingertips(skeleton, matched)
    if count < minimum:
        sample = ", ".join(skeleton.names[:6])
        raise ValueError(
            f"Cannot map this skeleton's joints ({sample}, …) onto the hand or body model: "
            f"at most {count} names match a known convention "
            f"({', '.join(sorted(JOINT_NAME_TABLES))})."
        )
    return JointMapping(convention, matched)
