"""Mode-shape tables and relative vector sums (analysis and result): what a torsional vibration
calculation tabulates for its natural modes.

Per elastic mode r: the natural frequency, the relative amplitude a_j of every mass j (the mode
shape of :func:`crankdyn.torsion.modal.natural_modes`, reflected to the reference speed, largest
magnitude 1) and the nodes. Per order q of the engine's cycle and per mode, the *relative vector
sum* of the cylinders::

    R_q,r = | sum_k beta_k,r exp(-i q Phi_k) |

where beta_k,r is the relative amplitude of the mass carrying cylinder k in mode r (normalised so
that the largest cylinder amplitude is 1: :func:`crankdyn.torsion.harmonics.cylinder_amplitudes`)
and Phi_k the crank angle at which cylinder k fires after cylinder 1 (the firing order), so that
q Phi_k is the phase of cylinder k's harmonic of order q (Ker Wilson, *Practical Solution of
Torsional Vibration Problems*, vol. 2, the "phase-vector" or "vector summation" of the relative
amplitudes; Nestorides, *A Handbook on Torsional Vibration*, BICERA 1958, ch. 7, "relative
vector sums"; seed 003 section 4.2 for the phase relation of the k-th harmonic of a multi-throw
crankshaft). The work the order's harmonic torque T_q does per cycle on mode r is pi T_q theta_1
R_q,r, so at resonance the amplitude of mode r under order q scales with R_q,r: the orders with
the largest sums are the dangerous ones; at a *major* order all cylinders act in phase and R is
|sum_k beta_k| (:func:`crankdyn.torsion.orders.major_orders`).

The numbers come from :func:`crankdyn.torsion.orders.relative_amplitude_sums` (the same sums the
Campbell diagram's critical speeds carry, :mod:`crankdyn.torsion.campbell`); this module
declares them as a result whose summary tables every front end renders.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.constants import DEG
from crankdyn.results import Result, array, freeze, scalar
from crankdyn.summary import SummaryColumn, SummaryTable, derived
from crankdyn.torsion.harmonics import cylinder_amplitudes
from crankdyn.torsion.orders import fundamental_order, major_orders, relative_amplitude_sums

if TYPE_CHECKING:
    from crankdyn.torsion.excitation import Excitation
    from crankdyn.torsion.modal import ModalResult
    from crankdyn.torsion.model import TorsionModel

__all__ = ["MODES_SHOWN", "ModeTable", "excited_mode_table", "mode_table"]

HZ = 1.0 / (2.0 * math.pi)

MODES_SHOWN = 6
"""The elastic modes tabulated by default (the lowest; those of the mode-shape plot)."""


def _largest_sum(t: ModeTable) -> tuple[float, str] | None:
    """The largest relative vector sum of the first mode, with its order."""
    if t.vector_sums is None or not t.modes.size or not t.orders.size:
        return None
    row = np.asarray(t.vector_sums[0], dtype=float)
    j = int(np.argmax(row))
    return float(row[j]), f"order {t.orders[j]:g}, mode {int(t.modes[0])}"


@dataclass(frozen=True)
class ModeTable(Result):
    """Relative amplitudes per mass, nodes and relative vector sums per order of the lowest
    elastic modes (:func:`mode_table`; module docstring).

    Parameters
    ----------
    shown : tuple of str
        The masses the mode-shape table lists (the model's masses less the interior elements
        of distributed shafts; not exported).
    """

    title = "Mode shapes and relative vector sums"
    modes: NDArray[np.int_] = array("modes", "Mode", "")
    natural_frequency: NDArray[np.float64] = array(
        "natural_frequencies_hz", "Natural frequency", "Hz", HZ
    )
    """Natural frequency omega_r of every mode tabulated (rad/s; exported in Hz)."""
    masses: tuple[str, ...] = scalar("masses", "Masses", "", summary=False)
    amplitudes: NDArray[np.float64] = array(
        "relative_amplitudes", "Relative amplitude (mode x mass)", ""
    )
    """Relative amplitude of every mass in every mode tabulated (dimensionless, largest
    magnitude 1 per mode, reflected to the reference speed), shape (modes, masses)."""
    nodes: tuple[str, ...] = scalar("nodes", "Nodes", "", summary=False)
    """The nodes of every mode tabulated, in words (:meth:`crankdyn.torsion.modal.Node.
    describe`)."""
    orders: NDArray[np.float64] = array("orders", "Order", "")
    firing_angles: NDArray[np.float64] | None = array(
        "firing_angles_deg", "Firing angle after cylinder 1", "deg", DEG
    )
    """Phi_k of every cylinder (rad; exported in degrees), or None without cylinders."""
    cylinder_amplitudes: NDArray[np.float64] | None = array(
        "cylinder_amplitudes", "Relative amplitude at the cylinders (mode x cylinder)", ""
    )
    """beta_k,r (dimensionless, largest cylinder amplitude 1 per mode), or None."""
    vector_sums: NDArray[np.float64] | None = array(
        "relative_vector_sums", "Relative vector sums (mode x order)", ""
    )
    """R_q,r (dimensionless), shape (modes, orders); None where the firing angles are unknown
    or the model has no cylinders."""
    major: NDArray[np.bool_] | None = array("major", "Major order", "")
    notes: tuple[str, ...] = scalar("notes", "Notes", "")
    shown: tuple[str, ...] = ()

    FIGURES = (
        derived(
            "max_relative_vector_sum_mode_1", "max_relative_vector_sum_mode_1",
            "Largest relative vector sum of the first mode", "", _largest_sum,
            reduction="max over the orders", better="min",
            unavailable="no cylinders with known firing angles: no vector sums",
            description="The largest relative vector sum of the cylinders' relative amplitudes "
            "in elastic mode 1 over the orders (Ker Wilson vol. 2; Nestorides 1958 ch. 7)",
        ),
    )  # fmt: skip

    def summary_tables(self) -> list[SummaryTable]:
        """The mode shapes (relative amplitude per mass and mode, the nodes) and the relative
        vector sums (per order and mode, the major orders marked).

        Returns
        -------
        list of crankdyn.summary.SummaryTable
            The tables.
        """
        heads = tuple(
            SummaryColumn(f"mode_{int(m)}", f"Mode {int(m)}, {f * HZ:.4g} Hz")
            for m, f in zip(self.modes, self.natural_frequency, strict=True)
        )
        index = {name: i for i, name in enumerate(self.masses)}
        rows = tuple(
            (name, *(round(float(a), 4) for a in self.amplitudes[:, index[name]]))
            for name in (self.shown or self.masses)
        )
        rows += (("Nodes", *self.nodes),)
        left_out = len(self.masses) - len(self.shown or self.masses)
        caption = (
            "Relative amplitude of every mass (largest 1 per mode, reflected to the reference "
            "speed); the last row: the nodes (on the shaft from its first mass, at a fraction "
            "of its length)."
        )
        if left_out:
            caption += (
                f" The {left_out} interior element masses of distributed shafts are left out "
                "(in the JSON)."
            )
        tables = [
            SummaryTable(
                "mode_shapes",
                "Mode shapes",
                (SummaryColumn("mass", "Mass"), *heads),
                rows,
                caption,
            )
        ]
        if self.vector_sums is not None and self.major is not None:
            sums = tuple(
                (
                    float(q),
                    "yes" if major else "",
                    *(round(float(v), 4) for v in self.vector_sums[:, j]),
                )
                for j, (q, major) in enumerate(zip(self.orders, self.major, strict=True))
            )
            tables.append(
                SummaryTable(
                    "relative_vector_sums",
                    "Relative vector sums",
                    (SummaryColumn("order", "Order"), SummaryColumn("major", "Major"), *heads),
                    sums,
                    "|Σ_k β_k exp(-i q Φ_k)| over the cylinders k with the firing order's "
                    "angles Φ_k, β_k the relative amplitude of cylinder k's mass (largest "
                    "cylinder amplitude 1): the larger, the more the order excites the mode "
                    "(Ker Wilson vol. 2; Nestorides 1958 ch. 7).",
                )
            )
        return tables


def _interior(model: TorsionModel) -> set[str]:
    """The masses inside distributed shafts (their elements' joints), not the shafts' ends."""
    inner: set[str] = set()
    ends: set[str] = set()
    for s in model.shafts:
        segment = getattr(s, "segment_of", None)
        if segment is not None:
            inner.update(s.between)
            ends.update(segment)
    return inner - ends


def mode_table(
    modes: ModalResult,
    model: TorsionModel,
    orders: ArrayLike,
    firing_angles: ArrayLike | None = None,
    *,
    count: int = MODES_SHOWN,
) -> ModeTable:
    """The mode-shape table and the relative vector sums of the lowest elastic modes (module
    docstring: Ker Wilson vol. 2; Nestorides 1958 ch. 7).

    Parameters
    ----------
    modes : crankdyn.torsion.modal.ModalResult
        The natural modes of ``model`` (:func:`crankdyn.torsion.modal.natural_modes`).
    model : crankdyn.torsion.model.TorsionModel
        The model (its masses' ``cylinders`` place the cylinders).
    orders : array_like
        The orders q (multiples of the crankshaft speed, dimensionless), shape (orders,).
    firing_angles : array_like or None
        Phi_k, the crank angle at which cylinder k fires after cylinder 1 (rad), shape
        (cylinders,); None: unknown (no vector sums, a note says so).
    count : int
        The lowest elastic modes tabulated (default :data:`MODES_SHOWN`).

    Returns
    -------
    ModeTable
        The relative amplitudes (dimensionless), nodes, and with firing angles the relative
        vector sums R_q,r (dimensionless) and the major orders.

    Examples
    --------
    Two equal cylinders at the ends of a shaft, firing 360 deg apart (a four-stroke twin):
    the one elastic mode swings them against each other (beta = 1, -1), so order 0.5 adds
    them (|1 - exp(-i 0.5 2 pi)| = 2) and order 1 cancels them.

    >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
    >>> from crankdyn.torsion.modal import natural_modes
    >>> m = TorsionModel((Mass("a", 1.0, cylinders=(1,)), Mass("b", 1.0, cylinders=(2,))),
    ...                  (Shaft(("a", "b"), 1e4),))
    >>> t = mode_table(natural_modes(m), m, [0.5, 1.0], np.radians([0.0, 360.0]))
    >>> t.vector_sums.round(12).tolist(), t.nodes
    ([[2.0, 0.0]], ('a - b at 0.500',))
    """
    q = np.atleast_1d(np.asarray(orders, dtype=float))
    elastic = np.flatnonzero(np.asarray(modes.natural_frequency) > 0.0)[: max(int(count), 0)]
    amplitudes = np.asarray(modes.mode_shapes, dtype=float)[elastic]
    nodes = tuple(
        "; ".join(n.describe() for n in modes.nodes[i]) or "none" for i in elastic.tolist()
    )
    count_cyl = max((max(m.cylinders, default=0) for m in model.masses), default=0)
    notes: list[str] = []
    beta = sums = major = angles = None
    if count_cyl:
        beta = cylinder_amplitudes(modes, model, count_cyl)[elastic]
        if firing_angles is None:
            notes.append(
                "the firing angles are unknown (neither a firing order nor firing angles): "
                "no relative vector sums"
            )
        else:
            angles = np.atleast_1d(np.asarray(firing_angles, dtype=float))
            sums = relative_amplitude_sums(beta, angles, q)
            major = major_orders(angles, q)
    else:
        notes.append("the model has no cylinders: no relative vector sums")
    inner = _interior(model)
    return ModeTable(
        modes=freeze(np.asarray(modes.mode)[elastic], dtype=int),
        natural_frequency=freeze(np.asarray(modes.natural_frequency)[elastic]),
        masses=tuple(modes.masses),
        amplitudes=freeze(amplitudes),
        nodes=nodes,
        orders=freeze(q),
        firing_angles=None if angles is None else freeze(angles),
        cylinder_amplitudes=None if beta is None else freeze(beta),
        vector_sums=None if sums is None else freeze(sums),
        major=None if major is None else freeze(major, dtype=bool),
        notes=tuple(notes),
        shown=tuple(m for m in modes.masses if m not in inner),
    )


def excited_mode_table(
    modes: ModalResult,
    model: TorsionModel,
    excitation: Excitation,
    orders: ArrayLike,
    *,
    count: int = MODES_SHOWN,
) -> ModeTable:
    """:func:`mode_table` for an engine's excitation: the orders of its working cycle among
    ``orders`` (a source's own orders, e.g. a propeller's blade orders, have no vector sum) and
    its firing angles where they are known.

    Parameters
    ----------
    modes : crankdyn.torsion.modal.ModalResult
        The natural modes of ``model``.
    model : crankdyn.torsion.model.TorsionModel
        The model.
    excitation : crankdyn.torsion.excitation.Excitation
        The cylinders' excitation (its ``cycle``, ``firing_angles`` in rad and whether its
        phases are known).
    orders : array_like
        Orders (dimensionless); those that are not multiples of the cycle's fundamental order
        (:func:`crankdyn.torsion.orders.fundamental_order`) are left out.
    count : int
        The lowest elastic modes tabulated.

    Returns
    -------
    ModeTable
        The table.
    """
    q = np.atleast_1d(np.asarray(orders, dtype=float))
    ratio = q / fundamental_order(excitation.cycle)
    q = q[np.abs(ratio - np.round(ratio)) < 1e-9]
    known = bool(getattr(excitation, "phases_known", True)) and excitation.cylinder_count > 0
    angles = excitation.firing_angles if known else None
    return mode_table(modes, model, q, angles, count=count)
