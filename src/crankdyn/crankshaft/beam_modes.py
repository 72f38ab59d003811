"""Coupled natural frequencies and mode shapes of the crankshaft beam model (analysis).

K phi = omega^2 M phi over the beam model's degrees of freedom
(:mod:`crankdyn.crankshaft.beam_model`), the lowest modes by the sparse symmetric Lanczos solver
in shift-invert mode (ARPACK through ``scipy.sparse.linalg.eigsh`` with ``sigma``: the modes
nearest a shift sigma < 0 below every eigenvalue are the lowest; one sparse LU factorisation
of K - sigma M; R. B. Lehoucq, D. C. Sorensen and C. Yang, *ARPACK Users' Guide*, SIAM, 1998,
sec. 3.2.3), or a dense ``scipy.linalg.eigh`` for small models.

Classification by modal kinetic energy (each shape mass-normalised, phi^T M phi = 1). The
translation of every node off the shaft axis (webs, pins) is taken relative to the axis's at its
station, q = T phi; with T^-T M phi the energy splits exactly, phi^T M phi = q^T (T^-T M phi) =
sum over degrees of freedom of q_d (T^-T M phi)_d, and each degree of freedom's share goes to
torsion (theta_z; the tangential motion of webs and pins relative to the axis), axial motion
(u_z) or bending (the axis's translations across the shaft, theta_x, theta_y; the radial
relative motion) (:func:`energy_fractions`). A pure rotation of the crankshaft is then all
torsional, the pins' tangential motion included, and a lateral translation all bending. A mode
is named after the motion with a fraction of at least ``threshold`` (default 0.75), else
"coupled" with its two largest motions; the (near-)zero modes of an unsupported motion are
"rigid".
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np
import scipy.linalg
import scipy.sparse.linalg as spla
from numpy.typing import ArrayLike, NDArray

from crankdyn.crankshaft.beam_model import CrankshaftBeamModel
from crankdyn.errors import InputError
from crankdyn.results import Result, column, scalar
from crankdyn.summary import SummaryColumn, SummaryTable, derived

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = [
    "MOTIONS",
    "BeamModesResult",
    "TorsionalComparison",
    "beam_modes",
    "compare_torsional_modes",
    "energy_fractions",
    "solve_lowest_modes",
]

HZ = 1.0 / (2.0 * math.pi)
MOTIONS = ("torsional", "axial", "bending")
"""The motions a mode's kinetic energy is split into (module docstring)."""
DENSE_SIZE = 120
"""Models up to this many degrees of freedom are solved densely."""
RIGID = 1e-9
"""A mode with omega^2 below RIGID x the largest omega^2 found is a rigid-body mode (omega = 0)."""


