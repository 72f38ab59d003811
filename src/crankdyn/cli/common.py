"""The command line's one vocabulary (docs/cli.md): the options every command shares and how
they are read.

- a bare ``--speed`` number is rpm in every command (a unit may be given: "50 Hz", "300 rad/s");
  the engine's (or the file's) own speed is the default wherever a speed is needed;
- every speed range is ``--speeds LOW:HIGH[:STEP]`` (rpm when bare; the step defaults to the
  analysis session's, 10 rpm);
- every order list is ``--orders`` in one grammar: ``FIRST:LAST[:STEP]`` or ``1.5,3,4.5``;
- ``--step DEG`` sets the crank-angle step of the rows shown or written (summaries always come
  from the full-resolution analysis);
- ``--plot FILE`` writes the command's figure (.png, .svg or .pdf);
- a torsiograph signal is read with ``--teeth N`` pulses per revolution from the wheel on the
  torsional model's mass ``--at MASS`` (``measure``, ``analyze --measurement``);
- ``--format table|csv|json``, ``-o/--output FILE`` and ``--force`` (:mod:`crankdyn.cli.writer`);
- every command that prints a verdict takes ``--rules KEY`` (the classification society's rule
  set, where the command judges by one) and ``--no-fail``, and exits with status 0 when every
  verdict passed, 1 when one failed (its output written), 2 on an error (:func:`verdict_status`);
- renamed options stay as hidden aliases that print a deprecation line.
"""

from __future__ import annotations

import errno
import functools
import io
import math
import os
import shutil
import sys
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import IO, TYPE_CHECKING, Any, Protocol, TypeVar, cast, overload

import click
import numpy as np
from numpy.typing import NDArray

from crankdyn.errors import InputError
from crankdyn.io.output import check_writable, write_bytes
from crankdyn.io.units import parse_quantity

if TYPE_CHECKING:
    from matplotlib.figure import Figure as MplFigure
    from rich.console import Console

F = TypeVar("F", bound=Callable[..., Any])
"""A command callback (or a click command) being decorated."""


class Decorator(Protocol):
    """What the option factories return: a decorator that adds an option to a command."""

    def __call__(self, f: F, /) -> F:
        """Add the option to the command callback ``f`` and return it."""
        ...


__all__ = [
    "FIGURE_FORMATS",
    "PIPE_WIDTH",
    "at_option",
    "before_work",
    "check_plot_path",
    "console",
    "deprecated_alias",
    "display_step",
    "engine_argument",
    "merge_alias",
    "option_quantity",
    "orders_option",
    "parse_orders",
    "parse_speed",
    "parse_speeds",
    "plot_option",
    "save_figure",
    "speed_option",
    "speeds_option",
    "stdout_width",
    "step_option",
    "teeth_option",
    "warn",
]


@functools.cache
def _plain_console_class() -> type[Console]:
    """The rich console class of the command line, made on first use: rich is imported only
    by a command that prints through it (:func:`console`)."""
    from rich.console import Console

    class _PlainConsole(Console):
        """A rich console whose closed pipe is an ordinary BrokenPipeError (rich would end the
        process with status 1); crankdyn.cli.main reports it in one line."""

        def on_broken_pipe(self) -> None:
            """Raise BrokenPipeError (rich would exit with status 1)."""
            raise BrokenPipeError(errno.EPIPE, os.strerror(errno.EPIPE))

    return _PlainConsole


PIPE_WIDTH = 120
"""Width of the tables written to a pipe or a file (not a terminal)."""


def stdout_width() -> int:
    """The width of a console on standard output (what :func:`console` gives standard output
    by default): a terminal's own width (``COLUMNS`` where set), so that a table never runs
    past its right edge; :data:`PIPE_WIDTH` (or ``COLUMNS``, if wider) for a pipe or a file.

    Returns
    -------
    int
        The width in columns.
    """
    columns = shutil.get_terminal_size((PIPE_WIDTH, 24)).columns
    stream = getattr(sys.stdout, "rich_proxied_file", sys.stdout)
    try:
        terminal = bool(stream is not None and stream.isatty())
    except (AttributeError, ValueError, OSError):  # no such method, or closed
        terminal = False
    if terminal:
        return max(columns, 20)
    return max(columns, PIPE_WIDTH)


