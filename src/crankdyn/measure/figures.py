"""The key figures and tables a measured order analysis declares (:mod:`crankdyn.summary`),
shared by the steady spectrum and the order tracking (:mod:`crankdyn.measure.orders`): the
largest measured synthesised vibration (every window of a run, not the speed bins), the largest
measured resonance and its damping ratio, each with the model's value beside it where the
analysis was held against a torsional model (:mod:`crankdyn.measure.compare`)."""

from __future__ import annotations

from typing import Any

import numpy as np

from crankdyn.constants import RPM
from crankdyn.display import quantity
from crankdyn.summary import FigureSpec, SummaryColumn, SummaryTable, derived

__all__ = ["MEASURED_FIGURES", "largest_per_order_table", "resonance_table"]


def _mrad(value: float) -> str:
    return quantity(value, "rad", to="mrad")


def _largest(r: Any) -> tuple[float, str]:
    """The largest synthesised amplitude: the steady one, or the largest window's of a run."""
    if r.kind == "steady":
        value, speed = float(r.synthesized), float(r.speed)
    else:  # every window, not the bins (a verdict must not depend on the bin width)
        j = int(np.argmax(r.window_synthesized))
        value, speed = float(r.window_synthesized[j]), float(r.window_speed[j])
    where = f"at {speed * RPM:.0f} rpm"
    model = getattr(r.comparison, "model_at_peak", None)
    if model is not None:
        where += f", model there {_mrad(model)}"
    return value, where


def _top(r: Any) -> Any:
    fits = () if r.kind == "steady" else (r.resonances or ())
    return max(fits, key=lambda f: f.peak_amplitude) if fits else None


def _resonance(r: Any) -> tuple[float, str] | None:
    top = _top(r)
    if top is None:
        return None
    where = f"order {top.order:g} at {top.peak_speed * RPM:.0f} rpm"
    peaks = r.comparison.peaks if r.comparison is not None else ()
    peak = next((p for p in peaks if p.order == top.order), None)
    if peak is not None:
        where += f", model {_mrad(peak.model_amplitude)} at {peak.model_speed * RPM:.0f} rpm"
    return float(top.peak_amplitude), where


def _damping(r: Any) -> tuple[float, str] | None:
    top = _top(r)
    if top is None:
        return None
    half = (
        f"half-power {top.half_power_damping:.4g}"
        if top.half_power_damping is not None
        else "half-power not available"
    )
    return float(top.damping), f"order {top.order:g}, single-mode fit; {half}"


MEASURED_FIGURES: tuple[FigureSpec, ...] = (
    derived(
        "measured_synthesized_amplitude", "measured_synthesized_amplitude_rad",
        "Largest measured vibration (synthesised)", "rad", _largest,
        reduction="max over every analysed window", headline=True,
        description="Half the peak-to-peak of the measured angular vibration over the "
        "analysed orders, at the measured mass",
    ),
    derived(
        "measured_resonance_peak", "measured_resonance_peak_rad",
        "Largest measured resonance", "rad", _resonance,
        reduction="max over the fitted resonances",
        unavailable="a steady-speed record has no resonance to fit",
    ),
    derived(
        "measured_damping_ratio", "measured_damping_ratio",
        "Damping ratio of the largest measured resonance", "", _damping,
        reduction="of the largest fitted resonance",
        unavailable="a steady-speed record has no resonance to fit",
    ),
)  # fmt: skip
"""The key figures of a measured order analysis (module docstring)."""


def resonance_table(r: Any) -> list[SummaryTable]:
    """The fitted resonances of a run, measured beside the model's peaks where there are
    (:class:`crankdyn.measure.compare.ResonancePeak`), else as fitted
    (:class:`crankdyn.measure.resonance.ResonanceFit`).

    Parameters
    ----------
    r : crankdyn.measure.orders.OrderTracking
        The run.

    Returns
    -------
    list of crankdyn.summary.SummaryTable
        One table, or none without fitted resonances.
    """
    compared = r.comparison is not None and r.comparison.peaks
    items = r.comparison.peaks if compared else (r.resonances or ())
    if not items:
        return []
    title = "Resonances: measured and model" if compared else "Resonances"
    return [type(items[0]).table_of(items, "measurement_resonances", title)]


def largest_per_order_table(r: Any) -> list[SummaryTable]:
    """The largest speed bin of every analysed order of a run, at its bin's speed, with the
    model's amplitude at that speed where the run was held against a model.

    Parameters
    ----------
    r : crankdyn.measure.orders.OrderTracking
        The run.

    Returns
    -------
    list of crankdyn.summary.SummaryTable
        One table, a row per order (amplitudes in rad, speeds in rpm); none without bins.
    """
    amplitude = np.asarray(r.amplitude)
    if amplitude.size == 0:
        return []
    at = np.argmax(amplitude, axis=0)
    orders = np.arange(amplitude.shape[1])
    columns = [
        SummaryColumn("order", "Order"),
        SummaryColumn("largest_bin_rad", "Largest bin", "rad"),
        SummaryColumn("at_rpm", "at", "rpm"),
    ]
    cells = [list(r.orders), list(amplitude[at, orders]), list(np.asarray(r.speed)[at] * RPM)]
    if r.comparison is not None:
        columns.append(SummaryColumn("model_rad", "Model at that speed", "rad"))
        cells.append(list(np.asarray(r.comparison.amplitude)[at, orders]))
    rows = tuple(tuple(float(v) for v in row) for row in zip(*cells, strict=True))
    caption = "speed bins; resolved resonance peaks below" if r.resonances else "speed bins"
    return [SummaryTable("largest_per_order", "Largest per order", tuple(columns), rows, caption)]