def solve_lowest_modes(
    stiffness: Any, mass: Any, count: int, sigma: float | None = None
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The lowest ``count`` eigenpairs of K phi = lambda M phi (module docstring).

    Parameters
    ----------
    stiffness, mass : scipy.sparse matrix
        K and M, symmetric, M positive definite (SI).
    count : int
        Number of modes, >= 1 (at most the size).
    sigma : float or None
        The shift (rad^2/s^2), below every eigenvalue; default -(2 pi x 1 Hz)^2.

    Returns
    -------
    lam : numpy.ndarray
        omega^2 (rad^2/s^2), ascending, shape (count,); rigid-body modes set to 0.
    shapes : numpy.ndarray
        Mass-normalised shapes, shape (size, count).
    """
    n = stiffness.shape[0]
    count = min(int(count), n)
    if n <= DENSE_SIZE or count >= n - 1:
        lam, vec = scipy.linalg.eigh(
            stiffness.toarray(), mass.toarray(), subset_by_index=[0, count - 1]
        )
    else:
        shift = -((2.0 * math.pi) ** 2) if sigma is None else float(sigma)
        # a fixed start vector: ARPACK's default is random, and the same model must give the
        # same digits in every front end (tests/engine/test_front_ends.py)
        start = np.random.default_rng(0).standard_normal(n)
        lam, vec = spla.eigsh(
            stiffness.tocsc(), k=count, M=mass.tocsc(), sigma=shift, which="LM", v0=start
        )
        order = np.argsort(lam)
        lam, vec = lam[order], vec[:, order]
    norm = np.sqrt(np.einsum("ij,ij->j", vec, mass @ vec))
    vec = vec / norm
    top = float(np.max(np.abs(lam))) if lam.size else 0.0
    lam = np.where(lam < RIGID * top, 0.0, lam)
    return lam, vec


def _axis_reference(
    model: CrankshaftBeamModel,
) -> tuple[NDArray[np.int_], NDArray[np.int_], NDArray[np.int_], NDArray[np.float64]]:
    """Off-axis beam nodes, the two axis nodes of their throw's webs, and the weight of the
    second (linear in z between the web mid-planes, clamped)."""
    xyz = model.node_xyz
    idx = model.dof_index
    beam = np.all(idx >= 0, axis=1)
    off = np.flatnonzero(beam & (np.hypot(xyz[:, 0], xyz[:, 1]) > 0.0))
    throw = np.clip(np.rint(model.throw_of_node[off]).astype(int), 0, model.geometry.throws - 1)
    a, b = model.web_axis_nodes[throw, 0], model.web_axis_nodes[throw, 1]
    za, zb = xyz[a, 2], xyz[b, 2]
    weight = np.clip((xyz[off, 2] - za) / (zb - za), 0.0, 1.0)
    return off, a, b, weight


def energy_fractions(model: CrankshaftBeamModel, shapes: ArrayLike) -> NDArray[np.float64]:
    """Kinetic-energy fractions of torsion, axial motion and bending.

    The translation of every node off the shaft axis (webs, pins) is taken relative to the
    axis's, interpolated between the axis nodes of its throw's two webs: q_u = u - u_axis(z)
    (q = T phi, T = I - C with C^2 = 0, so T^-1 = I + C). The relative translation across the
    shaft is split into its tangential part (torsional: the pins' and webs' motion as the throw
    twists) and its radial part (bending); the energy q_d (T^-T M phi)_d of each degree of
    freedom then sums exactly to phi^T M phi. Torsional: theta_z and the tangential relative
    motion; axial: u_z; bending: the axis's translations across the shaft, the rotations
    theta_x and theta_y and the radial relative motion (module docstring).

    Parameters
    ----------
    model : CrankshaftBeamModel
        The model.
    shapes : array_like
        Mode shapes, shape (size, modes) (any normalisation).

    Returns
    -------
    numpy.ndarray
        Shape (modes, 3): the fractions of :data:`MOTIONS` (dimensionless, each >= 0, summing
        to 1; the small negative cross terms of a consistent mass clipped).
    """
    phi = np.atleast_2d(np.asarray(shapes, dtype=float).T).T
    idx = model.dof_index
    w = np.asarray(model.mass @ phi)
    off, a, b, wt = _axis_reference(model)
    q = phi.copy()
    w_t = w.copy()
    for d in (0, 1):
        rows = idx[off, d]
        ref_a, ref_b = idx[a, d], idx[b, d]
        q[rows] -= (1.0 - wt)[:, None] * phi[ref_a] + wt[:, None] * phi[ref_b]
        np.add.at(w_t, ref_a, (1.0 - wt)[:, None] * w[rows])  # (I + C^T) M phi
        np.add.at(w_t, ref_b, wt[:, None] * w[rows])
    names = np.zeros(model.size, dtype=int)
    for d in range(6):
        names[idx[idx[:, d] >= 0, d]] = d
    kind = np.where(names == 5, 0, np.where(names == 2, 1, 2))
    energy = q * w_t
    # the relative translation of off-axis nodes: tangential part torsional, radial bending
    xyz = model.node_xyz[off]
    r = np.hypot(xyz[:, 0], xyz[:, 1])
    er = np.stack([xyz[:, 0] / r, xyz[:, 1] / r], axis=1)
    ux, uy = idx[off, 0], idx[off, 1]
    q_t = -er[:, 1:2] * q[ux] + er[:, 0:1] * q[uy]
    w_tan = -er[:, 1:2] * w_t[ux] + er[:, 0:1] * w_t[uy]
    tangential = q_t * w_tan  # rotation of (x, y) into (radial, tangential): orthogonal
    out = np.stack([energy[kind == k].sum(axis=0) for k in range(3)], axis=1)
    moved = tangential.sum(axis=0)
    out[:, 0] += moved
    out[:, 2] -= moved
    out = np.clip(out, 0.0, None)
    return out / np.maximum(out.sum(axis=1, keepdims=True), np.finfo(float).tiny)


def _labels(
    fractions: NDArray[np.float64], rigid: NDArray[np.bool_], threshold: float
) -> list[str]:
    out = []
    for f, r in zip(fractions, rigid, strict=True):
        top = int(np.argmax(f))
        if r:
            out.append(f"rigid {MOTIONS[top]}")
        elif f[top] >= threshold:
            out.append(MOTIONS[top])
        else:
            two = sorted(np.argsort(f)[-2:].tolist())
            out.append(f"coupled {MOTIONS[two[0]]}-{MOTIONS[two[1]]}")
    return out


def _decoupled_ring(model: CrankshaftBeamModel, shapes: NDArray[np.float64]) -> NDArray[np.float64]:
    """Each mode's kinetic-energy fraction in the ring of a viscous damper with no spring
    (k = 0: in the undamped modes the ring turns freely, one more rigid-body mode; the lumped
    model leaves such a ring out, :func:`crankdyn.torsion.campbell.with_dampers`); zeros when
    the damper has a spring or there is none."""
    damper = model.geometry.damper
    if damper is None or damper.stiffness > 0.0 or not model.extra_nodes:
        return np.zeros(shapes.shape[1])
    dof = int(model.dof_index[model.extra_nodes[0]].max())
    return np.asarray(damper.ring_inertia * shapes[dof] ** 2, dtype=float)


def _separate_ring(
    model: CrankshaftBeamModel, lam: NDArray[np.float64], shapes: NDArray[np.float64]
) -> NDArray[np.float64]:
    """The rigid-body shapes rotated within their (degenerate) space so that the free ring of a
    viscous damper is one of them alone, the last (:func:`_decoupled_ring`): Z Q with Q
    orthogonal, its first column Z^T M r of the ring's unit shape r; the others stay
    M-orthonormal."""
    zero = np.flatnonzero(lam == 0.0)
    damper = model.geometry.damper
    if zero.size < 2 or damper is None or damper.stiffness > 0.0 or not model.extra_nodes:
        return shapes
    dof = int(model.dof_index[model.extra_nodes[0]].max())
    c = math.sqrt(damper.ring_inertia) * shapes[dof, zero]
    if np.linalg.norm(c) < 0.99:  # the ring is not in the rigid-body space found
        return shapes
    q, _ = np.linalg.qr(np.column_stack([c, np.eye(zero.size)[:, 1:]]))
    rotated = shapes[:, zero] @ q
    out = shapes.copy()
    out[:, zero] = np.column_stack([rotated[:, 1:], rotated[:, 0]])
    return out


def _lowest(motion: str) -> Any:
    """The lowest elastic frequency (Hz) whose mode is ``motion`` (or coupled with it)."""

    def value(r: BeamModesResult) -> tuple[float, str] | None:
        for m, f, label in zip(r.mode, r.natural_frequency, r.motion, strict=True):
            if not label.startswith("rigid") and motion in label:
                return f * HZ, f"mode {int(m)}, {label}"
        return None

    return value


def _largest_difference(r: BeamModesResult) -> tuple[float, str] | None:
    """max |lumped / beam - 1| over the paired torsional modes, with the mode."""
    if r.lumped_difference is None or not np.isfinite(r.lumped_difference).any():
        return None
    d = np.where(np.isfinite(r.lumped_difference), np.abs(r.lumped_difference), -1.0)
    i = int(np.argmax(d))
    return float(d[i]), f"mode {int(r.mode[i])}, {r.natural_frequency[i] * HZ:.4g} Hz"


@dataclass(frozen=True)
class BeamModesResult(Result):
    """Coupled natural frequencies and mode shapes of a crankshaft beam model
    (:func:`beam_modes`; module docstring).

    Parameters
    ----------
    shapes : numpy.ndarray
        Mass-normalised mode shapes over the model's degrees of freedom (size x modes; not
        exported: :meth:`node_displacements`).
    model : CrankshaftBeamModel or None
        The model (not exported).
    """

    title = "Crankshaft beam model: natural frequencies"
    mode: np.ndarray = column("mode", "Mode", "")
    natural_frequency: np.ndarray = column("natural_frequencies_hz", "Natural frequency", "Hz", HZ)
    motion: np.ndarray = column("motion", "Motion", "")
    torsional_fraction: np.ndarray = column("torsional_fraction", "Torsional energy", "")
    axial_fraction: np.ndarray = column("axial_fraction", "Axial energy", "")
    bending_fraction: np.ndarray = column("bending_fraction", "Bending energy", "")
    mesh: str = scalar("mesh", "Mesh", "", summary=False)
    threshold: float = scalar("threshold", "Fraction that names a motion", "", summary=False)
    degrees_of_freedom: int = scalar("degrees_of_freedom", "Degrees of freedom", "", summary=False)
    lumped_frequency: np.ndarray | None = column(
        "lumped_frequency_hz", "Lumped model", "Hz", HZ, default=None
    )
    lumped_difference: np.ndarray | None = column(
        "lumped_difference", "Lumped / beam - 1", "", default=None
    )
    throw_torsional_stiffness: float | None = scalar(
        "throw_torsional_stiffness_Nm_per_rad",
        "Torsional stiffness of a throw (beam model)",
        "N·m/rad",
        default=None,
    )
    throw_axial_stiffness: float | None = scalar(
        "throw_axial_stiffness_N_per_m",
        "Axial stiffness of a throw (beam model)",
        "N/m",
        default=None,
    )
    lumped_model: str = scalar(
        "lumped_model", "Lumped model compared", "", default="", summary=False
    )
    lumped_mac: np.ndarray | None = column(
        "lumped_mac", "MAC with the lumped mode", "", default=None
    )
    lumped_pairing: str = scalar(
        "lumped_pairing", "How the modes are paired", "", default="", summary=False
    )
    notes: tuple[str, ...] = scalar("notes", "Notes", "", default=())
    shapes: NDArray[np.float64] = field(
        default_factory=lambda: np.zeros((0, 0)), repr=False, compare=False
    )
    model: CrankshaftBeamModel | None = field(default=None, repr=False, compare=False)

    FIGURES = (
        derived(
            "beam_lowest_frequency",
            "beam_lowest_natural_frequency_hz",
            "Lowest elastic mode of the beam model",
            "Hz",
            lambda r: next(
                (
                    (f * HZ, f"mode {int(m)}, {lab}")
                    for m, f, lab in zip(r.mode, r.natural_frequency, r.motion, strict=True)
                    if not lab.startswith("rigid")
                ),
                None,
            ),
        ),
        derived(
            "beam_lowest_torsional_frequency",
            "beam_lowest_torsional_frequency_hz",
            "Lowest torsional mode of the beam model",
            "Hz",
            _lowest("torsional"),
        ),
        derived(
            "beam_lowest_axial_frequency",
            "beam_lowest_axial_frequency_hz",
            "Lowest axial mode of the beam model",
            "Hz",
            _lowest("axial"),
        ),
        derived(
            "beam_lowest_bending_frequency",
            "beam_lowest_bending_frequency_hz",
            "Lowest bending mode of the beam model",
            "Hz",
            _lowest("bending"),
        ),
        derived(
            "beam_lumped_model_error",
            "lumped_model_largest_difference",
            "Largest difference of the lumped model's torsional modes",
            "",
            lambda r: _largest_difference(r),
            reduction="max |lumped / beam - 1| over the paired torsional modes",
            better="min",
            unavailable="no torsional mode paired with the lumped model",
        ),
    )

    @property
    def frequencies_hz(self) -> NDArray[np.float64]:
        """Natural frequencies (Hz)."""
        return self.natural_frequency * HZ

    def summary_tables(self) -> list[SummaryTable]:
        """The modes: frequency, motion and energy fractions, and the lumped model's frequency
        of the torsional ones (the comparison, :meth:`with_lumped`).

        Returns
        -------
        list of crankdyn.summary.SummaryTable
            The modes, one row per mode; the comparison, one row per paired torsional mode.
        """
        cols = (
            SummaryColumn("mode", "Mode"),
            SummaryColumn("natural_frequency_hz", "Natural frequency", "Hz"),
            SummaryColumn("motion", "Motion"),
            SummaryColumn("torsional_fraction", "Torsional energy"),
            SummaryColumn("axial_fraction", "Axial energy"),
            SummaryColumn("bending_fraction", "Bending energy"),
        )
        rows = tuple(
            (int(m), float(f) * HZ, str(lab), float(a), float(b), float(c))
            for m, f, lab, a, b, c in zip(
                self.mode,
                self.natural_frequency,
                self.motion,
                self.torsional_fraction,
                self.axial_fraction,
                self.bending_fraction,
                strict=True,
            )
        )
        out = [
            SummaryTable(
                "beam_modes",
                "Modes of the crankshaft beam model",
                cols,
                rows,
                caption="Kinetic-energy fractions of torsion, axial motion and bending.",
            )
        ]
        if self.lumped_frequency is not None and self.lumped_difference is not None:
            out.append(self._lumped_table())
        return out

    def _lumped_table(self) -> SummaryTable:
        """The paired torsional modes (:meth:`summary_tables`)."""
        assert self.lumped_frequency is not None and self.lumped_difference is not None
        paired = np.isfinite(self.lumped_frequency)
        cols = [
            SummaryColumn("mode", "Beam mode"),
            SummaryColumn("beam_frequency_hz", "Beam model", "Hz"),
            SummaryColumn("lumped_frequency_hz", "Lumped model", "Hz"),
            SummaryColumn("lumped_difference", "Lumped / beam - 1"),
            SummaryColumn("torsional_fraction", "Torsional energy"),
        ]
        values = [
            self.mode[paired],
            self.natural_frequency[paired] * HZ,
            self.lumped_frequency[paired] * HZ,
            self.lumped_difference[paired],
            self.torsional_fraction[paired],
        ]
        if self.lumped_mac is not None:
            cols.append(SummaryColumn("lumped_mac", "MAC"))
            values.append(self.lumped_mac[paired])
        rows = tuple(
            (int(row[0]), *(float(v) for v in row[1:])) for row in zip(*values, strict=True)
        )
        pairing = self.lumped_pairing or ORDER_PAIRING
        return SummaryTable(
            "lumped_comparison",
            "Torsional modes: how well the lumped model holds",
            tuple(cols),
            rows,
            caption=f"Against {self.lumped_model}; {pairing}.",
        )

    def with_lumped(self, comparison: TorsionalComparison, model: str) -> BeamModesResult:
        """These modes with a lumped model's torsional frequencies beside the paired ones
        (:func:`compare_torsional_modes`).

        Parameters
        ----------
        comparison : TorsionalComparison
            The pairs.
        model : str
            What the lumped model is, for the table's caption.

        Returns
        -------
        BeamModesResult
            A copy with :attr:`lumped_frequency` (rad/s, exported in Hz) and
            :attr:`lumped_difference` (NaN where a mode is not paired).
        """
        lumped = np.full(self.mode.size, np.nan)
        difference = np.full(self.mode.size, np.nan)
        index = np.searchsorted(self.mode, comparison.beam_mode)
        lumped[index] = comparison.lumped_frequency
        difference[index] = comparison.difference
        mac = None
        if comparison.mac is not None:
            mac = np.full(self.mode.size, np.nan)
            mac[index] = comparison.mac
        return replace(
            self,
            lumped_frequency=lumped,
            lumped_difference=difference,
            lumped_model=model,
            lumped_mac=mac,
            lumped_pairing=comparison.pairing,
        )

    def plot(self, modes: Sequence[int] | None = None, fig: Figure | None = None) -> Figure:
        """The mode shapes in three projections
        (:func:`crankdyn.plots.crankshaft.plot_beam_mode_shapes`).

        Parameters
        ----------
        modes : sequence of int or None
            Mode numbers (from 1); None: the first four elastic modes.
        fig : matplotlib.figure.Figure or None
            A figure to draw into; None makes a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.crankshaft import plot_beam_mode_shapes

        return plot_beam_mode_shapes(self, modes, fig=fig)

    def node_displacements(self, mode: int) -> NDArray[np.float64]:
        """The shape of one mode at every node (m, rad per unit modal coordinate).

        Parameters
        ----------
        mode : int
            The mode number (1-based, as :attr:`mode`).

        Returns
        -------
        numpy.ndarray
            Shape (nodes, 6): u_x, u_y, u_z, theta_x, theta_y, theta_z; 0 where inactive.

        Raises
        ------
        crankdyn.errors.InputError
            For a mode not computed (key ``mode``).
        """
        if self.model is None or not 1 <= mode <= self.shapes.shape[1]:
            raise InputError(
                f"expected a mode from 1 to {self.shapes.shape[1]}", key="mode", value=mode
            )
        idx = self.model.dof_index
        out = np.zeros(idx.shape)
        out[idx >= 0] = self.shapes[idx[idx >= 0], mode - 1]
        return out


