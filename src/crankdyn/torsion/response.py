"""Steady-state forced torsional response over a speed range, per order and synthesised
(numeric core and analysis).

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

Solving it fast. For a chain (the usual crank train) D is symmetric tridiagonal; all speeds x
orders are solved at once with the chain along the rows of the arrays: elimination without
interchanges (the Thomas algorithm), and for the rare frequencies with a multiplier above 1e8 (a
small pivot) elimination with partial pivoting (LAPACK's ``gtsv`` algorithm,
:func:`solve_tridiagonal`), both vectorised over every frequency and right-hand side, the Python
loop running over the chain's length only. The frequencies go in blocks whose buffers are
allocated once; each row of the dynamic stiffness is built when the elimination reaches it, the
small-pivot test is made exactly only on the systems a cheap filter inside the loop picks (the
same systems flagged as by the test on all of them) and the solved rows go to the result in
tiles while in cache (:class:`_ChainBlocks`). Branched models use numpy's batched dense solve.
No loop over speeds or orders.

Forcing and drivelines. F holds the cylinders' harmonic torques and those of the model's sources
(propellers, electric machines, tabulated sources and further engines at any mass, at orders of
that mass's own speed: :func:`crankdyn.torsion.sources.assemble_forcing`). Couplings whose
stiffness depends on the mean torque take each speed's stiffness
(:func:`crankdyn.torsion.loaded.solve_at_speeds`, still one batched solve); modal damping ratios
add C_modal to C (:mod:`crankdyn.torsion.damped`).

Resolution. By default a sweep is *resolved* (:mod:`crankdyn.torsion.resolve`): the critical
speeds inside the grid's range are added, every damped resonance is sampled across its width
(with the damping, modal damping and, for load-dependent couplings, the stiffness at the
resonance's own speed) and every peak is refined until it is resolved to 0.1 %; each round is
one batched evaluation of the new speeds.

Outputs. Per speed, order and mass the complex amplitude (the actual angle of a geared mass is
its reflected angle times its speed ratio); the vibratory torque of every shaft, the elastic
torque k (theta_b - theta_a) for a shaft between masses a and b (actual stiffness and angles);
the nominal shear stress tau = |T| / W_p with the polar section modulus W_p = pi (D^4 - d^4) /
(16 D) where the shaft's diameters are known. Synthesised over all orders:

- the sum of the order amplitudes sum_q |X_q| (the "vibratory torque" of Mendes et al. 2008,
  an upper bound: every order at its peak at once);
- the time-domain synthesis x(theta) = sum_q Re(X_q exp(i q theta)) over one working cycle (or,
  with sources' orders that are not the engine's, over the orders' common period), its
  peak-to-peak value and half of it, the half-range amplitude that IACS UR M68 limits ("the
  synthesis of all harmonic orders present"). The extremes are found on a grid of at least
  8 points per period of the highest order; every crest of the grid within the grid's error
  bound of its extreme is refined by Newton's method on x'(theta) = 0 (:func:`half_range`).
  Orders without a common period (index above 8192) are bounded by the sum of their amplitudes,
  their supremum (Kronecker's theorem; :func:`crankdyn.torsion.sources.synthesize`).

Dampers (:mod:`crankdyn.torsion.dampers`) add a ring degree of freedom joined to its hub by the
complex stiffness k_d + i (omega c_d + eta_d k_d); a damper at an end of a chain keeps the chain.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Any, Literal, cast

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.errors import InputError, did_you_mean
from crankdyn.results import Result, array, freeze, scalar
from crankdyn.summary import derived
from crankdyn.torsion.dampers import Damper
from crankdyn.torsion.loaded import change_matrix, solve_at_speeds, stiffness_change
from crankdyn.torsion.model import TorsionModel
from crankdyn.torsion.resolve import (
    MAX_ROUNDS,
    TOLERANCE,
    damped_frequency_rows,
    merge_speeds,
    refinement_speeds,
    seed_speeds,
)
from crankdyn.torsion.sources import (
    assemble_forcing,
    check_model_orders,
    forcing_notes,
    line_major,
    source_breakpoints,
    synthesis_index,
    synthesize_at,
)
from crankdyn.torsion.synthesis import half_range
from crankdyn.torsion.tridiagonal import solve_tridiagonal

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from crankdyn.torsion.excitation import Excitation
    from crankdyn.torsion.rules import RuleCheck, RuleSet

__all__ = [
    "QUANTITIES",
    "LinearSystem",
    "Peak",
    "RelativeAngle",
    "ResponseResult",
    "forced_response",
    "half_range",
    "linear_system",
    "solve_tridiagonal",
    "steady_state",
]

from crankdyn.constants import RPM

_FREQUENCY_BLOCK = 1 << 13
"""Frequencies per block of the chain solve: a block's rows (16 bytes x block each) stay in the
processor's cache through the elimination."""


def _abs2(z: NDArray[np.complex128]) -> NDArray[np.float64]:
    """|z|^2 of a complex array."""
    out = np.multiply(z.real, z.real)
    out += z.imag * z.imag
    return out


