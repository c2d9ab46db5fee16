"""Run the commands docs/reproducing.md documents, once each, for scripts/docs_figures.py.

Each runs in-process (its ``main``) in one temporary directory at its documented size;
the functions return the CSV rows the command wrote, which the figure blocks read.
"""

import atexit
import contextlib
import csv
import importlib
import io
import shutil
import tempfile
from functools import cache
from pathlib import Path

LETTERS = "ABCDEFGHIJKLMNOPQRSTUVWXYZ"
WORK = Path(tempfile.mkdtemp(prefix="docs-figures-"))
atexit.register(shutil.rmtree, WORK, True)


def run(module: str, *argv: str) -> str:
    """Run ``python -m module argv…`` in-process in the work directory; return its output.

    Each command-line package's ``__main__`` calls its ``cli.main``; so does this.
    """
    main = importlib.import_module(f"{module}.cli").main
    out = io.StringIO()
    with contextlib.chdir(WORK), contextlib.redirect_stdout(out):
        status = main(list(argv))
    if status != 0:
        raise RuntimeError(f"python -m {module} {' '.join(argv)} failed:\n{out.getvalue()}")
    return out.getvalue()


def rows(path: str) -> list[dict[str, str]]:
    """Return a CSV the commands wrote, relative to the work directory."""
    with open(WORK / path, newline="", encoding="utf-8") as handle:
        return list(csv.DictReader(handle))


# --- the commands, each run once -------------------------------------------------------


@cache
def transitions(holdout: str) -> str:
    """Run docs/reproducing.md's seed 001 commands on the default simulated database."""
    if not (WORK / "simulated.json").exists():
        run(
            "synthesis.transitions",
            "simulate",
            "--signers",
            "4",
            "--sentences",
            "6",
            "--out",
            "simulated/",
        )
        recordings = sorted(str(p.relative_to(WORK)) for p in (WORK / "simulated").glob("*.bvh"))
        run("synthesis.transitions", "build", *recordings, "--out", "simulated.json")
    out = f"table-5-1-{holdout}"
    run("synthesis.transitions", "evaluate", "simulated.json", "--holdout", holdout, "--out", out)
    return out


@cache
def reduction(which: str) -> list[dict[str, str]]:
    """Return ``steps.csv`` of ``hands reduce`` on the engine's ELEPHANT or the human letters."""
    words = ("--spell", "ELEPHANT") if which == "engine" else ("--human-letters", LETTERS)
    run("synthesis.hands", "reduce", *words, "--report", f"reduction-{which}/")
    return rows(f"reduction-{which}/steps.csv")


@cache
def reconstruction(method: str, variance: float = 1.0) -> dict[int, dict[str, str]]:
    """Return ``errors-by-markers.csv`` of ``hands reconstruct --spell HEAVEN``, by m."""
    out = f"heaven-{method}-{variance}"
    extra = ("--lwr-variance", str(variance)) if method == "lwr" else ()
    run(
        "synthesis.hands",
        "reconstruct",
        "--spell",
        "HEAVEN",
        "--method",
        method,
        *extra,
        "--report",
        out,
    )
    return {int(r["markers"]): r for r in rows(f"{out}/errors-by-markers.csv")}


@cache
def table_3_1() -> list[dict[str, str]]:
    """Return ``table-3-1.csv`` of ``hands markers --configuration both``."""
    run("synthesis.hands", "markers", "--configuration", "both", "--out", "table-3-1-ours/")
    return rows("table-3-1-ours/table-3-1.csv")


@cache
def leave_one_out_rows() -> list[dict[str, str]]:
    """Return ``leave-one-out.csv`` of ``timing evaluate`` (with the Constant model's error)."""
    run("synthesis.timing", "evaluate", "--out", "leave-one-out/")
    return rows("leave-one-out/leave-one-out.csv")


@cache
def curve_rows() -> list[dict[str, str]]:
    """Return ``curves.csv`` of ``timing curves`` (Figs 4.4–4.6)."""
    run("synthesis.timing", "curves", "--out", "fig-4-4/")
    return rows("fig-4-4/curves.csv")


def six_marker_rows() -> list[dict[str, str]]:
    """Return ``six-markers.csv``, which ``hands markers --configuration both`` writes too."""
    table_3_1()
    return rows("table-3-1-ours/six-markers.csv")
