"""Test the Variable model: features, the naïve Bayes classifier, transitions, defaults."""

import itertools

import numpy as np
import pytest

from synthesis.timing import (
    HoldClassifier,
    TimingError,
    TransitionModel,
    VariableModel,
    joint_differences,
    letter_distance,
    letter_features,
    normalized_constant_timing,
    pose_distance,
    published_model,
)
from synthesis.timing.bayes import CLASSES_MS, hold_class
from synthesis.timing.defaults import VOCABULARY, has_double, published_holds

STUDY_WORDS = ("GUITAR", "HEAVEN", "ARREST", "ELEPHANT", "PSYCHIATRY", "DAVID", "MICHAEL", "VICTOR")


def test_features_of_table_4_2():
    values = letter_features("arrest", 2)
    assert values == {
        "letter": "R",
        "word_length": "6",
        "previous": "R",
        "following": "E",
        "place": "middle",
        "index": "2",
        "vowel": "consonant",
        "double": "double",
        "shape": "open",
        "word": "ARREST",
    }
    assert letter_features("A", 0)["place"] == "first"
    assert letter_features("CAT", 2)["following"] == "#"


def test_classes_are_120_fps_frames_up_to_a_third_of_a_second():
    assert len(CLASSES_MS) == 40
    assert CLASSES_MS[0] == pytest.approx(8.333, abs=1e-3)
    assert CLASSES_MS[-1] == pytest.approx(333.333, abs=1e-3)
    assert hold_class(100.0) == 11 and hold_class(1.0) == 0 and hold_class(900.0) == 39


def test_classifier_learns_a_feature_and_smooths_unseen_values():
    samples = [({"letter": "A"}, 50.0)] * 5 + [({"letter": "B"}, 200.0)] * 5
    model = HoldClassifier.fit(samples, features=("letter",))
    assert model.predict_ms({"letter": "A"}) == pytest.approx(50.0, abs=4.2)
    assert model.predict_ms({"letter": "B"}) == pytest.approx(200.0, abs=4.2)
    # A letter never seen gives no evidence: the prior decides (a tie, first class wins).
    assert model.predict_ms({"letter": "Z"}) in (
        CLASSES_MS[hold_class(50)],
        CLASSES_MS[hold_class(200)],
    )


def test_a_class_without_training_holds_is_unlikely_not_impossible():
    """Issue 38: a hold class no training hold fell in had prior 0 (log −∞); Laplace's α
    gives it (0 + α) / (n + α·K), as it does every unseen feature value."""
    samples = [({"letter": "A"}, 50.0)] * 5 + [({"letter": "B"}, 200.0)] * 5
    model = HoldClassifier.fit(samples, features=("letter",))
    log_p = model.log_posterior({"letter": "A"})
    assert np.all(np.isfinite(log_p))
    empty = hold_class(300.0)
    assert log_p[empty] == pytest.approx(np.log(1 / (10 + len(CLASSES_MS))) + np.log(1 / 2))
    assert log_p[empty] < log_p[hold_class(50.0)]


def test_leave_one_out_matches_refitting_without_each_sample():
    rng = np.random.default_rng(1)
    samples = published_holds(rng)[:60]
    model = HoldClassifier.fit(samples)
    fast = model.leave_one_out(samples)
    hits = 0
    for k, (values, hold_ms) in enumerate(samples):
        others = HoldClassifier.fit(samples[:k] + samples[k + 1 :])
        hits += hold_class(others.predict_ms(values)) == hold_class(hold_ms)
    assert fast.accuracy == pytest.approx(hits / len(samples))


def test_transition_distances_are_symmetric_and_in_the_published_proportions():
    """Seed 000 §4.2.2: RMSD over 18 joints between letters 0–1.10 rad; E–Z 0.51 rad, 46 %
    of the largest. Over the engine's 17 joints the letters span 0–1.37 rad."""
    letters = "ABCDEFGHIJKLMNOPQRSTUVWXYZ"
    distances = [letter_distance(a, b) for a, b in itertools.combinations(letters, 2)]
    assert min(distances) >= 0.0 and 1.1 <= max(distances) < 1.5
    assert letter_distance("E", "Z") / max(distances) == pytest.approx(0.51 / 1.10, abs=0.03)
    assert letter_distance("K", "W") == letter_distance("W", "K")
    # The 30-DOF option (the engine's earlier measure) is kept and differs.
    over_dofs = [letter_distance(a, b, space="dofs") for a, b in itertools.combinations("AEZ", 2)]
    assert over_dofs != [letter_distance(a, b) for a, b in itertools.combinations("AEZ", 2)]
    with pytest.raises(ValueError, match="distance space"):
        letter_distance("A", "B", space="quaternions")
    a, b = np.zeros(4), np.array([1.0, -1.0, 0.5, 0.0])
    assert pose_distance(a, b, "manhattan") == 2.5 and pose_distance(a, b, "chebyshev") == 1.0
    with pytest.raises(ValueError, match="Unknown distance 'cosine'"):
        pose_distance(a, b, "cosine")


