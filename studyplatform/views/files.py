"""Send a file with byte ranges and conditional requests (RFC 9110 §14, §13).

Browsers' ``<video>`` asks for ranges, and Safari on iOS plays nothing from a server
that ignores them. One range is served as 206; several ranges, or an ``If-Range`` that
no longer matches, get the whole file (allowed by §14.2); a range past the end, 416.
"""

import mimetypes
import re
from pathlib import Path

from django.http import FileResponse, HttpRequest, HttpResponse
from django.utils.cache import get_conditional_response
from django.utils.http import http_date, quote_etag

RANGE = re.compile(r"^bytes=(\d*)-(\d*)$")
# A range is streamed through Python (no sendfile): larger reads than FileResponse's
# 4 KiB keep a whole-video range ("bytes=0-", what Chromium asks first) cheap.
CHUNK_BYTES = 64 * 1024


class _Slice:
    """Read at most *length* bytes of *file* from *start* (FileResponse streams it)."""

    def __init__(self, file, start: int, length: int):
        file.seek(start)
        self.file, self.left = file, length

    def read(self, size: int = -1) -> bytes:
        size = self.left if size < 0 else min(size, self.left)
        data = self.file.read(size)
        self.left -= len(data)
        return data

    def close(self) -> None:
        self.file.close()


def _requested_range(header: str, size: int) -> tuple[int, int] | bool | None:
    """Return (first, last) of a single byte range, None for the whole file, or False
    for a range that cannot be satisfied."""
    match = RANGE.match(header.replace(" ", ""))
    if match is None:  # several ranges or another unit: send the whole file
        return None
    first, last = match.groups()
    if not first and not last:
        return None
    if not first:  # the last N bytes
        length = int(last)
        return (max(size - length, 0), size - 1) if length and size else False
    start = int(first)
    if start >= size:
        return False
    return start, min(int(last), size - 1) if last else size - 1


def file_response(request: HttpRequest, path: Path, *, cache_control: str) -> HttpResponse:
    """Answer a GET or HEAD for the file at *path* (which exists), honouring ranges."""
    stat = path.stat()
    size = stat.st_size
    etag = quote_etag(f"{stat.st_mtime_ns:x}-{size:x}")
    last_modified = http_date(stat.st_mtime)
    # Django's RFC 9110 §13.2.2 evaluation: If-Match, If-None-Match, If-Modified-Since…
    conditional = get_conditional_response(request, etag=etag, last_modified=int(stat.st_mtime))
    if conditional is not None:
        conditional["ETag"], conditional["Cache-Control"] = etag, cache_control
        return conditional
    byte_range = None
    still_same = request.headers.get("If-Range", etag) in (etag, last_modified)
    if "Range" in request.headers and still_same:
        byte_range = _requested_range(request.headers["Range"], size)
    content_type = mimetypes.guess_type(path.name)[0] or "application/octet-stream"
    if byte_range is False:
        response = HttpResponse(status=416, content_type=content_type)
        response["Content-Range"] = f"bytes */{size}"
    elif request.method == "HEAD":
        response = HttpResponse(content_type=content_type)
        response["Content-Length"] = str(size)
    # FileResponse closes the file once the body is sent: no context manager here.
    elif byte_range is None:
        response = FileResponse(open(path, "rb"), content_type=content_type)  # noqa: SIM115
    else:
        first, last = byte_range
        body = _Slice(open(path, "rb"), first, last - first + 1)  # noqa: SIM115
        response = FileResponse(body, status=206, content_type=content_type)
        response.block_size = CHUNK_BYTES
        response["Content-Range"] = f"bytes {first}-{last}/{size}"
        response["Content-Length"] = str(last - first + 1)
    response["Accept-Ranges"] = "bytes"
    response["ETag"], response["Last-Modified"] = etag, last_modified
    response["Cache-Control"] = cache_control
    return response
