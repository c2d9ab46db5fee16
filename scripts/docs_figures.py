"""Write the figures docs/*.md quote from the project's own runs, or check that they hold.

    .venv/bin/python scripts/docs_figures.py           # rewrite every figure block
    .venv/bin/python scripts/docs_figures.py --check   # exit 1 naming each block that drifted

A figure block in the docs is the text between ``<!-- figures NAME -->`` and
``<!-- /figures -->`` (a table, a sentence or a single number). Each is written here
from what the documented commands print and write (``python -m synthesis.transitions
evaluate``, ``python -m synthesis.hands markers``, …, run in a temporary directory at
their documented sizes) or, where the docs quote a property of the engine rather than
a command's output, from the function the docs name. A change to the engine that moves
a figure changes the docs in the same commit; ``tests/test_docs_figures.py`` fails
until it does. Bench timings (machine-dependent) are not figure blocks.
"""

import argparse
import os
import platform
import re
import sys
from collections.abc import Callable
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import docs_figure_blocks as b
import docs_registry_tables as registry

# The runs behind some figures (LWR reconstruction, the GPLVM) amplify last-bit
# differences, and numpy's SIMD kernels and OpenBLAS's kernels are chosen per CPU: the
# same code gave 0.768 cm on an AVX-512 machine and 0.777 cm on an AVX2 one. With the
# kernels pinned (numpy's baseline, OpenBLAS's Haswell), every x86-64 machine computes
# the same figures; main() runs the script again, pinned, before it computes. The disk
# cache names results by their kernels too (synthesis.diskcache.kernels_digest), so the
# pinned run never loads what an unpinned test or bench cached.
PINNED = {
    "NPY_DISABLE_CPU_FEATURES": "X86_V3 X86_V4 AVX512_ICL AVX512_SPR",
    "OPENBLAS_CORETYPE": "Haswell",
}

ROOT = Path(__file__).resolve().parent.parent
DOCS = ("docs/transitions.md", "docs/hands.md", "docs/reproducing.md", "docs/architecture.md")
BLOCK = re.compile(r"<!-- figures (\S+) -->(.*?)<!-- /figures -->", re.S)


BLOCKS: dict[str, Callable[[], str]] = {
    "transitions-table-5-1": b.transitions_table,
    "transitions-winner": b.transitions_winner,
    "transitions-shares": b.transitions_shares,
    "transitions-searches": b.transitions_searches,
    "transitions-search-signers": b.transitions_search_signers,
    "hands-reduce-engine": b.hands_reduce_engine,
    "hands-reduce-human": b.hands_reduce_human,
    "hands-lwr-variance": b.hands_lwr_variance,
    "hands-heaven": b.hands_heaven,
    "hands-pose-database": b.hands_pose_database,
    "hands-table-3-1-engine": lambda: b.table_3_1_grid("engine"),
    "hands-table-3-1-ratio": b.table_3_1_ratio,
    "hands-exhaustive-m3": b.exhaustive_m3,
    "hands-table-3-1-gestures": lambda: b.table_3_1_grid("gestures"),
    "hands-table-3-1-sets": b.table_3_1_sets,
    "hands-table-3-1-letters": lambda: b.table_3_1_grid("letters"),
    "reproducing-seed-002": b.reduction_table,
    "reproducing-table-3-1": b.reproducing_table_3_1,
    "reproducing-leave-one-out": b.leave_one_out,
    "reproducing-letter-distances": b.letter_distances,
    "reproducing-spine": b.spine_table,
    "reproducing-six-markers": b.six_markers,
    "reproducing-constant": b.constant_errors,
    "reproducing-curves": b.learning_curves,
    "architecture-techniques": registry.techniques_table,
    "architecture-questions": registry.questions_table,
}
# Blocks written from a registry, not a run: quick enough for every test run.
REGISTRY_BLOCKS = ("architecture-techniques", "architecture-questions")


def blocks_in(text: str) -> dict[str, str]:
    """Return each figure block of a doc's *text* by name, as written."""
    return {match.group(1): match.group(2) for match in BLOCK.finditer(text)}


def rewrite(text: str, figures: dict[str, str]) -> str:
    """Return *text* with every figure block replaced by its figure."""
    return BLOCK.sub(
        lambda m: f"<!-- figures {m.group(1)} -->{figures[m.group(1)]}<!-- /figures -->", text
    )


def compute(names) -> dict[str, str]:
    """Return the figure of every block in *names*."""
    return {name: BLOCKS[name]() for name in names}


def _pin_kernels() -> None:
    """Run this script again with :data:`PINNED` set, unless it is (x86-64 only)."""
    if platform.machine() not in ("x86_64", "AMD64"):
        return
    if any(os.environ.get(name) != value for name, value in PINNED.items()):
        os.execve(sys.executable, [sys.executable, *sys.argv], {**os.environ, **PINNED})


def main() -> int:
    _pin_kernels()
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="change nothing; exit 1 on drift")
    args = parser.parse_args()
    texts = {doc: (ROOT / doc).read_text("utf-8") for doc in DOCS}
    written = {doc: blocks_in(text) for doc, text in texts.items()}
    figures = compute([name for found in written.values() for name in found])
    drifted = [
        (doc, n) for doc, found in written.items() for n, v in found.items() if figures[n] != v
    ]
    for doc, name in drifted:
        print(f"{doc}: {name} drifted:\n  docs: {written[doc][name]!r}\n  now:  {figures[name]!r}")
    if args.check:
        return 1 if drifted else 0
    for doc, text in texts.items():
        (ROOT / doc).write_text(rewrite(text, figures), "utf-8")
    print(f"rewrote {len(drifted)} of {len(figures)} figure blocks")
    return 0


if __name__ == "__main__":
    sys.exit(main())