def console(
    file: IO[str] | None = None, *, stderr: bool = False, width: int | None = None
) -> Console:
    """The one way the command line makes a rich console.

    Text is printed as written: markup is off, so user text (an engine named ``x [/] y``) needs
    no escaping anywhere; styles come from :class:`rich.text.Text` and :class:`rich.style.Style`
    objects. Standard output (or stderr with ``stderr``) is the default file; the console is
    ``width`` columns wide, by default wide enough for tables when it is not a terminal. A
    closed pipe is an ordinary BrokenPipeError (crankdyn.cli.main reports it in one line).

    Parameters
    ----------
    file
        The text stream to print to; default standard output (standard error with ``stderr``).
    stderr
        Print to standard error when no ``file`` is given.
    width
        The width in columns; default :func:`stdout_width` on standard output (no limit
        given on standard error).

    Returns
    -------
    rich.console.Console
        A console with markup, highlighting and emoji off.

    Examples
    --------
    >>> out = io.StringIO()
    >>> console(out).print("an engine named x [/] y")
    >>> out.getvalue()
    'an engine named x [/] y\\n'
    """
    if width is None and not stderr:
        width = stdout_width()
    return _plain_console_class()(
        file=file or (sys.stderr if stderr else sys.stdout),
        width=width,
        soft_wrap=False,
        highlight=False,
        markup=False,
        emoji=False,
    )


def warn(message: str) -> None:
    """One line on stderr: ``crankdyn: warning: ...``.

    Parameters
    ----------
    message
        The warning; runs of white space (line breaks included) become one space, other
        control characters are shown escaped.
    """
    from crankdyn.display import printable

    click.echo(f"crankdyn: warning: {printable(' '.join(str(message).split()))}", err=True)


@overload
def option_quantity(
    value: None, kind: str, option: str, default_unit: str | None = None
) -> None: ...


@overload
def option_quantity(
    value: str | float, kind: str, option: str, default_unit: str | None = None
) -> float: ...


@overload
def option_quantity(
    value: object, kind: str, option: str, default_unit: str | None = None
) -> float | None: ...


def option_quantity(
    value: object, kind: str, option: str, default_unit: str | None = None
) -> float | None:
    """Parse an option value with units; bare numbers in ``default_unit``. None passes through.

    Parameters
    ----------
    value
        The option's text (``"1500"``, ``"50 Hz"``), a number, or None.
    kind
        The quantity's kind in :mod:`crankdyn.io.units` (``"speed"``, ``"angle"``, ...).
    option
        The option's name (``--speed``), named in an error's message.
    default_unit
        The unit of a bare number; None: a bare number is already SI.

    Returns
    -------
    float or None
        The value in SI units of ``kind`` (rad/s, rad, ...), or None for None.

    Raises
    ------
    InputError
        On a malformed value or a unit of another kind, naming ``option`` and the value.

    Examples
    --------
    >>> round(option_quantity("50 Hz", "speed", "--speed", "rpm"), 6)
    314.159265
    >>> round(option_quantity("600", "speed", "--speed", "rpm"), 6)
    62.831853
    """
    if value is None:
        return None
    return parse_quantity(value, kind, key=option, default_unit=default_unit)


# ---- arguments ----------------------------------------------------------------------------------
def engine_argument(f: F) -> F:
    """ENGINE: an engine file or the name of a built-in engine.

    Parameters
    ----------
    f
        The command callback; it receives the argument as ``engine`` (the text given).

    Returns
    -------
    callable
        ``f`` with the argument added.
    """
    return click.argument("engine", metavar="ENGINE")(f)


# ---- speeds -------------------------------------------------------------------------------------
_SPEED_HELP = "Crank speed (rpm for a bare number, or with a unit); default: the file's own."


