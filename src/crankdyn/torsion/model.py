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
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from crankdyn.crank.geometry import check_finite, check_positive
from crankdyn.errors import InputError, did_you_mean

__all__ = [
    "GROUND",
    "ChainArrays",
    "Gear",
    "Mass",
    "Shaft",
    "ShaftGeometry",
    "TorsionModel",
    "shaft_stiffness",
]

GROUND = "ground"
"""Reserved mass name: a shaft ending at ``"ground"`` holds that end fixed."""

_RATIO_TOL = 1e-9
OMEGA2_LIMIT = 1e100
"""Largest omega^2 bound (Gershgorin, rad^2/s^2) a model may have: keeps every product of the
solvers (J omega^2 theta, determinants' ratios) far from overflow."""


def _nonnegative(name: str, value: float, what: str) -> float:
    number = check_finite(name, value)
    if number < 0.0:
        raise InputError(f"{what} must not be negative", key=name, value=value)
    return number


def _name(value: object, key: str = "name") -> str:
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
    length
        Shaft length l (m).
    outer_diameter, inner_diameter
        Outer diameter D and bore d (m), 0 <= d < D.
    shear_modulus
        Shear modulus G (Pa).
    """
    polar = math.pi * (outer_diameter**4 - inner_diameter**4) / 32.0
    return shear_modulus * polar / length


@dataclass(frozen=True)
class Mass:
    """A rigid disc of the lumped model.

    Parameters
    ----------
    name
        Unique name (``"ground"`` is reserved).
    inertia
        Moment of inertia J about the shaft axis (kg m^2), > 0.
    damping
        Absolute viscous damping to ground c (N m s/rad), >= 0 (e.g. piston friction at a
        crank throw).
    cylinders
        Engine cylinders whose gas and inertia torques act on this mass (1-based numbers), for
        the forced response; empty for masses that are not crank throws.
    """

    name: str
    inertia: float
    damping: float = 0.0
    cylinders: tuple[int, ...] = ()

    def __post_init__(self) -> None:
        name = _name(self.name)
        if name == GROUND:
            raise InputError(
                f'"{GROUND}" is reserved for the fixed end of a grounded shaft', key="name"
            )
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
        for key, value in (("name", name), ("inertia", inertia), ("damping", 0.0)):
            object.__setattr__(mass, key, value)
        object.__setattr__(mass, "cylinders", ())
        return mass


@dataclass(frozen=True)
class ShaftGeometry:
    """Cross-section (and, when known, length and material) of a uniform round shaft.

    Parameters
    ----------
    outer_diameter
        Outer diameter D (m).
    inner_diameter
        Bore d (m), 0 <= d < D.
    length
        Length l (m), or None when the stiffness is given directly.
    shear_modulus
        Shear modulus G (Pa), or None when the stiffness is given directly.
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
    """A massless elastic connection between two masses (or a mass and ``"ground"``).

    Parameters
    ----------
    between
        The two mass names; one of them may be ``"ground"`` (a grounded end).
    stiffness
        Torsional stiffness k (N m/rad), > 0; None to take it from ``geometry``.
    damping
        Relative viscous damping c between the two ends (N m s/rad), >= 0.
    loss_factor
        Hysteretic loss factor eta (dimensionless), >= 0: a damping torque eta k times the twist,
        in phase with the twist rate (equivalent viscous c = eta k / omega).
    geometry
        Shaft cross-section, and length and shear modulus when the stiffness is not given
        (kept for nominal shear stresses).
    """

    between: tuple[str, str]
    stiffness: float | None = None
    damping: float = 0.0
    loss_factor: float = 0.0
    geometry: ShaftGeometry | None = None

    def __post_init__(self) -> None:
        ends = tuple(self.between) if isinstance(self.between, (list, tuple)) else ()
        if len(ends) != 2 or any(not isinstance(e, str) or not e.strip() for e in ends):
            raise InputError("expected the names of two masses", key="between", value=ends)
        if ends[0] == ends[1]:
            raise InputError("a shaft must join two different masses", key="between", value=ends)
        if ends == (GROUND, GROUND):
            raise InputError("a shaft cannot join ground to ground", key="between", value=ends)
        object.__setattr__(self, "between", ends)
        given = self.stiffness
        from_geometry = self.geometry.stiffness if self.geometry is not None else None
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

    @classmethod
    def _checked(cls, between: tuple[str, str], stiffness: float) -> Shaft:
        """A shaft between two distinct masses (not ground) with a stiffness the caller has
        already validated (a positive finite float), without validating them again."""
        shaft = object.__new__(cls)
        for key, value in (
            ("between", between),
            ("stiffness", stiffness),
            ("damping", 0.0),
            ("loss_factor", 0.0),
            ("geometry", None),
        ):
            object.__setattr__(shaft, key, value)
        return shaft

    @property
    def grounded(self) -> bool:
        """Whether one end is ``"ground"``."""
        return GROUND in self.between

    @property
    def label(self) -> str:
        """``"a - b"`` for tables and messages."""
        return f"{self.between[0]} - {self.between[1]}"


