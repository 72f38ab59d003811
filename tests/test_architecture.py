"""The layering of DESIGN.md: the numeric core and domain never import the boundary or pint."""

from __future__ import annotations

import ast
from pathlib import Path

import crankdyn

PACKAGE = Path(crankdyn.__file__).parent
BOUNDARY = ("crankdyn.io", "crankdyn.cli", "crankdyn.report", "pint", "click", "rich")
ALLOWED_LAZY = {"from_file", "example"}  # documented alternate constructors import io lazily


def _imports(path: Path):
    tree = ast.parse(path.read_text(encoding="utf-8"))
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield node, alias.name
        elif isinstance(node, ast.ImportFrom) and node.module:
            yield node, node.module


def _enclosing_function(tree, target):
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            for child in ast.walk(node):
                if child is target:
                    return node.name
    return None


def test_core_and_domain_do_not_import_the_boundary():
    # study/ runs variants of files on process pools and writes tables and reports: boundary
    boundary_dirs = {"io", "cli", "report", "study"}
    offenders = []
    for path in PACKAGE.rglob("*.py"):
        rel = path.relative_to(PACKAGE)
        if rel.parts[0] in boundary_dirs or rel.name == "__main__.py":
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node, module in _imports(path):
            if module.startswith(BOUNDARY):
                where = None
                for n in ast.walk(tree):
                    if isinstance(n, type(node)) and ast.dump(n) == ast.dump(node):
                        where = _enclosing_function(tree, n)
                        break
                if where not in ALLOWED_LAZY:
                    offenders.append(f"{rel}: {module}")
    assert not offenders, offenders


def _calls(path: Path):
    tree = ast.parse(path.read_text(encoding="utf-8"))
    for node in ast.walk(tree):
        if isinstance(node, ast.Call):
            func = node.func
            name = func.attr if isinstance(func, ast.Attribute) else getattr(func, "id", None)
            yield node.lineno, name


def test_user_text_is_never_markup_or_mathtext():
    """Issue 17: every rich console is made by crankdyn.cli.common.console() (markup off), so
    no module builds its own Console or escapes markup; every figure is a plots.style.Figure
    (mathtext off for words), so no module builds a matplotlib Figure or uses pyplot."""
    offenders = []
    for path in PACKAGE.rglob("*.py"):
        rel = path.relative_to(PACKAGE).as_posix()
        text = path.read_text(encoding="utf-8")
        if "rich.markup" in text:
            offenders.append(f"{rel}: imports rich.markup (markup is off: print text as is)")
        if "pyplot" in text and rel != "plots/__init__.py":
            offenders.append(f"{rel}: uses pyplot")
        for line, name in _calls(path):
            if name == "Console" and rel != "cli/common.py":
                offenders.append(f"{rel}:{line}: Console(...): use crankdyn.cli.common.console()")
            if name == "Figure" and "from matplotlib.figure import Figure" in text:
                offenders.append(f"{rel}:{line}: matplotlib Figure: use crankdyn.plots.style")
    assert not offenders, offenders
