"""Choose the offscreen OpenGL platform and import pyrender lazily, with clear errors.

PyOpenGL reads ``PYOPENGL_PLATFORM`` once, when it is first imported, so the choice is
made before that: the variable if the caller set it, else OSMesa when Mesa's libOSMesa
is installed (faster on this kind of machine: ≈ 50 fps against ≈ 35 for EGL, spec 01),
else EGL (Mesa's llvmpipe through a surfaceless display). ``make install`` installs both.
"""

import ctypes.util
import os
import sys

PLATFORMS = ("osmesa", "egl")


class RenderUnavailable(RuntimeError):
    """Offscreen rendering cannot run here (no pyrender, no OSMesa or EGL)."""


def select_platform() -> str:
    """Return the offscreen platform to use, setting ``PYOPENGL_PLATFORM`` if unset."""
    chosen = os.environ.get("PYOPENGL_PLATFORM", "").strip().lower()
    if chosen:
        if chosen not in PLATFORMS:
            raise RenderUnavailable(
                f"PYOPENGL_PLATFORM={chosen!r} cannot render offscreen; use 'osmesa' or 'egl'."
            )
        return chosen
    if "OpenGL.platform" in sys.modules:
        # Too late to choose: keep what PyOpenGL picked if it can render offscreen.
        loaded = type(sys.modules["OpenGL.platform"].PLATFORM).__name__.lower()
        for platform in PLATFORMS:
            if loaded.startswith(platform):
                return platform
        raise RenderUnavailable(
            "PyOpenGL was imported for an on-screen platform before the renderer chose one; "
            "set PYOPENGL_PLATFORM=osmesa (or egl) before importing OpenGL."
        )
    if ctypes.util.find_library("OSMesa"):
        chosen = "osmesa"
    elif ctypes.util.find_library("EGL"):
        chosen = "egl"
    else:
        raise RenderUnavailable(
            "Neither OSMesa nor EGL is installed, so nothing can render offscreen. "
            "Run 'make install' (it installs libosmesa6 and libegl-mesa0 on Debian)."
        )
    os.environ["PYOPENGL_PLATFORM"] = chosen
    return chosen


def import_pyrender():
    """Return the pyrender module, configured for offscreen rendering."""
    select_platform()
    try:
        import pyrender
    except ImportError as error:  # pragma: no cover - depends on the install
        raise RenderUnavailable(
            f"pyrender cannot be imported ({error}); run 'make install' to install it."
        ) from error
    return pyrender
