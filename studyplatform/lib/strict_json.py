"""Parse JSON from outside strictly: finite numbers, bounded nesting, encodable text.

Python's ``json`` reads ``NaN``, ``Infinity`` and ``1e400`` (as infinity), nests until the
interpreter's recursion limit (a ``RecursionError``, not a ``ValueError``) and keeps lone
surrogates such as ``"\\ud800"``, which no database column stores. Each of these made a
participant's save or a study import fail with a server error instead of a message. So
did a NUL character (``"\\u0000"``), which PostgreSQL stores in no text or JSON column,
and an integer of thousands of digits, which no column or float holds: NUL is refused (or,
where the caller says so, stripped), and integers are bounded to 64 bits.
"""

import json
import math
from typing import Any

# Deeper than any body the pages send or any study definition holds (about 6 levels).
MAX_DEPTH = 32
INT_LIMIT = 2**63  # a 64-bit column's range


class JsonRejected(ValueError):
    """JSON that is not accepted; the message names the problem, to follow "… is"."""


def _finite(text: str) -> float:
    value = float(text)
    if not math.isfinite(value):
        raise JsonRejected(f"JSON with a number too large to use ({text[:20]})")
    return value


def _integer(text: str) -> int:
    if len(text.lstrip("-")) > 19 or not -INT_LIMIT <= (value := int(text)) < INT_LIMIT:
        raise JsonRejected(f"JSON with an integer too large to use ({text[:20]}…)")
    return value


def _constant(name: str):
    raise JsonRejected(f"JSON with {name}, which JSON does not allow")


def _check(value: Any, depth: int, strip_nul: bool) -> Any:
    """Refuse nesting beyond MAX_DEPTH, text that is not valid Unicode, and NUL (or strip it)."""
    if depth > MAX_DEPTH:
        raise JsonRejected(f"JSON nested deeper than {MAX_DEPTH} levels")
    if isinstance(value, str):
        try:
            value.encode("utf-8")
        except UnicodeEncodeError:
            raise JsonRejected("JSON with text that is not valid Unicode") from None
        if "\x00" in value:
            if not strip_nul:
                raise JsonRejected("JSON with a NUL character (\\u0000) in its text")
            value = value.replace("\x00", "")
        return value
    if isinstance(value, dict):
        return {
            _check(key, depth + 1, strip_nul): _check(item, depth + 1, strip_nul)
            for key, item in value.items()
        }
    if isinstance(value, list):
        return [_check(item, depth + 1, strip_nul) for item in value]
    return value


def loads(text: str | bytes, *, strip_nul: bool = False) -> Any:
    """Return the value of JSON *text* (bytes must be UTF-8), or raise JsonRejected.

    NUL characters are refused, or with *strip_nul* removed from every text.
    """
    if isinstance(text, bytes):
        try:
            text = text.decode("utf-8")
        except UnicodeDecodeError:
            raise JsonRejected("not UTF-8 text") from None
    try:
        value = json.loads(text, parse_float=_finite, parse_int=_integer, parse_constant=_constant)
    except json.JSONDecodeError as error:
        raise JsonRejected(
            f"not valid JSON: {error.msg} at line {error.lineno}, column {error.colno}"
        ) from None
    except RecursionError:
        raise JsonRejected(f"JSON nested deeper than {MAX_DEPTH} levels") from None
    except JsonRejected:
        raise
    except ValueError:  # an integer of more digits than Python converts
        raise JsonRejected("JSON with a number too large to use") from None
    return _check(value, 0, strip_nul)
