"""Coupling stiffness that depends on the mean torque: the model at each speed's load (analysis).

A rubber coupling's dynamic stiffness C_Tdyn rises with the mean torque it carries (the
catalogues tabulate it against the mean torque, DIN 740-2), and along the propeller law the
mean torque rises as n^2: the coupling is softer at low speed, and the low modes' resonances
move with the speed. When the model has such a coupling (a stiffness table of more than one row)
and load laws (:func:`crankdyn.torsion.sources.mean_torques`), the forced response takes at
every speed the stiffness at that speed's mean torque: the dynamic stiffness matrix becomes
D(omega, n) = D(omega) + (1 + i eta) Delta K(n), Delta K the change of the couplings'
(reflected) stiffness from the model's, the loss factor eta = psi / (2 pi) applying to the whole
stiffness. This module gives the change (:func:`load_change`); the forced response
(:mod:`crankdyn.torsion.sweep`) still solves all speeds and orders at once with it
(:meth:`crankdyn.torsion.solvers.LinearSystem.solve_with_change`: batched tridiagonal solves
with partial pivoting for a chain, batched dense solves otherwise). Natural frequencies and
the Campbell diagram use the model's own stiffness (at each coupling's ``reference_torque``);
:func:`model_at_speed` gives the model at one speed's load.
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.constants import RPM
from crankdyn.errors import InputError

if TYPE_CHECKING:
    from crankdyn.torsion.model import TorsionModel
    from crankdyn.torsion.solvers import LinearSystem

__all__ = [
    "coupling_stiffness",
    "load_change",
    "model_at_speed",
    "stiffness_change",
]


def _dependent(model: TorsionModel) -> list[int]:
    """Indices of the shafts that are couplings with a stiffness table of more than one row."""
    return [
        i
        for i, s in enumerate(model.shafts)
        if s.coupling is not None and s.coupling.load_dependent
    ]


def _has_loads(model: TorsionModel) -> bool:
    """Whether a source of the model carries a load law (a mean torque)."""
    return any(getattr(s, "load", None) is not None for s in model.sources)


def _has_drivers(model: TorsionModel) -> bool:
    """Whether an engine drives the loads (cylinders on the masses or an engine source): a
    shaft line alone has no mean torque, and keeps its couplings' model stiffness."""
    from crankdyn.torsion.sources import EngineSource

    return bool(model.cylinder_dofs) or any(isinstance(s, EngineSource) for s in model.sources)


