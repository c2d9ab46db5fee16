"""Test the rendering commands: render-pose, spell and render-bvh, and their errors."""

import json

import imageio.v3 as iio
import numpy as np
import pytest

from synthesis.cli import main
from synthesis.fingerspelling.spelling import REST_HOLD_MS, spell
from synthesis.render.video import count_frames
from synthesis.rigs.hand import HandModel
from synthesis.skeleton.bvh import write_bvh
from synthesis.skeleton.motion import Motion

pytestmark = pytest.mark.usefixtures("renderable")


def test_render_pose_writes_a_png(tmp_path, capsys):
    out = tmp_path / "r.png"
    assert main(["render-pose", "--letter", "R", "--out", str(out), "--size", "160x120"]) == 0
    assert iio.imread(out).shape == (120, 160, 3)
    assert "wrote" in capsys.readouterr().out


def test_spell_writes_an_mp4_with_the_expected_frame_count(tmp_path):
    out, poster = tmp_path / "ab.mp4", tmp_path / "ab.png"
    code = main(
        [
            "spell",
            "AB",
            "--out",
            str(out),
            "--poster",
            str(poster),
            "--size",
            "96x72",
            "--rate",
            "30",
        ]
    )
    assert code == 0
    assert count_frames(out) == len(spell("AB", rate_hz=30))
    assert iio.imread(poster).shape == (72, 96, 3)


def test_unknown_letter_is_one_clear_error(tmp_path, capsys):
    assert main(["spell", "HE7LO", "--out", str(tmp_path / "x.mp4")]) == 2
    assert "'7' is not a letter of the ASL manual alphabet" in capsys.readouterr().err
    assert not (tmp_path / "x.mp4").exists()


def test_spell_exports_the_motion_without_rendering_it(tmp_path, capsys):
    """Issue 54 (7): spell with an export and no --out wrote the export and exited 2."""
    bvh = tmp_path / "cab.bvh"
    assert main(["spell", "CAB", "--export-bvh", str(bvh)]) == 0
    assert bvh.read_text().startswith("HIERARCHY")
    assert main(["spell", "CAB"]) == 2
    assert "Give --out FILE.mp4, an export" in capsys.readouterr().err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cab.bvh"]


def test_a_libras_word_spells_in_its_alphabet_and_asl_names_the_letter(tmp_path, capsys):
    out = tmp_path / "cay.mp4"
    assert main(["spell", "ÇAY", "--alphabet", "libras", "--out", str(out), "--size", "96x72"]) == 0
    assert out.stat().st_size > 0
    assert main(["spell", "ÇAY", "--out", str(tmp_path / "x.mp4")]) == 2
    assert "'Ç' is not a letter of the ASL manual alphabet (A–Z)" in capsys.readouterr().err
    assert main(["landmarks", "çay", "--alphabet", "libras"]) == 0
    assert list(json.loads(capsys.readouterr().out)) == ["Ç", "A", "Y"]


def test_render_bvh_renders_a_hand_file(tmp_path):
    model = HandModel()
    dofs = spell("HI", rate_hz=30)[::3]
    path = tmp_path / "hi.bvh"
    write_bvh(Motion(model.skeleton, model.channel_values(dofs), 0.1), path)
    out = tmp_path / "hi.mp4"
    assert main(["render-bvh", str(path), "--out", str(out), "--size", "96x72"]) == 0
    assert count_frames(out) == len(dofs)


def test_render_bvh_reports_a_malformed_file_by_line(tmp_path, capsys):
    path = tmp_path / "bad.bvh"
    path.write_text(
        "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 zero\n  CHANNELS 3 Xrotation Yrotation"
        " Zrotation\n}\nMOTION\nFrames: 1\nFrame Time: 0.1\n0 0 0\n"
    )
    assert main(["render-bvh", str(path), "--out", str(tmp_path / "bad.mp4")]) == 2
    assert "line 4" in capsys.readouterr().err
    assert np.all([p.suffix != ".mp4" for p in tmp_path.iterdir()])


