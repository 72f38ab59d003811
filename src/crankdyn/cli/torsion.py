"""``crankdyn torsion``: lumped torsional models and their free vibration."""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

import click

from crankdyn.cli.common import (
    check_plot_path,
    option_quantity,
    plot_option,
    save_figure,
)
from crankdyn.cli.examples import examples_alias
from crankdyn.cli.writer import (
    Output,
    TextTable,
    output_options,
    result_table,
    summary_blocks,
    summary_table,
)
from crankdyn.display import column_text
from crankdyn.errors import InputError
from crankdyn.io.catalogue import resolve_model_and_engine
from crankdyn.session import Analysis
from crankdyn.torsion.modal import SOLVERS, ModalResult
from crankdyn.torsion.mode_blocks import (
    STREAMED_SIZE,
    ModeBlocks,
    modes_csv_chunks,
    modes_json_chunks,
)

if TYPE_CHECKING:
    from crankdyn.torsion.damped import DampedModalResult
    from crankdyn.torsion.model import TorsionModel

_MODEL_HELP = (
    "MODEL_OR_ENGINE is a torsional model file, an engine file with a [torsion] section, a "
    "mass-elastic table (.csv, `crankdyn torsion table`), the name of a built-in model or of a "
    "built-in engine (`crankdyn examples`). Modes are numbered as `crankdyn torsion modes` "
    "lists them: elastic modes from 1, a free model's rigid-body mode 0."
)


@click.group("torsion")
def torsion_group() -> None:
    """Crankshaft torsional vibration: lumped models, free and forced vibration.

    Models are TOML files of masses, shafts, couplings and gears, shaft lines joined to engines
    and excitation sources (crankdyn docs torsion-file), or mass-elastic tables (.csv).
    """


def model_session(
    spec: str, *, orders: str | None = None, option: str = "--orders", **options: Any
) -> Analysis:
    """The analysis session of a MODEL_OR_ENGINE argument (with the engine when it is one),
    with the ``--orders`` text read for its cycle: a range gives the cycle's harmonics, a list
    may also hold the orders of the model's excitation sources (a propeller's blade orders)."""
    from crankdyn.cli.common import parse_orders

    model, engine = resolve_model_and_engine(spec)
    subject = engine if engine is not None else model
    if orders is not None:
        probe = Analysis(subject)
        if model is not None and model.sources and ":" not in orders:
            options["orders"] = parse_orders(
                orders, probe.cycle, option, model=model, excitation=probe.excitation()
            )
        else:
            options["orders"] = parse_orders(orders, probe.cycle, option)
    return Analysis(subject, **options)


TABLED_MODES = 20
"""How many of the lowest modes ``torsion modes`` tables by default (``--modes``)."""
SHAPE_MODES = 10
"""The most modes the mode-shape table shows (one column each)."""
DESCRIBED_NODES = 10
"""A mode with more nodes shows their number in the table (JSON and CSV locate every one)."""


def _node_text(result: ModalResult, r: int) -> str:
    """The nodes of mode row ``r``: located ones, then the round-off regions where they are
    undetermined; their number only beyond :data:`DESCRIBED_NODES`."""
    if result.free and int(result.mode[r]) == 0:
        return "rigid-body mode"
    nodes = result.nodes[r]
    if len(nodes) > DESCRIBED_NODES:
        parts = [f"{len(nodes)} nodes (--format json locates each)"]
    else:
        parts = [node.describe() for node in nodes]
    if not result.nodes_resolved[r]:
        regions = ", ".join(f"{a}…{b}" for a, b in result.roundoff_regions[r])
        parts.append(f"round-off in {regions}: nodes there undetermined")
    return "; ".join(parts) or "-"


