"""Firing-order search: enumerate the firing orders a crankshaft allows and rank them.

Seed 000 section 2.3 lists what decides the crank arrangement and firing order, in this order:

1. the firing intervals should be as even as possible;
2. the engine should be well balanced (small free forces and moments);
3. adjacent cylinders should not fire one after the other, to spare the main bearing between
   them;
4. the crankshaft's torsional vibration should be small;
5. with pulse turbocharging, the exhaust branches should collect cylinders that fire far apart.

Each is a :class:`Criterion`: a function of a batch of firing schemes (n rows) returning n
values, with the direction that is better. The built-in ones:

- ``interval_deviation_deg``: the largest departure of a firing interval from the even
  interval (0 for even firing).
- ``free_force_1``, ``free_force_2``, ``free_moment_1``, ``free_moment_2``: the first- and
  second-order free forces and moments of the reciprocating masses, per unit harmonic force
  (the amplitude divided by m_j R w^2 A_n) and, for the moments, per unit cylinder pitch a,
  about the middle of the engine (see :mod:`crankdyn.engine.balance`). They depend on the crankshaft
  only, so they separate crankshafts, not orders; forces come first since counterweights can
  cancel a first-order moment but no crankshaft weight cancels a free force of the second
  order.
- ``adjacent_consecutive``: how many times in a cycle a cylinder fires right after an adjacent
  one (same bank, neighbouring throw), the cycle closing from the last cylinder to the first.
  Each bank of a V engine counts as the in-line engine it is: its cylinders' own firing
  sequence is judged (in the engine's order a bank-B cylinder may stand between them).
- ``main_bearing_min_interval_deg``: for every main bearing between two throws, the shortest
  firing interval between two cylinders on the throws either side of it (any banks); the
  smallest over the bearings. Two firings in quick succession next to one bearing load it
  twice without a pause; larger is better. (The two cylinders of one V throw are not paired:
  their interval is set by the bank angle.)
- ``torsional_vector_sum`` (given a mode shape, :func:`torsional_criterion`): the vector sum
  |sum_i beta_i exp(j n Phi_i)| of order n over the relative amplitudes beta_i of the mode at
  the cylinders, the largest over the minor orders (or over chosen orders). At a major order
  (n times the even interval a multiple of 360 deg) all cylinders act in phase and the sum is
  sum beta_i whatever the order; the minor orders depend on the firing order (Ker Wilson,
  *Practical Solution of Torsional Vibration Problems*, vol. 2; Nestorides, *A Handbook on
  Torsional Vibration*, 1958, ch. 7: phase-vector sums).
- ``exhaust_min_interval_deg`` (given exhaust groups, :func:`exhaust_criterion`): the shortest
  firing interval between two cylinders sharing an exhaust branch; pulse turbocharging wants
  the pulses of one branch spread evenly (e.g. 240 deg for three cylinders of a four-stroke).

Orders are ranked lexicographically by the criteria in priority order (seed order by default),
each rounded so that round-off does not separate equal values, the firing order itself breaking
the remaining ties.
"""

from __future__ import annotations

import csv
import io
import math
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.constants import DEG
from crankdyn.engine.balance import harmonic_phasors, phasor_amplitude
from crankdyn.engine.firing import (
    CYCLE_ANGLE,
    TWO_PI,
    FiringSchemes,
    all_firing_schemes,
    crank_end_view,
    crankshaft_firing_schemes,
    even_firing_schemes,
    v_scheme,
)
from crankdyn.errors import InputError
from crankdyn.results import Result, freeze, scalar
from crankdyn.summary import SummaryColumn, SummaryTable
from crankdyn.torsion.modal import natural_modes

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from crankdyn.engine.model import Cylinders
    from crankdyn.torsion.model import TorsionModel

__all__ = [
    "CRITERIA",
    "DEFAULT_PRIORITY",
    "Criterion",
    "FiringCandidate",
    "FiringOrderRanking",
    "Layout",
    "arrangement",
    "exhaust_criterion",
    "firing_order_search",
    "first_mode_shape",
    "torsional_criterion",
    "torsional_orders",
    "vector_sums",
]