def beam_modes(
    model: CrankshaftBeamModel,
    count: int = 12,
    *,
    threshold: float = 0.75,
    sigma: float | None = None,
) -> BeamModesResult:
    """The lowest coupled modes of a crankshaft beam model, classified (module docstring).

    Parameters
    ----------
    model : CrankshaftBeamModel
        The model (:func:`crankdyn.crankshaft.beam_model.build_beam_model`).
    count : int
        Number of modes (>= 1), rigid-body modes included.
    threshold : float
        Energy fraction (dimensionless, 0.5 < threshold <= 1) that names a mode after one motion.
    sigma : float or None
        Shift of the eigensolver (rad^2/s^2), below the lowest eigenvalue; default
        -(2 pi x 1 Hz)^2.

    Returns
    -------
    BeamModesResult
        Frequencies (rad/s, exported in Hz), motions, energy fractions and shapes.

    Raises
    ------
    crankdyn.errors.InputError
        For a count below 1 or a threshold outside (0.5, 1].

    Examples
    --------
    >>> from crankdyn.crankshaft.beam_elements import BeamMaterial
    >>> from crankdyn.crankshaft.beam_model import (CrankshaftBeamGeometry, MainBearings,
    ...     ThrowDimensions, build_beam_model)
    >>> g = CrankshaftBeamGeometry(ThrowDimensions(0.1, 0.05, 0.08, 0.04, 0.025, 0.12, 0.06),
    ...     (0.0, math.pi), BeamMaterial(210e9, 0.3, 7850.0), MainBearings(1e9))
    >>> r = beam_modes(build_beam_model(g), 4)
    >>> sorted(str(m) for m in r.motion[:2])  # no thrust bearing: free to move axially
    ['rigid axial', 'rigid torsional']
    """
    if int(count) != count or count < 1:
        raise InputError("expected a whole number of at least 1", key="count", value=count)
    if not 0.5 < threshold <= 1.0:
        raise InputError(
            "expected a fraction above 0.5, at most 1", key="threshold", value=threshold
        )
    lam, shapes = solve_lowest_modes(model.stiffness, model.mass, int(count), sigma)
    shapes = _separate_ring(model, lam, shapes)
    fractions = energy_fractions(model, shapes)
    labels = _labels(fractions, lam == 0.0, threshold)
    ring = _decoupled_ring(model, shapes)
    for j in np.flatnonzero((lam == 0.0) & (ring > 0.99)):
        labels[j] = "rigid damper ring"
    return BeamModesResult(
        mode=np.arange(1, lam.size + 1),
        natural_frequency=np.sqrt(lam),
        motion=np.array(labels),
        torsional_fraction=fractions[:, 0],
        axial_fraction=fractions[:, 1],
        bending_fraction=fractions[:, 2],
        mesh=model.mesh_note,
        threshold=float(threshold),
        degrees_of_freedom=model.size,
        notes=(
            "Rotating frame, no gyroscopic or centrifugal terms, isotropic bearings; the "
            "reciprocating masses as their mean over a revolution (m_j / 2 across the shaft).",
        ),
        shapes=shapes,
        model=model,
    )


