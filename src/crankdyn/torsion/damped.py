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
frequency: omega_h = omega_d,r of the eigenvalue nearest mode r in the MAC at omega_h, iterated
from the undamped omega_r until it no longer changes (to 1e-12; a single mass on a hysteretic
shaft then gives omega_d^2 = omega_n^2 (1 + sqrt(1 - eta^2)) / 2 exactly, and so does every mode
of a chain whose shafts share one loss factor, tested); or at one given frequency for every mode
(``hysteretic=omega_h``).

**Per mode** (a chain of more than 32 degrees of freedom without modal damping; any model with
the loss factors iterated; a smaller chain's one dense problem is quicker, 0.4 ms at 10 masses,
and gives the same modes): mode r
is followed from (omega_r, phi_r) by the Rayleigh functional iteration of
:mod:`crankdyn.torsion.quadratic` (O(n) a step on a chain's tridiagonal pencil, a dense LU on
another model's), with omega_h solved with it when iterated. Checked: converged (backward error),
and no two modes on one eigenpair (eigenvalues within 1e-8, parallel vectors): the one with the
smaller MAC is found again among the eigenpairs nearest its start and the pair it reached
(shift-invert Arnoldi on a chain, :func:`crankdyn.torsion.quadratic.eigenpairs_near`; the dense
eigenproblem otherwise), those no other mode has in descending MAC, each refined until one is
distinct (up to 6 rounds of 8 to 64 eigenpairs). The labels are then the MAC's optimal
assignment: where every mode's MAC with its own undamped mode exceeds 1/2 they are it (the MACs
of one eigenvector with all the undamped modes sum to 1, so every other entry of its column is
below 1/2), and around each mode where it does not the modes within 4 of it are assigned by the
MAC (``linear_sum_assignment``); with the loss factors iterated such a mode takes the MAC-nearest
of the 16 eigenpairs nearest its own at its omega_h, omega_h iterated as defined. With loss
factors near 1 on every shaft two modes can share a fixed point of that definition (the dense
iteration before did too); they are kept.

**Overdamped modes** have two real eigenvalues: the one reached from the mode, and a partner:
the real eigenvalues near the other roots of the modes' Rayleigh functionals that no mode has
reached are given to the overdamped modes by the MAC's optimal assignment, a free model's
rigid-body shape taking part where absolute damping splits its double zero (lambda = 0 and
about -1^T C 1 / 1^T M 1). (The dense solution before paired the real eigenvalues in order of
magnitude, which in a free chain with absolute damping could pair an elastic mode with the
rigid-body mode's eigenvalue: wrong, e.g. against Rayleigh damping's closed form, tested; the
dense solution, of branched models and the fallback, now also gives every mode its eigenvalue
by the MAC's assignment over the oscillating and the real eigenvalues, and a mode given a real
one its second by the assignment among the real ones left.) The pool is looked for only where
the direct way fails: each partner refined from its own other root and its own shape, kept
where every one converged to a real, non-zero eigenvalue, no two alike and none a mode's own,
and the MAC's assignment among them gives each its own (the spectrum's real eigenvalues are
then the modes' own and these, the set the pool's assignment chooses from; a 400-mass chain
with Rayleigh damping overdamped at both ends: 5 s -> 0.3 s). With the loss factors iterated
each overdamped mode's partner is the other root refined at its own omega_h.

**Fallback.** Modes still not found come from the dense solution (one state-space eigenproblem
and the assignment; with the loss factors iterated, the dense iteration mode by mode), up to
:data:`DENSE_MAX_DOF` degrees of freedom (LinAlgError above; not met in the tests). Other
models (branched, geared, looped) and modal damping (C_modal couples every mass) use the dense
state-space eigenproblem of size 2n, O(n^3), or, with loss factors iterated, the per-mode
iteration with a dense LU per step, O(n^4).

**Bounds** (:func:`size_bound`; docs/theory-torsion.md, "Damped modes", with the measured times
and memory): a chain :data:`CHAIN_MAX_DOF` degrees of freedom (O(n^2) time; memory the n x n
complex mode shapes and the n x n undamped ones, 24 n^2 bytes), another model
:data:`DENSE_MAX_DOF` (:data:`DENSE_ITERATED_MAX_DOF` with loss factors iterated), the JSON
:data:`JSON_MAX_DOF`; above, InputError (key ``degrees of freedom``, the count) before anything
is allocated.

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
from crankdyn.torsion.quadratic import (
    ChainPencil,
    DensePencil,
    eigenpairs_near,
    rayleigh,
    refine,
)

if TYPE_CHECKING:
    from crankdyn.torsion.model import TorsionModel

__all__ = [
    "CHAIN_MAX_DOF",
    "DENSE_ITERATED_MAX_DOF",
    "DENSE_MAX_DOF",
    "JSON_MAX_DOF",
    "DampedModalResult",
    "damped_modes",
    "modal_damping_matrix",
    "modal_damping_ratios",
    "size_bound",
]

