"""Anti-alias a drawn frame in OpenGL: one FXAA pass (shaders/fxaa.*), and its measure.

OSMesa draws into a single-sampled buffer; drawing pyrender's 4× multisampled
framebuffer instead took the signing view from 30 to 17.5 fps on llvmpipe, and 2 × 2
supersampling costs 3–4× the frame time (bench/bench_antialias.py). The FXAA pass over
the finished frame costs about 4 ms of the signing view's frame, limited to the avatar's
box on screen, and takes about a third off the edge error against a 4 × 4 supersampled
reference (:func:`edge_error`).
"""

from pathlib import Path

import numpy as np

SHADERS = Path(__file__).with_name("shaders")


def downsample(frame: np.ndarray, factor: int) -> np.ndarray:
    """Return a frame (h·f, w·f, 3) uint8 averaged over f × f blocks, (h, w, 3) uint8."""
    height, width = frame.shape[0] // factor, frame.shape[1] // factor
    blocks = frame[: height * factor, : width * factor].reshape(height, factor, width, factor, 3)
    return np.round(blocks.mean(axis=(1, 3))).astype(np.uint8)


def edge_error(frame: np.ndarray, reference: np.ndarray, step: int = 24) -> tuple[float, int]:
    """Return how far a frame's edges are from a supersampled reference's, and how many.

    The edge pixels are the reference's pixels whose colour differs from a 4-neighbour's
    by more than *step* levels (of 255) in a channel; returned are the mean absolute
    difference over their channels, in levels, and their count. A frame drawn with one
    sample per pixel is wrong mostly there (a staircase where the reference has a ramp).
    """
    ref = reference.astype(np.int16)
    jump = np.zeros(ref.shape[:2], dtype=bool)
    for axis in (0, 1):
        step_between = np.abs(np.diff(ref, axis=axis)).max(axis=-1) > step
        if axis == 0:
            jump[1:] |= step_between
            jump[:-1] |= step_between
        else:
            jump[:, 1:] |= step_between
            jump[:, :-1] |= step_between
    difference = np.abs(frame.astype(np.int16) - ref)[jump]
    return float(difference.mean()) if len(difference) else 0.0, int(jump.sum())


class Fxaa:
    """The anti-aliasing pass of one OpenGL context; call with that context current.

    Its program, texture and vertex array live as long as the context does.
    """

    def __init__(self) -> None:
        from OpenGL import GL
        from OpenGL.GL import shaders

        self._gl = GL
        self._program = shaders.compileProgram(
            shaders.compileShader((SHADERS / "fxaa.vert").read_text(), GL.GL_VERTEX_SHADER),
            shaders.compileShader((SHADERS / "fxaa.frag").read_text(), GL.GL_FRAGMENT_SHADER),
            validate=False,  # validation needs the vertex array bound, which draw() binds
        )
        self._texel = GL.glGetUniformLocation(self._program, "texel")
        self._frame = GL.glGetUniformLocation(self._program, "frame")
        self._vertex_array = GL.glGenVertexArrays(1)
        self._texture = GL.glGenTextures(1)
        self._size: tuple[int, int] | None = None

    def apply(
        self, width: int, height: int, box_px: tuple[int, int, int, int] | None = None
    ) -> None:
        """Replace the bound framebuffer's colours (*width* × *height*) by their FXAA.

        *box_px* (left, bottom, right, top; OpenGL's window pixels, y up) limits the pass
        to where the scene has edges, the rest of the frame being background.
        """
        GL = self._gl
        left, bottom, right, top = (0, 0, width, height) if box_px is None else box_px
        # FXAA's walk along an edge reads up to 19 px (fxaa.frag) beyond what it writes.
        reach = 21
        copy = (
            max(left - reach, 0),
            max(bottom - reach, 0),
            min(right + reach, width),
            min(top + reach, height),
        )
        GL.glActiveTexture(GL.GL_TEXTURE0)
        GL.glBindTexture(GL.GL_TEXTURE_2D, self._texture)
        if self._size != (width, height):
            GL.glTexImage2D(
                GL.GL_TEXTURE_2D,
                0,
                GL.GL_RGBA8,
                width,
                height,
                0,
                GL.GL_RGBA,
                GL.GL_UNSIGNED_BYTE,
                None,
            )
            for parameter, value in (
                (GL.GL_TEXTURE_MIN_FILTER, GL.GL_LINEAR),
                (GL.GL_TEXTURE_MAG_FILTER, GL.GL_LINEAR),
                (GL.GL_TEXTURE_WRAP_S, GL.GL_CLAMP_TO_EDGE),
                (GL.GL_TEXTURE_WRAP_T, GL.GL_CLAMP_TO_EDGE),
            ):
                GL.glTexParameteri(GL.GL_TEXTURE_2D, parameter, value)
            self._size = (width, height)
        # pyrender's shadow pass leaves its own framebuffer bound for reading.
        GL.glBindFramebuffer(GL.GL_FRAMEBUFFER, 0)
        x, y, w, h = copy[0], copy[1], copy[2] - copy[0], copy[3] - copy[1]
        GL.glCopyTexSubImage2D(GL.GL_TEXTURE_2D, 0, x, y, x, y, w, h)
        GL.glViewport(0, 0, width, height)
        GL.glEnable(GL.GL_SCISSOR_TEST)
        GL.glScissor(left, bottom, right - left, top - bottom)
        GL.glDisable(GL.GL_DEPTH_TEST)
        GL.glDisable(GL.GL_BLEND)
        GL.glUseProgram(self._program)
        GL.glUniform1i(self._frame, 0)
        GL.glUniform2f(self._texel, 1.0 / width, 1.0 / height)
        GL.glBindVertexArray(self._vertex_array)
        GL.glDrawArrays(GL.GL_TRIANGLES, 0, 3)
        GL.glBindVertexArray(0)
        GL.glDisable(GL.GL_SCISSOR_TEST)
        GL.glUseProgram(0)
        GL.glBindTexture(GL.GL_TEXTURE_2D, 0)
        GL.glEnable(GL.GL_DEPTH_TEST)
