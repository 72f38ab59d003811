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

Nodes only where the shape resolves them. A computed eigenvector u_r (unit length, u = M^1/2 phi)
differs from the exact one by an angle of at most about eps ||A||_2 / gap_r, gap_r the distance
of omega_r^2 to the nearest other eigenvalue and ||A||_2 the largest eigenvalue (the error bound
of the symmetric eigenproblem: E. Anderson et al., *LAPACK Users' Guide*, 3rd ed., SIAM 1999,
section 4.7.1; J. H. Wilkinson, *The Algebraic Eigenvalue Problem*, 1965, ch. 2). A component
below tau_r = 10 eps ||A||_2 / gap_r may therefore have any sign: in localised high modes of a
long chain whole stretches of the shape are such round-off. Only sign changes between resolved
components are nodes: between neighbours a node located on their shaft; across a round-off
region between components of opposite sign one node whose position is undetermined (reported
with the region). Round-off regions are reported per mode (``roundoff_regions``) and a mode with
one has ``nodes_resolved`` False: its node count is then a lower bound. For a chain the
oscillation theorem (F. R. Gantmacher and M. G. Krein, *Oscillation Matrices and Kernels and
Small Vibrations of Mechanical Systems*, 1950, ch. 2: the k-th eigenvector of a Jacobi matrix
has exactly k - 1 sign changes) gives mode r exactly r nodes in a free chain (the rigid-body
mode 0 none) and r - 1 in a grounded chain (the node at the ground not counted); the counted
nodes never exceed it and equal it wherever the shape is resolved (tested on chains of 10 to
1000 masses).

Large chains in blocks. Every mode of an N-mass model has N x N amplitudes (800 MB of float64 at
N = 10,000). :class:`ModeBlocks` computes a chain's modes a block at a time: all eigenvalues
first (``dsterf``; those whose absolute accuracy eps ||T|| is not small against them again by
bisection, ``dstebz``), then each block's eigenvectors by inverse iteration (``dstein``:
Anderson et al. 1999, section 2.4.4; the same error bound eps ||A|| / gap_r), normalised, their
nodes found with the whole spectrum's thresholds, and handed to :func:`modes_json_chunks` or
:func:`modes_csv_chunks`, which write what :meth:`ModalResult.to_dict` and
:meth:`~crankdyn.results.Result.to_csv` would, a block at a time.
"""

from __future__ import annotations

import contextlib
import itertools
import math
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from functools import cached_property, lru_cache
from typing import TYPE_CHECKING, Any, cast

import numpy as np
import numpy.typing as npt
from numpy.typing import NDArray

from crankdyn.docs import ref
from crankdyn.errors import InputError
from crankdyn.results import Result, array, column, freeze, scalar
from crankdyn.summary import SummaryColumn, SummaryTable, derived
from crankdyn.torsion.model import ChainArrays, TorsionModel

if TYPE_CHECKING:
    from collections.abc import Iterable

    from matplotlib.figure import Figure

__all__ = [
    "BLOCK_MODES",
    "SOLVERS",
    "STREAMED_SIZE",
    "ModalResult",
    "ModeBlocks",
    "Node",
    "chain_frequencies",
    "eigen_modes",
    "modes_csv_chunks",
    "modes_json_chunks",
    "natural_modes",
    "roundoff_thresholds",
]

SOLVERS = ("eigen", "holzer", "transfer", "closed-form")
HZ = 1.0 / (2.0 * math.pi)
_ZERO = 1e-9  # the first amplitude above this (of the largest) sets a shape's sign
_EPS = float(np.finfo(float).eps)
_BISECTION_TOL = 2.0 * np.finfo(float).tiny
"""Absolute tolerance of ``dstebz``: twice the underflow threshold, LAPACK's setting for the
most accurate eigenvalues (0 would mean eps x ||T||: 1e-9 relative on the lowest modes of a
1000-mass chain; this agrees with ``dstevd`` to 5e-11)."""


@dataclass(frozen=True)
class Node(Result):
    """A node of a mode: on a shaft (at a fraction of its length from its first mass), or, when
    the shape is round-off there (module docstring), somewhere in a round-off region of masses
    (``determined`` False; ``mass`` set when the region is a single mass).

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


@dataclass(frozen=True)
class ModalResult(Result):
    """Natural frequencies, mode shapes, nodes and modal inertias of a torsional model
    (:func:`natural_modes`; module docstring).

    Parameters
    ----------
    all_natural_frequency : numpy.ndarray or None
        Every natural frequency of the model (rad/s, ascending; not exported) when only the
        lowest modes were computed, else None.
    model : TorsionModel or None
        The model (not exported): names the shafts and masses of the nodes.
    shapes_dof : numpy.ndarray or None
        The normalised mode shapes by degree of freedom (mode x dof, dimensionless; not
        exported), for locating nodes and the mass-normalised :attr:`eigenvectors`.
    node_source : _Nodes or None
        The nodes and round-off regions of every mode in compact form (indices; not exported),
        found when first asked for (:attr:`node_arrays`).

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
    """Whether the whole shape is above round-off (module docstring); else the node count is a
    lower bound and the round-off regions are listed."""
    modal_inertia: np.ndarray = column("modal_inertias_kg_m2", "Modal inertia", "kg·m²")
    modal_stiffness: np.ndarray = column(
        "modal_stiffnesses_Nm_per_rad", "Modal stiffness", "N·m/rad"
    )
    mode_shapes: np.ndarray = array("mode_shapes", "Mode shapes (largest amplitude 1)", "")
    masses: tuple[str, ...] = scalar("masses", "Masses", "", summary=False)
    solver: str = scalar("solver", "Solver", "")
    structure: str = scalar("structure", "Structure", "")
    free: bool = scalar("free", "Free (rigid-body mode)", "")
    model_name: str = scalar("model", "Model", "")
    modes_of_the_model: int | None = scalar(
        "modes_of_the_model", "Modes of the model (the lowest are listed)", "", default=None
    )
    """Set when only the lowest modes were computed (``natural_modes(..., count=)``)."""
    all_natural_frequency: np.ndarray | None = field(default=None, repr=False, compare=False)
    """Every natural frequency of the model (rad/s) when only the lowest modes were computed."""
    model: TorsionModel | None = field(default=None, repr=False, compare=False)
    shapes_dof: np.ndarray | None = field(default=None, repr=False, compare=False)
    """Normalised mode shapes by degree of freedom (mode x dof), for locating nodes."""

    node_source: _Nodes | None = field(default=None, repr=False, compare=False)
    """The nodes and round-off regions of all modes, found when first asked for."""

    @property
    def node_arrays(self) -> _NodeArrays | None:
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
        (module docstring), where nodes cannot be located."""
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

    FIGURES = tuple(
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
    )

    def summary_tables(self) -> list[SummaryTable]:
        """The natural frequency and node count of every mode."""
        columns = (
            SummaryColumn("mode", "Mode"),
            SummaryColumn("natural_frequency_hz", "Natural frequency", "Hz"),
            SummaryColumn("node_count", "Nodes"),
        )
        rows = tuple(
            (int(m), float(f), int(k))
            for m, f, k in zip(self.mode, self.frequencies_hz, self.node_count, strict=True)
        )
        return [SummaryTable("modes", "Natural frequencies", columns, rows)]

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
                tol=_BISECTION_TOL,
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


