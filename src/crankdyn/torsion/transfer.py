"""The transfer-matrix method for chains (numeric core).

The state at a station is z = (theta, T): the angle and the shaft torque, T = k (theta_{i+1} -
theta_i) positive when the shaft is twisted forward (E. C. Pestel and F. A. Leckie, *Matrix
Methods in Elastomechanics*, McGraw-Hill 1963; seed 003, "传递矩阵法"). Across mass i (point
matrix, harmonic motion at omega, a grounded shaft of stiffness k_g at the mass)::

    theta^R = theta^L
    T^R     = T^L + (k_g - omega^2 J) theta^L          P_i = [[1, 0], [k_g - omega^2 J, 1]]

and along shaft i (field matrix)::

    theta_{i+1} = theta_i + T / k                      F_i = [[1, 1/k], [0, 1]]

so z_n^R = U z_1^L with U = P_n F_{n-1} P_{n-1} ... F_1 P_1. Both ends are free (a fixed end is
a grounded shaft in the point matrix): T_1^L = 0, and the frequency equation is
U_21(omega) = T_n^R = 0. With damping the same matrices hold with complex entries:
k -> k + i omega c + i eta k, and k_g - omega^2 J -> k_g + i omega c_g + i eta_g k_g - omega^2 J.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.errors import InputError
from crankdyn.torsion.model import ChainArrays, TorsionModel
from crankdyn.torsion.roots import eigenvalue_bound, isolate_and_refine, require_chain

__all__ = ["chain_transfer_matrix", "point_matrices", "transfer_frequencies"]


def _omega(omega: ArrayLike) -> NDArray[np.float64]:
    omega = np.asarray(omega, dtype=float)
    if np.any(~np.isfinite(omega)) or np.any(omega < 0.0):
        raise InputError("a frequency must be a finite number >= 0", key="frequency")
    return omega


def point_matrices(
    chain: ChainArrays, omega: ArrayLike, damped: bool = False
) -> tuple[NDArray[np.inexact], NDArray[np.inexact]]:
    """Point matrices of every mass and field matrices of every shaft (Pestel and Leckie 1963;
    seed 003; module docstring).

    Parameters
    ----------
    chain : crankdyn.torsion.model.ChainArrays
        The chain (inertias kg m^2, stiffnesses N m/rad, damping N m s/rad, loss factors).
    omega : array_like
        Frequencies (rad/s), >= 0.
    damped : bool
        Whether to include damping (complex matrices).

    Returns
    -------
    point : numpy.ndarray
        P_i, shape omega.shape + (n, 2, 2); entry (1, 0) in N m/rad.
    field : numpy.ndarray
        F_i, shape omega.shape + (n - 1, 2, 2); entry (0, 1) in rad/(N m).

    Raises
    ------
    crankdyn.errors.InputError
        A frequency that is negative or not finite (key ``frequency``).
    """
    w = _omega(omega)[..., None]
    ground = chain.ground_stiffness - w**2 * chain.inertia
    k = chain.stiffness + 0.0 * w
    if damped:
        ground = ground + 1j * (w * chain.ground_damping + chain.ground_hysteretic)
        k = k + 1j * (w * chain.damping + chain.hysteretic)
    dtype = complex if damped else float
    p = np.zeros((*ground.shape, 2, 2), dtype=dtype)
    p[..., 0, 0] = p[..., 1, 1] = 1.0
    p[..., 1, 0] = ground
    f = np.zeros((*k.shape, 2, 2), dtype=dtype)
    f[..., 0, 0] = f[..., 1, 1] = 1.0
    f[..., 0, 1] = 1.0 / k
    return p, f


def chain_transfer_matrix(
    model: TorsionModel, omega: ArrayLike, damped: bool = False
) -> NDArray[np.inexact]:
    """Overall transfer matrix U = P_n F_{n-1} ... F_1 P_1 from the left of the first mass to
    the right of the last, vectorised over omega (module docstring).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        An unbranched chain.
    omega : array_like
        Frequencies (rad/s), >= 0.
    damped : bool
        Whether to include damping (complex matrices).

    Returns
    -------
    numpy.ndarray
        U, shape omega.shape + (2, 2), acting on (theta in rad, T in N m); U_21 (N m/rad)
        vanishes at the natural frequencies of a free chain.

    Raises
    ------
    crankdyn.errors.InputError
        A branched model, or a frequency that is negative or not finite.

    Examples
    --------
    >>> from crankdyn.torsion.elements import Mass, Shaft
    >>> from crankdyn.torsion.model import TorsionModel
    >>> shaft = Shaft(("a", "b"), stiffness=300.0)
    >>> model = TorsionModel((Mass("a", 1.0), Mass("b", 3.0)), (shaft,))
    >>> np.round(chain_transfer_matrix(model, [10.0, 20.0])[:, 1, 0], 9)
    array([-300.,    0.])
    """
    chain = require_chain(model, "the transfer-matrix method")
    p, f = point_matrices(chain, omega, damped)
    u = p[..., 0, :, :]
    for i in range(1, chain.size):
        u = p[..., i, :, :] @ (f[..., i - 1, :, :] @ u)
    return u


def _walk(
    chain: ChainArrays, lam: NDArray[np.float64]
) -> tuple[NDArray[np.int_], NDArray[np.float64]]:
    """Carry z = (1, 0) through the point and field matrices at omega^2 = lam, scaling it at
    every station (the signs are kept). Returns the number of eigenvalues below each lam (sign
    changes of theta between stations, and theta_n T_n^R < 0 for the last minor) and the sign
    of the residual T_n^R."""
    n = chain.size
    theta = np.ones_like(lam)
    torque = np.zeros_like(lam)
    count = np.zeros(lam.shape, dtype=int)
    for i in range(n):
        point = chain.ground_stiffness[i] - lam * chain.inertia[i]
        # z <- P_i z
        torque = point * theta + torque
        if i < n - 1:
            # z <- F_i z
            new_theta = theta + torque / chain.stiffness[i]
            new_theta = np.where(new_theta == 0.0, -1e-300 * np.sign(theta), new_theta)
            count += np.sign(new_theta) != np.sign(theta)
            theta = new_theta
            scale = np.maximum(np.abs(theta), np.abs(torque) / chain.stiffness[i])
            theta, torque = theta / scale, torque / scale
    count += theta * torque < 0.0
    return count, np.sign(torque)


def _twisted_shape(chain: ChainArrays, lam: float) -> NDArray[np.float64]:
    """The mode shape at an eigenvalue: the state carried from the left end up to a joining
    mass m and from the right end (through the inverse matrices) beyond it, m being the mass
    where the two carried torques balance best (smallest |gamma_m|, gamma_m = T^R/theta from
    the right - T^L/theta from the left - (k_g - omega^2 J)); the twisted factorisation of
    Dhillon and Parlett (2004) in transfer-matrix terms. Scaled to theta_m = 1."""
    n = chain.size
    point = chain.ground_stiffness - lam * chain.inertia
    k = chain.stiffness
    left = np.zeros(n)  # T^L / theta from the left
    ratio_f = np.ones(max(n - 1, 0))  # theta_{i+1} / theta_i carried from the left
    z = np.array([1.0, 0.0])
    for i in range(n):
        left[i] = z[1] / z[0]
        z = np.array([[1.0, 0.0], [point[i], 1.0]]) @ z
        if i < n - 1:
            new = np.array([[1.0, 1.0 / k[i]], [0.0, 1.0]]) @ z
            new[0] = new[0] if new[0] != 0.0 else -1e-300
            ratio_f[i] = new[0] / z[0]
            z = new / abs(new[0])
    right = np.zeros(n)  # T^R / theta from the right
    ratio_b = np.ones(max(n - 1, 0))  # theta_{i+1} / theta_i carried from the right
    w = np.array([1.0, 0.0])
    for i in range(n - 1, -1, -1):
        right[i] = w[1] / w[0]
        w = np.array([[1.0, 0.0], [-point[i], 1.0]]) @ w
        if i > 0:
            new = np.array([[1.0, -1.0 / k[i - 1]], [0.0, 1.0]]) @ w
            new[0] = new[0] if new[0] != 0.0 else -1e-300
            ratio_b[i - 1] = w[0] / new[0]
            w = new / abs(new[0])
    gamma = right - left - point
    m = int(np.argmin(np.abs(gamma)))
    theta = np.empty(n)
    theta[m] = 1.0
    for i in range(m - 1, -1, -1):
        theta[i] = theta[i + 1] / ratio_f[i]
    for i in range(m + 1, n):
        theta[i] = theta[i - 1] * ratio_b[i - 1]
    return theta


def transfer_frequencies(model: TorsionModel) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Natural circular frequencies and mode shapes of a chain by the transfer-matrix method:
    the roots of U_21(omega), isolated by the sign count of the carried state (a Sturm
    sequence, :mod:`crankdyn.torsion.roots`); the shapes carried from both ends (the twisted
    factorisation of Dhillon and Parlett 2004).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        An unbranched chain.

    Returns
    -------
    omega : numpy.ndarray
        Natural frequencies (rad/s), ascending, shape (dofs,).
    shapes : numpy.ndarray
        Mode shapes (dimensionless, relative), shape (dofs, modes).

    Raises
    ------
    crankdyn.errors.InputError
        A branched model (names the model file).

    Examples
    --------
    Three equal masses on equal shafts, against :func:`crankdyn.torsion.closed_form.three_mass`
    (omega^2 = k/J and 3 k/J):

    >>> from crankdyn.torsion.elements import Mass, Shaft
    >>> from crankdyn.torsion.model import TorsionModel
    >>> model = TorsionModel(
    ...     (Mass("a", 1.0), Mass("b", 1.0), Mass("c", 1.0)),
    ...     (Shaft(("a", "b"), stiffness=100.0), Shaft(("b", "c"), stiffness=100.0)),
    ... )
    >>> omega, shapes = transfer_frequencies(model)
    >>> np.round(omega**2, 9)
    array([  0., 100., 300.])
    """
    chain = require_chain(model, "the transfer-matrix method")
    lam = isolate_and_refine(
        lambda x: _walk(chain, x)[0],
        lambda x: _walk(chain, x)[1],
        chain.size,
        eigenvalue_bound(chain),
        model.is_free,
    )
    shapes = np.column_stack([_twisted_shape(chain, x) for x in lam])
    return np.sqrt(lam), shapes
