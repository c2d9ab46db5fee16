"""Test the transition database: recordings cut into transitions, fits, file, search.

Data: the engine's simulated sentence captures (labelled simulated), built once per
module; see synthesis/transitions/simulate.py.
"""

import json

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from scipy.interpolate import BSpline

from synthesis.rigs.body import BodyModel
from synthesis.transitions import (
    DatabaseError,
    DescriptorSearch,
    RecordingError,
    TransitionDatabase,
    build_database,
    cut_transitions,
    fit_curve,
    fit_hermite,
    read_recording,
    simulated_captures,
    splice_points,
    write_recording,
)
from synthesis.transitions.hermite_fit import SMOOTHING_KERNEL, TANGENT_STEPS, fit_segment, smooth


@pytest.fixture(scope="module")
def recordings():
    return simulated_captures(signers=2, sentences=3, seed=1)


@pytest.fixture(scope="module")
def database(recordings):
    return build_database(recordings)


def test_simulated_signers_share_some_sentences_and_move_each_their_own_way():
    """Seed 001 §5.1: 63.6 % of best matches came from the query's own interpreter; a
    style that only scales one shape made the search find another signer's copy."""
    from synthesis.transitions.simulate import human_transition, signer_styles

    captures = simulated_captures(signers=2, sentences=4, seed=3, shared=0.5)
    texts = {}
    for c in captures:
        texts.setdefault(c.signer, []).append(
            tuple(s.label for s in c.segmentation.segments if s.kind == "sign")
        )
    first, second = texts.values()
    assert first[:2] == second[:2] and first[2:] != second[2:]
    styles = signer_styles(3, np.random.default_rng(0))
    assert len({s.lag for s in styles}) == 3 and all(any(s.wave) and any(s.stance) for s in styles)
    v0, v1 = np.zeros(7), np.array([0.6, 0.3, 0.2, 0.8, 0.1, 0.1, 0.0])
    curves = [human_transition(v0, v1, 60, s, np.random.default_rng(1)) for s in styles]
    # Each style's elbow path differs in shape, not only in size: normalized, they differ.
    elbow = [(c[:, 3] - c[:, 3].min()) / np.ptp(c[:, 3]) for c in curves]
    assert np.abs(elbow[0] - elbow[1]).max() > 0.05 and np.abs(elbow[0] - elbow[2]).max() > 0.05
    with pytest.raises(ValueError, match="shared"):
        simulated_captures(signers=1, sentences=1, shared=2.0)


