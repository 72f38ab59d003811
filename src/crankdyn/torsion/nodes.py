"""Mode shapes: their normalisation, the round-off thresholds of their components and their
nodes (numeric core of :mod:`crankdyn.torsion.modal`).

A shape is normalised to a largest absolute amplitude of 1, the first non-zero amplitude
positive (:func:`normalise_shapes`); its nodes are where the amplitude passes through zero, at a
fraction t = theta_a / (theta_a - theta_b) along a shaft from its first mass (the twist being
uniform along a uniform shaft).

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
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, cast

import numpy as np
import numpy.typing as npt
from numpy.typing import NDArray

if TYPE_CHECKING:
    from crankdyn.torsion.model import TorsionModel

__all__ = ["roundoff_thresholds"]

_ZERO = 1e-9  # the first amplitude above this (of the largest) sets a shape's sign
_EPS = float(np.finfo(float).eps)


def normalise_shapes(
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
    few = count <= FEW
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
    """:func:`normalise_shapes` of rows that may be zeros, inf or NaN, in place: a row of zeros
    stays zeros, a row with NaN NaN.

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
    distinct = distinct_thresholds(lam)
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
    if values.size > FEW:
        least, total = float(np.minimum.reduce(values)), float(np.add.reduce(values))
    else:
        listed = values.tolist()
        least, total = min(listed), sum(listed)
    return least if least > 0.0 and total < math.inf else None


FEW = 32
"""Values up to which :func:`_least_positive` and the chain's one-pass modes
(:mod:`crankdyn.torsion.modal`) reduce a 1-D array in Python (a list of 32 floats: as quick as one
numpy reduction)."""


def distinct_thresholds(lam: NDArray[np.float64]) -> tuple[NDArray[np.float64], float] | None:
    """:func:`roundoff_thresholds` of eigenvalues that ascend strictly (the rule: the solvers
    give them ascending), with the largest threshold; None otherwise (unordered, repeated or
    NaN: the general code). Two or more eigenvalues.

    gap_r = min(lambda_r+1 - lambda_r, lambda_r - lambda_r-1) from the steps padded with inf at
    both ends; the same operations, to the bit, as the general code."""
    n = lam.size
    if n <= FEW:  # a few: in Python on a list, the same IEEE operations (numpy's per-call cost)
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
class NodeArrays:
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
) -> NodeArrays:
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
    return NodeArrays(
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
) -> NodeArrays:
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

    return NodeArrays(
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
) -> NodeArrays:
    """Nodes and round-off regions of the modes in the rows of ``shapes_dof`` (module
    docstring); ``tau``, ``rigid``: :func:`_resolved`."""
    resolved = _resolved(model, np.abs(shapes_dof), modal_inertia, tau, rigid)
    if model.is_chain:
        return _chain_nodes(model, shapes_dof, resolved)
    return _graph_nodes(model, shapes_dof, resolved)


class Nodes:
    """The node arrays of some modes: given, or located from their inputs when first asked for
    (:func:`_find_nodes`; the inputs are dropped then)."""

    __slots__ = ("_arrays", "_inputs")

    def __init__(
        self,
        arrays: NodeArrays | None = None,
        inputs: tuple[
            TorsionModel, NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], bool
        ]
        | None = None,
    ) -> None:
        self._arrays = arrays
        self._inputs = inputs

    @property
    def arrays(self) -> NodeArrays:
        """The node arrays (:class:`NodeArrays`)."""
        if self._arrays is None:
            assert self._inputs is not None
            self._arrays = _find_nodes(*self._inputs)
            self._inputs = None
        return self._arrays


def chain_node_counts(
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
"""Modes x degrees of freedom from which :func:`chain_node_counts` sums a mode's sign changes
between its first and last resolved components (one ``reduceat``) rather than finding each
component's mode by a division (fewer calls below)."""

_FLAT_COUNTS = 1 << 16
"""Modes x degrees of freedom up to which :func:`chain_node_counts` counts from the flat indices of
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
class ModeRows:
    """The per-mode results of some modes (rows): shapes by mass and by dof, modal inertias,
    node counts, whether resolved, the nodes (mode indices counted from the first row)."""

    shapes: NDArray[np.float64]  # mode x mass (listing order), largest amplitude 1
    shapes_dof: NDArray[np.float64]  # mode x dof
    modal_inertia: NDArray[np.float64]  # kg·m²
    counts: NDArray[np.intp]  # nodes per mode
    resolved: NDArray[np.bool_]  # whether the mode's shape is above round-off throughout
    found: Nodes

    @property
    def nodes(self) -> NodeArrays:
        """The node arrays (located when first asked for)."""
        return self.found.arrays

    @classmethod
    def of(
        cls,
        shapes: NDArray[np.float64],
        shapes_dof: NDArray[np.float64],
        modal_inertia: NDArray[np.float64],
        nodes: NodeArrays,
    ) -> ModeRows:
        """The rows with their nodes located already."""
        m = modal_inertia.size
        return cls(
            shapes, shapes_dof, modal_inertia, nodes.counts(m), nodes.resolved(m), Nodes(nodes)
        )


def mode_rows(
    model: TorsionModel,
    phi_t: NDArray[np.float64],
    tau: NDArray[np.float64],
    rigid: bool,
    *,
    lazy: bool = False,
) -> ModeRows:
    """Normalise the shapes ``phi_t`` (mode x dof, changed in place), their modal inertias
    J_r = sum J_i phi_i^2 and nodes (``tau``, ``rigid``: :func:`_resolved`). ``lazy``: a
    chain's nodes are only counted (:func:`chain_node_counts`) and located when first asked for."""
    shapes_dof, size, _ = normalise_shapes(phi_t, least=False)  # mode x dof; size = |shapes_dof|
    # mode x mass (listing order)
    shapes = shapes_dof if model._dofs_in_listing_order else shapes_dof[:, model.mass_dof]
    square = size * size  # phi_i^2
    modal_inertia = square @ model.dof_inertia  # sum of J_i phi_i^2
    del square
    if lazy and model.is_chain:
        resolved = _resolved(model, size, modal_inertia, tau, rigid)
        del size
        counts, whole = chain_node_counts(shapes_dof, resolved)
        found = Nodes(inputs=(model, shapes_dof, modal_inertia, tau, rigid))
        return ModeRows(shapes, shapes_dof, modal_inertia, counts, whole, found)
    resolved = _resolved(model, size, modal_inertia, tau, rigid)
    del size
    if model.is_chain:
        nodes = _chain_nodes(model, shapes_dof, resolved)
    else:
        nodes = _graph_nodes(model, shapes_dof, resolved)
    return ModeRows.of(shapes, shapes_dof, modal_inertia, nodes)
