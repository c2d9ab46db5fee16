"""The ASL manual alphabet: handshapes from the project's data file, with contacts enforced.

``synthesis/data/asl_alphabet.yaml`` gives each letter's joint angles (degrees) and the
contacts that define it (D: thumb tip on the middle fingertip; F: thumb and index tips;
…). Authored angles are a starting point; a bounded least-squares solve then moves the
listed DOFs, as little as possible and within their limits, until every contact holds
(points at the stated distance, which accounts for the fingers' thickness: landmarks
sit on the bones' axes). J and Z are motion paths: a sequence of keyed poses. A
two-handed alphabet's letter is a handshape for each hand and where they touch
(:func:`two_handed_letter`).
"""

from dataclasses import dataclass
from functools import cache

import numpy as np
from scipy.optimize import least_squares

from synthesis.diskcache import cached
from synthesis.fingerspelling.alphabets import (
    DEFAULT_ALPHABET,
    AlphabetError,
    letter_entry,
    manual_alphabet,
)
from synthesis.rigs.hand import FINGERS, HandModel
from synthesis.skeleton.rotations import quat_rotate

# The libraries whose versions a solved letter depends on (synthesis.diskcache).
SOLVER_LIBRARIES = ("numpy", "scipy")

# The ASL alphabet's letters: the routes table and the shaping tools are made for them.
LETTERS = tuple("ABCDEFGHIJKLMNOPQRSTUVWXYZ")
# Shorthand groups of the data file → DOF names.
_FINGER_KEYS = ("mcp_flexion", "pip_flexion", "dip_flexion")
_THUMB_KEYS = ("cmc_abduction", "cmc_rotation", "cmc_flexion", "mcp_flexion", "ip_flexion")


@dataclass(frozen=True)
class Contact:
    """Two hand points that touch: each a joint, or a blend between two joints."""

    a: tuple[tuple[str, float], ...]
    b: tuple[tuple[str, float], ...]
    distance_m: float
    adjust: tuple[str, ...]
    # Shift of point b in the wrist's frame (x thumb side, y fingers, z palm side), m:
    # makes "in front of the fingers" a position, not just a distance.
    offset_m: tuple[float, float, float] = (0.0, 0.0, 0.0)


@dataclass(frozen=True)
class Letter:
    """One letter: its pose (DOF vector, radians) and, for J and Z, a keyed path."""

    letter: str
    description: str
    dofs_rad: np.ndarray
    path_rad: np.ndarray | None = None
    path_times: np.ndarray | None = None
    contacts: tuple[Contact, ...] = ()


def _point(spec, where: str) -> tuple[tuple[str, float], ...]:
    if isinstance(spec, str):
        return ((spec, 1.0),)
    if isinstance(spec, dict) and set(spec) == {"between", "t"}:
        first, second = spec["between"]
        t = float(spec["t"])
        return ((first, 1.0 - t), (second, t))
    raise AlphabetError(f"{where}: a contact point is a joint name or {{between: [a, b], t}}.")


# A letter's angle groups that name DOFs directly: group → the DOF name for a key.
_NAMED_GROUPS = {
    "spread": "{}_mcp_abduction",
    "twist": "{}_mcp_twist",
    "wrist": "wrist_{}",
    "forearm": "forearm_{}",
}


def _grouped_degrees(entry: dict, where: str) -> dict[str, float]:
    """Return a letter's angles (degrees) by DOF name from its groups (fingers, thumb…)."""
    degrees: dict[str, float] = {}
    for finger, values in (entry.get("fingers") or {}).items():
        if finger not in FINGERS or len(values) != 3:
            raise AlphabetError(f"{where}: fingers.{finger} must be [mcp, pip, dip] of a finger.")
        degrees.update({f"{finger}_{key}": v for key, v in zip(_FINGER_KEYS, values, strict=True)})
    for key, value in (entry.get("thumb") or {}).items():
        if key not in _THUMB_KEYS:
            raise AlphabetError(f"{where}: unknown thumb angle {key!r}.")
        degrees[f"thumb_{key}"] = value
    for group, name in _NAMED_GROUPS.items():
        for key, value in (entry.get(group) or {}).items():
            degrees[name.format(key)] = value
    return degrees


def _angles(entry: dict, model: HandModel, where: str) -> np.ndarray:
    """Turn a letter's grouped angles (degrees) into a DOF vector (radians)."""
    degrees = _grouped_degrees(entry, where)
    try:
        dofs = model.from_degrees(degrees)
    except KeyError as error:
        raise AlphabetError(f"{where}: {error.args[0]}") from None
    low, high = model.limits_rad
    outside = [
        model.dof_names[i] for i in np.flatnonzero((dofs < low - 1e-9) | (dofs > high + 1e-9))
    ]
    if outside:
        raise AlphabetError(f"{where}: outside the joint limits: {', '.join(outside)}.")
    return dofs


