"""Test the one header check of versioned files (synthesis/formats.py)."""

import pytest

from synthesis.formats import check_header


class FileError(ValueError):
    pass


def test_a_good_header_passes_and_a_bad_one_is_named():
    check_header({"format": "x.y", "version": 2}, "x.y", 2, "thing", FileError)
    with pytest.raises(FileError, match=r"^Not a thing \(format 'x.y', not 'z'\)\.$"):
        check_header({"format": "z", "version": 2}, "x.y", 2, "thing", FileError)
    with pytest.raises(FileError, match=r"^a.json: not a thing \(format 'x.y', not 'list'\)"):
        check_header([], "x.y", 2, "thing", FileError, "a.json")
    with pytest.raises(FileError, match=r"^Unsupported thing version 3 \(this installation reads"):
        check_header({"format": "x.y", "version": 3}, "x.y", 2, "thing", FileError)
    with pytest.raises(ValueError, match=r"^b.json: unsupported thing version None"):
        check_header({"format": "x.y"}, "x.y", 2, "thing", where="b.json")


def test_no_other_module_checks_a_format_header_by_hand():
    """Issue 39: the header check was written nine times. analysis imports nothing of
    the project, so its one mapping file (analysis/wide.py) keeps its own."""
    from pathlib import Path

    root = Path(__file__).resolve().parents[2]
    by_hand = [
        str(path.relative_to(root))
        for package in ("synthesis", "stimuli", "studyplatform")
        for path in (root / package).rglob("*.py")
        if 'get("format") !=' in path.read_text(encoding="utf-8") and path.name != "formats.py"
    ]
    assert by_hand == []
