"""Test the engine's disk cache with solved letters: solved once, loaded the same."""

import os
import platform
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from synthesis.diskcache import CACHE_ENV, cache_path, load_arrays, save_arrays
from synthesis.fingerspelling import alphabet

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture
def cache(monkeypatch, tmp_path):
    monkeypatch.setenv(CACHE_ENV, str(tmp_path / "cache"))
    alphabet.letter.cache_clear()
    yield tmp_path / "cache"
    alphabet.letter.cache_clear()


def test_a_solved_letter_is_kept_and_loaded_back_the_same(cache, monkeypatch):
    solved = alphabet.letter("J")
    (stored,) = cache.glob("letter-asl-right-J-*.npz")
    alphabet.letter.cache_clear()
    # Loaded, not solved: solving now would fail.
    monkeypatch.setattr(alphabet, "solve_contacts", lambda *args: pytest.fail("solved again"))
    loaded = alphabet.letter("J")
    np.testing.assert_array_equal(loaded.dofs_rad, solved.dofs_rad)
    np.testing.assert_array_equal(loaded.path_rad, solved.path_rad)
    assert loaded.contacts == solved.contacts and not loaded.dofs_rad.flags.writeable
    assert stored.stat().st_size > 0


def test_an_unreadable_or_misshapen_file_is_solved_again(cache):
    solved = alphabet.letter("A")
    (stored,) = cache.glob("letter-asl-right-A-*.npz")
    for damage in (b"not a zip file", None):
        if damage is None:
            save_arrays(stored, {"dofs_rad": np.zeros(3)})
        else:
            stored.write_bytes(damage)
        alphabet.letter.cache_clear()
        np.testing.assert_allclose(alphabet.letter("A").dofs_rad, solved.dofs_rad)
        assert load_arrays(stored)["dofs_rad"].shape == solved.dofs_rad.shape


def test_caching_can_be_turned_off(monkeypatch):
    monkeypatch.setenv(CACHE_ENV, "off")
    assert cache_path("letter-right-A", ("numpy",)) is None
    assert load_arrays(None) is None
    save_arrays(None, {"x": np.zeros(1)})  # nothing to do, no error


def _cache_name(environment: dict[str, str]) -> str:
    """Return the cache file name a fresh process gives one result under *environment*."""
    script = "from synthesis.diskcache import cache_path; print(cache_path('x', ('numpy',)).name)"
    run = subprocess.run(
        [sys.executable, "-c", script],
        env={**os.environ, CACHE_ENV: "/tmp/unused", **environment},
        capture_output=True,
        text=True,
        check=True,
        cwd=ROOT,
    )
    return run.stdout.strip()


def test_other_cpu_kernels_name_another_file():
    """Issue 52: a GPLVM cached with AVX-512 kernels was loaded by a run pinned to AVX2
    kernels (scripts/docs_figures.py) and its figure drifted. Results of other kernels
    are other files; the same kernels find the same file."""
    plain = _cache_name({})
    assert _cache_name({}) == plain
    assert _cache_name({"OPENBLAS_CORETYPE": "Haswell"}) != plain
    if platform.machine() in ("x86_64", "AMD64"):  # numpy refuses features it does not know
        assert _cache_name({"NPY_DISABLE_CPU_FEATURES": "X86_V3 X86_V4"}) != plain
