"""Run a parse or a conversion of an untrusted file confined, and bound what it costs.

The platform reads researchers' and participants' files (glTF/VRM avatars, FBX through
assimp, BVH, ``.pose``, videos through ffmpeg) only through here: in a child process
with an address-space, CPU-time and file-size limit, no network, only its input and the
code it runs readable (:mod:`studyplatform.confine.jail`), under a wall clock, with a
small environment that holds no key or database address. A hostile file costs at most
the limits and answers :class:`ConfinedError` naming what happened (issue 51: a cyclic
glTF hung a web worker and grew it to 1.7 GB; ffmpeg and assimp ran without limits).
"""

import contextlib
import json
import os
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

HERE = Path(__file__).resolve().parent
JAIL, WORKER = HERE / "jail.py", HERE / "worker.py"
ROOT = HERE.parents[1]
# What any confined program may read: the system's programs and libraries, the Python
# that runs the engine and the engine's code and data. Never the project's var/.
SYSTEM_READ = (
    "/usr",
    "/lib",
    "/lib32",
    "/lib64",
    "/bin",
    "/sbin",
    "/etc/ld.so.cache",
    "/etc/localtime",
    "/dev/null",
    "/dev/zero",
    "/dev/urandom",
)
ENVIRONMENT = (
    "PATH",
    "LANG",
    "LC_ALL",
    "OPENBLAS_CORETYPE",
    "OPENBLAS_L2_SIZE",
    "SIGNSTUDY_AVATAR_CACHE",
    "XDG_CACHE_HOME",
    "HOME",
    "PYOPENGL_PLATFORM",
)


class ConfinedError(Exception):
    """A confined run that failed: the file was refused, or it hit a limit."""


@dataclass(frozen=True)
class Limits:
    """What one confined run may cost."""

    memory_mb: int = 2048
    cpu_s: int = 60
    wall_s: float = 90.0
    file_mb: int = 1024
    output_mb: int = 256


PARSE = Limits()  # reading one avatar or motion file
MEDIA = Limits(memory_mb=3072, cpu_s=300, wall_s=330.0, file_mb=1024)  # ffmpeg on one video
# MediaPipe's capture of one recording's video, its fit and contact sheet (a job's).
CAPTURE = Limits(memory_mb=3072, cpu_s=1800, wall_s=1900.0, file_mb=1024)


def _python_paths() -> list[str]:
    interpreter = str(Path(sys.executable).resolve().parents[1])
    return sorted({sys.prefix, sys.base_prefix, sys.exec_prefix, interpreter})


def _engine_read() -> list[str]:
    from synthesis.diskcache import cache_directory

    paths = [str(ROOT / "synthesis"), str(HERE)]
    cache = cache_directory()
    if cache is not None and cache.is_dir():
        paths.append(str(cache))  # built avatars: read, never written, from here
    return paths


def _environment(scratch: str) -> dict[str, str]:
    kept = {name: os.environ[name] for name in ENVIRONMENT if name in os.environ}
    # One thread each: a confined parse is one of many, and OpenBLAS reserves memory
    # per thread against the address-space limit.
    return {
        **kept,
        "TMPDIR": scratch,
        "OPENBLAS_NUM_THREADS": "1",
        "OMP_NUM_THREADS": "1",
        "PYTHONDONTWRITEBYTECODE": "1",
    }