def coupling_stiffness(
    model: TorsionModel, speeds: ArrayLike
) -> tuple[list[int], NDArray[np.float64], NDArray[np.float64]] | None:
    """The load-dependent couplings' stiffness C_Tdyn at the mean torque of every speed (DIN
    740-2 catalogue tables, :meth:`crankdyn.torsion.coupling.Coupling.stiffness_at`; the mean
    torques from the load laws, :func:`crankdyn.torsion.sources.mean_torques`).

    The result is None when the model has no such coupling, no load law or no engine to drive
    the loads (a shaft line alone carries no mean torque).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The model.
    speeds : array_like
        Reference speeds (rad/s), shape (S,) (a scalar is taken as one speed).

    Returns
    -------
    shafts : list of int
        Indices (in ``model.shafts``) of the load-dependent couplings, count of them.
    stiffness : numpy.ndarray
        Their actual C_Tdyn (N m/rad, with temperature factors, not reflected), shape
        (S, count).
    torque : numpy.ndarray
        Their mean torques |T| (N m), shape (S, count).

    Raises
    ------
    crankdyn.errors.InputError
        When a mean torque lies outside a coupling's stiffness table (never extrapolated): the
        model's file, key ``stiffness_table``, the torque (N m) as value, the speed in the
        message.

    Examples
    --------
    An engine driving a propeller (propeller law, 20 kN m at 600 rpm) through a rubber
    coupling whose stiffness rises with the mean torque:

    >>> from crankdyn.constants import RPM
    >>> from crankdyn.torsion import Coupling, Mass, Shaft, TorsionModel
    >>> from crankdyn.torsion.sources import LoadLaw, propeller
    >>> coupling = Coupling(table_torque=[0.0, 10e3, 20e3], table_stiffness=[1e5, 2e5, 2.5e5],
    ...                     relative_damping=1.0, nominal_torque=20e3)
    >>> model = TorsionModel(
    ...     masses=(Mass("engine", 50.0, cylinders=(1,)), Mass("propeller", 200.0)),
    ...     shafts=(Shaft(("engine", "propeller"), coupling=coupling),),
    ...     sources=(propeller("propeller", 4, fractions=[0.05],
    ...                        load=LoadLaw(20e3, 600 / RPM, 2.0)),),
    ... )
    >>> shafts, k, torque = coupling_stiffness(model, [300 / RPM, 600 / RPM])
    >>> shafts, k.ravel().tolist(), torque.ravel().round(6).tolist()
    ([0], [150000.0, 250000.0], [5000.0, 20000.0])
    """
    shafts = _dependent(model)
    if not shafts or not _has_loads(model) or not _has_drivers(model):
        return None
    from crankdyn.torsion.sources import mean_torques

    speeds = np.atleast_1d(np.asarray(speeds, dtype=float))
    mean = mean_torques(model, speeds).mean_torque  # (S, shafts)
    out = np.empty((speeds.size, len(shafts)))
    torques = np.empty_like(out)
    for j, i in enumerate(shafts):
        coupling = model.shafts[i].coupling
        assert coupling is not None and coupling.table_torque is not None  # _dependent
        t = np.abs(mean[:, i])
        low, high = coupling.table_torque[0], coupling.table_torque[-1]
        outside = (t < low * (1 - 1e-9) - 1e-12) | (t > high * (1 + 1e-9))
        if np.any(outside):
            k = int(np.flatnonzero(outside)[0])
            label = model.shafts[i].name or model.shafts[i].label
            raise InputError(
                f'coupling "{label}" carries a mean torque of {t[k] / 1e3:.6g} kN·m at '
                f"{speeds[k] * RPM:.6g} rpm, outside its stiffness table ({low / 1e3:.6g} to "
                f"{high / 1e3:.6g} kN·m; not extrapolated)",
                file=model.source,
                key="stiffness_table",
                value=float(t[k]),
            )
        out[:, j] = coupling.stiffness_at(t)
        torques[:, j] = t
    return shafts, out, torques


def model_at_speed(model: TorsionModel, speed: float) -> TorsionModel:
    """The model with every load-dependent coupling's stiffness at the mean torque of the
    reference speed ``speed`` (the model itself when nothing depends on the load).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The model.
    speed : float
        Reference speed (rad/s).

    Returns
    -------
    crankdyn.torsion.model.TorsionModel
        The model with each such coupling's ``reference_torque`` set to its mean torque at
        ``speed`` (its natural frequencies are those at that speed's load).

    Raises
    ------
    crankdyn.errors.InputError
        As :func:`coupling_stiffness`, for a mean torque outside a coupling's table.

    Examples
    --------
    An engine driving a propeller (propeller law, 20 kN m at 600 rpm) through a rubber
    coupling whose stiffness rises with the mean torque:

    >>> from crankdyn.constants import RPM
    >>> from crankdyn.torsion import Coupling, Mass, Shaft, TorsionModel
    >>> from crankdyn.torsion.sources import LoadLaw, propeller
    >>> coupling = Coupling(table_torque=[0.0, 10e3, 20e3], table_stiffness=[1e5, 2e5, 2.5e5],
    ...                     relative_damping=1.0, nominal_torque=20e3)
    >>> model = TorsionModel(
    ...     masses=(Mass("engine", 50.0, cylinders=(1,)), Mass("propeller", 200.0)),
    ...     shafts=(Shaft(("engine", "propeller"), coupling=coupling),),
    ...     sources=(propeller("propeller", 4, fractions=[0.05],
    ...                        load=LoadLaw(20e3, 600 / RPM, 2.0)),),
    ... )
    >>> model.shafts[0].stiffness, model_at_speed(model, 300 / RPM).shafts[0].stiffness
    (250000.0, 150000.0)
    """
    found = coupling_stiffness(model, [speed])
    if found is None:
        return model
    shafts, _k, torque = found
    changed = list(model.shafts)
    for j, i in enumerate(shafts):
        s = changed[i]
        assert s.coupling is not None  # a load-dependent coupling (_dependent)
        coupling = dataclasses.replace(s.coupling, reference_torque=float(torque[0, j]))
        # stiffness None: derived again from the coupling in Shaft.__post_init__ (the field
        # holds the normalised float; replace is typed by the fields, not by Shaft's __init__)
        changed[i] = dataclasses.replace(
            s,
            coupling=coupling,
            stiffness=None,  # type: ignore[arg-type]
            loss_factor=0.0,
        )
    return dataclasses.replace(model, shafts=tuple(changed))


