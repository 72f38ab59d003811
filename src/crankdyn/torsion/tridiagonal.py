"""Batched tridiagonal solves (numeric core): the dynamic-stiffness matrix of a chain model at
every speed and order at once (:mod:`crankdyn.torsion.solvers`: the pivoting fallback of the
chain solve and the solve with the load-dependent couplings' stiffness)."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = ["solve_tridiagonal"]


# ---- batched tridiagonal solve ---------------------------------------------------
def _abs1(z: np.ndarray) -> np.ndarray:
    return np.abs(z.real) + np.abs(z.imag)


def solve_tridiagonal(
    lower: np.ndarray, diag: np.ndarray, upper: np.ndarray, rhs: np.ndarray
) -> NDArray[np.inexact]:
    """Solve tridiagonal systems A x = b for a batch of matrices and right-hand sides.

    Gaussian elimination with partial pivoting (rows i and i+1 swapped when the sub-diagonal
    entry is the larger), as LAPACK's ``?gtsv`` (E. Anderson et al., *LAPACK Users' Guide*,
    3rd ed., SIAM 1999), vectorised over the batch: the loop runs over the n rows only.

    Parameters
    ----------
    lower, diag, upper : numpy.ndarray
        Sub-diagonal (..., n-1), diagonal (..., n) and super-diagonal (..., n-1), complex or
        real, broadcast together (any consistent unit, e.g. the dynamic stiffness in N m/rad).
    rhs : numpy.ndarray
        Right-hand sides (..., n) or (..., n, r) (e.g. torques in N m). Arrays, not lists
        (their common type is taken with :func:`numpy.result_type`).

    Returns
    -------
    numpy.ndarray
        x with the shape of ``rhs`` (broadcast against the matrices' batch shape), in the unit
        of ``rhs`` over that of the matrix (e.g. rad); float or complex as the inputs.

    Examples
    --------
    A chain of three unit stiffnesses, loaded at its free end (the exact solution 1, 2, 3), and
    a zero pivot that partial pivoting handles:

    >>> off = np.array([-1.0, -1.0])
    >>> solve_tridiagonal(off, np.array([2.0, 2.0, 1.0]), off, np.array([0.0, 0.0, 1.0]))
    array([1., 2., 3.])
    >>> one = np.array([1.0])
    >>> solve_tridiagonal(one, np.array([0.0, 1.0]), one, np.array([2.0, 3.0]))
    array([1., 2.])
    """
    d = np.asarray(diag)
    dtype = np.result_type(lower, d, upper, rhs, 1.0)
    b = np.asarray(rhs, dtype=dtype)
    vector = b.ndim == d.ndim
    if vector:
        b = b[..., None]
    batch = np.broadcast_shapes(d.shape[:-1], b.shape[:-2])
    n = d.shape[-1]
    d = np.array(np.broadcast_to(d, (*batch, n)), dtype=dtype)
    du = np.array(np.broadcast_to(upper, (*batch, max(n - 1, 0))), dtype=dtype)
    dl = np.array(np.broadcast_to(lower, (*batch, max(n - 1, 0))), dtype=dtype)
    b = np.array(np.broadcast_to(b, (*batch, n, b.shape[-1])), dtype=dtype)
    du2 = np.zeros((*batch, max(n - 2, 0)), dtype=dtype)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for i in range(n - 1):
            di, li, ui = d[..., i], dl[..., i], du[..., i]
            swap = _abs1(di) < _abs1(li)
            keep = ~swap
            fact = np.where(swap, di / np.where(swap, li, 1.0), li / np.where(keep, di, 1.0))
            d_next = d[..., i + 1]
            bi, bn = b[..., i, :], b[..., i + 1, :]
            # no interchange: row i+1 -= fact * row i
            new_d_next = np.where(swap, ui - fact * d_next, d_next - fact * ui)
            new_bi = np.where(swap[..., None], bn, bi)
            new_bn = np.where(swap[..., None], bi - fact[..., None] * bn, bn - fact[..., None] * bi)
            if i < n - 2:
                u_next = du[..., i + 1]
                du2[..., i] = np.where(swap, u_next, 0.0)
                du[..., i + 1] = np.where(swap, -fact * u_next, u_next)
            du[..., i] = np.where(swap, d_next, ui)
            d[..., i] = np.where(swap, li, di)
            d[..., i + 1] = new_d_next
            b[..., i, :] = new_bi
            b[..., i + 1, :] = new_bn
        x = np.empty_like(b)
        x[..., n - 1, :] = b[..., n - 1, :] / d[..., n - 1, None]
        if n >= 2:
            x[..., n - 2, :] = (b[..., n - 2, :] - du[..., n - 2, None] * x[..., n - 1, :]) / d[
                ..., n - 2, None
            ]
        for i in range(n - 3, -1, -1):
            x[..., i, :] = (
                b[..., i, :]
                - du[..., i, None] * x[..., i + 1, :]
                - du2[..., i, None] * x[..., i + 2, :]
            ) / d[..., i, None]
    return x[..., 0] if vector else x
