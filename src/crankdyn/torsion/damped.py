"""Damped (complex) modes and modal damping (analysis and result).

Equations of free vibration of the lumped model (:mod:`crankdyn.torsion.model`):

    M theta'' + C_eff theta' + K theta = 0,   C_eff = C + C_modal + H / omega_h,

C the viscous damping matrix (absolute dampers and the shafts' relative dampers), C_modal the
damping of given modal damping ratios (below) and H = sum eta_s K_s the hysteretic matrix of the
loss factors, taken as the equivalent viscous damping H / omega_h at a frequency omega_h
(hysteretic damping dissipates eta k theta^2 pi per cycle at any frequency; a viscous damper
c = eta k / omega does the same at omega). With y = (theta, theta') it is the first-order system
y' = A y,

    A = [[0, I], [-M^-1 K, -M^-1 C_eff]]

(state-space form; e.g. M. I. Friswell et al., *Dynamics of Rotating Machines*, Cambridge
University Press 2010, §2.4 and §3.4; openTorsion's ``Assembly.modal_analysis`` solves the same
matrix), whose eigenvalues come in conjugate pairs lambda = -zeta omega_n +/- i omega_d for an
underdamped mode, with

    omega_n = |lambda|,  zeta = -Re(lambda) / |lambda|,  omega_d = |Im(lambda)| = omega_n
    sqrt(1 - zeta^2),  logarithmic decrement delta = 2 pi zeta / sqrt(1 - zeta^2)
    = 2 pi (-Re lambda) / omega_d

(the ratio ln(x_k / x_k+1) of successive peaks of the free decay; Friswell et al. §2.4, S. S.
Rao, *Mechanical Vibrations*, §2.6). An overdamped mode has two real eigenvalues lambda_1,
lambda_2 < 0: omega_n = sqrt(lambda_1 lambda_2), zeta = -(lambda_1 + lambda_2) / (2 omega_n)
>= 1, omega_d = 0 and no logarithmic decrement (null). The rigid-body mode of a free model does
not vibrate: omega_n = omega_d = 0, no damping ratio or decrement (null).

The modes are labelled by the undamped modes: each undamped mode phi_r (mass-normalised) is
given the eigenvalue whose eigenvector v (its angle part) is closest to it in the mass metric,
the modal assurance criterion MAC = |phi_r^T M v|^2 / (phi_r^T M phi_r v^H M v), by an optimal
assignment (every eigenvalue to one mode), and numbered as they are (elastic modes from 1, a
free model's rigid-body mode 0; docs/conventions.md), so damped mode r is undamped mode r.
Hysteretic damping (``hysteretic="iterate"``, the default) is taken at each mode's own damped
frequency: omega_h = omega_d,r, iterated from the undamped omega_r until it no longer changes
(to 1e-12; a single mass on a hysteretic shaft then gives omega_d^2 = omega_n^2
(1 + sqrt(1 - eta^2)) / 2 exactly, tested); or at one given frequency for every mode
(``hysteretic=omega_h``).

Complex mode shapes: the eigenvector's angle part over the masses (reflected amplitudes, in the
listing order), scaled so that the largest amplitude is 1 (real, positive).

Modal damping. Damping ratios zeta_r per elastic mode give the damping matrix

    C_modal = M Phi diag(2 zeta_r omega_r) Phi^T M

with the mass-normalised undamped modes Phi (Phi^T M Phi = I), so that Phi^T C_modal Phi =
diag(2 zeta_r omega_r) (D. J. Inman, "Critical damping in lumped parameter models",
*Encyclopedia of Vibration*, 2001; openTorsion's ``Assembly.C_modal``). With no other damping
the damped modes have exactly the ratios given (tested). The forced response takes it through
``forced_response(..., modal_damping=...)`` (a dense solve: C_modal couples every mass).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import linear_sum_assignment

from crankdyn.errors import InputError
from crankdyn.results import Result, column, freeze, scalar

if TYPE_CHECKING:
    from crankdyn.torsion.model import TorsionModel

__all__ = [
    "DampedModalResult",
    "damped_modes",
    "modal_damping_matrix",
    "modal_damping_ratios",
]

HZ = 1.0 / (2.0 * math.pi)
_ITERATIONS = 60
_REAL = 1e-9  # |Im lambda| below this x |lambda|: a real eigenvalue


def modal_damping_ratios(model: TorsionModel, ratios: ArrayLike) -> NDArray[np.float64]:
    """The damping ratio of every mode of ``model``, from the ratios of its elastic modes.

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The lumped model.
    ratios : float or array_like
        One damping ratio for every elastic mode, or one per elastic mode in ascending order
        (dimensionless, 0 <= zeta < 1; 0.02 is 2 % of critical).

    Returns
    -------
    numpy.ndarray
        (modes,) zeta_r of every mode in ascending order of the undamped natural frequency
        (dimensionless), a free model's rigid-body mode first with 0.

    Raises
    ------
    InputError
        Naming the key ``modal_damping`` and the value: neither one ratio nor one per elastic
        mode, or a ratio outside [0, 1) or not finite.

    Examples
    --------
    >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
    >>> free = TorsionModel(
    ...     masses=(Mass("a", 1.0), Mass("b", 3.0)), shafts=(Shaft(("a", "b"), 3e4),)
    ... )
    >>> modal_damping_ratios(free, 0.02).tolist()  # the rigid-body mode, then mode 1
    [0.0, 0.02]
    """
    from crankdyn.torsion.modal import eigen_modes

    lam, _phi = eigen_modes(model)
    elastic = np.flatnonzero(lam > 0.0) if model.is_free else np.arange(lam.size)
    if model.is_free:
        elastic = elastic[elastic > 0]
    z = np.atleast_1d(np.asarray(ratios, dtype=float))
    if z.ndim != 1 or z.size not in (1, elastic.size):
        raise InputError(
            f"expected one modal damping ratio, or one per elastic mode ({elastic.size})",
            key="modal_damping",
            value=z.tolist(),
        )
    if not np.all(np.isfinite(z)) or np.any(z < 0.0) or np.any(z >= 1.0):
        raise InputError(
            "modal damping ratios must lie in [0, 1) (0.02 is 2 % of critical)",
            key="modal_damping",
            value=z.tolist(),
        )
    out = np.zeros(lam.size)
    out[elastic] = np.broadcast_to(z, elastic.shape)
    return out


def modal_damping_matrix(model: TorsionModel, ratios: ArrayLike) -> NDArray[np.float64]:
    """The modal damping matrix C_modal = M Phi diag(2 zeta_r omega_r) Phi^T M.

    Inman (2001), "Critical damping in lumped parameter models", *Encyclopedia of Vibration*;
    openTorsion's ``Assembly.C_modal`` (module docstring): with the mass-normalised undamped
    modes Phi, Phi^T C_modal Phi = diag(2 zeta_r omega_r).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The lumped model.
    ratios : float or array_like
        Damping ratios of the elastic modes (dimensionless), as for
        :func:`modal_damping_ratios`.

    Returns
    -------
    numpy.ndarray
        (dof, dof) C_modal (N m s/rad, reflected to the reference speed), symmetric.

    Raises
    ------
    InputError
        As :func:`modal_damping_ratios` (key ``modal_damping``).

    Examples
    --------
    Two free masses: mode 1 has omega_1 = sqrt(k (1/J_a + 1/J_b)) = 200 rad/s and C_modal is
    2 zeta omega_1 J_a J_b / (J_a + J_b) = 6 N m s/rad on the shaft's twist.

    >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
    >>> free = TorsionModel(
    ...     masses=(Mass("a", 1.0), Mass("b", 3.0)), shafts=(Shaft(("a", "b"), 3e4),)
    ... )
    >>> np.round(modal_damping_matrix(free, 0.02), 9).tolist()
    [[6.0, -6.0], [-6.0, 6.0]]
    """
    from crankdyn.torsion.modal import eigen_modes

    zeta = modal_damping_ratios(model, ratios)
    lam, phi = eigen_modes(model)
    omega = np.sqrt(np.maximum(lam, 0.0))
    mphi = model.dof_inertia[:, None] * phi
    return (mphi * (2.0 * zeta * omega)[None, :]) @ mphi.T


@dataclass(frozen=True)
class DampedModalResult(Result):
    """Damped natural frequencies, damping ratios, logarithmic decrements and complex mode
    shapes of a torsional model, one per mode, in the order of the undamped modes that label
    them and with their numbers (elastic modes from 1, a free model's rigid-body mode 0:
    docs/conventions.md) (module docstring). Frequencies are held in rad/s
    (``natural_frequency`` |lambda|, ``damped_frequency`` omega_d), exported in Hz.

    Parameters
    ----------
    mode_shapes : numpy.ndarray or None
        (mode, mass) complex mode shapes, reflected, the largest amplitude of every mode 1
        (dimensionless; not a column: :meth:`to_dict` exports its real and imaginary parts).

    Examples
    --------
    >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
    >>> model = TorsionModel(
    ...     masses=(Mass("m", 2.0, damping=40.0),), shafts=(Shaft(("ground", "m"), 8e4),)
    ... )
    >>> result = damped_modes(model)
    >>> result.mode.tolist(), round(float(result.damping_ratio[0]), 12)
    ([1], 0.05)
    """

    title = "Damped modes"
    mode: np.ndarray = column("mode", "Mode", "")
    natural_frequency: np.ndarray = column(
        "undamped_natural_frequencies_hz", "Natural frequency |λ|", "Hz", HZ
    )
    damped_frequency: np.ndarray = column("damped_frequencies_hz", "Damped frequency", "Hz", HZ)
    damping_ratio: np.ndarray = column("damping_ratios", "Damping ratio", "")
    log_decrement: np.ndarray = column("log_decrements", "Logarithmic decrement", "")
    eigenvalue_real: np.ndarray = column("eigenvalues_real_per_s", "Re λ", "1/s")
    eigenvalue_imag: np.ndarray = column("eigenvalues_imag_rad_s", "Im λ", "rad/s")
    masses: tuple[str, ...] = scalar("masses", "Masses", "")
    hysteretic: str = scalar("hysteretic", "Loss factors as viscous", "")
    free: bool = scalar("free", "Free (rigid-body mode)", "")
    model_name: str = scalar("model", "Model", "", summary=False)
    mode_shapes: np.ndarray | None = field(default=None, repr=False, compare=False)
    """Complex mode shapes (mode x mass, reflected, largest amplitude 1)."""

    @property
    def damped_frequencies_hz(self) -> NDArray[np.float64]:
        """Damped natural frequencies omega_d / (2 pi) (Hz), one per mode."""
        return self.damped_frequency * HZ

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict; ``mode_shapes_real`` and ``mode_shapes_imag`` hold the complex mode
        shapes (mode x mass).

        Returns
        -------
        dict
            The columns and scalars in their exported units
            (:meth:`crankdyn.results.Result.to_dict`), and the mode shapes (dimensionless) as
            lists of rows.
        """
        out = super().to_dict()
        if self.mode_shapes is not None:
            out["mode_shapes_real"] = [[float(v) for v in row] for row in self.mode_shapes.real]
            out["mode_shapes_imag"] = [[float(v) for v in row] for row in self.mode_shapes.imag]
        return out


