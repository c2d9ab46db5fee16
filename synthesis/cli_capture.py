"""The command line's capture commands: capture a video, render a .pose file, and
export an engine motion as .pose landmarks and BVH (``python -m synthesis``)."""

import argparse
import json
from pathlib import Path

import numpy as np

from synthesis.rigs.hand import HandModel
from synthesis.techniques import avatar_and_camera
from synthesis.terminal import frame_progress as _progress


def export_motion(
    build, request, pose_path: Path | None, bvh_path: Path | None, glb_path: Path | None = None
) -> None:
    """Write a clip's motion as .pose landmarks (*pose_path*), as BVH (*bvh_path*) and
    with the avatar and camera as GLB (*glb_path*)."""
    if glb_path is not None:
        from synthesis.interchange import request_glb

        Path(glb_path).write_bytes(request_glb(request, build))
        print(f"wrote {glb_path}")
    if pose_path is None and bvh_path is None:
        return
    import numpy as np

    from synthesis.capture import write_pose
    from synthesis.capture.filmed import filmed_body_motion, filmed_hand_motion
    from synthesis.skeleton.bvh import write_bvh
    from synthesis.techniques.request import film

    dofs = build.motion
    if not isinstance(dofs, np.ndarray):
        raise ValueError("Only the engine's own motions export (not a retargeted recording).")
    if pose_path is not None:
        # The landmarks as the clip films them: its avatar's skeleton, its camera, its size.
        avatar, camera = film(request, build)
        filmed = filmed_hand_motion if isinstance(build.rig, HandModel) else filmed_body_motion
        size = (request.width, request.height)
        # An imported avatar's own skeleton has other joints: the engine's then stands in.
        rig = avatar.rig if type(avatar.rig) is type(build.rig) else build.rig
        landmarks = filmed(rig, dofs, request.rate_hz, camera, *size)
        print(f"wrote {write_pose(landmarks, pose_path)}")
    if bvh_path is not None:
        write_bvh(build.rig.as_motion(dofs, request.rate_hz), bvh_path)
        print(f"wrote {bvh_path}")


def _capture_body(args: argparse.Namespace) -> int:
    """Capture the body and hands (MediaPipe Holistic) and fit the upper body's arms."""
    from synthesis.capture import write_pose
    from synthesis.capture.armfit import fit_arms
    from synthesis.capture.video import capture_body
    from synthesis.rigs.body import BodyModel
    from synthesis.skeleton.bvh import write_bvh

    recording = capture_body(args.video, progress=_progress(Path(args.video).name))
    if args.out is not None:
        print(f"wrote {write_pose(recording, args.out)}")
    body = BodyModel(args.side)
    fit = fit_arms(body, recording)
    if args.bvh is not None:
        write_bvh(body.as_motion(fit.dofs_rad, recording.fps), args.bvh)
        print(f"wrote {args.bvh}")
    print(f"{recording.n_frames} frames at {recording.fps:g} fps; found: {_arms_found(fit)}")
    return 0


def capture_command(args: argparse.Namespace) -> int:
    """Run ``python -m synthesis capture``: a video's hands to .pose, BVH and a report."""
    from synthesis.capture import captured_hand, write_pose, write_report
    from synthesis.capture.video import capture_hands
    from synthesis.skeleton.bvh import write_bvh

    if args.body:
        return _capture_body(args)
    one_hand = args.side if args.one_hand else None
    recording = capture_hands(
        args.video,
        mirrored=args.mirrored,
        one_hand=one_hand,
        progress=_progress(Path(args.video).name),
    )
    hand = captured_hand(recording, args.side)
    if args.out is not None:
        print(f"wrote {write_pose(recording, args.out)}")
    if args.bvh is not None:
        write_bvh(hand.motion, args.bvh)
        print(f"wrote {args.bvh}")
    if args.report is not None:
        written = write_report(hand, recording, args.report, video=args.video)
        print(f"wrote {written}/quality.json, quality.png, contact.png")
    quality = hand.quality(recording)
    print(
        f"{recording.n_frames} frames at {recording.fps:g} fps; {args.side} hand found in "
        f"{quality['hands_found'].get(args.side, 0):.0%}; fit residual median "
        f"{quality['residual_mm_median']:.1f} mm"
    )
    if args.word:
        from synthesis.timing.extraction import extract

        timing = extract(hand.motion, args.word, args.side).timing
        print(json.dumps(timing.to_dict(), indent=2))
    return 0


def render_pose_file_command(args: argparse.Namespace) -> int:
    """Run ``python -m synthesis render-pose-file``: a .pose file's motion on the avatar."""
    from synthesis.capture import captured_hand, read_pose
    from synthesis.render.clip import render_clip
    from synthesis.rigs.retarget import retarget
    from synthesis.skeleton.retime import resample

    recording = read_pose(args.file)
    if args.view == "upper-body":
        return _render_pose_file_body(args, recording)
    hand = captured_hand(recording, args.side)
    motion = hand.motion
    if args.rate and abs(motion.rate_hz - args.rate) > 1e-9:
        motion = resample(motion, args.rate)
    avatar, camera = avatar_and_camera("hand", args.side)
    info = render_clip(
        avatar,
        retarget(motion, avatar.rig),
        camera,
        args.out,
        motion.rate_hz,
        poster=args.poster,
        width=args.size[0],
        height=args.size[1],
        progress=_progress(Path(args.file).name),
        workers=args.workers,
    )
    print(
        f"wrote {info.path} ({info.n_frames} frames at {info.rate_hz:g} fps; fit residual "
        f"median {hand.fit.median_residual_mm():.1f} mm)"
    )
    return 0


def _render_pose_file_body(args: argparse.Namespace, recording) -> int:
    """Render a .pose file's arms and hands on the upper body (synthesis.capture.armfit)."""
    from synthesis.capture.armfit import fit_arms
    from synthesis.render.clip import render_clip

    if args.rate and abs(recording.fps - args.rate) > 1e-9:
        raise ValueError("--rate resamples hand motions only; leave it out with --view upper-body.")
    avatar, camera = avatar_and_camera("upper-body", args.side)
    fit = fit_arms(avatar.rig, recording)
    info = render_clip(
        avatar,
        fit.dofs_rad,
        camera,
        args.out,
        recording.fps,
        poster=args.poster,
        width=args.size[0],
        height=args.size[1],
        progress=_progress(Path(args.file).name),
        workers=args.workers,
    )
    print(
        f"wrote {info.path} ({info.n_frames} frames at {info.rate_hz:g} fps; "
        f"found: {_arms_found(fit)})"
    )
    return 0


def _arms_found(fit) -> str:
    """Say in how many frames each arm, the trunk and the head were seen ("left arm 100%,
    right arm 97%, trunk 100%, head 99%"; no trunk or head for a file without them)."""
    parts = list(zip(("left arm", "right arm"), fit.found.mean(axis=0), strict=True))
    if fit.trunk is not None:
        parts += zip(("trunk", "head"), fit.trunk.found.mean(axis=0), strict=True)
    said = ", ".join(f"{part} {share:.0%}" for part, share in parts)
    if fit.depth == "lengths":
        said += "; the file's depth was flat: rebuilt from the model's proportions"
    if fit.image_miss is not None and np.isfinite(fit.image_miss).any():
        said += (
            f"; the arms lie within {np.nanmedian(fit.image_miss):.2f} shoulder widths "
            f"of its image points (median; worst {np.nanmax(fit.image_miss):.2f})"
        )
    return said