def speed_option(help: str = _SPEED_HELP, param: str = "speed") -> Decorator:
    """``--speed RPM``: rpm for a bare number in every command.

    Parameters
    ----------
    help
        The option's help text; default: a crank speed, rpm when bare, default the file's own.
    param
        The name of the callback's parameter that receives the text (read it with
        :func:`parse_speed`).

    Returns
    -------
    callable
        A decorator that adds the option to a command.
    """
    return click.option("--speed", param, metavar="RPM", default=None, help=help)


def parse_speed(text: str | None, option: str = "--speed") -> float | None:
    """A --speed value in rad/s (rpm when bare); None passes through.

    Parameters
    ----------
    text
        The option's text (``"1500"``, ``"50 Hz"``, ``"300 rad/s"``) or None.
    option
        The option's name, named in an error's message.

    Returns
    -------
    float or None
        The speed (rad/s), or None when ``text`` is None.

    Raises
    ------
    InputError
        On a malformed speed or one that is not positive and finite, naming ``option`` and
        ``text``.

    Examples
    --------
    >>> round(parse_speed("1500"), 6)
    157.079633
    >>> parse_speed("-3")
    Traceback (most recent call last):
    ...
    crankdyn.errors.InputError: --speed = "-3": the speed must be positive
    """
    w = option_quantity(text, "speed", option, "rpm")
    if w is not None and not (math.isfinite(w) and w > 0.0):
        raise InputError("the speed must be positive", key=option, value=text)
    return w


def speeds_option(help: str | None = None) -> Decorator:
    """``--speeds LOW:HIGH[:STEP]``: a speed range (rpm for bare numbers).

    Parameters
    ----------
    help
        The option's help text; default: the sweep's range, rpm when bare, default the model's
        operating range every 10 rpm. The callback's parameter is ``speeds`` (read it with
        :func:`parse_speeds` or :func:`speed_sweep`).

    Returns
    -------
    callable
        A decorator that adds the option to a command.
    """
    return click.option(
        "--speeds",
        metavar="LOW:HIGH[:STEP]",
        default=None,
        help=help
        or "Speed range of the sweep (rpm for bare numbers), e.g. 1000:2500 or 1000:2500:25; "
        "default: the model's operating range every 10 rpm.",
    )


@overload
def parse_speeds(text: None, option: str = "--speeds", *, need_step: bool = False) -> None: ...


@overload
def parse_speeds(
    text: str, option: str = "--speeds", *, need_step: bool = False
) -> tuple[float, float, float | None]: ...


@overload
def parse_speeds(
    text: str | None, option: str = "--speeds", *, need_step: bool = False
) -> tuple[float, float, float | None] | None: ...


def parse_speeds(
    text: str | None, option: str = "--speeds", *, need_step: bool = False
) -> tuple[float, float, float | None] | None:
    """LOW:HIGH[:STEP] as (low, high, step or None) in rad/s; None passes through.

    Parameters
    ----------
    text
        The option's text, each part rpm when bare or with a unit (``"1000:2500:25"``,
        ``"10 Hz:40 Hz"``), or None.
    option
        The option's name, named in an error's message.
    need_step
        Whether the step is required.

    Returns
    -------
    tuple of (float, float, float or None), or None
        The low and high speeds and the step (rad/s; None when not given), or None when
        ``text`` is None.

    Raises
    ------
    InputError
        On a malformed range, a speed or step that is not positive, or HIGH below LOW, naming
        ``option`` and ``text``.

    Examples
    --------
    >>> [round(v * 30 / math.pi, 6) for v in parse_speeds("1000:2500:25")]
    [1000.0, 2500.0, 25.0]
    >>> parse_speeds("2500:1000")
    Traceback (most recent call last):
    ...
    crankdyn.errors.InputError: --speeds = "2500:1000": the range is empty: HIGH is below LOW
    """
    if text is None:
        return None
    parts = [p.strip() for p in str(text).split(":")]
    if len(parts) not in (2, 3) or not all(parts) or (need_step and len(parts) != 3):
        expected = "LOW:HIGH:STEP" if need_step else "LOW:HIGH[:STEP]"
        raise InputError(f"expected {expected}, e.g. 1000:2500:25 (rpm)", key=option, value=text)
    values = [parse_quantity(p, "speed", key=option, default_unit="rpm") for p in parts]
    low, high = values[0], values[1]
    step = values[2] if len(values) == 3 else None
    if not (low > 0.0 and high > 0.0):
        raise InputError("speeds must be positive", key=option, value=text)
    if high < low:
        raise InputError("the range is empty: HIGH is below LOW", key=option, value=text)
    if step is not None and not step > 0.0:
        raise InputError("the step must be positive", key=option, value=text)
    return low, high, step


