"""A skeleton: a tree of joints with rest offsets and channel lists (the BVH model).

Joints are stored parents-first (every joint's parent comes before it), as BVH lists
them. BVH "End Site" entries are kept as joints without channels (``is_end_site``) so
that files round-trip; they carry no rotation of their own.
"""

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

POSITION_CHANNELS = ("Xposition", "Yposition", "Zposition")
ROTATION_CHANNELS = ("Xrotation", "Yrotation", "Zrotation")
CHANNEL_NAMES = POSITION_CHANNELS + ROTATION_CHANNELS
# Metres per file unit.
LENGTH_UNITS = {"m": 1.0, "cm": 0.01, "mm": 0.001, "in": 0.0254}


@dataclass(frozen=True)
class Joint:
    """One joint: its name, parent index (-1 for a root), rest offset and channels.

    ``offset`` is relative to the parent, in the skeleton's length unit.
    """

    name: str
    parent: int
    offset: tuple[float, float, float]
    channels: tuple[str, ...] = ()
    is_end_site: bool = False

    @property
    def rotation_order(self) -> str:
        """Return the Euler order of this joint's rotation channels, e.g. "ZXY" ("" if none)."""
        return "".join(c[0] for c in self.channels if c in ROTATION_CHANNELS)


@dataclass(frozen=True)
class Skeleton:
    """A tree of joints, parents first, with the length unit of its offsets."""

    joints: tuple[Joint, ...]
    length_unit: str = "cm"
    _index: dict[str, int] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        if self.length_unit not in LENGTH_UNITS:
            raise ValueError(
                f"Unknown length unit {self.length_unit!r}; use one of {list(LENGTH_UNITS)}."
            )
        index: dict[str, int] = {}
        for number, joint in enumerate(self.joints):
            if joint.parent >= number or joint.parent < -1:
                raise ValueError(f"Joint {joint.name!r} must come after its parent.")
            if number == 0 and joint.parent != -1:
                raise ValueError("The first joint must be a root.")
            for channel in joint.channels:
                if channel not in CHANNEL_NAMES:
                    raise ValueError(f"Joint {joint.name!r}: unknown channel {channel!r}.")
            if joint.is_end_site and joint.channels:
                raise ValueError(f"End site {joint.name!r} cannot have channels.")
            if joint.name in index:
                raise ValueError(f"Two joints are named {joint.name!r}.")
            index[joint.name] = number
        object.__setattr__(self, "_index", index)

    def __len__(self) -> int:
        return len(self.joints)

    @property
    def names(self) -> list[str]:
        """Return the joint names in order."""
        return [joint.name for joint in self.joints]

    @property
    def parents(self) -> np.ndarray:
        """Return each joint's parent index, shape (n_joints,), −1 for roots."""
        return np.array([joint.parent for joint in self.joints], dtype=np.intp)

    @property
    def offsets(self) -> np.ndarray:
        """Return rest offsets relative to the parent, shape (n_joints, 3), in file units."""
        return np.array([joint.offset for joint in self.joints], dtype=np.float64).reshape(-1, 3)

    @property
    def metres_per_unit(self) -> float:
        """Return the length of one offset unit in metres."""
        return LENGTH_UNITS[self.length_unit]

    @property
    def channel_count(self) -> int:
        """Return the number of motion channels of all joints together."""
        return sum(len(joint.channels) for joint in self.joints)

    def channel_slices(self) -> list[slice]:
        """Return, per joint, the slice of its channels in a frame's values."""
        slices, start = [], 0
        for joint in self.joints:
            slices.append(slice(start, start + len(joint.channels)))
            start += len(joint.channels)
        return slices

    @cached_property
    def rotation_groups(self) -> dict[str, tuple[np.ndarray, np.ndarray]]:
        """Return, per Euler order, the joints with rotation channels and their value columns.

        Columns are grouped per joint (len(order) each), in joint order; cached because
        kinematics and sampling use it on every call.
        """
        groups: dict[str, tuple[list[int], list[int]]] = {}
        for number, (joint, where) in enumerate(
            zip(self.joints, self.channel_slices(), strict=True)
        ):
            columns = [
                where.start + k for k, c in enumerate(joint.channels) if c in ROTATION_CHANNELS
            ]
            if columns:
                joints, cols = groups.setdefault(joint.rotation_order, ([], []))
                joints.append(number)
                cols.extend(columns)
        return {
            order: (np.array(joints, dtype=np.intp), np.array(cols, dtype=np.intp))
            for order, (joints, cols) in groups.items()
        }

    def index(self, name: str) -> int:
        """Return the index of the joint called *name* (KeyError naming it if absent)."""
        try:
            return self._index[name]
        except KeyError:
            raise KeyError(f"No joint named {name!r} in this skeleton.") from None

    def children(self, index: int) -> list[int]:
        """Return the indices of the joint's children."""
        return [number for number, joint in enumerate(self.joints) if joint.parent == index]

    def depth_levels(self) -> list[np.ndarray]:
        """Return joint indices grouped by depth (roots first), for batched kinematics."""
        depth = np.zeros(len(self.joints), dtype=np.intp)
        for number, joint in enumerate(self.joints):
            depth[number] = 0 if joint.parent < 0 else depth[joint.parent] + 1
        return [np.flatnonzero(depth == level) for level in range(int(depth.max()) + 1)]


def guess_length_unit(offsets: np.ndarray, parents: np.ndarray) -> str:
    """Guess a skeleton's unit from its size: a hand or body is 0.1–2.5 m tall.

    The longest root-to-leaf chain decides: ≤ 3 → metres, ≤ 300 → centimetres,
    else millimetres (a whole body in cm is ~100–190, a hand ~15–25).
    """
    reach = np.zeros(len(parents))
    for number, parent in enumerate(parents):
        length = float(np.linalg.norm(offsets[number]))
        reach[number] = length if parent < 0 else reach[parent] + length
    longest = float(reach.max()) if len(reach) else 0.0
    if longest <= 3.0:
        return "m"
    if longest <= 300.0:
        return "cm"
    return "mm"
