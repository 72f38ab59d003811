"""Options and output shared by the commands."""

from __future__ import annotations

import errno
import functools
import io
import math
import os
import shutil
import sys
from pathlib import Path

import click
import numpy as np
from rich.console import Console
from rich.table import Table as RichTable

from crankdyn.engine.model import Engine
from crankdyn.errors import InputError
from crankdyn.io.engine_file import resolve_engine
from crankdyn.io.output import check_writable, write_bytes, write_text
from crankdyn.io.units import parse_quantity
from crankdyn.results import Result

__all__ = [
    "FIGURE_FORMATS",
    "FORMATS",
    "angle_grid",
    "check_plot_path",
    "console",
    "emit",
    "engine_argument",
    "format_option",
    "load_engine_arg",
    "option_quantity",
    "output_options",
    "plot_option",
    "print_summary",
    "save_figure",
    "speed_of",
    "speed_option",
    "step_option",
]

FORMATS = ("table", "csv", "json")


class _PlainConsole(Console):
    """A rich console whose closed pipe is an ordinary BrokenPipeError (rich would end the
    process with status 1); crankdyn.cli.main reports it in one line."""

    def on_broken_pipe(self) -> None:
        raise BrokenPipeError(errno.EPIPE, os.strerror(errno.EPIPE))


def console(file=None, *, stderr: bool = False, record: bool = False) -> Console:
    """The one way the command line makes a rich console.

    Text is printed as written: markup is off, so user text (an engine named ``x [/] y``) needs
    no escaping anywhere; styles come from :class:`rich.text.Text` and :class:`rich.style.Style`
    objects. Standard output (or stderr with ``stderr``) is the default file; the console is
    wide enough for tables when it is not a terminal. ``record`` makes a console that renders
    to nothing and keeps the text for ``export_text()`` (160 columns), for writing to a file.
    """
    if record:
        return _PlainConsole(
            record=True, width=160, file=_Null(), markup=False, highlight=False, soft_wrap=False
        )
    width = shutil.get_terminal_size((120, 24)).columns
    return _PlainConsole(
        file=file or (sys.stderr if stderr else sys.stdout),
        width=None if stderr else max(width, 120),
        soft_wrap=False,
        highlight=False,
        markup=False,
        emoji=False,
    )


_SPEED_HELP = "Crank speed (rpm, or with a unit); default: the engine's [operating] speed."
_STEP_HELP = "Crank-angle step (deg, or with a unit); default 10 for tables, 1 otherwise."


def speed_option(help: str = _SPEED_HELP):
    """The --speed RPM option (rpm for bare numbers; the engine's speed when absent)."""
    return click.option("--speed", metavar="RPM", default=None, help=help)


def step_option(help: str = _STEP_HELP, default: str | None = None):
    """The --step DEG option (degrees for bare numbers)."""
    return click.option(
        "--step", metavar="DEG", default=default, help=help, show_default=default is not None
    )


FIGURE_FORMATS = ("png", "svg", "pdf")


def check_plot_path(path: str | None, force: bool, option: str = "--plot") -> None:
    """Refuse a figure path with an unknown format or an existing file (without --force) before
    any work is done."""
    if path is None:
        return
    suffix = Path(path).suffix.lower().lstrip(".")
    if suffix not in FIGURE_FORMATS:
        raise InputError(
            f"the plot file must end in {', '.join('.' + f for f in FIGURE_FORMATS)}",
            key=option,
            value=path,
        )
    check_writable(path, force=force)


def save_figure(fig, path: str, force: bool, option: str = "--plot", dpi: int = 120) -> Path:
    """Write a matplotlib figure atomically; the format follows the suffix (png, svg, pdf)."""
    check_plot_path(path, force, option)
    buffer = io.BytesIO()
    fig.savefig(buffer, format=Path(path).suffix.lower().lstrip("."), dpi=dpi)
    written = write_bytes(path, buffer.getvalue(), force=force)
    click.echo(f"wrote {written}", err=True)
    return written


def _checked_first(check):
    """Wrap a command so that ``check(kwargs)`` runs before its work (an output target that
    cannot be written costs no computing time)."""

    def decorate(f):
        @functools.wraps(f)
        def command(*args, **kwargs):
            check(kwargs)
            return f(*args, **kwargs)

        return command

    return decorate


def plot_option(help: str, param: str = "plot_path"):
    """The --plot FILE option: write a figure (.png, .svg or .pdf), never over an existing file
    without --force; the file is checked before the work."""

    def decorate(f):
        f = _checked_first(lambda kw: check_plot_path(kw.get(param), bool(kw.get("force", False))))(
            f
        )
        return click.option("--plot", param, default=None, metavar="FILE", help=help)(f)

    return decorate


def angle_grid(
    step_option: str | None,
    fmt: str,
    span: float = 2 * math.pi,
    default_table: float = 10.0,
    default_data: float = 1.0,
    *,
    start: float = 0.0,
    max_points: int = 1_000_000,
) -> np.ndarray:
    """Crank angles start..start+span every --step (deg when bare; the default step is coarser
    for tables); the step must divide the span."""
    default = default_table if fmt == "table" else default_data
    step = option_quantity(
        step_option if step_option is not None else default, "angle", "--step", "deg"
    )
    if not step > 0.0 or step > span:
        raise InputError(
            f"the step must lie between 0 and {math.degrees(span):g} deg",
            key="--step",
            value=step_option,
        )
    count = round(span / step)
    if abs(count * step - span) > 1e-9 * span:
        raise InputError(
            f"the step must divide {math.degrees(span):g} deg evenly",
            key="--step",
            value=step_option,
        )
    if count > max_points:
        raise InputError(
            f"the step is too small (more than {max_points} points)",
            key="--step",
            value=step_option,
        )
    return start + np.linspace(0.0, span, count + 1)


