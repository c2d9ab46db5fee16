"""Test that the GLB's edge palette draws the engine's colour edges (issue 54, item 7).

The engine draws necklines, cuffs, the waistband and the brows through triangles
(inside where the interpolated edge distance is non-negative); vertex colours blur
them across a triangle in other tools. At random points of every triangle of the human
signer's edged parts, the palette texture sampled NEAREST at the interpolated texture
coordinates (as a glTF viewer samples it) must give the engine's colour. Reference:
glTF 2.0 §3.8.4.2, §5.26; the renderer's rule in synthesis/render/renderer.py.
"""

import numpy as np
import pygltflib as gl
import pytest

from synthesis.avatar.colour import linear_to_srgb
from synthesis.interchange import request_glb
from synthesis.interchange.edge_texture import MAX_PAIRS, edge_texture, sample_nearest
from synthesis.techniques import ClipRequest, build_motion
from synthesis.techniques.request import film


@pytest.fixture(scope="module")
def signer():
    request = ClipRequest.from_parameters(
        "sentence", "ME", {"view": "upper-body", "width": 320, "height": 240, "rate_hz": 10.0}
    )
    build = build_motion(request)
    return request, build, film(request, build)[0]


def _points(part, rng, per_face: int = 4):
    """Return random barycentric weights (faces, k, 3) and the faces' vertex indices."""
    faces = np.asarray(part.faces)
    weights = rng.dirichlet(np.ones(3), size=(len(faces), per_face))
    return faces, weights


def _engine(part, faces, weights) -> np.ndarray:
    """Return the engine's colour (sRGB 0–255) at each point: its fragment rule."""
    edge = np.einsum("fkv,fv->fk", weights, part.edge_m[faces])
    inside = np.einsum("fkv,fvc->fkc", weights, part.colors_rgb[faces])
    across = np.einsum("fkv,fvc->fkc", weights, part.across_rgb[faces])
    return np.where((edge >= 0)[..., None], inside, across) * 255.0, edge


def test_the_palette_draws_the_engines_edges(signer):
    _, _, avatar = signer
    rng = np.random.default_rng(54)
    edged = [part for part in avatar.parts if part.edge_m is not None]
    assert {part.name for part in edged} == {"skin", "features"}
    for part in edged:
        texture = edge_texture(part.edge_m, part.colors_rgb, part.across_rgb)
        assert texture is not None and texture.image_srgb.shape[1] == 2
        faces, weights = _points(part, rng)
        expected, edge = _engine(part, faces, weights)
        uv = np.einsum("fkv,fvc->fkc", weights, texture.texcoords[faces])
        drawn = linear_to_srgb(sample_nearest(texture, uv.reshape(-1, 2))) * 255.0
        drawn = drawn.reshape(expected.shape)
        wrong = np.abs(drawn - expected).max(axis=-1) > 1.5
        # A triangle whose corners share one colour pair is drawn exactly as the engine
        # draws it, but at the edge itself (float32 rounding of the distance).
        one_pair = (texture.rows[faces] == texture.rows[faces][:, :1]).all(axis=1)
        on_edge = np.abs(edge) < 1e-6
        assert not (wrong & one_pair[:, None] & ~on_edge).any(), part.name
        # Where a triangle's corners have different pairs (0.5 % of the skin's triangles,
        # 4.9 % of the face features') the engine blends them, and v would pass through
        # other pairs' rows (an iris's colour between pupil and white): the GLB draws
        # those triangles with vertex colours (the next test).
        assert wrong[one_pair].mean() < 0.001 and (~one_pair).mean() < 0.06
        # The edges are where vertex colours fail: blended, a triangle the edge crosses
        # shows neither colour at most of its points.
        crossing = np.ptp(np.sign(part.edge_m[faces]), axis=1) > 0
        blended = np.einsum("fkv,fvc->fkc", weights, part.vertex_rgb()[faces]) * 255.0
        blur = np.abs(blended - expected).max(axis=-1) > 1.5
        assert blur[crossing & one_pair].mean() > 0.3


def test_the_glb_carries_the_palette_and_no_vertex_colours_on_edged_parts(signer, tmp_path):
    request, build, _ = signer
    path = tmp_path / "clip.glb"
    path.write_bytes(request_glb(request, build))
    gltf = gl.GLTF2().load(str(path))
    by_name = {mesh.name: mesh.primitives for mesh in gltf.meshes}
    for name in ("skin", "features"):
        palette, blended = by_name[name]
        assert palette.attributes.COLOR_0 is None and palette.attributes.TEXCOORD_0 is not None
        material = gltf.materials[palette.material]
        texture = gltf.textures[material.pbrMetallicRoughness.baseColorTexture.index]
        sampler = gltf.samplers[texture.sampler]
        assert (sampler.magFilter, sampler.minFilter) == (gl.NEAREST, gl.NEAREST)
        assert gltf.images[texture.source].mimeType == "image/png"
        # The triangles of two colour pairs: vertex colours over the same vertices.
        assert blended.attributes.COLOR_0 is not None and blended.attributes.TEXCOORD_0 is None
        assert blended.attributes.POSITION == palette.attributes.POSITION
        assert gltf.materials[blended.material].pbrMetallicRoughness.baseColorTexture is None
        assert gltf.accessors[palette.indices].count > 10 * gltf.accessors[blended.indices].count


def test_too_many_colour_pairs_keep_vertex_colours():
    count = MAX_PAIRS + 1
    colours = np.random.default_rng(0).random((count, 3))
    assert edge_texture(np.linspace(-1, 1, count), colours, colours[::-1]) is None
