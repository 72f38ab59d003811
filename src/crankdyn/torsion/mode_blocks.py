"""Every mode of a large chain, block by block, and its JSON and CSV written as it is computed
(analysis and output of :mod:`crankdyn.torsion.modal`).

Large chains in blocks. Every mode of an N-mass model has N x N amplitudes (800 MB of float64 at
N = 10,000). :class:`ModeBlocks` computes a chain's modes a block at a time: all eigenvalues
first (``dsterf``; those whose absolute accuracy eps ||T|| is not small against them again by
bisection, ``dstebz``), then each block's eigenvectors by inverse iteration (``dstein``:
Anderson et al. 1999, section 2.4.4; the same error bound eps ||A|| / gap_r), normalised, their
nodes found with the whole spectrum's thresholds, and handed to :func:`modes_json_chunks` or
:func:`modes_csv_chunks`, which write what
:meth:`~crankdyn.torsion.modal.ModalResult.to_dict` and
:meth:`~crankdyn.results.Result.to_csv` would, a block at a time.
"""

from __future__ import annotations

import contextlib
import itertools
import math
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from crankdyn.errors import InputError
from crankdyn.results import Result, freeze
from crankdyn.torsion.modal import BISECTION_TOL, HZ, ModalResult, modal_result
from crankdyn.torsion.model import TorsionModel
from crankdyn.torsion.nodes import ModeRows, NodeArrays, mode_rows, roundoff_thresholds

__all__ = [
    "BLOCK_MODES",
    "STREAMED_SIZE",
    "ModeBlocks",
    "modes_csv_chunks",
    "modes_json_chunks",
]

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
recomputed by bisection to full relative accuracy (``dstebz``, :data:`BISECTION_TOL`)."""


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
    accuracy, as the lowest modes of :func:`~crankdyn.torsion.modal.eigen_modes`)."""
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
        m, w, ib, _, info = lapack.dstebz(d, e, 2, 0.0, 0.0, 1, refine, BISECTION_TOL, b"E")
        if info != 0 or m != refine:
            raise np.linalg.LinAlgError(f"the bisection failed (dstebz info {info})")
        lam[:refine], iblock[:refine] = w[:refine], ib[:refine]
    return lam, iblock, isplit


@dataclass(frozen=True)
class _Block:
    """The modes ``start`` .. ``start + omega.size - 1`` (indices into the listed modes)."""

    start: int
    omega: NDArray[np.float64]  # rad/s
    rows: ModeRows


class ModeBlocks:
    """Every mode of a chain (or the lowest ``count``), computed and exported block by block.

    The eigenvalues come first, all of them (:func:`_chain_spectrum`: ``dsterf``, the lowest
    refined by bisection); then the eigenvectors of :data:`BLOCK_MODES` modes at a time by
    inverse iteration (LAPACK ``dstein``, E. Anderson et al., *LAPACK Users' Guide*, 3rd ed.,
    SIAM 1999, section 2.4.4), each block normalised, its nodes found (the round-off thresholds
    of the whole spectrum, :mod:`crankdyn.torsion.nodes`) and handed out, never the N x N
    matrix. Memory: N x :data:`BLOCK_MODES` floats and the per-mode columns. The numbers are
    those of :func:`~crankdyn.torsion.modal.natural_modes` (eigenvectors to round-off: the same
    bound eps ||A|| / gap_r).

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
            rows = mode_rows(self.model, u.T, self.tau[lo:hi], rigid)
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
            The modes, as :func:`~crankdyn.torsion.modal.natural_modes` gives them (to
            round-off).

        Examples
        --------
        >>> from crankdyn.torsion import TorsionModel
        >>> r = ModeBlocks(TorsionModel.chain_of([1.0, 1.0, 1.0], [1e4, 1e4]), block=2).result()
        >>> [round(float(w), 4) for w in r.natural_frequency]  # sqrt(k / J), sqrt(3 k / J)
        [0.0, 100.0, 173.2051]
        """
        parts = list(self.blocks())
        rows = ModeRows.of(
            np.concatenate([p.rows.shapes for p in parts]),
            np.concatenate([p.rows.shapes_dof for p in parts]),
            np.concatenate([p.rows.modal_inertia for p in parts]),
            _concat_nodes([(p.start, p.rows.nodes) for p in parts]),
        )
        total = self.total if self.count < self.total else None
        all_omega = self.all_omega if total is not None else None
        return modal_result(self.model, solver, self.omega.copy(), rows, 0, total, all_omega)


def _concat_nodes(parts: list[tuple[int, NodeArrays]]) -> NodeArrays:
    """The node arrays of consecutive blocks as one (mode indices shifted by each start)."""

    def cat(name: str, shift: bool) -> NDArray[np.int_] | NDArray[np.float64]:
        return np.concatenate([getattr(a, name) + (s if shift else 0) for s, a in parts])

    return NodeArrays(
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
        rows = ModeRows.of(
            result.mode_shapes[lo:hi],
            result.shapes_dof[lo:hi],
            result.modal_inertia[lo:hi],
            NodeArrays(sm, sh, fr, om, of, ol, rm, rf, rl),
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
        model=model,  # the figures derived from the model (the installation's inertia)
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
