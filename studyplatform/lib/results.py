"""Analyse a study's collected responses with :mod:`analysis`, for the admin's results page."""

import base64
import io
import json
import tempfile
import zipfile
from dataclasses import dataclass
from pathlib import Path

import pandas as pd
from django.db.models import Count

from analysis import (
    Report,
    ReportOptions,
    apply_exclusions,
    build_report,
    write_report,
)
from analysis.figures import all_figures
from studyplatform.lib.exchange import export_study
from studyplatform.lib.export import safe_csv, tidy_csv, tidy_table
from studyplatform.lib.quality import (
    EVENT_COLUMNS,
    PARTICIPANT_COLUMNS,
    media_event_rows,
    participant_rows,
)
from studyplatform.lib.signed import signed_videos
from studyplatform.models import Study
from studyplatform.rules import describe_condition


@dataclass(frozen=True)
class StudyResults:
    """A study's report and the table it was computed from (after exclusions)."""

    report: Report | None
    analysed: pd.DataFrame | None


def analyse_study(study: Study, options: ReportOptions) -> StudyResults:
    """Export *study*'s responses and run the report; report is None without responses."""
    table = tidy_table(study)
    if table is None:
        return StudyResults(report=None, analysed=None)
    # How each condition was made (techniques, settings, a model's training) for the
    # report's Method: the tidy table carries only the conditions' names.
    methods = {c.key: describe_condition(c) for c in study.conditions.all()}
    # Who started, consented and finished, from the participant records: the table has
    # no row for a participant who left before answering anything.
    participants = study.participants.aggregate(
        started=Count("pk"), consented=Count("consented_at"), finished=Count("finished_at")
    )
    report = build_report(
        table,
        options,
        f"{study.slug} (SignStudy export)",
        methods,
        title=study.title,
        participants=participants,
    )
    analysed, _ = apply_exclusions(table, options.exclusions)
    return StudyResults(report=report, analysed=analysed)


def figure_images(results: StudyResults) -> dict[str, str]:
    """Draw the report's figures and return them as PNG data URIs, by name."""
    if results.report is None:
        return {}
    images = {}
    with tempfile.TemporaryDirectory() as folder:
        out = Path(folder)
        names = all_figures(results.report, results.analysed, out, formats=("png",))
        for name in names:
            encoded = base64.b64encode((out / name).read_bytes()).decode("ascii")
            images[name.removesuffix(".png")] = f"data:image/png;base64,{encoded}"
    return images


def report_archive(
    study: Study, results: StudyResults, *, everything: bool, videos: bool = True
) -> bytes:
    """Zip the report files; with *everything*, add the data, the media events, each
    participant's seed and schedule, the study definition and, with *videos*, the
    signed answers (signed_answers/<sha256>.<ext>, named so in the CSV)."""
    buffer = io.BytesIO()
    with (
        tempfile.TemporaryDirectory() as folder,
        zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as archive,
    ):
        if results.report is not None:
            out = Path(folder) / "report"
            for name in write_report(results.report, results.analysed, out):
                archive.write(out / name, f"report/{name}")
        if everything:
            archive.writestr("responses.csv", tidy_csv(study))
            archive.writestr("media_events.csv", safe_csv(EVENT_COLUMNS, media_event_rows(study)))
            archive.writestr(
                "participants.csv", safe_csv(PARTICIPANT_COLUMNS, participant_rows(study))
            )
            archive.writestr(
                f"{study.slug}.study.json",
                json.dumps(export_study(study), indent=2, ensure_ascii=False) + "\n",
            )
            if videos:
                for video in signed_videos(study):
                    # Videos are compressed already: stored, not deflated again.
                    archive.write(video.path, video.archive_name, zipfile.ZIP_STORED)
    return buffer.getvalue()
