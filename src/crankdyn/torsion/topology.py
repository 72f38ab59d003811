"""The topology of a lumped torsional model: degrees of freedom, speed ratios and chain order
(domain).

Gears and reflection. A mass turning at ``r`` times the reference speed (the speed of the first
mass that carries a cylinder, else of the first mass: :func:`reference_mass`) enters the
equations reflected to the reference speed (W. Ker Wilson, *Practical Solution of Torsional
Vibration Problems*, vol. 1, ch. 3, "equivalent systems of geared drives";
:mod:`crankdyn.torsion.model`). The signed speed ratios follow from a breadth-first walk over
the shafts (ratio 1, or a coupling's own) and the gear meshes (ratio r and sense) from the
reference mass; a loop whose ratios or senses disagree is refused. A gear mesh is rigid, so the
two meshing masses become one degree of freedom.

Structure. After merging the meshing masses, a model whose shafts join its degrees of freedom
in a single line is a *chain*, its degrees of freedom numbered in chain order from the first
end; any other (branched or looped) model keeps the listing order and names a junction for
messages (:func:`model_structure`).
"""

from __future__ import annotations

from collections import deque
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from crankdyn.errors import InputError
from crankdyn.torsion.elements import GROUND, Gear, Mass, Shaft

if TYPE_CHECKING:
    from crankdyn.torsion.model import TorsionModel

__all__ = ["Structure", "model_structure", "reference_mass"]

_RATIO_TOL = 1e-9
"""Relative tolerance of two speed ratios of one mass found around a loop."""


@dataclass(frozen=True)
class Structure:
    """The topology of a model (:func:`model_structure`).

    Parameters
    ----------
    speed_ratio : numpy.ndarray
        Speed of every mass over the reference speed (dimensionless, > 0), shape (masses,).
    rotation : numpy.ndarray
        Sense of rotation of every mass relative to the reference mass (+1 or -1), shape
        (masses,).
    mass_dof : numpy.ndarray
        Degree of freedom of every mass (meshing masses share one), int, shape (masses,).
    dofs : tuple of tuple of int
        The mass indices of every degree of freedom, in chain order for a chain.
    shaft_dofs : numpy.ndarray
        Degrees of freedom at the ends of every shaft, -1 for ground, int, shape (shafts, 2).
    is_chain : bool
        Whether the shafts join the degrees of freedom in a single line.
    junction : str or None
        A mass where a branched model branches (for messages), or None.
    """

    speed_ratio: np.ndarray
    rotation: np.ndarray
    mass_dof: np.ndarray
    dofs: tuple[tuple[int, ...], ...]
    shaft_dofs: np.ndarray
    is_chain: bool
    junction: str | None


def reference_mass(masses: Sequence[Mass]) -> int:
    """The mass whose speed is the reference speed (module docstring).

    Parameters
    ----------
    masses : sequence of Mass
        The model's masses in listing order.

    Returns
    -------
    int
        Index of the first mass that carries a cylinder, else 0.

    Examples
    --------
    >>> reference_mass([Mass("pulley", 0.1), Mass("throw 1", 1.0, cylinders=(1,))])
    1
    """
    for i, m in enumerate(masses):
        if m.cylinders:
            return i
    return 0


