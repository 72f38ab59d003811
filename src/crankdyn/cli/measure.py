"""``crankdyn measure SIGNAL --teeth N``: measured torsional vibration (torsiograph signals, order
analysis, the model held against the measurement). docs/measurement.md."""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from typing import TYPE_CHECKING, Any, cast

import click
import numpy as np
from numpy.typing import ArrayLike

from crankdyn.cli.common import (
    at_option,
    check_plot_path,
    option_quantity,
    orders_option,
    parse_orders,
    parse_speed,
    plot_option,
    save_figure,
    speed_option,
    teeth_option,
)
from crankdyn.cli.torsion import model_session
from crankdyn.cli.writer import (
    Output,
    TextTable,
    output_options,
    result_table,
    summary_blocks,
)
from crankdyn.constants import RPM
from crankdyn.display import column_text, number
from crankdyn.errors import InputError
from crankdyn.measure.figures import largest_per_order_table
from crankdyn.measure.orders import ANALYSES, WINDOWS, OrderSpectrum, OrderTracking
from crankdyn.measure.records import PulseRecord
from crankdyn.measure.signals import MIN_TEETH, PulseTrain, SpeedSignal

if TYPE_CHECKING:
    from crankdyn.measure.compare import ModelComparison
    from crankdyn.measure.torque import TorqueSpectrum

_CYCLES = ("four-stroke", "two-stroke")
_SHOWN = 6


def _mrad(value: float) -> str:
    """An angle (rad) in the tables' mrad."""
    return number(float(value) * 1e3)


def _zeta(value: float | None) -> str:
    """A damping ratio or loss factor (dimensionless) as the tables show it."""
    return number(value)


def _rpm(speed: float) -> str:
    """A speed (rad/s) in the tables' rpm."""
    return number(float(speed) * RPM)


def load_measurement(
    signal: str,
    teeth: int | None,
    *,
    cycle: str,
    orders: ArrayLike | None = None,
    analysis: str = "auto",
    window: str = "hann",
    window_cycles: int = 4,
    bin_width: float | None = None,
    reference_angle: float = 0.0,
    tooth_correction: str | None = None,
) -> OrderSpectrum | OrderTracking:
    """Read SIGNAL (a file or a built-in name) and analyse its orders; the options as the
    command's (also used by ``crankdyn analyze --measurement``).

    Parameters
    ----------
    signal
        The SIGNAL argument: a signal file or a built-in signal's name
        (:func:`crankdyn.io.signals.resolve_signal`).
    teeth
        --teeth, the pulses per revolution (for a sampled speed signal, angle samples per
        revolution); None: from the file, or automatic.
    cycle
        ``four-stroke`` or ``two-stroke``.
    orders
        The orders to analyse (per revolution); None: every order up to 12, below N/2.
    analysis
        ``steady``, ``tracking`` or ``auto``.
    window
        The window of order tracking.
    window_cycles
        Cycles per window of order tracking.
    bin_width
        The speed bin of order tracking (rad/s); None: 10 rpm.
    reference_angle
        The crank angle at the reference mark (rad).
    tooth_correction
        ``none`` or None, ``self``, or a calibration record of the same wheel (file or name).

    Returns
    -------
    OrderSpectrum or OrderTracking
        The orders of a steady record, or of a run-up or run-down
        (:func:`crankdyn.measure.orders.order_analysis`).

    Raises
    ------
    InputError
        On a bad signal or option, naming the file or the option (``--teeth``, ``--orders``,
        ``--window-cycles``, ``--tooth-correction``) and the value.
    """
    from crankdyn.io.signals import resolve_signal
    from crankdyn.measure.orders import order_analysis

    if teeth is not None and teeth < MIN_TEETH:
        raise InputError(
            f"at least {MIN_TEETH} pulses per revolution are needed", key="--teeth", value=teeth
        )
    source = signal
    try:
        data = resolve_signal(signal, teeth)
        source = data.source
        correction: str | PulseTrain | PulseRecord | None = None
        if tooth_correction not in (None, "none"):
            if tooth_correction == "self":
                correction = "self"
            else:
                source = tooth_correction
                wheel = teeth or getattr(data, "teeth", None)
                calibration = resolve_signal(tooth_correction, wheel)
                if not isinstance(calibration, (PulseTrain, PulseRecord)):
                    raise InputError(
                        "the calibration record must hold pulse times of the same wheel",
                        key="--tooth-correction",
                        value=tooth_correction,
                    )
                correction = calibration
                source = data.source
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
            resolution=teeth if isinstance(data, SpeedSignal) else None,
        )
    except InputError as exc:
        raise _named(exc, source) from None


