"""``crankdyn firing-orders``, ``crankdyn balance`` and ``crankdyn flywheel``."""

from __future__ import annotations

import json
import math
from dataclasses import replace

import click
from rich.table import Table as RichTable

from crankdyn.cli.common import (
    FORMATS,
    console,
    engine_argument,
    load_engine_arg,
    option_quantity,
    output_options,
    plot_option,
    save_figure,
    speed_of,
    speed_option,
)
from crankdyn.engine.balance import BALANCE_METHODS, BalanceInputs, engine_balance
from crankdyn.engine.firing_search import (
    CRITERIA,
    FiringOrderRanking,
    firing_order_search,
    first_mode_shape,
)
from crankdyn.engine.flywheel import engine_flywheel
from crankdyn.engine.torque import engine_torque
from crankdyn.errors import InputError
from crankdyn.io.output import write_text

__all__ = ["register"]


def _format_option(f):
    return click.option(
        "--format",
        "fmt",
        type=click.Choice(FORMATS),
        default="table",
        show_default=True,
        help="Output format.",
    )(f)


_plot_option = plot_option("Also write the plot to FILE (.png, .svg or .pdf).", "plot_file")


def _write(text: str, output: str | None, force: bool) -> None:
    if output and output != "-":
        path = write_text(output, text, force=force)
        click.echo(f"wrote {path}", err=True)
    else:
        click.echo(text, nl=False)


def _print_or_record(renderables, output: str | None, force: bool) -> None:
    if not output:
        con = console()
        for r in renderables:
            con.print(r)
        return
    con = console(record=True)
    for r in renderables:
        con.print(r)
    _write(con.export_text(), output, force)


def _numbers(text: str | None, option: str, *, integer: bool = False):
    if text is None:
        return None
    parts = [p.strip() for p in text.replace(";", ",").split(",") if p.strip()]
    try:
        values = [int(p) if integer else float(p) for p in parts]
    except ValueError:
        kind = "whole numbers" if integer else "numbers"
        raise InputError(f"expected comma-separated {kind}", key=option, value=text) from None
    if not values or not all(math.isfinite(v) for v in values):
        raise InputError("expected comma-separated finite numbers", key=option, value=text)
    return values


def _groups(text: str | None):
    if text is None:
        return None
    groups = []
    for part in text.split(";"):
        if not part.strip():
            continue
        groups.append(_numbers(part, "--exhaust-groups", integer=True))
    if not groups:
        raise InputError(
            'expected groups such as "1,2,3;4,5,6"', key="--exhaust-groups", value=text
        )
    return groups


# ---- firing-orders ----------------------------------------------------------------------------


def _fmt(value, digits: str = ".4g") -> str:
    if value is None:
        return "-"
    if isinstance(value, float):
        if not math.isfinite(value):
            return "-"
        if abs(value) < 1e-9:
            return "0"
        return format(value, digits)
    return str(value)


def _intervals_text(values) -> str:
    rounded = [round(float(v), 6) for v in values]
    if len(set(rounded)) == 1:
        return f"{rounded[0]:g} × {len(rounded)}"
    return " ".join(f"{v:g}" for v in rounded)


def ranking_table(result: FiringOrderRanking, limit: int | None = None) -> RichTable:
    """A rich table of the ranked firing orders."""
    crit = [c for c in result.criteria if c != "interval_deviation_deg"]
    table = RichTable(title=f"{result.engine}: firing orders", header_style="bold")
    table.add_column("Rank", justify="right")
    table.add_column("Firing order")
    table.add_column("Intervals (deg)")
    headers = {
        "free_force_1": "F₁",
        "free_force_2": "F₂",
        "free_moment_1": "M₁",
        "free_moment_2": "M₂",
        "adjacent_consecutive": "Adjacent\nin a row",
        "main_bearing_min_interval_deg": "Main bearing\nmin gap (deg)",
        "torsional_vector_sum": "Torsional\nvector sum",
        "exhaust_min_interval_deg": "Exhaust group\nmin gap (deg)",
    }
    for c in crit:
        table.add_column(headers.get(c, c), justify="right")
    v_engine = any(c.v_scheme for c in result.candidates)
    if v_engine:
        table.add_column("V scheme")
    shown = result.candidates if limit is None else result.candidates[:limit]
    for cand in shown:
        d = cand.to_dict()
        mark = "*" if result.engine_rank == cand.rank else ""
        row = [f"{cand.rank}{mark}", cand.order_text, _intervals_text(d["firing_intervals_deg"])]
        for c in crit:
            value = d.get(c)
            row.append(_fmt(value, ".4g" if isinstance(value, float) else ""))
        if v_engine:
            row.append(cand.v_scheme or "")
        table.add_row(*row)
    return table


