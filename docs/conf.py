"""Sphinx configuration of the crankdyn documentation site (``make docs``).

The user guide and theory pages are the Markdown files of this folder (myst-parser); the command
reference is generated from the click commands (sphinx-click), the API reference from the
docstrings (autosummary + autodoc + numpydoc), the validation page from tests/validation, and the
worked examples in examples/ are run at build time (the local extension _ext/crankdyn_sphinx.py).
The build must stay free of warnings: ``make docs`` runs it with ``-W --keep-going``.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

import matplotlib
from sphinx import addnodes
from sphinx.util import inspect as _sphinx_inspect

DOCS = Path(__file__).resolve().parent
sys.path.insert(0, str(DOCS / "_ext"))
matplotlib.use("Agg")

import crankdyn  # noqa: E402

project = "crankdyn"
author = "crankdyn developers"
copyright = "crankdyn developers"
release = version = crankdyn.__version__

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "numpydoc",
    "sphinx_click",
    "crankdyn_sphinx",
]

root_doc = "index"
source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
exclude_patterns = ["_build", "_templates", "_ext", "**/__pycache__"]
templates_path = ["_templates"]

# Markdown: "## Section" anchors for links such as [keys](engine-file.md#geometry)
myst_heading_anchors = 3
myst_enable_extensions = ["colon_fence"]

# API reference: one page per module (templates/autosummary/module.rst), members from __all__
autosummary_generate = True
autosummary_imported_members = False
autodoc_member_order = "bysource"
autodoc_typehints = "signature"
autodoc_preserve_defaults = True
# no type comments in this code base: skip re-tokenising every function's source for them
autodoc_use_type_comments = False
# array annotations as written (numpy.typing), not expanded into numpy's internal unions
autodoc_type_aliases = {
    "ArrayLike": "numpy.typing.ArrayLike",
    "NDArray": "numpy.typing.NDArray",
}


def _alias_name(alias) -> str:
    return alias.name


# Sphinx 9 writes an alias inside a union (``ArrayLike | None``) as its repr,
# "TypeAliasForwardRef('numpy.typing.ArrayLike')": show the alias's name instead.
if hasattr(_sphinx_inspect, "TypeAliasForwardRef"):
    _sphinx_inspect.TypeAliasForwardRef.__repr__ = _alias_name
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
# A signature whose annotations cannot all be evaluated (names imported only for type checking)
# keeps them as strings, and Sphinx then looks a short name such as "Table" up anywhere: two
# classes of that name make an ambiguity warning, whatever the link. Not a docs error.
suppress_warnings = ["ref.python"]
# straight quotes as typed: the docs quote keys, units and code, and the curly-quote pass
# (docutils SmartQuotes) was the largest single cost of the build on the API pages
smartquotes = False

# Docstrings are numpydoc (reStructuredText) read as plain text too: |x| is a magnitude there, not
# a substitution, and *args a star argument, not emphasis; both are escaped before rendering.
_PIPE = re.compile(r"(?<![\\|])\|(?!\|)")
_STAR = re.compile(r"(?<![\\`\w*])(\*\*?)(?=[A-Za-z_]\w*(?![\w*]))")


def _escape_plain_text_math(app, what, name, obj, options, lines):
    literal = False
    for i, line in enumerate(lines):
        stripped = line.strip()
        if literal and stripped and not line.startswith((" ", "\t")):
            literal = False
        if literal or stripped.startswith(("| ", "+-", "+=", ">>>", "...")) or stripped == "|":
            pass
        else:
            parts = line.split("``")
            parts[::2] = [_STAR.sub(r"\\\1", _PIPE.sub(r"\\|", p)) for p in parts[::2]]
            lines[i] = "``".join(parts)
        if stripped.endswith("::"):
            literal = True


def _skip_foreign_members(app, what, name, obj, skip, options):
    """A crankdyn class derived from a library's (plots.style.Figure from matplotlib's) lists
    its own members only: matplotlib gives every Artist subclass a generated ``set`` whose
    docstring uses matplotlib's own Sphinx roles."""
    module = getattr(obj, "__module__", None) or ""
    if what == "class" and callable(obj) and module and not module.startswith("crankdyn"):
        return True
    return None


