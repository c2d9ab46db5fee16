"""Test the on-disk avatar store: stored once per engine version, loaded back the same."""

import dataclasses

import numpy as np
import pytest

from synthesis.avatar.model import Avatar, rigid_part
from synthesis.avatar.store import CACHE_ENV, cache_directory, cached_avatar
from synthesis.identity import code_digest
from synthesis.rigs.hand import HandModel


@pytest.fixture
def store(monkeypatch, tmp_path):
    monkeypatch.setenv(CACHE_ENV, str(tmp_path / "avatars"))
    return tmp_path / "avatars"


def _builder():
    """Return a build function for a small avatar and the list of its calls."""
    calls = []

    def build():
        calls.append(1)
        model = HandModel()
        vertices = np.array([[0.0, 0.0, 0.0], [0.01, 0.0, 0.0], [0.0, 0.01, 0.0], [0, 0, 0.01]])
        faces = np.array([[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]])
        part = rigid_part(
            "nails", vertices, faces, np.full(4, 3), (0.8, 0.6, 0.6), casts_shadow=False
        )
        edged = dataclasses.replace(
            part,
            name="cuffed",
            edge_m=vertices[:, 0] - 0.005,
            across_rgb=np.zeros((4, 3)),
            casts_shadow=True,
        )
        return Avatar("tiny", model, model.neutral(), (part, edged))

    return build, calls


def test_an_avatar_is_built_once_then_loaded_the_same(store):
    build, calls = _builder()
    built = cached_avatar("tiny", HandModel(), build)
    loaded = cached_avatar("tiny", HandModel(), build)
    assert len(calls) == 1
    (path,) = store.iterdir()
    assert code_digest() in path.name  # another engine names another file
    assert loaded.name == built.name and isinstance(loaded.rig, HandModel)
    np.testing.assert_array_equal(loaded.bind_dofs_rad, built.bind_dofs_rad)
    for ours, theirs in zip(loaded.parts, built.parts, strict=True):
        assert ours.name == theirs.name
        for field in ("vertices_m", "faces", "colors_rgb", "normals", "edge_m", "across_rgb"):
            np.testing.assert_array_equal(getattr(ours, field), getattr(theirs, field))
        np.testing.assert_array_equal(ours.weights.joints, theirs.weights.joints)
        np.testing.assert_array_equal(ours.weights.weights, theirs.weights.weights)
    assert loaded.parts[0].edge_m is None and loaded.parts[1].edge_m is not None
    assert [part.casts_shadow for part in loaded.parts] == [False, True]


def test_an_unreadable_file_is_built_again_and_replaced(store):
    build, calls = _builder()
    cached_avatar("tiny", HandModel(), build)
    (path,) = store.iterdir()
    path.write_bytes(path.read_bytes()[:100])  # truncated
    cached_avatar("tiny", HandModel(), build)
    cached_avatar("tiny", HandModel(), build)
    assert len(calls) == 2


def test_off_builds_every_time_and_an_unwritable_store_only_costs_time(monkeypatch, tmp_path):
    build, calls = _builder()
    monkeypatch.setenv(CACHE_ENV, "off")
    assert cache_directory() is None
    cached_avatar("tiny", HandModel(), build)
    cached_avatar("tiny", HandModel(), build)
    assert len(calls) == 2
    (tmp_path / "a file").write_text("not a directory")
    monkeypatch.setenv(CACHE_ENV, str(tmp_path / "a file" / "avatars"))
    assert cached_avatar("tiny", HandModel(), build).name == "tiny"
