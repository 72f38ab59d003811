"""The layering of DESIGN.md, enforced on the source (docs/developing.md, "Layers").

- the numeric core and the domain never import the boundary (io, cli, report, the study
  runner), pint, click or rich;
- plots/ and io/ import no boundary code above them (cli, report, the study runner);
- no domain module imports an analysis;
- the import graph is acyclic, leaving out only the documented lazy imports: the alternate
  constructors ``from_file``/``example`` (and the package's ``examples``/``example`` and lazy
  attributes) import the file readers on demand, the openTorsion converters
  ``from_opentorsion``/``to_opentorsion`` import :mod:`crankdyn.torsion.opentorsion` (and, in
  it, the optional openTorsion), and ``plot`` methods import ``crankdyn.plots``;
- no module imports another module's private helper (a name starting with ``_``);
- no module over 1,500 lines, no function over 150;
- user text is never markup or mathtext: every rich console comes from
  ``crankdyn.cli.common.console()`` (markup off), nothing imports ``rich.markup``, and every
  figure is a ``crankdyn.plots.style.Figure`` (no pyplot, no bare matplotlib ``Figure``).
"""

from __future__ import annotations

import ast
import functools
from pathlib import Path

import crankdyn

PACKAGE = Path(crankdyn.__file__).parent
BOUNDARY = ("crankdyn.io", "crankdyn.cli", "crankdyn.report", "crankdyn.study.run")
THIRD_PARTY_BOUNDARY = ("pint", "click", "rich")
LAZY_CONSTRUCTORS = {
    "from_file",
    "example",
    "examples",
    "__getattr__",
    "from_opentorsion",
    "to_opentorsion",
}
"""Functions whose imports of the file readers (and of the openTorsion converters) are
documented as lazy."""

DOMAIN = {
    "crankdyn.errors",
    "crankdyn.constants",
    "crankdyn.results",
    "crankdyn.display",
    "crankdyn.plausibility",
    "crankdyn.crank.geometry",
    "crankdyn.crank.masses",
    "crankdyn.crank.pressure",
    "crankdyn.engine.model",
    "crankdyn.linkage.elements",
    "crankdyn.torsion.elements",
    "crankdyn.torsion.excitation_spec",
    "crankdyn.torsion.model",
    "crankdyn.torsion.topology",
    "crankdyn.crankshaft.geometry",
    "crankdyn.crankshaft.beam_inputs",
}
"""The domain objects and what every layer shares (errors, units, the result mixin)."""

ANALYSES = {
    "crankdyn.crank.kinematics",
    "crankdyn.crank.indicated",
    "crankdyn.engine.forces",
    "crankdyn.engine.bearings",
    "crankdyn.engine.torque",
    "crankdyn.engine.balance",
    "crankdyn.engine.flywheel",
    "crankdyn.engine.firing_search",
    "crankdyn.session",
    "crankdyn.torsion.modal",
    "crankdyn.torsion.mode_blocks",
    "crankdyn.torsion.nodes",
    "crankdyn.torsion.response",
    "crankdyn.torsion.solvers",
    "crankdyn.torsion.sweep",
    "crankdyn.torsion.campbell",
    "crankdyn.torsion.excitation",
    "crankdyn.torsion.harmonics",
    "crankdyn.torsion.rules",
    "crankdyn.torsion.transient",
    "crankdyn.torsion.dampers",
    "crankdyn.linkage.kinetostatics",
    "crankdyn.linkage.friction",
    "crankdyn.crankshaft.m53",
    "crankdyn.crankshaft.loads",
    "crankdyn.crankshaft.strength",
    "crankdyn.crankshaft.span_torques",
    "crankdyn.crankshaft.beam_engine",
    "crankdyn.crankshaft.beam_model",
    "crankdyn.crankshaft.beam_modes",
    "crankdyn.crankshaft.beam_response",
    "crankdyn.crankshaft.beam_stiffness",
}


def _modules() -> dict[str, Path]:
    out = {}
    for path in PACKAGE.rglob("*.py"):
        parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
        name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
        out[name] = path
    return out


MODULES = _modules()


def _resolve(name: str) -> str | None:
    """The crankdyn module an imported name belongs to (a package's attribute: the package)."""
    while name and name not in MODULES:
        name = name.rpartition(".")[0]
    return name or None


@functools.cache
def _tree(path: Path) -> ast.Module:
    """A module's syntax tree, parsed once per test process (the checks below share it)."""
    return ast.parse(path.read_text(encoding="utf-8"))


