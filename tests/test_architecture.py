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
