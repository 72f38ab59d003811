"""Distributed-mass shafts: the shaft's own inertia by automatic subdivision (domain).

A uniform shaft of length L, polar second moment of area I_p, shear modulus G and density rho
has the stiffness k = G I_p / L and its own polar moment of inertia J_s = rho I_p L. Torsional
waves travel along it at c = sqrt(G / rho) (the wave equation theta_tt = c^2 theta_xx; e.g.
M. I. Friswell et al., *Dynamics of Rotating Machines*, Cambridge University Press 2010, §9.7,
or S. S. Rao, *Mechanical Vibrations*, ch. 8), so a free-free shaft has the natural frequencies
omega_n = n pi c / L and a shaft fixed at one end omega_n = (2n - 1) pi c / (2 L).

crankdyn divides the shaft into N equal lumped elements: N - 1 new masses J_s / N inside it,
J_s / (2N) added to each end mass, and N springs N k in series (viscous damping N c; the loss
factor unchanged). The mass matrix stays diagonal, so the model keeps its structure (a chain
stays a chain: the tridiagonal solvers, Holzer's method and the transfer matrices still apply).
The lumped chain has the dispersion relation omega = (2 / h) c sin(kappa h / 2) for a wave of
wavenumber kappa on elements of length h = L / N (the monatomic lattice; L. Brillouin, *Wave
Propagation in Periodic Structures*, 1946, ch. 1), so the frequency of a mode of wavenumber
kappa is too low by the factor sin(x)/x, x = kappa h / 2, about x^2 / 6 = (kappa h)^2 / 24.
For the frequencies up to omega_max (kappa = omega_max / c) to be within a relative error eps the
element count is

    N = ceil( L omega_max / (c sqrt(24 eps)) ),   eps = 0.001,

which :func:`element_count` returns (at least 1: one element puts half the shaft's inertia on
each end, the classical lumping). Without the geometry (an inertia given with a stiffness) the
wave speed follows from the same two numbers: L / c = sqrt(J_s / k).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING

from crankdyn.errors import InputError

if TYPE_CHECKING:
    from crankdyn.torsion.elements import Mass, Shaft, ShaftGeometry

__all__ = ["DEFAULT_MAX_FREQUENCY", "TOLERANCE", "element_count", "subdivide", "transit_time"]

DEFAULT_MAX_FREQUENCY = 2.0 * math.pi * 300.0
"""Default frequency (rad/s, 300 Hz) up to which a subdivided shaft's own modes are resolved."""
TOLERANCE = 1e-3
"""Relative frequency error allowed at the frequency target (module docstring)."""


def transit_time(inertia: float, stiffness: float) -> float:
    """L / c = sqrt(J_s / k): the time a torsional wave takes along the shaft (module
    docstring: J_s = rho I_p L and k = G I_p / L give J_s / k = L^2 rho / G = (L / c)^2).

    Parameters
    ----------
    inertia : float
        The shaft's own polar moment of inertia J_s (kg m^2), >= 0.
    stiffness : float
        Its stiffness k (N m/rad), > 0.

    Returns
    -------
    float
        L / c (s).

    Examples
    --------
    A steel shaft, G = 80 GPa and rho = 7850 kg/m^3 (c = 3192 m/s), 1 m long, of I_p = 1e-6 m^4:

    >>> k, j_s = 80e9 * 1e-6 / 1.0, 7850.0 * 1e-6 * 1.0
    >>> round(transit_time(j_s, k) * 1e6, 3)
    313.25
    """
    return math.sqrt(inertia / stiffness)


def element_count(
    inertia: float, stiffness: float, max_frequency: float, tolerance: float = TOLERANCE
) -> int:
    """Elements N for a relative frequency error below ``tolerance`` up to ``max_frequency``:
    N = ceil(omega_max sqrt(J_s/k) / sqrt(24 eps)) (the lattice dispersion, Brillouin 1946
    ch. 1; module docstring).

    Parameters
    ----------
    inertia : float
        The shaft's own polar moment of inertia J_s (kg m^2), >= 0.
    stiffness : float
        Its stiffness k (N m/rad), > 0.
    max_frequency : float
        omega_max (rad/s), the highest frequency to resolve.
    tolerance : float
        eps, the relative frequency error allowed there (dimensionless).

    Returns
    -------
    int
        N >= 1.

    Raises
    ------
    crankdyn.errors.InputError
        More than 10000 elements needed (key ``max_frequency`` and its value).

    Examples
    --------
    The shaft of :func:`transit_time` up to 300 Hz, then up to 3 kHz:

    >>> k, j_s = 80e9 * 1e-6 / 1.0, 7850.0 * 1e-6 * 1.0
    >>> element_count(j_s, k, 2 * math.pi * 300.0), element_count(j_s, k, 2 * math.pi * 3000.0)
    (4, 39)
    """
    n = max_frequency * transit_time(inertia, stiffness) / math.sqrt(24.0 * tolerance)
    if not math.isfinite(n) or n > 10_000:
        raise InputError(
            f"the shaft needs more than 10000 elements to resolve {max_frequency / 2 / math.pi:.6g}"
            " Hz; give elements, or a lower max_frequency",
            key="max_frequency",
            value=max_frequency,
        )
    return max(1, math.ceil(n - 1e-9))


