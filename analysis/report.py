"""Run every analysis on a tidy table and collect the results in one Report object."""

import dataclasses
import platform
from collections.abc import Mapping, Sequence
from importlib import metadata
from typing import Any

import pandas as pd

from analysis.comparative import compare_preferences
from analysis.conditions import compare_conditions, summarize_conditions
from analysis.exclusions import ExclusionRules, apply_exclusions
from analysis.flow import ParticipantFlow, participant_flow
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
    rendered,
)
from analysis.summaries import (
    ConditionComparison,
    ConditionSummary,
    IntelligibilityScore,
    RatingComparison,
    RatingSummary,
)
from analysis.tidy import (
    SIMULATED_SUFFIX,
    analysed,
    check_conditions,
    condition_keys,
    label_conditions,
    label_simulated,
    simulated_conditions,
    uploaded_conditions,
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
    # The study's title as its researchers wrote it ("" names the report by its studies).
    title: str = ""
    # Every participant accounted for: started, consented, finished, excluded, analysed.
    flow: ParticipantFlow | None = None
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
        "uploaded_conditions": uploaded_conditions(frame),
    }


def _methods(design: dict[str, Any], methods: Mapping[str, str]) -> dict[str, str]:
    """Return, per condition name of *design*, how it was made (*methods* by key)."""
    keys = design.get("condition_keys", {})
    found = {}
    for name in design.get("conditions", ()):
        key = keys.get(name, name.removesuffix(SIMULATED_SUFFIX))
        if key in methods:
            found[name] = methods[key]
    return found


def build_report(
    frame: pd.DataFrame,
    options: ReportOptions = ReportOptions(),
    source: str = "responses",
    methods: Mapping[str, str] | None = None,
    title: str = "",
    participants: Mapping[str, int] | None = None,
) -> Report:
    """Apply the exclusions, then run the pairwise, rating and intelligibility analyses.

    Conditions are named by their labels where the table has them, and simulated ones
    ``"<name> (simulated)"``, throughout (the table from
    :func:`~analysis.tidy.check_responses` names them so); *options* may list their keys.
    *methods* says how each condition (by key) was made, in words, for the Method
    section: the techniques and their settings, which the table itself does not carry.
    *title* heads the report (the study's own title; the table carries only its slug).
    *participants* are the study's own counts of participants who ``started``,
    ``consented`` and ``finished`` (the table lacks those who answered nothing), for the
    participant flow.
    """
    frame = label_simulated(label_conditions(frame))
    if options.conditions:
        conditions = with_simulated_labels(options.conditions, frame)
        options = dataclasses.replace(options, conditions=conditions)
        check_conditions(frame, conditions, source)
    kept, exclusions = apply_exclusions(frame, options.exclusions)
    design: dict[str, Any] = _design(kept) if not kept.empty else {"participants": 0, "rows": 0}
    if methods:
        design["condition_methods"] = _methods(design, methods)
    return Report(
        source=source,
        title=title,
        flow=participant_flow(frame, exclusions, participants),
        studies=tuple(sorted(set(frame["study"]) - {""})),
        design=design,
        exclusions=exclusions,
        options=options,
        software=software_versions(),
        quality=summarize_quality(frame),
        **(_analyses(kept, options) if not kept.empty else _NO_ANALYSES),
    )


# The Report's fields when every participant was excluded.
_NO_ANALYSES: dict[str, Any] = {
    "pairwise": None,
    "ratings": (),
    "rating_comparisons": (),
    "intelligibility": (),
}


def _analyses(kept: pd.DataFrame, options: ReportOptions) -> dict[str, Any]:
    """Run every analysis on the rows kept; return the Report's fields they fill."""
    found: dict[str, Any] = {
        "pairwise": analyze_pairwise(
            kept,
            conditions=options.conditions,
            tie_handling=options.tie_handling,
            correction=options.correction,
            comparative_points=options.comparative_points,
        ),
        "ratings": summarize_ratings(kept),
        "rating_comparisons": compare_ratings(kept, options.correction),
        "intelligibility": score_intelligibility(kept, options.fuzzy_scoring),
        "comparative": compare_preferences(
            kept, options.conditions, options.comparative_points, options.correction
        ),
    }
    for conditions, comparisons, long in (
        ("rating_conditions", "rating_condition_comparisons", rating_scores(kept)),
        (
            "intelligibility_conditions",
            "intelligibility_comparisons",
            accuracy_scores(kept, options.fuzzy_scoring),
        ),
    ):
        found[conditions] = summarize_conditions(long)
        found[comparisons] = compare_conditions(long, options.correction)
    if options.mixed_models:
        found["mixed"] = fit_mixed_models(
            kept,
            options.conditions,
            ties=options.mixed_ties,
            correction=options.correction,
            comparative_points=options.comparative_points,
        )
    # A summary that found nothing to summarise is an empty tuple in the Report.
    for name in ("ratings", "rating_comparisons", "intelligibility", "comparative"):
        found[name] = found[name] or ()
    return found


def results_json(report: Report) -> dict[str, Any]:
    """Render *report* as results.json (docs/tidy-format.md): every result in its own
    vocabulary (``statistic``, ``pvalue``, ``nobs``…), with its APA sentence."""
    return {
        "source": report.source,
        "title": report.title,
        "participant_flow": rendered(report.flow),
        "studies": list(report.studies),
        "design": plain(report.design),
        "exclusions": report.exclusions.to_dict(),
        "options": report.options.to_dict(),
        "software": report.software,
        "pairwise": rendered(report.pairwise),
        "ratings": rendered(report.ratings),
        "rating_comparisons": rendered(report.rating_comparisons),
        "rating_conditions": rendered(report.rating_conditions),
        "rating_condition_comparisons": rendered(report.rating_condition_comparisons),
        "intelligibility_conditions": rendered(report.intelligibility_conditions),
        "intelligibility_comparisons": rendered(report.intelligibility_comparisons),
        "intelligibility": rendered(report.intelligibility),
        "comparative": rendered(report.comparative),
        "mixed_models": rendered(report.mixed),
        "quality": rendered(report.quality),
    }


def condition_names(report: Report) -> Sequence[str]:
    """Return the conditions of the pairwise analysis in report order."""
    if report.pairwise is None:
        return ()
    return [c.condition for c in report.pairwise.conditions]
