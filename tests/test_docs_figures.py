"""Check that every figure the docs quote from the project's own runs is what the runs give.

``scripts/docs_figures.py`` runs the documented commands (docs/reproducing.md) at their
documented sizes and writes each figure block of docs/transitions.md, docs/hands.md and
docs/reproducing.md; this test runs the same computation and fails, naming the block,
when a change to the engine moved a figure without the docs (issue 53, item 2). The
published figures beside ours come from the seeds, through the same commands.
"""

import importlib.util
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _script():
    spec = importlib.util.spec_from_file_location(
        "docs_figures", ROOT / "scripts" / "docs_figures.py"
    )
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def script():
    return _script()


@pytest.fixture(scope="module")
def written(script) -> dict[str, dict[str, str]]:
    return {doc: script.blocks_in((ROOT / doc).read_text("utf-8")) for doc in script.DOCS}


def test_every_block_has_a_figure_and_every_figure_a_block(script, written):
    names = [name for found in written.values() for name in found]
    assert len(names) == len(set(names)), "a figure block appears twice"
    assert set(names) == set(script.BLOCKS)
    for doc, found in written.items():
        for name, text in found.items():
            assert text.strip() and text.strip() != "X", f"{doc}: {name} was never written"


def test_the_registry_tables_are_the_registries(script, written):
    """docs/architecture.md's tables of techniques and question types are written from
    the registries (issue 57: the hand-kept table lacked the avatar technique)."""
    found = written["docs/architecture.md"]
    for name, figure in script.compute(script.REGISTRY_BLOCKS).items():
        assert found[name] == figure, f"{name}: run .venv/bin/python scripts/docs_figures.py"
    assert "| `avatar` |" in found["architecture-techniques"]
    assert "| `slider` |" in found["architecture-questions"]


def test_the_docs_figures_are_what_the_commands_give_now():
    """The whole computation (about two minutes), run as the script runs it: with the CPU
    kernels pinned (scripts/docs_figures.py's PINNED), so a new machine is no drift. A
    drifted figure is named with both values."""
    run = subprocess.run(
        [sys.executable, str(ROOT / "scripts" / "docs_figures.py"), "--check"],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert run.returncode == 0, (
        "run .venv/bin/python scripts/docs_figures.py; " + run.stdout[-6000:] + run.stderr[-3000:]
    )


def test_a_changed_figure_is_found_and_rewritten(script):
    text = (
        "a <!-- figures n -->6.01<!-- /figures --> b\n"
        "<!-- figures t -->\n| 1 |\n<!-- /figures -->\n"
    )
    assert script.blocks_in(text) == {"n": "6.01", "t": "\n| 1 |\n"}
    rewritten = script.rewrite(text, {"n": "6.04", "t": "\n| 2 |\n"})
    assert script.blocks_in(rewritten) == {"n": "6.04", "t": "\n| 2 |\n"}
    assert rewritten.startswith("a <!-- figures n -->6.04<!-- /figures --> b\n")
