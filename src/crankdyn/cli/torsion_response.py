"""``crankdyn torsion response|campbell|damper|excitation|transient``: forced torsional
vibration (commands of the ``torsion`` group). Every number comes from the analysis session
(:class:`crankdyn.session.Analysis`): the sweep, the orders, the peaks, the shaft a plot
shows and the damper comparison are the session's, as in the report and the study figures."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import click
import numpy as np

from crankdyn.cli.common import (
    check_plot_path,
    deprecated_alias,
    merge_alias,
    no_fail_option,
    option_quantity,
    orders_option,
    parse_orders,
    parse_speed,
    parse_speeds,
    plot_option,
    rules_option,
    save_figure,
    speed_option,
    speed_sweep,
    speeds_option,
    verdict_status,
)
from crankdyn.cli.torsion import model_session, torsion_group
from crankdyn.cli.writer import (
    Output,
    TextTable,
    output_options,
    result_table,
    summary_blocks,
    summary_table,
)
from crankdyn.constants import DEG, RPM
from crankdyn.display import column_text
from crankdyn.docs import ref
from crankdyn.errors import InputError

if TYPE_CHECKING:
    from crankdyn.session import Analysis
    from crankdyn.torsion.response import RelativeAngle, ResponseResult
    from crankdyn.tvc import ConditionResult

_QUANTITIES = ("amplitude", "relative", "torque", "stress")
_ORDERS_HELP = (
    "Orders, e.g. 0.5:12 or 1.5,3,4.5,6 (default 0.5:12 four-stroke, 1:12 two-stroke, with the "
    "orders of the model's excitation sources); a list may hold a source's orders, e.g. a "
    "propeller's blade orders."
)


def _pair(text: str | None, option: str) -> tuple[str, str] | None:
    """Two mass names ``A,B`` (--relative), or None for None."""
    if text is None:
        return None
    parts = [p.strip() for p in text.split(",")]
    if len(parts) != 2 or not all(parts):
        raise InputError("expected two mass names separated by a comma", key=option, value=text)
    return parts[0], parts[1]


def _int_list(text: str | None, option: str) -> tuple[int, ...]:
    """Comma-separated cylinder numbers (--misfire); none for None or an empty text."""
    if not text:
        return ()
    try:
        return tuple(int(p) for p in text.split(",") if p.strip())
    except ValueError:
        raise InputError(
            "expected cylinder numbers separated by commas", key=option, value=text
        ) from None


def _session(model: str, speeds: str | None, orders: str | None, **options: Any) -> Analysis:
    """The session of MODEL_OR_ENGINE with the --speeds sweep and the --orders."""
    return model_session(model, speeds=speed_sweep(speeds), orders=orders, **options)


def _torque_amplitude(torque: str | None) -> float | None:
    """--torque (N·m for a bare number): positive, or None for None."""
    t = option_quantity(torque, "torque", "--torque", "N*m")
    if t is not None and not t > 0.0:
        raise InputError("the torque amplitude must be positive", key="--torque", value=torque)
    return t


def _at(speed: float) -> str:
    """A speed (rad/s) as the tables' rpm, one decimal."""
    return f"{speed * RPM:.1f}"


# ---- the response's tables: renderings of the results' summaries ------------------------------
def response_tables(
    result: ResponseResult,
    relative: RelativeAngle | None = None,
    judged: ConditionResult | None = None,
) -> list[TextTable | str]:
    """What ``torsion response`` prints: the response's summary (its key figures, the peaks of
    every mass and shaft on the resolved curve, the speeds added), the relative angle's, and
    the verdicts of the installation's checks with the barred ranges as found and as declared
    (:meth:`crankdyn.session.Analysis.judged`: the TVC's own evaluation).

    Parameters
    ----------
    result
        The forced response.
    relative
        The relative angle between two masses (--relative), or None.
    judged
        The response judged by the installation's checks, or None (no component with a limit).

    Returns
    -------
    list of TextTable and str
        The tables and note lines, in the order shown.
    """
    blocks = summary_blocks(result, f"{result.model_name}: forced response")
    if relative is not None:
        a, b = relative.between
        blocks += summary_blocks(relative, f"Relative angle {a} - {b}")
    if judged is not None:
        blocks += summary_blocks(judged, f"The installation's checks: {judged.name}")
    return blocks


