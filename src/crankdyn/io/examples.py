"""The index of the built-in examples: which files ship with the package, by kind.

Every example is a TOML file under ``crankdyn/examples`` (engines at the top, torsional models
in ``torsion/``, linkages in ``linkages/``, studies in ``studies/``), with any file it names
(pressure traces, load curves, harmonic tables) beside it. Names are unique across the kinds, so
a name alone finds an example. This module only locates files; :mod:`crankdyn.io.catalogue`
loads them.
"""

from __future__ import annotations

from importlib import resources
from importlib.resources.abc import Traversable
from pathlib import Path
from typing import Any

from crankdyn.errors import InputError, did_you_mean
from crankdyn.io.files import load_toml

__all__ = [
    "EXAMPLES_ROOT",
    "EXAMPLE_KINDS",
    "display_path",
    "example_files",
    "example_kind",
    "example_names",
    "example_path",
]

EXAMPLES_ROOT = resources.files("crankdyn") / "examples"

EXAMPLE_KINDS = {
    "engine": ("", "engine"),
    "model": ("torsion", "torsional model"),
    "linkage": ("linkages", "linkage"),
    "study": ("studies", "study"),
}
"""kind -> (folder under crankdyn/examples, what it is called in messages)."""


def _folder(kind: str) -> Traversable:
    sub = EXAMPLE_KINDS[kind][0]
    return EXAMPLES_ROOT / sub if sub else EXAMPLES_ROOT


def example_names(kind: str | None = None) -> list[str]:
    """Names of the built-in examples of one kind (``"engine"``, ``"model"``, ``"linkage"``,
    ``"study"``), or of every kind.

    Parameters
    ----------
    kind
        A key of :data:`EXAMPLE_KINDS`, or None for every kind.

    Returns
    -------
    list of str
        The names (file stems), sorted within each kind.

    Examples
    --------
    >>> "single-cylinder" in example_names("engine")
    True
    >>> "marine-shaft-line" in example_names("model")
    True
    """
    kinds = EXAMPLE_KINDS if kind is None else (kind,)
    names: list[str] = []
    for k in kinds:
        names += sorted(p.name[:-5] for p in _folder(k).iterdir() if p.name.endswith(".toml"))
    return names


def example_kind(name: str) -> str | None:
    """The kind of the built-in example ``name``, or None when there is none of that name.

    Parameters
    ----------
    name
        An example's name (``"single-cylinder"``).

    Returns
    -------
    str or None
        A key of :data:`EXAMPLE_KINDS`, or None.

    Examples
    --------
    >>> example_kind("marine-shaft-line"), example_kind("no-such-example")
    ('model', None)
    """
    for kind in EXAMPLE_KINDS:
        if name in example_names(kind):
            return kind
    return None


def example_path(name: str, kind: str | None = None) -> Path:
    """The TOML file of a built-in example (of ``kind``, or of any kind); an unknown name is a
    one-line error listing the examples, with a did-you-mean.

    Parameters
    ----------
    name
        The example's name.
    kind
        A key of :data:`EXAMPLE_KINDS` the example must be of, or None for any kind.

    Returns
    -------
    Path
        The example's TOML file inside the installed package.

    Raises
    ------
    InputError
        For an unknown name (or one of another kind), naming the key (``example``, or the kind)
        and the value, and listing the examples.

    Examples
    --------
    >>> example_path("single-cylinder").name
    'single-cylinder.toml'
    """
    found = example_kind(name)
    if found is None or (kind is not None and found != kind):
        names = example_names(kind)
        what = "example" if kind is None else f"{EXAMPLE_KINDS[kind][1]} example"
        raise InputError(
            f"no built-in {what} of that name (examples: {', '.join(names)})"
            + did_you_mean(name, names),
            key="example" if kind in (None, "engine") else kind,
            value=name,
        )
    return Path(str(_folder(found) / f"{name}.toml"))


def example_files(name: str, kind: str | None = None) -> list[Path]:
    """The files of a built-in example: its TOML file first, then the files it names (the
    pressure trace; the excitation's load curve, harmonic tables, traces and source tables; the
    transient events' torque histories; the
    shaft lines joined to an engine and the engine files joined to a line, with the files those
    name in turn), each once.

    Parameters
    ----------
    name
        The example's name.
    kind
        A key of :data:`EXAMPLE_KINDS`, or None for any kind.

    Returns
    -------
    list of Path
        The TOML file, then the files it names (some may be absent if the TOML is wrong).

    Raises
    ------
    InputError
        For an unknown name (:func:`example_path`) or a TOML file that does not parse.
    """
    path = example_path(name, kind)
    files = [path]
    _named_files(path, load_toml(path), files)
    return files


def _named_files(path: Path, data: dict[str, Any], files: list[Path]) -> None:
    """Append the files ``data`` (the TOML document of ``path``) names to ``files``, following
    shaft-line and engine files."""

    def table(value: object) -> dict[str, Any]:
        return value if isinstance(value, dict) else {}

    def entries(value: object) -> list[dict[str, Any]]:
        return [t for t in value if isinstance(t, dict)] if isinstance(value, list) else []

    def add(name: object, follow: bool = False) -> None:
        if not isinstance(name, str):
            return
        found = path.parent / name
        if found in files:
            return
        files.append(found)
        if follow and found.suffix == ".toml" and found.is_file():
            _named_files(found, load_toml(found), files)

    add(table(data.get("pressure")).get("file"))
    torsion = table(data.get("torsion")) if "geometry" in data else data
    excitation = table(torsion.get("excitation"))
    add(excitation.get("load_curve"))
    add(excitation.get("harmonics"))
    add(excitation.get("cylinder_harmonics"))
    for t in entries(table(torsion.get("tvc")).get("event")):
        add(t.get("file"))
    for t in entries(excitation.get("trace")):
        add(t.get("file"))
    for t in entries(excitation.get("source")):
        add(t.get("table"))
    add(torsion.get("shaft_line"), follow=True)
    for t in entries(torsion.get("line")):
        add(t.get("file"), follow=True)
    for t in entries(data.get("engine")):
        add(t.get("file"), follow=True)


def display_path(path: Path) -> str:
    """A file as the user knows it: by name for files that ship with the package, else relative
    to the working folder when inside it, else as given.

    Parameters
    ----------
    path
        A file.

    Returns
    -------
    str
        Its path relative to the package's examples folder, else to the working folder, else
        as given.

    Examples
    --------
    >>> display_path(example_path("single-cylinder"))
    'single-cylinder.toml'
    """
    try:
        return str(path.resolve().relative_to(Path(str(EXAMPLES_ROOT)).resolve()))
    except ValueError:
        pass
    try:
        return str(path.resolve().relative_to(Path.cwd().resolve()))
    except ValueError:
        return str(path)
