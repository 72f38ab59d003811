"""The ``crankdyn`` command line.

``main(argv) -> int`` runs in-process (tests call it directly). A mistake in the input ends in one
line on stderr, ``crankdyn: error: ...``, and exit status 2; anything else that escapes is a bug and
keeps its traceback. Command groups live in sibling modules listed in :data:`COMMAND_MODULES`, each
with a ``register(group)`` function.

The group is lazy: a command's module is imported when that command runs, so ``crankdyn
kinematics`` never imports what ``crankdyn study`` needs, and ``crankdyn --help`` lists the
commands from :data:`COMMAND_SUMMARIES` without importing any.
Command modules keep their module-level imports light (click, the shared vocabulary, the
domain's names); scipy, matplotlib, pint, Dask and pyarrow are imported where they are used.
"""

from __future__ import annotations

import contextlib
import errno
import gc
import importlib
import io
import os
import signal
import sys
import threading
import warnings
from collections.abc import Iterator, Mapping, MutableMapping
from gettext import gettext as _
from types import FrameType
from typing import Any

import click

from crankdyn import __version__
from crankdyn.allocator import keep_freed_memory
from crankdyn.errors import InputError
from crankdyn.threads import limit_blas_threads

__all__ = ["COMMAND_MODULES", "COMMAND_SUMMARIES", "LazyGroup", "Terminated", "cli", "main", "run"]

COMMAND_MODULES: dict[str, tuple[str, ...]] = {
    "examples": ("examples", "example"),
    "kinematics": ("kinematics", "coefficients"),
    "analyze": ("analyze", "demo"),
    "forces": ("forces", "bearings", "torque", "pressure"),
    "torsion": ("torsion",),
    "linkage": ("linkage",),
    "balance": ("firing-orders", "balance", "flywheel"),
    "torsion_response": ("torsion",),  # its commands join the torsion group
    "study": ("study",),
    "design": ("design",),
    "measure": ("measure",),
    "tvc": ("tvc",),
    "crankshaft": ("crankshaft",),
    "docs": ("docs",),
}
"""The command modules (``crankdyn.cli.<module>``) and the top-level commands each registers;
a command two modules name is complete once both are loaded (``tests/cli/test_lazy.py`` holds
this index to what the modules register)."""

COMMAND_SUMMARIES: dict[str, str] = {
    "analyze": "Run every analysis that applies to ENGINE and write an HTML report with its data.",
    "balance": "Free forces and moments of ENGINE's mass forces, order by order (seed 000 §2.2).",
    "bearings": (
        "Crank-pin loads (crank frame) of every throw and main-bearing loads (engine frame) of "
        "ENGINE over the working cycle."
    ),
    "coefficients": (
        "The seeds' dimensionless tables: A = x/R, B = v/(Rω), C = a/(Rω²) vs crank angle."
    ),
    "design": (
        "Search SPACE's catalogue choices and ranges for the design that passes the verdicts "
        "with the widest margin."
    ),
    "demo": "The full report on the built-in inline-6 diesel (crankdyn analyze inline6-diesel).",
    "crankshaft": (
        "The crankshaft: its fatigue strength by IACS UR M53 and the coupled vibration of its "
        "beam model."
    ),
    "docs": (
        "Read the user documentation offline: without TOPIC, list the topics; with one, show its "
        "page in the terminal (paged when the output is a terminal)."
    ),
    "example": (
        "Write the built-in example NAME (engine, torsional model, linkage or study, with any file "
        "it names, such as a pressure trace) to a file to edit."
    ),
    "examples": "List the built-in examples: engines, torsional models, linkages and studies.",
    "firing-orders": (
        "Enumerate the firing orders ENGINE's crankshaft allows and rank them (seed 000 §2.3)."
    ),
    "flywheel": "Speed fluctuation of ENGINE and the flywheel for a target δ (seed 000 §2.4).",
    "forces": (
        "Gas, inertia, rod, side, tangential and radial forces and the crank-pin load of one "
        "cylinder of ENGINE over the working cycle."
    ),
    "kinematics": "Piston and connecting-rod kinematics of ENGINE over one revolution.",
    "linkage": (
        "Planar linkages: four-bar, slider-crank and general mechanisms (kinematics, forces)."
    ),
    "measure": "Orders of the angular vibration measured by a torsiograph, held against a model.",
    "pressure": (
        "Cylinder pressure of ENGINE over the cycle (its trace, or the synthetic Wiebe model) with "
        "the indicated work, IMEP and peak pressure."
    ),
    "study": (
        "Run the parameter study STUDY (a study file, or a built-in example study; --list shows "
        "them): every case on a local process pool (all cores) or, with --scheduler, on a Dask "
        "cluster."
    ),
    "torque": (
        "Cylinder, total, main-journal and crank-pin torques of ENGINE over the working cycle, "
        "with mean torque, power, IMEP and peak pressure."
    ),
    "torsion": "Crankshaft torsional vibration: lumped models, free and forced vibration.",
    "tvc": (
        "The torsional vibration calculation of MODEL_OR_ENGINE: every running condition (normal "
        "firing, each cylinder misfiring, damper out of order) against every component's limit "
        "(the classification society's rule set, the engine builder's, the coupling, gear, "
        "generator and damper makers'), barred speed ranges and their passage, as a report "
        "folder with index.html, report.pdf (headless Chromium, where installed) and "
        "summary.json (crankdyn docs tvc)."
    ),
}
"""What ``crankdyn --help`` lists for each top-level command: its help up to the first word
that ends a sentence (click shortens a command's help to that, or less, for the listing; the
rest of the help never shows there), so listing the commands imports no command module
(``tests/cli/test_lazy.py`` holds this index to the commands' own help)."""


