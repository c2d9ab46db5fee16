"""Test glTF motion as other tools write it (issue 54, item 7).

Blender's "glTF Separate" export and three.js's GLTFExporter write a ``.gltf`` with its
buffer in a ``.bin`` beside it, and animate a face's blendshapes with ``weights``
channels. The command line reads both; an upload stays one file (a GLB), and a ``.gltf``
names only files in its own folder. Reference: glTF 2.0 §3.6.1.1 (buffer URIs, relative
to the document) and §3.11 (animation targets: translation, rotation, scale, weights).
"""

import numpy as np
import pygltflib as gl
import pytest

from synthesis.avatar.imported.gltf_read import GltfError
from synthesis.avatar.imported.motion import read_gltf_motion, read_motion_file
from synthesis.interchange import request_glb
from synthesis.techniques import ClipRequest, build_motion


@pytest.fixture(scope="module")
def clip_glb() -> bytes:
    """A sentence's GLB: skeleton keys and the face's morph weights keyed per frame."""
    values = {"rate_hz": 15.0, "width": 160, "height": 120}
    request = ClipRequest.from_parameters("sentence", "ME HAPPY", values)
    return request_glb(request, build_motion(request))


def _separate(glb: bytes, folder, uri: str, name: str | None = None):
    """Write *glb* as clip.gltf with its buffer in the file *name* (URI *uri*)."""
    gltf = gl.GLTF2.load_from_bytes(glb)
    (folder / (name or uri)).write_bytes(gltf.binary_blob())
    gltf.buffers[0].uri = uri
    gltf._glb_data = None
    path = folder / "clip.gltf"
    path.write_text(gltf.to_json())
    return path


def test_a_glb_with_animated_blendshapes_reads_as_its_skeletons_motion(clip_glb):
    motion = read_gltf_motion(clip_glb, "clip.glb")
    assert motion.n_frames == 30
    assert "right_wrist" in {joint.name for joint in motion.skeleton.joints}


def test_a_gltf_with_its_buffer_beside_it_reads_on_the_command_line(clip_glb, tmp_path):
    path = _separate(clip_glb, tmp_path, "clip%20data.bin", "clip data.bin")
    separate, single = read_motion_file(path), read_gltf_motion(clip_glb, "clip.glb")
    np.testing.assert_array_equal(separate.values, single.values)
    # An upload is bytes alone: its buffer file is not there to read.
    with pytest.raises(GltfError, match=r"separate file 'clip%20data\.bin'; upload a GLB"):
        read_gltf_motion(path.read_bytes(), "clip.gltf")


@pytest.mark.parametrize("uri", ["../clip.bin", "/etc/hostname", "sub/clip.bin", "gone.bin"])
def test_a_gltf_names_only_files_in_its_own_folder(clip_glb, tmp_path, uri):
    folder = tmp_path / "models"
    (folder / "sub").mkdir(parents=True)
    path = _separate(clip_glb, folder, uri, "clip.bin")
    (tmp_path / "clip.bin").write_bytes(b"\0" * 64)
    (folder / "sub" / "clip.bin").write_bytes(b"\0" * 64)
    with pytest.raises(GltfError, match="is not a file beside it"):
        read_motion_file(path)