def confined_run(
    command: list[str],
    *,
    read=(),
    write=(),
    limits: Limits = PARSE,
    stdin: bytes | None = None,
    progress=None,
) -> subprocess.CompletedProcess:
    """Run *command* confined, reading only *read* (and the system's programs) and
    writing only *write*; return what it printed. Raise ConfinedError when it ran past
    the wall clock or its CPU time, or was killed. *progress*, if given, is told each
    new percentage the command writes to ``$TMPDIR/progress`` (polled every second)."""
    with tempfile.TemporaryDirectory(prefix="signstudy-confined-") as scratch:
        policy = {
            "memory_bytes": limits.memory_mb * 1024**2,
            "cpu_s": limits.cpu_s,
            "file_bytes": limits.file_mb * 1024**2,
            "read": [*SYSTEM_READ, *_python_paths(), *map(str, read)],
            "write": [scratch, "/dev/null", *map(str, write)],
        }
        jailed = [sys.executable, "-I", str(JAIL), json.dumps(policy), "--", *map(str, command)]
        process = subprocess.Popen(
            jailed,
            stdin=subprocess.PIPE if stdin is not None else subprocess.DEVNULL,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            env=_environment(scratch),
            start_new_session=True,
            cwd=scratch,
        )
        try:
            out, err = _wait(process, stdin, limits.wall_s, Path(scratch) / "progress", progress)
        finally:
            _kill(process)
    if process.returncode in (-signal.SIGXCPU, -signal.SIGKILL):
        raise ConfinedError(f"used more than {limits.cpu_s} s of processor time")
    if process.returncode < 0:
        raise ConfinedError(f"crashed ({signal.Signals(-process.returncode).name})")
    return subprocess.CompletedProcess(jailed, process.returncode, out, err)


def _wait(process: subprocess.Popen, stdin, wall_s: float, reported: Path, progress):
    """Return the process's output once it ends, telling *progress* what it reports;
    ConfinedError past *wall_s*."""
    deadline, last = time.monotonic() + wall_s, None
    while True:
        step = min(1.0, deadline - time.monotonic()) if progress else deadline - time.monotonic()
        try:
            return process.communicate(stdin, timeout=max(step, 0.01))
        except subprocess.TimeoutExpired:
            stdin = None  # written by the first call; a second call must not write again
            if time.monotonic() >= deadline:
                raise ConfinedError(f"took longer than {wall_s:.0f} s") from None
        text = reported.read_text().strip() if reported.is_file() else ""
        if text.isdigit() and text != last:
            last = text
            progress(int(text))


def _kill(process: subprocess.Popen) -> None:
    """End the process and anything it started (its own session)."""
    if process.poll() is None:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(process.pid, signal.SIGKILL)
        process.wait()


def run_task(
    task: str,
    data: bytes,
    name: str,
    argument: str = "",
    limits: Limits = PARSE,
    progress=None,
):
    """Return what the confined worker's *task* makes of *data* (a file called *name*);
    ConfinedError names what is wrong with it, or the limit it hit. *progress* is told
    the percentages the task reports."""
    command = [sys.executable, "-I", str(WORKER), task, name, argument]
    done = confined_run(command, read=_engine_read(), limits=limits, stdin=data, progress=progress)
    try:
        answer = json.loads(done.stdout[: limits.output_mb * 1024**2])
    except ValueError:
        # No answer: the interpreter could not start or died at the limit it hit.
        memory = b"MemoryError" in done.stderr or b"Cannot allocate" in done.stderr
        if memory:
            raise ConfinedError(
                f"{name} needs more than {limits.memory_mb} MB to be read"
            ) from None
        raise ConfinedError(f"{name} could not be read") from None
    if "rejected" in answer:
        raise ConfinedError(answer["rejected"])
    return answer["result"]


def confinement_status() -> dict:
    """Return what confinement this machine gives: the Landlock ABI (0: none, files are
    not restricted) and whether the jail may take a network namespace."""
    from studyplatform.confine.jail import landlock_abi

    # Landlock hides /proc/net, so ask the kernel for the interfaces: an empty
    # namespace has only the loopback device.
    code = "import socket; print(' '.join(name for _, name in socket.if_nameindex()))"
    done = confined_run([sys.executable, "-I", "-c", code])
    isolated = done.returncode == 0 and done.stdout.split() == [b"lo"]
    return {"landlock_abi": landlock_abi(), "network_namespace": isolated}
