"""Report a long job's progress on the terminal (the command lines' shared helper)."""

import sys


def frame_progress(label: str, every: int = 50):
    """Return a progress callback: one updating line on a terminal, else every tenth.

    Called without a *total* (a video's frame count is not known ahead), it says the
    frames done every *every* frames.
    """
    interactive = sys.stderr.isatty()

    def report(done: int, total: int | None = None) -> None:
        if total is None:
            if done % every == 0:
                print(f"{label}: frame {done}", file=sys.stderr, flush=True)
        elif interactive:
            end = "\n" if done == total else ""
            print(f"\r{label}: frame {done}/{total}", end=end, file=sys.stderr, flush=True)
        elif done == total or done % max(1, total // 10) == 0:
            print(f"{label}: frame {done}/{total}", file=sys.stderr, flush=True)

    return report