# ---- the linear system of a model with dampers ------------------------------------------------
@dataclass(frozen=True, eq=False)
class LinearSystem:
    """The reflected equations of motion of a model with its dampers, ready for harmonic solves.

    ``chain`` holds the tridiagonal arrays in chain order (None for a branched system, which
    uses the dense matrices). Degrees of freedom: the model's, with each damper ring added.
    Everything is reflected to the reference (crankshaft) speed: inertias and stiffnesses times
    the squared speed ratio (:mod:`crankdyn.torsion.model`). Built by :func:`linear_system`.

    Parameters
    ----------
    inertia : numpy.ndarray
        (n,) inertia of every degree of freedom (kg m^2).
    stiffness : numpy.ndarray
        (n, n) stiffness matrix K (N m/rad).
    damping : numpy.ndarray
        (n, n) viscous damping matrix C (N m s/rad).
    hysteretic : numpy.ndarray
        (n, n) hysteretic matrix H = sum eta_s K_s (N m/rad).
    chain : tuple of numpy.ndarray or None
        (k_between, c_between, h_between, k_g, c_g, h_g) in dof order: the (n-1,) couplings
        between neighbours and the (n,) row sums (N m/rad, N m s/rad, N m/rad); None for a
        branched system.
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
    stiffness: np.ndarray  # (n, n) N m/rad
    damping: np.ndarray  # (n, n) N m s/rad
    hysteretic: np.ndarray  # (n, n) N m/rad
    chain: tuple[np.ndarray, ...] | None  # (k_between, c_between, h_between, k_g, c_g, h_g)
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
        f = np.asarray(forcing, dtype=complex)
        a = self.matrix(omega, hysteretic_frequency)
        vector = f.ndim == omega.ndim + 1
        b = f[..., None] if vector else f
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            try:
                x = np.linalg.solve(a, b)
            except np.linalg.LinAlgError:  # an undamped system exactly at resonance
                x = np.full(np.broadcast_shapes(a.shape[:-2], b.shape[:-2]) + b.shape[-2:], np.nan)
        return x[..., 0] if vector else x

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
        rows = max(1, _FREQUENCY_BLOCK // max(inner, 1))
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

_TILE = 8
"""Chain rows copied to the result at a time (a cache-friendly transposition)."""


class _ChainBlocks:
    """The chain solve of :meth:`LinearSystem._solve_chain` for one block of frequencies at a
    time, its buffers allocated once (module docstring, "Solving it fast").

    Elimination without interchanges (the Thomas algorithm) with the chain along the rows:
    the negated off-diagonal ``off`` and the diagonal of every row are built inside the forward
    loop, when the row is reached (the same operations in the same order as
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
        self.values = (
            kb.tolist(),
            cb.tolist(),
            hb.tolist(),
            kg.tolist(),
            cg.tolist(),
            hg.tolist(),
            system.inertia.tolist(),
        )
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
        self.term = np.empty(block)
        self.high = np.empty(2 * block)
        self.low = np.empty(2 * block)

    def solve(self, w: NDArray[np.float64], rhs: np.ndarray, out: np.ndarray) -> None:
        """Solve one block into ``out``: w (F,) rad/s, rhs (F, n, r) N m, out (F, n, r)."""
        n = self.n
        count = w.size
        kb, cb, hb, kg, cg, hg, inertia = self.values
        off, d = self.off[:, :count], self.diag[:, :count]
        x = self.x[:, :, :count]
        mult, tmp, tmp_b = self.mult[:count], self.tmp[:count], self.tmp_b[:, :count]
        w2, factor, term = self.w2[:count], self.factor[:count], self.term[:count]
        high, low = self.high[: 2 * count], self.low[: 2 * count]
        np.multiply(w, w, out=w2)
        hysteretic = self.hysteretic
        if hysteretic:
            if self.hysteretic_frequency is None:
                factor.fill(1.0)
            else:
                np.divide(w, self.hysteretic_frequency, out=factor)
        high.fill(0.0)
        low.fill(0.0)
        parts = mult.view(float)  # the multipliers' real and imaginary parts
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            for i in range(n):  # forward elimination: D[i, i-1] = D[i-1, i] = -off[i-1]
                di = d[i]
                if i < n - 1:  # off = k + i (w c + h factor)
                    oi = off[i]
                    oi.real = kb[i]
                    np.multiply(w, cb[i], out=oi.imag)
                    if hysteretic:
                        np.multiply(factor, hb[i], out=term)
                        np.add(oi.imag, term, out=oi.imag)
                np.multiply(w2, inertia[i], out=di.real)  # k_g - w^2 J + i (w c_g + h_g)
                np.subtract(kg[i], di.real, out=di.real)
                np.multiply(w, cg[i], out=di.imag)
                if hysteretic:
                    np.multiply(factor, hg[i], out=term)
                    np.add(di.imag, term, out=di.imag)
                if i < n - 1:
                    np.add(di, off[i], out=di)
                x[i] = rhs[:, i, :].T
                if i == 0:
                    continue
                prev = off[i - 1]
                np.add(di, prev, out=di)
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
                    out[:, i:top] = np.moveaxis(x[i:top], 2, 0)
                    top = i
            if top > 0:  # n == 1
                out[:, :top] = np.moveaxis(x[:top], 2, 0)
        if flagged.size:  # rare: part of the chain at its resonance
            off_k, diag_k = self.system._diagonals_of(w[flagged], self.hysteretic_frequency)
            lower = -off_k.T
            out[flagged] = solve_tridiagonal(lower, diag_k.T, lower, rhs[flagged])

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


def _hyst(h: np.ndarray, w: np.ndarray, hysteretic_frequency: float | None) -> np.ndarray:
    """eta k (in phase with the rate): exact (constant) in the frequency domain, or as viscous
    c = eta k / omega_h frozen at a frequency omega_h (to compare with the time domain)."""
    if hysteretic_frequency is None:
        return h
    return h * (w / hysteretic_frequency)


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
    n0 = model.dof_count
    ratio = model.signed_speed_ratios  # actual angles carry the sense of rotation
    mass_dof = np.array(model.mass_dof)
    chain = model.chain
    shaft_dofs = np.array(model.shaft_dofs)
    k_s, _c_s, _h_s = model._shaft_values()
    elem_ratio = [
        float(ratio[model.index(s.between[0] if s.between[0] != "ground" else s.between[1])])
        for s in model.shafts
    ]
    labels: list[tuple[str, str]] = [s.between for s in model.shafts]
    # ring placement: a ring at an end of a chain keeps the chain (one ring per end)
    chained = chain is not None and modal_damping is None
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
    dof_of_model = np.arange(n0) + shift
    n = n0 + len(dampers)
    ring_dof: dict[int, int] = {}
    if chained:
        if first is not None:
            ring_dof[id(first)] = 0
        if last is not None:
            ring_dof[id(last)] = n0 + shift
    else:
        for j, d in enumerate(dampers):
            ring_dof[id(d)] = n0 + j
    order = list(dampers)

    inertia = np.zeros(n)
    inertia[dof_of_model] = model.dof_inertia
    stiffness = np.zeros((n, n))
    damping = np.zeros((n, n))
    hysteretic = np.zeros((n, n))
    idx = np.ix_(dof_of_model, dof_of_model)
    stiffness[idx] = model.stiffness_matrix()
    damping[idx] = model.damping_matrix()
    if modal_damping is not None:
        from crankdyn.torsion.damped import modal_damping_matrix

        damping[idx] += modal_damping_matrix(model, modal_damping)
    hysteretic[idx] = model.hysteretic_matrix()
    element_dofs = [
        [int(dof_of_model[a]) if a >= 0 else -1, int(dof_of_model[b]) if b >= 0 else -1]
        for a, b in shaft_dofs
    ]
    element_k = list(k_s)
    ring_mass_dof: list[int] = []
    ring_ratio: list[float] = []
    for d in order:
        r = int(ring_dof[id(d)])
        hub_mass = model.index(d.at)
        hub = int(dof_of_model[mass_dof[hub_mass]])
        r2 = float(ratio[hub_mass]) ** 2
        inertia[r] = d.inertia * r2
        for mat, v in (
            (stiffness, d.stiffness * r2),
            (damping, d.damping * r2),
            (hysteretic, d.loss_factor * d.stiffness * r2),
        ):
            mat[r, r] += v
            mat[hub, hub] += v
            mat[r, hub] -= v
            mat[hub, r] -= v
        element_dofs.append([hub, r])
        element_k.append(d.stiffness * r2)
        elem_ratio.append(float(ratio[hub_mass]))
        labels.append((d.at, d.name))
        ring_mass_dof.append(r)
        ring_ratio.append(float(ratio[hub_mass]))
    chain_arrays = None
    if chained:
        sub = np.diagonal(stiffness, 1)
        chain_arrays = (
            -sub.copy(),
            -np.diagonal(damping, 1).copy(),
            -np.diagonal(hysteretic, 1).copy(),
            np.sum(stiffness, axis=1),
            np.sum(damping, axis=1),
            np.sum(hysteretic, axis=1),
        )
        # a chain in dof order must have no other couplings
        off = stiffness - np.diag(np.diagonal(stiffness))
        off -= np.diag(np.diagonal(stiffness, 1), 1) + np.diag(np.diagonal(stiffness, -1), -1)
        if np.any(off != 0.0):  # pragma: no cover - guarded by the placement above
            chain_arrays = None
    masses_dof = np.concatenate([dof_of_model[mass_dof], np.array(ring_mass_dof, dtype=int)])
    masses_ratio = np.concatenate([ratio, np.array(ring_ratio)])
    return LinearSystem(
        inertia=inertia,
        stiffness=stiffness,
        damping=damping,
        hysteretic=hysteretic,
        chain=chain_arrays,
        mass_dof=masses_dof.astype(int),
        mass_ratio=masses_ratio,
        mass_names=tuple(names),
        element_dofs=np.array(element_dofs, dtype=int).reshape(-1, 2),
        element_stiffness=np.array(element_k, dtype=float),
        element_ratio=np.array(elem_ratio, dtype=float),
        element_labels=tuple(labels),
        dampers=tuple(order),
    )


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


# ---- results -----------------------------------------------------------------------------------
_UNIT_KEYS = {"rad": "rad", "N·m": "Nm", "Pa": "Pa", "W": "W"}

QUANTITIES = {
    # name: (item kind, unit, per order, label)
    "amplitude": ("mass", "rad", True, "angular amplitude"),
    "synthesized_amplitude": ("mass", "rad", False, "synthesised half-range amplitude"),
    "order_sum_amplitude": ("mass", "rad", False, "sum of order amplitudes"),
    "peak_to_peak": ("mass", "rad", False, "peak-to-peak angle"),
    "order_shaft_torque": ("shaft", "N·m", True, "shaft torque"),
    "shaft_torque": ("shaft", "N·m", False, "vibratory torque, sum of orders"),
    "synthesized_shaft_torque": ("shaft", "N·m", False, "synthesised half-range torque"),
    "order_shaft_stress": ("shaft", "Pa", True, "nominal shear stress"),
    "shaft_stress": ("shaft", "Pa", False, "nominal shear stress, sum of orders"),
    "synthesized_shaft_stress": ("shaft", "Pa", False, "synthesised half-range shear stress"),
    "damper_power": ("damper", "W", False, "damper power"),
}
"""The quantities :meth:`ResponseResult.peak` knows: (item kind, unit, per order, label)."""


@dataclass(frozen=True)
class Peak(Result):
    """The largest value of a response quantity over the resolved speed range (its speed in
    rad/s, exported in rpm; the value in SI, its unit in ``unit`` and in the JSON key).

    Examples
    --------
    >>> from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
    >>> from crankdyn.torsion.excitation import UniformExcitation
    >>> model = TorsionModel(
    ...     masses=(Mass("m", 1.0, damping=20.0, cylinders=(1,)),),
    ...     shafts=(Shaft(("ground", "m"), 1e6, geometry=ShaftGeometry(0.05)),),
    ... )
    >>> excitation = UniformExcitation(100.0, [0.0], "two-stroke")
    >>> response = forced_response(model, excitation, np.arange(500.0, 1500.0, 130.0), [1.0])
    >>> peak = response.peak("synthesized_shaft_torque")
    >>> peak.item, round(peak.value), peak.unit
    ('ground - m', 5000, 'N·m')
    """

    title = "Peak"
    quantity: str = scalar("quantity", "Quantity", "")
    item: str | None = scalar("item", "Of", "")
    order: float | None = scalar("order", "Order", "", fmt=".4g")
    value: float = scalar("value", "Largest value", "")
    unit: str = scalar("unit", "Unit", "")
    speed: float = scalar("speed_rpm", "At speed", "rpm", RPM, fmt=".6g")
    on_grid: bool = scalar("on_grid", "On the user's speed grid", "")

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict, the value's key naming its unit (``value_rad``, ``value_Nm``,
        ``value_Pa``, ``value_W``).

        Returns
        -------
        dict
            The fields in their exported units (:meth:`crankdyn.results.Result.to_dict`; the
            speed in rpm).
        """
        out = super().to_dict()
        out[f"value_{_UNIT_KEYS.get(self.unit, self.unit)}"] = out.pop("value")
        return out

    def describe(self, scale: float = 1.0, unit: str | None = None, digits: int = 4) -> str:
        """The peak in words: ``"<value> <unit> at <speed> rpm"``.

        Parameters
        ----------
        scale : float
            Factor from the SI value to the unit shown (e.g. 1e3 for mrad).
        unit : str or None
            The unit shown; default the SI unit (``unit``).
        digits : int
            Significant digits of the value.

        Returns
        -------
        str
            The value times ``scale`` with ``digits`` significant digits, its unit and the
            speed (rpm, one decimal).

        Examples
        --------
        >>> from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
        >>> from crankdyn.torsion.excitation import UniformExcitation
        >>> model = TorsionModel(
        ...     masses=(Mass("m", 1.0, damping=20.0, cylinders=(1,)),),
        ...     shafts=(Shaft(("ground", "m"), 1e6, geometry=ShaftGeometry(0.05)),),
        ... )
        >>> excitation = UniformExcitation(100.0, [0.0], "two-stroke")
        >>> response = forced_response(model, excitation, np.arange(500.0, 1500.0, 130.0), [1.0])
        >>> response.peak("amplitude").describe(1e3, "mrad")
        '5 mrad at 9549.3 rpm'
        """
        return f"{self.value * scale:.{digits}g} {unit or self.unit} at {self.speed * RPM:.1f} rpm"


def _peak_of(
    values: ArrayLike,
    speed: np.ndarray,
    on_grid: np.ndarray,
    labels: Sequence[str] | None,
    orders: np.ndarray | None,
    quantity: str,
    unit: str,
    item_label: Callable[[int], str] | None,
) -> Peak:
    """Peak of values (S, Q, I) or (S, I) over speed (and order and item) -> Peak."""
    v = np.asarray(values, dtype=float)
    finite = np.where(np.isfinite(v), v, -np.inf)
    if not np.any(np.isfinite(v)):
        raise InputError(f"no finite values of {quantity}", key="quantity", value=quantity)
    k = int(np.argmax(finite))
    idx = np.unravel_index(k, v.shape)
    order = None
    if v.ndim == 3 and orders is not None:
        order = float(orders[idx[1]])
    if labels is not None:
        item = labels[int(idx[-1])]
    elif item_label is not None:
        item = item_label(int(idx[-1]))
    else:  # pragma: no cover - every caller gives labels or a labeller
        raise ValueError("the peak's item needs labels or a labeller")
    return Peak(
        quantity=quantity,
        item=item,
        order=order,
        value=float(v[idx]),
        unit=unit,
        speed=float(speed[idx[0]]),
        on_grid=bool(on_grid[idx[0]]),
    )


@dataclass(frozen=True)
class RelativeAngle(Result):
    """The relative angle between two masses over the speed range (per order and synthesised),
    e.g. pulley - flywheel, the V6 paper's criterion (seed 003). On a resolved response its
    peaks are resolved too (:meth:`ResponseResult.relative_angle`), so its speeds may add to the
    response's.

    Examples
    --------
    >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
    >>> from crankdyn.torsion.excitation import UniformExcitation
    >>> two = TorsionModel(
    ...     masses=(Mass("a", 1.0, damping=10.0, cylinders=(1,)), Mass("b", 3.0)),
    ...     shafts=(Shaft(("a", "b"), 3e4),),
    ... )
    >>> response = forced_response(
    ...     two, UniformExcitation(100.0, [0.0], "two-stroke"), [100.0, 150.0], [1.0],
    ...     resolve=False,
    ... )
    >>> relative = response.relative_angle("a", "b")
    >>> relative.amplitude.shape, relative.peak().item
    ((2, 1), 'a - b')
    """

    title = "Relative angle"
    between: tuple[str, str] = scalar("between", "Between", "")
    speed: np.ndarray = array("speed_rpm", "Speed", "rpm", RPM)
    amplitude: np.ndarray = array("amplitude_rad", "Amplitude per order", "rad")
    order_sum: np.ndarray = array("order_sum_amplitude_rad", "Sum of order amplitudes", "rad")
    synthesized: np.ndarray = array(
        "synthesized_amplitude_rad", "Synthesised half-range amplitude", "rad"
    )
    orders: np.ndarray | None = array("orders", "Orders", "", default=None)
    on_grid: np.ndarray | None = array("on_grid", "On the user's speed grid", "", default=None)

    FIGURES = (
        derived(
            "max_relative_angle", "max_relative_angle_rad",
            "Largest relative angle (synthesised)", "rad",
            lambda r: _peak_figure(r.peak("synthesized")),
            reduction="max over the resolved speeds", better="min", headline=True,
        ),
    )  # fmt: skip

    def peak(self, quantity: str = "synthesized", order: float | None = None) -> Peak:
        """The largest relative angle and its speed.

        Parameters
        ----------
        quantity : str
            ``"synthesized"`` (default, the half-range amplitude of the synthesis),
            ``"order_sum"`` or ``"amplitude"`` (per order).
        order : float or None
            For ``"amplitude"``: the order; None: the largest over all orders.

        Returns
        -------
        Peak
            The value (rad) and its speed (rad/s).

        Raises
        ------
        InputError
            Naming the key and value: an unknown ``quantity``, an ``order`` not among the
            response's or given for a quantity summed over the orders.

        Examples
        --------
        >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
        >>> from crankdyn.torsion.excitation import UniformExcitation
        >>> two = TorsionModel(
        ...     masses=(Mass("a", 1.0, damping=10.0, cylinders=(1,)), Mass("b", 3.0)),
        ...     shafts=(Shaft(("a", "b"), 3e4),),
        ... )
        >>> response = forced_response(
        ...     two, UniformExcitation(100.0, [0.0], "two-stroke"), [100.0, 150.0], [1.0],
        ...     resolve=False,
        ... )
        >>> found = response.relative_angle("a", "b").peak("amplitude", order=1.0)
        >>> found.quantity, found.order, found.speed
        ('relative_amplitude', 1.0, 150.0)
        """
        on_grid = self.on_grid if self.on_grid is not None else np.ones(self.speed.size, bool)
        label = f"{self.between[0]} - {self.between[1]}"
        if quantity == "amplitude":
            values = np.asarray(self.amplitude)
            orders = np.asarray(self.orders)
            if order is not None:
                k = _order_index(orders, order)
                values, orders = values[:, [k]], orders[[k]]
            return _peak_of(
                values[:, :, None],
                self.speed,
                on_grid,
                [label],
                orders,
                "relative_amplitude",
                "rad",
                None,
            )
        if order is not None:
            raise InputError("only the per-order amplitude has an order", key="order", value=order)
        field_ = {"synthesized": self.synthesized, "order_sum": self.order_sum}.get(quantity)
        if field_ is None:
            raise InputError(
                "expected synthesized, order_sum or amplitude", key="quantity", value=quantity
            )
        return _peak_of(
            np.asarray(field_)[:, None],
            self.speed,
            on_grid,
            [label],
            None,
            f"relative_{quantity}",
            "rad",
            None,
        )


def _peak_figure(peak: Peak | None) -> tuple[float, str] | None:
    """A peak as a key figure's value and where: ``"cylinder 6 - flywheel at 2165 rpm"``."""
    if peak is None:
        return None
    where = f"at {peak.speed * RPM:.6g} rpm"
    return peak.value, f"{peak.item} {where}" if peak.item else where