def test_spell_prints_the_constant_timing_and_renders_a_saved_one(tmp_path, capsys):
    import json

    from synthesis.timing import WordTiming

    assert main(["spell", "heaven", "--condition", "constant", "--timing-only"]) == 0
    printed = json.loads(capsys.readouterr().out)
    assert printed["hold_ms"][-1] == 800.0 and printed["transition_ms"] == [250.0] * 5
    saved = tmp_path / "fast.json"
    fast = WordTiming(("O", "K"), (100, 100), (100,), "mine")
    saved.write_text(json.dumps(fast.to_dict()))
    out = tmp_path / "ok.mp4"
    assert (
        main(
            [
                "spell",
                "OK",
                "--timing-file",
                str(saved),
                "--out",
                str(out),
                "--rate",
                "30",
                "--size",
                "64x48",
            ]
        )
        == 0
    )
    assert count_frames(out) == len(spell("OK", rate_hz=30, timing=fast))
    assert main(["spell", "NO", "--timing-file", str(saved), "--timing-only"]) == 2
    assert "times OK, not NO" in capsys.readouterr().err


def test_spell_variable_and_normalized_timings_last_equally_long(capsys):
    import json

    totals = {}
    for condition in ("variable", "normalized", "constant"):
        assert main(["spell", "DAVID", "--condition", condition, "--timing-only"]) == 0
        totals[condition] = json.loads(capsys.readouterr().out)["total_ms"]
    assert totals["normalized"] == pytest.approx(totals["variable"], abs=0.01)
    assert totals["constant"] > totals["variable"]  # seed 000 Table 4.3: constant is slower


def test_spell_retimes_a_recording_for_each_condition(tmp_path, capsys):
    import json

    from synthesis.timing import constant_timing

    model = HandModel()
    recording = tmp_path / "david.bvh"
    write_bvh(
        Motion(model.skeleton, model.channel_values(spell("DAVID", lead_ms=300)), 1 / 60), recording
    )
    assert (
        main(
            [
                "spell",
                "DAVID",
                "--condition",
                "mocap",
                "--recording",
                str(recording),
                "--timing-only",
            ]
        )
        == 0
    )
    assert json.loads(capsys.readouterr().out)["condition"] == "mocap"
    out = tmp_path / "constant.mp4"
    assert (
        main(
            [
                "spell",
                "DAVID",
                "--condition",
                "constant",
                "--recording",
                str(recording),
                "--out",
                str(out),
                "--size",
                "64x48",
            ]
        )
        == 0
    )
    # The recording's lead-in and lead-out (300 ms of movement after 100 ms of rest, each)
    # framed the new timing.
    expected_s = constant_timing("DAVID").total_ms / 1000 + 2 * (0.3 + REST_HOLD_MS / 1000)
    assert count_frames(out) == pytest.approx(expected_s * 60, abs=3)
    assert main(["spell", "DAVID", "--condition", "mocap", "--out", str(out)]) == 2
    assert "give --recording" in capsys.readouterr().err


def test_spell_with_a_simulated_capture(tmp_path, capsys):
    import json

    assert main(["spell", "DAVID", "--condition", "mocap", "--simulate", "7", "--timing-only"]) == 0
    timing = json.loads(capsys.readouterr().out)
    assert timing["condition"] == "mocap" and timing["metadata"]["simulated"] is True
    assert main(["spell", "DAVID", "--condition", "mocap", "--simulate", "7", "--timing-only"]) == 0
    assert json.loads(capsys.readouterr().out) == timing  # the seed fixes the take
    assert main(["spell", "DAVID", "--simulate", "7", "--recording", "x.bvh"]) == 2
    assert "not both" in capsys.readouterr().err


def test_sentence_renders_and_plots_the_spine_conditions(tmp_path, renderable):
    out, plot = tmp_path / "s.mp4", tmp_path / "torso.png"
    assert (
        main(
            [
                "sentence",
                "ME GET",
                "--spine",
                "off",
                "--out",
                str(out),
                "--size",
                "64x48",
                "--plot",
                str(plot),
                "--rate",
                "30",
            ]
        )
        == 0
    )
    assert count_frames(out) > 30 and plot.stat().st_size > 10_000
    assert main(["sentence", "ME FLY", "--out", str(out)]) == 2


def test_sentence_names_a_bad_library(tmp_path, capsys):
    library = tmp_path / "signs.yaml"
    library.write_text("format: other\n", encoding="utf-8")
    assert main(["sentence", "ME", "--library", str(library)]) == 2
    assert "Not a sign library" in capsys.readouterr().err