def _ranking_notes(result: FiringOrderRanking, shown: int) -> list[str]:
    lines = [
        f"{result.count} firing order(s) found, {result.even_count} evenly firing; "
        f"ranked by {', '.join(result.criteria)}.",
    ]
    order = "-".join(str(c) for c in result.engine_order)
    if result.engine_rank is not None:
        lines.append(f"* The engine's firing order {order} ranks {result.engine_rank}.")
    elif result.search == "crankshaft":
        lines.append(f"The engine's firing order {order} is not among them.")
    if shown < len(result.candidates):
        lines.append(
            f"Showing the best {shown} of {len(result.candidates)}; --top N or --format csv/json "
            "for more."
        )
    lines.extend(n[0].upper() + n[1:] + "." for n in result.notes[1:])
    lines.append(
        "F₁, F₂, M₁, M₂: free forces per m_j R ω² Aₙ and moments per m_j R ω² Aₙ a "
        "(a = cylinder pitch) of the reciprocating masses."
    )
    return lines


_OPTION_OF = {
    "priority": "--rank-by",
    "mode_shape": "--mode-shape",
    "orders": "--torsion-orders",
    "exhaust_groups": "--exhaust-groups",
    "search": "--any-crankshaft",
    "include_uneven": "--all",
}


def _mode_shape(eng, text: str | None):
    if text is None or text.strip().lower() != "torsion":
        return _numbers(text, "--mode-shape")
    if eng.torsion is None:
        raise InputError(
            "the engine file has no [torsion] model to take the first mode from; give the "
            "amplitudes",
            key="--mode-shape",
            value=text,
        )
    return first_mode_shape(eng.torsion, eng.cylinders.count)


def _search(
    eng, any_crankshaft, include_uneven, mode_shape, torsion_orders, exhaust_groups, priority, top
) -> FiringOrderRanking:
    return firing_order_search(
        eng.cylinders,
        search="any-crankshaft" if any_crankshaft else "crankshaft",
        include_uneven=True if include_uneven else None,
        mode_shape=_mode_shape(eng, mode_shape),
        torsion_orders=_numbers(torsion_orders, "--torsion-orders"),
        exhaust_groups=_groups(exhaust_groups),
        priority=priority,
        top=top,
        name=eng.name,
    )


