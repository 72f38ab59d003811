"""``crankdyn torsion response|campbell|damper|excitation|transient``: forced torsional
vibration (commands of the ``torsion`` group)."""

from __future__ import annotations

import math

import click
import numpy as np
from rich.table import Table as RichTable

from crankdyn.cli.common import (
    check_plot_path,
    emit,
    format_option,
    option_quantity,
    output_options,
    plot_option,
    save_figure,
    speed_range,
)
from crankdyn.cli.torsion import _print_tables, torsion_group
from crankdyn.constants import RPM
from crankdyn.errors import InputError
from crankdyn.io.torsion_response_file import resolve_model_and_engine
from crankdyn.torsion.excitation import (
    check_orders,
    excitation_for,
    fundamental_order,
    harmonic_analysis,
    order_grid,
)

_QUANTITIES = ("amplitude", "relative", "torque", "stress")


# ---- option parsing ------------------------------------------------------------------------------
def parse_orders(text: str | None, cycle: str, option: str = "--orders") -> np.ndarray:
    """FIRST:LAST[:STEP] or a comma-separated list; default 0.5:12 (four-stroke) / 1:12."""
    base = fundamental_order(cycle)
    if text is None:
        return order_grid(base, 12.0, base, cycle)
    ranged = ":" in text
    try:
        parts = [float(p) for p in (text.split(":") if ranged else text.split(",")) if p.strip()]
    except ValueError:
        parts = []
    if not parts or (ranged and len(parts) not in (2, 3)):
        raise InputError(
            "expected FIRST:LAST[:STEP] or a list of orders, e.g. 0.5:12 or 1.5,3,4.5,6",
            key=option,
            value=text,
        )
    try:
        if ranged:
            step = parts[2] if len(parts) == 3 else base
            return order_grid(parts[0], parts[1], step, cycle)
        return check_orders(parts, cycle, key=option)
    except InputError as exc:
        raise InputError(exc.message, key=option, value=text) from None


def _orders_option():
    """The --orders option shared by the response commands."""
    return click.option(
        "--orders",
        default=None,
        metavar="FIRST:LAST[:STEP]|LIST",
        help="Orders, e.g. 0.5:12 or 1.5,3,4.5,6 (default 0.5:12 four-stroke, 1:12 two-stroke).",
    )


def _pair(text: str | None, option: str) -> tuple[str, str] | None:
    if text is None:
        return None
    parts = [p.strip() for p in text.split(",")]
    if len(parts) != 2 or not all(parts):
        raise InputError("expected two mass names separated by a comma", key=option, value=text)
    return parts[0], parts[1]


def _int_list(text: str | None, option: str) -> tuple[int, ...]:
    if not text:
        return ()
    try:
        return tuple(int(p) for p in text.split(",") if p.strip())
    except ValueError:
        raise InputError(
            "expected cylinder numbers separated by commas", key=option, value=text
        ) from None


def _speeds(text: str | None, model, option: str = "--speeds") -> np.ndarray:
    if text is not None:
        return speed_range(text, option)
    if model.operating is None:
        raise InputError(
            "no speeds: give --speeds START:STOP:STEP (rpm), or [operating] speed_range in the "
            "model",
            key=option,
        )
    step = 25.0 / RPM
    low, high = model.operating.low, model.operating.high
    return low + step * np.arange(math.floor((high - low) / step * (1 + 1e-12)) + 1)


def _range(text: str | None, model) -> tuple[float, float] | None:
    if text is None:
        return None
    parts = [p.strip() for p in text.split(":")]
    if len(parts) != 2 or not all(parts):
        raise InputError("expected LOW:HIGH, e.g. 1000:2500 (rpm)", key="--range", value=text)
    low, high = (option_quantity(p, "speed", "--range", "rpm") for p in parts)
    if low <= 0.0 or high <= 0.0:
        raise InputError("speeds must be positive", key="--range", value=text)
    if high <= low:
        raise InputError("the range is empty: HIGH is not above LOW", key="--range", value=text)
    return low, high


