"""The transition database: every recorded transition, fitted and described (seed 001 §3.3–3.5).

Each entry is one arm's transition: its seven curves from the first sign's last frame
to the second sign's first, normalized (time and value to [0, 1], with each curve's
minimum and ΔY kept) and fitted as concatenated Hermite segments (App. A.1) and as a
smoothing B-spline (``scipy.interpolate.make_splrep``, App. A.2), its 42-number DCT-II
descriptor of the ten frames either side, and the recorded values and sign context the
evaluation needs. The file is versioned JSON (:data:`FORMAT`), readable by eye.
"""

import json
from collections.abc import Iterable
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path

import numpy as np
from scipy.interpolate import BSpline, make_splrep

from synthesis.formats import check_header
from synthesis.transitions.curves import ARM_CURVES, SIDES
from synthesis.transitions.descriptor import DESCRIPTOR_FRAMES, gap_descriptor
from synthesis.transitions.hermite_fit import HermiteCurve, fit_hermite
from synthesis.transitions.recording import CutTransition, SegmentedRecording, cut_transitions
from synthesis.transitions.skew import basis_peaks

FORMAT = "signstudy.transition-database"
FORMAT_VERSION = 1
# The B-spline's smoothing: the residual allowed per sample, in normalized units.
SPLINE_TOLERANCE = 0.01


class DatabaseError(ValueError):
    """A transition database file that cannot be read."""


@dataclass(frozen=True, eq=False)
class StoredCurve:
    """One curve of a stored transition: normalized fits plus its minimum and ΔY (rad)."""

    minimum_rad: float
    delta_rad: float
    hermite: HermiteCurve
    spline: BSpline

    @cached_property
    def spline_peaks(self) -> np.ndarray:
        """Return where the spline's basis functions peak (Eq. 3.11), computed once."""
        return basis_peaks(self.spline.t, self.spline.k)

    def to_dict(self) -> dict:
        count = len(self.spline.t) - self.spline.k - 1
        return {
            "min_rad": round(self.minimum_rad, 7),
            "delta_rad": round(self.delta_rad, 7),
            "hermite": self.hermite.to_dict(),
            "spline": {
                "k": int(self.spline.k),
                "t": _rounded(self.spline.t),
                "c": _rounded(self.spline.c[:count]),
            },
        }

    @classmethod
    def from_dict(cls, data: dict) -> "StoredCurve":
        spline = data["spline"]
        return cls(
            float(data["min_rad"]),
            float(data["delta_rad"]),
            HermiteCurve.from_dict(data["hermite"]),
            BSpline(np.array(spline["t"], float), np.array(spline["c"], float), int(spline["k"])),
        )


@dataclass(frozen=True, eq=False)
class TransitionEntry:
    """One arm's recorded transition: its fits, descriptor and context.

    *descriptor* (42,); *curves* the seven :class:`StoredCurve`; *before*/*after* the
    ten frames of the signs either side and *values* the recorded span from the first
    sign's last frame to the second's first (n + 2, 7), radians.
    """

    id: str
    recording: str
    signer: str
    side: str
    labels: tuple[str, str]
    rate_hz: float
    descriptor: np.ndarray
    curves: tuple[StoredCurve, ...]
    before: np.ndarray
    after: np.ndarray
    values: np.ndarray
    simulated: bool = False

    @property
    def gap_frames(self) -> int:
        """Return the number of frames strictly between the two signs."""
        return len(self.values) - 2

    def to_dict(self) -> dict:
        return {
            "id": self.id,
            "recording": self.recording,
            "signer": self.signer,
            "side": self.side,
            "labels": list(self.labels),
            "rate_hz": self.rate_hz,
            "simulated": self.simulated,
            "descriptor": _rounded(self.descriptor),
            "curves": dict(zip(ARM_CURVES, (c.to_dict() for c in self.curves), strict=True)),
            "before_rad": _rows(self.before),
            "after_rad": _rows(self.after),
            "values_rad": _rows(self.values),
        }

    @classmethod
    def from_dict(cls, data: dict) -> "TransitionEntry":
        """Return the entry :meth:`to_dict` wrote; raise ValueError when a part is malformed."""
        entry = cls(
            str(data["id"]),
            str(data["recording"]),
            str(data["signer"]),
            str(data["side"]),
            tuple(data["labels"]),
            float(data["rate_hz"]),
            np.array(data["descriptor"], float),
            tuple(StoredCurve.from_dict(data["curves"][c]) for c in ARM_CURVES),
            np.array(data["before_rad"], float),
            np.array(data["after_rad"], float),
            np.array(data["values_rad"], float),
            bool(data["simulated"]),
        )
        curves = len(ARM_CURVES)
        if entry.side not in SIDES or len(entry.labels) != 2 or not entry.rate_hz > 0:
            raise ValueError("side, labels or rate_hz is not what a transition has")
        if entry.descriptor.shape != (6 * curves,):
            raise ValueError(f"the descriptor holds {6 * curves} numbers")
        context = (entry.before, entry.after)
        if any(a.ndim != 2 or a.shape[1] != curves or len(a) < 5 for a in context):
            raise ValueError(f"before_rad and after_rad are at least 5 rows of {curves} angles")
        if entry.values.ndim != 2 or entry.values.shape[1] != curves or len(entry.values) < 3:
            raise ValueError(f"values_rad is at least 3 rows of {curves} angles")
        arrays = (entry.descriptor, *context, entry.values)
        if not all(np.all(np.isfinite(a)) for a in arrays):
            raise ValueError("the entry holds non-finite numbers")
        return entry


