"""The elements of a lumped torsional model: masses, shafts and gear meshes (domain objects).

A :class:`Mass` is a rigid disc (a moment of inertia and an absolute damping to ground); a
:class:`Shaft` a massless elastic shaft (a torsional stiffness, given or from the shaft's
geometry, :class:`ShaftGeometry`, with relative viscous damping and/or a loss factor), an elastic
coupling or an elastic gear mesh; a :class:`Gear` a rigid or elastic gear mesh (a speed ratio).
A shaft may end at the reserved name ``"ground"`` (:data:`GROUND`), which holds that end fixed
(a grounded end). :class:`crankdyn.torsion.model.TorsionModel` joins them into a model.

This is the equivalent system of seed 003 ("扭振当量系统": the equivalent moments of inertia are
placed where the real shaft carries its concentrated masses; the equivalent shaft sections have
the stiffness of the real sections and no mass).

Conventions (docs/conventions.md): masses are listed from the free end; SI units throughout
(kg m^2, N m/rad, N m s/rad); a shaft's stiffness and damping are referred to the speed of its
first mass (:mod:`crankdyn.torsion.model` reflects them to the reference speed).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from crankdyn.crank.geometry import check_finite, check_positive
from crankdyn.display import printable
from crankdyn.errors import InputError, did_you_mean
from crankdyn.torsion.coupling import Coupling

__all__ = [
    "GEAR_DIRECTIONS",
    "GROUND",
    "MASS_ROLES",
    "SHAFT_ROLES",
    "Gear",
    "Mass",
    "MassLimits",
    "Shaft",
    "ShaftGeometry",
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

GEAR_RATIO_LIMIT = 1e3
"""Largest speed ratio of one gear mesh, either way (n_b/n_a within 1/1000 to 1000): the
largest single-stage ratios built are about 100:1 (worm gears) to 300:1 (strain-wave gears),
so beyond 1000 the ratio or the tooth numbers are a mistake; reflected through such a mesh,
inertias and stiffnesses scale by the ratio squared and excitation orders by the ratio, beyond
what the solvers resolve (1e12 teeth made orders of 4e-12 and overflowing products)."""
SPEED_RATIO_LIMIT = GEAR_RATIO_LIMIT**2
"""Largest speed ratio of a mass to the reference mass through all the meshes between them,
either way (1e-6 to 1e6: two stages of the largest mesh)."""

SHAFT_ROLES = ("crankshaft", "propulsion shaft", "shaft")
"""What a plain shaft is, for the rule checks: a crank span, a propulsion shaft (intermediate,
thrust or propeller shaft: IACS UR M68) or another shaft. Couplings and gear meshes are told by
their data (:attr:`Shaft.kind`)."""

GEAR_DIRECTIONS = ("opposite", "same")
"""Direction of rotation of a gear's second wheel relative to its first: ``"opposite"`` for an
external mesh, ``"same"`` for an internal (ring) mesh or a gear train that keeps the sense."""


def _nonnegative(name: str, value: float, what: str) -> float:
    """``value`` as a finite float >= 0, else an InputError naming ``name`` and the value."""
    number = check_finite(name, value)
    if number < 0.0:
        raise InputError(f"{what} must not be negative", key=name, value=value)
    return number


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
        For an empty or reserved name (key ``name``), an unknown role (``role``, with the
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
        coupling), a negative damping or loss factor, an unknown role, a direction other than
        +1 or -1, an element count outside 1 to 10000, or distributed inertia on a mesh, a
        coupling or a grounded shaft (``inertia``); each message carries the value given.

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
        the tooth numbers (``ratio``), bad tooth numbers (``teeth``), an unknown direction
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
