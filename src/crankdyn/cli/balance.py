"""``crankdyn firing-orders``, ``crankdyn balance`` and ``crankdyn flywheel``."""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import replace
from typing import Any

import click

from crankdyn.cli.common import (
    check_plot_path,
    deprecated_alias,
    display_step,
    engine_argument,
    merge_alias,
    option_quantity,
    orders_option,
    parse_orders,
    parse_speed,
    plot_option,
    save_figure,
    speed_option,
    step_option,
)
from crankdyn.cli.writer import (
    Output,
    TextTable,
    output_options,
    result_table,
    summary_table,
)
from crankdyn.constants import RPM
from crankdyn.display import column_text, format_value
from crankdyn.engine.balance import BALANCE_METHODS, BalanceResult, OrderBalance
from crankdyn.engine.firing_search import CRITERIA, FiringOrderRanking
from crankdyn.engine.model import BalanceInputs, Engine
from crankdyn.errors import InputError
from crankdyn.io.catalogue import resolve_engine
from crankdyn.session import Analysis

__all__ = ["register"]


def _numbers(text: str | None, option: str, *, integer: bool = False) -> list[Any] | None:
    """A comma- (or semicolon-) separated list of finite numbers (ints with ``integer``), or
    None for None; a bad list is an InputError naming ``option``."""
    if text is None:
        return None
    return _number_list(text, option, integer=integer)


def _number_list(text: str, option: str, *, integer: bool = False) -> list[Any]:
    """:func:`_numbers` of a text."""
    parts = [p.strip() for p in text.replace(";", ",").split(",") if p.strip()]
    try:
        values = [int(p) if integer else float(p) for p in parts]
    except ValueError:
        kind = "whole numbers" if integer else "numbers"
        raise InputError(f"expected comma-separated {kind}", key=option, value=text) from None
    if not values or not all(math.isfinite(v) for v in values):
        raise InputError("expected comma-separated finite numbers", key=option, value=text)
    return values


def _groups(text: str | None) -> list[list[Any]] | None:
    """--exhaust-groups "1,2,3;4,5,6" as lists of cylinder numbers, or None for None."""
    if text is None:
        return None
    groups = []
    for part in text.split(";"):
        if not part.strip():
            continue
        groups.append(_number_list(part, "--exhaust-groups", integer=True))
    if not groups:
        raise InputError(
            'expected groups such as "1,2,3;4,5,6"', key="--exhaust-groups", value=text
        )
    return groups


def _sentence(text: str) -> str:
    """A note as a sentence: a capital first letter and a full stop."""
    return text[0].upper() + text[1:] + ("" if text.endswith(".") else ".")


# ---- firing-orders ----------------------------------------------------------------------------

_HEADERS = {
    "free_force_1": "Free force, 1st order (per m_j R ω²)",
    "free_force_2": "Free force, 2nd order (per m_j R ω² A₂)",
    "free_moment_1": "Free moment, 1st order (per m_j R ω² a)",
    "free_moment_2": "Free moment, 2nd order (per m_j R ω² A₂ a)",
    "adjacent_consecutive": "Adjacent cylinders firing in a row",
    "main_bearing_min_interval_deg": "Shortest gap next to a main bearing (deg)",
    "torsional_vector_sum": "Largest torsional vector sum",
    "exhaust_min_interval_deg": "Shortest gap in an exhaust group (deg)",
}


def _intervals_text(values: Iterable[float]) -> str:
    """Firing intervals (deg): ``120 × 6`` when all are equal, else each."""
    rounded = [round(float(v), 6) for v in values]
    if len(set(rounded)) == 1:
        return f"{rounded[0]:g} × {len(rounded)}"
    return " ".join(f"{v:g}" for v in rounded)


def ranking_table(result: FiringOrderRanking, limit: int | None = None) -> TextTable:
    """The ranked firing orders (the even-interval criterion is in the intervals column).

    Parameters
    ----------
    result
        The ranking.
    limit
        The most firing orders shown; None: all.

    Returns
    -------
    TextTable
        One row per firing order: rank (``*`` marks the engine's own), order, intervals (deg)
        and each criterion.
    """
    crit = [c for c in result.criteria if c != "interval_deviation_deg"]
    shown = result.candidates if limit is None else result.candidates[:limit]
    dicts = [c.to_dict() for c in shown]
    header = ["Rank", "Firing order", "Firing intervals (deg)"]
    columns = [
        [f"{c.rank}{'*' if result.engine_rank == c.rank else ''}" for c in shown],
        [c.order_text for c in shown],
        [_intervals_text(d["firing_intervals_deg"]) for d in dicts],
    ]
    for c in crit:
        values: list[Any] = [d.get(c) for d in dicts]
        header.append(_HEADERS.get(c, CRITERIA[c].label if c in CRITERIA else c))
        if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
            texts, _unit = column_text([float(v) for v in values], reference=1.0)
            if all(isinstance(v, int) for v in values):
                texts = [str(v) for v in values]
        else:
            texts = ["-" if v is None else str(v) for v in values]
        columns.append(texts)
    text_columns = {1, 2}
    if any(c.v_scheme for c in result.candidates):
        header.append("V scheme")
        columns.append([c.v_scheme or "" for c in shown])
        text_columns.add(len(header) - 1)
    rows = [list(r) for r in zip(*columns, strict=True)] if shown else []
    return TextTable(f"{result.engine}: firing orders", header, rows, text_columns)


