"""Command line of the animation engine.

    python -m synthesis landmarks ABC                  # MediaPipe landmarks as JSON
    python -m synthesis render-pose --letter R --out r.png
    python -m synthesis spell HEAVEN --out heaven.mp4
    python -m synthesis render-bvh file.bvh --out clip.mp4
    python -m synthesis capture video.mp4 --word HEAVEN --out heaven.pose --bvh heaven.bvh
    python -m synthesis render-pose-file file.pose --out clip.mp4
    python -m synthesis techniques                     # what a condition can set

Rendering commands take ``--view hand`` (the fingerspelling close-up) or ``--view
upper-body``, ``--side left`` for a left-handed signer, and ``--size 640x480``.
"""

import argparse
import json
import sys
from pathlib import Path

from synthesis.cli_capture import capture_command, export_motion, render_pose_file_command
from synthesis.fingerspelling.alphabet import AlphabetError, letter_pose
from synthesis.fingerspelling.alphabets import (
    DEFAULT_ALPHABET,
    alphabet_codes,
    as_letter,
    manual_alphabet,
)
from synthesis.rigs.hand import HandModel
from synthesis.rigs.landmarks import landmarks
from synthesis.skeleton.bvh import BvhError
from synthesis.techniques import (
    REGISTRY,
    ClipRequest,
    avatar_and_camera,
    build_motion,
    filming,
    render_request,
)
from synthesis.techniques.flags import add_technique_flags, technique_values, techniques_help
from synthesis.techniques.timing import TIMINGS
from synthesis.terminal import frame_progress as _progress


def _landmarks(args: argparse.Namespace) -> int:
    model = HandModel(args.side)
    manual = manual_alphabet(args.alphabet)
    letters = [manual.check(c) for c in as_letter(args.letters) if not c.isspace()]
    result = {}
    for character in letters:
        points = landmarks(model, letter_pose(character, args.side, args.alphabet))
        result[character] = [[round(float(v), 6) for v in point] for point in points]
    print(json.dumps(result, indent=args.indent))
    return 0


def _size(text: str) -> tuple[int, int]:
    try:
        width, height = (int(v) for v in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"size must look like 640x480, not {text!r}") from None
    if width <= 0 or height <= 0 or width % 2 or height % 2:
        raise argparse.ArgumentTypeError(f"size must be positive and even, not {text!r}")
    return width, height


def _render_pose(args: argparse.Namespace) -> int:
    from synthesis.render.clip import render_still
    from synthesis.rigs.posture import hand_motion_on

    rig = avatar_and_camera(args.view, args.side)[0].rig
    pose = letter_pose(args.letter, args.side, args.alphabet)
    dofs = hand_motion_on(rig, args.side, pose[None])
    avatar, camera = filming(
        args.view, args.side, dofs, 1.0, *args.size, word=args.letter, alphabet=args.alphabet
    )
    path = render_still(avatar, dofs[0], camera, args.out, *args.size)
    print(f"wrote {path}")
    return 0


def _request(args: argparse.Namespace, kind: str, text: str, **values) -> ClipRequest:
    fields = {
        "view": args.view or "",
        "side": args.side,
        "width": args.size[0],
        "height": args.size[1],
        "rate_hz": args.rate,
    }
    if getattr(args, "seed", None) is not None:
        fields["seed"] = args.seed
    return ClipRequest(kind, text, {**technique_values(args), **values}, **fields)


def _exports(args: argparse.Namespace) -> bool:
    """Return whether *args* ask for the motion as a file (BVH, .pose or GLB)."""
    return any(path is not None for path in (args.export_pose, args.export_bvh, args.export_glb))


def _spell(args: argparse.Namespace) -> int:
    given = technique_values(args)
    values = {}
    if given.get("recording") and args.simulate is not None:
        raise ValueError("Give either --recording or --simulate, not both.")
    if given.get("recording"):
        values["source"] = given.get("source", "recording")
    elif args.simulate is not None:
        values["source"] = "simulated"
        args.seed = args.simulate
    request = _request(args, "word", args.word, **values)
    build = build_motion(request)
    export_motion(build, request, args.export_pose, args.export_bvh, args.export_glb)
    if args.timing_only:
        if build.timing is None:
            _ = build.performance.extraction  # raises ExtractionError naming why
        print(json.dumps(build.timing.to_dict(), indent=2))
        return 0
    if args.out is None:
        if _exports(args):
            return 0  # the motion was what was asked for: nothing to render
        raise ValueError(
            "Give --out FILE.mp4, an export (--export-bvh, --export-pose, --export-glb) "
            "or --timing-only to print the timing."
        )
    info = render_request(
        request,
        args.out,
        poster=args.poster,
        workers=args.workers,
        progress=_progress(f"spelling {args.word}"),
        build=build,
    )
    print(
        f"wrote {info.path} ({info.n_frames} frames, {info.duration_s:.2f} s, "
        f"{build.timing.condition if build.timing is not None else 'as performed'} timing)"
    )
    return 0


