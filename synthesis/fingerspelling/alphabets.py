"""The manual alphabets the engine knows: one data file each in ``synthesis/data/alphabets``.

A file's ``alphabet`` mapping says what it is (``name``, ``sign_language``, ``hands``:
one or two, ``source``, ``review``); every other key is a letter, in the order the file
lists them. A letter of a one-handed alphabet is a handshape (:mod:`.alphabet` reads
it), or ``from: <alphabet>`` with ``letter:`` to borrow another alphabet's handshape
(Libras's A is ASL's A) and keys that replace the borrowed ones (a movement, a
description). A letter of a two-handed alphabet (BSL, Auslan, TİD) gives a handshape
for each hand, ``dominant`` and ``nondominant``, and ``touch``: where they meet.
``docs/alphabets.md`` describes the format; the registry is the files themselves, so a
new alphabet is a new file.
"""

import unicodedata
from dataclasses import dataclass
from functools import cache
from importlib import resources

import yaml

# The key of a file's description of itself: every other key is a letter.
ABOUT = "alphabet"
HANDS = ("one", "two")
DEFAULT_ALPHABET = "asl"
_FOLDER = "data/alphabets"


class AlphabetError(ValueError):
    """A letter that is not in the alphabet, or a malformed alphabet data file."""


@dataclass(frozen=True)
class ManualAlphabet:
    """One manual alphabet: its code (the file's name), what it is and its letters."""

    code: str
    name: str
    sign_language: str
    hands: str
    letters: tuple[str, ...]
    source: str = ""
    review: str = ""

    @property
    def two_handed(self) -> bool:
        return self.hands == "two"

    def letters_in_words(self) -> str:
        """Return the letters as people list them: "A–Z" and any beyond ("A–Z, Ç")."""
        latin = tuple("ABCDEFGHIJKLMNOPQRSTUVWXYZ")
        if set(latin) <= set(self.letters):
            others = [c for c in self.letters if c not in latin]
            return ", ".join(["A–Z", *others])
        return ", ".join(self.letters)

    def check(self, character: str) -> str:
        """Return *character* as a letter of this alphabet; AlphabetError names it if not."""
        key = as_letter(character)
        if key not in self.letters:
            raise AlphabetError(
                f"{character!r} is not a letter of the {self.name} manual alphabet "
                f"({self.letters_in_words()})."
            )
        return key


def as_letter(character: str) -> str:
    """Return *character* upper-cased and composed (NFC): "ç" and "c" + U+0327 are "Ç"."""
    if not isinstance(character, str):
        return character
    return unicodedata.normalize("NFC", character).upper()


@cache
def _files() -> dict[str, str]:
    """Return each alphabet file's text by its code (the file's name)."""
    folder = resources.files("synthesis").joinpath(_FOLDER)
    return {
        entry.name.removesuffix(".yaml"): entry.read_text("utf-8")
        for entry in sorted(folder.iterdir(), key=lambda e: e.name)
        if entry.name.endswith(".yaml")
    }


def parse_alphabet(code: str, data) -> tuple[ManualAlphabet, dict]:
    """Return the alphabet a file's content describes and its letters' entries."""
    where = f"alphabet file {code}.yaml"
    if not isinstance(data, dict) or not isinstance(data.get(ABOUT), dict):
        raise AlphabetError(f"{where}: it must map {ABOUT!r} and its letters to handshapes.")
    about = data[ABOUT]
    hands = about.get("hands", "one")
    if hands not in HANDS:
        raise AlphabetError(f"{where}: hands is one or two, not {hands!r}.")
    entries = {as_letter(str(k)): v for k, v in data.items() if k != ABOUT}
    if not entries:
        raise AlphabetError(f"{where}: it has no letters.")
    long = [k for k in entries if len(k) != 1]
    if long:
        raise AlphabetError(f"{where}: a letter is one character, not {', '.join(long)}.")
    for key in ("name", "sign_language"):
        if not isinstance(about.get(key), str) or not about[key].strip():
            raise AlphabetError(f"{where}: {ABOUT}.{key} is missing.")
    alphabet = ManualAlphabet(
        code,
        about["name"],
        about["sign_language"],
        hands,
        tuple(entries),
        about.get("source", ""),
        about.get("review", ""),
    )
    return alphabet, entries


@cache
def _parsed(code: str) -> tuple[ManualAlphabet, dict]:
    try:
        text = _files()[code]
    except KeyError:
        raise AlphabetError(
            f"Unknown manual alphabet {code!r}: the engine knows {', '.join(_files())}."
        ) from None
    return parse_alphabet(code, yaml.safe_load(text))


def manual_alphabet(code: str = DEFAULT_ALPHABET) -> ManualAlphabet:
    """Return the alphabet *code* names; AlphabetError names the known ones."""
    return _parsed(code)[0]


def alphabet_codes() -> tuple[str, ...]:
    """Return the codes of every alphabet the engine has a file for, ASL first."""
    codes = sorted(_files())
    return tuple(sorted(codes, key=lambda code: code != DEFAULT_ALPHABET))


def alphabet_choices() -> list[tuple[str, str]]:
    """Return (code, "name (sign language)") for every alphabet: form and model choices."""
    return [
        (code, f"{manual_alphabet(code).name} ({manual_alphabet(code).sign_language})")
        for code in alphabet_codes()
    ]


def letter_entry(code: str, key: str, _chain: tuple[str, ...] = ()) -> dict:
    """Return a letter's data-file entry, a borrowed handshape resolved (``from``)."""
    alphabet, entries = _parsed(code)
    key = alphabet.check(key)
    entry = entries[key]
    if not isinstance(entry, dict) or "from" not in entry:
        return entry
    where = f"alphabet {code}, letter {key}"
    source, borrowed = str(entry["from"]), as_letter(str(entry.get("letter", key)))
    chain = (*_chain, f"{code}:{key}")
    if f"{source}:{borrowed}" in chain:
        raise AlphabetError(f"{where}: the borrowings go round ({' → '.join(chain)}).")
    if manual_alphabet(source).two_handed != alphabet.two_handed:
        raise AlphabetError(
            f"{where}: a one-handed and a two-handed alphabet cannot borrow from each other."
        )
    base = letter_entry(source, borrowed, chain)
    own = {k: v for k, v in entry.items() if k not in ("from", "letter")}
    return {**base, **own}


__all__ = [
    "DEFAULT_ALPHABET",
    "AlphabetError",
    "ManualAlphabet",
    "alphabet_choices",
    "alphabet_codes",
    "as_letter",
    "letter_entry",
    "manual_alphabet",
    "parse_alphabet",
]