def _normalise(
    shapes: np.ndarray, least: bool = True
) -> tuple[np.ndarray, np.ndarray, NDArray[np.float64] | None]:
    """Scale every row to a largest absolute amplitude of 1, the first amplitude above 1e-9 of
    the largest positive; amplitudes below 1e-14 of the largest become 0 (a positive 0: no
    negative zeros). The array given is overwritten.

    Returns the normalised rows (the array given or a new one), their absolute values (the
    other) and, when ``least`` is asked for, each row's smallest absolute value (None when not
    asked for, when amplitudes were zeroed or when a row has no finite largest amplitude).

    Each row x with largest |x| = p is divided once, by p signed as the amplitude that sets its
    sign: its first, x_0, or, where that is at rest (|x_0| / p at most 1e-9), the first with
    |x_j| / p above 1e-9. The absolute values returned are |x| / p: those of the quotient
    (division is symmetric in sign), found in one flat pass rather than by a second division
    of each row by its own number, unless many rows are at rest (then |x| / p of every row is
    looked in for their first amplitude above 1e-9; else in those rows only). A row of zeros,
    inf or NaN: :func:`_normalise_rows`, the rule row by row."""
    count = shapes.shape[0]
    size = np.abs(shapes)
    peak = np.maximum.reduce(size, axis=1)  # NaN in a row with NaN
    if _least_positive(peak) is None:  # a row of zeros, inf or NaN
        shapes, size = _normalise_rows(shapes)
        return shapes, size, None
    few = count <= _FEW
    signed = shapes[:, 0]  # the amplitude that sets each row's sign
    head = np.abs(signed) / peak  # |x_0| / p
    if (min(head.tolist()) if few else np.minimum.reduce(head)) > _ZERO:
        np.divide(shapes, np.copysign(peak, signed)[:, None], out=shapes)
        np.abs(shapes, out=size)  # |x| / p: finite, a finite peak bounds its row
    else:  # rows at rest in the first amplitude: the first above 1e-9 of the largest signs them
        rows = np.flatnonzero(head <= _ZERO)
        signed = signed.copy()
        if 8 * rows.size > count:  # many (the localised modes of a long chain): |x| / p of all
            np.divide(size, peak[:, None], out=size)
            signed[rows] = shapes[rows, np.argmax(size > _ZERO, axis=1)[rows]]
            np.divide(shapes, np.copysign(peak, signed)[:, None], out=shapes)
        else:  # a few: |x| / p of those rows only
            part = size[rows]
            np.divide(part, peak[rows, None], out=part)
            signed[rows] = shapes[rows, np.argmax(part > _ZERO, axis=1)]
            np.divide(shapes, np.copysign(peak, signed)[:, None], out=shapes)
            np.abs(shapes, out=size)
    if not few:  # round-off amplitudes looked for first: one pass fewer when there are some
        tiny = size < 1e-14
        if not tiny.any():
            return shapes, size, np.minimum.reduce(size, axis=1) if least else None
    elif least:
        smallest = np.minimum.reduce(size, axis=1)
        if min(smallest.tolist()) >= 1e-14:
            return shapes, size, smallest
        tiny = size < 1e-14
    else:
        tiny = size < 1e-14
        if not tiny.any():
            return shapes, size, None
    np.copyto(shapes, 0.0, where=tiny)  # round-off amplitudes: a positive 0
    np.copyto(size, 0.0, where=tiny)
    return shapes, size, None


