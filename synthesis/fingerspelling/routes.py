"""Route a transition between two handshapes so that no finger passes through another.

Moving every DOF straight from one letter to the next often drives the thumb through
the fingers (A → T, H → A: the thumb must get from one side of a finger to the other).
A signer avoids that by moving the digits in an order: opening the fingers first, moving
the thumb out of their way, closing them again. Each such order is a *route*: zero to
three intermediate poses between the letters, passed through at equal steps of the
transition time. For each pair of letters the route is the shortest of :data:`ROUTES`
that passes no phalanx through another (:func:`synthesis.rigs.collisions.finger_crossings`)
and adds little overlap between digits beyond what the two letters themselves have.

Choosing takes about 0.1 s a pair, so the choices for the whole alphabet are computed
once into ``data/letter_routes.json`` (``scripts/letter_routes.py``) for the ASL
alphabet; pairs not in it, and every pair of another alphabet, are chosen on first use.
"""

import json
from functools import cache
from importlib import resources

import numpy as np
from scipy.interpolate import CubicSpline

from synthesis.fingerspelling.alphabet import LETTERS, letter, rest_pose
from synthesis.fingerspelling.alphabets import DEFAULT_ALPHABET
from synthesis.formats import check_header
from synthesis.rigs.collisions import finger_crossings, overlap_depths_m
from synthesis.rigs.hand import FINGERS, HandModel

FORMAT = "signstudy.letter-routes"
FORMAT_VERSION = 1
# In order of preference: the fewest detours first.
ROUTES = (
    "direct",
    "fingers_first",
    "thumb_first",
    "thumb_out",
    "open_thumb_out",
    "open_spread",
    "open_wide",
)
# The thumb held away from the palm, out of the fingers' way (degrees).
THUMB_OUT_DEG = {"thumb_cmc_abduction": 60.0, "thumb_cmc_flexion": -10.0}
# Finger flexion (MCP, PIP, DIP) the fingers open to at most while the thumb passes.
OPEN_FLEXION_DEG = 15.0
# Index and middle spread apart to let the thumb between them (T, N, M).
SPREAD_DEG = {"index_mcp_abduction": 20.0, "middle_mcp_abduction": -10.0}
SAMPLES = 121
# Overlap between digits beyond the letters' own contacts that a route may leave (soft
# tissue gives, and a longer detour would make the hand rush).
OVERLAP_TOLERANCE_M = 0.010
# Stands for the relaxed hand before and after a word, in pairs such as "_A" and "A_".
REST = "_"


def _masks(model: HandModel) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Return boolean masks over DOFs: the thumb's, the fingers', the fingers' flexions."""
    names = model.dof_names
    thumb = np.array([n.startswith("thumb_") for n in names])
    fingers = np.array([n.split("_")[0] in FINGERS for n in names])
    flexion = fingers & np.array([n.endswith("_flexion") for n in names])
    return thumb, fingers, flexion


def route_poses(route: str, a_rad: np.ndarray, b_rad: np.ndarray, side: str = "right"):
    """Return the intermediate poses (list of DOF vectors) of *route* from a to b."""
    if route not in ROUTES:
        raise ValueError(f"Unknown route {route!r}; routes are {', '.join(ROUTES)}.")
    model = HandModel(side)
    thumb, fingers, flexion = _masks(model)
    a, b = np.asarray(a_rad, dtype=float), np.asarray(b_rad, dtype=float)
    middle = (a + b) / 2
    out = model.from_degrees(THUMB_OUT_DEG)
    opened = np.minimum(np.minimum(a, b), np.radians(OPEN_FLEXION_DEG))
    if route == "direct":
        return []
    if route in ("fingers_first", "thumb_first"):
        via = middle.copy()
        lead, lag = (b, a) if route == "fingers_first" else (a, b)
        via[fingers], via[thumb] = lead[fingers], lag[thumb]
        return [via]
    if route == "thumb_out":
        via = middle.copy()
        via[thumb] = out[thumb]
        return [via]
    # Open the fingers with the thumb where it was, move it, close them over it.
    first, second = middle.copy(), middle.copy()
    first[thumb], second[thumb] = a[thumb], b[thumb]
    if route == "open_thumb_out":
        first[flexion], second[flexion] = opened[flexion], opened[flexion]
        first[thumb] = (a[thumb] + out[thumb]) / 2
        second[thumb] = (b[thumb] + out[thumb]) / 2
        return [first, second]
    first[flexion] = second[flexion] = 0.0
    if route == "open_spread":
        spread = model.from_degrees(SPREAD_DEG)
        for via in (first, second):
            for name in SPREAD_DEG:
                k = model.dof_names.index(name)
                via[k] = spread[k]
        return [first, second]
    wide = middle.copy()
    wide[flexion] = 0.0
    wide[thumb] = out[thumb]
    return [first, wide, second]