@click.command("firing-orders")
@engine_argument
@click.option(
    "--any-crankshaft",
    is_flag=True,
    help="Search every even-firing crankshaft of the layout, not only the engine's.",
)
@click.option(
    "--all",
    "include_uneven",
    is_flag=True,
    help="List uneven-firing orders too (by default only the even ones, if there are any).",
)
@click.option(
    "--mode-shape",
    default=None,
    metavar="LIST",
    help="Relative amplitudes of the first torsional mode at the cylinders (or throws), "
    "comma-separated, or 'torsion' for the first mode of the engine's [torsion] model: ranks "
    "by the torsional vector sum.",
)
@click.option(
    "--torsion-orders",
    default=None,
    metavar="LIST",
    help="Orders for the torsional criterion (default: the minor orders).",
)
@click.option(
    "--exhaust-groups",
    default=None,
    metavar="GROUPS",
    help='Cylinders sharing an exhaust branch, e.g. "1,2,3;4,5,6" (pulse turbocharging).',
)
@click.option(
    "--rank-by",
    default=None,
    metavar="LIST",
    help=f"Criteria in priority order (the rest follow); from: {', '.join(CRITERIA)}, "
    "torsional_vector_sum, exhaust_min_interval_deg.",
)
@click.option("--top", type=int, default=None, help="Keep the best N firing orders.")
@_format_option
@output_options
@_plot_option
def firing_orders_command(
    engine,
    any_crankshaft,
    include_uneven,
    mode_shape,
    torsion_orders,
    exhaust_groups,
    rank_by,
    top,
    fmt,
    output,
    force,
    plot_file,
) -> int:
    """Enumerate the firing orders ENGINE's crankshaft allows and rank them (seed 000 §2.3)."""
    eng = load_engine_arg(engine)
    if top is not None and top < 1:
        raise InputError("must be at least 1", key="--top", value=top)
    priority = None
    if rank_by is not None:
        priority = [p.strip() for p in rank_by.split(",") if p.strip()]
        if not priority:
            raise InputError("expected criterion names", key="--rank-by", value=rank_by)
    try:
        result = _search(
            eng,
            any_crankshaft,
            include_uneven,
            mode_shape,
            torsion_orders,
            exhaust_groups,
            priority,
            top,
        )
    except InputError as exc:
        if exc.key in _OPTION_OF and exc.file is None:
            extra = {"value": exc.value} if exc.has_value else {}
            raise InputError(exc.message, key=_OPTION_OF[exc.key], **extra) from None
        raise
    if fmt == "json":
        _write(json.dumps(result.ranked_list(), indent=2, allow_nan=False) + "\n", output, force)
    elif fmt == "csv":
        _write(result.to_csv(), output, force)
    else:
        limit = top if top is not None else 30
        shown = min(limit, len(result.candidates))
        _print_or_record(
            [ranking_table(result, limit), *_ranking_notes(result, shown)],
            output,
            force,
        )
    if plot_file:
        if not result.candidates:
            raise InputError("no firing order to plot", key="--plot", value=plot_file)
        save_figure(result.plot(), plot_file, force)
    return 0


# ---- balance ----------------------------------------------------------------------------------


def _row_name(row) -> str:
    if row.source == "reciprocating":
        return str(row.order)
    return "1 rotating" if row.source == "rotating" else "1 total"


def balance_table(result) -> RichTable:
    """A rich table of the free forces and moments by order."""
    table = RichTable(
        title=f"{result.engine}: free forces and moments at {result.speed * 30 / math.pi:.0f} rpm",
        header_style="bold",
    )
    table.add_column("Order")
    for label in (
        "F\n(N)",
        "F vertical\n(N)",
        "F horizontal\n(N)",
        "M\n(N·m)",
        "M vertical\nplane (N·m)",
        "M horizontal\nplane (N·m)",
        "F /\n(m_j R ω²)",
        "M /\n(m_j R ω² a)",
    ):
        table.add_column(label, justify="right")
    if result.power:
        table.add_column("M per kW\n(N·m/kW)", justify="right")
    rows = result.rows()

    def num(value):
        return "-" if value is None else ("0" if value == 0.0 else f"{value:.5g}")

    for r in rows:
        cells = [
            _row_name(r),
            num(r.free_force),
            num(r.free_force_vertical),
            num(r.free_force_horizontal),
            num(r.free_moment),
            num(r.free_moment_vertical),
            num(r.free_moment_horizontal),
            num(r.force_coefficient),
            num(r.moment_coefficient),
        ]
        if result.power:
            prp = r.power_related_unbalance
            cells.append(num(None if prp is None else prp * 1e3))
        table.add_row(*cells)
    return table