def test_joint_differences_count_each_joint_once_by_its_rotation_angle():
    from synthesis.rigs.hand import HandModel

    hand = HandModel("right")
    a, b = hand.neutral(), hand.neutral()
    b[hand.dof_names.index("index_pip_flexion")] += 0.5
    b[hand.dof_names.index("wrist_flexion")] += 0.3
    b[hand.dof_names.index("wrist_deviation")] += 0.4
    differences = joint_differences(a, b)
    assert differences.shape == (17,)
    # Two perpendicular turns compose to one: cos(θ/2) = cos(0.3/2) · cos(0.4/2).
    wrist = 2 * np.arccos(np.cos(0.15) * np.cos(0.2))
    assert sorted(differences[differences > 1e-9]) == pytest.approx(sorted([0.5, wrist]))


def test_a_transition_model_saved_without_a_space_measured_dofs():
    saved = {"intercept_ms": 100.0, "slope_ms_per_rad": 150.0, "metric": "rmsd"}
    assert TransitionModel.from_dict(saved).space == "dofs"
    assert TransitionModel(100.0, 150.0).space == "joints"
    model = TransitionModel(100.0, 150.0)
    assert TransitionModel.from_dict(model.to_dict()) == model
    with pytest.raises(ValueError, match="space"):
        TransitionModel.from_dict({**saved, "space": "pixels"})


def test_transition_fit_recovers_a_line():
    d = np.linspace(0.1, 1.0, 20)
    model = TransitionModel.fit(d, 120 + 150 * d)
    assert model.intercept_ms == pytest.approx(120) and model.slope_ms_per_rad == pytest.approx(150)
    assert model.r == pytest.approx(1.0)


def test_default_model_shows_the_published_regularities():
    """Seed 000 §4.1 / Table 4.1 at normal speed, from the default model's predictions."""
    model = published_model()
    assert "published statistics" in model.metadata["source"]
    timings = {word: model.timing(word) for word in (*VOCABULARY, *STUDY_WORDS)}
    last, others = [], []
    for timing in timings.values():
        last.append(timing.hold_ms[-1])
        others.extend(timing.hold_ms[:-1])
    assert np.mean(last) > 1.2 * np.mean(others)  # the last letter is held longer
    by_length = {
        n: np.mean([np.mean(t.hold_ms) for w, t in timings.items() if len(w) == n]) for n in (3, 4)
    }
    long = np.mean([np.mean(t.hold_ms) for w, t in timings.items() if len(w) >= 5])
    assert by_length[3] > by_length[4] > long  # shorter holds in longer words
    per_letter = {w: t.total_ms / len(w) for w, t in timings.items()}
    doubled = np.mean([v for w, v in per_letter.items() if has_double(w)])
    single = np.mean([v for w, v in per_letter.items() if not has_double(w)])
    assert doubled < single  # words with a double letter are spelled faster


def test_normalized_constant_equals_the_variable_duration():
    model = published_model()
    for word in STUDY_WORDS:
        variable = model.timing(word)
        assert normalized_constant_timing(word, variable).total_ms == pytest.approx(
            variable.total_ms
        )


def test_model_round_trips_through_its_file_and_names_bad_files(tmp_path):
    model = published_model()
    path = model.write(tmp_path / "model.json")
    again = VariableModel.read(path)
    assert again.timing("ELEPHANT") == model.timing("ELEPHANT")
    assert again.metadata == model.metadata
    (tmp_path / "bad.json").write_text('{"format": "signstudy.timing-model", "version": 1}')
    with pytest.raises(TimingError, match="Malformed timing model"):
        VariableModel.read(tmp_path / "bad.json")
    (tmp_path / "junk.json").write_text("{nope")
    with pytest.raises(TimingError, match="not JSON"):
        VariableModel.read(tmp_path / "junk.json")


def test_leave_one_out_reports_on_every_hold():
    samples = published_holds(np.random.default_rng(3))
    assert len(samples) >= 300
    result = HoldClassifier.fit(samples).leave_one_out(samples)
    assert result.nobs == len(samples) and 0 < result.accuracy < 1
    assert 0 < result.mean_abs_error_ms < 60
    assert set(result.to_dict()) == {
        "accuracy",
        "mean_abs_error_ms",
        "mean_signed_error_ms",
        "nobs",
    }


def test_the_gplvm_distance_runs_from_0_to_1_between_letters():
    """Seed 000 §4.2.2: GPLVMD = Σ (c_a − d_b)² / x, normalised to 0–1 (r = 0.22)."""
    from synthesis.timing.gplvm import ALPHABET, gplvm_distance

    distances = {
        (a, b): letter_distance(a, b, "gplvm") for a, b in itertools.combinations(ALPHABET, 2)
    }
    assert max(distances.values()) == pytest.approx(1.0)
    assert min(distances.values()) >= 0.0 and letter_distance("A", "A", "gplvm") == 0.0
    assert gplvm_distance("E", "Z") == gplvm_distance("z", "e")
    with pytest.raises(ValueError, match="between letters"):
        pose_distance(np.zeros(3), np.ones(3), "gplvm")


def test_the_gplvm_keeps_the_order_of_points_on_a_curve_and_needs_gpy(monkeypatch):
    import sys

    from synthesis.timing.gplvm import GplvmMissing, embed

    t = np.linspace(0.0, 1.0, 12)
    curve = np.column_stack([t, t**2, np.sin(2 * t), 0.5 * t, np.zeros_like(t)])
    latent = embed(curve, latent_dims=1, max_iterations=100)[:, 0]  # 0.98 already
    assert abs(np.corrcoef(latent, t)[0, 1]) > 0.9
    monkeypatch.setitem(sys.modules, "GPy", None)
    with pytest.raises(GplvmMissing, match="make install"):
        embed(curve)
