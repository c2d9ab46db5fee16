"""Score handshapes against real signers': which letter each is taken for, and a table.

The benchmark of issue 16: each candidate handshape (our alphabet's letter, seen as the
human recording of that letter sees its hand) is classified by orientation-free
features (:mod:`synthesis.capture.features`) as the nearest of the human letters. A
letter agrees when it is taken for itself or for its look-alike (G/Q, K/P, H/U, I/J:
one handshape, told apart by orientation or movement). The fist letters
A, E, M, N, S, T and X are the ones signers find hard to tell apart on an avatar; the
score counts how many are taken for another fist letter.
"""

from dataclasses import dataclass

import numpy as np

from synthesis.capture.features import handshape_features, nearest_handshape
from synthesis.capture.handfit import FIXED, calibrate_scale, fit_hand
from synthesis.rigs.hand import HandModel
from synthesis.rigs.landmarks import landmarks

LOOK_ALIKES = (frozenset("GQ"), frozenset("KP"), frozenset("HU"), frozenset("IJ"))
FIST_LETTERS = frozenset("AEMNSTX")


def same_handshape(a: str, b: str) -> bool:
    """Return whether letters *a* and *b* are one handshape (equal, or look-alikes)."""
    return a == b or any({a, b} <= pair for pair in LOOK_ALIKES)


@dataclass(frozen=True)
class HandshapeScore:
    """Which reference each candidate was taken for, and what that adds up to.

    *taken* maps each candidate letter to the reference letter nearest to it.
    """

    taken: dict[str, str]

    @property
    def agreeing(self) -> tuple[str, ...]:
        """Return the letters taken for themselves or their look-alike."""
        return tuple(k for k, v in self.taken.items() if same_handshape(k, v))

    @property
    def nobs(self) -> int:
        return len(self.taken)

    @property
    def fist_confusions(self) -> tuple[tuple[str, str], ...]:
        """Return (letter, taken for) of fist letters taken for another fist letter."""
        return tuple(
            (k, v)
            for k, v in self.taken.items()
            if k in FIST_LETTERS and v in FIST_LETTERS and k != v
        )

    def confusions(self) -> dict[str, list[str]]:
        """Return, per reference letter, the candidates wrongly taken for it (the table)."""
        table: dict[str, list[str]] = {}
        for k, v in self.taken.items():
            if not same_handshape(k, v):
                table.setdefault(v, []).append(k)
        return dict(sorted(table.items()))

    def to_dict(self) -> dict:
        return {
            "nobs": self.nobs,
            "agreeing": len(self.agreeing),
            "taken": dict(self.taken),
            "fist_confusions": [list(pair) for pair in self.fist_confusions],
            "confusions": self.confusions(),
        }

    def summary(self) -> str:
        """Return one line: "14 of 26 letters agree (look-alikes as one); fist …"."""
        fists = ", ".join(f"{k} as {v}" for k, v in self.fist_confusions) or "none"
        return (
            f"{len(self.agreeing)} of {self.nobs} letters agree with the human ones "
            f"(look-alikes as one); fist letters taken for another fist letter: "
            f"{len(self.fist_confusions)} ({fists})"
        )


def score_handshapes(
    candidates: dict[str, np.ndarray], references: dict[str, np.ndarray]
) -> HandshapeScore:
    """Classify each candidate's features (30,) among *references*' (letter → features)."""
    return HandshapeScore({k: nearest_handshape(v, references) for k, v in candidates.items()})


@dataclass(frozen=True)
class LetterView:
    """How a recording shows its letter: the middle frame's features (30,), in the image
    plane, the hand's orientation there (3, 3), our hand's DOFs (n_dofs,) fitted to it
    (the files keep no depth) and the fit's median landmark residual (mm)."""

    features: np.ndarray
    rotation: np.ndarray
    dofs_rad: np.ndarray
    residual_mm: float


def view_of(model: HandModel, points: np.ndarray, confidence: np.ndarray) -> LetterView:
    """Return the view of a letter recording's hand landmarks (n_frames, 21, 3): its
    middle frame, fitted alone (scale calibrated over all frames)."""
    flat = np.asarray(points, dtype=np.float64) * [1.0, 1.0, 0.0]
    middle = len(flat) // 2
    scale = calibrate_scale(model, flat, confidence, planar=True)
    fit = fit_hand(model, flat[middle : middle + 1], confidence[middle : middle + 1], scale)
    return LetterView(
        handshape_features(flat[middle]),
        fit.rotations[0],
        fit.dofs_rad[0],
        fit.median_residual_mm(),
    )


def seen_as(model: HandModel, dofs_rad: np.ndarray, view: LetterView) -> np.ndarray:
    """Return the features (30,) of hand DOFs (n_dofs,) turned and projected as *view*'s
    hand is (the forearm and wrist at rest: the view's rotation stands for them)."""
    dofs = np.array(dofs_rad, dtype=np.float64)
    placement = [model.dof_names.index(name) for name in FIXED]
    dofs[placement] = model.neutral()[placement]
    marks = landmarks(model, dofs) @ view.rotation.T
    marks[:, 2] = 0.0
    return handshape_features(marks)