class LazyGroup(click.Group):
    """A click group that imports a command's module on first use (:data:`COMMAND_MODULES`).

    ``commands`` (click's dict of every command) loads every module: the documentation build
    and the tests walk it; running one command does not.

    Parameters
    ----------
    *args, **kwargs
        What :class:`click.Group` takes (the name, ``context_settings``, ...).
    modules : dict of str to tuple of str
        The command modules (``crankdyn.cli.<module>``, each with a ``register(group)``
        function) and the names of the commands each registers.
    summaries : dict of str to str, optional
        The first sentence of the help of commands (by name): the help's listing of those
        commands imports no module (:meth:`format_commands`).
    """

    def __init__(
        self,
        *args: Any,
        modules: dict[str, tuple[str, ...]],
        summaries: dict[str, str] | None = None,
        **kwargs: Any,
    ) -> None:
        self._modules = modules
        self._summaries = dict(summaries or {})
        self._loaded: set[str] = set()
        self._commands: dict[str, click.Command] = {}
        super().__init__(*args, **kwargs)

    @property
    def commands(self) -> MutableMapping[str, click.Command]:
        """Every command (name to command), every command module loaded."""
        self._load(*self._modules)
        return self._commands

    @commands.setter
    def commands(self, value: Mapping[str, click.Command] | None) -> None:
        """Set the registered commands (click's Group sets them on construction)."""
        self._commands = dict(value or {})

    def _load(self, *modules: str) -> None:
        """Import the command ``modules`` not yet loaded and let each register its commands."""
        for module in modules:
            if module not in self._loaded:
                self._loaded.add(module)
                importlib.import_module(f"crankdyn.cli.{module}").register(self)

    def add_command(self, cmd: click.Command, name: str | None = None) -> None:
        """Register ``cmd`` under ``name`` (default its own name), as :class:`click.Group` does.

        Parameters
        ----------
        cmd
            The command.
        name
            The name it is run by.

        Raises
        ------
        TypeError
            When neither ``name`` nor the command has a name (a programming error).
        """
        name = name or cmd.name
        if name is None:
            raise TypeError("Command has no name.")
        self._commands[name] = cmd

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        """The command ``cmd_name``, its module(s) loaded first; None for an unknown name.

        Parameters
        ----------
        ctx
            The group's click context.
        cmd_name
            The command's name.

        Returns
        -------
        click.Command or None
            The command.
        """
        self._load(*(m for m, names in self._modules.items() if cmd_name in names))
        return self._commands.get(cmd_name)

    def list_commands(self, ctx: click.Context) -> list[str]:
        """The names of the commands, sorted, without loading a module.

        Parameters
        ----------
        ctx
            The group's click context.

        Returns
        -------
        list of str
            Every name in the module index.
        """
        return sorted({name for names in self._modules.values() for name in names})

    def _listed(self, ctx: click.Context, name: str) -> click.Command | None:
        """The command ``name`` as the help lists it: the command itself once its modules are
        loaded, else a stand-in carrying its summary (no module imported for it)."""
        modules = {m for m, names in self._modules.items() if name in names}
        if name in self._summaries and not modules <= self._loaded:
            return click.Command(name, help=self._summaries[name])
        return self.get_command(ctx, name)

    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        """The help's list of commands, as :class:`click.Group` writes it, a command not yet
        loaded listed from its summary (``summaries``) rather than by importing its module.

        Parameters
        ----------
        ctx
            The group's click context.
        formatter
            The help formatter written to.
        """
        commands = []
        for name in self.list_commands(ctx):
            cmd = self._listed(ctx, name)
            if cmd is not None and not cmd.hidden:
                commands.append((name, cmd))
        if commands:  # as click.Group.format_commands
            limit = formatter.width - 6 - max(len(name) for name, _cmd in commands)
            rows = [(name, cmd.get_short_help_str(limit)) for name, cmd in commands]
            with formatter.section(_("Commands")):
                formatter.write_dl(rows)


