"""Test that three.js shows a clip's GLB in the colours we render (issue 54, item 1).

glTF 2.0 defines vertex colours (COLOR_0) as linear; the engine wrote display (sRGB)
values, so every viewer showed a paler signer: three.js r187 gave the skin (218, 188,
166) where we mean (178, 128, 97). three.js (npm ``three``, pinned in package.json and
installed by scripts/bootstrap.sh) loads the file with its own GLTFLoader in Chromium
and draws the first frame unlit from the file's camera; its skin must be ours within 3
levels of 255. Reference: glTF 2.0 §3.7.2.1 (COLOR_0 is linear), three.js's colour
management (linear working space, sRGB output).
"""

import os
from pathlib import Path

import numpy as np
import pytest

from synthesis.avatar.human.build import DEFAULT_SKIN_TONE, SKIN_TONES
from synthesis.interchange import request_glb
from synthesis.techniques import ClipRequest, build_motion
from tests.conftest import CHROMIUM

ROOT = Path(__file__).resolve().parents[2]
THREE = ROOT / "node_modules" / "three"
ORIGIN = "http://three.test"
WIDTH, HEIGHT = 640, 480
# WebGL in headless Chromium without a GPU: ANGLE's software renderer.
WEBGL_ARGS = ["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader"]
PAGE = """<!doctype html><html><body style="margin:0">
<script type="importmap">{"imports": {"three": "/three/build/three.module.js",
  "three/addons/": "/three/examples/jsm/"}}</script>
<script type="module">
import * as THREE from "three";
import {GLTFLoader} from "three/addons/loaders/GLTFLoader.js";
const renderer = new THREE.WebGLRenderer({preserveDrawingBuffer: true});
renderer.setSize(WIDTH, HEIGHT);
document.body.appendChild(renderer.domElement);
new GLTFLoader().load("/clip.glb", (gltf) => {
  const scene = gltf.scene;
  scene.background = new THREE.Color(0, 0, 0);
  scene.traverse((o) => {
    // Unlit, each mesh in its own colours: vertex colours or its base colour texture.
    if (o.isMesh) o.material = new THREE.MeshBasicMaterial({
      vertexColors: Boolean(o.geometry.attributes.color), map: o.material.map});
  });
  new THREE.AnimationMixer(scene).clipAction(gltf.animations[0]).play().getMixer().update(0);
  const camera = gltf.cameras[0];
  camera.aspect = WIDTH / HEIGHT;
  camera.updateProjectionMatrix();
  renderer.render(scene, camera);
  const gl = renderer.getContext();
  const pixels = new Uint8Array(WIDTH * HEIGHT * 4);
  gl.readPixels(0, 0, WIDTH, HEIGHT, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
  const morphNames = [];
  scene.traverse((o) => {
    if (o.morphTargetDictionary) morphNames.push(...Object.keys(o.morphTargetDictionary));
  });
  window.result = {pixels: Array.from(pixels), revision: THREE.REVISION, morphNames};
}, undefined, (error) => { window.result = {error: String(error)}; });
</script></body></html>""".replace("WIDTH", str(WIDTH)).replace("HEIGHT", str(HEIGHT))


def _serve(route, glb: bytes) -> None:
    """Answer the page, three.js's modules and the clip from memory and node_modules."""
    path = route.request.url.removeprefix(ORIGIN)
    if path == "/clip.glb":
        route.fulfill(body=glb, content_type="model/gltf-binary")
    elif path.startswith("/three/"):
        file = (THREE / path.removeprefix("/three/")).resolve()
        if not file.is_relative_to(THREE.resolve()) or not file.is_file():
            route.fulfill(status=404)
        else:
            route.fulfill(body=file.read_bytes(), content_type="text/javascript")
    else:
        route.fulfill(body=PAGE, content_type="text/html")


def test_threejs_shows_the_signers_skin_in_our_colour():
    if not os.path.exists(CHROMIUM):
        pytest.skip(f"BROWSER TEST SKIPPED: {CHROMIUM} is missing (run `make test` as root)")
    if not THREE.is_dir():
        pytest.fail("three is not installed: run scripts/bootstrap.sh (npm ci)")
    from playwright.sync_api import sync_playwright

    values = {"rate_hz": 15.0, "width": WIDTH, "height": HEIGHT}
    request = ClipRequest.from_parameters("sentence", "ME HAPPY", values)
    glb = request_glb(request, build_motion(request))
    with sync_playwright() as playwright:
        chromium = playwright.chromium.launch(executable_path=CHROMIUM, args=WEBGL_ARGS)
        page = chromium.new_page()
        page.route(f"{ORIGIN}/**", lambda route: _serve(route, glb))
        page.goto(f"{ORIGIN}/")
        page.wait_for_function("window.result !== undefined", timeout=120_000)
        result = page.evaluate("window.result")
        chromium.close()
    assert "error" not in result, result
    assert result["revision"] == "187"
    # The face's morph targets by ARKit name, from the meshes' extras.targetNames.
    assert {"jawOpen", "browInnerUp", "eyeBlinkLeft"} <= set(result["morphNames"])
    pixels = np.array(result["pixels"], dtype=np.uint8).reshape(HEIGHT, WIDTH, 4)[..., :3]
    ours = np.array(SKIN_TONES[DEFAULT_SKIN_TONE][0]) * 255  # sRGB (178.5, 127.5, 96.9)
    colours, counts = np.unique(pixels.reshape(-1, 3), axis=0, return_counts=True)
    near = np.abs(colours - ours).max(axis=1) <= 12  # skin, shaded by nothing (unlit)
    assert counts[near].sum() > 2000  # the face and hands
    shown = colours[near][np.argmax(counts[near])]
    assert np.abs(shown - ours).max() <= 3, (tuple(shown), tuple(ours))
