"""Forces in the crank train: gas and inertia forces, rod, side, tangential and radial forces,
crank-pin load (seed 000 section 2.2), vectorized over crank angle and cylinders.

Conventions (docs/conventions.md, seed 000 section 2.2). For one cylinder at crank angle phi
(rad from its cylinder axis, positive in the direction of rotation), rod angle beta with
sin(beta) = lambda (sin(phi) - k):

- gas force P_g = (p - p_cc) A, positive pushing the piston toward the crank; p absolute,
  p_cc the crankcase pressure, A the piston area;
- reciprocating inertia force P_j = -m_j a (a: exact piston acceleration, positive toward the
  crank); its 1st- and 2nd-order parts are the first two harmonics of the exact force,
  P_jI = m_j R w^2 (c_1 cos(phi) + s_1 sin(phi)) and
  P_jII = 4 m_j R w^2 (c_2 cos(2 phi) + s_2 sin(2 phi)) with the Fourier coefficients c_m, s_m
  of x/R (:func:`crankdyn.crank.kinematics.series_coefficients`, taken to harmonic 24); for a
  central crank P_jI = -m_j R w^2 cos(phi) exactly and
  P_jII = -m_j R w^2 (lambda + lambda^3/4 + ...) cos(2 phi), the seed's
  -m_j R w^2 lambda cos(2 phi) to first order in lambda;
- resultant along the cylinder axis P = P_g + P_j;
- side force N = P tan(beta): the piston's push on the cylinder wall, positive toward the major
  thrust side (the side away from which the crank pin moves after TDC, which the piston presses
  against during expansion);
- rod force K = P / cos(beta), positive in compression;
- tangential force T = P sin(phi + beta)/cos(beta), positive driving the crank; radial force
  Z = P cos(phi + beta)/cos(beta), positive toward the crank centre; the cylinder's torque is
  M = T R;
- rotating inertia force P_r = m_r R w^2 along the crank, outward (of it m_CB R w^2 acts on the
  crank pin through the rod's big end, the rest on the crank web);
- crank-pin load: the force of the rod(s) on the pin in the crank frame, T and Z of every rod on
  the pin less the big ends' centrifugal force m_CB R w^2 along Z (V engines: two rods, each at
  its own bank's crank angle, combined in the crank frame).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import lru_cache
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.constants import DEG, RPM
from crankdyn.crank.geometry import check_step
from crankdyn.crank.indicated import indicated_work
from crankdyn.crank.kinematics import (
    CrankTerms,
    SliderCrankMotion,
    crank_terms,
    exact_acceleration,
    kinematics_summary,
    series_coefficients,
    slider_crank_exact,
)
from crankdyn.crank.masses import EquivalentMasses, equivalent_mass_model
from crankdyn.crank.pressure import PressureTrace
from crankdyn.crank.pressure_model import default_pressure
from crankdyn.engine.force_model import G, piston_force_with_friction
from crankdyn.engine.model import Engine
from crankdyn.errors import InputError
from crankdyn.plausibility import PlausibilityWarning, pressure_warnings
from crankdyn.results import Result, column, freeze, scalar

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = [
    "SUMMARY_STEP",
    "CrankTrain",
    "CylinderForces",
    "ForcesResult",
    "check_step",
    "crank_tangential",
    "crank_train",
    "cycle_grid",
    "cylinder_forces",
    "engine_forces",
    "engine_masses",
    "engine_warnings",
    "inertia_harmonics",
    "load_angle",
    "refined_extrema",
    "refined_extremum",
    "reuse_train",
    "rod_forces",
    "throw_sums",
]

_SERIES_ORDER = 24


# ---- numeric core ------------------------------------------------------------------------------


def rod_forces(
    piston_force: ArrayLike,
    phi: ArrayLike,
    lam: float,
    k: float = 0.0,
    *,
    terms: CrankTerms | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Side, rod, tangential and radial forces from the force along the cylinder axis.

    Parameters
    ----------
    piston_force : array_like
        P (N), positive toward the crank; array broadcastable with phi.
    phi : array_like
        Crank angle (rad).
    lam, k : float
        lambda = R/L and k = e/R (dimensionless).
    terms : CrankTerms or None
        :func:`crankdyn.crank.kinematics.crank_terms` at phi for lam and k, when already computed.

    Returns
    -------
    side, rod, tangential, radial : numpy.ndarray
        Side force N = P tan(beta), rod force K = P/cos(beta), tangential force
        T = P sin(phi + beta)/cos(beta), radial force Z = P cos(phi + beta)/cos(beta), all in N
        (seed 000 section 2.2).

    Examples
    --------
    At 90 deg on a central crank the whole axial force drives the crank: T = P.

    >>> side, rod, t, z = rod_forces(1000.0, math.pi / 2, 0.25)
    >>> round(float(t), 9), round(float(side), 3)
    (1000.0, 258.199)
    """
    p = np.asarray(piston_force, dtype=float)
    if terms is None:
        terms = crank_terms(np.asarray(phi, dtype=float), lam, k)
    rod = p / terms.cos_beta
    side = rod * terms.sin_beta
    tangential = rod * terms.sin_phi_beta
    radial = rod * terms.cos_phi_beta
    return side, rod, tangential, radial


@lru_cache(maxsize=64)
def _harmonics(lam: float, k: float) -> tuple[float, float, float, float]:
    cos_c, sin_c = series_coefficients(lam, k, _SERIES_ORDER)
    return float(cos_c[1]), float(sin_c[1]), float(cos_c[2]), float(sin_c[2])