@dataclass(frozen=True, eq=False)
class Layout:
    """What the criteria need of an engine's cylinder layout (arrays indexed by cylinder - 1).

    Parameters
    ----------
    count : int
        Number of cylinders Z.
    cycle : str
        ``"four-stroke"`` or ``"two-stroke"``.
    banks : tuple of str
        Bank (``"A"``/``"B"``) of every cylinder.
    throws : numpy.ndarray
        (Z,) throw (1-based) of every cylinder.
    axis_angles : numpy.ndarray
        (Z,) cylinder axis angle alpha_i from the vertical (rad).
    layout : str
        ``"inline"`` (default) or ``"V"``.
    """

    count: int
    cycle: str
    banks: tuple[str, ...]
    throws: NDArray[np.int_]
    axis_angles: NDArray[np.float64]
    layout: str = "inline"

    @classmethod
    def of(cls, cylinders: Cylinders) -> Layout:
        """The layout of an engine's cylinders.

        Parameters
        ----------
        cylinders : crankdyn.engine.Cylinders
            The engine's cylinders.

        Returns
        -------
        Layout
            Count, cycle, banks, throws and axis angles (rad).
        """
        return cls(
            count=cylinders.count,
            cycle=cylinders.cycle,
            banks=tuple(cylinders.banks),
            throws=np.asarray(cylinders.throws, dtype=int),
            axis_angles=np.asarray(cylinders.bank_axis_angles, dtype=float),
            layout=cylinders.layout,
        )

    @property
    def throw_count(self) -> int:
        """Number of crank throws."""
        return int(self.throws.max())

    @property
    def axial(self) -> NDArray[np.float64]:
        """Axial position of every cylinder from the middle of the engine, in pitches."""
        return self.throws.astype(np.float64) - 1.0 - (self.throw_count - 1.0) / 2.0

    def adjacent(self) -> NDArray[np.bool_]:
        """Which cylinders are adjacent (same bank, next throw).

        Returns
        -------
        numpy.ndarray
            (Z+1, Z+1) bool, indexed by cylinder numbers i, j (1-based; row and column 0
            unused).
        """
        z = self.count
        out = np.zeros((z + 1, z + 1), dtype=bool)
        t = self.throws
        b = np.array(self.banks)
        out[1:, 1:] = (np.abs(t[:, None] - t[None, :]) == 1) & (b[:, None] == b[None, :])
        return out

    def bearing_pairs(self) -> NDArray[np.int_]:
        """The pairs of cylinders either side of a main bearing between throws.

        Returns
        -------
        numpy.ndarray
            (P, 2) cylinder indices (0-based) on the two throws either side of a main bearing;
            empty for a single throw.
        """
        i, j = np.triu_indices(self.count, k=1)
        near = np.abs(self.throws[i] - self.throws[j]) == 1
        return np.stack([i[near], j[near]], axis=1)


@dataclass(frozen=True)
class Criterion:
    """A ranking criterion: a vectorised function of a batch of firing schemes.

    Parameters
    ----------
    name : str
        Key in the output (unit in the key).
    label : str
        Description for tables.
    better : str
        ``"lower"`` or ``"higher"``.
    evaluate : callable
        ``evaluate(schemes, layout) -> (n,) array`` (NaN where it does not apply), SI.
    decimals : int
        Decimals kept (of the written value) before ranking, so that round-off does not break
        ties; default 6.
    scale : float
        Factor from the evaluated SI value to the value written (DEG for angles); default 1.
    """

    name: str
    label: str
    better: str
    evaluate: Callable[[FiringSchemes, Layout], np.ndarray]
    decimals: int = 6
    scale: float = 1.0

    def key(self, values: ArrayLike) -> NDArray[np.float64]:
        """Values turned into a lower-is-better sort key (NaN last).

        Parameters
        ----------
        values : array_like
            The criterion's values (SI).

        Returns
        -------
        numpy.ndarray
            The sort key: the written values rounded to ``decimals``, negated when higher is
            better, NaN as inf.
        """
        v = np.round(np.asarray(values, dtype=float) * self.scale, self.decimals)
        v = -v if self.better == "higher" else v
        return np.where(np.isnan(v), np.inf, v)


def _interval_deviation(s: FiringSchemes, layout: Layout) -> np.ndarray:
    even = CYCLE_ANGLE[s.cycle] / s.count
    return np.max(np.abs(s.intervals - even), axis=1)


def _bank_sequences(orders: np.ndarray, layout: Layout) -> Iterator[np.ndarray]:
    """For each bank, the (n, k) firing sequence of its cylinders (each bank of a V engine
    fires as an in-line engine)."""
    banks = np.array(layout.banks)
    for bank in sorted(set(layout.banks)):
        size = layout.banks.count(bank)
        mask = banks[orders - 1] == bank
        yield orders[mask].reshape(orders.shape[0], size)


def _adjacent(s: FiringSchemes, layout: Layout) -> np.ndarray:
    adj = layout.adjacent()
    total = np.zeros(len(s))
    for seq in _bank_sequences(s.orders, layout):
        if seq.shape[1] > 1:
            total += adj[seq, np.roll(seq, -1, axis=1)].sum(axis=1)
    return total


def _cyclic_gap(a: np.ndarray, b: np.ndarray, cycle_angle: float) -> np.ndarray:
    d = np.mod(a - b, cycle_angle)
    return np.minimum(d, cycle_angle - d)


def _bearing(s: FiringSchemes, layout: Layout) -> np.ndarray:
    pairs = layout.bearing_pairs()
    if pairs.size == 0:
        return np.full(len(s), np.nan)
    gaps = _cyclic_gap(s.firing[:, pairs[:, 0]], s.firing[:, pairs[:, 1]], CYCLE_ANGLE[s.cycle])
    return gaps.min(axis=1)


def _snap(values: np.ndarray, reference: float) -> np.ndarray:
    """Sums that vanish exactly come out near 1e-16 of their terms: set them to zero."""
    return np.where(values < 1e-12 * reference, 0.0, values)


