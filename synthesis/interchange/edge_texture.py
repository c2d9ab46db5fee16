"""Bake a part's colour edge (a neckline, a cuff, a brow) into a glTF palette texture.

The engine draws an edge through triangles: a fragment takes the colour inside where
its interpolated distance to the edge is non-negative, the colour across elsewhere
(:mod:`synthesis.render.renderer`). glTF's core has no such rule, and vertex colours
blend across a triangle, so other tools drew jagged necklines and blotchy brows
(issue 54). The same rule fits glTF's core with a texture sampled NEAREST: each
distinct (inside, across) colour pair is a row of two texels, across then inside, and
a vertex's texture coordinate is ``u = ½ + ½·d/max|d|``, ``v`` its pair's row centre.
``u`` is affine in the distance ``d``, so the interpolated ``u`` crosses the texels'
border (½) exactly where ``d`` crosses 0, as the engine's does. A triangle whose
corners have different pairs would pass through the rows between theirs: the GLB
draws those with vertex colours (:mod:`synthesis.interchange.glb`). Reference: glTF 2.0
§3.8.4.2 (texture coordinates interpolated across a triangle), §5.26 (sampler
``NEAREST``), OpenGL ES 3.0 §3.8.10 (nearest texel: ``⌊u·width⌋``).
"""

from dataclasses import dataclass

import numpy as np

from synthesis.avatar.colour import srgb_to_linear

# A palette larger than this is not an edge's few colours: keep vertex colours.
MAX_PAIRS = 256


@dataclass(frozen=True)
class EdgeTexture:
    """A palette image (rows × 2 texels, sRGB 0–255), each vertex's (u, v) in it and
    its row (colour pair)."""

    image_srgb: np.ndarray
    texcoords: np.ndarray
    rows: np.ndarray


def edge_texture(
    edge_m: np.ndarray, inside_rgb: np.ndarray, across_rgb: np.ndarray
) -> EdgeTexture | None:
    """Return the palette texture drawing *edge_m*'s edge between the vertices' inside
    and across colours (sRGB 0–1), or None when the colours are too many for a palette.
    """
    pairs = np.round(np.column_stack([inside_rgb, across_rgb]) * 255.0).astype(np.uint8)
    palette, rows = np.unique(pairs, axis=0, return_inverse=True)
    if len(palette) > MAX_PAIRS:
        return None
    # Whole powers of two: every viewer samples them as written.
    height = 1 << max(0, int(np.ceil(np.log2(len(palette)))))
    image = np.zeros((height, 2, 3), dtype=np.uint8)
    image[: len(palette), 0], image[: len(palette), 1] = palette[:, 3:], palette[:, :3]
    image[len(palette) :] = image[len(palette) - 1]
    scale = float(np.abs(edge_m).max()) or 1.0
    u = 0.5 + 0.5 * np.asarray(edge_m, float) / scale
    v = (rows.ravel() + 0.5) / height
    return EdgeTexture(image, np.column_stack([u, v]), rows.ravel())


def sample_nearest(texture: EdgeTexture, texcoords: np.ndarray) -> np.ndarray:
    """Return the texels (linear 0–1) a viewer samples NEAREST at *texcoords* (n, 2)."""
    height, width = texture.image_srgb.shape[:2]
    column = np.clip(np.floor(texcoords[:, 0] * width).astype(int), 0, width - 1)
    row = np.clip(np.floor(texcoords[:, 1] * height).astype(int), 0, height - 1)
    return srgb_to_linear(texture.image_srgb[row, column] / 255.0)