@dataclass(frozen=True)
class Gear:
    """A rigid gear mesh between two masses.

    Parameters
    ----------
    between
        The two meshing masses (gear wheels) ``(a, b)``.
    ratio
        Speed ratio n_b / n_a (dimensionless), > 0; the direction of rotation does not matter
        for the reflected model.
    """

    between: tuple[str, str]
    ratio: float

    def __post_init__(self) -> None:
        ends = tuple(self.between) if isinstance(self.between, (list, tuple)) else ()
        if len(ends) != 2 or any(not isinstance(e, str) or not e.strip() for e in ends):
            raise InputError("expected the names of two masses", key="between", value=ends)
        if ends[0] == ends[1]:
            raise InputError("a gear must join two different masses", key="between", value=ends)
        if GROUND in ends:
            raise InputError(f'a gear cannot mesh with "{GROUND}"', key="between", value=ends)
        object.__setattr__(self, "between", ends)
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
                "give the gear ratio as a positive speed ratio n_b/n_a (the direction of "
                "rotation does not matter here)",
                key="ratio",
                value=self.ratio,
            )
        object.__setattr__(self, "ratio", ratio)


@dataclass(frozen=True)
class ChainArrays:
    """A chain model in chain order: degree of freedom i is joined to i + 1 (SI arrays).

    All values are reflected to the reference speed.
    """

    inertia: np.ndarray  # (n,) kg m^2
    stiffness: np.ndarray  # (n-1,) N m/rad, between neighbours
    damping: np.ndarray  # (n-1,) N m s/rad, relative viscous between neighbours
    hysteretic: np.ndarray  # (n-1,) N m/rad, sum of loss factor x stiffness between neighbours
    ground_stiffness: np.ndarray  # (n,) N m/rad, shafts to ground
    ground_damping: np.ndarray  # (n,) N m s/rad, absolute dampers and grounded shafts' damping
    ground_hysteretic: np.ndarray  # (n,) N m/rad, loss factor x stiffness of grounded shafts

    @property
    def size(self) -> int:
        return int(self.inertia.size)

    def stiffness_diagonals(self) -> tuple[np.ndarray, np.ndarray]:
        """Main and off diagonal of the tridiagonal stiffness matrix K."""
        k = self.stiffness
        diag = self.ground_stiffness.copy()
        diag[:-1] += k
        diag[1:] += k
        return diag, -k


def _positive_numbers(values: list) -> list[float] | None:
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


def _frozen(values, dtype=float) -> np.ndarray:
    arr = np.array(values, dtype=dtype)
    arr.setflags(write=False)
    return arr