def speed_sweep(text: str | None, option: str = "--speeds") -> NDArray[np.float64] | None:
    """--speeds as an array of speeds (rad/s), or None for the session's default sweep.

    Parameters
    ----------
    text
        The option's text (:func:`parse_speeds`) or None.
    option
        The option's name, named in an error's message.

    Returns
    -------
    numpy.ndarray or None
        The speeds (rad/s), ascending, every STEP (default the session's 10 rpm,
        :func:`crankdyn.session.speed_grid`); one speed when LOW equals HIGH; None when
        ``text`` is None.

    Raises
    ------
    InputError
        On a malformed range (:func:`parse_speeds`) or one of more than 100000 speeds, naming
        ``option`` and ``text``.

    Examples
    --------
    >>> (speed_sweep("1000:1030") * 30 / math.pi).round(6).tolist()
    [1000.0, 1010.0, 1020.0, 1030.0]
    """
    parsed = parse_speeds(text, option)
    if parsed is None:
        return None
    from crankdyn.session import SPEED_STEP, speed_grid

    low, high, step = parsed
    if high == low:
        return np.array([low])
    try:
        return speed_grid(low, high, SPEED_STEP if step is None else step)
    except InputError as exc:
        raise InputError(exc.message, key=option, value=text) from None


# ---- orders -------------------------------------------------------------------------------------
ORDERS_METAVAR = "LIST"


def orders_option(help: str, param: str = "orders") -> Decorator:
    """``--orders LIST``: ``FIRST:LAST[:STEP]`` or a comma-separated list.

    Parameters
    ----------
    help
        The option's help text (the command's default orders).
    param
        The name of the callback's parameter that receives the text (read it with
        :func:`parse_orders`).

    Returns
    -------
    callable
        A decorator that adds the option to a command.
    """
    return click.option("--orders", param, default=None, metavar=ORDERS_METAVAR, help=help)


def parse_orders(
    text: str | None,
    cycle: str = "four-stroke",
    option: str = "--orders",
    *,
    whole: bool = False,
    model: Any = None,
    excitation: Any = None,
) -> list[int] | NDArray[np.float64] | None:
    """An order list: ``FIRST:LAST[:STEP]`` (the step defaults to the cycle's fundamental
    order: 0.5 four-stroke, 1 two-stroke; 1 for ``whole`` orders) or ``1.5,3,4.5``; None
    passes through.

    Parameters
    ----------
    text
        The option's text or None.
    cycle
        ``"four-stroke"`` or ``"two-stroke"``: the orders must be multiples of its fundamental
        order (:func:`crankdyn.torsion.excitation.check_orders`).
    option
        The option's name, named in an error's message.
    whole
        Whole numbers from 1 to 64 (the balance's orders) instead of the cycle's orders.
    model
        A torsional model (:class:`crankdyn.torsion.model.TorsionalModel`): a list may then
        also hold the orders of the model's excitation sources (a propeller's blade orders, a
        machine's harmonics; :func:`crankdyn.torsion.sources.check_model_orders`).
    excitation
        The model's excitation, with ``model``.

    Returns
    -------
    list of int, numpy.ndarray or None
        The whole orders (``whole``), the orders (dimensionless, per revolution) in the order
        given, or None when ``text`` is None.

    Raises
    ------
    InputError
        On a malformed list, or an order that is not positive, repeated or not an order of the
        cycle (or of the model's sources), naming ``option`` and ``text``.

    Examples
    --------
    >>> parse_orders("0.5:2").tolist()
    [0.5, 1.0, 1.5, 2.0]
    >>> parse_orders("1:4", whole=True)
    [1, 2, 3, 4]
    >>> parse_orders("1,1")
    Traceback (most recent call last):
    ...
    crankdyn.errors.InputError: --orders = "1,1": orders must be distinct
    """
    if text is None:
        return None
    ranged = ":" in text
    try:
        parts = [float(p) for p in (text.split(":") if ranged else text.split(",")) if p.strip()]
    except ValueError:
        parts = []
    if not parts or (ranged and len(parts) not in (2, 3)) or not all(map(math.isfinite, parts)):
        raise InputError(
            "expected FIRST:LAST[:STEP] or a list of orders, e.g. 0.5:12 or 1.5,3,4.5,6",
            key=option,
            value=text,
        )
    if whole:
        if ranged:
            step = parts[2] if len(parts) == 3 else 1.0
            count = math.floor((parts[1] - parts[0]) / step * (1 + 1e-12)) + 1 if step > 0 else 0
            values = [parts[0] + step * k for k in range(max(count, 0))]
        else:
            values = parts
        if not values or any(v != round(v) or not 1 <= v <= 64 for v in values):
            raise InputError("orders must be whole numbers from 1 to 64", key=option, value=text)
        return [round(v) for v in values]
    from crankdyn.torsion.orders import check_orders, fundamental_order, order_grid

    try:
        if ranged:
            step = parts[2] if len(parts) == 3 else fundamental_order(cycle)
            return order_grid(parts[0], parts[1], step, cycle)
        if model is not None:
            from crankdyn.torsion.sources import check_model_orders

            return check_model_orders(model, excitation, parts, key=option)
        return check_orders(parts, cycle, key=option)
    except InputError as exc:
        raise InputError(exc.message, key=option, value=text) from None


