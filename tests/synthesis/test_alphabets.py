"""Test the manual alphabets as engine data: ASL and Libras, and two-handed ones (issue 55).

References: the Libras manual alphabet has 27 one-handed forms, A–Z and Ç, Ç being C
with a trembling movement (Brazilian teaching charts, as synthesis/data/alphabets/
libras.yaml says); two-handed alphabets (BSL, TİD) give each letter two handshapes.
"""

import numpy as np
import pytest

from synthesis.fingerspelling import alphabets
from synthesis.fingerspelling.alphabet import (
    LETTERS,
    AlphabetError,
    alphabet,
    letter,
    two_handed_letter,
)
from synthesis.fingerspelling.alphabets import (
    alphabet_choices,
    alphabet_codes,
    letter_entry,
    manual_alphabet,
)
from synthesis.fingerspelling.spelling import simple_timing, spell, word_letters
from synthesis.rigs.hand import HandModel
from synthesis.rigs.landmarks import landmarks
from synthesis.techniques import REGISTRY, ClipError, ClipRequest, build_motion

TWO_HANDED = """
alphabet:
  name: Test2
  sign_language: A test of the two-handed structure (not a real alphabet)
  hands: two
A:
  description: "Dominant index tip on the nondominant thumb tip."
  dominant:
    fingers: {index: [0, 0, 0], middle: [90, 100, 60], ring: [90, 100, 60], pinky: [90, 100, 60]}
  nondominant:
    fingers: {index: [0, 0, 0], middle: [0, 0, 0], ring: [0, 0, 0], pinky: [0, 0, 0]}
  touch: {dominant: index_tip, nondominant: thumb_tip}
B:
  description: "Two flat hands, apart."
  dominant: {fingers: {index: [0, 0, 0]}}
  nondominant: {fingers: {index: [0, 0, 0]}}
C: {from: test2, letter: B, description: "B again, by borrowing."}
"""


@pytest.fixture
def with_alphabet(monkeypatch):
    """Add alphabet files (code → YAML text) to the engine's for one test."""
    known = alphabets._files()

    def add(**texts: str) -> None:
        monkeypatch.setattr(alphabets, "_files", lambda: {**known, **texts})
        alphabets._parsed.cache_clear()

    yield add
    alphabets._parsed.cache_clear()


def test_the_engine_knows_asl_first_and_libras():
    assert alphabet_codes()[:2] == ("asl", "libras")
    assert dict(alphabet_choices())["libras"] == "Libras (Língua Brasileira de Sinais)"
    assert manual_alphabet("asl").letters == LETTERS
    libras = manual_alphabet("libras")
    assert libras.letters == (*"ABC", "Ç", *"DEFGHIJKLMNOPQRSTUVWXYZ")
    assert not libras.two_handed
    assert "Not yet reviewed by a Libras signer" in libras.review


def test_refused_letters_are_named_with_their_alphabet():
    with pytest.raises(
        AlphabetError, match=r"'Ç' is not a letter of the ASL manual alphabet \(A–Z\)"
    ):
        letter("Ç")
    with pytest.raises(AlphabetError, match=r"'Ğ' is not a letter of the Libras .* \(A–Z, Ç\)"):
        word_letters("DAĞ", "libras")
    with pytest.raises(AlphabetError, match=r"Unknown manual alphabet 'tid'.*asl, libras"):
        manual_alphabet("tid")


def test_letters_are_composed_before_they_are_looked_up():
    # "ç" typed as c + COMBINING CEDILLA (U+0327) is one letter, as NFC makes it.
    assert word_letters("c\u0327ay", "libras") == ["Ç", "A", "Y"]
    assert word_letters("maça", "libras") == ["M", "A", "Ç", "A"]


def test_libras_borrows_asl_handshapes_where_they_are_the_same():
    assert np.array_equal(letter("A", alphabet="libras").dofs_rad, letter("A").dofs_rad)
    # Libras T is the handshape ASL calls F; Libras M and N point down.
    assert np.array_equal(letter("T", alphabet="libras").dofs_rad, letter("F").dofs_rad)
    assert not np.allclose(letter("M", alphabet="libras").dofs_rad, letter("M").dofs_rad)
    assert letter_entry("libras", "Ç")["contacts"] == letter_entry("asl", "C")["contacts"]


def test_every_libras_letter_is_its_own_handshape():
    """No two letters that hold still look alike: the 21 landmarks differ by ≥ 1 cm
    somewhere (a letter that moves may start from another's handshape: I → J, C → Ç)."""
    model = HandModel("right")
    shapes = alphabet("right", "libras")
    still = {k: s for k, s in shapes.items() if s.path_rad is None}
    points = {k: landmarks(model, s.dofs_rad) for k, s in still.items()}
    assert len(points) == 27 - 6  # Ç, H, J, K, X and Z move
    for a in points:
        for b in points:
            if a < b:
                farthest = np.linalg.norm(points[a] - points[b], axis=-1).max()
                assert farthest > 0.01, (a, b, farthest)
    assert shapes["Ç"].path_rad is not None and shapes["C"].path_rad is None


