"""Enforce the packages' dependency direction (docs/architecture.md).

synthesis and analysis import nothing of the project and never Django; stimuli may use
synthesis only; studyplatform may use everything.
"""

import ast
import re
import shutil
import subprocess
import sys
import tokenize
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


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _type_checking_nodes(tree: ast.AST) -> set[int]:
    """Return the ids of nodes inside ``if TYPE_CHECKING:`` blocks (never run)."""
    inside = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
            inside |= {id(child) for child in ast.walk(node)}
    return inside


def _imported(node: ast.AST, module: str, is_package: bool) -> list[str]:
    """Return the modules an import statement may load (a name may be a submodule)."""
    if isinstance(node, ast.Import):
        return [alias.name for alias in node.names]
    if not isinstance(node, ast.ImportFrom):
        return []
    base = node.module or ""
    if node.level:
        bits = module.split(".") if is_package else module.split(".")[:-1]
        bits = bits[: len(bits) - node.level + 1]
        base = ".".join([*bits, base] if base else bits)
    return [base, *(f"{base}.{alias.name}" for alias in node.names)]


def module_edges(package: str) -> dict[str, set[str]]:
    """Return, per module of *package*, the package's modules it imports, at the top or
    inside a function (both run), but not under ``TYPE_CHECKING``. Importing a module runs
    its enclosing packages' ``__init__`` first, so they count as imported too; a module's
    own enclosing packages are left out (a package's ``__init__`` re-exports its modules)."""
    paths = {
        _module_name(path): path
        for path in (ROOT / package).rglob("*.py")
        if "migrations" not in path.parts
    }
    edges: dict[str, set[str]] = {name: set() for name in paths}
    for name, path in paths.items():
        tree = ast.parse(path.read_text(encoding="utf-8"))
        skipped = _type_checking_nodes(tree)
        for node in ast.walk(tree):
            if id(node) in skipped:
                continue
            for target in _imported(node, name, path.name == "__init__.py"):
                bits = target.split(".")
                for loaded in (".".join(bits[:end]) for end in range(1, len(bits) + 1)):
                    own = loaded == name or name.startswith(loaded + ".")
                    if loaded in paths and not own:
                        edges[name].add(loaded)
    return edges


@pytest.mark.parametrize("package", ["synthesis", "stimuli", "analysis", "studyplatform"])
def test_no_two_modules_import_each_other_round_a_circle(package):
    """Issue 39: a circle held open only by imports inside functions is still a circle.
    studyplatform's floors (rules and questions ← models ← lib ← actions ← jobs, views,
    admin) keep it open: docs/architecture.md."""
    cycle = find_cycle(module_edges(package))
    assert not cycle, f"import circle in {package}: " + " → ".join(cycle)


def test_the_module_check_sees_a_planted_circle(tmp_path, monkeypatch):
    planted = tmp_path / "planted"
    planted.mkdir()
    (planted / "__init__.py").write_text("")
    (planted / "a.py").write_text("def f():\n    from planted import b\n")
    (planted / "b.py").write_text("from planted.a import f\n")
    (planted / "c.py").write_text(
        "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from planted import a\n"
    )
    monkeypatch.setattr(sys.modules[__name__], "ROOT", tmp_path)
    assert find_cycle(module_edges("planted")) == ["planted.a", "planted.b", "planted.a"]
    assert module_edges("planted")["planted.c"] == set()


def test_the_module_check_sees_a_circle_through_a_package_init(tmp_path, monkeypatch):
    """The shape issue 39 found in studyplatform: a model's method imports one module of
    a package whose ``__init__`` imports the models back."""
    planted = tmp_path / "planted"
    for folder in ("models", "lib"):
        (planted / folder).mkdir(parents=True)
    (planted / "__init__.py").write_text("")
    (planted / "models" / "__init__.py").write_text("from planted.models.study import Study\n")
    (planted / "models" / "study.py").write_text(
        "class Study:\n    def clean(self):\n        from planted.lib.rules import check\n"
    )
    (planted / "lib" / "__init__.py").write_text("from planted.lib.reads import read\n")
    (planted / "lib" / "reads.py").write_text("from planted.models import Study\n")
    (planted / "lib" / "rules.py").write_text("def check(study):\n    pass\n")
    monkeypatch.setattr(sys.modules[__name__], "ROOT", tmp_path)
    assert find_cycle(module_edges("planted")) == [
        "planted.lib",
        "planted.lib.reads",
        "planted.models",
        "planted.models.study",
        "planted.lib",
    ]


