"""Closed forms of free torsional vibration (numeric core).

Seed 003 (曲轴轴系的扭转振动, 第二节 "扭转振动系统自由振动计算"):

- one mass on a shaft fixed at its other end (单质量扭振系统): J theta'' + k theta = 0,
  omega = sqrt(k / J);
- two masses on a free shaft (双质量扭振系统): omega^2 = k (J_1 + J_2) / (J_1 J_2); the
  amplitudes are in the ratio A_2 / A_1 = -J_1 / J_2 and the node (结点) divides the shaft in the
  ratio J_2 : J_1, at the fraction J_2 / (J_1 + J_2) of its length from mass 1;
- three masses on a free shaft (三质量扭振系统, eq. 4-13): substituting theta_i = phi_i sin(omega t)
  into J_1 theta_1'' + k_1 (theta_1 - theta_2) = 0, J_2 theta_2'' - k_1 theta_1 + (k_1 + k_2)
  theta_2 - k_2 theta_3 = 0, J_3 theta_3'' - k_2 (theta_2 - theta_3) = 0 gives omega = 0 and the
  frequency equation
  J_1 J_2 J_3 omega^4 - [k_1 J_3 (J_1 + J_2) + k_2 J_1 (J_2 + J_3)] omega^2
  + k_1 k_2 (J_1 + J_2 + J_3) = 0,
  with the amplitude ratios phi_2 / phi_1 = 1 - J_1 omega^2 / k_1 and
  phi_3 = phi_2 - omega^2 (J_1 phi_1 + J_2 phi_2) / k_2 (Holzer's walk);
- N equal masses J joined by equal shafts k (the multi-mass system, 多质量扭振系统), whose
  eigenvalue problem is the second-difference matrix (e.g. G. Strang, *Linear Algebra and Its
  Applications*, the "-1 2 -1" matrices; Den Hartog, *Mechanical Vibrations*):
  free-free omega_r = 2 sqrt(k/J) sin(r pi / (2N)), r = 0 ... N-1;
  fixed-free (one shaft to ground at the first mass) omega_r = 2 sqrt(k/J) sin((2r-1) pi /
  (2 (2N + 1))), r = 1 ... N; fixed-fixed (shafts to ground at both ends) omega_r =
  2 sqrt(k/J) sin(r pi / (2 (N + 1))), r = 1 ... N.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from crankdyn.errors import InputError
from crankdyn.torsion.model import TorsionModel

__all__ = [
    "ENDS",
    "closed_form_modes",
    "single_mass",
    "three_mass",
    "two_mass",
    "uniform_chain",
]

ENDS = ("free-free", "fixed-free", "fixed-fixed")


def single_mass(inertia: float, stiffness: float) -> float:
    """omega = sqrt(k / J) of one mass on a shaft fixed at its other end (seed 003,
    单质量扭振系统).

    Parameters
    ----------
    inertia : float
        J (kg m^2), > 0.
    stiffness : float
        k (N m/rad), > 0.

    Returns
    -------
    float
        omega (rad/s).

    Examples
    --------
    >>> single_mass(2.0, 800.0)
    20.0
    """
    return math.sqrt(stiffness / inertia)


def two_mass(j1: float, j2: float, k: float) -> tuple[float, float, float]:
    """The elastic mode of two free masses on one shaft (seed 003, 双质量扭振系统):
    omega^2 = k (J_1 + J_2) / (J_1 J_2).

    Parameters
    ----------
    j1, j2 : float
        Inertias J_1, J_2 (kg m^2), > 0.
    k : float
        Shaft stiffness (N m/rad), > 0.

    Returns
    -------
    omega : float
        Natural frequency (rad/s).
    ratio : float
        Amplitude ratio A_2 / A_1 = -J_1 / J_2 (dimensionless).
    node : float
        Node position as a fraction J_2 / (J_1 + J_2) of the shaft's length from mass 1.

    Examples
    --------
    >>> two_mass(1.0, 3.0, 300.0)
    (20.0, -0.3333333333333333, 0.75)
    """
    omega = math.sqrt(k * (j1 + j2) / (j1 * j2))
    return omega, -j1 / j2, j2 / (j1 + j2)


def three_mass(
    j1: float, j2: float, j3: float, k1: float, k2: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The two elastic modes of three free masses (seed 003 eq. 4-13 and its frequency
    equation; see the module docstring).

    Parameters
    ----------
    j1, j2, j3 : float
        Inertias J_1, J_2, J_3 along the chain (kg m^2), > 0.
    k1, k2 : float
        Stiffnesses of the shafts J_1-J_2 and J_2-J_3 (N m/rad), > 0.

    Returns
    -------
    omega : numpy.ndarray
        [omega_1, omega_2] (rad/s, ascending), shape (2,).
    shapes : numpy.ndarray
        Amplitudes (dimensionless, phi_1 = 1), shape (2, 3): one row per mode.

    Examples
    --------
    Three equal masses on equal shafts: omega^2 = k/J and 3 k/J, the middle mass still in the
    first mode.

    >>> omega, shapes = three_mass(1.0, 1.0, 1.0, 100.0, 100.0)
    >>> np.round(omega**2, 9), np.round(shapes, 9)
    (array([100., 300.]), array([[ 1.,  0., -1.],
           [ 1., -2.,  1.]]))
    """
    a = j1 * j2 * j3
    b = k1 * j3 * (j1 + j2) + k2 * j1 * (j2 + j3)
    c = k1 * k2 * (j1 + j2 + j3)
    root = math.sqrt(b * b - 4.0 * a * c)
    # the smaller root by Vieta's formula avoids cancellation
    large = (b + root) / (2.0 * a)
    small = c / (a * large)
    lam = np.array([small, large])
    phi2 = 1.0 - j1 * lam / k1
    phi3 = phi2 - lam * (j1 + j2 * phi2) / k2
    shapes = np.column_stack([np.ones(2), phi2, phi3])
    return np.sqrt(lam), shapes