def subdivide(
    masses: Iterable[Mass], shafts: Iterable[Shaft], mass_type: Callable[..., Mass]
) -> tuple[tuple[Mass, ...], tuple[Shaft, ...]]:
    """Masses and shafts with every shaft that carries its own inertia divided into N equal
    lumped elements (module docstring): N - 1 new masses J_s / N, J_s / (2N) added to each end,
    N springs N k (damping N c).

    Parameters
    ----------
    masses : iterable of crankdyn.torsion.elements.Mass
        The model's masses, in order.
    shafts : iterable of crankdyn.torsion.elements.Shaft
        Its shafts; those with ``inertia`` > 0 between known masses are divided into
        ``elements`` (or :func:`element_count` elements for their ``max_frequency``, default
        :data:`DEFAULT_MAX_FREQUENCY`).
    mass_type : callable
        Makes the new masses, ``mass_type(name, inertia, role="shaft")`` (the model's
        :class:`~crankdyn.torsion.elements.Mass`).

    Returns
    -------
    masses : tuple of crankdyn.torsion.elements.Mass
        The masses, the new ones named ``"<shaft> <i>/<N>"`` (the shaft's name, else
        ``"a - b"``) and listed after the first-listed end, in order from it.
    shafts : tuple of crankdyn.torsion.elements.Shaft
        The shafts, each divided shaft replaced by its N elements (``segment_of`` its ends).

    Raises
    ------
    crankdyn.errors.InputError
        A new mass's name that exists (key ``name``), or too many elements
        (:func:`element_count`).

    Examples
    --------
    >>> from crankdyn.torsion.elements import Mass, Shaft
    >>> masses, shafts = subdivide(
    ...     [Mass("a", 1.0), Mass("b", 2.0)],
    ...     [Shaft(("a", "b"), stiffness=1e5, inertia=0.2, elements=2)],
    ...     Mass,
    ... )
    >>> [(m.name, round(m.inertia, 9)) for m in masses]
    [('a', 1.05), ('a - b 1/2', 0.1), ('b', 2.05)]
    >>> [(s.between, s.stiffness) for s in shafts]
    [(('a', 'a - b 1/2'), 200000.0), (('a - b 1/2', 'b'), 200000.0)]
    """
    masses = list(masses)
    position = {m.name: i for i, m in enumerate(masses)}
    added: dict[str, float] = {}
    inserts: dict[str, list[Mass]] = {}
    out_shafts: list[Shaft] = []
    for s in shafts:
        if not s.inertia > 0.0 or any(end not in position for end in s.between):
            out_shafts.append(s)  # unknown ends: the model names them in its own check
            continue
        a, b = s.between
        k = s.stiffness
        assert k is not None  # Shaft.__post_init__ sets it (given or from the geometry)
        n = s.elements
        if n is None:
            target = s.max_frequency if s.max_frequency is not None else DEFAULT_MAX_FREQUENCY
            n = element_count(s.inertia, k, target)
        j_e = s.inertia / n
        base = s.name or f"{a} - {b}"
        nodes = [f"{base} {i}/{n}" for i in range(1, n)]
        for name in nodes:
            if name in position:
                raise InputError(
                    f'the subdivided shaft "{base}" would add a mass named "{name}", which '
                    "exists; rename one of them",
                    key="name",
                    value=name,
                )
        if position[a] > position[b]:  # list the new masses from the first-listed end
            first, chain = b, nodes[::-1]
        else:
            first, chain = a, nodes
        inserts.setdefault(first, []).extend(mass_type(name, j_e, role="shaft") for name in chain)
        for end in (a, b):
            added[end] = added.get(end, 0.0) + 0.5 * j_e
        points = [a, *nodes, b]
        for i in range(n):
            out_shafts.append(
                dataclasses.replace(
                    s,
                    between=(points[i], points[i + 1]),
                    stiffness=k * n,
                    damping=s.damping * n,
                    geometry=_segment_geometry(s.geometry, n),
                    inertia=0.0,
                    elements=None,
                    max_frequency=None,
                    segment_of=s.between,
                )
            )
    if not added:
        return tuple(masses), tuple(out_shafts)
    listed = []
    for m in masses:
        extra = added.get(m.name, 0.0)
        listed.append(dataclasses.replace(m, inertia=m.inertia + extra) if extra else m)
        listed.extend(inserts.get(m.name, ()))
    return tuple(listed), tuple(out_shafts)


def _segment_geometry(geometry: ShaftGeometry | None, n: int) -> ShaftGeometry | None:
    """The cross-section of a segment: the shaft's, with its length divided by n (the segment's
    stiffness is then given, not recomputed: the geometry is kept for the stress)."""
    if geometry is None:
        return None
    length = None if geometry.length is None else geometry.length / n
    return dataclasses.replace(geometry, length=length, shear_modulus=None)
