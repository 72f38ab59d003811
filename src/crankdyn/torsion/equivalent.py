"""The equivalent torsional system of an engine's crank throws (domain).

Each crank throw becomes one mass of the lumped model (seed 003, "扭振当量系统的组成": the
equivalent inertia sits where the real shaft carries its masses), and each crank span between
neighbouring throws one shaft.

Inertia of a throw
    J_throw = sum over its cylinders of (m_r + m_j / 2) R^2 + J_crank,
    with the rotating mass m_r and reciprocating mass m_j of each cylinder (seed 000 section 2.1,
    :func:`crankdyn.crank.masses.equivalent_mass_model`), the crank radius R and the crank's own
    inertia J_crank (journal, webs and pin about the shaft axis). The reciprocating mass enters with
    the mean of m_j (dx/dphi)^2 over a revolution, m_j R^2 (1/2 + lambda^2/8); the lambda^2/8 term
    (lambda^2/4 of the whole, 2-3 % for lambda near 0.3) is dropped, as in the classical
    equivalent system (W. Ker Wilson, *Practical Solution of Torsional Vibration Problems*,
    vol. 1, ch. 3; seed 003). On a V-engine
    throw carrying two rods the crank's unbalance m_k is counted once: each cylinder's rotating
    mass is m_k / 2 + m_CB (:func:`crankdyn.crank.masses.equivalent_mass_model`).

Stiffness of a crank span
    Given directly, or from the throw's dimensions by Carter's empirical formula for the length
    l_e of plain shaft of the journal's section that twists as much as one crank span
    (B. C. Carter, "An empirical formula for crankshaft stiffness in torsion", Engineering 126
    (1928) 36; quoted in Ker Wilson, vol. 1, and J. P. Den Hartog, *Mechanical Vibrations*,
    4th ed., 1956)::

        l_e / (D_j^4 - d_j^4) = (l_j + 0.8 h) / (D_j^4 - d_j^4)
                                + 0.75 l_p / (D_p^4 - d_p^4) + 1.5 R / (h b^3)
        k = G pi (D_j^4 - d_j^4) / (32 l_e)
          = (pi G / 32) / [(l_j + 0.8 h)/(D_j^4 - d_j^4) + 0.75 l_p/(D_p^4 - d_p^4) + 1.5 R/(h b^3)]

    with the journal diameter D_j, bore d_j and length l_j, the pin diameter D_p, bore d_p and
    length l_p, the web thickness h (axial) and width b, and the crank radius R. It is an
    empirical estimate for conventional crankshafts; a measured or FE stiffness is better.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from crankdyn.crank.geometry import check_finite, check_positive
from crankdyn.crank.masses import equivalent_mass_model
from crankdyn.errors import InputError
from crankdyn.torsion.elements import Gear, Mass, Shaft, ShaftGeometry
from crankdyn.torsion.model import TorsionModel

if TYPE_CHECKING:  # pragma: no cover
    from crankdyn.crank.geometry import CrankGeometry
    from crankdyn.crank.masses import Masses
    from crankdyn.engine.model import Cylinders

__all__ = [
    "CrankThrowGeometry",
    "ThrowSpec",
    "carter_throw_stiffness",
    "equivalent_system",
    "throw_inertias",
    "throw_name",
]


def throw_name(number: int) -> str:
    """Name of the mass of a crank throw.

    Parameters
    ----------
    number : int
        The throw, 1-based, from the free end.

    Returns
    -------
    str
        ``"throw N"``.

    Examples
    --------
    >>> throw_name(3)
    'throw 3'
    """
    return f"throw {number}"


@dataclass(frozen=True)
class CrankThrowGeometry:
    """Dimensions of one crank span for Carter's formula (m, Pa).

    Parameters
    ----------
    journal_diameter, journal_bore, journal_length : float
        Main journal outer diameter D_j, bore d_j (0 for solid) and length l_j (m).
    pin_diameter, pin_bore, pin_length : float
        Crank pin outer diameter D_p, bore d_p and length l_p (m).
    web_thickness, web_width : float
        Web thickness h (along the shaft axis) and width b (m).
    shear_modulus : float
        Shear modulus G of the crankshaft material (Pa).

    Raises
    ------
    crankdyn.errors.InputError
        A dimension or modulus not positive, or a bore not between 0 and its diameter (names
        the key and value).
    """

    journal_diameter: float
    journal_length: float
    pin_diameter: float
    pin_length: float
    web_thickness: float
    web_width: float
    shear_modulus: float
    journal_bore: float = 0.0
    pin_bore: float = 0.0

    def __post_init__(self) -> None:
        for name in (
            "journal_diameter",
            "journal_length",
            "pin_diameter",
            "pin_length",
            "web_thickness",
            "web_width",
            "shear_modulus",
        ):
            object.__setattr__(self, name, check_positive(name, getattr(self, name)))
        for bore, outer in (("journal_bore", "journal_diameter"), ("pin_bore", "pin_diameter")):
            value = check_finite(bore, getattr(self, bore))
            if not 0.0 <= value < getattr(self, outer):
                raise InputError(
                    f"the bore must lie between 0 and the {outer.replace('_', ' ')} "
                    f"({getattr(self, outer) * 1e3:.6g} mm)",
                    key=bore,
                    value=getattr(self, bore),
                )
            object.__setattr__(self, bore, value)

    @property
    def journal_section(self) -> ShaftGeometry:
        """The journal's cross-section (for nominal shear stress)."""
        return ShaftGeometry(self.journal_diameter, self.journal_bore)