def _free_force(order: int) -> Callable[[FiringSchemes, Layout], np.ndarray]:
    def evaluate(s: FiringSchemes, layout: Layout) -> np.ndarray:
        ph = harmonic_phasors(s.throw_angles, layout.axis_angles, 1.0, order)
        return _snap(phasor_amplitude(ph.x, ph.y), layout.count)

    return evaluate


def _free_moment(order: int) -> Callable[[FiringSchemes, Layout], np.ndarray]:
    def evaluate(s: FiringSchemes, layout: Layout) -> np.ndarray:
        if layout.throw_count < 2:
            return np.zeros(len(s))
        ph = harmonic_phasors(s.throw_angles, layout.axis_angles, 1.0, order, layout.axial)
        assert ph.xz is not None and ph.yz is not None  # axial positions given: moments
        return _snap(phasor_amplitude(ph.xz, ph.yz), layout.count * layout.throw_count)

    return evaluate


CRITERIA: dict[str, Criterion] = {
    c.name: c
    for c in (
        Criterion(
            "interval_deviation_deg",
            "Largest departure from the even interval (deg)",
            "lower",
            _interval_deviation,
            decimals=6,
            scale=DEG,
        ),
        Criterion(
            "free_force_1",
            "1st-order free force / (m_j R ω²)",
            "lower",
            _free_force(1),
            decimals=9,
        ),
        Criterion(
            "free_force_2",
            "2nd-order free force / (m_j R ω² A₂)",
            "lower",
            _free_force(2),
            decimals=9,
        ),
        Criterion(
            "free_moment_1",
            "1st-order free moment / (m_j R ω² a)",
            "lower",
            _free_moment(1),
            decimals=9,
        ),
        Criterion(
            "free_moment_2",
            "2nd-order free moment / (m_j R ω² A₂ a)",
            "lower",
            _free_moment(2),
            decimals=9,
        ),
        Criterion(
            "adjacent_consecutive",
            "Adjacent cylinders firing one after the other",
            "lower",
            _adjacent,
            decimals=0,
        ),
        Criterion(
            "main_bearing_min_interval_deg",
            "Shortest firing interval next to a main bearing (deg)",
            "higher",
            _bearing,
            decimals=6,
            scale=DEG,
        ),
    )
}
"""The built-in ranking criteria by name (module docstring)."""
DEFAULT_PRIORITY = (
    "interval_deviation_deg",
    "free_force_1",
    "free_force_2",
    "free_moment_1",
    "free_moment_2",
    "adjacent_consecutive",
    "main_bearing_min_interval_deg",
    "torsional_vector_sum",
    "exhaust_min_interval_deg",
)
"""The criteria in seed 000's order of importance (section 2.3), those that apply."""


# ---- torsional excitation ----------------------------------------------------------------------


def torsional_orders(count: int, cycle: str) -> NDArray[np.float64]:
    """The orders whose vector sums repeat for an evenly firing engine.

    Parameters
    ----------
    count : int
        Number of cylinders Z.
    cycle : str
        ``"four-stroke"`` or ``"two-stroke"``.

    Returns
    -------
    numpy.ndarray
        0.5, 1, ..., Z/2 (four-stroke) or 1, 2, ..., Z (two-stroke), multiples of the crankshaft
        speed (dimensionless).

    Examples
    --------
    >>> torsional_orders(4, "four-stroke")
    array([0.5, 1. , 1.5, 2. ])
    """
    if cycle == "four-stroke":
        return np.arange(1, count + 1) / 2.0
    return np.arange(1, count + 1, dtype=float)


def major_orders(orders: ArrayLike, count: int, cycle: str) -> NDArray[np.bool_]:
    """Whether each order is a major order.

    At a major order n times the even interval is a multiple of 360 deg (every cylinder in
    phase), i.e. n is a multiple of Z/2 (four-stroke) or Z (two-stroke).

    Parameters
    ----------
    orders : array_like
        Orders n (multiples of the crankshaft speed, dimensionless).
    count : int
        Number of cylinders Z.
    cycle : str
        ``"four-stroke"`` or ``"two-stroke"``.

    Returns
    -------
    numpy.ndarray
        Bool, of the shape of ``orders``.

    Examples
    --------
    >>> major_orders([0.5, 1.0, 1.5, 2.0, 4.0], 4, "four-stroke")
    array([False, False, False,  True,  True])
    """
    step = count / 2.0 if cycle == "four-stroke" else float(count)
    ratio = np.asarray(orders, dtype=float) / step
    return np.abs(ratio - np.round(ratio)) < 1e-9


