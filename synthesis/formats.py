"""Check the header of a versioned file: the one check every format of the project uses.

Every file the project writes for itself (sign libraries, timing models, word timings,
transition databases, lexicons, letter routes, stimuli manifests, study definitions,
backups) is a JSON or YAML mapping with ``format`` and ``version`` keys.
"""


def check_header(
    data, expected_format: str, version: int, what: str, error=ValueError, where: str = ""
) -> None:
    """Raise *error* naming the problem unless *data* is a mapping of *expected_format* at
    *version*; *where* (a path) starts the message when given."""
    prefix = f"{where}: " if where else ""
    found = data.get("format") if isinstance(data, dict) else type(data).__name__
    if not isinstance(data, dict) or found != expected_format:
        article = "not" if prefix else "Not"
        raise error(f"{prefix}{article} a {what} (format {expected_format!r}, not {found!r}).")
    if data.get("version") != version:
        unsupported = "unsupported" if prefix else "Unsupported"
        raise error(
            f"{prefix}{unsupported} {what} version {data.get('version')!r} (this "
            f"installation reads version {version})."
        )