def _sentence(args: argparse.Namespace) -> int:
    request = _request(args, "sentence", args.text)
    build = build_motion(request)
    export_motion(build, request, args.export_pose, args.export_bvh, args.export_glb)
    if args.plot is not None:
        from synthesis.signing.sentence_plots import torso_angles_figure

        spine = request.parameters["spine"]
        flipped = {**request.parameters, "spine": not spine}
        other = build_motion(ClipRequest(**{**request.to_dict(), "parameters": flipped}))
        pair = (build.result, other.result) if spine else (other.result, build.result)
        torso_angles_figure(*pair, title=args.text).savefig(args.plot, dpi=120)
        print(f"wrote {args.plot}")
    if args.out is None:
        return 0
    info = render_request(
        request,
        args.out,
        poster=args.poster,
        workers=args.workers,
        progress=_progress("signing"),
        build=build,
    )
    spine = "on" if request.parameters["spine"] else "off"
    print(f"wrote {info.path} ({info.n_frames} frames, {info.duration_s:.2f} s, spine {spine})")
    return 0


def _render_bvh(args: argparse.Namespace) -> int:
    from synthesis.avatar.imported.motion import read_motion_file
    from synthesis.render.clip import render_clip
    from synthesis.rigs.retarget import retarget
    from synthesis.skeleton.mapping import detect_mapping

    motion = read_motion_file(args.file, args.rate)
    mapping = detect_mapping(motion.skeleton)
    unmapped = mapping.unmapped_parts()
    if {"left arm", "right arm"} <= set(unmapped):
        raise ValueError(
            f"{Path(args.file).name}: no arm joint is mapped ({mapping.convention} names), "
            "so nothing would sign."
        )
    warning = mapping.at_rest_warning(Path(args.file).name)
    if warning:
        print(f"warning: {warning}", file=sys.stderr)
    view = args.view or ("hand" if mapping.is_single_hand else "upper-body")
    side = (mapping.side() or args.side) if mapping.is_single_hand else args.side
    rig = avatar_and_camera(view, side)[0].rig
    # A fixed camera films a body in place; a hand's travel is its signing.
    in_place = not mapping.is_single_hand and not args.as_captured
    pose = retarget(motion, rig, mapping, in_place=in_place)
    avatar, camera = filming(view, side, pose, motion.rate_hz, *args.size)
    info = render_clip(
        avatar,
        pose,
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
        f"wrote {info.path} ({info.n_frames} frames at {info.rate_hz:g} fps; "
        f"{mapping.convention} joint names, {len(mapping.to_canonical)} joints mapped)"
    )
    return 0


def _version(args: argparse.Namespace) -> int:
    from synthesis.identity import engine_digest

    print(engine_digest())
    return 0


def _techniques(args: argparse.Namespace) -> int:
    if args.json:
        print(json.dumps(REGISTRY.schema(), indent=2, ensure_ascii=False))
        return 0
    for technique in REGISTRY.techniques:
        print(
            f"{technique.name}: {technique.label} ({technique.source}), "
            f"for {', '.join(sorted(technique.kinds))}"
        )
        for parameter in technique.parameters:
            allowed = f" {{{', '.join(parameter.choices)}}}" if parameter.choices else ""
            print(
                f"  {parameter.name} ({parameter.type}{allowed}, default "
                f"{parameter.default!r}): {parameter.help}"
            )
    return 0


