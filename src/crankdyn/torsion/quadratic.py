"""The quadratic eigenvalue problem of a damped model, solved one mode at a time (numeric core).

The free vibration M theta'' + C theta' + K theta = 0 (:mod:`crankdyn.torsion.damped`) with
theta = x exp(lambda t) is the quadratic eigenvalue problem (QEP)

    Q(lambda) x = (lambda^2 M + lambda C_eff + K) x = 0,   C_eff = C + H / omega_h,

of 2n eigenvalues (F. Tisseur and K. Meerbergen, "The quadratic eigenvalue problem", *SIAM
Review* 43 (2001) 235-286, §1). M, C, H and K are real and symmetric, so Q(lambda) is complex
symmetric, Q^T = Q, and an eigenvector x gives the left eigenvector y = conj(x): y^H Q(lambda) =
x^T Q(lambda) = (Q(lambda) x)^T = 0.

**Per mode, from the undamped mode.** Mode r is found from the undamped pair (omega_r, phi_r)
(:func:`crankdyn.torsion.modal.eigen_modes`) by the Rayleigh functional iteration (A. Ruhe,
"Algorithms for the nonlinear eigenvalue problem", *SIAM J. Numer. Anal.* 10 (1973) 674-689,
inverse iteration; H. Voss, "Nonlinear eigenvalue problems", ch. 115 of L. Hogben (ed.),
*Handbook of Linear Algebra*, 2nd ed., CRC Press 2014, §115.4-115.5): with x_0 = phi_r,

    lambda_k = p(x_k):  the root of x_k^T Q(lambda) x_k = 0 nearest lambda_k-1,
    x_k+1 = Q(lambda_k)^-1 Q'(lambda_k) x_k,  normalised,  Q'(lambda) = 2 lambda M + C_eff.

p is the two-sided Rayleigh functional (left and right vectors x^T, x for the complex symmetric
Q), stationary at an eigenvector, so the iteration converges locally cubically to a simple
eigenvalue (Voss 2014, §115.5; K. Schreiber, *Nonlinear Eigenvalue Problems: Newton-type
Methods and Nonlinear Rayleigh Functionals*, PhD thesis, TU Berlin 2008). Its first value
p(phi_r) is the classical estimate of proportional damping: lambda^2 + (phi_r^T C phi_r)
lambda + omega_r^2 = 0 (mass-normalised phi_r). Each step is one solve with Q(lambda_k): for a
chain a tridiagonal one (LAPACK ``zgtsv``, Gaussian elimination with partial pivoting, O(n):
E. Anderson et al., *LAPACK Users' Guide*, 3rd ed., SIAM 1999), so a mode costs O(n) and all n
modes O(n^2) in time, with O(n) working memory beside the n x n mode shapes; other models a
dense LU (O(n^3) a step).

**Hysteretic damping at the mode's own frequency** (``omega_h`` None): each step solves the
scalar equation x^T Q(lambda; omega_h) x = 0 together with omega_h = |Im lambda| (a scalar
fixed point, iterated to round-off, omega_h moving at most a factor 2 a step), so the iteration
converges to an eigenpair of Q(lambda; |Im lambda|): the definition of
:mod:`crankdyn.torsion.damped`.

**Converged** when the normwise backward error (F. Tisseur, "Backward error and condition of
polynomial eigenvalue problems", *Linear Algebra Appl.* 309 (2000) 339-361)

    eta(x, lambda) = ||Q(lambda) x||_2 / ((|lambda|^2 ||M|| + |lambda| ||C_eff|| + ||K||) ||x||_2)

(infinity norms of the matrices) is at most :data:`TOLERANCE`, or at most :data:`LOOSE` and no
longer halving (round-off reached). (x, lambda) is then an exact eigenpair of a QEP whose
matrices differ from M, C_eff, K by eta times their norms; the eigenvalue's error is at most
about kappa(lambda) eta |lambda|, kappa(lambda) = (|lambda|^2 ||M|| + |lambda| ||C_eff|| + ||K||)
||x||^2 / (|lambda| |x^T Q'(lambda) x|) its condition number (Tisseur 2000).

**Overdamped modes** (a real eigenvalue): the second real eigenvalue is sought near the other
root of x^T Q(lambda) x = 0 with the converged x (:mod:`crankdyn.torsion.damped`).

**Near a shift** (:func:`eigenpairs_near`): the eigenvalues nearest sigma by shift-invert
Arnoldi (ARPACK through :func:`scipy.sparse.linalg.eigs`; R. B. Lehoucq, D. C. Sorensen and C.
Yang, *ARPACK Users' Guide*, SIAM 1998) on the first companion linearisation [[0, I], [-K,
-C_eff]] z = lambda diag(I, M) z, z = (x, lambda x) (Tisseur and Meerbergen 2001, §3.4 and
§6), each operator application one tridiagonal solve with Q(sigma): where
:mod:`crankdyn.torsion.damped` seeks a mode again whose iteration reached another mode's
eigenpair, and the overdamped modes' second eigenvalues.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:
    from crankdyn.torsion.model import ChainArrays

__all__ = [
    "LOOSE",
    "STEPS",
    "TOLERANCE",
    "ChainPencil",
    "DensePencil",
    "Refined",
    "backward_errors",
    "condition_numbers",
    "eigenpairs_near",
    "rayleigh",
    "refine",
]

_EPS = float(np.finfo(float).eps)
TOLERANCE = 16.0 * _EPS
"""Backward error at which a mode has converged (16 eps: round-off of the O(n) solve)."""
LOOSE = 1e-12
"""Backward error accepted when the iteration stalls at round-off (no longer halving)."""
STEPS = 40
"""Iterations per mode at most (the iteration converges cubically: 2 to 8 steps in practice)."""
_FIXED_POINT_STEPS = 200
_BLOCK_ELEMENTS = 1 << 16
"""Modes are iterated in blocks of about this many amplitudes (a block's arrays in cache)."""


def _tri_apply(diag: NDArray, off: NDArray, x: NDArray) -> NDArray[np.complex128]:
    """A x for every row of x (B, n); diag (B, n) or (n,), off (B, n - 1) or (n - 1,)."""
    y = diag * x
    if x.shape[-1] > 1:
        y[:, :-1] += off * x[:, 1:]
        y[:, 1:] += off * x[:, :-1]
    return y


def _norm_inf(diag: NDArray, off: NDArray) -> float:
    """Infinity norm of the symmetric tridiagonal (diag, off)."""
    row = np.abs(diag).astype(float)
    if off.size:
        row[:-1] += np.abs(off)
        row[1:] += np.abs(off)
    return float(row.max(initial=0.0))


@dataclass(frozen=True)
class ChainPencil:
    """M, C, H, K of a chain: M diagonal, the others symmetric tridiagonal.

    Every method works on a block of B rows, one mode each: vectors x (B, n), eigenvalues
    lambda and omega_h (B,). Q(lambda) = lambda^2 M + lambda (C + H / omega_h) + K.

    Parameters
    ----------
    m : numpy.ndarray
        (n,) inertias (kg m^2), reflected to the reference speed.
    k, c, h : tuple of numpy.ndarray
        (diagonal (n,), off-diagonal (n - 1,)) of K (N m/rad), C (N m s/rad) and H (N m/rad).

    Examples
    --------
    >>> from crankdyn.torsion import TorsionModel
    >>> p = ChainPencil.of(TorsionModel.chain_of([1.0, 2.0], [5.0], ground_left=3.0).chain)
    >>> p.k[0].tolist(), p.k[1].tolist(), p.hysteretic
    ([8.0, 5.0], [-5.0], False)
    """

    m: NDArray[np.float64]
    k: tuple[NDArray[np.float64], NDArray[np.float64]]
    c: tuple[NDArray[np.float64], NDArray[np.float64]]
    h: tuple[NDArray[np.float64], NDArray[np.float64]]

    @classmethod
    def of(cls, chain: ChainArrays) -> ChainPencil:
        """The pencil of a chain.

        Parameters
        ----------
        chain : crankdyn.torsion.model.ChainArrays
            The chain's arrays (SI, reflected).

        Returns
        -------
        ChainPencil
            Its M, C, H, K.
        """

        def tri(between: NDArray, ground: NDArray) -> tuple[NDArray, NDArray]:
            diag = np.array(ground, dtype=float)
            diag[:-1] += between
            diag[1:] += between
            return diag, -np.asarray(between, dtype=float)

        return cls(
            m=np.asarray(chain.inertia, dtype=float),
            k=tri(chain.stiffness, chain.ground_stiffness),
            c=tri(chain.damping, chain.ground_damping),
            h=tri(chain.hysteretic, chain.ground_hysteretic),
        )

    @property
    def size(self) -> int:
        """Degrees of freedom n."""
        return int(self.m.size)

    @property
    def block(self) -> int:
        """Modes iterated together (a block's arrays of about 2^14 amplitudes stay in cache)."""
        return max(1, (1 << 14) // max(self.size, 1))

    @cached_property
    def hysteretic(self) -> bool:
        """Whether H is not zero."""
        return bool(np.any(self.h[0] != 0.0))

    @cached_property
    def _diagonals(self) -> tuple[NDArray, NDArray]:
        """(n, 4) and (n - 1, 4): the diagonals and off-diagonals of M, C, H, K as columns."""
        zero = np.zeros(max(self.size - 1, 0))
        return (
            np.stack([self.m, self.c[0], self.h[0], self.k[0]], axis=1),
            np.stack([zero, self.c[1], self.h[1], self.k[1]], axis=1),
        )

    def dense(self) -> DensePencil:
        """The same pencil with dense matrices (for small chains).

        Returns
        -------
        DensePencil
            M, C, H, K as n x n matrices (M as its diagonal).
        """

        def full(tri: tuple[NDArray, NDArray]) -> NDArray[np.float64]:
            return np.diag(tri[0]) + np.diag(tri[1], 1) + np.diag(tri[1], -1)

        return DensePencil(self.m, full(self.k), full(self.c), full(self.h))

    @cached_property
    def norms(self) -> tuple[float, float, float, float]:
        """Infinity norms of M, C, H, K (kg m^2, N m s/rad, N m/rad, N m/rad)."""
        return (
            float(self.m.max(initial=0.0)),
            _norm_inf(*self.c),
            _norm_inf(*self.h),
            _norm_inf(*self.k),
        )

    def forms(self, x: NDArray) -> tuple[NDArray, NDArray, NDArray, NDArray]:
        """The quadratic forms x^T A x (no conjugate) of every row.

        Parameters
        ----------
        x : numpy.ndarray
            (B, n) vectors (rad per sqrt(kg m^2), or any scaling).

        Returns
        -------
        tuple of numpy.ndarray
            (B,) x^T M x, x^T C x, x^T H x, x^T K x (in the units of M, C, H, K times x^2).
        """
        diag, off = self._diagonals
        out = (x * x) @ diag
        if off.size:
            out += 2.0 * ((x[:, :-1] * x[:, 1:]) @ off)
        return out[:, 0], out[:, 1], out[:, 2], out[:, 3]

    def _damping(self, w: NDArray) -> tuple[NDArray, NDArray]:
        """C_eff = C + H / omega_h per row (B, n), (B, n - 1); C itself without H."""
        if not self.hysteretic:
            return self.c
        inv = (1.0 / w)[:, None]
        return self.c[0] + inv * self.h[0], self.c[1] + inv * self.h[1]

    def operator(self, lam: NDArray, w: NDArray) -> Any:
        """Q(lambda) of every row.

        Parameters
        ----------
        lam : numpy.ndarray
            (B,) eigenvalues (1/s, complex), one per row.
        w : numpy.ndarray
            (B,) omega_h (rad/s) of the hysteretic damping, one per row.

        Returns
        -------
        tuple of numpy.ndarray
            Its diagonals (B, n) and off-diagonals (B, n - 1) (N m/rad).
        """
        cd, co = self._damping(w)
        lam_ = lam[:, None]
        return (lam_ * self.m + cd) * lam_ + self.k[0], lam_ * co + self.k[1]

    @staticmethod
    def take(op: Any, keep: NDArray[np.bool_]) -> Any:
        """The operators of some rows.

        Parameters
        ----------
        op : tuple of numpy.ndarray
            Operators from :meth:`operator`.
        keep : numpy.ndarray
            (B,) the rows kept.

        Returns
        -------
        tuple of numpy.ndarray
            Their operators.
        """
        return op[0][keep], op[1][keep]

    @staticmethod
    def residual(op: Any, x: NDArray) -> NDArray[np.complex128]:
        """Q(lambda) x for every row.

        Parameters
        ----------
        op : tuple of numpy.ndarray
            Operators from :meth:`operator`.
        x : numpy.ndarray
            (B, n) vectors.

        Returns
        -------
        numpy.ndarray
            (B, n) Q(lambda) x (N m per unit of x).
        """
        return _tri_apply(op[0], op[1], x)

    def derivative(self, lam: NDArray, w: NDArray, x: NDArray) -> NDArray[np.complex128]:
        """Q'(lambda) x = (2 lambda M + C_eff) x for every row.

        Parameters
        ----------
        lam : numpy.ndarray
            (B,) eigenvalues (1/s, complex), one per row.
        w : numpy.ndarray
            (B,) omega_h (rad/s) of the hysteretic damping, one per row.
        x : numpy.ndarray
            (B, n) vectors.

        Returns
        -------
        numpy.ndarray
            (B, n) Q'(lambda) x (N m s per unit of x).
        """
        cd, co = self._damping(w)
        return _tri_apply(2.0 * lam[:, None] * self.m + cd, co, x)

    def solve(self, op: Any, rhs: NDArray) -> NDArray[np.complex128]:
        """Q(lambda)^-1 rhs for every row, by LAPACK ``zgtsv`` (one mode at a time).

        Parameters
        ----------
        op : tuple of numpy.ndarray
            Operators from :meth:`operator`.
        rhs : numpy.ndarray
            (B, n) right-hand sides.

        Returns
        -------
        numpy.ndarray
            (B, n) the solutions (rhs where Q(lambda) is exactly singular: lambda is exact).
        """
        from scipy.linalg.lapack import zgtsv  # imported here: keeps the start-up light

        diag, off = op
        if self.size == 1:  # LAPACK's wrapper takes no empty off-diagonal
            return np.asarray(rhs / np.where(diag != 0.0, diag, 1.0), dtype=complex)
        out = np.empty_like(rhs)
        for j in range(rhs.shape[0]):  # one O(n) solve per mode of the block
            _, _, _, sol, info = zgtsv(off[j], diag[j], off[j], rhs[j][:, None])
            out[j] = sol[:, 0] if info == 0 else rhs[j]  # info > 0: lambda is exact
        return out


@dataclass(frozen=True)
class DensePencil:
    """M (diagonal) and dense symmetric C, H, K: branched and geared models, and modal damping
    (which couples every mass); the methods of :class:`ChainPencil`, on n x n matrices.

    Parameters
    ----------
    m : numpy.ndarray
        (n,) inertias (kg m^2), reflected to the reference speed.
    k, c, h : numpy.ndarray
        (n, n) K (N m/rad), C (N m s/rad) and H (N m/rad).
    """

    m: NDArray[np.float64]
    k: NDArray[np.float64]
    c: NDArray[np.float64]
    h: NDArray[np.float64]

    @property
    def size(self) -> int:
        """Degrees of freedom n."""
        return int(self.m.size)

    block = 1
    """Modes iterated together: one (each holds an n x n operator)."""

    @cached_property
    def hysteretic(self) -> bool:
        """Whether H is not zero."""
        return bool(np.any(self.h != 0.0))

    @cached_property
    def norms(self) -> tuple[float, float, float, float]:
        """Infinity norms of M, C, H, K (kg m^2, N m s/rad, N m/rad, N m/rad)."""
        m = float(self.m.max(initial=0.0))
        c, h, k = (float(np.abs(a).sum(axis=-1).max(initial=0.0)) for a in (self.c, self.h, self.k))
        return m, c, h, k

    def forms(self, x: NDArray) -> tuple[NDArray, NDArray, NDArray, NDArray]:
        """The quadratic forms x^T A x (no conjugate) of every row.

        Parameters
        ----------
        x : numpy.ndarray
            (B, n) vectors.

        Returns
        -------
        tuple of numpy.ndarray
            (B,) x^T M x, x^T C x, x^T H x, x^T K x.
        """
        c, h, k = (np.einsum("bi,bi->b", x @ a, x) for a in (self.c, self.h, self.k))
        return np.einsum("bi,i,bi->b", x, self.m, x), c, h, k

    def operator(self, lam: NDArray, w: NDArray) -> Any:
        """Q(lambda) of every row.

        Parameters
        ----------
        lam : numpy.ndarray
            (B,) eigenvalues (1/s, complex), one per row.
        w : numpy.ndarray
            (B,) omega_h (rad/s) of the hysteretic damping, one per row.

        Returns
        -------
        numpy.ndarray
            (B, n, n) Q(lambda) (N m/rad).
        """
        lam_ = lam[:, None, None]
        c = self.c + self.h / w[:, None, None]
        return (lam_ * lam_) * np.diag(self.m) + lam_ * c + self.k

    @staticmethod
    def take(op: Any, keep: NDArray[np.bool_]) -> Any:
        """The operators of some rows.

        Parameters
        ----------
        op : numpy.ndarray
            Operators from :meth:`operator`.
        keep : numpy.ndarray
            (B,) the rows kept.

        Returns
        -------
        numpy.ndarray
            Their operators.
        """
        return op[keep]

    @staticmethod
    def residual(op: Any, x: NDArray) -> NDArray[np.complex128]:
        """Q(lambda) x for every row.

        Parameters
        ----------
        op : numpy.ndarray
            Operators from :meth:`operator`.
        x : numpy.ndarray
            (B, n) vectors.

        Returns
        -------
        numpy.ndarray
            (B, n) Q(lambda) x.
        """
        return np.einsum("bij,bj->bi", op, x)

    def derivative(self, lam: NDArray, w: NDArray, x: NDArray) -> NDArray[np.complex128]:
        """Q'(lambda) x = (2 lambda M + C_eff) x for every row.

        Parameters
        ----------
        lam : numpy.ndarray
            (B,) eigenvalues (1/s, complex), one per row.
        w : numpy.ndarray
            (B,) omega_h (rad/s) of the hysteretic damping, one per row.
        x : numpy.ndarray
            (B, n) vectors.

        Returns
        -------
        numpy.ndarray
            (B, n) Q'(lambda) x.
        """
        c = self.c + self.h / w[:, None, None]
        return 2.0 * lam[:, None] * self.m * x + np.einsum("bij,bj->bi", c, x)

    @staticmethod
    def solve(op: Any, rhs: NDArray) -> NDArray[np.complex128]:
        """Q(lambda)^-1 rhs for every row (dense LU, LAPACK ``zgesv``).

        Parameters
        ----------
        op : numpy.ndarray
            Operators from :meth:`operator`.
        rhs : numpy.ndarray
            (B, n) right-hand sides.

        Returns
        -------
        numpy.ndarray
            (B, n) the solutions (rhs where Q(lambda) is exactly singular).
        """
        out = np.empty_like(rhs)
        for j in range(rhs.shape[0]):
            try:
                out[j] = np.linalg.solve(op[j], rhs[j])
            except np.linalg.LinAlgError:  # singular: lambda is exact
                out[j] = rhs[j]
        return out


Pencil = ChainPencil | DensePencil


def _roots(a2: NDArray, a1: NDArray, a0: NDArray, near: NDArray) -> tuple[NDArray, NDArray]:
    """The roots of a2 l^2 + a1 l + a0 = 0 (complex, per element), the one nearer ``near``
    first; computed without cancellation (q = -(a1 + sign sqrt(a1^2 - 4 a2 a0)) / 2, roots q / a2
    and a0 / q: W. H. Press et al., *Numerical Recipes*, 3rd ed., 2007, §5.6)."""
    s = np.sqrt(a1 * a1 - 4.0 * a2 * a0 + 0j)
    q = -0.5 * (a1 + np.where((np.conj(a1) * s).real >= 0.0, s, -s))
    with np.errstate(divide="ignore", invalid="ignore"):
        r1 = q / a2
        r2 = np.where(q != 0.0, a0 / np.where(q != 0.0, q, 1.0), r1)
    first = np.abs(r1 - near) <= np.abs(r2 - near)
    return np.where(first, r1, r2), np.where(first, r2, r1)


def rayleigh(
    forms: tuple[NDArray, NDArray, NDArray, NDArray],
    near: NDArray,
    w: NDArray,
    iterate: bool,
) -> tuple[NDArray, NDArray, NDArray]:
    """The Rayleigh functional p(x): the root of x^T Q(lambda) x = 0 nearest ``near`` (module
    docstring), with omega_h = |Im lambda| solved with it when ``iterate``.

    Parameters
    ----------
    forms : tuple of numpy.ndarray
        x^T M x, x^T C x, x^T H x, x^T K x per row (kg m^2, N m s/rad, N m/rad, N m/rad).
    near : numpy.ndarray
        The previous eigenvalue estimates (1/s, complex).
    w : numpy.ndarray
        omega_h (rad/s): fixed, or the start of the fixed point when ``iterate``.
    iterate : bool
        Whether omega_h = |Im lambda| is solved with lambda (hysteretic damping at the mode's
        own damped frequency).

    Returns
    -------
    lam, other, w : numpy.ndarray
        The root nearest ``near`` and the other root (1/s), and omega_h (rad/s).

    Examples
    --------
    One mass (x = 1) J = 2, c = 40, k = 8e4: lambda = -10 +/- i sqrt(8e4/2 - 100).

    >>> one = np.ones(1)
    >>> lam, other, w = rayleigh((2 * one, 40 * one, 0 * one, 8e4 * one), 1j * one, one, False)
    >>> [round(float(v), 9) for v in (lam[0].real, lam[0].imag, other[0].imag, 39_900**0.5)]
    [-10.0, 199.749843554, -199.749843554, 199.749843554]
    """
    a2, a1, ah, a0 = forms
    lam, other = _roots(a2, a1 + ah / w, a0, near)
    if not iterate:
        return lam, other, w
    low, high = 0.5 * w, 2.0 * w  # omega_h moves by at most a factor of 2 a step (safeguard)
    for _ in range(_FIXED_POINT_STEPS):  # the scalar fixed point omega_h = |Im lambda|
        real = np.abs(lam.imag) <= 1e-9 * np.abs(lam)
        w_new = np.clip(np.where(real, w, np.abs(lam.imag)), low, high)
        done = np.abs(w_new - w) <= 2.0 * _EPS * w
        w = w_new
        lam, other = _roots(a2, a1 + ah / w, a0, lam)
        if np.all(done):
            break
    return lam, other, w


def backward_errors(
    pencil: Pencil, lam: NDArray, w: NDArray, x: NDArray, residual: NDArray | None = None
) -> NDArray[np.float64]:
    """The normwise backward error eta(x, lambda) of every row (module docstring; Tisseur
    2000), dimensionless.

    Parameters
    ----------
    pencil : ChainPencil or DensePencil
        M, C, H, K (SI).
    lam, w : numpy.ndarray
        (B,) eigenvalues (1/s) and omega_h (rad/s).
    x : numpy.ndarray
        (B, n) vectors.
    residual : numpy.ndarray or None
        Q(lambda) x when known (N m per unit of x).

    Returns
    -------
    numpy.ndarray
        (B,) eta (dimensionless).
    """
    nm, nc, nh, nk = pencil.norms
    if residual is None:
        residual = pencil.residual(pencil.operator(lam, w), x)
    a = np.abs(lam)
    scale = (a * nm + (nc + nh / w)) * a + nk
    size = np.linalg.norm(x, axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.linalg.norm(residual, axis=1) / (scale * np.where(size > 0.0, size, 1.0))


@dataclass(frozen=True)
class Refined:
    """Eigenpairs from :func:`refine`, one per row.

    Parameters
    ----------
    lam : numpy.ndarray
        (B,) eigenvalues (1/s, complex).
    x : numpy.ndarray
        (B, n) eigenvectors, unit 2-norm.
    w : numpy.ndarray
        (B,) omega_h (rad/s).
    eta : numpy.ndarray
        (B,) normwise backward errors (dimensionless).
    other : numpy.ndarray
        (B,) the other root of each Rayleigh functional (1/s).
    converged : numpy.ndarray
        (B,) whether each converged (module docstring).
    """

    lam: NDArray[np.complex128]
    x: NDArray[np.complex128]
    w: NDArray[np.float64]
    eta: NDArray[np.float64]
    other: NDArray[np.complex128]
    converged: NDArray[np.bool_]


def refine(
    pencil: Pencil,
    lam: NDArray,
    x: NDArray,
    w: NDArray,
    *,
    iterate: bool,
    steps: int = STEPS,
) -> Refined:
    """Eigenpairs of Q(lambda) by the Rayleigh functional iteration from (lambda, x) (module
    docstring), every row its own mode, in blocks of modes.

    Parameters
    ----------
    pencil : ChainPencil or DensePencil
        M, C, H, K (SI).
    lam : numpy.ndarray
        (B,) starting eigenvalues (1/s, complex): the root of x^T Q x = 0 to follow.
    x : numpy.ndarray
        (B, n) starting vectors (the undamped modes; rad per sqrt(kg m^2)); overwritten.
    w : numpy.ndarray
        (B,) omega_h (rad/s): fixed, or the start of the fixed point when ``iterate``.
    iterate : bool
        Hysteretic damping at each mode's own damped frequency (module docstring).
    steps : int
        Iterations per mode at most.

    Returns
    -------
    Refined
        The eigenpairs, each row's vector scaled to unit 2-norm.

    Examples
    --------
    Two masses on a damped shaft to ground: the iteration reaches the state-space eigenvalues.

    >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
    >>> model = TorsionModel(
    ...     masses=(Mass("a", 1.0, damping=30.0), Mass("b", 2.0)),
    ...     shafts=(Shaft(("ground", "a"), 1e5), Shaft(("a", "b"), 5e4)),
    ... )
    >>> p = ChainPencil.of(model.chain)
    >>> start = rayleigh(p.forms(np.eye(2)), 1j * np.ones(2), np.ones(2), False)[0]
    >>> r = refine(p, start, np.eye(2, dtype=complex), np.ones(2), iterate=False)
    >>> bool(r.converged.all()), bool(r.eta.max() < 1e-14)
    (True, True)
    """
    lam = np.array(lam, dtype=complex)
    x = np.asarray(x, dtype=complex)
    w = np.array(w, dtype=float)
    count = x.shape[0]
    eta = np.full(count, np.inf)
    other = lam.copy()
    converged = np.zeros(count, dtype=bool)
    for lo in range(0, count, pencil.block):
        rows = np.arange(lo, min(lo + pencil.block, count))
        previous = np.full(rows.size, np.inf)
        xr, lr, wr = x[rows], lam[rows], w[rows]
        op = pencil.operator(lr, wr)  # Q(lambda_k): solved with, then the residual's
        for _ in range(steps):
            y = pencil.solve(op, pencil.derivative(lr, wr, xr))
            y /= np.linalg.norm(y, axis=1)[:, None]
            lr, oth, wr = rayleigh(pencil.forms(y), lr, wr, iterate)
            op = pencil.operator(lr, wr)
            e = backward_errors(pencil, lr, wr, y, pencil.residual(op, y))
            x[rows], lam[rows], w[rows], eta[rows], other[rows] = y, lr, wr, e, oth
            done = (e <= TOLERANCE) | ((e <= LOOSE) & (e > 0.5 * previous))
            converged[rows[done]] = True
            keep = ~done & np.isfinite(e)  # a row that failed (overflow) stops, unconverged
            if not keep.any():
                break
            rows, previous, xr, lr, wr = rows[keep], e[keep], y[keep], lr[keep], wr[keep]
            op = pencil.take(op, keep)
    return Refined(lam=lam, x=x, w=w, eta=eta, other=other, converged=converged)


def eigenpairs_near(
    pencil: ChainPencil, sigma: complex, w: float, count: int
) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
    """The ``count`` eigenvalues of Q(lambda) (at a fixed omega_h) nearest ``sigma``, and their
    vectors, by shift-invert Arnoldi on the companion linearisation (module docstring).

    Parameters
    ----------
    pencil : ChainPencil
        The chain's M, C, H, K (SI).
    sigma : complex
        The shift (1/s), not an eigenvalue.
    w : float
        omega_h (rad/s) of the hysteretic damping.
    count : int
        How many eigenvalues, fewer than 2n - 1.

    Returns
    -------
    lam : numpy.ndarray
        (count,) eigenvalues (1/s).
    x : numpy.ndarray
        (count, n) their vectors (the first half of z), unit 2-norm.

    Examples
    --------
    >>> from crankdyn.torsion import TorsionModel
    >>> p = ChainPencil.of(TorsionModel.chain_of([1.0, 1.0, 1.0], [1e4, 1e4]).chain)
    >>> lam, x = eigenpairs_near(p, 170j, 1.0, 1)  # omega^2 = 1e4, 3e4: the nearest is 173.2j
    >>> round(float(abs(lam[0])) ** 2, 6)
    30000.0
    """
    from scipy.linalg.lapack import zgttrf, zgttrs  # imported here: keeps the start-up light
    from scipy.sparse.linalg import LinearOperator, eigs

    n = pencil.size
    inv = 1.0 / w
    cd, co = pencil.c[0] + inv * pencil.h[0], pencil.c[1] + inv * pencil.h[1]
    diag = (sigma * pencil.m + cd) * sigma + pencil.k[0]
    off = sigma * co + pencil.k[1]
    dl, d, du, du2, ipiv, info = zgttrf(off.astype(complex), diag.astype(complex), off.copy())
    if info != 0:
        raise np.linalg.LinAlgError(f"the shift {sigma} is an eigenvalue (zgttrf info {info})")

    def op(z: NDArray) -> NDArray:
        # (A - sigma B)^-1 B z for A = [[0, I], [-K, -C]], B = diag(I, M) (module docstring)
        z1, z2 = z[:n], z[n:]
        rhs = pencil.m * z2 + _tri_apply(cd + sigma * pencil.m, co, z1[None])[0]
        y1, _info = zgttrs(dl, d, du, du2, ipiv, rhs.astype(complex))
        y1 = -y1
        return np.concatenate([y1, z1 + sigma * y1])

    theta, z = eigs(LinearOperator((2 * n, 2 * n), matvec=op, dtype=complex), k=count, which="LM")
    lam = sigma + 1.0 / theta
    x = z[:n].T.copy()
    x /= np.linalg.norm(x, axis=1)[:, None]
    return lam, x


def condition_numbers(pencil: Pencil, lam: NDArray, w: NDArray, x: NDArray) -> NDArray[np.float64]:
    """The condition number kappa(lambda) of every row's eigenvalue (module docstring; Tisseur
    2000): |delta lambda| / |lambda| <= kappa eta to first order.

    Parameters
    ----------
    pencil : ChainPencil or DensePencil
        M, C, H, K (SI).
    lam : numpy.ndarray
        (B,) eigenvalues (1/s).
    w : numpy.ndarray
        (B,) omega_h (rad/s).
    x : numpy.ndarray
        (B, n) their eigenvectors.

    Returns
    -------
    numpy.ndarray
        (B,) kappa (dimensionless).
    """
    nm, nc, nh, nk = pencil.norms
    a = np.abs(lam)
    scale = (a * nm + (nc + nh / w)) * a + nk
    dq = np.einsum("bi,bi->b", x, pencil.derivative(lam, w, x))
    size = np.einsum("bi,bi->b", x.conj(), x).real
    with np.errstate(divide="ignore", invalid="ignore"):
        return scale * size / (a * np.abs(dq))
