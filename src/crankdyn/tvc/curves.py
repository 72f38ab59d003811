"""Quantities of a torsional vibration calculation over speed, from a forced response, and their
extremes on the resolved curve (numeric core).

Every quantity is a function ``curve(r)`` of a :class:`~crankdyn.torsion.response.ResponseResult`
``r`` returning one value per speed, so it can be evaluated at any speed through ``r.at``:

- the synthesised half-range of a harmonic quantity sum_q Re(c_q exp(i q theta)) over the
  orders' common period (:func:`crankdyn.torsion.sources.synthesize_at`, the basis of IACS UR M68
  "the synthesis of all harmonic orders present");
- the angular acceleration of a mass, coefficients -(q Omega)^2 X_q of its actual angle;
- the torque at a rigid gear mesh from the dynamic equilibrium of the driven wheel,
  T_mesh = J_w theta_w'' + c_w theta_w' - (the torques of the wheel's shafts on it, elastic and
  damping), per order T_q = -(q Omega)^2 J_w X_w,q + i q Omega c_w X_w,q - sum_s (+/- T_s,q)
  (Newton's second law of the wheel: J theta'' = the sum of the torques acting on it);
- the power dissipated in an element with loss factor eta and viscous damping c, the mean over
  a cycle of the damping torque times the twist rate, P = sum_q (1/2) omega_q (eta k + c omega_q)
  |dtheta_q|^2 with omega_q = q Omega (the damping work per cycle W = pi c_eq omega |dtheta|^2 of
  a harmonic twist, c_eq = eta k / omega + c, delivered omega / 2 pi times a second; e.g.
  S. S. Rao, *Mechanical Vibrations*, 5th ed., 2011, section 2.7, energy dissipated in viscous
  and hysteretic damping).

:func:`resolved_worst` finds the largest ratio of a curve to its limit over the speeds outside
given intervals, refining every local maximum of the ratio by successive parabolic
interpolation (:func:`crankdyn.torsion.resolve.refinement_speeds`) until a further refinement
changes it by less than 1e-6 relative, and sampling the intervals' ends exactly.

Examples
--------
Two free masses, J_1 = 1 and J_2 = 3 kg m^2, joined by a shaft of k = 1e5 N m/rad with loss
factor eta = 0.1, a harmonic torque of 100 N m per order (orders 1 and 2) on the first:

>>> import numpy as np
>>> from crankdyn.torsion.excitation import UniformExcitation
>>> from crankdyn.torsion.model import Mass, Shaft, TorsionModel
>>> from crankdyn.torsion.sweep import forced_response
>>> model = TorsionModel(
...     (Mass("crank", 1.0, cylinders=(1,)), Mass("flywheel", 3.0)),
...     (Shaft(("crank", "flywheel"), stiffness=1e5, loss_factor=0.1),),
... )
>>> r = forced_response(model, UniformExcitation(100.0, [0.0]), [100.0, 150.0, 200.0],
...                     [1.0, 2.0], resolve=False)

The power dissipated in the shaft is the mean power the torque puts in,
sum_q (1/2) Re(T_q conj(i q Omega X_1,q)) (W):

>>> omega = r.speed[:, None] * r.orders[None, :]
>>> put_in = 0.5 * np.real(100.0 * np.conj(1j * omega * r.mass_response[:, :, 0])).sum(axis=1)
>>> np.allclose(damping_power(r, 0, (0, 1), 0.1, 0.0), put_in, rtol=1e-12)
True

Newton's second law of the free flywheel, J_2 theta_2'' = -T_shaft:

>>> np.allclose(3.0 * acceleration_coefficients(r, 1), -element_torque(r, 0, (0, 1), 0.1, 0.0))
True
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.torsion.resolve import merge_speeds, refinement_speeds
from crankdyn.torsion.sources import synthesize_at

if TYPE_CHECKING:
    from crankdyn.torsion.response import ResponseResult

__all__ = [
    "acceleration_coefficients",
    "damping_power",
    "element_torque",
    "mesh_torque_coefficients",
    "resolved_worst",
    "synthesized",
]

_TOLERANCE = 1e-6
_ROUNDS = 60

MeshShaft = tuple[int, int, float, float, tuple[int, int]]
"""An element ending on a mesh's driven wheel: (shaft index, sign, loss factor eta
(dimensionless), damping c (N m s/rad), (a, b) its mass indices)
(:func:`mesh_torque_coefficients`)."""


def _responses(
    result: ResponseResult,
) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
    """(mass_response, shaft_response) of a forced response (complex angles (S, Q, masses) in
    rad, elastic torques (S, Q, shafts) in N m); :func:`crankdyn.torsion.response.
    forced_response` always fills them."""
    masses, shafts = result.mass_response, result.shaft_response
    assert masses is not None and shafts is not None  # set by every forced response
    return masses, shafts


def synthesized(result: ResponseResult, coefficients: ArrayLike) -> NDArray[np.float64]:
    """Half-range over time of a harmonic quantity sum_q Re(c_q exp(i q theta)).

    The synthesis of all orders over their common period, the basis of IACS UR M68
    (:func:`crankdyn.torsion.sources.synthesize_at`); the sum of |c_q| where the orders have
    none.

    Parameters
    ----------
    result : ResponseResult
        The forced response whose orders (and cycle) the coefficients belong to.
    coefficients : array_like
        Complex harmonic coefficients c_q, shape (S, Q): one row per speed of ``result``, one
        column per order (any unit).

    Returns
    -------
    numpy.ndarray
        (max - min) / 2 over a period, shape (S,), in the coefficients' unit.

    Examples
    --------
    cos(theta) + cos(2 theta) ranges from 2 (theta = 0) to -9/8 (cos(theta) = -1/4), so its
    half-range is 25/16:

    >>> from crankdyn.torsion.excitation import UniformExcitation
    >>> from crankdyn.torsion.model import Mass, Shaft, TorsionModel
    >>> from crankdyn.torsion.sweep import forced_response
    >>> model = TorsionModel((Mass("a", 1.0, cylinders=(1,)), Mass("b", 3.0)),
    ...                      (Shaft(("a", "b"), stiffness=1e5, loss_factor=0.1),))
    >>> r = forced_response(model, UniformExcitation(100.0, [0.0]), [100.0], [1.0, 2.0],
    ...                     resolve=False)
    >>> synthesized(r, [[1.0, 1.0]])
    array([1.5625])
    """
    index = getattr(result.evaluator, "synthesis", None) if result.evaluator is not None else None
    if index is None and result.evaluator is None:
        from crankdyn.torsion.sources import synthesis_index

        index = synthesis_index(result.orders, result.cycle)
    top, low = synthesize_at(np.asarray(coefficients, dtype=complex), index)
    return 0.5 * (np.asarray(top) - np.asarray(low))


def acceleration_coefficients(result: ResponseResult, mass: int) -> NDArray[np.complex128]:
    """Harmonics of a mass's angular acceleration, -(q Omega)^2 X_q (module docstring).

    Parameters
    ----------
    result : ResponseResult
        The forced response.
    mass : int
        The mass's index in the model (its actual angle).

    Returns
    -------
    numpy.ndarray
        Complex acceleration harmonics (rad/s^2), shape (S, Q): speeds x orders.
    """
    masses, _ = _responses(result)
    omega = np.asarray(result.speed)[:, None] * np.asarray(result.orders)[None, :]
    return -(omega**2) * masses[:, :, mass]


def mesh_torque_coefficients(
    result: ResponseResult,
    wheel: int,
    inertia: float,
    shafts: Iterable[MeshShaft],
    damping: float = 0.0,
) -> NDArray[np.complex128]:
    """Torque harmonics at a rigid gear mesh, from the dynamic equilibrium of its driven wheel.

    T_q = -(q Omega)^2 J_w X_w,q + i q Omega c_w X_w,q - sum_s (+/- T_s,q): Newton's second
    law of the wheel, J theta'' = the sum of the torques acting on it (module docstring).

    Parameters
    ----------
    result : ResponseResult
        The forced response.
    wheel : int
        The driven wheel's mass index.
    inertia : float
        The wheel's own moment of inertia J_w (kg m^2).
    shafts : iterable of MeshShaft
        (index, sign, loss factor eta, damping c (N m s/rad), (a, b)) of every element ending
        on the wheel: sign +1 where the wheel is the element's first mass (the element's torque
        k (1 + i eta) (theta_b - theta_a) + i omega c (theta_b - theta_a) acts on it
        positively), -1 where it is the second; (a, b) the element's mass indices.
    damping : float
        The wheel's absolute viscous damping c_w (N m s/rad), default 0.

    Returns
    -------
    numpy.ndarray
        Complex torque harmonics at the mesh (N m), shape (S, Q): speeds x orders.

    Examples
    --------
    A wheel that meshes with nothing (the flywheel of the module's example) carries no mesh
    torque: its shaft's torque is all that accelerates it.

    >>> from crankdyn.torsion.excitation import UniformExcitation
    >>> from crankdyn.torsion.model import Mass, Shaft, TorsionModel
    >>> from crankdyn.torsion.sweep import forced_response
    >>> model = TorsionModel((Mass("a", 1.0, cylinders=(1,)), Mass("b", 3.0)),
    ...                      (Shaft(("a", "b"), stiffness=1e5, loss_factor=0.1),))
    >>> r = forced_response(model, UniformExcitation(100.0, [0.0]), [100.0, 200.0], [1.0, 2.0],
    ...                     resolve=False)
    >>> torque = mesh_torque_coefficients(r, 1, 3.0, [(0, -1, 0.1, 0.0, (0, 1))])
    >>> bool(np.abs(torque).max() < 1e-9 * np.abs(element_torque(r, 0, (0, 1), 0.1, 0.0)).max())
    True
    """
    masses, _ = _responses(result)
    omega = np.asarray(result.speed)[:, None] * np.asarray(result.orders)[None, :]
    x = masses[:, :, wheel]
    torque = -(omega**2) * inertia * x + 1j * omega * damping * x
    for s, sign, eta, c, (a, b) in shafts:
        full = element_torque(result, s, (a, b), eta, c)
        torque = torque - sign * full
    return torque


def element_torque(
    result: ResponseResult,
    shaft: int,
    ends: Sequence[int],
    loss_factor: float,
    damping: float,
) -> NDArray[np.complex128]:
    """The whole torque an element transmits, elastic and damping.

    k (1 + i eta) dtheta + i omega c dtheta with dtheta = theta_b - theta_a (actual angles),
    from its elastic torque k dtheta (``shaft_response``): the hysteretic and viscous damping
    torques of a harmonic twist (S. S. Rao, *Mechanical Vibrations*, 5th ed., 2011, section
    2.7).

    Parameters
    ----------
    result : ResponseResult
        The forced response.
    shaft : int
        The element's index in the model.
    ends : sequence of int
        (a, b), the indices of its two masses.
    loss_factor : float
        Its hysteretic loss factor eta (dimensionless).
    damping : float
        Its viscous damping c (N m s/rad, actual).

    Returns
    -------
    numpy.ndarray
        Complex torque harmonics (N m), shape (S, Q): speeds x orders.
    """
    masses, shafts = _responses(result)
    omega = np.asarray(result.speed)[:, None] * np.asarray(result.orders)[None, :]
    a, b = ends
    twist = masses[:, :, b] - masses[:, :, a]
    return shafts[:, :, shaft] * (1.0 + 1j * loss_factor) + 1j * omega * (damping * twist)


def damping_power(
    result: ResponseResult,
    shaft: int,
    ends: Sequence[int],
    loss_factor: float,
    damping: float,
) -> NDArray[np.float64]:
    """Power dissipated in an element, the mean over a cycle of its damping torque times the
    twist rate.

    P = sum_q (1/2) omega_q (eta k + c omega_q) |dtheta_q|^2, omega_q = q Omega (the damping
    work per cycle of a harmonic twist times its frequency: S. S. Rao, *Mechanical
    Vibrations*, 5th ed., 2011, section 2.7; module docstring). The coupling's P_KV of DIN
    740-2 is checked against it.

    Parameters
    ----------
    result : ResponseResult
        The forced response.
    shaft : int
        The element's index in the model.
    ends : sequence of int
        (a, b), the indices of its two masses (actual angles).
    loss_factor : float
        Its hysteretic loss factor eta (dimensionless).
    damping : float
        Its viscous damping c (N m s/rad, actual).

    Returns
    -------
    numpy.ndarray
        Dissipated power (W), shape (S,).
    """
    masses, shafts = _responses(result)
    omega = np.asarray(result.speed)[:, None] * np.asarray(result.orders)[None, :]
    a, b = ends
    twist = masses[:, :, b] - masses[:, :, a]
    t = np.abs(shafts[:, :, shaft])
    dt = np.abs(twist)
    # eta k |dtheta|^2 = eta |T| |dtheta| (k = |T| / |dtheta|, the element's actual stiffness)
    per_order = 0.5 * omega * (loss_factor * t * dt + damping * omega * dt * dt)
    return np.sum(per_order, axis=1)


def resolved_worst(
    result: ResponseResult,
    curve: Callable[[ResponseResult], ArrayLike],
    limit: Callable[[NDArray[np.float64]], ArrayLike],
    excluded: Iterable[tuple[float, float]] = (),
    *,
    low: float | None = None,
    high: float | None = None,
) -> tuple[float, float, float] | None:
    """The largest curve / limit over the speeds of ``result`` outside the intervals
    ``excluded``, resolved (module docstring).

    Parameters
    ----------
    result : ResponseResult
        A resolved :class:`~crankdyn.torsion.response.ResponseResult` (``at`` evaluates more
        speeds).
    curve : callable
        ``curve(r)`` -> (S,) values at the speeds of a response ``r`` (the quantity's unit).
    limit : callable
        ``limit(speeds)`` -> (S,) limits at speeds (rad/s), in the curve's unit (NaN where none
        applies).
    excluded : iterable of (float, float)
        Speed intervals left out (rad/s; barred ranges); their ends are sampled.
    low, high : float or None
        The range considered (rad/s; default the response's).

    Returns
    -------
    (value, limit, speed) or None
        The curve's value, the limit and the speed (rad/s) where the ratio is largest; None when
        no speed outside the intervals has a limit.

    Examples
    --------
    The two-mass line of the module's example swept over 100-400 rad/s: with the order-2
    resonance (near 182.6 rad/s) left out, the worst shaft torque is the order-1 resonance at
    omega_n = sqrt(k (1/J_1 + 1/J_2)) = 365.148 rad/s, where the elastic torque k |dtheta| is
    T J_2 / (J_1 + J_2) / eta = 750 N m (the order-2 harmonic adds 0.002 N m):

    >>> from crankdyn.torsion.excitation import UniformExcitation
    >>> from crankdyn.torsion.model import Mass, Shaft, TorsionModel
    >>> from crankdyn.torsion.sweep import forced_response
    >>> model = TorsionModel((Mass("a", 1.0, cylinders=(1,)), Mass("b", 3.0)),
    ...                      (Shaft(("a", "b"), stiffness=1e5, loss_factor=0.1),))
    >>> r = forced_response(model, UniformExcitation(100.0, [0.0]), np.linspace(100, 400, 31),
    ...                     [1.0, 2.0])
    >>> def torque(x):
    ...     return x.synthesized_shaft_torque[:, 0]
    >>> def limit(w):
    ...     return np.full(np.size(w), 1000.0)
    >>> value, limit_value, speed = resolved_worst(r, torque, limit, [(170.0, 200.0)])
    >>> f"{value:.2f} N m / {limit_value:g} N m at {speed:.3f} rad/s"
    '750.00 N m / 1000 N m at 365.148 rad/s'
    """
    speed = np.asarray(result.speed, dtype=float)
    low = float(speed[0]) if low is None else float(low)
    high = float(speed[-1]) if high is None else float(high)
    ends = [low, high] + [v for pair in excluded for v in pair if low <= v <= high]
    extra = np.setdiff1d(np.array(ends, dtype=float), speed)
    values = np.asarray(curve(result), dtype=float)
    if extra.size and result.evaluator is not None:
        speed, first = merge_speeds(speed, extra)
        values = np.concatenate([values, np.asarray(curve(result.at(extra)), dtype=float)])[first]
    inside = (speed >= low * (1 - 1e-12)) & (speed <= high * (1 + 1e-12))
    speed, values = speed[inside], values[inside]
    limits = _limit_at(limit, speed)
    if result.evaluator is not None and speed.size >= 3:
        for _ in range(_ROUNDS):
            with np.errstate(divide="ignore", invalid="ignore"):
                ratio = np.where(np.isfinite(limits) & (limits > 0.0), values / limits, 0.0)
            new, _ = refinement_speeds(speed, ratio[:, None], tolerance=_TOLERANCE)
            if new.size == 0:
                break
            speed, first = merge_speeds(speed, new)
            values = np.concatenate([values, np.asarray(curve(result.at(new)), dtype=float)])[first]
            limits = np.concatenate([limits, _limit_at(limit, new)])[first]
    keep = np.isfinite(limits) & (limits > 0.0)
    for a, b in excluded:
        keep &= ~((speed > a) & (speed < b))
    if not np.any(keep):
        return None
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(keep, values / np.where(keep, limits, 1.0), -np.inf)
    k = int(np.argmax(ratio))
    return float(values[k]), float(limits[k]), float(speed[k])


def _limit_at(
    limit: Callable[[NDArray[np.float64]], ArrayLike], speed: NDArray[np.float64]
) -> NDArray[np.float64]:
    """A limit's values at the speeds (rad/s), one per speed: a constant limit (a maker's
    torque, a rule value above 0.8 n_0) may give one number for every speed."""
    return np.broadcast_to(np.asarray(limit(speed), dtype=float), speed.shape).copy()
