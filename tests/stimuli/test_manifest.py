"""Test clip specifications, content hashes and manifests."""

import json

import pytest

from stimuli import ClipError, ClipSpec, Entry, generate, read_manifest, write_manifest

TINY = {"width": 64, "height": 48, "rate_hz": 15.0}


def test_the_hash_covers_every_parameter():
    base = ClipSpec("word", "CAT", {"timing": "constant"}, seed=1, **TINY)
    assert base.content_hash() == ClipSpec.from_dict(base.to_dict()).content_hash()
    variants = [
        ClipSpec("word", "CAT", {"timing": "variable"}, seed=1, **TINY),
        ClipSpec("word", "CAB", {"timing": "constant"}, seed=1, **TINY),
        ClipSpec("word", "CAT", {"timing": "constant"}, seed=2, **TINY),
        ClipSpec("word", "CAT", {"timing": "constant"}, seed=1, side="left", **TINY),
        ClipSpec("word", "CAT", {"timing": "constant"}, seed=1, **{**TINY, "width": 80}),
        ClipSpec("word", "CAT", {"timing": "constant"}, seed=1, engine="other", **TINY),
    ]
    hashes = {base.content_hash(), *(v.content_hash() for v in variants)}
    assert len(hashes) == 1 + len(variants)
    assert base.view == "hand" and ClipSpec("sentence", "ME").view == "upper-body"


def test_bad_specifications_are_named():
    with pytest.raises(ClipError, match="Unknown timing 'fast'"):
        ClipSpec("word", "CAT", {"timing": "fast"})
    with pytest.raises(ClipError, match="'poem': the kinds are word, sentence and sign_pair"):
        ClipSpec("poem", "CAT")
    with pytest.raises(ClipError, match="Malformed clip specification"):
        ClipSpec.from_dict({"kind": "word", "text": "CAT", "colour": "red"})


def test_a_manifest_renders_the_study_again(tmp_path, renderable):
    entries = [
        Entry(f"{t} × AB", ClipSpec("word", "AB", {"timing": t}, seed=3, **TINY))
        for t in ("simple", "constant")
    ]
    done, rendered = generate(entries, tmp_path / "clips")
    assert rendered == 2
    manifest = write_manifest(done, tmp_path / "manifest.json", study="demo")
    data = json.loads(manifest.read_text())
    assert data["study"] == "demo" and len(data["clips"]) == 2
    clip = data["clips"][0]
    # What each technique did, in words (issue 53: a model's training travels with it).
    assert "Timing model: simple (equal holds)" in data["clips"][0]["techniques"]
    assert clip["clip"]["video"] == f"{clip['hash']}.mp4" and clip["clip"]["frame_count"] > 10
    # From the manifest alone: a second run into the same folder renders nothing, into a
    # new folder renders the same bytes.
    _, rendered = generate(read_manifest(manifest), tmp_path / "clips")
    assert rendered == 0
    fresh, rendered = generate(read_manifest(manifest), tmp_path / "fresh")
    assert rendered == 2
    assert [e.clip.sha256 for e in fresh] == [e.clip.sha256 for e in done]


def test_a_tampered_manifest_is_refused(tmp_path):
    entry = Entry("x", ClipSpec("word", "AB", {"timing": "simple"}, **TINY))
    path = write_manifest([entry], tmp_path / "m.json")
    data = json.loads(path.read_text())
    data["clips"][0]["spec"]["text"] = "ABC"
    path.write_text(json.dumps(data))
    with pytest.raises(ClipError, match="clip 1 does not match its recorded hash"):
        read_manifest(path)
    path.write_text("{}")
    with pytest.raises(ClipError, match="not a stimuli manifest"):
        read_manifest(path)