# ---- measurements -------------------------------------------------------------------------------
_TEETH_HELP = (
    "Pulses per revolution of the wheel (for a sampled speed signal: angle samples per "
    "revolution, default automatic)."
)
_AT_HELP = "The torsional model's mass that carries the wheel, e.g. pulley."


def teeth_option(help: str = _TEETH_HELP) -> Decorator:
    """``--teeth N``: the pulses per revolution of a torsiograph's wheel.

    Parameters
    ----------
    help
        The option's help text. The callback's parameter is ``teeth`` (an int or None).

    Returns
    -------
    callable
        A decorator that adds the option to a command.
    """
    return click.option("--teeth", type=int, default=None, metavar="N", help=help)


def at_option(help: str = _AT_HELP) -> Decorator:
    """``--at MASS``: the mass of the torsional model that carries the measuring wheel.

    Parameters
    ----------
    help
        The option's help text. The callback's parameter is ``mass`` (the mass's name or None).

    Returns
    -------
    callable
        A decorator that adds the option to a command.
    """
    return click.option("--at", "mass", default=None, metavar="MASS", help=help)


# ---- crank-angle steps --------------------------------------------------------------------------
_STEP_HELP = (
    "Crank-angle step of the rows (deg for a bare number, or with a unit); must divide the "
    "cycle; default 10 for tables, the analysis step (1) otherwise. Summaries always come "
    "from the full analysis."
)


def step_option(help: str = _STEP_HELP, default: str | None = None) -> Decorator:
    """``--step DEG``: the crank-angle step of the rows shown or written.

    Parameters
    ----------
    help
        The option's help text.
    default
        The default text (deg when bare), shown in the help; None: the command's own default
        (:func:`display_step`). The callback's parameter is ``step``.

    Returns
    -------
    callable
        A decorator that adds the option to a command.
    """
    return click.option(
        "--step", metavar="DEG", default=default, help=help, show_default=default is not None
    )