def test_contacts_hold_in_libras_own_letters():
    from synthesis.fingerspelling.alphabet import contact_gaps_m

    model = HandModel("right")
    for key in "FG":
        shape = letter(key, alphabet="libras")
        assert max(abs(g) for g in contact_gaps_m(model, shape.dofs_rad, shape.contacts)) < 0.002


def test_a_libras_word_is_spelled_with_its_moving_letters_held_longer():
    timing = simple_timing("ÇAY", "libras")
    assert timing.letters == ("Ç", "A", "Y")
    assert timing.hold_ms[0] > timing.hold_ms[1]
    frames = spell("çay", alphabet="libras", rate_hz=30.0)
    tilt = HandModel("right").dof_names.index("forearm_tilt_side")
    assert np.ptp(frames[:20, tilt]) > np.radians(5)  # Ç trembles side to side


def test_a_word_item_spells_in_the_alphabet_its_values_name():
    request = ClipRequest("word", "ÇAY", {"alphabet": "libras"}, rate_hz=15.0)
    assert build_motion(request).made_motion.shape[0] > 10
    REGISTRY.check_text("word", "ÇAY", {"alphabet": "libras"})
    with pytest.raises(ClipError, match="not a letter of the ASL manual alphabet"):
        REGISTRY.check_text("word", "ÇAY")
    # The default alphabet is ASL: a clip that names it is the clip that does not.
    plain = ClipRequest("word", "CAT")
    assert ClipRequest("word", "CAT", {"alphabet": "asl"}).parameters == plain.parameters


def test_what_was_fitted_to_asl_refuses_another_alphabet():
    with pytest.raises(ClipError, match="Variable model, fitted to ASL"):
        ClipRequest("word", "ÇAY", {"alphabet": "libras", "timing": "variable"})
    with pytest.raises(ClipError, match="capture of ASL fingerspelling"):
        ClipRequest("word", "ÇAY", {"alphabet": "libras", "source": "simulated"})


def test_a_two_handed_alphabet_gives_each_hand_its_handshape(with_alphabet):
    with_alphabet(test2=TWO_HANDED)
    shape = two_handed_letter("A", "right", "test2")
    right, left = HandModel("right"), HandModel("left")
    assert shape.touch == ("index_tip", "thumb_tip")
    assert shape.dominant.dofs_rad.shape == (len(right.dofs),)
    assert shape.nondominant.dofs_rad.shape == (len(left.dofs),)
    assert not np.allclose(shape.dominant.dofs_rad, shape.nondominant.dofs_rad)
    borrowed = two_handed_letter("C", "left", "test2")
    assert np.array_equal(
        borrowed.dominant.dofs_rad, two_handed_letter("B", "left", "test2").dominant.dofs_rad
    )
    assert borrowed.description == "B again, by borrowing."


def test_a_two_handed_alphabet_is_read_but_not_spelled_one_handed(with_alphabet):
    with_alphabet(test2=TWO_HANDED)
    with pytest.raises(AlphabetError, match="Test2 manual alphabet is two-handed"):
        letter("A", alphabet="test2")
    with pytest.raises(AlphabetError, match="spells words with one hand only so far"):
        word_letters("AB", "test2")
    with pytest.raises(AlphabetError, match="one-handed: use letter"):
        two_handed_letter("A", alphabet="libras")


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("A: {dominant: {}}", "a two-handed letter gives dominant and nondominant"),
        (
            "A: {dominant: {}, nondominant: {}, touch: {dominant: index_tip, nondominant: elbow}}",
            "unknown joint.*elbow.*in touch",
        ),
        ("A: {from: asl}", "one-handed and a two-handed alphabet cannot borrow"),
        ("A: {from: bad, letter: B}\nB: {from: bad, letter: A}", "the borrowings go round"),
    ],
)
def test_a_malformed_two_handed_letter_is_named(with_alphabet, text, message):
    header = "alphabet: {name: Bad, sign_language: Bad, hands: two}\n"
    with_alphabet(bad=header + text)
    with pytest.raises(AlphabetError, match=message):
        two_handed_letter("A", alphabet="bad")


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("A: {}", "must map 'alphabet'"),
        ("alphabet: {name: X, sign_language: Y, hands: three}\nA: {}", "hands is one or two"),
        ("alphabet: {name: X, hands: one}\nA: {}", "alphabet.sign_language is missing"),
        ("alphabet: {name: X, sign_language: Y}\nAB: {}", "a letter is one character"),
    ],
)
def test_a_malformed_alphabet_file_is_named(with_alphabet, text, message):
    with_alphabet(bad=text)
    with pytest.raises(AlphabetError, match=message):
        manual_alphabet("bad")