@dataclass(frozen=True)
class TorsionalComparison(Result):
    """The beam model's torsional modes against a lumped torsional chain's
    (:func:`compare_torsional_modes`).

    Parameters
    ----------
    mac : numpy.ndarray or None
        The modal assurance criterion of each pair (dimensionless) when paired by shape.
    pairing : str
        How the modes were paired, for captions.
    beam_mode : numpy.ndarray
        The beam model's mode number of each pair (int).
    """

    title = "Torsional modes: beam model against the lumped chain"
    beam_frequency: np.ndarray = column("beam_frequency_hz", "Beam model", "Hz", HZ)
    lumped_frequency: np.ndarray = column("lumped_frequency_hz", "Lumped chain", "Hz", HZ)
    difference: np.ndarray = column("difference", "Lumped / beam - 1", "")
    motion: np.ndarray = column("motion", "Beam mode's motion", "")
    mac: np.ndarray | None = column("mac", "MAC", "", default=None)
    pairing: str = scalar("pairing", "How the modes are paired", "", default="", summary=False)
    beam_mode: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))

    FIGURES = (
        derived(
            "beam_lumped_model_error",
            "lumped_model_largest_difference",
            "Largest difference of the lumped chain",
            "",
            lambda r: (
                None
                if r.difference.size == 0
                else (
                    float(np.max(np.abs(r.difference))),
                    f"torsional mode {int(np.argmax(np.abs(r.difference))) + 1}",
                )
            ),
        ),
    )

    def summary_tables(self) -> list[SummaryTable]:
        """One row per pair of torsional modes.

        Returns
        -------
        list of crankdyn.summary.SummaryTable
            The comparison table.
        """
        cols = [
            SummaryColumn("beam_mode", "Beam mode"),
            SummaryColumn("beam_frequency_hz", "Beam model", "Hz"),
            SummaryColumn("lumped_frequency_hz", "Lumped chain", "Hz"),
            SummaryColumn("difference", "Lumped / beam - 1"),
        ]
        values = [self.beam_frequency * HZ, self.lumped_frequency * HZ, self.difference]
        if self.mac is not None:
            cols.append(SummaryColumn("mac", "MAC"))
            values.append(self.mac)
        rows = tuple(
            (int(m), *(float(v) for v in row))
            for m, *row in zip(self.beam_mode, *values, strict=True)
        )
        return [
            SummaryTable(
                "torsional_comparison",
                "How well the lumped model holds",
                tuple(cols),
                rows,
                caption=self.pairing or ORDER_PAIRING,
            )
        ]


