"""Read and write BVH motion files (grammar: seed 004 App. B).

Reading then writing then reading gives bit-identical values: numbers are written in
their shortest exact decimal form. Every problem in a file raises :class:`BvhError`
naming the file and line, never quoting what the file holds beyond the grammar's own
words (a file named by mistake, a server's key say, must not come back in an error:
issue 51). End Sites become joints named ``<parent>_End``.
"""

import io
import math
import warnings
from pathlib import Path

import numpy as np

from synthesis.skeleton.motion import Motion
from synthesis.skeleton.skeleton import CHANNEL_NAMES, Joint, Skeleton, guess_length_unit

MAX_DEPTH = 256
_CHANNEL_LOOKUP = {name.lower(): name for name in CHANNEL_NAMES}
_KEYWORDS = {"HIERARCHY", "ROOT", "JOINT", "OFFSET", "CHANNELS", "END SITE", "MOTION", "{", "}"}


def _described(token: str) -> str:
    """Return *token* as an error may show it: the grammar's own words quoted, anything
    else only by its kind and length."""
    if token.upper() in _KEYWORDS or token.lower() in _CHANNEL_LOOKUP:
        return repr(token)
    try:
        float(token)
    except ValueError:
        return f"other text ({len(token)} character{'s' if len(token) != 1 else ''})"
    return "a number"


class BvhWarning(UserWarning):
    """A BVH file read leniently, as the field's tools read it (a frame line too many)."""


class BvhError(ValueError):
    """A BVH file that cannot be read; the message names the file and line."""


class _Tokens:
    """Hierarchy tokens with their line numbers; a joint's name is the rest of its line."""

    def __init__(self, lines: list[str], source: str):
        self.source = source
        self.items: list[tuple[str, int]] = []
        self.motion_line: int | None = None
        for number, line in enumerate(lines, start=1):
            words = line.split()
            if not words:
                continue
            head = words[0].upper()
            if head == "MOTION":
                self.motion_line = number
                if len(words) > 1:
                    raise self.error(number, "unexpected text after MOTION")
                break
            if head in ("ROOT", "JOINT"):
                name = line.strip()[len(words[0]) :].strip()
                opens = name.endswith("{")
                name = name.rstrip("{").strip()
                self.items += [(head, number), (name, number)]
                if opens:
                    self.items.append(("{", number))
            elif head == "END" and len(words) > 1 and words[1].upper().startswith("SITE"):
                self.items.append(("END SITE", number))
                rest = " ".join(words[1:])[4:].strip()
                if rest:
                    self.items += [(word, number) for word in rest.split()]
            else:
                self.items += [(word, number) for word in words]
        self.position = 0

    def error(self, line: int | None, message: str) -> BvhError:
        where = f"line {line}" if line is not None else "end of file"
        return BvhError(f"{self.source}, {where}: {message}.")

    def peek(self) -> tuple[str, int | None]:
        if self.position < len(self.items):
            return self.items[self.position]
        return "", None

    def take(self, expected: str | None = None) -> tuple[str, int | None]:
        token, line = self.peek()
        if line is None:
            raise self.error(None, f"file ends early; expected {expected or 'more'}")
        if expected is not None and token.upper() != expected:
            raise self.error(line, f"expected {expected}, found {_described(token)}")
        self.position += 1
        return token, line

    def offset(self) -> tuple[float, float, float]:
        """Take an OFFSET's three numbers."""
        return (
            self.number("OFFSET value"),
            self.number("OFFSET value"),
            self.number("OFFSET value"),
        )

    def number(self, what: str) -> float:
        token, line = self.take()
        try:
            value = float(token)
        except ValueError:
            raise self.error(line, f"{what}: {_described(token)} is not a number") from None
        if not math.isfinite(value):
            raise self.error(line, f"{what} must be finite")
        return value


def _parse_channels(tokens: _Tokens, name: str) -> tuple[str, ...]:
    """Parse a CHANNELS list (its keyword already taken): the count, then the names."""
    count_token, count_line = tokens.take()
    if not count_token.isdigit():
        raise tokens.error(
            count_line, f"channel count: {_described(count_token)} is not a whole number"
        )
    found = []
    for _ in range(int(count_token)):
        channel, channel_line = tokens.take()
        if channel.lower() not in _CHANNEL_LOOKUP:
            raise tokens.error(
                channel_line,
                f"unknown channel {_described(channel)} (expected {', '.join(CHANNEL_NAMES)})",
            )
        found.append(_CHANNEL_LOOKUP[channel.lower()])
    if len(set(found)) != len(found):
        raise tokens.error(count_line, "the joint lists a channel twice")
    return tuple(found)


def _parse_end_site(tokens: _Tokens, joints: list[Joint], parent: int, name: str) -> None:
    """Parse an End Site block (its keyword already taken) into a channel-less joint."""
    tokens.take("{")
    tokens.take("OFFSET")
    site_offset = tokens.offset()
    tokens.take("}")
    site_name = f"{name}_End"
    while any(joint.name == site_name for joint in joints):
        site_name += "_"
    joints.append(Joint(site_name, parent, site_offset, (), is_end_site=True))


