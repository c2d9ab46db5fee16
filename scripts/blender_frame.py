"""Render one frame of a GLB in Blender, as Blender's own glTF importer reads it.

Run inside Blender (Debian's ``blender``, scripts/system-packages.txt):

    blender -b --factory-startup --python scripts/blender_frame.py -- \\
        CLIP.glb FRAME WIDTH HEIGHT OUT.png [COLOURS.png]

The scene's frame rate is set to the file's ``asset.extras.signstudy.rate_hz`` before
the import, as the researcher guide tells a user to (the keys then land on whole
frames). FRAME counts from the animation's first key. The frame is drawn through the
file's own camera with Workbench, flat and white on a transparent film, so the PNG's
alpha is the signer's silhouette as Blender places it; COLOURS.png is the same frame
unlit in the file's texture colours (Workbench, no tone curve). Prints one JSON line: Blender's
version, the imported objects' counts and the frame drawn.
"""

import json
import struct
import sys

import bpy  # type: ignore[import-not-found]
import numpy

# Debian bookworm's Blender 3.4 glTF importer still asks for ``numpy.bool``, an alias
# NumPy 1.24 (Debian's python3-numpy) removed: every mesh import fails without it.
if not hasattr(numpy, "bool"):
    numpy.bool = bool


def _asset_extras(path: str) -> dict:
    """Return the GLB's ``asset.extras.signstudy`` (its JSON chunk, read by hand)."""
    with open(path, "rb") as file:
        header = file.read(20)
        length = struct.unpack("<I", header[12:16])[0]
        document = json.loads(file.read(length))
    return document.get("asset", {}).get("extras", {}).get("signstudy", {})


def _first_key(objects) -> float:
    """Return the earliest keyframe of any imported object's action (Blender's frame)."""
    frames = [
        action.frame_range[0]
        for action in bpy.data.actions
        if any(o.animation_data and o.animation_data.action == action for o in objects)
    ]
    return min(frames, default=bpy.context.scene.frame_start)


def main(path: str, frame: int, width: int, height: int, out: str, colours: str | None) -> None:
    """Import *path*, pose it at *frame* and write the silhouette through its camera (and
    the frame in its textures' colours to *colours*, if given)."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    rate_hz = float(_asset_extras(path).get("rate_hz", 24.0))
    scene.render.fps, scene.render.fps_base = round(rate_hz), round(rate_hz) / rate_hz
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    bpy.ops.import_scene.gltf(filepath=path)
    objects = list(scene.objects)
    cameras = [o for o in objects if o.type == "CAMERA"]
    scene.camera = cameras[0]
    at = _first_key(objects) + frame
    scene.frame_set(int(at))
    scene.render.engine = "BLENDER_WORKBENCH"
    scene.render.film_transparent = True
    scene.display.shading.light = "FLAT"
    scene.display.shading.color_type = "SINGLE"
    scene.display.shading.single_color = (1.0, 1.0, 1.0)
    scene.display.render_aa = "OFF"  # a hard silhouette, as a mask
    scene.render.image_settings.file_format = "PNG"
    scene.render.image_settings.color_mode = "RGBA"
    scene.render.filepath = out
    bpy.ops.render.render(write_still=True)
    if colours is not None:  # the same frame in the file's own colours, unlit
        scene.display.shading.color_type = "TEXTURE"
        scene.view_settings.view_transform = "Standard"  # sRGB out, no tone curve
        scene.render.filepath = colours
        bpy.ops.render.render(write_still=True)
    meshes = [o for o in objects if o.type == "MESH"]
    print(
        json.dumps(
            {
                "blender": bpy.app.version_string,
                "meshes": len(meshes),
                "skinned": sum(any(m.type == "ARMATURE" for m in o.modifiers) for o in meshes),
                "bones": sum(len(o.data.bones) for o in objects if o.type == "ARMATURE"),
                "shape_keys": sum(
                    len(o.data.shape_keys.key_blocks) - 1 for o in meshes if o.data.shape_keys
                ),
                "shape_key_names": sorted(
                    {
                        k.name
                        for o in meshes
                        if o.data.shape_keys
                        for k in o.data.shape_keys.key_blocks
                    }
                ),
                "cameras": len(cameras),
                "fps": scene.render.fps / scene.render.fps_base,
                "frame": at,
            }
        )
    )


if __name__ == "__main__":
    arguments = sys.argv[sys.argv.index("--") + 1 :]
    path, frame, width, height, out = arguments[:5]
    main(path, int(frame), int(width), int(height), out, (arguments[5:] or [None])[0])
