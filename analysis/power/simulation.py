"""Simulate a planned study under a model and count how often each planned test rejects.

The data-generating model is the analysis model itself (analysis.mixed): for paired
choices logit P(clip 1) = δ + s[a] − s[b] + b_p + b_i (+ participants' own strengths),
for ratings the cumulative logit with participant and item intercepts. Its parameters
come from a pilot's fit (:func:`effects_from_pilot`) or are stated. Each simulated
study is analysed with the planned tests: the mixed model (Wald tests; fitted with
glmer's nAGQ = 0 stage for speed, see :func:`analysis.mixed.fit_laplace`) and the
classical test the report also runs (exact binomial per pair, or paired t).
"""

import dataclasses
import functools
import os
from collections.abc import Sequence
from concurrent.futures import ProcessPoolExecutor
from itertools import combinations

import numpy as np
import pandas as pd
from scipy import stats

from analysis.mixed.common import coefficient, standard_error, wald_test
from analysis.mixed.families import Bernoulli, CumulativeLogit
from analysis.mixed.laplace import BOUNDARY_SD, fit_laplace
from analysis.mixed.ordinal import ordinal_problem
from analysis.mixed.pairwise import pairwise_problem
from analysis.power.design import PlannedDesign
from analysis.power.results import PowerCurve, PowerPoint
from analysis.within import adjust

TESTS = {"pairwise": ("mixed", "binomial"), "rating": ("mixed", "paired-t")}


@dataclasses.dataclass(frozen=True)
class Effects:
    """The parameters data are simulated from (scale of the linear predictor).

    ``effects`` maps each condition to its strength (pairwise: log-worth; ratings: log
    odds of rating higher); ``position`` the pull of clip 1; the SDs of participants'
    and items' intercepts and of participants' own strengths; ``thresholds`` the
    cumulative-logit cut points of a rating scale (rating = 1 + categories passed).
    """

    effects: dict[str, float]
    sd_participant: float = 0.0
    sd_item: float = 0.0
    sd_strengths: float = 0.0
    position: float = 0.0
    thresholds: tuple[float, ...] = ()
    source: str = "stated"
    # What a researcher must know about where the effects came from (a singular pilot).
    notes: tuple[str, ...] = ()


def effects_from_pilot(mixed_result, source: str = "pilot") -> Effects:
    """Take the estimates of a fitted mixed model (pairwise or ordinal) as the truth."""
    effects = {mixed_result.reference: 0.0}
    effects.update({c.name: c.estimate for c in mixed_result.effects})
    sds = {c.name: c.sd for c in mixed_result.random}
    zero = [c.name for c in mixed_result.random if c.sd < BOUNDARY_SD]
    notes: tuple[str, ...] = ()
    if getattr(mixed_result, "singular", False) and zero:
        notes = (
            f"The pilot's {' and '.join(zero)} SD{'s' if len(zero) > 1 else ''} sit"
            f"{'' if len(zero) > 1 else 's'} on the boundary of zero (a singular fit): the "
            "simulation assumes no such variation, which overstates power if there is "
            "some; a larger pilot, or an SD stated from the literature, is safer.",
        )
    return Effects(
        effects=effects,
        sd_participant=sds.get("participant", 0.0),
        sd_item=sds.get("item", 0.0),
        sd_strengths=sds.get("participant × condition strengths", 0.0),
        position=mixed_result.position.estimate if getattr(mixed_result, "position", None) else 0.0,
        thresholds=tuple(t.estimate for t in getattr(mixed_result, "thresholds", ())),
        source=source,
        notes=notes,
    )


@functools.lru_cache(maxsize=32)
def _layout(design: PlannedDesign, participants: int) -> pd.DataFrame:
    """Return every planned trial of *participants* participants, one row each."""
    rows = []
    for j in range(participants):
        for trial in design.schedules[j % len(design.schedules)]:
            rows.append((j, trial.item, trial.condition_a, trial.condition_b))
    return pd.DataFrame(rows, columns=["participant", "item", "clip1", "clip2"])