_OPTIONS = {
    "orders": "--orders",
    "window-cycles": "--window-cycles",
    "window": "--window-cycles",
    "tooth_correction": "--tooth-correction",
    "teeth": "--teeth",
}
"""The options behind the keys of the analysis's errors."""


def _named(exc: InputError, source: str) -> InputError:
    """An error of the order analysis as the command line says it: its key as the option that
    set it (``teeth`` is ``--teeth``), and an error about the record (its pulses, its length)
    naming the signal file it came from."""
    option = _OPTIONS.get(exc.key or "")
    about_the_record = option is None and not (exc.key or "").startswith("-")
    key = option or exc.key
    file = exc.file or (source if (about_the_record or key == "--window-cycles") else None)
    if exc.has_value:
        return InputError(exc.message, file=file, key=key, value=exc.value)
    return InputError(exc.message, file=file, key=key)


def _table(
    title: str, columns: Iterable[tuple[str, Sequence[Any]]], caption: str = ""
) -> TextTable:
    """A table from (header, cells) columns: cells are texts, or numbers (already in the
    header's unit) with five significant digits each (:func:`column_text`, not aligned: the
    amplitudes of the orders span decades)."""
    header, cells = [], []
    for head, values in columns:
        header.append(head)
        if values and all(isinstance(v, str) for v in values):
            cells.append(list(values))
        else:
            numbers = [np.nan if v is None else float(v) for v in values]
            cells.append(column_text(numbers, aligned=False)[0])
    rows = [list(r) for r in zip(*cells, strict=True)]
    return TextTable(title, header, rows, caption=caption)


def _mrad_values(values: Iterable[float | None]) -> list[float | None]:
    """Angles (rad) in mrad, None kept (a cell that reads ``-``)."""
    return [None if v is None else float(v) * 1e3 for v in values]


def _steady_tables(result: OrderSpectrum) -> list[TextTable | str]:
    """The tables and notes of a steady record: its orders (and the model's), a summary."""
    cmp = cast("ModelComparison | None", result.comparison)
    columns: list[tuple[str, Sequence[Any]]] = [
        ("Order", [f"{q:g}" for q in result.orders]),
        ("Amplitude (mrad)", _mrad_values(result.amplitude)),
        ("Phase (deg)", list(np.degrees(result.phase))),
        ("Cycle scatter (mrad)", _mrad_values(result.scatter)),
    ]
    if cmp is not None:
        model = np.asarray(cmp.amplitude[0], dtype=float)
        ratio = [a / m if m > 0 else None for a, m in zip(result.amplitude, model, strict=True)]
        columns += [
            ("Model (mrad)", _mrad_values(model)),
            ("Model phase (deg)", list(np.degrees(cmp.phase[0]))),
            ("Measured / model", ratio),
        ]
    table = _table(f"{result.source}: orders at {_rpm(result.speed)} rpm", columns)
    summary = _summary(result)
    summary.rows.append(["Synthesised half-range amplitude", _mrad(result.synthesized), "mrad"])
    if cmp is not None:
        summary.rows.append(
            [f"Model at {cmp.mass}, synthesised", _mrad(float(cmp.synthesized[0])), "mrad"]
        )
    summary.rows.append(["Cycles averaged", str(result.cycles), ""])
    summary.rows.append(
        ["Cycle speeds", f"{_rpm(result.speed_min)} - {_rpm(result.speed_max)}", "rpm"]
    )
    return [table, summary, *_notes(result)]


