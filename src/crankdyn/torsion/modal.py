"""Natural frequencies and mode shapes of a torsional model (analysis and result).

The undamped free vibration M theta'' + K theta = 0 with theta = phi sin(omega t) gives the
symmetric-definite eigenproblem K phi = omega^2 M phi (seed 003, 多质量扭振系统: one equation
per mass, eq. 4-13 generalised). M is diagonal, so with u = M^(1/2) phi it becomes the standard
symmetric problem (M^-1/2 K M^-1/2) u = omega^2 u. For a chain that matrix is tridiagonal
(d_i = K_ii / J_i, e_i = K_i,i+1 / sqrt(J_i J_i+1)) and is solved by LAPACK's tridiagonal
divide-and-conquer solver (``dstevd``: Cuppen's method, Gu and Eisenstat's stable deflation; it
never forms the dense matrix and was the fastest tridiagonal driver with all eigenvectors in
bench/, four times faster than ``dstemr`` at 1000 masses); branched or looped models use the
general symmetric-definite solver (``scipy.linalg.eigh(K, M)``).

A free model (no grounded shaft) has exactly one rigid-body mode, omega = 0 with all masses
turning together; it is reported as exactly 0.0 with the shape of ones.

Mode numbers (docs/conventions.md): the elastic modes are numbered 1, 2, ... in ascending
frequency; the rigid-body mode of a free model is mode 0. So "mode 1" is the first elastic mode
of every model, free or grounded, as TVC reports and openTorsion's users read it.

Other solvers give the same frequencies independently: Holzer's method
(:mod:`crankdyn.torsion.holzer`), the transfer-matrix method (:mod:`crankdyn.torsion.transfer`)
and the closed forms of seed 003 (:mod:`crankdyn.torsion.closed_form`).

Reported per mode: the natural frequency, the mode shape (reflected amplitudes of the masses in
listing order, normalised to a largest absolute amplitude of 1, the first non-zero amplitude
positive), the nodes (where the amplitude passes through zero: at a fraction t = theta_a /
(theta_a - theta_b) along a shaft from its first mass, the twist being uniform along a uniform
shaft), and the modal inertia J_r = sum J_i phi_i^2 and stiffness omega_r^2 J_r of that
normalisation.

The shapes are normalised, their round-off thresholds and nodes found by
:mod:`crankdyn.torsion.nodes` (nodes only where the shape resolves them); a large chain's modes
are computed and written a block at a time by :mod:`crankdyn.torsion.mode_blocks`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cached_property, lru_cache
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from crankdyn.docs import ref
from crankdyn.errors import InputError
from crankdyn.results import Result, array, column, freeze, scalar
from crankdyn.summary import SummaryColumn, SummaryTable, derived
from crankdyn.torsion.model import ChainArrays, TorsionModel
from crankdyn.torsion.nodes import (
    FEW,
    ModeRows,
    NodeArrays,
    Nodes,
    chain_node_counts,
    distinct_thresholds,
    mode_rows,
    normalise_shapes,
    roundoff_thresholds,
)

if TYPE_CHECKING:
    from collections.abc import Iterable

    from matplotlib.figure import Figure

    from crankdyn.plausibility import PlausibilityWarning

__all__ = [
    "SOLVERS",
    "ModalResult",
    "Node",
    "chain_frequencies",
    "eigen_modes",
    "natural_modes",
]

SOLVERS = ("eigen", "holzer", "transfer", "closed-form")
HZ = 1.0 / (2.0 * math.pi)
BISECTION_TOL = 2.0 * np.finfo(float).tiny
"""Absolute tolerance of ``dstebz``: twice the underflow threshold, LAPACK's setting for the
most accurate eigenvalues (0 would mean eps x ||T||: 1e-9 relative on the lowest modes of a
1000-mass chain; this agrees with ``dstevd`` to 5e-11)."""


@dataclass(frozen=True)
class Node(Result):
    """A node of a mode: on a shaft (at a fraction of its length from its first mass), or, when
    the shape is round-off there (:mod:`crankdyn.torsion.nodes`), somewhere in a round-off
    region of masses (``determined`` False; ``mass`` set when the region is a single mass).

    The fraction is t = theta_a / (theta_a - theta_b) of the amplitudes at the shaft's ends, the
    twist being uniform along a uniform shaft (seed 003, 多质量扭振系统: the node of a two-mass
    system divides the shaft in the inverse ratio of the inertias).

    Examples
    --------
    >>> Node(shaft=("a", "b"), fraction=0.25).describe()
    'a - b at 0.250'
    >>> Node(mass="c", region=("c", "c"), determined=False).describe()
    'at or near c (round-off, undetermined)'
    """

    shaft: tuple[str, str] | None = scalar("shaft", "Shaft", "", default=None)
    mass: str | None = scalar("mass", "At or near mass", "", default=None)
    fraction: float | None = scalar(
        "fraction_from_first", "Position along the shaft from its first mass", "", default=None
    )
    region: tuple[str, str] | None = scalar(
        "roundoff_region", "Somewhere in the round-off region (first, last mass)", "", default=None
    )
    determined: bool = scalar("determined", "Position determined", "", default=True)

    def describe(self) -> str:
        """The node in words, as the modes table shows it.

        Returns
        -------
        str
            ``"a - b at 0.250"`` (on the shaft from a to b, at that fraction of its length from
            a), ``"at m"`` (at rest at a mass) or, in a round-off region, ``"at or near m"`` /
            ``"between a and b"`` with ``(round-off, undetermined)``.
        """
        if not self.determined:
            if self.mass is not None:
                return f"at or near {self.mass} (round-off, undetermined)"
            first, last = self.region if self.region is not None else ("?", "?")
            return f"between {first} and {last} (round-off, undetermined)"
        if self.mass is not None:
            return f"at {self.mass}"
        a, b = self.shaft if self.shaft is not None else ("?", "?")
        return f"{a} - {b} at {self.fraction:.3f}"


NATURAL_FREQUENCY_MODES = (1, 2, 3)
"""The elastic modes whose natural frequencies are key figures of their own."""


def natural_frequency(modes: ModalResult, n: int) -> float | None:
    """The natural frequency (Hz) of elastic mode ``n``; elastic modes are numbered from 1, a
    free model's rigid-body mode is 0 (:meth:`ModalResult.index`); None when the model has fewer
    modes.

    Parameters
    ----------
    modes : ModalResult
        The model's modes.
    n : int
        1 for the first elastic mode.

    Returns
    -------
    float or None
        The frequency (Hz).
    """
    if not modes.mode.size or not 1 <= n <= int(modes.mode[-1]):
        return None
    return float(modes.frequencies_hz[modes.index(n)])


def _frequency_of(n: int) -> Callable[[ModalResult], float | None]:
    return lambda modes: natural_frequency(modes, n)


def installation_inertia(model: TorsionModel | None) -> float | None:
    """The inertia of a model's masses and dampers as written, each at its own shaft's speed
    (the design search's added-inertia constraint).

    Parameters
    ----------
    model : TorsionModel or None
        The model.

    Returns
    -------
    float or None
        sum J_i + sum J_damper (kg m^2); None without a model.
    """
    if model is None:
        return None
    masses = sum(float(m.inertia) for m in model.masses)
    return masses + sum(float(getattr(d, "inertia", 0.0) or 0.0) for d in model.dampers)


@dataclass(frozen=True)
class ModalResult(Result):
    """Natural frequencies, mode shapes, nodes and modal inertias of a torsional model
    (:func:`natural_modes`; module docstring).

    Parameters
    ----------
    all_natural_frequency : numpy.ndarray or None
        Every natural frequency of the model (rad/s, ascending; not exported) when only the
        lowest modes were computed and the whole spectrum was, else None.
    highest_natural_frequency : float or None
        The model's highest natural frequency (rad/s; not exported) when only the lowest modes
        were computed, else None.
    model : TorsionModel or None
        The model (not exported): names the shafts and masses of the nodes.
    shapes_dof : numpy.ndarray or None
        The normalised mode shapes by degree of freedom (mode x dof, dimensionless; not
        exported), for locating nodes and the mass-normalised :attr:`eigenvectors`.
    node_source : Nodes or None
        The nodes and round-off regions of every mode in compact form (indices; not exported),
        found when first asked for (:attr:`node_arrays`).
    warnings : tuple of crankdyn.plausibility.PlausibilityWarning
        The input warnings of the model's file(s) (:mod:`crankdyn.io.plausibility`), given by
        the analysis session (not exported as a field: ``to_dict`` lists them under
        ``input_warnings``).

    Examples
    --------
    >>> from crankdyn.torsion import TorsionModel
    >>> r = natural_modes(TorsionModel.chain_of([1.0, 1.0], [1e4]))
    >>> [round(float(f), 4) for f in r.frequencies_hz]  # sqrt(2 k / J) / 2 pi
    [0.0, 22.5079]
    >>> r.index(1), r.nodes[1][0].describe()
    (1, '1 - 2 at 0.500')
    """

    title = "Natural frequencies"
    mode: np.ndarray = column("mode", "Mode", "")
    natural_frequency: np.ndarray = column("natural_frequencies_hz", "Natural frequency", "Hz", HZ)
    """Natural frequency omega_r (rad/s; exported in Hz, :attr:`frequencies_hz`)."""
    node_count: np.ndarray = column("node_counts", "Nodes", "")
    nodes_resolved: np.ndarray = column("nodes_resolved", "Nodes resolved", "")
    """Whether the whole shape is above round-off (:mod:`crankdyn.torsion.nodes`); else the node
    count is a lower bound and the round-off regions are listed."""
    modal_inertia: np.ndarray = column("modal_inertias_kg_m2", "Modal inertia", "kg·m²")
    modal_stiffness: np.ndarray = column(
        "modal_stiffnesses_Nm_per_rad", "Modal stiffness", "N·m/rad"
    )
    mode_shapes: np.ndarray = array("mode_shapes", "Mode shapes (largest amplitude 1)", "")
    masses: tuple[str, ...] = scalar("masses", "Masses", "", summary=False)
    solver: str = scalar("solver", "Solver", "")
    structure: str = scalar("structure", "Structure", "")
    free: bool = scalar("free", "Free (rigid-body mode)", "")
    model_name: str = scalar("model", "Model", "", summary=False)
    modes_of_the_model: int | None = scalar(
        "modes_of_the_model", "Modes of the model (the lowest are listed)", "", default=None
    )
    """Set when only the lowest modes were computed (``natural_modes(..., count=)``)."""
    all_natural_frequency: np.ndarray | None = field(default=None, repr=False, compare=False)
    """Every natural frequency of the model (rad/s) when only the lowest modes were computed
    and the whole spectrum was (a branched model's, the block-wise writer's); None for a
    chain's lowest modes, whose thresholds need only the spectrum's edges."""
    highest_natural_frequency: float | None = field(default=None, repr=False, compare=False)
    """The model's highest natural frequency (rad/s) when only the lowest modes are listed."""
    model: TorsionModel | None = field(default=None, repr=False, compare=False)
    shapes_dof: np.ndarray | None = field(default=None, repr=False, compare=False)
    """Normalised mode shapes by degree of freedom (mode x dof), for locating nodes."""

    node_source: Nodes | None = field(default=None, repr=False, compare=False)
    """The nodes and round-off regions of all modes, found when first asked for."""
    warnings: tuple[PlausibilityWarning, ...] = field(default=(), repr=False, compare=False)

    @property
    def node_arrays(self) -> NodeArrays | None:
        """The nodes and round-off regions of all modes in compact form (indices into the
        modes, the model's shafts and its degrees of freedom), located when first asked for:
        the node counts and :attr:`nodes_resolved` are computed with the modes, the positions
        only for the nodes, the JSON and the streamed writers."""
        return None if self.node_source is None else self.node_source.arrays

    def index(self, mode: int) -> int:
        """Row of a mode number (docs/conventions.md: elastic modes from 1, a free model's
        rigid-body mode 0).

        Parameters
        ----------
        mode : int
            The mode number.

        Returns
        -------
        int
            Its row in the per-mode arrays.

        Raises
        ------
        InputError
            For a number the result does not hold (key ``mode``, the value given; the message
            says which modes there are).
        """
        first = int(self.mode[0]) if self.mode.size else 1
        if (
            isinstance(mode, bool)
            or not isinstance(mode, (int, np.integer))
            or not first <= mode < first + self.mode.size
        ):
            last = first + self.mode.size - 1
            raise InputError(
                f"the model has modes 1 to {last}"
                + (" and the rigid-body mode 0" if self.free else "")
                + f" ({ref('conventions')})",
                key="mode",
                value=mode,
            )
        return int(mode) - first

    @cached_property
    def eigenvectors(self) -> NDArray[np.float64] | None:
        """Mass-normalised eigenvectors (dof x mode, phi^T M phi = I; rad per sqrt(kg·m²)),
        made from :attr:`shapes_dof` when first asked for (no copy is held otherwise)."""
        if self.shapes_dof is None:
            return None
        return _readonly(self.shapes_dof.T / np.sqrt(self.modal_inertia)[None, :])

    @cached_property
    def nodes(self) -> tuple[tuple[Node, ...], ...]:
        """The nodes of every mode (none for the rigid-body mode): located ones on shafts, then
        the undetermined ones in round-off regions."""
        out: list[list[Node]] = [[] for _ in range(self.mode.size)]
        arrays = self.node_arrays
        if arrays is None or self.model is None:
            return tuple(tuple(n) for n in out)
        shafts = self.model.shafts
        for r, s, t in zip(arrays.shaft_mode, arrays.shaft, arrays.fraction, strict=True):
            out[r].append(Node(shaft=shafts[s].between, fraction=float(t)))
        names = self.model.dof_names
        for r, a, b in zip(arrays.open_mode, arrays.open_first, arrays.open_last, strict=True):
            out[r].append(
                Node(
                    mass=names[a] if a == b else None,
                    region=(names[a], names[b]),
                    determined=False,
                )
            )
        return tuple(tuple(n) for n in out)

    @cached_property
    def roundoff_regions(self) -> tuple[tuple[tuple[str, str], ...], ...]:
        """Per mode the (first, last) masses of every stretch of the shape that is round-off
        (:mod:`crankdyn.torsion.nodes`), where nodes cannot be located."""
        out: list[list[tuple[str, str]]] = [[] for _ in range(self.mode.size)]
        arrays = self.node_arrays
        if arrays is None or self.model is None:
            return tuple(tuple(n) for n in out)
        names = self.model.dof_names
        for r, a, b in zip(
            arrays.region_mode, arrays.region_first, arrays.region_last, strict=True
        ):
            out[r].append((names[a], names[b]))
        return tuple(tuple(n) for n in out)

    def to_dict(self) -> dict[str, Any]:
        """The result as a JSON-ready dict (:meth:`crankdyn.results.Result.to_dict`) with the
        nodes.

        Returns
        -------
        dict
            The exported fields (frequencies in Hz, modal inertias in kg·m², modal stiffnesses
            in N·m/rad, shapes dimensionless), then ``nodes``: one list per mode of {shaft,
            fraction_from_first, determined} or, for a node in a round-off region,
            {roundoff_region, determined: false} entries; ``roundoff_regions``: one list per mode
            of [first, last] masses.
        """
        out = super().to_dict()
        out["nodes"] = [[n.to_dict() for n in mode] for mode in self.nodes]
        out["roundoff_regions"] = [[list(r) for r in mode] for mode in self.roundoff_regions]
        return out

    FIGURES = (
        *(
            derived(
                f"natural_frequency_{n}",
                f"natural_frequency_{n}_hz",
                f"Natural frequency of elastic mode {n}",
                "Hz",
                _frequency_of(n),
                headline=n == 1,
                description=f"Torsional natural frequency of the {n}. elastic mode (an engine: its "
                "[torsion] model)",
            )
            for n in NATURAL_FREQUENCY_MODES
        ),
        derived(
            "installation_inertia",
            "installation_inertia_kgm2",
            "Inertia of the torsional model's masses and dampers",
            "kg·m²",
            lambda r: installation_inertia(r.model),
            better="min",
            description="Sum of the mass and damper inertias as written (each at its own "
            "shaft's speed)",
        ),
    )

    def summary_tables(self) -> list[SummaryTable]:
        """The natural frequency and node count of every mode.

        Returns
        -------
        list of crankdyn.summary.SummaryTable
            The tables.
        """
        columns = (
            SummaryColumn("mode", "Mode"),
            SummaryColumn("natural_frequency_hz", "Natural frequency", "Hz"),
            SummaryColumn("natural_frequency_cpm", "Natural frequency (cycles/min)"),
            SummaryColumn("nodes", "Nodes"),
            SummaryColumn("node_positions", "Node positions"),
        )
        rows = tuple(
            (
                int(m),
                float(f),
                float(f) * 60.0,
                str(int(n)) if ok else f"at least {int(n)}",
                "; ".join(
                    [node.describe() for node in nodes]
                    + [f"round-off in {a}…{b}: nodes undetermined" for a, b in regions]
                )
                or "-",
            )
            for m, f, n, ok, nodes, regions in zip(
                self.mode,
                self.frequencies_hz,
                self.node_count,
                self.nodes_resolved,
                self.nodes,
                self.roundoff_regions,
                strict=True,
            )
        )
        return [SummaryTable("natural_frequencies", "Natural frequencies and nodes", columns, rows)]

    @property
    def frequencies_hz(self) -> NDArray[np.float64]:
        """Natural frequencies (Hz), omega_r / 2 pi."""
        return self.natural_frequency * HZ

    def columns(self) -> dict[str, np.ndarray]:
        """The per-mode columns, then one amplitude column per mass (``amplitude_<n>``).

        Returns
        -------
        dict of str to numpy.ndarray
            {key: values per mode} in the units of the keys; the amplitudes dimensionless.
        """
        out = super().columns()
        for i in range(len(self.masses)):
            out[f"amplitude_{i + 1}"] = np.asarray(self.mode_shapes[:, i], dtype=float)
        return out

    def column_labels(self) -> dict[str, tuple[str, str]]:
        """Label and unit of every column of :meth:`columns`.

        Returns
        -------
        dict of str to (str, str)
            {column key: (label, unit)}; ``amplitude_<n>``: ("Amplitude <mass>", "").
        """
        out = super().column_labels()
        for i, name in enumerate(self.masses):
            out[f"amplitude_{i + 1}"] = (f"Amplitude {name}", "")
        return out

    def plot(self, modes: Iterable[int] | None = None, fig: Figure | None = None) -> Figure:
        """Mode shapes of the elastic modes (:func:`crankdyn.plots.torsion.plot_mode_shapes`).

        Parameters
        ----------
        modes : iterable of int or None
            Mode numbers to draw (elastic modes from 1); None: the first six.
        fig : matplotlib.figure.Figure or None
            A figure to draw into; None makes a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.torsion import plot_mode_shapes

        return plot_mode_shapes(self, modes=modes, fig=fig)


def eigen_modes(
    model: TorsionModel, count: int | None = None, *, free: bool | None = None
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Eigenvalues and mass-normalised eigenvectors of K phi = omega^2 M phi by the structured
    symmetric solver (module docstring: seed 003, eq. 4-13 generalised; LAPACK ``dstevd`` on a
    chain's tridiagonal matrix, ``scipy.linalg.eigh(K, M)`` otherwise).

    Parameters
    ----------
    model : TorsionModel
        The lumped model.
    count : int or None
        The lowest ``count`` modes only (a chain's by bisection and inverse iteration, LAPACK
        ``dstebz`` and ``dstein``: memory of N x count, not N x N; scipy's ``dstemr`` wrapper
        allocates N x N); None: every mode.
    free : bool or None
        ``model.is_free`` when the caller has it (None: asked of the model).

    Returns
    -------
    lam : numpy.ndarray
        omega^2 (rad²/s², ascending; exactly 0 for a free model's rigid-body mode).
    phi : numpy.ndarray
        Eigenvectors (dof x mode, rad per sqrt(kg·m²)), phi^T M phi = I.

    Examples
    --------
    >>> from crankdyn.torsion import TorsionModel
    >>> lam, phi = eigen_modes(TorsionModel.chain_of([1.0, 1.0], [1e4]))
    >>> [round(float(v), 6) for v in lam]  # 0 and 2 k / J
    [0.0, 20000.0]
    """
    J = model.dof_inertia
    chain = model.chain
    n = J.size
    partial = count is not None and count < n
    if chain is not None:
        a = chain.normalised
        d, s = a.diagonal, a.root_inertia
        if n == 1:
            lam, u = d.copy(), np.ones((1, 1))
        elif partial:
            import scipy.linalg  # imported here: keeps the start-up light

            lam, u = scipy.linalg.eigh_tridiagonal(
                d,
                a.off_diagonal,
                select="i",
                select_range=(0, (count or n) - 1),
                lapack_driver="stebz",
                tol=BISECTION_TOL,
            )
        else:
            lam, u = _tridiagonal_eigh(d, a.off_diagonal)
        u /= s[:, None]
        phi = u
    else:
        import scipy.linalg  # imported here: keeps the start-up light

        lam, phi = scipy.linalg.eigh(
            model.stiffness_matrix(),
            np.diag(J),
            subset_by_index=(0, count - 1) if partial and count is not None else None,
        )
    lam = np.maximum(lam, 0.0)
    if model.is_free if free is None else free:
        lam[0] = 0.0
        phi[:, 0] = 1.0 / math.sqrt(float(J.sum()))
    return lam, phi


def _tridiagonal_eigh(d: np.ndarray, e: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """All eigenvalues (ascending) and orthonormal eigenvectors (columns) of the symmetric
    tridiagonal matrix with diagonal d and off-diagonal e, by LAPACK ``dstevd``."""
    lam, u, info = _stevd()(d, e, compute_v=1)
    if info != 0:
        raise np.linalg.LinAlgError(f"the tridiagonal eigensolver failed (dstevd info {info})")
    return lam, u


def chain_frequencies(model: TorsionModel) -> NDArray[np.float64]:
    """Every natural frequency without the mode shapes (LAPACK ``dsterf``, the Pal-Walker-Kahan
    QL/QR iteration, on a chain's tridiagonal matrix; the dense symmetric-definite solver
    otherwise; module docstring).

    Parameters
    ----------
    model : TorsionModel
        The lumped model.

    Returns
    -------
    numpy.ndarray
        omega (rad/s, ascending; exactly 0 for a free model's rigid-body mode).

    Examples
    --------
    >>> from crankdyn.torsion import TorsionModel
    >>> [round(float(w), 4) for w in chain_frequencies(TorsionModel.chain_of([1.0, 1.0], [1e4]))]
    [0.0, 141.4214]
    """
    import scipy.linalg  # imported here: keeps the start-up light

    J = model.dof_inertia
    chain = model.chain
    if chain is not None and chain.size > 1:
        a = chain.normalised
        lam = scipy.linalg.eigvalsh_tridiagonal(a.diagonal, a.off_diagonal, lapack_driver="sterf")
    else:
        lam = scipy.linalg.eigh(model.stiffness_matrix(), np.diag(J), eigvals_only=True)
    lam = np.maximum(lam, 0.0)
    if model.is_free:
        lam[0] = 0.0
    return np.sqrt(lam)


@lru_cache(maxsize=1)
def _stevd():
    """LAPACK's ``dstevd`` (looked up once: the look-up costs as much as a small solve)."""
    import scipy.linalg  # imported here: keeps the start-up light

    (stevd,) = scipy.linalg.get_lapack_funcs(("stevd",), (np.zeros(1), np.zeros(1)))
    return stevd


def _solve(
    model: TorsionModel, solver: str, count: int | None, free: bool
) -> tuple[np.ndarray, np.ndarray]:
    """(omega (rad/s), shapes (dof x mode)) by the named solver (``count``: at least the lowest
    ``count`` modes)."""
    if solver == "eigen":
        lam, phi = eigen_modes(model, count, free=free)
        return np.sqrt(lam), phi
    if solver == "holzer":
        from crankdyn.torsion.holzer import holzer_frequencies

        return holzer_frequencies(model)
    if solver == "transfer":
        from crankdyn.torsion.transfer import transfer_frequencies

        return transfer_frequencies(model)
    if solver == "closed-form":
        from crankdyn.torsion.closed_form import closed_form_modes

        return closed_form_modes(model)
    raise InputError(f"expected one of {', '.join(SOLVERS)}", key="solver", value=solver)


def _readonly(arr: np.ndarray) -> np.ndarray:
    """Mark an array this module created (and hands over) read-only, without a copy."""
    arr.setflags(write=False)
    return arr


def natural_modes(
    model: TorsionModel, solver: str = "eigen", count: int | None = None
) -> ModalResult:
    """Natural frequencies and mode shapes of a torsional model (K phi = omega^2 M phi, seed
    003 eq. 4-13 generalised; module docstring).

    Parameters
    ----------
    model : TorsionModel
        The lumped model (inertias in kg·m², stiffnesses in N·m/rad).
    solver : str
        ``"eigen"`` (structured symmetric eigen solver, any model), ``"holzer"`` (Holzer's
        method), ``"transfer"`` (transfer-matrix method), both for chains, or ``"closed-form"``
        (seed 003's one-, two- and three-mass formulas).
    count : int or None
        The lowest ``count`` modes only (default: every mode). The eigen solver then computes
        only their shapes (memory N x count); ``modes_of_the_model`` and
        ``all_natural_frequency`` say what the model has beyond them.

    Returns
    -------
    ModalResult
        Every mode (or the lowest ``count``), ascending (0.0 first for a free model):
        frequencies in rad/s (exported in Hz), shapes with a largest amplitude of 1, nodes.

    Raises
    ------
    InputError
        For ``count`` below 1 (key ``count``) or an unknown ``solver`` (key ``solver``, naming
        the solvers).

    Examples
    --------
    Two equal masses on a shaft: omega = sqrt(2 k / J), the node in the middle (seed 003):

    >>> from crankdyn.torsion import TorsionModel
    >>> r = natural_modes(TorsionModel.chain_of([1.0, 1.0], [1e4]))
    >>> round(float(r.natural_frequency[1]), 4), r.node_count.tolist()
    (141.4214, [0, 1])
    """
    total = model.dof_inertia.size
    if count is not None and count < 1:
        raise InputError("expected at least one mode", key="count", value=count)
    partial = count is not None and count < total
    free = model.is_free
    if solver == "eigen" and not partial and 1 < total <= _ONE_PASS:
        chain = model.chain
        if chain is not None:
            return _chain_modes(model, chain, free)
    return _modes(model, solver, count, partial, free)


_ONE_PASS = 128
"""Degrees of freedom up to which :func:`natural_modes` solves a chain in one pass
(:func:`_chain_modes`: a third quicker at 10 masses, where numpy's per-call cost is most of the
time, 4 % at 100); beyond, step by step (:func:`_modes`), which was as quick from 150 to 300
masses, where localised modes send most rows through the general branches."""


def _modes(
    model: TorsionModel, solver: str, count: int | None, partial: bool, free: bool
) -> ModalResult:
    """:func:`natural_modes` by any solver, step by step (:func:`_solve`, :func:`mode_rows`,
    :func:`modal_result`): the lowest modes, other solvers, branched models, a single mass."""
    total = model.dof_inertia.size
    omega, phi = _solve(model, solver, count if partial else None, free)
    omega = np.asarray(omega, dtype=float)
    phi = np.asarray(phi, dtype=float)
    if partial:
        omega, phi = omega[:count], phi[:, :count]
    if free:
        omega[0] = 0.0
    if solver != "eigen" or not phi.flags.writeable:
        phi = phi.copy()  # normalised in place below: only the eigen solver's own array
    all_omega = None
    spectrum = omega
    highest = None
    if partial and solver == "eigen" and model.chain is not None:
        spectrum = np.concatenate([omega, _spectrum_edges(model, omega.size)])
        highest = float(spectrum[-1])
    elif partial:
        all_omega = spectrum = chain_frequencies(model)
        highest = float(all_omega[-1])
    tau = roundoff_thresholds(spectrum * spectrum)[: omega.size]
    rows = mode_rows(model, phi.T, tau, free, lazy=True)
    del phi
    total_or_none = total if partial else None
    return modal_result(model, solver, omega, rows, 0, total_or_none, all_omega, free, highest)


def _spectrum_edges(model: TorsionModel, count: int) -> NDArray[np.float64]:
    """omega (rad/s) of the first mode not listed (index ``count``) and, when it is not the
    last, of the highest: with the lowest ``count`` they give every round-off threshold of
    those modes (:func:`~crankdyn.torsion.nodes.roundoff_thresholds`: a mode's gap needs only
    its neighbours, ||A||_2 only the largest eigenvalue), each by bisection (LAPACK
    ``dstebz``: O(n) per eigenvalue) instead of the whole spectrum (``dsterf``, O(n^2))."""
    import scipy.linalg  # imported here: keeps the start-up light

    chain = model.chain
    assert chain is not None  # called for a chain only
    a = chain.normalised
    n = a.diagonal.size
    wanted = [count] if count + 1 >= n else [count, n - 1]
    lam = [
        scipy.linalg.eigvalsh_tridiagonal(
            a.diagonal,
            a.off_diagonal,
            select="i",
            select_range=(i, i),
            lapack_driver="stebz",
            tol=BISECTION_TOL,
        )[0]
        for i in wanted
    ]
    return np.sqrt(np.maximum(np.array(lam, dtype=float), 0.0))


def _chain_modes(model: TorsionModel, chain: ChainArrays, free: bool) -> ModalResult:
    """Every mode of a chain of two or more degrees of freedom: :func:`eigen_modes`'s
    ``dstevd`` solve and the post-processing of :func:`_modes` in one pass, the same numbers to
    the bit (tests/torsion/test_modal_reference.py), in fewer numpy calls.

    Each step takes the common case directly and hands any other to the general helper: the
    thresholds of strictly ascending eigenvalues (:func:`distinct_thresholds`, else
    :func:`roundoff_thresholds`); the shapes by :func:`normalise_shapes`; every component resolved
    when each mode's smallest amplitude times the smallest sqrt(J_i) is above its threshold (a
    sufficient test, rounding being monotone), the nodes then counted as the sign changes
    between neighbours (else each component tested and :func:`chain_node_counts`). Up to
    :data:`FEW` values a 1-D reduction is Python's ``min`` on a list.
    """
    J = model.dof_inertia
    n = J.size
    a = chain.normalised  # the model's M^-1/2 K M^-1/2, made once
    s = a.root_inertia
    lam, u = _tridiagonal_eigh(a.diagonal, a.off_diagonal)
    shapes = u.T  # mode x dof: dstevd's eigenvectors are the columns of a Fortran array
    np.divide(shapes, s, out=shapes)  # phi = M^-1/2 u
    if not lam[1 if free else 0] > 0.0:  # (ascending) round-off below 0: to 0
        np.maximum(lam, 0.0, out=lam)
    total = a.total_inertia
    if free:  # the rigid-body mode exactly (module docstring)
        lam[0] = 0.0
        shapes[0] = 1.0 / math.sqrt(total)
    omega = np.sqrt(lam, out=lam)
    omega2 = omega * omega
    distinct = distinct_thresholds(omega2)
    if distinct is None:
        tau, largest = roundoff_thresholds(omega2), math.inf
    else:
        tau, largest = distinct
    shapes, size, least = normalise_shapes(shapes)  # largest amplitude 1, the first positive
    few = n <= FEW
    modal_inertia = np.multiply(size, size) @ J  # sum of J_i phi_i^2
    # resolved components: |phi_i| sqrt(J_i) > tau_r sqrt(J_r) (crankdyn.torsion.nodes)
    if largest * math.sqrt(2.0 * total) < 1e300:  # tau sqrt(J_r) cannot overflow
        limit = tau * np.sqrt(modal_inertia)
    else:
        with np.errstate(invalid="ignore", over="ignore"):
            limit = tau * np.sqrt(modal_inertia)
    whole = None
    if least is not None:
        whole = np.multiply(least, a.least_root_inertia) > limit
        if free:
            whole[0] = True
        if not (all(whole.tolist()) if few else whole.all()):
            whole = None
    if whole is not None:  # every component resolved: a node between neighbours of two signs
        negative = np.signbit(shapes)
        counts = np.add.reduce(negative[:, 1:] != negative[:, :-1], axis=1, dtype=np.intp)
    else:
        np.multiply(size, s, out=size)
        resolved = size > limit[:, None]
        if free:
            resolved[0] = True
        counts, whole = chain_node_counts(shapes, resolved)
    del size
    by_mass = shapes if model._dofs_in_listing_order else shapes[:, model.mass_dof]
    first = 0 if free else 1  # mode numbers: docs/conventions.md
    mode = _mode_numbers(first, n)
    stiffness = np.multiply(omega2, modal_inertia, out=omega2)
    for handed in (omega, counts, whole, modal_inertia, stiffness, by_mass, shapes):
        handed.setflags(write=False)  # handed over read-only, without a copy
    return ModalResult._assembled(
        mode=mode,
        natural_frequency=omega,
        node_count=counts,
        nodes_resolved=whole,
        modal_inertia=modal_inertia,
        modal_stiffness=stiffness,
        mode_shapes=by_mass,
        masses=model.mass_names,
        solver="eigen",
        structure="chain",
        free=free,
        model_name=model.name,
        modes_of_the_model=None,
        all_natural_frequency=None,
        highest_natural_frequency=None,
        model=model,
        shapes_dof=shapes,
        node_source=Nodes(inputs=(model, shapes, modal_inertia, tau, free)),
        warnings=(),
    )


@lru_cache(maxsize=64)
def _mode_numbers(first: int, count: int) -> NDArray[np.int_]:
    """The mode numbers first, first + 1, ... (``count`` of them), read-only and shared: the same
    numbers for every chain of a size."""
    return _readonly(np.arange(first, first + count))


def modal_result(
    model: TorsionModel,
    solver: str,
    omega: NDArray[np.float64],
    rows: ModeRows,
    start: int,
    total: int | None,
    all_omega: NDArray[np.float64] | None = None,
    free: bool | None = None,
    highest: float | None = None,
) -> ModalResult:
    """The ModalResult of the modes ``start``, ``start + 1``, ... (indices into the model's
    ascending modes) held by ``rows``; ``free``: ``model.is_free`` when the caller has it;
    ``highest``: the model's highest natural frequency (rad/s; default the last of
    ``all_omega``) when only the lowest modes are listed."""
    if highest is None and all_omega is not None and total is not None:
        highest = float(all_omega[-1])
    free = model.is_free if free is None else free
    first = (0 if free else 1) + start  # mode numbers: docs/conventions.md
    inertia = rows.modal_inertia
    return ModalResult(
        # arrays made here are handed over read-only, without a copy; another solver's
        # frequencies are copied (it may hold on to them)
        mode=_readonly(np.arange(first, first + omega.size)),
        natural_frequency=_readonly(omega) if solver == "eigen" else freeze(omega),
        node_count=_readonly(rows.counts),
        nodes_resolved=_readonly(rows.resolved),
        modal_inertia=_readonly(inertia),
        modal_stiffness=_readonly(omega**2 * inertia),
        mode_shapes=_readonly(rows.shapes),
        masses=model.mass_names,
        solver=solver,
        structure="chain" if model.is_chain else "branched",
        free=free,
        model_name=model.name,
        modes_of_the_model=total,
        all_natural_frequency=None if all_omega is None else freeze(all_omega),
        highest_natural_frequency=highest,
        model=model,
        shapes_dof=_readonly(rows.shapes_dof),
        node_source=rows.found,
    )
