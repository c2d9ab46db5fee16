"""Read what a participant's page posts: JSON bodies, answers and response times.

This is the one gate between a participant's browser and the actions: every body is
strict JSON (``lib.strict_json``) of the right content type, every answer is text or a
finite number, and text loses the characters no answer needs before it is checked by its
question type: C0 and C1 control characters other than tab and line breaks (NUL among
them), and the bidirectional embedding, override and isolate controls, which would
reorder what a researcher reads in an export. They are stripped, not refused: a pasted
answer keeps its words.
"""

import math
import re
from dataclasses import replace

from django.http import HttpRequest

from studyplatform.actions import Answer, AnswerRejected
from studyplatform.lib import strict_json
from studyplatform.models import Question
from studyplatform.questions import question_type

_UNWANTED_CHARACTERS = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\x7f-\x9f\u202a-\u202e\u2066-\u2069]")


class BodyRejected(ValueError):
    """A request body that is not JSON of the expected kind; the message says why."""

    def __init__(self, message: str, status: int = 400):
        super().__init__(message)
        self.status = status


def json_body(request: HttpRequest, *, strip_nul: bool = True):
    """Return the request's JSON body; BodyRejected if it is not strict JSON sent as JSON.

    NUL is stripped from its text like the other control characters no answer needs
    (above), or with *strip_nul* false refused: the page's own event log never holds one.
    """
    if request.content_type != "application/json":
        raise BodyRejected(
            f"The request must be sent as JSON (application/json), not "
            f"“{request.content_type or 'nothing'}”.",
            status=415,
        )
    try:
        return strict_json.loads(request.body or b"null", strip_nul=strip_nul)
    except strict_json.JsonRejected as error:
        raise BodyRejected(f"The request is not in the expected form: {error}.") from None


def page_number(value) -> int | None:
    """Return *value* if it is a page number (an integer, not a boolean), else None."""
    return value if isinstance(value, int) and not isinstance(value, bool) else None


def reached_page(value: str, reached: int) -> int | None:
    """Return the posted page number *value* if it is one of the first *reached* pages."""
    return int(value) if value.isdigit() and 1 <= int(value) <= reached else None


def clean_text(value: str) -> str:
    """Return *value* without control and bidirectional-override characters."""
    return _UNWANTED_CHARACTERS.sub("", value)


def parse_answer(
    question: Question, value, rt_ms: str | int | None, client_ms: str | int | None = None
) -> Answer:
    """Turn a posted value into an Answer for *question*; AnswerRejected if it is not one.

    *client_ms* is when the answer was given on the browser's clock (ms since the epoch).
    """
    rt = parse_rt_ms(rt_ms)
    given = parse_client_ms(client_ms)
    if value is None:
        value = ""
    elif isinstance(value, int | float) and not isinstance(value, bool):
        value = str(value)
    elif not isinstance(value, str):
        raise AnswerRejected(f"The answer to “{question.key}” is not text or a number.")
    value = clean_text(value)
    try:
        answer = question_type(question).parse(question, value)
    except ValueError:
        raise AnswerRejected(f"“{value[:40]}” is not an answer to “{question.key}”.") from None
    return replace(answer, rt_ms=rt, client_ms=given)


# Browser clocks from 2001 to 2286: anything else is not a time an answer was given.
_CLIENT_MS = (1_000_000_000_000, 9_999_999_999_999)


def parse_client_ms(client_ms) -> int | None:
    """Return a browser timestamp in ms, None if none (or an implausible one) was sent."""
    if client_ms is None or client_ms == "" or isinstance(client_ms, bool):
        return None
    if isinstance(client_ms, str):
        if not client_ms.isascii() or not client_ms.isdigit() or len(client_ms) > 13:
            return None
        client_ms = int(client_ms)
    if not isinstance(client_ms, int | float) or not math.isfinite(client_ms):
        return None
    value = int(client_ms)
    return value if _CLIENT_MS[0] <= value <= _CLIENT_MS[1] else None


def parse_rt_ms(rt_ms) -> int | None:
    """Return a response time in ms (clamped to a day), None if none was sent, or raise
    AnswerRejected for anything but a finite number."""
    if rt_ms is None or rt_ms == "":
        return None
    try:
        if isinstance(rt_ms, bool) or not isinstance(rt_ms, int | float | str):
            raise ValueError
        value = float(rt_ms)  # "1e999" is infinite; "٣" is no number here
        if not math.isfinite(value) or (isinstance(rt_ms, str) and not rt_ms.isascii()):
            raise ValueError
    except (ValueError, OverflowError):  # OverflowError: an integer beyond any float
        raise AnswerRejected(
            f"The response time {str(rt_ms)[:20]!r} is not a number of milliseconds."
        ) from None
    return max(0, min(int(value), 86_400_000))