def _balance_notes(result) -> list[str]:
    lines = [
        f"m_j = {result.reciprocating_mass:.4g} kg per cylinder; rotating "
        f"{result.rotating_mass:.4g} kg per throw; counterweights c = "
        f"{result.counterweight_ratio:g}, b = {result.reciprocating_balance_ratio:g}; "
        f"harmonics: {result.method}.",
        "Orders 1, 2, ...: reciprocating masses; '1 rotating': rotating masses and "
        "counterweights; '1 total': both. Amplitudes are the largest magnitude over one "
        "revolution; moments about the middle of the engine; vertical plane = pitching moment "
        "(from vertical forces), horizontal plane = yawing moment.",
    ]
    if result.overturning is not None:
        o = result.overturning
        lines.append(
            f"Overturning moment: steady {o.mean:.5g} N·m, fluctuation up to "
            f"{o.amplitude:.5g} N·m (peak to peak {o.peak_to_peak:.5g} N·m)."
        )
    lines.extend(n[0].upper() + n[1:] + "." for n in result.notes)
    return lines


@click.command("balance")
@engine_argument
@speed_option("Crank speed (rpm, or with a unit); default: the engine's [operating] speed.")
@click.option(
    "--orders",
    default=None,
    metavar="LIST",
    help="Orders of the reciprocating masses (default 1,2,4,6; 1-6 for offset engines).",
)
@click.option(
    "--method",
    type=click.Choice(BALANCE_METHODS),
    default="exact",
    show_default=True,
    help="Piston-acceleration harmonics: exact (converged λ-series) or the seed's "
    "second-order approximation.",
)
@click.option(
    "--counterweight-ratio",
    type=float,
    default=None,
    help="Counterweight per throw as a fraction of its rotating unbalance (default: the "
    "file's [balance], else 0).",
)
@click.option(
    "--reciprocating-balance-ratio",
    type=float,
    default=None,
    help="Share of the reciprocating mass added to each counterweight (default: file, else 0).",
)
@click.option(
    "--rod-offset",
    default=None,
    metavar="MM",
    help="Axial offset of the bank-B rod from the bank-A rod on a V throw (mm, or with a unit).",
)
@click.option(
    "--power",
    default=None,
    metavar="KW",
    help="Engine power for the power-related unbalance (kW, or with a unit).",
)
@click.option(
    "--no-torque",
    is_flag=True,
    help="Leave out the overturning moment (and the power from the torque analysis).",
)
@_format_option
@output_options
@_plot_option
def balance_command(
    engine,
    speed,
    orders,
    method,
    counterweight_ratio,
    reciprocating_balance_ratio,
    rod_offset,
    power,
    no_torque,
    fmt,
    output,
    force,
    plot_file,
) -> int:
    """Free forces and moments of ENGINE's mass forces, order by order (seed 000 §2.2)."""
    eng = load_engine_arg(engine)
    w = speed_of(eng, speed)
    inputs = eng.balance or BalanceInputs()
    changes = {}
    for key, value in (
        ("counterweight_ratio", counterweight_ratio),
        ("reciprocating_balance_ratio", reciprocating_balance_ratio),
    ):
        if value is not None:
            if not math.isfinite(value) or value < 0.0:
                raise InputError(
                    "must be a number >= 0", key="--" + key.replace("_", "-"), value=value
                )
            changes[key] = value
    if rod_offset is not None:
        changes["rod_offset"] = option_quantity(rod_offset, "length", "--rod-offset", "mm")
    if power is not None:
        p = option_quantity(power, "power", "--power", "kW")
        if not p > 0.0:
            raise InputError("the power must be positive", key="--power", value=power)
        changes["power"] = p
    if changes:
        inputs = replace(inputs, **changes)
    order_list = _numbers(orders, "--orders", integer=True)
    if order_list is not None and any(not 1 <= n <= 64 for n in order_list):
        raise InputError("orders must be whole numbers from 1 to 64", key="--orders", value=orders)
    result = engine_balance(
        eng,
        w,
        orders=order_list,
        method=method,
        inputs=inputs,
        torque=None if no_torque else engine_torque(eng, w),
    )
    if fmt == "json":
        _write(result.to_json() + "\n", output, force)
    elif fmt == "csv":
        _write(result.to_csv(), output, force)
    else:
        _print_or_record([balance_table(result), *_balance_notes(result)], output, force)
    if plot_file:
        save_figure(result.plot(), plot_file, force)
    return 0


