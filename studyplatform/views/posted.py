"""Read what a participant's page posts: JSON bodies, answers and response times."""

import math
from dataclasses import replace

from django.http import HttpRequest

from studyplatform.actions import Answer, AnswerRejected
from studyplatform.lib import strict_json
from studyplatform.models import Question
from studyplatform.questions import question_type


def json_body(request: HttpRequest):
    """Return the request's JSON body, None if it is not strict JSON (strict_json)."""
    try:
        return strict_json.loads(request.body or b"null")
    except strict_json.JsonRejected:
        return None


def parse_answer(question: Question, value: str, rt_ms: str | int | None) -> Answer:
    """Turn a posted value into an Answer for *question*; AnswerRejected if it is not one."""
    rt = parse_rt_ms(rt_ms)
    value = "" if value is None else str(value)
    try:
        answer = question_type(question).parse(question, value)
    except ValueError:
        raise AnswerRejected(f"“{value[:40]}” is not an answer to “{question.key}”.") from None
    return replace(answer, rt_ms=rt)


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
        raise AnswerRejected(f"The response time {str(rt_ms)[:20]!r} is not a number of "
                             "milliseconds.") from None  # fmt: skip
    return max(0, min(int(value), 86_400_000))
