"""Hostile glTF files are refused naming the problem, quickly and with bounded memory.

Issue 51's findings replayed on the engine's readers (tests/hostile.py makes each from a
good humanoid GLB or VRM 1.0): a parent cycle hung the avatar reader forever and grew
the motion reader to 1.7 GB; a 200,000-node chain did not finish in 40 s; the rest raised
AttributeError, ValueError, IndexError, KeyError or MemoryError. Each must now raise
GltfError within 5 s and 200 MB of Python allocations; and Hypothesis's damaged files
never raise anything else.
"""

import contextlib
import time
import tracemalloc

import pytest
from hypothesis import HealthCheck, given, settings

from synthesis.avatar.imported.gltf_avatar import read_gltf_avatar
from synthesis.avatar.imported.gltf_read import GltfError
from synthesis.avatar.imported.motion import read_gltf_motion
from tests.hostile import GLTF_CASES, damaged_glb, long_chain, with_animation
from tests.synthesis.humanoids import humanoid_glb

GOOD = humanoid_glb()
GOOD_VRM = humanoid_glb(vrm=True, morphs=("eyeBlinkLeft",), expressions={"blink": 0})
READERS = {"avatar": read_gltf_avatar, "motion": read_gltf_motion}


def _bounded(reader, data: bytes) -> str:
    """Return the GltfError message of reading *data*, checking time and memory."""
    tracemalloc.start()
    started = time.perf_counter()
    try:
        with pytest.raises(GltfError) as error:
            reader(data, "hostile.glb")
    finally:
        _, peak = tracemalloc.get_traced_memory()
        tracemalloc.stop()
    assert time.perf_counter() - started < 5.0
    assert peak < 200 * 1024**2
    return str(error.value)


def test_the_good_files_read():
    assert read_gltf_avatar(GOOD).joint_names
    assert read_gltf_avatar(GOOD_VRM).humanoid
    assert read_gltf_motion(with_animation(GOOD, [0.0, 1.0])).n_frames > 1


PAIRS = [(case, reader) for case in sorted(GLTF_CASES) for reader in GLTF_CASES[case][2]]


@pytest.mark.parametrize(("case", "reader"), PAIRS)
def test_each_finding_is_refused_naming_it(case, reader):
    make, vrm, _ = GLTF_CASES[case]
    data = make(GOOD_VRM if vrm else GOOD)
    if reader == "motion" and "animation" not in case:
        data = with_animation(data, [0.0, 0.5, 1.0], node=0)
    message = _bounded(READERS[reader], data)
    assert "hostile.glb" in message or "VRM" in message, message


@pytest.mark.parametrize(
    ("case", "words"),
    [
        ("parent cycle", "own ancestor"),
        ("node with two parents", "two parents"),
        ("200,000-node chain", "nodes, over the"),
        ("accessor of 10^15 elements without a buffer view", "claims"),
        ("sparse indices out of range", "sparse indices"),
        ("sparse componentType 9999", "sparse indices have an unknown type"),
        ("VRM humanoid as a list", "humanoid is not an object"),
        ("VRM bone entry as a string", "bone hips is not an object"),
        ("VRM expression weight 'abc'", "weight is not a number"),
    ],
)
def test_the_message_says_what_is_wrong(case, words):
    make, vrm, _ = GLTF_CASES[case]
    assert words in _bounded(read_gltf_avatar, make(GOOD_VRM if vrm else GOOD))


def test_a_long_chain_under_the_cap_reads_in_linear_time():
    """9,000 nodes in one chain (the cap is 10,000): read, not refused, in under 8 s of CPU
    (3.0 and 3.9 s here) and about 9 times 1,000 nodes' time, not 81 times (quadratic).
    CPU time, not the wall clock: a CI run on a busy machine failed at 5.5 s of wall time
    against a 5 s budget."""
    short, long = (long_chain(with_animation(GOOD, [0.0, 1.0]), n) for n in (1_000, 9_000))
    for name, reader in READERS.items():
        seconds = []
        for data in (short, long):
            started = time.process_time()
            reader(data, "chain.glb")
            seconds.append(time.process_time() - started)
        assert seconds[1] < 8.0, (name, seconds)
        assert seconds[1] < 30 * max(seconds[0], 0.01), (name, seconds)


def test_keys_spanning_too_long_are_refused_before_sampling():
    message = _bounded(read_gltf_motion, GLTF_CASES["animation keys from 0 to 10^12 s"][0](GOOD))
    assert "lasts" in message and "600 s" in message


QUICK = settings(
    max_examples=60,
    deadline=None,
    derandomize=True,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)


@QUICK
@given(data=damaged_glb(with_animation(GOOD_VRM, [0.0, 0.5, 1.0])))
def test_damaged_files_raise_only_gltf_errors(data):
    for reader in READERS.values():
        with contextlib.suppress(GltfError):
            reader(data, "damaged.glb")