def _excitation(model, engine, misfire, torque):
    t = option_quantity(torque, "torque", "--torque", "N*m")
    if t is not None and not t > 0.0:
        raise InputError("the torque amplitude must be positive", key="--torque", value=torque)
    return excitation_for(model, engine, misfire=misfire, torque=t)


def _g(value: float, scale: float = 1.0) -> str:
    return f"{value * scale:.4g}" if math.isfinite(value) else "-"


def _response_tables(result, relative=None) -> list[RichTable]:
    n = result.speed * RPM
    masses = RichTable(title=f"{result.model_name}: angular amplitudes", header_style="bold")
    for col in (
        "Mass",
        "Largest synthesised\n(mrad)",
        "at\n(rpm)",
        "Largest sum of\norders (mrad)",
    ):
        masses.add_column(col, justify="left" if col == "Mass" else "right")
    for i, name in enumerate(result.masses):
        j = int(np.argmax(result.synthesized_amplitude[:, i]))
        masses.add_row(
            name,
            _g(result.synthesized_amplitude[j, i], 1e3),
            f"{n[j]:.0f}",
            _g(np.max(result.order_sum_amplitude[:, i]), 1e3),
        )
    shafts = RichTable(title="Vibratory torque and stress", header_style="bold")
    for col in (
        "Shaft",
        "Sum of orders\n(N·m)",
        "at\n(rpm)",
        "Synthesised\n(N·m)",
        "Stress, synthesised\n(MPa)",
    ):
        shafts.add_column(col, justify="left" if col == "Shaft" else "right")
    for s, (a, b) in enumerate(result.shafts):
        j = int(np.argmax(result.shaft_torque[:, s]))
        stress = np.max(result.synthesized_shaft_stress[:, s])
        shafts.add_row(
            f"{a} - {b}",
            _g(result.shaft_torque[j, s]),
            f"{n[j]:.0f}",
            _g(np.max(result.synthesized_shaft_torque[:, s])),
            _g(stress, 1e-6),
        )
    shafts.caption = f"excitation: {result.excitation}"
    tables = [masses, shafts]
    if relative is not None:
        rel = RichTable(
            title=f"Relative angle {relative.between[0]} - {relative.between[1]}",
            header_style="bold",
        )
        for col in ("Largest synthesised\n(mrad)", "at\n(rpm)", "Largest sum of\norders (mrad)"):
            rel.add_column(col, justify="right")
        j = int(np.argmax(relative.synthesized))
        rel.add_row(
            _g(relative.synthesized[j], 1e3), f"{n[j]:.0f}", _g(np.max(relative.order_sum), 1e3)
        )
        tables.append(rel)
    check = result.rule_check
    if check is not None:
        rules = RichTable(
            title=f"{check.rule}: {'passed' if check.passed else 'FAILED'}",
            header_style="bold",
        )
        for col in ("Shaft", "Barred range (rpm)", "Largest stress / τ_C", "Verdict"):
            rules.add_column(col)
        if not check.barred_ranges:
            rules.add_row("all checked", "none", "-", "stress below τ_C everywhere")
        for br in check.barred_ranges:
            rules.add_row(
                f"{br.shaft[0]} - {br.shaft[1]}",
                f"{br.start * RPM:.0f} - {br.end * RPM:.0f}",
                f"{br.max_ratio:.3g}",
                br.reason,
            )
        tables.append(rules)
    if result.notes:
        notes = RichTable(title="Notes", show_header=False)
        notes.add_column("")
        for text in result.notes:
            notes.add_row(text)
        tables.append(notes)
    return tables


# ---- commands -----------------------------------------------------------------------------------
_MODEL_ARG = click.argument("model", metavar="MODEL_OR_ENGINE")