@dataclass(frozen=True)
class _Structure:
    speed_ratio: np.ndarray  # per mass
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
    masses
        The masses, listed from the free end (the listing order of every output).
    shafts
        Elastic connections between masses, or between a mass and ``"ground"``.
    gears
        Rigid gear meshes; the masses beyond a gear are reflected to the reference speed.
    name
        Name for reports.
    source
        The file the model came from, for messages.
    excitation
        How the model is excited in a forced response
        (:class:`crankdyn.torsion.excitation.ExcitationSpec`), or None.
    dampers
        Vibration dampers (:class:`crankdyn.torsion.dampers.Damper`) added by the forced
        response; not part of the matrices above (model a tuned damper as a mass and a shaft to
        see it in the natural frequencies, or use :func:`crankdyn.torsion.campbell.with_dampers`).
    rules
        Rule-check inputs (:class:`crankdyn.torsion.rules.RuleSet`), or None.
    operating
        Operating speed range (:class:`crankdyn.torsion.campbell.OperatingRange`), or None.

    Raises
    ------
    InputError
        For duplicate or reserved names, a shaft or gear naming an unknown mass, a cylinder on
        two masses, gear ratios that disagree around a loop, a shaft between two masses a gear
        already ties together, or a disconnected model.
    """

    masses: tuple[Mass, ...]
    shafts: tuple[Shaft, ...] = ()
    gears: tuple[Gear, ...] = ()
    name: str = "torsional model"
    source: str | None = field(default=None, compare=False)
    excitation: object = None
    dampers: tuple = ()
    rules: object = None
    operating: object = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "dampers", tuple(self.dampers))
        masses = tuple(self.masses)
        if not masses:
            raise InputError("a torsional model needs at least one mass", key="mass")
        if any(not isinstance(m, Mass) for m in masses):
            raise TypeError("masses must be Mass objects")
        object.__setattr__(self, "masses", masses)
        object.__setattr__(self, "shafts", tuple(self.shafts))
        object.__setattr__(self, "gears", tuple(self.gears))
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
        _ = self._structure  # validate the topology now
        self._check_scale()

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

    # ---- names and indices --------------------------------------------------------------------
    @cached_property
    def _index(self) -> dict[str, int]:
        return {m.name: i for i, m in enumerate(self.masses)}

    def index(self, name: str) -> int:
        """Listing index of a mass by name."""
        try:
            return self._index[name]
        except KeyError:
            raise InputError(
                f'no mass named "{name}"{did_you_mean(name, self._index)}', key="mass", value=name
            ) from None

    @property
    def mass_names(self) -> tuple[str, ...]:
        return tuple(m.name for m in self.masses)

    @property
    def mass_count(self) -> int:
        return len(self.masses)

    # ---- structure ----------------------------------------------------------------------------
    @cached_property
    def _structure(self) -> _Structure:
        return _analyse(self)

    @property
    def speed_ratios(self) -> np.ndarray:
        """Speed of every mass over the reference speed (dimensionless, 1 without gears)."""
        return self._structure.speed_ratio

    @property
    def reference_mass(self) -> int:
        """Index of the mass whose speed is the reference: the first one carrying a cylinder,
        else the first mass."""
        return _reference(self.masses)

    @property
    def mass_dof(self) -> np.ndarray:
        """Degree of freedom of every mass (meshing masses share one)."""
        return self._structure.mass_dof

    @property
    def dofs(self) -> tuple[tuple[int, ...], ...]:
        """Mass indices of every degree of freedom (in chain order for a chain)."""
        return self._structure.dofs

    @property
    def dof_count(self) -> int:
        return len(self._structure.dofs)

    @property
    def dof_names(self) -> tuple[str, ...]:
        """A name per degree of freedom: the mass name, or ``"a + b"`` for meshing masses."""
        return tuple(" + ".join(self.masses[i].name for i in d) for d in self.dofs)

    @property
    def shaft_dofs(self) -> np.ndarray:
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

    @property
    def is_free(self) -> bool:
        """Whether no shaft is grounded (the model then has one rigid-body mode)."""
        return not any(s.grounded for s in self.shafts)

    @property
    def cylinder_dofs(self) -> dict[int, int]:
        """{cylinder number: degree of freedom} for the masses that carry cylinders."""
        dof = self.mass_dof
        return {c: int(dof[i]) for i, m in enumerate(self.masses) for c in m.cylinders}

    # ---- matrices -----------------------------------------------------------------------------
    @cached_property
    def dof_inertia(self) -> np.ndarray:
        """Reflected moment of inertia of every degree of freedom (kg m^2)."""
        r2 = self.speed_ratios**2
        out = np.zeros(self.dof_count)
        np.add.at(out, self.mass_dof, np.array([m.inertia for m in self.masses]) * r2)
        return _frozen(out)

    @cached_property
    def _absolute_damping(self) -> np.ndarray:
        r2 = self.speed_ratios**2
        out = np.zeros(self.dof_count)
        np.add.at(out, self.mass_dof, np.array([m.damping for m in self.masses]) * r2)
        return out

    @cached_property
    def _shaft_arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        ratios = self.speed_ratios
        index = self._index
        first = [index[b[0] if b[0] != GROUND else b[1]] for b in (s.between for s in self.shafts)]
        r2 = ratios[np.array(first, dtype=int)] ** 2
        k = np.array([s.stiffness for s in self.shafts], dtype=float) * r2
        c = np.array([s.damping for s in self.shafts], dtype=float) * r2
        eta = np.array([s.loss_factor for s in self.shafts], dtype=float)
        return _frozen(k), _frozen(c), _frozen(eta * k)

    def _shaft_values(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Reflected stiffness, viscous damping and eta*k of every shaft (read-only arrays)."""
        return self._shaft_arrays

    def _assemble(self, values: np.ndarray, diagonal: np.ndarray | None = None) -> np.ndarray:
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

    def mass_matrix(self) -> np.ndarray:
        """Diagonal inertia matrix M (kg m^2), degrees of freedom in :attr:`dofs` order."""
        return np.diag(self.dof_inertia)

    def stiffness_matrix(self) -> np.ndarray:
        """Stiffness matrix K (N m/rad)."""
        return self._assemble(self._shaft_values()[0])

    def damping_matrix(self) -> np.ndarray:
        """Viscous damping matrix C (N m s/rad): absolute dampers and the shafts' relative
        damping."""
        return self._assemble(self._shaft_values()[1], self._absolute_damping)

    def hysteretic_matrix(self) -> np.ndarray:
        """Hysteretic damping matrix H = sum of eta_s K_s (N m/rad): the dynamic stiffness is
        K + i H - omega^2 M + i omega C."""
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
    def from_file(cls, path) -> TorsionModel:
        """Load a torsional model file (TOML; docs/torsion-file.md)."""
        from crankdyn.io.catalogue import load_torsion_model  # boundary, on demand

        return load_torsion_model(path)

    @classmethod
    def example(cls, name: str) -> TorsionModel:
        """A built-in torsional model by name (``crankdyn torsion examples`` lists them)."""
        from crankdyn.io.catalogue import load_example

        return load_example(name, "model")

    @classmethod
    def chain_of(
        cls,
        inertias,
        stiffnesses,
        *,
        ground_left: float | None = None,
        ground_right: float | None = None,
        name: str = "chain",
    ) -> TorsionModel:
        """A chain of masses ``"1"``, ``"2"``... joined by the given shaft stiffnesses, with an
        optional grounded shaft at either end (stiffness in N m/rad)."""
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


