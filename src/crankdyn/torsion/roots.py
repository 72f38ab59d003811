"""Isolating and refining the natural frequencies of a chain by a Sturm count (numeric core).

For a chain, the leading principal minors D_i(lambda) of K - lambda M (lambda = omega^2) form a
Sturm sequence: the number of sign changes in D_0 = 1, D_1, ..., D_n equals the number of
eigenvalues below lambda (J. H. Wilkinson, *The Algebraic Eigenvalue Problem*, 1965, ch. 5
sections 37-39; the bisection method of LAPACK's ``dstebz``). Holzer's and the transfer-matrix
recurrences compute exactly these minors, scaled by positive shaft stiffnesses: with theta_1 = 1,
theta_{i+1} = D_i / (k_1 ... k_i) and the residual torque T_n = -D_n / (k_1 ... k_{n-1}). So each
method counts the eigenvalues below a trial frequency from the signs of its own table, isolates
every natural frequency in a bracket holding exactly one, and refines it by bisection on the
sign of its residual, whose zeros are the natural frequencies. Vectorised over all modes at once.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from crankdyn.errors import InputError
from crankdyn.torsion.model import ChainArrays, TorsionModel

__all__ = ["eigenvalue_bound", "isolate_and_refine", "require_chain"]

_EPS = np.finfo(float).eps


def require_chain(model: TorsionModel, method: str) -> ChainArrays:
    """The model's chain arrays, or a one-line InputError for a branched model.

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The model.
    method : str
        The method that needs a chain, for the message (e.g. ``"Holzer's method"``).

    Returns
    -------
    crankdyn.torsion.model.ChainArrays
        The chain's inertias and stiffnesses, in order along the chain.

    Raises
    ------
    crankdyn.errors.InputError
        The model branches (names the model file and the junction mass).
    """
    chain = model.chain
    if chain is None:
        where = f' (it branches at "{model.junction}")' if model.junction else ""
        raise InputError(
            f"{method} needs an unbranched chain of masses and this model is not one{where}; "
            "use the eigen solver",
            file=model.source,
        )
    return chain


def eigenvalue_bound(chain: ChainArrays) -> float:
    """An upper bound of omega^2: Gershgorin's theorem applied to M^-1 K (every eigenvalue lies
    in a disc about a diagonal entry of radius the row's off-diagonal sum; Wilkinson 1965,
    ch. 2).

    Parameters
    ----------
    chain : crankdyn.torsion.model.ChainArrays
        The chain (inertias in kg m^2, stiffnesses in N m/rad).

    Returns
    -------
    float
        The bound (rad^2/s^2), slightly widened (relative 1e-9) so that it is strict.
    """
    diag, off = chain.stiffness_diagonals()
    row = np.abs(diag).copy()
    row[:-1] += np.abs(off)
    row[1:] += np.abs(off)
    return float(np.max(row / chain.inertia)) * (1.0 + 1e-9) + 1e-300


def isolate_and_refine(
    count_below: Callable[[NDArray[np.float64]], np.ndarray],
    residual_sign: Callable[[NDArray[np.float64]], np.ndarray],
    n: int,
    upper: float,
    free: bool,
    max_iterations: int = 400,
) -> NDArray[np.float64]:
    """All n eigenvalues lambda_r = omega_r^2 (ascending) of a chain, by bisection on the Sturm
    count, then on the residual's sign (module docstring; Wilkinson 1965, ch. 5 sections
    37-39).

    Parameters
    ----------
    count_below : callable
        lambda array (rad^2/s^2) -> number of eigenvalues below each lambda (int array).
    residual_sign : callable
        lambda array (rad^2/s^2) -> sign of the residual (-1, 0 or 1), which changes at every
        eigenvalue.
    n : int
        Number of degrees of freedom.
    upper : float
        An upper bound of the largest eigenvalue (rad^2/s^2).
    free : bool
        Whether the chain is free; its lowest eigenvalue is then exactly 0 (rigid body).
    max_iterations : int
        Most bisection steps of each phase (400 reach the last bit from any bound).

    Returns
    -------
    numpy.ndarray
        The eigenvalues (rad^2/s^2), ascending, shape (n,), to a relative 2 machine epsilons.

    Examples
    --------
    The eigenvalues 1, 4 and 9, seen only through their count and a residual that changes
    sign at each:

    >>> eig = np.array([1.0, 4.0, 9.0])
    >>> count = lambda lam: np.sum(lam[:, None] > eig, axis=1)
    >>> sign = lambda lam: np.sign(np.prod(lam[:, None] - eig, axis=1))
    >>> np.round(isolate_and_refine(count, sign, 3, 20.0, False), 12)
    array([1., 4., 9.])
    """
    lam = np.zeros(n)
    first = 1 if free else 0
    targets = np.arange(first, n)
    if targets.size == 0:
        return lam
    lo = np.zeros(targets.size)
    hi = np.full(targets.size, upper)
    count_lo = np.full(targets.size, first)  # eigenvalues at or below lo that are not targets
    count_hi = np.full(targets.size, n)
    # phase 1: bisect on the count until each bracket holds one eigenvalue
    active = count_hi - count_lo > 1
    for _ in range(max_iterations):
        if not active.any():
            break
        idx = np.flatnonzero(active)
        mid = 0.5 * (lo[idx] + hi[idx])
        c = count_below(mid)
        up = c >= targets[idx] + 1  # the target lies below mid
        hi[idx[up]], count_hi[idx[up]] = mid[up], c[up]
        lo[idx[~up]], count_lo[idx[~up]] = mid[~up], np.maximum(c[~up], first)
        converged = hi[idx] - lo[idx] <= 4.0 * _EPS * hi[idx]
        active[idx] = (count_hi[idx] - count_lo[idx] > 1) & ~converged
    # phase 2: bisect on the residual's sign, which changes once inside each bracket
    sign_hi = residual_sign(hi)
    active = hi - lo > 2.0 * _EPS * hi
    for _ in range(max_iterations):
        if not active.any():
            break
        idx = np.flatnonzero(active)
        mid = 0.5 * (lo[idx] + hi[idx])
        s = residual_sign(mid)
        exact = s == 0
        lo[idx[exact]] = hi[idx[exact]] = mid[exact]
        down = (s == sign_hi[idx]) & ~exact
        hi[idx[down]] = mid[down]
        up = ~down & ~exact
        lo[idx[up]] = mid[up]
        active[idx] = hi[idx] - lo[idx] > 2.0 * _EPS * hi[idx]
    lam[first:] = 0.5 * (lo + hi)
    return lam