@torsion_group.command("response")
@_MODEL_ARG
@click.option(
    "--speeds",
    default=None,
    metavar="START:STOP:STEP",
    help="Speed range (rpm for bare numbers), e.g. 1000:2500:25; default the model's "
    "operating range every 25 rpm.",
)
@_orders_option()
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
    metavar="N*M",
    help="Uniform harmonic torque per order at every cylinder instead of the engine's.",
)
@click.option("--no-dampers", is_flag=True, help="Leave out the model's [[damper]] entries.")
@plot_option("Write the response against speed per order and synthesised.")
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
    help="The mass (amplitude) or shaft 'a - b' (torque, stress) for --plot.",
)
@click.option(
    "--plot-stress",
    "stress_path",
    default=None,
    metavar="FILE",
    help="Write the shaft stresses against the rule limits (needs [rules]).",
)
@format_option()
@output_options
def response_command(
    model,
    speeds,
    orders,
    relative,
    misfire,
    torque,
    no_dampers,
    plot_path,
    plot_quantity,
    item,
    stress_path,
    fmt,
    output,
    force,
) -> int:
    """Steady-state forced response of MODEL_OR_ENGINE over a speed range.

    Per speed, order and mass the angular amplitude; synthesised over all orders (half of the
    peak-to-peak in the time domain, and the sum of the order amplitudes); vibratory torque and
    nominal shear stress of every shaft; the IACS UR M68 check when the model has [rules].
    """
    pair = _pair(relative, "--relative")
    cylinders = _int_list(misfire, "--misfire")
    check_plot_path(plot_path, force)
    check_plot_path(stress_path, force)
    torsion, engine = resolve_model_and_engine(model)
    ex = _excitation(torsion, engine, cylinders, torque)
    order_list = parse_orders(orders, ex.cycle)
    w = _speeds(speeds, torsion)
    from crankdyn.torsion.response import forced_response

    result = forced_response(torsion, ex, w, order_list, dampers=() if no_dampers else None)
    rel = None
    try:
        if pair is not None:
            rel = result.relative_angle(*pair)
    except InputError as exc:
        raise InputError(exc.message, key="--relative", value=relative) from None
    try:
        if item is not None:
            if (plot_quantity or "torque") in ("torque", "stress"):
                result.shaft_index(item)
            else:
                result.mass_index(item)
    except InputError as exc:
        raise InputError(exc.message, key="--item", value=item) from None
    if stress_path and result.rule_check is None:
        raise InputError(
            "the model has no [rules] (docs/torsion-file.md): nothing to plot",
            key="--plot-stress",
            value=stress_path,
        )
    if plot_path:
        what = plot_quantity or ("relative" if pair else "torque")
        target = pair if what == "relative" else item
        if what == "stress" and target is None:
            finite = np.flatnonzero(np.isfinite(result.section_modulus))
            if finite.size == 0:
                raise InputError(
                    "no shaft has diameters: no stress to plot", key="--plot-quantity", value=what
                )
            target = result.shafts[
                int(finite[np.argmax(np.max(result.synthesized_shaft_stress[:, finite], axis=0))])
            ]
        save_figure(result.plot(what, target), plot_path, force)
    if stress_path:
        save_figure(result.plot_stress_limits(), stress_path, force)
    if fmt == "table":
        _print_tables(_response_tables(result, rel), output, force)
        return 0
    if fmt == "json" and rel is not None:
        import json

        data = result.to_dict()
        data["relative_angle"] = rel.to_dict()
        text = json.dumps(data, indent=2, allow_nan=False) + "\n"
        _write(text, output, force)
        return 0
    emit(result, fmt, output, force)
    return 0


def _write(text: str, output: str | None, force: bool) -> None:
    from crankdyn.io.output import write_text

    if output and output != "-":
        path = write_text(output, text, force=force)
        click.echo(f"wrote {path}", err=True)
    else:
        click.echo(text, nl=False)


