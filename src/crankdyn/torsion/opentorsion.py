"""Conversion to and from openTorsion (Aalto-Arotor/openTorsion, MIT licence) assemblies.

openTorsion is optional: it is imported only by :func:`to_opentorsion` (and
:func:`from_opentorsion` only reads the attributes of the objects it is given). The element
semantics followed (openTorsion 0.3, ``opentorsion/elements``):

- ``Disk(node, I, c=0, k=0)``: inertia I (kg m^2) at a node with damping c and stiffness k to
  ground -> a crankdyn mass (``"node <i>"``) with that damping, and a grounded shaft of k;
- ``Shaft(nl, nr, L, odl, idl, G, rho, k, I, c)``: stiffness k (given, or G I_p / L with L,
  odl, idl in mm), viscous damping c, and a consistent mass matrix (J_s / 6) [[2, 1], [1, 2]]
  of the shaft's own inertia J_s -> a crankdyn shaft (diameters kept, in m) whose own inertia is
  lumped half on each end node (the one-element lumping of :mod:`crankdyn.torsion.distributed`;
  its frequencies differ from openTorsion's consistent-mass element by O((kappa L)^2), and both
  converge to the continuous shaft as the shaft is divided);
- ``Gear(node, I, R, parent)``: a rigid mesh with the parent gear, the constraint
  R_parent theta_parent + R theta = 0, i.e. the speed ratio n / n_parent = R_parent / R and the
  opposite sense of rotation -> a rigid crankdyn gear ``direction = "opposite"``;
- ``ElasticGear(node, I, R, k, c, parent)``: the mesh stiffness k referred to the parent,
  the energy k (theta_parent + (R / R_parent) theta)^2 / 2 -> an elastic crankdyn gear of
  stiffness k (referred to its first wheel, the parent).
"""

from __future__ import annotations

import importlib
from collections import deque
from typing import Any

from crankdyn.errors import InputError
from crankdyn.torsion.elements import GROUND, Gear, Mass, Shaft, ShaftGeometry
from crankdyn.torsion.model import TorsionModel

__all__ = ["from_opentorsion", "to_opentorsion"]


def _node(i: int) -> str:
    """The crankdyn name of openTorsion node ``i``."""
    return f"node {i}"