def simulate(
    design: PlannedDesign, effects: Effects, participants: int, rng: np.random.Generator
) -> pd.DataFrame:
    """Return one simulated study: judgements (position 1/2) or ratings (1 … K)."""
    table = _layout(design, participants)
    items = sorted(set(table["item"]))
    item_code = table["item"].map({item: i for i, item in enumerate(items)}).to_numpy()
    person = table["participant"].to_numpy()
    strength = np.array([effects.effects.get(c, 0.0) for c in design.conditions])
    index = {c: i for i, c in enumerate(design.conditions)}
    a = table["clip1"].map(index).to_numpy()
    eta = (
        rng.normal(0, effects.sd_participant, participants)[person]
        + rng.normal(0, effects.sd_item, len(items))[item_code]
    )
    if design.kind == "pairwise":
        b = table["clip2"].map(index).to_numpy()
        own = rng.normal(0, effects.sd_strengths, (participants, len(strength)))
        eta += effects.position + strength[a] - strength[b] + own[person, a] - own[person, b]
        first = Bernoulli().simulate(eta, np.zeros(0), rng)
        return table.assign(position=np.where(first == 1, 1, 2))
    eta += strength[a]
    ratings = CumulativeLogit(len(effects.thresholds) + 1).simulate(
        eta, np.asarray(effects.thresholds), rng
    )
    return pd.DataFrame(
        {
            "participant": person,
            "item": table["item"],
            "condition": table["clip1"],
            "rating": 1 + ratings,
        }
    )


def _pvalues_mixed(design, effects, data) -> dict[str, float]:
    order = list(design.conditions)
    extra = None
    if design.kind == "pairwise":
        problem = pairwise_problem(data, order, random_strengths=effects.sd_strengths > 0)
    else:
        if data["rating"].nunique() < 2:
            return {}
        problem = ordinal_problem(data, order)
        # The true thresholds start the search only when every scale point was drawn.
        if data["rating"].nunique() == len(effects.thresholds) + 1:
            extra = np.asarray(effects.thresholds)
    truth = {
        "participant": effects.sd_participant,
        "item": effects.sd_item,
        "participant × condition strengths": effects.sd_strengths,
    }
    start = np.maximum([truth[c.name] for c in problem.components], 0.1)
    fit = fit_laplace(problem, stage="fast", sd_start=start, extra_start=extra)
    offset = 1 if design.kind == "pairwise" else 0
    return _mixed_tests(order, fit, offset, len(problem.fixed_names) - offset)


def _mixed_tests(order, fit, offset, width) -> dict[str, float]:
    if fit.dropped:
        # A simulated study whose draw cannot tell conditions apart: every test fails.
        pairs = [f"mixed: {order[j]} vs {order[i]}" for i, j in combinations(range(len(order)), 2)]
        return dict.fromkeys(["mixed: conditions", *pairs], float("nan"))
    estimates = fit.params[offset : offset + width]
    cov = fit.cov[offset : offset + width, offset : offset + width]
    found = {"mixed: conditions": wald_test(estimates, cov)[2]}
    full = np.concatenate([[0.0], estimates])
    full_cov = np.zeros((len(order), len(order)))
    full_cov[1:, 1:] = cov
    for i, j in combinations(range(len(order)), 2):
        se = standard_error(full_cov[i, i] + full_cov[j, j] - 2 * full_cov[i, j])
        # A degenerate fit (no positive SE) gives p = NaN: counted as a failure, not a hit.
        found[f"mixed: {order[j]} vs {order[i]}"] = coefficient("", full[j] - full[i], se).pvalue
    return found


def _pvalues_classical(design, data) -> dict[str, float]:
    order = list(design.conditions)
    found = {}
    if design.kind == "pairwise":
        clip1, clip2 = data["clip1"].to_numpy(), data["clip2"].to_numpy()
        chosen = np.where(data["position"].to_numpy() == 1, clip1, clip2)
        for i, j in combinations(range(len(order)), 2):
            a, b = order[i], order[j]
            pair = ((clip1 == a) & (clip2 == b)) | ((clip1 == b) & (clip2 == a))
            n = int(pair.sum())
            if n:
                wins = int((chosen[pair] == b).sum())
                found[f"binomial: {b} vs {a}"] = stats.binomtest(wins, n).pvalue
        return found
    means = data.pivot_table(index="participant", columns="condition", values="rating")
    for i, j in combinations(range(len(order)), 2):
        a, b = order[i], order[j]
        if a in means and b in means:
            diff = (means[b] - means[a]).dropna()
            if len(diff) > 1 and diff.std() > 0:
                found[f"paired-t: {b} vs {a}"] = stats.ttest_1samp(diff, 0.0).pvalue
    return found


def _one_batch(args) -> list[tuple[int, dict[str, float]]]:
    design, effects, participants, seeds, tests, correction = args
    results = []
    for seed in seeds:
        rng = np.random.default_rng(seed)
        data = simulate(design, effects, participants, rng)
        pvalues = {}
        if "mixed" in tests:
            pvalues.update(_adjusted(_pvalues_mixed(design, effects, data), correction))
        classical = [t for t in tests if t != "mixed"]
        if classical:
            pvalues.update(_adjusted(_pvalues_classical(design, data), correction))
        results.append((participants, pvalues))
    return results