@torsion_group.command("campbell")
@_MODEL_ARG
@click.option(
    "--range",
    "speed_span",
    default=None,
    metavar="LOW:HIGH",
    help="Operating speed range (rpm), e.g. 1000:2500; default the model's.",
)
@_orders_option()
@plot_option("Write the Campbell diagram (.png, .svg or .pdf).")
@format_option()
@output_options
def campbell_command(model, speed_span, orders, plot_path, fmt, output, force) -> int:
    """Critical speeds (mode x order -> speed) of MODEL_OR_ENGINE in the operating range, with
    major orders marked, and the Campbell diagram."""
    check_plot_path(plot_path, force)
    torsion, engine = resolve_model_and_engine(model)
    from crankdyn.torsion.campbell import campbell

    ex = excitation_for(torsion, engine) if torsion.cylinder_dofs else None
    cycle = ex.cycle if ex is not None else "four-stroke"
    order_list = parse_orders(orders, cycle)
    result = campbell(torsion, order_list, _range(speed_span, torsion), excitation=ex, cycle=cycle)
    if plot_path:
        save_figure(result.plot(), plot_path, force)
    if fmt == "table":
        table = RichTable(
            title=(
                f"{result.model_name}: critical speeds "
                f"{result.low * RPM:.0f}-{result.high * RPM:.0f} rpm"
            ),
            header_style="bold",
        )
        for col in (
            "Speed\n(rpm)",
            "Mode",
            "Nodes",
            "Order",
            "Frequency\n(Hz)",
            "Major",
            "Relative\namplitude sum",
        ):
            table.add_column(col, justify="right")
        for c in result.critical_speeds:
            table.add_row(
                f"{c.speed * RPM:.1f}",
                str(c.mode),
                str(c.nodes),
                f"{c.order:g}",
                f"{c.frequency / (2 * math.pi):.5g}",
                "-" if c.major is None else ("yes" if c.major else "no"),
                "-" if c.relative_amplitude_sum is None else f"{c.relative_amplitude_sum:.3g}",
            )
        if result.notes:
            table.caption = "; ".join(result.notes)
        _print_tables([table], output, force)
        return 0
    emit(result, fmt, output, force)
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
    help="The mode to damp (numbered as `crankdyn torsion modes` lists them).",
)
@click.option("--inertia", required=True, metavar="KG*M^2", help="The ring's inertia.")
@click.option(
    "--kind",
    type=click.Choice(("tuned", "viscous")),
    default="tuned",
    show_default=True,
    help="Tuned rubber damper or untuned viscous (Houdaille).",
)
@click.option(
    "--speeds",
    default=None,
    metavar="START:STOP:STEP",
    help="Also the response with and without the damper over this speed range (rpm).",
)
@_orders_option()
@plot_option("Write the synthesised response with and without the damper (needs --speeds).")
@format_option()
@output_options
def damper_command(
    model, hub, mode, inertia, kind, speeds, orders, plot_path, fmt, output, force
) -> int:
    """Optimum damper (Den Hartog) on a mass of MODEL_OR_ENGINE for one mode, and the response
    with and without it."""
    check_plot_path(plot_path, force)
    if plot_path and speeds is None:
        raise InputError("a plot needs --speeds", key="--plot", value=plot_path)
    j = option_quantity(inertia, "inertia", "--inertia", "kg*m^2")
    if not j > 0.0:
        raise InputError("the ring's inertia must be positive", key="--inertia", value=inertia)
    torsion, engine = resolve_model_and_engine(model)
    torsion.index(hub)
    from crankdyn.torsion.dampers import design_damper

    design = design_damper(torsion, hub, mode, j, kind)
    comparison = None
    if speeds is not None:
        from crankdyn.torsion.response import forced_response

        ex = excitation_for(torsion, engine)
        w = speed_range(speeds)
        order_list = parse_orders(orders, ex.cycle)
        damper = design.damper(_ring_name(torsion))
        with_d = forced_response(torsion, ex, w, order_list, dampers=(*torsion.dampers, damper))
        without = forced_response(torsion, ex, w, order_list, dampers=())
        comparison = (with_d, without)
        if plot_path:
            from crankdyn.plots.torsion_response import plot_damper_comparison

            save_figure(plot_damper_comparison(with_d, without, "amplitude", hub), plot_path, force)
    if fmt == "table":
        from crankdyn.cli.common import summary_table

        tables = [summary_table(design, "Optimum damper (Den Hartog)")]
        if comparison is not None:
            with_d, without = comparison
            i = without.mass_index(hub)
            t = RichTable(title=f"Synthesised amplitude at {hub}", header_style="bold")
            for col in ("", "Largest (mrad)", "at (rpm)", "Damper power at it (W)"):
                t.add_column(col, justify="right")
            for label, r in (("without damper", without), ("with damper", with_d)):
                k = int(np.argmax(r.synthesized_amplitude[:, i]))
                power = "-" if r.damper_power is None else _g(r.damper_power[k, -1])
                t.add_row(
                    label, _g(r.synthesized_amplitude[k, i], 1e3), f"{r.speed[k] * RPM:.0f}", power
                )
            tables.append(t)
        _print_tables(tables, output, force)
        return 0
    if fmt == "json" and comparison is not None:
        import json

        data = design.to_dict()
        data["with_damper"] = comparison[0].to_dict()
        data["without_damper"] = comparison[1].to_dict()
        _write(json.dumps(data, indent=2, allow_nan=False) + "\n", output, force)
        return 0
    emit(design, "json" if fmt == "csv" else fmt, output, force)
    return 0


