"""Critical speeds and the Campbell diagram (analysis).

A critical speed is a crankshaft speed at which an order q of the excitation meets a natural
frequency f_r of the shaft line: q n_c / 60 = f_r, so n_c = 60 f_r / q (rpm) (seed 003, 第5章
"临界转速"; Ker Wilson vol. 2). The Campbell (interference) diagram plots the excitation
frequency q n / 60 of every order against the speed n with the natural frequencies as horizontal
lines; its crossings are the critical speeds. Each crossing is marked *major* when the order is
a major order of the engine (all cylinders' phase vectors of that order line up,
:func:`crankdyn.torsion.orders.major_orders`) and carries the relative amplitude sum of the
order over that mode's shape (how strongly the order excites the mode). Without firing angles
(a model with neither firing angles nor a firing order) both are undetermined (None, noted).
Orders that are not harmonics of the engine's cycle (a propeller's blade orders, an electric
machine's harmonics, :mod:`crankdyn.torsion.sources`) are never major and have no relative
amplitude sum, known firing angles or not; ``excited_by`` names what excites each order
(``"engine"`` and the sources acting at it).

Mode numbers as :func:`crankdyn.torsion.modal.natural_modes` gives them (elastic modes from 1;
docs/conventions.md). Attributes hold SI values: ``natural_frequency`` is the circular
frequency omega_r (rad/s), ``frequency_hz`` the same in Hz.

Natural frequencies are those of the undamped model (:func:`crankdyn.torsion.modal.natural_modes`);
tuned dampers of the model are included as a mass and a shaft, viscous dampers' rings are left
out (undamped, a viscous ring is decoupled).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.crank.geometry import check_positive
from crankdyn.errors import InputError
from crankdyn.results import Result, array, freeze, scalar
from crankdyn.summary import SummaryColumn, SummaryTable, derived
from crankdyn.torsion.elements import Mass, Shaft
from crankdyn.torsion.excitation import Excitation
from crankdyn.torsion.harmonics import cylinder_amplitudes
from crankdyn.torsion.model import TorsionModel
from crankdyn.torsion.orders import check_orders, relative_amplitude_sums
from crankdyn.torsion.sources import (
    check_model_orders,
    engine_orders_mask,
    line_major,
    order_sources,
)

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from crankdyn.plausibility import PlausibilityWarning

__all__ = [
    "CampbellResult",
    "CriticalSpeed",
    "OperatingRange",
    "campbell",
    "with_dampers",
]

from crankdyn.constants import RPM

HZ = 1.0 / (2.0 * math.pi)


@dataclass(frozen=True)
class OperatingRange:
    """The operating speed range and the rated speed.

    Parameters
    ----------
    low, high : float
        Lowest and highest operating speed (rad/s), 0 < low < high.
    rated : float or None
        The rated speed n_0 (rad/s), > 0, or None.

    Raises
    ------
    crankdyn.errors.InputError
        A speed not positive, or an empty range (key ``speed_range`` or ``rated_speed`` and
        the value).

    Examples
    --------
    >>> OperatingRange(50.0, 150.0, rated=140.0).high
    150.0
    """

    low: float
    high: float
    rated: float | None = None

    def __post_init__(self) -> None:
        low = check_positive("speed_range", self.low, "the lowest speed")
        high = check_positive("speed_range", self.high, "the highest speed")
        if high <= low:
            raise InputError(
                "the speed range is empty: its end is not above its start",
                key="speed_range",
                value=[low * RPM, high * RPM],
            )
        object.__setattr__(self, "low", low)
        object.__setattr__(self, "high", high)
        if self.rated is not None:
            object.__setattr__(
                self, "rated", check_positive("rated_speed", self.rated, "the rated speed")
            )


def with_dampers(model: TorsionModel) -> TorsionModel:
    """The model with its tuned dampers as masses and shafts (for natural frequencies); viscous
    dampers are left out (module docstring).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The model.

    Returns
    -------
    crankdyn.torsion.model.TorsionModel
        The model itself when it has no tuned damper; else a copy with every tuned damper's
        ring (kg m^2) as a mass, joined to its hub mass by a shaft of the damper's stiffness
        (N m/rad), damping (N m s/rad) and loss factor, and no dampers.
    """
    tuned = [d for d in model.dampers if d.kind == "tuned"]
    if not tuned:
        return model
    masses = list(model.masses)
    shafts = list(model.shafts)
    for d in tuned:
        masses.append(Mass(d.name, d.inertia))
        shafts.append(Shaft((d.at, d.name), d.stiffness, d.damping, d.loss_factor))
    return dataclasses.replace(model, masses=tuple(masses), shafts=tuple(shafts), dampers=())


@dataclass(frozen=True)
class CriticalSpeed(Result):
    """One resonance: a mode met by an order at a speed n_c = omega_r / q (rad/s; exported in
    rpm; seed 003 ch. 5)."""

    mode: int = scalar("mode", "Mode", "")
    nodes: int = scalar("nodes", "Nodes", "")
    order: float = scalar("order", "Order", "", fmt=".4g")
    speed: float = scalar("speed_rpm", "Critical speed", "rpm", RPM, fmt=".6g")
    natural_frequency: float = scalar("natural_frequency_hz", "Natural frequency", "Hz", HZ)
    """omega_r (rad/s; exported in Hz)."""
    major: bool | None = scalar("major", "Major order", "")
    relative_amplitude_sum: float | None = scalar(
        "relative_amplitude_sum", "Relative amplitude sum", "", fmt=".4g"
    )
    excited_by: str | None = scalar("excited_by", "Excited by", "", default=None)

    @property
    def frequency_hz(self) -> float:
        """The natural frequency (Hz)."""
        return self.natural_frequency * HZ


def _majors(result: CampbellResult) -> tuple[int | None, str]:
    """The number of major-order critical speeds in the range, and where they are (None:
    undetermined, the model gives no firing order)."""
    if result.major is None:
        return None, "undetermined: the model gives no firing order or firing angles"
    majors = [c for c in result.critical_speeds if c.major]
    where = ", ".join(f"order {c.order:g} at {c.speed * RPM:.5g} rpm" for c in majors)
    return len(majors), where


@dataclass(frozen=True)
class CampbellResult(Result):
    """Critical speeds in the operating range and the data of the Campbell diagram
    (:func:`campbell`).

    Parameters
    ----------
    warnings : tuple of crankdyn.plausibility.PlausibilityWarning
        The input warnings of the model's file(s) (:mod:`crankdyn.io.plausibility`), given by
        the analysis session (not exported as a field: ``to_dict`` lists them under
        ``input_warnings``).
    """

    title = "Critical speeds"
    critical_speeds: tuple[CriticalSpeed, ...] = scalar("critical_speeds", "Critical speeds", "")
    modes: np.ndarray = array("modes", "Elastic modes", "")
    natural_frequency: np.ndarray = array("natural_frequencies_hz", "Natural frequencies", "Hz", HZ)
    orders: np.ndarray = array("orders", "Orders", "")
    major: np.ndarray | None = array("major_orders", "Major order", "")
    low: float = scalar("speed_min_rpm", "Operating range from", "rpm", RPM)
    high: float = scalar("speed_max_rpm", "Operating range to", "rpm", RPM)
    model_name: str = scalar("model", "Model", "", summary=False)
    notes: tuple[str, ...] | None = scalar("notes", "Notes", "")
    order_sources: tuple[str, ...] | None = scalar(
        "order_sources", "What excites each order", "", default=None, summary=False
    )
    """Per order, ``"engine"`` and/or the sources acting at it (:func:`crankdyn.torsion.
    sources.order_sources`); None without excitation points."""
    warnings: tuple[PlausibilityWarning, ...] = field(default=(), repr=False, compare=False)

    FIGURES = (
        derived(
            "major_critical_speeds", "major_critical_speeds",
            "Major-order critical speeds in the range", "",
            _majors, headline=True, better="min",
            status=lambda count: "warn" if count is None or count > 0 else "pass",
            description="Resonances of major orders inside the operating range (undetermined "
            "without a firing order)",
        ),
    )  # fmt: skip

    @property
    def frequencies_hz(self) -> NDArray[np.float64]:
        """The natural frequencies (Hz)."""
        return np.asarray(self.natural_frequency) * HZ

    def summary_tables(self) -> list[SummaryTable]:
        """Every mode x order crossing in the range: the critical speeds, major or minor
        (undetermined without a firing order), and what excites the order where sources act
        besides the engine.

        Returns
        -------
        list of crankdyn.summary.SummaryTable
            The tables.
        """
        sources = any(c.excited_by not in (None, "engine") for c in self.critical_speeds)
        columns = [
            SummaryColumn("speed_rpm", "Critical speed", "rpm"),
            SummaryColumn("mode", "Mode"),
            SummaryColumn("nodes", "Nodes"),
            SummaryColumn("order", "Order"),
            SummaryColumn("natural_frequency_hz", "Natural frequency", "Hz"),
            SummaryColumn("major", "Major order"),
            SummaryColumn("relative_amplitude_sum", "Relative amplitude sum"),
        ]
        if sources:
            columns.append(SummaryColumn("excited_by", "Excited by"))
        rows = []
        for c in self.critical_speeds:
            row: list[Any] = [
                round(c.speed * RPM, 1),
                c.mode,
                c.nodes,
                f"{c.order:g}",
                c.natural_frequency * HZ,
                "undetermined" if c.major is None else ("yes" if c.major else "no"),
                c.relative_amplitude_sum,
            ]
            if sources:
                row.append(c.excited_by or "-")
            rows.append(tuple(row))
        majors = sum(1 for c in self.critical_speeds if c.major)
        span = f"{self.low * RPM:.0f}-{self.high * RPM:.0f} rpm"
        return [
            SummaryTable(
                "critical_speeds",
                f"{self.model_name}: critical speeds {span}",
                tuple(columns),
                tuple(rows),
                caption=f"Every mode × order crossing in the range: {len(rows)} critical "
                f"speed(s), {majors} of major orders.",
            )
        ]

    def plot(self, fig: Figure | None = None, max_speed: float | None = None) -> Figure:
        """The Campbell diagram: the order lines q n against the speed, the natural frequencies
        and their crossings.

        Parameters
        ----------
        fig : matplotlib.figure.Figure or None
            A figure to draw into; None makes a new one.
        max_speed : float or None
            Highest speed of the diagram (rad/s); None for the plot's default beyond the
            operating range.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.torsion_response import plot_campbell

        return plot_campbell(self, fig=fig, max_speed=max_speed)