def _normalise_rows(shapes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`_normalise` of rows that may be zeros, inf or NaN, in place: a row of zeros stays
    zeros, a row with NaN NaN.

    Returns the array and its absolute values (a new array the caller may overwrite). The
    absolute values come first, |x|, then the row's largest, and are divided by it in place:
    |x| / peak is exactly |x / (peak sign)|, the absolute value of the result. The amplitude
    that fixes a row's sign (the first above 1e-9 of the largest) is looked for beyond the first
    column only in the rows where that one is at rest."""
    count = shapes.shape[0]
    size = np.abs(shapes)
    peak = size.max(axis=1)  # max |x|
    if not peak.min() > 0.0:  # a row of zeros (or NaN)
        peak[~(peak > 0.0)] = 1.0
    np.divide(size, peak[:, None], out=size)  # |x| / peak
    head = size[:, 0] > _ZERO
    later = count - np.count_nonzero(head)
    if not later:
        sign = np.sign(shapes[:, 0])
    else:  # the first amplitude above _ZERO in the rows at rest in the first column
        if 8 * later > count:  # many (the localised modes of a long chain): in every row
            first = np.argmax(size > _ZERO, axis=1)
        else:  # a few: in those rows only
            rows = np.flatnonzero(~head)
            first = np.zeros(count, dtype=np.intp)
            first[rows] = np.argmax(size[rows] > _ZERO, axis=1)
        sign = np.sign(shapes[np.arange(count), first])
    if not sign.all():
        sign[sign == 0.0] = 1.0
    np.divide(shapes, (peak * sign)[:, None], out=shapes)  # exactly sign * (shapes / peak)
    tiny = size < 1e-14
    if tiny.any():  # round-off to 0 (a positive 0: no negative zeros)
        if np.isfinite(sign).all():
            np.copyto(shapes, 0.0, where=tiny)
        else:  # a row of NaN (its sign is NaN) stays NaN: x * 0 + 0, not a written 0
            np.multiply(shapes, ~tiny, out=shapes)
            np.add(shapes, 0.0, out=shapes)
        np.copyto(size, 0.0, where=tiny)
    return shapes, size


def _readonly(arr: np.ndarray) -> np.ndarray:
    """Mark an array this module created (and hands over) read-only, without a copy."""
    arr.setflags(write=False)
    return arr


EIGENVECTOR_SAFETY = 10.0
"""Factor on eps ||A|| / gap in the round-off threshold of a mode's components (module
docstring)."""


def roundoff_thresholds(eigenvalues: npt.ArrayLike) -> NDArray[np.float64]:
    """tau_r = 10 eps ||A||_2 / gap_r for every mode: the size of a component of the unit
    eigenvector u_r = M^1/2 phi_r / |M^1/2 phi_r| below which its sign is not determined (the
    error bound of the symmetric eigenproblem, E. Anderson et al., *LAPACK Users' Guide*, 3rd
    ed., SIAM 1999, section 4.7.1; module docstring).

    Parameters
    ----------
    eigenvalues : array_like
        omega_r^2 (rad²/s²), in any order.

    Returns
    -------
    numpy.ndarray
        One threshold per eigenvalue (dimensionless; inf for a repeated eigenvalue, 0 for a
        single mode).

    Examples
    --------
    >>> [f"{t:.3g}" for t in roundoff_thresholds([0.0, 1.0, 4.0])]
    ['8.88e-15', '8.88e-15', '2.96e-15']
    """
    lam = np.asarray(eigenvalues, dtype=float)
    n = lam.size
    if n < 2:
        return np.zeros(n)
    distinct = _distinct_thresholds(lam)
    if distinct is not None:
        return distinct[0]
    step = lam[1:] - lam[:-1]
    if (step >= 0.0).all():  # ascending, as the solvers give them: no sort (and no NaN)
        order, sorted_lam = None, lam
        norm = max(abs(float(lam[0])), abs(float(lam[-1])))  # the largest |lambda|
    else:
        order = np.argsort(lam, kind="stable")
        sorted_lam = lam[order]
        step = sorted_lam[1:] - sorted_lam[:-1]
        norm = float(np.max(np.abs(sorted_lam)))
    gap = np.empty(n)
    gap[:-1] = step
    gap[-1] = np.inf
    np.minimum(gap[1:], step, out=gap[1:])
    scale = EIGENVECTOR_SAFETY * _EPS * norm
    if gap.min() > 0.0:  # distinct eigenvalues (the rule)
        tau_sorted = scale / gap
    else:  # inf where there is no gap
        tau_sorted = np.full(n, np.inf)
        np.divide(scale, gap, out=tau_sorted, where=gap > 0.0)
    if order is None:
        return tau_sorted
    tau = np.empty(n)
    tau[order] = tau_sorted
    return tau


def _least_positive(values: NDArray[np.float64]) -> float | None:
    """The smallest of a 1-D array's values when every one is positive and finite (their sum
    finite: NaN or inf make it not), else None. A few values by Python's ``min`` and ``sum`` on
    a list: a numpy reduction costs 1 µs whatever the size.

    Examples
    --------
    >>> [_least_positive(np.array(v)) for v in ([2.0, 0.5], [1.0, np.nan], [1.0, np.inf])]
    [0.5, None, None]
    """
    if values.size > _FEW:
        least, total = float(np.minimum.reduce(values)), float(np.add.reduce(values))
    else:
        listed = values.tolist()
        least, total = min(listed), sum(listed)
    return least if least > 0.0 and total < math.inf else None


_FEW = 32
"""Values up to which :func:`_least_positive` and :func:`_chain_modes` reduce a 1-D array in Python
(a list of 32 floats: as quick as one numpy reduction)."""


def _distinct_thresholds(lam: NDArray[np.float64]) -> tuple[NDArray[np.float64], float] | None:
    """:func:`roundoff_thresholds` of eigenvalues that ascend strictly (the rule: the solvers
    give them ascending), with the largest threshold; None otherwise (unordered, repeated or
    NaN: the general code). Two or more eigenvalues.

    gap_r = min(lambda_r+1 - lambda_r, lambda_r - lambda_r-1) from the steps padded with inf at
    both ends; the same operations, to the bit, as the general code."""
    n = lam.size
    if n <= _FEW:  # a few: in Python on a list, the same IEEE operations (numpy's per-call cost)
        listed = lam.tolist()
        steps = [b - a for a, b in itertools.pairwise(listed)]
        least, total = min(steps), sum(steps)
        if not (least > 0.0 and total < math.inf):
            return None
        scale = EIGENVECTOR_SAFETY * _EPS * max(abs(listed[0]), abs(listed[-1]))
        gaps = [steps[0], *map(min, itertools.pairwise(steps)), steps[-1]]
        return np.array([scale / g for g in gaps]), scale / least
    pad = np.empty(n + 1)
    step = np.subtract(lam[1:], lam[:-1], out=pad[1:n])
    least = _least_positive(step)
    if least is None:
        return None
    pad[0] = pad[n] = np.inf
    scale = EIGENVECTOR_SAFETY * _EPS * max(abs(float(lam[0])), abs(float(lam[-1])))
    tau = np.minimum(pad[:-1], pad[1:])
    return np.divide(scale, tau, out=tau), scale / least


@dataclass(frozen=True)
class _NodeArrays:
    """Nodes of all modes in compact form (indices into the modes, the model's shafts and its
    degrees of freedom)."""

    shaft_mode: np.ndarray  # mode index of every located node
    shaft: np.ndarray  # its shaft (model.shafts)
    fraction: np.ndarray  # its position along that shaft from the shaft's first mass
    open_mode: np.ndarray  # mode index of every node in a round-off region (undetermined)
    open_first: np.ndarray  # first and last dof of that region
    open_last: np.ndarray
    region_mode: np.ndarray  # every round-off region: mode, first and last dof
    region_first: np.ndarray
    region_last: np.ndarray

    def counts(self, modes: int) -> np.ndarray:
        return np.bincount(self.shaft_mode, minlength=modes) + np.bincount(
            self.open_mode, minlength=modes
        )

    def resolved(self, modes: int) -> np.ndarray:
        return np.bincount(self.region_mode, minlength=modes) == 0


def _edge_shafts(
    model: TorsionModel,
) -> tuple[NDArray[np.int_], NDArray[np.int_], NDArray[np.int_]]:
    """(a, b, shaft) for every pair of degrees of freedom joined by a shaft (the first shaft of
    parallel ones), a < b."""
    ends = model.shaft_dofs
    inner = np.flatnonzero((ends[:, 0] >= 0) & (ends[:, 1] >= 0))
    lo = np.minimum(ends[inner, 0], ends[inner, 1])
    hi = np.maximum(ends[inner, 0], ends[inner, 1])
    _, first = np.unique(lo * (model.dof_count + 1) + hi, return_index=True)
    first = np.sort(first)
    return lo[first], hi[first], inner[first]


def _fractions(
    model: TorsionModel,
    shapes_dof: NDArray[np.float64],
    mode: NDArray[np.int_],
    shaft: NDArray[np.int_],
) -> NDArray[np.float64]:
    """Node position along each shaft from its first mass, t = theta_a / (theta_a - theta_b)."""
    ends = model.shaft_dofs[shaft]
    ta = shapes_dof[mode, ends[:, 0]]
    tb = shapes_dof[mode, ends[:, 1]]
    return ta / (ta - tb)


def _nonzero(mask: NDArray[np.bool_]) -> tuple[NDArray[np.intp], NDArray[np.intp]]:
    """(rows, columns) of the True entries of a 2-D mask in row-major order, as
    ``np.nonzero`` gives them, from the flat indices (``np.nonzero`` tracks a 2-D index per
    entry: ten times slower on an n x n mask)."""
    columns = mask.shape[1]
    flat = np.flatnonzero(mask)
    if not columns:
        return flat, flat.copy()
    return np.divmod(flat, columns)


def _chain_nodes(
    model: TorsionModel, shapes_dof: NDArray[np.float64], resolved: NDArray[np.bool_]
) -> _NodeArrays:
    """Nodes of a chain (dofs in chain order), all modes at once: a sign change between
    neighbouring resolved components is a node on their shaft; one across a run of round-off
    components a node somewhere in that run."""
    n = resolved.shape[1]
    negative = np.signbit(shapes_dof)
    # a node between neighbours that are both resolved (the common case): a sign change
    both = resolved[:, 1:] & resolved[:, :-1]
    both &= negative[:, 1:] != negative[:, :-1]
    located_mode, located_first = _nonzero(both)
    shaft_of = np.full(max(n - 1, 0), -1, dtype=int)
    ends = model.shaft_dofs
    inner = np.flatnonzero((ends[:, 0] >= 0) & (ends[:, 1] >= 0))
    if inner.size == n - 1:  # no parallel shafts: one per edge, no search for the first
        shaft_of[np.minimum(ends[inner, 0], ends[inner, 1])] = inner
    else:
        a, _, edge_shaft = _edge_shafts(model)
        shaft_of[a] = edge_shaft  # a chain: edge (i, i + 1) is keyed by i
    located_shaft = shaft_of[located_first]
    fraction = _fractions(model, shapes_dof, located_mode, located_shaft)
    region_mode, region_first, region_last, open_mode, open_first, open_last = _roundoff_runs(
        resolved, negative
    )
    return _NodeArrays(
        shaft_mode=located_mode,
        shaft=located_shaft,
        fraction=fraction,
        open_mode=open_mode,
        open_first=open_first,
        open_last=open_last,
        region_mode=region_mode,
        region_first=region_first,
        region_last=region_last,
    )


def _roundoff_runs(
    resolved: NDArray[np.bool_], negative: NDArray[np.bool_]
) -> tuple[NDArray[np.intp], ...]:
    """The round-off runs of a chain's modes (rows): (mode, first dof, last dof) of every run of
    unresolved components, then (mode, first, last) of the runs whose resolved neighbours on
    both sides differ in sign (a node somewhere in the run)."""
    count, n = resolved.shape
    loose = ~resolved
    starts = loose & np.concatenate([np.ones((count, 1), bool), resolved[:, :-1]], axis=1)
    run_ends = loose & np.concatenate([resolved[:, 1:], np.ones((count, 1), bool)], axis=1)
    region_mode, region_first = _nonzero(starts)
    region_last = _nonzero(run_ends)[1]
    inside = (region_first > 0) & (region_last < n - 1)
    o_mode, o_first, o_last = region_mode[inside], region_first[inside], region_last[inside]
    flips = negative[o_mode, o_first - 1] != negative[o_mode, o_last + 1]
    return region_mode, region_first, region_last, o_mode[flips], o_first[flips], o_last[flips]


def _graph_nodes(
    model: TorsionModel, shapes_dof: NDArray[np.float64], resolved: NDArray[np.bool_]
) -> _NodeArrays:
    """Nodes of a branched model: sign changes across shafts between resolved components
    (all modes at once), and for every connected round-off region whose resolved neighbours
    have both signs one node somewhere in it (a loop over the modes that have such regions:
    branched models are small)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    n = resolved.shape[1]
    negative = np.signbit(shapes_dof)
    a, b, edge_shaft = _edge_shafts(model)
    crossing = resolved[:, a] & resolved[:, b] & (negative[:, a] != negative[:, b])
    located_mode, e = _nonzero(crossing)
    located_shaft = edge_shaft[e]
    fraction = _fractions(model, shapes_dof, located_mode, located_shaft)
    open_mode, open_first, open_last = [], [], []
    region_mode, region_first, region_last = [], [], []
    for r in np.flatnonzero(~np.all(resolved, axis=1)):
        loose = ~resolved[r]
        keep = loose[a] & loose[b]
        graph = coo_matrix((np.ones(int(keep.sum())), (a[keep], b[keep])), shape=(n, n))
        _, label = connected_components(graph, directed=False)
        for comp in np.unique(label[loose]):
            members = np.flatnonzero(loose & (label == comp))
            inside = np.isin(a, members) | np.isin(b, members)
            border = np.setdiff1d(np.concatenate([a[inside], b[inside]]), members)
            border = border[resolved[r, border]]
            region_mode.append(r)
            region_first.append(members[0])
            region_last.append(members[-1])
            signs = negative[r, border]
            if signs.size and signs.any() and not signs.all():
                open_mode.append(r)
                open_first.append(members[0])
                open_last.append(members[-1])

    def ints(values):
        return np.asarray(values, dtype=int)

    return _NodeArrays(
        shaft_mode=located_mode,
        shaft=located_shaft,
        fraction=fraction,
        open_mode=ints(open_mode),
        open_first=ints(open_first),
        open_last=ints(open_last),
        region_mode=ints(region_mode),
        region_first=ints(region_first),
        region_last=ints(region_last),
    )


