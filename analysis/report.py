"""Run every analysis on a tidy table and collect the results in one Report object."""

import dataclasses
import platform
from collections.abc import Sequence
from importlib import metadata
from typing import Any

import pandas as pd

from analysis.comparative import compare_preferences
from analysis.conditions import compare_conditions, summarize_conditions
from analysis.exclusions import ExclusionRules, apply_exclusions
from analysis.intelligibility import accuracy_scores, score_intelligibility
from analysis.mixed.results import MixedModels
from analysis.mixed.section import fit_mixed_models
from analysis.pairwise import analyze_pairwise
from analysis.quality import ParticipantQuality, summarize_quality
from analysis.ratings import compare_ratings, rating_scores, summarize_ratings
from analysis.results import (
    ComparativePreference,
    ExclusionReport,
    PairwiseAnalysis,
    Result,
    plain,
)
from analysis.summaries import (
    ConditionComparison,
    ConditionSummary,
    IntelligibilityScore,
    PairedComparison,
    RatingComparison,
    RatingSummary,
)
from analysis.tidy import (
    analysed,
    check_conditions,
    condition_keys,
    label_conditions,
    label_simulated,
    simulated_conditions,
    with_simulated_labels,
)

SOFTWARE = ("numpy", "scipy", "pandas", "statsmodels", "matplotlib")


@dataclasses.dataclass(frozen=True)
class ReportOptions(Result):
    """How to analyse: condition order, ties, correction, exclusions."""

    conditions: tuple[str, ...] | None = None
    tie_handling: str = "exclude"
    correction: str = "holm"
    comparative_points: int = 5
    fuzzy_scoring: bool = True
    mixed_models: bool = True
    mixed_ties: str = "exclude"
    exclusions: ExclusionRules = dataclasses.field(default_factory=ExclusionRules)


@dataclasses.dataclass(frozen=True)
class Report(Result):
    """All results of one analysis run, with what is needed to reproduce it."""

    source: str
    studies: tuple[str, ...]
    design: dict[str, Any]
    exclusions: ExclusionReport
    pairwise: PairwiseAnalysis | None
    ratings: tuple[RatingSummary, ...]
    rating_comparisons: tuple[RatingComparison, ...]
    intelligibility: tuple[IntelligibilityScore, ...]
    options: ReportOptions
    software: dict[str, str]
    mixed: MixedModels | None = None
    # How each participant took the pages (all participants, before exclusions).
    quality: tuple[ParticipantQuality, ...] = ()
    # Comparative-scale preferences per pair of conditions (signed-rank tests).
    comparative: tuple[ComparativePreference, ...] = ()
    # Each condition across items, on participants' means, and paired tests between them.
    rating_conditions: tuple[ConditionSummary, ...] = ()
    rating_condition_comparisons: tuple[ConditionComparison, ...] = ()
    intelligibility_conditions: tuple[ConditionSummary, ...] = ()
    intelligibility_comparisons: tuple[ConditionComparison, ...] = ()


def software_versions() -> dict[str, str]:
    """Return the versions of Python and the libraries the numbers come from."""
    versions = {"python": platform.python_version()}
    for package in SOFTWARE:
        versions[package] = metadata.version(package)
    return versions


def _design(frame: pd.DataFrame) -> dict[str, Any]:
    conditions = sorted((set(frame["condition_a"]) | set(frame["condition_b"])) - {""})
    tested = frame[analysed(frame)]
    return {
        "participants": int(frame["participant"].nunique()),
        "rows": len(frame),
        "rows_by_kind": {k: int(v) for k, v in frame["kind"].value_counts().sort_index().items()},
        "conditions": conditions,
        "condition_keys": condition_keys(frame),
        # Practice and attention-check pages are not the study's items.
        "items": sorted(set(tested["item"]) - {""}),
        "practice_items": sorted(set(frame["item"]) - set(tested["item"]) - {""}),
        "questions": sorted(set(frame.loc[frame["kind"] == "rating", "question"]) - {""}),
        "simulated_conditions": simulated_conditions(frame),
    }


