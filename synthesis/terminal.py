"""Report a long job's progress on the terminal (the command lines' shared helper)."""

import sys


def frame_progress(label: str):
    """Return a progress callback: one updating line on a terminal, else every tenth."""
    interactive = sys.stderr.isatty()

    def report(done: int, total: int) -> None:
        if interactive:
            end = "\n" if done == total else ""
            print(f"\r{label}: frame {done}/{total}", end=end, file=sys.stderr, flush=True)
        elif done == total or done % max(1, total // 10) == 0:
            print(f"{label}: frame {done}/{total}", file=sys.stderr, flush=True)

    return report
