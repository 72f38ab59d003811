"""The linear system of a torsional model with its dampers, and its batched harmonic solves
(numeric core).

Equations of motion (seed 003, the V6 paper's eq. 1; Ker Wilson vol. 2):

    M theta'' + C theta' + K theta + (hysteretic) = T(t),

with M the inertias, K the shaft stiffnesses, C the absolute dampers (to ground) and the shafts'
relative viscous damping, and the hysteretic (loss-factor) damping of the shafts, a torque
eta k times the twist in phase with the twist rate. For one order q at crankshaft speed Omega the
excitation is harmonic at omega = q Omega, T(t) = Re(F exp(i omega t)), and so is the steady
response theta(t) = Re(X exp(i omega t)) with the dynamic-stiffness equation (the V6 paper's
eqs. 2 and 6, {T}_n = [K(n omega)] {theta}_n)

    D(omega) X = F,    D(omega) = K + i H - omega^2 M + i omega C,    H = sum_s eta_s K_s

(hysteretic damping is exact in the frequency domain: eta k = omega c_eq with c_eq = eta k/omega;
Mendes et al. 2008 use c = 0.035 k/omega). A single damped mass gives seed 003's formulas: with
2n = c/J, p^2 = k/J, h = T/J, the amplitude B = h / sqrt((p^2 - omega^2)^2 + 4 n^2 omega^2) and
the lag psi = arctan(2 n omega / (p^2 - omega^2)) (seed 003, "单质量有阻尼强迫扭转振动").

Dampers (:mod:`crankdyn.torsion.dampers`) add a ring degree of freedom joined to its hub by the
complex stiffness k_d + i (omega c_d + eta_d k_d); a damper at an end of a chain keeps the chain
(:func:`linear_system`).

Solving it fast. For a chain (the usual crank train) D is symmetric tridiagonal; all speeds x
orders are solved at once with the chain along the rows of the arrays: elimination without
interchanges (the Thomas algorithm), and for the rare frequencies with a multiplier above 1e8 (a
small pivot) elimination with partial pivoting (LAPACK's ``gtsv`` algorithm,
:func:`~crankdyn.torsion.tridiagonal.solve_tridiagonal`), both vectorised over every frequency
and right-hand side, the Python loop running over the chain's length only. The frequencies go in
blocks whose buffers are allocated once; each row of the dynamic stiffness is built when the
elimination reaches it, the small-pivot test is made exactly only on the systems a cheap filter
inside the loop picks (the same systems flagged as by the test on all of them) and the solved
rows go to the result in tiles while in cache (:class:`_ChainBlocks`). A branched model
without closed loops (a gearbox with a power take-off, a damper ring on an inner mass) is a tree
and is solved the same way, by elimination from the leaves inward, batched over the frequencies
(:mod:`crankdyn.torsion.tree`: no fill-in, O(n) per frequency, small pivots re-solved with
partial pivoting). Only a system with loops (a closed gear train) or with modal damping, which
couples every mass, takes the general dense solve (LU with partial pivoting, LAPACK ``zgesv``),
a block of frequencies at a time. The system is held in sparse form (links and terms to
ground); the dense K, C and H are assembled only when asked for. No loop over speeds or
orders.

A change of the stiffness at each speed (the load-dependent couplings,
:func:`crankdyn.torsion.loaded.load_change`) is added to D before the same batched solves
(:meth:`LinearSystem.solve_with_change`). The forced response over a speed range
(:mod:`crankdyn.torsion.sweep`) calls these solvers; the result is
:class:`crankdyn.torsion.response.ResponseResult`.
"""

from __future__ import annotations

import contextlib
import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import Any, cast

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.errors import InputError
from crankdyn.torsion.dampers import Damper
from crankdyn.torsion.model import TorsionModel
from crankdyn.torsion.tree import DENSE_FALLBACK, EliminationTree, TreeSolver, elimination_tree
from crankdyn.torsion.tridiagonal import solve_tridiagonal

__all__ = [
    "LinearSystem",
    "change_matrix",
    "linear_system",
    "steady_state",
]

_FREQUENCY_BLOCK = 1 << 13
"""Frequencies per block of the chain solve: a block's rows (16 bytes x block each) stay in the
processor's cache through the elimination."""

_BLOCK_ELEMENTS = 1 << 23
"""At most this many elements (128 MB of complex numbers) per buffer of the chain solve, down
to :data:`_MIN_BLOCK` frequencies: a long chain's blocks hold fewer frequencies, and its
buffers, reused by every block, stay a fraction of the result's size."""

_MIN_BLOCK = 512
"""The fewest frequencies per block of the chain solve (fewer: a numpy call's fixed cost would
outweigh its work)."""


def _abs2(z: NDArray[np.complex128]) -> NDArray[np.float64]:
    """|z|^2 of a complex array."""
    out = np.multiply(z.real, z.real)
    out += z.imag * z.imag
    return out