def test_simulated_captures_are_segmented_and_labelled(recordings):
    recording = recordings[0]
    assert recording.simulated and recording.rate_hz == 120
    kinds = [s.kind for s in recording.segmentation.segments]
    assert kinds[0] == kinds[-1] == "rest"
    assert kinds[1::2] == ["sign"] * (len(kinds) // 2)  # sign, transition, sign, …
    assert set(kinds[2:-1:2]) == {"transition"}
    gaps_s = [t.n_frames / 120 for _, t, _ in recording.segmentation.transitions()]
    assert min(gaps_s) > 0.25 and max(gaps_s) < 0.95  # 0.3–0.9 s, seed 001 §4.2's 0.54 s mean


def test_cut_transitions_join_up_with_their_signs(recordings):
    recording = recordings[0]
    cuts = cut_transitions(recording)
    assert cuts and all(c.simulated for c in cuts)
    cut = cuts[0]
    before, middle, after = next(
        t for t in recording.segmentation.transitions() if t[1].order == cut.order
    )
    curves = recording.curves(cut.side)
    np.testing.assert_array_equal(cut.gap, curves[middle.start_frame : middle.end_frame + 1])
    np.testing.assert_array_equal(cut.before[-1], curves[before.end_frame])
    np.testing.assert_array_equal(cut.after[0], curves[after.start_frame])
    # A resting arm is no transition: with a huge threshold nothing is cut.
    assert cut_transitions(recording, min_range_deg=1000) == []


def test_bvh_and_segmentation_round_trip(tmp_path, recordings):
    recording = recordings[0]
    path = write_recording(recording, tmp_path)
    back = read_recording(path)
    assert back.simulated and back.signer == recording.signer
    assert back.segmentation == recording.segmentation
    # BVH keeps 6 decimals of degrees.
    np.testing.assert_allclose(back.dofs_rad, recording.dofs_rad, atol=1e-6)


def test_body_dofs_round_trip_through_bvh_channels():
    body = BodyModel("right")
    dofs = body.neutral() + np.random.default_rng(3).normal(0, 0.3, (6, len(body.dof_names)))
    # A fist flexes fingers past 90°, where the ZXY decomposition's first answer flips.
    dofs[:, body.dof_names.index("right_index_mcp_flexion")] = np.radians(95)
    dofs[:, body.dof_names.index("right_middle_pip_flexion")] = np.radians(100)
    np.testing.assert_allclose(body.dofs_from_motion(body.as_motion(dofs, 60)), dofs, atol=1e-12)


def test_bad_recordings_are_named(tmp_path, recordings):
    path = write_recording(recordings[0], tmp_path)
    (tmp_path / "lonely.bvh").write_text(path.read_text())
    with pytest.raises(RecordingError, match="no segmentation beside it"):
        read_recording(tmp_path / "lonely.bvh")
    segments = tmp_path / f"{recordings[0].name}.segments.json"
    data = json.loads(segments.read_text())
    data["sentences"][0]["segments"][-1]["end"] = 10**6
    segments.write_text(json.dumps(data))
    with pytest.raises(RecordingError, match="ends at frame 1000000, but the recording's last"):
        read_recording(path)
    (tmp_path / "x.txt").write_text("hello")
    with pytest.raises(RecordingError, match=r"a \.bvh or a \.pose file"):
        read_recording(tmp_path / "x.txt", segments)
    broken = tmp_path / "broken.bvh"
    broken.write_text("HIERARCHY\nROOT hips\n{")
    with pytest.raises(RecordingError, match=r"broken\.bvh"):
        read_recording(broken, segments)


def test_smoothing_kernel_and_splice_points():
    """App. A.1.1: the 5-tap kernel keeps a line; extrema splice (Eq. A.5), plateaus keep
    their ends (Eq. A.6) and crowded candidates merge."""
    line = np.arange(20.0)
    np.testing.assert_allclose(smooth(line)[2:-2], line[2:-2])
    assert SMOOTHING_KERNEL.sum() == pytest.approx(1.0, abs=1e-3)
    x = np.arange(80)
    wave = np.sin(2 * np.pi * x / 80)
    frames = splice_points(wave, min_gap=5)
    assert list(frames[[0, -1]]) == [0, 79]
    assert {20, 60} <= set(frames)
    plateau = np.concatenate([np.linspace(0, 1, 20), np.ones(20), np.linspace(1, 0, 20)])
    frames = splice_points(plateau, min_gap=3)
    assert {19, 40} <= set(frames)  # the plateau (value 1 from frame 19 to 40) keeps its ends


def test_hermite_segment_fit_finds_the_known_tangent_lengths():
    """Eq. A.8: a segment drawn with lengths k0, k1 on the grid is fitted back exactly."""
    from synthesis.transitions import hermite_points

    d0, d1 = np.array([1.0, 0.0]), np.array([1.0, 0.0])
    k = np.linspace(0, 5 * 30, TANGENT_STEPS)  # App. A.1.2's grid: 100 lengths
    assert TANGENT_STEPS == 100
    curve = hermite_points([0, 0], [30, 1], k[21] * d0, k[29] * d1, np.linspace(0, 1, 4001))
    x = np.arange(31.0)
    y = np.interp(x, curve[:, 0], curve[:, 1])
    t0, t1, rmse = fit_segment(x, y, d0, d1)
    assert rmse < 1e-3
    np.testing.assert_allclose([t0[0], t1[0]], [k[21], k[29]])


def test_hermite_fit_follows_a_noisy_curve():
    rng = np.random.default_rng(0)
    x = np.arange(70)
    y = 0.5 * np.sin(2 * np.pi * x / 70) + rng.normal(0, 0.005, 70)
    curve = fit_hermite(y)
    assert np.sqrt(np.mean((curve.evaluate(x) - y) ** 2)) < 0.015
    assert curve.points[0, 0] == 0 and curve.points[-1, 0] == 69


def test_fit_curve_normalizes_and_both_fits_follow(database):
    entry = database.entries[0]
    values = entry.values[:, 3]
    stored = fit_curve(values)
    assert stored.minimum_rad == pytest.approx(values.min())
    assert stored.delta_rad == pytest.approx(np.ptp(values))
    x = np.linspace(0, 1, len(values))
    back = stored.minimum_rad + stored.delta_rad * stored.spline(x)
    assert np.degrees(np.sqrt(np.mean((back - values) ** 2))) < 1.0
    back = stored.minimum_rad + stored.delta_rad * stored.hermite.evaluate(x)
    assert np.degrees(np.sqrt(np.mean((back - values) ** 2))) < 1.0


def test_database_file_round_trips_and_says_simulated(tmp_path, database):
    path = database.write(tmp_path / "db.json")
    data = json.loads(path.read_text())
    assert data["format"] == "signstudy.transition-database" and data["version"] == 1
    assert data["simulated"] is True and len(data["entries"][0]["descriptor"]) == 42
    back = TransitionDatabase.read(path)
    assert [e.id for e in back.entries] == [e.id for e in database.entries]
    first, again = database.entries[0], back.entries[0]
    np.testing.assert_allclose(again.descriptor, first.descriptor, atol=1e-6)
    x = np.linspace(0, 1, 9)
    assert isinstance(again.curves[0].spline, BSpline)
    np.testing.assert_allclose(again.curves[0].spline(x), first.curves[0].spline(x), atol=1e-5)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("{", "not JSON"),
        ('{"format": "other"}', "not a transition database"),
        ('{"format": "signstudy.transition-database", "version": 9}', "version 9"),
        (
            '{"format": "signstudy.transition-database", "version": 1, "entries": [{}]}',
            "entry 1 is malformed",
        ),
        (
            '{"format": "signstudy.transition-database", "version": 1, "entries": []}',
            "no transitions",
        ),
    ],
)
def test_bad_database_files_are_named(text, message):
    with pytest.raises(DatabaseError, match=message):
        TransitionDatabase.from_json(text, "db.json")