def _reference(masses) -> int:
    for i, m in enumerate(masses):
        if m.cylinders:
            return i
    return 0


def _analyse(model: TorsionModel) -> _Structure:
    masses, shafts, gears = model.masses, model.shafts, model.gears
    n = len(masses)
    index = {m.name: i for i, m in enumerate(masses)}

    # speed ratios by a breadth-first walk over shafts (ratio 1) and gears (ratio r); the
    # neighbour lists name the joining element by (kind, index) and its label is written only
    # for a message
    neighbours: list[list[tuple[int, float, str, int]]] = [[] for _ in range(n)]
    for i_s, s in enumerate(shafts):
        if s.grounded:
            continue
        a, b = index[s.between[0]], index[s.between[1]]
        neighbours[a].append((b, 1.0, "shaft", i_s))
        neighbours[b].append((a, 1.0, "shaft", i_s))
    for i_g, g in enumerate(gears):
        a, b = index[g.between[0]], index[g.between[1]]
        neighbours[a].append((b, g.ratio, "gear", i_g))
        neighbours[b].append((a, 1.0 / g.ratio, "gear", i_g))
    ref = _reference(masses)
    found: list[float | None] = [None] * n
    found[ref] = 1.0
    queue = deque([ref])
    while queue:
        i = queue.popleft()
        here = found[i]
        for j, r, kind, k in neighbours[i]:
            value = here * r
            there = found[j]
            if there is None:
                found[j] = value
                queue.append(j)
            elif abs(there - value) > _RATIO_TOL * max(there, value):
                if kind == "shaft":
                    label = f'shaft "{shafts[k].label}"'
                else:
                    label = f'gear "{gears[k].between[0]}" - "{gears[k].between[1]}"'
                raise InputError(
                    f'the speed of "{masses[j].name}" comes out as {there:.6g} and as '
                    f"{value:.6g} times the reference speed around a loop through the {label}: "
                    "the gear ratios disagree",
                )
    ratio = np.array([np.nan if r is None else r for r in found], dtype=float)
    lost = [masses[i].name for i in range(n) if found[i] is None]
    if lost:
        more = f" and {len(lost) - 1} more" if len(lost) > 1 else ""
        raise InputError(
            f'the model is disconnected: no shaft or gear joins "{lost[0]}"{more} to '
            f'"{masses[ref].name}"',
        )

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
    return _Structure(
        speed_ratio=ratio,
        mass_dof=mass_dof,
        dofs=dofs,
        shaft_dofs=shaft_dofs,
        is_chain=is_chain,
        junction=junction,
    )
