"""``crankdyn measure SIGNAL --teeth N``: measured torsional vibration (torsiograph signals, order
analysis, the model held against the measurement). docs/measurement.md."""

from __future__ import annotations

import math

import click
import numpy as np
from rich.markup import escape
from rich.table import Table as RichTable

from crankdyn.cli.common import (
    check_plot_path,
    emit,
    format_option,
    option_quantity,
    output_options,
    plot_option,
    save_figure,
)
from crankdyn.cli.torsion import _print_tables
from crankdyn.cli.torsion_response import parse_orders
from crankdyn.constants import RPM
from crankdyn.errors import InputError
from crankdyn.io.output import check_writable
from crankdyn.measure.orders import ANALYSES, WINDOWS
from crankdyn.measure.signals import MIN_TEETH, PulseTrain

_CYCLES = ("four-stroke", "two-stroke")
_SHOWN = 6


def _mrad(value: float) -> str:
    return f"{value * 1e3:.4g}" if math.isfinite(value) else "-"


def _zeta(value) -> str:
    return "-" if value is None else f"{value:.4g}"


def load_measurement(
    signal: str,
    teeth: int | None,
    *,
    cycle: str,
    orders=None,
    analysis: str = "auto",
    window: str = "hann",
    window_cycles: int = 4,
    bin_width=None,
    reference_angle: float = 0.0,
    tooth_correction: str | None = None,
):
    """Read SIGNAL (a file or a built-in name) and analyse its orders; the options as the
    command's (also used by ``crankdyn analyze --measurement``)."""
    from crankdyn.io.signals import resolve_signal
    from crankdyn.measure.orders import order_analysis

    if teeth is not None and teeth < MIN_TEETH:
        raise InputError(
            f"at least {MIN_TEETH} pulses per revolution are needed", key="--teeth", value=teeth
        )
    data = resolve_signal(signal, teeth)
    correction = None
    if tooth_correction not in (None, "none"):
        if tooth_correction == "self":
            correction = "self"
        else:
            calibration = resolve_signal(tooth_correction, teeth or getattr(data, "teeth", None))
            if not isinstance(calibration, PulseTrain):
                raise InputError(
                    "the calibration record must hold pulse times of the same wheel",
                    key="--tooth-correction",
                    value=tooth_correction,
                )
            correction = calibration
    try:
        return order_analysis(
            data,
            cycle=cycle,
            orders=orders,
            analysis=analysis,
            window_cycles=window_cycles,
            window=window,
            bin_width=bin_width,
            reference_angle=reference_angle,
            tooth_correction=correction,
            resolution=teeth if not isinstance(data, PulseTrain) else None,
        )
    except InputError as exc:
        option = {
            "orders": "--orders",
            "window-cycles": "--window-cycles",
            "window": "--window-cycles",
            "tooth_correction": "--tooth-correction",
        }.get(exc.key or "")
        if option is None:
            raise
        raise InputError(
            exc.message, file=exc.file, key=option, value=exc.value if exc.has_value else None
        ) from None


def _steady_tables(result) -> list[RichTable]:
    cmp = result.comparison
    table = RichTable(
        title=escape(f"{result.source}: orders at {result.speed * RPM:.1f} rpm"),
        header_style="bold",
    )
    cols = ["Order", "Amplitude\n(mrad)", "Phase\n(deg)", "Cycle scatter\n(mrad)"]
    if cmp is not None:
        cols += ["Model\n(mrad)", "Model phase\n(deg)", "Measured /\nmodel"]
    for col in cols:
        table.add_column(col, justify="right")
    for j, q in enumerate(result.orders):
        row = [
            f"{q:g}",
            _mrad(result.amplitude[j]),
            f"{math.degrees(result.phase[j]):.1f}",
            _mrad(result.scatter[j]),
        ]
        if cmp is not None:
            model = float(cmp.amplitude[0, j])
            row += [
                _mrad(model),
                f"{math.degrees(cmp.phase[0, j]):.1f}",
                f"{result.amplitude[j] / model:.3g}" if model > 0 else "-",
            ]
        table.add_row(*row)
    summary = _summary(result)
    summary.add_row("Synthesised half-range amplitude", _mrad(result.synthesized), "mrad")
    if cmp is not None:
        summary.add_row(
            escape(f"Model at {cmp.mass}, synthesised"), _mrad(float(cmp.synthesized[0])), "mrad"
        )
    summary.add_row("Cycles averaged", str(result.cycles), "")
    summary.add_row(
        "Cycle speeds", f"{result.speed_min * RPM:.1f} - {result.speed_max * RPM:.1f}", "rpm"
    )
    return [table, summary, *_notes(result)]