def _rounded(values) -> list[float]:
    return [round(float(v), 7) for v in np.ravel(values)]


def _rows(values: np.ndarray) -> list[list[float]]:
    return [_rounded(row) for row in values]


def fit_curve(values: np.ndarray) -> StoredCurve:
    """Return one curve over a transition's span, normalized and fitted both ways."""
    values = np.asarray(values, dtype=float)
    minimum, delta = float(values.min()), float(np.ptp(values))
    y = (values - minimum) / delta if delta > 1e-12 else np.zeros_like(values)
    x = np.linspace(0.0, 1.0, len(y))
    hermite = fit_hermite(y)
    # Hermite fits in frames; stored in normalized time like the spline.
    scale = np.array([1.0 / (len(y) - 1), 1.0])
    hermite = HermiteCurve(hermite.points * scale, hermite.t0 * scale, hermite.t1 * scale)
    spline = make_splrep(x, y, k=3, s=len(y) * SPLINE_TOLERANCE**2)
    return StoredCurve(minimum, delta, hermite, spline)


def entry_from_cut(cut: CutTransition) -> TransitionEntry:
    """Return the database entry of one cut transition."""
    span = np.vstack([cut.before[-1:], cut.gap, cut.after[:1]])
    return TransitionEntry(
        cut.id,
        cut.recording,
        cut.signer,
        cut.side,
        tuple(str(x) for x in cut.labels),
        cut.rate_hz,
        gap_descriptor(cut.before, cut.after),
        tuple(fit_curve(span[:, c]) for c in range(span.shape[1])),
        cut.before[-DESCRIPTOR_FRAMES:],
        cut.after[:DESCRIPTOR_FRAMES],
        span,
        cut.simulated,
    )


@dataclass(frozen=True, eq=False)
class TransitionDatabase:
    """The stored transitions, with what they were built from (*sources*)."""

    entries: tuple[TransitionEntry, ...]
    sources: tuple[str, ...] = ()

    @property
    def simulated(self) -> bool:
        """Return whether any entry comes from a simulated capture."""
        return any(e.simulated for e in self.entries)

    def descriptors(self) -> np.ndarray:
        """Return every entry's descriptor (n_entries, 42)."""
        return np.stack([e.descriptor for e in self.entries])

    def to_json(self) -> str:
        return (
            json.dumps(
                {
                    "format": FORMAT,
                    "version": FORMAT_VERSION,
                    "simulated": self.simulated,
                    "sources": list(self.sources),
                    "curves": list(ARM_CURVES),
                    "entries": [e.to_dict() for e in self.entries],
                },
                indent=1,
            )
            + "\n"
        )

    def write(self, path: str | Path) -> Path:
        path = Path(path)
        path.write_text(self.to_json(), "utf-8")
        return path

    @classmethod
    def from_json(cls, text: str, source: str = "<database>") -> "TransitionDatabase":
        """Return the database in *text*; raise :class:`DatabaseError` naming the problem."""
        try:
            data = json.loads(text)
        except json.JSONDecodeError as error:
            raise DatabaseError(f"{source}: not JSON ({error.msg}, line {error.lineno}).") from None
        check_header(data, FORMAT, FORMAT_VERSION, "transition database", DatabaseError, source)
        entries = []
        for number, raw in enumerate(data.get("entries") or [], 1):
            try:
                entries.append(TransitionEntry.from_dict(raw))
            except (KeyError, TypeError, ValueError, IndexError, AttributeError) as error:
                raise DatabaseError(f"{source}: entry {number} is malformed ({error!r}).") from None
        if not entries:
            raise DatabaseError(f"{source}: the database has no transitions.")
        return cls(tuple(entries), tuple(data.get("sources") or ()))

    @classmethod
    def read(cls, path: str | Path) -> "TransitionDatabase":
        path = Path(path)
        try:
            text = path.read_text("utf-8")
        except (OSError, UnicodeDecodeError) as error:
            raise DatabaseError(f"{path}: cannot be read ({error}).") from None
        return cls.from_json(text, str(path))


def build_database(
    recordings: Iterable[SegmentedRecording],
    min_range_deg: float = 5.0,
    sources: tuple[str, ...] = (),
) -> TransitionDatabase:
    """Return the database of every moving arm's transition in *recordings*."""
    recordings = list(recordings)
    entries = tuple(
        entry_from_cut(cut)
        for recording in recordings
        for cut in cut_transitions(recording, min_range_deg)
    )
    if not entries:
        raise DatabaseError(
            "The recordings hold no transition with signs of at least "
            f"{DESCRIPTOR_FRAMES} frames either side."
        )
    return TransitionDatabase(entries, sources or tuple(r.name for r in recordings))
