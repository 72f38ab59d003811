"""Exact time integration of a linear torsional model between samples (numeric core).

The equations of motion of the reflected model (:mod:`crankdyn.torsion.model`),

    M x'' + C x' + K x = f(t),

x the angles of the degrees of freedom (rad), M the diagonal inertia (kg m^2), C and K the
symmetric damping and stiffness matrices (N m s/rad, N m/rad), f the generalised torques (N m),
are integrated *exactly* for a forcing that is linear in time between samples (a first-order
hold): the only approximation is the straight line drawn between two samples of f. There is no
truncation error of a difference scheme, no stability limit on the step, and an undamped line
keeps its energy to rounding (the discrete map is the exact flow of the equations, whose
eigenvalues lie on the unit circle: |exp(i omega h)| = 1).

Method (Nigam and Jennings, "Calculation of response spectra from strong-motion earthquake
records", Bull. Seism. Soc. Am. 59 (2), 1969, 909-922: the exact solution of a linear oscillator
for a piecewise-linear excitation; in the language of exponential integrators, Hochbruck and
Ostermann, "Exponential integrators", Acta Numerica 19, 2010, 209-286, sec. 2.1):

1. *Free bodies.* Each group of degrees of freedom joined by elements (stiffness or damping) and
   held by no grounded element turns as a rigid body: x = 1_c (reflected angles turn together).
   Their uniform rotations, M-normalised, are the columns of G. By default the absolute damping
   of the masses acts on the vibration only (C is replaced by P^T C P, P = I - G G^T M, which
   leaves the damping of every elastic mode unchanged, since P phi = phi for a mode M-orthogonal
   to G): the mean rotation is driven by the applied torques alone (the loads' mean torques are
   applied torques, :mod:`crankdyn.torsion.event_run`). A free body is then a double
   integrator, r'' = G^T f, integrated exactly: for g linear over a step h,
   v_1 = v_0 + h (g_0 + g_1) / 2, r_1 = r_0 + h v_0 + h^2 (g_0 / 3 + g_1 / 6).
2. *The rest* (the elastic modes, and the zero-stiffness relative motions that damping holds,
   e.g. a viscous damper's ring): the undamped modes Phi of K in the M-orthogonal complement of
   G (Phi^T M Phi = I, K Phi = M Phi Omega^2), the modal damping D = Phi^T C Phi (full: the
   damping need not be classical), the first-order system z' = A z + B Phi^T f with
   z = (q, q'), A = [[0, I], [-Omega^2, -D]], diagonalised A = V Lambda V^-1. Every complex
   modal coordinate w_j obeys w' = lambda_j w + u_j(t), whose exact step for u linear is

       w_1 = exp(lambda h) w_0 + h (phi_1(lambda h) - phi_2(lambda h)) u_0 + h phi_2(lambda h) u_1,

   phi_1(z) = (e^z - 1) / z, phi_2(z) = (e^z - 1 - z) / z^2 (series for small |z|). Of each
   conjugate pair only one coordinate is carried (the forcing is real: its partner is its
   conjugate, and the state is twice the real part).

3. *Modal truncation* (:func:`modal_system` with ``max_frequency`` omega_c): only the elastic
   modes up to omega_c are integrated (Phi_k, the lowest eigenpairs of a partial symmetric
   eigen-solve: no eigen-solve of the whole first-order matrix), the modes above respond
   quasi-statically: the mode-acceleration method (R. R. Craig and A. J. Kurdila,
   *Fundamentals of Structural Dynamics*, 2nd ed., Wiley 2006, sec. 14.5; residual
   flexibility),

       x = G r + Phi_k q + R f,   R = sum over the dropped modes phi_j phi_j^T / omega_j^2,

   R formed only in the columns of the loaded dofs (:class:`Residual`), and x' the same with
   f' (the slope of the first-order hold). The kept modes carry the damping of their own
   block, D_k = Phi_k^T C Phi_k, and the damping force of the dropped modes' quasi-static
   rates, -Phi_k^T C R f' (a non-classical damping couples them; the coupling through the
   dropped modes' dynamic part is left out). The error is the dropped modes' dynamic part:
   for a forcing of frequencies up to omega_f below the lowest dropped mode omega_d it is at
   most r^2 / (1 - r^2), r = omega_f / omega_d, of their quasi-static part R f (the steady-state
   amplification of an undamped mode, 1 / (1 - r^2), less one), each mode's (a damped mode's:
   :func:`crankdyn.torsion.event_run.truncation_factor`); a jump of the forcing adds at most
   the quasi-static part of the jump itself in each mode (an undamped mode overshoots a step by
   its static deflection). The modes summed at their own worst are bounded by Cauchy-Schwarz,
   sqrt(t^T R t) sqrt(f^T R f) for a torque pattern t (:mod:`crankdyn.torsion.event_run`).

The recurrence w_k = a w_(k-1) + c_k of every coordinate over a block of samples is evaluated
for all coordinates at once by a blocked scan (:func:`linear_recurrence`): no Python call per
step.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "ModalState",
    "ModalSystem",
    "Residual",
    "free_bodies",
    "linear_recurrence",
    "loaded",
    "modal_system",
    "phi_functions",
]

_SERIES = 1e-2
"""Below this |z| the phi functions are evaluated by their Taylor series (relative error below
1e-16 with eight terms), above it by their closed forms (cancellation below 1e-13)."""


def phi_functions(z: ArrayLike) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
    """phi_1(z) = (e^z - 1) / z and phi_2(z) = (e^z - 1 - z) / z^2, the weights of the exact
    step of w' = lambda w + u for u linear in time (module docstring; Hochbruck and Ostermann
    2010, sec. 2.1).

    Parameters
    ----------
    z : array_like
        lambda h (dimensionless, complex).

    Returns
    -------
    phi1, phi2 : numpy.ndarray
        Complex, the shape of z (dimensionless); phi_1(0) = 1, phi_2(0) = 1/2.

    Examples
    --------
    >>> p1, p2 = phi_functions([0.0, 1.0])
    >>> [round(float(v.real), 12) for v in p1], [round(float(v.real), 12) for v in p2]
    ([1.0, 1.718281828459], [0.5, 0.718281828459])
    """
    z = np.asarray(z, dtype=complex)
    small = np.abs(z) < _SERIES
    zs = np.where(small, 0.0, z)
    with np.errstate(divide="ignore", invalid="ignore"):
        e = np.exp(zs)
        p1 = np.where(small, 0.0, (e - 1.0) / zs)
        p2 = np.where(small, 0.0, (e - 1.0 - zs) / (zs * zs))
    if np.any(small):
        zz = np.where(small, z, 0.0)
        # phi_k(z) = sum_j z^j / (j + k)!
        s1 = np.zeros_like(zz)
        s2 = np.zeros_like(zz)
        for j in range(7, -1, -1):
            s1 = s1 * zz + 1.0 / math.factorial(j + 1)
            s2 = s2 * zz + 1.0 / math.factorial(j + 2)
        p1 = np.where(small, s1, p1)
        p2 = np.where(small, s2, p2)
    return p1, p2


FEW_ROWS_MODES = 200
"""Above this many modes :meth:`ModalSystem.to_physical` of a few dofs forms their rows of
Phi V first (O(dofs) per instant); below it, the modal coordinates q first and then the rows
(the all-dof products' rounding: the same numbers to the last digits)."""

SCAN_BLOCK = 16
"""Samples per block of :func:`linear_recurrence`."""


def linear_recurrence(a: ArrayLike, c: ArrayLike, start: ArrayLike) -> NDArray[np.complex128]:
    """w_k = a w_(k-1) + c_k for k = 1..L, w_0 = ``start``, for many coordinates at once.

    A blocked scan: within blocks of B = :data:`SCAN_BLOCK` samples the sums
    sum_(i <= j) a^(j-i) c_i are one batched product with the blocks' Toeplitz matrices of
    powers of a; the blocks' starts obey the same recurrence with a^B over the blocks' ends,
    solved the same way (log_B L levels); then w = a^(j+1) w_start + the block's sum. Only
    powers a^j with j >= 0 occur, so |a| <= 1 (a stable or undamped coordinate) stays bounded.

    Parameters
    ----------
    a : array_like
        (m,) the coordinates' factors (complex).
    c : array_like
        (L, m) the increments (complex).
    start : array_like
        (m,) w_0.

    Returns
    -------
    numpy.ndarray
        (L, m) w_1 .. w_L.

    Examples
    --------
    >>> w = linear_recurrence([0.5], np.ones((40, 1)), [0.0])
    >>> round(float(w[-1, 0].real), 12), round(2 * (1 - 0.5**40), 12)
    (2.0, 2.0)
    """
    a = np.asarray(a, dtype=complex)
    c = np.asarray(c, dtype=complex)
    w0 = np.asarray(start, dtype=complex)
    count, m = c.shape
    b = SCAN_BLOCK
    if count <= b:
        out = np.empty((count, m), dtype=complex)
        w = w0
        for k in range(count):  # at most B steps, at the deepest level only
            w = a * w + c[k]
            out[k] = w
        return out
    nb = -(-count // b)
    padded = np.zeros((nb * b, m), dtype=complex)
    padded[:count] = c
    blocks = padded.reshape(nb, b, m)
    j = np.arange(b)
    powers = a[None, :] ** np.arange(b + 1)[:, None]  # (B + 1, m): a^0 .. a^B
    lag = j[:, None] - j[None, :]
    toeplitz = np.where((lag >= 0)[None, :, :], powers[np.clip(lag, 0, b)].transpose(2, 0, 1), 0.0)
    # (m, B, B) @ (m, B, nb): one batched product
    local = np.matmul(toeplitz, blocks.transpose(2, 1, 0)).transpose(2, 1, 0)
    starts = np.empty((nb, m), dtype=complex)
    starts[0] = w0
    if nb > 1:
        starts[1:] = linear_recurrence(powers[b], local[:-1, -1, :], w0)
    out = powers[1:][None, :, :] * starts[:, None, :] + local
    return out.reshape(nb * b, m)[:count]


def free_bodies(
    stiffness: NDArray[np.float64], damping: NDArray[np.float64]
) -> list[NDArray[np.int_]]:
    """The groups of degrees of freedom that turn as free rigid bodies: the connected
    components of the elements (nonzero off-diagonal terms of K or C) that no grounded element
    holds (a component whose stiffness and damping row sums vanish, to 1e-12 of the largest
    diagonal term: a grounded element leaves its stiffness there).

    Parameters
    ----------
    stiffness, damping : numpy.ndarray
        K (N m/rad) and C (N m s/rad), (n, n), assembled from elements (every element adds
        v [[1, -1], [-1, 1]], a grounded one v on its diagonal) and absolute dampers (C's
        diagonal).

    Returns
    -------
    list of numpy.ndarray
        The degrees of freedom of every free body (int arrays), in order of their first one.
        Absolute damping alone does not hold a body (it acts on the vibration: module
        docstring), so it is left out of the test.

    Examples
    --------
    >>> k = np.array([[1.0, -1.0, 0.0], [-1.0, 1.0, 0.0], [0.0, 0.0, 2.0]])
    >>> [b.tolist() for b in free_bodies(k, np.zeros((3, 3)))]
    [[0, 1]]
    """
    n = stiffness.shape[0]
    parent = list(range(n))

    def find(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    links = (stiffness != 0.0) | (damping != 0.0)
    rows, cols = np.nonzero(np.triu(links, 1))
    for i, j in zip(rows.tolist(), cols.tolist(), strict=True):
        a, b = find(i), find(j)
        if a != b:
            parent[max(a, b)] = min(a, b)
    roots = np.array([find(i) for i in range(n)])
    scale = float(np.max(np.abs(np.diagonal(stiffness)), initial=0.0))
    out = []
    for root in np.unique(roots):
        dofs = np.flatnonzero(roots == root)
        held = np.abs(stiffness[:, dofs].sum(axis=1)) > 1e-12 * max(scale, 1e-300)
        if not np.any(held):
            out.append(dofs)
    return out


def loaded(forcing: ArrayLike) -> NDArray[np.int_]:
    """The degrees of freedom a forcing (..., n) loads at some instant (its nonzero columns).

    Parameters
    ----------
    forcing : array_like
        (..., n) generalised torques (N m).

    Returns
    -------
    numpy.ndarray
        The loaded dofs (int), ascending.

    Examples
    --------
    >>> loaded([[0.0, 1.0, 0.0], [0.0, 0.0, 0.0]]).tolist()
    [1]
    """
    f = np.asarray(forcing, dtype=float)
    if f.ndim == 0 or f.shape[-1] == 0:
        return np.zeros(0, dtype=int)
    return np.flatnonzero(np.any(f.reshape(-1, f.shape[-1]) != 0.0, axis=0))


@dataclass(frozen=True, eq=False)
class Residual:
    """The residual flexibility of the elastic modes left out of a truncated
    :class:`ModalSystem` (module docstring, "Modal truncation"),

        R = sum over the dropped modes phi_j phi_j^T / omega_j^2 = (I - Psi Psi^T M) F,

    F the static flexibility on the complement of the zero-frequency motions, Psi the carried
    modes and free bodies (M-orthonormal). A column of F is a solve with the shifted stiffness
    K_s = K + alpha M V V^T M (V the zero-frequency motions: K_s x = K x for x M-orthogonal to
    V, and K_s is regular), so only the columns of the loaded dofs are formed (cached).

    Parameters
    ----------
    inertia : numpy.ndarray
        (n,) M's diagonal (kg m^2).
    kept : numpy.ndarray
        (n, r) Psi (kg^-0.5 m^-1).
    factor : tuple
        The LU factors of K_s (:func:`scipy.linalg.lu_factor`).
    modes : numpy.ndarray
        (n, p) the kept elastic modes Phi_k (kg^-0.5 m^-1).
    damping : numpy.ndarray
        (n, n) C (N m s/rad): the damping force of the dropped modes' quasi-static rates on
        the kept modes, Phi_k^T C R f', is carried (:meth:`coupling`).
    """

    inertia: NDArray[np.float64]
    kept: NDArray[np.float64]
    factor: tuple[Any, Any]
    modes: NDArray[np.float64]
    damping: NDArray[np.float64]
    _cols: dict[int, NDArray[np.float64]] = field(
        default_factory=dict, init=False, repr=False, compare=False
    )
    _coupled: dict[int, NDArray[np.float64]] = field(
        default_factory=dict, init=False, repr=False, compare=False
    )
    _stacked: dict[tuple[int, ...], NDArray[np.float64]] = field(
        default_factory=dict, init=False, repr=False, compare=False
    )

    def coupling(self, forcing: ArrayLike) -> NDArray[Any]:
        """Phi_k^T C R f: the damping force (N m, in the kept modes' coordinates) of the
        dropped modes' quasi-static motion R f on the kept modes, for f (..., n) (N m; or
        their rates: the force then in N m per unit speed, as C R f').

        Parameters
        ----------
        forcing : array_like
            (..., n), real or complex.

        Returns
        -------
        numpy.ndarray
            (..., p) (the kept modes' coordinates).
        """
        f = np.asarray(forcing)
        cols = loaded(np.abs(f))
        missing = [int(c) for c in cols if int(c) not in self._coupled]
        if missing:
            block = self.modes.T @ (self.damping @ self.columns(missing))
            for i, c in enumerate(missing):
                self._coupled[c] = block[:, i]
        if cols.size == 0:
            return np.zeros((*f.shape[:-1], self.modes.shape[1]), dtype=f.dtype)
        return f[..., cols] @ np.stack([self._coupled[int(c)] for c in cols], axis=1).T

    def columns(self, cols: ArrayLike) -> NDArray[np.float64]:
        """Columns of R (rad/(N m)) for unit torques at the dofs ``cols``, (n, len(cols)).

        Parameters
        ----------
        cols : array_like
            Degrees of freedom (int).

        Returns
        -------
        numpy.ndarray
            (n, len(cols)).
        """
        from scipy.linalg import lu_solve

        cols = [int(c) for c in np.asarray(cols, dtype=int).ravel()]
        missing = [c for c in cols if c not in self._cols]
        if missing:
            n = self.inertia.size
            unit = np.zeros((n, len(missing)))
            unit[missing, np.arange(len(missing))] = 1.0
            y = lu_solve(self.factor, unit)
            for _ in range(2):  # the carried components off, twice for rounding
                y = y - self.kept @ (self.kept.T @ (self.inertia[:, None] * y))
            for i, c in enumerate(missing):
                self._cols[c] = y[:, i]
        key = tuple(cols)
        if key not in self._stacked:  # the same few columns, block after block
            self._stacked[key] = (
                np.stack([self._cols[c] for c in cols], axis=1)
                if cols
                else np.zeros((self.inertia.size, 0))
            )
        return self._stacked[key]

    def angles(self, forcing: ArrayLike, rows: Any = slice(None)) -> NDArray[np.float64]:
        """R f at the dofs ``rows`` (rad) of torques f (..., n) (N m), (..., len(rows)).

        Parameters
        ----------
        forcing : array_like
            (..., n) generalised torques (N m) (or their rates: R f' in rad/s).
        rows : slice or array_like
            The dofs wanted.

        Returns
        -------
        numpy.ndarray
            (..., len(rows)).
        """
        f = np.asarray(forcing, dtype=float)
        cols = loaded(f)
        return f[..., cols] @ self.columns(cols)[rows].T


@dataclass(frozen=True, eq=False)
class ModalState:
    """The state of a :class:`ModalSystem` in its own coordinates, at one instant or at many.

    Parameters
    ----------
    w : numpy.ndarray
        Complex modal coordinates (..., m) (one per conjugate pair or real eigenvalue).
    r : numpy.ndarray
        Free-body rotations (..., b) (M-normalised coordinates: rad kg^0.5 m).
    rd : numpy.ndarray
        Their rates (..., b).
    """

    w: NDArray[np.complex128]
    r: NDArray[np.float64]
    rd: NDArray[np.float64]

    def last(self) -> ModalState:
        """The state at the last of many instants (this one for a single instant).

        Returns
        -------
        ModalState
            At one instant.
        """
        if self.r.ndim == 1:
            return self
        return ModalState(self.w[-1], self.r[-1], self.rd[-1])


@dataclass(frozen=True, eq=False)
class ModalSystem:
    """The exact propagator of M x'' + C x' + K x = f for f linear between samples (module
    docstring). Built by :func:`modal_system`.

    Parameters
    ----------
    inertia : numpy.ndarray
        (n,) M's diagonal (kg m^2).
    bodies : numpy.ndarray
        (n, b) G: the free bodies' uniform rotations, M-normalised (kg^-0.5 m^-1).
    modes : numpy.ndarray
        (n, p) Phi: the other undamped modes, M-normalised (kg^-0.5 m^-1).
    natural_frequency : numpy.ndarray
        (p,) Omega of ``modes`` (rad/s), ascending.
    eigenvalues : numpy.ndarray
        (m,) lambda of the carried coordinates (1/s): one of each conjugate pair, then the
        real ones.
    weight : numpy.ndarray
        (m,) 2 for a pair (the state is twice the real part), 1 for a real eigenvalue.
    input_gain : numpy.ndarray
        (m, p) rows of V^-1 B: u = input_gain @ (Phi^T f).
    position : numpy.ndarray
        (p, m) rows of V for q; ``velocity`` (p, m) for q'.
    velocity : numpy.ndarray
        (p, m), as ``position``.
    modal_damping : numpy.ndarray
        (p, p) D = Phi^T C Phi (1/s).
    stiffness : numpy.ndarray
        (n, n) K (N m/rad).
    damping : numpy.ndarray
        (n, n) the C integrated (absolute damping projected off the free bodies by default)
        (N m s/rad).
    inverse : numpy.ndarray
        (m, 2p) the carried rows of V^-1 (the modal state of (q, q')).
    residual : Residual or None
        The residual flexibility of the modes left out above ``cutoff`` (module docstring,
        "Modal truncation"); None when every mode is carried.
    cutoff : float
        The cut-off frequency (rad/s): the elastic modes up to it are carried; inf for all.
    dropped : int
        Number of elastic modes left out.
    lowest_dropped : float
        The lowest natural frequency left out (rad/s); inf when none is.
    """

    inertia: NDArray[np.float64]
    bodies: NDArray[np.float64]
    modes: NDArray[np.float64]
    natural_frequency: NDArray[np.float64]
    eigenvalues: NDArray[np.complex128]
    weight: NDArray[np.float64]
    input_gain: NDArray[np.complex128]
    position: NDArray[np.complex128]
    velocity: NDArray[np.complex128]
    modal_damping: NDArray[np.float64]
    stiffness: NDArray[np.float64]
    damping: NDArray[np.float64]
    inverse: NDArray[np.complex128]
    residual: Residual | None = None
    cutoff: float = math.inf
    dropped: int = 0
    lowest_dropped: float = math.inf
    _flex: dict[int, NDArray[np.float64]] = field(
        default_factory=dict, init=False, repr=False, compare=False
    )
    _stacked: dict[tuple[int, ...], NDArray[np.float64]] = field(
        default_factory=dict, init=False, repr=False, compare=False
    )

    @property
    def size(self) -> int:
        """Number of degrees of freedom n."""
        return int(self.inertia.size)

    def to_modal(self, x: ArrayLike, v: ArrayLike) -> ModalState:
        """The modal state of angles x (rad) and rates v (rad/s), each (n,).

        Parameters
        ----------
        x, v : array_like
            Angles (rad) and angular speeds (rad/s) of the degrees of freedom.

        Returns
        -------
        ModalState
            The state in modal coordinates.
        """
        mx = self.inertia * np.asarray(x, dtype=float)
        mv = self.inertia * np.asarray(v, dtype=float)
        z = np.concatenate([self.modes.T @ mx, self.modes.T @ mv])
        return ModalState(self.inverse @ z, self.bodies.T @ mx, self.bodies.T @ mv)

    def to_physical(
        self,
        state: ModalState,
        dofs: ArrayLike | None = None,
        forcing: ArrayLike | None = None,
        rate: ArrayLike | None = None,
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Angles (rad) and rates (rad/s) of a modal state, shape (..., n) each (or
        (..., len(dofs))), with the quasi-static part of the modes left out (module docstring,
        "Modal truncation") when the forcing is given.

        Parameters
        ----------
        state : ModalState
            At one instant or many.
        dofs : array_like or None
            Only these degrees of freedom (int); None: all.
        forcing : array_like or None
            (..., n) the generalised torques at the same instants (N m): the residual
            flexibility's angles R f are added (nothing when every mode is carried).
        rate : array_like or None
            (..., n) their rates (N m/s): R f' is added to the rates.

        Returns
        -------
        x, v : numpy.ndarray
            Angles (rad) and angular speeds (rad/s).
        """
        rows = slice(None) if dofs is None else np.asarray(dofs, dtype=int)
        modes, bodies = self.modes[rows], self.bodies[rows]
        ww = state.w * self.weight
        # Re(w P^T) as two real products: a complex product of a few rows runs far slower in
        # threaded BLAS on a busy machine (thread start-up), the same numbers to rounding
        wr, wi = np.ascontiguousarray(ww.real), np.ascontiguousarray(ww.imag)
        if dofs is not None and modes.shape[1] > FEW_ROWS_MODES:
            # a few dofs: their rows of Phi V first (O(dofs) per instant, not O(modes))
            px, pv = modes @ self.position, modes @ self.velocity
            x = wr @ px.real.T - wi @ px.imag.T + state.r @ bodies.T
            v = wr @ pv.real.T - wi @ pv.imag.T + state.rd @ bodies.T
        else:
            q = wr @ self.position.real.T - wi @ self.position.imag.T
            qd = wr @ self.velocity.real.T - wi @ self.velocity.imag.T
            x = q @ modes.T + state.r @ bodies.T
            v = qd @ modes.T + state.rd @ bodies.T
        if self.residual is not None and forcing is not None:
            x = x + self.residual.angles(forcing, rows)
            if rate is not None:
                v = v + self.residual.angles(rate, rows)
        return x, v

    def flexibility(self, cols: ArrayLike) -> NDArray[np.float64]:
        """Columns of the static flexibility: the twist (rad) under a unit torque (N m) at
        each dof of ``cols`` (K x = P^T f, the free bodies' share taken by their inertia),
        (n, len(cols)); cached per column (the static influence of the few loaded dofs).

        Parameters
        ----------
        cols : array_like
            Degrees of freedom (int).

        Returns
        -------
        numpy.ndarray
            (n, len(cols)) (rad/(N m)).
        """
        cols = [int(c) for c in np.asarray(cols, dtype=int).ravel()]
        missing = [c for c in cols if c not in self._flex]
        if missing:
            omega2 = self.natural_frequency**2
            inverse = np.where(omega2 > 0.0, 1.0 / np.where(omega2 > 0.0, omega2, 1.0), 0.0)
            block = self.modes @ (self.modes[missing].T * inverse[:, None])
            if self.residual is not None:
                block = block + self.residual.columns(missing)
            for i, c in enumerate(missing):
                self._flex[c] = block[:, i]
        key = tuple(cols)
        if key not in self._stacked:
            self._stacked[key] = (
                np.stack([self._flex[c] for c in cols], axis=1)
                if cols
                else np.zeros((self.size, 0))
            )
        return self._stacked[key]

    def static(self, forcing: ArrayLike) -> NDArray[np.float64]:
        """The static twist under generalised torques f (N m), (n,): K x = P^T f, the part of
        f that accelerates the free bodies taken by their inertia (a quasi-static start).

        Parameters
        ----------
        forcing : array_like
            (..., n) generalised torques (N m).

        Returns
        -------
        numpy.ndarray
            (..., n) angles (rad), M-orthogonal to the free bodies.
        """
        f = np.asarray(forcing, dtype=float)
        cols = loaded(f)
        return f[..., cols] @ self.flexibility(cols).T

    def harmonic(self, forcing: ArrayLike, omega: ArrayLike) -> NDArray[np.complex128]:
        """Steady-state amplitudes X of M x'' + C x' + K x = Re(F e^{i omega t}), for every
        frequency: (K - omega^2 M + i omega C) X = F solved in the modal coordinates (the same
        damping as the integration's).

        Parameters
        ----------
        forcing : array_like
            (Q, n) complex amplitudes F (N m).
        omega : array_like
            (Q,) frequencies (rad/s), > 0.

        Returns
        -------
        numpy.ndarray
            (Q, n) complex amplitudes (rad).
        """
        f = np.asarray(forcing, dtype=complex)
        w = np.asarray(omega, dtype=float)
        omega2 = self.natural_frequency**2
        p = omega2.size
        out = np.zeros(f.shape, dtype=complex)
        for i in range(w.size):
            dyn = np.diag(omega2 - w[i] ** 2) + 1j * w[i] * self.modal_damping
            rhs = self.modes.T @ f[i]
            if self.residual is not None:  # the dropped modes' damping force on the kept ones
                rhs = rhs - 1j * w[i] * self.residual.coupling(f[i])
            q = np.linalg.solve(dyn, rhs) if p else np.zeros(0)
            out[i] = self.modes @ q - self.bodies @ (self.bodies.T @ f[i]) / w[i] ** 2
        if self.residual is not None:  # the modes left out: quasi-statically
            out = out + self.residual.angles(f.real) + 1j * self.residual.angles(f.imag)
        return out

    def modal_forcing(
        self, forcing: ArrayLike, rate: ArrayLike | None = None
    ) -> tuple[NDArray[np.complex128], NDArray[np.float64]]:
        """The modal inputs of generalised torques f (N m), shape (..., n).

        Parameters
        ----------
        forcing : array_like
            Generalised torques on the degrees of freedom (N m), (..., n).
        rate : array_like or None
            (..., n) their rates f' (N m/s): with modes left out, the damping force of their
            quasi-static rates R f' on the kept modes, -Phi_k^T C R f', is added (module
            docstring, "Modal truncation").

        Returns
        -------
        u : numpy.ndarray
            (..., m) inputs of the complex coordinates.
        g : numpy.ndarray
            (..., b) accelerations of the free bodies' coordinates.
        """
        f = np.asarray(forcing, dtype=float)
        modal = f @ self.modes
        if self.residual is not None and rate is not None:
            modal = modal - self.residual.coupling(rate)
        return modal @ self.input_gain.T, f @ self.bodies

    def run(
        self,
        start: ModalState,
        u: NDArray[np.complex128],
        g: NDArray[np.float64],
        step: float,
    ) -> ModalState:
        """The states at samples 1..L of L steps of length ``step`` from ``start`` (sample 0),
        the forcing linear between the samples (module docstring).

        Parameters
        ----------
        start : ModalState
            The state at sample 0.
        u, g : numpy.ndarray
            (L + 1, m) and (L + 1, b) modal inputs at samples 0..L (:meth:`modal_forcing`).
        step : float
            The step h (s), > 0.

        Returns
        -------
        ModalState
            At samples 1..L: w (L, m), r and rd (L, b).
        """
        a, b0, b1 = self.coefficients(step)
        w = linear_recurrence(a, b0 * u[:-1] + b1 * u[1:], start.w)
        # free bodies: exact double integration of a piecewise-linear acceleration
        gk, gk1 = g[:-1], g[1:]
        rd = start.rd + np.cumsum(0.5 * step * (gk + gk1), axis=0)
        rd_before = np.concatenate([start.rd[None, :], rd[:-1]])
        r = start.r + np.cumsum(step * rd_before + step * step * (gk / 3.0 + gk1 / 6.0), axis=0)
        return ModalState(w, r, rd)

    def coefficients(
        self, step: float
    ) -> tuple[NDArray[np.complex128], NDArray[np.complex128], NDArray[np.complex128]]:
        """(exp(lambda h), h (phi_1 - phi_2), h phi_2) of every carried coordinate (module
        docstring).

        Parameters
        ----------
        step : float
            h (s).

        Returns
        -------
        a, b0, b1 : numpy.ndarray
            (m,) complex (dimensionless, s, s).
        """
        z = self.eigenvalues * step
        p1, p2 = phi_functions(z)
        return np.exp(z), step * (p1 - p2), step * p2

    def within(
        self,
        start: ModalState,
        u0: NDArray[np.complex128],
        u1: NDArray[np.complex128],
        g0: NDArray[np.float64],
        g1: NDArray[np.float64],
        step: float,
        taus: ArrayLike,
    ) -> ModalState:
        """The states at times ``taus`` (s) into a step of length ``step`` from ``start``, the
        forcing linear from (u0, g0) to (u1, g1) over the step (the same exact solution as
        :meth:`run`: w(tau) = e^{lambda tau} w_0 + u_0 tau phi_1 + (u_1 - u_0) / h tau^2 phi_2).

        Parameters
        ----------
        start : ModalState
            The state at the step's start.
        u0, u1 : numpy.ndarray
            (m,) inputs at the step's ends.
        g0, g1 : numpy.ndarray
            (b,) free-body accelerations at the step's ends.
        step : float
            h (s).
        taus : array_like
            (T,) times into the step (s), 0 <= tau <= h.

        Returns
        -------
        ModalState
            w (T, m), r and rd (T, b).
        """
        tau = np.asarray(taus, dtype=float)[:, None]
        z = self.eigenvalues[None, :] * tau
        p1, p2 = phi_functions(z)
        slope = (u1 - u0) / step
        w = np.exp(z) * start.w + u0 * tau * p1 + slope * tau * tau * p2
        gs = (g1 - g0) / step
        rd = start.rd + g0 * tau + 0.5 * gs * tau * tau
        r = start.r + start.rd * tau + 0.5 * g0 * tau * tau + gs * tau**3 / 6.0
        return ModalState(w, r, rd)


def _orthonormal(inertia: NDArray[np.float64], groups: list[NDArray[np.int_]]) -> np.ndarray:
    """The uniform rotations of ``groups``, M-normalised (n, b) (disjoint groups are
    M-orthogonal)."""
    n = inertia.size
    out = np.zeros((n, len(groups)))
    for c, dofs in enumerate(groups):
        out[dofs, c] = 1.0 / math.sqrt(float(np.sum(inertia[dofs])))
    return out


def modal_system(
    inertia: ArrayLike,
    stiffness: ArrayLike,
    damping: ArrayLike,
    *,
    absolute_damping: str = "vibration",
    max_frequency: float | None = None,
) -> ModalSystem:
    """The exact propagator of a linear model (module docstring).

    Parameters
    ----------
    inertia : array_like
        (n,) inertia of every degree of freedom (kg m^2), > 0.
    stiffness : array_like
        (n, n) K (N m/rad), symmetric.
    damping : array_like
        (n, n) C (N m s/rad), symmetric (the loss factors already as viscous damping).
    absolute_damping : {"vibration", "absolute"}
        ``"vibration"`` (default): the masses' damping acts on the vibration, not on the free
        bodies' mean rotation (module docstring); ``"absolute"``: C as given (a free body with
        absolute damping slows down).
    max_frequency : float or None
        The cut-off (rad/s): only the elastic modes up to it are integrated, those above it
        quasi-statically (module docstring, "Modal truncation"); None (default): every mode.

    Returns
    -------
    ModalSystem
        The propagator.

    Raises
    ------
    ValueError
        For an unknown ``absolute_damping``, or a system whose first-order matrix cannot be
        diagonalised (critical damping to the digit, or a zero-stiffness motion without
        damping).

    Examples
    --------
    An undamped grounded mass: one conjugate pair at omega = 1000 rad/s.

    >>> s = modal_system([1.0], [[1e6]], [[0.0]])
    >>> s.eigenvalues.round(6).tolist(), s.bodies.shape
    ([1000j], (1, 0))
    """
    if absolute_damping not in ("vibration", "absolute"):
        raise ValueError("absolute_damping must be 'vibration' or 'absolute'")
    m = np.asarray(inertia, dtype=float)
    k = np.asarray(stiffness, dtype=float)
    c = np.asarray(damping, dtype=float)
    n = m.size
    # free bodies: the relative damping (off-diagonal terms) joins dofs too, the masses'
    # absolute damping (C's row sums) does not hold a body
    relative = c - np.diag(np.sum(c, axis=1))
    groups = free_bodies(k, relative)
    g = _orthonormal(m, groups)
    if absolute_damping == "vibration" and groups:
        p = np.eye(n) - g @ (g.T * m)  # P = I - G G^T M
        c = p.T @ c @ p
        c = 0.5 * (c + c.T)
    elif groups:
        # a body with absolute damping is not free: it joins the coupled part
        tol = 1e-12 * float(np.max(np.abs(c), initial=0.0))
        slowed = [i for i in range(len(groups)) if np.any(np.abs(c @ g[:, i]) > tol)]
        keep = [i for i in range(len(groups)) if i not in slowed]
        g = g[:, keep]
    b = g.shape[1]
    # the undamped modes in the M-orthogonal complement of G: K shifted on G beyond every mode
    scale = 1.0 / np.sqrt(m)
    ks = k * scale[:, None] * scale[None, :]  # M^-1/2 K M^-1/2
    top = float(np.max(np.sum(np.abs(ks), axis=1), initial=0.0))
    shift = 2.0 * top + 1.0
    gs = g * np.sqrt(m)[:, None]  # orthonormal in the plain inner product
    vals, vecs, lowest = _undamped(ks + shift * (gs @ gs.T), n - b, max_frequency)
    phi = vecs * scale[:, None]  # M-normalised
    residual = None
    if vals.size < n - b:
        residual = _residual(m, k, c, g, phi, vals, top, float(max_frequency or 0.0))
    # a zero-frequency motion (a damper's ring without stiffness) to rounding: exactly zero
    omega2 = np.where(vals > 1e-12 * max(top, 1e-300), vals, 0.0)
    p_count = omega2.size
    d = phi.T @ c @ phi  # the kept block only: the coupling to the modes left out is dropped
    d = 0.5 * (d + d.T)
    a = np.zeros((2 * p_count, 2 * p_count))
    a[:p_count, p_count:] = np.eye(p_count)
    a[p_count:, :p_count] = -np.diag(omega2)
    a[p_count:, p_count:] = -d
    lam, vr = np.linalg.eig(a) if p_count else (np.zeros(0, complex), np.zeros((0, 0), complex))
    lam = np.asarray(lam, dtype=complex)
    vr = np.asarray(vr, dtype=complex)
    if p_count:
        inv = np.linalg.inv(vr)
        if not np.allclose(inv @ vr, np.eye(2 * p_count), atol=1e-8):
            raise ValueError(
                "the model's first-order matrix cannot be diagonalised (critical damping to the "
                "digit, or a motion with neither stiffness nor damping)"
            )
    else:
        inv = np.zeros((0, 0), dtype=complex)
    pair = lam.imag > 0.0
    real = lam.imag == 0.0
    if 2 * int(pair.sum()) + int(real.sum()) != lam.size:  # pragma: no cover - LAPACK pairs
        raise ValueError("unpaired complex eigenvalues")
    sel = np.concatenate([np.flatnonzero(pair), np.flatnonzero(real)])
    weight = np.concatenate([np.full(int(pair.sum()), 2.0), np.ones(int(real.sum()))])
    return ModalSystem(
        inertia=m,
        bodies=g,
        modes=phi,
        natural_frequency=np.sqrt(omega2),
        eigenvalues=lam[sel],
        weight=weight,
        input_gain=inv[sel][:, p_count:],
        position=vr[:p_count][:, sel],
        velocity=vr[p_count:][:, sel],
        modal_damping=d,
        stiffness=k,
        damping=c,
        inverse=inv[sel],
        residual=residual,
        cutoff=math.inf if residual is None else float(max_frequency or 0.0),
        dropped=n - b - p_count,
        lowest_dropped=lowest,
    )


def _undamped(
    shifted: NDArray[np.float64], count: int, max_frequency: float | None
) -> tuple[NDArray[np.float64], NDArray[np.float64], float]:
    """(omega^2, the mass-scaled modes, the lowest natural frequency left out (rad/s), inf
    when none is) of the ``count`` lowest eigenpairs of M^-1/2 K M^-1/2 shifted on the free
    bodies: every mode, or those up to ``max_frequency`` (a partial symmetric eigen-solve: the
    eigenvalues, then the vectors of the lowest ones only)."""
    from scipy.linalg import eigh

    if max_frequency is not None and count > 0:
        cut2 = float(max_frequency) ** 2
        # the pairs up to (2 omega_c)^2: the kept ones and the lowest dropped one (the free
        # bodies, shifted above every mode, come last if at all)
        vals, vecs = eigh(shifted, subset_by_value=(-np.inf, 4.0 * cut2))
        vals, vecs = vals[:count], vecs[:, :count]
        kept = int(np.searchsorted(vals, cut2, side="right"))
        if kept < count:
            # none found up to 2 omega_c: the lowest dropped mode is above it (a lower bound)
            lowest = (
                math.sqrt(max(float(vals[kept]), 0.0))
                if kept < vals.size
                else 2.0 * math.sqrt(cut2)
            )
            return vals[:kept], vecs[:, :kept], lowest
    vals, vecs = np.linalg.eigh(shifted)
    return vals[:count], vecs[:, :count], math.inf


def _residual(
    m: NDArray[np.float64],
    k: NDArray[np.float64],
    c: NDArray[np.float64],
    g: NDArray[np.float64],
    phi: NDArray[np.float64],
    vals: NDArray[np.float64],
    top: float,
    cutoff: float,
) -> Residual:
    """The residual flexibility of the modes left out (:class:`Residual`): K shifted on the
    zero-frequency motions (the free bodies, and the carried modes at zero frequency) by
    alpha = cutoff^2, factorised once."""
    from scipy.linalg import lu_factor

    zero = phi[:, vals <= 1e-12 * max(top, 1e-300)]
    v = np.concatenate([g, zero], axis=1) * m[:, None]  # M V
    alpha = max(cutoff * cutoff, 1e-300)
    factor = lu_factor(k + alpha * (v @ v.T))
    return Residual(m, np.concatenate([g, phi], axis=1), factor, phi, c)