_RST_SPECIAL = re.compile(r"([\\`*_|])")
_MEMORY_UNIT = {"deg": "rad", "rpm": "rad/s"}  # held in SI, exported in deg and rpm


def _rst_text(text: str) -> str:
    return _RST_SPECIAL.sub(r"\\\1", text)


def _no_unit(field) -> str:
    """'dimensionless' for a number without a unit, a dash for text, flags and sub-results."""
    numeric = any(t in str(field.type) for t in ("float", "ndarray", "NDArray", "int"))
    return "dimensionless" if numeric else "—"


def _result_fields(app, what, name, obj, options, lines):
    """A result class's exported fields (crankdyn.results.column/array/scalar: label, unit, JSON
    key) as a table under its docstring, so that the API reference gives the unit of every
    number a result holds."""
    import dataclasses

    if what != "class" or not dataclasses.is_dataclass(obj):
        return
    rows = [f for f in dataclasses.fields(obj) if "label" in f.metadata]
    if not rows:
        return
    lines += [
        "",
        ".. rubric:: Fields",
        "",
        "Held in SI (angles in rad, speeds in rad/s); exported under the key shown, in its unit.",
        "",
        ".. list-table::",
        "   :header-rows: 1",
        "",
        "   * - Field",
        "     - Quantity",
        "     - Unit",
        "     - Export key (unit)",
    ]
    for f in rows:
        meta = f.metadata
        unit = meta["unit"]
        kind = {"column": "column", "array": "array"}.get(meta["kind"], "")
        lines += [
            f"   * - ``{f.name}``",
            f"     - {_rst_text(meta['label'])}" + (f" ({kind})" if kind else ""),
            f"     - {_rst_text(_MEMORY_UNIT.get(unit, unit) or _no_unit(f))}",
            f"     - ``{meta['key']}``" + (f" ({_rst_text(unit)})" if unit else ""),
        ]


def _hide_module_toctree(app, doctree):
    """Mark autosummary's toctree of the API's per-module pages hidden (see the sidebar below)."""
    from sphinx.ext.autosummary import autosummary_toc

    for table in doctree.findall(autosummary_toc):
        for toctree in table.findall(addnodes.toctree):
            toctree["hidden"] = True


def _sidebar_without_module_pages(app, pagename, templatename, context, doctree):
    """Leave the API's per-module pages out of the sidebar.

    The theme draws the sidebar from the whole site's toctree on every page, so its cost grows
    with the square of the page count; with the 200-odd module pages in it, it was the larger
    half of the build (and a sidebar of 250 entries). The sidebar links "API reference", whose
    table links every module page.
    """
    toctree = context.get("toctree")
    if toctree is None:
        return

    def visible_toctree(**kwargs):
        kwargs["includehidden"] = False
        return toctree(**kwargs)

    context["toctree"] = visible_toctree


def setup(app):
    # before the theme's own handler (priority 500), which draws the sidebar from "toctree"
    app.connect("doctree-read", _hide_module_toctree, priority=400)
    app.connect("html-page-context", _sidebar_without_module_pages, priority=400)
    app.connect("autodoc-process-docstring", _escape_plain_text_math, priority=900)
    app.connect("autodoc-skip-member", _skip_foreign_members)
    app.connect("autodoc-process-docstring", _result_fields, priority=950)


# worked examples (crankdyn_sphinx): run at build time unless -D crankdyn_run_examples=0
crankdyn_run_examples = True

html_theme = "furo"
html_title = f"crankdyn {release}"
html_short_title = "crankdyn"
html_static_path: list[str] = []
html_copy_source = False
html_show_sourcelink = False
