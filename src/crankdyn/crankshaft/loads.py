"""Bending moments and forces of a crank throw over the working cycle by the statically
determinate method of IACS UR M53.2.1.1 (analysis).

Each crank throw is a beam simply supported at the centres of its two main bearings, L_3 apart,
loaded by its connecting rod(s) on the crankpin (UR M53 2.1.1, Fig. 1 and 2): the rod force's
radial component F_R (along the crank, positive toward the crankshaft axis) and tangential
component F_T (positive in the direction of rotation), in the crank frame, from the crank train
(:func:`crankdyn.engine.forces.crank_train`: gas at the analysis speed's pressure plus the
inertia of the reciprocating masses; the force of the rod on the pin, less its big end's
centrifugal force, :meth:`~crankdyn.engine.forces.CrankTrain.pin_loads`). A rod sits L_2 from the
free-end bearing: at the pin's middle, L_3/2, on an inline engine; on a V engine's shared pin
each rod half the engine's ``rod_offset`` either side of the middle (bank A toward the free end),
the two triangular moment diagrams superposed according to phase (2.1.1).

A force F at a from the left support of a simply supported span L gives the bending moment
M(x) = F (L - a) x / L for x <= a and F a (L - x) / L for x >= a, and the left and right
reactions F (L - a)/L and F a/L (statics; :func:`simply_supported_moment`). Hence:

- the webs (2.1.1.1): at the web centres, L_1 from each bearing, M_BRF = L_1 R with R the
  bearing's reaction to F_R, and the radial force in the web Q_RF = R; the free-end web with
  the left reaction, the other with the right;
- the oil bore (2.1.1.2): M_BRO and M_BTO, the moments of F_R and F_T in the crankpin's
  section through the oil bore, taken at the pin's middle (x = L_3/2), combined at the
  outlet's position psi as M_BO = M_BTO cos(psi) + M_BRO sin(psi) (2.1.2.2).

Verified against the text UR M53 was read in (KR Rules 2025 Pt 5 Guidance Annex 5-3,
:mod:`crankdyn.crankshaft.m53`): 2(1)(A)(a) (a single crankthrow supported in the centres of
the adjacent main journals, bending length L_3, gas and inertia forces), (b) (triangular
bending moment diagrams of F_R and F_T), (c) (two rods on one pin superposed according to
phase), (d)(i) (M_BRF and Q_RF at the web centre, L_1, from the radial component), (e) (M_BRO
and M_BTO in the crankpin section through the oil bore) and 2(1)(B)(a)(i)-(iii), (c)
(over one working cycle; M_BO = M_BTO cos(psi) + M_BRO sin(psi)). The rod positions of a V
engine and the choice of the pin's middle for the oil bore's section are crankdyn's (the text's
Fig 2 and Fig 4 are not in the copy read).

The nominal alternating values are their half-ranges over the cycle (:func:`crankdyn.crankshaft.
m53.half_range`), the largest and smallest found on a 1 deg grid and refined
(:func:`crankdyn.engine.forces.refined_extrema`), so they do not depend on the grid. Of a
throw's two webs the larger half-range of each quantity is kept (the same on an inline engine;
on a V engine the webs differ by the rods' offset, and the larger of each is conservative).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.crank.pressure import PressureTrace
from crankdyn.engine.forces import (
    SUMMARY_STEP,
    CrankTrain,
    crank_train,
    cycle_grid,
    refined_extrema,
)
from crankdyn.engine.model import Engine

__all__ = ["ThrowLoads", "rod_positions", "simply_supported_moment", "throw_loads"]


def simply_supported_moment(
    force: ArrayLike, at: ArrayLike, section: float, span: float
) -> NDArray[np.float64]:
    """Bending moment at a section of a simply supported span under a point force (statics):
    M = F (L - a) x / L where x <= a, F a (L - x) / L where x >= a (module docstring).

    Parameters
    ----------
    force : array_like
        F (N), any shape broadcasting with ``at``.
    at : array_like
        a, the force's distance from the left support (m), 0 <= a <= L.
    section : float
        x, the section's distance from the left support (m).
    span : float
        L (m).

    Returns
    -------
    numpy.ndarray
        M (N m), sagging positive for a force toward the beam's positive side.

    Examples
    --------
    A force at mid-span: F L / 4 in the middle, F x / 2 at x from a support.

    >>> float(simply_supported_moment(1000.0, 0.5, 0.5, 1.0))
    250.0
    >>> float(simply_supported_moment(1000.0, 0.5, 0.2, 1.0))
    100.0
    """
    f = np.asarray(force, dtype=float)
    a = np.asarray(at, dtype=float)
    return np.where(section <= a, f * (span - a) * section / span, f * a * (span - section) / span)


def rod_positions(engine: Engine, span: float) -> NDArray[np.float64]:
    """L_2 of every cylinder's rod: its distance from its throw's free-end main bearing (m).

    The pin's middle, L_3/2; on a V engine's shared pin bank A's rod half the balance table's
    ``rod_offset`` toward the free end of it and bank B's half of it toward the flywheel
    (:class:`crankdyn.engine.model.BalanceInputs`; 0 when not given).

    Parameters
    ----------
    engine : crankdyn.engine.Engine
        The engine.
    span : float
        L_3 (m).

    Returns
    -------
    numpy.ndarray
        L_2 per cylinder (m).
    """
    cyl = engine.cylinders
    offset = 0.0 if engine.balance is None else engine.balance.rod_offset
    shared = np.array([cyl.throws.count(t) > 1 for t in cyl.throws])
    side = np.array([-0.5 if b == "A" else 0.5 for b in cyl.banks])
    return span / 2.0 + np.where(shared, side * offset, 0.0)


@dataclass(frozen=True)
class ThrowLoads:
    """The loads of every crank throw by the statically determinate method (module
    docstring), over one cycle and as the nominal alternating values of UR M53.

    Parameters
    ----------
    theta : numpy.ndarray
        Crankshaft angle (rad), the grid of the curves, shape (angles,).
    web_moment : numpy.ndarray
        M_BRF at the centre of each throw's free-end web (N m), shape (throws, angles).
    web_force : numpy.ndarray
        Q_RF in that web (N), positive compressing it, shape (throws, angles).
    oil_bore_moment : numpy.ndarray
        M_BO at the oil bore's outlet (N m), shape (throws, angles).
    moment_half_range : numpy.ndarray
        M_BN, half-range of the web's bending moment, the larger of the two webs (N m),
        shape (throws,).
    force_half_range : numpy.ndarray
        Q_N, half-range of the web's radial force, the larger of the two webs (N).
    oil_bore_half_range : numpy.ndarray
        M_BON, half-range of the oil bore's bending moment (N m).
    max_journal_torque : float
        The largest magnitude of the quasi-static torque through a main journal (N m): the
        cylinders' tangential forces times the crank radius, summed from the free end.
    """

    theta: NDArray[np.float64]
    web_moment: NDArray[np.float64]
    web_force: NDArray[np.float64]
    oil_bore_moment: NDArray[np.float64]
    moment_half_range: NDArray[np.float64]
    force_half_range: NDArray[np.float64]
    oil_bore_half_range: NDArray[np.float64]
    max_journal_torque: float


def _quantities(
    train: CrankTrain, span: float, web: float, psi: float, positions: NDArray[np.float64]
) -> NDArray[np.float64]:
    """The quantities of every throw at the train's angles, shape (6, throws, angles): the
    free-end and flywheel-end webs' moments and forces, the oil bore's moment, and the
    quasi-static torque through the journal after the throw."""
    cyl = train.engine.cylinders
    w2r = train.speed**2 * train.crank_radius
    big_end = np.array([m.rod_big_end or 0.0 for m in train.masses])[:, None]
    radial = train.radial - big_end * w2r  # F_R per cylinder, toward the axis
    tangential = train.tangential
    a = positions[:, None]
    left = radial * (span - a) / span  # the free-end bearing's reaction to F_R
    right = radial * a / span
    middle = span / 2.0
    m_ro = simply_supported_moment(radial, a, middle, span)
    m_to = simply_supported_moment(tangential, a, middle, span)
    oil = m_to * math.cos(psi) + m_ro * math.sin(psi)
    per_cylinder = np.stack([left * web, right * web, left, right, oil, tangential])
    count = cyl.throw_count
    out = np.zeros((6, count, train.theta.size))
    for i, t in enumerate(cyl.throws):  # a handful of cylinders, vectorised over angles
        out[:, t - 1] += per_cylinder[:, i]
    out[5] = np.cumsum(out[5], axis=0) * train.crank_radius
    return out


def throw_loads(
    engine: Engine,
    speed: float,
    *,
    bearing_span: float,
    web_centre_distance: float,
    oil_bore_angle: float = 0.0,
    pressure: PressureTrace | None = None,
) -> ThrowLoads:
    """The loads of every crank throw over one cycle and their nominal alternating values
    (UR M53.2.1.1; module docstring).

    Parameters
    ----------
    engine : crankdyn.engine.Engine
        The engine (masses required).
    speed : float
        Crank speed w (rad/s), the rule's at maximum continuous rating.
    bearing_span : float
        L_3 (m).
    web_centre_distance : float
        L_1 (m).
    oil_bore_angle : float
        psi (rad; :class:`crankdyn.crankshaft.geometry.CrankshaftGeometry`).
    pressure : PressureTrace or None
        The cylinder pressure; default the engine's trace or its synthetic model.

    Returns
    -------
    ThrowLoads
        Curves on a 1 deg grid and the refined half-ranges.

    Raises
    ------
    InputError
        If the speed is not positive or the engine has no masses.

    Examples
    --------
    >>> import crankdyn
    >>> engine = crankdyn.Engine.example("inline6-diesel")
    >>> loads = throw_loads(engine, 2200 * math.pi / 30, bearing_span=0.13,
    ...                     web_centre_distance=0.04)
    >>> loads.moment_half_range.shape
    (6,)
    """
    theta = cycle_grid(engine, SUMMARY_STEP)
    positions = rod_positions(engine, bearing_span)
    train = crank_train(engine, speed, theta, pressure=pressure)
    values = _quantities(train, bearing_span, web_centre_distance, oil_bore_angle, positions)
    rows = values.reshape(-1, theta.size)
    both = np.vstack([rows, -rows])  # largest values, then (negated) smallest

    def at(angles: NDArray[np.float64]) -> NDArray[np.float64]:
        count, samples = angles.shape
        local = crank_train(engine, speed, angles.reshape(-1), pressure=train.trace)
        q = _quantities(local, bearing_span, web_centre_distance, oil_bore_angle, positions)
        flat = q.reshape(-1, count, samples)  # quantity rows x (rows x samples)
        flat = np.vstack([flat, -flat])
        return flat[np.arange(count), np.arange(count)]

    peaks = refined_extrema(at, theta, both, period=engine.cycle_angle)[0]
    n = rows.shape[0]
    top, bottom = peaks[:n], -peaks[n:]
    half = (0.5 * (top - bottom)).reshape(values.shape[:2])
    extreme = np.maximum(top, -bottom).reshape(values.shape[:2])
    return ThrowLoads(
        theta=theta,
        web_moment=values[0],
        web_force=values[2],
        oil_bore_moment=values[4],
        moment_half_range=np.maximum(half[0], half[1]),
        force_half_range=np.maximum(half[2], half[3]),
        oil_bore_half_range=half[4],
        max_journal_torque=float(np.max(extreme[5])),
    )
