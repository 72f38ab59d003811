"""The bare-numpy limits crankdyn's solvers are measured against (issue 16).

Nothing here is crankdyn: each function is the least a solver of the problem must do, written as
plainly and as fast as numpy and LAPACK allow, without crankdyn's checks, fallbacks, result
objects or exports. A ratio to one of them says how much crankdyn's own work costs.

- :func:`thomas`: the forced response of a chain, D(omega) X = F for every frequency, by one
  in-place Thomas elimination (no pivoting, no fallback) over all frequencies at once: the
  dynamic stiffness D = K - omega^2 M + i omega C of a chain with absolute dampers and shaft
  damping, arrays (rows x frequencies), every row operation into preallocated buffers.
- :func:`tree_elimination`: the forced response of a branched line without loops, D(omega) X = F
  for every frequency, by elimination from the leaves inward (every degree of freedom before
  its parent, no fill-in) over all frequencies at once: the Thomas elimination of a tree, in
  place, no pivoting check, the order and the rows' constant parts given (made before the
  clock).
- :func:`chain_modes`: the natural frequencies and mode shapes of a chain, LAPACK ``dstevd`` on
  the mass-normalised tridiagonal matrix, the shapes scaled back and normalised to a largest
  amplitude of 1 (what a modal result needs at least).
"""

from __future__ import annotations

import numpy as np
import scipy.linalg

__all__ = ["chain_modes", "thomas", "tree_elimination"]


def thomas(inertia, stiffness, shaft_damping, ground_damping, omega, forcing) -> np.ndarray:
    """X (n, F) with D(omega) X = F for a free chain (module docstring).

    Parameters
    ----------
    inertia, ground_damping
        (n,) kg m^2 and N m s/rad.
    stiffness, shaft_damping
        (n-1,) N m/rad and N m s/rad of the shafts between neighbours.
    omega
        (F,) rad/s.
    forcing
        (n,) N m, the same at every frequency.
    """
    n = inertia.size
    w = np.asarray(omega, dtype=float)
    f = w.size
    off = np.empty((n - 1, f), dtype=complex)  # the negated off-diagonal, k + i w c
    off.real = stiffness[:, None]
    np.multiply(shaft_damping[:, None], w, out=off.imag)
    d = np.empty((n, f), dtype=complex)
    np.multiply(-inertia[:, None], w * w, out=d.real)
    np.multiply(ground_damping[:, None], w, out=d.imag)
    d[:-1] += off
    d[1:] += off
    x = np.empty((n, f), dtype=complex)
    x[...] = forcing[:, None]
    m = np.empty(f, dtype=complex)
    t = np.empty(f, dtype=complex)
    for i in range(1, n):
        np.divide(off[i - 1], d[i - 1], out=m)
        np.multiply(m, off[i - 1], out=t)
        np.subtract(d[i], t, out=d[i])
        np.multiply(m, x[i - 1], out=t)
        np.add(x[i], t, out=x[i])
    np.divide(x[n - 1], d[n - 1], out=x[n - 1])
    for i in range(n - 2, -1, -1):
        np.multiply(off[i], x[i + 1], out=t)
        np.add(x[i], t, out=x[i])
        np.divide(x[i], d[i], out=x[i])
    return x


def tree_elimination(parent, inertia, up, diagonal, omega, forcing) -> np.ndarray:
    """X (n, F) with D(omega) X = F for a tree in elimination order (module docstring).

    Parameters
    ----------
    parent
        (n-1,) position of the parent of position k (above k); the root is position n-1.
    inertia
        (n,) kg m^2.
    up
        (3, n-1) stiffness, viscous damping and eta k of the link from k to its parent.
    diagonal
        (3, n) the same summed over the links of each degree of freedom and to ground.
    omega
        (F,) rad/s.
    forcing
        (n,) N m, the same at every frequency.
    """
    n = inertia.size
    w = np.asarray(omega, dtype=float)
    f = w.size
    off = np.empty((n - 1, f), dtype=complex)  # the negated off-diagonal, k + i (w c + eta k)
    off.real = up[0][:, None]
    np.multiply(up[1][:, None], w, out=off.imag)
    off.imag += up[2][:, None]
    d = np.empty((n, f), dtype=complex)
    np.multiply(-inertia[:, None], w * w, out=d.real)
    d.real += diagonal[0][:, None]
    np.multiply(diagonal[1][:, None], w, out=d.imag)
    d.imag += diagonal[2][:, None]
    x = np.empty((n, f), dtype=complex)
    x[...] = forcing[:, None]
    m = np.empty(f, dtype=complex)
    t = np.empty(f, dtype=complex)
    for k in range(n - 1):
        p = parent[k]
        np.divide(off[k], d[k], out=m)
        np.multiply(m, off[k], out=t)
        np.subtract(d[p], t, out=d[p])
        np.multiply(m, x[k], out=t)
        np.add(x[p], t, out=x[p])
    np.divide(x[n - 1], d[n - 1], out=x[n - 1])
    for k in range(n - 2, -1, -1):
        np.multiply(off[k], x[parent[k]], out=t)
        np.add(x[k], t, out=x[k])
        np.divide(x[k], d[k], out=x[k])
    return x


def chain_modes(inertia, stiffness) -> tuple[np.ndarray, np.ndarray]:
    """(omega^2 (n,), shapes (n, n), columns normalised to a largest amplitude of 1) of a free
    chain (module docstring)."""
    s = np.sqrt(inertia)
    diag = np.zeros(inertia.size)
    diag[:-1] += stiffness
    diag[1:] += stiffness
    (stevd,) = scipy.linalg.get_lapack_funcs(("stevd",), (diag, stiffness))
    lam, u, _info = stevd(diag / inertia, -stiffness / (s[:-1] * s[1:]), compute_v=1)
    u /= s[:, None]
    u /= np.max(np.abs(u), axis=0)
    return lam, u