class _OutputFailed(Exception):
    """An OSError raised by a command, carried past click (which would turn a closed pipe into
    a silent exit status 1) to :func:`main`."""

    def __init__(self, error: OSError) -> None:
        super().__init__(error)
        self.error = error


class _Group(LazyGroup):
    """The lazy group whose commands' operating-system errors reach :func:`main`."""

    def invoke(self, ctx: click.Context) -> Any:
        """Run the command as :class:`click.Group` does, an OSError carried to :func:`main`."""
        try:
            return super().invoke(ctx)
        except OSError as exc:
            raise _OutputFailed(exc) from exc


@click.group(
    cls=_Group,
    modules=COMMAND_MODULES,
    summaries=COMMAND_SUMMARIES,
    context_settings={"help_option_names": ["-h", "--help"], "max_content_width": 100},
)
@click.version_option(__version__, prog_name="crankdyn")
def cli() -> None:
    """crankdyn: dynamics of crank mechanisms.

    ENGINE arguments take an engine file (TOML, see `crankdyn docs engine-file`) or the name of a
    built-in example (`crankdyn examples` lists them). Quantities take units ("76 mm",
    "4900 rpm"); options whose metavar names a unit (RPM, DEG) take that unit for bare numbers.
    """


def _error(message: str) -> None:
    """``crankdyn: error: MESSAGE`` on one line of standard error (white space runs joined,
    other control characters shown escaped: a click message may quote the user's text)."""
    from crankdyn.display import printable

    text = printable(" ".join(str(message).split()))
    with contextlib.suppress(OSError, ValueError):  # stderr itself may be gone
        click.echo(f"crankdyn: error: {text}", err=True)


class Terminated(KeyboardInterrupt):
    """SIGTERM (or SIGHUP), handled like Ctrl-C: the work stops, nothing is left half-written,
    temporary outputs are removed; the exit status is 128 + the signal's number.

    Parameters
    ----------
    signum : int
        The signal's number.
    """

    def __init__(self, signum: int) -> None:
        super().__init__(signum)
        self.signum = signum


_TERMINATING = tuple(getattr(signal, n) for n in ("SIGTERM", "SIGHUP") if hasattr(signal, n))


@contextlib.contextmanager
def _terminate_like_interrupt() -> Iterator[list[int]]:
    """While a command runs, SIGTERM (and SIGHUP) raise :class:`Terminated` in the main thread,
    as SIGINT raises KeyboardInterrupt; yields the list of the signals received. A signal the
    process ignores (e.g. nohup's SIGHUP) stays ignored; the previous handlers come back
    afterwards."""
    received: list[int] = []
    if threading.current_thread() is not threading.main_thread():
        yield received
        return

    def handler(signum: int, _frame: FrameType | None) -> None:
        """Note the signal and raise :class:`Terminated`."""
        received.append(signum)
        raise Terminated(signum)

    previous: dict[int, Any] = {}
    for sig in _TERMINATING:
        old = signal.getsignal(sig)
        if old == signal.SIG_DFL:
            previous[sig] = old
            signal.signal(sig, handler)
    try:
        yield received
    finally:
        for sig, old in previous.items():
            signal.signal(sig, old)


def _signal_name(signum: int) -> str:
    """The signal's name (``SIGTERM``), or ``signal N`` for an unknown number."""
    try:
        return signal.Signals(signum).name
    except ValueError:
        return f"signal {signum}"


def _quiet_stdout() -> None:
    """Point a standard output that failed (a closed pipe, a full disk) at the null device, so
    that the interpreter's last flush at exit does not fail again."""
    with contextlib.suppress(OSError, ValueError, AttributeError):
        stdout = sys.stdout
        if stdout is sys.__stdout__ and stdout is not None:
            null = os.open(os.devnull, os.O_WRONLY)
            os.dup2(null, stdout.fileno())
            os.close(null)