def _contact_points(model: HandModel, pose, contact: Contact):
    """Return the two contact points' world positions in *pose* (b shifted by the offset)."""
    positions = pose.positions_m[0]
    a = sum(weight * positions[model.skeleton.index(name)] for name, weight in contact.a)
    b = sum(weight * positions[model.skeleton.index(name)] for name, weight in contact.b)
    if any(contact.offset_m):
        wrist = pose.quaternions[0, model.skeleton.index("wrist")]
        # Offsets are authored for the right hand: reflect them for a left hand.
        b = b + quat_rotate(wrist, model.mirror @ np.asarray(contact.offset_m))
    return a, b


def solve_contacts(model: HandModel, dofs_rad: np.ndarray, contacts) -> np.ndarray:
    """Move the contacts' adjustable DOFs, minimally and within limits, until they touch."""
    if not contacts:
        return dofs_rad
    free = sorted(
        {
            i
            for contact in contacts
            for group in contact.adjust
            for i, name in enumerate(model.dof_names)
            if name.startswith(f"{group}_") or name == group
        }
    )
    low, high = model.limits_rad
    start = np.clip(dofs_rad[free], low[free] + 1e-9, high[free] - 1e-9)

    def residuals(values: np.ndarray) -> np.ndarray:
        dofs = dofs_rad.copy()
        dofs[free] = values
        pose = model.pose(dofs)  # once per evaluation, shared by all contacts
        gaps = np.concatenate([_residual_m(model, pose, c) / 0.001 for c in contacts])
        # 1 mm of contact error weighs like 19° away from the authored pose: contacts
        # hold, and the rest of the hand keeps the authored, natural configuration.
        return np.concatenate([gaps, 3.0 * (values - dofs_rad[free])])

    result = least_squares(residuals, start, bounds=(low[free], high[free]), xtol=1e-9)
    solved = dofs_rad.copy()
    solved[free] = result.x
    return solved


def _residual_m(model: HandModel, pose, contact: Contact) -> np.ndarray:
    """Return a smooth residual: the difference vector for a position target (distance 0,
    where ‖a − b‖ would have a kink at the solution), else ‖a − b‖ − distance."""
    a, b = _contact_points(model, pose, contact)
    if contact.distance_m == 0:
        return a - b
    return np.array([np.linalg.norm(a - b) - contact.distance_m])


def contact_gap_m(model: HandModel, dofs_rad: np.ndarray, contact: Contact) -> float:
    """Return how far a contact is from holding: distance minus the wanted distance (m)."""
    a, b = _contact_points(model, model.pose(dofs_rad), contact)
    return float(np.linalg.norm(a - b) - contact.distance_m)


def contact_gaps_m(model: HandModel, dofs_rad: np.ndarray, contacts) -> list[float]:
    """Return :func:`contact_gap_m` for each contact."""
    return [contact_gap_m(model, dofs_rad, c) for c in contacts]


def _contacts(entry: dict, model: HandModel, where: str) -> tuple[Contact, ...]:
    """Return a letter's contacts; AlphabetError names a joint the hand does not have."""
    contacts = tuple(
        Contact(
            a=_point(c["a"], where),
            b=_point(c["b"], where),
            distance_m=float(c.get("distance_mm", 0 if "offset_mm" in c else 10)) / 1000,
            adjust=tuple(c.get("adjust", ["thumb"])),
            offset_m=tuple(float(v) / 1000 for v in c.get("offset_mm", (0, 0, 0))),
        )
        for c in entry.get("contacts", [])
    )
    unknown = [
        name
        for c in contacts
        for point in (c.a, c.b)
        for name, _ in point
        if name not in model.skeleton.names
    ]
    if unknown:
        raise AlphabetError(f"{where}: unknown joint(s) {', '.join(unknown)} in contacts.")
    return contacts


def _path(entry: dict, model: HandModel, contacts, where: str, solved) -> np.ndarray:
    """Return a moving letter's path (n_keys, n_dofs): solved here, or the stored solution."""
    keys = entry["path"]
    if solved is not None:
        path = np.array(solved["path_rad"], dtype=np.float64)
        if path.shape != (len(keys), len(model.dofs)):
            raise ValueError(f"{where}: a stored path of another shape.")
        return path
    return np.stack(
        [
            solve_contacts(model, _angles({**entry, **k.get("pose", {})}, model, where), contacts)
            for k in keys
        ]
    )


def parse_letter(letter: str, entry: dict, model: HandModel, solved=None) -> Letter:
    """Build one letter from its data-file entry, solving its contacts.

    *solved* (``dofs_rad`` and, for a letter with a path, ``path_rad``) gives the
    solution found before; ValueError if it does not fit the entry.
    """
    where = f"letter {letter}"
    if not isinstance(entry, dict):
        raise AlphabetError(f"{where}: expected a mapping of angles.")
    dofs = _angles(entry, model, where)
    contacts = _contacts(entry, model, where)
    if solved is not None:
        dofs = np.array(solved["dofs_rad"], dtype=np.float64)
        if dofs.shape != (len(model.dofs),):
            raise ValueError(f"{where}: a stored solution of another shape.")
    else:
        dofs = solve_contacts(model, dofs, contacts)
    path = times = None
    if "path" in entry:
        times = np.array([float(k["t"]) for k in entry["path"]])
        path = _path(entry, model, contacts, where, solved)
        path.setflags(write=False)
    dofs.setflags(write=False)
    return Letter(letter, entry.get("description", ""), dofs, path, times, contacts)


