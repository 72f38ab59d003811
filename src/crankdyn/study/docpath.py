"""Addressing keys of a parsed TOML document by path, and editing a copy of it.

A study parameter names the engine-file (or model-file) key it varies by its TOML path:
``geometry.rod_length``, ``masses.piston_group``, ``cylinders.firing_order``; an entry of an
array of tables takes a 1-based index, as crankdyn's messages number them
(``[[torsion.shaft]] #2`` is ``torsion.shaft[2]``): ``torsion.shaft[2].stiffness``.

A case is applied to a deep copy of the base document; the copy is then parsed by the file's
own reader, so every variant is validated exactly like a file a user wrote.
"""

from __future__ import annotations

import copy
import re
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from crankdyn.errors import InputError, did_you_mean

__all__ = ["KeyPath", "apply_values", "check_path", "parse_path", "referenced_files"]

_SEGMENT = re.compile(r"([A-Za-z0-9_-]+)(?:\[(\d+)\])?")


@dataclass(frozen=True)
class KeyPath:
    """A parsed key path (:func:`parse_path`).

    Parameters
    ----------
    text : str
        The path as written (``torsion.shaft[2].stiffness``).
    parts : tuple of (str, int or None)
        (name, index) pairs, the index 1-based or None.
    """

    text: str
    parts: tuple[tuple[str, int | None], ...]

    def __str__(self) -> str:
        return self.text


def parse_path(text: object, *, file: str | None = None, key: str | None = None) -> KeyPath:
    """Parse ``geometry.rod_length`` or ``torsion.shaft[2].stiffness``.

    Parameters
    ----------
    text : object
        The path as given in the study file.
    file : str or None
        The study file, for messages.
    key : str or None
        The study file's key that holds the path, for messages.

    Returns
    -------
    KeyPath
        The parsed path.

    Raises
    ------
    InputError
        For anything else (empty segments, quoted keys, a zero index).

    Examples
    --------
    >>> parse_path("torsion.shaft[2].stiffness").parts
    (('torsion', None), ('shaft', 2), ('stiffness', None))
    """
    if not isinstance(text, str) or not text.strip():
        raise InputError(
            'expected a key path such as "geometry.rod_length"', file=file, key=key, value=text
        )
    parts = []
    for segment in text.split("."):
        match = _SEGMENT.fullmatch(segment)
        if not match:
            raise InputError(
                'expected a key path such as "geometry.rod_length" or '
                '"torsion.shaft[2].stiffness" (bare keys joined by dots, 1-based [n] for '
                "entries of an array of tables)",
                file=file,
                key=key,
                value=text,
            )
        index = None if match.group(2) is None else int(match.group(2))
        if index is not None and index < 1:
            raise InputError("array entries are numbered from 1", file=file, key=key, value=text)
        parts.append((match.group(1), index))
    return KeyPath(text, tuple(parts))


def check_path(
    document: dict[str, Any],
    path: KeyPath,
    *,
    must_exist: bool = False,
    file: str | None = None,
    key: str | None = None,
) -> None:
    """Check that ``path`` can address ``document``: every table on the way is a table (or is
    missing and can be created, unless ``must_exist``), every index is within its array of
    tables, and (``must_exist``) the final key is present.

    Parameters
    ----------
    document : dict
        The parsed base document.
    path : KeyPath
        The path.
    must_exist : bool
        The final key must be present (not created); default False.
    file : str or None
        The study file, for messages.
    key : str or None
        The study file's key that holds the path, for messages.

    Raises
    ------
    InputError
        Naming the first part that does not fit, with a did-you-mean from the keys present.
    """
    node: Any = document
    walked: list[str] = []
    for depth, (name, index) in enumerate(path.parts):
        last = depth == len(path.parts) - 1
        here = ".".join([*walked, name])
        if not isinstance(node, dict):
            raise InputError(
                f"{'.'.join(walked)} is not a table in the base file",
                file=file,
                key=key,
                value=path.text,
            )
        if name not in node:
            if must_exist or index is not None:
                raise InputError(
                    f"{here} is not in the base file{did_you_mean(name, list(node))}",
                    file=file,
                    key=key,
                    value=path.text,
                )
            # created on application, with every table after it: an entry of an array of
            # tables there cannot be made (its array is not in the base file)
            indexed = next((f"{n}[{i}]" for n, i in path.parts[depth + 1 :] if i), None)
            if indexed is not None:
                raise InputError(
                    f"{here} is not in the base file ({indexed} names an entry of an array of "
                    f"tables the base file must have){did_you_mean(name, list(node))}",
                    file=file,
                    key=key,
                    value=path.text,
                )
            return
        node = node[name]
        if index is not None:
            if not isinstance(node, list) or (
                not last and any(not isinstance(item, dict) for item in node)
            ):
                raise InputError(
                    f"{here} is not an array in the base file", file=file, key=key, value=path.text
                )
            if index > len(node):
                raise InputError(
                    f"{here} has {len(node)} entries in the base file",
                    file=file,
                    key=key,
                    value=path.text,
                )
            node = node[index - 1]
        walked.append(name if index is None else f"{name}[{index}]")


