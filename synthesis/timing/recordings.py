"""Recordings of fingerspelled words: retime them onto a model's timing, train on them,
and compare whole-word durations (seed 000 §4.3, Table 4.3).

The Motion capture condition is the recording itself; the other conditions are the same
recording time-warped so that its holds and transitions land on the predicted timing:
natural poses, new rhythm.
"""

from dataclasses import dataclass, field, replace
from functools import cached_property
from pathlib import Path

import numpy as np

from synthesis.fingerspelling.spelling import LEAD_MS, hold_times_s
from synthesis.fingerspelling.word_timing import TimingError, WordTiming
from synthesis.skeleton.bvh import read_bvh
from synthesis.skeleton.motion import Motion
from synthesis.skeleton.retime import piecewise_linear_warp, time_warp
from synthesis.timing.constant import constant_timing, normalized_constant_timing
from synthesis.timing.extraction import Extraction, extract
from synthesis.timing.simulate import simulate_recording
from synthesis.timing.training import Annotation, train
from synthesis.timing.variable import VariableModel


@dataclass(frozen=True)
class Recording:
    """A recorded word: the motion, its letters and what extraction finds in it.

    *known* holds the holds when they are known (a simulation's own); otherwise they
    are extracted on first use, so a recording played as performed never needs them.
    """

    word: str
    motion: Motion
    side: str = "right"
    known: Extraction | None = field(default=None, repr=False)

    @cached_property
    def extraction(self) -> Extraction:
        """Return the holds and transitions found in the motion (seed 000 §4.2).

        Raise ExtractionError when the hand's poses do not show the word's letters.
        """
        if self.known is not None:
            return self.known
        return extract(self.motion, self.word, self.side)

    @classmethod
    def read(cls, path: str | Path, word: str | None = None, side: str = "right") -> "Recording":
        """Read a BVH or .pose recording; the word defaults to the file name's letters.

        A .pose file (captured landmarks) is fitted to the hand model first
        (synthesis.capture); the signer's *side* hand is the one read.
        """
        path = Path(path)
        word = (word or "".join(c for c in path.stem if c.isalpha())).upper()
        if not word:
            raise TimingError(f"{path}: give the word it spells (its name has no letters).")
        if path.suffix.lower() == ".pose":
            from synthesis.capture import captured_hand, read_pose

            motion = captured_hand(read_pose(path), side).motion
        else:
            motion = read_bvh(path)
        return cls.from_motion(motion, word, side)

    @classmethod
    def from_motion(cls, motion: Motion, word: str, side: str = "right") -> "Recording":
        """Return *motion* as a recording of *word* (its holds are extracted when needed)."""
        return cls(word.upper(), motion, side)

    @classmethod
    def simulate(
        cls,
        word: str,
        seed: int,
        model: VariableModel | None = None,
        side: str = "right",
        rate_hz: float = 60.0,
    ) -> "Recording":
        """Return a simulated capture of *word*: the stand-in for the Motion capture
        condition when no recording exists, labelled so in its timing's metadata.

        Its holds are the simulation's own (known exactly), not extracted.
        """
        motion, truth = simulate_recording(word, np.random.default_rng(seed), model, side, rate_hz)
        metadata = {"rate_hz": rate_hz, "simulated": True, "seed": seed}
        timing = replace(truth, metadata=metadata)
        bounds = hold_times_s(timing, LEAD_MS)
        empty = np.zeros((0,))
        return cls(truth.word, motion, side, Extraction(timing, bounds, empty, empty))

    def hold_times_s(self) -> np.ndarray:
        """Return each hold's (start, end) in seconds, shape (n_letters, 2), sub-frame."""
        return np.asarray(self.extraction.hold_bounds_s, dtype=float)