def _state_matrices(m, k, c):
    """A = [[0, I], [-M^-1 K, -M^-1 C]] for diagonal M (m: the diagonal), stacked over the
    leading axis of c (..., n, n)."""
    n = m.size
    inv = (1.0 / m)[:, None]
    lead = c.shape[:-2]
    a = np.zeros((*lead, 2 * n, 2 * n))
    a[..., :n, n:] = np.eye(n)
    a[..., n:, :n] = -inv * k
    a[..., n:, n:] = -inv * c
    return a


def _mac(phi, vectors, m):
    """|phi_r^T M v|^2 / (phi_r^T M phi_r v^H M v): (modes, candidates)."""
    num = np.abs(phi.T @ (m[:, None] * vectors)) ** 2
    den = (
        np.sum(m[:, None] * phi**2, axis=0)[:, None]
        * np.real(np.sum(m[:, None] * np.abs(vectors) ** 2, axis=0))[None, :]
    )
    return num / np.where(den > 0.0, den, 1.0)


def _mode_values(lam, partner=None):
    """(omega_n, omega_d, zeta) of an eigenvalue (and its real partner for overdamped modes)."""
    if partner is None:
        wn = abs(lam)
        return wn, abs(lam.imag), (-lam.real / wn if wn > 0.0 else math.nan)
    l1, l2 = lam.real, partner.real
    wn = math.sqrt(max(l1 * l2, 0.0))
    zeta = -(l1 + l2) / (2.0 * wn) if wn > 0.0 else math.nan
    return wn, 0.0, zeta


