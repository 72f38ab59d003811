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

A finer system: journals and webs as two inertias and a spring (seed 003)
    Seed 003 ("发动机曲轴系统扭转振动建模与实测分析", 1.1 建模, 图 1 and 图 2): in the lumped model
    every part of the crankshaft (main journal 主轴颈, crank web 曲柄臂, the crankshaft's front
    end) of moment of inertia J and torsional stiffness k becomes two equal inertias J/2 joined
    by a spring k. Here each crank span between throws t and t + 1 is, in order, a web, the main
    journal, a web: with the journal's inertia J_j and the web's J_w, the chain::

        throw t -[k_w]- (J_w/2 + J_j/2) -[k_j]- (J_j/2 + J_w/2) -[k_w]- throw t + 1,

    each throw keeping its crank pin (J_p), its running gear R^2 sum (m_r + m_j/2) and the halves
    of the webs beside it. The crank's own inertia per throw splits as J_crank = J_p + 2 J_w + J_j
    (one journal per throw): the end throws keep, lumped as before, the parts outside the
    refined spans (an outer web and half an end journal each, J_w + J_j/2), so that both systems
    hold the same inertia. The stiffnesses split Carter's compliance term by term (the seed's
    own formulas are not in its extracted text; Carter's terms are the journal's, the pin's and
    the webs')::

        1/k_j = (32 / (pi G)) (l_j + 0.8 h) / (D_j^4 - d_j^4)
        1/k_w = (32 / (pi G)) [0.75 R / (h b^3) + 0.375 l_p / (D_p^4 - d_p^4)]

    (each web's spring carries its own bending-twist and half the pin's twist, the pin being one
    mass), so that 1/k_j + 2/k_w = 1/k_span: the finer span is exactly as stiff as the one-mass
    system's between two throws. Or the two stiffnesses are given. The span's loss factor
    applies to each spring (a chain of springs of one loss factor has that loss factor), its
    relative viscous damping c splits as c k_part / k_span (proportional damping in series is
    again proportional); the journal's spring carries the journal's section (the stress at the
    journal, where seed 003's V6 paper measured the torques).
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
    "ThrowParts",
    "ThrowSpec",
    "carter_part_stiffnesses",
    "carter_throw_stiffness",
    "equivalent_system",
    "journal_names",
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


def carter_part_stiffnesses(crank_radius: float, g: CrankThrowGeometry) -> tuple[float, float]:
    """The stiffnesses of a crank span's journal and of each web by Carter's terms (module
    docstring, "A finer system"; Carter 1928, seed 003).

    1/k_j = (32/(pi G)) (l_j + 0.8 h)/(D_j^4 - d_j^4),
    1/k_w = (32/(pi G)) [0.75 R/(h b^3) + 0.375 l_p/(D_p^4 - d_p^4)], so that
    1/k_j + 2/k_w is the span's compliance by :func:`carter_throw_stiffness`.

    Parameters
    ----------
    crank_radius : float
        Crank radius R (m).
    g : CrankThrowGeometry
        The span's dimensions (m) and shear modulus (Pa).

    Returns
    -------
    tuple of float
        (k_j, k_w) (N m/rad).

    Examples
    --------
    >>> span = CrankThrowGeometry(journal_diameter=0.1, journal_length=0.05, pin_diameter=0.08,
    ...                           pin_length=0.04, web_thickness=0.025, web_width=0.12,
    ...                           shear_modulus=80e9)
    >>> k_j, k_w = carter_part_stiffnesses(0.06, span)
    >>> round(1 / (1 / k_j + 2 / k_w) / carter_throw_stiffness(0.06, span), 12)
    1.0
    """
    factor = 32.0 / (math.pi * g.shear_modulus)
    journal = g.journal_diameter**4 - g.journal_bore**4
    pin = g.pin_diameter**4 - g.pin_bore**4
    c_j = factor * (g.journal_length + 0.8 * g.web_thickness) / journal
    c_w = factor * (
        0.75 * crank_radius / (g.web_thickness * g.web_width**3) + 0.375 * g.pin_length / pin
    )
    return 1.0 / c_j, 1.0 / c_w


@dataclass(frozen=True)
class ThrowParts:
    """The finer equivalent system of the throws: journals and webs as two inertias and a
    spring (seed 003; module docstring, "A finer system").

    Parameters
    ----------
    journal_inertia : float
        A main journal's inertia J_j (kg m^2), >= 0.
    web_inertia : float
        A crank web's inertia J_w (kg m^2), >= 0; the crank pin's is what remains of the
        crank's inertia per throw, J_p = J_crank - J_j - 2 J_w (>= 0).
    journal_stiffness : float or None
        A journal's stiffness k_j (N m/rad); None with the span's Carter dimensions.
    web_stiffness : float or None
        A web's stiffness k_w (N m/rad), half the pin's twist included; None with the span's
        Carter dimensions.

    Raises
    ------
    crankdyn.errors.InputError
        A negative inertia, a stiffness not positive, or one stiffness without the other (names
        the key and value).
    """

    journal_inertia: float
    web_inertia: float
    journal_stiffness: float | None = None
    web_stiffness: float | None = None

    def __post_init__(self) -> None:
        for name in ("journal_inertia", "web_inertia"):
            value = check_finite(name, getattr(self, name))
            if value < 0.0:
                raise InputError("must not be negative", key=name, value=value)
            object.__setattr__(self, name, value)
        if (self.journal_stiffness is None) != (self.web_stiffness is None):
            raise InputError(
                "give both the journal's and the web's stiffness, or neither (Carter's terms)",
                key="journal_stiffness" if self.journal_stiffness is None else "web_stiffness",
            )
        for name in ("journal_stiffness", "web_stiffness"):
            if getattr(self, name) is not None:
                object.__setattr__(self, name, check_positive(name, getattr(self, name)))


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
    parts : ThrowParts or None
        The finer system (journals and webs as two inertias and a spring, seed 003), or None
        for one mass per throw.

    Raises
    ------
    crankdyn.errors.InputError
        A negative inertia or damping, a stiffness not positive, both or neither of
        ``stiffness`` and ``geometry`` (with ``parts``: the parts' stiffnesses or ``geometry``),
        or parts heavier than the crank (names the key and value).
    """

    crank_inertia: float
    stiffness: float | None = None
    geometry: CrankThrowGeometry | None = None
    damping: float = 0.0
    shaft_damping: float = 0.0
    loss_factor: float = 0.0
    parts: ThrowParts | None = None

    def __post_init__(self) -> None:
        value = check_finite("inertia", self.crank_inertia)
        if value < 0.0:
            raise InputError("the crank's inertia must not be negative", key="inertia", value=value)
        object.__setattr__(self, "crank_inertia", value)
        if self.parts is not None:
            self._check_parts(self.parts)
        elif (self.stiffness is None) == (self.geometry is None):
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

    def _check_parts(self, parts: ThrowParts) -> None:
        given = parts.journal_stiffness is not None
        if self.stiffness is not None:
            raise InputError(
                "the finer system takes the journal's and the web's stiffness (or the Carter "
                "dimensions), not the span's",
                key="stiffness",
                value=self.stiffness,
            )
        if given == (self.geometry is not None):
            raise InputError(
                "give the journal's and the web's stiffness or the span's dimensions (Carter's "
                "terms), not both or neither",
                key="journal_stiffness",
            )
        pin = self.crank_inertia - parts.journal_inertia - 2.0 * parts.web_inertia
        if pin < -1e-12 * max(self.crank_inertia, 1e-300):
            raise InputError(
                f"the journal and two webs ({parts.journal_inertia + 2 * parts.web_inertia:.6g} "
                f"kg·m²) outweigh the crank's inertia per throw ({self.crank_inertia:.6g} kg·m²)",
                key="web_inertia",
                value=parts.web_inertia,
            )

    def part_stiffnesses(self, crank_radius: float) -> tuple[float, float]:
        """The journal's and a web's stiffness of the finer system: given, or by Carter's terms
        (:func:`carter_part_stiffnesses`).

        Parameters
        ----------
        crank_radius : float
            Crank radius R (m), for Carter's terms.

        Returns
        -------
        tuple of float
            (k_j, k_w) (N m/rad).

        Raises
        ------
        crankdyn.errors.InputError
            The spec has no parts (key ``parts``).
        """
        if self.parts is None:
            raise InputError("one mass per throw has no parts", key="parts")
        if self.parts.journal_stiffness is not None and self.parts.web_stiffness is not None:
            return self.parts.journal_stiffness, self.parts.web_stiffness
        assert self.geometry is not None  # one of the two (__post_init__)
        return carter_part_stiffnesses(crank_radius, self.geometry)

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
        if self.parts is not None:
            k_j, k_w = self.part_stiffnesses(crank_radius)
            return 1.0 / (1.0 / k_j + 2.0 / k_w)
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
    count = cylinders.throw_count
    on_throw = [
        tuple(c + 1 for c in range(cylinders.count) if cylinders.throws[c] == t)
        for t in range(1, count + 1)
    ]
    if throws.parts is not None:
        crank_masses, spans = _parts_chain(geometry, cylinders, masses, throws, on_throw)
    else:
        inertias = throw_inertias(geometry, cylinders, masses, throws.crank_inertia)
        crank_masses = [
            Mass(
                throw_name(t + 1),
                float(inertias[t]),
                throws.damping,
                on_throw[t],
                role="crank throw",
            )
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
    listed = tuple(other_masses[:before]) + tuple(crank_masses) + tuple(other_masses[before:])
    return TorsionModel(
        masses=listed,
        shafts=spans + tuple(shafts),
        gears=tuple(gears),
        name=name,
        source=source,
    )


def journal_names(number: int) -> tuple[str, str]:
    """Names of the two masses of a main journal in the finer system (seed 003).

    Parameters
    ----------
    number : int
        The main journal, 1-based from the free end (journal t + 1 lies between throws t and
        t + 1).

    Returns
    -------
    tuple of str
        ``("journal N front", "journal N rear")``: its free-end and flywheel-end halves.

    Examples
    --------
    >>> journal_names(2)
    ('journal 2 front', 'journal 2 rear')
    """
    return f"journal {number} front", f"journal {number} rear"


def _parts_chain(
    geometry: CrankGeometry,
    cylinders: Cylinders,
    masses: Masses,
    throws: ThrowSpec,
    on_throw: list[tuple[int, ...]],
) -> tuple[list[Mass], tuple[Shaft, ...]]:
    """The finer system's crank masses (throws and journal halves, free end first) and springs
    (module docstring, "A finer system"; seed 003)."""
    parts = throws.parts
    assert parts is not None  # the caller's branch
    count = cylinders.throw_count
    j_j, j_w = parts.journal_inertia, parts.web_inertia
    pin = max(throws.crank_inertia - j_j - 2.0 * j_w, 0.0)
    running = throw_inertias(geometry, cylinders, masses, 0.0)
    k_j, k_w = throws.part_stiffnesses(geometry.crank_radius)
    k_span = 1.0 / (1.0 / k_j + 2.0 / k_w)
    section = throws.geometry.journal_section if throws.geometry is not None else None
    out: list[Mass] = []
    shafts: list[Shaft] = []
    for t in range(count):
        inner = j_w / 2.0 * ((t > 0) + (t < count - 1))  # web halves of the refined spans
        outer = (j_w + j_j / 2.0) * ((t == 0) + (t == count - 1))  # lumped end parts
        out.append(
            Mass(
                throw_name(t + 1),
                float(running[t] + pin + inner + outer),
                throws.damping,
                on_throw[t],
                role="crank throw",
            )
        )
        if t == count - 1:
            break
        front, rear = journal_names(t + 2)
        out += [
            Mass(front, j_w / 2.0 + j_j / 2.0, role="shaft"),
            Mass(rear, j_j / 2.0 + j_w / 2.0, role="shaft"),
        ]
        for ends, k, role, geom in (
            ((throw_name(t + 1), front), k_w, None, None),
            ((front, rear), k_j, "crankshaft", section),
            ((rear, throw_name(t + 2)), k_w, None, None),
        ):
            shafts.append(
                Shaft(
                    ends,
                    k,
                    damping=throws.shaft_damping * k / k_span,
                    loss_factor=throws.loss_factor,
                    geometry=geom,
                    role=role,
                )
            )
    return out, tuple(shafts)