ORDER_PAIRING = (
    "the k-th torsional beam mode (torsional energy at least one half) paired with the k-th "
    "elastic lumped mode"
)
SHAPE_PAIRING = (
    "each torsional beam mode (torsional energy at least one half) paired with the elastic "
    "lumped mode whose shape it matches (the largest sum of MAC; pairs with MAC at least one half)"
)


def compare_torsional_modes(
    result: BeamModesResult,
    lumped: Sequence[float] | NDArray[np.float64],
    *,
    minimum: float = 0.5,
    shapes: tuple[ArrayLike, ArrayLike] | None = None,
) -> TorsionalComparison:
    """Pair the beam model's torsional modes with a lumped chain's: in ascending order, or by
    their shapes.

    A beam mode counts as torsional when its torsional energy fraction is at least ``minimum``
    (rigid modes excluded). Without ``shapes`` the k-th such mode is paired with the k-th
    positive lumped frequency; this crosses pairs where a mode of one model has no counterpart
    below the other's next (a crankshaft mode that bending lowers below a shaft-line mode).
    With ``shapes`` the pairs are those of the largest sum of the modal assurance criterion,
    MAC = (phi_b . phi_l)^2 / (|phi_b|^2 |phi_l|^2) over the lumped model's degrees of freedom
    (R. J. Allemang and D. L. Brown, "A correlation coefficient for modal vector analysis",
    Proc. 1st IMAC, 1982, 110-116), an assignment problem
    (``scipy.optimize.linear_sum_assignment``), and pairs with MAC below one half are dropped.

    Parameters
    ----------
    result : BeamModesResult
        The beam model's modes.
    lumped : sequence of float
        The lumped chain's natural frequencies (rad/s; zeros, the rigid-body mode, are
        skipped), e.g. ``crankdyn.torsion.natural_modes(model).natural_frequency``.
    minimum : float
        Torsional energy fraction that makes a beam mode torsional (dimensionless).
    shapes : tuple of two arrays, or None
        The beam modes' rotations theta_z at the lumped model's degrees of freedom (dof x beam
        mode, every mode of ``result``) and the lumped modes' shapes (dof x lumped mode, in the
        order of ``lumped``); any normalisation.

    Returns
    -------
    TorsionalComparison
        The pairs, in the beam's order.
    """
    elastic = ~np.char.startswith(result.motion.astype(str), "rigid")
    use = np.flatnonzero(elastic & (result.torsional_fraction >= minimum))
    frequencies = np.asarray(lumped, dtype=float)
    if shapes is None:
        order = np.argsort(frequencies)
        chain = order[frequencies[order] > 0.0]
        n = min(use.size, chain.size)
        use, chain, mac, pairing = use[:n], chain[:n], None, ORDER_PAIRING
    else:
        from scipy.optimize import linear_sum_assignment

        chain = np.flatnonzero(frequencies > 0.0)
        b = np.asarray(shapes[0], dtype=float)[:, use]
        c = np.asarray(shapes[1], dtype=float)[:, chain]
        b = b / np.maximum(np.linalg.norm(b, axis=0), np.finfo(float).tiny)
        c = c / np.maximum(np.linalg.norm(c, axis=0), np.finfo(float).tiny)
        table = (b.T @ c) ** 2
        rows, cols = linear_sum_assignment(table, maximize=True)
        keep = table[rows, cols] >= 0.5
        rows, cols = rows[keep], cols[keep]
        use, chain, mac, pairing = use[rows], chain[cols], table[rows, cols], SHAPE_PAIRING
    beam = result.natural_frequency[use]
    return TorsionalComparison(
        beam_frequency=beam,
        lumped_frequency=frequencies[chain],
        difference=frequencies[chain] / beam - 1.0,
        motion=result.motion[use],
        mac=mac,
        pairing=pairing,
        beam_mode=result.mode[use],
    )