def vector_sums(firing: ArrayLike, amplitudes: ArrayLike, orders: ArrayLike) -> NDArray[np.float64]:
    """Phase-vector sums |sum_i beta_i exp(j n Phi_i)| of the cylinders' excitation (module
    docstring).

    Parameters
    ----------
    firing : array_like
        Firing angles Phi_i (rad), shape (Z,) or a batch (m, Z).
    amplitudes : array_like
        Relative amplitude beta_i of the mode shape at every cylinder's crank (Z,).
    orders : array_like
        Orders n (multiples of the crankshaft speed, dimensionless).

    Returns
    -------
    numpy.ndarray
        Shape (..., len(orders)), in the units of the amplitudes.

    Examples
    --------
    An inline-4 firing 1-3-4-2 with equal amplitudes: the major orders 2 and 4 add up (sum of
    beta = 4), the minor orders cancel.

    >>> phi = np.radians([0, 540, 180, 360])
    >>> np.round(vector_sums(phi, np.ones(4), [0.5, 1, 1.5, 2]), 12)
    array([0., 0., 0., 4.])
    """
    phi = np.asarray(firing, dtype=float)
    beta = np.asarray(amplitudes, dtype=float)
    n = np.asarray(orders, dtype=float)
    # one (m, Z) complex array per order keeps memory bounded for large batches
    return np.stack([np.abs(np.exp(1j * k * phi) @ beta) for k in n], axis=-1)


def _mode_amplitudes(mode_shape: ArrayLike, layout: Layout) -> np.ndarray:
    beta = np.asarray(mode_shape, dtype=float).ravel()
    if beta.size == layout.count:
        out = beta
    elif beta.size == layout.throw_count:
        out = beta[layout.throws - 1]
    else:
        raise InputError(
            f"expected {layout.count} amplitudes (one per cylinder) or {layout.throw_count} "
            f"(one per throw), got {beta.size}",
            key="mode_shape",
            value=[float(b) for b in beta],
        )
    if not np.all(np.isfinite(out)) or not np.any(out != 0.0):
        raise InputError(
            "the mode shape must hold finite amplitudes, not all zero",
            key="mode_shape",
            value=[float(b) for b in beta],
        )
    return out


def first_mode_shape(model: TorsionModel, count: int) -> NDArray[np.float64]:
    """Relative amplitudes of a torsional model's first elastic mode at the cylinders.

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        An engine's ``[torsion]`` model, whose masses name the cylinders acting on them.
    count : int
        Number of cylinders Z.

    Returns
    -------
    numpy.ndarray
        (Z,) the mode's amplitude at the mass carrying each cylinder (dimensionless, largest
        amplitude of the mode 1; 0 for a cylinder on no mass), from
        :func:`crankdyn.torsion.modal.natural_modes`.

    Raises
    ------
    InputError
        If the model has no elastic mode.
    """
    modes = natural_modes(model)
    first = 1 if modes.free else 0
    if first >= len(modes.mode):
        raise InputError(
            "the torsional model has no elastic mode (it needs two masses or a grounded shaft)",
            key="mode_shape",
        )
    shape = np.asarray(modes.mode_shapes[first], dtype=float)
    amplitudes = np.zeros(count)
    for i, mass in enumerate(model.masses):
        for c in mass.cylinders:
            if c <= count:
                amplitudes[c - 1] = shape[i]
    return amplitudes


def torsional_criterion(
    mode_shape: ArrayLike, layout: Layout, orders: ArrayLike | None = None
) -> Criterion:
    """The torsional-excitation criterion for a mode shape.

    Parameters
    ----------
    mode_shape : array_like
        Relative amplitudes of the mode (the first torsional mode, typically) at the cylinders'
        cranks: one per cylinder, or one per throw (V engines); dimensionless.
    layout : Layout
        The engine layout.
    orders : array_like or None
        Orders to judge by (dimensionless); default the minor orders of
        :func:`torsional_orders` (all of them if there are no minor orders).

    Returns
    -------
    Criterion
        ``torsional_vector_sum``: the largest vector sum over the orders (lower is better;
        Nestorides 1958, ch. 7).

    Raises
    ------
    InputError
        If the mode shape has the wrong length, is not finite or is all zero, or an order is
        not positive.
    """
    beta = _mode_amplitudes(mode_shape, layout)
    if orders is None:
        all_orders = torsional_orders(layout.count, layout.cycle)
        minor = all_orders[~major_orders(all_orders, layout.count, layout.cycle)]
        chosen = minor if minor.size else all_orders
    else:
        chosen = np.atleast_1d(np.asarray(orders, dtype=float))
        if chosen.size == 0 or np.any(~np.isfinite(chosen)) or np.any(chosen <= 0.0):
            raise InputError("orders must be positive numbers", key="orders", value=list(chosen))

    def evaluate(s: FiringSchemes, lay: Layout) -> np.ndarray:
        return vector_sums(s.firing, beta, chosen).max(axis=1)

    names = ", ".join(f"{o:g}" for o in chosen)
    return Criterion(
        "torsional_vector_sum",
        f"Largest vector sum, orders {names}",
        "lower",
        evaluate,
        decimals=9,
    )


# ---- exhaust grouping -------------------------------------------------------------------------


def _check_groups(groups: Sequence[Sequence[int]], count: int) -> list[list[int]]:
    try:
        out = [[int(c) for c in g] for g in groups]
    except (TypeError, ValueError):
        raise InputError(
            "expected groups of cylinder numbers", key="exhaust_groups", value=groups
        ) from None
    flat = [c for g in out for c in g]
    if any(len(g) < 2 for g in out) or not out:
        raise InputError(
            "every exhaust group needs at least two cylinders", key="exhaust_groups", value=out
        )
    if any(not 1 <= c <= count for c in flat) or len(flat) != len(set(flat)):
        raise InputError(
            f"exhaust groups must name cylinders 1..{count}, each at most once",
            key="exhaust_groups",
            value=out,
        )
    return out


