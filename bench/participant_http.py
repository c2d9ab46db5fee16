"""Take a study over HTTP the way the participant page's script does, retries included.

A participant opens the study link, agrees, and on each page loads it, saves every answer
at once as JSON and presses Next, as ``participate.js`` does: a lost connection is retried
with backoff until it is back (up to *patience_s*), a server error (5xx) a few times. The
load benchmark runs hundreds of these against the application server; the fault test runs
one while the server is killed. Timings are kept per request kind.
"""

import http.cookiejar
import json
import random
import re
import time
import urllib.error
import urllib.parse
import urllib.request
from dataclasses import dataclass, field

SERVER_ERROR_ATTEMPTS = 5
JSON_HEADERS = {"Content-Type": "application/json", "Accept": "application/json"}


def backoff_s(attempt: int) -> float:
    """Return participate.js's wait before retry *attempt*: 0.5 s doubling to 8 s."""
    return min(0.5 * 2**attempt, 8.0)


class Refused(Exception):
    """The server answered 4xx, or kept failing: the participant cannot go on."""


@dataclass
class Answered:
    """What one participant sent, by (trial key, question key), and how long requests took."""

    token: str = ""
    sent: dict = field(default_factory=dict)
    timings: dict = field(default_factory=lambda: {"page": [], "save": [], "next": []})
    retries: int = 0
    requests: int = 0  # attempts sent, retries included


class HttpParticipant:
    """One participant's browser: cookies, the CSRF token, and retrying requests."""

    def __init__(self, base_url: str, patience_s: float = 60.0, seed: int = 0):
        self.base = base_url.rstrip("/")
        self.jar = http.cookiejar.CookieJar()
        self.opener = urllib.request.build_opener(
            urllib.request.HTTPCookieProcessor(self.jar), _NoRedirect()
        )
        self.patience_s = patience_s
        self.random = random.Random(seed)
        self.answered = Answered()

    def _csrf(self) -> str:
        return next((c.value for c in self.jar if c.name == "csrftoken"), "")

    def request(
        self, kind: str | None, path: str, data: bytes | None = None, headers: dict | None = None
    ) -> tuple[int, dict, bytes]:
        """Send a request, retrying like the page's script; return (status, headers, body)."""
        deadline = time.monotonic() + self.patience_s
        server_errors = 0
        for attempt in range(10_000):
            self.answered.requests += 1
            sent = {"X-CSRFToken": self._csrf(), "Referer": self.base + "/", **(headers or {})}
            request = urllib.request.Request(self.base + path, data=data, headers=sent)
            started = time.perf_counter()
            try:
                with self.opener.open(request, timeout=30) as response:
                    status, body, got = response.status, response.read(), dict(response.headers)
            except urllib.error.HTTPError as error:
                status, body, got = error.code, error.read(), dict(error.headers)
            except (urllib.error.URLError, ConnectionError, TimeoutError):
                status, body, got = 0, b"", {}  # no connection: the server is down
            if kind and status and status < 500:
                self.answered.timings[kind].append(time.perf_counter() - started)
            if status and status < 500:
                return status, got, body
            if status >= 500:
                server_errors += 1
                if server_errors >= SERVER_ERROR_ATTEMPTS:
                    raise Refused(f"{path}: {server_errors} server errors")
            if time.monotonic() > deadline:
                raise Refused(f"{path}: no answer for {self.patience_s:g} s")
            self.answered.retries += 1
            time.sleep(backoff_s(attempt))
        raise Refused(path)

    def enroll(self, slug: str) -> str:
        """Open the study link and agree; return the participant's token."""
        self.request(None, f"/s/{slug}/")
        body = f"consent=yes&csrfmiddlewaretoken={self._csrf()}".encode()
        status, headers, _ = self.request(
            None, f"/s/{slug}/", body, {"Content-Type": "application/x-www-form-urlencoded"}
        )
        match = re.search(r"/p/([^/]+)/1/", headers.get("Location", ""))
        if status != 302 or match is None:
            raise Refused(f"enrolment answered {status}")
        self.answered.token = match.group(1)
        return self.answered.token

    def take_page(self, number: int) -> bool:
        """Load page *number*, answer and save every question, press Next; False at the end."""
        token = self.answered.token
        status, _, body = self.request("page", f"/p/{token}/{number}/")
        page = body.decode()
        trial = re.search(r'data-trial="([^"]+)"', page)
        if status != 200 or trial is None:
            return False
        form = {"nav": "next"}
        for question, value in _answers(page, self.random):
            payload = json.dumps(
                {
                    "page": number,
                    "trial": trial.group(1),
                    "question": question,
                    "value": value,
                    "rt_ms": 900,
                }
            ).encode()
            for _ in range(2):  # the second is the retry of a lost reply: changes nothing
                saved, _, reply = self.request("save", f"/p/{token}/answer/", payload, JSON_HEADERS)
                if saved != 200:
                    raise Refused(f"save answered {saved}: {reply[:200]!r}")
            self.answered.sent[(trial.group(1), question)] = value
            form[f"q-{question}"] = value
        encoded = urllib.parse.urlencode(form).encode()
        form_headers = {
            "Content-Type": "application/x-www-form-urlencoded",
            "Accept": "application/json",
        }
        moved, _, reply = self.request("next", f"/p/{token}/{number}/", encoded, form_headers)
        if moved != 200:
            raise Refused(f"Next answered {moved}: {reply[:200]!r}")
        return "/done/" not in json.loads(reply).get("url", "")


def _answers(page: str, rng: random.Random) -> list[tuple[str, str]]:
    """Return an answer for each question on the page's HTML (radio, number, e-mail, text)."""
    options: dict[str, list[str]] = {}
    answers: dict[str, str] = {}
    for tag, attributes in re.findall(r"<(input|textarea)\b([^>]*)>", page):
        attrs = dict(re.findall(r'([\w-]+)="([^"]*)"', attributes))
        name = attrs.get("name", "")
        if not name.startswith("q-"):
            continue
        kind = attrs.get("type", tag)
        if kind == "radio":
            options.setdefault(name[2:], []).append(attrs.get("value", ""))
        elif kind == "number":
            answers[name[2:]] = "30"
        elif kind == "email":
            answers[name[2:]] = f"participant{rng.randrange(1000)}@example.org"
        else:
            answers[name[2:]] = f"open answer {rng.randrange(1000)}"
    answers.update({name: rng.choice(values) for name, values in options.items()})
    return sorted(answers.items())


class _NoRedirect(urllib.request.HTTPRedirectHandler):
    """Hand redirects back (the enrolment's Location names the participant's token)."""

    def redirect_request(self, *args, **kwargs):
        return None
