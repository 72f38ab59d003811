"""The site's local Sphinx extension (docs/_ext/crankdyn_sphinx.py): its Python domain's search
by a name's last parts gives the same matches in the same order as Sphinx's own scan of every
object (the build's output was compared page by page when it came in: identical)."""

from __future__ import annotations

import sys
from pathlib import Path
from types import SimpleNamespace

import pytest

pytest.importorskip("sphinx")
pytest.importorskip("numpydoc")

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "docs" / "_ext"))

import crankdyn_sphinx
from crankdyn_sphinx import PythonDomain
from sphinx.domains.python import ObjectEntry
from sphinx.domains.python import PythonDomain as SphinxPythonDomain


def _domain(cls, names: dict[str, str]):
    """A domain of ``cls`` on an empty environment holding ``names`` (full name: type)."""
    domain = cls(SimpleNamespace(domaindata={}))
    for full, objtype in names.items():
        domain.objects[full] = ObjectEntry("page", full, objtype, False)
    return domain


@pytest.mark.parametrize(
    ("modname", "classname", "name", "role"),
    [
        (None, None, "float", "class"),
        ("crankdyn.torsion.model", None, "TorsionModel", "class"),
        ("crankdyn.torsion", "Sweep", "evaluate", "meth"),
        (None, None, "model.TorsionModel", "class"),
        (None, None, "evaluate", "meth"),
        (None, None, "Result", None),
        ("crankdyn.x", None, "", "class"),
    ],
)
def test_fuzzy_search_matches_sphinx(monkeypatch, modname, classname, name, role):
    names = {
        "crankdyn.torsion.model.TorsionModel": "class",
        "crankdyn.io.model.TorsionModel": "class",
        "crankdyn.torsion.Sweep.evaluate": "method",
        "crankdyn.torsion.Other.evaluate": "method",
        "crankdyn.torsion.evaluate": "function",
        "crankdyn.tvc.Result": "class",
        "crankdyn.tvc.result.Result": "data",
        "float_like": "data",
    }
    found = []
    for cls in (PythonDomain, SphinxPythonDomain):
        domain = _domain(cls, names)
        found.append(domain.find_obj(None, modname, classname, name, role, 1))
        found.append(domain.find_obj(None, modname, classname, name, role, 0))
    assert found[0] == found[2] and found[1] == found[3]


def test_the_index_follows_the_objects():
    domain = _domain(PythonDomain, {"a.b.Thing": "class"})
    assert [n for n, _ in domain.find_obj(None, None, None, "Thing", "class", 1)] == ["a.b.Thing"]
    domain.objects["c.Thing"] = ObjectEntry("page", "c.Thing", "class", False)
    found = domain.find_obj(None, None, None, "Thing", "class", 1)
    assert [n for n, _ in found] == ["a.b.Thing", "c.Thing"]


def test_the_numpydoc_template_compiled_once_renders_the_same(monkeypatch):
    from numpydoc import docscrape_sphinx
    from numpydoc import numpydoc as hook

    from crankdyn.torsion.sweep import forced_response
    from crankdyn.torsion.synthesis import half_range

    monkeypatch.setattr(hook, "get_doc_object", hook.get_doc_object)
    crankdyn_sphinx._numpydoc_template()
    for obj in (half_range, forced_response, PythonDomain):
        config = {"show_class_members": False}
        ours = str(hook.get_doc_object(obj, config=dict(config)))
        theirs = str(docscrape_sphinx.get_doc_object(obj, config=dict(config)))
        assert ours == theirs
        assert "Parameters" in ours or obj is PythonDomain
    assert hook.get_doc_object is not docscrape_sphinx.get_doc_object
