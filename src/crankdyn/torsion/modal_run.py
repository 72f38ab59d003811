"""Time-domain response of a linear torsional model in truncated modal coordinates (numeric core).

The equations of motion of the reflected model (:mod:`crankdyn.torsion.transient`),

    M x'' + C x' + K x = f(t),

are integrated in the undamped modes of (K, M) up to a cut-off frequency omega_c, the rest of the
response taken quasi-steadily. Every step is exact for the retained modes; there is no Python
call per step and no stability limit on the step, so the work grows linearly with the number of
masses (the modes below omega_c do not multiply when a shaft is subdivided more finely).

1. *Modes.* Phi_r (n, p), M-normalised, Phi_r^T K Phi_r = Omega_r^2, the p modes with
   omega <= omega_c: for a chain by bisection and inverse iteration on the mass-normalised
   tridiagonal matrix (LAPACK ``dstebz``/``dstein`` through ``scipy.linalg.eigh_tridiagonal``,
   O(n p)), otherwise by a dense symmetric solve restricted to the range. The reduced damping
   D_r = Phi_r^T C Phi_r keeps the coupling of the retained modes (the damping need not be
   classical); its first-order form is diagonalised by :func:`crankdyn.torsion.integrator.
   modal_system` (free bodies integrated as double integrators).
2. *Exact steps for a cubic hold.* Between samples t_k and t_k + h the forcing is the cubic
   Hermite interpolant of its values and time derivatives at both ends (error h^4 |f''''| / 384,
   (nu h)^4 / 384 of a harmonic of frequency nu; Burden and Faires, *Numerical Analysis*, 9th
   ed., sec. 3.4). For u(tau) = sum_j c_j tau^j every complex modal coordinate
   w' = lambda w + u has the exact step

       w(h) = exp(lambda h) w(0) + sum_(j=0..3) c_j j! h^(j+1) phi_(j+1)(lambda h),

   phi_k(z) = sum_(i>=0) z^i / (i + k)! (Hochbruck and Ostermann, "Exponential integrators",
   Acta Numerica 19, 2010, 209-286, sec. 2.1: phi_(k+1)(z) = (phi_k(z) - 1/k!) / z), a free
   body's the exact double integral of the cubic. The recurrence over all steps is the blocked
   scan :func:`crankdyn.torsion.integrator.linear_recurrence`.
3. *The residual, quasi-steadily.* For harmonic forcing f = Re sum_q F_q(Omega) exp(i q phi) the
   part of the response the truncated system misses is, in the steady state, exactly
   Delta_q = X_q - Phi_r Y_q, X_q the full system's amplitudes (D(q Omega) X_q = F_q,
   :meth:`crankdyn.torsion.solvers.LinearSystem.solve`) and Y_q the truncated system's; it is
   added at the speed of every sample (the mode-acceleration idea of a residual flexibility
   carried to harmonic forcing with damping: R. R. Craig and A. J. Kurdila, *Fundamentals of
   Structural Dynamics*, 2nd ed., Wiley 2006, sec. 14.5). At constant speed the response is then
   the full system's steady state to the hold's accuracy; in a run-up the quasi-steady part is
   in error only by its own departure from the steady state, which the modes above omega_c
   (more than :data:`CUTOFF_FACTOR` times the highest excitation frequency) follow closely. The
   largest quasi-steady torque over the run, relative to the largest torque
   (:attr:`ModalRun.truncation`), bounds the part of the response not integrated in time and is
   reported with the result.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.torsion.integrator import (
    ModalState,
    ModalSystem,
    linear_recurrence,
    modal_system,
)
from crankdyn.torsion.solvers import LinearSystem

__all__ = [
    "CUTOFF_FACTOR",
    "ModalRun",
    "TruncatedSystem",
    "harmonic_run",
    "hermite_step",
    "phi_functions_4",
    "truncated_system",
]

CUTOFF_FACTOR = 4.0
"""The lower of the two cut-off frequencies of a run as a multiple of the highest excitation
frequency (module docstring; the default omega_c is twice it, the error estimate's run has it):
a mode at 4 times the excitation frequency responds to it within (1/4)^2 / (1 - (1/4)^2) = 6.7 %
of its static response, and above it the quasi-steady part carries it."""

TIME_BLOCK = 4096
"""Steps per block of the integration (the forcing's samples and the modal states of one block
are held at a time: memory bounded by the block, not by the run's length)."""

OUTPUT_BLOCK_BYTES = 1 << 25
"""Bytes of the quasi-steady part's temporaries per block of output samples (32 MiB)."""

_SERIES = 1.0
"""Below this |z| the phi functions are summed as their series (:data:`_TERMS` terms, relative
error below 1e-20), above it by the recurrence from exp(z), which loses no accuracy there."""
_TERMS = 22


def phi_functions_4(z: ArrayLike) -> NDArray[np.complex128]:
    """phi_1 .. phi_4 of z (module docstring), phi_k(z) = sum_i z^i / (i + k)!.

    Parameters
    ----------
    z : array_like
        lambda h (dimensionless, complex), shape (...).

    Returns
    -------
    numpy.ndarray
        (4, ...) complex: phi_1(z), phi_2(z), phi_3(z), phi_4(z); phi_k(0) = 1/k!.

    Examples
    --------
    >>> p = phi_functions_4([0.0, 2.0])
    >>> [round(float(v.real), 12) for v in p[:, 0]]
    [1.0, 0.5, 0.166666666667, 0.041666666667]
    >>> round(float(p[0, 1].real), 12), round((math.exp(2.0) - 1.0) / 2.0, 12)
    (3.194528049465, 3.194528049465)
    """
    z = np.asarray(z, dtype=complex)
    out = np.empty((4, *z.shape), dtype=complex)
    small = np.abs(z) < _SERIES
    zs = np.where(small, 1.0, z)
    with np.errstate(over="ignore", invalid="ignore"):
        p = np.exp(zs)
        for k in range(4):  # phi_(k+1) = (phi_k - 1/k!) / z, phi_0 = exp
            p = (p - 1.0 / math.factorial(k)) / zs
            out[k] = p
    if np.any(small):
        zz = np.where(small, z, 0.0)
        for k in range(4):
            s = np.zeros_like(zz)
            for i in range(_TERMS - 1, -1, -1):
                s = s * zz + 1.0 / math.factorial(i + k + 1)
            out[k] = np.where(small, s, out[k])
    return out


def hermite_step(
    eigenvalues: ArrayLike, step: float
) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
    """The exact step of w' = lambda w + u for u the cubic Hermite interpolant of (u, u') at both
    ends of a step h (module docstring): w(h) = a w(0) + weights @ (u_0, u_0', u_1, u_1').

    With u(tau) = c_0 + c_1 tau + c_2 tau^2 + c_3 tau^3, c_0 = u_0, c_1 = u_0',
    c_2 = (3 (u_1 - u_0) / h - 2 u_0' - u_1') / h, c_3 = (2 (u_0 - u_1) / h + u_0' + u_1') / h^2,
    and b_(j+1) = j! h^(j+1) phi_(j+1)(lambda h), the weights are those of u_0, u_0', u_1, u_1' in
    sum_j c_j b_(j+1).

    Parameters
    ----------
    eigenvalues : array_like
        lambda (1/s), shape (m,), complex.
    step : float
        h (s), > 0.

    Returns
    -------
    a : numpy.ndarray
        (m,) exp(lambda h).
    weights : numpy.ndarray
        (4, m) the weights of u_0 (s), u_0' (s^2), u_1 (s), u_1' (s^2).

    Examples
    --------
    u = 1 from rest on w' = -w: w(h) = 1 - exp(-h).

    >>> a, wt = hermite_step([-1.0], 0.5)
    >>> round(float((wt[0] + wt[2])[0].real), 12), round(1.0 - math.exp(-0.5), 12)
    (0.393469340287, 0.393469340287)
    """
    lam = np.asarray(eigenvalues, dtype=complex)
    h = float(step)
    p = phi_functions_4(lam * h)
    b1, b2, b3, b4 = h * p[0], h * h * p[1], 2.0 * h**3 * p[2], 6.0 * h**4 * p[3]
    weights = np.stack(
        [
            b1 - 3.0 * b3 / h**2 + 2.0 * b4 / h**3,
            b2 - 2.0 * b3 / h + b4 / h**2,
            3.0 * b3 / h**2 - 2.0 * b4 / h**3,
            -b3 / h + b4 / h**2,
        ]
    )
    return np.exp(lam * h), weights


def _body_step(h: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Weights of (g_0, g_0', g_1, g_1') in the exact double integral of the cubic Hermite
    interpolant g over a step h: the change of rate (first row) and of angle beyond
    rd_0 h (second row) (module docstring)."""
    # integral of tau^j over [0, h]: h^(j+1)/(j+1); twice: h^(j+2)/((j+1)(j+2))
    once = np.array([h, h**2 / 2.0, h**3 / 3.0, h**4 / 4.0])
    twice = np.array([h**2 / 2.0, h**3 / 6.0, h**4 / 12.0, h**5 / 20.0])
    # c = T @ (g0, g0', g1, g1')
    t = np.array(
        [
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [-3.0 / h**2, -2.0 / h, 3.0 / h**2, -1.0 / h],
            [2.0 / h**3, 1.0 / h**2, -2.0 / h**3, 1.0 / h**2],
        ]
    )
    return once @ t, twice @ t


@dataclass(frozen=True, eq=False)
class TruncatedSystem:
    """A linear system reduced to its undamped modes up to a cut-off frequency, with the exact
    propagator of the reduced equations (module docstring). Built by :func:`truncated_system`.

    Parameters
    ----------
    modes : numpy.ndarray
        (n, p) Phi_r, M-normalised (kg^-0.5 m^-1).
    natural_frequency : numpy.ndarray
        (p,) Omega_r (rad/s), ascending.
    damping : numpy.ndarray
        (p, p) D_r = Phi_r^T C Phi_r (1/s).
    cutoff : float
        omega_c (rad/s).
    propagator : crankdyn.torsion.integrator.ModalSystem
        The exact propagator of q'' + D_r q' + Omega_r^2 q = Phi_r^T f.
    """

    modes: NDArray[np.float64]
    natural_frequency: NDArray[np.float64]
    damping: NDArray[np.float64]
    cutoff: float
    propagator: ModalSystem

    @property
    def count(self) -> int:
        """The number of retained modes p."""
        return int(self.natural_frequency.size)

    def harmonic(self, forcing: ArrayLike, omega: ArrayLike) -> NDArray[np.complex128]:
        """Steady-state amplitudes of the reduced coordinates under harmonic torques given in
        the reduced coordinates: (Omega_r^2 - omega^2 + i omega D_r) Y = G, by the
        eigenvectors of the first-order form (z = (Y, i omega Y) = V (i omega - Lambda)^-1
        V^-1 (0, G)), or by batched solves where they are ill-conditioned (an undamped rigid
        motion).

        Parameters
        ----------
        forcing : array_like
            (..., p) complex amplitudes G = Phi_r^T F (kg^-0.5 m^-1 N m).
        omega : array_like
            (...) frequencies (rad/s), not 0.

        Returns
        -------
        numpy.ndarray
            (..., p) complex Y (kg^0.5 m rad).

        Examples
        --------
        >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
        >>> from crankdyn.torsion.solvers import linear_system
        >>> model = TorsionModel((Mass("m", 2.0),), (Shaft(("ground", "m"), 8.0, damping=1.0),))
        >>> t = truncated_system(linear_system(model), 10.0, 1.0)
        >>> x = t.modes[0] @ t.harmonic(3.0 * t.modes[0], 1.0)  # X = Phi Y
        >>> round(float(abs(x - 3.0 / (8.0 - 2.0 + 1j))), 12)  # F / (k - omega^2 J + i omega c)
        0.0
        """
        g = np.asarray(forcing, dtype=complex)
        w = np.asarray(omega, dtype=float)
        p = self.count
        if p == 0:
            return np.zeros(g.shape, dtype=complex)
        lam, top, gain = self._first_order
        if lam is not None:
            z = (g @ gain.T) / (1j * w[..., None] - lam)
            return z @ top.T
        dyn = np.diag(self.natural_frequency**2) + 1j * w[..., None, None] * self.damping
        dyn = dyn - (w * w)[..., None, None] * np.eye(p)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            return np.linalg.solve(dyn, g[..., None])[..., 0]

    @cached_property
    def _first_order(
        self,
    ) -> tuple[NDArray[np.complex128] | None, NDArray[np.complex128], NDArray[np.complex128]]:
        """(Lambda, V's rows for Y, V^-1's columns for the torques) of the first-order form
        [[0, I], [-Omega^2, -D_r]]; Lambda None where V is ill-conditioned."""
        p = self.count
        a = np.zeros((2 * p, 2 * p))
        a[:p, p:] = np.eye(p)
        a[p:, :p] = -np.diag(self.natural_frequency**2)
        a[p:, p:] = -self.damping
        lam, v = np.linalg.eig(a)
        if np.linalg.cond(v) > 1e8:  # e.g. a rigid motion without damping: a Jordan block
            return None, np.zeros((0, 0), complex), np.zeros((0, 0), complex)
        inv = np.linalg.inv(v)
        return lam.astype(complex), v[:p].astype(complex), inv[:, p:].astype(complex)

    def leading(self, cutoff: float) -> TruncatedSystem:
        """The system of the retained modes up to a lower cut-off alone.

        Parameters
        ----------
        cutoff : float
            The lower cut-off frequency (rad/s).

        Returns
        -------
        TruncatedSystem
            With the modes up to ``cutoff``, their damping and their own propagator.
        """
        count = int(np.count_nonzero(self.natural_frequency <= cutoff))
        omega2 = self.natural_frequency[:count] ** 2
        d = self.damping[:count, :count]
        return TruncatedSystem(
            modes=self.modes[:, :count],
            natural_frequency=self.natural_frequency[:count],
            damping=d,
            cutoff=float(cutoff),
            propagator=modal_system(
                np.ones(count), np.diag(omega2), d, absolute_damping="absolute"
            ),
        )


def _chain_product(
    lower: NDArray[np.float64], ground: NDArray[np.float64], x: NDArray[np.float64]
) -> NDArray[np.float64]:
    """A @ x for the symmetric tridiagonal matrix of elements ``lower`` (n-1,) between
    neighbours and ``ground`` (n,) to ground (a chain's assembly: off-diagonal -lower, diagonal
    ground plus the links on both sides), x (n, p)."""
    diag = ground.copy()
    diag[:-1] += lower
    diag[1:] += lower
    out = diag[:, None] * x
    out[:-1] -= lower[:, None] * x[1:]
    out[1:] -= lower[:, None] * x[:-1]
    return out


def _undamped_modes(
    system: LinearSystem, cutoff: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(Omega^2 (p,), Phi (n, p)) of the modes of (K, M) with omega <= cutoff (module docstring:
    a chain by bisection and inverse iteration, otherwise a dense solve on the range); round-off
    eigenvalues of the rigid motions (below n eps |K|) set to zero."""
    import scipy.linalg

    j = system.inertia
    scale = 1.0 / np.sqrt(j)
    if system.chain is not None and system.size > 1:
        kb, _, _, kg, _, _ = system.chain
        diag = np.array(kg, dtype=float)
        diag[:-1] += kb
        diag[1:] += kb
        d = diag / j
        e = -kb * scale[:-1] * scale[1:]
        top = float(np.max(np.abs(d)) + 2.0 * np.max(np.abs(e), initial=0.0))
        lam, psi = scipy.linalg.eigh_tridiagonal(
            d, e, select="v", select_range=(-top - 1.0, cutoff * cutoff)
        )
    else:
        ks = system.stiffness * scale[:, None] * scale[None, :]
        top = float(np.max(np.sum(np.abs(ks), axis=1), initial=0.0))
        lam, psi = scipy.linalg.eigh(ks, subset_by_value=(-top - 1.0, cutoff * cutoff))
    lam = np.where(lam <= system.size * np.finfo(float).eps * max(top, 1e-300), 0.0, lam)
    return lam, psi * scale[:, None]


def truncated_system(
    system: LinearSystem, cutoff: float, hysteretic_frequency: float
) -> TruncatedSystem:
    """The system reduced to its modes up to ``cutoff`` with the loss factors as viscous damping
    eta k / omega_h (module docstring).

    Parameters
    ----------
    system : crankdyn.torsion.solvers.LinearSystem
        The model's linear system with its dampers.
    cutoff : float
        omega_c (rad/s), > 0.
    hysteretic_frequency : float
        omega_h (rad/s), > 0.

    Returns
    -------
    TruncatedSystem
        The retained modes and their propagator (the masses' absolute damping acting on the
        rigid motions too, as in the equations).

    Examples
    --------
    Two masses of 1 and 3 kg m^2 on a shaft of 1e5 N m/rad: the rigid mode and the elastic one
    at sqrt(k (1/J_1 + 1/J_2)) = 365.148 rad/s.

    >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
    >>> from crankdyn.torsion.solvers import linear_system
    >>> model = TorsionModel((Mass("a", 1.0), Mass("b", 3.0)), (Shaft(("a", "b"), 1e5),))
    >>> t = truncated_system(linear_system(model), 1e4, 100.0)
    >>> t.count, [round(float(w), 3) for w in t.natural_frequency]
    (2, [0.0, 365.148])
    """
    omega2, phi = _undamped_modes(system, cutoff)
    c_phi: NDArray[np.float64]
    if system.chain is not None and system.size > 1:
        _, cb, hb, _, cg, hg = system.chain
        c_phi = _chain_product(cb + hb / hysteretic_frequency, cg + hg / hysteretic_frequency, phi)
    else:
        c_phi = (system.damping + system.hysteretic / hysteretic_frequency) @ phi
    d = phi.T @ c_phi
    d = 0.5 * (d + d.T)
    p = omega2.size
    propagator = modal_system(np.ones(p), np.diag(omega2), d, absolute_damping="absolute")
    return TruncatedSystem(
        modes=phi,
        natural_frequency=np.sqrt(omega2),
        damping=d,
        cutoff=float(cutoff),
        propagator=propagator,
    )


@dataclass(frozen=True, eq=False)
class ModalRun:
    """The angles of a run at its output samples and the estimate of its truncation error.

    Parameters
    ----------
    angles : numpy.ndarray
        (T, n) reflected angles of the degrees of freedom (rad).
    cutoff : float
        omega_c (rad/s): the modes up to it integrated in time.
    modes : int
        The number of modes integrated in time.
    steps : int
        The number of integration steps (cubic hold between them).
    change : numpy.ndarray
        (T, n) the change of ``angles`` (rad) from the same run with the cut-off halved: the
        estimate of the truncation error (module docstring).
    """

    angles: NDArray[np.float64]
    cutoff: float
    modes: int
    steps: int
    change: NDArray[np.float64]


Samples = Callable[[int, int], tuple[NDArray[np.float64], NDArray[np.float64]]]
"""``forcing_at(k0, k1)``: the generalised torques in the reduced coordinates and their time
derivatives at the samples k0..k1 - 1, (k1 - k0, p) each."""


def _synthesis(
    grid: NDArray[np.float64],
    values: NDArray[np.complex128],
    orders: NDArray[np.float64],
    speed: NDArray[np.float64],
    angle: NDArray[np.float64],
    rate: float,
    derivative: bool,
) -> tuple[NDArray[np.float64], NDArray[np.float64] | None]:
    """Re sum_q V_q(Omega) exp(i q phi) and its time derivative at samples of speed Omega and
    crank angle phi, V (G, Q, k) interpolated linearly over the grid of speeds and held at its
    ends (as :func:`crankdyn.torsion.excitation.interp_complex`): (T, k) each. One product per
    grid interval the samples fall in (the samples of a run lie in few)."""
    phase = np.exp(1j * angle[:, None] * orders[None, :])  # (T, Q)
    spin = 1j * speed[:, None] * orders[None, :] * phase  # d phase / dt
    k = values.shape[2]
    x = np.empty((speed.size, k))
    xd = np.empty((speed.size, k)) if derivative else None
    if grid.size == 1:
        x[:] = (phase @ values[0]).real
        if xd is not None:
            xd[:] = (spin @ values[0]).real
        return x, xd
    i = np.clip(np.searchsorted(grid, speed) - 1, 0, grid.size - 2)
    t = (speed - grid[i]) / (grid[i + 1] - grid[i])
    inside = (t >= 0.0) & (t <= 1.0)
    t = np.clip(t, 0.0, 1.0)[:, None]
    cuts = np.concatenate([[0], np.flatnonzero(np.diff(i)) + 1, [speed.size]])
    for a, b in zip(cuts[:-1].tolist(), cuts[1:].tolist(), strict=True):
        g = int(i[a])
        lo, hi = values[g], values[g + 1]
        ta = t[a:b]
        x[a:b] = ((phase[a:b] * (1.0 - ta)) @ lo + (phase[a:b] * ta) @ hi).real
        if xd is not None:
            slope = (hi - lo) * (rate / (grid[g + 1] - grid[g]))
            moving = (spin[a:b] * (1.0 - ta)) @ lo + (spin[a:b] * ta) @ hi
            xd[a:b] = (moving + (phase[a:b] * inside[a:b, None]) @ slope).real
    return x, xd


def _propagate(
    systems: list[TruncatedSystem],
    starts: list[ModalState],
    forcing_at: Samples,
    count: int,
    step: float,
    stride: int,
) -> list[NDArray[np.float64]]:
    """The reduced coordinates of every system at every ``stride``-th of ``count`` steps
    (sample 0 included; (T, p) each, T = count // stride + 1), all driven by the same forcing
    (each system taking the leading coordinates it has), the steps in blocks of
    :data:`TIME_BLOCK`: memory bounded by a block and the output."""
    outs = count // stride + 1
    block = max(stride, (TIME_BLOCK // stride) * stride)
    coefficients = []
    for system in systems:
        prop = system.propagator
        a, weights = hermite_step(prop.eigenvalues, step)
        coefficients.append((a, weights, prop.modes @ prop.input_gain.T, *_body_step(step)))
    states = [(s.w, s.r, s.rd) for s in starts]
    kept: list[list[ModalState]] = [[s] for s in starts]
    for k0 in range(0, count, block):
        k1 = min(count, k0 + block)
        f_all, fd_all = forcing_at(k0, k1 + 1)  # samples k0..k1, the block's ends
        ks = np.arange(k0 + 1, k1 + 1)
        keep = ks % stride == 0
        for j, system in enumerate(systems):
            prop = system.propagator
            a, weights, to_u, once, twice = coefficients[j]
            f, fd = f_all[:, : system.count], fd_all[:, : system.count]
            w, r, rd = states[j]
            u, ud = f @ to_u, fd @ to_u
            inc = weights[0] * u[:-1] + weights[1] * ud[:-1]
            inc += weights[2] * u[1:] + weights[3] * ud[1:]
            ws = linear_recurrence(a, inc, w)  # samples k0+1..k1
            g, gd = f @ prop.bodies, fd @ prop.bodies
            parts = np.stack([g[:-1], gd[:-1], g[1:], gd[1:]])  # (4, L, b)
            rds = rd + np.cumsum(np.tensordot(once, parts, axes=1), axis=0)
            before = np.concatenate([rd[None, :], rds[:-1]])
            rs = r + np.cumsum(step * before + np.tensordot(twice, parts, axes=1), axis=0)
            kept[j].append(ModalState(ws[keep], rs[keep], rds[keep]))
            states[j] = (ws[-1], rs[-1], rds[-1])
    out = []
    for j, system in enumerate(systems):
        parts_j = kept[j]
        state = ModalState(
            np.concatenate([parts_j[0].w[None, :]] + [s.w for s in parts_j[1:]]),
            np.concatenate([parts_j[0].r[None, :]] + [s.r for s in parts_j[1:]]),
            np.concatenate([parts_j[0].rd[None, :]] + [s.rd for s in parts_j[1:]]),
        )
        q, _ = system.propagator.to_physical(state)
        assert q.shape[0] == outs
        out.append(q)
    return out


def _start(
    system: TruncatedSystem, start: str, g0: NDArray[np.complex128], nu0: NDArray[np.float64]
) -> ModalState:
    """The reduced system's state at rest or in its steady state under the harmonic torques
    g0 (Q, p) at the frequencies nu0 (Q,) (rad/s)."""
    p = system.count
    if start != "steady" or p == 0:
        return system.propagator.to_modal(np.zeros(p), np.zeros(p))
    y0 = system.harmonic(g0[:, :p], nu0)
    q0 = np.real(np.sum(y0, axis=0))
    v0 = np.real(np.sum(1j * nu0[:, None] * y0, axis=0))
    return system.propagator.to_modal(q0, v0)


def harmonic_run(
    system: LinearSystem,
    forcing: ArrayLike,
    grid: ArrayLike,
    orders: ArrayLike,
    speeds: tuple[float, float],
    duration: float,
    hysteretic_frequency: float,
    start: str,
    outputs: int,
    *,
    cutoff: float | None = None,
    rtol: float = 1e-8,
) -> ModalRun:
    """The response of ``system`` to the harmonic torques ``forcing`` over a run at a speed
    linear in time (module docstring), at ``outputs + 1`` samples equally spaced over
    [0, duration].

    The torque is T(t) = Re sum_q F_q(Omega(t)) exp(i q phi(t)), Omega(t) = Omega_0 +
    (Omega_1 - Omega_0) t / t_end, phi(t) = Omega_0 t + (Omega_1 - Omega_0) t^2 / (2 t_end), the
    amplitudes F_q interpolated linearly between the grid's speeds
    (:func:`crankdyn.torsion.transient.transient_response`'s equations). The modes up to
    omega_c are integrated in time, the rest taken quasi-steadily; the same run with the
    cut-off halved gives the estimate of the truncation error (module docstring).

    Parameters
    ----------
    system : crankdyn.torsion.solvers.LinearSystem
        The model's linear system with its dampers.
    forcing : array_like
        (G, Q, n) complex harmonic torques on the degrees of freedom at the grid's speeds (N m).
    grid : array_like
        (G,) speeds (rad/s), ascending.
    orders : array_like
        (Q,) orders (dimensionless).
    speeds : (float, float)
        Omega_0 and Omega_1 (rad/s).
    duration : float
        t_end (s), > 0.
    hysteretic_frequency : float
        omega_h (rad/s): the loss factors as viscous damping eta k / omega_h.
    start : str
        ``"rest"`` or ``"steady"`` (the steady state at Omega_0, module docstring).
    outputs : int
        The number of output intervals (>= 1).
    cutoff : float or None
        omega_c (rad/s); default 2 :data:`CUTOFF_FACTOR` times the highest excitation
        frequency max |q| max(Omega_0, Omega_1).
    rtol : float
        The cubic hold's relative accuracy at the highest excitation frequency nu_max: steps
        h with (nu_max h)^4 / 384 <= rtol (dimensionless), 0 < rtol < 1.

    Returns
    -------
    ModalRun
        The angles of the degrees of freedom (rad) at the output samples and their change
        with the cut-off halved.

    Examples
    --------
    One damped mass started in its steady state at 900 rad/s stays there: the amplitude over a
    cycle is seed 003's T / |k - omega^2 J + i omega c|.

    >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
    >>> from crankdyn.torsion.solvers import linear_system
    >>> model = TorsionModel((Mass("m", 1.0, damping=20.0),), (Shaft(("ground", "m"), 1e6),))
    >>> run = harmonic_run(linear_system(model), [[[100.0 + 0j]]], [900.0], [1.0],
    ...                    (900.0, 900.0), 2 * np.pi / 900.0, 1000.0, "steady", 360)
    >>> exact = 100.0 / abs(1e6 - 900.0**2 + 900j * 20.0)
    >>> round(float(np.max(np.abs(run.angles))) / exact, 8)
    1.0
    """
    f = np.asarray(forcing, dtype=complex)
    grid = np.asarray(grid, dtype=float)
    orders = np.asarray(orders, dtype=float)
    w0, w1 = float(speeds[0]), float(speeds[1])
    rate = (w1 - w0) / duration
    nu_max = float(np.max(np.abs(orders))) * max(w0, w1)
    if cutoff is None:
        cutoff = 2.0 * CUTOFF_FACTOR * nu_max
    fine = truncated_system(system, cutoff, hysteretic_frequency)
    coarse = fine.leading(0.5 * cutoff)
    fr = (f @ fine.modes).astype(complex)  # (G, Q, p): the torques in reduced coordinates
    omega = grid[:, None] * orders[None, :]
    # steps: a whole number per output interval, the hold within rtol at nu_max
    spacing = duration / outputs
    h_max = (384.0 * rtol) ** 0.25 / max(nu_max, 1e-300)
    stride = max(1, math.ceil(spacing / h_max))
    count = outputs * stride
    h = duration / count

    def forcing_at(k0: int, k1: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        t = np.arange(k0, k1) * h
        x, xd = _synthesis(grid, fr, orders, w0 + rate * t, w0 * t + 0.5 * rate * t * t, rate, True)
        assert xd is not None
        return x, xd

    g0 = fr[0] if w0 <= w1 else fr[-1]
    nu0 = orders * w0
    starts = [_start(s, start, g0, nu0) for s in (fine, coarse)]
    q_fine, q_coarse = _propagate([fine, coarse], starts, forcing_at, count, h, stride)
    t_out = np.linspace(0.0, duration, outputs + 1)
    speed_out, angle_out = w0 + rate * t_out, w0 * t_out + 0.5 * rate * t_out * t_out
    # the change with the cut-off halved, in the fine system's coordinates: the integrated
    # modes' difference less the quasi-steady difference of the two truncated responses
    y_fine = fine.harmonic(fr, omega)
    y_coarse = coarse.harmonic(fr[..., : coarse.count], omega)
    y_fine[..., : coarse.count] -= y_coarse
    qs_change, _ = _synthesis(grid, y_fine, orders, speed_out, angle_out, rate, False)
    change = q_fine - qs_change
    change[:, : coarse.count] -= q_coarse
    y_fine[..., : coarse.count] += y_coarse
    residual = _residual(system, fine, f, omega, hysteretic_frequency, y_fine)
    angles = q_fine @ fine.modes.T + _quasi_steady(grid, residual, orders, speed_out, angle_out)
    return ModalRun(
        angles=angles,
        cutoff=float(cutoff),
        modes=fine.count,
        steps=count,
        change=change @ fine.modes.T,
    )


def _residual(
    system: LinearSystem,
    reduced: TruncatedSystem,
    forcing: NDArray[np.complex128],
    omega: NDArray[np.float64],
    hysteretic_frequency: float,
    reduced_response: NDArray[np.complex128],
) -> NDArray[np.complex128]:
    """Delta_q = X_q - Phi_r Y_q on the grid (G, Q, n) (module docstring), the full solves by
    blocks of speeds."""
    out = np.empty(forcing.shape, dtype=complex)
    per_speed = max(1, forcing.shape[1] * forcing.shape[2] * 16 * 2)
    rows = max(1, OUTPUT_BLOCK_BYTES // per_speed)
    for s0 in range(0, forcing.shape[0], rows):
        s1 = min(forcing.shape[0], s0 + rows)
        out[s0:s1] = system.solve(omega[s0:s1], forcing[s0:s1], hysteretic_frequency)
        out[s0:s1] -= reduced_response[s0:s1] @ reduced.modes.T
    return out


def _quasi_steady(
    grid: NDArray[np.float64],
    residual: NDArray[np.complex128],
    orders: NDArray[np.float64],
    speed: NDArray[np.float64],
    angle: NDArray[np.float64],
) -> NDArray[np.float64]:
    """Re sum_q Delta_q(Omega(t)) exp(i q phi(t)) at the output samples (T, n), by blocks of
    samples (:data:`OUTPUT_BLOCK_BYTES`)."""
    n = residual.shape[2]
    out = np.empty((speed.size, n))
    rows = max(1, OUTPUT_BLOCK_BYTES // max(1, residual.shape[1] * n * 16 * 2))
    for k0 in range(0, speed.size, rows):
        k1 = min(speed.size, k0 + rows)
        out[k0:k1], _ = _synthesis(grid, residual, orders, speed[k0:k1], angle[k0:k1], 0.0, False)
    return out