def modes_tables(result: ModalResult, tabled: int | None = None) -> list[TextTable | str]:
    """The lowest ``tabled`` modes of ``result`` (default every one: frequency, modal inertia
    and stiffness, nodes), the shapes of the first :data:`SHAPE_MODES`, and a note of what the
    tables leave out and where it is; elastic modes numbered from 1, a free model's rigid-body
    mode 0."""
    n = result.mode.size if tabled is None else min(tabled, result.mode.size)
    # five significant digits in every cell: the modes of a long line span decades
    hz, hz_unit = column_text(result.frequencies_hz[:n], "Hz", aligned=False)
    omega, omega_unit = column_text(result.natural_frequency[:n], "rad/s", aligned=False)
    inertia, i_unit = column_text(result.modal_inertia[:n], "kg·m²", aligned=False)
    stiffness, k_unit = column_text(result.modal_stiffness[:n], "N·m/rad", aligned=False)
    rows = []
    for r in range(n):
        count = int(result.node_count[r])
        nodes = str(count) if result.nodes_resolved[r] else f"at least {count}"
        rows.append(
            [
                str(int(result.mode[r])),
                hz[r],
                omega[r],
                inertia[r],
                stiffness[r],
                nodes,
                _node_text(result, r),
            ]
        )
    summary = TextTable(
        result.model_name,
        [
            "Mode",
            f"Frequency ({hz_unit})",
            f"Angular frequency ({omega_unit})",
            f"Modal inertia ({i_unit})",
            f"Modal stiffness ({k_unit})",
            "Node count",
            "Nodes",
        ],
        rows,
        text_columns={5, 6},
        caption=f"{result.structure}, {'free' if result.free else 'grounded'}; "
        f"solver: {result.solver}; elastic modes numbered from 1"
        + (", the rigid-body mode is 0" if result.free else ""),
    )
    shown = min(n, SHAPE_MODES)
    shape_rows = [
        [name, *(f"{v:.4f}" for v in result.mode_shapes[:shown, i])]
        for i, name in enumerate(result.masses)
    ]
    shapes = TextTable(
        "Mode shapes (largest amplitude 1)",
        ["Mass", *(f"Mode {int(result.mode[r])} ({hz[r]} {hz_unit})" for r in range(shown))],
        shape_rows,
        text_columns={0},
    )
    return [summary, shapes, *_left_out(result, n, shown)]


def _left_out(result: ModalResult, n: int, shown: int) -> list[str]:
    """Notes of the modes and shapes the tables leave out (nothing is dropped unsaid)."""
    total = result.modes_of_the_model or result.mode.size
    notes = []
    if total > n:
        if result.highest_natural_frequency is not None:
            top = result.highest_natural_frequency / (2.0 * math.pi)
        else:
            top = float(result.frequencies_hz[-1])
        text, unit = column_text([top], "Hz", aligned=False)
        last = int(result.mode[0]) + total - 1
        notes.append(
            f"Modes {int(result.mode[n - 1]) + 1} to {last} (up to {text[0].strip()} {unit}) "
            f"are not listed: --modes {total} lists them; --format json or csv writes every "
            "mode with its shape and nodes."
        )
    if n > shown:
        notes.append(
            f"Mode shapes of modes {int(result.mode[shown])} to {int(result.mode[n - 1])} are "
            "not shown: --format json or csv writes them."
        )
    return notes


def damped_table(result: DampedModalResult) -> TextTable:
    """The damped modes: undamped |λ| and damped frequencies, damping ratios and logarithmic
    decrements, numbered as the undamped modes."""
    hz, hz_unit = column_text(result.natural_frequency / (2.0 * math.pi), "Hz", aligned=False)
    damped, d_unit = column_text(result.damped_frequency / (2.0 * math.pi), "Hz", aligned=False)
    rows = [
        [
            str(int(result.mode[r])),
            hz[r],
            damped[r],
            _ratio(result.damping_ratio[r]),
            _ratio(result.log_decrement[r]),
        ]
        for r in range(result.mode.size)
    ]
    return TextTable(
        f"{result.model_name}: damped modes",
        [
            "Mode",
            f"Natural frequency |λ| ({hz_unit})",
            f"Damped frequency ({d_unit})",
            "Damping ratio",
            "Logarithmic decrement",
        ],
        rows,
        caption=f"loss factors as viscous damping {result.hysteretic}; elastic modes numbered "
        "from 1" + (", the rigid-body mode is 0" if result.free else ""),
    )


def _ratio(value: float) -> str:
    return "-" if not math.isfinite(value) else f"{value:.5g}"


