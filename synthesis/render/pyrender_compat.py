"""Every use of pyrender's private attributes, in one place, for the pinned version only.

The renderer reaches inside pyrender for speed and reproducibility (a program cache
that survives OSMesa's context objects, lights in a fixed order, vertex buffers updated
in place, a colour-only read-back). Those attributes are pyrender-maintained 1.0.1's;
importing this module checks that version is the one installed, so an upgrade fails
loudly here instead of rendering wrong pixels somewhere else.
"""

import functools
from importlib import metadata

import numpy as np

from synthesis.render.backend import RenderUnavailable

DISTRIBUTION = "pyrender-maintained"
PINNED_VERSION = "1.0.1"


def check_version() -> str:
    """Return the installed pyrender version, or raise if it is not the pinned one."""
    try:
        installed = metadata.version(DISTRIBUTION)
    except metadata.PackageNotFoundError:
        raise RenderUnavailable(
            f"{DISTRIBUTION} is not installed; run 'make install' to install it."
        ) from None
    if installed != PINNED_VERSION:
        raise RenderUnavailable(
            f"The renderer relies on private attributes of {DISTRIBUTION} {PINNED_VERSION}, "
            f"but {installed} is installed; install {PINNED_VERSION} (requirements/lock.txt) "
            "or port synthesis/render/pyrender_compat.py to it."
        )
    return installed


check_version()


def install_program_cache(pyrender, offscreen, shader_dir: str, extra_defines=None) -> None:
    """Give *offscreen*'s renderer a shader program cache that compiles each program once.

    pyrender keys its cache on the current context object, and OSMesa hands out a new
    pointer object on every make-current, so with pyrender's own key every frame missed
    the cache, compiled its shaders again and kept the old programs (a tenth of the frame
    time, and a leak). One renderer owns one context, so the key here leaves it out.
    *extra_defines*, if given, returns defines (name → value) added to pyrender's for
    every program; pyrender replaces a define's name by its value throughout a shader's
    text, so a name must not be part of another.
    """

    class ProgramCache(pyrender.shader_program.ShaderProgramCache):
        def __init__(self) -> None:
            super().__init__(shader_dir=shader_dir)
            self._compiled: dict = {}

        def get_program(self, vertex_shader, fragment_shader, geometry_shader=None, defines=None):
            defines = {**(defines or {}), **(extra_defines() if extra_defines else {})}
            key = (vertex_shader, fragment_shader, geometry_shader, tuple(sorted(defines.items())))
            if key not in self._compiled:
                self._compiled[key] = super().get_program(
                    vertex_shader, fragment_shader, geometry_shader, defines
                )
            return self._compiled[key]

        def clear(self) -> None:
            super().clear()
            self._compiled = {}

    offscreen._renderer._program_cache = ProgramCache()


@functools.cache
def ordered_node_class(pyrender):
    """Return a pyrender Node class whose nodes hash to the order they were given.

    pyrender keeps lights in a set and numbers them for the shader in the set's
    iteration order, which for plain nodes follows their memory addresses; the shader
    then summed the lights in an order that changed from run to run, and so did the
    last bits of some pixels. Small-integer hashes make a set iterate in their order.
    """

    class OrderedNode(pyrender.Node):
        def __init__(self, order: int, **kwargs) -> None:
            super().__init__(**kwargs)
            self.order = order

        def __hash__(self) -> int:
            return self.order

    return OrderedNode


def forget_bounds(mesh, scene) -> None:
    """Drop the bounds pyrender cached on *mesh* and *scene* (vertices moved).

    The directional lights' shadow volume follows the scene's bounds.
    """
    mesh._bounds = None
    scene._bounds = None


def cast_shadows_from(offscreen, mesh, casters: list) -> None:
    """Draw only *casters*, some of *mesh*'s primitives, into *offscreen*'s shadow maps.

    pyrender's shadow pass draws every primitive of every mesh; the pass here hands it
    the mesh with the casters alone. The scene's bounds, which place the directional
    lights' shadow volume, are taken first with every primitive, as the colour pass
    sees them.
    """
    inner = offscreen._renderer
    shadow_pass = type(inner)._shadow_mapping_pass

    def casters_only(scene, light_node, flags):
        scene.bounds  # noqa: B018 (cached on the scene for the rest of the frame)
        drawn = mesh._primitives
        mesh._primitives = casters
        try:
            shadow_pass(inner, scene, light_node, flags)
        finally:
            mesh._primitives = drawn

    inner._shadow_mapping_pass = casters_only


def vertex_buffer(primitive) -> int | None:
    """Return the OpenGL buffer holding *primitive*'s interleaved vertices, None before upload.

    pyrender's vertex buffer interleaves position (3), normal (3) and colour (4) floats
    per vertex for primitives without tangents or texture coordinates.
    """
    if primitive._vaid is None:
        return None
    return primitive._buffers[0]


def render_color(
    pyrender, offscreen, scene, flags, width: int, height: int, before_draw=None, after_draw=None
) -> np.ndarray:
    """Draw *scene* with *offscreen* and return its colours (height, width, 3) uint8.

    ``OffscreenRenderer.render`` also reads and linearises the depth buffer, a tenth of
    the frame time that clips never use; this is its colour-only path. *before_draw* runs
    with the context current (to update buffers); *after_draw* too, on a platform without
    framebuffers (OSMesa), between drawing and reading (to post-process the frame). On a
    platform with framebuffers (EGL) pyrender draws into a 4× multisampled one and
    resolves it itself, so there is nothing left to post-process.
    """
    inner = offscreen._renderer
    offscreen._platform.make_current()
    try:
        if before_draw is not None:
            before_draw()
        inner.viewport_width, inner.viewport_height = width, height
        if offscreen._platform.supports_framebuffers():
            color, _ = inner.render(scene, flags | pyrender.RenderFlags.OFFSCREEN)
        else:
            inner.render(scene, flags)
            if after_draw is not None:
                after_draw()
            color = inner.read_color_buf()
    finally:
        offscreen._platform.make_uncurrent()
    return np.ascontiguousarray(color[..., :3])


def set_shadow_map_size(pyrender, size_px: int) -> None:
    """Make pyrender's shadow maps *size_px* square (its default, 2048, for all processes).

    pyrender reads the size from a module constant when it makes a light's shadow
    texture and sets the shadow pass's viewport, so this applies to lights made after it.
    """
    pyrender.renderer.SHADOW_TEX_SZ = size_px
    pyrender.light.SHADOW_TEX_SZ = size_px


def delete_offscreen(offscreen) -> None:
    """Free *offscreen*'s OpenGL objects and context, as ``OffscreenRenderer.delete`` does.

    pyrender's delete ends with a full ``gc.collect()``: 0.2–0.3 s in a process with a
    large heap, paid for every clip a render process finishes and every renderer a test
    closes. What the collection hides is that its renderer's delete keeps the shadow
    framebuffer's name: when the renderer (in a reference cycle) is collected later, its
    ``__del__`` deletes it again, in whatever context is current then, where the name
    may be another renderer's framebuffer. Forgetting the name makes that second delete
    free nothing.
    """
    inner = offscreen._renderer
    offscreen._platform.make_current()
    inner.delete()
    inner._shadow_fb = None
    offscreen._platform.delete_context()
    offscreen._renderer = None
    offscreen._platform = None
