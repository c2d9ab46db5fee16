"""The result of a power simulation: each planned test's power at each N."""

import dataclasses
from typing import Any

from analysis.results import Result


@dataclasses.dataclass(frozen=True)
class PowerPoint(Result):
    """Share of simulated studies of ``participants`` participants in which ``test`` rejected.

    ``failures`` counts studies whose test could not be computed (a degenerate fit);
    they count as not significant.
    """

    participants: int
    test: str
    power: float
    mc_se: float
    simulations: int
    failures: int = 0


@dataclasses.dataclass(frozen=True)
class PowerCurve(Result):
    """Simulated power of every planned test over a range of N, and what it assumed."""

    kind: str
    conditions: tuple[str, ...]
    question: str
    points: tuple[PowerPoint, ...]
    alpha: float
    correction: str
    simulations: int
    seed: int
    effects: dict[str, Any]
    schedules: int
    trials_per_participant: float
    mixed_fit: str

    @property
    def tests(self) -> tuple[str, ...]:
        names = dict.fromkeys(p.test for p in self.points)
        return tuple(sorted(names, key=lambda name: (not name.endswith(": conditions"), name)))

    def power(self, test: str, participants: int) -> float:
        """Return the simulated power of *test* at *participants*."""
        for point in self.points:
            if point.test == test and point.participants == participants:
                return point.power
        raise KeyError(f"no simulation of {test!r} at N = {participants}")

    def required_n(self, test: str, target: float = 0.8) -> int | None:
        """Return the smallest simulated N whose power reaches *target*, or None."""
        reached = [p.participants for p in self.points if p.test == test and p.power >= target]
        return min(reached) if reached else None

    def apa(self, test: str | None = None, target: float = 0.8) -> str:
        test = test or self.tests[0]
        n = self.required_n(test, target)
        if n is None:
            largest = max(p.participants for p in self.points if p.test == test)
            return (
                f"{test}: power stays below {target:.2f} up to N = {largest} "
                f"({self.simulations} simulated studies per N, α = {self.alpha:g})"
            )
        return (
            f"{test}: N = {n} participants give power {self.power(test, n):.2f} "
            f"(target {target:.2f}; {self.simulations} simulated studies per N, α = {self.alpha:g})"
        )

    def table(self):
        """Return power as a data frame: one row per N, one column per test."""
        import pandas as pd

        frame = pd.DataFrame([p.to_dict() for p in self.points])
        return frame.pivot(index="participants", columns="test", values="power").reset_index()

    def summary(self) -> str:
        lines = [
            f"Simulated power ({self.kind}, {self.simulations} studies per N, α = {self.alpha:g}, "
            f"{self.correction} correction of pairwise tests, seed {self.seed}). SIMULATED.",
            f"Effects ({self.effects['source']}): {self.effects}",
            self.table().to_string(index=False, float_format=lambda v: f"{v:.3f}"),
        ]
        lines += [self.apa(test) for test in self.tests]
        lines += [f"note: {note}" for note in self.effects.get("notes", ())]
        failed = sum(p.failures for p in self.points)
        if failed:
            lines.append(
                f"{failed} test results could not be computed (degenerate fits) and count "
                "as not significant."
            )
        return "\n".join(lines)