def _summary(result) -> RichTable:
    summary = RichTable(title="Analysis", header_style="bold")
    summary.add_column("Quantity")
    summary.add_column("Value", justify="right")
    summary.add_column("Unit")
    for label, value in (
        ("Signal", result.source),
        ("Pulses per revolution", str(result.teeth)),
        ("Cycle", result.cycle),
        ("Phase reference", result.reference),
        ("Window", result.window),
        ("Averaging", result.averaging),
        ("Tooth-spacing correction", result.tooth_correction),
    ):
        summary.add_row(label, escape(value), "")
    return summary


def _notes(result) -> list[RichTable]:
    notes = list(result.notes or ())
    cmp = result.comparison
    if cmp is not None:
        notes += list(cmp.notes or ())
    if not notes:
        return []
    table = RichTable(title="Notes", show_header=False)
    table.add_column("")
    for text in notes:
        table.add_row(escape(text))
    return [table]


def _tracking_tables(result) -> list[RichTable]:
    cmp = result.comparison
    n = result.speed * RPM
    orders = RichTable(title="Largest per order", header_style="bold")
    cols = ["Order", "Largest bin\n(mrad)", "at\n(rpm)"]
    if cmp is not None:
        cols += ["Model at that\nspeed (mrad)"]
    for col in cols:
        orders.add_column(col, justify="right")
    for j, q in enumerate(result.orders):
        k = int(np.argmax(result.amplitude[:, j]))
        row = [f"{q:g}", _mrad(result.amplitude[k, j]), f"{n[k]:.1f}"]
        if cmp is not None:
            row.append(_mrad(float(cmp.amplitude[k, j])))
        orders.add_row(*row)
    orders.caption = "speed bins; resolved resonance peaks below" if result.resonances else None
    shown = np.sort(np.argsort(np.max(result.amplitude, axis=0))[::-1][:_SHOWN])
    bins = RichTable(title="Per speed bin", header_style="bold")
    for col in ("Speed\n(rpm)", "Windows", "Synthesised\n(mrad)"):
        bins.add_column(col, justify="right")
    if cmp is not None:
        bins.add_column("Model synth.\n(mrad)", justify="right")
    for j in shown:
        bins.add_column(f"Order {result.orders[j]:g}\n(mrad)", justify="right")
    for i in range(n.size):
        row = [f"{n[i]:.1f}", str(int(result.windows[i])), _mrad(result.synthesized[i])]
        if cmp is not None:
            row.append(_mrad(float(cmp.synthesized[i])))
        row += [_mrad(result.amplitude[i, j]) for j in shown]
        bins.add_row(*row)
    bins.caption = (
        f"the {len(shown)} largest of {result.orders.size} orders; every order in "
        "--format csv or json"
    )
    tables = [orders, bins]
    peaks = RichTable(title="Resonances (every window, single-mode fits)", header_style="bold")
    cols = [
        "Order",
        "Peak at\n(rpm)",
        "Peak\n(mrad)",
        "ζ fit",
        "ζ half-power",
        "Natural freq.\n(Hz)",
    ]
    if cmp is not None:
        cols += ["Model peak at\n(rpm)", "Model peak\n(mrad)", "Model ζ\n(same fit)"]
    for col in cols:
        peaks.add_column(col, justify="right")
    by_order = {p.order: p for p in (cmp.peaks if cmp is not None else ())}
    for fit in result.resonances:
        row = [
            f"{fit.order:g}",
            f"{fit.peak_speed * RPM:.1f}",
            _mrad(fit.peak_amplitude),
            _zeta(fit.damping),
            _zeta(fit.half_power_damping),
            f"{fit.natural_frequency / (2 * math.pi):.2f}",
        ]
        if cmp is not None:
            p = by_order.get(fit.order)
            row += (
                [f"{p.model_speed * RPM:.1f}", _mrad(p.model_amplitude), _zeta(p.model_damping)]
                if p is not None
                else ["-", "-", "-"]
            )
        peaks.add_row(*row)
    if not result.resonances:
        peaks.caption = "no resonance inside the record"
    tables.append(peaks)
    if cmp is not None and cmp.damping is not None:
        d = cmp.damping
        damp = RichTable(title="Damping identified and written back", header_style="bold")
        damp.add_column("Quantity")
        damp.add_column("Value", justify="right")
        for label, value in (
            ("From order", f"{d.order:g} at {d.critical_speed * RPM:.0f} rpm"),
            (
                "Measured natural frequency",
                f"{d.natural_frequency / (2 * math.pi):.2f} Hz (model: "
                f"{d.mode_frequency / (2 * math.pi):.2f} Hz, {d.mode_nodes}-node mode)",
            ),
            ("Damping ratio, single-mode fit", _zeta(d.damping)),
            ("Damping ratio, half-power", _zeta(d.half_power_damping)),
            ("Model's damping ratio (same fit)", _zeta(d.model_damping)),
            ("Model's shaft loss factors", d.current_loss_factor),
            ("Loss factor that reproduces the measurement", _zeta(d.loss_factor)),
            (
                "Peak: measured / model / model with it",
                f"{_mrad(d.measured_peak)} / {_mrad(d.model_peak)} / "
                f"{_mrad(d.corrected_peak) if d.corrected_peak is not None else '-'} mrad",
            ),
        ):
            damp.add_row(label, escape(value))
        damp.caption = escape(f"apply: {d.advice}")
        tables.append(damp)
    summary = _summary(result)
    summary.add_row("Record", f"{result.kind} {n.min():.0f} - {n.max():.0f}", "rpm")
    tables.append(summary)
    tables.extend(_notes(result))
    return tables


