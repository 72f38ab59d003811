"""Batched solves of a branched (tree-shaped) torsional system by elimination from the leaves
inward (numeric core of :mod:`crankdyn.torsion.solvers`).

A branched shaft line without closed loops (a gearbox with a power take-off, a damper ring on an
inner mass, twin engines on one gearbox) has a dynamic stiffness D(omega) = K + i H - omega^2 M
+ i omega C whose off-diagonal entries join the degrees of freedom along the edges of a tree
(seed 003, the V6 paper's eqs. 2 and 6; :mod:`crankdyn.torsion.solvers`). Numbered so that
every degree of freedom comes before its parent (leaves first, a root last: the reverse of a
breadth-first order from the root), Gaussian elimination without interchanges makes no fill-in:
eliminating degree of freedom k changes only its parent p's pivot and right-hand side,

    d_p <- d_p - D_pk D_kp / d_k,    b_p <- b_p - (D_pk / d_k) b_k,

and back substitution from the root runs the tree outward, x_k = (b_k - D_kp x_p) / d_k (A.
George and J. W. H. Liu, *Computer Solution of Large Sparse Positive Definite Systems*,
Prentice-Hall 1981, ch. 6: the elimination tree of a tree-structured matrix has no fill;
the chain's Thomas algorithm is the case of a path). O(n) work and memory per frequency; all
frequencies at once, the arrays laid out with the degrees of freedom along the rows and the
frequencies along the columns, the Python loop running over the n - 1 edges only.

Small pivots. Elimination without interchanges is stable for the diagonally dominant and the
definite systems far from resonance; near an undamped resonance of a part of the tree a pivot
can become small and the multipliers D_pk / d_k large. A system whose multipliers have a real
or imaginary part above :data:`GROWTH` = 1e7 in magnitude, or are not a number, is flagged
and solved again by LU decomposition with partial pivoting (LAPACK ``zgesv`` through
:func:`numpy.linalg.solve` on the dense matrix of a small system, SuperLU on the sparse matrix
of a large one), the same rule as the chain's (:mod:`crankdyn.torsion.solvers`).
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

__all__ = ["EliminationTree", "TreeSolver", "elimination_tree"]

GROWTH = 1e7
"""A multiplier with a real or imaginary part above this in magnitude (or not a number) sends
its system to the pivoting solver (module docstring)."""

DENSE_FALLBACK = 200
"""Degrees of freedom up to which a flagged system is solved densely (above: sparse LU)."""

_FREQUENCY_BLOCK = 1 << 12
"""Frequencies per block: a block's rows stay in the processor's cache through the
elimination."""


@dataclass(frozen=True)
class EliminationTree:
    """The elimination order of a tree-shaped system (:func:`elimination_tree`).

    Parameters
    ----------
    order : numpy.ndarray
        (n,) the degrees of freedom in elimination order: every one before its parent, the
        root last (int).
    parent : numpy.ndarray
        (n - 1,) position in ``order`` of the parent of position k (always above k; int).
    edge : numpy.ndarray
        (n - 1,) index of the link that joins position k to its parent (int).
    """

    order: NDArray[np.intp]
    parent: NDArray[np.intp]
    edge: NDArray[np.intp]

    @property
    def size(self) -> int:
        """Number of degrees of freedom n."""
        return int(self.order.size)


def elimination_tree(n: int, links: NDArray[np.int_]) -> EliminationTree | None:
    """The elimination order of n degrees of freedom joined by ``links``, or None when the
    links do not make a tree (a closed loop, or parts not joined).

    The root is a degree of freedom with the most links (a junction); the order is the
    reverse of a breadth-first walk from it, so every degree of freedom comes before its parent
    (module docstring).

    Parameters
    ----------
    n : int
        Number of degrees of freedom.
    links : numpy.ndarray
        (L, 2) the degrees of freedom joined by each link, distinct pairs (int).

    Returns
    -------
    EliminationTree or None
        The order, parents and edges; None for L != n - 1 or a graph that is not connected.

    Examples
    --------
    A junction 1 with three branches 0, 2 and 3 (the root, eliminated last):

    >>> tree = elimination_tree(4, np.array([[0, 1], [1, 2], [1, 3]]))
    >>> tree.order.tolist(), tree.parent.tolist(), tree.edge.tolist()
    ([3, 2, 0, 1], [3, 3, 3], [2, 1, 0])
    >>> elimination_tree(3, np.array([[0, 1], [1, 2], [2, 0]])) is None  # a loop
    True
    """
    links = np.asarray(links, dtype=np.intp).reshape(-1, 2)
    if n < 1 or links.shape[0] != n - 1:
        return None
    neighbours: list[list[tuple[int, int]]] = [[] for _ in range(n)]
    for e, (a, b) in enumerate(links.tolist()):
        neighbours[a].append((b, e))
        neighbours[b].append((a, e))
    root = max(range(n), key=lambda i: len(neighbours[i]))
    seen = [False] * n
    seen[root] = True
    walk = [root]
    up = [-1] * n  # the link to the parent, by degree of freedom
    towards = [-1] * n  # the parent, by degree of freedom
    queue = deque([root])
    while queue:
        i = queue.popleft()
        for j, e in neighbours[i]:
            if not seen[j]:
                seen[j] = True
                towards[j] = i
                up[j] = e
                walk.append(j)
                queue.append(j)
    if len(walk) != n:
        return None
    order = walk[::-1]
    position = [0] * n
    for k, i in enumerate(order):
        position[i] = k
    parent = [position[towards[i]] for i in order[:-1]]
    edge = [up[i] for i in order[:-1]]
    return EliminationTree(
        order=np.array(order, dtype=np.intp),
        parent=np.array(parent, dtype=np.intp),
        edge=np.array(edge, dtype=np.intp),
    )


class TreeSolver:
    """D(omega) X = F of a tree-shaped system for every frequency (module docstring).

    Parameters
    ----------
    tree : EliminationTree
        The elimination order.
    inertia : numpy.ndarray
        (n,) inertia of every degree of freedom (kg m^2).
    links : numpy.ndarray
        (L, 2) the degrees of freedom joined by each link (int), L = n - 1.
    link_values : numpy.ndarray
        (3, L) stiffness (N m/rad), viscous damping (N m s/rad) and hysteretic term eta k
        (N m/rad) of every link.
    ground_values : numpy.ndarray
        (3, n) the same to ground at every degree of freedom (grounded shafts, absolute
        dampers).
    """

    def __init__(
        self,
        tree: EliminationTree,
        inertia: NDArray[np.float64],
        links: NDArray[np.int_],
        link_values: NDArray[np.float64],
        ground_values: NDArray[np.float64],
    ) -> None:
        order, edge = tree.order, tree.edge
        n = order.size
        self.tree = tree
        self.n = n
        self.parent = tree.parent.tolist()
        # the rows in elimination order: the links to the parents, the diagonals' parts
        self.off_values = np.ascontiguousarray(link_values[:, edge])  # (3, n-1)
        diag = np.zeros((3, n))
        diag += ground_values
        np.add.at(diag.T, links[:, 0], link_values.T)
        np.add.at(diag.T, links[:, 1], link_values.T)
        self.diag_values = np.ascontiguousarray(diag[:, order])  # (3, n)
        self.inertia = np.ascontiguousarray(inertia[order])
        self.hysteretic = bool(np.any(link_values[2]) or np.any(ground_values[2]))
        self.position = np.empty(n, dtype=np.intp)
        self.position[order] = np.arange(n)
        self.links = links

    def change_positions(self, ends: NDArray[np.int_]) -> NDArray[np.intp]:
        """Position (in elimination order) of the child end of every link.

        Parameters
        ----------
        ends : numpy.ndarray
            (count, 2) the degrees of freedom at the two ends of each link.

        Returns
        -------
        numpy.ndarray
            (count,) the position of each link's child end.

        Raises
        ------
        ValueError
            For a pair that is no link of the tree.
        """
        pos = self.position
        out = np.empty(len(ends), dtype=np.intp)
        for j, (a, b) in enumerate(np.asarray(ends).tolist()):
            pa, pb = int(pos[a]), int(pos[b])
            k = min(pa, pb)
            if k == max(pa, pb) or self.parent[k] != max(pa, pb):
                raise ValueError(f"degrees of freedom {a} and {b} are not joined by a link")
            out[j] = k
        return out

    def solve(
        self,
        w: NDArray[np.float64],
        rhs: np.ndarray,
        hysteretic_frequency: float | None,
        change: tuple[NDArray[np.intp], np.ndarray] | None = None,
    ) -> tuple[NDArray[np.complex128], NDArray[np.intp]]:
        """X for every frequency, eliminated from the leaves inward (module docstring).

        Parameters
        ----------
        w : numpy.ndarray
            (F,) frequencies (rad/s).
        rhs : numpy.ndarray
            (F, n, r) right-hand sides (N m), read block by block, not copied whole.
        hysteretic_frequency : float or None
            The frequency (rad/s) at which loss factors are frozen as viscous terms, or None
            for loss factors at every frequency.
        change : (numpy.ndarray, numpy.ndarray) or None
            Positions from :meth:`change_positions` and (F, c) complex stiffness (N m/rad)
            added to those links' dynamic stiffness; or None.

        Returns
        -------
        x : numpy.ndarray
            (F, n, r) the solutions (rad).
        flagged : numpy.ndarray
            The indices of the flagged systems (small pivots), whose rows the caller solves
            again with pivoting.
        """
        count = w.size
        r = rhs.shape[-1]
        n = self.n
        out = np.empty((count, n, r), dtype=complex)
        flagged: list[NDArray[np.intp]] = []
        size = min(count, _FREQUENCY_BLOCK)
        buffers = (  # allocated once, reused by every block (no fresh pages per block)
            np.empty((max(n - 1, 0), size), dtype=complex),  # off
            np.empty((n, size), dtype=complex),  # diag
            np.empty((n, r, size), dtype=complex),  # x
            np.empty((2, size), dtype=complex),  # multiplier, product
            np.empty((r, size), dtype=complex),
            np.empty((2, 2 * size)),  # the multipliers' largest and smallest parts
            np.empty(size),  # w^2
        )
        for a in range(0, count, _FREQUENCY_BLOCK):
            b = min(count, a + _FREQUENCY_BLOCK)
            part = None if change is None else (change[0], change[1][a:b])
            found = self._block(w[a:b], rhs[a:b], out[a:b], hysteretic_frequency, part, buffers)
            flagged.append(a + found)
        bad = np.concatenate(flagged) if flagged else np.zeros(0, dtype=np.intp)
        return out, bad

    def _rows(
        self,
        w: NDArray[np.float64],
        hysteretic_frequency: float | None,
        off: NDArray[np.complex128],
        diag: NDArray[np.complex128],
        w2: NDArray[np.float64],
    ) -> None:
        """(off (n-1, F), diag (n, F)) in elimination order: off = k + i (w c + eta k f) of the
        link to the parent (D_kp = -off), diag = K_kk - w^2 J_k + i (w C_kk + H_kk f), f = 1
        or w / omega_h (then w (c + eta k / omega_h): viscous), written into ``off`` and
        ``diag``; ``w2`` a buffer (F,)."""
        k, c, h = self.off_values
        kd, cd, hd = self.diag_values
        exact = hysteretic_frequency is None
        if not exact and self.hysteretic:  # eta k f = w eta k / omega_h: viscous
            c, cd = c + h / hysteretic_frequency, cd + hd / hysteretic_frequency
        off.real = k[:, None]
        np.multiply(c[:, None], w, out=off.imag)
        np.multiply(w, w, out=w2)
        np.negative(w2, out=w2)
        np.multiply(self.inertia[:, None], w2, out=diag.real)
        diag.real += kd[:, None]
        np.multiply(cd[:, None], w, out=diag.imag)
        if exact and self.hysteretic:
            off.imag += h[:, None]
            diag.imag += hd[:, None]

    def _block(
        self,
        w: NDArray[np.float64],
        rhs: np.ndarray,
        out: np.ndarray,
        hysteretic_frequency: float | None,
        change: tuple[NDArray[np.intp], np.ndarray] | None,
        buffers: tuple[np.ndarray, ...],
    ) -> NDArray[np.intp]:
        """Solve one block of frequencies into ``out`` in the ``buffers`` of :meth:`solve`; the
        indices of its flagged systems."""
        n, parent = self.n, self.parent
        count = w.size
        off, d, x = buffers[0][:, :count], buffers[1][:, :count], buffers[2][:, :, :count]
        m, tmp, w2 = buffers[3][0, :count], buffers[3][1, :count], buffers[6][:count]
        t = buffers[4][:, :count]
        high, low = buffers[5][0, : 2 * count], buffers[5][1, : 2 * count]
        self._rows(w, hysteretic_frequency, off, d, w2)
        if change is not None:  # the changed links: their off-diagonal and both diagonals
            where, delta = change
            for j, k in enumerate(where.tolist()):
                dj = delta[:, j]
                off[k] += dj
                d[k] += dj
                d[parent[k]] += dj
        order = self.tree.order.tolist()
        for k, i in enumerate(order):  # the right-hand sides in elimination order
            x[k] = rhs[:, i, :].T
        high.fill(0.0)
        low.fill(0.0)
        parts = buffers[3][0].view(float)[: 2 * count]  # the multipliers' parts
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            for k in range(n - 1):  # forward: eliminate k into its parent
                p = parent[k]
                ok = off[k]
                np.divide(ok, d[k], out=m)
                np.maximum(high, parts, out=high)
                np.minimum(low, parts, out=low)
                np.multiply(m, ok, out=tmp)
                np.subtract(d[p], tmp, out=d[p])
                np.multiply(m, x[k], out=t)
                np.add(x[p], t, out=x[p])
            np.divide(x[n - 1], d[n - 1], out=x[n - 1])
            out[:, order[n - 1], :] = x[n - 1].T
            for k in range(n - 2, -1, -1):  # back substitution, from the root outward
                np.multiply(off[k], x[parent[k]], out=t)
                xk = x[k]
                np.add(xk, t, out=xk)
                np.divide(xk, d[k], out=xk)
                out[:, order[k], :] = xk.T
        inside = (high <= GROWTH) & (low >= -GROWTH)  # False for NaN
        return np.flatnonzero(~np.all(inside.reshape(count, 2), axis=1))