def _parent(document: dict[str, Any], path: KeyPath, *, create: bool) -> Any:
    node: Any = document
    for name, index in path.parts[:-1]:
        if name not in node:
            if not create:
                return None
            node[name] = {}
        node = node[name]
        if index is not None:
            node = node[index - 1]
    return node


def apply_values(
    document: dict[str, Any], values: dict[KeyPath, Any], remove: tuple[KeyPath, ...] = ()
) -> dict[str, Any]:
    """A copy of a document with keys removed and values set.

    Paths must have passed :func:`check_path` against ``document``.

    Parameters
    ----------
    document : dict
        The parsed base document (not modified).
    values : dict of KeyPath to object
        The values to set (tables on the way created when missing); None removes the key
        (TOML has no null, so a file never gives it: a bundle that replaces one key by
        another, e.g. a coupling's ``stiffness_table`` by its ``dynamic_stiffness``).
    remove : tuple of KeyPath
        Keys deleted first; default none.

    Returns
    -------
    dict
        A deep copy of ``document`` with the ``remove`` keys deleted and every ``values`` key
        set.

    Examples
    --------
    >>> doc = {"torsion": {"shaft": [{"stiffness": 1}, {"stiffness": 2}]}}
    >>> apply_values(doc, {parse_path("torsion.shaft[2].stiffness"): 5})
    {'torsion': {'shaft': [{'stiffness': 1}, {'stiffness': 5}]}}
    >>> doc["torsion"]["shaft"][1]
    {'stiffness': 2}
    """
    out = copy.deepcopy(document)
    for path in remove:
        parent = _parent(out, path, create=False)
        name, index = path.parts[-1]
        if parent is not None and name in parent:
            if index is None:
                del parent[name]
            else:
                del parent[name][index - 1]
    for path, value in values.items():
        if value is None:
            parent = _parent(out, path, create=False)
            name, index = path.parts[-1]
            if parent is not None and index is None and name in parent:
                del parent[name]
            continue
        parent = _parent(out, path, create=True)
        name, index = path.parts[-1]
        if index is None:
            parent[name] = copy.deepcopy(value)
        else:
            parent[name][index - 1] = copy.deepcopy(value)
    return out


_MAX_REFERENCED_BYTES = 64 << 20


def _strings(value: Any) -> Iterator[str]:
    if isinstance(value, str):
        yield value
    elif isinstance(value, dict):
        for v in value.values():
            yield from _strings(v)
    elif isinstance(value, list):
        for v in value:
            yield from _strings(v)


def referenced_files(document: dict[str, Any], folder: Path) -> list[tuple[str, Path]]:
    """The files a document names, a pressure trace for instance.

    Every string value that is the path of an existing file (relative to ``folder`` unless
    absolute, at most 64 MiB); the reader decides what a string means, so this errs on the
    side of including.

    Parameters
    ----------
    document : dict
        The parsed document.
    folder : pathlib.Path
        The folder relative paths resolve against.

    Returns
    -------
    list of (str, pathlib.Path)
        (text as written, path), sorted by text.
    """
    out = []
    for text in sorted(set(_strings(document))):
        if not text.strip() or len(text) > 4096 or "\n" in text or "\0" in text:
            continue
        try:
            path = Path(text).expanduser()
            path = path if path.is_absolute() else folder / path
            if path.is_file() and path.stat().st_size <= _MAX_REFERENCED_BYTES:
                out.append((text, path))
        except (OSError, ValueError):
            continue
    return out