def _ranking_notes(result: FiringOrderRanking, shown: int) -> list[str]:
    """The lines under the ranking: counts, the engine's own order's rank, the units."""
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
            "lists more."
        )
    lines.extend(_sentence(n) for n in result.notes[1:])
    lines.append(
        "Free forces per m_j R ω² Aₙ and moments per m_j R ω² Aₙ a (a = cylinder pitch) of the "
        "reciprocating masses."
    )
    return lines


_OPTION_OF = {
    "priority": "--rank-by",
    "mode_shape": "--mode-shape",
    "orders": "--orders",
    "torsion_orders": "--orders",
    "exhaust_groups": "--exhaust-groups",
    "search": "--any-crankshaft",
    "include_uneven": "--all",
}


def _mode_shape(eng: Engine, text: str | None) -> list[Any] | None:
    """--mode-shape: the amplitudes given, or None for the first mode of the engine's
    [torsion] model (``torsion`` or no option)."""
    if text is None or text.strip().lower() != "torsion":
        return _numbers(text, "--mode-shape")
    if eng.torsion is None:
        raise InputError(
            "the engine file has no [torsion] model to take the first mode from; give the "
            "amplitudes",
            key="--mode-shape",
            value=text,
        )
    return None  # the session takes the first mode of the engine's [torsion] model


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
    "comma-separated, for the torsional vector sum; default (or 'torsion'): the first mode of "
    "the engine's [torsion] model when it has one.",
)
@orders_option(
    "Orders of the torsional criterion, e.g. 0.5:3 or 1.5,3 (default: the minor orders)."
)
@deprecated_alias("--torsion-orders", "--orders", "torsion_orders", "LIST")
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
@click.option("--top", type=int, default=None, metavar="N", help="Keep the best N firing orders.")
@plot_option("Also write the crank end view and firing diagram of the best (.png, .svg or .pdf).")
@output_options
def firing_orders_command(
    engine: str,
    any_crankshaft: bool,
    include_uneven: bool,
    mode_shape: str | None,
    orders: str | None,
    torsion_orders: str | None,
    exhaust_groups: str | None,
    rank_by: str | None,
    top: int | None,
    plot_path: str | None,
    fmt: str,
    output_path: str | None,
    force: bool,
) -> int:
    """Enumerate the firing orders ENGINE's crankshaft allows and rank them (seed 000 §2.3)."""
    out = Output(fmt, output_path, force)
    out.check()
    check_plot_path(plot_path, force)
    orders = merge_alias(orders, torsion_orders, "--orders", "--torsion-orders")
    eng = resolve_engine(engine)
    session = Analysis(eng)
    if top is not None and top < 1:
        raise InputError("must be at least 1", key="--top", value=top)
    priority = None
    if rank_by is not None:
        priority = [p.strip() for p in rank_by.split(",") if p.strip()]
        if not priority:
            raise InputError("expected criterion names", key="--rank-by", value=rank_by)
    order_list = parse_orders(orders, eng.cycle)
    try:
        result = session.firing_orders(
            any_crankshaft=any_crankshaft,
            include_uneven=True if include_uneven else None,
            mode_shape=_mode_shape(eng, mode_shape),
            orders=None if order_list is None else [float(q) for q in order_list],
            exhaust_groups=_groups(exhaust_groups),
            priority=priority,
            top=top,
        )
    except InputError as exc:
        if exc.key in _OPTION_OF and exc.file is None:
            extra: dict[str, Any] = {"value": exc.value} if exc.has_value else {}
            raise InputError(exc.message, key=_OPTION_OF[exc.key], **extra) from None
        raise
    limit = top if top is not None else 30
    shown = min(limit, len(result.candidates))
    out.write(
        blocks=[ranking_table(result, limit), *_ranking_notes(result, shown)],
        json_data=result.ranked_list(),
        csv_text=result.to_csv(),
    )
    if plot_path:
        if not result.candidates:
            raise InputError("no firing order to plot", key="--plot", value=plot_path)
        save_figure(result.plot(), plot_path, force)
    return 0


# ---- balance ----------------------------------------------------------------------------------