def display_step(
    text: str | None, fmt: str, span: float, *, table_default: float = 10.0
) -> float | None:
    """The --step of the rows (rad): the given one, else 10 deg for tables and None (the
    analysis step) for data; it must divide ``span`` (rad).

    Parameters
    ----------
    text
        The option's text (deg when bare, or with a unit) or None.
    fmt
        The output format (``table``, ``csv``, ``json``).
    span
        The angle the rows cover (rad), e.g. the cycle, 4 pi for a four-stroke engine.
    table_default
        The step of a table when none is given (deg).

    Returns
    -------
    float or None
        The step (rad), or None for data formats without ``text`` (the analysis step).

    Raises
    ------
    InputError
        On a step that is not positive, exceeds ``span``, does not divide it evenly or would
        give more than 1000000 rows, naming ``--step`` and ``text``.

    Examples
    --------
    >>> round(math.degrees(display_step("30", "csv", 4 * math.pi)), 9)
    30.0
    >>> display_step(None, "csv", 4 * math.pi) is None
    True
    >>> display_step("7", "table", 2 * math.pi)
    Traceback (most recent call last):
    ...
    crankdyn.errors.InputError: --step = "7": the step must divide 360 deg evenly
    """
    if text is None:
        return math.radians(table_default) if fmt == "table" else None
    step = parse_quantity(text, "angle", key="--step", default_unit="deg")
    if not (math.isfinite(step) and 0.0 < step <= span):
        raise InputError(
            f"the step must lie between 0 and {math.degrees(span):g} deg", key="--step", value=text
        )
    count = round(span / step)
    if abs(count * step - span) > 1e-9 * span:
        raise InputError(
            f"the step must divide {math.degrees(span):g} deg evenly", key="--step", value=text
        )
    if count > 1_000_000:
        raise InputError(
            "the step is too small (more than 1000000 points)", key="--step", value=text
        )
    return step


def angle_grid(
    text: str | None, fmt: str, span: float = 2 * math.pi, *, start: float = 0.0
) -> NDArray[np.float64]:
    """Angles start..start+span every --step (10 deg for tables, 1 deg for data).

    Parameters
    ----------
    text
        The ``--step`` text (:func:`display_step`) or None.
    fmt
        The output format (``table``, ``csv``, ``json``).
    span
        The angle covered (rad); default one revolution.
    start
        The first angle (rad).

    Returns
    -------
    numpy.ndarray
        The angles (rad), both ends included.

    Raises
    ------
    InputError
        On a bad ``--step`` (:func:`display_step`).

    Examples
    --------
    >>> np.degrees(angle_grid("90", "csv")).round(9).tolist()
    [0.0, 90.0, 180.0, 270.0, 360.0]
    """
    step = display_step(text, fmt, span)
    step = math.radians(1.0) if step is None else step
    count = round(span / step)
    return start + np.linspace(0.0, span, count + 1)


# ---- plots --------------------------------------------------------------------------------------
FIGURE_FORMATS = ("png", "svg", "pdf")


def plot_option(
    help: str = "Also write the figure to FILE (.png, .svg or .pdf).",
    param: str = "plot_path",
    name: str = "--plot",
) -> Decorator:
    """``--plot FILE`` (or another ``name``, e.g. ``--plot-map``): a figure file, checked
    before the work (:func:`check_plot_path`, through :func:`before_work`).

    Parameters
    ----------
    help
        The option's help text.
    param
        The name of the callback's parameter that receives the path.
    name
        The option's name.

    Returns
    -------
    callable
        A decorator that adds the option, and its check before the command's body, to a command
        (whose ``force`` parameter, when it has one, allows replacing the file).
    """

    def decorate(f: F) -> F:
        """Add the option and the check of its file to ``f``."""
        f = before_work(lambda kw: check_plot_path(kw.get(param), bool(kw.get("force")), name))(f)
        return click.option(name, param, default=None, metavar="FILE", help=help)(f)

    return decorate


def check_plot_path(path: str | None, force: bool, option: str = "--plot") -> None:
    """Refuse a figure path with an unknown format, or one crankdyn cannot write
    (:func:`crankdyn.io.output.check_writable`: an existing file without --force, a folder, a
    dangling link, a missing or unwritable folder), before any work is done.

    Parameters
    ----------
    path
        The figure file, or None (nothing to check).
    force
        Whether an existing file may be replaced.
    option
        The option's name, named in an error's message.

    Raises
    ------
    InputError
        On a suffix other than .png, .svg or .pdf (naming ``option`` and ``path``) or a target
        that cannot be written (naming the file and the reason).

    Examples
    --------
    >>> check_plot_path("figure.gif", False)
    Traceback (most recent call last):
    ...
    crankdyn.errors.InputError: --plot = "figure.gif": the plot file must end in .png, .svg, .pdf
    """
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