HZ = 1.0 / (2.0 * math.pi)
CHAIN_MAX_DOF = 5_000
"""The most degrees of freedom of a chain's damped modes (module docstring, "Bounds")."""
JSON_MAX_DOF = 2_000
"""The most degrees of freedom of damped modes written as JSON (``torsion modes --damped
--format json``): the n x n complex mode shapes as text (157 MB at 2,000)."""
DENSE_MAX_DOF = 1_000
"""The most degrees of freedom of another model's damped modes, or a chain's with modal
damping (one dense state-space eigenproblem of twice the size)."""
DENSE_ITERATED_MAX_DOF = 300
"""The most degrees of freedom of a branched or geared model's damped modes with loss factors
at each mode's own frequency (a dense LU per mode and step)."""
_REAL = 1e-9  # |Im lambda| below this x |lambda|: a real eigenvalue
_CLOSE = 1e-8  # eigenvalues this close (relative) with parallel vectors are one eigenpair
_PARALLEL = 1e-6  # unit vectors with |x^H y| >= 1 - this are parallel
_REPAIRS = 6  # rounds of repair (module docstring, "Per mode")
_ITERATIONS = 60  # omega_h iterations of the dense fallback at most
_NEIGHBOURS = 4  # modes either side of a mixed mode that its assignment may exchange with
_CLUSTER = 256  # modes assigned together at most
_SMALL = 32  # chains of at most this many degrees of freedom: the dense problem (quicker there)
_CANDIDATES = 8  # eigenvalues near the start in the first round of repair, doubled each round


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


def size_bound(model: TorsionModel, *, modal_damping: bool = False, iterated: bool = True) -> int:
    """The most degrees of freedom :func:`damped_modes` takes for ``model`` (module docstring,
    "Bounds"): :data:`CHAIN_MAX_DOF` for a chain without modal damping (the per-mode iteration
    on its tridiagonal pencil), :data:`DENSE_ITERATED_MAX_DOF` for another model with loss
    factors iterated to each mode's frequency (a dense LU per step), :data:`DENSE_MAX_DOF`
    otherwise (one dense eigenvalue problem of twice the size).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The lumped model.
    modal_damping : bool
        Whether modal damping ratios are added (C_modal is dense).
    iterated : bool
        Whether loss factors are taken at each mode's own frequency (``hysteretic="iterate"``).

    Returns
    -------
    int
        The bound (degrees of freedom).

    Examples
    --------
    >>> from crankdyn.torsion import TorsionModel
    >>> size_bound(TorsionModel.chain_of([1.0, 2.0], [5.0])) == CHAIN_MAX_DOF
    True
    """
    if model.is_chain and not modal_damping:
        return CHAIN_MAX_DOF
    if iterated and any(s.loss_factor > 0.0 for s in model.shafts):
        return DENSE_ITERATED_MAX_DOF
    return DENSE_MAX_DOF


def _check_size(model: TorsionModel, modal_damping: bool, iterated: bool) -> None:
    """Refuse a model above :func:`size_bound` in one line, before anything is allocated."""
    bound = size_bound(model, modal_damping=modal_damping, iterated=iterated)
    n = model.dof_count
    if n <= bound:
        return
    if model.is_chain and not modal_damping:
        kind = "a chain"
    elif model.is_chain:
        kind = "a model with modal damping"
    else:
        kind = "a branched or geared model" + (
            " with loss factors at each mode's frequency" if bound == DENSE_ITERATED_MAX_DOF else ""
        )
    raise InputError(
        f"the damped modes of {kind} take at most {bound:,} degrees of freedom "
        "(crankdyn docs torsion-file, damped modes)",
        key="degrees of freedom",
        value=n,
    )


def _hysteretic_frequency(hysteretic: str | float | None) -> float | None:
    """omega_h (rad/s) of ``hysteretic``, or None for each mode's own frequency."""
    if hysteretic == "iterate" or hysteretic is None:
        return None
    try:
        fixed = float(hysteretic)
    except (TypeError, ValueError):
        raise InputError(
            'expected "iterate" or a frequency', key="hysteretic", value=hysteretic
        ) from None
    if not (math.isfinite(fixed) and fixed > 0.0):
        raise InputError("the frequency must be positive", key="hysteretic", value=hysteretic)
    return fixed