def _row_name(row: OrderBalance) -> str:
    """The Order cell of a balance row: the order, ``1 rotating`` or ``1 total``."""
    if row.source == "reciprocating":
        return str(row.order)
    return "1 rotating" if row.source == "rotating" else "1 total"


def balance_table(result: BalanceResult, unit_force: float, pitch: float | None) -> TextTable:
    """The free forces and moments by order: forces and moments in engineering units, round-off
    next to the unit force m_j R ω² (and moment m_j R ω² a) as 0.

    Parameters
    ----------
    result
        The balance.
    unit_force
        m_j R ω², the reference of the force columns (N).
    pitch
        The cylinder pitch a (m), for the moments' reference m_j R ω² a; None: 1 m.

    Returns
    -------
    TextTable
        One row per order (then ``1 rotating`` and ``1 total``).
    """
    rows = result.rows()
    moment_ref = unit_force * (pitch or 1.0)
    spec = [
        ("Free force", "N", lambda r: r.free_force, unit_force),
        ("Free force, vertical", "N", lambda r: r.free_force_vertical, unit_force),
        ("Free force, horizontal", "N", lambda r: r.free_force_horizontal, unit_force),
        ("Free moment", "N·m", lambda r: r.free_moment, moment_ref),
        ("Free moment, vertical plane", "N·m", lambda r: r.free_moment_vertical, moment_ref),
        ("Free moment, horizontal plane", "N·m", lambda r: r.free_moment_horizontal, moment_ref),
        ("Free force per m_j R ω²", "", lambda r: r.force_coefficient, 1.0),
        ("Free moment per m_j R ω² a", "", lambda r: r.moment_coefficient, 1.0),
    ]
    if result.power:
        spec.append(
            (
                "Moment per power",
                "N·m/kW",
                lambda r: (
                    None if r.power_related_unbalance is None else r.power_related_unbalance * 1e3
                ),
                moment_ref / result.power * 1e3,
            )
        )
    header = ["Order"]
    columns = [[_row_name(r) for r in rows]]
    for label, unit, get, ref in spec:
        values = [get(r) for r in rows]
        floats = [math.nan if v is None else float(v) for v in values]
        texts, shown = column_text(floats, unit, reference=ref)
        header.append(f"{label} ({shown})" if shown else label)
        columns.append(texts)
    title = f"{result.engine}: free forces and moments at {result.speed * RPM:.0f} rpm"
    return TextTable(title, header, [list(r) for r in zip(*columns, strict=True)], {0})


def _balance_notes(result: BalanceResult) -> list[str]:
    """The lines under the balance table: the masses, what the rows are, the overturning
    moment, the result's notes."""
    lines = [
        f"m_j = {format_value(result.reciprocating_mass)[0]} kg per cylinder; rotating "
        f"{format_value(result.rotating_mass)[0]} kg per throw; counterweights c = "
        f"{result.counterweight_ratio:g}, b = {result.reciprocating_balance_ratio:g}; "
        f"harmonics: {result.method}.",
        "Orders 1, 2, ...: reciprocating masses; '1 rotating': rotating masses and "
        "counterweights; '1 total': both. Amplitudes are the largest magnitude over one "
        "revolution; moments about the middle of the engine; vertical plane = pitching moment "
        "(from vertical forces), horizontal plane = yawing moment.",
    ]
    if result.overturning is not None:
        o = result.overturning
        mean, mean_unit = format_value(o.mean, "N·m")
        amp, amp_unit = format_value(o.amplitude, "N·m")
        ptp, ptp_unit = format_value(o.peak_to_peak, "N·m")
        lines.append(
            f"Overturning moment: steady {mean} {mean_unit}, fluctuation up to {amp} {amp_unit} "
            f"(peak to peak {ptp} {ptp_unit})."
        )
    lines.extend(_sentence(n) for n in result.notes)
    return lines