def save_figure(
    fig: MplFigure, path: str, force: bool, option: str = "--plot", dpi: int = 120
) -> Path:
    """Write a matplotlib figure atomically; the format follows the suffix (png, svg, pdf).

    Prints ``wrote PATH`` on standard error.

    Parameters
    ----------
    fig
        The figure.
    path
        The figure file (.png, .svg or .pdf).
    force
        Whether an existing file may be replaced.
    option
        The option that named the file, named in an error's message.
    dpi
        The resolution of a .png (dots per inch).

    Returns
    -------
    Path
        The file written (:func:`crankdyn.io.output.write_bytes`).

    Raises
    ------
    InputError
        On a path :func:`check_plot_path` refuses.
    """
    check_plot_path(path, force, option)
    buffer = io.BytesIO()
    fig.savefig(buffer, format=Path(path).suffix.lower().lstrip("."), dpi=dpi)
    written = write_bytes(path, buffer.getvalue(), force=force)
    click.echo(f"wrote {written}", err=True)
    return written


# ---- renamed options ----------------------------------------------------------------------------
def deprecated_alias(old: str, new: str, param: str, metavar: str = "VALUE") -> Decorator:
    """A hidden ``old`` option kept for scripts, read into ``param`` (the command merges it
    with ``new``, :func:`merge_alias`); using it prints one deprecation line.

    Parameters
    ----------
    old
        The former option's name (``--rpm``).
    new
        The option that replaces it, named in the deprecation line.
    param
        The name of the callback's parameter that receives the value.
    metavar
        The value's placeholder.

    Returns
    -------
    callable
        A decorator that adds the hidden option to a command.
    """

    def note(_ctx: click.Context, _param: click.Parameter, value: Any) -> Any:
        """Print the deprecation line when the option is given; pass its value on."""
        if value is not None:
            warn(f"{old} is deprecated; use {new}")
        return value

    return click.option(old, param, default=None, metavar=metavar, hidden=True, callback=note)


def merge_alias(value: Any, alias: Any, new: str, old: str) -> Any:
    """The value of an option or of its deprecated alias (not both).

    Parameters
    ----------
    value
        The new option's value, or None.
    alias
        The deprecated alias's value, or None.
    new, old
        The two options' names, named in an error's message.

    Returns
    -------
    object
        ``value`` when given, else ``alias``.

    Raises
    ------
    InputError
        When both are given, naming ``new`` and ``value``.

    Examples
    --------
    >>> merge_alias(None, "1500", "--speed", "--rpm")
    '1500'
    """
    if value is not None and alias is not None:
        raise InputError(f"give {new} or the older {old}, not both", key=new, value=value)
    return value if value is not None else alias


# ---- outputs: checked before the work ------------------------------------------------------------
def before_work(check: Callable[[Mapping[str, Any]], object]) -> Decorator:
    """Decorate a command so that ``check(kwargs)`` (its parsed options) runs before its body.

    Every option that names an output registers the check of its target this way: ``--plot``
    (:func:`plot_option`) and ``-o/--output FILE`` (:func:`crankdyn.cli.writer.output_options`);
    a report or study folder is checked by its command first thing
    (:func:`crankdyn.io.output.check_output_dir`). A target crankdyn cannot write (an existing one
    without ``--force``, a folder for a file, a dangling symbolic link, a missing or unwritable
    parent folder; :mod:`crankdyn.io.output`) is then one line before any computing time is
    spent, and a command cannot forget the check.

    Parameters
    ----------
    check
        Called with the command's keyword arguments (its parsed options) before the body; it
        raises :class:`InputError` to refuse them.

    Returns
    -------
    callable
        A decorator for a command callback.
    """

    def decorate(f: F) -> F:
        """``f``, with ``check`` run first."""

        @functools.wraps(f)
        def command(*args: Any, **kwargs: Any) -> Any:
            """The command: ``check`` of the options, then the body."""
            check(kwargs)
            return f(*args, **kwargs)

        return cast(F, command)

    return decorate