def carter_throw_stiffness(crank_radius: float, g: CrankThrowGeometry) -> float:
    """Torsional stiffness of one crank span by Carter's formula (N m/rad).

    k = (pi G / 32) / [(l_j + 0.8 h)/(D_j^4 - d_j^4) + 0.75 l_p/(D_p^4 - d_p^4) + 1.5 R/(h b^3)]
    (Carter 1928; see the module docstring for the symbols and sources).

    Parameters
    ----------
    crank_radius : float
        Crank radius R (m).
    g : CrankThrowGeometry
        The span's dimensions (m) and shear modulus (Pa).

    Returns
    -------
    float
        k (N m/rad).

    Examples
    --------
    >>> span = CrankThrowGeometry(journal_diameter=0.1, journal_length=0.05, pin_diameter=0.08,
    ...                           pin_length=0.04, web_thickness=0.025, web_width=0.12,
    ...                           shear_modulus=80e9)
    >>> f"{carter_throw_stiffness(0.06, span):.6g}"
    '2.23394e+06'
    """
    journal = g.journal_diameter**4 - g.journal_bore**4
    pin = g.pin_diameter**4 - g.pin_bore**4
    compliance = (
        (g.journal_length + 0.8 * g.web_thickness) / journal
        + 0.75 * g.pin_length / pin
        + 1.5 * crank_radius / (g.web_thickness * g.web_width**3)
    )
    return math.pi * g.shear_modulus / 32.0 / compliance


@dataclass(frozen=True)
class ThrowSpec:
    """How the crank throws enter the equivalent system.

    Parameters
    ----------
    crank_inertia : float
        The crank's own inertia per throw (journal, webs and pin) J_crank (kg m^2), >= 0.
    stiffness : float or None
        Stiffness of a crank span between neighbouring throws (N m/rad); or None with
        ``geometry`` (Carter's formula).
    geometry : CrankThrowGeometry or None
        Crank-span dimensions for Carter's formula.
    damping : float
        Absolute damping at every throw (N m s/rad), >= 0.
    shaft_damping : float
        Relative viscous damping of every crank span (N m s/rad), >= 0.
    loss_factor : float
        Loss factor of every crank span (dimensionless), >= 0.

    Raises
    ------
    crankdyn.errors.InputError
        A negative inertia or damping, a stiffness not positive, or both or neither of
        ``stiffness`` and ``geometry`` (names the key and value).
    """

    crank_inertia: float
    stiffness: float | None = None
    geometry: CrankThrowGeometry | None = None
    damping: float = 0.0
    shaft_damping: float = 0.0
    loss_factor: float = 0.0

    def __post_init__(self) -> None:
        value = check_finite("inertia", self.crank_inertia)
        if value < 0.0:
            raise InputError("the crank's inertia must not be negative", key="inertia", value=value)
        object.__setattr__(self, "crank_inertia", value)
        if (self.stiffness is None) == (self.geometry is None):
            raise InputError(
                "give the crank span's stiffness or its dimensions (Carter's formula), "
                "not both or neither",
                key="stiffness",
            )
        if self.stiffness is not None:
            object.__setattr__(
                self, "stiffness", check_positive("stiffness", self.stiffness, "the stiffness")
            )
        for name in ("damping", "shaft_damping", "loss_factor"):
            v = check_finite(name, getattr(self, name))
            if v < 0.0:
                raise InputError("must not be negative", key=name, value=v)
            object.__setattr__(self, name, v)

    def span_stiffness(self, crank_radius: float) -> float:
        """Stiffness of one crank span: given, or by Carter's formula
        (:func:`carter_throw_stiffness`).

        Parameters
        ----------
        crank_radius : float
            Crank radius R (m), for Carter's formula.

        Returns
        -------
        float
            k (N m/rad).

        Examples
        --------
        >>> ThrowSpec(0.5, stiffness=1.0e6).span_stiffness(0.06)
        1000000.0
        """
        if self.stiffness is not None:
            return self.stiffness
        assert self.geometry is not None  # one of the two (__post_init__)
        return carter_throw_stiffness(crank_radius, self.geometry)