def from_opentorsion(assembly: Any, *, name: str = "openTorsion assembly") -> TorsionModel:
    """A :class:`TorsionModel` from an openTorsion ``Assembly`` (module docstring): one mass per
    node, named ``"node <i>"``.

    Only the element attributes are read (``shaft_elements``: ``nl``, ``nr``, ``k``, ``c``,
    ``mass``, ``odl``, ``idl``; ``disk_elements``: ``node``, ``I``, ``c``, ``k``;
    ``gear_elements`` and ``elastic_gear_elements``: ``node``, ``I``, ``R``, ``parent``,
    ``k``, ``c``), so openTorsion need not be installed. Units are openTorsion's SI ones
    (kg m^2, N m/rad, N m s/rad); the diameters ``odl``, ``idl`` are kept as given.

    Parameters
    ----------
    assembly : opentorsion.Assembly
        The assembly, or any object with its element lists.
    name : str
        Name of the model, for reports.

    Returns
    -------
    crankdyn.torsion.model.TorsionModel
        One mass per node in node order: a disk's inertia and damping, half of the own inertia
        of each shaft at the node, a gear's inertia (``role="gear"``); a shaft per ``Shaft``
        element, a grounded shaft per disk stiffness, a rigid gear per ``Gear`` and an elastic
        one per ``ElasticGear`` (ratio R_parent / R, opposite sense).

    Raises
    ------
    crankdyn.errors.InputError
        For an assembly without elements (key ``assembly``), or an element the model refuses
        (its key and value).

    Examples
    --------
    Two disks on a shaft of 10 kN m/rad, the second held to ground by 2 kN m/rad (openTorsion's
    ``Disk(node, I, c, k)`` and ``Shaft(nl, nr, ..., k)`` given here as plain objects):

    >>> from types import SimpleNamespace as Element
    >>> assembly = Element(
    ...     shaft_elements=[Element(nl=0, nr=1, k=1e4, c=0.0, mass=0.0, odl=None)],
    ...     disk_elements=[
    ...         Element(node=0, I=0.4, c=0.0, k=0.0),
    ...         Element(node=1, I=0.7, c=0.1, k=2e3),
    ...     ],
    ... )
    >>> model = from_opentorsion(assembly)
    >>> model.mass_names, [s.label for s in model.shafts]
    (('node 0', 'node 1'), ['node 0 - node 1', 'ground - node 1'])
    >>> model.stiffness_matrix().tolist(), model.damping_matrix().tolist()
    ([[10000.0, -10000.0], [-10000.0, 12000.0]], [[0.0, 0.0], [0.0, 0.1]])
    """
    shafts_in = list(getattr(assembly, "shaft_elements", None) or [])
    disks = list(getattr(assembly, "disk_elements", None) or [])
    gears = list(getattr(assembly, "gear_elements", None) or [])
    elastic = list(getattr(assembly, "elastic_gear_elements", None) or [])
    nodes: set[int] = set()
    for s in shafts_in:
        nodes.update((int(s.nl), int(s.nr)))
    nodes.update(int(d.node) for d in disks)
    nodes.update(int(g.node) for g in gears + elastic)
    if not nodes:
        raise InputError("the assembly has no elements", key="assembly")
    inertia = dict.fromkeys(nodes, 0.0)
    damping = dict.fromkeys(nodes, 0.0)
    ground: dict[int, float] = {}
    for d in disks:
        inertia[int(d.node)] += float(d.I)
        damping[int(d.node)] += float(getattr(d, "c", 0.0) or 0.0)
        k = float(getattr(d, "k", 0.0) or 0.0)
        if k:
            ground[int(d.node)] = ground.get(int(d.node), 0.0) + k
    gear_nodes: set[int] = set()
    for g in gears + elastic:
        inertia[int(g.node)] += float(g.I)
        gear_nodes.add(int(g.node))
    shafts = []
    for s in shafts_in:
        a, b = int(s.nl), int(s.nr)
        own = 6.0 * float(getattr(s, "mass", 0.0) or 0.0)  # M = (J_s / 6) [[2, 1], [1, 2]]
        inertia[a] += 0.5 * own
        inertia[b] += 0.5 * own
        odl = getattr(s, "odl", None)
        geometry = None
        if odl:
            geometry = ShaftGeometry(float(odl), float(getattr(s, "idl", 0.0) or 0.0))
        shafts.append(
            Shaft(
                (_node(a), _node(b)),
                float(s.k),
                damping=float(getattr(s, "c", 0.0) or 0.0),
                geometry=geometry,
            )
        )
    for node, k in ground.items():
        shafts.append(Shaft((GROUND, _node(node)), k))
    meshes = []
    for g in gears:
        if g.parent is not None:
            ratio = float(g.parent.R) / float(g.R)
            meshes.append(Gear((_node(int(g.parent.node)), _node(int(g.node))), ratio))
    for g in elastic:
        if g.parent is not None:
            ratio = float(g.parent.R) / float(g.R)
            meshes.append(
                Gear(
                    (_node(int(g.parent.node)), _node(int(g.node))),
                    ratio,
                    stiffness=float(g.k),
                    damping=float(g.c or 0.0),
                )
            )
    masses = tuple(
        Mass(
            _node(i),
            inertia[i],
            damping=damping[i],
            role="gear" if i in gear_nodes else None,
        )
        for i in sorted(nodes)
    )
    return TorsionModel(masses=masses, shafts=tuple(shafts), gears=tuple(meshes), name=name)