def _parse_joint(
    tokens: _Tokens, joints: list[Joint], parent: int, keyword: str, depth: int
) -> None:
    """Parse one ROOT/JOINT block (its keyword already taken) and its children."""
    name, line = tokens.take()
    if depth > MAX_DEPTH:
        raise tokens.error(line, f"joints nested deeper than {MAX_DEPTH}")
    if not name or name == "{":
        raise tokens.error(line, f"{keyword} needs a name")
    if any(joint.name == name for joint in joints):
        raise tokens.error(line, "a second joint has a name already taken")
    tokens.take("{")
    tokens.take("OFFSET")
    offset = tokens.offset()
    channels: tuple[str, ...] = ()
    if tokens.peek()[0].upper() == "CHANNELS":
        tokens.take()
        channels = _parse_channels(tokens, name)
    elif keyword == "ROOT":
        raise tokens.error(tokens.peek()[1], "the ROOT needs CHANNELS")
    index = len(joints)
    joints.append(Joint(name, parent, offset, channels))
    while True:
        token, token_line = tokens.peek()
        upper = token.upper()
        if upper == "}":
            tokens.take()
            return
        if upper == "JOINT":
            tokens.take()
            _parse_joint(tokens, joints, index, "JOINT", depth + 1)
        elif upper == "END SITE":
            tokens.take()
            _parse_end_site(tokens, joints, index, name)
        elif token_line is None:
            raise tokens.error(None, f"file ends inside the joint of line {line}; expected '}}'")
        else:
            raise tokens.error(
                token_line, f"expected JOINT, End Site or '}}', found {_described(token)}"
            )


def _header_value(line: str, keyword: str, number: int, source: str) -> str:
    head, _, value = line.partition(":")
    if " ".join(head.split()).upper() != keyword.upper():
        raise BvhError(f"{source}, line {number}: expected '{keyword}:'.")
    return value.strip()


def _read_numbers(text: str) -> np.ndarray | None:
    """Parse whitespace-separated rows of numbers; None if they do not form a table.

    pandas' C reader parses about twice as fast as numpy.loadtxt and, since pandas 3,
    rounds exactly like Python's float(), so BVH values round-trip bit for bit.
    """
    import pandas as pd

    try:
        frame = pd.read_csv(io.StringIO(text), sep=r"\s+", header=None, dtype=np.float64)
    except (ValueError, pd.errors.ParserError, pd.errors.EmptyDataError):
        return None
    return frame.to_numpy(dtype=np.float64)


def _unreadable_values(rows, values, n_channels: int, source: str) -> BvhError:
    """Return the error naming the first frame line that cannot be read as values."""
    for number, line in rows:
        words = line.split()
        if len(words) != n_channels:
            return BvhError(
                f"{source}, line {number}: {len(words)} values, expected {n_channels} "
                "(one per channel)."
            )
        for word in words:
            try:
                float(word)
            except ValueError:
                return BvhError(f"{source}, line {number}: {_described(word)} is not a number.")
    if values is not None and np.isnan(values).any():
        row = int(np.flatnonzero(np.isnan(values).any(axis=1))[0])
        return BvhError(f"{source}, line {rows[row][0]}: values must be finite numbers.")
    return BvhError(f"{source}: the frame values cannot be read.")


def _parse_values(
    lines: list[str], first_line: int, n_frames: int, n_channels: int, source: str
) -> np.ndarray:
    """Parse the frame lines into an (n_frames, n_channels) array."""
    rows = [(first_line + k, line) for k, line in enumerate(lines) if line.strip()]
    if n_channels == 0:
        # No channels: frames are empty lines, so only the declared count says how many.
        if rows:
            raise BvhError(f"{source}, line {rows[0][0]}: values given but no joint has channels.")
        return np.zeros((n_frames, 0))
    if len(rows) < n_frames:
        raise BvhError(
            f"{source}, line {first_line + len(lines)}: 'Frames: {n_frames}' but the file "
            f"has {len(rows)} frame lines (cut short?)."
        )
    # Lines past the declared count are left out, as assimp does (CMU's Boxing_Toes.bvh
    # declares 3069 frames above 3070 lines; Blender and bvhio read it too), and said.
    if len(rows) > n_frames:
        warnings.warn(
            f"{source}: 'Frames: {n_frames}' above {len(rows)} frame lines; the last "
            f"{len(rows) - n_frames} left out, as assimp reads it.",
            BvhWarning,
            stacklevel=2,
        )
    rows = rows[:n_frames]
    if n_frames == 0:
        return np.zeros((0, n_channels))
    values = _read_numbers("\n".join(line for _, line in rows))
    if values is None or values.shape != (n_frames, n_channels) or np.isnan(values).any():
        raise _unreadable_values(rows, values, n_channels, source)
    bad = ~np.isfinite(values)
    if bad.any():
        row = int(np.flatnonzero(bad.any(axis=1))[0])
        raise BvhError(f"{source}, line {rows[row][0]}: values must be finite numbers.")
    return values