def parser() -> argparse.ArgumentParser:
    """Build the command-line parser."""
    main = argparse.ArgumentParser(
        prog="python -m synthesis",
        description=__doc__.split("\n\n")[0],
        epilog=techniques_help(),
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    commands = main.add_subparsers(dest="command", required=True)
    marks = commands.add_parser(
        "landmarks", help="print the 21 MediaPipe hand landmarks of letters as JSON (metres)"
    )
    marks.add_argument("letters", help="letters, e.g. ABC")
    marks.add_argument("--side", choices=("right", "left"), default="right")
    marks.add_argument("--indent", type=int, default=None)
    marks.add_argument("--alphabet", choices=alphabet_codes(), default=DEFAULT_ALPHABET)
    marks.set_defaults(run=_landmarks)

    def rendering(
        name: str, help: str, view: str | None = "hand", out_required: bool = True
    ) -> argparse.ArgumentParser:
        command = commands.add_parser(name, help=help)
        command.add_argument("--out", required=out_required, type=Path, help="output file")
        command.add_argument(
            "--side", choices=("right", "left"), default="right", help="the signer's dominant hand"
        )
        command.add_argument("--view", choices=("hand", "upper-body"), default=view)
        command.add_argument("--size", type=_size, default=(640, 480), help="WIDTHxHEIGHT")
        return command

    def clip_options(command: argparse.ArgumentParser) -> None:
        command.add_argument("--poster", type=Path, help="also write the first frame as a PNG")
        command.add_argument("--workers", type=int, default=1, help="render in this many processes")

    def export_options(command: argparse.ArgumentParser) -> None:
        command.add_argument(
            "--export-pose",
            type=Path,
            metavar="FILE.pose",
            help="also write the motion as .pose landmarks",
        )
        command.add_argument(
            "--export-bvh", type=Path, metavar="FILE.bvh", help="also write the motion as BVH"
        )
        command.add_argument(
            "--export-glb",
            type=Path,
            metavar="FILE.glb",
            help="also write the avatar, its motion, face and camera as "
            "glTF binary (Blender, Unity, three.js)",
        )

    pose = rendering("render-pose", "render one letter's handshape to a PNG")
    pose.add_argument("--letter", required=True)
    pose.add_argument("--alphabet", choices=alphabet_codes(), default=DEFAULT_ALPHABET)
    pose.set_defaults(run=_render_pose)

    spell = rendering("spell", "render a fingerspelled word to an MP4", out_required=False)
    spell.add_argument("word")
    spell.add_argument("--rate", type=float, default=60.0, help="frames per second")
    spell.add_argument(
        "--condition", dest="technique_timing", choices=TIMINGS, help="the same as --timing"
    )
    spell.add_argument(
        "--simulate",
        type=int,
        metavar="SEED",
        help="a simulated capture of the word (timing sampled from the model, capture noise "
        "added) in place of --recording; labelled simulated in the timing",
    )
    add_technique_flags(spell, "word")
    spell.add_argument(
        "--timing-only", action="store_true", help="print the timing as JSON, render nothing"
    )
    clip_options(spell)
    export_options(spell)
    spell.set_defaults(run=_spell)

    sentence = rendering(
        "sentence",
        "render a signed sentence on the upper body",
        view="upper-body",
        out_required=False,
    )
    sentence.add_argument("text", help='glosses, e.g. "BUT SURPRISE MY BROTHER GET NEW C-A-R"')
    sentence.add_argument("--rate", type=float, default=60.0, help="frames per second")
    sentence.add_argument("--seed", type=int, default=0, help="seed of the liveliness noise")
    sentence.add_argument(
        "--plot", type=Path, help="plot torso bend and twist, spine on vs off (PNG/PDF)"
    )
    add_technique_flags(sentence, "sentence")
    clip_options(sentence)
    export_options(sentence)
    sentence.set_defaults(run=_sentence)

    version = commands.add_parser(
        "version", help="print the engine digest that names every clip this engine renders"
    )
    version.set_defaults(run=_version)

    listing = commands.add_parser("techniques", help="list the registered techniques")
    listing.add_argument("--json", action="store_true", help="print the parameters' JSON Schema")
    listing.set_defaults(run=_techniques)

    capture = commands.add_parser(
        "capture", help="find the hands in a video (MediaPipe), fit the hand model, report"
    )
    capture.add_argument("video", type=Path, help="an MP4, WebM or MOV video")
    capture.add_argument("--word", help="the word it spells: print its holds and transitions")
    capture.add_argument("--out", type=Path, help="write the landmarks as a .pose file")
    capture.add_argument("--bvh", type=Path, help="write the fitted hand motion as BVH")
    capture.add_argument("--report", type=Path, help="write quality.json and quality.png here")
    capture.add_argument(
        "--side", choices=("right", "left"), default="right", help="the signer's dominant hand"
    )
    capture.add_argument(
        "--one-hand", action="store_true", help="the video shows only that hand (a close-up)"
    )
    capture.add_argument("--mirrored", action="store_true", help="the video is a selfie view")
    capture.add_argument(
        "--body", action="store_true", help="capture the body (MediaPipe Holistic), fit the arms"
    )
    capture.set_defaults(run=capture_command)

    pose_file = rendering(
        "render-pose-file",
        "render a .pose file's hand (or, with --view upper-body, its arms and hands) on the avatar",
        view="hand",
    )
    pose_file.add_argument("file", type=Path)
    pose_file.add_argument("--rate", type=float, default=None, help="resample to this rate")
    clip_options(pose_file)
    pose_file.set_defaults(run=render_pose_file_command)

    bvh = rendering(
        "render-bvh", "render a BVH, glTF/GLB or (through assimp) FBX motion to an MP4", view=None
    )
    bvh.add_argument("file", type=Path)
    bvh.add_argument("--rate", type=float, default=None, help="resample to this frame rate")
    bvh.add_argument(
        "--as-captured",
        action="store_true",
        help="keep a body's facing and its travel across the floor as captured (by default "
        "it is turned to face the camera and kept in place, as signing is filmed)",
    )
    clip_options(bvh)
    bvh.set_defaults(run=_render_bvh)
    return main


def main(argv: list[str] | None = None) -> int:
    """Run the command line; bad input prints one error line and returns 2."""
    args = parser().parse_args(argv)
    try:
        return args.run(args)
    except (AlphabetError, BvhError, ValueError, OSError) as error:  # SignError is a ValueError
        print(f"error: {error}", file=sys.stderr)
        return 2
    except ImportError as error:
        print(f"error: {error}", file=sys.stderr)
        return 3