def inertia_harmonics(
    phi: ArrayLike,
    mass: float,
    crank_radius: float,
    rod_length: float,
    offset: float = 0.0,
    omega: float = 1.0,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """First- and second-order parts of the reciprocating inertia force -m_j a, the first two
    harmonics of the exact force (module docstring; seed 000 section 2.2).

    Parameters
    ----------
    phi : array_like
        Crank angle (rad).
    mass : float
        Reciprocating mass m_j (kg).
    crank_radius, rod_length, offset : float
        R, L, e (m).
    omega : float
        Crank speed w (rad/s); default 1.

    Returns
    -------
    first, second : numpy.ndarray
        P_jI and P_jII (N), of the shape of ``phi``.

    Examples
    --------
    The first order of a central crank is -m_j R w^2 cos(phi) exactly:

    >>> first, second = inertia_harmonics(0.0, 1.0, 0.05, 0.2, omega=100.0)
    >>> round(float(first), 9)
    -500.0
    """
    phi = np.asarray(phi, dtype=float)
    c1, s1, c2, s2 = _harmonics(crank_radius / rod_length, offset / crank_radius)
    scale = mass * crank_radius * omega * omega
    first = scale * (c1 * np.cos(phi) + s1 * np.sin(phi))
    second = 4.0 * scale * (c2 * np.cos(2 * phi) + s2 * np.sin(2 * phi))
    return first, second


def load_angle(along: ArrayLike, across: ArrayLike) -> NDArray[np.float64]:
    """Direction of a load from its components along a reference direction and across it.

    Parameters
    ----------
    along : array_like
        Component along the reference direction (N).
    across : array_like
        Component across it, the reference turned 90 deg in the direction of rotation (N).

    Returns
    -------
    numpy.ndarray
        The direction (rad), 0 <= angle < 2 pi from the reference.

    Examples
    --------
    >>> float(np.degrees(load_angle(0.0, -1.0)))
    270.0
    """
    return np.mod(np.arctan2(across, along), 2.0 * math.pi)


def throw_sums(values: ArrayLike, throws: tuple[int, ...], count: int) -> NDArray[np.float64]:
    """Per-cylinder rows summed per throw: row t of the result is the sum of the rows of the
    cylinders on throw t + 1, added in cylinder order (equal to the bit to
    ``np.add.at(zeros, throws - 1, values)``).

    Parameters
    ----------
    values : array_like
        One row per cylinder, shape (cylinders, angles) (any unit).
    throws : tuple of int
        Every cylinder's throw (1-based).
    count : int
        Number of throws.

    Returns
    -------
    numpy.ndarray
        Shape (count, angles), the unit of ``values``.

    Examples
    --------
    >>> throw_sums([[1.0], [2.0], [4.0]], (1, 2, 1), 2).ravel().tolist()
    [5.0, 2.0]
    """
    values = np.asarray(values, dtype=float)
    index = np.asarray(throws) - 1
    out = np.zeros((count, *values.shape[1:]))
    # layer k: the k-th cylinder of every throw (at most one row per throw, so that a fancy
    # index adds each once); the layers in turn add as add.at does, in cylinder order
    rank = np.zeros(index.size, dtype=int)
    seen: dict[int, int] = {}
    for c, t in enumerate(index.tolist()):
        rank[c] = seen.get(t, 0)
        seen[t] = rank[c] + 1
    for k in range(int(rank.max(initial=-1)) + 1):
        rows = np.flatnonzero(rank == k)
        out[index[rows]] += values[rows]
    return out


# ---- the crank train of an engine ----------------------------------------------------------------


def engine_masses(engine: Engine) -> list[EquivalentMasses]:
    """Equivalent masses of every cylinder (a V engine's throws share the crank unbalance).

    Parameters
    ----------
    engine : crankdyn.engine.Engine
        The engine.

    Returns
    -------
    list of crankdyn.crank.masses.EquivalentMasses
        One per cylinder (kg), seed 000 section 2.1.

    Raises
    ------
    InputError
        If the engine has no masses.
    """
    if engine.masses is None:
        raise InputError(
            "the engine has no [masses]: forces and torque need the reciprocating and rotating "
            "masses (give reciprocating and rotating, or the components)",
            file=engine.source,
            key="[masses]",
        )
    throws = engine.cylinders.throws
    counts = {t: throws.count(t) for t in set(throws)}
    return [
        equivalent_mass_model(engine.masses, engine.geometry.rod_length, counts[t]) for t in throws
    ]


@dataclass(frozen=True)
class CrankTrain:
    """Forces of every cylinder of an engine at a set of crankshaft angles (arrays of shape
    (cylinders, angles), SI); the building block of the force, bearing and torque results.

    Made by :func:`crank_train`; signs as in the module docstring.

    Parameters
    ----------
    theta : numpy.ndarray
        Crankshaft angle (rad), 0 at cylinder 1's firing TDC; shape (angles,).
    speed : float
        Crank speed w (rad/s).
    phi : numpy.ndarray
        Each cylinder's crank angle from its own TDC (rad).
    cycle_phase : numpy.ndarray
        Each cylinder's angle from its firing TDC, 0..cycle (rad).
    pressure : numpy.ndarray
        Absolute cylinder pressure (Pa).
    gas, inertia, piston : numpy.ndarray
        Gas force P_g, inertia force P_j and their sum P along the cylinder axis (N).
    side, rod, tangential, radial : numpy.ndarray
        Side force N, rod force K, tangential force T, radial force Z (N).
    gas_tangential, inertia_tangential : numpy.ndarray
        The tangential forces of the gas and of the inertia force alone (N).
    weight, friction : numpy.ndarray or None
        With the engine's optional forces (:mod:`crankdyn.engine.force_model`): the
        reciprocating mass's weight along the axis and the piston's friction force, both in P
        (N); None when off. T and Z then hold, besides the rod's, the rotating mass's weight at
        the crank radius (gravity on).
    masses : tuple of crankdyn.crank.masses.EquivalentMasses
        Equivalent masses of every cylinder (kg).
    trace : PressureTrace
        The cylinder pressure used.
    engine : crankdyn.engine.Engine
        The engine.
    motion : SliderCrankMotion or None
        Piston and rod kinematics of every cylinder (arrays of shape (cylinders, angles)).
    """

    theta: NDArray[np.float64]
    speed: float
    phi: NDArray[np.float64]
    cycle_phase: NDArray[np.float64]
    pressure: NDArray[np.float64]
    gas: NDArray[np.float64]
    inertia: NDArray[np.float64]
    piston: NDArray[np.float64]
    side: NDArray[np.float64]
    rod: NDArray[np.float64]
    tangential: NDArray[np.float64]
    radial: NDArray[np.float64]
    gas_tangential: NDArray[np.float64]
    inertia_tangential: NDArray[np.float64]
    masses: tuple[EquivalentMasses, ...]
    trace: PressureTrace
    engine: Engine = field(repr=False)
    motion: SliderCrankMotion | None = field(default=None, repr=False)
    weight: NDArray[np.float64] | None = field(default=None, repr=False)
    friction: NDArray[np.float64] | None = field(default=None, repr=False)
    _derived: dict[str, Any] = field(
        default_factory=dict, init=False, repr=False, compare=False
    )  # what summary_train() and warnings() computed once

    def summary_train(self) -> CrankTrain:
        """The crank train of this engine, speed and pressure on the :data:`SUMMARY_STEP` grid
        over one cycle, on which the summary figures are found: computed once and shared by
        the analyses that reuse this train (torque and bearing loads of one cycle).

        Returns
        -------
        CrankTrain
            The train on ``cycle_grid(engine, SUMMARY_STEP)``.
        """
        if "summary" not in self._derived:
            grid = cycle_grid(self.engine, SUMMARY_STEP)
            self._derived["summary"] = crank_train(
                self.engine, self.speed, grid, pressure=self.trace
            )
        train: CrankTrain = self._derived["summary"]
        return train

    def indicated_work(self) -> float:
        """The indicated work per cylinder and cycle of this train's pressure on its engine's
        geometry (:func:`crankdyn.crank.indicated.indicated_work`), computed once for the
        analyses sharing this train (the torque and the plausibility warnings).

        Returns
        -------
        float
            W_i (J per cylinder and cycle).
        """
        if "work" not in self._derived:
            self._derived["work"] = indicated_work(self.trace, self.engine.geometry)
        work: float = self._derived["work"]
        return work

    def warnings(self) -> tuple[PlausibilityWarning, ...]:
        """The plausibility warnings of this engine at this speed and pressure
        (:func:`engine_warnings`), computed once for the analyses sharing this train.

        Returns
        -------
        tuple of crankdyn.plausibility.PlausibilityWarning
            The warnings.
        """
        if "warnings" not in self._derived:
            self._derived["warnings"] = engine_warnings(
                self.engine, self.speed, self.trace, work=self.indicated_work()
            )
        found: tuple[PlausibilityWarning, ...] = self._derived["warnings"]
        return found

    @property
    def crank_radius(self) -> float:
        """Crank radius R (m)."""
        return self.engine.geometry.crank_radius

    @property
    def throw_direction(self) -> NDArray[np.float64]:
        """Direction of each cylinder's crank in the engine frame (rad from the vertical,
        clockwise seen from the free end): alpha_i + phi_i."""
        return self.engine.cylinders.bank_axis_angles[:, None] + self.phi

    def pin_loads(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Crank-pin load of every throw in the crank frame (seed 000 section 2.2).

        T and Z of every rod on the pin less the big ends' centrifugal force m_CB R w^2 along Z.

        Returns
        -------
        tangential, radial : numpy.ndarray
            Shape (throws, angles), N; radial positive toward the crank centre.
        """
        cyl = self.engine.cylinders
        w2r = self.speed**2 * self.crank_radius
        big_end = np.array([m.rod_big_end or 0.0 for m in self.masses])
        radial = self.radial - (big_end * w2r)[:, None]
        tangential = self.tangential
        if self.weight is not None:  # T and Z hold m_r's weight: the pin carries m_CB's only
            crank = np.array([m.rotating - (m.rod_big_end or 0.0) for m in self.masses])[:, None]
            chi = self.throw_direction
            tangential = tangential - crank * G * np.sin(chi)
            radial = radial - crank * G * np.cos(chi)
        t_pin = throw_sums(tangential, cyl.throws, cyl.throw_count)
        z_pin = throw_sums(radial, cyl.throws, cyl.throw_count)
        return t_pin, z_pin

    def throw_forces(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Force of every throw on the crankshaft in the engine frame.

        The rods' forces plus the rotating masses' centrifugal force.

        Returns
        -------
        horizontal, vertical : numpy.ndarray
            Shape (throws, angles), N; horizontal positive to the right seen from the free end,
            vertical positive up.
        """
        cyl = self.engine.cylinders
        alpha = cyl.bank_axis_angles[:, None]
        # rod force on the pin in the cylinder frame: side component N along +n, -P along +a
        # with a = (sin alpha, cos alpha), n = (cos alpha, -sin alpha) in (horizontal, up)
        fx = self.side * np.cos(alpha) - self.piston * np.sin(alpha)
        fy = -self.side * np.sin(alpha) - self.piston * np.cos(alpha)
        rotating = np.array([m.rotating for m in self.masses])[:, None]
        centrifugal = rotating * self.crank_radius * self.speed**2
        chi = self.throw_direction
        fx = fx + centrifugal * np.sin(chi)
        fy = fy + centrifugal * np.cos(chi)
        if self.weight is not None:  # the rotating masses' weight (the piston's is in P)
            fy = fy - rotating * G
        hx = throw_sums(fx, cyl.throws, cyl.throw_count)
        hy = throw_sums(fy, cyl.throws, cyl.throw_count)
        return hx, hy


def crank_train(
    engine: Engine, speed: float, theta: ArrayLike, *, pressure: PressureTrace | None = None
) -> CrankTrain:
    """Kinematics and forces of every cylinder at a set of crankshaft angles and a speed.

    Cylinder i's crank angle is phi_i = theta - psi_i (psi_i its throw angle) and its angle from
    firing TDC is theta - Phi_i (Phi_i its firing angle); the forces follow seed 000
    section 2.2 (module docstring).

    Parameters
    ----------
    engine : crankdyn.engine.Engine
        The engine (its masses are required).
    speed : float
        Crank speed w (rad/s), > 0.
    theta : array_like
        Crankshaft angles (rad), 0 at cylinder 1's firing TDC; 1-D.
    pressure : PressureTrace or None
        The cylinder pressure; default the engine's trace or the synthetic model
        (:func:`crankdyn.crank.pressure_model.default_pressure`).

    Returns
    -------
    CrankTrain
        Arrays of shape (cylinders, angles), SI.

    Raises
    ------
    InputError
        If the speed is not positive or the engine has no masses.
    """
    masses, trace, theta, phi, phase, p, gas, terms = _train_inputs(engine, speed, theta, pressure)
    g = engine.geometry
    motion = slider_crank_exact(phi, g.crank_radius, g.rod_length, g.offset, speed, terms=terms)
    m_j = np.array([m.reciprocating for m in masses])[:, None]
    inertia = -m_j * motion.acceleration
    piston, weight, friction = _axial(engine, masses, gas + inertia, terms)
    side, rod, tangential, radial = rod_forces(piston, phi, g.lam, g.k, terms=terms)
    if weight is not None:
        tangential, radial = _with_rotating_weight(engine, masses, phi, tangential, radial)
    lever = (1.0 / terms.cos_beta) * terms.sin_phi_beta  # sin(phi + beta)/cos(beta)
    return CrankTrain(
        theta=theta,
        speed=float(speed),
        phi=phi,
        cycle_phase=phase,
        pressure=p,
        gas=gas,
        inertia=inertia,
        piston=piston,
        side=side,
        rod=rod,
        tangential=tangential,
        radial=radial,
        gas_tangential=gas * lever,
        inertia_tangential=inertia * lever,
        masses=tuple(masses),
        trace=trace,
        engine=engine,
        motion=motion,
        weight=weight,
        friction=friction,
    )


def _axial(
    engine: Engine, masses: list[EquivalentMasses], p0: NDArray[np.float64], terms: CrankTerms
) -> tuple[NDArray[np.float64], NDArray[np.float64] | None, NDArray[np.float64] | None]:
    """P with the engine's optional forces (:mod:`crankdyn.engine.force_model`): the
    reciprocating weight along the axis m_j g cos(alpha), then the piston's friction solved
    exactly; (P, weight or None, friction or None), each (cylinders, angles) in N."""
    model = engine.forces
    if model is None or not model.active:
        return p0, None, None
    weight = None
    if model.gravity:
        m_j = np.array([m.reciprocating for m in masses])[:, None]
        alpha = np.asarray(engine.cylinders.bank_axis_angles)[:, None]
        weight = m_j * G * np.cos(alpha) * np.ones_like(p0)
        p0 = p0 + weight
    if not model.friction:
        return p0, weight, None
    tan_beta = terms.sin_beta / terms.cos_beta
    piston, friction = piston_force_with_friction(
        p0, terms.sin_phi_beta, tan_beta, model.ring_friction, model.skirt_friction
    )
    return piston, weight, friction


def _with_rotating_weight(
    engine: Engine,
    masses: list[EquivalentMasses],
    phi: NDArray[np.float64],
    tangential: NDArray[np.float64],
    radial: NDArray[np.float64],
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """T and Z with the rotating mass's weight at the crank radius: m_r g sin(chi) in the
    direction of rotation, m_r g cos(chi) toward the centre, chi = alpha + phi
    (:mod:`crankdyn.engine.force_model`)."""
    m_r = np.array([m.rotating for m in masses])[:, None]
    chi = np.asarray(engine.cylinders.bank_axis_angles)[:, None] + phi
    return tangential + m_r * G * np.sin(chi), radial + m_r * G * np.cos(chi)


def _train_inputs(
    engine: Engine, speed: float, theta: ArrayLike, pressure: PressureTrace | None
) -> tuple[
    list[EquivalentMasses],
    PressureTrace,
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.float64],
    CrankTerms,
]:
    """What :func:`crank_train` and :func:`crank_tangential` start from: the masses, the trace,
    the angles, every cylinder's crank angle and cycle phase, pressure, gas force and terms."""
    if not (math.isfinite(speed) and speed > 0.0):
        raise InputError("the speed must be positive", key="speed", value=speed)
    masses = engine_masses(engine)
    trace = default_pressure(engine) if pressure is None else pressure
    g, cyl = engine.geometry, engine.cylinders
    theta = np.asarray(theta, dtype=float)
    psi = np.asarray(cyl.throw_angles)[:, None]
    firing = np.asarray(cyl.firing_angles)[:, None]
    phi = theta[None, :] - psi
    phase = np.mod(theta[None, :] - firing, engine.cycle_angle)
    p = trace.at(phase)
    gas = (p - engine.crankcase_pressure) * g.piston_area
    terms = crank_terms(phi, g.lam, g.k)  # shared by the kinematics and the forces
    return masses, trace, theta, phi, phase, p, gas, terms


def crank_tangential(
    engine: Engine, speed: float, theta: ArrayLike, *, pressure: PressureTrace | None = None
) -> NDArray[np.float64]:
    """The tangential force of every cylinder alone: ``crank_train(...).tangential`` to the bit
    (the same formulas in the same order), without the rest of the train (rod angle, piston
    displacement and velocity, rod motion, side and radial forces), e.g. for the mean torque
    on a fine grid.

    Parameters
    ----------
    engine, speed, theta, pressure
        As :func:`crank_train`.

    Returns
    -------
    numpy.ndarray
        T (N), shape (cylinders, angles).
    """
    masses, _, _, phi, _, _, gas, terms = _train_inputs(engine, speed, theta, pressure)
    g = engine.geometry
    r, l, w = float(g.crank_radius), float(g.rod_length), float(speed)
    acceleration = exact_acceleration(terms, r, r / l, w)  # as slider_crank_exact
    m_j = np.array([m.reciprocating for m in masses])[:, None]
    piston, weight, _ = _axial(engine, masses, gas + -m_j * acceleration, terms)
    tangential = (piston / terms.cos_beta) * terms.sin_phi_beta  # rod_forces' rod force, then T
    if weight is not None:
        tangential = _with_rotating_weight(engine, masses, phi, tangential, tangential)[0]
    return tangential


SUMMARY_STEP = math.radians(1.0)
"""Crank-angle step of the grid on which summary figures (maxima, minima, means) are found, then
refined (:func:`refined_extremum`): the same whatever grid the rows of a result use."""


def cycle_grid(engine: Engine, step: float) -> NDArray[np.float64]:
    """Crankshaft angles over one working cycle, 0..cycle inclusive.

    Parameters
    ----------
    engine : crankdyn.engine.Engine
        The engine (its cycle).
    step : float
        Angle step (rad); it must divide the cycle (:func:`check_step`).

    Returns
    -------
    numpy.ndarray
        The angles (rad), both ends included.

    Raises
    ------
    InputError
        If the step does not divide the cycle.
    """
    count = check_step(step, engine.cycle_angle)
    return np.linspace(0.0, engine.cycle_angle, count + 1)


def refined_extremum(
    f: Callable[[NDArray[np.float64]], ArrayLike],
    theta: ArrayLike,
    values: ArrayLike,
    *,
    period: float,
    passes: int = 4,
    points: int = 33,
) -> tuple[float, float]:
    """The largest value of a periodic function of the crankshaft angle and where it lies,
    found on a grid and refined around the grid's largest value.

    Around the best grid point the function is sampled on ``points`` equally spaced angles
    spanning one grid step either side, ``passes`` times, each time around the best sample
    with the span shrunk to one sample spacing either side: the angle is resolved to
    h (2/(points - 1))^passes (about 1e-5 deg from a 1 deg grid), so the maximum of a smooth
    peak is exact to round-off and that of a kink (the knots of a piecewise-linear pressure
    trace) to the slope times that angle.

    Parameters
    ----------
    f : callable
        Vectorised callable of the crankshaft angle (rad) returning the quantity.
    theta : array_like
        The grid (rad, increasing, spanning the cycle).
    values : array_like
        The quantity on the grid (its unit).
    period : float
        The cycle angle (rad).
    passes : int
        Refinement passes; default 4.
    points : int
        Samples per pass; default 33.

    Returns
    -------
    value : float
        The largest value (the quantity's unit).
    angle : float
        Its angle (rad), in [0, period).

    Examples
    --------
    The maximum of cos(theta - 1) found from a 10 deg grid:

    >>> grid = np.radians(np.arange(0.0, 361.0, 10.0))
    >>> f = lambda t: np.cos(t - 1.0)
    >>> value, at = refined_extremum(f, grid, f(grid), period=2 * np.pi)
    >>> round(value, 12), round(at, 6)
    (1.0, 1.0)
    """
    best, at = refined_extrema(
        lambda local: np.asarray(f(local[0]), dtype=float)[None, :],
        theta,
        np.asarray(values, dtype=float)[None, :],
        period=period,
        passes=passes,
        points=points,
    )
    return float(best[0]), float(at[0])


def refined_extrema(
    f: Callable[[NDArray[np.float64]], ArrayLike],
    theta: ArrayLike,
    values: ArrayLike,
    *,
    period: float,
    passes: int = 4,
    points: int = 33,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """:func:`refined_extremum` of several quantities at once, each refined around its own
    largest grid value, with one call of ``f`` per pass for all of them.

    Parameters
    ----------
    f : callable
        ``f(angles)`` with angles (rad) of shape (rows, samples), row k the samples of
        quantity k, returns the quantities there: row k quantity k at row k's angles.
    theta : array_like
        The grid (rad, increasing, spanning the cycle), shape (angles,).
    values : array_like
        The quantities on the grid, shape (rows, angles) (their units).
    period : float
        The cycle angle (rad).
    passes : int
        Refinement passes; default 4.
    points : int
        Samples per pass; default 33.

    Returns
    -------
    value : numpy.ndarray
        The largest value of every quantity, shape (rows,); each equal to
        :func:`refined_extremum` of that quantity alone.
    angle : numpy.ndarray
        Their angles (rad), in [0, period).

    Examples
    --------
    >>> grid = np.radians(np.arange(0.0, 361.0, 10.0))
    >>> f = lambda t: np.cos(t - np.array([[1.0], [2.0]]))
    >>> value, at = refined_extrema(f, grid, f(grid[None, :]), period=2 * np.pi)
    >>> value.round(12).tolist(), at.round(6).tolist()
    ([1.0, 1.0], [1.0, 2.0])
    """
    theta = np.asarray(theta, dtype=float)
    values = np.asarray(values, dtype=float)
    rows = np.arange(values.shape[0])
    i = np.argmax(values, axis=1)
    best, at = values[rows, i], theta[i]
    h = float(np.max(np.diff(theta))) if theta.size > 1 else period
    for _ in range(passes):
        local = at[:, None] + np.linspace(-h, h, points)[None, :]
        sampled = np.asarray(f(local), dtype=float)
        j = np.argmax(sampled, axis=1)
        top = sampled[rows, j]
        better = top > best
        best = np.where(better, top, best)
        at = np.where(better, local[rows, j], at)
        h = 2.0 * h / (points - 1)
    return best, np.mod(at, period)


def reuse_train(
    train: CrankTrain | None,
    engine: Engine,
    speed: float,
    theta: np.ndarray,
    pressure: PressureTrace | None,
) -> CrankTrain:
    """The crank train at (engine, speed, theta, pressure), computed once.

    ``train`` when one was computed already for exactly these (so that the torque and bearing
    analyses of one cycle share a single evaluation), else a new one.

    Parameters
    ----------
    train : CrankTrain or None
        A crank train computed before, or None.
    engine : crankdyn.engine.Engine
        The engine.
    speed : float
        Crank speed (rad/s).
    theta : numpy.ndarray
        Crankshaft angles (rad).
    pressure : PressureTrace or None
        The cylinder pressure, or None for the engine's own.

    Returns
    -------
    CrankTrain
        ``train``, or :func:`crank_train` of the arguments.

    Raises
    ------
    ValueError
        When ``train`` was computed for another engine, speed, pressure or set of angles (a
        programming error, not an input error).
    """
    if train is None:
        return crank_train(engine, speed, theta, pressure=pressure)
    trace = engine.pressure if pressure is None else pressure  # None: the synthetic default
    if (
        train.engine is not engine
        or train.speed != float(speed)
        or not (trace is None or train.trace is trace or train.trace == trace)
        or not np.array_equal(train.theta, theta)
    ):
        raise ValueError(
            "the crank train was computed for another engine, speed, pressure or angle grid"
        )
    return train


# ---- one cylinder: result ------------------------------------------------------------------------


@dataclass(frozen=True)
class ForcesResult(Result):
    """Forces of one cylinder over the working cycle (:func:`engine_forces`; module docstring
    for signs). The time column is t = theta / w at the constant speed (seed 002 eq. 1:
    phi = w t = 6 n t, in degrees and rpm), from theta = 0 at cylinder 1's firing TDC.

    Parameters
    ----------
    warnings : tuple of crankdyn.plausibility.PlausibilityWarning
        Plausibility warnings of the engine at this speed (:func:`engine_warnings`).
    """

    title = "Cylinder forces"
    crank_angle: NDArray[np.float64] = column("crank_angle_deg", "Crank angle θ", "deg", DEG)
    cylinder_angle: NDArray[np.float64] = column("cylinder_angle_deg", "Cylinder angle", "deg", DEG)
    pressure: NDArray[np.float64] = column("pressure_Pa", "Cylinder pressure", "Pa")
    gas_force: NDArray[np.float64] = column("gas_force_N", "Gas force P_g", "N")
    inertia_force: NDArray[np.float64] = column("inertia_force_N", "Inertia force P_j", "N")
    inertia_force_1: NDArray[np.float64] = column("inertia_force_1st_N", "P_j 1st order", "N")
    inertia_force_2: NDArray[np.float64] = column("inertia_force_2nd_N", "P_j 2nd order", "N")
    piston_force: NDArray[np.float64] = column("piston_force_N", "Axial force P", "N")
    side_force: NDArray[np.float64] = column("side_force_N", "Side force N", "N")
    rod_force: NDArray[np.float64] = column("rod_force_N", "Rod force K", "N")
    tangential_force: NDArray[np.float64] = column("tangential_force_N", "Tangential T", "N")
    radial_force: NDArray[np.float64] = column("radial_force_N", "Radial Z", "N")
    rotating_axial: NDArray[np.float64] = column("rotating_force_axial_N", "Rotating, axial", "N")
    rotating_lateral: NDArray[np.float64] = column(
        "rotating_force_lateral_N", "Rotating, lateral", "N"
    )
    pin_load: NDArray[np.float64] = column("crank_pin_load_N", "Crank-pin load", "N")
    pin_load_angle: NDArray[np.float64] = column(
        "crank_pin_load_angle_deg", "Pin load angle", "deg", DEG
    )
    pin_tangential: NDArray[np.float64] = column(
        "crank_pin_load_tangential_N", "Pin load, tangential", "N"
    )
    pin_radial: NDArray[np.float64] = column("crank_pin_load_radial_N", "Pin load, radial", "N")
    torque: NDArray[np.float64] = column("torque_Nm", "Torque M", "N·m")
    gas_torque: NDArray[np.float64] = column("gas_torque_Nm", "Gas torque", "N·m")
    inertia_torque: NDArray[np.float64] = column("inertia_torque_Nm", "Inertia torque", "N·m")
    inertia_torque_error: NDArray[np.float64] | None = column(
        "rod_model_torque_error_Nm", "Rod-model torque error", "N·m"
    )
    time: NDArray[np.float64] = column("time_s", "Time t = θ/ω (θ = 6 n t)", "s")
    weight_force: NDArray[np.float64] | None = column(
        "weight_force_N", "Weight along the axis m_j g cos α", "N"
    )
    friction_force: NDArray[np.float64] | None = column(
        "friction_force_N", "Piston friction F_f", "N"
    )
    cylinder: int = scalar("cylinder", "Cylinder", "")
    bank: str = scalar("bank", "Bank", "")
    throw: int = scalar("throw", "Throw", "")
    rods_on_pin: int = scalar("rods_on_pin", "Rods on the crank pin", "")
    speed: float = scalar("speed_rpm", "Speed", "rpm", RPM)
    masses: EquivalentMasses = scalar("masses", "Masses", "")
    rotating_force: float = scalar("rotating_force_N", "Rotating inertia force m_r R ω²", "N")
    pin_rotating_force: float = scalar(
        "pin_rotating_force_N", "Big-end centrifugal force on the pin m_CB R ω²", "N"
    )
    max_gas_force: float = scalar("max_gas_force_N", "Max gas force", "N", headline=True)
    max_side_force: float = scalar(
        "max_side_force_N", "Max piston side force", "N", better="min", headline=True
    )
    max_rod_compression: float = scalar(
        "max_rod_compression_N", "Max rod compression", "N", better="min", headline=True
    )
    max_rod_tension: float = scalar(
        "max_rod_tension_N", "Max rod tension", "N", better="min", headline=True
    )
    max_pin_load: float = scalar(
        "throw_max_crank_pin_load_N",
        "Max crank-pin load of its throw",
        "N",
        name="throw_max_crank_pin_load",
    )
    mean_pin_load: float = scalar(
        "throw_mean_crank_pin_load_N",
        "Mean crank-pin load of its throw",
        "N",
        name="throw_mean_crank_pin_load",
    )
    max_rod_couple_error: float | None = scalar(
        "max_rod_couple_error_Nm", "Two-mass rod couple error max |ΔI ε_L|", "N·m"
    )
    pressure_source: str = scalar("pressure_source", "Pressure from", "")
    notes: tuple[str, ...] | None = scalar("notes", "Notes", "")
    warnings: tuple[PlausibilityWarning, ...] = field(default=(), repr=False, compare=False)

    def plot(self, fig: Figure | None = None) -> Figure:
        """Forces vs crank angle.

        Parameters
        ----------
        fig : matplotlib.figure.Figure or None
            A figure to draw into; None makes a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.forces import plot_cylinder_forces

        return plot_cylinder_forces(self, fig=fig)

    def plot_pin_polar(self, fig: Figure | None = None) -> Figure:
        """Polar diagram of the crank-pin load in the crank frame.

        Parameters
        ----------
        fig : matplotlib.figure.Figure or None
            A figure to draw into; None makes a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.forces import plot_pin_polar

        return plot_pin_polar(self, fig=fig)


def engine_forces(
    engine: Engine,
    speed: float,
    angles: ArrayLike | None = None,
    *,
    cylinder: int = 1,
    step: float = math.radians(1.0),
    pressure: PressureTrace | None = None,
    train: CrankTrain | None = None,
) -> ForcesResult:
    """Forces of cylinder ``cylinder`` (1-based, numbered from the free end) over the cycle.

    Parameters
    ----------
    engine : crankdyn.engine.Engine
        The engine (its masses are required).
    speed : float
        Crank speed w (rad/s).
    angles : array_like or None
        Crankshaft angles (rad), 0 at cylinder 1's firing TDC; default one cycle every ``step``.
    cylinder : int
        Which cylinder (1-based); default 1.
    step : float
        Angle step of the default grid (rad); it must divide the cycle. Default 1 deg.
    pressure : PressureTrace or None
        Pressure trace; default the engine's own or its synthetic model.
    train : CrankTrain or None
        The crank train of this engine at this speed and pressure at exactly these angles, when
        already computed (e.g. shared with :func:`crankdyn.engine.torque.engine_torque` and
        :func:`crankdyn.engine.bearings.engine_bearings`, which then share its summary grid and
        warnings too); default: evaluated here.

    Returns
    -------
    ForcesResult
        The summary figures (maxima, the mean pin load) are those of the whole cycle on the
        :data:`SUMMARY_STEP` grid, the maxima refined (:func:`refined_extremum`), whatever
        ``angles`` or ``step`` the rows use. The crank-pin load is that of the cylinder's throw
        (both rods of a V engine's shared pin). The rod-model torque error (two-mass minus
        three-mass, -dI w_L eps_L / w with dI = m_C l_A l_B - I_C, seed 000 section 2.1) is
        given when the rod's moment of inertia is known.

    Raises
    ------
    InputError
        If the cylinder does not exist, the speed is not positive, the step does not divide the
        cycle, or the engine has no masses.

    Examples
    --------
    >>> import crankdyn
    >>> engine = crankdyn.Engine.example("inline6-diesel")
    >>> f = engine_forces(engine, 2200 * math.pi / 30)
    >>> round(f.max_gas_force / 1e3, 1)  # kN
    130.7
    >>> p_max = engine.pressure.peak[0]  # the gas force at the trace's peak pressure
    >>> round((p_max - engine.crankcase_pressure) * engine.geometry.piston_area / 1e3, 1)
    130.7
    """
    cyl = engine.cylinders
    if isinstance(cylinder, bool) or not isinstance(cylinder, (int, np.integer)):
        raise InputError("expected a cylinder number", key="cylinder", value=cylinder)
    if not 1 <= cylinder <= cyl.count:
        raise InputError(
            f"the engine has cylinders 1 to {cyl.count}", key="cylinder", value=cylinder
        )
    theta = cycle_grid(engine, step) if angles is None else np.asarray(angles, dtype=float)
    train = reuse_train(train, engine, speed, theta, pressure)
    summary = _force_summary(engine, train, cylinder, pressure, full=angles is None)
    i = cylinder - 1
    g = engine.geometry
    r, w = g.crank_radius, train.speed
    m = train.masses[i]
    phi = train.phi[i]
    first, second = inertia_harmonics(phi, m.reciprocating, r, g.rod_length, g.offset, w)
    t_pin, z_pin = train.pin_loads()
    t = cyl.throws[i] - 1
    pin = np.hypot(t_pin[t], z_pin[t])
    notes = []
    error = None
    couple = None
    if m.inertia_error is not None:
        if train.motion is not None:  # the crank train's kinematics: the same numbers
            w_rod, e_rod = (
                train.motion.rod_angular_velocity[i],
                train.motion.rod_angular_acceleration[i],
            )
        else:
            motion = slider_crank_exact(phi, r, g.rod_length, g.offset, w)
            w_rod, e_rod = motion.rod_angular_velocity, motion.rod_angular_acceleration
        error = -m.inertia_error * w_rod * e_rod / w
        couple = float(m.inertia_error * np.max(np.abs(e_rod)))
    if not m.pin_mass_known:
        notes.append(
            "rod big-end mass unknown (give [masses] rod and rod_cg_from_big_end): the crank-pin "
            "load leaves out its centrifugal force"
        )
    if engine.pressure is None:
        notes.append("no pressure trace: synthetic Wiebe model with default parameters")
    if engine.forces is not None and engine.forces.active:
        notes.append(f"with {engine.forces.describe()} ([forces])")
    return ForcesResult(
        crank_angle=freeze(theta),
        cylinder_angle=freeze(train.cycle_phase[i]),
        pressure=freeze(train.pressure[i]),
        gas_force=freeze(train.gas[i]),
        inertia_force=freeze(train.inertia[i]),
        inertia_force_1=freeze(first),
        inertia_force_2=freeze(second),
        piston_force=freeze(train.piston[i]),
        side_force=freeze(train.side[i]),
        rod_force=freeze(train.rod[i]),
        tangential_force=freeze(train.tangential[i]),
        radial_force=freeze(train.radial[i]),
        rotating_axial=freeze(m.rotating * r * w * w * np.cos(phi)),
        rotating_lateral=freeze(m.rotating * r * w * w * np.sin(phi)),
        pin_load=freeze(pin),
        pin_load_angle=freeze(load_angle(-z_pin[t], t_pin[t])),
        pin_tangential=freeze(t_pin[t]),
        pin_radial=freeze(z_pin[t]),
        torque=freeze(train.tangential[i] * r),
        gas_torque=freeze(train.gas_tangential[i] * r),
        inertia_torque=freeze(train.inertia_tangential[i] * r),
        inertia_torque_error=None if error is None else freeze(error),
        time=freeze(theta / w),
        weight_force=None if train.weight is None else freeze(train.weight[i]),
        friction_force=None if train.friction is None else freeze(train.friction[i]),
        cylinder=int(cylinder),
        bank=cyl.banks[i],
        throw=int(cyl.throws[i]),
        rods_on_pin=int(cyl.throws.count(cyl.throws[i])),
        speed=w,
        masses=m,
        rotating_force=m.rotating * r * w * w,
        pin_rotating_force=(m.rod_big_end or 0.0) * r * w * w,
        **summary,
        max_rod_couple_error=couple,
        pressure_source=train.trace.source or "",
        notes=tuple(notes) or None,
        warnings=train.warnings(),
    )


def _force_summary(
    engine: Engine,
    train: CrankTrain,
    cylinder: int,
    pressure: PressureTrace | None,
    *,
    full: bool,
) -> dict[str, float]:
    """The summary figures of one cylinder's forces over the whole cycle (on the summary grid,
    the maxima refined), whatever grid ``train`` holds."""
    if not (full and np.allclose(np.diff(train.theta), SUMMARY_STEP, rtol=0.0, atol=1e-12)):
        train = train.summary_train()
    i = cylinder - 1
    t = engine.cylinders.throws[i] - 1
    names = ("gas", "side", "rod", "tension", "pin")

    def quantities(local: CrankTrain) -> NDArray[np.float64]:
        """Every summary quantity of the cylinder (rows in the order of ``names``)."""
        tp, zp = local.pin_loads()
        rod = local.rod[i]
        return np.vstack([local.gas[i], np.abs(local.side[i]), rod, -rod, np.hypot(tp[t], zp[t])])

    def f(angles: NDArray[np.float64]) -> NDArray[np.float64]:
        """Quantity k at row k's angles: one crank train over every row's samples."""
        local = crank_train(engine, train.speed, angles.reshape(-1), pressure=train.trace)
        count, samples = angles.shape
        every = quantities(local).reshape(count, count, samples)
        return every[np.arange(count), np.arange(count)]

    grid = quantities(train)
    pin = grid[4]
    peaks = refined_extrema(f, train.theta, grid, period=engine.cycle_angle)[0]
    peak = {name: float(value) for name, value in zip(names, peaks, strict=True)}
    return {
        "max_gas_force": peak["gas"],
        "max_side_force": peak["side"],
        "max_rod_compression": max(peak["rod"], 0.0),
        "max_rod_tension": max(peak["tension"], 0.0),
        "max_pin_load": peak["pin"],
        "mean_pin_load": float(np.mean(pin[:-1])),
    }


CylinderForces = ForcesResult
"""The former name of :class:`ForcesResult` (kept as an alias)."""


cylinder_forces = engine_forces
"""The former name of :func:`engine_forces` (kept as an alias)."""


def engine_warnings(
    engine: Engine,
    speed: float,
    trace: PressureTrace | None = None,
    *,
    work: float | None = None,
) -> tuple[PlausibilityWarning, ...]:
    """Every plausibility warning of an engine running at a speed.

    Its piston motion (:func:`crankdyn.plausibility.kinematics_warnings`) and its cylinder
    pressure (:func:`crankdyn.plausibility.pressure_warnings`), checked against the ranges of
    its ``fuel`` and ``aspiration``.

    Parameters
    ----------
    engine : crankdyn.engine.Engine
        The engine.
    speed : float
        Crank speed (rad/s).
    trace : PressureTrace or None
        The pressure to check, e.g. the scaled trace a forced response uses; default the
        engine's trace or its synthetic default.
    work : float or None
        The indicated work of that trace on the engine's geometry (J), when already computed
        (:meth:`CrankTrain.indicated_work`); default: computed here.

    Returns
    -------
    tuple of crankdyn.plausibility.PlausibilityWarning
        The warnings (none for a typical engine): those of
        :func:`crankdyn.crank.kinematics.piston_kinematics` and
        :func:`crankdyn.crank.indicated.pressure_analysis`, from the same figures (the
        kinematics summary shared through :func:`crankdyn.crank.kinematics.kinematics_summary`,
        IMEP = W_i / V_d and the trace's peak) without their tables.
    """
    g = engine.geometry
    kin = kinematics_summary(g, speed).plausibility(engine.fuel)
    trace = trace if trace is not None else default_pressure(engine)
    if work is None:
        work = indicated_work(trace, g)
    peak, _ = trace.peak
    pressure = pressure_warnings(work / g.swept_volume, peak, engine.fuel, engine.aspiration)
    return (*kin, *pressure)