def exhaust_criterion(groups: Sequence[Sequence[int]], layout: Layout) -> Criterion:
    """The pulse-turbocharging criterion: the shortest firing interval between two cylinders of
    one exhaust group (larger is better; the ideal is the cycle divided by the group size).

    Parameters
    ----------
    groups : sequence of sequences of int
        Lists of cylinder numbers sharing an exhaust branch, e.g. [[1, 2, 3], [4, 5, 6]].
    layout : Layout
        The engine layout.

    Returns
    -------
    Criterion
        ``exhaust_min_interval_deg`` (evaluated in rad, written in deg; higher is better).

    Raises
    ------
    InputError
        If a group has fewer than two cylinders or the groups name a cylinder twice or one that
        does not exist.
    """
    checked = _check_groups(groups, layout.count)
    pairs = np.array(
        [(a - 1, b - 1) for g in checked for i, a in enumerate(g) for b in g[i + 1 :]], dtype=int
    )

    def evaluate(s: FiringSchemes, lay: Layout) -> np.ndarray:
        gaps = _cyclic_gap(s.firing[:, pairs[:, 0]], s.firing[:, pairs[:, 1]], CYCLE_ANGLE[s.cycle])
        return gaps.min(axis=1)

    return Criterion(
        "exhaust_min_interval_deg",
        "Shortest firing interval within an exhaust group (deg)",
        "higher",
        evaluate,
        decimals=6,
        scale=DEG,
    )


# ---- results ------------------------------------------------------------------------------------