# ---- commands -----------------------------------------------------------------------------------
_MODEL_ARG = click.argument("model", metavar="MODEL_OR_ENGINE")


@torsion_group.command("response")
@_MODEL_ARG
@speeds_option()
@orders_option(_ORDERS_HELP)
@click.option(
    "--relative",
    default=None,
    metavar="A,B",
    help="Also the relative angle between two masses, e.g. pulley,flywheel.",
)
@click.option(
    "--misfire",
    default=None,
    metavar="LIST",
    help="Misfiring cylinders (motored), e.g. 3 or 2,5 (engines).",
)
@click.option(
    "--torque",
    default=None,
    metavar="NM",
    help="Uniform harmonic torque per order at every cylinder (N·m, or with a unit); default: "
    "the engine's excitation.",
)
@click.option("--no-dampers", is_flag=True, help="Leave out the model's [[damper]] entries.")
@plot_option("Write the response against speed per order and synthesised (.png, .svg or .pdf).")
@click.option(
    "--plot-quantity",
    type=click.Choice(_QUANTITIES),
    default=None,
    help="What --plot shows (default: relative angle with --relative, else the torque "
    "of the most loaded shaft).",
)
@click.option(
    "--item",
    default=None,
    metavar="NAME",
    help="The mass (amplitude) or shaft 'a - b' (torque, stress) for --plot; default the most "
    "loaded (stressed) shaft, or the first mass.",
)
@click.option(
    "--plot-stress",
    "stress_path",
    default=None,
    metavar="FILE",
    help="Write the shaft stresses against the rule limits (needs [rules]).",
)
@rules_option()
@no_fail_option
@output_options
def response_command(
    model: str,
    speeds: str | None,
    orders: str | None,
    relative: str | None,
    misfire: str | None,
    torque: str | None,
    no_dampers: bool,
    plot_path: str | None,
    plot_quantity: str | None,
    item: str | None,
    stress_path: str | None,
    rules: str | None,
    no_fail: bool,
    fmt: str,
    output_path: str | None,
    force: bool,
) -> int:
    """Steady-state forced response of MODEL_OR_ENGINE over a speed range.

    Per speed, order and mass the angular amplitude; synthesised over all orders (half of the
    peak-to-peak in the time domain, and the sum of the order amplitudes); vibratory torque and
    nominal shear stress of every shaft; the installation's checks (the TVC's rows of the same
    condition: the shafts of [rules] against the rule set's limits, couplings, gears, machines,
    dampers), each row citing its rule, edition and clause (--rules chooses the rule set).

    Exit status: 0 when every verdict passed (or nothing was judged), 1 when one failed (the
    output is written), 2 on an error; --no-fail gives 0 whatever the verdict.
    """
    out = Output(fmt, output_path, force)
    out.check()
    pair = _pair(relative, "--relative")
    cylinders = _int_list(misfire, "--misfire")
    check_plot_path(plot_path, force)
    check_plot_path(stress_path, force)
    session = _session(model, speeds, orders, rules=rules)
    result = session.response(
        dampers=() if no_dampers else None, misfire=cylinders, torque=_torque_amplitude(torque)
    )
    rel = None
    if pair is not None:
        try:
            rel = session.relative_angle(*pair, response=result)
        except InputError as exc:
            raise InputError(exc.message, key="--relative", value=relative) from None
    what = plot_quantity or ("relative" if pair else "torque")
    target = pair if what == "relative" else item
    try:
        if item is not None:
            if what in ("torque", "stress"):
                result.shaft_index(item)
            else:
                result.mass_index(item)
    except InputError as exc:
        raise InputError(exc.message, key="--item", value=item) from None
    judged = session.judged(
        dampers=() if no_dampers else None, misfire=cylinders, torque=_torque_amplitude(torque)
    )
    if stress_path and (judged is None or not any(c.m68 for c in judged.curves.values())):
        raise InputError(
            f"the model has no [rules] ({ref('torsion-file')}): nothing to plot",
            key="--plot-stress",
            value=stress_path,
        )
    if plot_path and target is None and what in ("torque", "stress"):
        try:
            target = (
                result.most_stressed_shaft() if what == "stress" else result.most_loaded_shaft()
            )
        except InputError as exc:
            raise InputError(exc.message, key="--plot-quantity", value=what) from None
    data = result.to_dict()
    if rel is not None:
        data["relative_angle"] = rel.to_dict()
    if judged is not None:  # its key figures, verdict rows and barred ranges
        data["judged"] = judged.to_dict()
    out.write(
        blocks=response_tables(result, rel, judged),
        json_data=data,
        csv_text=result.to_csv(),
        warnings=(result, judged),
    )
    if plot_path:
        save_figure(result.plot(what, target), plot_path, force)
    if stress_path:
        assert judged is not None
        save_figure(judged.plot_stress_limits(), stress_path, force)
    return verdict_status(judged.passed if judged is not None else None, no_fail)