@pytest.mark.parametrize("weighting", ["raw", "zscore", "pca"])
def test_leave_one_out_never_returns_the_query(database, weighting):
    search = DescriptorSearch(database, weighting)
    for index, entry in enumerate(database.entries):
        assert search.nearest(entry.descriptor) == index  # itself, when allowed
        found = search.nearest(entry.descriptor, exclude={entry.id})
        assert database.entries[found].id != entry.id
    with pytest.raises(LookupError):
        search.nearest(entry.descriptor, exclude={e.id for e in database.entries})


def test_zscore_puts_every_column_on_one_scale(database):
    """§5.2.4: z-scored, the k = 0 columns no longer dominate the distance."""
    search = DescriptorSearch(database, "zscore")
    space = search.transform(database.descriptors())
    np.testing.assert_allclose(space.std(axis=0)[space.std(axis=0) > 0], 1.0)
    raw = database.descriptors()
    k0 = np.abs(raw.reshape(len(raw), 7, 2, 3)[..., 0]).mean()
    k2 = np.abs(raw.reshape(len(raw), 7, 2, 3)[..., 2]).mean()
    assert k0 > 10 * k2  # why the seed proposes it
    pca = DescriptorSearch(database, "pca")
    assert pca.transform(raw).shape[1] < 42


JSON_VALUES = st.recursive(
    st.none() | st.booleans() | st.integers() | st.floats(allow_nan=False) | st.text(max_size=4),
    lambda inner: (
        st.lists(inner, max_size=3) | st.dictionaries(st.text(max_size=3), inner, max_size=3)
    ),
    max_leaves=6,
)


@settings(
    max_examples=200, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)
@given(data=st.data())
def test_mangled_database_files_are_refused_never_crash(database, data):
    """Fuzz: any field of an entry replaced by any JSON value reads or raises DatabaseError."""
    document = json.loads(TransitionDatabase((database.entries[0],)).to_json())
    entry = document["entries"][0]
    path = [data.draw(st.sampled_from(sorted(entry)))]
    target = entry
    while isinstance(target[path[-1]], dict) and data.draw(st.booleans()):
        target = target[path[-1]]
        path.append(data.draw(st.sampled_from(sorted(target))))
    target[path[-1]] = data.draw(JSON_VALUES)
    text = json.dumps(document)
    cut = data.draw(st.integers(0, len(text)))
    text = text if data.draw(st.booleans()) else text[:cut]
    try:
        TransitionDatabase.from_json(text, "db.json")
    except DatabaseError as error:
        assert str(error).startswith("db.json: ")
