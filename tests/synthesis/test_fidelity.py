"""Test the handshape benchmark: scoring rules, and our alphabet against real signers."""

import numpy as np
import pytest

from synthesis.capture import read_pose
from synthesis.capture.fidelity import (
    HandshapeScore,
    same_handshape,
    score_handshapes,
    seen_as,
    view_of,
)
from synthesis.capture.lexicon import LexiconMissing, human_letter_files
from synthesis.fingerspelling import letter_pose
from synthesis.rigs.hand import HandModel


def test_look_alikes_count_as_one_handshape_and_fists_are_counted():
    assert same_handshape("G", "Q") and same_handshape("P", "K") and same_handshape("A", "A")
    assert not same_handshape("G", "K") and not same_handshape("H", "V")
    score = HandshapeScore({"A": "X", "G": "Q", "B": "B", "M": "N", "V": "X", "R": "U"})
    assert score.agreeing == ("G", "B") and score.nobs == 6
    assert score.fist_confusions == (("A", "X"), ("M", "N"))
    assert score.confusions() == {"N": ["M"], "U": ["R"], "X": ["A", "V"]}
    assert score.to_dict()["agreeing"] == 2
    assert score.summary().startswith("2 of 6 letters agree")


def test_a_candidate_is_taken_for_its_nearest_reference():
    references = {"A": np.zeros(30), "B": np.ones(30), "C": np.linspace(0, 2, 30)}
    score = score_handshapes({"A": np.full(30, 0.1), "B": np.full(30, 0.6)}, references)
    assert score.taken == {"A": "A", "B": "B"}


@pytest.mark.slow
def test_our_alphabet_against_real_signers():
    """Source: spoken-to-signed 0.4.0's ASL letters. Measured: 20 of 26 agree (the
    misses: A, T and V taken for X, C for O, R and U for P), two fist letters taken for
    another (A, T); the target of issue 16 is 20 and at most two. Before the refit of
    L, M, N, S and X: 15, and six. bench/bench_alphabet_fidelity.py prints the table."""
    try:
        files = human_letter_files()
    except LexiconMissing as error:
        pytest.skip(str(error))
    model = HandModel()
    views = {k: view_of(model, *read_pose(p).hand("right")) for k, p in files.items()}
    human = {k: v.features for k, v in views.items()}
    # Each human letter seen as itself is taken for itself: the views are consistent.
    assert score_handshapes(human, human).agreeing == tuple(files)
    ours = score_handshapes({k: seen_as(model, letter_pose(k), v) for k, v in views.items()}, human)
    assert len(ours.agreeing) >= 20, ours.summary()
    assert len(ours.fist_confusions) <= 2, ours.summary()
    # Our hand can show them all: the human letters fitted onto it agree.
    fitted = score_handshapes({k: seen_as(model, v.dofs_rad, v) for k, v in views.items()}, human)
    assert len(fitted.agreeing) == 26, fitted.summary()
