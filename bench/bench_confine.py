"""Time what confinement costs and what a hostile file costs confined (issue 51).

    .venv/bin/python bench/bench_confine.py

Prints, with the machine line: the confined jail's own start (a command that does
nothing); a good avatar's report and a good glTF motion read in process and confined
(the price of a child process that imports the engine); each of issue 51's hostile
glTFs read confined (target: refused within 5 s) with the largest resident size the
child reached; and a 3 GB allocation stopped at the 2 GB limit. Asserts nothing.
"""

import resource
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import machine

from studyplatform.confine import ConfinedError, Limits, confined_run, run_task
from tests.hostile import GLTF_CASES, with_animation
from tests.synthesis.humanoids import humanoid_glb


def children_peak_mb() -> float:
    return resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024


def timed(function, *args) -> tuple[float, object]:
    started = time.perf_counter()
    try:
        result = function(*args)
    except ConfinedError as error:
        result = error
    return time.perf_counter() - started, result


def main() -> None:
    print(machine.describe())
    good = humanoid_glb()
    vrm = humanoid_glb(vrm=True, morphs=("eyeBlinkLeft",), expressions={"blink": 0})
    animated = with_animation(good, [0.0, 0.5, 1.0])
    seconds, _ = timed(confined_run, ["/bin/true"])
    print(f"jail start, /bin/true: {1000 * seconds:.0f} ms")

    from synthesis.avatar.imported.gltf_avatar import read_gltf_avatar
    from synthesis.avatar.imported.motion import read_gltf_motion

    read_gltf_avatar(good)  # imports warmed
    seconds, _ = timed(read_gltf_avatar, good)
    confined_s, _ = timed(run_task, "avatar", good, "good.glb")
    print(
        f"good avatar: read in process {1000 * seconds:.0f} ms; report confined "
        f"(read, mapped, described) {1000 * confined_s:.0f} ms"
    )
    seconds, _ = timed(read_gltf_motion, animated)
    confined_s, _ = timed(run_task, "motion", animated, "good.glb", ".glb")
    print(
        f"good glTF motion: in process {1000 * seconds:.0f} ms; confined {1000 * confined_s:.0f} ms"
    )
    for case, (make, needs_vrm, readers) in sorted(GLTF_CASES.items()):
        data = make(vrm if needs_vrm else animated)
        task, argument = ("avatar", "") if "avatar" in readers else ("motion", ".glb")
        seconds, result = timed(run_task, task, data, "hostile.glb", argument)
        verdict = "refused" if isinstance(result, ConfinedError) else "ACCEPTED"
        print(f"  {case:52s} {len(data) / 1024:8.0f} KB  {verdict} in {seconds:5.2f} s")
    print(f"largest child resident size so far: {children_peak_mb():.0f} MB")
    code = "b = bytearray(3 * 1024**3)"
    command = [sys.executable, "-c", code]
    seconds, result = timed(lambda: confined_run(command, limits=Limits(memory_mb=2048)))
    stopped = isinstance(result, ConfinedError) or b"MemoryError" in result.stderr
    verdict = "stopped" if stopped else "NOT STOPPED"
    print(f"3 GB allocation under a 2 GB limit: {verdict} in {seconds:.2f} s")


if __name__ == "__main__":
    main()