def stiffness_change(
    model: TorsionModel, system: LinearSystem, speeds: ArrayLike
) -> (
    tuple[
        NDArray[np.int_], NDArray[np.float64], NDArray[np.float64], list[int], NDArray[np.float64]
    ]
    | None
):
    """The change of the load-dependent couplings' reflected stiffness from the model's at the
    mean torque of every reference speed (module docstring). The dynamic stiffness at speed n
    is D(omega) + (1 + i eta) Delta K(n). The result is None when nothing depends on the load
    (:func:`coupling_stiffness`).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The model.
    system : crankdyn.torsion.solvers.LinearSystem
        Its linear system (:func:`crankdyn.torsion.solvers.linear_system`).
    speeds : array_like
        Reference speeds (rad/s), shape (S,).

    Returns
    -------
    ends : numpy.ndarray
        The couplings' degrees of freedom in ``system``, shape (count, 2).
    delta : numpy.ndarray
        Reflected stiffness change (k(n) - k_model) r^2 (N m/rad), shape (S, count).
    eta : numpy.ndarray
        The couplings' loss factors (dimensionless), shape (count,).
    shafts : list of int
        The couplings' indices in ``model.shafts``.
    k_actual : numpy.ndarray
        Their actual stiffness k(n) (N m/rad), shape (S, count).

    Raises
    ------
    crankdyn.errors.InputError
        As :func:`coupling_stiffness`, for a mean torque outside a coupling's table.

    Examples
    --------
    An engine driving a propeller (propeller law, 20 kN m at 600 rpm) through a rubber
    coupling whose stiffness rises with the mean torque:

    >>> from crankdyn.constants import RPM
    >>> from crankdyn.torsion import Coupling, Mass, Shaft, TorsionModel
    >>> from crankdyn.torsion.sources import LoadLaw, propeller
    >>> coupling = Coupling(table_torque=[0.0, 10e3, 20e3], table_stiffness=[1e5, 2e5, 2.5e5],
    ...                     relative_damping=1.0, nominal_torque=20e3)
    >>> model = TorsionModel(
    ...     masses=(Mass("engine", 50.0, cylinders=(1,)), Mass("propeller", 200.0)),
    ...     shafts=(Shaft(("engine", "propeller"), coupling=coupling),),
    ...     sources=(propeller("propeller", 4, fractions=[0.05],
    ...                        load=LoadLaw(20e3, 600 / RPM, 2.0)),),
    ... )
    >>> from crankdyn.torsion.solvers import linear_system
    >>> ends, delta, eta, shafts, k = stiffness_change(model, linear_system(model), [300 / RPM])
    >>> ends.tolist(), delta.tolist(), f"{eta[0]:.6f}"
    ([[0, 1]], [[-100000.0]], '0.159155')
    """
    found = coupling_stiffness(model, speeds)
    if found is None:
        return None
    shafts, k_actual, _torque = found  # (S, count)
    first = np.array([model.index(model.shafts[i].between[0]) for i in shafts], dtype=int)
    r = model.speed_ratios[first]  # couplings join two masses at one speed (not ground)
    k_model = np.array([model.shafts[i].stiffness for i in shafts])
    eta = np.array([model.shafts[i].loss_factor for i in shafts])
    delta = (k_actual - k_model[None, :]) * (r * r)[None, :]  # reflected (S, count)
    ends = system.element_dofs[shafts]  # (count, 2)
    return ends, delta, eta, shafts, k_actual


