"""Parse one untrusted file in a confined process: the engine's readers, nothing else.

Run by path under the jail (:mod:`studyplatform.confine.runner`), never imported by the
platform: ``python worker.py TASK NAME [ARGUMENT]`` with the file's bytes on standard
input. It writes one JSON object to standard output: ``{"result": …}``, or
``{"rejected": message}`` naming what is wrong with the file. It imports the engine
(synthesis) and never Django, so it holds no setting, key or connection.
"""

import base64
import contextlib
import json
import os
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


@contextlib.contextmanager
def _named(path: Path, name: str):
    """Name the file in a reader's error by *name*, not by the worker's copy of it."""
    try:
        yield
    except ValueError as error:
        message = str(error).replace(str(path), name).replace(path.name, name)
        raise ValueError(message) from None


def avatar_report(data: bytes, name: str, _: str) -> dict:
    """Return the engine's report on an avatar: joints mapped, fingers, face channels."""
    from synthesis.avatar.imported.gltf_avatar import read_gltf_avatar
    from synthesis.avatar.imported.humanoid import describe_avatar, engine_avatar
    from synthesis.avatar.looks import Look, avatar_for

    imported = read_gltf_avatar(data, f"“{name}”")
    builtin = avatar_for("upper-body", "right", Look())
    engine_avatar(imported, builtin.rig, builtin.bind_pose, builtin.drive)  # maps enough
    return describe_avatar(imported, builtin.rig, builtin.drive)


def mapped_avatar(data: bytes, name: str, bones: str) -> dict:
    """Return the avatar with a bone mapping saved in it (base64) and its new report."""
    from synthesis.avatar.imported.gltf_avatar import with_bone_mapping

    mapped = with_bone_mapping(data, json.loads(bones), name)
    return {"data": base64.b64encode(mapped).decode(), "report": avatar_report(mapped, name, "")}


def motion(data: bytes, name: str, suffix: str) -> dict:
    """Check a recording's motion (.pose, BVH, glTF, FBX); return its frame count, rate,
    and for glTF and FBX the motion as BVH text (what clips read)."""
    from synthesis.capture import PoseFileError, parse_pose
    from synthesis.skeleton.bvh import format_bvh, parse_bvh

    if suffix == ".pose":
        recording = parse_pose(data, name)
        if not any(recording.found_hands().values()):
            raise PoseFileError(f"{name}: no hand in any frame.")
        return {"frames": recording.n_frames, "fps": recording.fps}
    if suffix == ".bvh":
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError:
            raise ValueError(f"“{name}” is not a BVH text file.") from None
        parsed = parse_bvh(text, name)
        return {"frames": parsed.n_frames, "fps": parsed.rate_hz}
    from synthesis.avatar.imported.motion import read_motion_file

    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / f"motion{suffix}"
        path.write_bytes(data)
        with _named(path, name):
            read = read_motion_file(path)
    return {"frames": read.n_frames, "fps": read.rate_hz, "bvh": format_bvh(read)}


def video_capture(data: bytes, name: str, options: str) -> dict:
    """Capture the hands in a recording's video (MediaPipe), fit the hand to them and
    draw the contact sheet; return the landmarks (``.pose``) and the sheet (PNG, None
    where nothing renders), base64. *options*: JSON of suffix, mirrored, one_hand, side."""
    from synthesis.capture import captured_hand, format_pose
    from synthesis.capture.contact import contact_sheet_png
    from synthesis.capture.video import capture_hands, expected_frames
    from synthesis.render.backend import RenderUnavailable

    chosen = json.loads(options)
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / f"video{chosen['suffix']}"
        path.write_bytes(data)
        total = expected_frames(path) or 0
        step = max(1, total // 20)

        def report(done: int) -> None:  # read by the parent (runner.confined_run)
            if total and done % step == 0:
                percent = min(99, round(100 * done / total))
                (Path(os.environ["TMPDIR"]) / "progress").write_text(str(percent))

        with _named(path, name):
            landmarks = capture_hands(
                path, mirrored=chosen["mirrored"], one_hand=chosen["one_hand"], progress=report
            )
        try:
            sheet = contact_sheet_png(captured_hand(landmarks, chosen["side"]), path)
        except RenderUnavailable:  # a machine without OpenGL still captures
            sheet = None
    return {
        "pose": base64.b64encode(format_pose(landmarks)).decode(),
        "sheet": base64.b64encode(sheet).decode() if sheet is not None else None,
    }


TASKS = {
    "avatar": avatar_report,
    "mapped_avatar": mapped_avatar,
    "motion": motion,
    "capture": video_capture,
}


def main(argv: list[str]) -> None:
    sys.path.insert(0, str(ROOT))
    task, name = TASKS[argv[1]], argv[2]
    argument = argv[3] if len(argv) > 3 else ""
    data = sys.stdin.buffer.read()
    try:
        answer = {"result": task(data, name, argument)}
    except MemoryError:
        answer = {"rejected": f"{name} needs more memory than a file is given to be read."}
    except RecursionError:
        answer = {"rejected": f"{name} is nested too deeply to be read."}
    except ValueError as error:  # the engine's readers name the problem (GltfError, …)
        answer = {"rejected": str(error)}
    except Exception as error:  # anything else a hostile file provokes is its damage
        answer = {"rejected": f"{name} cannot be read: it is damaged ({type(error).__name__})."}
    sys.stdout.write(json.dumps(answer))
    sys.stdout.flush()
    os._exit(0)  # no interpreter teardown: the answer is out


if __name__ == "__main__":
    main(sys.argv)
