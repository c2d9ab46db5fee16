"""Render an imported avatar's preview stills: at rest, a letter, a face channel."""

import tempfile
from pathlib import Path

import numpy as np

STILLS = {
    "rest": ("sentence", "ME", 0),
    "letter": ("word", "B", None),
    "face": ("sentence", "[rhq WHERE]", None),
}


def avatar_stills(
    path: str | Path, side: str = "right", size: tuple[int, int] = (320, 240)
) -> dict[str, bytes]:
    """Return PNG stills of the avatar file at *path* in the signing view: at rest, holding
    the letter B (its hand's bones), and raising its brows for a question (its face)."""
    from synthesis.render.clip import render_still
    from synthesis.techniques import ClipRequest, build_motion, filming

    stills = {}
    for name, (kind, text, frame) in STILLS.items():
        parameters = {
            "avatar_file": str(path),
            "rate_hz": 15.0,
            "view": "upper-body",
            "side": side,
            "width": size[0],
            "height": size[1],
        }
        request = ClipRequest.from_parameters(kind, text, parameters)
        build = build_motion(request)
        avatar, camera = filming("upper-body", side, build.motion, 15.0, *size, look=build.look)
        if frame is None and name == "face":
            engine = build.rig
            face = [engine.dof_names.index(n) for n in engine.dof_names if n.endswith("brow_raise")]
            frame = int(np.argmax(np.abs(build.motion[:, face]).sum(axis=1)))
        elif frame is None:
            frame = len(build.motion) // 2  # the letter's hold
        with tempfile.TemporaryDirectory() as folder:
            out = render_still(
                avatar, build.motion[frame], camera, Path(folder) / "still.png", *size
            )
            stills[name] = Path(out).read_bytes()
    return stills
