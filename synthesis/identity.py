"""The engine's identity: a digest of the source and data files a clip's pixels come from.

Every clip's hash includes :func:`engine_digest`, so a change to any file that makes a
clip — the techniques and everything they import, the renderer, the alphabet, routes,
sign library, shaders — names every clip anew instead of reusing a cached one rendered
by other code. Files a clip cannot come from (command lines, reports, evaluations of
the seeds' tables, exports, the stimulus check) are left out: a fix there must not
re-render a study's clips or lock an open study's (issue 57). Which modules count is
read from the code itself, the imports of :data:`CLIP_ENTRIES` followed through the
package (:func:`clip_modules`), so a new module is counted by being used. A hand-set
version number could be forgotten; the imports cannot. A module counts by its syntax
tree, docstrings and type hints left out: reformatting it, or editing its comments,
docstrings or types, cannot change a pixel and leaves every clip valid.

:func:`code_digest` covers every file of the engine: the disk cache of built avatars and
databases, and the stimulus check kept beside each clip, are keyed by it.
"""

import ast
import hashlib
from functools import cache
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent
IGNORED_DIRECTORIES = {"__pycache__"}
IGNORED_SUFFIXES = {".pyc", ".pyo"}
# What rendering a clip imports (stimuli.clips: ClipRequest, build_motion, film, render).
CLIP_ENTRIES = ("synthesis.techniques", "synthesis.techniques.request", "synthesis.render")


def engine_files(root: Path = PACKAGE) -> list[Path]:
    """Return every file of the engine under *root*, in a fixed order."""
    return sorted(
        path
        for path in root.rglob("*")
        if path.is_file()
        and path.suffix not in IGNORED_SUFFIXES
        and not IGNORED_DIRECTORIES & set(path.relative_to(root).parts)
    )


def clip_files(root: Path = PACKAGE) -> list[Path]:
    """Return the files a clip can come from: every data file (YAML, JSON, shaders) and
    the modules :func:`clip_modules` finds, in a fixed order."""
    modules = clip_modules(root)
    return [p for p in engine_files(root) if p.suffix != ".py" or p in modules]


def clip_modules(root: Path = PACKAGE) -> set[Path]:
    """Return the engine's modules that :data:`CLIP_ENTRIES` import, directly or through
    others, at the top of a module or inside a function (each package's ``__init__``
    with its modules)."""
    seen: set[Path] = set()
    todo = list(CLIP_ENTRIES)
    while todo:
        name = todo.pop()
        parts = name.split(".")
        for depth in range(1, len(parts) + 1):
            path = _module_file(root, parts[:depth])
            if path is not None and path not in seen:
                seen.add(path)
                todo += _imported(path)
    return seen


def _module_file(root: Path, parts: list[str]) -> Path | None:
    """Return the file of module *parts* (``["synthesis", "render"]``) under *root*."""
    if parts[0] != root.name:
        return None
    base = root.joinpath(*parts[1:])
    for path in (base.with_suffix(".py"), base / "__init__.py"):
        if path.is_file():
            return path
    return None


def _imported(path: Path) -> tuple[str, ...]:
    """Return every module name a file imports at run time (``from a import b`` names a
    and a.b); imports a type checker alone reads (``if TYPE_CHECKING:``) are not."""
    return _module_facts(path)[0]


def _code_sha256(path: Path) -> bytes:
    """Return the SHA-256 of what of a file can change a result: a module's syntax tree
    without its docstrings and type hints (its layout, comments, prose and types cannot),
    any other file's bytes."""
    if path.suffix != ".py":
        return hashlib.sha256(path.read_bytes()).digest()
    return _module_facts(path)[1]


def _module_facts(path: Path) -> tuple[tuple[str, ...], bytes]:
    """Return a module's run-time imports and code digest, from one parse per version of
    the file: the imports and the digest both need its tree, and parsing the engine
    twice was most of a server's first study page (issue 57). Only the facts are kept,
    not the trees (tens of megabytes in every process)."""
    stat = path.stat()
    return _parsed_facts(path, stat.st_mtime_ns, stat.st_size)


@cache
def _parsed_facts(path: Path, mtime_ns: int, size: int) -> tuple[tuple[str, ...], bytes]:
    tree = ast.parse(path.read_text("utf-8"))
    for node in ast.walk(tree):
        body = getattr(node, "body", None)
        if (
            isinstance(node, ast.Module | ast.ClassDef | ast.FunctionDef | ast.AsyncFunctionDef)
            and body
            and isinstance(body[0], ast.Expr)
            and isinstance(body[0].value, ast.Constant)
            and isinstance(body[0].value.value, str)
        ):
            node.body = body[1:] or [ast.Pass()]
    tree = _WithoutTypes().visit(tree)
    names: list[str] = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names += [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            names += [node.module, *(f"{node.module}.{alias.name}" for alias in node.names)]
    return tuple(names), hashlib.sha256(ast.dump(tree).encode()).digest()


class _WithoutTypes(ast.NodeTransformer):
    """Drop what only a type checker reads: annotations of arguments and returns, the
    types of annotated names, ``if TYPE_CHECKING:`` blocks and imports from ``typing``
    and ``__future__`` (names used at run time are counted where they are used).

    A dataclass field's annotation stays a field; only a ``ClassVar`` or ``InitVar``,
    which change what a dataclass is, keep their annotation.
    """

    def visit_arg(self, node: ast.arg) -> ast.arg:
        node.annotation = None
        return node

    def visit_FunctionDef(self, node):
        node.returns = None
        return self.generic_visit(node)

    visit_AsyncFunctionDef = visit_FunctionDef

    def visit_AnnAssign(self, node: ast.AnnAssign) -> ast.AnnAssign:
        if not {"ClassVar", "InitVar"} & _names(node.annotation):
            node.annotation = ast.Name("_", ast.Load())
        return node

    def visit_If(self, node: ast.If):
        if "TYPE_CHECKING" in _names(node.test):
            return node.orelse or None
        return self.generic_visit(node)

    def visit_ImportFrom(self, node: ast.ImportFrom):
        return None if node.module in ("typing", "__future__") else node


def _names(node: ast.AST) -> set[str]:
    return {
        n.id if isinstance(n, ast.Name) else n.attr
        for n in ast.walk(node)
        if isinstance(n, ast.Name | ast.Attribute)
    }


def _digest(root: Path, files: list[Path]) -> str:
    digest = hashlib.sha256()
    for path in files:
        digest.update(path.relative_to(root).as_posix().encode() + b"\0")
        digest.update(_code_sha256(path))
    return digest.hexdigest()[:16]


@cache
def engine_digest(root: Path = PACKAGE) -> str:
    """Return the first 16 hex digits of the SHA-256 over the path and code (:func:`_code_sha256`)
    of every file a clip can come from (:func:`clip_files`)."""
    return _digest(root, clip_files(root))


@cache
def code_digest(root: Path = PACKAGE) -> str:
    """Return the first 16 hex digits of the SHA-256 over every engine file's path and code."""
    return _digest(root, engine_files(root))


def file_sha256(path: str | Path) -> str:
    """Return the SHA-256 of a file's bytes, read a megabyte at a time."""
    digest = hashlib.sha256()
    with open(path, "rb") as handle:
        for block in iter(lambda: handle.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()