@torsion_group.command("modes")
@click.argument("model", metavar="MODEL_OR_ENGINE")
@click.option(
    "--solver",
    type=click.Choice(SOLVERS),
    default="eigen",
    show_default=True,
    help="Structured eigen solver (any model); Holzer or transfer matrices (chains); the closed "
    "forms (one grounded mass, two or three free masses).",
)
@plot_option("Also write the mode-shape figure (.png, .svg or .pdf).")
@plot_option(
    "Also write the schematic of the mass-elastic system (.png, .svg or .pdf): masses as blocks "
    "by inertia, shafts, couplings, gear meshes and branches.",
    param="schematic_path",
    name="--schematic",
)
@click.option(
    "--plot-modes",
    default=None,
    metavar="LIST",
    help="Mode numbers to plot, e.g. 1,2,3 (elastic modes from 1; default: the first six).",
)
@click.option(
    "--modes",
    "tabled",
    type=click.IntRange(min=1),
    default=None,
    metavar="N",
    help=f"The lowest N modes only (default: the table lists {TABLED_MODES} and the shapes of the "
    f"first {SHAPE_MODES}; --format json and csv write every mode, a large chain's a block of "
    "modes at a time).",
)
@click.option(
    "--damped",
    is_flag=True,
    help="Damped (complex) modes instead: damped frequencies, damping ratios, logarithmic "
    "decrements (loss factors at each mode's own frequency), numbered as the undamped modes.",
)
@click.option(
    "--modal-damping",
    default=None,
    metavar="LIST",
    help="With --damped: damping ratios of the elastic modes added, one for all or one per "
    "mode, e.g. 0.02 or 0.02,0.03.",
)
@output_options
def modes_command(
    model: str,
    solver: str,
    plot_path: str | None,
    schematic_path: str | None,
    plot_modes: str | None,
    tabled: int | None,
    damped: bool,
    modal_damping: str | None,
    fmt: str,
    output_path: str | None,
    force: bool,
) -> int:
    """Natural frequencies, mode shapes, nodes and modal inertias of MODEL_OR_ENGINE.

    The modes are listed ascending (the lowest --modes of them in the table, which says what it
    leaves out; every mode, or the lowest --modes, in JSON and CSV): elastic modes numbered from
    1, a free model's rigid-body mode is mode 0 (0.0 Hz). Mode shapes are normalised to a largest
    absolute amplitude of 1. The JSON and CSV of a large chain (more than a million mode-shape
    amplitudes) are computed and written a block of modes at a time, in bounded memory (crankdyn
    docs torsion-file).
    With --damped: the damped modes (complex eigenvalues of the damped system), one per mode,
    ascending, numbered the same way.
    """
    out = Output(fmt, output_path, force)
    out.check()
    chosen = _mode_list(plot_modes)
    check_plot_path(plot_path, force)
    ratios = _ratios(modal_damping)
    if ratios is not None and not damped:
        raise InputError("applies with --damped", key="--modal-damping", value=modal_damping)
    if damped and (plot_path or plot_modes or solver != "eigen"):
        key, value = next(
            (k, v)
            for k, v, given in (
                ("--plot", plot_path, plot_path),
                ("--plot-modes", plot_modes, plot_modes),
                ("--solver", solver, solver != "eigen"),
            )
            if given
        )
        raise InputError("does not apply to the damped modes", key=key, value=value)
    session = model_session(model)
    if schematic_path:
        from crankdyn.plots.schematic import plot_schematic

        assert session.model is not None  # resolve_model_and_engine always gives a model
        save_figure(plot_schematic(session.model), schematic_path, force, option="--schematic")
    if damped:
        _check_damped_json(out, session.model)
        try:
            damped_result = session.damped_modes(modal_damping=ratios)
        except InputError as exc:
            if exc.key != "modal_damping":
                raise
            raise InputError(exc.message, key="--modal-damping", value=modal_damping) from None
        out.write(
            blocks=[damped_table(damped_result)],
            json_data=damped_result,
            csv_text=damped_result.to_csv(),
        )
        return 0
    torsion_model = session.model
    assert torsion_model is not None  # resolve_model_and_engine always gives a model
    size = torsion_model.dof_inertia.size
    needed = max([*(m + 1 for m in chosen or ()), 7 if plot_path else 0], default=0)
    shown = TABLED_MODES if tabled is None else tabled
    result: ModalResult | None = None
    if out.for_people:  # the lowest modes only: a large model's shapes are N x N
        result = session.modes_by(solver, count=max(shown, needed))
    elif not streamed(torsion_model, solver, tabled):
        result = session.modes_by(solver, count=tabled)
    shapes = result
    if needed and (shapes is None or shapes.mode.size < min(needed, size)):
        shapes = session.modes_by(solver, count=needed)  # the plotted modes
    if shapes is not None and chosen is not None:
        for m in chosen:
            try:
                shapes.index(m)
            except InputError as exc:
                raise InputError(exc.message, key="--plot-modes", value=plot_modes) from None
    if result is None:  # a large chain: block by block, never N x N (ModeBlocks)
        write_streamed(out, ModeBlocks(torsion_model, tabled), warnings=session.input_warnings)
    elif out.for_people:
        out.write(
            blocks=[
                summary_table(result, f"{result.model_name}: modes"),
                *modes_tables(result, shown),
            ],
            warnings=result,
        )
    else:
        out.write(json_data=result, csv_text=result.to_csv() if out.fmt == "csv" else None)
    if plot_path and shapes is not None:
        save_figure(shapes.plot(modes=chosen), plot_path, force)
    return 0


