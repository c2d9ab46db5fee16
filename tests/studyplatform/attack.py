"""Talk to a live server as an attacker would: raw HTTP with cookies, CSRF and any bytes."""

import http.cookiejar
import io
import json
import re
import urllib.error
import urllib.parse
import urllib.request
import zipfile
from dataclasses import dataclass


@dataclass(frozen=True)
class Answer:
    """What the server answered."""

    status: int
    headers: dict
    body: bytes

    def json(self):
        return json.loads(self.body)

    @property
    def text(self) -> str:
        return self.body.decode("utf-8", "replace")


class _NoRedirect(urllib.request.HTTPRedirectHandler):
    def redirect_request(self, *args, **kwargs):
        return None


class Attacker:
    """An HTTP client of the live server at *base* with its own cookies; never raises on 4xx/5xx."""

    def __init__(self, base: str, address: str | None = None):
        self.base, self.address = base, address
        self.jar = http.cookiejar.CookieJar()
        self.opener = urllib.request.build_opener(
            urllib.request.HTTPCookieProcessor(self.jar), _NoRedirect()
        )

    def cookie(self, name: str) -> str | None:
        return next((c.value for c in self.jar if c.name == name), None)

    def request(
        self, method: str, path: str, body: bytes | None = None, headers: dict | None = None
    ) -> Answer:
        headers = {"Referer": self.base + "/", **(headers or {})}
        if self.address:
            headers["X-Forwarded-For"] = self.address
        token = self.cookie("csrftoken")
        if token and method == "POST":
            headers.setdefault("X-CSRFToken", token)
        request = urllib.request.Request(
            self.base + path, data=body, method=method, headers=headers
        )
        try:
            with self.opener.open(request, timeout=60) as response:
                return Answer(response.status, dict(response.headers), response.read())
        except urllib.error.HTTPError as error:
            return Answer(error.code, dict(error.headers), error.read())

    def get(self, path: str, **headers) -> Answer:
        return self.request("GET", path, headers=headers)

    def post_json(self, path: str, data) -> Answer:
        body = data if isinstance(data, bytes) else json.dumps(data).encode()
        return self.request(
            "POST", path, body, {"Content-Type": "application/json", "Accept": "application/json"}
        )

    def post_form(self, path: str, fields: dict) -> Answer:
        token = self.cookie("csrftoken") or ""
        body = urllib.parse.urlencode({"csrfmiddlewaretoken": token, **fields}, doseq=True)
        return self.request(
            "POST", path, body.encode(), {"Content-Type": "application/x-www-form-urlencoded"}
        )

    def post_file(
        self,
        path: str,
        fields: dict,
        name: str,
        filename: str,
        content: bytes,
        headers: dict | None = None,
    ) -> Answer:
        boundary = "----signstudy-attack-boundary"
        parts = []
        for key, value in {"csrfmiddlewaretoken": self.cookie("csrftoken") or "", **fields}.items():
            parts.append(
                f'--{boundary}\r\nContent-Disposition: form-data; name="{key}"\r\n\r\n'
                f"{value}\r\n".encode()
            )
        parts.append(
            f'--{boundary}\r\nContent-Disposition: form-data; name="{name}"; '
            f'filename="{filename}"\r\nContent-Type: application/zip\r\n\r\n'.encode()
            + content
            + b"\r\n"
        )
        parts.append(f"--{boundary}--\r\n".encode())
        content_type = f"multipart/form-data; boundary={boundary}"
        headers = {"Content-Type": content_type, **(headers or {})}
        return self.request("POST", path, b"".join(parts), headers)

    def sign_in(self, username: str, password: str) -> Answer:
        self.get("/admin/login/")
        fields = {"username": username, "password": password, "next": "/admin/"}
        return self.post_form("/admin/login/?next=/admin/", fields)

    def enroll(self, slug: str, query: str = "") -> str:
        """Take part in study *slug*; return the participant's token."""
        self.get(f"/s/{slug}/")
        answer = self.post_form(f"/s/{slug}/{query}", {"consent": "yes"})
        match = re.search(r"/p/([^/]+)/", answer.headers.get("Location", ""))
        assert match, (answer.status, answer.text[:300])
        return match.group(1)


def bundle(
    definition: dict,
    files: dict[str, bytes],
    extra: dict[str, bytes] | None = None,
    compress: bool = True,
) -> bytes:
    """Return a study bundle zip of *definition* and its files (and *extra* members)."""
    buffer = io.BytesIO()
    method = zipfile.ZIP_DEFLATED if compress else zipfile.ZIP_STORED
    with zipfile.ZipFile(buffer, "w", method) as archive:
        archive.writestr("study.json", json.dumps(definition))
        for name, content in files.items():
            archive.writestr(f"files/{name}", content)
        for member, content in (extra or {}).items():
            archive.writestr(member, content)
    return buffer.getvalue()