def _summary(result: OrderSpectrum | OrderTracking) -> TextTable:
    """The analysis's settings as a Quantity / Value / Unit table."""
    rows = [
        [label, value, ""]
        for label, value in (
            ("Signal", result.source),
            ("Pulses per revolution", str(result.teeth)),
            ("Cycle", result.cycle),
            ("Phase reference", result.reference),
            ("Window", result.window),
            ("Averaging", result.averaging),
            ("Tooth-spacing correction", result.tooth_correction),
        )
    ]
    return TextTable("Analysis", ["Quantity", "Value", "Unit"], rows, text_columns={0, 1, 2})


def _notes(result: OrderSpectrum | OrderTracking) -> list[str]:
    """The notes of the analysis and of its comparison with the model, as lines."""
    notes = list(result.notes or ())
    cmp = cast("ModelComparison | None", result.comparison)
    if cmp is not None:
        notes += list(cmp.notes or ())
    return [f"Note: {text}" for text in notes]


def _tracking_tables(result: OrderTracking) -> list[TextTable | str]:
    """The tables and notes of a run-up or run-down: the largest bin per order, the speed
    bins, the resonance fits, the damping identified, a summary."""
    cmp = cast("ModelComparison | None", result.comparison)
    n = result.speed * RPM
    tables: list[TextTable | str] = []
    for table in largest_per_order_table(result):
        header, rows = table.cells()
        tables.append(TextTable(table.title, header, rows, table.text_columns(), table.caption))
    shown = np.sort(np.argsort(np.max(result.amplitude, axis=0))[::-1][:_SHOWN])
    columns = [
        ("Speed (rpm)", list(n)),
        ("Windows", [str(int(w)) for w in result.windows]),
        ("Synthesised (mrad)", _mrad_values(result.synthesized)),
    ]
    if cmp is not None:
        columns.append(("Model synthesised (mrad)", _mrad_values(cmp.synthesized)))
    columns += [
        (f"Order {result.orders[j]:g} (mrad)", _mrad_values(result.amplitude[:, j])) for j in shown
    ]
    bins = _table(
        "Per speed bin",
        columns,
        f"the {len(shown)} largest of {result.orders.size} orders; every order in "
        "--format csv or json",
    )
    tables.append(bins)
    fits = result.resonances
    columns = [
        ("Order", [f"{f.order:g}" for f in fits]),
        ("Peak at (rpm)", [f.peak_speed * RPM for f in fits]),
        ("Peak (mrad)", _mrad_values(f.peak_amplitude for f in fits)),
        ("ζ fit", [f.damping for f in fits]),
        ("ζ half-power", [f.half_power_damping for f in fits]),
        ("Natural frequency (Hz)", [f.natural_frequency / (2 * math.pi) for f in fits]),
    ]
    if cmp is not None:
        by_order = {p.order: p for p in cmp.peaks}
        peaks = [by_order.get(f.order) for f in fits]
        columns += [
            ("Model peak at (rpm)", [None if p is None else p.model_speed * RPM for p in peaks]),
            (
                "Model peak (mrad)",
                _mrad_values(None if p is None else p.model_amplitude for p in peaks),
            ),
            ("Model ζ (same fit)", [None if p is None else p.model_damping for p in peaks]),
        ]
    tables.append(
        _table(
            "Resonances (every window, single-mode fits)",
            columns,
            "" if fits else "no resonance inside the record",
        )
    )
    if cmp is not None and cmp.damping is not None:
        d = cmp.damping
        corrected = _mrad(d.corrected_peak) if d.corrected_peak is not None else "-"
        rows = [
            ["From order", f"{d.order:g} at {_rpm(d.critical_speed)} rpm"],
            [
                "Measured natural frequency",
                f"{number(d.natural_frequency / (2 * math.pi))} Hz (model: "
                f"{number(d.mode_frequency / (2 * math.pi))} Hz, {d.mode_nodes}-node mode)",
            ],
            ["Damping ratio, single-mode fit", _zeta(d.damping)],
            ["Damping ratio, half-power", _zeta(d.half_power_damping)],
            ["Model's damping ratio (same fit)", _zeta(d.model_damping)],
            ["Model's shaft loss factors", d.current_loss_factor],
            ["Loss factor that reproduces the measurement", _zeta(d.loss_factor)],
            [
                "Peak: measured / model / model with it",
                f"{_mrad(d.measured_peak)} / {_mrad(d.model_peak)} / {corrected} mrad",
            ],
        ]
        tables.append(
            TextTable(
                "Damping identified and written back",
                ["Quantity", "Value"],
                rows,
                text_columns={0, 1},
                caption=f"apply: {d.advice}",
            )
        )
    summary = _summary(result)
    summary.rows.append(["Record", f"{result.kind} {number(n.min())} - {number(n.max())}", "rpm"])
    tables.append(summary)
    tables.extend(_notes(result))
    return tables


