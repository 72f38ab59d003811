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

import contextlib
import importlib
import math
import numbers
from collections import deque
from collections.abc import Iterator
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
        For an assembly without elements (key ``assembly``); a node number that is not a whole
        number >= 0, a value that is not a finite number >= 0, a gear radius of zero, or an
        element the model refuses; naming the element (``disk_elements[2].node``) and value.

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
    shafts_in = _elements(assembly, "shaft_elements")
    disks = _elements(assembly, "disk_elements")
    gears = _elements(assembly, "gear_elements")
    elastic = _elements(assembly, "elastic_gear_elements")
    nodes: set[int] = set()
    for key, s in shafts_in:
        nodes.update((_node_number(s.nl, f"{key}.nl"), _node_number(s.nr, f"{key}.nr")))
    nodes.update(_node_number(d.node, f"{key}.node") for key, d in disks)
    nodes.update(_node_number(g.node, f"{key}.node") for key, g in gears + elastic)
    if not nodes:
        raise InputError("the assembly has no elements", key="assembly")
    inertia = dict.fromkeys(nodes, 0.0)
    damping = dict.fromkeys(nodes, 0.0)
    ground: dict[int, float] = {}
    for key, d in disks:
        node = _node_number(d.node, f"{key}.node")
        inertia[node] += _real(d.I, f"{key}.I")
        damping[node] += _real(getattr(d, "c", 0.0), f"{key}.c")
        k = _real(getattr(d, "k", 0.0), f"{key}.k")
        if k:
            ground[node] = ground.get(node, 0.0) + k
    gear_nodes: set[int] = set()
    for key, g in gears + elastic:
        node = _node_number(g.node, f"{key}.node")
        inertia[node] += _real(g.I, f"{key}.I")
        gear_nodes.add(node)
    shafts = []
    for key, s in shafts_in:
        a, b = _node_number(s.nl, f"{key}.nl"), _node_number(s.nr, f"{key}.nr")
        own = 6.0 * _real(getattr(s, "mass", 0.0), f"{key}.mass")  # M = (J_s/6) [[2,1],[1,2]]
        inertia[a] += 0.5 * own
        inertia[b] += 0.5 * own
        odl = getattr(s, "odl", None)
        geometry = None
        if odl:
            geometry = ShaftGeometry(
                _real(odl, f"{key}.odl"), _real(getattr(s, "idl", 0.0), f"{key}.idl")
            )
        with _element(key):
            shafts.append(
                Shaft(
                    (_node(a), _node(b)),
                    _real(s.k, f"{key}.k"),
                    damping=_real(getattr(s, "c", 0.0), f"{key}.c"),
                    geometry=geometry,
                )
            )
    for node, k in ground.items():
        shafts.append(Shaft((GROUND, _node(node)), k))
    meshes = []
    for key, g in gears + elastic:
        if g.parent is None:
            continue
        parent = _node_number(g.parent.node, f"{key}.parent.node")
        ratio = _radius(g.parent.R, f"{key}.parent.R") / _radius(g.R, f"{key}.R")
        stiffness = _real(g.k, f"{key}.k") if key.startswith("elastic") else None
        with _element(key):
            meshes.append(
                Gear(
                    (_node(parent), _node(_node_number(g.node, f"{key}.node"))),
                    ratio,
                    stiffness=stiffness,
                    damping=0.0 if stiffness is None else _real(g.c, f"{key}.c"),
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


def _elements(assembly: Any, name: str) -> list[tuple[str, Any]]:
    """The elements of one list of the assembly, each with its key for messages
    (``disk_elements[2]``)."""
    items = getattr(assembly, name, None) or []
    try:
        return [(f"{name}[{i}]", item) for i, item in enumerate(items)]
    except TypeError:
        raise InputError("expected a list of elements", key=name) from None


def _shown(value: object) -> object:
    """A value for a message: numpy scalars as Python numbers."""
    item = getattr(value, "item", None)
    return item() if callable(item) and getattr(value, "ndim", None) == 0 else value


def _is_number(value: object) -> bool:
    """Whether ``value`` is a real number (Python's or numpy's), not a bool or a text."""
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


def _node_number(value: object, key: str) -> int:
    """An openTorsion node number: a whole number >= 0 (1.5 was truncated to node 1, -1 taken
    for the last node), else an InputError naming the element's key and the value."""
    number = float(value) if _is_number(value) else math.nan  # type: ignore[arg-type]
    if not (number.is_integer() and number >= 0):
        raise InputError(
            "expected a node number, a whole number >= 0", key=key, value=_shown(value)
        )
    return int(number)


def _real(value: object, key: str) -> float:
    """A finite number (SI, as openTorsion's; None counts as 0), else an InputError; the sign
    is checked by the element that takes it (a negative inertia, stiffness or damping)."""
    if value is None:
        return 0.0
    if not _is_number(value):
        raise InputError("expected a number", key=key, value=_shown(value))
    number = float(value)  # type: ignore[arg-type]
    if not math.isfinite(number):
        raise InputError("the value is not finite", key=key, value=_shown(value))
    if number < 0.0:
        raise InputError("must not be negative", key=key, value=_shown(value))
    return number


def _radius(value: object, key: str) -> float:
    """A gear's pitch radius R (m, or any unit common to the meshing gears): positive (a zero
    radius divided the speed ratio by zero)."""
    radius = _real(value, key)
    if radius == 0.0:
        raise InputError(
            "a gear's radius must be positive (the speed ratio is R_parent / R)",
            key=key,
            value=_shown(value),
        )
    return radius


@contextlib.contextmanager
def _element(key: str) -> Iterator[None]:
    """Errors of the crankdyn element made from openTorsion element ``key`` name it."""
    try:
        yield
    except InputError as exc:
        where = f"{key}: {exc.key}" if exc.key else key
        if exc.has_value:
            raise InputError(exc.message, key=where, value=exc.value) from None
        raise InputError(exc.message, key=where) from None


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
