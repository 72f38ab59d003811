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

from crankdyn.errors import InputError
from crankdyn.torsion.model import ChainArrays, TorsionModel

__all__ = ["eigenvalue_bound", "isolate_and_refine", "require_chain"]

_EPS = np.finfo(float).eps


def require_chain(model: TorsionModel, method: str) -> ChainArrays:
    """The model's chain arrays, or a one-line InputError for a branched model."""
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
    """An upper bound of omega^2 (rad^2/s^2): Gershgorin's theorem applied to M^-1 K."""
    diag, off = chain.stiffness_diagonals()
    row = np.abs(diag).copy()
    row[:-1] += np.abs(off)
    row[1:] += np.abs(off)
    return float(np.max(row / chain.inertia)) * (1.0 + 1e-9) + 1e-300


def isolate_and_refine(
    count_below: Callable[[np.ndarray], np.ndarray],
    residual_sign: Callable[[np.ndarray], np.ndarray],
    n: int,
    upper: float,
    free: bool,
    max_iterations: int = 400,
) -> np.ndarray:
    """All n eigenvalues lambda_r = omega_r^2 (ascending) of a chain.

    Parameters
    ----------
    count_below
        lambda array -> number of eigenvalues below each lambda.
    residual_sign
        lambda array -> sign of the residual (-1, 0 or 1), which changes at every eigenvalue.
    n
        Number of degrees of freedom.
    upper
        An upper bound of the largest eigenvalue.
    free
        Whether the chain is free; its lowest eigenvalue is then exactly 0 (rigid body).
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