@click.command("measure")
@click.argument("signal", metavar="SIGNAL")
@click.option(
    "--teeth",
    type=int,
    default=None,
    metavar="N",
    help="Pulses per revolution of the wheel (for a sampled speed signal: angle "
    "samples per revolution, default automatic).",
)
@click.option(
    "--cycle",
    type=click.Choice(_CYCLES),
    default=None,
    help="Working cycle (orders 0.5, 1, ... or 1, 2, ...); default the model's, else four-stroke.",
)
@click.option(
    "--model",
    default=None,
    metavar="MODEL_OR_ENGINE",
    help="Hold the measurement against this model's forced response (needs --at).",
)
@click.option(
    "--at",
    "mass",
    default=None,
    metavar="MASS",
    help="The model's mass that carries the wheel, e.g. pulley.",
)
@click.option(
    "--orders",
    default=None,
    metavar="FIRST:LAST[:STEP]|LIST",
    help="Orders to analyse (default every order up to 12, below N/2).",
)
@click.option(
    "--analysis",
    type=click.Choice(ANALYSES),
    default="auto",
    show_default=True,
    help="steady, tracking (run-up/run-down) or auto (by the spread of the speeds).",
)
@click.option(
    "--window",
    type=click.Choice(WINDOWS),
    default="hann",
    show_default=True,
    help="Window of order tracking (steady records: uniform, one cycle).",
)
@click.option(
    "--window-cycles",
    type=int,
    default=4,
    show_default=True,
    metavar="N",
    help="Cycles per window of order tracking (windows step by one cycle).",
)
@click.option(
    "--bin",
    "bin_width",
    default=None,
    metavar="RPM",
    help="Speed bin of order tracking (rpm); default 10.",
)
@click.option(
    "--reference-angle",
    default=None,
    metavar="DEG",
    help="Crank angle at the reference mark (deg), e.g. of cylinder 1's firing TDC; default 0.",
)
@click.option(
    "--tooth-correction",
    default=None,
    metavar="none|self|FILE",
    help="Tooth-spacing errors: none (default), self (this record's mean over "
    "revolutions) or a calibration record of the same wheel.",
)
@plot_option("Write order amplitudes (against speed for a run-up), with the model's.")
@click.option(
    "--plot-map",
    "map_path",
    default=None,
    metavar="FILE",
    help="Write the colour map of order amplitudes over a run-up.",
)
@click.option(
    "--plot-fit",
    "fit_path",
    default=None,
    metavar="FILE",
    help="Write the resonance fits of a run-up.",
)
@click.option(
    "--plot-trace",
    "trace_path",
    default=None,
    metavar="FILE",
    help="Write the instantaneous speed and angular vibration.",
)
@format_option()
@output_options
def measure_command(
    signal,
    teeth,
    cycle,
    model,
    mass,
    orders,
    analysis,
    window,
    window_cycles,
    bin_width,
    reference_angle,
    tooth_correction,
    plot_path,
    map_path,
    fit_path,
    trace_path,
    fmt,
    output,
    force,
) -> int:
    """Orders of the angular vibration measured by a torsiograph, held against a model.

    SIGNAL is a CSV file with a `time [s]` column of pulse times (and optionally a
    `reference [s]` column of mark times), or `time [s]` and `speed [rpm]` columns of a sampled
    speed signal, a NumPy .npy/.npz file (SI), or a built-in example: inline6-runup,
    inline6-2000rpm. A steady record gives the orders at its speed; a run-up or run-down, the
    orders against speed, the resonances and their damping; with --model and --at, the model's
    forced response beside them and the damping written back as a shaft loss factor.
    """
    # the options' own checks first, before any work
    for path, option in (
        (plot_path, "--plot"),
        (map_path, "--plot-map"),
        (fit_path, "--plot-fit"),
        (trace_path, "--plot-trace"),
    ):
        check_plot_path(path, force, option)
    if output and output != "-":
        check_writable(output, force=force)
    if (model is None) != (mass is None):
        raise InputError(
            "--model and --at go together: the model and the mass that carries the wheel",
            key="--at" if model else "--model",
        )
    width = option_quantity(bin_width, "speed", "--bin", "rpm")
    if width is not None and not width > 0.0:
        raise InputError("the speed bin must be positive", key="--bin", value=bin_width)
    angle = option_quantity(reference_angle, "angle", "--reference-angle", "deg") or 0.0
    torsion = excitation = None
    if model is not None:
        from crankdyn.io.torsion_response_file import resolve_model_and_engine
        from crankdyn.torsion.excitation import excitation_for

        torsion, engine = resolve_model_and_engine(model)
        try:
            torsion.index(mass)
        except InputError as exc:
            raise InputError(exc.message, key="--at", value=mass) from None
        excitation = excitation_for(torsion, engine)
        if cycle is not None and cycle != excitation.cycle:
            raise InputError(
                f"the model's excitation is {excitation.cycle}", key="--cycle", value=cycle
            )
        cycle = excitation.cycle
    cycle = cycle or "four-stroke"
    order_list = None if orders is None else parse_orders(orders, cycle)
    result = load_measurement(
        signal,
        teeth,
        cycle=cycle,
        orders=order_list,
        analysis=analysis,
        window=window,
        window_cycles=window_cycles,
        bin_width=width,
        reference_angle=angle,
        tooth_correction=tooth_correction,
    )
    if torsion is not None:
        result = result.with_model(torsion, excitation, mass)
    steady = result.kind == "steady"
    for path, option in ((map_path, "--plot-map"), (fit_path, "--plot-fit")):
        if path and steady:
            raise InputError(
                "needs a run-up or run-down; this record is steady", key=option, value=path
            )
    if fit_path and not result.resonances:
        raise InputError(
            "no resonance was found in the record: nothing to fit", key="--plot-fit", value=fit_path
        )
    if plot_path:
        save_figure(result.plot("orders"), plot_path, force)
    if map_path:
        save_figure(result.plot("map"), map_path, force, "--plot-map")
    if fit_path:
        save_figure(result.plot("fit"), fit_path, force, "--plot-fit")
    if trace_path:
        save_figure(result.plot("trace"), trace_path, force, "--plot-trace")
    if fmt == "table":
        tables = _steady_tables(result) if steady else _tracking_tables(result)
        _print_tables(tables, output, force)
        return 0
    emit(result, fmt, output, force)
    return 0


def register(group: click.Group) -> None:
    group.add_command(measure_command)