def model_structure(model: TorsionModel) -> Structure:
    """The model's topology: degrees of freedom (rigid meshes merged), signed speed ratios (a
    breadth-first walk from the reference mass), chain order or a junction (module docstring).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The model (its masses, shafts and rigid gears; the constructor calls this).

    Returns
    -------
    Structure
        Speed ratios and senses of rotation, degrees of freedom, whether it is a chain.

    Raises
    ------
    crankdyn.errors.InputError
        For gear ratios or senses that disagree around a loop, a shaft between two masses a
        gear already ties together (``between``) or a disconnected model.

    Examples
    --------
    A flywheel, a gearbox 3:1 (one degree of freedom for both wheels) and a propeller:

    >>> from crankdyn.torsion.model import TorsionModel
    >>> model = TorsionModel(
    ...     masses=(Mass("flywheel", 10.0), Mass("pinion", 0.5), Mass("wheel", 4.0),
    ...             Mass("propeller", 90.0)),
    ...     shafts=(Shaft(("flywheel", "pinion"), 1e6), Shaft(("wheel", "propeller"), 9e6)),
    ...     gears=(Gear(("pinion", "wheel"), 1 / 3),),
    ... )
    >>> found = model_structure(model)
    >>> found.dofs, found.is_chain, [round(float(r), 6) for r in found.speed_ratio]
    (((0,), (1, 2), (3,)), True, [1.0, 1.0, 0.333333, 0.333333])
    """
    masses, shafts, gears = model.masses, model.shafts, model.gears
    n = len(masses)
    index = {m.name: i for i, m in enumerate(masses)}
    group_of, groups = _gear_groups(n, gears, index)
    tied = next(  # a shaft inside a rigid gear group: reported before a sense conflict
        (
            s
            for s in shafts
            if not s.grounded and group_of[index[s.between[0]]] == group_of[index[s.between[1]]]
        ),
        None,
    )
    ref = reference_mass(masses)
    found = _signed_ratios(masses, shafts, gears, index, ref, tied)
    signed = np.array([np.nan if r is None else r for r in found], dtype=float)
    ratio = np.abs(signed)
    rotation = np.where(signed < 0.0, -1.0, 1.0)
    lost = [masses[i].name for i in range(n) if found[i] is None]
    if lost:
        more = f" and {len(lost) - 1} more" if len(lost) > 1 else ""
        raise InputError(
            f'the model is disconnected: no shaft or gear joins "{lost[0]}"{more} to '
            f'"{masses[ref].name}"',
        )
    is_chain, order, junction = _chain_order(masses, shafts, groups, group_of, index)
    dofs = tuple(tuple(groups[old]) for old in order)
    dof_of = [0] * n
    for d, members in enumerate(dofs):
        for i in members:
            dof_of[i] = d
    mass_dof = np.array(dof_of, dtype=int)
    shaft_dofs = np.array(
        [[-1 if end == GROUND else dof_of[index[end]] for end in s.between] for s in shafts],
        dtype=int,
    ).reshape(len(shafts), 2)
    mass_dof.setflags(write=False)
    shaft_dofs.setflags(write=False)
    ratio.setflags(write=False)
    rotation.setflags(write=False)
    return Structure(
        speed_ratio=ratio,
        rotation=rotation,
        mass_dof=mass_dof,
        dofs=dofs,
        shaft_dofs=shaft_dofs,
        is_chain=is_chain,
        junction=junction,
    )