def damped_modes(
    model: TorsionModel,
    *,
    hysteretic: str | float | None = "iterate",
    modal_damping: ArrayLike | None = None,
) -> DampedModalResult:
    """Damped modes of a torsional model (module docstring).

    The eigenvalues of Q(lambda) = lambda^2 M + lambda C_eff + K, i.e. of the state-space
    matrix A = [[0, I], [-M^-1 K, -M^-1 C_eff]] (Friswell et al. 2010, secs. 2.4 and 3.4):
    omega_n = |lambda|, zeta = -Re(lambda)/|lambda|, omega_d = |Im(lambda)| and the logarithmic
    decrement 2 pi zeta / sqrt(1 - zeta^2) (Rao, *Mechanical Vibrations*, sec. 2.6), each
    labelled by its undamped mode: a chain's per mode from that mode
    (:mod:`crankdyn.torsion.quadratic`), another model's by the MAC.

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
        positive finite frequency; the key ``modal_damping`` as :func:`modal_damping_ratios`;
        the key ``degrees of freedom`` and the model's count above :func:`size_bound`.

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

    fixed = _hysteretic_frequency(hysteretic)
    structured = model.is_chain and modal_damping is None
    _check_size(model, modal_damping is not None, fixed is None)
    lam0, phi = eigen_modes(model)
    omega0 = np.sqrt(np.maximum(lam0, 0.0))
    n = omega0.size
    rigid = np.zeros(n, dtype=bool)
    rigid[0] = model.is_free
    shapes = np.empty((n, n), dtype=complex)  # (mode, dof), filled in place
    if structured:
        pencil: ChainPencil | DensePencil = ChainPencil.of(model.chain)  # type: ignore[arg-type]
    else:
        c = model.damping_matrix()
        if modal_damping is not None:
            c += modal_damping_matrix(model, modal_damping)
        pencil = DensePencil(
            model.dof_inertia, model.stiffness_matrix(), c, model.hysteretic_matrix()
        )
    has_h = pencil.hysteretic
    if has_h and fixed is None:
        label = "at each mode's damped frequency (iterated)"
    else:
        label = f"at {fixed * HZ:.6g} Hz" if has_h and fixed is not None else "none"
    iterated = has_h and fixed is None
    if structured and n <= _SMALL and not iterated:  # one small dense problem: quicker
        pencil, structured = pencil.dense(), False  # type: ignore[union-attr]
    if structured or iterated:
        found = _per_mode(pencil, omega0, phi, rigid, fixed, shapes)
        values, eig = _fallback(model, pencil, phi, omega0, rigid, fixed, found, shapes)
    else:
        assert isinstance(pencil, DensePencil)
        c_eff = pencil.c + pencil.h / fixed if (has_h and fixed is not None) else pencil.c
        lam, vec = np.linalg.eig(_state_matrices(pencil.m, pencil.k, c_eff))
        values, eig = np.full((n, 3), math.nan), np.zeros(n, dtype=complex)
        _assign(lam, vec[:n], phi, pencil.m, rigid, values, eig, shapes)
    del phi
    return _result(model, omega0, values, eig, shapes, label)


def _result(
    model: TorsionModel,
    omega0: NDArray[np.float64],
    values: NDArray[np.float64],
    eig: NDArray[np.complex128],
    shapes: NDArray[np.complex128],
    label: str,
) -> DampedModalResult:
    """The result: rows in the order of the undamped modes that label them (ascending),
    numbered as they are (docs/conventions.md: elastic modes from 1, a free model's
    rigid-body mode 0); shapes over the masses, largest amplitude 1 (in place where the
    orders are the identity: a large chain's n x n shapes are not copied)."""
    n = omega0.size
    order = np.argsort(omega0, kind="stable")
    if not np.array_equal(order, np.arange(n)):
        shapes, values, eig = shapes[order], values[order], eig[order]
    dof = model.mass_dof
    if not np.array_equal(dof, np.arange(n)):
        shapes = shapes[:, dof]
    with np.errstate(divide="ignore", invalid="ignore"):
        log_dec = np.where(
            values[:, 1] > 0.0, 2.0 * math.pi * values[:, 2] * values[:, 0] / values[:, 1], math.nan
        )
    step = max(1, (1 << 16) // max(n, 1))  # a block of rows at a time: no n x n temporary
    peak = np.zeros(n, dtype=np.intp)
    for lo in range(0, n, step):
        peak[lo : lo + step] = np.argmax(np.abs(shapes[lo : lo + step]), axis=1)
    scale = shapes[np.arange(n), peak]
    shapes /= np.where(scale != 0.0, scale, 1.0)[:, None]
    shapes.setflags(write=False)
    first = 0 if model.is_free else 1
    return DampedModalResult(
        mode=freeze(np.arange(first, first + n), dtype=int),
        natural_frequency=freeze(values[:, 0]),
        damped_frequency=freeze(values[:, 1]),
        damping_ratio=freeze(values[:, 2]),
        log_decrement=freeze(log_dec),
        eigenvalue_real=freeze(eig.real),
        eigenvalue_imag=freeze(eig.imag),
        masses=model.mass_names,
        hysteretic=label,
        free=model.is_free,
        model_name=model.name,
        mode_shapes=shapes,
    )


def _per_mode(
    pencil: ChainPencil | DensePencil,
    omega0: NDArray[np.float64],
    phi: NDArray[np.float64],
    rigid: NDArray[np.bool_],
    fixed: float | None,
    shapes: NDArray[np.complex128],
) -> tuple[NDArray[np.float64], NDArray[np.complex128], NDArray[np.intp]]:
    """Every mode by the iteration from its undamped mode (module docstring, "Per mode"):
    (omega_n, omega_d, zeta) per mode (rad/s, rad/s, dimensionless), the eigenvalues (1/s) and
    the modes not found (their rows nan, for the fallback); the eigenvectors go into
    ``shapes`` (mode x dof)."""
    modes = _Modes(pencil, omega0, phi, rigid, fixed, shapes)
    bad = bad_partner = np.zeros(0, dtype=np.intp)
    for attempt in range(_REPAIRS + 1):
        bad, bad_partner = modes.check(shared=modes.iterate and attempt == _REPAIRS)
        if not (bad.size or bad_partner.size) or attempt == _REPAIRS:
            break
        count = min(_CANDIDATES << min(attempt, 3), 2 * pencil.size - 2)  # 8 to 64
        modes.repair(bad, bad_partner, count=count)
    failed = np.union1d(bad, bad_partner)
    if modes.iterate:
        modes.nearest_in_mac(failed)
    values, eig = modes.values(failed)
    if not modes.iterate:
        _relabel(modes.first, phi, pencil.m, values, eig, shapes, failed)
    return values, eig, failed + modes.first


def _own_mac(
    x: NDArray[np.complex128], phi: NDArray[np.float64], m: NDArray[np.float64]
) -> NDArray:
    """MAC of every row of ``x`` with the same column of ``phi`` (mass-normalised), a block of
    rows at a time (no n x n temporary)."""
    out = np.empty(x.shape[0])
    step = max(1, (1 << 16) // max(x.shape[1], 1))
    for lo in range(0, x.shape[0], step):
        xs, ps = x[lo : lo + step], phi[:, lo : lo + step].T
        out[lo : lo + step] = np.abs(np.einsum("ri,ri,i->r", xs, ps, m)) ** 2 / np.einsum(
            "ri,i->r", (xs * xs.conj()).real, m
        )
    return out


def _relabel(
    first: int,
    phi: NDArray[np.float64],
    m: NDArray[np.float64],
    values: NDArray[np.float64],
    eig: NDArray[np.complex128],
    shapes: NDArray[np.complex128],
    failed: NDArray[np.intp],
) -> None:
    """The MAC's optimal assignment where the per-mode labels may differ from it (module
    docstring, "Per mode"): around every elastic mode whose MAC with its own undamped mode is at
    most 1/2, the modes within :data:`_NEIGHBOURS` of it (runs merged, at most
    :data:`_CLUSTER` modes together) are assigned to their eigenpairs by the MAC
    (``linear_sum_assignment``), rows permuted in place."""
    n = phi.shape[0]
    x = shapes[first:]
    p = phi[:, first:]
    own = _own_mac(x, p, m)
    low = np.setdiff1d(np.flatnonzero(~(own > 0.5)), failed)
    if not low.size:
        return  # every MAC above 1/2: the labels are the optimal assignment (docstring)
    edges = np.flatnonzero(np.diff(low) > 2 * _NEIGHBOURS)
    for run in np.split(low, edges + 1):
        lo, hi = max(run[0] - _NEIGHBOURS, 0), min(run[-1] + _NEIGHBOURS + 1, n - first)
        for start in range(lo, hi, _CLUSTER):
            rows = np.setdiff1d(np.arange(start, min(start + _CLUSTER, hi)), failed)
            xs = x[rows]
            mac = np.abs((xs * m) @ p[:, rows]) ** 2  # (eigenpair, mode)
            mac /= np.einsum("ri,ri,i->r", xs.conj(), xs, m).real[:, None]
            _, mode_of = linear_sum_assignment(-mac)
            target = first + rows[mode_of]
            source = first + rows
            values[target], eig[target], shapes[target] = values[source], eig[source], xs


def _fallback(
    model: TorsionModel,
    pencil: ChainPencil | DensePencil,
    phi: NDArray[np.float64],
    omega0: NDArray[np.float64],
    rigid: NDArray[np.bool_],
    fixed: float | None,
    found: tuple[NDArray[np.float64], NDArray[np.complex128], NDArray[np.intp]],
    shapes: NDArray[np.complex128],
) -> tuple[NDArray[np.float64], NDArray[np.complex128]]:
    """The modes the per-mode iteration did not find, by the dense solution (module docstring,
    "Per mode"): with loss factors at each mode's frequency those modes one by one
    (:func:`_iterated_dense`), otherwise every mode from one state-space eigenproblem and the
    MAC's optimal assignment; refused (LinAlgError) above :data:`DENSE_MAX_DOF`."""
    values, eig, failed = found
    n = omega0.size
    if not failed.size:
        return values, eig
    if n > DENSE_MAX_DOF:
        raise np.linalg.LinAlgError(
            f"the damped modes did not converge for mode(s) {failed[:10].tolist()} of a "
            f"model of {n} degrees of freedom (more than {DENSE_MAX_DOF} for the dense fallback)"
        )
    if isinstance(pencil, DensePencil):
        k, c, h = pencil.k, pencil.c, pencil.h
    else:
        k, c, h = model.stiffness_matrix(), model.damping_matrix(), model.hysteretic_matrix()
    m = pencil.m
    if fixed is None and pencil.hysteretic:
        _iterated_dense(m, k, c, h, phi, omega0, failed, values, eig, shapes)
        return values, eig
    c_eff = c + h / fixed if (pencil.hysteretic and fixed is not None) else c
    lam, vec = np.linalg.eig(_state_matrices(m, k, c_eff))
    values, eig = np.full((n, 3), math.nan), np.zeros(n, dtype=complex)
    _assign(lam, vec[:n], phi, m, rigid, values, eig, shapes)
    return values, eig


def _iterated_dense(
    m: NDArray[np.float64],
    k: NDArray[np.float64],
    c: NDArray[np.float64],
    h: NDArray[np.float64],
    phi: NDArray[np.float64],
    omega0: NDArray[np.float64],
    rows: NDArray[np.intp],
    values: NDArray[np.float64],
    eig: NDArray[np.complex128],
    shapes: NDArray[np.complex128],
) -> None:
    """Modes ``rows`` with the loss factors at their own damped frequency, one by one: the
    state-space eigenvalues at omega_h, the one nearest mode r in the MAC (upper half-plane),
    omega_h = its |Im lambda| until it no longer changes (to 1e-12; the version before the
    per-mode iteration, kept as its fallback)."""
    n = m.size
    for r in rows.tolist():
        w = omega0[r]
        for _ in range(_ITERATIONS):
            lam, vec = np.linalg.eig(_state_matrices(m, k, c + h / w))
            mac = _mac(phi[:, [r]], vec[:n], m)[0]
            mac[lam.imag < -_REAL * np.abs(lam)] = -1.0  # one of each conjugate pair
            j = int(np.argmax(mac))
            new = abs(lam[j].imag)
            if new == 0.0 or abs(new - w) <= 1e-12 * w:
                break
            w = new
        shapes[r] = vec[:n, j]
        if abs(lam[j].imag) <= _REAL * abs(lam[j]):  # overdamped: its real partner
            real = np.flatnonzero(np.abs(lam.imag) <= _REAL * np.abs(lam))
            order = real[np.argsort(-_mac(phi[:, [r]], vec[:n, real], m)[0])]
            values[r] = _mode_values(lam[j], lam[order[1]] if order.size > 1 else lam[j])
        else:
            values[r] = _mode_values(lam[j])
        eig[r] = lam[j] if lam[j].imag >= 0.0 else np.conj(lam[j])


class _Modes:
    """The eigenpairs of the elastic modes, their overdamped partners, the checks and repairs
    (module docstring, "Per mode"). Row r of ``x`` (a view of the shapes) is elastic mode r."""

    def __init__(
        self,
        pencil: ChainPencil | DensePencil,
        omega0: NDArray[np.float64],
        phi: NDArray[np.float64],
        rigid: NDArray[np.bool_],
        fixed: float | None,
        shapes: NDArray[np.complex128],
    ) -> None:
        self.pencil, self.first = pencil, int(rigid.sum())
        first = self.first
        shapes[:first] = phi[:, :first].T
        self.phi, self.x = phi[:, first:], shapes[first:]
        self.x[...] = self.phi.T
        self.iterate = fixed is None and pencil.hysteretic
        self.fixed_w = fixed or 1.0  # omega_h when not iterated (1: no effect without H)
        count = self.x.shape[0]
        w = omega0[first:].copy() if self.iterate else np.full(count, fixed or 1.0)
        lam = 1j * omega0[first:]
        step = max(1, (1 << 16) // max(phi.shape[0], 1))  # forms a block at a time
        blocks = [pencil.forms(self.x[lo : lo + step]) for lo in range(0, count, step)]
        forms = tuple(np.concatenate([b[i] for b in blocks] or [np.zeros(0)]) for i in range(4))
        self.start, _, w = rayleigh(forms, lam, w, self.iterate)  # type: ignore[arg-type]
        found = refine(pencil, self.start, self.x, w, iterate=self.iterate)
        self.lam, self.w, self.ok = found.lam, found.w, found.converged
        flip = self.lam.imag < 0.0  # one of each conjugate pair: the upper half-plane
        self.lam[flip] = np.conj(self.lam[flip])
        self.x[flip] = np.conj(self.x[flip])
        self.partner = np.full(count, np.nan, dtype=complex)
        self.partner_x: dict[int, NDArray[np.complex128]] = {}
        self.partner_ok = np.zeros(count, dtype=bool)
        self.fixed_lam = np.zeros(self.first, dtype=complex)  # a free model's lambda = 0
        self.fixed_x = [np.full(phi.shape[0], 1.0 + 0j)] if self.first else []
        real = np.flatnonzero(self._real(self.lam))
        if self.iterate:  # each mode its own omega_h: each its own partner
            self._partners(real, found.other[real])
        else:
            self._assign_partners(real, found.other[real], phi[:, 0])

    @staticmethod
    def _real(lam: NDArray) -> NDArray[np.bool_]:
        return np.abs(lam.imag) <= _REAL * np.abs(lam)

    def _assign_partners(
        self, rows: NDArray[np.intp], other: NDArray[np.complex128], rigid_shape: NDArray
    ) -> None:
        """The second real eigenvalue of every overdamped mode ``rows`` (and a free model's
        rigid-body partner, with absolute damping), one eigenproblem: the real eigenvalues near
        the other roots ``other`` of their Rayleigh functionals, less those the modes have,
        given by the MAC's optimal assignment, each refined (module docstring, "Overdamped")."""
        a2, a1, _, _ = self.pencil.forms(np.ones((1, rigid_shape.size)))
        rigid = bool(self.first) and abs(a1[0]) > 0.0  # C 1 != 0: the rigid-body pair splits
        estimates = np.r_[other.real, -(a1 / a2).real if rigid else np.zeros(0)]
        need = estimates.size
        if not need:
            return
        shapes = np.column_stack([self.phi[:, rows], rigid_shape[:, None]][: 2 if rigid else 1])
        if self._direct_partners(rows, estimates, shapes):
            return
        n = self.pencil.size
        count = min(max(16, 2 * need), 2 * n - 2)
        for _ in range(4):
            lam, x = self._real_pool(estimates, count)
            if lam.size >= need or count == 2 * n - 2:
                break
            count = min(2 * count, 2 * n - 2)
        if lam.size < need:
            return  # the partners stay unfound: checked, repaired, or the fallback's
        picked, assigned = self._assignment(x, shapes)
        w = np.full(need, self.fixed_w)
        found = refine(self.pencil, lam[assigned], x[assigned].copy(), w, iterate=False)
        for j, r in zip(picked.tolist(), range(need), strict=True):
            self._set_partner(rows, j, found.lam[r], found.x[r], bool(found.converged[r]))

    def _assignment(
        self, x: NDArray[np.complex128], shapes: NDArray
    ) -> tuple[NDArray[np.intp], NDArray[np.intp]]:
        """(shape, candidate) pairs of the MAC's optimal assignment of the candidate vectors
        ``x`` (rows) to ``shapes`` (columns)."""
        m = self.pencil.m
        mac = np.abs(x @ (m[:, None] * shapes)) ** 2  # (candidate, mode)
        mac /= np.einsum("bi,i,bi->b", x.conj(), m, x).real[:, None]
        return linear_sum_assignment(-mac.T)

    def _set_partner(
        self, rows: NDArray[np.intp], j: int, lam: complex, x: NDArray, ok: bool
    ) -> None:
        """Shape j's partner: of elastic mode ``rows[j]``, or (j past the rows) the rigid-body
        pair's second eigenvalue."""
        if j < rows.size:
            row = int(rows[j])
            self.partner[row], self.partner_x[row], self.partner_ok[row] = lam, x, ok
        else:
            self.fixed_lam = np.r_[self.fixed_lam, lam]
            self.fixed_x.append(x)

    def _direct_partners(
        self, rows: NDArray[np.intp], estimates: NDArray[np.float64], shapes: NDArray
    ) -> bool:
        """The partners of :meth:`_assign_partners` without the pool's eigenproblems where that
        is safe: each refined from its own estimate (the other root) and its own shape (an
        elastic mode's, or the rigid-body shape); kept, and True, only where every one converged
        to a real eigenvalue that is not zero, no two of them and none of them a mode's own
        eigenvalue, and the MAC's optimal assignment among them gives each its own. The real
        eigenvalues of the spectrum are then every mode's own and these: the set the pool's
        assignment chooses from, assigned as it assigns them. Otherwise False, nothing set."""
        need = estimates.size
        w = np.full(need, self.fixed_w)
        found = refine(self.pencil, estimates + 0j, shapes.T.astype(complex), w, iterate=False)
        lam, x = found.lam, found.x
        floor = self._floor()
        if not (np.all(found.converged) and np.all(self._real(lam))):
            return False
        if np.any(np.abs(lam) <= floor):
            return False
        count = self.lam.size
        if any(max(i, j) >= count for i, j in _close_pairs(np.r_[self.lam, lam], floor)):
            return False
        picked, assigned = self._assignment(x, shapes)
        if not np.array_equal(assigned[np.argsort(picked)], np.arange(need)):
            return False
        for j in range(need):
            self._set_partner(rows, j, lam[j], x[j], True)
        return True

    def _real_pool(self, estimates: NDArray, count: int) -> tuple[NDArray, NDArray]:
        """Real eigenpairs near ``estimates`` (1/s) that are no mode's own eigenvalue nor 0:
        ``count`` nearest each of at most 32 shifts across them (every pair of a dense model)."""
        shifts = np.unique(np.quantile(estimates, np.linspace(0.0, 1.0, min(estimates.size, 32))))
        if isinstance(self.pencil, DensePencil):
            shifts, count = shifts[:1], 2 * self.pencil.size
        near = [
            _candidates(self.pencil, complex(v) * (1 + 1e-9j), self.fixed_w, count) for v in shifts
        ]
        lam = np.concatenate([a for a, _ in near])
        x = np.concatenate([b for _, b in near])
        floor = self._floor()
        keep = self._real(lam) & (np.abs(lam) > floor)
        keep &= np.array(
            [np.min(np.abs(self.lam - v), initial=np.inf) > _CLOSE * abs(v) for v in lam],
            dtype=bool,
        )
        lam, x = lam[keep], x[keep]
        order = np.argsort(lam.real, kind="stable")  # one of each eigenvalue found twice
        lam, x = lam[order], x[order]
        distinct = np.ones(lam.size, dtype=bool)
        distinct[1:] = np.abs(np.diff(lam)) > _CLOSE * np.abs(lam[1:])
        return lam[distinct].real + 0j, x[distinct]

    def _partners(self, rows: NDArray[np.intp], other: NDArray[np.complex128]) -> None:
        """The second real eigenvalue of the overdamped modes ``rows``, from ``other`` (the
        other root of their Rayleigh functionals, one per row)."""
        if not rows.size:
            return
        found = refine(
            self.pencil, other.real + 0j, self.x[rows].copy(), self.w[rows], iterate=False
        )
        for j, r in enumerate(rows.tolist()):
            self.partner[r], self.partner_x[r] = found.lam[j], found.x[j]
            self.partner_ok[r] = bool(found.converged[j])

    def _vector(self, i: int) -> NDArray[np.complex128]:
        count = self.lam.size
        if i < count:
            return self.x[i]
        if i < 2 * count:
            return self.partner_x[i - count]
        return self.fixed_x[i - 2 * count]

    def _mac(self, i: int) -> float:
        """MAC of entry i (main or partner) with its undamped mode."""
        count = self.lam.size
        if i >= 2 * count:
            return math.inf  # the rigid-body pairs are never given up
        v, p = self._vector(i), self.phi[:, i % count]
        m = self.pencil.m
        return float(abs(p @ (m * v)) ** 2 / (p @ (m * p) * np.real(np.vdot(v, m * v))))

    def _entries(self) -> NDArray[np.complex128]:
        """Every eigenvalue found: mains, partners (nan where none), the rigid-body pairs."""
        return np.concatenate([self.lam, self.partner, self.fixed_lam])

    def _same(self, i: int, j: int) -> bool:
        a, b = self._vector(i), self._vector(j)
        cos = abs(np.vdot(a, b)) / (np.linalg.norm(a) * np.linalg.norm(b))
        return bool(cos >= 1.0 - _PARALLEL)

    def check(self, shared: bool = False) -> tuple[NDArray[np.intp], NDArray[np.intp]]:
        """The elastic modes whose main eigenpair, and whose overdamped partner, must be found
        again: not converged, or the eigenpair of another mode (the one nearer its own undamped
        mode in the MAC keeps it; with ``shared``, two modes may share a converged pair)."""
        count = self.lam.size
        bad = ~self.ok
        real = self._real(self.lam)
        bad_partner = real & ~(
            self.partner_ok & self._real(np.where(np.isnan(self.partner), 1j, self.partner))
        )
        for i, j in _close_pairs(self._entries(), self._floor()):
            if not self._same(i, j) or (shared and max(i, j) < count):
                continue
            if i == j + count or j == i + count:  # a mode's pair: the partner gives way
                loser = max(i, j)
            else:
                loser = i if self._mac(i) < self._mac(j) else j
            if loser < count:
                bad[loser] = True
            elif loser < 2 * count:
                bad_partner[loser - count] = True
        bad_partner &= ~bad
        return np.flatnonzero(bad), np.flatnonzero(bad_partner & real)

    def _floor(self) -> float:
        """Eigenvalues below this (1/s) are zero for the comparisons: 1e-9 omega_max."""
        return 1e-9 * float(np.max(np.abs(self.lam), initial=0.0))

    def repair(self, bad: NDArray[np.intp], bad_partner: NDArray[np.intp], count: int) -> None:
        """Find the eigenpairs of ``bad`` (and ``bad_partner``) again: among the ``count``
        eigenvalues nearest the start (the other root), those no other mode has, in descending
        MAC with the undamped mode, each refined until one converges to a pair no other mode
        has (module docstring, "Per mode")."""
        for r, partner in [(int(r), False) for r in bad] + [(int(r), True) for r in bad_partner]:
            # near the start and the pair it reached; a partner near the other root and near
            # its mode's eigenvalue
            shifts = [self.partner[r], self.lam[r] * (1.0 + 1e-3)]
            if not partner:
                shifts = [self.start[r], self.lam[r] * (1.0 + 1e-6j)]
            near = [
                _candidates(self.pencil, complex(v), float(self.w[r]), count)
                for v in shifts
                if np.isfinite(v)
            ]
            lam, x = np.concatenate([a for a, _ in near]), np.concatenate([b for _, b in near])
            keep = self._real(lam) if partner else lam.imag >= -_REAL * np.abs(lam)
            keep &= np.array(
                [not self._taken(v, y, r, partner) for v, y in zip(lam, x, strict=True)], dtype=bool
            )
            lam, x = lam[keep], x[keep]
            p, m = self.phi[:, r], self.pencil.m
            mac = np.abs(x @ (m * p)) ** 2 / np.real(np.einsum("bi,i,bi->b", x.conj(), m, x))
            for j in np.argsort(-mac, kind="stable").tolist():
                w = self.w[r : r + 1]
                found = refine(
                    self.pencil,
                    lam[j : j + 1],
                    x[j : j + 1].copy(),
                    w,
                    iterate=self.iterate and not partner,
                )
                lam_r, x_r = complex(found.lam[0]), found.x[0]
                if lam_r.imag < 0.0:
                    lam_r, x_r = lam_r.conjugate(), np.conj(x_r)
                if found.converged[0] and not self._taken(lam_r, x_r, r, partner):
                    break
            else:
                continue  # none this round: more candidates in the next
            if partner:
                self.partner[r], self.partner_x[r], self.partner_ok[r] = lam_r, x_r, True
                continue
            self.lam[r], self.x[r], self.w[r], self.ok[r] = lam_r, x_r, found.w[0], True
            self.partner_ok[r] = False
            if self._real(np.array([lam_r]))[0]:
                self._partners(np.array([r]), found.other[:1])

    def nearest_in_mac(self, failed: NDArray[np.intp]) -> None:
        """With loss factors at each mode's frequency, a mode whose MAC with its undamped mode
        is at most 1/2 takes the eigenpair nearest that mode in the MAC among the
        2 :data:`_CANDIDATES` nearest its eigenvalue at its omega_h, omega_h = that pair's
        |Im lambda|, until omega_h no longer changes (to 1e-12; the definition of the module
        docstring: where the MAC is above 1/2 the iteration's pair is that one)."""
        p, m = self.phi, self.pencil.m
        own = _own_mac(self.x, p, m)
        count = min(2 * _CANDIDATES, 2 * self.pencil.size - 2)
        for r in np.setdiff1d(np.flatnonzero(~(own > 0.5) & ~self._real(self.lam)), failed):
            lam, x, w = complex(self.lam[r]), self.x[r], float(self.w[r])
            for _ in range(_ITERATIONS):
                near, vectors = _candidates(self.pencil, lam * (1.0 + 1e-9j), w, count)
                mac = np.abs(vectors @ (m * p[:, r])) ** 2
                mac /= np.einsum("bi,i,bi->b", vectors.conj(), m, vectors).real
                mac[near.imag < -_REAL * np.abs(near)] = -1.0  # one of each conjugate pair
                j = int(np.argmax(mac))
                lam, x, new = complex(near[j]), vectors[j], abs(near[j].imag)
                if new <= _REAL * abs(lam) or abs(new - w) <= 1e-12 * w:
                    break
                w = new
            if abs(lam.imag) > _REAL * abs(lam):
                self.lam[r], self.x[r], self.w[r] = lam, x, w

    def _taken(self, lam: complex, x: NDArray, r: int, partner: bool) -> bool:
        """Whether eigenpair (lam, x) already belongs to another entry than the one sought."""
        count = self.lam.size
        entries = self._entries()
        own = r + count if partner else r
        tol = _CLOSE * max(abs(lam), self._floor())
        for i in np.flatnonzero(np.abs(entries - lam) <= tol):
            if i == own:
                continue
            v = self._vector(int(i))
            if abs(np.vdot(v, x)) / (np.linalg.norm(v) * np.linalg.norm(x)) >= 1.0 - _PARALLEL:
                return True
        return False

    def values(
        self, failed: NDArray[np.intp]
    ) -> tuple[NDArray[np.float64], NDArray[np.complex128]]:
        """(omega_n, omega_d, zeta) and the eigenvalue of every mode (nan for ``failed``); an
        overdamped mode's row takes the eigenvalue and vector of the smaller |lambda| of its
        pair."""
        first, count = self.first, self.lam.size
        values = np.empty((first + count, 3))
        eig = np.zeros(first + count, dtype=complex)
        values[:first] = (0.0, 0.0, math.nan)
        lam = self.lam
        wn = np.abs(lam)
        with np.errstate(divide="ignore", invalid="ignore"):
            values[first:] = np.stack(
                [wn, np.abs(lam.imag), np.where(wn > 0.0, -lam.real / wn, math.nan)], axis=1
            )
        eig[first:] = lam
        real = self._real(lam)
        real[failed] = False
        values[first + failed] = math.nan
        for r in np.flatnonzero(real).tolist():
            a, b = lam[r], self.partner[r]
            values[first + r] = _mode_values(a, b)
            if abs(b) < abs(a):
                eig[first + r], self.x[r] = b, self.partner_x[r]
            else:
                eig[first + r] = a
        return values, eig


def _close_pairs(lam: NDArray[np.complex128], floor: float) -> list[tuple[int, int]]:
    """Index pairs (i, j) of eigenvalues within 1e-8 of each other (relative, ``floor`` (1/s)
    the least scale), found by sorting on |lambda| (nan entries skipped)."""
    a = np.abs(lam)
    valid = np.flatnonzero(np.isfinite(a))
    order = valid[np.argsort(a[valid], kind="stable")]
    pairs: list[tuple[int, int]] = []
    for s in range(1, order.size):
        i, j = order[:-s], order[s:]
        scale = _CLOSE * np.maximum(np.maximum(a[i], a[j]), floor)
        within = a[j] - a[i] <= scale
        if not within.any():
            break
        close = within & (np.abs(lam[i] - lam[j]) <= scale)
        pairs.extend(zip(i[close].tolist(), j[close].tolist(), strict=True))
    return pairs


def _candidates(
    pencil: ChainPencil | DensePencil, sigma: complex, w: float, count: int
) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
    """The ``count`` eigenpairs nearest ``sigma`` (1/s) at omega_h = w (rad/s): shift-invert
    Arnoldi on a chain (:func:`crankdyn.torsion.quadratic.eigenpairs_near`), the dense
    state-space eigenproblem otherwise. Vectors as rows, unit 2-norm."""
    if isinstance(pencil, ChainPencil) and (pencil.size <= _SMALL or count > 2 * pencil.size - 2):
        pencil = pencil.dense()
    if isinstance(pencil, ChainPencil):
        from scipy.sparse.linalg import ArpackNoConvergence

        for shift in (sigma, sigma * (1.0 + 1e-6j)):
            try:
                return eigenpairs_near(pencil, shift, w, count)
            except (np.linalg.LinAlgError, ArpackNoConvergence):  # an eigenvalue; no luck
                continue
        return np.zeros(0, dtype=complex), np.zeros((0, pencil.size), dtype=complex)
    n = pencil.size
    lam, vec = np.linalg.eig(_state_matrices(pencil.m, pencil.k, pencil.c + pencil.h / w))
    near = np.argsort(np.abs(lam - sigma))[:count]
    x = vec[:n, near].T
    return lam[near], x / np.linalg.norm(x, axis=1)[:, None]


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
    docstring): the MAC's optimal assignment over the oscillating eigenvalues (upper
    half-plane) and the real ones; a mode given a real eigenvalue (overdamped, or the
    rigid-body mode) takes a second real one by the MAC's assignment among those left."""
    oscillating = np.flatnonzero(lam.imag > _REAL * np.abs(lam))
    real = np.flatnonzero(np.abs(lam.imag) <= _REAL * np.abs(lam))
    cols = np.r_[oscillating, real]
    rows, picked = linear_sum_assignment(-_mac(phi, vectors[:, cols], m))  # (modes, candidates)
    chosen = cols[picked]
    need = rows[np.isin(chosen, real)]
    pool = np.setdiff1d(real, chosen)
    partner: dict[int, int] = {}
    if need.size and pool.size:
        r2, p2 = linear_sum_assignment(-_mac(phi[:, need], vectors[:, pool], m))
        partner = {int(need[i]): int(pool[j]) for i, j in zip(r2, p2, strict=True)}
    for r, a in zip(rows.tolist(), chosen.tolist(), strict=True):
        if rigid[r]:
            values[r] = (0.0, 0.0, math.nan)
            eig[r] = 0.0
            shapes[r] = phi[:, r]
            continue
        b = partner.get(r)
        if b is not None and abs(lam[b]) < abs(lam[a]):  # the smaller |lambda| first
            a, b = b, a
        values[r] = _mode_values(lam[a], None if b is None else lam[b])
        eig[r] = lam[a]
        shapes[r] = vectors[:, a]
