"""Test that Blender shows a clip's GLB as we render it (issue 54: exports the field's
tools read as we see them).

Blender 3.4 (Debian's ``blender``, scripts/system-packages.txt) imports the GLB with its
own glTF importer, at the frame rate the file's extras name (the researcher guide's
steps), and draws a frame through the file's camera (scripts/blender_frame.py). Its
silhouette must be ours at the same frame: intersection over union at least 0.98 and
every outline pixel within 2 px of the other's, at 320 × 240. The check must tell
frames apart: our frame eight frames earlier fails it. Both views are checked: the
signing view with the face's morph targets, and the close-up whose camera follows the
hand. Blender names the face's shape keys from the meshes' ``extras.targetNames``
(ARKit's names), where three.js reads them too (test_gltf_three_browser.py).
Reference: glTF 2.0 §3.7.3 (skins), §3.11 (animations), §3.10 (cameras).
"""

import json
import shutil
import subprocess
from pathlib import Path

import imageio.v3 as iio
import numpy as np
import pytest
from scipy import ndimage

from synthesis.interchange import request_glb
from synthesis.render.renderer import Renderer
from synthesis.render.scene import CameraPath
from synthesis.techniques import ClipRequest, build_motion
from synthesis.techniques.request import film

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "scripts" / "blender_frame.py"
WIDTH, HEIGHT = 320, 240
KINDS = {
    # kind, text, view; bones and shape keys Blender must find
    "signing view": ("sentence", "ME HAPPY", "upper-body", 73, 72),
    "close-up": ("word", "JAY", "hand", 22, 0),
}


def _blender_frame(glb: Path, frame: int, out: Path) -> dict:
    """Draw *frame* of *glb* in Blender; return what its importer found."""
    blender = shutil.which("blender")
    if blender is None:
        pytest.skip("BLENDER TEST SKIPPED: no `blender` (scripts/bootstrap.sh installs it)")
    script = [str(SCRIPT), "--", str(glb), str(frame), str(WIDTH), str(HEIGHT), str(out)]
    run = subprocess.run(
        [blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python", *script],
        capture_output=True,
        text=True,
        timeout=300,
    )
    lines = [line for line in run.stdout.splitlines() if line.startswith("{")]
    assert run.returncode == 0 and lines, run.stdout[-3000:] + run.stderr[-3000:]
    return json.loads(lines[-1])


def _silhouette(mask: np.ndarray) -> np.ndarray:
    return ndimage.binary_fill_holes(mask)


def _outline_distance(a: np.ndarray, b: np.ndarray) -> float:
    """Return the largest distance in pixels from either outline to the other."""

    def outline(mask):
        return mask ^ ndimage.binary_erosion(mask)

    to_a = ndimage.distance_transform_edt(~outline(a))
    to_b = ndimage.distance_transform_edt(~outline(b))
    return float(max(to_a[outline(b)].max(), to_b[outline(a)].max()))


def _iou(a: np.ndarray, b: np.ndarray) -> float:
    return float((a & b).sum() / (a | b).sum())


@pytest.mark.parametrize("name", KINDS)
def test_blender_draws_our_frame(name, tmp_path):
    kind, text, view, bones, shape_keys = KINDS[name]
    values = {"rate_hz": 15.0, "width": WIDTH, "height": HEIGHT, "view": view}
    request = ClipRequest.from_parameters(kind, text, values)
    build = build_motion(request)
    glb = tmp_path / "clip.glb"
    glb.write_bytes(request_glb(request, build))
    frame = len(build.motion) // 2
    found = _blender_frame(glb, frame, tmp_path / "blender.png")
    assert found["blender"].startswith("3.") and found["fps"] == 15.0
    assert (found["bones"], found["shape_keys"], found["cameras"]) == (bones, shape_keys, 1)
    assert found["skinned"] == found["meshes"] == 2
    if shape_keys:  # named from the mesh's extras.targetNames, as Blender reads them
        assert {"jawOpen", "browInnerUp", "eyeBlinkLeft"} <= set(found["shape_key_names"])
    theirs = _silhouette(iio.imread(tmp_path / "blender.png")[..., 3] > 127)

    avatar, camera = film(request, build)

    def ours(number: int) -> np.ndarray:
        at = camera.at(number) if isinstance(camera, CameraPath) else camera
        with Renderer(avatar, at, WIDTH, HEIGHT) as renderer:
            pixels = renderer.frame(build.motion[number]).astype(int)
        background = pixels[0, 0]  # the backdrop's flat colour
        return _silhouette(np.abs(pixels - background).max(axis=-1) > 24)

    same = ours(frame)
    assert same.sum() > 0.1 * WIDTH * HEIGHT  # the signer fills the frame
    assert _iou(same, theirs) >= 0.98, _iou(same, theirs)
    assert _outline_distance(same, theirs) <= 2.0
    earlier = ours(frame - 8)
    assert _iou(earlier, theirs) < 0.98 or _outline_distance(earlier, theirs) > 2.0