def load_change(
    model: TorsionModel,
    system: LinearSystem,
    speeds: ArrayLike,
    omega: ArrayLike,
    hysteretic_frequency: float | None = None,
) -> tuple[NDArray[np.int_], NDArray[np.complexfloating], NDArray[np.float64]] | None:
    """The change of the load-dependent couplings' dynamic stiffness at every speed and order,
    (1 + i eta) Delta K(n) (module docstring), and every element's actual stiffness at each
    speed: what the forced response adds to D(omega) at speed n
    (:meth:`crankdyn.torsion.solvers.LinearSystem.solve_with_change`). The result is None when
    no coupling depends on the load (:func:`stiffness_change`).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The model.
    system : crankdyn.torsion.solvers.LinearSystem
        Its linear system (:func:`crankdyn.torsion.solvers.linear_system`).
    speeds : array_like
        Reference speeds n (rad/s), shape (S,).
    omega : array_like
        Circular frequencies of the orders at every speed (rad/s), shape (S, Q).
    hysteretic_frequency : float or None
        None: loss factors act as hysteretic damping (i eta k); else the circular frequency
        omega_h (rad/s) at which they are turned into viscous damping eta k / omega_h.

    Returns
    -------
    ends : numpy.ndarray
        The couplings' degrees of freedom in ``system``, shape (count, 2).
    change : numpy.ndarray
        Complex change of the couplings' reflected dynamic stiffness (N m/rad), shape
        (S, Q, count): (1 + i eta) delta, or delta + i omega eta delta / omega_h.
    k : numpy.ndarray
        Actual stiffness of every element (N m/rad) for the element torques
        k (theta_b - theta_a) / r, shape (S, 1, elements) (signed by the sense of rotation).

    Raises
    ------
    crankdyn.errors.InputError
        As :func:`coupling_stiffness`, for a mean torque outside a coupling's table.

    Examples
    --------
    An engine driving a propeller (propeller law, 20 kN m at 600 rpm) through a rubber
    coupling whose stiffness rises with the mean torque; the batched solve with the change
    agrees with the ordinary solve of the model at each speed's load:

    >>> from crankdyn.constants import RPM
    >>> from crankdyn.torsion import Coupling, Mass, Shaft, TorsionModel
    >>> from crankdyn.torsion.sources import LoadLaw, propeller
    >>> coupling = Coupling(table_torque=[0.0, 10e3, 20e3], table_stiffness=[1e5, 2e5, 2.5e5],
    ...                     relative_damping=1.0, nominal_torque=20e3)
    >>> model = TorsionModel(
    ...     masses=(Mass("engine", 50.0, cylinders=(1,)), Mass("propeller", 200.0)),
    ...     shafts=(Shaft(("engine", "propeller"), coupling=coupling),),
    ...     sources=(propeller("propeller", 4, fractions=[0.05],
    ...                        load=LoadLaw(20e3, 600 / RPM, 2.0)),),
    ... )
    >>> import numpy as np
    >>> from crankdyn.torsion.solvers import linear_system
    >>> system = linear_system(model)
    >>> speeds = np.array([300.0, 600.0]) / RPM
    >>> omega = 4.0 * speeds[:, None]
    >>> ends, change, k = load_change(model, system, speeds, omega)
    >>> k[:, 0, 0].tolist()
    [150000.0, 250000.0]
    >>> forcing = np.ones((2, 1, 2), dtype=complex)
    >>> x = system.solve_with_change(omega, forcing, ends, change)
    >>> one = linear_system(model_at_speed(model, speeds[0])).solve(omega[0], forcing[0])
    >>> bool(np.allclose(x[0], one, rtol=1e-12, atol=0.0))
    True
    """
    found = stiffness_change(model, system, speeds)
    if found is None:
        return None
    ends, delta, eta, shafts, k_actual = found
    first = np.array([model.index(model.shafts[i].between[0]) for i in shafts], dtype=int)
    w = np.asarray(omega, dtype=float)
    # the change of the dynamic stiffness per element: (1 + i eta) delta, or with the loss
    # factor as viscous damping at omega_h: delta + i omega eta delta / omega_h
    factor = (
        (1.0 + 1j * eta)[None, None, :]
        if hysteretic_frequency is None
        else 1.0 + 1j * eta[None, None, :] * (w[..., None] / hysteretic_frequency)
    )
    change = delta[:, None, :] * factor  # (S, Q, count)
    # element torques k_actual (actual twist) = k_actual rho (reflected twist), rho signed
    base_k = system.element_stiffness / system.element_ratio
    k = np.broadcast_to(base_k, (w.shape[0], 1, base_k.size)).copy()
    k[:, 0, shafts] = k_actual * model.signed_speed_ratios[first][None, :]
    return ends, change, k