def build_report(
    frame: pd.DataFrame, options: ReportOptions = ReportOptions(), source: str = "responses"
) -> Report:
    """Apply the exclusions, then run the pairwise, rating and intelligibility analyses.

    Conditions are named by their labels where the table has them, and simulated ones
    ``"<name> (simulated)"``, throughout (the table from
    :func:`~analysis.tidy.check_responses` names them so); *options* may list their keys.
    """
    frame = label_simulated(label_conditions(frame))
    if options.conditions:
        options = dataclasses.replace(
            options, conditions=with_simulated_labels(options.conditions, frame)
        )
        check_conditions(frame, options.conditions, source)
    kept, exclusions = apply_exclusions(frame, options.exclusions)
    pairwise = ratings = comparisons = scores = mixed = preferences = None
    across: dict[str, tuple] = {}
    if not kept.empty:
        pairwise = analyze_pairwise(
            kept,
            conditions=options.conditions,
            tie_handling=options.tie_handling,
            correction=options.correction,
            comparative_points=options.comparative_points,
        )
        ratings = summarize_ratings(kept)
        comparisons = compare_ratings(kept, options.correction)
        scores = score_intelligibility(kept, options.fuzzy_scoring)
        for name, long in (
            ("rating", rating_scores(kept)),
            ("intelligibility", accuracy_scores(kept, options.fuzzy_scoring)),
        ):
            across[name] = (
                summarize_conditions(long),
                compare_conditions(long, options.correction),
            )
        preferences = compare_preferences(
            kept, options.conditions, options.comparative_points, options.correction
        )
        if options.mixed_models:
            mixed = fit_mixed_models(
                kept,
                options.conditions,
                ties=options.mixed_ties,
                correction=options.correction,
                comparative_points=options.comparative_points,
            )
    return Report(
        source=source,
        studies=tuple(sorted(set(frame["study"]) - {""})),
        design=_design(kept) if not kept.empty else {"participants": 0, "rows": 0},
        exclusions=exclusions,
        pairwise=pairwise,
        ratings=ratings or (),
        rating_comparisons=comparisons or (),
        intelligibility=scores or (),
        options=options,
        software=software_versions(),
        mixed=mixed,
        quality=summarize_quality(frame),
        comparative=preferences or (),
        rating_conditions=across.get("rating", ((), ()))[0],
        rating_condition_comparisons=across.get("rating", ((), ()))[1],
        intelligibility_conditions=across.get("intelligibility", ((), ()))[0],
        intelligibility_comparisons=across.get("intelligibility", ((), ()))[1],
    )


def _pair_row(pair) -> dict[str, Any]:
    return {
        **({"item": pair.item} if pair.item is not None else {}),
        "a": pair.a,
        "b": pair.b,
        "a_wins": pair.a_wins,
        "b_wins": pair.b_wins,
        "ties": pair.ties,
        "n": pair.nobs,
        "pct_a": None if pair.nobs == 0 else 100 * pair.statistic,
        "p_two_sided": pair.pvalue,
        "p_one_sided_majority": pair.pvalue_one_sided_majority,
        "majority": pair.majority,
        "p_adjusted": pair.pvalue_adjusted,
    }


