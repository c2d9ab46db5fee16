"""Render a clip's frames in several processes, handed back in order.

Mesa's llvmpipe spends part of every frame in serial work, so on a 2-core machine two
single-threaded renderers give about 1.7 times the frames of one two-threaded renderer
(bench/bench_render.py). Worker k renders frames k, k + n, k + 2n, …; the caller reads
them round-robin through small bounded queues, so memory stays flat on long clips.
Processes are spawned, never forked: an OpenGL context does not survive a fork.
"""

import multiprocessing
import os
from collections.abc import Iterator
from queue import Empty

import numpy as np

from synthesis.avatar.model import Avatar
from synthesis.render.renderer import Progress, Renderer
from synthesis.render.scene import CameraPath, CameraPreset
from synthesis.skeleton.kinematics import Pose

QUEUE_FRAMES = 6
# Below this many frames a second process costs more to start than it saves.
MIN_FRAMES_PER_WORKER = 24


def default_workers() -> int:
    """Return how many render processes suit this machine: one per core, at most four."""
    return max(1, min(4, os.cpu_count() or 1))


def _every(motion, start: int, step: int):
    if isinstance(motion, Pose):
        return Pose(motion.quaternions[start::step], motion.positions_m[start::step])
    return motion[start::step]


def _share(camera, start: int, step: int):
    """Return a worker's camera: a path's frames start, start + step, …; or the camera."""
    return camera.every(start, step) if isinstance(camera, CameraPath) else camera


def _work(avatar, camera, motion, width, height, queue) -> None:
    # One rasteriser thread each: the processes, not Mesa's threads, share the cores.
    os.environ["LP_NUM_THREADS"] = "1"
    try:
        with Renderer(avatar, camera, width, height) as renderer:
            for frame in renderer.frames(motion):
                queue.put(frame)
    except Exception as error:  # handed to the parent, which raises it
        queue.put(RuntimeError(f"render worker failed: {error!r}"))
    queue.put(None)


def _next(queue, process):
    """Return the next item from a worker, or raise if the worker died without one."""
    while True:
        try:
            return queue.get(timeout=1.0)
        except Empty:
            if not process.is_alive():
                raise RuntimeError(
                    f"A render worker exited with code {process.exitcode} before its frames "
                    "were done."
                ) from None


def render_frames(
    avatar: Avatar,
    camera: CameraPreset | CameraPath,
    motion: np.ndarray | Pose,
    width: int = 640,
    height: int = 480,
    workers: int | None = 1,
    progress: Progress | None = None,
) -> Iterator[np.ndarray]:
    """Yield the frames of *motion* in order, rendered by *workers* processes.

    One process is the default: more need a main module that can be imported again
    (spawn) and cannot start inside a daemon process such as a Celery prefork worker.
    """
    if not isinstance(motion, Pose):
        motion = np.atleast_2d(motion)
    total = motion.quaternions.shape[0] if isinstance(motion, Pose) else len(motion)
    workers = max(1, min(workers or 1, total // MIN_FRAMES_PER_WORKER))
    if workers == 1:
        with Renderer(avatar, camera, width, height) as renderer:
            yield from renderer.frames(motion, progress)
        return
    context = multiprocessing.get_context("spawn")
    queues = [context.Queue(maxsize=QUEUE_FRAMES) for _ in range(workers)]
    processes = [
        context.Process(
            target=_work,
            args=(
                avatar,
                _share(camera, k, workers),
                _every(motion, k, workers),
                width,
                height,
                queues[k],
            ),
            daemon=True,
        )
        for k in range(workers)
    ]
    for process in processes:
        process.start()
    try:
        for number in range(total):
            item = _next(queues[number % workers], processes[number % workers])
            if isinstance(item, Exception):
                raise item
            if item is None:
                raise RuntimeError("A render worker stopped early.")
            yield item
            if progress is not None:
                progress(number + 1, total)
    finally:
        for process in processes:
            if process.is_alive():
                process.terminate()
            process.join()
        for queue in queues:
            queue.close()