# ---- the linear system of a model with dampers ------------------------------------------------
@dataclass(frozen=True, eq=False)
class LinearSystem:
    """The reflected equations of motion of a model with its dampers, ready for harmonic solves.

    Held in sparse form, O(n) for a chain or a tree: the inertias, the links between degrees
    of freedom (shafts and damper couplings, parallel ones added together) with their
    stiffness, damping and hysteretic terms, and the same to ground; the dense matrices
    K, C and H are assembled only when asked for (:attr:`stiffness`, :attr:`damping`,
    :attr:`hysteretic`: the time-domain solvers and the small systems' eigenproblems).
    ``chain`` holds the tridiagonal arrays in chain order, ``tree`` the elimination order of a
    branched system without loops (:mod:`crankdyn.torsion.tree`); a system with loops (closed
    gear trains) or modal damping has neither and is solved by the general dense solver.
    Degrees of freedom: the model's, with each damper ring added. Everything is reflected to the
    reference (crankshaft) speed: inertias and stiffnesses times the squared speed ratio
    (:mod:`crankdyn.torsion.model`). Built by :func:`linear_system`.

    Parameters
    ----------
    inertia : numpy.ndarray
        (n,) inertia of every degree of freedom (kg m^2).
    links : numpy.ndarray
        (L, 2) the two degrees of freedom of every link, distinct pairs (int).
    link_values : numpy.ndarray
        (3, L) every link's stiffness (N m/rad), viscous damping (N m s/rad) and hysteretic
        term eta k (N m/rad).
    ground_values : numpy.ndarray
        (3, n) the same to ground at every degree of freedom: grounded shafts, and the
        absolute dampers in the viscous row.
    modal_damping : numpy.ndarray or None
        (n, n) the modal damping matrix C_modal added to C (N m s/rad), or None.
    chain : tuple of numpy.ndarray or None
        (k_between, c_between, h_between, k_g, c_g, h_g) in dof order: the (n-1,) couplings
        between neighbours and the (n,) terms to ground (N m/rad, N m s/rad, N m/rad); None
        for a branched system.
    tree : EliminationTree or None
        The elimination order of a branched system without loops (no modal damping); None
        otherwise.
    mass_dof : numpy.ndarray
        (N,) dof of every listed mass (the model's masses, then the damper rings), int.
    mass_ratio : numpy.ndarray
        (N,) signed speed ratio of every listed mass (dimensionless).
    mass_names : tuple of str
        The listed masses' names.
    element_dofs : numpy.ndarray
        (E, 2) dofs of every element's ends (shafts, then damper couplings), -1 = ground.
    element_stiffness : numpy.ndarray
        (E,) reflected stiffness of every element (N m/rad).
    element_ratio : numpy.ndarray
        (E,) speed ratio of every element's masses (dimensionless).
    element_labels : tuple of (str, str)
        Every element's ends by name.
    dampers : tuple of Damper
        The dampers whose rings were added.

    Examples
    --------
    >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
    >>> from crankdyn.torsion.dampers import Damper
    >>> model = TorsionModel(masses=(Mass("m", 1.0),), shafts=(Shaft(("ground", "m"), 1e6),))
    >>> system = linear_system(model, [Damper("ring", "m", 0.1, damping=30.0)])
    >>> system.size, system.mass_names, system.element_labels
    (2, ('m', 'ring'), (('ground', 'm'), ('m', 'ring')))
    """

    inertia: np.ndarray  # (n,) kg m^2
    links: np.ndarray  # (L, 2) dof pairs
    link_values: np.ndarray  # (3, L) k, c, eta k
    ground_values: np.ndarray  # (3, n) k, c, eta k to ground
    modal_damping: np.ndarray | None  # (n, n) C_modal
    chain: tuple[np.ndarray, ...] | None  # (k_between, c_between, h_between, k_g, c_g, h_g)
    tree: EliminationTree | None
    mass_dof: np.ndarray  # dof of every listed mass (model masses, then damper rings)
    mass_ratio: np.ndarray  # speed ratio of every listed mass
    mass_names: tuple[str, ...]
    element_dofs: np.ndarray  # (elements, 2): shafts then damper couplings, -1 = ground
    element_stiffness: np.ndarray  # reflected k of every element
    element_ratio: np.ndarray  # speed ratio of every element's masses
    element_labels: tuple[tuple[str, str], ...]
    dampers: tuple[Damper, ...]

    @property
    def size(self) -> int:
        """Number of degrees of freedom n (the model's and the damper rings)."""
        return int(self.inertia.size)

    def _dense(self, row: int) -> NDArray[np.float64]:
        """The (n, n) matrix of row ``row`` of the link and ground values (0: K, 1: C, 2: H),
        each link v [[1, -1], [-1, 1]] at its two degrees of freedom."""
        n = self.size
        out = np.zeros((n, n))
        out[np.diag_indices(n)] = self.ground_values[row]
        if self.links.size:
            a, b = self.links[:, 0], self.links[:, 1]
            v = self.link_values[row]
            np.add.at(out, (a, a), v)
            np.add.at(out, (b, b), v)
            np.add.at(out, (a, b), -v)
            np.add.at(out, (b, a), -v)
        return out

    @cached_property
    def stiffness(self) -> NDArray[np.float64]:
        """The dense stiffness matrix K (N m/rad), (n, n), assembled when first asked for."""
        return self._dense(0)

    @cached_property
    def damping(self) -> NDArray[np.float64]:
        """The dense viscous damping matrix C (N m s/rad), (n, n), with the modal damping,
        assembled when first asked for."""
        out = self._dense(1)
        if self.modal_damping is not None:
            out += self.modal_damping
        return out

    @cached_property
    def hysteretic(self) -> NDArray[np.float64]:
        """The dense hysteretic matrix H = sum eta_s K_s (N m/rad), (n, n), assembled when
        first asked for."""
        return self._dense(2)

    def _chain(self) -> tuple[np.ndarray, ...]:
        """The chain arrays; a branched system has none (ValueError)."""
        if self.chain is None:
            raise ValueError("a branched system has no tridiagonal form: use matrix()")
        return self.chain

    def diagonals(
        self, omega: ArrayLike, hysteretic_frequency: float | None = None
    ) -> tuple[
        NDArray[np.complexfloating], NDArray[np.complexfloating], NDArray[np.complexfloating]
    ]:
        """The three diagonals of the dynamic stiffness D(omega) of a chain.

        D(omega) = K + i H - omega^2 M + i omega C (seed 003, the V6 paper's eqs. 2 and 6;
        module docstring), symmetric tridiagonal for a chain.

        Parameters
        ----------
        omega : float or array_like
            Circular frequencies (rad/s).
        hysteretic_frequency : float or None
            None: loss factors as exact hysteretic damping; omega_h (rad/s): as viscous
            damping eta k / omega_h.

        Returns
        -------
        lower, diag, upper : numpy.ndarray
            Complex (N m/rad), of shapes omega.shape + (n-1,), + (n,), + (n-1,).

        Raises
        ------
        ValueError
            For a branched system (``chain`` None).

        Examples
        --------
        >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
        >>> model = TorsionModel(
        ...     masses=(Mass("a", 1.0), Mass("b", 2.0)),
        ...     shafts=(Shaft(("ground", "a"), 3e4), Shaft(("a", "b"), 1e4)),
        ... )
        >>> lower, diag, upper = linear_system(model).diagonals(100.0)  # k - omega^2 J
        >>> diag.real.tolist(), upper.real.tolist()
        ([30000.0, -10000.0], [-10000.0])
        """
        kb, cb, hb, kg, cg, hg = self._chain()
        w = np.asarray(omega, dtype=float)[..., None]
        hb_, hg_ = _hyst(hb, w, hysteretic_frequency), _hyst(hg, w, hysteretic_frequency)
        link = kb + 1j * (w * cb + hb_)
        diag = kg - w**2 * self.inertia + 1j * (w * cg + hg_)
        diag = diag + np.concatenate([link, np.zeros((*link.shape[:-1], 1))], axis=-1)
        diag = diag + np.concatenate([np.zeros((*link.shape[:-1], 1)), link], axis=-1)
        return -link, diag, -link

    def matrix(
        self, omega: ArrayLike, hysteretic_frequency: float | None = None
    ) -> NDArray[np.complexfloating]:
        """The dense dynamic stiffness D(omega) = K + i H - omega^2 M + i omega C.

        Seed 003 (the V6 paper's eqs. 2 and 6; module docstring).

        Parameters
        ----------
        omega : float or array_like
            Circular frequencies (rad/s).
        hysteretic_frequency : float or None
            None: loss factors as exact hysteretic damping; omega_h (rad/s): as viscous
            damping eta k / omega_h.

        Returns
        -------
        numpy.ndarray
            Complex D (N m/rad), shape omega.shape + (n, n).

        Examples
        --------
        >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
        >>> model = TorsionModel(
        ...     masses=(Mass("m", 1.0, damping=20.0),), shafts=(Shaft(("ground", "m"), 1e6),)
        ... )
        >>> complex(linear_system(model).matrix(900.0)[0, 0])  # k - omega^2 J + i omega c
        (190000+18000j)
        """
        w = np.asarray(omega, dtype=float)[..., None, None]
        h = _hyst(self.hysteretic, w, hysteretic_frequency)
        return self.stiffness - w**2 * np.diag(self.inertia) + 1j * (w * self.damping + h)

    def solve(
        self, omega: ArrayLike, forcing: ArrayLike, hysteretic_frequency: float | None = None
    ) -> NDArray[np.complexfloating]:
        """The steady-state amplitudes X with D(omega) X = F for every frequency.

        A chain by elimination (the Thomas algorithm, pivoting where a pivot is small:
        :func:`solve_tridiagonal`), a branched system by numpy's batched dense solve (module
        docstring).

        Parameters
        ----------
        omega : float or array_like
            Circular frequencies (rad/s), shape (...).
        forcing : array_like
            Harmonic torque amplitudes F on the degrees of freedom (N m, complex), shape
            (..., n) or (..., n, r) for r right-hand sides.
        hysteretic_frequency : float or None
            None: loss factors as exact hysteretic damping; omega_h (rad/s): as viscous
            damping eta k / omega_h.

        Returns
        -------
        numpy.ndarray
            Complex reflected angles of the degrees of freedom (rad), the shape of
            ``forcing``; NaN for an undamped branched system exactly at a resonance.

        Examples
        --------
        One damped mass: X = T / (k - omega^2 J + i omega c) (seed 003, the single damped
        mass).

        >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
        >>> model = TorsionModel(
        ...     masses=(Mass("m", 1.0, damping=20.0),), shafts=(Shaft(("ground", "m"), 1e6),)
        ... )
        >>> x = linear_system(model).solve(900.0, [100.0])
        >>> round(abs(complex(x[0]) * (190000 + 18000j)), 9)
        100.0
        """
        omega = np.asarray(omega, dtype=float)
        if self.chain is not None:  # the forcing read block by block, as it is (no copy)
            return self._solve_chain(omega, np.asarray(forcing), hysteretic_frequency)
        return self._solve_branched(omega, np.asarray(forcing), hysteretic_frequency)

    def _solve_branched(
        self,
        omega: NDArray[np.float64],
        f: np.ndarray,
        hysteretic_frequency: float | None,
        change: tuple[NDArray[np.int_], np.ndarray] | None = None,
    ) -> NDArray[np.complexfloating]:
        """:meth:`solve` (and :meth:`solve_with_change`: ``change`` the (count, 2) ends and
        the (..., count) changes) of a branched system: a tree by elimination from the leaves
        inward (:class:`~crankdyn.torsion.tree.TreeSolver`), any other by the dense solve, a
        block of frequencies at a time (never a (frequencies, n, n) array of them all)."""
        n = self.size
        vector = f.ndim == omega.ndim + 1
        fb = f[..., None] if vector else f
        r = fb.shape[-1]
        batch = np.broadcast_shapes(omega.shape, fb.shape[:-2])
        if change is not None:
            batch = np.broadcast_shapes(batch, np.shape(change[1])[:-1])
        w = np.broadcast_to(omega, batch).reshape(-1)
        rhs = np.broadcast_to(fb, (*batch, n, r)).reshape(-1, n, r)
        delta = None
        if change is not None:
            values = np.asarray(change[1])
            delta = np.broadcast_to(values, (*batch, values.shape[-1])).reshape(w.size, -1)
        if self.tree is not None:
            solver = self._tree_solver
            where = None if change is None else solver.change_positions(change[0])
            x, bad = solver.solve(
                w,
                rhs,
                hysteretic_frequency,
                None if where is None or delta is None else (where, delta),
            )
            if bad.size:  # rare: a part of the tree at its resonance
                ends = None if change is None else np.asarray(change[0])
                some = None if delta is None else delta[bad]
                x[bad] = self._pivoting(w[bad], rhs[bad], hysteretic_frequency, ends, some)
        else:
            ends = None if change is None else np.asarray(change[0])
            x = self._pivoting(w, rhs, hysteretic_frequency, ends, delta)
        x = x.reshape(*batch, n, r)
        return x[..., 0] if vector else x

    @cached_property
    def _tree_solver(self) -> TreeSolver:
        """The tree's batched solver (:mod:`crankdyn.torsion.tree`), made once."""
        assert self.tree is not None  # called for a tree only
        return TreeSolver(self.tree, self.inertia, self.links, self.link_values, self.ground_values)

    def _pivoting(
        self,
        w: NDArray[np.float64],
        rhs: np.ndarray,
        hysteretic_frequency: float | None,
        ends: NDArray[np.int_] | None = None,
        delta: np.ndarray | None = None,
    ) -> NDArray[np.complex128]:
        """LU decomposition with partial pivoting for frequencies w (F,) rad/s, rhs (F, n, r)
        N m, the changes ``delta`` (F, count) N m/rad of the links ``ends`` added: the dense
        matrices a block of frequencies at a time (LAPACK ``zgesv``), or, for a large tree
        (above :data:`~crankdyn.torsion.tree.DENSE_FALLBACK` degrees of freedom: its few
        flagged systems), the sparse matrix of each (SuperLU). NaN for a singular system (an
        undamped system exactly at a resonance)."""
        n = self.size
        out = np.empty(rhs.shape, dtype=complex)
        if self.tree is not None and n > DENSE_FALLBACK and self.modal_damping is None:
            for i in range(w.size):  # the few flagged systems of a large tree
                one = None if delta is None else delta[i]
                out[i] = self._sparse_solve(float(w[i]), rhs[i], hysteretic_frequency, ends, one)
            return out
        step = max(1, min(_FREQUENCY_BLOCK, (1 << 22) // max(n * n, 1)))
        for a in range(0, w.size, step):
            b = min(w.size, a + step)
            matrix = self.matrix(w[a:b], hysteretic_frequency)
            if ends is not None and delta is not None:
                matrix = matrix + change_matrix(ends, delta[a:b], n)
            out[a:b] = _dense_solve(matrix, rhs[a:b])
        return out

    def _sparse_solve(
        self,
        w: float,
        rhs: np.ndarray,
        hysteretic_frequency: float | None,
        ends: NDArray[np.int_] | None,
        delta: np.ndarray | None,
    ) -> NDArray[np.complex128]:
        """D(w) X = rhs (n, r) by sparse LU with partial pivoting (SuperLU), the changes of the
        links ``ends`` added; NaN when D is singular."""
        import scipy.sparse
        import scipy.sparse.linalg

        n = self.size
        f = 1.0 if hysteretic_frequency is None else w / hysteretic_frequency
        k, c, h = self.link_values
        kg, cg, hg = self.ground_values
        link = k + 1j * (w * c + h * f)
        a, b = self.links[:, 0], self.links[:, 1]
        rows = [np.arange(n), a, b, a, b]
        cols = [np.arange(n), a, b, b, a]
        vals = [kg - w * w * self.inertia + 1j * (w * cg + hg * f), link, link, -link, -link]
        if ends is not None and delta is not None:
            e = np.asarray(ends)
            rows += [e[:, 0], e[:, 1], e[:, 0], e[:, 1]]
            cols += [e[:, 0], e[:, 1], e[:, 1], e[:, 0]]
            vals += [delta, delta, -delta, -delta]
        matrix = scipy.sparse.csc_matrix(
            (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n)
        )
        try:
            lu = scipy.sparse.linalg.splu(matrix, permc_spec="NATURAL", diag_pivot_thresh=1.0)
        except RuntimeError:  # exactly singular
            return np.full(rhs.shape, np.nan + 0j)
        return np.asarray(lu.solve(np.asarray(rhs, dtype=complex)), dtype=complex)

    def solve_with_change(
        self,
        omega: ArrayLike,
        forcing: ArrayLike,
        ends: NDArray[np.int_],
        change: ArrayLike,
        hysteretic_frequency: float | None = None,
    ) -> NDArray[np.complexfloating]:
        """The amplitudes X with (D(omega) + Delta D) X = F, Delta D a change of the dynamic
        stiffness of some elements at every frequency (the load-dependent couplings at each
        speed's mean torque, :func:`crankdyn.torsion.loaded.load_change`).

        Each element is a spring between its two ends, assembled like a shaft
        (:func:`change_matrix`); a chain keeps its tridiagonal form (the elements are its
        links) and is solved with partial pivoting
        (:func:`~crankdyn.torsion.tridiagonal.solve_tridiagonal`), a tree keeps its tree (the
        elements are its links: elimination from the leaves inward,
        :mod:`crankdyn.torsion.tree`), any other system is solved densely (module
        docstring).

        Parameters
        ----------
        omega : array_like
            Circular frequencies (rad/s), shape (S, Q).
        forcing : array_like
            Harmonic torque amplitudes F on the degrees of freedom (N m, complex), shape
            (S, Q, n).
        ends : numpy.ndarray
            Degrees of freedom (a, b) at the ends of every changed element, shape (count, 2),
            int.
        change : array_like
            Complex change of every element's dynamic stiffness (N m/rad), shape
            (S, Q, count).
        hysteretic_frequency : float or None
            None: loss factors as exact hysteretic damping; omega_h (rad/s): as viscous
            damping eta k / omega_h.

        Returns
        -------
        numpy.ndarray
            Complex reflected angles of the degrees of freedom (rad), shape (S, Q, n).

        Examples
        --------
        A change of the only shaft's stiffness is the model with the changed stiffness:

        >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
        >>> def model(k):
        ...     masses = (Mass("a", 1.0, damping=20.0), Mass("b", 2.0))
        ...     return TorsionModel(masses=masses, shafts=(Shaft(("a", "b"), k),))
        >>> w, f = np.array([[300.0]]), np.array([[[100.0, 0.0]]])
        >>> x = linear_system(model(1e5)).solve_with_change(w, f, np.array([[0, 1]]), [[[5e4]]])
        >>> bool(np.allclose(x, linear_system(model(1.5e5)).solve(w, f), rtol=1e-12, atol=0))
        True
        """
        w = np.asarray(omega, dtype=float)
        change = np.asarray(change)
        f = np.asarray(forcing, dtype=complex)
        if self.chain is not None:
            lower, diag, upper = self.diagonals(w, hysteretic_frequency)
            lower, diag, upper = lower.copy(), diag.copy(), upper.copy()
            for j, (a, b) in enumerate(ends):  # the elements (a few): the chain's links
                lo = min(a, b)
                diag[..., a] += change[..., j]
                diag[..., b] += change[..., j]
                lower[..., lo] -= change[..., j]
                upper[..., lo] -= change[..., j]
            x = solve_tridiagonal(lower, diag, upper, f)
        else:
            x = self._solve_branched(w, f, hysteretic_frequency, (np.asarray(ends), change))
        return cast("NDArray[np.complexfloating]", x)

    def _solve_chain(
        self, omega: NDArray[np.float64], f: np.ndarray, hysteretic_frequency: float | None
    ) -> NDArray[np.complexfloating]:
        """The chain's symmetric tridiagonal systems for all frequencies, in blocks of about
        :data:`_FREQUENCY_BLOCK` frequencies laid out with the chain along the first axis
        (contiguous rows of one block's frequencies): elimination without interchanges (the
        Thomas algorithm, :class:`_ChainBlocks`), every row operation into buffers allocated
        once and reused by every block, then the pivoting solver for the few systems whose
        pivots came out small relative to their rows (where elimination without interchanges
        can lose accuracy), their rows recomputed. The forcing is read block by block (never
        expanded); memory: the result and one block's buffers."""
        n = self.size
        scalar_omega = omega.ndim == 0
        vector = f.ndim == omega.ndim + 1
        omega = np.atleast_1d(omega)
        batch = omega.shape
        fb = f[..., None] if vector else f
        r = fb.shape[-1]
        fb = np.broadcast_to(fb, (*batch, n, r))
        out = np.empty((*batch, n, r), dtype=complex)
        inner = math.prod(batch[1:])
        per_block = max(_MIN_BLOCK, min(_FREQUENCY_BLOCK, _BLOCK_ELEMENTS // max(n * r, 1)))
        rows = max(1, per_block // max(inner, 1))
        rows = -(-batch[0] // -(-batch[0] // rows))  # blocks of even size
        flat_omega = omega.reshape(-1)
        flat_out = out.reshape(-1, n, r)
        blocks = _ChainBlocks(self, min(batch[0], rows) * inner, r, hysteretic_frequency)
        for s0 in range(0, batch[0], rows):
            s1 = min(batch[0], s0 + rows)
            a, b = s0 * inner, s1 * inner
            blocks.solve(flat_omega[a:b], fb[s0:s1].reshape(b - a, n, r), flat_out[a:b])
        if scalar_omega:
            out = out[0]
        return out[..., 0] if vector else out

    def _diagonals_of(
        self, w: NDArray[np.float64], hysteretic_frequency: float | None
    ) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
        """(off, diag) of D(w) in chain order for frequencies w (1-D): off (n-1, F) the negated
        off-diagonal, diag (n, F) (the pivoting fallback's systems)."""
        kb, cb, hb, kg, cg, hg = self._chain()
        factor = 1.0 if hysteretic_frequency is None else w / hysteretic_frequency
        off = np.empty((kb.size, w.size), dtype=complex)
        off.real = kb[:, None]
        off.imag = w * cb[:, None] + hb[:, None] * factor
        diag = np.empty((self.size, w.size), dtype=complex)
        diag.real = kg[:, None] - (w * w) * self.inertia[:, None]
        diag.imag = w * cg[:, None] + hg[:, None] * factor
        diag[:-1] += off
        diag[1:] += off
        return off, diag


_GROWTH = 1e8
"""The largest multiplier |off / pivot| of elimination without interchanges; a system with a
larger one (a small pivot) is solved again with partial pivoting."""

_CANDIDATE = 1e7
"""A multiplier with a real or imaginary part above this in magnitude makes its system a
candidate for the exact growth test (:class:`_ChainBlocks`)."""

_TINY, _HUGE = 1e-140, 1e140
"""The range of |off| in which the candidate filter's argument holds (:class:`_ChainBlocks`)."""

_CHUNK_ELEMENTS = 1 << 13
"""Rows of the chain solve built at a time: about this many elements (128 KB of complex numbers)
of each of ``off``, ``diag`` and ``x``, still in cache when the elimination reaches them; one
row at a time for a block of 8192 frequencies, several for a long chain's small blocks (fewer
numpy calls per row)."""

_TILE = 8
"""Chain rows copied to the result at a time (a cache-friendly transposition)."""


class _ChainBlocks:
    """The chain solve of :meth:`LinearSystem._solve_chain` for one block of frequencies at a
    time, its buffers allocated once (module docstring, "Solving it fast").

    Elimination without interchanges (the Thomas algorithm) with the chain along the rows:
    the negated off-diagonal ``off`` and the diagonal of every row are built inside the forward
    loop, a few rows (:data:`_CHUNK_ELEMENTS`) just before the elimination reaches them
    (:meth:`_rows`: the same operations in the same order as
    :meth:`LinearSystem._diagonals_of`, so the same numbers), the right-hand side copied in at
    the same time; the back substitution divides by the stored pivots and copies the solved
    rows to the result :data:`_TILE` rows at a time while they are in cache.

    Small pivots. A system is solved again with partial pivoting (:func:`solve_tridiagonal`)
    when, for some row, not ``|off|^2 <= 1e16 |pivot|^2`` (a multiplier above
    :data:`_GROWTH` = 1e8, or not a number). That test is exact but costs a pass over every
    row; it is made only on *candidates*: the systems with a computed multiplier
    m = off / pivot whose real or imaginary part exceeds :data:`_CANDIDATE` = 1e7 in magnitude
    or is not a number (tracked inside the forward loop by a running maximum and minimum of
    the multipliers, which the loop computes anyway), and for every system on the rows whose
    |off| may leave [1e-140, 1e140] (no stiffness, or huge values). The flagged systems are
    exactly those of the test on every system: a system that is not a candidate has, on each
    remaining row, |m| <= sqrt(2) 1e7; numpy divides complex numbers by Smith's method,
    whose computed quotient has |m| >= |off| / (sqrt(2) |pivot|) (1 - 16 eps) (the
    numerator's norm is at least |off|, the denominator at most |pivot_r| + |pivot_i|), so
    |off| <= 2.01e7 |pivot|, far from the 1e8 bound; with |off| in [1e-140, 1e140], |off|^2
    and |pivot|^2 >= 2e-295 are normal numbers computed to a few rounding errors, so the test
    holds. A multiplier that overflows or is not a number makes a candidate.
    """

    def __init__(
        self, system: LinearSystem, block: int, r: int, hysteretic_frequency: float | None
    ) -> None:
        n = system.size
        kb, cb, hb, kg, cg, hg = system._chain()
        self.system = system
        self.n = n
        self.hysteretic_frequency = hysteretic_frequency
        self.arrays = (kb, cb, hb, kg, cg, hg, system.inertia)
        # rows built at a time (_CHUNK_ELEMENTS), in cache when the elimination reaches them
        self.chunk = max(1, min(64, _CHUNK_ELEMENTS // max(block * r, 1)))
        self.magnitudes = (np.abs(kb), np.abs(cb), np.abs(hb))  # |off| >= |kb| (class docstring)
        # the loss factors' terms: hb * factor, added unless they are zero (factor 1.0)
        self.hysteretic = hysteretic_frequency is not None or bool(np.any(hb) or np.any(hg))
        self.off = np.empty((max(n - 1, 0), block), dtype=complex)
        self.diag = np.empty((n, block), dtype=complex)
        self.x = np.empty((n, r, block), dtype=complex)
        self.mult = np.empty(block, dtype=complex)
        self.tmp = np.empty(block, dtype=complex)
        self.tmp_b = np.empty((r, block), dtype=complex)
        self.w2 = np.empty(block)
        self.factor = np.empty(block)
        self.term = np.empty((self.chunk, block))
        self.high = np.empty(2 * block)
        self.low = np.empty(2 * block)

    def solve(self, w: NDArray[np.float64], rhs: np.ndarray, out: np.ndarray) -> None:
        """Solve one block into ``out``: w (F,) rad/s, rhs (F, n, r) N m, out (F, n, r)."""
        n = self.n
        count = w.size
        off, d = self.off[:, :count], self.diag[:, :count]
        x = self.x[:, :, :count]
        mult, tmp, tmp_b = self.mult[:count], self.tmp[:count], self.tmp_b[:, :count]
        w2, factor = self.w2[:count], self.factor[:count]
        high, low = self.high[: 2 * count], self.low[: 2 * count]
        np.multiply(w, w, out=w2)
        if self.hysteretic:
            if self.hysteretic_frequency is None:
                factor.fill(1.0)
            else:
                np.divide(w, self.hysteretic_frequency, out=factor)
        high.fill(0.0)
        low.fill(0.0)
        parts = mult.view(float)  # the multipliers' real and imaginary parts
        chunk = self.chunk
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            for i in range(n):  # forward elimination: D[i, i-1] = D[i-1, i] = -off[i-1]
                if i % chunk == 0:  # the next rows, built while the elimination reaches them
                    self._rows(i, min(n, i + chunk), w, w2, factor, rhs, count)
                if i == 0:
                    continue
                prev, di = off[i - 1], d[i]
                np.divide(prev, d[i - 1], out=mult)
                np.maximum(high, parts, out=high)
                np.minimum(low, parts, out=low)
                np.multiply(mult, prev, out=tmp)
                np.subtract(di, tmp, out=di)
                np.multiply(mult, x[i - 1], out=tmp_b)
                np.add(x[i], tmp_b, out=x[i])
            flagged = self._flagged(w, off, d, high, low) if n > 1 else np.empty(0, dtype=int)
            np.divide(x[n - 1], d[n - 1], out=x[n - 1])
            top = n
            for i in range(n - 2, -1, -1):  # back substitution, in place: x becomes X
                np.multiply(off[i], x[i + 1], out=tmp_b)
                np.add(x[i], tmp_b, out=x[i])
                np.divide(x[i], d[i], out=x[i])
                if i % _TILE == 0:  # rows i..top-1 solved, still in cache
                    out[:, i:top] = x[i:top].transpose(2, 0, 1)
                    top = i
            if top > 0:  # n == 1
                out[:, :top] = x[:top].transpose(2, 0, 1)
        if flagged.size:  # rare: part of the chain at its resonance
            off_k, diag_k = self.system._diagonals_of(w[flagged], self.hysteretic_frequency)
            lower = -off_k.T
            out[flagged] = solve_tridiagonal(lower, diag_k.T, lower, rhs[flagged])

    def _rows(
        self,
        a: int,
        b: int,
        w: NDArray[np.float64],
        w2: NDArray[np.float64],
        factor: NDArray[np.float64],
        rhs: np.ndarray,
        count: int,
    ) -> None:
        """Rows a..b-1 of the block's ``off`` (the links a..min(b, n-1)-1: k + i (w c + h
        factor)), ``diag`` (k_g - w^2 J + i (w c_g + h_g factor) + off[i] + off[i-1]) and
        right-hand sides ``x``: the operations of :meth:`LinearSystem._diagonals_of` in the
        same order on every element (the same numbers), a few numpy calls for the rows
        together (class docstring)."""
        kb, cb, hb, kg, cg, hg, inertia = self.arrays
        col = np.newaxis
        e = min(b, self.n - 1)
        off, rows = self.off[a:e, :count], self.diag[a:b, :count]
        term = self.term[: b - a, :count]
        off.real = kb[a:e, col]
        np.multiply(w, cb[a:e, col], out=off.imag)
        np.multiply(w2, inertia[a:b, col], out=rows.real)
        np.subtract(kg[a:b, col], rows.real, out=rows.real)
        np.multiply(w, cg[a:b, col], out=rows.imag)
        if self.hysteretic:
            np.multiply(factor, hb[a:e, col], out=term[: e - a])
            np.add(off.imag, term[: e - a], out=off.imag)
            np.multiply(factor, hg[a:b, col], out=term)
            np.add(rows.imag, term, out=rows.imag)
        np.add(rows[: e - a], off, out=rows[: e - a])
        lo = max(a, 1)
        np.add(
            self.diag[lo:b, :count], self.off[lo - 1 : b - 1, :count], out=self.diag[lo:b, :count]
        )
        np.copyto(self.x[a:b, :, :count], rhs[:, a:b, :].transpose(1, 2, 0))

    def _flagged(
        self,
        w: NDArray[np.float64],
        off: NDArray[np.complex128],
        d: NDArray[np.complex128],
        high: NDArray[np.float64],
        low: NDArray[np.float64],
    ) -> NDArray[np.intp]:
        """The block's systems (indices) with a multiplier above :data:`_GROWTH` or not a
        number: the exact test on the candidates and on the rows outside the filter's range
        (class docstring); ``off`` (n-1, F) and ``d`` (n, F) the eliminated rows, ``high`` and
        ``low`` (2F,) the running extremes of the multipliers' parts."""
        count = w.size
        inside = (high <= _CANDIDATE) & (low >= -_CANDIDATE)  # False also for NaN
        candidate = np.any(~inside.reshape(count, 2), axis=1)
        flagged = np.zeros(count, dtype=bool)
        idx = np.flatnonzero(candidate)
        if idx.size:
            flagged[idx] = _growth(off[:, idx], d[:-1, idx])
        top_w = float(np.max(np.abs(w))) if count else 0.0
        top_f = 1.0 if self.hysteretic_frequency is None else top_w / abs(self.hysteretic_frequency)
        k, c, h = self.magnitudes
        bound = k + top_w * c + top_f * h  # at least every |off| of the block
        rows = np.flatnonzero(~((k >= _TINY) & (bound <= _HUGE)))
        for i in rows:  # outside the filter's range: the exact test on the row
            flagged |= _growth(off[i : i + 1], d[i : i + 1])
        return np.flatnonzero(flagged)


def _growth(off: NDArray[np.complex128], pivot: NDArray[np.complex128]) -> NDArray[np.bool_]:
    """Per system (column), a multiplier |off / pivot| above :data:`_GROWTH` on some row (a
    small pivot, elimination may have lost accuracy) or not a number: not
    |off|^2 <= 1e16 |pivot|^2 (arrays (rows, F))."""
    return ~np.all(_abs2(off) <= 1e16 * _abs2(pivot), axis=0)


def _dense_solve(matrix: np.ndarray, rhs: np.ndarray) -> NDArray[np.complex128]:
    """X with matrix X = rhs for a batch (F, n, n) and (F, n, r) by LU decomposition with
    partial pivoting (LAPACK ``zgesv``); NaN for a singular system (the others solved)."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        try:
            return np.asarray(np.linalg.solve(matrix, rhs), dtype=complex)
        except np.linalg.LinAlgError:  # an undamped system exactly at a resonance
            out = np.full(rhs.shape, np.nan + 0j)
            for i in range(matrix.shape[0]):  # the block's systems one by one
                with contextlib.suppress(np.linalg.LinAlgError):
                    out[i] = np.linalg.solve(matrix[i], rhs[i])
            return out


def _hyst(h: np.ndarray, w: np.ndarray, hysteretic_frequency: float | None) -> np.ndarray:
    """eta k (in phase with the rate): exact (constant) in the frequency domain, or as viscous
    c = eta k / omega_h frozen at a frequency omega_h (to compare with the time domain)."""
    if hysteretic_frequency is None:
        return h
    return h * (w / hysteretic_frequency)


def change_matrix(
    ends: Iterable[Sequence[int]] | NDArray[np.int_], values: ArrayLike, size: int
) -> NDArray[Any]:
    """Delta K of some elements (the load-dependent couplings,
    :func:`crankdyn.torsion.loaded.stiffness_change`): each a spring between its two ends,
    assembled like a shaft (k [[1, -1], [-1, 1]];
    :meth:`crankdyn.torsion.model.TorsionModel.stiffness_matrix`).

    Parameters
    ----------
    ends : array_like of int
        Degrees of freedom (a, b) at the ends of every element, shape (count, 2).
    values : array_like
        Stiffness changes (N m/rad; complex for a dynamic stiffness change), shape
        (..., count).
    size : int
        Number of degrees of freedom n.

    Returns
    -------
    numpy.ndarray
        Delta K (N m/rad, the dtype of ``values``), shape (..., n, n).

    Examples
    --------
    >>> change_matrix([(0, 1)], [2.0], 3).tolist()
    [[2.0, -2.0, 0.0], [-2.0, 2.0, 0.0], [0.0, 0.0, 0.0]]
    """
    values = np.asarray(values)
    out = np.zeros((*values.shape[:-1], size, size), dtype=values.dtype)
    for j, (a, b) in enumerate(ends):  # the elements (a few)
        out[..., a, a] += values[..., j]
        out[..., b, b] += values[..., j]
        out[..., a, b] -= values[..., j]
        out[..., b, a] -= values[..., j]
    return out


def linear_system(
    model: TorsionModel,
    dampers: Iterable[Damper] = (),
    modal_damping: ArrayLike | None = None,
) -> LinearSystem:
    """The model's reflected matrices with the dampers' rings added (module docstring).

    Each ring is a degree of freedom joined to its hub by the complex stiffness
    k_d + i (omega c_d + eta_d k_d) (:mod:`crankdyn.torsion.dampers`); a ring at an end of a
    chain keeps the chain. Modal damping ratios add C_modal
    (:func:`crankdyn.torsion.damped.modal_damping_matrix`), which couples every mass: the
    system is then solved densely.

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The lumped model.
    dampers : iterable of Damper
        Dampers whose rings are added (default none).
    modal_damping : float, array_like or None
        Damping ratios of the elastic modes (dimensionless; one for all or one per mode), or
        None.

    Returns
    -------
    LinearSystem
        The reflected system (kg m^2, N m/rad, N m s/rad).

    Raises
    ------
    InputError
        Naming the key and value: a damper's hub not a mass of the model, a ring named like
        a mass (``name``), modal damping ratios as
        :func:`crankdyn.torsion.damped.modal_damping_ratios`.

    Examples
    --------
    >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
    >>> from crankdyn.torsion.dampers import Damper
    >>> model = TorsionModel(masses=(Mass("m", 1.0),), shafts=(Shaft(("ground", "m"), 1e6),))
    >>> system = linear_system(model, [Damper("ring", "m", 0.1, damping=30.0)])
    >>> system.inertia.tolist(), system.damping.tolist()
    ([1.0, 0.1], [[30.0, -30.0], [-30.0, 30.0]])
    """
    dampers = tuple(dampers)
    names = _ring_names(model, dampers)
    n0 = model.dof_count
    ratio = model.signed_speed_ratios  # actual angles carry the sense of rotation
    mass_dof = np.array(model.mass_dof)
    chain = model.chain
    shaft_dofs = np.array(model.shaft_dofs)
    k_s, c_s, h_s = model._shaft_values()
    elem_ratio = [
        float(ratio[model.index(s.between[0] if s.between[0] != "ground" else s.between[1])])
        for s in model.shafts
    ]
    labels: list[tuple[str, str]] = [s.between for s in model.shafts]
    chained, shift, ring_dof = _ring_dofs(
        model, dampers, chain is not None and modal_damping is None
    )
    dof_of_model = np.arange(n0) + shift
    n = n0 + len(dampers)
    inertia = np.zeros(n)
    inertia[dof_of_model] = model.dof_inertia
    ends = np.where(shaft_dofs >= 0, dof_of_model[np.maximum(shaft_dofs, 0)], -1)
    values = np.array([k_s, c_s, h_s], dtype=float).reshape(3, -1)  # (3, shafts)
    grounded = np.any(ends < 0, axis=1)
    ground = np.zeros((3, n))
    np.add.at(ground.T, np.max(ends[grounded], axis=1), values[:, grounded].T)
    ground[1, dof_of_model] += model._absolute_damping
    pairs = [ends[~grounded]]
    pair_values = [values[:, ~grounded]]
    element_k = list(k_s)
    ring_mass_dof: list[int] = []
    ring_ratio: list[float] = []
    for d in dampers:
        r = int(ring_dof[id(d)])
        hub_mass = model.index(d.at)
        hub = int(dof_of_model[mass_dof[hub_mass]])
        r2 = float(ratio[hub_mass]) ** 2
        inertia[r] = d.inertia * r2
        pairs.append(np.array([[hub, r]]))
        pair_values.append(
            np.array([[d.stiffness], [d.damping], [d.loss_factor * d.stiffness]]) * r2
        )
        element_k.append(d.stiffness * r2)
        elem_ratio.append(float(ratio[hub_mass]))
        labels.append((d.at, d.name))
        ring_mass_dof.append(r)
        ring_ratio.append(float(ratio[hub_mass]))
    links, link_values = _merged_links(np.concatenate(pairs), np.concatenate(pair_values, axis=1))
    modal = None
    if modal_damping is not None:
        from crankdyn.torsion.damped import modal_damping_matrix

        modal = np.zeros((n, n))
        modal[np.ix_(dof_of_model, dof_of_model)] = modal_damping_matrix(model, modal_damping)
    element_dofs = np.concatenate([ends, np.array(pairs[1:], dtype=int).reshape(-1, 2)])
    masses_dof = np.concatenate([dof_of_model[mass_dof], np.array(ring_mass_dof, dtype=int)])
    masses_ratio = np.concatenate([ratio, np.array(ring_ratio)])
    chain_arrays = _chain_arrays(n, links, link_values, ground) if chained else None
    tree = None
    if chain_arrays is None and modal is None:
        tree = elimination_tree(n, links)
    return LinearSystem(
        inertia=inertia,
        links=links,
        link_values=link_values,
        ground_values=ground,
        modal_damping=modal,
        chain=chain_arrays,
        tree=tree,
        mass_dof=masses_dof.astype(int),
        mass_ratio=masses_ratio,
        mass_names=tuple(names),
        element_dofs=element_dofs.astype(int).reshape(-1, 2),
        element_stiffness=np.array(element_k, dtype=float),
        element_ratio=np.array(elem_ratio, dtype=float),
        element_labels=tuple(labels),
        dampers=dampers,
    )


def _merged_links(
    pairs: NDArray[np.int_], values: NDArray[np.float64]
) -> tuple[NDArray[np.intp], NDArray[np.float64]]:
    """(links (L, 2), values (3, L)): the pairs of degrees of freedom (each as (lower,
    higher)) once, in ascending order, the values of parallel ones added."""
    if pairs.size == 0:
        return np.zeros((0, 2), dtype=np.intp), np.zeros((3, 0))
    ordered = np.sort(pairs, axis=1)
    links, index = np.unique(ordered, axis=0, return_inverse=True)
    merged = np.zeros((3, links.shape[0]))
    np.add.at(merged.T, index.reshape(-1), values.T)
    return links.astype(np.intp), merged


def _ring_names(model: TorsionModel, dampers: Sequence[Damper]) -> list[str]:
    """The listed masses' names: the model's, then the dampers' rings (InputError for a hub
    that is not a mass of the model or a ring named like a mass)."""
    names = list(model.mass_names)
    for d in dampers:
        model.index(d.at)  # the hub must exist (one-line error otherwise)
        if d.name in names:
            raise InputError(
                f'the damper ring is named "{d.name}" like a mass; give it another name',
                key="name",
                value=d.name,
            )
        names.append(d.name)
    return names


def _ring_dofs(
    model: TorsionModel, dampers: Sequence[Damper], chained: bool
) -> tuple[bool, int, dict[int, int]]:
    """Ring placement: (chained, shift, ring dof by ``id(damper)``). A ring at an end of a
    chain keeps the chain (one ring per end; a ring at the first end shifts the model's dofs
    by one); any other ring, or a model that is no chain (``chained`` False), puts the rings
    after the model's dofs."""
    n0 = model.dof_count
    mass_dof = np.array(model.mass_dof)
    first = last = None
    for d in dampers:
        hub = int(mass_dof[model.index(d.at)])
        if not chained:
            break
        if hub == n0 - 1 and last is None:
            last = d
        elif hub == 0 and first is None:
            first = d
        else:
            chained = False
    shift = 1 if chained and first is not None else 0
    ring_dof: dict[int, int] = {}
    if chained:
        if first is not None:
            ring_dof[id(first)] = 0
        if last is not None:
            ring_dof[id(last)] = n0 + shift
    else:
        for j, d in enumerate(dampers):
            ring_dof[id(d)] = n0 + j
    return chained, shift, ring_dof


def _chain_arrays(
    n: int, links: NDArray[np.intp], values: NDArray[np.float64], ground: NDArray[np.float64]
) -> tuple[np.ndarray, ...] | None:
    """(k_between, c_between, h_between, k_g, c_g, h_g) of a chain in dof order (the
    :class:`LinearSystem` field ``chain``) from its links (lower, higher) and its terms to
    ground, None when the links are not those of neighbours."""
    if links.shape[0] != max(n - 1, 0) or np.any(links[:, 1] != links[:, 0] + 1):
        return None  # pragma: no cover - guarded by the placement of the rings
    between = np.zeros((3, max(n - 1, 0)))
    between[:, links[:, 0]] = values
    return (between[0], between[1], between[2], ground[0], ground[1], ground[2])


def steady_state(
    model: TorsionModel,
    omega: ArrayLike,
    forcing: ArrayLike,
    *,
    dampers: Iterable[Damper] = (),
    hysteretic_frequency: float | None = None,
) -> NDArray[np.complexfloating]:
    """Steady-state complex amplitudes under harmonic torques: X = D(omega)^-1 F.

    For every frequency at once (seed 003, the V6 paper's eqs. 2 and 6; module docstring).
    The counterpart of openTorsion's ``Assembly.ss_response``.

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The lumped model.
    omega : float or array_like
        Circular frequencies (rad/s), shape (...).
    forcing : array_like
        Harmonic torques on the degrees of freedom (N m, complex), shape (..., dofs) or
        (..., dofs, r).
    dampers : iterable of Damper
        Dampers whose rings are added (default none).
    hysteretic_frequency : float or None
        None: loss factors as exact hysteretic damping; omega_h (rad/s): as viscous damping
        eta k / omega_h.

    Returns
    -------
    numpy.ndarray
        Complex reflected angles of the degrees of freedom (rad), the shape of ``forcing``.

    Examples
    --------
    One damped mass at 900 rad/s: X = T / (k - omega^2 J + i omega c) (seed 003,
    "单质量有阻尼强迫扭转振动").

    >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
    >>> model = TorsionModel(
    ...     masses=(Mass("m", 1.0, damping=20.0),), shafts=(Shaft(("ground", "m"), 1e6),)
    ... )
    >>> x = steady_state(model, [900.0], [[100.0]])
    >>> round(float(abs(x[0, 0])) / abs(100.0 / (1e6 - 900.0**2 + 900j * 20.0)), 12)
    1.0
    """
    return linear_system(model, dampers).solve(omega, forcing, hysteretic_frequency)
