"""Export a study's responses in the tidy format that :mod:`analysis` reads.

One row per participant × trial × question (docs/tidy-format.md). Demographic answers
(choice, number and short-text questions, on whatever page they are asked) become
participant columns; identifying answers (name, e-mail) are never exported. The
``condition_simulated`` column names the row's conditions that are simulated stand-ins,
so an analysis of the CSV alone labels them too; ``condition_a_label`` and
``condition_b_label`` carry the researcher's labels, which reports name conditions by.
The quality columns (:mod:`studyplatform.lib.quality`) say how each page was taken:
its order, times, plays and ends of each clip, errors, viewport and device.
"""

import csv
import io
import re
from collections import defaultdict
from collections.abc import Iterator

from analysis import REQUIRED_COLUMNS
from analysis.tidy import LABEL_COLUMNS, OPTIONAL_COLUMNS, SIGNED_COLUMNS, SOURCE_COLUMNS
from studyplatform.lib.presentation import presented_conditions
from studyplatform.lib.quality import QUALITY_COLUMNS, page_orders, quality_cells, study_quality
from studyplatform.lib.signed import signed_cells
from studyplatform.models import Block, Participant, Question, Response, Stimulus, Study, Trial
from studyplatform.questions import QUESTION_TYPES


def _failed_attention(response: Response, trial: Trial) -> bool:
    expected = trial.expected_answer.strip()
    if not expected:
        return False
    given = response.chosen if response.chosen else str(response.rating)
    return given != expected


def _demographic_questions(study: Study) -> list[Question]:
    """Return the questions whose answers are participant columns, in page order."""
    # Kinds whose answers describe the participant: exported as participant columns.
    attribute_kinds = [kind for kind, type_ in QUESTION_TYPES.items() if type_.export_kind is None]
    return list(
        Question.objects.filter(
            study=study, kind__in=attribute_kinds, trials__isnull=False, is_personal=False
        )
        .distinct()
        .order_by("position", "pk")
    )


def _responses(study: Study) -> list[Response]:
    """Return the study's responses with what a row needs, in participant and page order."""
    return list(
        Response.objects.filter(participant__study=study)
        .select_related(
            "participant",
            "question",
            "trial__block",
            "trial__item",
            "trial__condition_a",
            "trial__condition_b",
        )
        .order_by(
            "participant__started_at", "participant_id", "trial__position", "question__position"
        )
    )


def _participant_answers(responses, questions: list[Question]) -> tuple[dict, set[int]]:
    """Return each participant's demographic answers by question key, and who failed an
    attention check."""
    labels = {
        (option.question_id, option.value): option.label or str(option.value)
        for question in questions
        for option in question.options.all()
    }
    attributes: dict[int, dict[str, str]] = defaultdict(dict)
    failed: set[int] = set()
    keys = {q.pk for q in questions}
    for response in responses:
        if response.question_id in keys:
            question = response.question
            attributes[response.participant_id][question.key] = question.type.export_value(
                question, response, labels
            )
        if response.trial.is_attention_check and _failed_attention(response, response.trial):
            failed.add(response.participant_id)
    return attributes, failed


def tidy_rows(study: Study) -> tuple[list[str], Iterator[dict[str, str]]]:
    """Return the column names and the rows of *study*'s responses in the tidy format."""
    demographic_questions = _demographic_questions(study)
    responses = _responses(study)
    attributes, failed = _participant_answers(responses, demographic_questions)
    attribute_columns = [q.key for q in demographic_questions]
    clash = set(attribute_columns) & {*REQUIRED_COLUMNS, *OPTIONAL_COLUMNS}
    if clash:
        attribute_columns = [f"demo_{k}" if k in clash else k for k in attribute_columns]
    columns = [
        *REQUIRED_COLUMNS,
        "target",
        "scale",
        *LABEL_COLUMNS.values(),
        "condition_simulated",
        *SOURCE_COLUMNS,
        *QUALITY_COLUMNS,
        *SIGNED_COLUMNS,
        *attribute_columns,
    ]
    attribute_pairs = list(
        zip((q.key for q in demographic_questions), attribute_columns, strict=True)
    )
    conditions = {condition.key: condition for condition in study.conditions.all()}
    ready = Stimulus.objects.filter(condition__study=study, status=Stimulus.Status.READY)
    files = {
        (key, item): sha256
        for key, item, sha256 in ready.values_list("condition__key", "item_id", "sha256")
    }
    quality = study_quality(study)
    orders: dict[int, dict[str, str]] = {}  # each participant's schedule, read once

    def rows() -> Iterator[dict[str, str]]:
        for response in responses:
            participant = response.participant
            if response.question.type.export_kind is None:
                continue  # demographic answers are participant columns
            row = _row(study, response, conditions, participant.pk in failed)
            row.update(_source_cells(row, response.trial, conditions, files))
            if participant.pk not in orders:
                orders[participant.pk] = page_orders(participant)
            row.update(
                quality_cells(
                    participant,
                    response.trial,
                    quality.get(participant.pk, {}).get(response.trial.pk),
                    response.rt_ms,
                    response.updated_at,
                    orders[participant.pk],
                    response.answered_client_ms,
                )
            )
            row.update(signed_cells(response))
            answers = attributes.get(participant.pk, {})
            for key, column in attribute_pairs:
                row[column] = answers.get(key, "")
            yield row

    return columns, rows()


