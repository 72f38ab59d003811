"""Hypothesis strategies for hostile input: mutated documents and arbitrary values."""

from __future__ import annotations

import copy
import math

from hypothesis import strategies as st

UNITS = [
    "mm",
    "m",
    "kg",
    "g",
    "rpm",
    "deg",
    "rad",
    "Hz",
    "MPa",
    "bar",
    "N",
    "N*m",
    "kg*m^2",
    "kN*m/rad",
    "s",
    "",
    "furlong",
    "mm^2",
    "1/s",
    "%",
    "°",
    "kg m",
    "m/s",
]

scalars = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(min_value=-(10**12), max_value=10**12),
    st.floats(allow_nan=True, allow_infinity=True),
    st.text(max_size=30),
    st.builds(
        lambda x, u: f"{x} {u}".strip(),
        st.floats(allow_nan=True, allow_infinity=True, width=32),
        st.sampled_from(UNITS),
    ),
    st.builds(lambda x, u: f"{x}{u}", st.integers(-(10**6), 10**6), st.sampled_from(UNITS)),
)
values = st.recursive(
    scalars.filter(lambda v: v is not None),
    lambda children: st.one_of(
        st.lists(children, max_size=6), st.dictionaries(st.text(max_size=12), children, max_size=4)
    ),
    max_leaves=12,
)


def _paths(doc, prefix=()):
    for key, value in doc.items():
        yield (*prefix, key)
        if isinstance(value, dict):
            yield from _paths(value, (*prefix, key))


@st.composite
def mutated(draw, base: dict, max_mutations: int = 4):
    """A copy of ``base`` with 1..max_mutations random edits: delete, replace, add, rename,
    shorten or lengthen lists."""
    doc = copy.deepcopy(base)
    for _ in range(draw(st.integers(1, max_mutations))):
        paths = list(_paths(doc))
        action = draw(st.sampled_from(["delete", "replace", "add", "rename", "list"]))
        if not paths:
            action = "add"
        if action == "add":
            target = doc
            if paths and draw(st.booleans()):
                parent = draw(st.sampled_from(paths))
                holder = doc
                for part in parent[:-1]:
                    holder = holder[part]
                if isinstance(holder[parent[-1]], dict):
                    target = holder[parent[-1]]
            target[draw(st.text(min_size=1, max_size=12))] = draw(values)
            continue
        path = draw(st.sampled_from(paths))
        holder = doc
        for part in path[:-1]:
            holder = holder[part]
        key = path[-1]
        if action == "delete":
            del holder[key]
        elif action == "replace":
            holder[key] = draw(values)
        elif action == "rename":
            holder[key + draw(st.sampled_from(["s", "_", "x"]))] = holder.pop(key)
        elif action == "list" and isinstance(holder[key], list):
            items = holder[key]
            if items and draw(st.booleans()):
                items.pop(draw(st.integers(0, len(items) - 1)))
            else:
                items.append(copy.deepcopy(items[0]) if items else draw(values))
    return doc


def finite(x) -> bool:
    return isinstance(x, (int, float)) and math.isfinite(x)


def _toml_value(value) -> str:
    import json

    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, list):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return (
            "{" + ", ".join(f"{json.dumps(k)} = {_toml_value(v)}" for k, v in value.items()) + "}"
        )
    raise TypeError(type(value))


def to_toml(doc: dict) -> str:
    """A TOML document for a parsed one (every table written inline; TOML has no null, so None
    values are dropped)."""
    import json

    def clean(v):
        if isinstance(v, dict):
            return {k: clean(x) for k, x in v.items() if x is not None}
        if isinstance(v, list):
            return [clean(x) for x in v if x is not None]
        return v

    return "".join(
        f"{json.dumps(k)} = {_toml_value(clean(v))}\n" for k, v in doc.items() if v is not None
    )