def test_the_module_check_fails_on_a_circle_planted_in_studyplatform(tmp_path, monkeypatch):
    """The studyplatform check itself, shown failing: a copy of the package with one
    import added that runs from the models back up to an action."""
    import shutil

    copy = tmp_path / "studyplatform"
    shutil.copytree(ROOT / "studyplatform", copy, ignore=shutil.ignore_patterns("migrations"))
    study = copy / "models" / "studies.py"
    study.write_text(
        study.read_text(encoding="utf-8")
        + "\n\ndef _planted():\n    from studyplatform.actions import do_save_response\n"
    )
    monkeypatch.setattr(sys.modules[__name__], "ROOT", tmp_path)
    cycle = find_cycle(module_edges("studyplatform"))
    assert "studyplatform.models.studies" in cycle and "studyplatform.actions" in cycle


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


def formatter_overrides(root: Path, packages=PROJECT_PACKAGES) -> list[str]:
    """Return where code keeps the formatter out (``fmt: skip``, ``fmt: off``)."""
    found = []
    for package in sorted(packages):
        for path in sorted((root / package).rglob("*.py")):
            with path.open("rb") as source:
                for token in tokenize.tokenize(source.readline):
                    if token.type == tokenize.COMMENT and re.match(
                        r"#\s*fmt:\s*(skip|off)", token.string
                    ):
                        found.append(f"{path.relative_to(root).as_posix()}:{token.start[0]}")
    return found


def test_the_formatter_owns_the_layout():
    """Issue 57: 542 ``# fmt: skip`` markers kept code hand-packed under line caps on
    modules and functions; the caps are gone (size is for review, complexity for ruff's
    C901, pyproject.toml) and ``ruff format`` lays out every line of the project."""
    assert formatter_overrides(ROOT, PROJECT_PACKAGES | {"tests", "bench", "scripts"}) == []


def test_the_formatter_check_sees_an_override(tmp_path):
    package = tmp_path / "synthesis"
    package.mkdir()
    (package / "packed.py").write_text('x = "# fmt: skip"  # fmt: skip\ny = 1\n')
    assert formatter_overrides(tmp_path, {"synthesis"}) == ["synthesis/packed.py:1"]


def test_the_import_contracts_hold_and_see_a_planted_breach(tmp_path):
    """import-linter's contracts (pyproject.toml) hold on the tree, and a model that
    imports an action (a floor upside down) breaks the platform's floors contract."""
    import tomllib

    linter = Path(sys.executable).with_name("lint-imports")
    result = subprocess.run([linter], cwd=ROOT, capture_output=True, text=True)
    assert result.returncode == 0, result.stdout[-3000:]
    config = tomllib.loads((ROOT / "pyproject.toml").read_text("utf-8"))["tool"]["importlinter"]
    (floors,) = [c for c in config["contracts"] if c.get("containers") == ["studyplatform"]]
    shutil.copytree(
        ROOT / "studyplatform",
        tmp_path / "studyplatform",
        ignore=shutil.ignore_patterns("__pycache__", "static", "templates"),
    )
    model = tmp_path / "studyplatform" / "models" / "design.py"
    model.write_text(model.read_text("utf-8") + "\nfrom studyplatform.actions import studies\n")
    (tmp_path / ".importlinter").write_text(
        "[importlinter]\nroot_package = studyplatform\n\n"
        "[importlinter:contract:floors]\nname = floors\ntype = layers\n"
        "containers = studyplatform\nlayers =\n"
        + "".join(f"    {layer}\n" for layer in floors["layers"]),
        "utf-8",
    )
    planted = subprocess.run(
        [linter],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        env={"PYTHONPATH": str(tmp_path), "PATH": "/usr/bin:/bin"},
    )
    assert planted.returncode == 1, planted.stdout[-3000:]
    assert "studyplatform.models.design -> studyplatform.actions.studies" in planted.stdout


def test_the_platform_root_holds_only_what_django_and_celery_find_by_name():
    """Issue 57: 26 root modules of studyplatform mixed five floors; each floor is a
    folder now (docs/architecture.md), and every folder is a floor of the contract."""
    import tomllib

    by_name = {
        "__init__",
        "apps",
        "asgi",
        "celery",
        "checks",
        "middleware",
        "settings",
        "signals",
        "tasks",
        "urls",
        "wsgi",
    }
    package = ROOT / "studyplatform"
    assert {path.stem for path in package.glob("*.py")} == by_name
    config = tomllib.loads((ROOT / "pyproject.toml").read_text("utf-8"))["tool"]["importlinter"]
    (floors,) = [c for c in config["contracts"] if c.get("containers") == ["studyplatform"]]
    named = {part.strip() for layer in floors["layers"] for part in layer.split("|")}
    folders = {
        path.name
        for path in package.iterdir()
        if (path / "__init__.py").exists() and path.name != "migrations"
    }
    assert folders <= named, folders - named
    assert by_name - {"__init__", "settings"} - named == set()