def throw_inertias(
    geometry: CrankGeometry, cylinders: Cylinders, masses: Masses, crank_inertia: float
) -> NDArray[np.float64]:
    """Equivalent moment of inertia of every crank throw, throw 1 first.

    J_t = R^2 sum over the throw's n_t cylinders of (m_r + m_j / 2) + J_crank, with each
    cylinder's m_j and m_r from :func:`crankdyn.crank.masses.equivalent_mass_model` for n_t rods on
    the throw (so the crank's unbalance m_k is counted once per throw; seed 000 section 2.1,
    seed 003; Ker Wilson vol. 1 ch. 3; see the module docstring).

    Parameters
    ----------
    geometry : crankdyn.crank.geometry.CrankGeometry
        Crank radius R and rod length (m).
    cylinders : crankdyn.engine.model.Cylinders
        The cylinders and the throw each acts on.
    masses : crankdyn.crank.masses.Masses
        The running-gear masses of one cylinder (kg).
    crank_inertia : float
        The crank's own inertia per throw J_crank (kg m^2).

    Returns
    -------
    numpy.ndarray
        J_t (kg m^2), shape (throws,).
    """
    counts = np.bincount(np.asarray(cylinders.throws) - 1, minlength=cylinders.throw_count)
    out = np.empty(counts.size)
    for t, n in enumerate(counts):
        eq = equivalent_mass_model(masses, geometry.rod_length, rods_per_throw=int(n))
        out[t] = n * (eq.rotating + eq.reciprocating / 2.0)
    return geometry.crank_radius**2 * out + crank_inertia


def equivalent_system(
    geometry: CrankGeometry,
    cylinders: Cylinders,
    masses: Masses,
    throws: ThrowSpec,
    *,
    other_masses: tuple[Mass, ...] = (),
    shafts: tuple[Shaft, ...] = (),
    gears: tuple[Gear, ...] = (),
    name: str = "equivalent system",
    source: str | None = None,
) -> TorsionModel:
    """The engine's equivalent torsional system: one mass per crank throw (named
    ``"throw 1"`` ... from the free end, carrying its cylinders), crank spans between them, and
    the other masses (pulley, damper, flywheel, driven machine...) with the shafts and gears
    that join them to the throws by name.

    The throws are listed after the mass that a shaft joins to throw 1 (the free-end side), or
    first when no listed mass is joined to throw 1. Inertias by :func:`throw_inertias`, span
    stiffnesses by :meth:`ThrowSpec.span_stiffness` (seed 003; module docstring).

    Parameters
    ----------
    geometry : crankdyn.crank.geometry.CrankGeometry
        The engine's crank geometry (m).
    cylinders : crankdyn.engine.model.Cylinders
        Its cylinders and their throws.
    masses : crankdyn.crank.masses.Masses
        The running-gear masses of one cylinder (kg).
    throws : ThrowSpec
        Crank inertia, span stiffness (or dimensions) and damping of the throws.
    other_masses : tuple of crankdyn.torsion.elements.Mass
        The other masses of the line (pulley, damper, flywheel, driven machine...).
    shafts : tuple of crankdyn.torsion.elements.Shaft
        The shafts joining them to the throws and to each other.
    gears : tuple of crankdyn.torsion.elements.Gear
        Gears of the line.
    name : str
        The model's name.
    source : str or None
        The file it came from, for messages.

    Returns
    -------
    crankdyn.torsion.model.TorsionModel
        The equivalent system.

    Raises
    ------
    crankdyn.errors.InputError
        The errors of :class:`~crankdyn.torsion.model.TorsionModel` (e.g. a shaft naming an
        unknown mass).
    """
    inertias = throw_inertias(geometry, cylinders, masses, throws.crank_inertia)
    count = cylinders.throw_count
    on_throw = [
        tuple(c + 1 for c in range(cylinders.count) if cylinders.throws[c] == t)
        for t in range(1, count + 1)
    ]
    throw_masses = [
        Mass(throw_name(t + 1), float(inertias[t]), throws.damping, on_throw[t], role="crank throw")
        for t in range(count)
    ]
    k = throws.span_stiffness(geometry.crank_radius)
    section = throws.geometry.journal_section if throws.geometry is not None else None
    spans = tuple(
        Shaft(
            (throw_name(t), throw_name(t + 1)),
            k,
            damping=throws.shaft_damping,
            loss_factor=throws.loss_factor,
            geometry=section,
            role="crankshaft",
        )
        for t in range(1, count)
    )
    first = throw_name(1)
    before = 0
    for s in shafts:
        if first in s.between:
            other = s.between[1] if s.between[0] == first else s.between[0]
            for i, m in enumerate(other_masses):
                if m.name == other:
                    before = i + 1
                    break
            break
    listed = tuple(other_masses[:before]) + tuple(throw_masses) + tuple(other_masses[before:])
    return TorsionModel(
        masses=listed,
        shafts=spans + tuple(shafts),
        gears=tuple(gears),
        name=name,
        source=source,
    )