def streamed(model: TorsionModel, solver: str, count: int | None) -> bool:
    """Whether ``torsion modes --format json/csv`` writes the modes of ``model`` block by block
    (:class:`crankdyn.torsion.modal.ModeBlocks`): a chain solved by the eigen solver with more
    than :data:`crankdyn.torsion.modal.STREAMED_SIZE` mode-shape amplitudes."""
    n = model.dof_inertia.size
    listed = n if count is None else min(count, n)
    return solver == "eigen" and model.is_chain and listed * n > STREAMED_SIZE


def write_streamed(out: Output, modes: ModeBlocks, warnings: Any = ()) -> None:
    """Write the JSON or CSV of ``modes`` (a ModeBlocks) a piece at a time: to standard output
    as it comes, or to the ``-o`` file atomically (:func:`crankdyn.io.output.atomic_file`: a
    temporary file in the target's folder, moved into place when complete), the path written
    said on stderr as :meth:`Output.write` does, and so are ``warnings`` (the model's input
    warnings)."""
    from crankdyn.io.output import atomic_file

    out.say_warnings(warnings)

    if out.fmt == "json":
        spool = None if out.path is None else str(Path(out.path).resolve().parent)
        chunks = modes_json_chunks(modes, spool_dir=spool)
    else:
        chunks = modes_csv_chunks(modes)
    if out.path is None:
        for chunk in chunks:
            click.echo(chunk, nl=False)
        return
    target = atomic_file(out.path, force=out.force)
    with target as handle:
        for chunk in chunks:
            handle.write(chunk.encode("utf-8"))
    click.echo(f"wrote {target.path}", err=True)


def _check_damped_json(out: Output, model: TorsionModel | None) -> None:
    """Refuse the JSON of a model's damped modes above
    :data:`crankdyn.torsion.damped.JSON_MAX_DOF` degrees of freedom, before the work."""
    from crankdyn.torsion.damped import JSON_MAX_DOF

    if out.fmt == "json" and model is not None and model.dof_count > JSON_MAX_DOF:
        raise InputError(
            f"the damped modes' JSON holds every complex mode shape: at most {JSON_MAX_DOF:,} "
            f"degrees of freedom, this model has {model.dof_count:,} (--format csv or table "
            "take more; crankdyn docs torsion-file)",
            key="--format",
            value="json",
        )


def _ratios(text: str | None) -> float | list[float] | None:
    if text is None:
        return None
    try:
        values = [float(t) for t in text.split(",") if t.strip()]
    except ValueError:
        values = []
    if not values:
        raise InputError(
            "expected damping ratios separated by commas, e.g. 0.02 or 0.02,0.03",
            key="--modal-damping",
            value=text,
        )
    return values[0] if len(values) == 1 else values


