"""Pose databases with sequences withheld from them: seed 000 §3.1's evaluation inputs.

Seed 000 §3.1 chose markers and measured Table 3.1 on a sequence "not a part of the
original corpus". Two such inputs are built here, each as a database rooted at the
lower forearm (App. A) and two withheld sequences, one to choose markers on and one to
test:

- **simulated gestures** (:func:`simulated_gestures`): the paper's kind of motion,
  simulated (:mod:`synthesis.hands.gestures`); database, selection and test come from
  independent streams of one generator;
- **the human letters** (:func:`human_letters`): the 26 ASL letters of
  ``spoken-to-signed``'s lexicon, real signers fitted by the hand model; some letters
  are withheld for selection and test, the rest are the database. The letters are few
  (about 26 s at 120 Hz once resampled from 25 fps), so a withheld letter's handshape
  is often unlike any in the database: a harder test than the paper's.
"""

from dataclasses import dataclass

import numpy as np

from synthesis.hands.gestures import simulate_gestures
from synthesis.hands.posedb import ALPHABET, RATE_HZ, human_letter_poses, pose_database_of
from synthesis.hands.reconstruct import PoseDatabase
from synthesis.rigs.hand import HandModel

PAPER_ROOT = "forearm"
# Withheld from the human-letter database: every fourth letter from D is tested, every
# fourth from B chooses the markers; the other 14 are the database.
TEST_LETTERS = "DHLPTX"
SELECTION_LETTERS = "BFJNRV"


@dataclass(frozen=True, eq=False)
class HeldOut:
    """A pose database and two sequences withheld from it (hand DOFs at 120 Hz):
    *selection* to choose markers on (Alg. 1), *test* to measure; *input* names them."""

    database: PoseDatabase
    selection_dofs: np.ndarray
    test_dofs: np.ndarray
    input: str


def simulated_gestures(
    side: str,
    rng: np.random.Generator,
    database_s: float = 90.0,
    selection_s: float = 10.0,
    test_s: float = 20.0,
) -> HeldOut:
    """Return simulated gestures: a *database_s* database (the paper's was over 10,000
    frames: 90 s at 120 Hz), and selection and test sequences generated apart from it."""
    hand = HandModel(side)
    streams = rng.spawn(3)
    database = simulate_gestures(hand, database_s, RATE_HZ, streams[0])
    source = f"simulated gestures, {len(database)} poses at 120 Hz"
    return HeldOut(
        pose_database_of(hand, database, source, PAPER_ROOT),
        simulate_gestures(hand, selection_s, RATE_HZ, streams[1]),
        simulate_gestures(hand, test_s, RATE_HZ, streams[2]),
        f"simulated gestures: database {database_s:g} s, markers chosen on {selection_s:g} s "
        f"more, tested on {test_s:g} s more",
    )


def human_letters(
    side: str = "right",
    test_letters: str = TEST_LETTERS,
    selection_letters: str = SELECTION_LETTERS,
    database_letters: str | None = None,
) -> HeldOut:
    """Return the human letters: the database of *database_letters* (default: the
    letters neither tested nor used to choose markers), the selection and test letters
    withheld. Raise LexiconMissing without ``spoken-to-signed``."""
    hand = HandModel(side)
    withheld = set(test_letters) | set(selection_letters)
    if set(test_letters) & set(selection_letters):
        raise ValueError("A letter is either tested or used to choose markers, not both.")
    if database_letters is None:
        database_letters = "".join(x for x in ALPHABET if x not in withheld)
    if set(database_letters) & withheld:
        raise ValueError("The database may not hold a withheld letter.")
    database = human_letter_poses(side, database_letters)
    source = f"human letters {database_letters} (spoken-to-signed), {len(database)} poses at 120 Hz"
    return HeldOut(
        pose_database_of(hand, database, source, PAPER_ROOT),
        human_letter_poses(side, selection_letters),
        human_letter_poses(side, test_letters),
        f"human letters (spoken-to-signed): database {database_letters}, markers chosen on "
        f"{selection_letters}, tested on {test_letters}",
    )
