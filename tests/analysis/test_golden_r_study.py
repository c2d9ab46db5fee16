"""Golden end-to-end test: a study simulated in R, analysed by the report, every number R's.

Reference: tests/analysis/reference/study_r.R (R 4.2.2, lme4 1.1-31, lmerTest 3.1-3,
ordinal 2022.11-16) simulated the study (study_r.csv: 16 participants, three conditions,
six phrases; pairwise judgements with ties, 1–5 ratings, typed answers) and computed every
number the report writes to results.json for its pairwise, rating, intelligibility and
mixed-model sections (study_r.json): binom.test, Holm, anova.mlm with Mauchly's test and
both sphericity corrections, aov's η²p, paired t.test with d_z's noncentral-t CI,
wilcox.test's defaults, friedman.test, glm, glmer (tolPwrss = 1e-13), clmm with
nominal_test, lmerTest's lmer, contest and anova with profile CIs. R is not a dependency:
the script and its outputs are committed. Tolerance, the issue's (56): 1e-4 relative;
1e-3 for what rests on a Laplace fit's standard errors and for profile limits.
"""

import json
import math
from pathlib import Path

import pytest

from analysis import ReportOptions, build_report, read_responses, results_json

REFERENCE = Path(__file__).parent / "reference"
R = json.loads((REFERENCE / "study_r.json").read_text())
# The fields that name a list entry (a condition, a pair, an item, a question).
IDENTITY = ("question", "measure", "item", "condition", "a", "b", "name")
SECTIONS = tuple(key for key in R if key != "software")
# Fields of the Laplace fits (Bradley–Terry, ordinal) that rest on their standard errors.
FROM_LAPLACE_SES = {"se", "statistic", "pvalue", "pvalue_adjusted", "ci"}


@pytest.fixture(scope="module")
def ours() -> dict:
    frame = read_responses(REFERENCE / "study_r.csv")
    report = build_report(frame, ReportOptions(mixed_models=True), source="study_r.csv")
    return json.loads(json.dumps(results_json(report)))


def _identity(entry: dict) -> tuple:
    return tuple((key, entry[key]) for key in IDENTITY if isinstance(entry.get(key), str))


def _walk(mine, theirs, path: str):
    """Yield (path, ours, R's) for every number of R's, ours found by the same path."""
    if isinstance(theirs, dict):
        for key, value in theirs.items():
            if not isinstance(value, str):
                yield from _walk(
                    mine.get(key) if isinstance(mine, dict) else None, value, f"{path}.{key}"
                )
    elif isinstance(theirs, list) and theirs and isinstance(theirs[0], dict):
        for entry in theirs:
            name = _identity(entry)
            found = [m for m in mine or [] if _identity(m)[: len(name)] == name]
            label = ",".join(str(value) for _, value in name)
            yield from _walk(found[0] if len(found) == 1 else None, entry, f"{path}[{label}]")
    elif isinstance(theirs, list):
        mine = mine if isinstance(mine, list) and len(mine) == len(theirs) else [None] * len(theirs)
        for index, (a, b) in enumerate(zip(mine, theirs, strict=True)):
            yield from _walk(a, b, f"{path}[{index}]")
    else:
        yield path, mine, theirs


def _tolerance(path: str) -> float:
    laplace = path.startswith((".mixed_models.pairwise", ".mixed_models.ordinal"))
    field = path.split(".")[-1].split("[")[0]
    profile = path.startswith(".mixed_models.linear") and "ci" in field
    return 1e-3 if (laplace and field in FROM_LAPLACE_SES) or profile else 1e-4


def _numbers(value, path: str = ""):
    """Yield the path of every number in *value* (lists of entries by their identity)."""
    if isinstance(value, dict):
        for key, inner in value.items():
            yield from _numbers(inner, f"{path}.{key}")
    elif isinstance(value, list):
        for index, inner in enumerate(value):
            if isinstance(inner, dict):
                label = ",".join(str(v) for _, v in _identity(inner))
                yield from _numbers(inner, f"{path}[{label}]")
            else:
                yield from _numbers(inner, f"{path}[{index}]")
    elif isinstance(value, int | float) and not isinstance(value, bool):
        yield path


def _differing(compared) -> list[tuple[str, object, object]]:
    return [
        (path, mine, theirs)
        for path, mine, theirs in compared
        if not isinstance(mine, int | float)
        or not math.isclose(mine, theirs, rel_tol=_tolerance(path), abs_tol=1e-12)
    ]


def test_every_number_of_the_report_is_rs(ours):
    compared = [
        c for section in SECTIONS for c in _walk(ours.get(section), R[section], f".{section}")
    ]
    assert len(compared) > 1100
    assert _differing(compared) == []


def test_no_number_of_the_report_goes_unchecked(ours):
    compared = {
        c[0] for section in SECTIONS for c in _walk(ours.get(section), R[section], f".{section}")
    }
    printed = {path for section in SECTIONS for path in _numbers(ours[section], f".{section}")}
    assert sorted(printed - compared) == []
