"""Local Sphinx extension of the crankdyn site: the worked-example gallery and the validation list.

``crankdyn-gallery``
    In ``examples/index.md``: every ``*.py`` beside the page, each as a section with the
    script's docstring, its code, and (unless ``-D crankdyn_run_examples=0``) what it printed
    and the figures it wrote, from a run at build time. The scripts run in parallel
    subprocesses, each with a temporary output folder as its argument (the scripts take
    ``OUTDIR`` as ``sys.argv[1]``); figures are embedded in the page, nothing is written into
    the source tree. A script that fails is a build warning (an error under ``-W``).

``crankdyn-validation``
    In ``reference/validation.md``: every module of ``tests/validation`` (the tests named after
    published sources), with its docstring (the source and the tolerances) and its tests.

Two savings in the build of the API reference, neither changing a page: numpydoc's docstring
template compiled once per builder, not once per docstring (:func:`_numpydoc_template`), and
the Python domain's search for a name it does not know (every ``float`` or ``int`` in a
signature: a scan of every object's full name) answered from an index of the names' last
parts (:class:`PythonDomain`).
"""

from __future__ import annotations

import ast
import base64
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

from docutils import nodes
from docutils.statemachine import StringList
from sphinx.domains.python import PythonDomain as _SphinxPythonDomain
from sphinx.util import logging
from sphinx.util.docutils import SphinxDirective

LOG = logging.getLogger(__name__)
REPOSITORY = Path(__file__).resolve().parents[2]
EXAMPLE_TIMEOUT_S = 600


def _blocks(text: str) -> list[list[str]]:
    blocks: list[list[str]] = [[]]
    for line in text.splitlines():
        if line.strip():
            blocks[-1].append(line.strip())
        elif blocks[-1]:
            blocks.append([])
    return [b for b in blocks if b]


def plain_nodes(text: str) -> list[nodes.Node]:
    """Paragraphs and "- " bullet lists of a plain-text docstring, with no markup parsed."""
    out: list[nodes.Node] = []
    for block in _blocks(text):
        items: list[str] = []
        lead: list[str] = []
        for line in block:
            if line.startswith("- "):
                items.append(line[2:])
            elif items:
                items[-1] += " " + line
            else:
                lead.append(line)
        if lead:
            out.append(nodes.paragraph(text=" ".join(lead)))
        if items:
            out.append(
                nodes.bullet_list(
                    "", *(nodes.list_item("", nodes.paragraph(text=i)) for i in items)
                )
            )
    return out


def _title_and_body(doc: str, fallback: str) -> tuple[str, str]:
    blocks = _blocks(doc)
    if not blocks:
        return fallback, ""
    first = " ".join(blocks[0])
    first = re.sub(r"\s*\(run: [^)]*\)", "", first)
    head, sep, rest = first.partition(": ")
    if not sep:
        head, sep, rest = first.partition(". ")
    title = head.rstrip(".")
    rest = rest.strip()
    body = "\n\n".join([rest[:1].upper() + rest[1:], *("\n".join(b) for b in blocks[1:])])
    return title, body.strip()


def _without_docstring(source: str, tree: ast.Module) -> str:
    """The script's code after its module docstring (shown as text above it)."""
    if ast.get_docstring(tree) is None:
        return source
    return "\n".join(source.splitlines()[tree.body[0].end_lineno :]).strip("\n") + "\n"


def _section(document, title: str, ident: str) -> nodes.section:
    section = nodes.section(ids=[nodes.make_id(ident)])
    section += nodes.title(text=title)
    document.note_implicit_target(section)
    return section