def _ring_name(model) -> str:
    name, k = "damper ring", 1
    taken = set(model.mass_names) | {d.name for d in model.dampers}
    while name in taken:
        k += 1
        name = f"damper ring {k}"
    return name


@torsion_group.command("excitation")
@click.argument("model", metavar="ENGINE")
@click.option("--speed", required=True, metavar="RPM", help="Engine speed (rpm for bare numbers).")
@_orders_option()
@click.option("--misfire", default=None, metavar="LIST", help="Misfiring cylinders (motored).")
@plot_option("Write the bar chart of the harmonics.")
@format_option()
@output_options
def excitation_command(model, speed, orders, misfire, plot_path, fmt, output, force) -> int:
    """Harmonic analysis of the cylinder torque of ENGINE at one speed: per order the gas,
    inertia and total amplitude, the phase-vector sum over the cylinders (major orders), and,
    with a [torsion] section, the relative amplitude sums over its modes."""
    check_plot_path(plot_path, force)
    w = option_quantity(speed, "speed", "--speed", "rpm")
    if not w > 0.0:
        raise InputError("the speed must be positive", key="--speed", value=speed)
    from crankdyn.io.engine_file import resolve_engine
    from crankdyn.torsion.excitation import EngineExcitation

    engine = resolve_engine(model)
    spec = engine.torsion.excitation if engine.torsion is not None else None
    ex = EngineExcitation(engine, spec, _int_list(misfire, "--misfire"))
    order_list = parse_orders(orders, ex.cycle)
    modes = None
    if engine.torsion is not None and engine.torsion.cylinder_dofs:
        from crankdyn.torsion.modal import natural_modes

        modes = natural_modes(engine.torsion)
    result = harmonic_analysis(ex, w, order_list, modes, engine.torsion)
    if plot_path:
        save_figure(result.plot(), plot_path, force)
    if fmt == "table":
        table = RichTable(
            title=f"{engine.name}: torque harmonics at {w * RPM:.0f} rpm",
            header_style="bold",
        )
        cols = [
            "Order",
            "Amplitude\n(N·m)",
            "Gas\n(N·m)",
            "Inertia\n(N·m)",
            "Phase\n(deg)",
            "|Σ e^(-iqΦ)|",
            "Major",
            "All cylinders\n(N·m)",
        ]
        if result.modes is not None:
            cols += [f"Rel. sum\nmode {int(m)}" for m in result.modes[:3]]
        for col in cols:
            table.add_column(col, justify="right")
        for j, q in enumerate(result.orders):
            row = [
                f"{q:g}",
                _g(result.amplitude[j]),
                _g(result.gas_amplitude[j]),
                _g(result.inertia_amplitude[j]),
                f"{math.degrees(result.phase[j]):.1f}",
                f"{result.phase_sum[j]:.3g}",
                "yes" if result.major[j] else "no",
                _g(result.engine_amplitude[j]),
            ]
            if result.modes is not None:
                row += [f"{v:.3g}" for v in result.relative_amplitude_sums[:3, j]]
            table.add_row(*row)
        table.caption = result.source
        _print_tables([table], output, force)
        return 0
    emit(result, "json" if fmt == "csv" else fmt, output, force)
    return 0


