"""Lumped torsional model of a shaft line (domain objects).

A :class:`TorsionModel` is a set of rigid discs (:class:`Mass`: a moment of inertia and an
absolute damping to ground) joined by massless elastic shafts (:class:`Shaft`: a torsional
stiffness, given or from the shaft's geometry, with relative viscous damping and/or a loss
factor) and by rigid gear meshes (:class:`Gear`: a speed ratio). A shaft may end at the reserved
name ``"ground"``, which holds that end fixed (a grounded end); without such a shaft the system
is free and has one rigid-body mode.

This is the equivalent system of seed 003 ("扭振当量系统": the equivalent moments of inertia are
placed where the real shaft carries its concentrated masses; the equivalent shaft sections have
the stiffness of the real sections and no mass).

Gears and reflection. A mass turning at ``r`` times the reference speed (the speed of the first
mass that carries a cylinder, else of the first mass) enters the equations with its inertia,
damping and the stiffness and damping of its shafts multiplied by ``r**2``, and its angle is
measured in the reference frame (theta_reflected = theta / r): the kinetic and strain energies
are unchanged (W. Ker Wilson, *Practical Solution of Torsional Vibration Problems*, vol. 1,
ch. 3, "equivalent systems of geared drives"). A gear mesh is rigid, so the two meshing masses
become one degree of freedom with their reflected inertias added.

Structure. After merging the meshing masses, a model whose shafts join its degrees of freedom in
a single line is a *chain*: its stiffness matrix is tridiagonal in chain order, and the modal
solver, Holzer's method and the transfer-matrix method work on :attr:`TorsionModel.chain`.
Other (branched or looped) models use the general symmetric solver on the dense matrices.

Conventions (docs/conventions.md): masses are listed from the free end; SI units throughout
(kg m^2, N m/rad, N m s/rad).
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from crankdyn.crank.geometry import check_finite, check_positive
from crankdyn.display import printable
from crankdyn.errors import InputError, did_you_mean
from crankdyn.torsion.coupling import Coupling

if TYPE_CHECKING:
    from crankdyn.engine.model import Engine
    from crankdyn.torsion.campbell import OperatingRange
    from crankdyn.torsion.dampers import Damper
    from crankdyn.torsion.excitation import ExcitationSpec
    from crankdyn.torsion.rules import RuleSet
    from crankdyn.torsion.sources import EngineSource, HarmonicSource
    from crankdyn.tvc.spec import TvcSpec

__all__ = [
    "GEAR_DIRECTIONS",
    "GROUND",
    "MASS_ROLES",
    "SHAFT_ROLES",
    "ChainArrays",
    "Gear",
    "Mass",
    "MassLimits",
    "Shaft",
    "ShaftGeometry",
    "TorsionModel",
    "shaft_stiffness",
]

GROUND = "ground"
"""Reserved mass name: a shaft ending at ``"ground"`` holds that end fixed."""

MASS_ROLES = (
    "crank throw",
    "damper",
    "pulley",
    "flywheel",
    "coupling",
    "gear",
    "propeller",
    "alternator",
    "motor",
    "pump",
    "compressor",
    "turbine",
    "load",
    "shaft",
    "other",
)
"""What a mass is, for reports and the rule checks (e.g. the alternator's limits)."""

SHAFT_ROLES = ("crankshaft", "propulsion shaft", "shaft")
"""What a plain shaft is, for the rule checks: a crank span, a propulsion shaft (intermediate,
thrust or propeller shaft: IACS UR M68) or another shaft. Couplings and gear meshes are told by
their data (:attr:`Shaft.kind`)."""

GEAR_DIRECTIONS = ("opposite", "same")
"""Direction of rotation of a gear's second wheel relative to its first: ``"opposite"`` for an
external mesh, ``"same"`` for an internal (ring) mesh or a gear train that keeps the sense."""

_RATIO_TOL = 1e-9
OMEGA2_LIMIT = 1e100
"""Largest omega^2 bound (Gershgorin, rad^2/s^2) a model may have: keeps every product of the
solvers (J omega^2 theta, determinants' ratios) far from overflow."""
GEAR_RATIO_LIMIT = 1e3
"""Largest speed ratio of one gear mesh, either way (n_b/n_a within 1/1000 to 1000): the
largest single-stage ratios built are about 100:1 (worm gears) to 300:1 (strain-wave gears),
so beyond 1000 the ratio or the tooth numbers are a mistake; reflected through such a mesh,
inertias and stiffnesses scale by the ratio squared and excitation orders by the ratio, beyond
what the solvers resolve (1e12 teeth made orders of 4e-12 and overflowing products)."""
SPEED_RATIO_LIMIT = GEAR_RATIO_LIMIT**2
"""Largest speed ratio of a mass to the reference mass through all the meshes between them,
either way (1e-6 to 1e6: two stages of the largest mesh)."""
MAGNITUDE_LIMIT = 1e20
"""Largest reflected inertia (kg m^2) or stiffness (N m/rad) a model may have, far beyond any
machine (a large marine shaft line: 1e7 kg m^2, 1e10 N m/rad): beyond it the values are a unit
mistake, and the products of the solvers (J omega^2 theta) approach overflow."""


def _nonnegative(name: str, value: float, what: str) -> float:
    """``value`` as a finite float >= 0, else an InputError naming ``name`` and the value."""
    number = check_finite(name, value)
    if number < 0.0:
        raise InputError(f"{what} must not be negative", key=name, value=value)
    return number


def _name(value: object, key: str = "name") -> str:
    """``value`` when it is a non-empty string, else an InputError naming ``key``."""
    if not isinstance(value, str) or not value.strip():
        raise InputError("expected a non-empty name", key=key, value=value)
    return value


def shaft_stiffness(
    length: float, outer_diameter: float, inner_diameter: float, shear_modulus: float
) -> float:
    """Torsional stiffness of a uniform round (hollow) shaft (N m/rad).

    k = G I_p / l with the polar second moment of area I_p = pi (D^4 - d^4) / 32 (seed 003, the
    three-disc example: shaft stiffness from G, d and l; any strength-of-materials text).

    Parameters
    ----------
    length : float
        Shaft length l (m).
    outer_diameter, inner_diameter : float
        Outer diameter D and bore d (m), 0 <= d < D.
    shear_modulus : float
        Shear modulus G (Pa).

    Returns
    -------
    float
        Torsional stiffness k (N m/rad); the values are not checked (:class:`ShaftGeometry`
        checks them).

    Examples
    --------
    A steel shaft (G = 80 GPa) 1 m long, 100 mm across, solid and with a 50 mm bore:

    >>> f"{shaft_stiffness(1.0, 0.1, 0.0, 80e9):.6g}"
    '785398'
    >>> f"{shaft_stiffness(1.0, 0.1, 0.05, 80e9):.6g}"
    '736311'
    """
    polar = math.pi * (outer_diameter**4 - inner_diameter**4) / 32.0
    return shear_modulus * polar / length


@dataclass(frozen=True)
class MassLimits:
    """Limits a maker gives for a component on a mass (e.g. an alternator's rotor), kept with the
    model for the rule checks (the vibration analysis does not check them).

    Parameters
    ----------
    vibratory_torque : float or None
        Permissible vibratory torque amplitude at the component (N m), > 0, or None.
    angular_acceleration : float or None
        Permissible angular acceleration amplitude (rad/s^2), > 0, or None.
    amplitude : float or None
        Permissible vibratory angle amplitude (rad), > 0, or None.
    source : str or None
        Where the limits come from (the maker's document), for reports.

    Raises
    ------
    crankdyn.errors.InputError
        For a limit that is not a positive finite number, naming its key and value.

    Examples
    --------
    >>> MassLimits(vibratory_torque=12e3, source="alternator data sheet").vibratory_torque
    12000.0
    """

    vibratory_torque: float | None = None
    angular_acceleration: float | None = None
    amplitude: float | None = None
    source: str | None = None

    def __post_init__(self) -> None:
        for name in ("vibratory_torque", "angular_acceleration", "amplitude"):
            value = getattr(self, name)
            if value is not None:
                object.__setattr__(self, name, check_positive(name, value, "the limit"))


@dataclass(frozen=True)
class Mass:
    """A rigid disc of the lumped model.

    Parameters
    ----------
    name : str
        Unique name (``"ground"`` is reserved).
    inertia : float
        Moment of inertia J about the shaft axis (kg m^2), > 0.
    damping : float
        Absolute viscous damping to ground c (N m s/rad), >= 0 (e.g. piston friction at a
        crank throw).
    cylinders : tuple of int
        Engine cylinders whose gas and inertia torques act on this mass (1-based numbers), for
        the forced response; empty for masses that are not crank throws.
    role : str or None
        What the mass is (:data:`MASS_ROLES`), or None. A gear wheel (``role="gear"``) may have
        no inertia when a rigid mesh joins it to a wheel that has some (the mesh's degree of
        freedom carries the sum).
    limits : MassLimits or None
        The maker's limits for the component (:class:`MassLimits`), or None.

    Raises
    ------
    crankdyn.errors.InputError
        For an empty or reserved name, or one with control characters or white space at its
        ends (key ``name``), an unknown role (``role``, with the
        nearest valid one), a negative or non-finite inertia or damping (``inertia``,
        ``damping``) or cylinder numbers that are not distinct whole numbers from 1
        (``cylinders``); each message carries the value given.

    Examples
    --------
    >>> m = Mass("throw 1", 1.8, damping=40.0, cylinders=[1], role="crank throw")
    >>> m.cylinders, m.inertia
    ((1,), 1.8)
    >>> Mass("ground", 1.0)
    Traceback (most recent call last):
    ...
    crankdyn.errors.InputError: name: "ground" is reserved for the fixed end of a grounded shaft
    """

    name: str
    inertia: float
    damping: float = 0.0
    cylinders: tuple[int, ...] = ()
    role: str | None = None
    limits: MassLimits | None = None

    def __post_init__(self) -> None:
        name = _name(self.name)
        if name != name.strip() or printable(name) != name:
            # a name is one line, as typed: tables (the mass-elastic CSV) and files carry it
            # exactly, and no terminal receives its control characters
            raise InputError(
                "a mass name has no control characters (line breaks, tabs, escapes) and no "
                "white space at its ends",
                key="name",
                value=name,
            )
        if name == GROUND:
            raise InputError(
                f'"{GROUND}" is reserved for the fixed end of a grounded shaft', key="name"
            )
        if self.role is not None and self.role not in MASS_ROLES:
            raise InputError(
                f"expected one of {', '.join(MASS_ROLES)}"
                f"{did_you_mean(str(self.role), MASS_ROLES)}",
                key="role",
                value=self.role,
            )
        if self.role == "gear":
            object.__setattr__(
                self, "inertia", _nonnegative("inertia", self.inertia, "the moment of inertia")
            )
        else:
            object.__setattr__(
                self, "inertia", check_positive("inertia", self.inertia, "the moment of inertia")
            )
        object.__setattr__(self, "damping", _nonnegative("damping", self.damping, "damping"))
        cylinders = tuple(self.cylinders)
        if not cylinders:
            object.__setattr__(self, "cylinders", ())
            return
        if any(isinstance(c, bool) or not isinstance(c, (int, np.integer)) for c in cylinders):
            raise InputError("expected cylinder numbers", key="cylinders", value=list(cylinders))
        cylinders = tuple(int(c) for c in cylinders)
        if any(c < 1 for c in cylinders) or len(set(cylinders)) != len(cylinders):
            raise InputError(
                "expected distinct cylinder numbers from 1 up", key="cylinders", value=cylinders
            )
        object.__setattr__(self, "cylinders", cylinders)

    @classmethod
    def _checked(cls, name: str, inertia: float) -> Mass:
        """A mass from a name and an inertia the caller has already validated (a positive
        finite float; no damping, no cylinders), without validating them again."""
        mass = object.__new__(cls)
        # the fields written at once (a frozen dataclass's __init__ sets each through
        # object.__setattr__: most of the cost of a 1000-mass chain_of)
        mass.__dict__.update(
            name=name, inertia=inertia, damping=0.0, cylinders=(), role=None, limits=None
        )
        return mass


@dataclass(frozen=True)
class ShaftGeometry:
    """Cross-section (and, when known, length and material) of a uniform round shaft.

    Parameters
    ----------
    outer_diameter : float
        Outer diameter D (m), > 0.
    inner_diameter : float
        Bore d (m), 0 <= d < D.
    length : float or None
        Length l (m), or None when the stiffness is given directly.
    shear_modulus : float or None
        Shear modulus G (Pa), or None when the stiffness is given directly.

    Raises
    ------
    crankdyn.errors.InputError
        For a diameter, length or shear modulus that is not positive and finite, or a bore not
        smaller than the outer diameter, naming the key and value.

    Examples
    --------
    >>> g = ShaftGeometry(0.1, 0.05, length=1.0, shear_modulus=80e9)
    >>> f"{g.polar_moment:.6g} m^4, {g.section_modulus:.6g} m^3, {g.stiffness:.6g} N m/rad"
    '9.20388e-06 m^4, 0.000184078 m^3, 736311 N m/rad'
    >>> ShaftGeometry(0.1).stiffness is None
    True
    """

    outer_diameter: float
    inner_diameter: float = 0.0
    length: float | None = None
    shear_modulus: float | None = None

    def __post_init__(self) -> None:
        outer = check_positive("outer_diameter", self.outer_diameter, "the diameter")
        inner = _nonnegative("inner_diameter", self.inner_diameter, "the bore")
        if inner >= outer:
            raise InputError(
                f"the bore must be smaller than the outer diameter ({outer * 1e3:.6g} mm)",
                key="inner_diameter",
                value=self.inner_diameter,
            )
        object.__setattr__(self, "outer_diameter", outer)
        object.__setattr__(self, "inner_diameter", inner)
        if self.length is not None:
            object.__setattr__(self, "length", check_positive("length", self.length, "the length"))
        if self.shear_modulus is not None:
            object.__setattr__(
                self,
                "shear_modulus",
                check_positive("shear_modulus", self.shear_modulus, "the shear modulus"),
            )

    @property
    def polar_moment(self) -> float:
        """Polar second moment of area I_p = pi (D^4 - d^4) / 32 (m^4)."""
        return math.pi * (self.outer_diameter**4 - self.inner_diameter**4) / 32.0

    @property
    def section_modulus(self) -> float:
        """Polar section modulus W_p = I_p / (D/2) (m^3): nominal shear stress tau = T / W_p."""
        return self.polar_moment / (self.outer_diameter / 2.0)

    @property
    def stiffness(self) -> float | None:
        """k = G I_p / l (N m/rad), or None without length and shear modulus."""
        if self.length is None or self.shear_modulus is None:
            return None
        return shaft_stiffness(
            self.length, self.outer_diameter, self.inner_diameter, self.shear_modulus
        )


@dataclass(frozen=True)
class Shaft:
    """An elastic connection between two masses (or a mass and ``"ground"``): a shaft, an
    elastic coupling or an elastic gear mesh.

    Parameters
    ----------
    between : tuple of (str, str)
        The two mass names; one of them may be ``"ground"`` (a grounded end).
    stiffness : float or None
        Torsional stiffness k (N m/rad), > 0, referred to the first mass's speed; None to take
        it from ``geometry`` (k = G I_p / l, :func:`shaft_stiffness`) or from ``coupling``.
        Always a float after construction.
    damping : float
        Relative viscous damping c between the two ends (N m s/rad), >= 0.
    loss_factor : float
        Hysteretic loss factor eta (dimensionless), >= 0: a damping torque eta k times the twist,
        in phase with the twist rate (equivalent viscous c = eta k / omega).
    geometry : ShaftGeometry or None
        Shaft cross-section, and length and shear modulus when the stiffness is not given
        (kept for nominal shear stresses).
    name : str or None
        Name of the component (e.g. ``"intermediate shaft"``, a coupling's type), or None.
    role : str or None
        What a plain shaft is (:data:`SHAFT_ROLES`), for the rule checks; None: a crank span
        for the generated crank throws, else unspecified.
    coupling : crankdyn.torsion.coupling.Coupling or None
        Catalogue data of an elastic coupling (:class:`crankdyn.torsion.coupling.Coupling`):
        the stiffness (C_Tdyn at the coupling's model torque, with its temperature factor) and
        the loss factor (psi / 2 pi) come from it.
    inertia : float
        The shaft's own polar moment of inertia (kg m^2), >= 0: a distributed-mass shaft, which
        the model divides into ``elements`` lumped elements (:mod:`crankdyn.torsion.distributed`).
    elements : int or None
        Number of elements of a distributed-mass shaft (>= 1), or None to set it from
        ``max_frequency``.
    max_frequency : float or None
        Highest natural frequency (rad/s) the subdivision must resolve to 0.1 % (default
        :data:`crankdyn.torsion.distributed.DEFAULT_MAX_FREQUENCY`).
    ratio : float
        Speed ratio n_b / n_a across the element (dimensionless, > 0): 1 for shafts and
        couplings; the gear ratio of an elastic gear mesh.
    direction : int
        +1 when the second mass turns in the sense of the first, -1 when it turns the other way
        (an external gear mesh).
    gear : Gear or None
        The :class:`Gear` an elastic mesh came from (its data for the rule checks), or None.
    segment_of : tuple of (str, str) or None
        For the elements of a subdivided shaft, the masses the whole shaft joins.

    Raises
    ------
    crankdyn.errors.InputError
        For ends that are not two different mass names (key ``between``), a missing or doubled
        stiffness (``stiffness``: a value, a geometry with length and shear modulus, or a
        coupling), a negative damping or loss factor, a speed ratio that is not positive or lies
        beyond :data:`GEAR_RATIO_LIMIT` either way (``ratio``), an unknown role, a direction
        other than +1 or -1, an element count outside 1 to 10000, or distributed inertia on a
        mesh, a coupling or a grounded shaft (``inertia``); each message carries the value
        given.

    Examples
    --------
    >>> s = Shaft(("flywheel", "propeller"), geometry=ShaftGeometry(0.1, 0.0, 1.0, 80e9))
    >>> f"{s.stiffness:.6g}", s.kind, s.label, s.grounded
    ('785398', 'shaft', 'flywheel - propeller', False)
    >>> Shaft(("ground", "hub"), 2e6, loss_factor=0.02).grounded
    True
    """

    between: tuple[str, str]
    # None on input: derived in __post_init__ (the __init__ below tells the type checker)
    stiffness: float = None  # type: ignore[assignment]
    damping: float = 0.0
    loss_factor: float = 0.0
    geometry: ShaftGeometry | None = None
    name: str | None = None
    role: str | None = None
    coupling: Coupling | None = None
    inertia: float = 0.0
    elements: int | None = None
    max_frequency: float | None = None
    ratio: float = 1.0
    direction: int = 1
    gear: Gear | None = field(default=None, compare=False)
    segment_of: tuple[str, str] | None = None

    if TYPE_CHECKING:  # what the constructor accepts; the fields hold the normalised values

        def __init__(
            self,
            between: tuple[str, str] | Sequence[str],
            stiffness: float | None = None,
            damping: float = 0.0,
            loss_factor: float = 0.0,
            geometry: ShaftGeometry | None = None,
            name: str | None = None,
            role: str | None = None,
            coupling: Coupling | None = None,
            inertia: float = 0.0,
            elements: int | None = None,
            max_frequency: float | None = None,
            ratio: float = 1.0,
            direction: int = 1,
            gear: Gear | None = None,
            segment_of: tuple[str, str] | None = None,
        ) -> None: ...

    def __post_init__(self) -> None:
        ends = tuple(self.between) if isinstance(self.between, (list, tuple)) else ()
        if len(ends) != 2 or any(not isinstance(e, str) or not e.strip() for e in ends):
            raise InputError("expected the names of two masses", key="between", value=ends)
        if ends[0] == ends[1]:
            raise InputError("a shaft must join two different masses", key="between", value=ends)
        if ends == (GROUND, GROUND):
            raise InputError("a shaft cannot join ground to ground", key="between", value=ends)
        object.__setattr__(self, "between", ends)
        if self.role is not None and self.role not in SHAFT_ROLES:
            raise InputError(
                f"expected one of {', '.join(SHAFT_ROLES)}"
                f"{did_you_mean(str(self.role), SHAFT_ROLES)}",
                key="role",
                value=self.role,
            )
        given = self.stiffness
        from_geometry = self.geometry.stiffness if self.geometry is not None else None
        if self.coupling is not None:
            own = self.coupling.model_stiffness
            if from_geometry is not None or (
                given is not None and abs(given - own) > 1e-12 * own  # a copy keeps its own
            ):
                raise InputError(
                    "a coupling's stiffness comes from its catalogue data (dynamic_stiffness); "
                    "give no other stiffness",
                    key="stiffness",
                    value=given if given is not None else from_geometry,
                )
            if self.loss_factor and abs(self.loss_factor - self.coupling.loss_factor) > 1e-12:
                raise InputError(
                    "a coupling's damping comes from its relative damping psi; give no loss_factor",
                    key="loss_factor",
                    value=self.loss_factor,
                )
            given = self.coupling.model_stiffness
            object.__setattr__(self, "loss_factor", self.coupling.loss_factor)
        if given is not None and from_geometry is not None:
            raise InputError(
                "give the stiffness or the shaft's length and shear modulus, not both",
                key="stiffness",
                value=given,
            )
        if given is None and from_geometry is None:
            raise InputError(
                "missing; give the stiffness, or the length, diameters and shear modulus",
                key="stiffness",
            )
        k = check_positive("stiffness", given, "the stiffness") if given is not None else None
        object.__setattr__(self, "stiffness", k if k is not None else from_geometry)
        object.__setattr__(self, "damping", _nonnegative("damping", self.damping, "damping"))
        object.__setattr__(
            self,
            "loss_factor",
            _nonnegative("loss_factor", self.loss_factor, "the loss factor"),
        )
        object.__setattr__(self, "inertia", _nonnegative("inertia", self.inertia, "the inertia"))
        ratio = check_positive("ratio", self.ratio, "the speed ratio")
        _check_gear_ratio(ratio, "ratio", None)
        object.__setattr__(self, "ratio", ratio)
        if self.direction not in (1, -1):
            raise InputError("expected +1 or -1", key="direction", value=self.direction)
        if self.elements is not None:
            if isinstance(self.elements, bool) or not isinstance(self.elements, (int, np.integer)):
                raise InputError("expected a whole number", key="elements", value=self.elements)
            if not 1 <= int(self.elements) <= 10_000:
                raise InputError(
                    "expected 1 to 10000 elements", key="elements", value=self.elements
                )
            object.__setattr__(self, "elements", int(self.elements))
        if self.max_frequency is not None:
            object.__setattr__(
                self,
                "max_frequency",
                check_positive("max_frequency", self.max_frequency, "the frequency"),
            )
        if self.is_mesh:
            if GROUND in ends:
                raise InputError(
                    f'a gear mesh cannot join "{GROUND}"', key="between", value=list(ends)
                )
            if self.inertia > 0.0:
                raise InputError(
                    "a gear mesh has no distributed inertia; put the wheels' inertias on their "
                    "masses",
                    key="inertia",
                    value=self.inertia,
                )
        if self.inertia > 0.0 and self.coupling is not None:
            raise InputError(
                "put a coupling's inertias on its primary and secondary masses",
                key="inertia",
                value=self.inertia,
            )
        if self.inertia > 0.0 and GROUND in ends:
            raise InputError(
                "a grounded shaft cannot carry distributed inertia; model the shaft up to a "
                "mass and ground that mass",
                key="inertia",
                value=self.inertia,
            )

    @classmethod
    def _checked(cls, between: tuple[str, str], stiffness: float) -> Shaft:
        """A shaft between two distinct masses (not ground) with a stiffness the caller has
        already validated (a positive finite float), without validating them again."""
        shaft = object.__new__(cls)
        shaft.__dict__.update(  # every field at once, as Mass._checked
            between=between,
            stiffness=stiffness,
            damping=0.0,
            loss_factor=0.0,
            geometry=None,
            name=None,
            role=None,
            coupling=None,
            inertia=0.0,
            elements=None,
            max_frequency=None,
            ratio=1.0,
            direction=1,
            gear=None,
            segment_of=None,
        )
        return shaft

    @property
    def grounded(self) -> bool:
        """Whether one end is ``"ground"``."""
        return GROUND in self.between

    @property
    def is_mesh(self) -> bool:
        """Whether this element is an elastic gear mesh (its ends turn at different speeds or
        in opposite senses)."""
        return self.gear is not None or self.ratio != 1.0 or self.direction != 1

    @property
    def kind(self) -> str:
        """``"coupling"``, ``"mesh"`` (an elastic gear mesh) or ``"shaft"``."""
        if self.coupling is not None:
            return "coupling"
        if self.is_mesh:
            return "mesh"
        return "shaft"

    @property
    def label(self) -> str:
        """``"a - b"`` for tables and messages."""
        return f"{self.between[0]} - {self.between[1]}"


def _check_gear_ratio(ratio: float, key: str, teeth: tuple[int, int] | None) -> None:
    """Refuse a mesh's speed ratio (dimensionless) beyond :data:`GEAR_RATIO_LIMIT` either way,
    naming ``key`` (``teeth`` when the ratio came from tooth numbers) and the value given."""
    if 1.0 / GEAR_RATIO_LIMIT <= ratio <= GEAR_RATIO_LIMIT:
        return
    raise InputError(
        f"a speed ratio of {ratio:.3g} lies beyond the 1:{GEAR_RATIO_LIMIT:g} to "
        f"{GEAR_RATIO_LIMIT:g}:1 of one gear mesh (the largest built are about 300:1); check the "
        f"{'tooth numbers' if teeth is not None else 'ratio'}, or give a gear train as its stages",
        key=key,
        value=list(teeth) if teeth is not None else ratio,
    )


def _teeth(value: object) -> tuple[int, int]:
    """Tooth numbers (z_a, z_b) as two whole numbers >= 1, else an InputError (key ``teeth``)."""
    pair = tuple(value) if isinstance(value, (list, tuple)) else ()
    if len(pair) != 2 or any(
        isinstance(z, bool) or not isinstance(z, (int, np.integer)) or z < 1 for z in pair
    ):
        raise InputError(
            "expected the tooth numbers of the two wheels, e.g. [23, 71]",
            key="teeth",
            value=value,
        )
    return int(pair[0]), int(pair[1])


@dataclass(frozen=True)
class Gear:
    """A gear mesh between two masses (the gear wheels), rigid or elastic.

    Parameters
    ----------
    between : tuple of (str, str)
        The two meshing masses (gear wheels) ``(a, b)``.
    ratio : float or None
        Speed ratio n_b / n_a (dimensionless), > 0; None with ``teeth``. Always a float after
        construction.
    teeth : tuple of (int, int) or None
        Tooth numbers (z_a, z_b) instead of the ratio: n_b / n_a = z_a / z_b.
    direction : str
        ``"opposite"`` (default: an external mesh, the second wheel turns the other way) or
        ``"same"`` (an internal mesh, or a gear train given as one stage that keeps the sense).
        Angles and torques beyond a reversing mesh change sign (docs/torsion-file.md).
    stiffness : float or None
        Mesh stiffness as a torsional stiffness referred to wheel a (N m/rad): k_a = c r_b,a^2
        for a mesh stiffness c (N/m) along the line of action and the base radius r_b,a of
        wheel a (the tangential spring at the base circle, twist r_b theta; Ker Wilson, vol. 1,
        ch. 3). None: a rigid mesh (the two wheels are one degree of freedom).
    damping : float
        Viscous mesh damping referred to wheel a (N m s/rad), >= 0 (elastic meshes).
    loss_factor : float
        Loss factor of the mesh stiffness (dimensionless), >= 0 (elastic meshes).
    name : str or None
        Name of the gear stage, for reports.
    joint : bool
        True for a rigid joint of two masses bolted together (e.g. an engine's flywheel and a
        shaft line's first mass, :mod:`crankdyn.torsion.driveline`): ratio 1, same sense, no
        gear for the rule checks.

    Raises
    ------
    crankdyn.errors.InputError
        For ends that are not two different mass names or include ``"ground"`` (key
        ``between``), a missing, zero, negative or non-finite ratio or one that disagrees with
        the tooth numbers (``ratio``), bad tooth numbers (``teeth``), a ratio beyond
        :data:`GEAR_RATIO_LIMIT` either way (``ratio`` or ``teeth``), an unknown direction
        (``direction``), a non-positive mesh stiffness (``stiffness``), damping on a rigid mesh,
        or a joint that is not ratio 1 and ``"same"`` (``joint``); each with the value given.

    Examples
    --------
    >>> g = Gear(("pinion", "wheel"), teeth=(23, 71))
    >>> f"{g.ratio:.6g}", g.sign, g.elastic, g.label
    ('0.323944', -1, False, 'pinion - wheel')
    >>> e = Gear(("pinion", "wheel"), 3.0, stiffness=5e7, direction="same").mesh_shaft()
    >>> e.kind, e.ratio, e.direction, e.stiffness
    ('mesh', 3.0, 1, 50000000.0)
    """

    between: tuple[str, str]
    # None on input with teeth: derived in __post_init__ (the __init__ below tells the type
    # checker)
    ratio: float = None  # type: ignore[assignment]
    teeth: tuple[int, int] | None = None
    direction: str = "opposite"
    stiffness: float | None = None
    damping: float = 0.0
    loss_factor: float = 0.0
    name: str | None = None
    joint: bool = False

    if TYPE_CHECKING:  # what the constructor accepts; the fields hold the normalised values

        def __init__(
            self,
            between: tuple[str, str] | Sequence[str],
            ratio: float | None = None,
            teeth: tuple[int, int] | Sequence[int] | None = None,
            direction: str = "opposite",
            stiffness: float | None = None,
            damping: float = 0.0,
            loss_factor: float = 0.0,
            name: str | None = None,
            joint: bool = False,
        ) -> None: ...

    def __post_init__(self) -> None:
        ends = tuple(self.between) if isinstance(self.between, (list, tuple)) else ()
        if len(ends) != 2 or any(not isinstance(e, str) or not e.strip() for e in ends):
            raise InputError("expected the names of two masses", key="between", value=ends)
        if ends[0] == ends[1]:
            raise InputError("a gear must join two different masses", key="between", value=ends)
        if self.joint and (
            self.ratio not in (None, 1.0) or self.direction != "same" or self.stiffness
        ):
            raise InputError(
                'a rigid joint has ratio 1 and direction "same"', key="joint", value=True
            )
        if GROUND in ends:
            raise InputError(f'a gear cannot mesh with "{GROUND}"', key="between", value=ends)
        object.__setattr__(self, "between", ends)
        if self.teeth is not None:
            teeth = _teeth(self.teeth)
            object.__setattr__(self, "teeth", teeth)
            from_teeth = teeth[0] / teeth[1]
            if self.ratio is not None:
                given = check_finite("ratio", self.ratio)
                if abs(given - from_teeth) > 1e-9 * from_teeth:
                    raise InputError(
                        f"the ratio disagrees with the tooth numbers {teeth[0]}:{teeth[1]} "
                        f"(n_b/n_a = z_a/z_b = {from_teeth:.9g}); give one of them",
                        key="ratio",
                        value=self.ratio,
                    )
            object.__setattr__(self, "ratio", from_teeth)
        if self.ratio is None:
            raise InputError(
                "missing; give the speed ratio n_b/n_a or the tooth numbers", key="ratio"
            )
        ratio = check_finite("ratio", self.ratio)
        if ratio == 0.0:
            raise InputError(
                "a gear ratio cannot be zero (it is the speed of the second mass over the "
                "speed of the first)",
                key="ratio",
                value=self.ratio,
            )
        if ratio < 0.0:
            raise InputError(
                'give the gear ratio as a positive speed ratio n_b/n_a (and direction = "same" '
                'or "opposite" for the sense of rotation)',
                key="ratio",
                value=self.ratio,
            )
        _check_gear_ratio(ratio, "teeth" if self.teeth is not None else "ratio", self.teeth)
        object.__setattr__(self, "ratio", ratio)
        if self.direction not in GEAR_DIRECTIONS:
            raise InputError(
                f"expected one of {', '.join(GEAR_DIRECTIONS)}"
                f"{did_you_mean(str(self.direction), GEAR_DIRECTIONS)}",
                key="direction",
                value=self.direction,
            )
        if self.stiffness is not None:
            object.__setattr__(
                self, "stiffness", check_positive("stiffness", self.stiffness, "the mesh stiffness")
            )
        object.__setattr__(self, "damping", _nonnegative("damping", self.damping, "damping"))
        object.__setattr__(
            self, "loss_factor", _nonnegative("loss_factor", self.loss_factor, "the loss factor")
        )
        if self.stiffness is None and (self.damping or self.loss_factor):
            raise InputError(
                "a rigid mesh has no damping; give the mesh stiffness for an elastic mesh",
                key="damping" if self.damping else "loss_factor",
                value=self.damping or self.loss_factor,
            )

    @property
    def sign(self) -> int:
        """-1 when the second wheel turns the other way, +1 when it keeps the sense."""
        return -1 if self.direction == "opposite" else 1

    @property
    def elastic(self) -> bool:
        """Whether the mesh has a stiffness (two degrees of freedom joined by a spring)."""
        return self.stiffness is not None

    @property
    def label(self) -> str:
        """``"a - b"`` for tables and messages."""
        return f"{self.between[0]} - {self.between[1]}"

    def mesh_shaft(self) -> Shaft:
        """The elastic mesh as an element of the model: a spring of the mesh stiffness (referred
        to wheel a) between the wheels, carrying the speed ratio and the direction.

        Returns
        -------
        Shaft
            A shaft of kind ``"mesh"`` with this gear's stiffness (N m/rad, referred to wheel
            a), damping (N m s/rad), loss factor, ratio and sense (+1 or -1), and ``gear`` set
            to this gear.

        Raises
        ------
        crankdyn.errors.InputError
            For a rigid mesh (no stiffness; key ``stiffness``).
        """
        return Shaft(
            self.between,
            self.stiffness,
            damping=self.damping,
            loss_factor=self.loss_factor,
            name=self.name,
            ratio=self.ratio,
            direction=self.sign,
            gear=self,
        )


@dataclass(frozen=True)
class ChainArrays:
    """A chain model in chain order: degree of freedom i is joined to i + 1 (SI arrays).

    All values are reflected to the reference speed (module docstring: inertia and the
    stiffness and damping of a shaft times r^2, Ker Wilson vol. 1 ch. 3); n is the number of
    degrees of freedom (:attr:`TorsionModel.chain`).

    Parameters
    ----------
    inertia : numpy.ndarray
        Moment of inertia of every degree of freedom (kg m^2), shape (n,).
    stiffness : numpy.ndarray
        Stiffness between neighbours i and i + 1 (N m/rad), shape (n - 1,).
    damping : numpy.ndarray
        Relative viscous damping between neighbours (N m s/rad), shape (n - 1,).
    hysteretic : numpy.ndarray
        Sum of loss factor times stiffness between neighbours (N m/rad), shape (n - 1,).
    ground_stiffness : numpy.ndarray
        Stiffness of the shafts to ground at every degree of freedom (N m/rad), shape (n,).
    ground_damping : numpy.ndarray
        Absolute viscous damping (the masses' own and the grounded shafts') at every degree of
        freedom (N m s/rad), shape (n,).
    ground_hysteretic : numpy.ndarray
        Loss factor times stiffness of the grounded shafts (N m/rad), shape (n,).

    Examples
    --------
    >>> chain = TorsionModel.chain_of([1.0, 2.0, 3.0], [10.0, 20.0], ground_right=5.0).chain
    >>> chain.size, chain.stiffness.tolist(), chain.ground_stiffness.tolist()
    (3, [10.0, 20.0], [0.0, 0.0, 5.0])
    """

    inertia: NDArray[np.float64]
    stiffness: NDArray[np.float64]
    damping: NDArray[np.float64]
    hysteretic: NDArray[np.float64]
    ground_stiffness: NDArray[np.float64]
    ground_damping: NDArray[np.float64]
    ground_hysteretic: NDArray[np.float64]

    @property
    def size(self) -> int:
        """Number of degrees of freedom n."""
        return int(self.inertia.size)

    def stiffness_diagonals(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Main and off diagonal of the tridiagonal stiffness matrix K.

        Returns
        -------
        diagonal : numpy.ndarray
            K_ii (N m/rad), shape (n,): the stiffnesses of the shafts at degree of freedom i,
            to its neighbours and to ground.
        off_diagonal : numpy.ndarray
            K_i,i+1 = K_i+1,i = -k_i (N m/rad), shape (n - 1,).

        Examples
        --------
        >>> chain = TorsionModel.chain_of([1.0, 2.0, 3.0], [10.0, 20.0], ground_right=5.0).chain
        >>> [a.tolist() for a in chain.stiffness_diagonals()]
        [[10.0, 30.0, 25.0], [-10.0, -20.0]]
        """
        k = self.stiffness
        diag = self.ground_stiffness.copy()
        diag[:-1] += k
        diag[1:] += k
        return diag, -k

    @cached_property
    def normalised(self) -> NormalisedChain:
        """The mass-normalised matrix M^-1/2 K M^-1/2 of the chain, computed once per model
        (read-only arrays; the dense solvers' K and M are the model's in the same way).

        For K phi = lambda M phi with M = diag(J), u = M^1/2 phi solves A u = lambda u with
        A = M^-1/2 K M^-1/2, symmetric tridiagonal: A_ii = K_ii / J_i and
        A_i,i+1 = -k_i / sqrt(J_i J_i+1) (Golub and Van Loan, *Matrix Computations*, 4th ed.,
        section 8.7.2, the symmetric-definite problem by Cholesky reduction, here diagonal).

        Examples
        --------
        >>> c = TorsionModel.chain_of([1.0, 4.0], [8.0]).chain.normalised
        >>> c.diagonal.tolist(), c.off_diagonal.tolist(), c.total_inertia
        ([8.0, 2.0], [-4.0], 5.0)
        """
        diag, off = self.stiffness_diagonals()
        s = np.sqrt(self.inertia)
        np.divide(off, s[:-1] * s[1:], out=off)
        np.divide(diag, self.inertia, out=diag)
        for arr in (diag, off, s):
            arr.setflags(write=False)
        listed = s.tolist()
        return NormalisedChain(
            diagonal=diag,
            off_diagonal=off,
            root_inertia=s,
            total_inertia=float(np.add.reduce(self.inertia)),
            least_root_inertia=min(listed) if listed else math.inf,
        )


@dataclass(frozen=True)
class NormalisedChain:
    """A chain's mass-normalised tridiagonal matrix A = M^-1/2 K M^-1/2 and the inertia figures
    its eigenvector post-processing uses (:attr:`ChainArrays.normalised`).

    Parameters
    ----------
    diagonal : numpy.ndarray
        A_ii = K_ii / J_i (rad²/s²), shape (n,).
    off_diagonal : numpy.ndarray
        A_i,i+1 = -k_i / sqrt(J_i J_i+1) (rad²/s²), shape (n - 1,).
    root_inertia : numpy.ndarray
        sqrt(J_i) (sqrt(kg m²)), shape (n,).
    total_inertia : float
        The sum of J_i (kg m²).
    least_root_inertia : float
        The smallest sqrt(J_i) (sqrt(kg m²)).
    """

    diagonal: NDArray[np.float64]
    off_diagonal: NDArray[np.float64]
    root_inertia: NDArray[np.float64]
    total_inertia: float
    least_root_inertia: float


def _positive_numbers(values: list[Any]) -> list[float] | None:
    """The values as floats when every one is a real number (not bool), finite and > 0, else
    None (so that the caller lets the constructors report the offending value)."""
    if any(
        isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating))
        for v in values
    ):
        return None
    arr = np.asarray(values, dtype=float)
    if arr.ndim != 1 or not (np.all(np.isfinite(arr)) and np.all(arr > 0.0)):
        return None
    return arr.tolist()


def _frozen(values: Any, dtype: Any = float) -> NDArray[Any]:
    """``values`` as a new read-only array."""
    arr = np.array(values, dtype=dtype)
    arr.setflags(write=False)
    return arr


@dataclass(frozen=True)
class _Structure:
    """The topology of a model (:func:`_analyse`)."""

    speed_ratio: np.ndarray  # per mass
    rotation: np.ndarray  # per mass, +1 / -1: sense of rotation relative to the reference
    mass_dof: np.ndarray  # per mass, index of its degree of freedom
    dofs: tuple[tuple[int, ...], ...]  # mass indices of every degree of freedom
    shaft_dofs: np.ndarray  # (n_shafts, 2) dof indices, -1 for ground
    is_chain: bool
    junction: str | None  # a mass where a branched model branches, for messages


@dataclass(frozen=True)
class TorsionModel:
    """A lumped torsional model: masses, shafts (possibly grounded) and gear meshes.

    Parameters
    ----------
    masses : tuple of Mass
        The masses, listed from the free end (the listing order of every output).
    shafts : tuple of Shaft
        Elastic connections between masses, or between a mass and ``"ground"``: shafts,
        couplings and elastic gear meshes. Shafts with distributed inertia are divided into
        lumped elements on construction (:mod:`crankdyn.torsion.distributed`: the generated
        masses are listed between the shaft's ends and its ends get half an element each).
    gears : tuple of Gear
        Gear meshes; the masses beyond a gear are reflected to the reference speed. Elastic
        meshes (with a stiffness) become elements of ``shafts`` on construction
        (:meth:`Gear.mesh_shaft`); rigid ones stay here and merge their wheels into one degree
        of freedom.
    name : str
        Name for reports.
    source : str or None
        The file the model came from, for messages.
    excitation : crankdyn.torsion.excitation.ExcitationSpec or None
        How the model is excited in a forced response
        (:class:`crankdyn.torsion.excitation.ExcitationSpec`), or None.
    dampers : tuple of crankdyn.torsion.dampers.Damper
        Vibration dampers (:class:`crankdyn.torsion.dampers.Damper`) added by the forced
        response; not part of the matrices above (model a tuned damper as a mass and a shaft to
        see it in the natural frequencies, or use :func:`crankdyn.torsion.campbell.with_dampers`).
    rules : crankdyn.torsion.rules.RuleSet or None
        Rule-check inputs (:class:`crankdyn.torsion.rules.RuleSet`), or None.
    operating : crankdyn.torsion.campbell.OperatingRange or None
        Operating speed range (:class:`crankdyn.torsion.campbell.OperatingRange`), or None.
    sources : tuple of HarmonicSource or EngineSource
        Excitation sources besides the cylinders on the masses
        (:mod:`crankdyn.torsion.sources`: propellers, electric machines, tabulated sources,
        further engines), each acting on a named mass at orders of that mass's speed.
    engine : crankdyn.engine.model.Engine or None
        The first engine of a model file that includes engines (``[[engine]]``; its cylinders
        sit on the model's masses), or None.
    tvc : crankdyn.tvc.TvcSpec or None
        The settings of a torsional vibration calculation (:class:`crankdyn.tvc.TvcSpec`,
        ``[tvc]``), or None (the defaults).

    Raises
    ------
    crankdyn.errors.InputError
        For duplicate or reserved names (key ``name``), a shaft, gear, damper or source naming
        an unknown mass (``between``, ``at``, with the nearest name), a cylinder on two masses
        (``cylinders``), gear ratios or senses that disagree around a loop, a shaft between two
        masses a gear already ties together (``between``), a disconnected model, a degree of
        freedom without inertia (``inertia``), a mass turning beyond :data:`SPEED_RATIO_LIMIT`
        times the reference speed either way (``gear``), or magnitudes beyond
        :data:`MAGNITUDE_LIMIT` or :data:`OMEGA2_LIMIT` (a unit mistake).
    TypeError
        When ``masses`` holds something other than :class:`Mass` objects.

    Examples
    --------
    A flywheel, a coupling and a propeller, with a gearbox 3:1 between the last two (Ker Wilson
    vol. 1 ch. 3: the propeller's inertia and its shaft's stiffness enter reflected by r^2):

    >>> model = TorsionModel(
    ...     masses=(Mass("flywheel", 10.0), Mass("pinion", 0.5, role="gear"),
    ...             Mass("wheel", 4.0, role="gear"), Mass("propeller", 90.0)),
    ...     shafts=(Shaft(("flywheel", "pinion"), 1e6), Shaft(("wheel", "propeller"), 9e6)),
    ...     gears=(Gear(("pinion", "wheel"), 1 / 3),),
    ... )
    >>> model.dof_names, model.is_chain, model.is_free
    (('flywheel', 'pinion + wheel', 'propeller'), True, True)
    >>> [round(float(j), 6) for j in model.dof_inertia]
    [10.0, 0.944444, 10.0]
    >>> (model.stiffness_matrix() / 1e6).round(9).tolist()  # MN m/rad
    [[1.0, -1.0, 0.0], [-1.0, 2.0, -1.0], [0.0, -1.0, 1.0]]
    """

    masses: tuple[Mass, ...]
    shafts: tuple[Shaft, ...] = ()
    gears: tuple[Gear, ...] = ()
    name: str = "torsional model"
    source: str | None = field(default=None, compare=False)
    excitation: ExcitationSpec | None = None
    dampers: tuple[Damper, ...] = ()
    rules: RuleSet | None = None
    operating: OperatingRange | None = None
    sources: tuple[HarmonicSource | EngineSource, ...] = ()
    engine: Engine | None = field(default=None, compare=False, repr=False)
    tvc: TvcSpec | None = field(default=None, compare=False, repr=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "dampers", tuple(self.dampers))
        object.__setattr__(self, "sources", tuple(self.sources))
        masses = tuple(self.masses)
        if not masses:
            raise InputError("a torsional model needs at least one mass", key="mass")
        if any(not isinstance(m, Mass) for m in masses):
            raise TypeError("masses must be Mass objects")
        gears = tuple(self.gears)
        shafts = tuple(self.shafts) + tuple(g.mesh_shaft() for g in gears if g.elastic)
        gears = tuple(g for g in gears if not g.elastic)
        if any(s.inertia > 0.0 for s in shafts):
            from crankdyn.torsion.distributed import subdivide

            masses, shafts = subdivide(masses, shafts, Mass)
        object.__setattr__(self, "masses", masses)
        object.__setattr__(self, "shafts", shafts)
        object.__setattr__(self, "gears", gears)
        seen: dict[str, int] = {}
        for i, m in enumerate(masses):
            if m.name in seen:
                raise InputError(
                    f'two masses are named "{m.name}" (masses {seen[m.name] + 1} and {i + 1})',
                    key="name",
                    value=m.name,
                )
            seen[m.name] = i
        owner: dict[int, str] = {}
        for m in masses:
            for c in m.cylinders:
                if c in owner:
                    raise InputError(
                        f'cylinder {c} is on two masses ("{owner[c]}" and "{m.name}")',
                        key="cylinders",
                        value=list(m.cylinders),
                    )
                owner[c] = m.name
        for items, what in ((self.shafts, "shaft"), (self.gears, "gear")):
            for item in items:
                for end in item.between:
                    if end != GROUND and end not in seen:
                        raise InputError(
                            f'{what} "{item.between[0]}" - "{item.between[1]}": '
                            f'no mass named "{end}"{did_you_mean(end, seen)}',
                            key="between",
                            value=list(item.between),
                        )
        for d in self.dampers:
            if d.at not in seen:
                raise InputError(
                    f'damper "{d.name}": no mass named "{d.at}"{did_you_mean(d.at, seen)}',
                    key="at",
                    value=d.at,
                )
            if d.name in seen or d.name == GROUND:
                raise InputError(
                    f'damper "{d.name}": a mass has this name already; name the ring otherwise',
                    key="name",
                    value=d.name,
                )
        if len({d.name for d in self.dampers}) != len(self.dampers):
            raise InputError("two dampers have the same name", key="name")
        for source in self.sources:
            for name in source.mass_names():
                if name not in seen:
                    raise InputError(
                        f'excitation source "{source.name}": no mass named "{name}"'
                        f"{did_you_mean(name, seen)}",
                        key="at",
                        value=name,
                    )
        _ = self._structure  # validate the topology now
        self._check_speed_ratios()
        self._check_inertia()
        self._check_scale()

    def _check_speed_ratios(self) -> None:
        """Refuse a mass turning more than :data:`SPEED_RATIO_LIMIT` times faster or slower
        than the reference through the gears (each mesh within its own bound, several in
        series can still multiply beyond what the solvers resolve)."""
        ratio = self._structure.speed_ratio
        bad = np.flatnonzero(~((ratio >= 1.0 / SPEED_RATIO_LIMIT) & (ratio <= SPEED_RATIO_LIMIT)))
        if bad.size:
            i = int(bad[0])
            raise InputError(
                f'"{self.masses[i].name}" turns at {ratio[i]:.3g} times the speed of '
                f'"{self.masses[self.reference_mass].name}" through the gears, beyond the 1e-6 to '
                "1e6 crankdyn resolves; check the gear ratios",
                key="gear",
                value=float(ratio[i]),
            )

    def _check_inertia(self) -> None:
        """Every degree of freedom needs inertia: a wheel without inertia only in a rigid mesh
        with one that has some."""
        empty = np.flatnonzero(self.dof_inertia <= 0.0)
        if empty.size:
            names = [self.masses[i].name for i in self.dofs[int(empty[0])]]
            if len(names) == 1:
                text = (
                    f'mass "{names[0]}" has no inertia: only a gear wheel joined by a rigid mesh '
                    "to a wheel with inertia may have none"
                )
            else:
                text = (
                    "the gear wheels "
                    + ", ".join(f'"{n}"' for n in names)
                    + " have no inertia together; give one of them the inertia of the gear "
                    "stage"
                )
            raise InputError(text, key="inertia", value=0.0)

    def _check_scale(self) -> None:
        """Refuse magnitudes whose natural frequencies would overflow double precision (a unit
        mistake, e.g. an inertia in kg mm^2 read as kg m^2 by orders of magnitude)."""
        total = float(np.sum(self.dof_inertia))
        k = self._shaft_values()[0]
        ends = self.shaft_dofs
        rows = np.zeros(self.dof_count)
        if k.size:
            grounded = (ends[:, 0] < 0) | (ends[:, 1] < 0)
            for e in (0, 1):
                inner = ~grounded
                np.add.at(rows, ends[inner, e], 2.0 * k[inner])
            g = np.where(ends[:, 0] < 0, ends[:, 1], ends[:, 0])[grounded]
            np.add.at(rows, g, k[grounded])
        with np.errstate(over="ignore"):
            bound = float(np.max(rows / self.dof_inertia))
        if not (math.isfinite(total) and bound <= OMEGA2_LIMIT):
            raise InputError(
                "the stiffnesses and inertias give natural frequencies beyond "
                f"{math.sqrt(OMEGA2_LIMIT):.0e} rad/s; check their units",
            )
        largest = max(float(np.max(self.dof_inertia)), float(np.max(k, initial=0.0)))
        if not largest <= MAGNITUDE_LIMIT:
            raise InputError(
                f"the model's inertias or stiffnesses reach {largest:.3g} (kg·m², N·m/rad), "
                f"beyond {MAGNITUDE_LIMIT:.0e}; check their units",
            )

    # ---- names and indices --------------------------------------------------------------------
    @cached_property
    def _index(self) -> dict[str, int]:
        return {m.name: i for i, m in enumerate(self.masses)}

    def index(self, name: str) -> int:
        """Listing index of a mass by name.

        Parameters
        ----------
        name : str
            Name of a mass.

        Returns
        -------
        int
            Its index in :attr:`masses` (0-based, from the free end).

        Raises
        ------
        crankdyn.errors.InputError
            For an unknown name (key ``mass``, the name as value, with the nearest name).

        Examples
        --------
        >>> model = TorsionModel.chain_of([1.0, 2.0], [5.0])
        >>> model.index("2")
        1
        >>> model.index("3")
        Traceback (most recent call last):
        ...
        crankdyn.errors.InputError: mass = "3": no mass named "3"
        """
        try:
            return self._index[name]
        except KeyError:
            raise InputError(
                f'no mass named "{name}"{did_you_mean(name, self._index)}', key="mass", value=name
            ) from None

    @cached_property
    def mass_names(self) -> tuple[str, ...]:
        """The names of the masses, in listing order."""
        return tuple(m.name for m in self.masses)

    @property
    def mass_count(self) -> int:
        """Number of masses (distributed-mass shafts' elements included)."""
        return len(self.masses)

    # ---- structure ----------------------------------------------------------------------------
    @cached_property
    def _structure(self) -> _Structure:
        return _analyse(self)

    @property
    def speed_ratios(self) -> NDArray[np.float64]:
        """Speed of every mass over the reference speed (dimensionless, > 0, 1 without gears)."""
        return self._structure.speed_ratio

    @property
    def rotation(self) -> NDArray[np.float64]:
        """Sense of rotation of every mass relative to the reference (+1 or -1): -1 beyond an
        odd number of reversing gear meshes."""
        return self._structure.rotation

    @cached_property
    def signed_speed_ratios(self) -> NDArray[np.float64]:
        """Speed ratio times the sense of rotation of every mass: the actual angle of a mass,
        measured in the reference mass's positive sense, is this times its reflected angle."""
        return _frozen(self._structure.speed_ratio * self._structure.rotation)

    @property
    def reference_mass(self) -> int:
        """Index of the mass whose speed is the reference: the first one carrying a cylinder,
        else the first mass."""
        return _reference(self.masses)

    @property
    def mass_dof(self) -> NDArray[np.int_]:
        """Degree of freedom of every mass (meshing masses share one)."""
        return self._structure.mass_dof

    @cached_property
    def _dofs_in_listing_order(self) -> bool:
        """Whether degree of freedom i is mass i for every mass (no rigid gear meshes, a chain
        listed in chain order): results by degree of freedom are then by mass."""
        dof = self.mass_dof
        return dof.size == self.dof_count and bool((dof == np.arange(dof.size)).all())

    @property
    def dofs(self) -> tuple[tuple[int, ...], ...]:
        """Mass indices of every degree of freedom (in chain order for a chain)."""
        return self._structure.dofs

    @property
    def dof_count(self) -> int:
        """Number of degrees of freedom (masses joined by rigid gear meshes count once)."""
        return len(self._structure.dofs)

    @cached_property
    def dof_names(self) -> tuple[str, ...]:
        """A name per degree of freedom: the mass name, or ``"a + b"`` for meshing masses."""
        return tuple(" + ".join(self.masses[i].name for i in d) for d in self.dofs)

    @property
    def shaft_dofs(self) -> NDArray[np.int_]:
        """(n_shafts, 2) degrees of freedom at the ends of every shaft, -1 for ground."""
        return self._structure.shaft_dofs

    @property
    def is_chain(self) -> bool:
        """Whether the degrees of freedom form a single line (tridiagonal stiffness)."""
        return self._structure.is_chain

    @property
    def junction(self) -> str | None:
        """A mass at which a branched model branches (None for a chain)."""
        return self._structure.junction

    @cached_property
    def is_free(self) -> bool:
        """Whether no shaft is grounded (the model then has one rigid-body mode)."""
        return not bool((self.shaft_dofs < 0).any())

    @property
    def cylinder_dofs(self) -> dict[int, int]:
        """{cylinder number: degree of freedom} for the masses that carry cylinders."""
        dof = self.mass_dof
        return {c: int(dof[i]) for i, m in enumerate(self.masses) for c in m.cylinders}

    # ---- matrices -----------------------------------------------------------------------------
    @cached_property
    def dof_inertia(self) -> NDArray[np.float64]:
        """Reflected moment of inertia of every degree of freedom (kg m^2)."""
        r2 = self.speed_ratios**2
        out = np.zeros(self.dof_count)
        np.add.at(out, self.mass_dof, np.array([m.inertia for m in self.masses]) * r2)
        return _frozen(out)

    @cached_property
    def _absolute_damping(self) -> NDArray[np.float64]:
        r2 = self.speed_ratios**2
        out = np.zeros(self.dof_count)
        np.add.at(out, self.mass_dof, np.array([m.damping for m in self.masses]) * r2)
        return out

    @cached_property
    def _shaft_arrays(
        self,
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        ratios = self.speed_ratios
        index = self._index
        first = [index[b[0] if b[0] != GROUND else b[1]] for b in (s.between for s in self.shafts)]
        r2 = ratios[np.array(first, dtype=int)] ** 2
        k = np.array([s.stiffness for s in self.shafts], dtype=float) * r2
        c = np.array([s.damping for s in self.shafts], dtype=float) * r2
        eta = np.array([s.loss_factor for s in self.shafts], dtype=float)
        return _frozen(k), _frozen(c), _frozen(eta * k)

    def _shaft_values(
        self,
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """Reflected stiffness, viscous damping and eta*k of every shaft (read-only arrays)."""
        return self._shaft_arrays

    def _assemble(
        self, values: NDArray[np.float64], diagonal: NDArray[np.float64] | None = None
    ) -> NDArray[np.float64]:
        """A symmetric (dof, dof) matrix of the shafts' ``values`` (each shaft a 2x2 block
        [[v, -v], [-v, v]], a grounded one v on its diagonal), plus ``diagonal``."""
        n = self.dof_count
        out = np.zeros((n, n))
        if diagonal is not None:
            out[np.diag_indices(n)] += diagonal
        ends = self.shaft_dofs
        if len(values) == 0:
            return out
        a, b = ends[:, 0], ends[:, 1]
        grounded = (a < 0) | (b < 0)
        g_dof = np.where(a < 0, b, a)[grounded]
        np.add.at(out, (g_dof, g_dof), values[grounded])
        a, b, v = a[~grounded], b[~grounded], values[~grounded]
        np.add.at(out, (a, a), v)
        np.add.at(out, (b, b), v)
        np.add.at(out, (a, b), -v)
        np.add.at(out, (b, a), -v)
        return out

    def mass_matrix(self) -> NDArray[np.float64]:
        """Diagonal inertia matrix M (kg m^2), degrees of freedom in :attr:`dofs` order.

        Returns
        -------
        numpy.ndarray
            M = diag(:attr:`dof_inertia`) (kg m^2), shape (dof, dof), reflected to the
            reference speed.

        Examples
        --------
        >>> TorsionModel.chain_of([1.0, 2.0], [5.0]).mass_matrix().tolist()
        [[1.0, 0.0], [0.0, 2.0]]
        """
        return np.diag(self.dof_inertia)

    def stiffness_matrix(self) -> NDArray[np.float64]:
        """Stiffness matrix K (N m/rad).

        Every shaft adds k [[1, -1], [-1, 1]] at its two degrees of freedom (k at its one for a
        grounded shaft), reflected to the reference speed (seed 003; Ker Wilson vol. 1 ch. 3).

        Returns
        -------
        numpy.ndarray
            K (N m/rad), shape (dof, dof), symmetric, in :attr:`dofs` order.

        Examples
        --------
        >>> TorsionModel.chain_of([1.0, 2.0], [5.0], ground_left=3.0).stiffness_matrix().tolist()
        [[8.0, -5.0], [-5.0, 5.0]]
        """
        return self._assemble(self._shaft_values()[0])

    def damping_matrix(self) -> NDArray[np.float64]:
        """Viscous damping matrix C (N m s/rad): absolute dampers and the shafts' relative
        damping.

        Returns
        -------
        numpy.ndarray
            C (N m s/rad), shape (dof, dof), symmetric: the masses' absolute damping on the
            diagonal, the shafts' relative damping assembled like the stiffness.

        Examples
        --------
        >>> model = TorsionModel(
        ...     masses=(Mass("a", 1.0, damping=2.0), Mass("b", 1.0)),
        ...     shafts=(Shaft(("a", "b"), 100.0, damping=0.5),),
        ... )
        >>> model.damping_matrix().tolist()
        [[2.5, -0.5], [-0.5, 0.5]]
        """
        return self._assemble(self._shaft_values()[1], self._absolute_damping)

    def hysteretic_matrix(self) -> NDArray[np.float64]:
        """Hysteretic damping matrix H = sum of eta_s K_s (N m/rad): the dynamic stiffness is
        K + i H - omega^2 M + i omega C.

        Returns
        -------
        numpy.ndarray
            H (N m/rad), shape (dof, dof), symmetric: every shaft's loss factor times its
            stiffness, assembled like the stiffness.

        Examples
        --------
        >>> model = TorsionModel(
        ...     masses=(Mass("a", 1.0), Mass("b", 1.0)),
        ...     shafts=(Shaft(("a", "b"), 100.0, loss_factor=0.1),),
        ... )
        >>> model.hysteretic_matrix().round(12).tolist()
        [[10.0, -10.0], [-10.0, 10.0]]
        """
        return self._assemble(self._shaft_values()[2])

    @cached_property
    def chain(self) -> ChainArrays | None:
        """The chain arrays (reflected, chain order), or None for a branched model."""
        if not self.is_chain:
            return None
        n = self.dof_count
        values = np.stack(self._shaft_values())  # (3, shafts): k, c, eta k
        ends = self.shaft_dofs
        grounded = (ends[:, 0] < 0) | (ends[:, 1] < 0)
        between = np.zeros((3, max(n - 1, 0)))
        ground = np.zeros((3, n))
        inner = ~grounded
        np.add.at(between.T, np.minimum(ends[inner, 0], ends[inner, 1]), values[:, inner].T)
        g = np.maximum(ends[grounded, 0], ends[grounded, 1])
        np.add.at(ground.T, g, values[:, grounded].T)
        return ChainArrays(
            inertia=self.dof_inertia,
            stiffness=_frozen(between[0]),
            damping=_frozen(between[1]),
            hysteretic=_frozen(between[2]),
            ground_stiffness=_frozen(ground[0]),
            ground_damping=_frozen(ground[1] + self._absolute_damping),
            ground_hysteretic=_frozen(ground[2]),
        )

    # ---- alternate constructors ---------------------------------------------------------------
    def _repr_html_(self) -> str:
        """The mass-elastic system: masses, shafts and gears (notebooks)."""
        from crankdyn.display import torsion_model_html

        return torsion_model_html(self)

    @classmethod
    def from_file(cls, path: str | Path) -> TorsionModel:
        """Load a torsional model file (TOML; docs/torsion-file.md), an engine file's
        [torsion] section, or a mass-elastic table (.csv, :mod:`crankdyn.io.mass_elastic`).

        Parameters
        ----------
        path : str or pathlib.Path
            The file.

        Returns
        -------
        TorsionModel
            The model, with its ``source`` set to the file.

        Raises
        ------
        crankdyn.errors.InputError
            For a missing, unreadable or malformed file, or a bad value, naming the file, the
            key and the value (:func:`crankdyn.io.catalogue.load_torsion_model`).
        """
        from crankdyn.io.catalogue import load_torsion_model  # boundary, on demand

        return load_torsion_model(path)

    @classmethod
    def example(cls, name: str) -> TorsionModel:
        """A built-in torsional model by name (``crankdyn torsion examples`` lists them).

        Parameters
        ----------
        name : str
            Name of the example.

        Returns
        -------
        TorsionModel
            The example model.

        Raises
        ------
        crankdyn.errors.InputError
            For an unknown name (with the nearest one).
        """
        from crankdyn.io.catalogue import load_example

        return load_example(name, "model")

    @classmethod
    def from_opentorsion(cls, assembly: Any, *, name: str = "openTorsion assembly") -> TorsionModel:
        """A model from an openTorsion ``Assembly`` (:mod:`crankdyn.torsion.opentorsion`).

        Parameters
        ----------
        assembly : opentorsion.Assembly
            The assembly (only its element attributes are read; openTorsion need not be
            installed).
        name : str
            Name of the model, for reports.

        Returns
        -------
        TorsionModel
            One mass per node, named ``"node <i>"``
            (:func:`crankdyn.torsion.opentorsion.from_opentorsion`).
        """
        from crankdyn.torsion.opentorsion import from_opentorsion

        return from_opentorsion(assembly, name=name)

    def to_opentorsion(self, *, hysteretic_frequency: float | None = None) -> Any:
        """The model as an openTorsion ``Assembly`` (:mod:`crankdyn.torsion.opentorsion`; needs
        openTorsion installed).

        Parameters
        ----------
        hysteretic_frequency : float or None
            Circular frequency omega_h (rad/s) at which loss factors are exported as viscous
            damping eta k / omega_h; required when a shaft has a loss factor.

        Returns
        -------
        opentorsion.Assembly
            The assembly (:func:`crankdyn.torsion.opentorsion.to_opentorsion`).
        """
        from crankdyn.torsion.opentorsion import to_opentorsion

        return to_opentorsion(self, hysteretic_frequency=hysteretic_frequency)

    @classmethod
    def chain_of(
        cls,
        inertias: Iterable[float],
        stiffnesses: Iterable[float],
        *,
        ground_left: float | None = None,
        ground_right: float | None = None,
        name: str = "chain",
    ) -> TorsionModel:
        """A chain of masses ``"1"``, ``"2"``... joined by the given shaft stiffnesses, with an
        optional grounded shaft at either end.

        Parameters
        ----------
        inertias : iterable of float
            Moments of inertia of the masses (kg m^2), each > 0, shape (n,).
        stiffnesses : iterable of float
            Stiffnesses of the shafts between neighbours (N m/rad), each > 0, shape (n - 1,).
        ground_left, ground_right : float or None
            Stiffness (N m/rad) of a shaft from the first (last) mass to ground, or None.
        name : str
            Name of the model, for reports.

        Returns
        -------
        TorsionModel
            The chain, masses named ``"1"`` to ``"n"``.

        Raises
        ------
        crankdyn.errors.InputError
            For a stiffness count other than n - 1 (key ``stiffness``, the count as value), or a
            value that is not positive and finite (its key and value).

        Examples
        --------
        Two equal discs on a shaft: one rigid-body mode and omega^2 = 2 k / J (seed 003):

        >>> import numpy as np
        >>> model = TorsionModel.chain_of([2.0, 2.0], [100.0])
        >>> model.mass_names, model.is_free
        (('1', '2'), True)
        >>> np.linalg.eigvalsh(model.stiffness_matrix() / 2.0).round(9).tolist()
        [0.0, 100.0]
        """
        inertias = list(inertias)
        stiffnesses = list(stiffnesses)
        if len(stiffnesses) != len(inertias) - 1:
            raise InputError(
                f"a chain of {len(inertias)} masses needs {len(inertias) - 1} stiffnesses",
                key="stiffness",
                value=len(stiffnesses),
            )
        names = [str(i + 1) for i in range(len(inertias))]
        values = _positive_numbers(inertias), _positive_numbers(stiffnesses)
        if values[0] is not None and values[1] is not None:
            # plain positive finite numbers, checked at once: what Mass and Shaft would accept
            masses = tuple(Mass._checked(n, j) for n, j in zip(names, values[0], strict=True))
            pairs = zip(names[:-1], names[1:], values[1], strict=True)
            shafts = [Shaft._checked((a, b), k) for a, b, k in pairs]
        else:  # the constructors name the offending value
            masses = tuple(Mass(n, j) for n, j in zip(names, inertias, strict=True))
            shafts = [Shaft((names[i], names[i + 1]), k) for i, k in enumerate(stiffnesses)]
        if ground_left is not None:
            shafts.insert(0, Shaft((GROUND, names[0]), ground_left))
        if ground_right is not None:
            shafts.append(Shaft((names[-1], GROUND), ground_right))
        return cls(masses=masses, shafts=tuple(shafts), name=name)


# ---- topology ---------------------------------------------------------------------------------


def _reference(masses: Sequence[Mass]) -> int:
    """Index of the first mass that carries a cylinder, else 0."""
    for i, m in enumerate(masses):
        if m.cylinders:
            return i
    return 0


def _analyse(model: TorsionModel) -> _Structure:
    """The model's topology: degrees of freedom (rigid meshes merged), signed speed ratios
    (a breadth-first walk from the reference mass), chain order or a junction; InputError for
    inconsistent gear loops, shafts inside a rigid gear group or a disconnected model."""
    masses, shafts, gears = model.masses, model.shafts, model.gears
    n = len(masses)
    index = {m.name: i for i, m in enumerate(masses)}

    # degrees of freedom: masses tied by gear meshes are one
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

    tied = next(  # a shaft inside a rigid gear group: reported before a sense conflict
        (
            s
            for s in shafts
            if not s.grounded and group_of[index[s.between[0]]] == group_of[index[s.between[1]]]
        ),
        None,
    )

    # speed ratios by a breadth-first walk over shafts (ratio 1) and gears (ratio r); the
    # neighbour lists name the joining element by (kind, index) and its label is written only
    # for a message
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
    ref = _reference(masses)
    # signed speed ratios: the sense of rotation travels with the ratio
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
    return _Structure(
        speed_ratio=ratio,
        rotation=rotation,
        mass_dof=mass_dof,
        dofs=dofs,
        shaft_dofs=shaft_dofs,
        is_chain=is_chain,
        junction=junction,
    )