def results_json(report: Report) -> dict[str, Any]:
    """Render *report* in the documented results.json layout (docs/tidy-format.md)."""
    pairwise = report.pairwise
    correction = report.options.correction
    data: dict[str, Any] = {
        "source": report.source,
        "studies": list(report.studies),
        "design": report.design,
        "exclusions": report.exclusions.to_dict(),
        "options": report.options.to_dict(),
        "software": report.software,
        "pairwise": None,
        "ratings": [r.to_dict() for r in report.ratings],
        "rating_comparisons": [
            {"item": c.item, "question": c.question, **_paired_json(c)}
            for c in report.rating_comparisons
        ],
        "rating_conditions": [s.to_dict() for s in report.rating_conditions],
        "rating_condition_comparisons": [
            {"measure": c.measure, **_paired_json(c)} for c in report.rating_condition_comparisons
        ],
        "intelligibility_conditions": [s.to_dict() for s in report.intelligibility_conditions],
        "intelligibility_comparisons": [
            {"measure": c.measure, **_paired_json(c)} for c in report.intelligibility_comparisons
        ],
        "intelligibility": [s.to_dict() for s in report.intelligibility],
        "comparative": [{**c.to_dict(), "apa": c.apa()} for c in report.comparative],
        "mixed_models": None if report.mixed is None else mixed_json(report.mixed),
        "quality": [q.to_dict() for q in report.quality],
    }
    if pairwise is not None:
        anova = pairwise.rm_anova
        data["pairwise"] = {
            "participants": pairwise.participants,
            "judgements": pairwise.judgements,
            "ties": pairwise.ties,
            "tie_handling": pairwise.tie_handling,
            "correction": correction,
            "notes": list(pairwise.notes),
            "pairs": [_pair_row(p) for p in pairwise.pairs],
            "items": [_pair_row(p) for p in pairwise.items],
            "conditions": [
                {
                    "condition": c.condition,
                    "shown": c.shown,
                    "chosen": c.chosen,
                    "win_rate": c.win_rate,
                    "share": c.share,
                    "mean_participant_rate": c.mean_participant_rate,
                    "sem": c.sem,
                    "n_participants": c.nobs,
                }
                for c in pairwise.conditions
            ],
            "rm_anova": None
            if anova is None
            else {
                "F": anova.statistic,
                "df_num": anova.df_num,
                "df_den": anova.df_den,
                "p": anova.pvalue,
                "p_gg": anova.pvalue_gg,
                "epsilon_gg": anova.epsilon_gg,
                "eta_p2": anova.eta_p2,
                "mauchly_W": anova.mauchly_w,
                "mauchly_p": anova.mauchly_pvalue,
                "n": anova.nobs,
                "apa": anova.apa(),
            },
            "posthoc": [
                {
                    "a": t.a,
                    "b": t.b,
                    "t": t.statistic,
                    "df": t.df,
                    "p": t.pvalue,
                    "p_adjusted": t.pvalue_adjusted,
                    "dz": t.dz,
                    "mean_difference": t.mean_difference,
                    "ci": list(t.ci),
                    "apa": t.apa(),
                }
                for t in pairwise.posthoc
            ],
            "friedman": None if pairwise.friedman is None else pairwise.friedman.to_dict(),
            "wilcoxon": [{**w.to_dict(), "apa": w.apa()} for w in pairwise.wilcoxon],
            "bradley_terry": None
            if pairwise.bradley_terry is None
            else pairwise.bradley_terry.to_dict(),
            "position_bias": None
            if pairwise.position_bias is None
            else {**pairwise.position_bias.to_dict(), "apa": pairwise.position_bias.apa()},
        }
    return plain(data)


def _paired_json(c: PairedComparison) -> dict[str, Any]:
    """Render two conditions' paired t and Wilcoxon tests (rating_comparisons' columns)."""
    return {
        "a": c.a,
        "b": c.b,
        "n": c.nobs,
        "mean_difference": c.ttest.mean_difference,
        "ci": list(c.ttest.ci),
        "t": c.ttest.statistic,
        "df": c.ttest.df,
        "t_p": c.ttest.pvalue,
        "t_p_adjusted": c.ttest.pvalue_adjusted,
        "dz": c.ttest.dz,
        "wilcoxon_W": c.wilcoxon.statistic,
        "wilcoxon_p": c.wilcoxon.pvalue,
        "wilcoxon_p_adjusted": c.wilcoxon.pvalue_adjusted,
        "rank_biserial": c.wilcoxon.rank_biserial,
        "apa": c.apa(),
    }


def _model_json(result) -> dict[str, Any]:
    return {**result.to_dict(), "apa": result.apa(), "summary": result.summary()}


def mixed_json(mixed: MixedModels) -> dict[str, Any]:
    """Render the mixed models with each one's APA string and plain-text summary."""
    pairwise = None
    if mixed.pairwise is not None:
        pairwise = _model_json(mixed.pairwise)
        pairwise["contrasts"] = [{**c.to_dict(), "apa": c.apa()} for c in mixed.pairwise.contrasts]
    ordinal = []
    for model in mixed.ordinal:
        entry = _model_json(model)
        entry["proportional_odds"]["apa"] = model.proportional_odds.apa()
        ordinal.append(entry)
    return {
        "pairwise": pairwise,
        "ordinal": ordinal,
        "linear": [_model_json(model) for model in mixed.linear],
        "skipped": list(mixed.skipped),
    }


def condition_names(report: Report) -> Sequence[str]:
    """Return the conditions of the pairwise analysis in report order."""
    if report.pairwise is None:
        return ()
    return [c.condition for c in report.pairwise.conditions]