_MEASURE_OPTIONS: tuple[Callable[[Any], Any], ...] = (
    teeth_option(),
    click.option(
        "--cycle",
        type=click.Choice(_CYCLES),
        default=None,
        help="Working cycle (orders 0.5, 1, ... or 1, 2, ...); default the model's, else "
        "four-stroke.",
    ),
    click.option(
        "--model",
        default=None,
        metavar="MODEL_OR_ENGINE",
        help="Hold the measurement against this model's forced response (needs --at).",
    ),
    at_option(),
    orders_option(
        "Orders to analyse, FIRST:LAST[:STEP] or 1.5,3,4.5 (default every order up to 12, "
        "below N/2)."
    ),
    click.option(
        "--analysis",
        type=click.Choice(ANALYSES),
        default="auto",
        show_default=True,
        help="steady, tracking (run-up/run-down) or auto (by the spread of the speeds).",
    ),
    click.option(
        "--window",
        type=click.Choice(WINDOWS),
        default="hann",
        show_default=True,
        help="Window of order tracking (steady records: uniform, one cycle).",
    ),
    click.option(
        "--window-cycles",
        type=int,
        default=4,
        show_default=True,
        metavar="N",
        help="Cycles per window of order tracking (windows step by one cycle).",
    ),
    click.option(
        "--bin",
        "bin_width",
        default=None,
        metavar="RPM",
        help="Speed bin of order tracking (rpm); default 10.",
    ),
    click.option(
        "--reference-angle",
        default=None,
        metavar="DEG",
        help="Crank angle at the reference mark (deg), e.g. of cylinder 1's firing TDC; default 0.",
    ),
    click.option(
        "--tooth-correction",
        default=None,
        metavar="FILE",
        help="Tooth-spacing errors: none (default), self (this record's mean over "
        "revolutions) or FILE, a calibration record of the same wheel.",
    ),
    click.option(
        "--torque",
        is_flag=True,
        help="SIGNAL is a measured shaft torque (strain gauges: torque over crank angle, or over "
        "time with a once-per-cycle reference), analysed by order; with --model, --span.",
    ),
    click.option(
        "--span",
        default=None,
        metavar="MASS,MASS",
        help="With --torque and --model: the two masses at the ends of the measured span.",
    ),
    speed_option(
        "With --torque: the mean speed (rpm for a bare number, or with a unit) of a record over "
        "crank angle without times; default: from the record's times."
    ),
    plot_option("Write order amplitudes (against speed for a run-up), with the model's."),
    click.option(
        "--plot-map",
        "map_path",
        default=None,
        metavar="FILE",
        help="Write the colour map of order amplitudes over a run-up.",
    ),
    click.option(
        "--plot-fit",
        "fit_path",
        default=None,
        metavar="FILE",
        help="Write the resonance fits of a run-up.",
    ),
    click.option(
        "--plot-trace",
        "trace_path",
        default=None,
        metavar="FILE",
        help="Write the instantaneous speed and angular vibration.",
    ),
)
"""The options of ``crankdyn measure`` (in the order of its help), applied by
:func:`_measure_options`."""


