"""Docstring meta-test (python-control's habit): every parameter of a public callable is in its
numpydoc ``Parameters`` section, and nothing documented there is stale; every public module,
class, function, method and property has a docstring; a function that returns something has a
``Returns`` (or ``Yields``) section; and the public API is annotated (parameters and return).

Scope: the API reference's (every module but ``crankdyn.cli``): the names a module lists in
``__all__`` (else its public names defined there), the public methods (class and static methods
included) and properties of public classes, and the fields of public dataclasses (a field
declared with ``results.column/array/scalar`` documents itself: its label and unit are its
documentation, and the API reference shows them in a table). Every module of the package is
checked (issue 21's waves brought them all to the rule; a new module is documented when it lands).
"""

from __future__ import annotations

import dataclasses
import importlib
import inspect
import pkgutil
import warnings

import pytest

import crankdyn

numpydoc = pytest.importorskip("numpydoc.docscrape")

SKIPPED_PARAMETERS = {"self", "cls"}


def _modules() -> list[str]:
    names = [crankdyn.__name__]
    for info in pkgutil.walk_packages(crankdyn.__path__, "crankdyn."):
        if info.name.startswith("crankdyn.cli") or info.name.endswith("__main__"):
            continue
        names.append(info.name)
    return sorted(names)


def _public(module) -> list[tuple[str, object]]:
    names = getattr(module, "__all__", None)
    if names is None:
        names = [
            n
            for n, obj in vars(module).items()
            if not n.startswith("_") and getattr(obj, "__module__", None) == module.__name__
        ]
    out = []
    for name in names:
        obj = getattr(module, name)
        if getattr(obj, "__module__", None) != module.__name__:
            continue  # a re-export: checked where it is defined
        if inspect.isfunction(obj) or inspect.isclass(obj):
            out.append((f"{module.__name__}.{name}", obj))
    return out


def _self_documenting_fields(cls) -> set[str]:
    if not dataclasses.is_dataclass(cls):
        return set()
    return {f.name for f in dataclasses.fields(cls) if "label" in f.metadata}


def _parameters(func, skip: set[str] = frozenset()) -> list[str]:
    try:
        sig = inspect.signature(func)
    except (TypeError, ValueError):
        return []
    return [p for p in sig.parameters if p not in SKIPPED_PARAMETERS and p not in skip]


def _documented(doc) -> set[str]:
    names = set()
    for section in ("Parameters", "Other Parameters", "Attributes"):
        for param in doc[section]:
            for name in param.name.split(","):
                names.add(name.strip().lstrip("*"))
    return names


def _methods(cls):
    """(name, function, kind) of the public methods and properties a class defines; kind is
    "method" (class and static methods included) or "property"."""
    for attr, member in vars(cls).items():
        if attr.startswith("_"):
            continue
        if isinstance(member, (classmethod, staticmethod)):
            yield attr, member.__func__, "method"
        elif inspect.isfunction(member):
            yield attr, member, "method"
        elif isinstance(member, property) and member.fget is not None:
            yield attr, member.fget, "property"


def problems(name: str, obj, strict: bool = True) -> list[str]:
    """What is missing or stale in the docstring of a public function or class (and of the
    public methods a class defines). ``strict`` adds the checks beyond the parameters: a
    docstring everywhere and a Returns section where something is returned."""
    out = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        if inspect.isclass(obj):
            if strict and not (obj.__doc__ or "").strip():
                out.append(f"{name}: no docstring")
            doc = numpydoc.ClassDoc(obj, config={"show_class_members": False})
            wanted = _parameters(obj, _self_documenting_fields(obj))
            params = {p.lstrip("*") for p in wanted}
            documented = _documented(doc)
            out += [f"{name}: parameter {p!r} undocumented" for p in params - documented]
            for attr, member, kind in _methods(obj):
                if kind == "property":
                    if strict and not (member.__doc__ or "").strip():
                        out.append(f"{name}.{attr}: no docstring")
                    continue
                if not strict and not inspect.isfunction(vars(obj)[attr]):
                    continue
                out += _function_problems(f"{name}.{attr}", member, strict)
        else:
            out += _function_problems(name, obj, strict)
    return out


def _function_problems(name: str, func, strict: bool = True) -> list[str]:
    if strict and not (func.__doc__ or "").strip():
        return [f"{name}: no docstring"]
    doc = numpydoc.FunctionDoc(func)
    params = {p.lstrip("*") for p in _parameters(func)}
    documented = {n for n in _documented(doc)}
    out = [f"{name}: parameter {p!r} undocumented" for p in sorted(params - documented)]
    out += [f"{name}: documented parameter {p!r} does not exist" for p in documented - params]
    returned = inspect.signature(func).return_annotation
    if (
        strict
        and returned not in ("None", None, inspect.Signature.empty)
        and not (doc["Returns"] or doc["Yields"])
    ):
        out.append(f"{name}: returns {returned} but has no Returns section")
    return out


def annotation_problems(name: str, obj) -> list[str]:
    """Parameters and return values of a public function (or of a class's public methods and
    properties) that carry no type annotation."""
    if inspect.isclass(obj):
        out = []
        for attr, member, _kind in _methods(obj):
            out += annotation_problems(f"{name}.{attr}", member)
        return out
    try:
        sig = inspect.signature(obj)
    except (TypeError, ValueError):
        return []
    out = [
        f"{name}: parameter {p.name!r} unannotated"
        for p in sig.parameters.values()
        if p.name not in SKIPPED_PARAMETERS and p.annotation is inspect.Parameter.empty
    ]
    if sig.return_annotation is inspect.Signature.empty:
        out.append(f"{name}: return value unannotated")
    return out


def test_every_package_is_walked():
    """The walk reaches every subpackage (a module that fails to import would drop out)."""
    found = {m.split(".")[1] for m in _modules() if m.count(".") >= 1}
    assert found >= {"crank", "engine", "io", "linkage", "measure", "plots", "report", "study"}
    assert found >= {"torsion", "tvc", "results", "display", "errors"}


@pytest.mark.parametrize("module_name", _modules())
def test_every_parameter_is_documented(module_name):
    module = importlib.import_module(module_name)
    found = [p for name, obj in _public(module) for p in problems(name, obj, True)]
    if not (module.__doc__ or "").strip():
        found.append(f"{module_name}: no module docstring")
    assert not found, "\n".join(found)


@pytest.mark.parametrize("module_name", _modules())
def test_the_public_api_is_annotated(module_name):
    module = importlib.import_module(module_name)
    found = [p for name, obj in _public(module) for p in annotation_problems(name, obj)]
    assert not found, "\n".join(found)