def _mode_list(text: str | None) -> list[int] | None:
    if text is None:
        return None
    try:
        values = [int(t) for t in text.split(",") if t.strip()]
    except ValueError:
        raise InputError(
            "expected mode numbers separated by commas, e.g. 1,2,3",
            key="--plot-modes",
            value=text,
        ) from None
    if not values:
        raise InputError("expected at least one mode number", key="--plot-modes", value=text)
    return values


@torsion_group.command("holzer")
@click.argument("model", metavar="MODEL_OR_ENGINE")
@click.option(
    "--frequency",
    required=True,
    metavar="HZ",
    help="Trial frequency (Hz for a bare number, or with a unit: '120 Hz', '7200 rpm').",
)
@plot_option("Also write the residual-torque curve with its zeros (.png, .svg or .pdf).")
@click.option(
    "--max-frequency",
    default=None,
    metavar="HZ",
    help="Upper end of the plotted curve (Hz for a bare number, or with a unit; default: 1.15 x "
    "the highest natural frequency).",
)
@output_options
def holzer_command(
    model: str,
    frequency: str,
    plot_path: str | None,
    max_frequency: str | None,
    fmt: str,
    output_path: str | None,
    force: bool,
) -> int:
    """Holzer's table of MODEL_OR_ENGINE (a chain) at a trial frequency.

    Per mass: the angle (the first mass's is 1), the inertia torque J ω² θ, the accumulated
    torque and the twist of the shaft to the next mass. The residual torque after the last mass
    vanishes at a natural frequency.
    """
    out = Output(fmt, output_path, force)
    out.check()
    f = option_quantity(frequency, "frequency", "--frequency", "Hz")
    if f < 0.0:
        raise InputError("the frequency must not be negative", key="--frequency", value=frequency)
    f_max = option_quantity(max_frequency, "frequency", "--max-frequency", "Hz")
    if f_max is not None and not f_max > 0.0:
        raise InputError(
            "the frequency must be positive", key="--max-frequency", value=max_frequency
        )
    check_plot_path(plot_path, force)
    session = model_session(model)
    try:
        table = session.holzer(2.0 * math.pi * f)
    except InputError as exc:
        if exc.key != "frequency":
            raise
        raise InputError(exc.message, key="--frequency", value=frequency) from None
    out.write(
        blocks=[result_table(table, title="Holzer's table"), *summary_blocks(table)],
        json_data=table,
        csv_text=table.to_csv(),
    )
    if plot_path:
        curve = session.residual_curve(None if f_max is None else 2.0 * math.pi * f_max)
        save_figure(curve.plot(), plot_path, force)
    return 0


@torsion_group.command("table")
@click.argument("model", metavar="MODEL_OR_ENGINE")
@click.option(
    "-o",
    "--output",
    "output_path",
    default=None,
    metavar="FILE",
    help="Write to FILE (atomically) instead of standard output.",
)
@click.option("--force", is_flag=True, help="Overwrite an existing output file.")
def table_command(model: str, output_path: str | None, force: bool) -> int:
    """Write the mass-elastic table of MODEL_OR_ENGINE (a chain) as CSV: one row per mass with
    its inertia, damping and cylinders, and the shaft, coupling or gear to the next mass, in SI
    with the unit in the header. The table read back (a .csv MODEL_OR_ENGINE) is the same
    model (crankdyn docs torsion-file)."""
    from crankdyn.io.mass_elastic import mass_elastic_csv

    out = Output("csv", output_path, force)
    out.check()
    torsion_model = model_session(model).model
    assert torsion_model is not None  # resolve_model_and_engine always gives a model
    out.write(csv_text=mass_elastic_csv(torsion_model), warnings=torsion_model.input_warnings)
    return 0


torsion_group.add_command(examples_alias("model", "torsion"))
torsion_group.help = (torsion_group.help or "") + "\n\n" + _MODEL_HELP


def register(group: click.Group) -> None:
    group.add_command(torsion_group)