def engine_argument(f):
    return click.argument("engine", metavar="ENGINE")(f)


def format_option(default: str = "table"):
    return click.option(
        "--format",
        "fmt",
        type=click.Choice(FORMATS),
        default=default,
        show_default=True,
        help="Output format.",
    )


def _check_output(kwargs) -> None:
    output = kwargs.get("output")
    if output and output != "-":
        check_writable(output, force=bool(kwargs.get("force", False)))


def output_options(f):
    """-o/--output FILE and --force; FILE is checked before the work (crankdyn.io.output)."""
    f = _checked_first(_check_output)(f)
    f = click.option("--force", is_flag=True, help="Overwrite an existing output file.")(f)
    return click.option(
        "-o",
        "--output",
        type=str,
        default=None,
        metavar="FILE",
        help="Write to FILE (atomically) instead of standard output.",
    )(f)


def option_quantity(value, kind: str, option: str, default_unit: str | None = None):
    """Parse an option value with units; bare numbers in ``default_unit``. None passes through."""
    if value is None:
        return None
    return parse_quantity(value, kind, key=option, default_unit=default_unit)


def load_engine_arg(spec: str) -> Engine:
    return resolve_engine(spec)


def speed_of(engine: Engine, speed_option: str | None) -> float:
    """The speed (rad/s) from --speed (rpm when bare) or the engine's [operating] speed."""
    speed = option_quantity(speed_option, "speed", "--speed", "rpm")
    if speed is None:
        speed = engine.speed
    if speed is None:
        raise InputError(
            "no speed: give --speed RPM or [operating] speed in the engine file", file=engine.source
        )
    if not speed > 0.0:
        raise InputError("the speed must be positive", key="--speed", value=speed_option)
    return speed


def _fmt(value: float, scale: float = 0.0) -> str:
    if isinstance(value, str):
        return value
    if not math.isfinite(value):
        return "-"
    if abs(value) <= 1e-12 * scale:
        return "0"  # round-off next to the column's magnitude
    return f"{value:.6g}"


def render_table(result: Result, title: str | None = None) -> RichTable:
    """A rich table of a result's columns."""
    labels = result.column_labels()
    table = RichTable(title=title, show_lines=False, header_style="bold")
    cols = result.columns()
    for key in labels:
        label, unit = labels[key]
        text = cols[key].dtype.kind in "OUS"
        table.add_column(
            f"{label}\n({unit})" if unit else label, justify="left" if text else "right"
        )
    scales = [
        float(np.max(np.abs(c), initial=0.0, where=np.isfinite(c))) if c.dtype.kind in "fiu" else 0
        for c in cols.values()
    ]
    for row in zip(*cols.values(), strict=True):
        table.add_row(*(_fmt(v, s) for v, s in zip(row, scales, strict=True)))
    return table


def summary_table(result: Result, title: str = "Summary") -> RichTable:
    """A rich table of a result's scalar figures."""
    table = RichTable(title=title, header_style="bold")
    table.add_column("Quantity", justify="left")
    table.add_column("Value", justify="right")
    table.add_column("Unit", justify="left")
    for label, value, unit in result.summary_rows():  # user text may hold [brackets]
        table.add_row(label, value, unit)
    return table


def print_summary(result: Result, title: str = "Summary", out: Console | None = None) -> None:
    (out or console()).print(summary_table(result, title))


def emit(
    result: Result, fmt: str, output: str | None, force: bool, summary: Result | None = None
) -> None:
    """Write a result as a table, CSV or JSON to stdout or (atomically) to a file."""
    if fmt == "json":
        text = result.to_json() + "\n"
    elif fmt == "csv":
        text = result.to_csv()
    else:
        con = console(record=True) if output else console()
        con.print(render_table(result, getattr(result, "title", None)))
        if summary is not None:
            con.print(summary_table(summary))
        if not output:
            return
        text = con.export_text()
    if output and output != "-":
        path = write_text(output, text, force=force)
        click.echo(f"wrote {path}", err=True)
    else:
        click.echo(text, nl=False)


class _Null:
    def write(self, _text):
        return 0

    def flush(self):
        pass


def resolve_output_dir(out: str | None, default: str) -> Path:
    return Path(out or default)


def speed_range(text: str | None, option: str = "--speeds"):
    """Parse A:B:STEP (rpm when bare, units allowed on each part) into speeds in rad/s."""
    if text is None:
        return None
    parts = [p.strip() for p in text.split(":")]
    if len(parts) != 3 or not all(parts):
        raise InputError(
            "expected START:STOP:STEP, e.g. 1000:2500:25 (rpm)", key=option, value=text
        )
    start, stop, step = (option_quantity(p, "speed", option, "rpm") for p in parts)
    if start <= 0.0 or stop <= 0.0:
        raise InputError("speeds must be positive", key=option, value=text)
    if step <= 0.0:
        raise InputError("the step must be positive", key=option, value=text)
    if stop < start:
        raise InputError("the range is empty: STOP is below START", key=option, value=text)
    count = math.floor((stop - start) / step * (1 + 1e-12)) + 1
    if count > 100_000:
        raise InputError("too many speeds (more than 100000)", key=option, value=text)
    return start + step * np.arange(count)