def retime(recording: Recording, timing: WordTiming) -> Motion:
    """Return the recording time-warped so that its holds follow *timing*.

    The lead-in before the first hold and the lead-out after the last keep their
    recorded length; everything between moves linearly from key to key.
    """
    if timing.letters != recording.extraction.timing.letters:
        raise TimingError(f"The timing is for {timing.word}, not {recording.word}.")
    holds = recording.hold_times_s()
    end_s = recording.motion.duration_s
    source = [0.0]
    target = [0.0]
    start = holds[0, 0]
    new_starts = start + timing.hold_starts_ms() / 1000
    for k in range(len(holds)):
        source += [holds[k, 0], holds[k, 1]]
        target += [new_starts[k], new_starts[k] + timing.hold_ms[k] / 1000]
    source.append(end_s)
    target.append(target[-1] + max(end_s - holds[-1, 1], 0.0))
    kept = [(target[0], source[0])]
    for key in zip(target[1:], source[1:], strict=True):
        # Keys that coincide (a hold that starts the clip) would make the warp ill-posed.
        if key[0] > kept[-1][0] and key[1] >= kept[-1][1]:
            kept.append(key)
    warp = piecewise_linear_warp([k[0] for k in kept], [k[1] for k in kept])
    return time_warp(recording.motion, warp, kept[-1][0])


# The timing models a word is retimed under (Table 4.3's columns), named as the timing
# technique names them; the technique adds the recording itself and equal holds.
MODEL_TIMINGS = ("variable", "constant", "normalized")


def condition_timings(word: str, model: VariableModel) -> dict[str, WordTiming]:
    """Return the Variable, Constant and Normalized constant timings of *word*, in
    :data:`MODEL_TIMINGS` order."""
    variable = model.timing(word)
    return {
        "variable": variable,
        "constant": constant_timing(word),
        "normalized": normalized_constant_timing(word, variable),
    }


def annotations(recordings: list[Recording]) -> tuple[list[Annotation], list[Annotation]]:
    """Return the holds and transitions extracted from recordings, as training data."""
    holds, transitions = [], []
    for recording in recordings:
        timing = recording.extraction.timing
        holds += [Annotation(recording.word, k, v) for k, v in enumerate(timing.hold_ms)]
        transitions += [
            Annotation(recording.word, k, v) for k, v in enumerate(timing.transition_ms)
        ]
    return holds, transitions


def train_on_recordings(recordings: list[Recording], metric: str = "rmsd", space: str = "joints"):
    """Train a Variable model on the holds and transitions found in recordings."""
    holds, transitions = annotations(recordings)
    words = ", ".join(sorted({r.word for r in recordings}))
    source = f"{len(recordings)} recordings: {words}"
    return train(holds, transitions, metric, source=source, space=space)


def duration_table(recordings: list[Recording], model: VariableModel) -> list[dict]:
    """Return, per recording, the whole-word duration of mocap and each model (ms), and
    each model's error against the recording (seed 000 Table 4.3); a final mean row."""
    rows = []
    for recording in recordings:
        mocap = recording.extraction.timing.total_ms
        row = {"word": recording.word, "mocap_ms": mocap}
        for name, timing in condition_timings(recording.word, model).items():
            row[f"{name}_ms"] = timing.total_ms
            row[f"{name}_error_ms"] = timing.total_ms - mocap
        rows.append(row)
    if rows:
        mean = {"word": "mean |error|", "mocap_ms": float(np.mean([r["mocap_ms"] for r in rows]))}
        for name in MODEL_TIMINGS:
            mean[f"{name}_ms"] = float(np.mean([r[f"{name}_ms"] for r in rows]))
            mean[f"{name}_error_ms"] = float(np.mean([abs(r[f"{name}_error_ms"]) for r in rows]))
        rows.append(mean)
    return rows


def format_table(rows: list[dict]) -> str:
    """Return the duration table as Markdown."""
    names = MODEL_TIMINGS
    header = "| word | mocap (ms) | " + " | ".join(f"{n} (ms) | {n} error" for n in names) + " |"
    lines = [header, "|" + "---|" * (2 + 2 * len(names))]
    for row in rows:
        cells = [row["word"], f"{row['mocap_ms']:.1f}"]
        for name in names:
            cells += [f"{row[f'{name}_ms']:.1f}", f"{row[f'{name}_error_ms']:+.1f}"]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)