def damped_modes(
    model: TorsionModel,
    *,
    hysteretic: str | float | None = "iterate",
    modal_damping: ArrayLike | None = None,
) -> DampedModalResult:
    """Damped modes of a torsional model (module docstring).

    The eigenvalues of the state-space matrix A = [[0, I], [-M^-1 K, -M^-1 C_eff]] (Friswell
    et al. 2010, secs. 2.4 and 3.4): omega_n = |lambda|, zeta = -Re(lambda)/|lambda|,
    omega_d = |Im(lambda)| and the logarithmic decrement 2 pi zeta / sqrt(1 - zeta^2) (Rao,
    *Mechanical Vibrations*, sec. 2.6), labelled by the undamped modes through the MAC.

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The lumped model (its ``[[damper]]`` rings are not included, as in the undamped modes).
    hysteretic : str, float or None
        ``"iterate"`` (default; None the same): loss factors as viscous damping eta k / omega
        at each mode's own damped frequency; a number omega_h (rad/s), > 0: at that frequency
        for every mode.
    modal_damping : float, array_like or None
        Damping ratios per elastic mode (dimensionless) added as C_modal (one number for all;
        :func:`modal_damping_matrix`), or None.

    Returns
    -------
    DampedModalResult
        One row per mode, ascending in the undamped natural frequency: frequencies (rad/s),
        damping ratios and logarithmic decrements (dimensionless), eigenvalues (1/s, rad/s)
        and complex mode shapes.

    Raises
    ------
    InputError
        Naming the key ``hysteretic`` and its value when it is neither ``"iterate"`` nor a
        positive finite frequency; the key ``modal_damping`` as :func:`modal_damping_ratios`.

    Examples
    --------
    One mass J = 2 kg m^2 on a grounded shaft k = 8e4 N m/rad with an absolute damper
    c = 40 N m s/rad: omega_n = sqrt(k/J) = 200 rad/s, zeta = c / (2 sqrt(k J)) = 0.05 and
    omega_d = omega_n sqrt(1 - zeta^2) (Rao sec. 2.6).

    >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
    >>> model = TorsionModel(
    ...     masses=(Mass("m", 2.0, damping=40.0),), shafts=(Shaft(("ground", "m"), 8e4),)
    ... )
    >>> result = damped_modes(model)
    >>> round(float(result.natural_frequency[0]), 9), round(float(result.damping_ratio[0]), 12)
    (200.0, 0.05)
    >>> round(float(result.damped_frequency[0]) / (200.0 * math.sqrt(1 - 0.05**2)), 12)
    1.0
    >>> round(float(result.log_decrement[0]), 6)  # 2 pi zeta / sqrt(1 - zeta^2)
    0.314553
    """
    from crankdyn.torsion.modal import eigen_modes

    m = np.asarray(model.dof_inertia, dtype=float)
    k = model.stiffness_matrix()
    c = model.damping_matrix()
    if modal_damping is not None:
        c = c + modal_damping_matrix(model, modal_damping)
    h = model.hysteretic_matrix()
    lam0, phi = eigen_modes(model)
    omega0 = np.sqrt(np.maximum(lam0, 0.0))
    n = m.size
    rigid = np.zeros(n, dtype=bool)
    if model.is_free:
        rigid[0] = True
    has_h = bool(np.any(h != 0.0))
    if hysteretic == "iterate" or hysteretic is None:
        label = "at each mode's damped frequency (iterated)" if has_h else "none"
        fixed = None
    else:
        try:
            fixed = float(hysteretic)
        except (TypeError, ValueError):
            raise InputError(
                'expected "iterate" or a frequency', key="hysteretic", value=hysteretic
            ) from None
        if not (math.isfinite(fixed) and fixed > 0.0):
            raise InputError("the frequency must be positive", key="hysteretic", value=hysteretic)
        label = f"at {fixed * HZ:.6g} Hz" if has_h else "none"

    values = np.full((n, 3), math.nan)  # omega_n, omega_d, zeta
    eig = np.zeros(n, dtype=complex)
    shapes = np.zeros((n, n), dtype=complex)
    if not has_h or fixed is not None:
        c_eff = c + h / fixed if (has_h and fixed is not None) else c
        lam, vec = np.linalg.eig(_state_matrices(m, k, c_eff))
        _assign(lam, vec[:n], phi, m, rigid, values, eig, shapes)
    else:
        # each elastic mode at its own damped frequency, all modes' systems at once
        elastic = np.flatnonzero(~rigid)
        w = omega0[elastic].copy()
        for _ in range(_ITERATIONS):
            c_eff = c[None] + h[None] / w[:, None, None]
            lam, vec = np.linalg.eig(_state_matrices(m, k, c_eff))  # (E, 2n), (E, 2n, 2n)
            picked = np.empty(elastic.size, dtype=complex)
            for e, r in enumerate(elastic):  # the modes (not speeds or orders): small
                mac = _mac(phi[:, [r]], vec[e, :n], m)[0]
                mac[lam[e].imag < -_REAL * np.abs(lam[e])] = -1.0  # one of each conjugate pair
                j = int(np.argmax(mac))
                picked[e] = lam[e, j]
                shapes[r] = vec[e, :n, j]
            new = np.abs(picked.imag)
            done = np.all(np.abs(new - w) <= 1e-12 * np.maximum(w, 1e-300)) or np.any(new == 0.0)
            w = np.where(new > 0.0, new, w)
            if done:
                break
        for e, r in enumerate(elastic):
            lam_r = picked[e]
            if abs(lam_r.imag) <= _REAL * abs(lam_r):  # overdamped: its real partner
                lam_e, vec_e = lam[e], vec[e, :n]
                real = np.flatnonzero(np.abs(lam_e.imag) <= _REAL * np.abs(lam_e))
                mac = _mac(phi[:, [r]], vec_e[:, real], m)[0]
                order = real[np.argsort(-mac)]
                partner = lam_e[order[1]] if order.size > 1 else lam_r
                values[r] = _mode_values(lam_r, partner)
            else:
                values[r] = _mode_values(lam_r)
            eig[r] = lam_r if lam_r.imag >= 0.0 else np.conj(lam_r)
        for r in np.flatnonzero(rigid):
            values[r] = (0.0, 0.0, math.nan)
            shapes[r] = phi[:, r]
    log_dec = np.where(
        values[:, 1] > 0.0,
        2.0 * math.pi * values[:, 2] * values[:, 0] / np.where(values[:, 1] > 0, values[:, 1], 1),
        math.nan,
    )
    # rows in the order of the undamped modes that label them (ascending), numbered as they
    # are (docs/conventions.md: elastic modes from 1, a free model's rigid-body mode 0)
    order = np.argsort(omega0, kind="stable")
    first = 0 if model.is_free else 1
    dof = model.mass_dof
    shapes = shapes[order][:, dof]
    peak = np.argmax(np.abs(shapes), axis=1)
    scale = shapes[np.arange(n), peak]
    shapes = shapes / np.where(scale != 0.0, scale, 1.0)[:, None]
    shapes.setflags(write=False)
    return DampedModalResult(
        mode=freeze(np.arange(first, first + n), dtype=int),
        natural_frequency=freeze(values[order, 0]),
        damped_frequency=freeze(values[order, 1]),
        damping_ratio=freeze(values[order, 2]),
        log_decrement=freeze(log_dec[order]),
        eigenvalue_real=freeze(eig[order].real),
        eigenvalue_imag=freeze(eig[order].imag),
        masses=model.mass_names,
        hysteretic=label,
        free=model.is_free,
        model_name=model.name,
        mode_shapes=shapes,
    )