class GalleryDirective(SphinxDirective):
    """The worked examples beside the page, run at build time."""

    has_content = False

    def run(self) -> list[nodes.Node]:
        folder = Path(self.env.doc2path(self.env.docname)).parent
        scripts = sorted(folder.glob("*.py"), key=lambda p: (p.stem != "quickstart", p.stem))
        for script in scripts:
            self.env.note_dependency(str(script))
        runs = self._run_all(scripts) if self.config.crankdyn_run_examples else {}
        sections = []
        for script in scripts:
            source = script.read_text(encoding="utf-8")
            tree = ast.parse(source)
            title, body = _title_and_body(ast.get_docstring(tree) or "", script.stem)
            section = _section(self.state.document, title, f"example-{script.stem}")
            if body:  # the docstring is Markdown/reST-light: ``code`` and `code` render as code
                holder = nodes.container()
                self.state.nested_parse(StringList(body.splitlines(), str(script)), 0, holder)
                section += holder.children
            section += nodes.paragraph("", "", nodes.literal(text=f"python {script.name} OUTDIR"))
            code = _without_docstring(source, tree)
            section += nodes.literal_block(code, code, language="python")
            if script in runs:
                section += self._results(script, *runs[script])
            else:
                section += nodes.paragraph(text="(Not run in this build.)")
            sections.append(section)
        return sections

    def _run_all(self, scripts: list[Path]) -> dict[Path, tuple[int, str, str, Path]]:
        tmp = Path(tempfile.mkdtemp(prefix="crankdyn-gallery-"))
        env = {**os.environ, "MPLBACKEND": "Agg", "PYTHONHASHSEED": "0"}
        started = {}
        for script in scripts:
            out = tmp / script.stem
            started[script] = (
                subprocess.Popen(
                    [sys.executable, str(script), str(out / "output")],
                    cwd=tmp,
                    env=env,
                    stdout=subprocess.PIPE,
                    stderr=subprocess.PIPE,
                    text=True,
                ),
                out / "output",
            )
        runs = {}
        for script, (proc, out) in started.items():
            try:
                stdout, stderr = proc.communicate(timeout=EXAMPLE_TIMEOUT_S)
            except subprocess.TimeoutExpired:
                proc.kill()
                stdout, stderr = proc.communicate()
                stderr += f"\n(timed out after {EXAMPLE_TIMEOUT_S} s)"
            runs[script] = (proc.returncode, stdout, stderr, out)
        return runs

    def _results(self, script: Path, status: int, stdout: str, stderr: str, out: Path):
        if status != 0:
            tail = " | ".join(stderr.strip().splitlines()[-3:])
            LOG.warning(
                "worked example %s failed (status %s): %s",
                script.name,
                status,
                tail,
                location=(self.env.docname, self.lineno),
            )
        result: list[nodes.Node] = [nodes.rubric(text="Output")]
        result.append(nodes.literal_block(stdout, stdout or "(nothing printed)"))
        files = sorted(p for p in out.rglob("*") if p.is_file()) if out.is_dir() else []
        if files:
            names = ", ".join(p.relative_to(out).as_posix() for p in files)
            result.append(nodes.paragraph(text=f"Files written: {names}."))
        for png in (p for p in files if p.suffix == ".png"):
            data = base64.b64encode(png.read_bytes()).decode("ascii")
            image = nodes.image(uri=f"data:image/png;base64,{data}", alt=png.name)
            result.append(nodes.figure("", image, nodes.caption(text=png.name)))
        return result


class ValidationDirective(SphinxDirective):
    """The validation cases of tests/validation, with their sources."""

    has_content = False

    def run(self) -> list[nodes.Node]:
        folder = REPOSITORY / "tests" / "validation"
        sections = []
        for path in sorted(folder.glob("test_*.py")):
            self.env.note_dependency(str(path))
            tree = ast.parse(path.read_text(encoding="utf-8"))
            rel = path.relative_to(REPOSITORY).as_posix()
            section = _section(self.state.document, rel, f"validation-{path.stem}")
            section += plain_nodes(ast.get_docstring(tree) or "")
            tests = [
                node
                for node in tree.body
                if isinstance(node, ast.FunctionDef) and node.name.startswith("test_")
            ]
            items = []
            for test in tests:
                para = nodes.paragraph("", "", nodes.literal(text=test.name))
                doc = ast.get_docstring(test)
                if doc:
                    para += nodes.Text(": " + " ".join(_blocks(doc)[0]))
                items.append(nodes.list_item("", para))
            section += nodes.rubric(text=f"Tests ({len(tests)})")
            section += nodes.bullet_list("", *items)
            sections.append(section)
        return sections