@torsion_group.command("campbell")
@_MODEL_ARG
@speeds_option(
    "Speed range (rpm for bare numbers), e.g. 1000:2500; default the model's operating range."
)
@deprecated_alias("--range", "--speeds", "speed_span", "LOW:HIGH")
@orders_option(_ORDERS_HELP)
@plot_option("Write the Campbell diagram (.png, .svg or .pdf).")
@output_options
def campbell_command(
    model: str,
    speeds: str | None,
    speed_span: str | None,
    orders: str | None,
    plot_path: str | None,
    fmt: str,
    output_path: str | None,
    force: bool,
) -> int:
    """Critical speeds (mode x order -> speed) of MODEL_OR_ENGINE in the operating range, with
    major orders marked, and the Campbell diagram."""
    out = Output(fmt, output_path, force)
    out.check()
    check_plot_path(plot_path, force)
    speeds = merge_alias(speeds, speed_span, "--speeds", "--range")
    parsed = parse_speeds(speeds, "--speeds")
    sweep = None if parsed is None else np.array([parsed[0], parsed[1]])
    if parsed is not None and not parsed[1] > parsed[0]:
        raise InputError("the range is empty: HIGH is not above LOW", key="--speeds", value=speeds)
    result = model_session(model, speeds=sweep, orders=orders).campbell()
    # what excites each order, where sources act besides the engine (drivelines)
    sources = any(c.excited_by not in (None, "engine") for c in result.critical_speeds)
    rows = [
        [
            f"{c.speed * RPM:.1f}",
            str(c.mode),
            str(c.nodes),
            f"{c.order:g}",
            f"{c.frequency_hz:.5g}",
            "undetermined" if c.major is None else ("yes" if c.major else "no"),
            "-" if c.relative_amplitude_sum is None else f"{c.relative_amplitude_sum:.3g}",
            *([c.excited_by or "-"] if sources else []),
        ]
        for c in result.critical_speeds
    ]
    table = TextTable(
        f"{result.model_name}: critical speeds {result.low * RPM:.0f}-{result.high * RPM:.0f} rpm",
        [
            "Critical speed (rpm)",
            "Mode",
            "Nodes",
            "Order",
            "Natural frequency (Hz)",
            "Major order",
            "Relative amplitude sum",
            *(["Excited by"] if sources else []),
        ],
        rows,
        text_columns={7} if sources else set(),
        caption="; ".join(result.notes or ()),
    )
    out.write(blocks=[table], json_data=result)
    if plot_path:
        save_figure(result.plot(), plot_path, force)
    return 0


