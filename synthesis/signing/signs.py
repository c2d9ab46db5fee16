"""A sign library: glosses as sparse key postures of both hands, with keyed spine poses.

Signs are sequences of keys (seed 003 §2, the segmental style of SLPA): where each
wrist is, which handshape, which way the palm and fingers face, how long the posture is
held (a postural segment); the moves between keys are transforming segments. The
format is ``data/signs.yaml``'s: positions and directions in the signer's torso frame
(x right, y forward, z up) from the sternal notch, metres.
"""

import itertools
from dataclasses import dataclass, field
from functools import cache
from importlib import resources
from pathlib import Path

import numpy as np
import yaml

from synthesis.fingerspelling.alphabet import AlphabetError, letter, rest_pose
from synthesis.formats import check_header
from synthesis.rigs.hand import HandModel
from synthesis.signing.nonmanual import NonmanualError, parse_markers

FORMAT = "signstudy.sign-library"
FORMAT_VERSION = 1
DIRECTIONS = {
    "forward": (0.0, 1.0, 0.0),
    "back": (0.0, -1.0, 0.0),
    "up": (0.0, 0.0, 1.0),
    "down": (0.0, 0.0, -1.0),
    "right": (1.0, 0.0, 0.0),
    "left": (-1.0, 0.0, 0.0),
}
# Hand DOFs a handshape sets: the digits; the wrist and forearm follow the orientation.
_PLACEMENT = (
    "forearm_tilt_side",
    "forearm_tilt_forward",
    "forearm_twist",
    "wrist_deviation",
    "wrist_flexion",
)
KEYED_DOFS = ("flexion", "side_bend", "rotation")


class SignError(ValueError):
    """A malformed sign library or an unknown gloss."""


# Body parts a hand key can be placed on, and the joint whose motion carries it.
BODY_PARTS = {"head": "head", "chest": "spine_upper"}
# The fields of a hand key in the library.
HAND_FIELDS = ("at", "body", "shape", "palm", "fingers", "swivel_deg")


@dataclass(frozen=True)
class HandKey:
    """One hand in one key: wrist position (3,) and palm and finger directions (3,), torso
    frame; handshape DOFs (radians, right-hand model order); elbow swivel (rad).

    *body* names the body part the key is placed at (``BODY_PARTS``): the hand goes with
    the part when the automated spine moves it (synthesis.signing.keys); empty for a key
    in the signing space, which stays where it is.
    """

    at_m: np.ndarray
    palm: np.ndarray
    fingers: np.ndarray
    shape_rad: np.ndarray
    swivel_rad: float
    body: str = ""


@dataclass(frozen=True)
class SignKey:
    """A key posture at *ms* from the sign's start, held *hold_ms*; a missing hand rests."""

    ms: float
    hold_ms: float
    hands: dict
    spine_deg: dict
    head_deg: dict


@dataclass(frozen=True)
class SignLibrary:
    """Signs by gloss, with the library's shared settings; *nonmanuals* the non-manual
    signals by name (synthesis.signing.nonmanual) and *sign_nonmanuals* those a gloss
    carries itself."""

    signs: dict
    rest: dict
    spelling: dict
    transition_ms: float
    shapes: dict
    locations: dict
    nonmanuals: dict = field(default_factory=dict)
    sign_nonmanuals: dict = field(default_factory=dict)

    def sign(self, gloss: str) -> tuple[SignKey, ...]:
        """Return a sign's keys; SignError names an unknown gloss."""
        try:
            return self.signs[gloss.upper()]
        except KeyError:
            raise SignError(f"{gloss!r} is not in the sign library.") from None

    def hand(self, side: str, spec: dict, where: str) -> HandKey:
        """Return a hand key from its library entry (positions mirrored for the left)."""
        try:
            at = spec["at"]
            named = self.locations[at] if isinstance(at, str) else at
            place = named if isinstance(named, dict) else {"at": named}
            position = np.array(place["at"], dtype=float)
            if position.shape != (3,):
                raise ValueError
        except (KeyError, ValueError, TypeError):
            raise SignError(f"{where}: unknown or malformed position {spec.get('at')!r}.") from None
        body = str(spec.get("body", place.get("body", "")))
        if body and body not in BODY_PARTS:
            raise SignError(
                f"{where}: a key's body part is one of {', '.join(BODY_PARTS)}, not {body!r}."
            )
        if side == "left":
            position[0] = -position[0]
        return HandKey(
            position,
            _direction(spec.get("palm", "forward"), side, where),
            _direction(spec.get("fingers", "up"), side, where),
            self.shape(spec.get("shape", "relaxed"), where),
            np.radians(float(spec.get("swivel_deg", 20.0))),
            body,
        )

    def shape(self, name, where: str) -> np.ndarray:
        """Return a handshape's digit DOFs (right-hand model, radians)."""
        name = str(name)
        try:
            return self.shapes[name]
        except KeyError:
            raise SignError(f"{where}: unknown handshape {name!r}.") from None