def _row(study: Study, response: Response, conditions: dict, failed: bool) -> dict[str, str]:
    """Return the tidy row of one response: its page, clips as shown, answer and flags."""
    question, trial, participant = response.question, response.trial, response.participant
    clip1 = clip2 = label1 = label2 = ""
    if trial.condition_a is not None:
        first, second = presented_conditions(participant, trial, conditions)
        clip1, label1 = (first.key, first.label) if first is not None else ("", "")
        clip2, label2 = (second.key, second.label) if second is not None else ("", "")
    simulated = {key for key, condition in conditions.items() if condition.simulated}
    return {
        "participant": str(participant.pk),
        "study": study.slug,
        "block": trial.block.key,
        "trial": trial.key,
        "item": trial.item.key if trial.item else "",
        "kind": question.type.export_kind,
        "condition_a": clip1,
        "condition_b": clip2,
        "chosen": response.chosen,
        "question": question.key,
        "rating": "" if response.rating is None else str(response.rating),
        "text": response.text,
        "rt_ms": "" if response.rt_ms is None else str(response.rt_ms),
        "flags": ";".join(_flags(participant, trial, failed)),
        "target": trial.item.scoring_target if question.type.is_scored and trial.item else "",
        "scale": question.type.exported_scale,
        "condition_a_label": label1,
        "condition_b_label": label2,
        "condition_simulated": ";".join(
            key for key in dict.fromkeys((clip1, clip2)) if key in simulated
        ),
    }


def _source_cells(row: dict, trial: Trial, conditions: dict, files: dict) -> dict[str, str]:
    """Return where each clip of the row came from and the SHA-256 of its file."""
    cells = {}
    for column, number in (("condition_a", 1), ("condition_b", 2)):
        condition = conditions.get(row[column])
        cells[f"{column}_source"] = condition.source if condition is not None else ""
        cells[f"clip{number}_sha256"] = files.get((row[column], trial.item_id), "")
    return cells


def _flags(participant: Participant, trial: Trial, failed_attention: bool) -> list[str]:
    flags = []
    if participant.is_pilot:
        flags.append("pilot")
    if participant.finished_at is None:
        flags.append("incomplete")
    if failed_attention:
        flags.append("attention_failed")
    if participant.review == Participant.Review.REJECTED:
        flags.append("excluded")
    if trial.block.kind == Block.Kind.PRACTICE:
        flags.append("practice")
    if trial.is_attention_check:
        flags.append("attention_check")
    return flags


# What a spreadsheet reads as a formula when a cell starts with it (OWASP, "CSV
# injection"), and the apostrophe that makes a cell text.
FORMULA_STARTS = ("=", "+", "-", "@", "\t", "\r")
_NUMBER = re.compile(r"[+-]?(\d+(\.\d*)?|\.\d+)([eE][+-]?\d+)?")


def spreadsheet_safe(cell: str) -> str:
    """Return a CSV cell that no spreadsheet runs as a formula.

    A cell starting with ``= + - @``, a tab or a carriage return, unless it is a plain
    number, gets a leading apostrophe, which Excel and LibreOffice read as "text" and do
    not show; so does a cell already starting with one, so that a reader takes exactly
    one off (:func:`analysis.tidy.read_responses` does).
    """
    if cell.startswith("'") or (cell.startswith(FORMULA_STARTS) and not _NUMBER.fullmatch(cell)):
        return "'" + cell
    return cell


def tidy_table(study: Study):
    """Return *study*'s responses as the checked tidy table, or None without responses.

    Raises :class:`analysis.TidyFormatError` naming a problem in the data.
    """
    import pandas as pd

    from analysis import check_responses

    columns, rows = tidy_rows(study)
    frame = pd.DataFrame(list(rows), columns=columns, dtype=str)
    if frame.empty:
        return None
    return check_responses(frame, source=f"{study.slug} responses")


def safe_csv(columns, rows) -> str:
    """Return *rows* (dicts of text) as CSV text whose cells are safe in a spreadsheet."""
    buffer = io.StringIO()
    writer = csv.DictWriter(buffer, fieldnames=columns, lineterminator="\n")
    writer.writeheader()
    writer.writerows({key: spreadsheet_safe(value) for key, value in row.items()} for row in rows)
    return buffer.getvalue()


def tidy_csv(study: Study) -> str:
    """Return *study*'s responses as tidy CSV text, safe to open in a spreadsheet."""
    return safe_csv(*tidy_rows(study))