@functools.cache
def _imports(path: Path):
    """(imported module, enclosing function or None, the names imported) of every import,
    leaving out ``if TYPE_CHECKING:`` blocks."""
    tree = _tree(path)
    found = []

    def visit(node, function):
        for child in ast.iter_child_nodes(node):
            if (
                isinstance(child, ast.If)
                and isinstance(child.test, ast.Name)
                and child.test.id == "TYPE_CHECKING"
            ):
                continue
            inner = function
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef)):
                inner = child.name
            if isinstance(child, ast.Import):
                for alias in child.names:
                    found.append((alias.name, inner, ()))
            elif isinstance(child, ast.ImportFrom) and child.module and child.level == 0:
                names = tuple(a.name for a in child.names)
                found.append((child.module, inner, names))
                for n in names:  # ``from crankdyn.study import run`` imports a module
                    if f"{child.module}.{n}" in MODULES:
                        found.append((f"{child.module}.{n}", inner, ()))
            visit(child, inner)

    visit(tree, None)
    return found


def _lazy(module: str, function: str | None, target: str) -> bool:
    """A documented lazy import: a file reader from an alternate constructor, or a plot."""
    if function is None:
        return False
    if function in LAZY_CONSTRUCTORS:
        return True
    return function.startswith("plot") and target.startswith("crankdyn.plots")


@functools.cache
def _graph() -> dict[str, set[str]]:
    graph: dict[str, set[str]] = {m: set() for m in MODULES}
    for module, path in MODULES.items():
        for imported, function, _names in _imports(path):
            if not imported.startswith("crankdyn"):
                continue
            target = _resolve(imported)
            if target is None or target == module or _lazy(module, function, target):
                continue
            graph[module].add(target)
    return graph


def _is_boundary(module: str) -> bool:
    return module.startswith(BOUNDARY) or module == "crankdyn.__main__"


def test_core_and_domain_do_not_import_the_boundary():
    offenders = []
    for module, path in MODULES.items():
        if _is_boundary(module):
            continue
        for imported, function, _names in _imports(path):
            if not imported.startswith(BOUNDARY + THIRD_PARTY_BOUNDARY):
                continue
            if function in LAZY_CONSTRUCTORS:
                continue
            offenders.append(f"{module} ({function or 'top'}): {imported}")
    assert not offenders, offenders


def test_plots_and_io_import_no_boundary_above_them():
    above = ("crankdyn.cli", "crankdyn.report", "crankdyn.study.run")
    offenders = [
        f"{module}: {imported}"
        for module, path in MODULES.items()
        if module.startswith(("crankdyn.plots", "crankdyn.io"))
        for imported, _function, _names in _imports(path)
        if imported.startswith(above)
    ]
    assert not offenders, offenders


def test_no_domain_module_imports_an_analysis():
    graph = _graph()
    offenders = [
        f"{module}: {target}" for module in DOMAIN for target in graph[module] if target in ANALYSES
    ]
    assert not offenders, offenders


def test_the_import_graph_is_acyclic():
    graph = _graph()
    state: dict[str, int] = {}
    cycles = []

    def visit(node, stack):
        state[node] = 1
        stack.append(node)
        for nxt in sorted(graph[node]):
            if state.get(nxt) == 1:
                cycles.append([*stack[stack.index(nxt) :], nxt])
            elif nxt not in state:
                visit(nxt, stack)
        stack.pop()
        state[node] = 2

    for node in sorted(graph):
        if node not in state:
            visit(node, [])
    assert not cycles, [" -> ".join(c) for c in cycles]


def test_private_helpers_are_not_imported_across_modules():
    offenders = [
        f"{module}: {imported}.{name}"
        for module, path in MODULES.items()
        for imported, _function, names in _imports(path)
        if imported.startswith("crankdyn")
        for name in names
        if name.startswith("_") and not name.startswith("__")
    ]
    assert not offenders, offenders


def test_the_architecture_sets_name_real_modules():
    assert set(MODULES) >= DOMAIN and set(MODULES) >= ANALYSES
    graph = _graph()  # the scan sees the imports it judges
    assert "crankdyn.engine.model" in graph["crankdyn.engine.forces"]
    assert "crankdyn.session" in graph["crankdyn.report.sections"]


def _calls(path: Path):
    for node in ast.walk(_tree(path)):
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


MAX_MODULE_LINES = 1500
MAX_FUNCTION_LINES = 150


def test_modules_and_functions_stay_small():
    """No source module over 1,500 lines and no function over 150 (docstrings included): a
    long function that is a list of checks becomes a table of check objects (issue 31)."""
    too_long = []
    for path in sorted(PACKAGE.rglob("*.py")):
        text = path.read_text(encoding="utf-8")
        name = path.relative_to(PACKAGE).as_posix()
        if text.count("\n") > MAX_MODULE_LINES:
            too_long.append(f"{name}: {text.count(chr(10))} lines")
        for node in ast.walk(_tree(path)):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                length = (node.end_lineno or node.lineno) - node.lineno + 1
                if length > MAX_FUNCTION_LINES:
                    too_long.append(f"{name}: {node.name} {length} lines")
    assert not too_long, too_long