@dataclass(frozen=True)
class FiringCandidate(Result):
    """One firing order with its crankshaft and the values of the ranking criteria.

    Parameters
    ----------
    layout : Layout or None
        The engine layout the criteria were evaluated on (for the plot; not exported).
    """

    title = "Firing order"
    rank: int = scalar("rank", "Rank", "")
    firing_order: tuple[int, ...] = scalar("firing_order", "Firing order", "")
    firing_angles: NDArray[np.float64] = scalar(
        "firing_angles_deg", "Firing angles", "deg", DEG, ".6g"
    )
    firing_intervals: NDArray[np.float64] = scalar(
        "firing_intervals_deg", "Firing intervals", "deg", DEG, ".6g"
    )
    even_firing: bool = scalar("even_firing", "Even firing", "", headline=True)
    throw_angles: NDArray[np.float64] = scalar(
        "throw_angles_deg", "Throw angles", "deg", DEG, ".6g"
    )
    crank_end_view: NDArray[np.float64] = scalar(
        "crank_end_view_deg", "Crank end view (throw positions)", "deg", DEG, ".6g"
    )
    interval_deviation: float = scalar(
        "interval_deviation_deg", "Largest departure from the even interval", "deg", DEG
    )
    adjacent_consecutive: int = scalar(
        "adjacent_consecutive", "Adjacent cylinders firing in a row", "", headline=True
    )
    adjacent_pairs: tuple[str, ...] = scalar("adjacent_pairs", "Adjacent pairs", "")
    main_bearing_min_interval: float | None = scalar(
        "main_bearing_min_interval_deg",
        "Shortest firing interval next to a main bearing",
        "deg",
        DEG,
    )
    free_force_1: float = scalar("free_force_1", "Free force, 1st order (per m_j R ω²)", "")
    free_force_2: float = scalar("free_force_2", "Free force, 2nd order (per m_j R ω² A₂)", "")
    free_moment_1: float = scalar("free_moment_1", "Free moment, 1st order (per m_j R ω² a)", "")
    free_moment_2: float = scalar("free_moment_2", "Free moment, 2nd order (per m_j R ω² A₂ a)", "")
    v_scheme: str | None = scalar("v_scheme", "V firing scheme", "")
    torsional_vector_sum: float | None = scalar(
        "torsional_vector_sum", "Largest torsional vector sum", ""
    )
    torsional_vector_sums: dict[str, float] | None = scalar(
        "torsional_vector_sums", "Torsional vector sums by order", ""
    )
    exhaust_min_interval: float | None = scalar(
        "exhaust_min_interval_deg", "Shortest interval within an exhaust group", "deg", DEG
    )
    layout: Layout | None = field(default=None, repr=False, compare=False)

    @property
    def order_text(self) -> str:
        """The firing order as people write it, ``"1-5-3-6-2-4"``."""
        return "-".join(str(c) for c in self.firing_order)

    @property
    def intervals_text(self) -> str:
        """The firing intervals (deg) as people write them: ``120 × 6`` when all are equal."""
        rounded = [round(math.degrees(float(v)), 6) for v in self.firing_intervals]
        if len(set(rounded)) == 1:
            return f"{rounded[0]:g} × {len(rounded)}"
        return " ".join(f"{v:g}" for v in rounded)

    def plot(self, fig: Figure | None = None) -> Figure:
        """Crank end view and firing diagram.

        Parameters
        ----------
        fig : matplotlib.figure.Figure or None
            A figure to draw into; None makes a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.firing import plot_arrangement

        return plot_arrangement(self, fig=fig)


@dataclass(frozen=True)
class FiringOrderRanking(Result):
    """Firing orders a crankshaft (or a layout) allows, ranked by the seed's criteria
    (:func:`firing_order_search`)."""

    title = "Firing orders"
    engine: str = scalar("engine", "Engine", "")
    cycle: str = scalar("cycle", "Cycle", "")
    search: str = scalar("search", "Search", "")
    count: int = scalar("count", "Firing orders found", "")
    even_count: int = scalar("even_count", "Of which fire evenly", "")
    criteria: tuple[str, ...] = scalar("criteria", "Ranked by (in priority order)", "")
    engine_order: tuple[int, ...] = scalar("engine_firing_order", "Engine's firing order", "")
    engine_rank: int | None = scalar(
        "engine_rank", "Rank of the engine's firing order", "", headline=True
    )
    candidates: tuple[FiringCandidate, ...] = scalar("candidates", "Candidates", "")
    notes: tuple[str, ...] = scalar("notes", "Notes", "")

    def summary_tables(self) -> list[SummaryTable]:
        """The ranked firing orders: rank (``*`` the engine's own), firing order, intervals and
        every criterion, each column labelled as :class:`FiringCandidate` declares it."""
        fields = FiringCandidate.__dataclass_fields__
        by_key = {f.metadata.get("key"): f for f in fields.values()}
        crit = [c for c in self.criteria if c != "interval_deviation_deg" and c in by_key]
        columns = [
            SummaryColumn("rank", "Rank"),
            SummaryColumn("firing_order", "Firing order"),
            SummaryColumn("firing_intervals_deg", "Firing intervals (deg)"),
        ]
        for c in crit:
            meta = by_key[c].metadata
            columns.append(SummaryColumn(c, meta["label"], meta["unit"]))
        v_scheme = any(c.v_scheme for c in self.candidates)
        if v_scheme:
            columns.append(SummaryColumn("v_scheme", "V scheme"))
        rows = []
        for cand in self.candidates:
            mark = "*" if self.engine_rank == cand.rank else ""
            row: list[Any] = [f"{cand.rank}{mark}", cand.order_text, cand.intervals_text]
            for c in crit:
                name = by_key[c].name
                value = getattr(cand, name)
                row.append(value * by_key[c].metadata["scale"] if value is not None else None)
            if v_scheme:
                row.append(cand.v_scheme or "")
            rows.append(tuple(row))
        relative = [None, None, None, *(1.0 if by_key[c].metadata["unit"] == "" else None
                                        for c in crit)]  # fmt: skip
        if v_scheme:
            relative.append(None)
        return [
            SummaryTable(
                "firing_orders",
                f"{self.engine}: firing orders",
                tuple(columns),
                tuple(rows),
                caption=f"{self.count} firing order(s), {self.even_count} evenly firing, best "
                f"first; * the engine's own.",
                reference=tuple(relative),
            )
        ]

    def ranked_list(self) -> list[dict[str, Any]]:
        """The ranked candidates as JSON-ready dicts (what ``--format json`` writes).

        Returns
        -------
        list of dict
            :meth:`FiringCandidate.to_dict` of every candidate, best first.
        """
        return [c.to_dict() for c in self.candidates]

    def to_csv(self) -> str:
        """The ranking as CSV text.

        Returns
        -------
        str
            One row per candidate: rank, firing order, intervals (deg) and the criteria (in the
            units of their keys).
        """
        buffer = io.StringIO()
        writer = csv.writer(buffer, lineterminator="\n")
        header = ["rank", "firing_order", "firing_intervals_deg", *self.criteria]
        if any(c.v_scheme for c in self.candidates):
            header.append("v_scheme")
        writer.writerow(header)
        for c in self.candidates:
            d = c.to_dict()
            row = [
                c.rank,
                c.order_text,
                " ".join(f"{v:g}" for v in d["firing_intervals_deg"]),
            ]
            row += [_csv_value(d.get(name)) for name in self.criteria]
            if "v_scheme" in header:
                row.append(c.v_scheme or "")
            writer.writerow(row)
        return buffer.getvalue()

    def plot(self, fig: Figure | None = None, index: int = 0) -> Figure:
        """Crank end view and firing diagram of one candidate.

        Parameters
        ----------
        fig : matplotlib.figure.Figure or None
            A figure to draw into; None makes a new one.
        index : int
            The candidate ranked ``index + 1``; default 0 (the best).

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        return self.candidates[index].plot(fig=fig)


def _csv_value(value: object) -> str:
    if value is None:
        return ""
    if isinstance(value, float):
        return f"{value:.10g}"
    return str(value)


# ---- the search ------------------------------------------------------------------------------


SEARCHES = ("crankshaft", "any-crankshaft")
"""The searches of :func:`firing_order_search`."""


def _schemes(
    cylinders: Cylinders, search: str, include_uneven: bool | None
) -> tuple[FiringSchemes, str]:
    if search == "any-crankshaft":
        s = crankshaft_firing_schemes(cylinders.throws, cylinders.bank_axis_angles, cylinders.cycle)
        return s, "every even-firing crankshaft of the layout"
    psi = np.asarray(cylinders.throw_angles)
    if include_uneven:
        return all_firing_schemes(psi, cylinders.cycle), "every order the crankshaft allows"
    even = even_firing_schemes(psi, cylinders.cycle)
    if len(even) or include_uneven is False:
        return even, "the even-firing orders of the crankshaft"
    return (
        all_firing_schemes(psi, cylinders.cycle),
        "every order the crankshaft allows (it cannot fire evenly)",
    )


def firing_order_search(
    cylinders: Cylinders,
    *,
    search: str = "crankshaft",
    include_uneven: bool | None = None,
    mode_shape: ArrayLike | None = None,
    torsion_orders: ArrayLike | None = None,
    exhaust_groups: Sequence[Sequence[int]] | None = None,
    priority: Sequence[str] | None = None,
    top: int | None = None,
    name: str = "",
) -> FiringOrderRanking:
    """Enumerate and rank firing orders (module docstring).

    Parameters
    ----------
    cylinders : crankdyn.engine.Cylinders
        The engine's cylinders (layout, crankshaft, firing order).
    search : str
        ``"crankshaft"`` (default): the orders the engine's crankshaft allows;
        ``"any-crankshaft"``: every even-firing crankshaft of the layout with its orders.
    include_uneven : bool or None
        With ``search="crankshaft"``: True lists every order (even or not), False the even
        ones only, None (default) the even ones, or every order when there is no even one.
    mode_shape : array_like or None
        Relative amplitudes of the first torsional mode at the cylinders (or throws),
        dimensionless: adds the ``torsional_vector_sum`` criterion.
    torsion_orders : array_like or None
        Orders for the torsional criterion (dimensionless; default: the minor orders).
    exhaust_groups : sequence of sequences of int or None
        Cylinder groups sharing an exhaust branch: adds ``exhaust_min_interval_deg``.
    priority : sequence of str or None
        Criteria names in priority order (default :data:`DEFAULT_PRIORITY`, those that apply).
    top : int or None
        Keep only the best ``top`` candidates.
    name : str
        Engine name for the result.

    Returns
    -------
    FiringOrderRanking
        The candidates, best first, with the criteria values (angles in rad in memory, deg in
        the exports) and the rank of the engine's own order.

    Raises
    ------
    InputError
        If the search or a criterion is unknown, the torsional orders come without a mode
        shape, a mode shape or exhaust group is invalid, or there are too many schemes to
        enumerate.

    Examples
    --------
    Seed 000's inline-8 (section 2.3, exercise 1): eight even orders; four of them have no
    adjacent cylinders firing one after the other and rank first.

    >>> import math
    >>> from crankdyn.engine.model import Cylinders
    >>> psi = [math.radians(a) for a in (0, 180, 270, 90, 90, 270, 180, 0)]
    >>> ranking = firing_order_search(Cylinders(8, (1, 4, 2, 3, 8, 5, 7, 6), throw_angles=psi))
    >>> ranking.count, [c.adjacent_consecutive for c in ranking.candidates]
    (8, [0, 0, 0, 0, 2, 2, 2, 2])
    """
    if search not in SEARCHES:
        raise InputError(f"expected one of {', '.join(SEARCHES)}", key="search", value=search)
    layout = Layout.of(cylinders)
    schemes, what = _schemes(cylinders, search, include_uneven)
    available = dict(CRITERIA)
    if mode_shape is not None:
        available["torsional_vector_sum"] = torsional_criterion(mode_shape, layout, torsion_orders)
    elif torsion_orders is not None:
        raise InputError("orders for the torsional criterion need a mode shape", key="orders")
    if exhaust_groups is not None:
        available["exhaust_min_interval_deg"] = exhaust_criterion(exhaust_groups, layout)
    if priority is None:
        chosen = [c for c in DEFAULT_PRIORITY if c in available]
    else:
        chosen = list(priority)
        for c in chosen:
            if c not in available:
                hint = (
                    " (needs a mode shape)"
                    if c == "torsional_vector_sum"
                    else " (needs exhaust groups)"
                    if c == "exhaust_min_interval_deg"
                    else ""
                )
                raise InputError(
                    f"unknown or unavailable criterion{hint}; choose from {', '.join(available)}",
                    key="priority",
                    value=c,
                )
        chosen += [c for c in DEFAULT_PRIORITY if c in available and c not in chosen]
    values = {c: available[c].evaluate(schemes, layout) for c in available}
    notes = [f"searched {what}"]
    if len(schemes) == 0:
        notes.append("no firing order fits: the crankshaft cannot fire evenly")
        order_idx = np.zeros(0, dtype=int)
    else:
        keys = [available[c].key(values[c]) for c in chosen]
        # lexsort: the last key is the primary one; the order itself breaks ties
        tie = [schemes.orders[:, k] for k in range(schemes.count - 1, -1, -1)]
        order_idx = np.lexsort([*tie, *reversed(keys)])
    even_count = int(np.sum(values["interval_deviation_deg"] < 1e-6)) if len(schemes) else 0
    engine_order = tuple(cylinders.firing_order)
    engine_rank = _rank_of(schemes, order_idx, cylinders)
    shown = order_idx if top is None else order_idx[: max(int(top), 0)]
    torsion = available.get("torsional_vector_sum")
    per_order = None
    if torsion is not None and mode_shape is not None and len(shown):
        orders = torsional_orders(layout.count, layout.cycle)
        if torsion_orders is not None:
            orders = np.union1d(orders, np.asarray(torsion_orders, dtype=float))
        beta = _mode_amplitudes(mode_shape, layout)
        per_order = (orders, vector_sums(schemes.firing[shown], beta, orders))
    candidates = tuple(
        _candidate(schemes, layout, values, int(row), rank, per_order, k)
        for k, (rank, row) in enumerate(zip(range(1, len(shown) + 1), shown, strict=True))
    )
    if top is not None and len(order_idx) > len(shown):
        notes.append(f"showing the best {len(shown)} of {len(order_idx)}")
    return FiringOrderRanking(
        engine=name,
        cycle=cylinders.cycle,
        search=search,
        count=len(schemes),
        even_count=even_count,
        criteria=tuple(chosen),
        engine_order=engine_order,
        engine_rank=engine_rank,
        candidates=candidates,
        notes=tuple(notes),
    )


def _rank_of(schemes: FiringSchemes, order_idx: np.ndarray, cylinders: Cylinders) -> int | None:
    if len(schemes) == 0:
        return None
    target = np.asarray(cylinders.firing_order)
    psi = np.asarray(cylinders.throw_angles)
    same_order = np.all(schemes.orders == target[None, :], axis=1)
    diff = np.remainder(schemes.throw_angles - psi[None, :] + math.pi, TWO_PI) - math.pi
    same_crank = np.all(np.abs(diff) < 1e-6, axis=1)
    hits = np.flatnonzero(same_order & same_crank)
    if hits.size == 0:
        return None
    position = np.flatnonzero(np.isin(order_idx, hits))
    return int(position[0]) + 1


def _candidate(
    schemes: FiringSchemes,
    layout: Layout,
    values: dict[str, np.ndarray],
    row: int,
    rank: int,
    per_order: tuple[np.ndarray, np.ndarray] | None,
    k: int,
) -> FiringCandidate:
    order = tuple(int(c) for c in schemes.orders[row])
    firing = schemes.firing[row]
    psi = schemes.throw_angles[row]
    adj = layout.adjacent()
    pairs = tuple(
        f"{a}-{b}"
        for seq in _bank_sequences(schemes.orders[row : row + 1], layout)
        if seq.shape[1] > 1
        for a, b in zip(seq[0], np.roll(seq[0], -1), strict=True)
        if adj[a, b]
    )
    scheme = None
    if layout.layout == "V":
        scheme = v_scheme(order, layout.banks, layout.throws, firing, layout.cycle)
    bearing = values["main_bearing_min_interval_deg"][row]
    sums = None
    if per_order is not None:
        orders, table = per_order
        sums = {f"{o:g}": float(v) for o, v in zip(orders, table[k], strict=True)}
    return FiringCandidate(
        rank=rank,
        firing_order=order,
        firing_angles=freeze(firing),
        firing_intervals=freeze(schemes.intervals[row]),
        even_firing=bool(values["interval_deviation_deg"][row] < 1e-6),
        throw_angles=freeze(psi),
        crank_end_view=freeze(crank_end_view(psi, layout.throws, layout.axis_angles)),
        interval_deviation=float(values["interval_deviation_deg"][row]),
        adjacent_consecutive=int(values["adjacent_consecutive"][row]),
        adjacent_pairs=pairs,
        main_bearing_min_interval=None if math.isnan(bearing) else float(bearing),
        free_force_1=float(values["free_force_1"][row]),
        free_force_2=float(values["free_force_2"][row]),
        free_moment_1=float(values["free_moment_1"][row]),
        free_moment_2=float(values["free_moment_2"][row]),
        v_scheme=scheme,
        torsional_vector_sum=(
            float(values["torsional_vector_sum"][row]) if "torsional_vector_sum" in values else None
        ),
        torsional_vector_sums=sums,
        exhaust_min_interval=(
            float(values["exhaust_min_interval_deg"][row])
            if "exhaust_min_interval_deg" in values
            else None
        ),
        layout=layout,
    )


def arrangement(cylinders: Cylinders) -> FiringCandidate:
    """The engine's own crank arrangement and firing order, with the criteria values.

    For its crank end view and firing diagram: ``arrangement(engine.cylinders).plot()``.

    Parameters
    ----------
    cylinders : crankdyn.engine.Cylinders
        The engine's cylinders.

    Returns
    -------
    FiringCandidate
        Rank 1, the engine's firing order, angles (rad in memory) and criteria values.
    """
    layout = Layout.of(cylinders)
    psi = np.asarray(cylinders.throw_angles)
    s = FiringSchemes.from_firing(cylinders.firing_angles, psi, cylinders.cycle)
    values = {name: c.evaluate(s, layout) for name, c in CRITERIA.items()}
    return _candidate(s, layout, values, 0, 1, None, 0)