def _resolved(
    model: TorsionModel,
    size: NDArray[np.float64],
    modal_inertia: NDArray[np.float64],
    tau: NDArray[np.float64],
    rigid: bool,
) -> NDArray[np.bool_]:
    """Which components of the modes are resolved (above round-off, module docstring): ``size``
    the absolute normalised amplitudes (mode x dof; overwritten), ``tau`` the modes' round-off
    thresholds (:func:`roundoff_thresholds` of the whole spectrum), ``rigid``: the first row is
    the rigid-body mode."""
    # |u_i| = |phi_i| sqrt(J_i) / sqrt(J_r) > tau_r: the component is resolved
    np.multiply(size, np.sqrt(model.dof_inertia), out=size)
    with np.errstate(invalid="ignore", over="ignore"):
        resolved = size > (tau * np.sqrt(modal_inertia))[:, None]
    if rigid and resolved.shape[0]:
        resolved[0] = True  # the rigid-body mode: exactly ones
    return resolved


def _find_nodes(
    model: TorsionModel,
    shapes_dof: NDArray[np.float64],
    modal_inertia: NDArray[np.float64],
    tau: NDArray[np.float64],
    rigid: bool,
) -> _NodeArrays:
    """Nodes and round-off regions of the modes in the rows of ``shapes_dof`` (module
    docstring); ``tau``, ``rigid``: :func:`_resolved`."""
    resolved = _resolved(model, np.abs(shapes_dof), modal_inertia, tau, rigid)
    if model.is_chain:
        return _chain_nodes(model, shapes_dof, resolved)
    return _graph_nodes(model, shapes_dof, resolved)


class _Nodes:
    """The node arrays of some modes: given, or located from their inputs when first asked for
    (:func:`_find_nodes`; the inputs are dropped then)."""

    __slots__ = ("_arrays", "_inputs")

    def __init__(
        self,
        arrays: _NodeArrays | None = None,
        inputs: tuple[
            TorsionModel, NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], bool
        ]
        | None = None,
    ) -> None:
        self._arrays = arrays
        self._inputs = inputs

    @property
    def arrays(self) -> _NodeArrays:
        """The node arrays (:class:`_NodeArrays`)."""
        if self._arrays is None:
            assert self._inputs is not None
            self._arrays = _find_nodes(*self._inputs)
            self._inputs = None
        return self._arrays


