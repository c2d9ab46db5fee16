"""Mixed-effects Bradley–Terry model of paired choices (spec 07 "Pairwise", beyond the sources).

logit P(clip 1 chosen) = δ + s[clip 1] − s[clip 2] + b_p + b_i (+ a_p,clip 1 − a_p,clip 2):
condition strengths s (log-worths, the reference at 0) as fixed effects, the position
effect δ (the pull of the first clip between equals) as a covariate, random intercepts
for participants and items (each one's own pull towards clip 1), and, where the data can
identify them, each participant's own strengths a_p,c ~ N(0, σ²). "Cannot see a
difference" answers are excluded or, with ``ties="davidson"``, modelled as ties
(Davidson 1970) with one tie parameter ν.
"""

from collections.abc import Sequence

import numpy as np
import pandas as pd

from analysis.mixed.common import (
    codes,
    coefficient,
    condition_effects,
    contrasts,
    covariance_note,
    fit_notes,
    intercepts,
    separation_note,
    standard_error,
    variance_components,
    wald_test,
)
from analysis.mixed.families import FIRST, SECOND, TIE, Bernoulli, Davidson
from analysis.mixed.laplace import BOUNDARY_SD, Component, MixedProblem, fit_laplace
from analysis.mixed.results import MixedBradleyTerryResult
from analysis.pairwise import condition_order, judgements
from analysis.tidy import TidyFormatError

TIE_MODELS = ("exclude", "davidson")
POSITION = "position (clip 1)"


def strengths_identifiable(data: pd.DataFrame, conditions: Sequence[str]) -> bool:
    """Say whether participants' own strengths can be told apart from their other effects.

    Each participant must have judged at least two different pairs, in both orders, and
    at least twice as many judgements as there are conditions, over five participants.
    """
    if data["participant"].nunique() < 5:
        return False
    per = data.assign(pair=[frozenset(p) for p in zip(data["clip1"], data["clip2"], strict=True)])
    enough = per.groupby("participant").agg(
        pairs=("pair", "nunique"), rows=("pair", "size"), firsts=("clip1", "nunique")
    )
    return bool(
        (enough["pairs"] >= 2).all()
        and (enough["firsts"] >= 2).all()
        and (enough["rows"] >= 2 * len(conditions)).all()
    )


def pairwise_problem(
    data: pd.DataFrame,
    conditions: Sequence[str],
    *,
    ties: str = "exclude",
    random_strengths: bool = False,
) -> MixedProblem:
    """Build the model's response, design and components from judgements (analysis.judgements).

    *data* needs participant, item, clip1, clip2 and position (1, 2, or 0 for a tie).
    """
    if ties not in TIE_MODELS:
        raise ValueError(f"ties must be one of {', '.join(TIE_MODELS)}, not {ties!r}")
    keep = data["position"].isin((1, 2) if ties == "exclude" else (0, 1, 2))
    data = data[keep]
    y = np.select([data["position"].eq(1), data["position"].eq(2)], [FIRST, SECOND], TIE)
    columns = list(conditions)
    first = data["clip1"].map({c: i for i, c in enumerate(columns)}).to_numpy()
    second = data["clip2"].map({c: i for i, c in enumerate(columns)}).to_numpy()
    contrast = np.zeros((len(data), len(columns)))
    rows = np.arange(len(data))
    contrast[rows, first] += 1.0
    contrast[rows, second] -= 1.0
    X = np.column_stack([np.ones(len(data)), contrast[:, 1:]])
    participant, participant_levels = codes(data["participant"])
    components = intercepts(data)
    if random_strengths:
        components.append(
            Component.from_codes(
                "participant × condition strengths",
                "participant",
                participant,
                participant_levels,
                values=contrast,
                columns=tuple(columns),
            )
        )
    return MixedProblem(
        y=y.astype(float),
        X=X,
        fixed_names=(POSITION, *columns[1:]),
        components=tuple(components),
        family=Bernoulli() if ties == "exclude" else Davidson(),
    )


