"""Holzer's method for the free vibration of a chain (numeric core and results).

Holzer's tabular method (H. Holzer, *Die Berechnung der Drehschwingungen*, Springer 1921; seed 003,
"霍尔茨法计算系统的自由振动"; J. P. Den Hartog, *Mechanical Vibrations*, 4th ed. 1956): at a trial
frequency omega, give the free-end mass the amplitude theta_1 = 1 and walk along the chain; at
every mass i

    inertia torque        J_i omega^2 theta_i
    ground torque         -k_g,i theta_i            (a grounded shaft at mass i, if any)
    accumulated torque    T_i = T_{i-1} + J_i omega^2 theta_i - k_g,i theta_i
    twist of shaft i      T_i / k_i
    next amplitude        theta_{i+1} = theta_i - T_i / k_i

The torque left after the last mass, the residual T_n(omega), must vanish at the far (free) end:
its zeros are the natural frequencies. The method needs no matrix; each row of the table is one
mass. Amplitudes are relative (theta_1 = 1); torques are per radian of theta_1 (N m/rad).
Masses beyond gears enter reflected to the reference speed (:mod:`crankdyn.torsion.model`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.errors import InputError
from crankdyn.results import Result, column, freeze, scalar
from crankdyn.torsion.model import ChainArrays, TorsionModel
from crankdyn.torsion.roots import eigenvalue_bound, isolate_and_refine, require_chain

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = [
    "HolzerTable",
    "ResidualCurve",
    "holzer_frequencies",
    "holzer_residual",
    "holzer_table",
    "residual_curve",
]

_TINY = 1e-300
HZ = 1.0 / (2.0 * math.pi)  # scale rad/s -> Hz for exported keys


@dataclass(frozen=True)
class HolzerTable(Result):
    """Holzer's table of a chain at one trial frequency (one row per degree of freedom;
    :func:`holzer_table`, module docstring).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel or None
        The model the table is of (not exported).
    """

    title = "Holzer table"
    mass: np.ndarray = column("mass", "Mass", "")
    inertia: np.ndarray = column("inertia_kg_m2", "Inertia J", "kg·m²")
    inertia_omega2: np.ndarray = column("j_omega2_Nm_per_rad", "J ω²", "N·m/rad")
    angle: np.ndarray = column("angle", "Angle θ (θ₁ = 1)", "")
    inertia_torque: np.ndarray = column(
        "inertia_torque_Nm_per_rad", "Inertia torque J ω² θ", "N·m/rad"
    )
    ground_torque: np.ndarray | None = column(
        "ground_torque_Nm_per_rad", "Ground torque -k_g θ", "N·m/rad"
    )
    accumulated_torque: np.ndarray = column(
        "accumulated_torque_Nm_per_rad", "Accumulated torque ΣT", "N·m/rad"
    )
    stiffness: np.ndarray = column("shaft_stiffness_Nm_per_rad", "Shaft stiffness k", "N·m/rad")
    twist: np.ndarray = column("twist", "Twist ΣT / k", "")
    frequency: float = scalar("frequency_hz", "Trial frequency", "Hz", HZ)
    residual_torque: float = scalar(
        "residual_torque_Nm_per_rad", "Residual torque (zero at a natural frequency)", "N·m/rad"
    )
    model_name: str = scalar("model", "Model", "", summary=False)
    model: TorsionModel | None = field(default=None, repr=False, compare=False)


def _trial_lambda(omega: ArrayLike) -> NDArray[np.float64]:
    omega = np.asarray(omega, dtype=float)
    if np.any(~np.isfinite(omega)) or np.any(omega < 0.0):
        raise InputError("a trial frequency must be a finite number >= 0", key="frequency")
    if np.any(omega > 1e100):
        raise InputError("the trial frequency is too high (above 1e100 rad/s)", key="frequency")
    return omega * omega


def holzer_table(model: TorsionModel, omega: float) -> HolzerTable:
    """Holzer's table of a chain at a trial circular frequency (Holzer 1921; seed 003; Den
    Hartog 1956; the recurrence in the module docstring).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        An unbranched chain.
    omega : float
        The trial frequency (rad/s), >= 0.

    Returns
    -------
    HolzerTable
        Amplitudes (theta_1 = 1), torques per radian of theta_1 (N m/rad) of every mass, and
        the residual torque (N m/rad), zero at a natural frequency.

    Raises
    ------
    crankdyn.errors.InputError
        A branched model (names the model file), a trial frequency that is negative, not
        finite or so high that the table overflows (key ``frequency``).

    Examples
    --------
    Two masses, 1 and 3 kg m^2, on a shaft of 300 N m/rad: at its natural frequency, 20 rad/s,
    the residual vanishes.

    >>> from crankdyn.torsion.elements import Mass, Shaft
    >>> from crankdyn.torsion.model import TorsionModel
    >>> shaft = Shaft(("a", "b"), stiffness=300.0)
    >>> model = TorsionModel((Mass("a", 1.0), Mass("b", 3.0)), (shaft,))
    >>> table = holzer_table(model, 20.0)
    >>> [round(float(x), 9) for x in table.angle], round(table.residual_torque, 9)
    ([1.0, -0.333333333], 0.0)
    """
    chain = require_chain(model, "Holzer's method")
    lam = float(_trial_lambda(omega))
    J, k, kg = chain.inertia, chain.stiffness, chain.ground_stiffness
    n = chain.size
    theta = np.empty(n)
    inertia_torque = np.empty(n)
    ground_torque = np.empty(n)
    accumulated = np.empty(n)
    twist = np.full(n, np.nan)
    t, th = 0.0, 1.0
    with np.errstate(all="ignore"):  # an overflow is reported below
        for i in range(n):
            theta[i] = th
            inertia_torque[i] = J[i] * lam * th
            ground_torque[i] = -kg[i] * th
            t = t + inertia_torque[i] + ground_torque[i]
            accumulated[i] = t
            if i < n - 1:
                twist[i] = t / k[i]
                th = th - twist[i]
    stiffness = np.append(k, np.nan)
    if not np.all(np.isfinite(accumulated)):
        raise InputError(
            "the trial frequency is too high for this model: Holzer's table overflows",
            key="frequency",
            value=float(omega) / (2.0 * math.pi),
        )
    return HolzerTable(
        mass=freeze(model.dof_names, dtype=object),
        inertia=freeze(J),
        inertia_omega2=freeze(J * lam),
        angle=freeze(theta),
        inertia_torque=freeze(inertia_torque),
        ground_torque=freeze(ground_torque) if np.any(kg) else None,
        accumulated_torque=freeze(accumulated),
        stiffness=freeze(stiffness),
        twist=freeze(twist),
        frequency=float(omega),
        residual_torque=float(accumulated[-1]),
        model_name=model.name,
        model=model,
    )


def holzer_residual(model: TorsionModel, omega: ArrayLike) -> NDArray[np.float64]:
    """Holzer's residual torque T_n at every trial frequency, vectorised over omega; its zeros
    are the natural frequencies (module docstring).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        An unbranched chain.
    omega : array_like
        Trial frequencies (rad/s), >= 0.

    Returns
    -------
    numpy.ndarray
        T_n (N m per rad of theta_1), the shape of ``omega`` (inf or NaN where it overflows).

    Raises
    ------
    crankdyn.errors.InputError
        A branched model, or a trial frequency that is negative or not finite.

    Examples
    --------
    >>> from crankdyn.torsion.elements import Mass, Shaft
    >>> from crankdyn.torsion.model import TorsionModel
    >>> shaft = Shaft(("a", "b"), stiffness=300.0)
    >>> model = TorsionModel((Mass("a", 1.0), Mass("b", 3.0)), (shaft,))
    >>> np.round(holzer_residual(model, [0.0, 10.0, 20.0]), 9)
    array([  0., 300.,   0.])
    """
    chain = require_chain(model, "Holzer's method")
    lam = _trial_lambda(omega)
    J, k, kg = chain.inertia, chain.stiffness, chain.ground_stiffness
    t = np.zeros_like(lam)
    th = np.ones_like(lam)
    with np.errstate(over="ignore", invalid="ignore"):  # a long chain's residual may overflow
        for i in range(chain.size):
            t = t + (J[i] * lam - kg[i]) * th
            if i < chain.size - 1:
                th = th - t / k[i]
    return t


def _ratio_walk(
    chain: ChainArrays, lam: NDArray[np.float64]
) -> tuple[NDArray[np.int_], NDArray[np.float64]]:
    """Holzer's walk in ratio form (no overflow): tau_i = T_i / theta_i and
    rho_i = theta_{i+1} / theta_i = 1 - tau_i / k_i. Returns the number of eigenvalues below
    every lambda (negative rho_i, and tau_n > 0 for the last minor D_n / D_{n-1} = -tau_n) and
    the sign of the residual T_n = tau_n * theta_n."""
    J, k, kg = chain.inertia, chain.stiffness, chain.ground_stiffness
    n = chain.size
    count = np.zeros(lam.shape, dtype=int)
    sign = np.ones(lam.shape)
    carry = np.zeros_like(lam)  # T_{i-1} / theta_i
    tau = carry
    for i in range(n):
        tau = carry + J[i] * lam - kg[i]
        if i < n - 1:
            rho = 1.0 - tau / k[i]
            rho = np.where(rho == 0.0, -_TINY, rho)
            count += rho < 0.0
            sign *= np.sign(rho)
            carry = tau / rho
    count += tau > 0.0
    return count, sign * np.sign(tau)


def _walk_ratios(
    J: NDArray[np.float64], k: NDArray[np.float64], kg: NDArray[np.float64], lam: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """One Holzer walk at lambda in ratio form: the carried torque per angle arriving at every
    mass (T_{i-1} / theta_i) and the ratios rho_i = theta_{i+1} / theta_i."""
    n = J.size
    carry = np.zeros(n)
    rho = np.ones(max(n - 1, 0))
    c = 0.0
    for i in range(n):
        carry[i] = c
        tau = c + J[i] * lam - kg[i]
        if i < n - 1:
            r = 1.0 - tau / k[i]
            rho[i] = r if r != 0.0 else -_TINY
            c = tau / rho[i]
    return carry, rho


def _amplitudes(chain: ChainArrays, lam: float) -> NDArray[np.float64]:
    """The mode shape at an eigenvalue lambda from Holzer walks from both free ends.

    A walk from one end alone loses accuracy where the mode dies away (the recurrence then
    amplifies its rounding errors), so the walk from the left is used up to a joining mass m
    and the walk from the right beyond it. At m the two walks' torques and mass m's inertia
    torque balance, carry_left + carry_right + J_m lambda - k_g,m = gamma_m = 0 at an exact
    eigenvalue; m is the mass with the smallest |gamma_m| (the twisted factorisation of
    I. S. Dhillon and B. N. Parlett, Linear Algebra Appl. 387 (2004) 1-28, in Holzer's terms).
    Scaled to theta_m = 1.
    """
    J, k, kg = chain.inertia, chain.stiffness, chain.ground_stiffness
    n = chain.size
    left_carry, left_rho = _walk_ratios(J, k, kg, lam)
    right_carry, right_rho = _walk_ratios(J[::-1], k[::-1], kg[::-1], lam)
    gamma = left_carry + right_carry[::-1] + J * lam - kg
    m = int(np.argmin(np.abs(gamma)))
    theta = np.empty(n)
    theta[m] = 1.0
    for i in range(m - 1, -1, -1):
        theta[i] = theta[i + 1] / left_rho[i]
    for i in range(m + 1, n):
        theta[i] = theta[i - 1] / right_rho[n - 1 - i]
    return theta


def holzer_frequencies(model: TorsionModel) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Natural circular frequencies and mode shapes of a chain by Holzer's method: every root
    of the residual torque, isolated by the sign count of Holzer's amplitudes (a Sturm
    sequence, :mod:`crankdyn.torsion.roots`); the shapes from Holzer walks from both ends
    (the twisted factorisation of Dhillon and Parlett 2004).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        An unbranched chain.

    Returns
    -------
    omega : numpy.ndarray
        Natural frequencies (rad/s), ascending (0 for the rigid-body mode of a free chain),
        shape (dofs,).
    shapes : numpy.ndarray
        Mode shapes (dimensionless, relative), shape (dofs, modes).

    Raises
    ------
    crankdyn.errors.InputError
        A branched model (names the model file).

    Examples
    --------
    Against the closed form of two masses (:func:`crankdyn.torsion.closed_form.two_mass`:
    omega^2 = k (J_1 + J_2) / (J_1 J_2) = 400 rad^2/s^2):

    >>> from crankdyn.torsion.elements import Mass, Shaft
    >>> from crankdyn.torsion.model import TorsionModel
    >>> shaft = Shaft(("a", "b"), stiffness=300.0)
    >>> model = TorsionModel((Mass("a", 1.0), Mass("b", 3.0)), (shaft,))
    >>> omega, shapes = holzer_frequencies(model)
    >>> np.round(omega, 9), round(float(shapes[1, 1] / shapes[0, 1]), 9)
    (array([ 0., 20.]), -0.333333333)
    """
    chain = require_chain(model, "Holzer's method")
    lam = isolate_and_refine(
        lambda x: _ratio_walk(chain, x)[0],
        lambda x: _ratio_walk(chain, x)[1],
        chain.size,
        eigenvalue_bound(chain),
        model.is_free,
    )
    shapes = np.column_stack([_amplitudes(chain, x) for x in lam])
    return np.sqrt(lam), shapes


@dataclass(frozen=True)
class ResidualCurve(Result):
    """Holzer's residual torque against the trial frequency (:func:`residual_curve`)."""

    title = "Holzer residual torque"
    frequency: np.ndarray = column("frequency_hz", "Trial frequency", "Hz", HZ)
    residual_torque: np.ndarray = column("residual_torque_Nm_per_rad", "Residual torque", "N·m/rad")
    natural_frequencies: np.ndarray = scalar(
        "natural_frequencies_hz", "Natural frequencies (residual zeros)", "Hz", HZ
    )
    model_name: str = scalar("model", "Model", "", summary=False)

    def plot(self, fig: Figure | None = None) -> Figure:
        """The residual torque against the frequency, with its zeros marked.

        Parameters
        ----------
        fig : matplotlib.figure.Figure or None
            A figure to draw into; None makes a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.torsion import plot_residual_curve

        return plot_residual_curve(self, fig=fig)


def residual_curve(
    model: TorsionModel, omega_max: float | None = None, points: int = 2001
) -> ResidualCurve:
    """Holzer's residual torque from 0 to omega_max, with the natural frequencies found by
    :func:`holzer_frequencies` (sampled exactly, so the curve's zeros show at them).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        An unbranched chain.
    omega_max : float or None
        The highest trial frequency (rad/s), > 0; None for 1.15 times the highest natural
        frequency (1 rad/s when that is 0).
    points : int
        Equally spaced trial frequencies from 0 to ``omega_max`` (the natural frequencies
        are added).

    Returns
    -------
    ResidualCurve
        Trial frequencies (rad/s; exported in Hz), residual torques (N m/rad) and the natural
        frequencies (rad/s).

    Raises
    ------
    crankdyn.errors.InputError
        A branched model, or ``omega_max`` not positive (key ``frequency``).

    Examples
    --------
    >>> from crankdyn.torsion.elements import Mass, Shaft
    >>> from crankdyn.torsion.model import TorsionModel
    >>> shaft = Shaft(("a", "b"), stiffness=300.0)
    >>> model = TorsionModel((Mass("a", 1.0), Mass("b", 3.0)), (shaft,))
    >>> curve = residual_curve(model, points=5)
    >>> curve.frequency
    array([ 0.  ,  5.75, 11.5 , 17.25, 20.  , 23.  ])
    """
    natural, _ = holzer_frequencies(model)
    if omega_max is None:
        omega_max = 1.15 * float(natural[-1]) if natural[-1] > 0 else 1.0
    if not (math.isfinite(omega_max) and omega_max > 0.0):
        raise InputError("the highest frequency must be positive", key="frequency")
    omega = np.linspace(0.0, omega_max, points)
    omega = np.union1d(omega, natural[natural <= omega_max])
    return ResidualCurve(
        frequency=freeze(omega),
        residual_torque=freeze(holzer_residual(model, omega)),
        natural_frequencies=freeze(natural),
        model_name=model.name,
    )