# ---- flywheel ---------------------------------------------------------------------------------


def flywheel_table(result) -> RichTable:
    """The flywheel figures as a rich table."""
    table = RichTable(
        title=f"{result.engine}: speed fluctuation and flywheel at "
        f"{result.speed * 30 / math.pi:.0f} rpm",
        header_style="bold",
    )
    table.add_column("Quantity")
    table.add_column("Value", justify="right")
    table.add_column("Unit")
    for label, value, unit in result.summary_rows():
        if label in ("Engine", "Notes"):
            continue
        table.add_row(label, value, unit)
    return table


@click.command("flywheel")
@engine_argument
@speed_option("Mean crank speed (rpm, or with a unit); default: the engine's [operating] speed.")
@click.option(
    "--delta",
    default=None,
    metavar="δ",
    help="Target degree of cyclic irregularity (ω_max − ω_min)/ω_m, e.g. 0.01 or 1/150 "
    "(default: the file's [flywheel] delta).",
)
@click.option(
    "--inertia",
    default=None,
    metavar="KGM2",
    help="A given flywheel's inertia (kg·m², or with a unit), to find the δ it gives.",
)
@click.option(
    "--step",
    metavar="DEG",
    default="0.5",
    show_default=True,
    help="Crank-angle step of the torque curve (deg, or with a unit).",
)
@_format_option
@output_options
@_plot_option
def flywheel_command(engine, speed, delta, inertia, step, fmt, output, force, plot_file) -> int:
    """Speed fluctuation of ENGINE and the flywheel for a target δ (seed 000 §2.4)."""
    eng = load_engine_arg(engine)
    w = speed_of(eng, speed)
    target = None if delta is None else _fraction(delta, "--delta")
    if target is not None and not 0.0 < target < 1.0:
        raise InputError("δ must lie between 0 and 1, e.g. 0.01", key="--delta", value=delta)
    given = option_quantity(inertia, "inertia", "--inertia", "kg*m^2")
    if given is not None and not given > 0.0:
        raise InputError("the inertia must be positive", key="--inertia", value=inertia)
    h = option_quantity(step, "angle", "--step", "deg")
    cycle = eng.cycle_angle
    if not 0.0 < h <= math.radians(10.0) or abs(round(cycle / h) * h - cycle) > 1e-9 * cycle:
        raise InputError(
            f"the step must divide {math.degrees(cycle):.0f} deg evenly and be at most 10 deg",
            key="--step",
            value=step,
        )
    result = engine_flywheel(eng, w, delta=target, inertia=given, step=h)
    if fmt == "json":
        data = result.to_dict()
        _write(json.dumps(data, indent=2, allow_nan=False) + "\n", output, force)
    elif fmt == "csv":
        _write(result.to_csv(), output, force)
    else:
        notes = [n[0].upper() + n[1:] + "." for n in result.notes]
        _print_or_record([flywheel_table(result), *notes], output, force)
    if plot_file:
        save_figure(result.plot(), plot_file, force)
    return 0


def _fraction(text: str, option: str) -> float:
    try:
        parts = [float(p) for p in text.split("/")]
        if len(parts) > 2 or not all(math.isfinite(p) for p in parts):
            raise ValueError
        return parts[0] / parts[1] if len(parts) == 2 else parts[0]
    except (ValueError, ZeroDivisionError):
        raise InputError(
            "expected a number or a fraction such as 1/150", key=option, value=text
        ) from None


def register(group: click.Group) -> None:
    group.add_command(firing_orders_command)
    group.add_command(balance_command)
    group.add_command(flywheel_command)
