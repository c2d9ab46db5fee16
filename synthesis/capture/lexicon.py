"""Find real signers' ASL letter recordings: the fingerspelling lexicon that the
``spoken-to-signed`` package ships as ``.pose`` files (installed as a test and demo
dependency; the files are read where the package put them, never copied)."""

import csv
from importlib import resources
from pathlib import Path

PACKAGE = "spoken-to-signed"


class LexiconMissing(LookupError):
    """The package with the human letter recordings is not installed."""


def human_letter_files(language: str = "ase") -> dict[str, Path]:
    """Return each letter's recording in the installed lexicon (ASL by default), A–Z.

    Raise LexiconMissing, saying how to install it, when the package is not there.
    """
    try:
        root = Path(str(resources.files("spoken_to_signed") / "assets" / "fingerspelling_lexicon"))
    except ModuleNotFoundError:
        raise LexiconMissing(
            f"The human letter recordings come with the {PACKAGE} package, which is not "
            "installed: run 'make install' (it installs the development dependencies)."
        ) from None
    files: dict[str, Path] = {}
    with open(root / "index.csv", encoding="utf-8") as handle:
        for row in csv.DictReader(handle):
            word = row["words"]
            if row["signed_language"] == language and len(word) == 1 and word.isalpha():
                files.setdefault(word.upper(), root / row["path"])
    return dict(sorted(files.items()))