def _gear_groups(
    n: int, gears: Sequence[Gear], index: dict[str, int]
) -> tuple[list[int], list[list[int]]]:
    """(group of every mass, the masses of every group): masses tied by rigid gear meshes are
    one degree of freedom (union-find), groups numbered by their first mass."""
    parent = list(range(n))

    def find(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for g in gears:
        a, b = find(index[g.between[0]]), find(index[g.between[1]])
        if a != b:
            parent[max(a, b)] = min(a, b)
    if gears:
        roots = sorted({find(i) for i in range(n)})
        provisional = {r: k for k, r in enumerate(roots)}
        group_of = [provisional[find(i)] for i in range(n)]
        groups: list[list[int]] = [[] for _ in roots]
        for i in range(n):
            groups[group_of[i]].append(i)
    else:  # every mass is its own degree of freedom
        group_of = list(range(n))
        groups = [[i] for i in range(n)]
    return group_of, groups


def _signed_ratios(
    masses: Sequence[Mass],
    shafts: Sequence[Shaft],
    gears: Sequence[Gear],
    index: dict[str, int],
    ref: int,
    tied: Shaft | None,
) -> list[float | None]:
    """Signed speed ratio of every mass (None where the walk does not reach it) by a
    breadth-first walk from the reference mass over shafts (ratio 1) and gears (ratio r): the
    sense of rotation travels with the ratio. InputError where a loop disagrees (a shaft
    ``tied`` inside a rigid gear group reported first)."""
    # the neighbour lists name the joining element by (kind, index) and its label is written
    # only for a message
    n = len(masses)
    neighbours: list[list[tuple[int, float, str, int]]] = [[] for _ in range(n)]
    for i_s, s in enumerate(shafts):
        if s.grounded:
            continue
        a, b = index[s.between[0]], index[s.between[1]]
        neighbours[a].append((b, s.ratio * s.direction, "shaft", i_s))
        neighbours[b].append((a, s.direction / s.ratio, "shaft", i_s))
    for i_g, g in enumerate(gears):
        a, b = index[g.between[0]], index[g.between[1]]
        neighbours[a].append((b, g.ratio * g.sign, "gear", i_g))
        neighbours[b].append((a, g.sign / g.ratio, "gear", i_g))
    found: list[float | None] = [None] * n
    found[ref] = 1.0
    queue = deque([ref])
    while queue:
        i = queue.popleft()
        here = found[i]
        assert here is not None  # queued once found
        for j, r, kind, k in neighbours[i]:
            value = here * r
            there = found[j]
            if there is None:
                found[j] = value
                queue.append(j)
            elif abs(there - value) > _RATIO_TOL * max(abs(there), abs(value)):
                if kind == "shaft":
                    label = f'shaft "{shafts[k].label}"'
                else:
                    label = f'gear "{gears[k].between[0]}" - "{gears[k].between[1]}"'
                magnitude = abs(abs(there) - abs(value)) > _RATIO_TOL * max(abs(there), abs(value))
                if not magnitude and tied is not None:
                    raise InputError(
                        f'shaft "{tied.label}" joins two masses that a gear mesh already ties '
                        "together",
                        key="between",
                        value=list(tied.between),
                    )
                what = (
                    "the gear ratios disagree"
                    if magnitude
                    else "the gears' senses of rotation disagree"
                )
                raise InputError(
                    f'the speed of "{masses[j].name}" comes out as {there:.6g} and as '
                    f"{value:.6g} times the reference speed around a loop through the {label}: "
                    f"{what}",
                )
    return found


def _chain_order(
    masses: Sequence[Mass],
    shafts: Sequence[Shaft],
    groups: list[list[int]],
    group_of: list[int],
    index: dict[str, int],
) -> tuple[bool, list[int], str | None]:
    """(is_chain, order of the groups, junction): a chain's groups from its first end, any
    other model's in listing order with the mass where it branches. InputError for a shaft
    between two masses of one rigid gear group."""
    edges: set[tuple[int, int]] = set()
    for s in shafts:
        if s.grounded:
            continue
        a = group_of[index[s.between[0]]]
        b = group_of[index[s.between[1]]]
        if a == b:
            raise InputError(
                f'shaft "{s.label}" joins two masses that a gear mesh already ties together',
                key="between",
                value=list(s.between),
            )
        edges.add((min(a, b), max(a, b)))
    m = len(groups)
    degree = [0] * m
    adjacency: list[list[int]] = [[] for _ in range(m)]
    for a, b in sorted(edges):
        degree[a] += 1
        degree[b] += 1
        adjacency[a].append(b)
        adjacency[b].append(a)
    is_chain = m == 1 or (len(edges) == m - 1 and max(degree) <= 2)
    junction = None
    if is_chain and m > 1:
        start = degree.index(1)  # the first end of the chain
        order = [start]
        previous = -1
        while len(order) < m:
            here = order[-1]
            step = next(j for j in adjacency[here] if j != previous)
            previous = here
            order.append(step)
    else:
        order = list(range(m))
        if m > 1:
            branch = degree.index(max(degree))
            junction = masses[groups[branch][0]].name if degree[branch] > 2 else None
    return is_chain, order, junction
