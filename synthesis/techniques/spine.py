"""Automated spine motion on or off, with seed 003's constants (spec 03; seed 003 §3)."""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING, Any

from synthesis.signing.spine import FORMULAS, SpineParams
from synthesis.techniques.kinds import SIGNED
from synthesis.techniques.parameters import Parameter
from synthesis.techniques.registry import Technique

if TYPE_CHECKING:
    from collections.abc import Mapping

    from synthesis.techniques.request import Build

DEFAULTS = SpineParams()
# Each constant's parameter and the SpineParams field it sets (seed 003's c0–c3).
CONSTANTS = {
    "spine_bend_deg": ("bend_deg", "c0", "the largest torso bend toward the hands' reach"),
    "spine_twist_deg": ("twist_deg", "c1", "the largest torso twist"),
    "clavicle_raise_deg": ("clavicle_raise_deg", "c2", "the largest shoulder raise"),
    "clavicle_forward_deg": ("clavicle_forward_deg", "c3", "the largest shoulder forward"),
}
FORMULA_LABELS = {
    "seed": "seed 003 as printed",
    "comfort": "comfort-radius variant (SignStudy's, not the seed's)",
}


# Seed 003's V_w = (X_w, Y_w): how much lateral and one-sided forward reach twist.
WEIGHTS = ("spine_twist_weight_x", "spine_twist_weight_y")


def _params(values: Mapping[str, Any]) -> SpineParams:
    """Return the spine tuning a condition's values choose."""
    fields = {field: values[name] for name, (field, *_) in CONSTANTS.items()}
    weights = tuple(values[name] for name in WEIGHTS)
    return replace(DEFAULTS, formula=values["spine_formula"], twist_weights=weights, **fields)


def _apply(build: Build) -> Build:
    values = build.request.parameters
    options = replace(build.sentence_options, spine=values["spine"], params=_params(values))
    return build.but(options=options)


def _summary(values: Mapping[str, Any]) -> str:
    if not values["spine"]:
        return "off"
    words = [f"on, {FORMULA_LABELS[values['spine_formula']]}"]
    words += [
        f"{symbol} {values[name]:g}°"
        for name, (field, symbol, _) in CONSTANTS.items()
        if values[name] != getattr(DEFAULTS, field)
    ]
    weights = tuple(values[name] for name in WEIGHTS)
    if weights != DEFAULTS.twist_weights:
        words.append(f"V_w ({weights[0]:g}, {weights[1]:g})")
    return ", ".join(words)


def _constant(name: str, field: str, symbol: str, meaning: str) -> Parameter:
    return Parameter(
        name,
        "float",
        getattr(DEFAULTS, field),
        f"Seed 003's {symbol}, {meaning}, in degrees (the seed prints no value; the "
        "default is this project's).",
        minimum=0.0,
        maximum=45.0,
        units="°",
    )


TECHNIQUE = Technique(
    name="spine",
    label="Automated spine motion",
    kinds=SIGNED,
    parameters=(
        Parameter(
            "spine",
            "bool",
            True,
            "Seed 003's automated spine bend and twist and "
            "clavicle motion, with staggered onsets; off leaves them out and changes "
            "nothing else that is signed.",
        ),
        Parameter(
            "spine_formula",
            "choice",
            DEFAULTS.formula,
            "seed (the default): §3.1's bend c0·smoothstep(|V_reach|/L_arm) and one-way "
            "twist as printed (it bends the torso about 11° with the hands in front of "
            "the chest and 15° with the arms at rest; hands placed on the body go with "
            "it); comfort: SignStudy's variant, bending only for the horizontal reach "
            "beyond a 0.25 m comfort radius and twisting both ways (a departure from "
            "seed 003, named in every condition's description).",
            choices=FORMULAS,
            labels=FORMULA_LABELS,
        ),
        *(_constant(name, *spec) for name, spec in CONSTANTS.items()),
        *(
            Parameter(
                name,
                "float",
                DEFAULTS.twist_weights[k],
                f"Seed 003's {axis}_w, the twist's weight on the hands' {meaning} "
                "(V_w = ⟨X_w, Y_w, 0⟩; the seed prints no value).",
                minimum=-10.0,
                maximum=10.0,
            )
            for k, (name, axis, meaning) in enumerate(
                zip(WEIGHTS, "XY", ("lateral reach", "one-sided forward reach"), strict=True)
            )
        ),
    ),
    source="seed 003 §3.1–3.3",
    order=30,
    apply=_apply,
    summary=_summary,
    # Off, the arm reaches alone: judged against arms that reach alone (synthesis.quality).
    reference_keeps=("spine",),
)
