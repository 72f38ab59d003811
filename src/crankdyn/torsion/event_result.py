"""The result of a transient event: speeds and element torques against time, and every
element's extremes (result object of :func:`crankdyn.torsion.event_run.event_response`)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from crankdyn.constants import RPM
from crankdyn.errors import InputError, did_you_mean
from crankdyn.results import Result, array, column, scalar

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["EventResult", "time_above"]

HZ = 1.0 / (2.0 * math.pi)


def time_above(
    time: NDArray[np.float64], values: NDArray[np.float64], level: float
) -> float:
    """The time (s) a sampled quantity spends above a level, its crossings interpolated
    linearly between the samples.

    Parameters
    ----------
    time : numpy.ndarray
        (T,) increasing times (s).
    values : numpy.ndarray
        (T,) the quantity (any unit).
    level : float
        The level (the quantity's unit).

    Returns
    -------
    float
        Seconds above the level (s).

    Examples
    --------
    >>> time_above(np.array([0.0, 1.0, 2.0]), np.array([0.0, 2.0, 0.0]), 1.0)
    1.0
    """
    t = np.asarray(time, dtype=float)
    y = np.asarray(values, dtype=float) - level
    if t.size < 2:
        return 0.0
    y0, y1 = y[:-1], y[1:]
    dt = np.diff(t)
    both = (y0 > 0.0) & (y1 > 0.0)
    total = float(np.sum(dt[both]))
    up = (y0 <= 0.0) & (y1 > 0.0)
    down = (y0 > 0.0) & (y1 <= 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        total += float(np.sum(dt[up] * y1[up] / (y1[up] - y0[up])))
        total += float(np.sum(dt[down] * y0[down] / (y0[down] - y1[down])))
    return total


@dataclass(frozen=True)
class EventResult(Result):
    """Speeds and element torques of a shaft line through a transient event.

    ``torque`` holds the torque every element transmits (own sense: positive when its first
    mass drives its second, k x twist / |r|; a slipping clutch carries its friction torque),
    ``mass_speed`` every listed mass's speed (own sense), both at the kept samples; the
    extremes (``max_torque``, ``min_torque``) come from every step of the integration, refined
    on the exact solution between the steps (:mod:`crankdyn.torsion.event_run`), whatever was
    kept. ``element_kinds`` says what every element is (``"shaft"``, ``"coupling"``,
    ``"mesh"``, ``"damper"``), ``section_modulus`` its W_p where it has a diameter (NaN
    otherwise), ``limit_torque`` a coupling's T_Kmax from the model (NaN otherwise).
    """

    title = "Transient event"
    time: np.ndarray = column("time_s", "Time", "s")
    speed: np.ndarray = column("speed_rpm", "Mean speed (reference)", "rpm", RPM)
    mass_speed: np.ndarray = array("mass_speed_rpm", "Speed (time x mass)", "rpm", RPM)
    torque: np.ndarray = array("torque_Nm", "Torque (time x element)", "N·m")
    max_torque: np.ndarray = array("max_torque_Nm", "Largest torque per element", "N·m")
    min_torque: np.ndarray = array("min_torque_Nm", "Smallest torque per element", "N·m")
    max_time: np.ndarray = array("max_torque_time_s", "Time of the largest torque", "s")
    min_time: np.ndarray = array("min_torque_time_s", "Time of the smallest torque", "s")
    initial_torque: np.ndarray = array("initial_torque_Nm", "Torque before the event", "N·m")
    event: str = scalar("event", "Event", "")
    kind: str = scalar("event_kind", "Kind of event", "")
    severity: str = scalar("severity", "Severity", "")
    source: str = scalar("source", "Source of the event", "")
    masses: tuple[str, ...] = scalar("masses", "Masses", "")
    elements: tuple[tuple[str, str], ...] = scalar("elements", "Elements", "")
    element_names: tuple[str, ...] = scalar("element_names", "Element names", "")
    duration: float = scalar("duration_s", "Duration", "s")
    step: float = scalar("step_s", "Time step", "s")
    step_rule: str = scalar("step_rule", "Step rule", "")
    highest_frequency: float = scalar(
        "highest_frequency_hz", "Highest frequency resolved", "Hz", HZ
    )
    stride: int = scalar("stride", "Steps per kept sample", "")
    memory_bound: float = scalar("memory_bound_bytes", "Memory bound of the run", "B")
    switches: tuple[str, ...] = scalar("switches", "Clutch switches", "")
    notes: tuple[str, ...] = scalar("notes", "Notes", "")
    model_name: str = scalar("model", "Model", "")
    element_kinds: tuple[str, ...] = scalar("element_kinds", "Element kinds", "")
    section_modulus: np.ndarray = array("section_modulus_m3", "Section modulus W_p", "m³")
    limit_torque: np.ndarray = array("limit_torque_Nm", "T_Kmax of the couplings", "N·m")

    # ---- reading ------------------------------------------------------------------------------
    def element_index(self, spec: str | Sequence[str]) -> int:
        """An element by its name (``"intermediate shaft (a - b)"``), its label ``"a - b"`` or
        its two masses.

        Parameters
        ----------
        spec : str or (str, str)
            The element.

        Returns
        -------
        int
            Its index.

        Raises
        ------
        InputError
            For an element the result does not hold (key ``element``, with the nearest).
        """
        if not isinstance(spec, str):
            a, b = spec
            for e, (p, q) in enumerate(self.elements):
                if {p, q} == {a, b}:
                    return e
            spec = f"{a} - {b}"
        labels = [f"{a} - {b}" for a, b in self.elements]
        for names in (self.element_names, labels):
            if spec in names:
                return names.index(spec)
        raise InputError(
            f"no such element{did_you_mean(spec, labels + list(self.element_names))}",
            key="element",
            value=spec,
        )

    def peak(self, e: int) -> float:
        """The largest |torque| of element e over the run (N m).

        Parameters
        ----------
        e : int
            The element.

        Returns
        -------
        float
            (N m).
        """
        return float(max(abs(self.max_torque[e]), abs(self.min_torque[e])))

    def peak_time(self, e: int) -> float:
        """When element e's largest |torque| occurs (s).

        Parameters
        ----------
        e : int
            The element.

        Returns
        -------
        float
            (s).
        """
        high = abs(self.max_torque[e]) >= abs(self.min_torque[e])
        return float(self.max_time[e] if high else self.min_time[e])

    def time_above(self, e: int, level: float) -> float:
        """The time element e's |torque| spends above ``level`` (s), from the kept samples
        (:func:`time_above`; resolution: the kept interval, ``stride`` x ``step``).

        Parameters
        ----------
        e : int
            The element.
        level : float
            The level (N m), > 0.

        Returns
        -------
        float
            (s).
        """
        return time_above(self.time, np.abs(self.torque[:, e]), level)

    # ---- export -------------------------------------------------------------------------------
    def columns(self) -> dict[str, np.ndarray]:
        """The time columns, then one speed column per mass (``speed_rpm.<mass>``) and one
        torque column per element (``torque_Nm.<a> - <b>``) for the CSV.

        Returns
        -------
        dict of str to numpy.ndarray
            {key: values} in the unit of the key.
        """
        out = super().columns()
        for i, name in enumerate(self.masses):
            out[f"speed_rpm.{name}"] = np.round(self.mass_speed[:, i] * RPM, 9)
        for e, (a, b) in enumerate(self.elements):
            out[f"torque_Nm.{a} - {b}"] = self.torque[:, e]
        return out

    def column_labels(self) -> dict[str, tuple[str, str]]:
        """Label and unit of every column of :meth:`columns`.

        Returns
        -------
        dict of str to (str, str)
            {column key: (label, unit)}.
        """
        out = super().column_labels()
        for name in self.masses:
            out[f"speed_rpm.{name}"] = (f"Speed {name}", "rpm")
        for a, b in self.elements:
            out[f"torque_Nm.{a} - {b}"] = (f"Torque {a} - {b}", "N·m")
        return out

    def plot(self, *, limits: bool = True, fig: Figure | None = None) -> Figure:
        """Shaft torques, coupling torques and speeds against time, with the couplings' T_Kmax
        drawn (:func:`crankdyn.plots.events.plot_event`).

        Parameters
        ----------
        limits : bool
            Whether to draw the limits the result holds.
        fig : matplotlib.figure.Figure or None
            A figure to draw into; default a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.events import plot_event

        return plot_event(self, limits=limits, fig=fig)