def _measure_options(f: Any) -> Any:
    """``f`` with the options of :data:`_MEASURE_OPTIONS` (the first listed first in the help) and
    ``--format``, ``-o`` and ``--force`` (:func:`crankdyn.cli.writer.output_options`)."""
    f = output_options(f)
    for option in reversed(_MEASURE_OPTIONS):
        f = option(f)
    return f


@click.command("measure")
@click.argument("signal", metavar="SIGNAL")
@_measure_options
def measure_command(
    signal: str,
    teeth: int | None,
    cycle: str | None,
    model: str | None,
    mass: str | None,
    orders: str | None,
    analysis: str,
    window: str,
    window_cycles: int,
    bin_width: str | None,
    reference_angle: str | None,
    tooth_correction: str | None,
    torque: bool,
    span: str | None,
    speed: str | None,
    plot_path: str | None,
    map_path: str | None,
    fit_path: str | None,
    trace_path: str | None,
    fmt: str,
    output_path: str | None,
    force: bool,
) -> int:
    """Orders of the angular vibration measured by a torsiograph, held against a model.

    SIGNAL is a CSV file with a `time [s]` column of pulse times (and optionally a
    `reference [s]` column of mark times), or `time [s]` and `speed [rpm]` columns of a sampled
    speed signal, a NumPy .npy/.npz file (SI), or a built-in example: inline6-runup,
    inline6-2000rpm. A steady record gives the orders at its speed; a run-up or run-down, the
    orders against speed, the resonances and their damping; with --model and --at, the model's
    forced response beside them and the damping written back as a shaft loss factor.
    With --torque, SIGNAL is a measured shaft torque (`crank_angle [deg]` or `time [s]` with
    `reference [s]`, and `torque [N*m]`): its mean and orders, with --model and --span the
    model's torque at that span beside them.
    """
    # the options' own checks first, before any work
    for path, option in (
        (plot_path, "--plot"),
        (map_path, "--plot-map"),
        (fit_path, "--plot-fit"),
        (trace_path, "--plot-trace"),
    ):
        check_plot_path(path, force, option)
    out = Output(fmt, output_path, force)
    out.check()
    if torque:
        _refuse_pulse_options(teeth, tooth_correction, map_path, fit_path, trace_path, mass)
        spectrum = _torque_record(signal, cycle, model, span, orders, reference_angle, speed)
        if plot_path:
            save_figure(spectrum.plot(), plot_path, force)
        blocks: list[TextTable | str] = [result_table(spectrum), *summary_blocks(spectrum)]
        out.write(blocks=blocks, json_data=spectrum, csv_text=spectrum.to_csv())
        return 0
    for option, value in (("--span", span), ("--speed", speed)):
        if value is not None:
            raise InputError("applies to a torque record (--torque)", key=option, value=value)
    if (model is None) != (mass is None):
        raise InputError(
            "--model and --at go together: the model and the mass that carries the wheel",
            key="--at" if model else "--model",
        )
    width = option_quantity(bin_width, "speed", "--bin", "rpm")
    if width is not None and not width > 0.0:
        raise InputError("the speed bin must be positive", key="--bin", value=bin_width)
    angle = option_quantity(reference_angle, "angle", "--reference-angle", "deg") or 0.0
    session = None
    if model is not None and mass is not None:  # (both or neither, checked above)
        # the model's analysis session: its excitation and forced response
        session = model_session(model)
        if session.model is None:  # (resolve_model_and_engine gives a model or refuses)
            raise InputError("has no torsional model", key="--model", value=model)
        try:
            session.model.index(mass)
        except InputError as exc:
            raise InputError(exc.message, key="--at", value=mass) from None
        excitation = session.excitation()
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
    if session is not None and mass is not None:
        result = session.measurement(result, mass)
    steady = isinstance(result, OrderSpectrum)  # (kind "steady"; a run-up is OrderTracking)
    for path, option in ((map_path, "--plot-map"), (fit_path, "--plot-fit")):
        if path and steady:
            raise InputError(
                "needs a run-up or run-down; this record is steady", key=option, value=path
            )
    if fit_path and isinstance(result, OrderTracking) and not result.resonances:
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
    out.write(
        blocks=_steady_tables(result)
        if isinstance(result, OrderSpectrum)
        else _tracking_tables(result),
        json_data=result,
        csv_text=result.to_csv(),
    )
    return 0