def _order_index(orders: ArrayLike, order: float) -> int:
    q = np.asarray(orders, dtype=float)
    hit = np.flatnonzero(np.abs(q - float(order)) <= 1e-9 * max(1.0, abs(float(order))))
    if hit.size == 0:
        listed = ", ".join(f"{x:g}" for x in q[:12])
        raise InputError(
            f"order {float(order):g} is not among the response's orders ({listed}"
            + (", ..." if q.size > 12 else "")
            + ")",
            key="order",
            value=order,
        )
    return int(hit[0])


@dataclass(frozen=True)
class ResponseResult(Result):
    """Forced response over a speed range (module docstring): per speed, order and mass the
    angular amplitude; synthesised amplitudes; vibratory torque and nominal shear stress of
    every shaft; damper power; rule check.

    ``speed`` holds the user's grid and, on a resolved sweep (the default), the speeds added to
    resolve every resonance peak (``on_grid`` tells them apart; ``added_speeds`` and
    ``added_reasons`` say why each was added). :meth:`peak` gives the largest value of any
    quantity and its speed on the resolved curve.

    Parameters
    ----------
    mass_response : numpy.ndarray or None
        (S, Q, N) complex amplitudes of the listed masses' actual angles (rad), not exported.
    shaft_response : numpy.ndarray or None
        (S, Q, E) complex torques of the shafts and damper couplings (N m), not exported.
    section_modulus : numpy.ndarray or None
        (E,) polar section modulus W_p of every element (m^3), NaN where the diameters are
        unknown.
    evaluator : _Sweep or None
        The (private) sweep that evaluates the same response at other speeds (:meth:`at`); None on a
        result read back from a file.

    Examples
    --------
    One damped mass J = 1 kg m^2 on k = 1e6 N m/rad, c = 20 N m s/rad, excited by 100 N m at
    order 1 of a two-stroke engine, swept on a 130 rad/s grid:

    >>> from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
    >>> from crankdyn.torsion.excitation import UniformExcitation
    >>> model = TorsionModel(
    ...     masses=(Mass("m", 1.0, damping=20.0, cylinders=(1,)),),
    ...     shafts=(Shaft(("ground", "m"), 1e6, geometry=ShaftGeometry(0.05)),),
    ... )
    >>> excitation = UniformExcitation(100.0, [0.0], "two-stroke")
    >>> response = forced_response(model, excitation, np.arange(500.0, 1500.0, 130.0), [1.0])
    >>> int(response.on_grid.sum()), response.speed.size  # the grid, and speeds added
    (8, 14)
    >>> response.amplitude.shape  # speed x order x mass
    (14, 1, 1)
    """

    title = "Forced response"
    speed: np.ndarray = array("speed_rpm", "Speed", "rpm", RPM)
    orders: np.ndarray = array("orders", "Orders", "")
    major: np.ndarray | None = array("major_orders", "Major order", "")
    """None when the excitation has no firing angles (major orders undetermined)."""
    masses: tuple[str, ...] = scalar("masses", "Masses", "", summary=False)
    shafts: tuple[tuple[str, str], ...] = scalar("shafts", "Shafts", "", summary=False)
    amplitude: np.ndarray = array("amplitude_rad", "Amplitude (speed x order x mass)", "rad")
    synthesized_amplitude: np.ndarray = array(
        "synthesized_amplitude_rad", "Synthesised half-range amplitude (speed x mass)", "rad"
    )
    peak_to_peak: np.ndarray = array("peak_to_peak_rad", "Peak-to-peak angle", "rad")
    order_sum_amplitude: np.ndarray = array(
        "order_sum_amplitude_rad", "Sum of order amplitudes (speed x mass)", "rad"
    )
    order_shaft_torque: np.ndarray = array(
        "order_shaft_torque_Nm", "Shaft torque (speed x order x shaft)", "N·m"
    )
    shaft_torque: np.ndarray = array(
        "shaft_torque_Nm", "Vibratory torque, sum of orders (speed x shaft)", "N·m"
    )
    synthesized_shaft_torque: np.ndarray = array(
        "synthesized_shaft_torque_Nm", "Synthesised half-range shaft torque", "N·m"
    )
    shaft_stress: np.ndarray = array(
        "shaft_stress_Pa", "Nominal shear stress, sum of orders (speed x shaft)", "Pa"
    )
    synthesized_shaft_stress: np.ndarray = array(
        "synthesized_shaft_stress_Pa", "Synthesised half-range shear stress", "Pa"
    )
    damper_power: np.ndarray | None = array(
        "damper_power_W", "Damper power (speed x damper)", "W", default=None
    )
    dampers: tuple[str, ...] | None = scalar("dampers", "Dampers", "", default=None, summary=False)
    model_name: str = scalar("model", "Model", "", default="")
    excitation: str = scalar("excitation", "Excitation", "", default="")
    cycle: str = scalar("cycle", "Cycle", "", default="four-stroke")
    on_grid: np.ndarray | None = array("on_grid", "On the user's speed grid", "", default=None)
    added_speeds: np.ndarray | None = array(
        "added_speeds_rpm", "Speeds added to resolve the peaks", "rpm", RPM, default=None
    )
    added_reasons: tuple[str, ...] | None = scalar(
        "added_speed_reasons", "Why each speed was added", "", default=None, summary=False
    )
    resolved: bool = scalar("resolved", "Peaks resolved", "", default=False)
    tolerance: float | None = scalar(
        "peak_tolerance", "Peaks resolved to (relative)", "", default=None
    )
    rule_check: RuleCheck | None = scalar("rule_check", "Rule check", "", default=None)
    notes: tuple[str, ...] | None = scalar("notes", "Notes", "", default=None)
    mass_response: np.ndarray | None = field(default=None, repr=False, compare=False)
    shaft_response: np.ndarray | None = field(default=None, repr=False, compare=False)
    section_modulus: np.ndarray | None = field(default=None, repr=False, compare=False)
    evaluator: _Sweep | None = field(default=None, repr=False, compare=False)
    """Evaluates the same response at other speeds (:meth:`at`)."""

    # ---- access -------------------------------------------------------------------------------
    @cached_property
    def _mass_index(self) -> dict[str, int]:
        return {name: i for i, name in enumerate(self.masses)}

    def mass_index(self, name: str) -> int:
        """Index of a mass (or damper ring) by name.

        Parameters
        ----------
        name : str
            The mass's or ring's name.

        Returns
        -------
        int
            Its column in the per-mass arrays.

        Raises
        ------
        InputError
            Naming the key ``mass`` and the value (with the nearest names) when there is no
            such mass.

        Examples
        --------
        >>> from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
        >>> from crankdyn.torsion.excitation import UniformExcitation
        >>> model = TorsionModel(
        ...     masses=(Mass("m", 1.0, damping=20.0, cylinders=(1,)),),
        ...     shafts=(Shaft(("ground", "m"), 1e6, geometry=ShaftGeometry(0.05)),),
        ... )
        >>> excitation = UniformExcitation(100.0, [0.0], "two-stroke")
        >>> response = forced_response(model, excitation, np.arange(500.0, 1500.0, 130.0), [1.0])
        >>> response.mass_index("m")
        0
        """
        try:
            return self._mass_index[name]
        except KeyError:
            raise InputError(
                f'no mass named "{name}"{did_you_mean(name, self._mass_index)}',
                key="mass",
                value=name,
            ) from None

    def shaft_index(self, spec: str | Sequence[str]) -> int:
        """Index of a shaft (or damper coupling) by its ends.

        Parameters
        ----------
        spec : str or (str, str)
            The ends as ``(a, b)`` or ``"a - b"``, in either order.

        Returns
        -------
        int
            Its column in the per-shaft arrays.

        Raises
        ------
        InputError
            Naming the key ``shaft`` and the value (with the nearest names) when there is no
            such shaft.

        Examples
        --------
        >>> from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
        >>> from crankdyn.torsion.excitation import UniformExcitation
        >>> model = TorsionModel(
        ...     masses=(Mass("m", 1.0, damping=20.0, cylinders=(1,)),),
        ...     shafts=(Shaft(("ground", "m"), 1e6, geometry=ShaftGeometry(0.05)),),
        ... )
        >>> excitation = UniformExcitation(100.0, [0.0], "two-stroke")
        >>> response = forced_response(model, excitation, np.arange(500.0, 1500.0, 130.0), [1.0])
        >>> response.shaft_index("m - ground"), response.shaft_index(("ground", "m"))
        (0, 0)
        """
        if isinstance(spec, str):
            parts = tuple(p.strip() for p in spec.split(" - ")) if " - " in spec else (spec,)
        else:
            parts = tuple(spec)
        for i, (a, b) in enumerate(self.shafts):
            if parts in ((a, b), (b, a)):
                return i
        labels = [f"{a} - {b}" for a, b in self.shafts]
        text = " - ".join(parts)
        raise InputError(f'no shaft "{text}"{did_you_mean(text, labels)}', key="shaft", value=text)

    def _on_grid(self) -> NDArray[np.bool_]:
        return self.on_grid if self.on_grid is not None else np.ones(self.speed.size, bool)

    def at(self, speeds: ArrayLike) -> ResponseResult:
        """The same response (model, excitation, orders, dampers) at exactly ``speeds``,
        without resolution or rule check.

        Parameters
        ----------
        speeds : array_like
            Crankshaft speeds (rad/s), > 0.

        Returns
        -------
        ResponseResult
            The response at those speeds, in their order.

        Raises
        ------
        ValueError
            When the result has no evaluator (read back from a file).
        InputError
            Naming the key ``speeds`` and the value (rpm) of a speed that is not positive.

        Examples
        --------
        At the undamped natural frequency the single mass's amplitude is T / (c omega):

        >>> from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
        >>> from crankdyn.torsion.excitation import UniformExcitation
        >>> model = TorsionModel(
        ...     masses=(Mass("m", 1.0, damping=20.0, cylinders=(1,)),),
        ...     shafts=(Shaft(("ground", "m"), 1e6, geometry=ShaftGeometry(0.05)),),
        ... )
        >>> excitation = UniformExcitation(100.0, [0.0], "two-stroke")
        >>> response = forced_response(model, excitation, np.arange(500.0, 1500.0, 130.0), [1.0])
        >>> round(float(response.at([1000.0]).amplitude[0, 0, 0]), 12)
        0.005
        """
        if self.evaluator is None:
            raise ValueError("this result cannot be evaluated at other speeds")
        speeds = _check_speeds(speeds)
        return self.evaluator.result(self.evaluator.evaluate(speeds))

    # ---- peaks ----------------------------------------------------------------------------------
    def peak(
        self,
        quantity: str,
        item: str | Sequence[str] | None = None,
        order: float | None = None,
    ) -> Peak:
        """The largest value of a quantity over the speed range and its speed.

        Parameters
        ----------
        quantity : str
            A name of :data:`QUANTITIES` (the field names: ``"synthesized_shaft_stress"``,
            ``"amplitude"``, ...).
        item : str, (str, str) or None
            The mass (or damper ring), shaft (``(a, b)`` or ``"a - b"``) or damper; None: the
            largest over all of them (shafts without diameters left out of stresses).
        order : float or None
            For the per-order quantities (``amplitude``, ``order_shaft_torque``,
            ``order_shaft_stress``): the order; None: the largest over all orders.

        Returns
        -------
        Peak
            The value in the quantity's SI unit (rad, N m, Pa, W) and its speed (rad/s). On a
            resolved response (the default of :func:`forced_response`) the peak is resolved
            to ``tolerance``: a finer sweep changes it by less than that.

        Raises
        ------
        InputError
            Naming the key and value: an unknown ``quantity``, ``item`` or ``order``, an order
            given for a quantity summed over the orders, a quantity with no finite value.

        Examples
        --------
        The peak of a single damped mass, T / (c sqrt(k/J - (c/2J)^2)) (seed 003, the single
        damped mass), found between the grid's speeds to the tolerance 0.1 %:

        >>> from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
        >>> from crankdyn.torsion.excitation import UniformExcitation
        >>> model = TorsionModel(
        ...     masses=(Mass("m", 1.0, damping=20.0, cylinders=(1,)),),
        ...     shafts=(Shaft(("ground", "m"), 1e6, geometry=ShaftGeometry(0.05)),),
        ... )
        >>> excitation = UniformExcitation(100.0, [0.0], "two-stroke")
        >>> response = forced_response(model, excitation, np.arange(500.0, 1500.0, 130.0), [1.0])
        >>> found = response.peak("amplitude", "m")
        >>> exact = 100.0 / (20.0 * math.sqrt(1e6 - 100.0))
        >>> abs(found.value / exact - 1.0) < 1e-3, found.on_grid
        (True, False)
        """
        spec = QUANTITIES.get(quantity)
        if spec is None:
            raise InputError(
                f"expected one of {', '.join(QUANTITIES)}", key="quantity", value=quantity
            )
        kind, unit, per_order, _ = spec
        values = self._quantity_values(quantity)
        if values is None:
            raise InputError(f"the response has no {quantity}", key="quantity", value=quantity)
        orders = np.asarray(self.orders)
        if per_order and order is not None:
            k = _order_index(self.orders, order)
            values, orders = values[:, [k]], orders[[k]]
        elif order is not None:
            raise InputError(
                f"{quantity} is summed over the orders: give no order", key="order", value=order
            )
        if kind == "mass":
            labels = list(self.masses)
            index = None if item is None else self.mass_index(cast(str, item))
        elif kind == "shaft":
            labels = [f"{a} - {b}" for a, b in self.shafts]
            index = None if item is None else self.shaft_index(item)
        else:
            labels = list(self.dampers or ())
            index = None
            if item is not None:
                if item not in labels:
                    raise InputError(f'no damper named "{item}"', key="damper", value=item)
                index = labels.index(item)
        if index is not None:
            values = values[..., [index]]
            labels = [labels[index]]
        return _peak_of(values, self.speed, self._on_grid(), labels, orders, quantity, unit, None)

    def _quantity_values(self, quantity: str) -> np.ndarray | None:
        if quantity == "order_shaft_stress":
            return np.asarray(self.order_shaft_torque) / np.asarray(self.section_modulus)
        return getattr(self, quantity)

    def peaks(self) -> tuple[Peak, ...]:
        """The peaks of the summed and synthesised quantities of every mass, shaft (stresses
        where the diameters are known) and damper: the figures of the response tables.

        Returns
        -------
        tuple of Peak
            Per mass the synthesised and order-sum amplitudes (rad), per shaft the torques
            (N m) and stresses (Pa), per damper the power (W); quantities without a finite
            value left out.

        Examples
        --------
        >>> from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
        >>> from crankdyn.torsion.excitation import UniformExcitation
        >>> model = TorsionModel(
        ...     masses=(Mass("m", 1.0, damping=20.0, cylinders=(1,)),),
        ...     shafts=(Shaft(("ground", "m"), 1e6, geometry=ShaftGeometry(0.05)),),
        ... )
        >>> excitation = UniformExcitation(100.0, [0.0], "two-stroke")
        >>> response = forced_response(model, excitation, np.arange(500.0, 1500.0, 130.0), [1.0])
        >>> [p.quantity for p in response.peaks()][:3]
        ['synthesized_amplitude', 'order_sum_amplitude', 'shaft_torque']
        """
        wanted: list[tuple[str, str | tuple[str, str]]] = [
            (q, name)
            for name in self.masses
            for q in ("synthesized_amplitude", "order_sum_amplitude")
        ]
        for s, shaft in enumerate(self.shafts):
            quantities = ["shaft_torque", "synthesized_shaft_torque"]
            if self.section_modulus is not None and np.isfinite(self.section_modulus[s]):
                quantities += ["shaft_stress", "synthesized_shaft_stress"]
            wanted += [(q, shaft) for q in quantities]
        wanted += [("damper_power", name) for name in self.dampers or ()]
        out = []
        for q, item in wanted:
            try:
                out.append(self.peak(q, item))
            except InputError:  # no finite value (an undamped system exactly at resonance)
                continue
        return tuple(out)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (module docstring), with ``peaks``: :meth:`peaks`.

        Returns
        -------
        dict
            The fields in their exported units (:meth:`crankdyn.results.Result.to_dict`:
            speeds in rpm) and the peaks' dicts (:meth:`Peak.to_dict`).
        """
        out = super().to_dict()
        out["peaks"] = [p.to_dict() for p in self.peaks()]
        return out

    def relative_angle(self, a: str, b: str) -> RelativeAngle:
        """Relative angle theta_a - theta_b per order and synthesised.

        On a resolved response its peaks are resolved as well: speeds are added where they
        need it (the pairs given to :func:`forced_response` as ``relative`` need none).

        Parameters
        ----------
        a, b : str
            The two masses (or damper rings).

        Returns
        -------
        RelativeAngle
            Per speed (rad/s) and order the amplitude, the sum of the order amplitudes and the
            synthesised half-range amplitude (rad).

        Raises
        ------
        InputError
            Naming the key ``mass`` and the value of an unknown mass.
        ValueError
            When the result holds no complex amplitudes (read back from a file).

        Examples
        --------
        >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
        >>> from crankdyn.torsion.excitation import UniformExcitation
        >>> two = TorsionModel(
        ...     masses=(Mass("a", 1.0, damping=10.0, cylinders=(1,)), Mass("b", 3.0)),
        ...     shafts=(Shaft(("a", "b"), 3e4),),
        ... )
        >>> response = forced_response(
        ...     two, UniformExcitation(100.0, [0.0], "two-stroke"), [100.0, 150.0], [1.0],
        ...     resolve=False,
        ... )
        >>> response.relative_angle("a", "b").between
        ('a', 'b')
        """
        if self.mass_response is None:
            raise ValueError("this result holds no complex amplitudes (read from a file?)")
        i, j = self.mass_index(a), self.mass_index(b)
        speed = np.asarray(self.speed)
        on_grid = self._on_grid()
        diff = self.mass_response[:, :, i] - self.mass_response[:, :, j]
        index = synthesis_index(self.orders, self.cycle)
        top, low = synthesize_at(diff, index)
        if self.resolved and self.evaluator is not None:
            for _ in range(MAX_ROUNDS):
                amp = np.abs(diff)
                values = np.column_stack([amp, amp.sum(axis=1), 0.5 * (top - low)])
                new, _ = refinement_speeds(speed, values, tolerance=self.tolerance or TOLERANCE)
                if new.size == 0:
                    break
                x = self.evaluator.evaluate(new).x
                more = x[:, :, i] - x[:, :, j]
                t2, l2 = synthesize_at(more, index)
                speed, first = merge_speeds(speed, new)
                diff = np.concatenate([diff, more])[first]
                top = np.concatenate([top, t2])[first]
                low = np.concatenate([low, l2])[first]
                on_grid = np.concatenate([on_grid, np.zeros(new.size, bool)])[first]
        return RelativeAngle(
            between=(a, b),
            speed=freeze(speed),
            amplitude=freeze(np.abs(diff)),
            order_sum=freeze(np.sum(np.abs(diff), axis=1)),
            synthesized=freeze(0.5 * (top - low)),
            orders=freeze(self.orders),
            on_grid=freeze(on_grid, dtype=bool),
        )

    def plot(
        self,
        what: str = "amplitude",
        item: str | Sequence[str] | None = None,
        fig: Figure | None = None,
        **kw: Any,
    ) -> Figure:
        """Response against speed per order and synthesised
        (:func:`crankdyn.plots.torsion_response.plot_response`).

        Parameters
        ----------
        what : str
            ``"amplitude"`` (mass ``item``, default the first), ``"torque"`` or ``"stress"``
            (shaft ``item``, default the one with the largest torque), ``"relative"``
            (``item = (a, b)``).
        item : str, (str, str) or None
            The mass, shaft or pair drawn.
        fig : matplotlib.figure.Figure or None
            A figure to draw into; default a new one.
        **kw
            Passed to :func:`~crankdyn.plots.torsion_response.plot_response`.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.torsion_response import plot_response

        return plot_response(self, what=what, item=item, fig=fig, **kw)

    def plot_stress_limits(self, fig: Figure | None = None) -> Figure:
        """Synthesised shaft stress against the rule limits (needs a rule check;
        :func:`crankdyn.plots.torsion_response.plot_stress_limits`).

        Parameters
        ----------
        fig : matplotlib.figure.Figure or None
            A figure to draw into; default a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.torsion_response import plot_stress_limits

        return plot_stress_limits(self, fig=fig)

    # ---- the key figures (crankdyn.summary): peaks on the resolved curve --------------------
    @property
    def model_shafts(self) -> tuple[tuple[str, str], ...]:
        """The model's own shafts (the dampers' couplings, which follow them, left out)."""
        return self.shafts[: len(self.shafts) - len(self.dampers or ())]

    def largest_peak(self, quantity: str, items: Sequence[Any] | None = None) -> Peak | None:
        """The largest resolved peak of a synthesised quantity over items (default: the model's
        own shafts for a shaft quantity, every mass for an amplitude); None where no item has
        a finite value (no diameters for a stress, an undamped line at a resonance).

        Parameters
        ----------
        quantity : str
            A quantity of :meth:`peak` (``"synthesized_shaft_torque"``...).
        items : sequence or None
            The masses or shafts.

        Returns
        -------
        Peak or None
            The largest peak, naming its item and speed.
        """
        if items is None:
            items = self.model_shafts if "shaft" in quantity else self.masses
        found = []
        for item in items:
            try:
                found.append(self.peak(quantity, item))
            except InputError:  # no finite value of this item
                continue
        return max(found, key=lambda p: p.value) if found else None

    def most_loaded_shaft(self) -> tuple[str, str]:
        """The model's shaft with the largest synthesised vibratory torque over the resolved
        sweep: the shaft a torque plot shows by default.

        Raises
        ------
        InputError
            If no shaft has a finite torque.
        """
        peak = self.largest_peak("synthesized_shaft_torque")
        if peak is None or peak.item is None:
            raise InputError("no shaft has a finite vibratory torque", key="torque")
        return cast("tuple[str, str]", tuple(self.shafts[self.shaft_index(peak.item)]))

    def most_stressed_shaft(self) -> tuple[str, str]:
        """The model's shaft (with diameters) with the largest synthesised shear stress over the
        resolved sweep: the shaft a stress plot shows by default.

        Raises
        ------
        InputError
            If no shaft has diameters.
        """
        peak = self.largest_peak("synthesized_shaft_stress")
        if peak is None or peak.item is None:
            raise InputError(
                "no shaft of the torsional model has diameters (outer_diameter): no stress",
                key="stress",
            )
        return cast("tuple[str, str]", tuple(self.shafts[self.shaft_index(peak.item)]))

    FIGURES = (
        derived(
            "max_shaft_torque", "max_shaft_torque_Nm",
            "Largest vibratory shaft torque (synthesised)", "N·m",
            lambda r: _peak_figure(r.largest_peak("synthesized_shaft_torque")),
            reduction="max over the shafts and the resolved speeds", better="min",
            headline=True,
        ),
        derived(
            "max_shaft_stress", "max_shaft_stress_Pa",
            "Largest shaft shear stress (synthesised)", "Pa",
            lambda r: _peak_figure(r.largest_peak("synthesized_shaft_stress")),
            reduction="max over the shafts with diameters and the resolved speeds",
            better="min", headline=True,
        ),
        derived(
            "max_free_end_amplitude", "max_free_end_amplitude_rad",
            "Largest amplitude of the first mass (synthesised)", "rad",
            lambda r: _peak_figure(r.largest_peak("synthesized_amplitude", r.masses[:1])),
            reduction="max over the resolved speeds", better="min",
        ),
        derived(
            "max_damper_power", "max_damper_power_W", "Largest damper power", "W",
            lambda r: None if r.damper_power is None else _peak_figure(r.peak("damper_power")),
            reduction="max over the dampers and the resolved speeds", better="min",
        ),
        derived(
            "max_stress_ratio", "max_stress_ratio",
            "Largest shaft stress / permissible τ_C (IACS UR M68)", "",
            lambda r: None if r.rule_check is None else r.rule_check.max_ratio(),
            reduction="max over the checked shafts and speeds", better="min",
        ),
    )  # fmt: skip

    # ---- CSV: one row per speed -----------------------------------------------------------------
    def columns(self) -> dict[str, np.ndarray]:
        """One row per speed, every speed (the peaks included); ``on_grid`` is 1 on the user's
        grid, 0 at the speeds added to resolve the peaks.

        Returns
        -------
        dict of str to numpy.ndarray
            {key: values}: the speed (rpm), ``on_grid``, and per mass and shaft the summed and
            synthesised amplitudes (rad), torques (N m) and stresses (Pa, where the diameters
            are known), in the unit the key names.

        Examples
        --------
        >>> from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
        >>> from crankdyn.torsion.excitation import UniformExcitation
        >>> model = TorsionModel(
        ...     masses=(Mass("m", 1.0, damping=20.0, cylinders=(1,)),),
        ...     shafts=(Shaft(("ground", "m"), 1e6, geometry=ShaftGeometry(0.05)),),
        ... )
        >>> excitation = UniformExcitation(100.0, [0.0], "two-stroke")
        >>> response = forced_response(model, excitation, np.arange(500.0, 1500.0, 130.0), [1.0])
        >>> list(response.columns())[:3]
        ['speed_rpm', 'on_grid', 'synthesized_amplitude_rad.m']
        """
        out = {"speed_rpm": np.asarray(self.speed) * RPM}
        out["on_grid"] = self._on_grid().astype(int)
        for i, name in enumerate(self.masses):
            out[f"synthesized_amplitude_rad.{name}"] = self.synthesized_amplitude[:, i]
        for i, name in enumerate(self.masses):
            out[f"order_sum_amplitude_rad.{name}"] = self.order_sum_amplitude[:, i]
        for s, (a, b) in enumerate(self.shafts):
            out[f"shaft_torque_Nm.{a} - {b}"] = self.shaft_torque[:, s]
        for s, (a, b) in enumerate(self.shafts):
            out[f"synthesized_shaft_torque_Nm.{a} - {b}"] = self.synthesized_shaft_torque[:, s]
        for s, (a, b) in enumerate(self.shafts):
            if np.all(np.isfinite(self.shaft_stress[:, s])):
                out[f"shaft_stress_Pa.{a} - {b}"] = self.shaft_stress[:, s]
                out[f"synthesized_shaft_stress_Pa.{a} - {b}"] = self.synthesized_shaft_stress[:, s]
        return out

    def column_labels(self) -> dict[str, tuple[str, str]]:
        """Label and unit of every column of :meth:`columns`.

        Returns
        -------
        dict of str to (str, str)
            {column key: (label, unit)}.
        """
        out = {}
        for key in self.columns():
            if key == "speed_rpm":
                out[key] = ("Speed", "rpm")
                continue
            if key == "on_grid":
                out[key] = ("On the speed grid", "")
                continue
            head, name = key.split(".", 1)
            unit = head.rsplit("_", 1)[1].replace("Nm", "N·m")
            out[key] = (f"{head.rsplit('_', 1)[0].replace('_', ' ')} {name}", unit)
        return out


def _check_speeds(speeds: ArrayLike) -> NDArray[np.float64]:
    s = np.atleast_1d(np.asarray(speeds, dtype=float))
    if s.ndim != 1 or s.size == 0:
        raise InputError("the speed range is empty", key="speeds")
    if not np.all(np.isfinite(s)) or np.any(s <= 0.0):
        bad = s[~(np.isfinite(s) & (s > 0.0))][0]
        raise InputError("speeds must be positive", key="speeds", value=float(bad) * RPM)
    return s


# ---- the sweep: the response at any speeds -------------------------------------------------
@dataclass(frozen=True, eq=False)
class _Block:
    """The response at a set of speeds (rows)."""

    speed: np.ndarray  # (S,) rad/s
    x: np.ndarray  # (S, Q, N) complex actual angles of the listed masses
    torque: np.ndarray  # (S, Q, E) complex element torques
    power: np.ndarray | None  # (S, D)
    top: np.ndarray  # (S, N + E + P) largest value over the cycle: masses, elements, pairs
    low: np.ndarray  # (S, N + E + P) smallest

    def merged(self, other: _Block) -> tuple[_Block, np.ndarray]:
        """Both blocks' rows in ascending speed (a speed in both once) and the row of the
        concatenation each row came from."""
        speed, first = merge_speeds(self.speed, other.speed)

        def cat(a: np.ndarray, b: np.ndarray) -> np.ndarray:
            return np.concatenate([a, b])[first]

        return (
            _Block(
                speed=speed,
                x=cat(self.x, other.x),
                torque=cat(self.torque, other.torque),
                power=None
                if self.power is None or other.power is None
                else cat(self.power, other.power),
                top=cat(self.top, other.top),
                low=cat(self.low, other.low),
            ),
            first,
        )


class _Sweep:
    """Everything of a forced response that does not depend on the speed, and its evaluation
    at any speeds (one batched solve)."""

    def __init__(
        self,
        model: TorsionModel,
        excitation: Excitation,
        orders: NDArray[np.float64],
        dampers: Iterable[Damper],
        hysteretic_frequency: float | None,
        pairs: Iterable[tuple[int, int]],
        modal_damping: ArrayLike | None = None,
    ) -> None:
        self.model = model
        self.excitation = excitation
        self.orders = orders
        self.hysteretic_frequency = hysteretic_frequency
        self.system = system = linear_system(model, dampers, modal_damping)
        # harmonic indices over the orders' common period (None: none short enough, the
        # synthesis is the sum of the amplitudes; crankdyn.torsion.sources.synthesize)
        self.synthesis = synthesis_index(orders, excitation.cycle)
        self.n_shafts = len(model.shafts)
        modulus = np.full(len(system.element_labels), np.nan)
        for s, shaft in enumerate(model.shafts):
            if shaft.geometry is not None:
                modulus[s] = shaft.geometry.section_modulus
        self.modulus = modulus
        self.pairs = tuple(pairs)
        self.major = line_major(excitation, orders)
        # (mode, order, critical speed) of the undamped resonances in the range (:meth:`seeds`)
        self.unbounded: list[tuple[int, float, float]] = []

    # ---- evaluation ---------------------------------------------------------------------------
    def evaluate(self, speeds: ArrayLike) -> _Block:
        """The response at ``speeds`` (rad/s): one batched solve over speeds x orders."""
        speeds = np.asarray(speeds, dtype=float)
        system = self.system
        orders = self.orders
        # harmonic torques of the cylinders and of the model's sources (crankdyn.torsion.sources)
        forcing, _ = assemble_forcing(self.model, system, self.excitation, speeds, orders)
        omega = speeds[:, None] * orders[None, :]
        # each speed with its couplings' stiffness at that speed's mean torque, where it depends
        # on it (crankdyn.torsion.loaded; otherwise system.solve and the model's stiffness)
        x_dof, k = solve_at_speeds(
            self.model, system, speeds, omega, forcing, self.hysteretic_frequency
        )
        # actual angles of the listed masses (signed speed ratios: the sense of rotation)
        x = x_dof[:, :, system.mass_dof] * system.mass_ratio[None, None, :]
        # element torques: k_actual (theta_b - theta_a)_actual = k_ref/r (dX_ref)
        ends = system.element_dofs
        xa = np.where(ends[:, 0] >= 0, x_dof[:, :, np.maximum(ends[:, 0], 0)], 0.0)
        xb = np.where(ends[:, 1] >= 0, x_dof[:, :, np.maximum(ends[:, 1], 0)], 0.0)
        twist = xb - xa
        torque = k * twist
        n_shafts = self.n_shafts
        power = None
        if system.dampers:
            ratio = system.element_ratio[n_shafts:]
            coupling = np.stack([d.complex_stiffness(omega) for d in system.dampers], axis=-1) * (
                ratio**2 / ratio
            )
            torque[:, :, n_shafts:] = coupling * twist[:, :, n_shafts:]
            actual_twist = twist[:, :, n_shafts:] * ratio
            power = np.sum(
                np.stack(
                    [d.power(omega, actual_twist[:, :, j]) for j, d in enumerate(system.dampers)],
                    axis=-1,
                ),
                axis=1,
            )
        parts = [x, torque]
        if self.pairs:
            i = np.array([p[0] for p in self.pairs])
            j = np.array([p[1] for p in self.pairs])
            parts.append(x[:, :, i] - x[:, :, j])
        top, low = synthesize_at(np.moveaxis(np.concatenate(parts, axis=2), 1, -1), self.synthesis)
        return _Block(speed=speeds, x=x, torque=torque, power=power, top=top, low=low)

    # ---- the curves whose peaks are resolved ----------------------------------------------------
    def tracked(self, block: _Block) -> tuple[np.ndarray, np.ndarray]:
        """(values (S, C), scale (C,)): every reported curve (per order, summed, synthesised:
        mass amplitudes, element torques (the stresses are proportional), damper power, the
        tracked relative angles) and the value each one's tolerance is relative to
        (:meth:`scale`)."""
        values, bounds = self._values(block)
        return values, self.scale(values, bounds)

    @staticmethod
    def scale(values: np.ndarray, bounds: np.ndarray) -> np.ndarray:
        """Per curve its largest value, at least 1e-9 of its family's largest (columns
        ``bounds[k]:bounds[k+1]``), so that curves at round-off level ask for no refinement."""
        top = np.max(values, axis=0) if values.shape[0] else np.zeros(values.shape[1])
        family = np.maximum.reduceat(top, bounds[:-1]) if top.size else top
        floor = np.repeat(1e-9 * family, np.diff(bounds))
        return np.maximum(top, floor)

    def _values(self, block: _Block) -> tuple[np.ndarray, np.ndarray]:
        """The tracked curves (S, C) and the column bounds of their families."""
        s = block.speed.size
        n, e = block.x.shape[2], block.torque.shape[2]
        ax = np.abs(block.x)
        at = np.abs(block.torque)
        half = 0.5 * (block.top - block.low)
        families = [
            ax.reshape(s, -1),
            ax.sum(axis=1),
            half[:, :n],
            at.reshape(s, -1),
            at.sum(axis=1),
            half[:, n : n + e],
        ]
        if block.power is not None:
            families.append(block.power)
        if self.pairs:
            i = np.array([p[0] for p in self.pairs])
            j = np.array([p[1] for p in self.pairs])
            rel = np.abs(block.x[:, :, i] - block.x[:, :, j])
            families += [rel.reshape(s, -1), rel.sum(axis=1), half[:, n + e :]]
        families = [f for f in families if f.shape[1]]
        bounds = np.concatenate([[0], np.cumsum([f.shape[1] for f in families])])
        return np.concatenate(families, axis=1), bounds

    def describe(self, column: int, block: _Block) -> str:
        """Which curve a column of :meth:`tracked` is (for the added speeds' reasons)."""
        q_count = self.orders.size
        n, e = block.x.shape[2], block.torque.shape[2]
        names = self.system.mass_names
        elements = [f"{a} - {b}" for a, b in self.system.element_labels]
        dampers = [d.name for d in self.system.dampers]
        pairs = [f"{names[i]} - {names[j]}" for i, j in self.pairs]
        layout = [
            ("angular amplitude", q_count * n, lambda k: _per_order(k, n, names, self.orders)),
            ("sum of order amplitudes", n, lambda k: names[k]),
            ("synthesised amplitude", n, lambda k: names[k]),
            ("torque", q_count * e, lambda k: _per_order(k, e, elements, self.orders)),
            ("vibratory torque (sum of orders)", e, lambda k: elements[k]),
            ("synthesised torque", e, lambda k: elements[k]),
        ]
        if block.power is not None:
            layout.append(("damper power", len(dampers), lambda k: dampers[k]))
        if self.pairs:
            p = len(pairs)
            layout += [
                ("relative angle", q_count * p, lambda k: _per_order(k, p, pairs, self.orders)),
                ("relative angle, sum of orders", p, lambda k: pairs[k]),
                ("relative angle, synthesised", p, lambda k: pairs[k]),
            ]
        for label, size, name in layout:
            if column < size:
                return f"{label}, {name(column)}"
            column -= size
        return "response"  # pragma: no cover

    # ---- resonances ----------------------------------------------------------------------------
    def _rigid_count(self) -> int:
        """Zero natural frequencies of the system: the rigid-body mode of a free model and one
        per damper ring joined by a viscous film only."""
        viscous = sum(1 for d in self.system.dampers if d.stiffness == 0.0)
        return (1 if self.model.is_free else 0) + viscous

    def undamped(self) -> np.ndarray:
        """The elastic undamped natural frequencies (rad/s) of the system with its damper
        rings, ascending: mode r is row r - 1 (docs/conventions.md)."""
        import scipy.linalg  # here, not at start-up (the command line's help imports this module)

        system = self.system
        if system.chain is not None and system.size > 1:
            kb, _, _, kg, _, _ = system.chain
            diag = np.array(kg, dtype=float)
            diag[:-1] += kb
            diag[1:] += kb
            j = system.inertia
            lam = scipy.linalg.eigvalsh_tridiagonal(diag / j, -kb / np.sqrt(j[:-1] * j[1:]))
        else:
            lam = scipy.linalg.eigh(system.stiffness, np.diag(system.inertia), eigvals_only=True)
        lam = np.sort(lam)[self._rigid_count() :]
        return np.sqrt(np.maximum(lam, 0.0))

    def _damping(self) -> tuple[np.ndarray, np.ndarray]:
        """(C, H) of the poles: the system's viscous and hysteretic damping matrices, the loss
        factors as viscous eta k / omega_h when the sweep freezes them at omega_h."""
        system = self.system
        c, h = system.damping, system.hysteretic
        if self.hysteretic_frequency is not None:
            c = c + h / self.hysteretic_frequency
            h = np.zeros_like(h)
        return c, h

    def poles(self, top: float) -> np.ndarray:
        """Damped natural frequencies a + i b (rad/s) with a <= top (module
        :mod:`crankdyn.torsion.resolve`), with the model's stiffness (load-dependent couplings
        at their reference torque): the quadratic eigenproblem for systems of up to
        :data:`POLE_LIMIT` degrees of freedom, else the undamped modes with the modal damping
        of their shapes (b_r = phi^T (H + omega_r C) phi / (2 omega_r phi^T M phi))."""
        w = self._pole_rows(self.system.stiffness, *self._damping())
        w = w[np.isfinite(w)]
        return np.sort_complex(w[w.real <= top])

    def _pole_rows(self, stiffness: np.ndarray, c: np.ndarray, h: np.ndarray) -> np.ndarray:
        """Damped natural frequencies of systems with the stiffness matrices (..., n, n) (the
        system's mass and damping c, h, broadcast): (..., P) complex, ascending in the real
        part, NaN-padded (:meth:`poles`)."""
        system = self.system
        if system.size <= POLE_LIMIT:
            return damped_frequency_rows(system.inertia, stiffness, c, h)
        j = np.sqrt(system.inertia)
        lam, psi = np.linalg.eigh(stiffness / j[:, None] / j[None, :])
        lam, psi = lam[..., self._rigid_count() :], psi[..., self._rigid_count() :]
        phi = psi / j[:, None]  # mass-normalised mode shapes
        omega = np.sqrt(np.maximum(lam, 0.0))
        modal_h = np.einsum("...ir,...ij,...jr->...r", phi, h, phi)
        modal_c = np.einsum("...ir,...ij,...jr->...r", phi, c, phi)
        with np.errstate(divide="ignore", invalid="ignore"):
            b = (modal_h + omega * modal_c) / (2.0 * np.maximum(omega, 1e-300))
        return np.where(omega > 0.0, omega + 1j * np.abs(b), np.nan)

    def _loaded_change(self, speeds: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
        """(ends, delta, eta) of the load-dependent couplings at reference speeds (rad/s)
        (:func:`crankdyn.torsion.loaded.stiffness_change`), or None."""
        found = stiffness_change(self.model, self.system, speeds)
        return None if found is None else found[:3]

    def loaded_poles(self, speeds: ArrayLike) -> np.ndarray:
        """Damped natural frequencies (rad/s) with the load-dependent couplings' stiffness at
        the mean torque of every speed (rad/s): (S, P), NaN-padded, ascending (:meth:`poles`;
        the forced response takes the same stiffness at that speed)."""
        speeds = np.asarray(speeds, dtype=float)
        found = self._loaded_change(speeds)
        if found is None:  # pragma: no cover - called only with load-dependent couplings
            raise ValueError("no coupling of the model depends on the load")
        ends, delta, eta = found
        size = self.system.size
        c, h = self._damping()
        k = self.system.stiffness + change_matrix(ends, delta, size)
        if self.hysteretic_frequency is None:
            h = h + change_matrix(ends, delta * eta, size)
        else:
            c = c + change_matrix(ends, delta * eta / self.hysteretic_frequency, size)
        return self._pole_rows(k, c, h)

    def _tracked_resonances(
        self, poles: np.ndarray, orders: np.ndarray, low: float, high: float
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The resonances of the damped modes with the load-dependent couplings' stiffness at
        the resonance's own speed: for every pole p (at the reference torque) and order q, the
        speed n with Re a_p(n) = q n, a_p(n) the pole at the stiffness of speed n (clipped to
        the range, beyond which the load laws give no stiffness), found by the secant method
        from the fixed-point step n = Re a_p(n0) / q, all pairs at once, each iteration one
        batched eigenproblem; the pole followed from speed to speed as the one nearest in
        frequency. Returns (centre (rad/s), half width (rad/s), pole frequency (rad/s), order
        index) of the pairs whose resonance lies within two half widths of the range."""
        rows = self.loaded_poles([low, high])  # (2, P)

        def follow(rows_at: np.ndarray, previous: np.ndarray) -> np.ndarray:
            gap = np.abs(rows_at.real - previous[:, None])
            k = np.argmin(np.where(np.isnan(gap), np.inf, gap), axis=1)
            return rows_at[np.arange(k.size), k]  # NaN where there is no pole at all

        # candidates: a pole p at the reference torque, followed to both ends of the range
        p_ref = poles
        at_low = follow(np.broadcast_to(rows[0], (p_ref.size, rows.shape[1])), p_ref.real)
        at_high = follow(np.broadcast_to(rows[1], (p_ref.size, rows.shape[1])), p_ref.real)
        q = orders[None, :]
        g_low = at_low.real[:, None] - q * low + 2.0 * np.abs(at_low.imag)[:, None]
        g_high = at_high.real[:, None] - q * high - 2.0 * np.abs(at_high.imag)[:, None]
        with np.errstate(invalid="ignore"):
            p_idx, q_idx = np.nonzero((g_low >= 0.0) & (g_high <= 0.0))
        if p_idx.size == 0:
            return np.zeros(0), np.zeros(0), np.zeros(0), np.zeros(0, dtype=int)
        q_sel = orders[q_idx]
        # start: the resonance interpolated between the ends, then one fixed-point step
        lo_f, hi_f = at_low.real[p_idx], at_high.real[p_idx]
        gl, gh = lo_f - q_sel * low, hi_f - q_sel * high
        with np.errstate(divide="ignore", invalid="ignore"):
            t = np.clip(np.where(gl != gh, gl / (gl - gh), 0.5), 0.0, 1.0)
        n0 = low + t * (high - low)
        track = lo_f + t * (hi_f - lo_f)

        def step(
            n: np.ndarray, track: np.ndarray, which: np.ndarray
        ) -> tuple[np.ndarray, np.ndarray]:
            """The followed poles and g = Re a - q n at speeds n of the pairs ``which``."""
            at = np.clip(np.where(np.isfinite(n), n, low), low, high)
            a = follow(self.loaded_poles(at), track)
            return a, a.real - q_sel[which] * n

        every = np.arange(q_sel.size)
        a0, g0 = step(n0, track, every)
        n1 = a0.real / q_sel
        a1, g1 = step(n1, a0.real, every)
        for _ in range(TRACK_ITERATIONS):
            # converged, or lost (no pole to follow): no further evaluation
            active = np.flatnonzero(
                np.isfinite(n1) & np.isfinite(g1) & (np.abs(n1 - n0) > 1e-9 * np.abs(n1))
            )
            if active.size == 0:
                break
            m0, m1, h0, h1 = n0[active], n1[active], g0[active], g1[active]
            with np.errstate(divide="ignore", invalid="ignore"):
                secant = m1 - h1 * (m1 - m0) / (h1 - h0)
            # a secant step that fails (flat or non-finite) falls back to the fixed point
            fixed = a1.real[active] / q_sel[active]
            m2 = np.where(np.isfinite(secant) & (h1 != h0), secant, fixed)
            a2, h2 = step(m2, a1.real[active], active)
            n0, g0 = n1.copy(), g1.copy()
            n1[active], g1[active], a1[active] = m2, h2, a2
        centre = a1.real / q_sel
        width = np.maximum(np.abs(a1.imag), 1e-6 * a1.real) / q_sel
        with np.errstate(invalid="ignore"):
            near = (centre + 2.0 * width >= low) & (centre - 2.0 * width <= high)
        return centre[near], width[near], a1.real[near], q_idx[near]

    def seeds(self, grid: np.ndarray, low: float, high: float) -> tuple[np.ndarray, list[str]]:
        """The critical speeds (undamped modes x orders) inside [low, high] and the speeds
        that sample every damped resonance across its width (resolve module, step 1), with a
        reason for each: (speeds (rad/s), reasons). The critical speeds are the Campbell
        diagram's (the model's stiffness: load-dependent couplings at their reference torque);
        with load-dependent couplings the damped resonances are followed to the coupling
        stiffness at their own speed (:meth:`_tracked_resonances`), where the forced response
        has them."""
        orders = self.orders
        omega = self.undamped()
        poles = self.poles(float(np.max(orders)) * high * 1.5)
        # a mode without damping (its pole on the real axis) has an unbounded resonance: its
        # critical speeds are not evaluated (the solve would be singular) but noted
        free = poles.real[np.abs(poles.imag) <= 1e-9 * poles.real]
        undamped = np.zeros(omega.size, dtype=bool)
        if free.size and omega.size:
            gap = np.min(np.abs(omega[:, None] - free[None, :]), axis=1)
            undamped = gap <= 1e-6 * omega
        crit = omega[:, None] / orders[None, :]
        inside = (crit >= low) & (crit <= high)
        self.unbounded = [
            (int(a) + 1, float(orders[b]), float(crit[a, b]))
            for a, b in zip(*np.nonzero(inside & undamped[:, None]), strict=True)
        ]
        r, q = np.nonzero(inside & ~undamped[:, None])
        crit_speeds = crit[r, q]
        crit_reasons = [
            f"critical speed: mode {int(a) + 1} x order {orders[b]:g}"
            for a, b in zip(r, q, strict=True)
        ]
        poles = poles[np.abs(poles.imag) > 1e-9 * poles.real]
        if self._loaded_change([low]) is None:
            centre = poles.real[:, None] / orders[None, :]
            width = np.maximum(np.abs(poles.imag), 1e-6 * poles.real)[:, None] / orders[None, :]
            near = (centre + 2.0 * width >= low) & (centre - 2.0 * width <= high)
            p, q2 = np.nonzero(near)
            centre, width, frequency = centre[p, q2], width[p, q2], poles.real[p]
            loaded = ""
        else:
            centre, width, frequency, q2 = self._tracked_resonances(poles, orders, low, high)
            loaded = ", couplings at that speed's mean torque"
        points, which = seed_speeds(np.concatenate([grid, crit_speeds]), centre, width, low, high)
        seed_reasons = [
            f"resonance sampling: {frequency[k] / (2 * math.pi):.4g} Hz x order "
            f"{orders[q2[k]]:g}{loaded}"
            for k in which
        ]
        kinks = np.concatenate(
            [
                np.asarray(getattr(self.excitation, "breakpoints", lambda: ())(), dtype=float),
                source_breakpoints(self.model),
            ]
        )
        kinks = kinks[(kinks > low) & (kinks < high)]
        return (
            np.concatenate([crit_speeds, points, kinks]),
            crit_reasons
            + seed_reasons
            + ["excitation breakpoint (a point of a load curve, trace or source table)"]
            * kinks.size,
        )

    # ---- results ------------------------------------------------------------------------------
    def result(self, block: _Block, **extra: Any) -> ResponseResult:
        """The ResponseResult of a block (``extra``: the resolution fields and notes)."""
        n, e = block.x.shape[2], block.torque.shape[2]
        x, torque = block.x, block.torque
        shaft_torque = np.sum(np.abs(torque), axis=1)
        synth_torque = 0.5 * (block.top[:, n : n + e] - block.low[:, n : n + e])
        ptp = block.top[:, :n] - block.low[:, :n]
        system = self.system
        return ResponseResult(
            speed=freeze(block.speed),
            orders=freeze(self.orders),
            major=None if self.major is None else freeze(self.major, dtype=bool),
            masses=system.mass_names,
            shafts=system.element_labels,
            amplitude=freeze(np.abs(x)),
            synthesized_amplitude=freeze(0.5 * ptp),
            peak_to_peak=freeze(ptp),
            order_sum_amplitude=freeze(np.sum(np.abs(x), axis=1)),
            order_shaft_torque=freeze(np.abs(torque)),
            shaft_torque=freeze(shaft_torque),
            synthesized_shaft_torque=freeze(synth_torque),
            shaft_stress=freeze(shaft_torque / self.modulus),
            synthesized_shaft_stress=freeze(synth_torque / self.modulus),
            damper_power=None if block.power is None else freeze(block.power),
            dampers=tuple(d.name for d in system.dampers) or None,
            model_name=self.model.name,
            excitation="; ".join(
                [self.excitation.description] + [src.describe() for src in self.model.sources]
            ),
            cycle=self.excitation.cycle,
            mass_response=x,
            shaft_response=torque,
            section_modulus=self.modulus,
            evaluator=self,
            **extra,
        )


TRACK_ITERATIONS = 30
"""Secant iterations at most when following a resonance to its load-dependent coupling
stiffness (each one batched eigenproblem; they converge superlinearly, in a few)."""

POLE_LIMIT = 200
"""Largest system (degrees of freedom) whose damped natural frequencies are found by the
quadratic eigenproblem; above it the undamped modes with modal damping are used."""


def _per_order(k: int, count: int, names: Sequence[str], orders: np.ndarray) -> str:
    return f"{names[k % count]}, order {orders[k // count]:g}"


def forced_response(
    model: TorsionModel,
    excitation: Excitation,
    speeds: ArrayLike,
    orders: ArrayLike,
    *,
    dampers: Sequence[Damper] | None = None,
    hysteretic_frequency: float | None = None,
    rules: RuleSet | Literal[False] | None = None,
    resolve: bool = True,
    tolerance: float = TOLERANCE,
    relative: Iterable[tuple[str, str]] | None = None,
    modal_damping: ArrayLike | None = None,
) -> ResponseResult:
    """Steady-state forced response of ``model`` to ``excitation`` over a speed range.

    The dynamic-stiffness equation D(q Omega) X = F for every speed and order (seed 003, the
    V6 paper's eqs. 1, 2 and 6), its synthesis over the orders and the shafts' torques and
    nominal stresses (module docstring); the peaks resolved by :mod:`crankdyn.torsion.resolve`.

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The torsional model (masses carrying cylinders are the excitation points).
    excitation : EngineExcitation or UniformExcitation
        :class:`~crankdyn.torsion.excitation.EngineExcitation` or
        :class:`~crankdyn.torsion.excitation.UniformExcitation` (see
        :func:`~crankdyn.torsion.excitation.excitation_for`).
    speeds : array_like
        Crankshaft speeds (rad/s), > 0: the user's grid.
    orders : array_like
        Orders to solve (multiples of the cycle's fundamental order, or orders of the model's
        sources).
    dampers : sequence of Damper or None
        Dampers to add (:class:`~crankdyn.torsion.dampers.Damper`); None: the model's own
        (``model.dampers``); ``()``: none (the response without them).
    hysteretic_frequency : float or None
        None (default): loss factors as exact hysteretic damping. A frequency omega_h (rad/s):
        loss factors as viscous damping eta k / omega_h (the time-domain equivalent).
    rules : RuleSet, False or None
        A :class:`~crankdyn.torsion.rules.RuleSet` to check the synthesised stresses against;
        None: the model's own (``model.rules``) when it has one; False: no check.
    resolve : bool
        True (default): add the critical speeds inside the grid's range and refine around
        every resonance until the peak of every reported quantity is resolved to
        ``tolerance`` (:mod:`crankdyn.torsion.resolve`); the result's speeds are the sorted
        union of the grid and the added speeds. False: exactly the given speeds, in their
        order (for comparisons on a fixed grid).
    tolerance : float
        Relative change of a peak below which it counts as resolved (dimensionless, default
        0.1 %), 0 < tolerance < 1.
    relative : iterable of (str, str) or None
        Pairs of masses (a, b) whose relative angle is resolved with the rest (in the same
        batched rounds); any other pair is resolved when asked for
        (:meth:`ResponseResult.relative_angle`).
    modal_damping : float, array_like or None
        Damping ratios of the elastic modes (one for all, or one per mode) added to the model's
        damping as C_modal (:mod:`crankdyn.torsion.damped`, as openTorsion's ``C_modal``), or
        None. The damped-resonance sampling of a resolved sweep includes it.

    Returns
    -------
    ResponseResult
        Amplitudes (rad), torques (N m), stresses (Pa) and damper power (W) per speed
        (rad/s); ``speed``, ``on_grid``, ``added_speeds`` and ``added_reasons``;
        :meth:`~ResponseResult.peak` for the largest value of any quantity; ``rule_check``.

    Raises
    ------
    InputError
        Naming the key and value: an empty speed range or a speed that is not positive
        (``speeds``), orders the model cannot take (``orders``), a tolerance outside (0, 1),
        an unknown mass in ``relative``, excitation points the model lacks, dampers and modal
        damping as :func:`linear_system`, and the rule check's errors
        (:func:`crankdyn.torsion.rules.check_rules`).

    Examples
    --------
    One damped mass on a grounded shaft swept on a 130 rad/s grid: the peak of the resolved
    response is the single damped mass's, T / (c sqrt(k/J - (c/2J)^2)) (seed 003), to the
    tolerance; the grid alone misses it by more than half.

    >>> from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
    >>> from crankdyn.torsion.excitation import UniformExcitation
    >>> model = TorsionModel(
    ...     masses=(Mass("m", 1.0, damping=20.0, cylinders=(1,)),),
    ...     shafts=(Shaft(("ground", "m"), 1e6, geometry=ShaftGeometry(0.05)),),
    ... )
    >>> excitation = UniformExcitation(100.0, [0.0], "two-stroke")
    >>> grid = np.arange(500.0, 1500.0, 130.0)
    >>> exact = 100.0 / (20.0 * math.sqrt(1e6 - 100.0))
    >>> resolved = forced_response(model, excitation, grid, [1.0])
    >>> abs(resolved.peak("amplitude").value / exact - 1.0) < 1e-3
    True
    >>> on_grid = forced_response(model, excitation, grid, [1.0], resolve=False)
    >>> round(on_grid.peak("amplitude").value / exact, 2)
    0.44
    """
    speeds = _check_speeds(speeds)
    orders = check_model_orders(model, excitation, orders)
    if not (math.isfinite(tolerance) and 0.0 < tolerance < 1.0):
        raise InputError("the tolerance must lie between 0 and 1", key="tolerance", value=tolerance)
    if dampers is None:
        dampers = getattr(model, "dampers", ()) or ()
    system_names = list(model.mass_names) + [d.name for d in dampers]
    pairs: list[tuple[int, int]]
    if relative is None:
        pairs = []
    else:
        pairs = []
        for a, b in relative:
            for name in (a, b):
                if name not in system_names:
                    raise InputError(
                        f'no mass named "{name}"{did_you_mean(name, system_names)}',
                        key="relative",
                        value=name,
                    )
            pairs.append((system_names.index(a), system_names.index(b)))
    # the excitation points are checked (cylinders on the masses, sources) before any solve
    forcing_notes(model, excitation, speeds[:1], orders)
    sweep = _Sweep(model, excitation, orders, dampers, hysteretic_frequency, pairs, modal_damping)
    extra: dict[str, Any]
    notes: list[str]
    if not resolve:
        block = sweep.evaluate(speeds)
        extra = {"on_grid": freeze(np.ones(speeds.size), dtype=bool)}
        notes = []
    else:
        block, extra, notes = _resolved(sweep, speeds, tolerance)
    # notes of the cylinders' and sources' excitation over every evaluated speed
    notes = list(forcing_notes(model, excitation, block.speed, orders)) + notes
    result = sweep.result(block, notes=tuple(notes) or None, **extra)
    if rules is None:
        rules = getattr(model, "rules", None)
    if rules is not None and rules is not False:
        from crankdyn.torsion.rules import check_rules

        engine = getattr(excitation, "engine", None)
        fallback = getattr(engine, "speed", None)
        operating: Any = getattr(model, "operating", None)
        if fallback is None and operating is not None:
            fallback = operating.rated
        object.__setattr__(result, "rule_check", check_rules(result, rules, model, fallback))
    return result


def _resolved(
    sweep: _Sweep, speeds: np.ndarray, tolerance: float
) -> tuple[_Block, dict[str, Any], list[str]]:
    """Evaluate the grid, the critical speeds and the resonance seeds, then refine until every
    peak is resolved (module :mod:`crankdyn.torsion.resolve`): (block, resolution fields,
    notes)."""
    grid, _ = merge_speeds(speeds)
    low, high = float(grid[0]), float(grid[-1])
    seeds, seed_reasons = (np.zeros(0), []) if grid.size < 2 else sweep.seeds(grid, low, high)
    start, first = merge_speeds(grid, seeds)
    reasons_all = [""] * grid.size + seed_reasons
    reason = [reasons_all[k] for k in first]
    block = sweep.evaluate(start)
    values, bounds = sweep._values(block)
    notes = []
    unbounded = getattr(sweep, "unbounded", [])
    if unbounded:
        listed = ", ".join(f"mode {r} x order {q:g} at {w * RPM:.1f} rpm" for r, q, w in unbounded)
        notes.append(
            f"undamped resonances (no damping acts on the mode: the steady response is unbounded "
            f"there; the peaks next to them are not refined): {listed}"
        )
    for _ in range(MAX_ROUNDS):
        scale = sweep.scale(values, bounds)
        new, column = refinement_speeds(
            block.speed, values, scale, tolerance, exclude=[w for _, _, w in unbounded]
        )
        if new.size == 0:
            break
        labels = [f"refinement: peak of {sweep.describe(int(c), block)}" for c in column]
        more = sweep.evaluate(new)
        block, first = block.merged(more)
        values = np.concatenate([values, sweep._values(more)[0]])[first]
        combined = reason + labels
        reason = [combined[k] for k in first]
    else:
        notes.append(
            f"the peaks were refined {MAX_ROUNDS} times and some are still not resolved to "
            f"{tolerance * 100:g} %"
        )
    on_grid = np.isin(block.speed, grid)
    added = np.flatnonzero(~on_grid)
    if added.size:
        notes.append(
            f"{added.size} speeds added to the grid (critical speeds and refinement around the "
            f"resonances) so that every peak is resolved to {tolerance * 100:g} %: see "
            "added_speeds"
        )
    extra = {
        "on_grid": freeze(on_grid, dtype=bool),
        "added_speeds": freeze(block.speed[added]),
        "added_reasons": tuple(reason[k] for k in added),
        "resolved": True,
        "tolerance": float(tolerance),
    }
    return block, extra, notes