@torsion_group.command("damper-modes")
@_MODEL_ARG
@speeds_option(
    "Speed range (rpm for bare numbers), e.g. 1000:2500; default the model's operating range."
)
@orders_option(_ORDERS_HELP)
@output_options
def damper_modes_command(
    model: str,
    speeds: str | None,
    orders: str | None,
    fmt: str,
    output_path: str | None,
    force: bool,
) -> int:
    """The natural modes of MODEL_OR_ENGINE with its tuned damper stages (several [[damper]]
    rings on one hub: a multi-stage damper), the rings' share of each mode's energy, and the
    resonances the damper modes add in the operating range (seed 003)."""
    from crankdyn.torsion.dampers import damper_modes

    out = Output(fmt, output_path, force)
    out.check()
    parsed = parse_speeds(speeds, "--speeds")
    sweep = None if parsed is None else np.array([parsed[0], parsed[1]])
    if parsed is not None and not parsed[1] > parsed[0]:
        raise InputError("the range is empty: HIGH is not above LOW", key="--speeds", value=speeds)
    session = model_session(model, speeds=sweep, orders=orders)
    the_model = session.model
    if the_model is None:
        raise InputError("has no torsional model", key="MODEL_OR_ENGINE", value=model)
    excited = bool(the_model.cylinder_dofs) or bool(the_model.sources)
    result = damper_modes(
        the_model,
        session.orders,
        session.speed_range,
        excitation=session.excitation() if excited else None,
    )
    blocks: list[TextTable | str] = [result_table(result), *summary_blocks(result)]
    if result.critical_speeds:
        blocks.insert(1, result_table(result.resonances))
    out.write(blocks=blocks, json_data=result, csv_text=result.to_csv())
    return 0


@torsion_group.command("damper")
@_MODEL_ARG
@click.option("--at", "hub", required=True, metavar="MASS", help="The mass the damper sits on.")
@click.option(
    "--mode",
    "mode",
    required=True,
    type=int,
    metavar="N",
    help="The mode to damp: elastic modes numbered from 1, as `crankdyn torsion modes` lists "
    "them (a free model's rigid-body mode is 0).",
)
@click.option(
    "--inertia", required=True, metavar="KGM2", help="The ring's inertia (kg·m², or with a unit)."
)
@click.option(
    "--kind",
    type=click.Choice(("tuned", "viscous")),
    default="tuned",
    show_default=True,
    help="Tuned rubber damper or untuned viscous (Houdaille).",
)
@speeds_option(
    "Speed range of the response with and without the damper (rpm for bare numbers); default "
    "the model's operating range every 10 rpm (no comparison without one)."
)
@orders_option(_ORDERS_HELP)
@plot_option("Write the synthesised amplitude at the damper's mass with and without it.")
@output_options
def damper_command(
    model: str,
    hub: str,
    mode: int,
    inertia: str,
    kind: str,
    speeds: str | None,
    orders: str | None,
    plot_path: str | None,
    fmt: str,
    output_path: str | None,
    force: bool,
) -> int:
    """Optimum damper (Den Hartog) on a mass of MODEL_OR_ENGINE for one mode, and the response
    with and without it."""
    out = Output(fmt, output_path, force)
    out.check()
    check_plot_path(plot_path, force)
    j = option_quantity(inertia, "inertia", "--inertia", "kg*m^2")
    if not j > 0.0:
        raise InputError("the ring's inertia must be positive", key="--inertia", value=inertia)
    session = _session(model, speeds, orders)
    model_obj = session.model
    if model_obj is None:  # (model_session gives a model or refuses)
        raise InputError("has no torsional model", key="MODEL_OR_ENGINE", value=model)
    try:
        model_obj.index(hub)
    except InputError as exc:
        raise InputError(exc.message, key="--at", value=hub) from None
    try:
        design = session.damper(hub, mode, j, kind)
    except InputError as exc:
        if exc.key != "mode":
            raise
        raise InputError(exc.message, key="--mode", value=mode) from None
    comparison = None
    has_range = speeds is not None or model_obj.operating is not None
    if has_range:
        comparison = session.damper_comparison(design)
    elif plot_path:
        raise InputError(
            "a plot needs a speed range: give --speeds LOW:HIGH[:STEP]",
            key="--plot",
            value=plot_path,
        )
    blocks: list[TextTable | str] = [summary_table(design, "Optimum damper (Den Hartog)")]
    data = design.to_dict()
    if comparison is not None:
        with_d, without = comparison
        rows = []
        peaks = []
        for label, r in (("without damper", without), ("with damper", with_d)):
            found = r.peak("synthesized_amplitude", hub)  # resolved: one of r's speeds
            value, speed = found.value, found.speed
            k = int(np.argmin(np.abs(r.speed - speed)))
            power = math.nan if r.damper_power is None else float(r.damper_power[k, -1])
            peaks.append((label, value, speed, power))
        amp, unit = column_text([p[1] for p in peaks], "rad")
        pw, pw_unit = column_text([p[3] for p in peaks], "W")
        for (label, _v, speed, _p), a, w in zip(peaks, amp, pw, strict=True):
            rows.append([label, a, _at(speed), w])
        blocks.append(
            TextTable(
                f"Synthesised amplitude at {hub}",
                ["", f"Largest ({unit})", "At speed (rpm)", f"Damper power there ({pw_unit})"],
                rows,
                text_columns={0},
            )
        )
        data["with_damper"] = with_d.to_dict()
        data["without_damper"] = without.to_dict()
        if plot_path:
            from crankdyn.plots.torsion_response import plot_damper_comparison

            save_figure(plot_damper_comparison(with_d, without, "amplitude", hub), plot_path, force)
    out.write(blocks=blocks, json_data=data, warnings=session.input_warnings)
    return 0


