"""Lumped torsional model of a shaft line (domain objects).

A :class:`TorsionModel` is a set of rigid discs (:class:`~crankdyn.torsion.elements.Mass`: a
moment of inertia and an absolute damping to ground) joined by massless elastic shafts
(:class:`~crankdyn.torsion.elements.Shaft`: a torsional stiffness, given or from the shaft's
geometry, with relative viscous damping and/or a loss factor) and by rigid gear meshes
(:class:`~crankdyn.torsion.elements.Gear`: a speed ratio): the elements of
:mod:`crankdyn.torsion.elements`. A shaft may end at the reserved name ``"ground"``, which holds
that end fixed (a grounded end); without such a shaft the system is free and has one rigid-body
mode.

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
a single line is a *chain* (:mod:`crankdyn.torsion.topology`): its stiffness matrix is
tridiagonal in chain order, and the modal solver, Holzer's method and the transfer-matrix method
work on :attr:`TorsionModel.chain`.
Other (branched or looped) models use the general symmetric solver on the dense matrices.

Conventions (docs/conventions.md): masses are listed from the free end; SI units throughout
(kg m^2, N m/rad, N m s/rad).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Iterable
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from crankdyn.errors import InputError, did_you_mean
from crankdyn.torsion.elements import GROUND, SPEED_RATIO_LIMIT, Gear, Mass, Shaft
from crankdyn.torsion.topology import Structure, model_structure, reference_mass

if TYPE_CHECKING:
    from crankdyn.engine.model import Engine
    from crankdyn.plausibility import PlausibilityWarning
    from crankdyn.project import Project
    from crankdyn.torsion.campbell import OperatingRange
    from crankdyn.torsion.dampers import Damper
    from crankdyn.torsion.excitation_spec import ExcitationSpec
    from crankdyn.torsion.rules import RuleSet
    from crankdyn.torsion.sources import EngineSource, HarmonicSource
    from crankdyn.tvc.spec import TvcSpec

__all__ = ["ChainArrays", "TorsionModel"]

OMEGA2_LIMIT = 1e100
"""Largest omega^2 bound (Gershgorin, rad^2/s^2) a model may have: keeps every product of the
solvers (J omega^2 theta, determinants' ratios) far from overflow."""
MAGNITUDE_LIMIT = 1e20
"""Largest reflected inertia (kg m^2) or stiffness (N m/rad) a model may have, far beyond any
machine (a large marine shaft line: 1e7 kg m^2, 1e10 N m/rad): beyond it the values are a unit
mistake, and the products of the solvers (J omega^2 theta) approach overflow."""


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
        (:meth:`~crankdyn.torsion.elements.Gear.mesh_shaft`); rigid ones stay here and merge
        their wheels into one degree of freedom.
    name : str
        Name for reports.
    source : str or None
        The file the model came from, for messages.
    excitation : crankdyn.torsion.excitation_spec.ExcitationSpec or None
        How the model is excited in a forced response
        (:class:`crankdyn.torsion.excitation_spec.ExcitationSpec`), or None.
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
    project : crankdyn.project.Project or None
        The document control of the installation (``[project]``: project, yard, engine type,
        revisions, signatures) for the TVC's title page, or None; no calculation reads it.
    input_warnings : tuple of crankdyn.plausibility.InputWarning
        The values of the file(s) the model was read from that lie outside the plausible
        range of their role (:mod:`crankdyn.io.plausibility`); every result of an analysis
        session on the model carries them, and its verdicts cannot read a clean "passed".

    Raises
    ------
    crankdyn.errors.InputError
        For duplicate or reserved names (key ``name``), a shaft, gear, damper or source naming
        an unknown mass (``between``, ``at``, with the nearest name), a cylinder on two masses
        (``cylinders``), gear ratios or senses that disagree around a loop, a shaft between two
        masses a gear already ties together (``between``), a disconnected model, a degree of
        freedom without inertia (``inertia``), or magnitudes beyond :data:`MAGNITUDE_LIMIT` or
        :data:`OMEGA2_LIMIT` (a unit mistake).
    TypeError
        When ``masses`` holds something other than :class:`~crankdyn.torsion.elements.Mass`
        objects.

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
    project: Project | None = field(default=None, compare=False, repr=False)
    input_warnings: tuple[PlausibilityWarning, ...] = field(default=(), compare=False, repr=False)

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
        """Refuse a mass turning more than :data:`~crankdyn.torsion.elements.SPEED_RATIO_LIMIT`
        times faster or slower than the reference through the gears (each mesh within its own
        bound, several in series can still multiply beyond what the solvers resolve)."""
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
    def _structure(self) -> Structure:
        return model_structure(self)

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
        return reference_mass(self.masses)

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
    def static_factor(self) -> tuple[NDArray[np.bool_], Any] | None:
        """The stiffness matrix K factorised once for the static equilibrium K X = F of the mean
        torques (:func:`crankdyn.torsion.sources.mean_torques`): a free model held at its
        reference mass's degree of freedom. (kept degrees of freedom, the LU factors of K on
        them: :func:`scipy.linalg.lu_factor`, LAPACK getrf, the factorisation
        ``numpy.linalg.solve`` makes at every call), or None when no degree of freedom is kept.
        Every speed and every evaluation of a sweep then costs a triangular solve, not a new
        factorisation (O(n^2) against O(n^3))."""
        import scipy.linalg  # here: not on the command line's start-up path

        keep = np.ones(self.dof_count, dtype=bool)
        if self.is_free:
            keep[int(self.mass_dof[self.reference_mass])] = False
        if not np.any(keep):
            return None
        k = self.stiffness_matrix()[np.ix_(keep, keep)]
        with warnings.catch_warnings():  # a singular K: refused where it is solved
            warnings.simplefilter("ignore", scipy.linalg.LinAlgWarning)
            return keep, scipy.linalg.lu_factor(k, check_finite=False)

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