@cache
def letter(letter: str, side: str = "right", alphabet: str = DEFAULT_ALPHABET) -> Letter:
    """Return one letter of a one-handed alphabet (solved on first use, then cached in
    memory and in the engine's disk cache, synthesis.diskcache: solving a letter's
    contacts takes a quarter of a second, and every render process solved the letters
    it spells)."""
    manual = manual_alphabet(alphabet)
    key = manual.check(letter)
    if manual.two_handed:
        raise AlphabetError(
            f"The {manual.name} manual alphabet is two-handed: each letter is two "
            "handshapes (two_handed_letter), not one."
        )
    model = HandModel(side)
    entry = letter_entry(alphabet, key)
    return cached(
        f"letter-{alphabet}-{side}-{key}",
        SOLVER_LIBRARIES,
        lambda: parse_letter(key, entry, model),
        _solution,
        lambda stored: parse_letter(key, entry, model, solved=stored),
    )


@dataclass(frozen=True)
class TwoHandedLetter:
    """A letter of a two-handed alphabet: each hand's handshape and where they touch."""

    letter: str
    description: str
    dominant: Letter
    nondominant: Letter
    # The joints that meet: (dominant hand's, nondominant hand's); none when apart.
    touch: tuple[str, str] | None = None


def _other(side: str) -> str:
    return "left" if side == "right" else "right"


@cache
def two_handed_letter(
    letter: str, side: str = "right", alphabet: str = DEFAULT_ALPHABET
) -> TwoHandedLetter:
    """Return one letter of a two-handed alphabet, *side* the dominant hand's."""
    manual = manual_alphabet(alphabet)
    key = manual.check(letter)
    if not manual.two_handed:
        raise AlphabetError(f"The {manual.name} manual alphabet is one-handed: use letter().")
    entry = letter_entry(alphabet, key)
    where = f"alphabet {alphabet}, letter {key}"
    if not isinstance(entry, dict) or not {"dominant", "nondominant"} <= set(entry):
        raise AlphabetError(f"{where}: a two-handed letter gives dominant and nondominant.")
    hands = {
        role: parse_letter(key, entry[role], HandModel(hand_side))
        for role, hand_side in (("dominant", side), ("nondominant", _other(side)))
    }
    touch = entry.get("touch")
    if touch is not None:
        model = HandModel(side)
        if not isinstance(touch, dict) or set(touch) != {"dominant", "nondominant"}:
            raise AlphabetError(f"{where}: touch names a joint of each hand.")
        unknown = [name for name in touch.values() if name not in model.skeleton.names]
        if unknown:
            raise AlphabetError(f"{where}: unknown joint(s) {', '.join(unknown)} in touch.")
        touch = (touch["dominant"], touch["nondominant"])
    return TwoHandedLetter(
        key, entry.get("description", ""), hands["dominant"], hands["nondominant"], touch
    )


def _solution(solved: Letter) -> dict[str, np.ndarray]:
    """Return a solved letter's arrays, as the disk cache keeps them."""
    if solved.path_rad is None:
        return {"dofs_rad": solved.dofs_rad}
    return {"dofs_rad": solved.dofs_rad, "path_rad": solved.path_rad}


def alphabet(side: str = "right", code: str = DEFAULT_ALPHABET) -> dict[str, Letter]:
    """Return every letter of a one-handed alphabet for a right or left hand."""
    return {key: letter(key, side, code) for key in manual_alphabet(code).letters}


def letter_pose(name: str, side: str = "right", alphabet: str = DEFAULT_ALPHABET) -> np.ndarray:
    """Return the DOF vector (radians) of one letter; AlphabetError for anything else."""
    return letter(name, side, alphabet).dofs_rad


# A relaxed, slightly open hand: where a word starts and ends.
REST_DEGREES = {
    **{f"{f}_mcp_flexion": 20.0 for f in ("index", "middle", "ring", "pinky")},
    **{f"{f}_pip_flexion": 25.0 for f in ("index", "middle", "ring", "pinky")},
    "thumb_cmc_flexion": 10.0,
    "thumb_mcp_flexion": 10.0,
}


def rest_pose(side: str = "right") -> np.ndarray:
    """Return the DOF vector (radians) of the relaxed hand between words."""
    return HandModel(side).from_degrees(REST_DEGREES)


__all__ = [
    "LETTERS",
    "REST_DEGREES",
    "AlphabetError",
    "Letter",
    "TwoHandedLetter",
    "alphabet",
    "letter",
    "letter_pose",
    "rest_pose",
    "two_handed_letter",
]
