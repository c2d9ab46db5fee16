"""The confined runner: what a parser of an untrusted file may reach and spend (issue 51).

Each test runs a real child through studyplatform.confine's jail and checks one wall:
no server file, no network (PostgreSQL answers on 127.0.0.1:5432 here), no key in its
environment, memory and time bounded, and the engine's readers refusing issue 51's
hostile glTFs from inside it.
"""

import socket
import sys
import time

import pytest

from studyplatform.confine import ConfinedError, Limits, confined_run, confinement_status, run_task
from studyplatform.confine.ffmpeg import run_ffmpeg
from studyplatform.confine.jail import landlock_abi
from tests.hostile import GLTF_CASES, with_animation
from tests.synthesis.humanoids import humanoid_glb

PYTHON = [sys.executable, "-I", "-c"]
needs_landlock = pytest.mark.skipif(
    landlock_abi() == 0, reason="THIS KERNEL HAS NO LANDLOCK: file confinement untested here"
)


def _python(code: str, **options):
    return confined_run([*PYTHON, code], **options)


@needs_landlock
def test_a_confined_program_reads_only_what_it_is_given(tmp_path):
    secret, given = tmp_path / "secret_key", tmp_path / "given.txt"
    secret.write_text("the key")
    given.write_text("the input")
    code = (
        "import sys\n"
        "for path in sys.argv[1:]:\n"
        "    try:\n"
        "        print(path, open(path).read())\n"
        "    except OSError as error:\n"
        "        print(path, type(error).__name__)\n"
    )
    paths = [str(secret), str(given), "/proc/self/environ", "/etc/passwd"]
    done = confined_run([*PYTHON, code, *paths], read=[given])
    lines = done.stdout.decode().splitlines()
    assert lines == [
        f"{secret} PermissionError",
        f"{given} the input",
        "/proc/self/environ PermissionError",
        "/etc/passwd PermissionError",
    ]


def test_a_confined_program_reaches_no_network():
    with socket.create_connection(("127.0.0.1", 5432), timeout=5):
        pass  # the database answers here, outside
    code = (
        "import socket\n"
        "try:\n"
        "    socket.create_connection(('127.0.0.1', 5432), timeout=3)\n"
        "    print('connected')\n"
        "except OSError as error:\n"
        "    print(type(error).__name__)\n"
    )
    assert _python(code).stdout.decode().strip() != "connected"
    assert confinement_status()["network_namespace"]


def test_its_environment_holds_no_key_or_database(monkeypatch):
    monkeypatch.setenv("SIGNSTUDY_SECRET_KEY", "k3y")
    monkeypatch.setenv("DATABASE_URL", "postgres://postgres@127.0.0.1/x")
    done = _python("import os; print(sorted(os.environ))")
    names = done.stdout.decode()
    assert "SIGNSTUDY_SECRET_KEY" not in names and "DATABASE_URL" not in names


def test_memory_is_bounded():
    code = "b = bytearray(3 * 1024**3)\nprint('allocated')"
    done = _python(code, limits=Limits(memory_mb=512, wall_s=30))
    assert b"allocated" not in done.stdout and b"MemoryError" in done.stderr


def test_time_is_bounded():
    started = time.monotonic()
    with pytest.raises(ConfinedError, match="took longer than 2 s"):
        _python("while True: pass", limits=Limits(cpu_s=60, wall_s=2))
    assert time.monotonic() - started < 10
    with pytest.raises(ConfinedError, match="processor time"):
        _python("while True: pass", limits=Limits(cpu_s=1, wall_s=30))


@pytest.mark.parametrize("case", sorted(c for c, v in GLTF_CASES.items() if "avatar" in v[2]))
def test_the_avatar_reader_refuses_each_finding_from_inside(case):
    make, vrm, _ = GLTF_CASES[case]
    good = humanoid_glb(
        vrm=vrm, morphs=("eyeBlinkLeft",) if vrm else (), expressions={"blink": 0} if vrm else None
    )
    started = time.monotonic()
    with pytest.raises(ConfinedError):
        run_task("avatar", make(good), "hostile.glb")
    assert time.monotonic() - started < 5


def test_the_motion_reader_refuses_keys_too_long_and_reads_a_good_one():
    good = with_animation(humanoid_glb(), [0.0, 0.5, 1.0])
    assert run_task("motion", good, "good.glb", ".glb")["bvh"].startswith("HIERARCHY")
    hostile = GLTF_CASES["animation keys from 0 to 10^12 s"][0](humanoid_glb())
    with pytest.raises(ConfinedError, match="lasts"):
        run_task("motion", hostile, "hostile.glb", ".glb")


def test_ffmpeg_opens_no_url_a_playlist_names(tmp_path):
    """An HLS playlist (as a researcher could upload it renamed .mp4) naming a URL and a
    server file: ffmpeg, confined and limited to local protocols, reads neither."""
    secret = tmp_path / "secret_key"
    secret.write_text("the key")
    playlist = tmp_path / "clip.m3u8"
    playlist.write_text(
        "#EXTM3U\n#EXT-X-TARGETDURATION:1\n#EXTINF:1,\nhttp://127.0.0.1:5432/x.ts\n"
        f"#EXTINF:1,\nfile://{secret}\n#EXT-X-ENDLIST\n"
    )
    done = run_ffmpeg("-v", "error", "-i", str(playlist), "-f", "null", "-", read=[playlist])
    assert done is None or done.returncode != 0


def test_progress_a_confined_program_reports_reaches_the_caller():
    """A capture reports its percentage through $TMPDIR/progress, polled each second."""
    code = (
        "import os, pathlib, time\n"
        "for percent in (10, 60):\n"
        "    pathlib.Path(os.environ['TMPDIR'], 'progress').write_text(str(percent))\n"
        "    time.sleep(1.3)\n"
    )
    seen = []
    _python(code, progress=seen.append)
    assert seen == [10, 60]