def _chain_counts(
    shapes_dof: NDArray[np.float64], resolved: NDArray[np.bool_]
) -> tuple[NDArray[np.intp], NDArray[np.bool_]]:
    """(node count, whether resolved) of every mode of a chain without locating the nodes: the
    sign changes between resolved neighbours, plus, in the modes with round-off runs, the runs
    between resolved components of opposite sign (:func:`_chain_nodes` counts the same)."""
    count, n = resolved.shape
    if count * n <= _FLAT_COUNTS:
        # small: the sign changes between consecutive resolved components of a mode (a node
        # between neighbours or across a run), from their flat indices in a few calls
        if count * n < _ROW_SUMS:  # each component's row by a division
            at = np.flatnonzero(resolved)
            sign = np.signbit(shapes_dof.ravel()[at])
            row = at // n
            change = sign[1:] != sign[:-1]
            change &= row[1:] == row[:-1]
            whole = cast("NDArray[np.bool_]", resolved.all(axis=1))
            return np.bincount(row[1:][change], minlength=count), whole
        # the changes between consecutive resolved components summed row by row: the change
        # after a row's last resolved component (into the next row) is not counted
        per_row = np.add.reduce(resolved, axis=1, dtype=np.intp)
        whole = per_row == n
        sign = np.signbit(shapes_dof).ravel()[resolved.ravel()]  # row-major, as flatnonzero
        m = sign.size
        change = np.empty(m + 1, dtype=bool)  # padded: a row's first index is at most m
        np.not_equal(sign[1:], sign[:-1], out=change[: m - 1])
        change[m - 1 :] = False
        end = np.cumsum(per_row)
        change[end - 1] = False  # after each row's last (-1, a row ending before any: the pad)
        counts = np.add.reduceat(change, end - per_row, dtype=np.intp)
        if not per_row.all():  # reduceat gives a row of none resolved the next row's first
            counts[per_row == 0] = 0
        return counts, whole
    whole = cast("NDArray[np.bool_]", resolved.all(axis=1))
    negative = np.signbit(shapes_dof)
    both = negative[:, 1:] != negative[:, :-1]
    both &= resolved[:, 1:]
    both &= resolved[:, :-1]
    counts = both.sum(axis=1, dtype=np.intp)
    del both
    if not whole.all():
        counts += _open_counts(resolved, negative)
    return counts, whole


_ROW_SUMS = 1 << 13
"""Modes x degrees of freedom from which :func:`_chain_counts` sums a mode's sign changes
between its first and last resolved components (one ``reduceat``) rather than finding each
component's mode by a division (fewer calls below)."""

_FLAT_COUNTS = 1 << 16
"""Modes x degrees of freedom up to which :func:`_chain_counts` counts from the flat indices of
the resolved components (fewer calls); beyond, by whole-array passes (less memory traffic)."""


def _open_counts(resolved: NDArray[np.bool_], negative: NDArray[np.bool_]) -> NDArray[np.intp]:
    """Per mode (row) of a chain the round-off runs between resolved components of opposite
    sign (the nodes somewhere in a run, :func:`_roundoff_runs`), from the flat indices of the
    runs' ends: a row padded with a resolved component at either end changes from resolved to
    round-off and back once per run."""
    count, n = resolved.shape
    pad = np.ones((count, n + 2), dtype=bool)
    pad[:, 1:-1] = resolved
    width = n + 1
    edges = np.flatnonzero(pad[:, 1:] != pad[:, :-1])  # per row: each run's start, its end + 1
    first = edges[0::2]
    row = first // width
    at = row * width
    first -= at  # the run's first column
    last = edges[1::2] - at - 1  # its last column
    inside = (first > 0) & (last < n - 1)
    row, first, last = row[inside], first[inside], last[inside]
    at = row * n - 1
    flat = negative.ravel()
    flips = flat[at + first] != flat[at + last + 2]
    return np.bincount(row[flips], minlength=count)


@dataclass(frozen=True)
class _Rows:
    """The per-mode results of some modes (rows): shapes by mass and by dof, modal inertias,
    node counts, whether resolved, the nodes (mode indices counted from the first row)."""

    shapes: NDArray[np.float64]  # mode x mass (listing order), largest amplitude 1
    shapes_dof: NDArray[np.float64]  # mode x dof
    modal_inertia: NDArray[np.float64]  # kg·m²
    counts: NDArray[np.intp]  # nodes per mode
    resolved: NDArray[np.bool_]  # whether the mode's shape is above round-off throughout
    found: _Nodes

    @property
    def nodes(self) -> _NodeArrays:
        """The node arrays (located when first asked for)."""
        return self.found.arrays

    @classmethod
    def of(
        cls,
        shapes: NDArray[np.float64],
        shapes_dof: NDArray[np.float64],
        modal_inertia: NDArray[np.float64],
        nodes: _NodeArrays,
    ) -> _Rows:
        """The rows with their nodes located already."""
        m = modal_inertia.size
        return cls(
            shapes, shapes_dof, modal_inertia, nodes.counts(m), nodes.resolved(m), _Nodes(nodes)
        )


def _rows(
    model: TorsionModel,
    phi_t: NDArray[np.float64],
    tau: NDArray[np.float64],
    rigid: bool,
    *,
    lazy: bool = False,
) -> _Rows:
    """Normalise the shapes ``phi_t`` (mode x dof, changed in place), their modal inertias
    J_r = sum J_i phi_i^2 and nodes (``tau``, ``rigid``: :func:`_resolved`). ``lazy``: a
    chain's nodes are only counted (:func:`_chain_counts`) and located when first asked for."""
    shapes_dof, size, _ = _normalise(phi_t, least=False)  # mode x dof; size = |shapes_dof|
    # mode x mass (listing order)
    shapes = shapes_dof if model._dofs_in_listing_order else shapes_dof[:, model.mass_dof]
    square = size * size  # phi_i^2
    modal_inertia = square @ model.dof_inertia  # sum of J_i phi_i^2
    del square
    if lazy and model.is_chain:
        resolved = _resolved(model, size, modal_inertia, tau, rigid)
        del size
        counts, whole = _chain_counts(shapes_dof, resolved)
        found = _Nodes(inputs=(model, shapes_dof, modal_inertia, tau, rigid))
        return _Rows(shapes, shapes_dof, modal_inertia, counts, whole, found)
    resolved = _resolved(model, size, modal_inertia, tau, rigid)
    del size
    if model.is_chain:
        nodes = _chain_nodes(model, shapes_dof, resolved)
    else:
        nodes = _graph_nodes(model, shapes_dof, resolved)
    return _Rows.of(shapes, shapes_dof, modal_inertia, nodes)


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
    """:func:`natural_modes` by any solver, step by step (:func:`_solve`, :func:`_rows`,
    :func:`_result`): the lowest modes, other solvers, branched models, a single mass."""
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
    all_omega = chain_frequencies(model) if partial else None
    spectrum = omega if all_omega is None else all_omega
    tau = roundoff_thresholds(spectrum * spectrum)[: omega.size]
    rows = _rows(model, phi.T, tau, free, lazy=True)
    del phi
    return _result(model, solver, omega, rows, 0, total if partial else None, all_omega, free)


