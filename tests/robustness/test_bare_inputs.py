"""Every speed and every millimetre of the built-in examples, written as a bare number: a bare
speed is refused in one line naming the file, the key and the value; a bare number of
millimetres (read as metres, 1000 times too large) never passes silently: it is refused or a
listed input warning names its key (crankdyn.io.plausibility's table covers every length the
examples give)."""

from __future__ import annotations

import copy
import re
from collections.abc import Iterator
from typing import Any

import pytest

from crankdyn.errors import InputError
from crankdyn.io.engine_file import parse_engine, parse_model_file
from crankdyn.io.examples import example_names, example_path
from crankdyn.io.files import load_toml
from crankdyn.io.units import BARE_SPEED

_QUANTITY = re.compile(r"^\s*([-+]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][-+]?\d+)?)\s+(\S.*)$")
_SPEED_UNITS = ("rpm", "rad/s")  # "150 Hz" in the examples is a frequency


def _quantities(node: Any, path: tuple[Any, ...] = ()) -> Iterator[tuple[tuple[Any, ...], str]]:
    """(path, unit) of every "number unit" string of a document."""
    if isinstance(node, dict):
        for key, value in node.items():
            yield from _quantities(value, (*path, key))
    elif isinstance(node, list):
        for i, value in enumerate(node):
            yield from _quantities(value, (*path, i))
    elif isinstance(node, str):
        m = _QUANTITY.match(node)
        if m:
            yield path, m.group(2)


def _with(document: dict, path: tuple[Any, ...]) -> tuple[dict, float]:
    """The document with the quantity at ``path`` written as its bare number."""
    doc = copy.deepcopy(document)
    node = doc
    for part in path[:-1]:
        node = node[part]
    m = _QUANTITY.match(node[path[-1]])
    assert m is not None
    node[path[-1]] = float(m.group(1))
    return doc, float(m.group(1))


def _cases(units: tuple[str, ...]) -> list[tuple[str, str, tuple[Any, ...]]]:
    out = []
    for kind in ("engine", "model"):
        for name in example_names(kind):
            document = load_toml(example_path(name, kind))
            out += [(kind, name, p) for p, unit in _quantities(document) if unit in units]
    return out


def _parse(kind: str, name: str, document: dict) -> Any:
    read = parse_engine if kind == "engine" else parse_model_file
    return read(document, file=name, base_dir=example_path(name, kind).parent)


def _key(path: tuple[Any, ...]) -> str:
    return next(p for p in reversed(path) if isinstance(p, str))


SPEEDS = _cases(_SPEED_UNITS)
LENGTHS = _cases(("mm",))


def test_the_examples_give_speeds_and_lengths():
    assert len(SPEEDS) > 15 and len(LENGTHS) > 30


@pytest.mark.parametrize("kind, name, path", SPEEDS)
def test_a_bare_speed_is_refused(kind, name, path):
    document, number = _with(load_toml(example_path(name, kind)), path)
    if number == 0.0:  # a bare 0 is the same speed in every unit: read as it is
        _parse(kind, name, document)
        return
    with pytest.raises(InputError) as exc:
        _parse(kind, name, document)
    text = str(exc.value)
    assert "\n" not in text and text.endswith(BARE_SPEED), text
    assert text.startswith(f"{name}: ") and _key(path) in text and f"{number:g}" in text


@pytest.mark.parametrize("kind, name, path", LENGTHS)
def test_bare_millimetres_never_pass_silently(kind, name, path):
    document, number = _with(load_toml(example_path(name, kind)), path)
    if number == 0.0:
        return  # 0 mm is 0 m
    try:
        subject = _parse(kind, name, document)
    except InputError as exc:  # refused (by a domain check: e.g. a rod shorter than the crank)
        assert "\n" not in str(exc)
        return
    key = _key(path)
    named = [w for w in subject.input_warnings if w.input_key.split(" ")[-1] == key]
    assert named, f"{name}: {key} = {number:g} (m) passed silently"
    assert all(w.file == name and "did you mean" in w.message for w in named)