class PythonDomain(_SphinxPythonDomain):
    """Sphinx's Python domain, its "fuzzy" search (a reference in a signature to a name that is
    no object's full name: every object whose name ends in ``.name``, of the role's types)
    answered from an index of the objects' last name parts, rebuilt when the objects change;
    the same matches in the same order as Sphinx's scan of every object."""

    _index: tuple[int, dict[str, list[str]]] = (-1, {})

    def _ending(self, name: str) -> list[str]:
        """The objects' full names whose last part is ``name``'s last part, in their order."""
        count, index = self._index
        if count != len(self.objects):
            index = {}
            for oname in self.objects:
                index.setdefault(oname.rpartition(".")[2], []).append(oname)
            self._index = (len(self.objects), index)
        return index.get(name.rpartition(".")[2], [])

    def find_obj(self, env, modname, classname, name, type, searchmode=0):
        name = name.removesuffix("()")
        if searchmode != 1 or not name:
            return super().find_obj(env, modname, classname, name, type, searchmode)
        objtypes = list(self.object_types) if type is None else self.objtypes_for_role(type)
        if objtypes is None:
            return []
        for full in (
            f"{modname}.{classname}.{name}" if modname and classname else None,
            f"{modname}.{name}" if modname else None,
            name,
        ):
            if full and full in self.objects and self.objects[full].objtype in objtypes:
                return [(full, self.objects[full])]
        searchname = f".{name}"
        return [
            (oname, self.objects[oname])
            for oname in self._ending(name)
            if oname.endswith(searchname) and self.objects[oname].objtype in objtypes
        ]


def _numpydoc_template() -> None:
    """numpydoc builds a Jinja environment and compiles its docstring template for every
    docstring (numpydoc.docscrape_sphinx.get_doc_object); its module-level ``get_doc_object``
    is the replaceable hook (numpydoc's ``setup(app, get_doc_object_=...)``): the same
    template, compiled once per builder."""
    from jinja2 import FileSystemLoader
    from jinja2.sandbox import SandboxedEnvironment
    from numpydoc import docscrape, docscrape_sphinx
    from numpydoc import numpydoc as hook
    from sphinx.jinja2glue import BuiltinTemplateLoader

    compiled: dict[int, object] = {}
    folders = [os.path.join(os.path.dirname(docscrape_sphinx.__file__), "templates")]

    def get_doc_object(obj, what=None, doc=None, config=None, builder=None):
        config = {} if config is None else config
        template = compiled.get(id(builder))
        if template is None:
            if builder is not None:
                loader = BuiltinTemplateLoader()
                loader.init(builder, dirs=folders)
            else:
                loader = FileSystemLoader(folders)
            template = SandboxedEnvironment(loader=loader).get_template("numpydoc_docstring.rst")
            compiled[id(builder)] = template
        config["template"] = template
        return docscrape.get_doc_object(
            obj,
            what=what,
            doc=doc,
            config=config,
            class_doc=docscrape_sphinx.SphinxClassDoc,
            func_doc=docscrape_sphinx.SphinxFunctionDoc,
            obj_doc=docscrape_sphinx.SphinxObjDoc,
        )

    hook.get_doc_object = get_doc_object


def setup(app):
    app.setup_extension("numpydoc")  # loaded first: its setup resets its hook
    app.add_domain(PythonDomain, override=True)
    _numpydoc_template()
    app.add_config_value("crankdyn_run_examples", True, "env", types=(bool, int))
    app.add_directive("crankdyn-gallery", GalleryDirective)
    app.add_directive("crankdyn-validation", ValidationDirective)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