@torsion_group.command("excitation")
@click.argument("model", metavar="ENGINE")
@speed_option("Engine speed (rpm for a bare number, or with a unit); default: the engine's own.")
@orders_option(_ORDERS_HELP)
@click.option("--misfire", default=None, metavar="LIST", help="Misfiring cylinders (motored).")
@plot_option("Write the bar chart of the harmonics (.png, .svg or .pdf).")
@output_options
def excitation_command(
    model: str,
    speed: str | None,
    orders: str | None,
    misfire: str | None,
    plot_path: str | None,
    fmt: str,
    output_path: str | None,
    force: bool,
) -> int:
    """Harmonic analysis of the cylinder torque of ENGINE at one speed: per order the gas,
    inertia and total amplitude, the phase-vector sum over the cylinders (major orders), and,
    with a [torsion] section, the relative amplitude sums over its modes."""
    from crankdyn.io.catalogue import resolve_engine
    from crankdyn.session import Analysis

    out = Output(fmt, output_path, force)
    out.check()
    check_plot_path(plot_path, force)
    w = parse_speed(speed)
    engine = resolve_engine(model)
    session = Analysis(engine, speed=w)
    order_list = None if orders is None else parse_orders(orders, engine.cycle)
    result = session.harmonics(orders=order_list, misfire=_int_list(misfire, "--misfire"))
    cols = [
        ("Total amplitude", result.amplitude),
        ("Gas", result.gas_amplitude),
        ("Inertia", result.inertia_amplitude),
        ("All cylinders", result.engine_amplitude),
    ]
    header = ["Order"]
    columns = [[f"{q:g}" for q in result.orders]]
    for label, values in cols:
        texts, unit = column_text(values, "N·m")
        header.append(f"{label} ({unit})")
        columns.append(texts)
    header += ["Phase (deg)", "Phase-vector sum |Σ e^(-iqΦ)|", "Major order"]
    columns.append([f"{p * DEG:.1f}" for p in result.phase])
    if result.phase_sum is None or result.major is None:  # no firing angles (both None):
        # the major orders are undetermined
        columns.append(["-"] * len(result.orders))
        columns.append(["undetermined"] * len(result.orders))
    else:
        columns.append(column_text(result.phase_sum, reference=1.0)[0])
        columns.append(["yes" if m else "no" for m in result.major])
    sums = result.relative_amplitude_sums
    if result.modes is not None and sums is not None:  # (both or neither: a model's modes)
        for r, m in enumerate(result.modes):
            header.append(f"Relative amplitude sum, mode {int(m)}")
            columns.append([f"{v:.3g}" for v in sums[r]])
    table = TextTable(
        f"{engine.name}: torque harmonics at {session.speed * RPM:.0f} rpm",
        header,
        [list(r) for r in zip(*columns, strict=True)],
        caption=result.source,
    )
    out.write(blocks=[table], json_data=result)
    if plot_path:
        save_figure(result.plot(), plot_path, force)
    return 0


