"""A body shape: MakeHuman's macro values (gender, age, muscle, weight, height,
proportions, ancestry) and the vertex offsets they add to the base mesh.

MakeHuman's macro model (``targets/macrodetails/macro.json``): each value in 0–1 weighs
the two labels on either side of it — gender female 0 … male 1; age baby 0, child
0.1875, young 0.5, old 1 (1, 11, 25 and 90 years); muscle and weight min 0, average
0.5, max 1; height and proportions add their target only away from 0.5 (min/uncommon
below, max/ideal above) — and a target named by one label of each variable of a
combination (``universal-female-young-averagemuscle-averageweight``, ``height/…``)
is added with the product of those labels' weights. Ancestry (African, Asian,
Caucasian) weighs the ``race-gender-age`` targets and sums to one. Targets that do not
exist (the averages, which are the base mesh itself) add nothing.
"""

from dataclasses import asdict, dataclass, fields
from itertools import pairwise, product
from types import MappingProxyType

import numpy as np

# Knots of each variable: (value, label); a value between two knots weighs both.
_KNOTS = {
    "gender": ((0.0, "female"), (1.0, "male")),
    "age": ((0.0, "baby"), (0.1875, "child"), (0.5, "young"), (1.0, "old")),
    "muscle": ((0.0, "minmuscle"), (0.5, "averagemuscle"), (1.0, "maxmuscle")),
    "weight": ((0.0, "minweight"), (0.5, "averageweight"), (1.0, "maxweight")),
    "height": ((0.0, "minheight"), (0.5, ""), (1.0, "maxheight")),
    "proportions": ((0.0, "uncommonproportions"), (0.5, ""), (1.0, "idealproportions")),
    "cupsize": ((0.0, "mincup"), (0.5, "averagecup"), (1.0, "maxcup")),
    "firmness": ((0.0, "minfirmness"), (0.5, "averagefirmness"), (1.0, "maxfirmness")),
}
# Each combination: its variables and the folder and prefix of its targets.
_COMBINATIONS = (
    (("gender", "age", "muscle", "weight"), "universal-"),
    (("gender", "age", "muscle", "weight", "height"), "height/"),
    (("gender", "age", "muscle", "weight", "proportions"), "proportions/"),
    (("gender", "age", "muscle", "weight", "cupsize", "firmness"), "breast/"),
)
RACES = ("african", "asian", "caucasian")


@dataclass(frozen=True)
class Phenotype:
    """A body's macro values, each 0–1 (MakeHuman's); ancestry shares are normalised."""

    gender: float = 0.5
    age: float = 0.5
    muscle: float = 0.5
    weight: float = 0.5
    height: float = 0.5
    proportions: float = 0.5
    cupsize: float = 0.5
    firmness: float = 0.5
    african: float = 1 / 3
    asian: float = 1 / 3
    caucasian: float = 1 / 3

    def __post_init__(self) -> None:
        for field in fields(self):
            value = getattr(self, field.name)
            if not 0.0 <= value <= 1.0:
                raise ValueError(f"Phenotype {field.name} must be within 0–1, not {value!r}.")
        if self.african + self.asian + self.caucasian <= 0:
            raise ValueError("At least one ancestry share must be above 0.")

    def to_dict(self) -> dict[str, float]:
        return asdict(self)

    def label_weights(self, variable: str) -> dict[str, float]:
        """Return the weight of each label of *variable* at this phenotype's value."""
        value, knots = getattr(self, variable), _KNOTS[variable]
        for (low, low_label), (high, high_label) in pairwise(knots):
            if low <= value <= high:
                t = (value - low) / (high - low)
                return {low_label: 1.0 - t, high_label: t}
        raise AssertionError(value)

    def target_weights(self) -> dict[str, float]:
        """Return every macro target this phenotype adds, by name, with its weight."""
        weights: dict[str, float] = {}
        share = np.array([self.african, self.asian, self.caucasian])
        share = share / share.sum()
        for race, race_weight in zip(RACES, share, strict=True):
            for (gender, g), (age, a) in product(
                self.label_weights("gender").items(), self.label_weights("age").items()
            ):
                weights[f"{race}-{gender}-{age}"] = race_weight * g * a
        for variables, prefix in _COMBINATIONS:
            for labelled in product(*(self.label_weights(v).items() for v in variables)):
                labels = [label for label, _ in labelled]
                if "" in labels:
                    continue
                weight = float(np.prod([w for _, w in labelled]))
                weights[prefix + "-".join(labels)] = weight
        return {name: w for name, w in weights.items() if w > 1e-9}


PRESETS = MappingProxyType(
    {
        # MakeHuman's default human: between female and male, 25, average build.
        "neutral": Phenotype(),
        "woman": Phenotype(gender=0.0, cupsize=0.5),
        "man": Phenotype(gender=1.0),
        "older woman": Phenotype(gender=0.0, age=0.8, weight=0.6),
        "older man": Phenotype(gender=1.0, age=0.8, weight=0.6),
    }
)
DEFAULT_PRESET = "woman"
# A body given by its macro values instead of a preset (Look, the avatar technique).
CUSTOM = "custom"
# The values a custom body sets; ancestry, cup size and firmness stay MakeHuman's.
RAW_VALUES = ("gender", "age", "muscle", "weight", "height", "proportions")
# Youngest age a custom body may have: 0.5 is 25 years (the signers the rig is fitted to).
ADULT_AGE = 0.5


def body_phenotype(body: str | Phenotype) -> Phenotype:
    """Return the phenotype of a preset's name, or *body* itself when it is one."""
    if isinstance(body, Phenotype):
        return body
    if body not in PRESETS:
        raise ValueError(f"Unknown body {body!r}: the bodies are {', '.join(PRESETS)}.")
    return PRESETS[body]


def body_key(body: str | Phenotype) -> str:
    """Return a file-name-safe key of a body: its preset's name, or its macro values."""
    phenotype = body_phenotype(body)
    for name, preset in PRESETS.items():
        if preset == phenotype:
            return name.replace(" ", "_")
    return "custom_" + "_".join(f"{value:.3f}" for value in phenotype.to_dict().values())


def shaped_vertices(vertices_m: np.ndarray, phenotype: Phenotype, target) -> np.ndarray:
    """Return the base mesh's vertices with *phenotype*'s macro targets added.

    *target(name)* returns a target's (indices, offsets m) or raises KeyError for a
    combination MakeHuman ships no file for (the averages: the base mesh itself).
    """
    shaped = np.array(vertices_m, dtype=np.float64, copy=True)
    for name, weight in phenotype.target_weights().items():
        try:
            indices, offsets = target(name)
        except KeyError:
            continue
        np.add.at(shaped, indices, weight * offsets)
    return shaped
