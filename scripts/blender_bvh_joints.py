"""Print where Blender's own BVH importer puts every joint of a BVH file at one frame.

Run inside Blender (Debian's ``blender``, scripts/system-packages.txt):

    blender -b --factory-startup --python scripts/blender_bvh_joints.py -- CLIP.bvh FRAME

Imported with Blender's defaults (its scene's rate taken from the file, each joint's
rotation in the file's own channel order), FRAME counts from the file's first frame.
Prints one JSON line: Blender's version and each joint's head in the file's own axes
and unit (Blender turns Y-up into Z-up on import; this turns it back).
"""

import builtins
import json
import sys

import bpy  # type: ignore[import-not-found]

_open = builtins.open


def _open_without_u(file, mode="r", *args, **kwargs):
    """Open as Python 3.11 does, where mode "U" is gone: Debian bookworm's Blender 3.4
    runs on Python 3.11, and its BVH importer still opens files "rU" (it fails there)."""
    return _open(file, mode.replace("U", ""), *args, **kwargs)


def main(path: str, frame: int) -> None:
    """Import *path*, go to *frame* and print its joints' positions."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    builtins.open = _open_without_u
    bpy.ops.import_anim.bvh(
        filepath=path, rotate_mode="NATIVE", update_scene_fps=True, update_scene_duration=True
    )
    armature = next(o for o in bpy.context.scene.objects if o.type == "ARMATURE")
    bpy.context.scene.frame_set(bpy.context.scene.frame_start + frame)
    joints = {}
    for bone in armature.pose.bones:
        x, y, z = armature.matrix_world @ bone.head
        joints[bone.name] = (x, z, -y)  # Blender's Z-up back to the file's Y-up
    print(json.dumps({"blender": bpy.app.version_string, "joints": joints}))


if __name__ == "__main__":
    arguments = sys.argv[sys.argv.index("--") + 1 :]
    main(arguments[0], int(arguments[1]))
