"""Plan a sample size from a pilot: effects from its mixed model, then write the curve."""

import json
from pathlib import Path
from typing import Any

import pandas as pd

from analysis.mixed.ordinal import ordinal_mixed
from analysis.mixed.pairwise import mixed_bradley_terry
from analysis.mixed.section import MIN_PARTICIPANTS
from analysis.power.design import PlannedDesign
from analysis.power.results import PowerCurve
from analysis.power.simulation import Effects, effects_from_pilot
from analysis.results import plain
from analysis.tidy import TidyFormatError

STATED_KEYS = {f.name for f in Effects.__dataclass_fields__.values()}


def effects_for(
    pilot: pd.DataFrame | None,
    design: PlannedDesign,
    stated: dict[str, Any] | None = None,
    source: str = "pilot",
) -> Effects:
    """Return the effects to simulate: *stated* ones, else the pilot's mixed-model fit."""
    if stated is not None:
        unknown = set(stated) - STATED_KEYS
        if unknown or "effects" not in stated:
            raise TidyFormatError(
                f"stated effects need 'effects' and may have {', '.join(sorted(STATED_KEYS))}; "
                f"unknown: {', '.join(sorted(unknown)) or 'none'}."
            )
        missing = set(design.conditions) - set(stated["effects"])
        if missing:
            raise TidyFormatError(f"stated effects lack condition(s) {', '.join(sorted(missing))}.")
        if design.kind == "rating" and len(stated.get("thresholds", ())) < 1:
            raise TidyFormatError("stated effects of a rating design need its thresholds.")
        values = {k: v for k, v in stated.items() if k != "source"}
        values["thresholds"] = tuple(values.get("thresholds", ()))
        return Effects(**values, source="stated")
    if pilot is None:
        raise TidyFormatError("plan from a pilot's responses or from stated effects.")
    participants = pilot["participant"].nunique()
    if participants < MIN_PARTICIPANTS:
        raise TidyFormatError(
            f"the pilot has {participants} participant{'s' if participants != 1 else ''}; "
            f"planning from a pilot needs at least {MIN_PARTICIPANTS}, because its mixed "
            "model must estimate how much participants differ (the report fits no mixed "
            "model below that either). Take more pilot participants, or state the effects "
            "(from the literature) instead."
        )
    source = f"{source}: mixed-model estimates"
    if design.kind == "pairwise":
        return effects_from_pilot(mixed_bradley_terry(pilot, design.conditions), source=source)
    return effects_from_pilot(ordinal_mixed(pilot, design.question, design.conditions), source)


def power_figure(curve: PowerCurve, path: Path) -> None:
    """Draw power against N, one line per test, with the 80 % line."""
    from analysis.plotting import pyplot

    plt = pyplot()

    figure, axes = plt.subplots(figsize=(7, 4.2))
    table = curve.table()
    for test in curve.tests:
        axes.plot(table["participants"], table[test], marker="o", label=test)
    axes.axhline(0.8, color="grey", linestyle="--", linewidth=1)
    axes.set_xlabel("participants (N)")
    axes.set_ylabel("power")
    axes.set_ylim(0, 1.02)
    axes.set_title(f"Simulated power ({curve.simulations} simulated studies per N)")
    axes.legend(fontsize=7, ncols=2)
    figure.tight_layout()
    figure.savefig(path, dpi=120)
    plt.close(figure)


def write_power(curve: PowerCurve, out_dir: str | Path) -> list[str]:
    """Write power.csv (long), power.json and power.png into *out_dir*."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    pd.DataFrame([p.to_dict() for p in curve.points]).assign(simulated=True).to_csv(
        out / "power.csv", index=False
    )
    data = {**plain(curve.to_dict()), "simulated": True, "summary": curve.summary()}
    (out / "power.json").write_text(json.dumps(data, indent=2, ensure_ascii=False) + "\n")
    power_figure(curve, out / "power.png")
    return ["power.csv", "power.json", "power.png"]