def uniform_chain(
    count: int, inertia: float, stiffness: float, ends: str = "free-free"
) -> NDArray[np.float64]:
    """Natural frequencies of N equal masses J on equal shafts k (the "-1 2 -1" matrices:
    Strang; Den Hartog; formulas in the module docstring).

    Parameters
    ----------
    count : int
        N, the number of masses.
    inertia : float
        J of every mass (kg m^2), > 0.
    stiffness : float
        k of every shaft (N m/rad), > 0.
    ends : str
        ``"free-free"`` (N - 1 shafts, one rigid-body mode at 0), ``"fixed-free"`` (also a
        shaft k from the first mass to ground) or ``"fixed-fixed"`` (shafts k to ground at both
        ends).

    Returns
    -------
    numpy.ndarray
        omega_r (rad/s), ascending, shape (N,).

    Raises
    ------
    ValueError
        An unknown ``ends``.

    Examples
    --------
    >>> [round(float(w), 9) for w in uniform_chain(3, 1.0, 100.0)]
    [0.0, 10.0, 17.320508076]
    >>> np.round(uniform_chain(1, 1.0, 100.0, "fixed-fixed") ** 2, 9)
    array([200.])
    """
    if ends not in ENDS:
        raise ValueError(f"ends must be one of {ENDS}")
    scale = 2.0 * math.sqrt(stiffness / inertia)
    n = int(count)
    if ends == "free-free":
        r = np.arange(n)
        return scale * np.sin(r * np.pi / (2 * n))
    r = np.arange(1, n + 1)
    if ends == "fixed-free":
        return scale * np.sin((2 * r - 1) * np.pi / (2 * (2 * n + 1)))
    return scale * np.sin(r * np.pi / (2 * (n + 1)))


def closed_form_modes(model: TorsionModel) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Natural frequencies and mode shapes of the models seed 003 solves in closed form: one
    mass grounded through one shaft (or alone and free), two or three free masses in a chain
    (:func:`single_mass`, :func:`two_mass`, :func:`three_mass`).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The model.

    Returns
    -------
    omega : numpy.ndarray
        Natural frequencies (rad/s), ascending (0 for the rigid-body mode), shape (modes,).
    shapes : numpy.ndarray
        Mode shapes (dimensionless, first amplitude 1), shape (dofs, modes).

    Raises
    ------
    crankdyn.errors.InputError
        Any other model (names the model file, its degrees of freedom and whether it is
        grounded or branched).
    """
    chain = model.chain
    n = model.dof_count
    grounded = chain is not None and bool(np.any(chain.ground_stiffness))
    if chain is not None and n == 1:
        if not grounded:
            return np.zeros(1), np.ones((1, 1))
        return np.array([single_mass(chain.inertia[0], chain.ground_stiffness[0])]), np.ones((1, 1))
    if chain is not None and not grounded and n in (2, 3):
        j = chain.inertia
        k = chain.stiffness
        if n == 2:
            omega, ratio, _ = two_mass(j[0], j[1], k[0])
            return np.array([0.0, omega]), np.array([[1.0, 1.0], [1.0, ratio]])
        omegas, shapes = three_mass(j[0], j[1], j[2], k[0], k[1])
        return np.concatenate([[0.0], omegas]), np.column_stack([np.ones(3), shapes.T])
    raise InputError(
        "closed forms exist for one grounded mass and for free chains of two or three masses; "
        f"this model has {n} degrees of freedom"
        + (" and grounded ends" if grounded else "")
        + ("" if chain is not None else " and branches"),
        file=model.source,
    )
