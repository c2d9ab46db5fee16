"""Fixtures for the synthesis tests: offscreen rendering, skipped loudly where impossible."""

import os

import pytest


@pytest.fixture(scope="session")
def renderable():
    """Make sure an offscreen OpenGL context can be created; skip (or fail in CI) if not."""
    from synthesis.render.backend import RenderUnavailable, import_pyrender

    try:
        pyrender = import_pyrender()
        probe = pyrender.OffscreenRenderer(16, 16)
        probe.delete()
    except (RenderUnavailable, Exception) as error:  # any GL failure means "cannot render"
        message = f"RENDERING TESTS SKIPPED: no offscreen OpenGL here ({error})."
        if os.environ.get("SIGNSTUDY_REQUIRE_RENDER"):
            pytest.fail(message)
        pytest.skip(message)
    return pyrender
