"""Test every kind of GLB the engine exports with the Khronos glTF-Validator (issue 54).

The validator is the reference implementation of the glTF 2.0 specification's rules
(KhronosGroup/glTF-Validator, npm ``gltf-validator``, pinned in package.json and
installed by scripts/bootstrap.sh). Blender, three.js and Unity's glTFast read what it
passes; the issue found the simple avatar's weights refused (ACCESSOR_WEIGHTS_NEGATIVE,
−2.2e-16). Every GLB kind must have 0 errors and 0 warnings.
"""

import json
import shutil
import subprocess
from pathlib import Path

import pytest

from synthesis.interchange import request_glb
from synthesis.techniques import ClipRequest, build_motion

ROOT = Path(__file__).resolve().parents[2]
VALIDATE = ROOT / "scripts" / "gltf_validate.cjs"
KINDS = [
    ("sentence", "ME HAPPY", {"view": "upper-body"}),
    ("sentence", "ME HAPPY", {"view": "upper-body", "avatar": "simple"}),
    ("word", "JAY", {"view": "hand"}),
    ("word", "AB", {"view": "hand", "avatar": "simple"}),
]


def _validated(paths: list[Path]) -> list[dict]:
    if shutil.which("node") is None:
        pytest.skip("NO NODE.JS: the glTF-Validator needs it (scripts/bootstrap.sh, npm)")
    if not (ROOT / "node_modules" / "gltf-validator").is_dir():
        pytest.fail("gltf-validator is not installed: run scripts/bootstrap.sh (npm ci)")
    run = subprocess.run(
        ["node", str(VALIDATE), *map(str, paths)],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=True,
        timeout=300,
    )
    return [json.loads(line) for line in run.stdout.splitlines()]


def test_every_glb_kind_passes_the_khronos_validator(tmp_path):
    paths = []
    for kind, text, parameters in KINDS:
        values = {"rate_hz": 15.0, "width": 320, "height": 240, **parameters}
        request = ClipRequest.from_parameters(kind, text, values)
        path = tmp_path / f"{kind}-{parameters.get('avatar', 'human')}.glb"
        path.write_bytes(request_glb(request, build_motion(request)))
        paths.append(path)
    reports = _validated(paths)
    assert len(reports) == len(KINDS)
    for report in reports:
        assert (report["errors"], report["warnings"]) == (0, 0), report