def campbell(
    model: TorsionModel,
    orders: ArrayLike,
    speed_range: tuple[float, float] | None = None,
    *,
    excitation: Excitation | None = None,
    cycle: str | None = None,
) -> CampbellResult:
    """Critical speeds of ``model`` for ``orders`` inside a speed range: n_c = omega_r / q for
    every elastic mode r and order q (seed 003 ch. 5; Ker Wilson vol. 2; module docstring).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The torsional model (its tuned dampers are included).
    orders : array_like
        The orders to consider (dimensionless), shape (Q,).
    speed_range : tuple of (float, float) or None
        (low, high) in rad/s; default the model's operating range.
    excitation : crankdyn.torsion.excitation.Excitation or None
        An excitation (for the firing angles: major orders and relative amplitude sums); default
        :func:`~crankdyn.torsion.excitation.excitation_for` of the model when it has excitation
        points.
    cycle : str or None
        The working cycle when there is no excitation (default four-stroke).

    Returns
    -------
    CampbellResult
        The critical speeds inside the range (rad/s, ascending), each with its mode, order,
        natural frequency (rad/s), major flag and relative amplitude sum, and the diagram's data.

    Raises
    ------
    crankdyn.errors.InputError
        No speed range (names the model file, key ``speed_range``), an empty range, or orders
        that no excitation of the model has (key ``orders``).

    Examples
    --------
    Two masses (20 rad/s, :func:`crankdyn.torsion.closed_form.two_mass`) and orders 1 and 2:

    >>> from crankdyn.torsion.elements import Mass, Shaft
    >>> from crankdyn.torsion.model import TorsionModel
    >>> shaft = Shaft(("a", "b"), stiffness=300.0)
    >>> model = TorsionModel((Mass("a", 1.0), Mass("b", 3.0)), (shaft,))
    >>> result = campbell(model, [1.0, 2.0], (5.0, 30.0))
    >>> [(c.order, c.speed) for c in result.critical_speeds]
    [(2.0, 10.0), (1.0, 20.0)]
    """
    from crankdyn.torsion.excitation import excitation_for
    from crankdyn.torsion.modal import natural_modes

    notes: list[str] = []
    if speed_range is None:
        if model.operating is None:
            raise InputError(
                "no speed range: give the operating range ([operating] speed_range in the "
                "model) or the range option",
                file=model.source,
                key="speed_range",
            )
        speed_range = _range_of(model.operating)
    rng = OperatingRange(*speed_range)
    if excitation is None and (model.cylinder_dofs or model.sources):
        excitation = excitation_for(model, None)
    if excitation is not None:
        cycle = excitation.cycle
    cycle = cycle or "four-stroke"
    if excitation is not None:  # engine harmonics and the orders of the model's sources
        orders = np.sort(check_model_orders(model, excitation, orders))
    else:
        orders = np.sort(check_orders(orders, cycle))
    full = with_dampers(model)
    modes = natural_modes(full)
    elastic = np.flatnonzero(modes.natural_frequency > 0.0)
    omega = modes.natural_frequency[elastic]
    major: NDArray[np.bool_] | None = None
    rel: NDArray[np.float64] | None = None
    sources: list[str] | None = None
    order_major: list[bool | None] | None = None
    if excitation is not None:
        angles = excitation.firing_angles
        major = line_major(excitation, orders)
        engine = engine_orders_mask(orders, excitation.cycle)
        if excitation.cylinder_count == 0 or major is None:
            # no engine, or its firing angles unknown: no relative amplitude sums
            rel = np.full((elastic.size, orders.size), np.nan)
        else:  # relative amplitude sums belong to the engine's own orders only
            beta = cylinder_amplitudes(modes, full, excitation.cylinder_count)[elastic]
            rel = relative_amplitude_sums(beta, angles, orders)  # (modes, orders)
            rel[:, ~engine] = np.nan
        if major is None:  # undetermined for the engine's orders; other orders are not major
            order_major = [None if engine[q] else False for q in range(orders.size)]
        else:
            order_major = [bool(v) for v in major]
        sources = order_sources(model, excitation, orders)
        note = getattr(excitation, "note", "")
        if note:
            notes.append(note)
    else:
        notes.append("no excitation points: major orders not marked")
    # every (mode, order) pair at once
    speed = omega[:, None] / orders[None, :]
    inside = (speed >= rng.low * (1 - 1e-12)) & (speed <= rng.high * (1 + 1e-12))
    rows = []
    for r, q in zip(*np.nonzero(inside), strict=True):  # only the crossings found
        rows.append(
            CriticalSpeed(
                mode=int(modes.mode[elastic[r]]),
                nodes=int(modes.node_count[elastic[r]]),
                order=float(orders[q]),
                speed=float(speed[r, q]),
                natural_frequency=float(omega[r]),
                major=None if order_major is None else order_major[q],
                relative_amplitude_sum=(
                    None if rel is None or not np.isfinite(rel[r, q]) else float(rel[r, q])
                ),
                excited_by=None if sources is None else sources[q] or None,
            )
        )
    rows.sort(key=lambda c: (c.speed, c.mode))
    return CampbellResult(
        critical_speeds=tuple(rows),
        modes=freeze(modes.mode[elastic], dtype=int),
        natural_frequency=freeze(omega),
        orders=freeze(orders),
        major=None if major is None else freeze(major, dtype=bool),
        low=rng.low,
        high=rng.high,
        model_name=model.name,
        notes=tuple(notes) or None,
        order_sources=None if sources is None else tuple(sources),
    )


def _range_of(operating: Any) -> tuple[float, float]:
    """(low, high) of the model's operating range (an :class:`OperatingRange`; rad/s)."""
    return operating.low, operating.high
