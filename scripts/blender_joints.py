"""Print where Blender's own importer puts every joint of a motion file at one frame.

Run inside Blender (Debian's ``blender``, scripts/system-packages.txt):

    blender -b --factory-startup --python scripts/blender_joints.py -- FILE FRAME [RATE]

A BVH is imported with Blender's defaults (its scene's rate taken from the file, each
joint's rotation in the file's own channel order); a glTF or GLB with Blender's glTF
importer, the scene's rate set to RATE first (the keys then fall on whole frames).
FRAME counts from the first frame. Prints one JSON line: Blender's version and each
joint's head in the file's own axes and unit (Blender turns Y-up into Z-up on import;
this turns it back).
"""

import builtins
import json
import sys

import bpy  # type: ignore[import-not-found]
import numpy

_open = builtins.open


def _open_without_u(file, mode="r", *args, **kwargs):
    """Open as Python 3.11 does, where mode "U" is gone: Debian bookworm's Blender 3.4
    runs on Python 3.11, and its BVH importer still opens files "rU" (it fails there)."""
    return _open(file, mode.replace("U", ""), *args, **kwargs)


def main(path: str, frame: int, rate_hz: float) -> None:
    """Import *path*, go to *frame* and print its joints' positions."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    if path.lower().endswith(".bvh"):
        builtins.open = _open_without_u
        bpy.ops.import_anim.bvh(
            filepath=path, rotate_mode="NATIVE", update_scene_fps=True, update_scene_duration=True
        )
        first = scene.frame_start
    else:
        numpy.bool = getattr(numpy, "bool", bool)  # see scripts/blender_frame.py
        scene.render.fps, scene.render.fps_base = round(rate_hz), round(rate_hz) / rate_hz
        bpy.ops.import_scene.gltf(filepath=path)
        first = min(action.frame_range[0] for action in bpy.data.actions)
    armature = next(o for o in scene.objects if o.type == "ARMATURE")
    scene.frame_set(int(first) + frame)
    joints = {}
    for bone in armature.pose.bones:
        x, y, z = armature.matrix_world @ bone.head
        joints[bone.name] = (x, z, -y)  # Blender's Z-up back to the file's Y-up
    print(json.dumps({"blender": bpy.app.version_string, "joints": joints}))


if __name__ == "__main__":
    arguments = sys.argv[sys.argv.index("--") + 1 :]
    main(arguments[0], int(arguments[1]), float((arguments[2:] or ["24"])[0]))