def _refuse_pulse_options(
    teeth: int | None,
    tooth_correction: str | None,
    map_path: str | None,
    fit_path: str | None,
    trace_path: str | None,
    mass: str | None,
) -> None:
    """The torsiograph's options have no meaning for a torque record."""
    for option, value in (
        ("--teeth", teeth),
        ("--tooth-correction", tooth_correction),
        ("--plot-map", map_path),
        ("--plot-fit", fit_path),
        ("--plot-trace", trace_path),
        ("--at", mass),
    ):
        if value is not None:
            hint = " (the span is --span MASS,MASS)" if option == "--at" else ""
            raise InputError(f"applies to a torsiograph signal, not to --torque{hint}", key=option,
                             value=value)  # fmt: skip


def _torque_record(
    signal: str,
    cycle: str | None,
    model: str | None,
    span: str | None,
    orders: str | None,
    reference_angle: str | None,
    speed: str | None,
) -> TorqueSpectrum:
    """--torque: read the record, its orders, and with --model the model's torque at --span."""
    from crankdyn.io.signals import read_torque_record
    from crankdyn.measure.torque import torque_orders

    if (model is None) != (span is None):
        raise InputError(
            "--model and --span go together: the model and the two masses of the measured span",
            key="--span" if model else "--model",
        )
    session = excitation = None
    ends: tuple[str, str] | None = None
    if model is not None and span is not None:
        parts = tuple(p.strip() for p in span.split(","))
        if len(parts) != 2 or not all(parts):
            raise InputError("expected two masses, MASS,MASS", key="--span", value=span)
        ends = (parts[0], parts[1])
        session = model_session(model)
        if session.model is None:
            raise InputError("has no torsional model", key="--model", value=model)
        for end in ends:
            try:
                session.model.index(end)
            except InputError as exc:
                raise InputError(exc.message, key="--span", value=span) from None
        excitation = session.excitation()
        if cycle is not None and cycle != excitation.cycle:
            raise InputError(
                f"the model's excitation is {excitation.cycle}", key="--cycle", value=cycle
            )
        cycle = excitation.cycle
    cycle = cycle or "four-stroke"
    order_list = None if orders is None else parse_orders(orders, cycle)
    angle = option_quantity(reference_angle, "angle", "--reference-angle", "deg") or 0.0
    record = read_torque_record(signal, speed=parse_speed(speed))
    try:
        result = torque_orders(record, cycle=cycle, orders=order_list, reference_angle=angle)
    except InputError as exc:
        if exc.key == "speed":
            raise InputError(exc.message, key="--speed") from None
        raise exc.within(file=record.source) from None
    if session is not None and ends is not None and excitation is not None:
        assert session.model is not None  # (checked above)
        try:
            result = result.with_model(session.model, excitation, ends)
        except InputError as exc:
            if exc.key == "shaft":
                raise InputError(
                    f"no shaft joins {ends[0]} and {ends[1]}", key="--span", value=span
                ) from None
            raise
    return result


def register(group: click.Group) -> None:
    """Add ``measure`` to the command ``group``."""
    group.add_command(measure_command)