def to_opentorsion(model: TorsionModel, *, hysteretic_frequency: float | None = None) -> Any:
    """An openTorsion ``Assembly`` of the model (module docstring).

    Node i is the model's mass i (listing order), its inertia a ``Disk`` (with its absolute
    damping and any grounded shaft's stiffness), shafts and couplings ``Shaft`` elements of
    their stiffness and viscous damping, rigid meshes ``Gear`` pairs and elastic meshes
    ``ElasticGear`` pairs. Loss factors have no openTorsion counterpart: they are refused
    unless ``hysteretic_frequency`` is given, and then exported as viscous damping
    eta k / omega_h (the same damping torque at omega_h). Dampers and excitation are not
    exported.

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The model.
    hysteretic_frequency : float or None
        Circular frequency omega_h (rad/s) at which loss factors become viscous damping.

    Returns
    -------
    opentorsion.Assembly
        The assembly (SI units, as openTorsion's).

    Raises
    ------
    crankdyn.errors.InputError
        When a shaft has a loss factor and no ``hysteretic_frequency`` is given (key
        ``hysteretic_frequency``, the shaft named in the message).
    ModuleNotFoundError
        Without openTorsion installed.

    Examples
    --------
    >>> assembly = TorsionModel.chain_of([0.4, 0.7], [1e4]).to_opentorsion()  # doctest: +SKIP
    >>> assembly.K  # doctest: +SKIP
    array([[ 10000., -10000.],
           [-10000.,  10000.]])
    """
    # optional and untyped: imported by name, so that the type checker needs neither
    ot: Any = importlib.import_module("opentorsion")

    index = {m.name: i for i, m in enumerate(model.masses)}
    lossy = [s for s in model.shafts if s.loss_factor]
    if lossy and hysteretic_frequency is None:
        raise InputError(
            f'openTorsion has no hysteretic damping and shaft "{lossy[0].label}" has a loss '
            "factor: give hysteretic_frequency to export it as viscous damping eta k / omega",
            key="hysteretic_frequency",
        )
    ground_k: dict[int, float] = {}
    ground_c: dict[int, float] = {}
    shafts = []
    elastic = []
    parents: dict[int, Any] = {}
    for s in model.shafts:
        extra = 0.0
        if s.loss_factor:
            assert hysteretic_frequency is not None  # refused above without it
            extra = s.loss_factor * s.stiffness / hysteretic_frequency
        c = s.damping + extra
        if s.grounded:
            i = index[s.between[1] if s.between[0] == GROUND else s.between[0]]
            ground_k[i] = ground_k.get(i, 0.0) + s.stiffness
            ground_c[i] = ground_c.get(i, 0.0) + c
            continue
        a, b = index[s.between[0]], index[s.between[1]]
        if s.is_mesh:
            if a not in parents:
                parents[a] = ot.ElasticGear(a, 0.0, 1.0)
                elastic.append(parents[a])
            parent = parents[a]
            elastic.append(
                ot.ElasticGear(b, 0.0, parent.R / s.ratio, k=s.stiffness, c=c, parent=parent)
            )
            continue
        shafts.append(ot.Shaft(a, b, None, None, k=s.stiffness, I=0.0, c=c))
    disks = [
        ot.Disk(
            i,
            m.inertia,
            c=m.damping + ground_c.get(i, 0.0),
            k=ground_k.get(i, 0.0),
        )
        for i, m in enumerate(model.masses)
    ]
    gears = _gear_tree(model, index, ot)
    return ot.Assembly(
        shafts,
        disk_elements=disks,
        gear_elements=gears or None,
        elastic_gear_elements=elastic or None,
    )


def _gear_tree(model: TorsionModel, index: dict[str, int], ot: Any) -> list[Any]:
    """openTorsion ``Gear`` objects for the rigid meshes, walked as trees from their first
    wheel (a gear has one parent, so the meshes must not form a loop)."""
    links: dict[int, list[tuple[int, float]]] = {}
    for g in model.gears:
        a, b = index[g.between[0]], index[g.between[1]]
        links.setdefault(a, []).append((b, g.ratio))
        links.setdefault(b, []).append((a, 1.0 / g.ratio))
    made: dict[int, Any] = {}
    out = []
    for root in links:
        if root in made:
            continue
        made[root] = ot.Gear(root, 0.0, 1.0)
        out.append(made[root])
        queue = deque([root])
        while queue:
            p = queue.popleft()
            for c, ratio in links[p]:  # ratio = n_c / n_p = R_p / R_c
                if c in made:
                    continue
                made[c] = ot.Gear(c, 0.0, made[p].R / ratio, parent=made[p])
                out.append(made[c])
                queue.append(c)
    return out
