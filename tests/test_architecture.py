"""Enforce the packages' dependency direction (docs/architecture.md).

synthesis and analysis import nothing of the project and never Django; stimuli may use
synthesis only; studyplatform may use everything.
"""

import ast
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PROJECT_PACKAGES = {"synthesis", "stimuli", "studyplatform", "analysis"}
FORBIDDEN = {
    "synthesis": {"django", "celery", "stimuli", "studyplatform", "analysis"},
    "analysis": {"django", "celery", "synthesis", "stimuli", "studyplatform"},
    "stimuli": {"django", "studyplatform", "analysis"},
}


def imported_top_levels(path: Path) -> set[str]:
    """Return the top-level names of every module *path* imports, at any depth."""
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    names = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names.update(alias.name.split(".")[0] for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            names.add(node.module.split(".")[0])
    return names


@pytest.mark.parametrize("package", sorted(FORBIDDEN))
def test_package_imports_only_what_it_may(package):
    offences = []
    for path in sorted((ROOT / package).rglob("*.py")):
        bad = imported_top_levels(path) & FORBIDDEN[package]
        if bad:
            offences.append(f"{path.relative_to(ROOT)} imports {', '.join(sorted(bad))}")
    assert not offences, "\n".join(offences)


def test_the_check_sees_a_forbidden_import(tmp_path):
    module = tmp_path / "bad.py"
    module.write_text("def f():\n    from django.db import models\n    import studyplatform.x\n")
    assert imported_top_levels(module) == {"django", "studyplatform"}


def test_importing_the_pure_packages_loads_no_django():
    code = (
        "import sys, synthesis, analysis, stimuli\n"
        "loaded = sorted(m for m in sys.modules if m.split('.')[0] in "
        "{'django', 'studyplatform', 'celery'})\n"
        "print(','.join(loaded))\n"
    )
    result = subprocess.run(
        [sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, check=True
    )
    assert result.stdout.strip() == ""


def _synthesis_edges() -> dict[str, set[str]]:
    """Return, per subpackage of synthesis, the other subpackages its modules import."""
    package = ROOT / "synthesis"
    subpackages = {p.name for p in package.iterdir() if (p / "__init__.py").exists()}
    edges: dict[str, set[str]] = {name: set() for name in subpackages}
    for path in package.rglob("*.py"):
        parts = path.relative_to(package).parts
        if len(parts) < 2:
            continue  # top-level modules (cli, identity, the package's API) sit above all
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            names = []
            if isinstance(node, ast.Import):
                names = [alias.name for alias in node.names]
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                names = [node.module]
            for name in names:
                bits = name.split(".")
                inside = bits[0] == "synthesis" and len(bits) > 1 and bits[1] in subpackages
                if inside and bits[1] != parts[0]:
                    edges[parts[0]].add(bits[1])
    return edges


def find_cycle(edges: dict[str, set[str]]) -> list[str]:
    """Return one cycle of the graph *edges* as a path (first node repeated), or []."""
    state: dict[str, int] = {}
    path: list[str] = []

    def visit(node: str) -> list[str]:
        state[node] = 1
        path.append(node)
        for target in sorted(edges.get(node, ())):
            if state.get(target) == 1:
                return [*path[path.index(target) :], target]
            if target not in state and (cycle := visit(target)):
                return cycle
        state[node] = 2
        path.pop()
        return []

    for node in sorted(edges):
        if node not in state and (cycle := visit(node)):
            return cycle
    return []


def test_the_engine_subpackages_import_each_other_without_a_cycle():
    cycle = find_cycle(_synthesis_edges())
    assert not cycle, "import cycle between synthesis subpackages: " + " → ".join(cycle)


def test_the_cycle_check_sees_a_cycle():
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b"}, "b": set()}) == []


def test_no_module_is_longer_than_about_400_lines():
    long = []
    for package in sorted(PROJECT_PACKAGES):
        for path in sorted((ROOT / package).rglob("*.py")):
            if "migrations" in path.parts:
                continue
            lines = len(path.read_text(encoding="utf-8").splitlines())
            if lines > 400:
                long.append(f"{path.relative_to(ROOT)}: {lines} lines")
    assert not long, "split these modules:\n" + "\n".join(long)
