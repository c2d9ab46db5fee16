"""Power planning: the design file, the simulation against closed forms, the command line."""

import json

import numpy as np
import pytest
from scipy.special import logit

from analysis.cli import main
from analysis.power import (
    Effects,
    PlannedDesign,
    Trial,
    binomial_n,
    binomial_power,
    design_from_responses,
    paired_t_n,
    paired_t_power,
    parse_design,
    power_curve,
    simulate,
)
from analysis.tidy import TidyFormatError
from tests.analysis.mixed_data import pairwise_tidy


def _two_conditions(trials: int = 4) -> PlannedDesign:
    pair = (Trial("W", "a", "b"), Trial("W", "b", "a")) * (trials // 2)
    return PlannedDesign("pairwise", ("a", "b"), (pair,))


def test_binomial_closed_form():
    # 0.65 vs ½: the exact test's power at 85 trials (normal approximation: about 0.80).
    n = binomial_n(0.65)
    assert binomial_power(n, 0.65) >= 0.8 > binomial_power(n - 1, 0.65)
    assert 75 <= n <= 95
    assert paired_t_power(0.5, paired_t_n(0.5)) >= 0.8


def test_simulated_binomial_power_matches_the_closed_form():
    """At the N the closed form gives, simulated power is within 5 points of it."""
    p = 0.65
    trials = 4
    participants = -(-binomial_n(p) // trials)
    expected = binomial_power(participants * trials, p)
    effects = Effects({"a": 0.0, "b": float(logit(p))})
    curve = power_curve(
        _two_conditions(trials),
        effects,
        [participants],
        simulations=400,
        seed=3,
        tests=["binomial"],
        workers=1,
    )
    assert curve.power("binomial: b vs a", participants) == pytest.approx(expected, abs=0.05)


def test_simulation_is_reproducible_and_independent_of_workers():
    effects = Effects({"a": 0.0, "b": 0.4}, sd_participant=0.5)
    design = _two_conditions(8)
    one = power_curve(design, effects, [6], simulations=6, seed=9, workers=1)
    two = power_curve(design, effects, [6], simulations=6, seed=9, workers=2)
    assert one.points == two.points
    assert one.tests[0] == "mixed: conditions"


def test_simulated_data_follow_the_design():
    design = PlannedDesign(
        "pairwise",
        ("a", "b", "c"),
        ((Trial("X", "a", "b"), Trial("Y", "c", "a")), (Trial("X", "b", "c"),)),
    )
    data = simulate(design, Effects({"a": 0, "b": 0, "c": 0}), 4, np.random.default_rng(0))
    assert len(data) == 2 + 1 + 2 + 1
    assert list(data["clip1"][:3]) == ["a", "c", "b"]
    assert set(data["position"]) <= {1, 2}


@pytest.mark.parametrize(
    ("document", "message"),
    [
        ([], "a JSON object"),
        ({"kind": "survey"}, "kind must be one of"),
        ({"kind": "pairwise", "conditions": ["a"]}, "two or more condition"),
        ({"kind": "pairwise", "conditions": ["a", "b"], "schedules": []}, "non-empty list"),
        (
            {"kind": "pairwise", "conditions": ["a", "b"], "schedules": [[{"condition_a": "a"}]]},
            "schedule 1, trial 1: condition",
        ),
        (
            {
                "kind": "pairwise",
                "conditions": ["a", "b"],
                "schedules": [[{"condition_a": "a", "condition_b": "a"}]],
            },
            "two different conditions",
        ),
    ],
)
def test_malformed_designs_are_refused_by_name(document, message):
    with pytest.raises(TidyFormatError, match=message):
        parse_design(document)


def test_design_from_a_pilot_keeps_each_participants_trials():
    design = design_from_responses(pairwise_tidy(), "pairwise")
    assert design.conditions == ("a", "b", "c", "d")
    assert len(design.schedules) == 48 and design.trials_per_participant() == 48


def test_command_line_plans_from_a_pilot(tmp_path, capsys):
    frame = pairwise_tidy()
    frame = frame[frame["participant"].isin(sorted(set(frame["participant"]))[:12])]
    frame.assign(flags="pilot").to_csv(tmp_path / "pilot.csv", index=False)
    design = {
        "kind": "pairwise",
        "conditions": ["a", "b", "c", "d"],
        "schedules": [
            [{"item": "W1", "condition_a": a, "condition_b": b} for a, b in pairs]
            for pairs in (
                [("a", "b"), ("c", "d"), ("a", "c"), ("b", "d"), ("a", "d"), ("b", "c")] * 2,
                [("b", "a"), ("d", "c"), ("c", "a"), ("d", "b"), ("d", "a"), ("c", "b")] * 2,
            )
        ],
    }
    (tmp_path / "design.json").write_text(json.dumps(design))
    code = main(
        [
            "power",
            str(tmp_path / "pilot.csv"),
            "--design",
            str(tmp_path / "design.json"),
            "--n",
            "6:12:6",
            "--simulations",
            "8",
            "--workers",
            "1",
            "--out",
            str(tmp_path / "out"),
        ]
    )
    assert code == 0
    printed = capsys.readouterr().out
    assert "SIMULATED" in printed and "mixed: conditions" in printed
    data = json.loads((tmp_path / "out" / "power.json").read_text())
    assert data["simulated"] is True and data["effects"]["source"].startswith("pilot.csv")
    assert {p["participants"] for p in data["points"]} == {6, 12}
    assert (tmp_path / "out" / "power.png").stat().st_size > 1000


def test_command_line_names_bad_input(tmp_path, capsys):
    frame = pairwise_tidy().head(200)
    frame.to_csv(tmp_path / "pilot.csv", index=False)
    assert main(["power", str(tmp_path / "pilot.csv"), "--n", "ten"]) == 2
    assert "--n takes START:STOP:STEP" in capsys.readouterr().err
    (tmp_path / "e.json").write_text(json.dumps({"effects": {"a": 0}}))
    assert main(["power", str(tmp_path / "pilot.csv"), "--effects", str(tmp_path / "e.json")]) == 2
    assert "lack condition(s) b, c, d" in capsys.readouterr().err


def test_a_degenerate_fit_counts_as_a_failure_not_a_hit():
    """An SE of zero must not become z = ∞ and a rejection."""
    from types import SimpleNamespace

    from analysis.power.simulation import _mixed_tests

    fit = SimpleNamespace(params=np.array([0.0, 0.5]), cov=np.zeros((2, 2)), dropped=())
    found = _mixed_tests(["a", "b", "c"], fit, 0, 2)
    assert np.isnan(found["mixed: b vs a"]) and np.isnan(found["mixed: c vs b"])


def test_malformed_effects_file_is_named(tmp_path, capsys):
    pairwise_tidy().head(200).to_csv(tmp_path / "pilot.csv", index=False)
    (tmp_path / "e.json").write_text("{not json")
    assert main(["power", str(tmp_path / "pilot.csv"), "--effects", str(tmp_path / "e.json")]) == 2
    assert "e.json: not valid JSON" in capsys.readouterr().err