def _direction(value, side: str, where: str) -> np.ndarray:
    if isinstance(value, str):
        inward = "left" if side == "right" else "right"
        named = {
            **DIRECTIONS,
            "in": DIRECTIONS[inward],
            "out": DIRECTIONS["right" if side == "right" else "left"],
        }
        if value not in named:
            raise SignError(f"{where}: unknown direction {value!r}.")
        return np.array(named[value])
    vector = np.asarray(value, dtype=float)
    if vector.shape != (3,) or not np.linalg.norm(vector) > 0:
        raise SignError(f"{where}: a direction is a name or a non-zero [x, y, z].")
    return vector / np.linalg.norm(vector)


def _shapes(entries: dict) -> dict[str, np.ndarray]:
    """Return every letter, the relaxed hand and the named handshapes as digit DOFs."""
    model = HandModel()
    keep = np.array([name not in _PLACEMENT for name in model.dof_names])
    shapes = {}
    for character in "ABCDEFGHIJKLMNOPQRSTUVWXYZ":
        shapes[character] = np.where(keep, letter(character).dofs_rad, 0.0)
    shapes["relaxed"] = np.where(keep, rest_pose(), 0.0)
    for name, entry in (entries or {}).items():
        try:
            base = shapes[entry] if isinstance(entry, str) else model.from_degrees(entry)
        except KeyError as error:
            raise SignError(f"Handshape {name!r}: {error.args[0]}") from None
        shapes[str(name)] = np.where(keep, base, 0.0)
    return shapes


def parse_library(data) -> SignLibrary:
    """Return a library from parsed YAML; SignError names what is wrong."""
    check_header(data, FORMAT, FORMAT_VERSION, "sign library", SignError)
    try:
        shapes = _shapes(data.get("handshapes"))
    except AlphabetError as error:
        raise SignError(str(error)) from None
    try:
        nonmanuals = parse_markers(data.get("nonmanuals"))
    except (NonmanualError, TypeError, ValueError, AttributeError) as error:
        raise SignError(f"Non-manual signals: {error}") from None
    library = SignLibrary(
        {},
        data.get("rest") or {},
        data.get("spelling") or {},
        float(data.get("transition_ms", 200)),
        shapes,
        dict(data.get("locations") or {}),
        nonmanuals,
    )
    for gloss, entry in (data.get("signs") or {}).items():
        _add_sign(library, str(gloss).upper(), entry or {})
    return library


def _add_sign(library: SignLibrary, gloss: str, entry: dict) -> None:
    """Check one sign's entry and add its keys and non-manual signals to *library*."""
    carried = entry.get("nonmanual") or ()
    carried = (carried,) if isinstance(carried, str) else tuple(carried)
    for name in carried:
        if name not in library.nonmanuals:
            raise SignError(f"{gloss}: unknown non-manual signal {name!r}.")
    if carried:
        library.sign_nonmanuals[gloss] = carried
    keys = [
        _sign_key(library, key, f"{gloss} key {k + 1}")
        for k, key in enumerate(entry.get("keys") or [])
    ]
    if not keys:
        raise SignError(f"{gloss}: a sign needs at least one key.")
    if any(b.ms < a.ms for a, b in itertools.pairwise(keys)):
        raise SignError(f"{gloss}: keys must be in time order.")
    library.signs[gloss] = tuple(keys)


def _hand_fields(spec, where: str):
    """Return a sign key's hand entry; SignError names a field a hand key does not have."""
    unknown = sorted(set(spec) - set(HAND_FIELDS), key=str) if isinstance(spec, dict) else []
    if unknown:
        # A misspelt field was read as absent: six left-hand keys of HAVE, SAD, SURPRISE
        # and GIVE-ME said "on: chest" or "on: head" (YAML reads "on" as true) for
        # "body: …", and stayed behind as the spine bent the chest into them (issue 52).
        field = unknown[0]
        named = repr(field) if isinstance(field, str) else f"{field} (YAML's on, off, yes or no)"
        raise SignError(
            f"{where}: a hand key has no field {named} (its fields: {', '.join(HAND_FIELDS)})."
        )
    return spec


def _sign_key(library: SignLibrary, key: dict, where: str) -> SignKey:
    """Return one key of a sign: its hands, time, hold and spine and head angles."""
    hands = {
        side: library.hand(side, _hand_fields(key[side], where), where)
        for side in ("right", "left")
        if side in key
    }
    for part in ("spine", "head"):
        unknown = set(key.get(part) or {}) - set(KEYED_DOFS)
        if unknown:
            raise SignError(f"{where}: unknown {part} angle {sorted(unknown)[0]!r}.")
    times = float(key.get("ms", 0)), float(key.get("hold_ms", 0))
    poses = dict(key.get("spine") or {}), dict(key.get("head") or {})
    return SignKey(*times, hands, *poses)


def read_library(path: str | Path) -> SignLibrary:
    """Read a sign library file (YAML)."""
    try:
        data = yaml.safe_load(Path(path).read_text(encoding="utf-8"))
    except yaml.YAMLError as error:
        raise SignError(f"{path}: not YAML ({error}).") from None
    return parse_library(data)


@cache
def default_library() -> SignLibrary:
    """Return the library that ships with the platform (the spine study's story)."""
    text = resources.files("synthesis").joinpath("data/signs.yaml").read_text("utf-8")
    return parse_library(yaml.safe_load(text))
