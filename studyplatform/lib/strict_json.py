"""Parse JSON from outside strictly: finite numbers, bounded nesting, encodable text.

Python's ``json`` reads ``NaN``, ``Infinity`` and ``1e400`` (as infinity), nests until the
interpreter's recursion limit (a ``RecursionError``, not a ``ValueError``) and keeps lone
surrogates such as ``"\\ud800"``, which no database column stores. Each of these made a
participant's save or a study import fail with a server error instead of a message.
"""

import json
import math
from typing import Any

# Deeper than any body the pages send or any study definition holds (about 6 levels).
MAX_DEPTH = 32


class JsonRejected(ValueError):
    """JSON that is not accepted; the message names the problem, to follow "… is"."""


def _finite(text: str) -> float:
    value = float(text)
    if not math.isfinite(value):
        raise JsonRejected(f"JSON with a number too large to use ({text[:20]})")
    return value


def _constant(name: str):
    raise JsonRejected(f"JSON with {name}, which JSON does not allow")


def _check(value: Any, depth: int) -> None:
    """Refuse nesting beyond MAX_DEPTH and text that is not valid Unicode."""
    if depth > MAX_DEPTH:
        raise JsonRejected(f"JSON nested deeper than {MAX_DEPTH} levels")
    if isinstance(value, str):
        try:
            value.encode("utf-8")
        except UnicodeEncodeError:
            raise JsonRejected("JSON with text that is not valid Unicode") from None
    elif isinstance(value, dict):
        for key, item in value.items():
            _check(key, depth + 1)
            _check(item, depth + 1)
    elif isinstance(value, list):
        for item in value:
            _check(item, depth + 1)


def loads(text: str | bytes) -> Any:
    """Return the value of JSON *text* (bytes must be UTF-8), or raise JsonRejected."""
    if isinstance(text, bytes):
        try:
            text = text.decode("utf-8")
        except UnicodeDecodeError:
            raise JsonRejected("not UTF-8 text") from None
    try:
        value = json.loads(text, parse_float=_finite, parse_constant=_constant)
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
    _check(value, 0)
    return value