def route_path(a_rad, b_rad, vias, samples: int = SAMPLES) -> np.ndarray:
    """Return *samples* poses from a to b through *vias*, eased as spelling eases them.

    A cubic spline through the keys at equal steps, at rest at both ends (clamped): C²
    through the intermediate poses, so the hand sweeps round an obstacle rather than
    stopping at each turn; with no intermediate pose it is the smoothstep ease.
    """
    keys = np.stack([a_rad, *vias, b_rad])
    spline = CubicSpline(np.linspace(0.0, 1.0, len(keys)), keys, axis=0, bc_type="clamped")
    return spline(np.linspace(0.0, 1.0, samples))


def assess(route: str, a_rad, b_rad, side: str = "right") -> tuple[int, float, float]:
    """Return a route's crossings, its deepest overlap beyond the letters' own (m) and
    its length (the summed joint-angle change along it, rad)."""
    model = HandModel(side)
    path = model.clip(route_path(a_rad, b_rad, route_poses(route, a_rad, b_rad, side)))
    depths = overlap_depths_m(model, path)
    allowed = np.maximum(np.maximum(depths[0], depths[-1]), 0.0)
    length = float(np.abs(np.diff(path, axis=0)).sum())
    return len(finger_crossings(model, path)), float(np.max(depths - allowed)), length


def choose_route(a_rad, b_rad, side: str = "right") -> str:
    """Return the best route from pose a to pose b: fewest crossings, then overlap beyond
    the letters' own kept under :data:`OVERLAP_TOLERANCE_M`, then the shortest: the
    transition time is the timing model's, so every detour makes the hand move faster."""
    scores = []
    for rank, route in enumerate(ROUTES):
        crossings, excess_m, length = assess(route, a_rad, b_rad, side)
        scores.append((crossings, max(excess_m - OVERLAP_TOLERANCE_M, 0.0), length, rank))
    return ROUTES[min(scores)[3]]


def end_pose(character: str, side: str = "right", alphabet: str = DEFAULT_ALPHABET) -> np.ndarray:
    """Return the pose a letter is left from (a path letter's last key; REST the rest)."""
    if character == REST:
        return rest_pose(side)
    shape = letter(character, side, alphabet)
    return shape.dofs_rad if shape.path_rad is None else shape.path_rad[-1]


def start_pose(character: str, side: str = "right", alphabet: str = DEFAULT_ALPHABET) -> np.ndarray:
    """Return the pose a letter is reached at (a path letter's first key; REST the rest)."""
    if character == REST:
        return rest_pose(side)
    shape = letter(character, side, alphabet)
    return shape.dofs_rad if shape.path_rad is None else shape.path_rad[0]


@cache
def _table() -> dict[str, str]:
    text = resources.files("synthesis").joinpath("data/letter_routes.json").read_text("utf-8")
    data = json.loads(text)
    check_header(data, FORMAT, FORMAT_VERSION, "letter-routes file", where="letter_routes.json")
    return data["routes"]


@cache
def letter_route(first: str, second: str, alphabet: str = DEFAULT_ALPHABET) -> str:
    """Return the route from one letter to the next, or from or to :data:`REST` (the same
    for either hand: the left hand mirrors the right)."""
    pair = (first + second).upper()
    if first.upper() == second.upper():
        return "direct"  # a doubled letter only slides
    route = _table().get(pair) if alphabet == DEFAULT_ALPHABET else None
    if route is None:
        route = choose_route(
            end_pose(first, alphabet=alphabet), start_pose(second, alphabet=alphabet)
        )
    return route


def compute_table(letters: str = "".join(LETTERS)) -> dict:
    """Return the letter-routes file's content for every ordered pair of *letters* and
    for the moves from and to the rest pose."""
    keys = REST + letters
    routes = {a + b: choose_route(end_pose(a), start_pose(b)) for a in keys for b in keys if a != b}
    return {"format": FORMAT, "version": FORMAT_VERSION, "routes": routes}
