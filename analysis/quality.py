"""Summarize how each participant took the pages, from the tidy table's quality columns.

One row per participant over their analysed pages (not practice, not attention checks):
how many pages, the median time on a page, the share of clips played to their end,
replays, playback errors, the pages answered before their clips ended, and the device.
A table without quality columns (data collected elsewhere) has no summary.
"""

import dataclasses

import numpy as np
import pandas as pd

from analysis.results import Result
from analysis.tidy import analysed


@dataclasses.dataclass(frozen=True)
class ParticipantQuality(Result):
    """How one participant took the analysed pages."""

    participant: str
    pages: int
    median_page_s: float
    clips_ended_share: float
    replays: int
    playback_errors: int
    answered_before_end: int
    device: str


def _numbers(frame: pd.DataFrame, column: str) -> pd.Series:
    if column not in frame.columns:
        return pd.Series(np.nan, index=frame.index)
    return pd.to_numeric(frame[column], errors="coerce")


def summarize_quality(frame: pd.DataFrame) -> tuple[ParticipantQuality, ...]:
    """Return one ParticipantQuality per participant, or () without quality columns."""
    if "time_on_page_ms" not in frame.columns:
        return ()
    # One row per page: a page with several questions repeats its quality cells.
    pages = frame[analysed(frame)].drop_duplicates(["participant", "trial"])
    summaries = []
    for participant, rows in pages.groupby("participant", sort=True):
        ended = pd.concat([_numbers(rows, "clip1_ended"), _numbers(rows, "clip2_ended")])
        seconds = _numbers(rows, "time_on_page_ms").dropna() / 1000
        devices = rows["device"][rows["device"].ne("")] if "device" in rows else pd.Series([])
        summaries.append(
            ParticipantQuality(
                participant=str(participant),
                pages=len(rows),
                median_page_s=float(seconds.median()) if len(seconds) else float("nan"),
                clips_ended_share=float(ended.mean()) if ended.notna().any() else float("nan"),
                replays=int(_numbers(rows, "replays").fillna(0).sum()),
                playback_errors=int(_numbers(rows, "playback_errors").fillna(0).sum()),
                answered_before_end=int(_numbers(rows, "answered_before_end").eq(1).sum()),
                device=str(devices.iloc[0]) if len(devices) else "",
            )
        )
    return tuple(summaries)
