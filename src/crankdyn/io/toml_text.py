"""TOML text from a parsed document (what :func:`tomllib.loads` returns), for the files crankdyn
writes that a person and crankdyn read again (the design search's chosen design, ``best.toml``).

The writer covers what crankdyn's files hold: tables, arrays of tables, strings, integers,
floats (finite; written in their shortest round-trip form), booleans, dates and times (a
project's date) and arrays of these. A
table's plain keys come first, then its sub-tables (``[a.b]``) and arrays of tables
(``[[a.c]]``), so that ``tomllib.loads(dumps(d)) == d`` (TOML 1.0, https://toml.io/en/v1.0.0).
"""

from __future__ import annotations

import datetime as _dt
import json
import math
import re
from typing import Any

__all__ = ["dumps"]

_BARE = re.compile(r"^[A-Za-z0-9_-]+$")


def _key(key: str) -> str:
    return key if _BARE.match(key) else json.dumps(key, ensure_ascii=False)


def _value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ValueError(f"TOML has no finite form for {value!r} here")
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, _dt.date | _dt.time):  # TOML's dates and times (RFC 3339), bare
        return value.isoformat()
    if isinstance(value, list):
        return "[" + ", ".join(_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{_key(k)} = {_value(v)}" for k, v in value.items()) + "}"
    raise TypeError(f"cannot write {type(value).__name__} as TOML")


def _is_tables(value: Any) -> bool:
    return isinstance(value, list) and bool(value) and all(isinstance(v, dict) for v in value)


def _table(lines: list[str], prefix: str, table: dict[str, Any]) -> None:
    for key, value in table.items():
        if not isinstance(value, dict) and not _is_tables(value):
            lines.append(f"{_key(key)} = {_value(value)}")
    for key, value in table.items():
        name = f"{prefix}.{_key(key)}" if prefix else _key(key)
        if isinstance(value, dict):
            lines.extend(["", f"[{name}]"])
            _table(lines, name, value)
        elif _is_tables(value):
            for item in value:
                lines.extend(["", f"[[{name}]]"])
                _table(lines, name, item)


def dumps(document: dict[str, Any]) -> str:
    """A document as TOML text (module docstring).

    Parameters
    ----------
    document : dict
        The document (str keys; values as above).

    Returns
    -------
    str
        TOML text that reads back as ``document``.

    Raises
    ------
    TypeError, ValueError
        For a value TOML cannot hold here (a non-finite float, an object).

    Examples
    --------
    >>> import tomllib
    >>> import datetime
    >>> doc = {"name": "x", "a": {"b": [1, 2.5]}, "m": [{"n": "p"}, {"n": "q"}],
    ...        "d": datetime.date(2026, 11, 29)}
    >>> tomllib.loads(dumps(doc)) == doc
    True
    """
    lines: list[str] = []
    _table(lines, "", document)
    return "\n".join(lines).lstrip("\n") + "\n"