@torsion_group.command("transient")
@_MODEL_ARG
@speed_option("Constant speed (rpm for a bare number, or with a unit); default: the engine's own.")
@speeds_option(
    "A linear run-up START:END between two speeds (rpm), with --duration; default: a constant "
    "--speed."
)
@deprecated_alias("--run-up", "--speeds", "run_up", "START:END")
@click.option(
    "--duration",
    default=None,
    metavar="S",
    help="Simulated time (s, or with a unit); default: --cycles at a constant speed.",
)
@click.option(
    "--cycles",
    default=None,
    type=float,
    metavar="N",
    help="Working cycles at constant speed (default 30).",
)
@orders_option(_ORDERS_HELP)
@click.option(
    "--event",
    "event",
    default=None,
    metavar="KIND",
    help="A transient event instead: clutch, short-circuit, ice, start, stop, emergency-stop, "
    "ramp, step or table (its keys with -p; crankdyn docs events).",
)
@click.option(
    "-p",
    "--param",
    "params",
    multiple=True,
    metavar="KEY=VALUE",
    help='A key of the --event, e.g. -p "torque=60 kN*m" (bare speeds in rpm; lists '
    "comma-separated); repeat for each key.",
)
@plot_option("Write the torque of the most loaded shaft against time (.png, .svg or .pdf).")
@no_fail_option
@output_options
def transient_command(
    model: str,
    speed: str | None,
    speeds: str | None,
    run_up: str | None,
    duration: str | None,
    cycles: float | None,
    orders: str | None,
    event: str | None,
    params: tuple[str, ...],
    plot_path: str | None,
    no_fail: bool,
    fmt: str,
    output_path: str | None,
    force: bool,
) -> int:
    """Time-domain response of MODEL_OR_ENGINE to the engine torque (scipy's solve_ivp), at a
    constant speed or in a run-up; or through a transient event (--event).

    Exit status: 0 when every verdict passed (the verdicts of an --event; a run without one
    has none), 1 when one failed (the output is written), 2 on an error; --no-fail gives 0
    whatever the verdict."""
    out = Output(fmt, output_path, force)
    out.check()
    check_plot_path(plot_path, force)
    speeds = merge_alias(speeds, run_up, "--speeds", "--run-up")
    w = parse_speed(speed)
    t_end = option_quantity(duration, "time", "--duration", "s")
    if event is not None:
        from crankdyn.cli.torsion_events import run_event

        if speeds is not None or cycles is not None:
            raise InputError("an --event takes --speed and --duration", key="--event", value=event)
        return run_event(
            _session(model, None, orders, speed=w),
            event,
            params,
            speed=w,
            duration=t_end,
            out=out,
            plot_path=plot_path,
            force=force,
            no_fail=no_fail,
        )
    if params:
        raise InputError("-p gives the keys of an --event", key="-p", value=params[0])
    if w is not None and speeds is not None:
        raise InputError("give --speed or --speeds START:END, not both", key="--speed", value=speed)
    ramp = None
    if speeds is not None:
        low, high, step = parse_speeds(speeds, "--speeds")
        if step is not None:
            raise InputError("expected START:END (rpm)", key="--speeds", value=speeds)
        ramp = (low, high)
        if t_end is None:
            raise InputError("a run-up needs --duration", key="--duration")
    if t_end is not None and not t_end > 0.0:
        raise InputError("the duration must be positive", key="--duration", value=duration)
    if cycles is not None and not cycles > 0.0:
        raise InputError("the number of cycles must be positive", key="--cycles", value=cycles)
    session = _session(model, None, orders, speed=w)
    if ramp is None:
        session.speed  # noqa: B018  (no speed: the one-line error before the run)
    result = session.transient(run_up=ramp, duration=t_end, cycles=cycles)
    out.write(
        blocks=summary_blocks(result, figures=False), json_data=result, csv_text=result.to_csv()
    )
    if plot_path:
        save_figure(result.plot(), plot_path, force)
    return 0


def register(group: click.Group) -> None:
    """The commands attach to the ``torsion`` group on import."""


__all__ = ["register", "response_tables"]