def _motion_header(lines: list[str], motion_line: int, source: str) -> tuple[int, float, int]:
    """Return the MOTION section's frame count and frame time, and the frame time's line."""
    header = [
        (number, line)
        for number, line in enumerate(lines[motion_line:], start=motion_line + 1)
        if line.strip()
    ][:2]
    if len(header) < 2:
        raise BvhError(f"{source}, end of file: expected 'Frames:' and 'Frame Time:' after MOTION.")
    (frames_line, frames_text), (time_line, time_text) = header
    frames_value = _header_value(frames_text, "Frames", frames_line, source)
    if not frames_value.isdigit():
        raise BvhError(f"{source}, line {frames_line}: the frame count is not a whole number.")
    time_value = _header_value(time_text, "Frame Time", time_line, source)
    try:
        frame_time = float(time_value)
    except ValueError:
        raise BvhError(f"{source}, line {time_line}: the frame time is not a number.") from None
    if not (math.isfinite(frame_time) and frame_time > 0):
        raise BvhError(f"{source}, line {time_line}: frame time must be positive.")
    return int(frames_value), frame_time, time_line


def parse_bvh(text: str, source: str = "<bvh>", length_unit: str | None = None) -> Motion:
    """Parse BVH text into a Motion; *length_unit* overrides the guessed unit ("cm", "m", …)."""
    lines = text.splitlines()
    tokens = _Tokens(lines, source)
    tokens.take("HIERARCHY")
    joints: list[Joint] = []
    while tokens.peek()[1] is not None:
        token, line = tokens.peek()
        if token == "}":
            raise tokens.error(line, "'}' closes nothing (one brace too many)")
        tokens.take("ROOT")
        _parse_joint(tokens, joints, -1, "ROOT", 0)
    if not joints:
        raise tokens.error(tokens.motion_line, "no ROOT joint")
    if tokens.motion_line is None:
        raise BvhError(f"{source}, end of file: MOTION section missing.")
    n_frames, frame_time, time_line = _motion_header(lines, tokens.motion_line, source)
    n_channels = sum(len(joint.channels) for joint in joints)
    values = _parse_values(lines[time_line:], time_line + 1, n_frames, n_channels, source)
    offsets = np.array([joint.offset for joint in joints], dtype=np.float64)
    parents = np.array([joint.parent for joint in joints])
    unit = length_unit or guess_length_unit(offsets, parents)
    return Motion(Skeleton(tuple(joints), length_unit=unit), values, frame_time)


def read_bvh(path: str | Path, length_unit: str | None = None) -> Motion:
    """Read a BVH file (see :func:`parse_bvh`)."""
    path = Path(path)
    try:
        data = path.read_bytes()
    except OSError as error:
        raise BvhError(f"{path}: cannot read the file ({error.strerror}).") from None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        text = data.decode("latin-1")  # old exporters write joint names in Latin-1
    if "\x00" in text:
        raise BvhError(f"{path}: not a text file.")
    return parse_bvh(text, str(path), length_unit)


def _number(value: float) -> str:
    """Write a float in its shortest exact positional form ("-90", "0.1", "1e-7" → "0.0000001")."""
    return np.format_float_positional(value, unique=True, trim="-")


def format_bvh(motion: Motion) -> str:
    """Return *motion* as BVH text, tab-indented, one frame a line."""
    skeleton = motion.skeleton
    out = io.StringIO()
    out.write("HIERARCHY\n")

    def write_joint(index: int, depth: int) -> None:
        joint = skeleton.joints[index]
        pad = "\t" * depth
        offset = " ".join(_number(v) for v in joint.offset)
        if joint.is_end_site:
            out.write(f"{pad}End Site\n{pad}{{\n{pad}\tOFFSET {offset}\n{pad}}}\n")
            return
        keyword = "ROOT" if joint.parent < 0 else "JOINT"
        out.write(f"{pad}{keyword} {joint.name}\n{pad}{{\n{pad}\tOFFSET {offset}\n")
        if joint.channels or joint.parent < 0:
            out.write(f"{pad}\tCHANNELS {len(joint.channels)} {' '.join(joint.channels)}".rstrip())
            out.write("\n")
        for child in skeleton.children(index):
            write_joint(child, depth + 1)
        out.write(f"{pad}}}\n")

    for index, joint in enumerate(skeleton.joints):
        if joint.parent < 0:
            write_joint(index, 0)
    out.write(f"MOTION\nFrames: {motion.n_frames}\nFrame Time: {_number(motion.frame_time_s)}\n")
    for row in motion.values:
        out.write(" ".join(_number(v) for v in row))
        out.write("\n")
    return out.getvalue()


def write_bvh(motion: Motion, path: str | Path) -> None:
    """Write *motion* to a BVH file."""
    Path(path).write_text(format_bvh(motion), encoding="utf-8")