def _adjusted(pvalues: dict[str, float], correction: str) -> dict[str, float]:
    """Correct the pairwise tests as the report does; the omnibus test stays as it is."""
    keys = [k for k in pvalues if not k.endswith(": conditions")]
    raw = [pvalues[k] for k in keys]
    adjusted = adjust(raw, correction)
    return {**pvalues, **dict(zip(keys, map(float, adjusted), strict=True))}


def _one_blas_thread() -> None:
    """Keep a pool process to one BLAS thread: the processes already share the cores."""
    from threadpoolctl import threadpool_limits

    threadpool_limits(limits=1)


def _checked_sizes(design: PlannedDesign, effects: Effects, tests, participants) -> list[int]:
    """Return the planned Ns in order; ValueError names what cannot be simulated."""
    unknown = set(tests) - set(TESTS[design.kind])
    if unknown:
        raise ValueError(f"unknown test(s) {sorted(unknown)} for a {design.kind} design")
    if design.kind == "rating" and not effects.thresholds:
        raise ValueError(
            "a rating design needs the scale's thresholds to simulate ratings from "
            "(Effects(thresholds=…), or effects from a pilot's ordinal model)"
        )
    sizes = sorted({int(n) for n in participants})
    if not sizes or sizes[0] < 2:
        raise ValueError("plan for two or more participants")
    return sizes


def _power_points(batches, alpha: float) -> tuple[PowerPoint, ...]:
    """Return each N's and test's power: the share of simulated studies with p < *alpha*."""
    pvalues_by: dict[tuple[int, str], list[float]] = {}
    for batch in batches:
        for n, pvalues in batch:
            for test, pvalue in pvalues.items():
                pvalues_by.setdefault((n, test), []).append(float(pvalue))
    points = []
    for (n, test), listed in sorted(pvalues_by.items()):
        found = np.asarray(listed)
        # A study whose test could not be computed counts as not significant.
        hits = np.nan_to_num(found, nan=1.0) < alpha
        points.append(
            PowerPoint(
                participants=n,
                test=test,
                power=float(hits.mean()),
                mc_se=float(np.sqrt(hits.mean() * (1 - hits.mean()) / len(hits))),
                simulations=len(hits),
                failures=int(np.isnan(found).sum()),
            )
        )
    return tuple(points)


def power_curve(
    design: PlannedDesign,
    effects: Effects,
    participants: Sequence[int],
    *,
    simulations: int = 200,
    alpha: float = 0.05,
    seed: int = 0,
    tests: Sequence[str] | None = None,
    correction: str = "holm",
    workers: int | None = None,
) -> PowerCurve:
    """Simulate *simulations* studies at each N in *participants*; return each test's power.

    Seeds come from ``numpy.random.SeedSequence(seed)``, one per simulated study, so the
    answer does not depend on *workers* (processes; default: the machine's cores).
    """
    tests = tuple(tests or TESTS[design.kind])
    sizes = _checked_sizes(design, effects, tests, participants)
    children = np.random.SeedSequence(seed).spawn(len(sizes) * simulations)
    seeds = [int(child.generate_state(1)[0]) for child in children]
    workers = workers if workers is not None else (os.cpu_count() or 1)
    chunk = max(1, simulations // max(workers, 1) // 2)
    jobs = []
    for k, n in enumerate(sizes):
        mine = seeds[k * simulations : (k + 1) * simulations]
        jobs += [
            (design, effects, n, mine[i : i + chunk], tests, correction)
            for i in range(0, simulations, chunk)
        ]
    if workers > 1:
        with ProcessPoolExecutor(workers, initializer=_one_blas_thread) as pool:
            batches = list(pool.map(_one_batch, jobs))
    else:
        batches = [_one_batch(job) for job in jobs]
    points = _power_points(batches, alpha)
    return PowerCurve(
        kind=design.kind,
        conditions=design.conditions,
        question=design.question,
        points=points,
        alpha=alpha,
        correction=correction,
        simulations=simulations,
        seed=seed,
        effects=dataclasses.asdict(effects),
        schedules=len(design.schedules),
        trials_per_participant=design.trials_per_participant(),
        mixed_fit="nAGQ = 0 (penalised IRLS for β, Laplace for the variances)",
    )
