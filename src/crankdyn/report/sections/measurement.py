"""Report section: measured torsional vibration held against the engine's torsional model
(``crankdyn analyze ENGINE --measurement SIGNAL --teeth N --at MASS``; docs/measurement.md)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from crankdyn.report.model import Plot, Section, Table
from crankdyn.report.sections import Context, NotRequested

__all__ = ["MeasurementInput", "build"]


@dataclass(frozen=True)
class MeasurementInput:
    """An analysed measurement (:func:`crankdyn.measure.orders.order_analysis`) and the mass of
    the engine's torsional model that carries the wheel.

    Parameters
    ----------
    result : crankdyn.measure.orders.OrderSpectrum or crankdyn.measure.orders.OrderTracking
        The order analysis of the torsiograph signal (angles in rad, speeds in rad/s).
    at : str
        Name of the mass of the torsional model where the signal was measured.
    """

    result: Any
    at: str


def _plots(measured: Any, compared: bool) -> list[Plot]:
    """The section's figures: the orders (and the model's), a run's map and fits, the trace."""
    steady = measured.kind == "steady"
    plots = [
        Plot(
            "measurement_orders",
            "Measured orders" + (" and the model's" if compared else ""),
            measured.plot("orders"),
            "Order amplitudes of the angular vibration at the measured mass"
            + (" against speed" if not steady else "")
            + ("; dashed: the model's forced response" if compared else "")
            + ".",
        )
    ]
    if not steady:
        plots.append(
            Plot(
                "measurement_map",
                "Order map of the run",
                measured.plot("map"),
                "Amplitude of every order in every window (+: resonance peaks).",
            )
        )
        if measured.resonances:
            plots.append(
                Plot(
                    "measurement_fits",
                    "Resonance fits",
                    measured.plot("fit"),
                    "Measured windows, single-mode fits and half-power bandwidths.",
                )
            )
    plots.append(
        Plot(
            "measurement_trace",
            "Instantaneous speed and angular vibration",
            measured.plot("trace"),
            "At the measured mass.",
        )
    )
    return plots


def build(ctx: Context) -> Section:
    """The measurement section: the measured torsional vibration (orders at the measured mass)
    held against the engine's torsional model; its key figures and tables are those the order
    analysis declares (:mod:`crankdyn.measure.figures`).

    Parameters
    ----------
    ctx : crankdyn.report.sections.Context
        The analysis session (SI units) and the optional inputs of the report.

    Returns
    -------
    crankdyn.report.model.Section
        The section: key figures, tables and plots.

    Raises
    ------
    NotRequested
        No measurement was given (``ctx.measurement`` is None).
    """
    spec = getattr(ctx, "measurement", None)
    if spec is None:
        raise NotRequested(
            "no measurement given (crankdyn analyze ENGINE --measurement SIGNAL --teeth N --at "
            "MASS)"
        )
    a, measured = ctx.analysis, spec.result
    model = a.model
    notes = []
    if model is not None and model.cylinder_dofs:
        measured = a.measurement(measured, spec.at)
    else:
        notes.append("the engine has no torsional model with cylinders: measurement only")
    cmp = measured.comparison
    intro = (
        f"Torsiograph signal {measured.source}: {measured.teeth} pulses per revolution at "
        f"{spec.at}" + (", held against the torsional model." if cmp is not None else ".")
    )
    extra = list((cmp.notes if cmp is not None else None) or ())
    if extra or notes:
        intro += " Notes: " + "; ".join(notes + extra) + "."
    data: dict[str, Any] = {
        "resonances": [f.to_dict() for f in (getattr(measured, "resonances", None) or ())],
    }
    if cmp is not None and cmp.damping is not None:
        data["damping"] = cmp.damping.to_dict()
    return Section.of(
        "measurement",
        "Measured torsional vibration",
        [measured],
        intro=intro,
        plots=_plots(measured, cmp is not None),
        tables=[Table("measurement_orders", "Measured orders", result=measured, show=False)],
        json=data,
    )