@torsion_group.command("transient")
@_MODEL_ARG
@click.option("--speed", default=None, metavar="RPM", help="Constant speed (rpm).")
@click.option(
    "--run-up",
    "run_up",
    default=None,
    metavar="START:END",
    help="Linear run-up between two speeds (rpm), with --duration.",
)
@click.option("--duration", default=None, metavar="S", help="Simulated time (s).")
@click.option(
    "--cycles",
    default=None,
    type=float,
    metavar="N",
    help="Working cycles at constant speed (default 30).",
)
@_orders_option()
@plot_option("Write the torque of the most loaded shaft against time.")
@format_option()
@output_options
def transient_command(
    model, speed, run_up, duration, cycles, orders, plot_path, fmt, output, force
) -> int:
    """Time-domain response of MODEL_OR_ENGINE to the engine torque (scipy's solve_ivp), at a
    constant speed or in a run-up."""
    check_plot_path(plot_path, force)
    w = option_quantity(speed, "speed", "--speed", "rpm")
    t_end = option_quantity(duration, "time", "--duration", "s")
    if (w is None) == (run_up is None):
        raise InputError("give --speed or --run-up START:END", key="--speed")
    ramp = None
    if run_up is not None:
        parts = [p.strip() for p in run_up.split(":")]
        if len(parts) != 2 or not all(parts):
            raise InputError("expected START:END (rpm)", key="--run-up", value=run_up)
        ramp = tuple(option_quantity(p, "speed", "--run-up", "rpm") for p in parts)
        if min(ramp) <= 0.0:
            raise InputError("speeds must be positive", key="--run-up", value=run_up)
        if t_end is None:
            raise InputError("a run-up needs --duration", key="--duration")
    elif w <= 0.0:
        raise InputError("the speed must be positive", key="--speed", value=speed)
    if t_end is not None and not t_end > 0.0:
        raise InputError("the duration must be positive", key="--duration", value=duration)
    if cycles is not None and not cycles > 0.0:
        raise InputError("the number of cycles must be positive", key="--cycles", value=cycles)
    torsion, engine = resolve_model_and_engine(model)
    ex = excitation_for(torsion, engine)
    order_list = parse_orders(orders, ex.cycle)
    from crankdyn.torsion.transient import transient_response

    result = transient_response(
        torsion,
        ex,
        order_list,
        speed=w,
        run_up=ramp,
        duration=t_end,
        cycles=None if t_end is not None else (cycles or 30.0),
    )
    if plot_path:
        save_figure(result.plot(), plot_path, force)
    if fmt == "table":
        cycle_angle = 4.0 * math.pi if ex.cycle == "four-stroke" else 2.0 * math.pi
        last = result.last_cycle(cycle_angle)
        table = RichTable(
            title=f"{result.model_name}: shaft torques, last cycle", header_style="bold"
        )
        for col in ("Shaft", "Half range (N·m)", "Largest |T| over the run (N·m)"):
            table.add_column(col, justify="left" if col == "Shaft" else "right")
        for s, (a, b) in enumerate(result.shafts):
            seg = result.shaft_torque[last, s]
            table.add_row(
                f"{a} - {b}",
                _g(0.5 * (seg.max() - seg.min())),
                _g(np.max(np.abs(result.shaft_torque[:, s]))),
            )
        table.caption = (
            f"{result.time.size} samples to {result.time[-1]:.4g} s; loss factors "
            f"as viscous at {result.hysteretic_frequency / (2 * math.pi):.4g} Hz"
        )
        _print_tables([table], output, force)
        return 0
    emit(result, fmt, output, force)
    return 0


def register(group: click.Group) -> None:
    """The commands attach to the ``torsion`` group on import."""