def _check_judgements(data: pd.DataFrame, order: Sequence[str]) -> None:
    """Refuse judgements of conditions outside *order*, or too few to fit the model."""
    unknown = (set(data["clip1"]) | set(data["clip2"])) - set(order)
    if unknown:
        raise TidyFormatError(f"conditions {sorted(unknown)} are not in the condition order")
    decisive = data["position"].isin((1, 2)).sum()
    if len(order) < 2 or decisive < 2 * len(order):
        raise TidyFormatError(
            f"a mixed Bradley–Terry model needs two or more conditions and at least "
            f"{2 * len(order)} decisive judgements; there are {decisive}."
        )


def _notes(data, order, ties: str, fit, random, coefficients, p: int) -> list[str]:
    """Return what a reader of the model must know: its scale, the ties, the fit."""
    notes = [
        f"Strengths are log-worths relative to {order[0]}; a positive position effect "
        "means clip 1 was chosen more often between equals.",
    ]
    ties_seen = int(data["position"].eq(0).sum())
    if ties == "exclude" and ties_seen:
        notes.append(f"{ties_seen} “cannot see a difference” answers were left out.")
    if ties == "davidson":
        notes.append(f"{ties_seen} “cannot see a difference” answers were modelled as ties.")
    notes += fit_notes(fit, random, fit.sd < BOUNDARY_SD)
    notes += separation_note(coefficients)
    notes += covariance_note(fit.cov[:p, :p])
    return notes


def mixed_bradley_terry(
    frame: pd.DataFrame,
    conditions: Sequence[str] | None = None,
    *,
    ties: str = "exclude",
    random_strengths: bool | None = False,
    correction: str = "holm",
    comparative_points: int = 5,
) -> MixedBradleyTerryResult:
    """Fit the mixed Bradley–Terry model to the pairwise and comparative rows of *frame*.

    ``random_strengths=True`` adds participants' own strengths (one more column per
    participant and condition: slow for a thousand participants); ``None`` adds them
    where :func:`strengths_identifiable` says the data allow it.
    """
    data = judgements(frame, comparative_points)
    order = condition_order(data, conditions)
    _check_judgements(data, order)
    if random_strengths is None:
        random_strengths = strengths_identifiable(data, order)
    problem = pairwise_problem(data, order, ties=ties, random_strengths=random_strengths)
    fit = fit_laplace(problem)
    if fit.dropped:
        raise TidyFormatError(
            f"conditions {', '.join(fit.dropped)} cannot be estimated: no judgement tells "
            "them apart from the others (a condition never shown, or shown only with "
            "another); leave them out of the condition order."
        )
    p = problem.X.shape[1]
    estimates, cov = fit.params[1:p], fit.cov[1:p, 1:p]
    effects, full, full_cov = condition_effects(order, estimates, cov)
    statistic, df, pvalue = wald_test(estimates, cov)
    position = coefficient(POSITION, fit.params[0], standard_error(fit.cov[0, 0]))
    random = variance_components(problem.components, fit.sd)
    notes = _notes(data, order, ties, fit, random, [position, *effects], p)
    formula = "chose clip 1 ~ position + strengths + (1 | participant)" + (
        " + (1 | item)" if any(c.group == "item" for c in problem.components) else ""
    )
    if random_strengths:
        formula += " + (strengths | participant)"
    return MixedBradleyTerryResult.from_fit(
        fit,
        data,
        order,
        test=(statistic, df, pvalue),
        notes=notes,
        model="Mixed-effects Bradley–Terry"
        + (" with Davidson ties" if ties == "davidson" else " (logistic)"),
        estimator="maximum likelihood, Laplace approximation (as lme4::glmer, nAGQ = 1)",
        formula=formula,
        effects=tuple(effects),
        contrasts=contrasts(order, full, full_cov, correction),
        random=random,
        correction=correction,
        position=position,
        tie_handling=ties,
        tie_parameter=float(np.exp(fit.params[p])) if ties == "davidson" else None,
    )
