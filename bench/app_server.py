"""Start, kill and restart the application server (gunicorn, as `make demo` runs it).

The load benchmark and the fault test serve the study through the same server a
deployment uses, on a free loopback port, and kill it (SIGKILL, the whole process group:
master and workers, as a crash or an out-of-memory kill would) in the middle of saves.
"""

import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def free_port() -> int:
    """Return a TCP port on 127.0.0.1 that nothing listens on now."""
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


class AppServer:
    """gunicorn serving ``studyplatform.wsgi`` with deploy/gunicorn.conf.py."""

    def __init__(
        self, env: dict[str, str], workers: int = 2, threads: int = 8, port: int | None = None
    ):
        self.port = port or free_port()
        self.env = {
            **env,
            "SIGNSTUDY_WORKERS": str(workers),
            "SIGNSTUDY_THREADS": str(threads),
            "SIGNSTUDY_LOG_LEVEL": "warning",
        }
        self.process: subprocess.Popen | None = None

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    def start(self, timeout_s: float = 30.0) -> None:
        """Start the server and wait until it accepts connections."""
        command = [
            sys.executable,
            "-m",
            "gunicorn",
            "-c",
            str(ROOT / "deploy/gunicorn.conf.py"),
            "--bind",
            f"127.0.0.1:{self.port}",
            "studyplatform.wsgi",
        ]
        self.process = subprocess.Popen(command, cwd=ROOT, env=self.env, start_new_session=True)
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            if self.process.poll() is not None:
                raise RuntimeError(f"gunicorn exited with {self.process.returncode}")
            try:
                with socket.create_connection(("127.0.0.1", self.port), timeout=0.5):
                    return
            except OSError:
                time.sleep(0.1)
        raise RuntimeError(f"gunicorn did not listen on port {self.port} in {timeout_s:g} s")

    def kill(self) -> None:
        """Kill the master and every worker at once (SIGKILL), as a crash would."""
        if self.process is not None and self.process.poll() is None:
            os.killpg(self.process.pid, signal.SIGKILL)
            self.process.wait()

    def kill_worker(self) -> int:
        """Kill one worker (SIGKILL) and leave the master to replace it; return its pid."""
        children = Path(f"/proc/{self.process.pid}/task/{self.process.pid}/children")
        workers = [int(pid) for pid in children.read_text().split()]
        if not workers:
            raise RuntimeError("gunicorn has no worker to kill")
        os.kill(workers[0], signal.SIGKILL)
        return workers[0]

    def stop(self) -> None:
        """Stop the server gracefully (SIGTERM), or kill it if it does not stop."""
        if self.process is None or self.process.poll() is not None:
            return
        os.killpg(self.process.pid, signal.SIGTERM)
        try:
            self.process.wait(timeout=30)
        except subprocess.TimeoutExpired:
            self.kill()