def _assign(
    lam: NDArray[np.complex128],
    vectors: NDArray[np.complex128],
    phi: NDArray[np.float64],
    m: NDArray[np.float64],
    rigid: NDArray[np.bool_],
    values: NDArray[np.float64],
    eig: NDArray[np.complex128],
    shapes: NDArray[np.complex128],
) -> None:
    """Give every undamped mode its eigenvalue(s) of one state-space solution (module
    docstring: optimal assignment on the MAC)."""
    oscillating = np.flatnonzero(lam.imag > _REAL * np.abs(lam))
    real = np.flatnonzero(np.abs(lam.imag) <= _REAL * np.abs(lam))
    # candidates: every oscillating eigenvalue (upper half-plane) once, real ones in pairs
    real = real[np.argsort(np.abs(lam[real]))]
    pairs = [(real[i], real[i + 1]) for i in range(0, real.size - 1, 2)]
    candidates = [(int(j), None) for j in oscillating] + [(int(a), int(b)) for a, b in pairs]
    if real.size % 2:  # an odd real eigenvalue: the double 0 of a free undamped model split
        candidates.append((int(real[-1]), None))
    cols = np.array([a for a, _ in candidates], dtype=int)
    mac = _mac(phi, vectors[:, cols], m)  # (modes, candidates)
    rows, picked = linear_sum_assignment(-mac)
    for r, j in zip(rows, picked, strict=True):
        a, b = candidates[j]
        if rigid[r]:
            values[r] = (0.0, 0.0, math.nan)
            eig[r] = 0.0
            shapes[r] = phi[:, r]
            continue
        values[r] = _mode_values(lam[a], None if b is None else lam[b])
        eig[r] = lam[a]
        shapes[r] = vectors[:, a]
