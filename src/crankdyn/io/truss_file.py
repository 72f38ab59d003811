"""Truss files (TOML): a plane pin-jointed truss, its supports and joint loads; see
docs/linkage-file.md ("Truss files").

```toml
name = "Roof truss"
[nodes]                                  # NAME = [x, y]
A = ["0 m", "0 m"]
...
[[members]]
between = ["A", "B"]                     # name = "AB" optional (default "A-B")
[[supports]]
node = "A"
kind = "pin"                             # or "roller", with direction = "90 deg"
[[loads]]
node = "C"
force = ["0 kN", "-10 kN"]
```
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from crankdyn.io.files import display_name, load_toml
from crankdyn.io.schema import Table
from crankdyn.linkage.truss import SUPPORT_KINDS, Truss, TrussLoad, TrussSupport

__all__ = ["load_truss", "parse_truss"]


def load_truss(path: str | Path) -> Truss:
    """Load a truss file (TOML; docs/linkage-file.md, ``crankdyn docs linkage-file``).

    Parameters
    ----------
    path
        The truss file.

    Returns
    -------
    crankdyn.linkage.truss.Truss
        The truss, coordinates in m and loads in N.

    Raises
    ------
    InputError
        On an unreadable or malformed file, a missing or unknown key, a value of the wrong
        unit, a reference to an unknown joint, or a truss that is not statically determinate;
        naming the file, the key and the value.
    """
    data = load_toml(Path(path), what="truss file")
    return parse_truss(data, file=display_name(path))


def _pair(t: Table, key: str, kind: str) -> tuple[float, float]:
    x, y = t.quantity_list(key, kind, length=2)
    return x, y


def parse_truss(data: dict[str, Any], *, file: str | None = None) -> Truss:
    """Build a Truss from a parsed truss document (a dict as from tomllib).

    Keys: ``name``; ``[nodes]`` (NAME = [x, y], lengths); ``[[members]]`` (``between``, two
    joints; ``name``); ``[[supports]]`` (``node``, ``kind`` pin or roller, ``direction`` of a
    roller's reaction, an angle, default 90 deg); ``[[loads]]`` (``node``, ``force`` = [F_x,
    F_y]). Quantities as strings with units or bare SI numbers.

    Parameters
    ----------
    data
        The parsed document.
    file
        The file's name for messages.

    Returns
    -------
    crankdyn.linkage.truss.Truss
        The truss, in SI.

    Raises
    ------
    InputError
        As :func:`load_truss`.
    """
    root = Table(data, file=file)
    name = root.string("name", "truss")
    nodes = root.table("nodes", required=True)
    points = {key: _pair(nodes, key, "length") for key in list(nodes.data)}
    if not points:
        raise nodes.error(None, "no joints; give each joint as NAME = [x, y]")
    nodes.finish()
    members, names = [], []
    for t in root.tables("members", required=True):
        a, b = t.string_list("between", length=2)
        members.append((a, b))
        names.append(t.string("name", f"{a}-{b}"))
        t.finish()
    supports = []
    for t in root.tables("supports", required=True):
        node = t.string("node")
        kind = t.string("kind", "pin", choices=SUPPORT_KINDS)
        direction = t.quantity("direction", "angle", None)
        if kind == "pin" and direction is not None:
            raise t.error("direction", "a pin holds its joint in every direction", direction)
        with t.context():
            supports.append(
                TrussSupport(node, kind)
                if direction is None
                else TrussSupport(node, kind, direction)
            )
        t.finish()
    loads = []
    for t in root.tables("loads"):
        node = t.string("node")
        fx, fy = _pair(t, "force", "force")
        with t.context():
            loads.append(TrussLoad(node, (fx, fy)))
        t.finish()
    with root.context():
        truss = Truss(
            tuple(points),
            np.array([points[n] for n in points], dtype=float),
            tuple(members),
            tuple(supports),
            tuple(loads),
            name=name,
            member_names=tuple(names),
            source=file,
        )
    root.finish()
    return truss