# ---- verdicts: the rule set and the exit status ---------------------------------------------
EXIT_STATUS_HELP = (
    "Exit status: 0 when every verdict passed, 1 when one failed (the analysis ran and its "
    "output is written), 2 on an error; --no-fail gives 0 whatever the verdict."
)
"""What every command that prints a verdict says of its exit status (docs/errors.md)."""


def rules_option(help: str | None = None) -> Decorator:
    """``--rules KEY``: the classification society's rule set of the verdicts, a key of
    :data:`crankdyn.tvc.rulesets.RULESETS` (replacing the file's ``[tvc] rules``).

    Parameters
    ----------
    help
        The option's help text; default: the keys and the default. The callback's parameter
        is ``rules`` (the key, normalised, or None).

    Returns
    -------
    callable
        A decorator that adds the option to a command.
    """
    from crankdyn.defaults import RULES
    from crankdyn.tvc.rulesets import RULESET_KEYS

    text = help or (
        f"The classification society's rule set of the verdicts: {', '.join(RULESET_KEYS)} "
        f"(default: the file's [tvc] rules, else {RULES}; crankdyn docs tvc)."
    )

    def check(_ctx: click.Context, _param: click.Parameter, value: str | None) -> str | None:
        if value is None:
            return None
        from crankdyn.tvc.rulesets import get

        try:
            return get(value).key
        except InputError as exc:
            raise InputError(exc.message, key="--rules", value=value) from None

    return click.option("--rules", default=None, metavar="KEY", callback=check, help=text)


def pool_options(verb: str = "Run") -> Decorator:
    """``--workers N`` (the local pool's processes, >= 1, checked as it is read) and
    ``--scheduler ADDRESS`` (a Dask cluster), as ``study`` and ``design`` take them.

    Parameters
    ----------
    verb
        The help's first word for the scheduler ("Run", "Evaluate").

    Returns
    -------
    callable
        The decorator adding both options (parameters ``workers`` and ``scheduler``).
    """

    def check(_ctx: click.Context, _param: click.Parameter, value: int | None) -> int | None:
        if value is not None and value < 1:
            raise InputError("expected a number of processes >= 1", key="--workers", value=value)
        return value

    workers = click.option(
        "--workers",
        type=int,
        default=None,
        metavar="N",
        callback=check,
        help="Processes of the local pool (default: all cores; 1 runs in this process).",
    )
    scheduler = click.option(
        "--scheduler",
        default=None,
        metavar="ADDRESS",
        help=f"{verb} on the Dask distributed cluster at ADDRESS (e.g. tcp://10.0.0.5:8786).",
    )

    def decorate(f: F) -> F:
        return workers(scheduler(f))

    return decorate


def no_fail_option(f: F) -> F:
    """``--no-fail``: exit with status 0 even when a verdict fails (:func:`verdict_status`).

    Parameters
    ----------
    f
        The command callback; its parameter is ``no_fail`` (bool).

    Returns
    -------
    callable
        The callback with the option.
    """
    return click.option(
        "--no-fail",
        is_flag=True,
        help="Exit with status 0 even when a verdict fails (default 1; the output is written "
        "either way).",
    )(f)


def verdict_status(passed: bool | None, no_fail: bool = False) -> int:
    """The exit status of a command that prints a verdict: 1 when the result's verdict failed
    (unless ``--no-fail``), else 0. The verdict is the result's own (``TvcResult.passed``,
    ``ConditionResult.passed``, ``result.summary().passed``), never re-derived here.

    Parameters
    ----------
    passed
        The result's verdict: True, False, or None where nothing was judged.
    no_fail
        ``--no-fail``: 0 whatever the verdict.

    Returns
    -------
    int
        0 or 1.

    Examples
    --------
    >>> verdict_status(True), verdict_status(False), verdict_status(False, True)
    (0, 1, 0)
    >>> verdict_status(None)
    0
    """
    return 1 if passed is False and not no_fail else 0