def _chain_modes(model: TorsionModel, chain: ChainArrays, free: bool) -> ModalResult:
    """Every mode of a chain of two or more degrees of freedom: :func:`eigen_modes`'s
    ``dstevd`` solve and the post-processing of :func:`_modes` in one pass, the same numbers to
    the bit (tests/torsion/test_modal_reference.py), in fewer numpy calls.

    Each step takes the common case directly and hands any other to the general helper: the
    thresholds of strictly ascending eigenvalues (:func:`_distinct_thresholds`, else
    :func:`roundoff_thresholds`); the shapes by :func:`_normalise`; every component resolved
    when each mode's smallest amplitude times the smallest sqrt(J_i) is above its threshold (a
    sufficient test, rounding being monotone), the nodes then counted as the sign changes
    between neighbours (else each component tested and :func:`_chain_counts`). Up to
    :data:`_FEW` values a 1-D reduction is Python's ``min`` on a list.
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
    distinct = _distinct_thresholds(omega2)
    if distinct is None:
        tau, largest = roundoff_thresholds(omega2), math.inf
    else:
        tau, largest = distinct
    shapes, size, least = _normalise(shapes)  # largest amplitude 1, the first positive
    few = n <= _FEW
    modal_inertia = np.multiply(size, size) @ J  # sum of J_i phi_i^2
    # resolved components: |phi_i| sqrt(J_i) > tau_r sqrt(J_r) (module docstring, _resolved)
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
        counts, whole = _chain_counts(shapes, resolved)
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
        model=model,
        shapes_dof=shapes,
        node_source=_Nodes(inputs=(model, shapes, modal_inertia, tau, free)),
    )


@lru_cache(maxsize=64)
def _mode_numbers(first: int, count: int) -> NDArray[np.int_]:
    """The mode numbers first, first + 1, ... (``count`` of them), read-only and shared: the same
    numbers for every chain of a size."""
    return _readonly(np.arange(first, first + count))


def _result(
    model: TorsionModel,
    solver: str,
    omega: NDArray[np.float64],
    rows: _Rows,
    start: int,
    total: int | None,
    all_omega: NDArray[np.float64] | None = None,
    free: bool | None = None,
) -> ModalResult:
    """The ModalResult of the modes ``start``, ``start + 1``, ... (indices into the model's
    ascending modes) held by ``rows``; ``free``: ``model.is_free`` when the caller has it."""
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
        model=model,
        shapes_dof=_readonly(rows.shapes_dof),
        node_source=rows.found,
    )


# ---- every mode of a large chain, block by block ------------------------------------------------

BLOCK_MODES = 32
"""Modes per block of :class:`ModeBlocks`: the eigenvectors of one block (N x 32 floats, 2.6 MB
at N = 10,000) are computed by inverse iteration, written and dropped. ``dstein``
reorthogonalises the vectors of close eigenvalues within a block (Gram-Schmidt, quadratic in
the block size): blocks of 8 to 64 modes took the same time at N = 10,000."""

STREAMED_SIZE = 1_000_000
"""Modes x masses above which ``torsion modes --format json/csv`` writes a chain's modes block by
block (:class:`ModeBlocks`) instead of from one :class:`ModalResult` (N x N shapes: 8 MB here,
800 MB at N = 10,000)."""

_REFINED = 1e-10
"""Eigenvalues whose absolute accuracy eps ||T|| (``dsterf``) is above this relative to them are
recomputed by bisection to full relative accuracy (``dstebz``, :data:`_BISECTION_TOL`)."""


def _chain_matrix(
    model: TorsionModel,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """(d, e, sqrt(J)) of a chain's symmetric tridiagonal matrix M^-1/2 K M^-1/2 (module
    docstring): diagonal (rad²/s², N), off-diagonal (rad²/s², N - 1), sqrt(J) (sqrt(kg·m²))."""
    chain = model.chain
    assert chain is not None
    a = chain.normalised
    return a.diagonal, a.off_diagonal, a.root_inertia


def _chain_spectrum(
    d: NDArray[np.float64], e: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.int32], NDArray[np.int32]]:
    """Every eigenvalue of the tridiagonal (d, e), ascending, with its split-off block (1-based)
    and the blocks' last rows (1-based), as ``dstebz`` gives them to ``dstein``.

    The matrix splits where e_j² <= |d_j d_j+1| ulp² + safe minimum (``dstebz``'s test); each
    block's eigenvalues by ``dsterf`` (absolute accuracy eps ||T||), those of relative accuracy
    worse than :data:`_REFINED` again by bisection (``dstebz`` by index, full relative
    accuracy, as the lowest modes of :func:`eigen_modes`)."""
    import scipy.linalg.lapack as lapack  # imported here: keeps the start-up light

    n = d.size
    finfo = np.finfo(float)
    cut = np.flatnonzero(np.abs(d[1:] * d[:-1]) * finfo.eps**2 + finfo.tiny > e * e) + 1
    bounds = [0, *cut.tolist(), n]
    values, blocks = [], []
    for b, (lo, hi) in enumerate(itertools.pairwise(bounds), start=1):
        if hi - lo == 1:
            w = d[lo : lo + 1].copy()
        else:
            w, info = lapack.dsterf(d[lo:hi], e[lo : hi - 1])
            if info != 0:
                raise np.linalg.LinAlgError(f"the tridiagonal eigensolver failed (dsterf {info})")
        values.append(w)
        blocks.append(np.full(w.size, b, dtype=np.int32))
    lam = np.concatenate(values)
    order = np.argsort(lam, kind="stable")
    lam, iblock = lam[order], np.concatenate(blocks)[order]
    isplit = np.zeros(n, dtype=np.int32)
    isplit[: len(bounds) - 1] = bounds[1:]
    norm = float(np.max(np.abs(lam)))
    refine = int(np.searchsorted(np.abs(lam), finfo.eps * norm / _REFINED)) if n > 1 else 0
    if refine:
        m, w, ib, _, info = lapack.dstebz(d, e, 2, 0.0, 0.0, 1, refine, _BISECTION_TOL, b"E")
        if info != 0 or m != refine:
            raise np.linalg.LinAlgError(f"the bisection failed (dstebz info {info})")
        lam[:refine], iblock[:refine] = w[:refine], ib[:refine]
    return lam, iblock, isplit


@dataclass(frozen=True)
class _Block:
    """The modes ``start`` .. ``start + omega.size - 1`` (indices into the listed modes)."""

    start: int
    omega: NDArray[np.float64]  # rad/s
    rows: _Rows


class ModeBlocks:
    """Every mode of a chain (or the lowest ``count``), computed and exported block by block.

    The eigenvalues come first, all of them (:func:`_chain_spectrum`: ``dsterf``, the lowest
    refined by bisection); then the eigenvectors of :data:`BLOCK_MODES` modes at a time by
    inverse iteration (LAPACK ``dstein``, E. Anderson et al., *LAPACK Users' Guide*, 3rd ed.,
    SIAM 1999, section 2.4.4), each block normalised, its nodes found (the round-off thresholds
    of the whole spectrum, module docstring) and handed out, never the N x N matrix. Memory:
    N x :data:`BLOCK_MODES` floats and the per-mode columns. The numbers are those of
    :func:`natural_modes` (eigenvectors to round-off: the same bound eps ||A|| / gap_r).

    Parameters
    ----------
    model
        A chain model (:attr:`TorsionModel.is_chain`).
    count
        The lowest ``count`` modes only (default: every mode).
    block
        Modes per block.

    Raises
    ------
    InputError
        If ``count`` is below 1 (key ``count``).
    ValueError
        If the model is not a chain.
    """

    def __init__(
        self, model: TorsionModel, count: int | None = None, *, block: int = BLOCK_MODES
    ) -> None:
        if model.chain is None:
            raise ValueError("ModeBlocks needs a chain model")
        if count is not None and count < 1:
            raise InputError("expected at least one mode", key="count", value=count)
        self.model = model
        self.total = model.dof_inertia.size
        self.count = self.total if count is None else min(count, self.total)
        self.block = max(1, int(block))
        self.free = model.is_free
        self._d, self._e, self._s = _chain_matrix(model)
        if self.total == 1:
            lam = self._d.copy()
            self._iblock = np.ones(1, dtype=np.int32)
            self._isplit = np.ones(1, dtype=np.int32)
        else:
            lam, self._iblock, self._isplit = _chain_spectrum(self._d, self._e)
        self._lam = lam
        lam = np.maximum(lam, 0.0)
        if self.free:
            lam[0] = 0.0
        self.all_omega: NDArray[np.float64] = np.sqrt(lam)
        self.tau = roundoff_thresholds(lam)
        self.omega: NDArray[np.float64] = self.all_omega[: self.count]

    def _vectors(self, lo: int, hi: int) -> NDArray[np.float64]:
        """Orthonormal eigenvectors u (dof x mode) of modes ``lo`` .. ``hi - 1`` (``dstein``;
        the eigenvalues grouped by split-off block as it requires)."""
        import scipy.linalg.lapack as lapack  # imported here: keeps the start-up light

        n = self.total
        if n == 1:
            return np.ones((1, hi - lo))
        group = np.argsort(self._iblock[lo:hi], kind="stable")
        iblock = np.zeros(n, dtype=np.int32)
        iblock[: hi - lo] = self._iblock[lo:hi][group]
        z, info = lapack.dstein(self._d, self._e, self._lam[lo:hi][group], iblock, self._isplit)
        if info != 0:
            raise np.linalg.LinAlgError(f"inverse iteration failed (dstein info {info})")
        u = np.empty_like(z)
        u[:, group] = z
        return u

    def blocks(self) -> Iterator[_Block]:
        """The blocks of modes, ascending, each computed when reached.

        Returns
        -------
        iterator of _Block
            Per block: the index of its first mode, omega (rad/s) and the normalised shapes,
            modal inertias (kg·m²) and nodes of its modes.
        """
        for lo in range(0, self.count, self.block):
            hi = min(lo + self.block, self.count)
            u = self._vectors(lo, hi)
            u /= self._s[:, None]  # phi = M^-1/2 u
            rigid = self.free and lo == 0
            if rigid:
                u[:, 0] = 1.0
            rows = _rows(self.model, u.T, self.tau[lo:hi], rigid)
            yield _Block(lo, self.omega[lo:hi], rows)

    def result(self, solver: str = "eigen") -> ModalResult:
        """All the listed modes as one :class:`ModalResult` (small models; for tests).

        Parameters
        ----------
        solver : str
            The solver named in the result.

        Returns
        -------
        ModalResult
            The modes, as :func:`natural_modes` gives them (to round-off).

        Examples
        --------
        >>> from crankdyn.torsion import TorsionModel
        >>> r = ModeBlocks(TorsionModel.chain_of([1.0, 1.0, 1.0], [1e4, 1e4]), block=2).result()
        >>> [round(float(w), 4) for w in r.natural_frequency]  # sqrt(k / J), sqrt(3 k / J)
        [0.0, 100.0, 173.2051]
        """
        parts = list(self.blocks())
        rows = _Rows.of(
            np.concatenate([p.rows.shapes for p in parts]),
            np.concatenate([p.rows.shapes_dof for p in parts]),
            np.concatenate([p.rows.modal_inertia for p in parts]),
            _concat_nodes([(p.start, p.rows.nodes) for p in parts]),
        )
        total = self.total if self.count < self.total else None
        all_omega = self.all_omega if total is not None else None
        return _result(self.model, solver, self.omega.copy(), rows, 0, total, all_omega)


def _concat_nodes(parts: list[tuple[int, _NodeArrays]]) -> _NodeArrays:
    """The node arrays of consecutive blocks as one (mode indices shifted by each start)."""

    def cat(name: str, shift: bool) -> NDArray[np.int_] | NDArray[np.float64]:
        return np.concatenate([getattr(a, name) + (s if shift else 0) for s, a in parts])

    return _NodeArrays(
        shaft_mode=cat("shaft_mode", True),
        shaft=cat("shaft", False),
        fraction=cat("fraction", False),
        open_mode=cat("open_mode", True),
        open_first=cat("open_first", False),
        open_last=cat("open_last", False),
        region_mode=cat("region_mode", True),
        region_first=cat("region_first", False),
        region_last=cat("region_last", False),
    )


def _slices(result: ModalResult, block: int) -> Iterator[_Block]:
    """The modes of an in-memory result in blocks (the same numbers; nodes re-indexed)."""
    arrays = result.node_arrays
    assert arrays is not None and result.shapes_dof is not None
    for lo in range(0, result.mode.size, block):
        hi = min(lo + block, result.mode.size)

        sm, sh, fr = _part(lo, hi, arrays.shaft_mode, arrays.shaft, arrays.fraction)
        om, of, ol = _part(lo, hi, arrays.open_mode, arrays.open_first, arrays.open_last)
        rm, rf, rl = _part(lo, hi, arrays.region_mode, arrays.region_first, arrays.region_last)
        rows = _Rows.of(
            result.mode_shapes[lo:hi],
            result.shapes_dof[lo:hi],
            result.modal_inertia[lo:hi],
            _NodeArrays(sm, sh, fr, om, of, ol, rm, rf, rl),
        )
        yield _Block(lo, result.natural_frequency[lo:hi], rows)


def _part(lo: int, hi: int, mode: NDArray[np.int_], *others: NDArray[Any]) -> list[NDArray[Any]]:
    """The entries of modes ``lo`` .. ``hi - 1`` of node arrays, the modes counted from ``lo``."""
    keep = (mode >= lo) & (mode < hi)
    return [mode[keep] - lo, *(o[keep] for o in others)]


def _source(
    source: ModeBlocks | ModalResult, block: int
) -> tuple[TorsionModel, str, int | None, Iterator[_Block]]:
    """(model, solver, modes of the model when only the lowest are listed, the blocks)."""
    if isinstance(source, ModeBlocks):
        total = source.total if source.count < source.total else None
        return source.model, "eigen", total, source.blocks()
    assert source.model is not None
    return source.model, source.solver, source.modes_of_the_model, _slices(source, block)


_MARK = "\x00{}\x00"


def _number(value: float) -> str:
    """A float as JSON writes it (``repr``; NaN and inf as null, as :meth:`Result.to_dict`)."""
    return repr(value) if math.isfinite(value) else "null"


def modes_json_chunks(
    source: ModeBlocks | ModalResult, *, block: int = BLOCK_MODES, spool_dir: str | None = None
) -> Iterator[str]:
    """The compact JSON text of the modes, piece by piece, as ``json.dumps(result.to_dict(),
    separators=(",", ":"))`` writes it (the same keys, layout and digits), a block of modes at a
    time: never the N x N shapes in memory.

    The per-mode columns come before the shapes in the JSON and the nodes after them, all known
    only once every block is done: the shapes, nodes and round-off regions are spooled to
    anonymous temporary files (in ``spool_dir``, default the system's) and copied out at the
    end.

    Parameters
    ----------
    source
        The modes: a :class:`ModeBlocks` (computed block by block) or a :class:`ModalResult`.
    block
        Modes per block when ``source`` is a ModalResult.
    spool_dir
        Folder of the spool files (the output's folder: the same file system).

    Yields
    ------
    str
        Consecutive pieces of the JSON text, the last ending in a newline.
    """
    import json
    import tempfile

    model, solver, total, blocks = _source(source, block)
    names = [json.dumps(n) for n in model.dof_names]
    shaft_text = [json.dumps(list(s.between), separators=(",", ":")) for s in model.shafts]
    counts: list[NDArray[np.int_]] = []
    resolved: list[NDArray[np.bool_]] = []
    inertia: list[NDArray[np.float64]] = []
    omega: list[NDArray[np.float64]] = []
    with contextlib.ExitStack() as stack:
        spools = [
            stack.enter_context(
                tempfile.TemporaryFile("w+", encoding="utf-8", dir=spool_dir, newline="")
            )
            for _ in range(3)
        ]
        shapes_spool, nodes_spool, regions_spool = spools
        for b in blocks:
            rows, m = b.rows, b.omega.size
            comma = "," if b.start else ""
            text = json.dumps(rows.shapes.tolist(), separators=(",", ":"), allow_nan=False)
            shapes_spool.write(comma + text[1:-1])
            arrays = rows.nodes
            located = [
                f'{{"shaft":{shaft_text[s]},"fraction_from_first":{_number(t)},"determined":true}}'
                for s, t in zip(arrays.shaft.tolist(), arrays.fraction.tolist(), strict=True)
            ]
            loose = [
                (f'{{"mass":{names[a]},' if a == z else "{")
                + f'"roundoff_region":[{names[a]},{names[z]}],"determined":false}}'
                for a, z in zip(arrays.open_first.tolist(), arrays.open_last.tolist(), strict=True)
            ]
            regions = [
                f"[{names[a]},{names[z]}]"
                for a, z in zip(
                    arrays.region_first.tolist(), arrays.region_last.tolist(), strict=True
                )
            ]
            edges = np.arange(m + 1)
            ls = np.searchsorted(arrays.shaft_mode, edges).tolist()
            us = np.searchsorted(arrays.open_mode, edges).tolist()
            rs = np.searchsorted(arrays.region_mode, edges).tolist()
            nodes_spool.write(
                comma
                + ",".join(
                    "[" + ",".join(located[ls[r] : ls[r + 1]] + loose[us[r] : us[r + 1]]) + "]"
                    for r in range(m)
                )
            )
            regions_spool.write(
                comma + ",".join("[" + ",".join(regions[rs[r] : rs[r + 1]]) + "]" for r in range(m))
            )
            counts.append(arrays.counts(m))
            resolved.append(arrays.resolved(m))
            inertia.append(rows.modal_inertia)
            omega.append(b.omega)
            del rows, arrays, located, loose, regions, text
        head = _header(model, solver, total, omega, counts, resolved, inertia)
        data = head.to_dict()
        for key in ("mode_shapes", "nodes", "roundoff_regions"):
            data[key] = _MARK.format(key)
        text = json.dumps(data, separators=(",", ":"), allow_nan=False) + "\n"
        for key, spool in zip(("mode_shapes", "nodes", "roundoff_regions"), spools, strict=True):
            before, text = text.split(json.dumps(_MARK.format(key)), 1)
            yield before + "["
            spool.seek(0)
            while piece := spool.read(1 << 16):
                yield piece
            yield "]"
        yield text


def _header(
    model: TorsionModel,
    solver: str,
    total: int | None,
    omega: list[NDArray[np.float64]],
    counts: list[NDArray[np.int_]],
    resolved: list[NDArray[np.bool_]],
    inertia: list[NDArray[np.float64]],
) -> ModalResult:
    """A ModalResult of the per-mode columns without shapes or nodes (the exported keys in
    their order, for the streamed writers)."""
    w = np.concatenate(omega)
    j = np.concatenate(inertia)
    first = 0 if model.is_free else 1
    return ModalResult(
        mode=freeze(np.arange(first, first + w.size), dtype=int),
        natural_frequency=freeze(w),
        node_count=freeze(np.concatenate(counts), dtype=int),
        nodes_resolved=freeze(np.concatenate(resolved), dtype=bool),
        modal_inertia=freeze(j),
        modal_stiffness=freeze(w**2 * j),
        mode_shapes=np.zeros((w.size, 0)),
        masses=model.mass_names,
        solver=solver,
        structure="chain" if model.is_chain else "branched",
        free=model.is_free,
        model_name=model.name,
        modes_of_the_model=total,
    )


def modes_csv_chunks(
    source: ModeBlocks | ModalResult, *, block: int = BLOCK_MODES
) -> Iterator[str]:
    """The CSV text of the modes (:meth:`ModalResult.to_csv`: one row per mode, the per-mode
    columns, then ``amplitude_1`` ... ``amplitude_N``), a block of rows at a time.

    Parameters
    ----------
    source
        The modes: a :class:`ModeBlocks` (computed block by block) or a :class:`ModalResult`.
    block
        Modes per block when ``source`` is a ModalResult.

    Yields
    ------
    str
        The header line, then one row (mode) at a time.
    """
    model, _solver, _total, blocks = _source(source, block)
    first = 0 if model.is_free else 1
    keys = list(
        Result.columns(
            _header(
                model, "", None, [np.zeros(1)], [np.zeros(1, int)], [np.ones(1, bool)], [np.ones(1)]
            )
        )
    )
    keys += [f"amplitude_{i + 1}" for i in range(len(model.mass_names))]
    yield ",".join(keys) + "\n"
    line = ",".join(["%.10g"] * len(keys)) + "\n"
    for b in blocks:
        rows, m = b.rows, b.omega.size
        table = np.column_stack(
            [
                np.arange(first + b.start, first + b.start + m, dtype=float),
                b.omega * HZ,
                rows.counts.astype(float),
                rows.resolved.astype(float),
                rows.modal_inertia,
                b.omega**2 * rows.modal_inertia,
                rows.shapes,
            ]
        )
        del rows
        for r in table:  # a row at a time: never the block as Python floats
            yield line % tuple(r.tolist())