@click.command("balance")
@engine_argument
@speed_option()
@orders_option(
    "Orders of the reciprocating masses, whole numbers: e.g. 1:8 or 1,2,4,6 (default 1,2,4,6; "
    "1:6 for offset engines)."
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
    metavar="C",
    help="Counterweight per throw as a fraction of its rotating unbalance (default: the "
    "file's [balance], else 0).",
)
@click.option(
    "--reciprocating-balance-ratio",
    type=float,
    default=None,
    metavar="B",
    help="Share of the reciprocating mass added to each counterweight (default: file, else 0).",
)
@click.option(
    "--rod-offset",
    default=None,
    metavar="MM",
    help="Axial offset of the bank-B rod from the bank-A rod on a V throw (mm, or with a unit); "
    "default: the file's [balance], else 0.",
)
@click.option(
    "--power",
    default=None,
    metavar="KW",
    help="Engine power for the power-related unbalance (kW, or with a unit); default: the "
    "file's [balance], else the torque analysis's.",
)
@click.option(
    "--no-torque",
    is_flag=True,
    help="Leave out the overturning moment (and the power from the torque analysis).",
)
@plot_option("Also write the free-force and free-moment polar plots (.png, .svg or .pdf).")
@output_options
def balance_command(
    engine: str,
    speed: str | None,
    orders: str | None,
    method: str,
    counterweight_ratio: float | None,
    reciprocating_balance_ratio: float | None,
    rod_offset: str | None,
    power: str | None,
    no_torque: bool,
    plot_path: str | None,
    fmt: str,
    output_path: str | None,
    force: bool,
) -> int:
    """Free forces and moments of ENGINE's mass forces, order by order (seed 000 §2.2)."""
    out = Output(fmt, output_path, force)
    out.check()
    check_plot_path(plot_path, force)
    eng = resolve_engine(engine)
    session = Analysis(eng, speed=parse_speed(speed))
    inputs = eng.balance or BalanceInputs()
    changes: dict[str, float] = {}
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
    order_list = parse_orders(orders, eng.cycle, whole=True)
    result = session.balance(
        orders=None if order_list is None else tuple(order_list),
        method=method,
        inputs=replace(inputs, **changes) if changes else None,
        overturning=not no_torque,
    )
    unit_force = result.reciprocating_mass * eng.geometry.crank_radius * session.speed**2
    out.write(
        blocks=[balance_table(result, unit_force, result.pitch), *_balance_notes(result)],
        json_data=result,
        csv_text=result.to_csv(),
    )
    if plot_path:
        save_figure(result.plot(), plot_path, force)
    return 0


# ---- flywheel ---------------------------------------------------------------------------------


@click.command("flywheel")
@engine_argument
@speed_option("Mean crank speed (rpm for a bare number, or with a unit); default: the file's own.")
@click.option(
    "--delta",
    default=None,
    metavar="X",
    help="Target degree of cyclic irregularity (ω_max − ω_min)/ω_m, e.g. 0.01 or 1/150 "
    "(default: the file's [flywheel] delta, else 0.01).",
)
@click.option(
    "--inertia",
    default=None,
    metavar="KGM2",
    help="A given flywheel's inertia (kg·m², or with a unit), to find the δ it gives; default: "
    "none (the flywheel for the target δ).",
)
@step_option(
    "Crank-angle step of the rows of the torque, excess-work and speed curves (deg for a bare "
    "number); must divide the cycle; default 10 for tables, the analysis step (1) otherwise."
)
@plot_option("Also write the torque, energy swing and crank speed figure (.png, .svg or .pdf).")
@output_options
def flywheel_command(
    engine: str,
    speed: str | None,
    delta: str | None,
    inertia: str | None,
    step: str | None,
    plot_path: str | None,
    fmt: str,
    output_path: str | None,
    force: bool,
) -> int:
    """Speed fluctuation of ENGINE and the flywheel for a target δ (seed 000 §2.4)."""
    out = Output(fmt, output_path, force)
    out.check()
    check_plot_path(plot_path, force)
    target = None if delta is None else _fraction(delta, "--delta")
    if target is not None and not 0.0 < target < 1.0:
        raise InputError("δ must lie between 0 and 1, e.g. 0.01", key="--delta", value=delta)
    given = option_quantity(inertia, "inertia", "--inertia", "kg*m^2")
    if given is not None and not given > 0.0:
        raise InputError("the inertia must be positive", key="--inertia", value=inertia)
    eng = resolve_engine(engine)
    session = Analysis(eng, speed=parse_speed(speed))
    h = display_step(step, fmt, eng.cycle_angle)
    result = session.flywheel(delta=target, inertia=given, step=h)
    summary = [r for r in result.summary_rows() if r[0] not in ("Engine", "Notes")]
    notes = [_sentence(n) for n in result.notes]
    if target is None and given is None and session.flywheel_default_delta():
        notes.append("The target δ is the default 0.01 (give --delta or [flywheel] delta).")
    blocks: list[TextTable | str] = [
        summary_table(summary, f"{eng.name}: speed fluctuation and flywheel"),
        *notes,
    ]
    if step is not None:
        blocks.insert(0, result_table(result, title="Torque, excess work and crank speed"))
    out.write(blocks=blocks, json_data=result, csv_text=result.to_csv())
    if plot_path:
        save_figure(result.plot(), plot_path, force)
    return 0


def _fraction(text: str, option: str) -> float:
    """A number or a fraction such as 1/150; anything else is an InputError naming ``option``."""
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
    """Add ``firing-orders``, ``balance`` and ``flywheel`` to the command ``group``."""
    group.add_command(firing_orders_command)
    group.add_command(balance_command)
    group.add_command(flywheel_command)