def main(argv: list[str] | None = None) -> int:
    """Run the command line with ``argv`` (default: sys.argv[1:]); return the exit status.

    Parameters
    ----------
    argv
        The arguments after ``crankdyn``; default the process's own.

    Returns
    -------
    int
        0 on success (also when the reader of standard output quit early: a closed pipe ends
        the command quietly), 1 when a command that prints a verdict ran and its verdict
        failed (``--no-fail`` gives 0), 2 after an input error or an output that failed (one
        line on standard error), 128 + the signal's number after an interrupt or termination.

    Examples
    --------
    >>> main(["kinematics", "--speed", "-5", "no-such-engine"])
    2
    """
    args = list(sys.argv[1:] if argv is None else argv)
    try:
        limit_blas_threads()  # the processors not already busy (crankdyn.threads)
        keep_freed_memory()  # freed arrays' memory used again, not unmapped (crankdyn.allocator)
    except InputError as exc:
        _error(str(exc))
        return 2
    with _terminate_like_interrupt() as received, warnings.catch_warnings():
        # a RuntimeWarning of crankdyn's numerics (an overflow, an invalid value) is a bug, as
        # in the test suite (pyproject's filterwarnings): raised with its traceback, never
        # printed beside a result; bad input is refused before it reaches the numerics
        warnings.filterwarnings("error", category=RuntimeWarning, module=r"crankdyn\.")
        status = _run(args)
        if status == 130 and received:  # a command that handled the interrupt itself
            status = 128 + received[-1]
    return status


class _ClosedStdout(io.TextIOBase):
    """Standard output of a process started with it closed (``crankdyn ... >&-``: Python sets
    ``sys.stdout`` to None): writing to it fails as writing to a closed descriptor does, so a
    command that prints ends in one line and status 2, and one that only writes files runs."""

    def writable(self) -> bool:
        return True

    def write(self, text: str) -> int:
        raise OSError(errno.EBADF, "standard output is closed")

    def flush(self) -> None:
        """Nothing is buffered."""


def _run(args: list[str]) -> int:
    """Run the group on ``args``; every error that is not a bug becomes a line and a status."""
    if sys.stdout is None:
        sys.stdout = _ClosedStdout()
    try:
        result = cli.main(args=args, prog_name="crankdyn", standalone_mode=False)
        sys.stdout.flush()  # an output error shows here, not at the interpreter's exit
    except InputError as exc:
        _error(str(exc))
        return 2
    except click.exceptions.NoArgsIsHelpError as exc:
        click.echo(exc.ctx.get_help() if exc.ctx else str(exc))
        return 0
    except click.UsageError as exc:
        where = exc.ctx.command_path if exc.ctx is not None else "crankdyn"
        _error(f"{where}: {exc.format_message()}")
        return 2
    except click.exceptions.Exit as exc:
        return exc.exit_code
    except (click.Abort, KeyboardInterrupt) as exc:
        # click turns KeyboardInterrupt (and Terminated) into Abort, the signal in its cause
        signum = int(
            getattr(exc, "signum", 0) or getattr(exc.__cause__, "signum", 0) or signal.SIGINT
        )
        if signum == signal.SIGINT:
            _error("interrupted; nothing was written")
        else:
            _error(f"terminated ({_signal_name(signum)}); nothing was written")
        return 128 + signum
    except click.ClickException as exc:
        _error(exc.format_message())
        return max(exc.exit_code, 2)  # an error is status 2, whatever click's default
    except (OSError, _OutputFailed) as caught:
        # an error of the operating system while writing: standard output closed (a pipe whose
        # reader quit) or full, or a file the output modules did not name
        # (crankdyn.io.output names the files and folders it writes, also on an error of a
        # write inside a folder being built; an error without a file name comes from writing
        # to standard output)
        error = caught.error if isinstance(caught, _OutputFailed) else caught
        reason = error.strerror or " ".join(str(error).split()) or type(error).__name__
        if error.filename:
            _error(f"{error.filename}: {reason}")
            return 2
        _quiet_stdout()
        if error.errno == errno.EPIPE:
            # the reader of the pipe quit (``crankdyn examples | head -2``): it has what it
            # wanted; like other command-line tools, end quietly with status 0
            return 0
        _error(f"cannot write to standard output: {reason}")
        return 2
    return result if isinstance(result, int) else 0


def run() -> None:
    """Console-script entry point (and ``python -m crankdyn``).

    The process ends with its objects frozen (:func:`gc.freeze`): the interpreter's last
    collection at exit would otherwise traverse every object the command made and imported
    (0.1-0.3 s after a report, with matplotlib's figures), to free memory the exit frees anyway.
    Files are closed where they are written; the standard streams are flushed at exit as
    always.
    """
    status = main()
    gc.freeze()
    sys.exit(status)
