"""Command line of the animation engine.

    python -m synthesis landmarks ABC                  # MediaPipe landmarks as JSON
    python -m synthesis render-pose --letter R --out r.png
    python -m synthesis spell HEAVEN --out heaven.mp4
    python -m synthesis render-bvh file.bvh --out clip.mp4

Rendering commands take ``--view hand`` (the fingerspelling close-up) or ``--view
upper-body``, ``--side left`` for a left-handed signer, and ``--size 640x480``.
"""

import argparse
import json
import sys
from pathlib import Path

import numpy as np

from synthesis.alphabet import AlphabetError, letter_pose
from synthesis.bvh import BvhError
from synthesis.hand import HandModel
from synthesis.landmarks import landmarks


def _landmarks(args: argparse.Namespace) -> int:
    model = HandModel(args.side)
    letters = [character for character in args.letters if not character.isspace()]
    result = {}
    for character in letters:
        points = landmarks(model, letter_pose(character, args.side))
        result[character.upper()] = [[round(float(v), 6) for v in point] for point in points]
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


def _progress(label: str):
    """Return a progress callback: one updating line on a terminal, else every tenth."""
    interactive = sys.stderr.isatty()

    def report(done: int, total: int) -> None:
        if interactive:
            end = "\n" if done == total else ""
            print(f"\r{label}: frame {done}/{total}", end=end, file=sys.stderr, flush=True)
        elif done == total or done % max(1, total // 10) == 0:
            print(f"{label}: frame {done}/{total}", file=sys.stderr, flush=True)

    return report


def _scene(view: str, side: str):
    from synthesis.render.scene import hand_close_up, upper_body_front

    if view == "hand":
        from synthesis.avatar.hand import hand_avatar

        return hand_avatar(side), hand_close_up(side)
    from synthesis.avatar.body import body_avatar

    return body_avatar(side), upper_body_front(side)


def _hand_motion_for(avatar, side: str, hand_dofs: np.ndarray) -> np.ndarray:
    """Return the avatar's DOFs for hand-model DOFs (a body holds the hand up to sign)."""
    if isinstance(avatar.rig, HandModel):
        return hand_dofs
    from synthesis.posture import fingerspelling_posture

    return fingerspelling_posture(avatar.rig, side, hand_dofs)


def _render_pose(args: argparse.Namespace) -> int:
    from synthesis.render.clip import render_still

    avatar, camera = _scene(args.view, args.side)
    dofs = _hand_motion_for(avatar, args.side, letter_pose(args.letter, args.side)[None])[0]
    path = render_still(avatar, dofs, camera, args.out, *args.size)
    print(f"wrote {path}")
    return 0


def _timing(args: argparse.Namespace, recording=None):
    """Return the word timing the spell command asks for (a recording's own for mocap)."""
    from synthesis.spelling import simple_timing, word_letters
    from synthesis.timing import WordTiming, constant_timing, normalized_constant_timing

    if args.timing_file is not None:
        timing = WordTiming.from_dict(json.loads(args.timing_file.read_text("utf-8")))
        if timing.word != "".join(word_letters(args.word)):
            raise ValueError(f"{args.timing_file} times {timing.word}, not {args.word.upper()}.")
        return timing
    word = "".join(word_letters(args.word))
    if args.condition == "mocap":
        if recording is None:
            raise ValueError(
                "The mocap condition plays a recording: give --recording FILE.bvh of the word "
                "(or --simulate SEED for a simulated one)."
            )
        return recording.extraction.timing
    if args.condition == "constant":
        return constant_timing(word)
    if args.condition in ("variable", "normalized"):
        variable = _model(args).timing(word)
        if args.condition == "variable":
            return variable
        return normalized_constant_timing(word, variable)
    return simple_timing(args.word)


def _model(args: argparse.Namespace):
    """Return the Variable model the command asks for (the published one by default)."""
    from synthesis.timing import VariableModel, published_model

    return VariableModel.load(args.model) if args.model else published_model()


def _recorded_motion(recording, timing, avatar, args: argparse.Namespace):
    """Return the recording (retimed unless mocap) as the hand avatar's joint transforms.

    Seed 000 §4.3: with a recording, every condition is the recording itself, its holds
    and transitions moved onto the condition's timing.
    """
    from synthesis.retarget import retarget
    from synthesis.retime import resample
    from synthesis.timing.recordings import retime

    if not isinstance(avatar.rig, HandModel):
        raise ValueError("Recordings are rendered in the hand view for now: use --view hand.")
    motion = recording.motion if args.condition == "mocap" else retime(recording, timing)
    if abs(motion.rate_hz - args.rate) > 1e-9:
        motion = resample(motion, args.rate)
    return retarget(motion, avatar.rig)


def _spell(args: argparse.Namespace) -> int:
    from synthesis.render.clip import render_clip
    from synthesis.spelling import spell

    recording = None
    if args.recording is not None and args.simulate is not None:
        raise ValueError("Give either --recording or --simulate, not both.")
    if args.recording is not None:
        from synthesis.timing.recordings import Recording

        recording = Recording.read(args.recording, args.word, args.side)
    elif args.simulate is not None:
        from synthesis.timing.recordings import Recording

        model = _model(args)
        recording = Recording.simulate(args.word, args.simulate, model, args.side, args.rate)
    timing = _timing(args, recording)
    if args.timing_only:
        print(json.dumps(timing.to_dict(), indent=2))
        return 0
    if args.out is None:
        raise ValueError("Give --out FILE.mp4 (or --timing-only to print the timing).")
    avatar, camera = _scene(args.view, args.side)
    if recording is not None:
        motion = _recorded_motion(recording, timing, avatar, args)
    else:
        hand_motion = spell(args.word, args.side, args.rate, timing=timing)
        motion = _hand_motion_for(avatar, args.side, hand_motion)
    info = render_clip(
        avatar, motion, camera, args.out, args.rate, poster=args.poster,
        width=args.size[0], height=args.size[1], progress=_progress(f"spelling {args.word}"),
        workers=args.workers,
    )  # fmt: skip
    print(
        f"wrote {info.path} ({info.n_frames} frames, {info.duration_s:.2f} s, "
        f"{timing.condition} timing)"
    )
    return 0


def _render_bvh(args: argparse.Namespace) -> int:
    from synthesis.bvh import read_bvh
    from synthesis.mapping import detect_mapping
    from synthesis.render.clip import render_clip
    from synthesis.retarget import retarget
    from synthesis.retime import resample

    motion = read_bvh(args.file)
    if args.rate and abs(motion.rate_hz - args.rate) > 1e-9:
        motion = resample(motion, args.rate)
    mapping = detect_mapping(motion.skeleton)
    view = args.view or ("hand" if mapping.is_single_hand else "upper-body")
    side = (mapping.side() or args.side) if mapping.is_single_hand else args.side
    avatar, camera = _scene(view, side)
    pose = retarget(motion, avatar.rig, mapping)
    info = render_clip(
        avatar, pose, camera, args.out, motion.rate_hz, poster=args.poster,
        width=args.size[0], height=args.size[1], progress=_progress(Path(args.file).name),
        workers=args.workers,
    )  # fmt: skip
    print(
        f"wrote {info.path} ({info.n_frames} frames at {info.rate_hz:g} fps; "
        f"{mapping.convention} joint names, {len(mapping.to_canonical)} joints mapped)"
    )
    return 0


def _sentence(args: argparse.Namespace) -> int:
    from dataclasses import replace

    from synthesis.render.clip import render_clip
    from synthesis.sentence import SentenceOptions, synthesize
    from synthesis.signs import read_library

    library = read_library(args.library) if args.library else None
    options = SentenceOptions(spine=args.spine == "on", rate_hz=args.rate, seed=args.seed,
                              dominant=args.side)  # fmt: skip
    sentence = synthesize(args.text, options, library)
    if args.plot is not None:
        from synthesis.sentence_plots import torso_angles_figure

        other = synthesize(args.text, replace(options, spine=not options.spine), library)
        pair = (sentence, other) if args.spine == "on" else (other, sentence)
        torso_angles_figure(*pair, title=args.text).savefig(args.plot, dpi=120)
        print(f"wrote {args.plot}")
    if args.out is None:
        return 0
    avatar, camera = _scene("upper-body", args.side)
    info = render_clip(
        avatar, sentence.dofs_rad, camera, args.out, args.rate, poster=args.poster,
        width=args.size[0], height=args.size[1], progress=_progress("signing"),
        workers=args.workers,
    )  # fmt: skip
    print(
        f"wrote {info.path} ({info.n_frames} frames, {info.duration_s:.2f} s, spine {args.spine})"
    )
    return 0


def parser() -> argparse.ArgumentParser:
    """Build the command-line parser."""
    main = argparse.ArgumentParser(
        prog="python -m synthesis",
        description=__doc__.split("\n\n")[0],
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    commands = main.add_subparsers(dest="command", required=True)
    marks = commands.add_parser(
        "landmarks", help="print the 21 MediaPipe hand landmarks of letters as JSON (metres)"
    )
    marks.add_argument("letters", help="letters, e.g. ABC")
    marks.add_argument("--side", choices=("right", "left"), default="right")
    marks.add_argument("--indent", type=int, default=None)
    marks.set_defaults(run=_landmarks)

    def rendering(
        name: str, help: str, view: str | None = "hand", out_required: bool = True
    ) -> argparse.ArgumentParser:
        command = commands.add_parser(name, help=help)
        command.add_argument("--out", required=out_required, type=Path, help="output file")
        command.add_argument("--side", choices=("right", "left"), default="right",
                             help="the signer's dominant hand")  # fmt: skip
        command.add_argument("--view", choices=("hand", "upper-body"), default=view)
        command.add_argument("--size", type=_size, default=(640, 480), help="WIDTHxHEIGHT")
        return command

    def clip_options(command: argparse.ArgumentParser) -> None:
        command.add_argument("--poster", type=Path, help="also write the first frame as a PNG")
        command.add_argument("--workers", type=int, default=1, help="render in this many processes")

    pose = rendering("render-pose", "render one letter's handshape to a PNG")
    pose.add_argument("--letter", required=True)
    pose.set_defaults(run=_render_pose)

    spell = rendering("spell", "render a fingerspelled word to an MP4", out_required=False)
    spell.add_argument("word")
    spell.add_argument("--rate", type=float, default=60.0, help="frames per second")
    spell.add_argument(
        "--condition", choices=("simple", "constant", "variable", "normalized", "mocap"),
        default="simple",
        help="timing: simple (equal holds), constant (Huenerfauth: 243/800 ms holds), "
        "variable (naïve Bayes + pose distance), normalized (constant at variable's length), "
        "mocap (the --recording as it is)",
    )  # fmt: skip
    spell.add_argument(
        "--recording", type=Path,
        help="a BVH recording of the word: conditions retime it instead of synthesising",
    )  # fmt: skip
    spell.add_argument(
        "--simulate", type=int, metavar="SEED",
        help="a simulated capture of the word (timing sampled from the model, capture noise "
        "added) in place of --recording; labelled simulated in the timing",
    )  # fmt: skip
    spell.add_argument(
        "--model", type=Path,
        help="a trained Variable model (JSON); default: built from published statistics",
    )  # fmt: skip
    spell.add_argument("--timing-file", type=Path, help="a word timing saved as JSON")
    spell.add_argument(
        "--timing-only", action="store_true", help="print the timing as JSON, render nothing"
    )
    clip_options(spell)
    spell.set_defaults(run=_spell)

    sentence = rendering("sentence", "render a signed sentence on the upper body",
                         view="upper-body", out_required=False)  # fmt: skip
    sentence.add_argument("text", help='glosses, e.g. "BUT SURPRISE MY BROTHER GET NEW C-A-R"')
    sentence.add_argument("--spine", choices=("on", "off"), default="on",
                          help="automated spine and shoulder motion (spec 03)")  # fmt: skip
    sentence.add_argument("--rate", type=float, default=60.0, help="frames per second")
    sentence.add_argument("--seed", type=int, default=0, help="seed of the liveliness noise")
    sentence.add_argument("--library", type=Path, help="a sign library (YAML) to use instead")
    sentence.add_argument("--plot", type=Path,
                          help="plot torso bend and twist, spine on vs off (PNG/PDF)")  # fmt: skip
    clip_options(sentence)
    sentence.set_defaults(run=_sentence)

    bvh = rendering("render-bvh", "render a BVH motion to an MP4", view=None)
    bvh.add_argument("file", type=Path)
    bvh.add_argument("--rate", type=float, default=None, help="resample to this frame rate")
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
