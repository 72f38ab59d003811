"""The ``crankdyn`` command line.

``main(argv) -> int`` runs in-process (tests call it directly). A mistake in the input ends in one
line on stderr, ``crankdyn: error: ...``, and exit status 2; anything else that escapes is a bug and
keeps its traceback. Command groups live in sibling modules listed in :data:`COMMAND_MODULES`, each
with a ``register(group)`` function.

The group is lazy: a command's module is imported when that command runs (or when ``--help``
lists the commands), so ``crankdyn kinematics`` never imports what ``crankdyn study`` needs.
Command modules keep their module-level imports light (click, the shared vocabulary, the
domain's names); scipy, matplotlib, pint, Dask and pyarrow are imported where they are used.
"""

from __future__ import annotations

import contextlib
import gc
import importlib
import os
import signal
import sys
import threading
from collections.abc import Iterator, Mapping, MutableMapping
from types import FrameType
from typing import Any

import click

from crankdyn import __version__
from crankdyn.errors import InputError

__all__ = ["COMMAND_MODULES", "LazyGroup", "Terminated", "cli", "main", "run"]

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
    "measure": ("measure",),
    "tvc": ("tvc",),
    "docs": ("docs",),
}
"""The command modules (``crankdyn.cli.<module>``) and the top-level commands each registers;
a command two modules name is complete once both are loaded (``tests/cli/test_lazy.py`` holds
this index to what the modules register)."""


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
    """

    def __init__(self, *args: Any, modules: dict[str, tuple[str, ...]], **kwargs: Any) -> None:
        self._modules = modules
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
    """``crankdyn: error: MESSAGE`` on one line of standard error (white space runs joined)."""
    text = " ".join(str(message).split())
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
        0 on success, 2 after an input error or an output that failed (one line on standard
        error), 128 + the signal's number after an interrupt or termination.

    Examples
    --------
    >>> main(["kinematics", "--speed", "-5", "no-such-engine"])
    2
    """
    args = list(sys.argv[1:] if argv is None else argv)
    with _terminate_like_interrupt() as received:
        status = _run(args)
        if status == 130 and received:  # a command that handled the interrupt itself
            status = 128 + received[-1]
    return status


def _run(args: list[str]) -> int:
    """Run the group on ``args``; every error that is not a bug becomes a line and a status."""
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
        return exc.exit_code
    except (OSError, _OutputFailed) as caught:
        # an error of the operating system while writing: standard output closed (a pipe whose
        # reader quit) or full, or a file the output modules did not name
        # (crankdyn.io.output names the files it writes; an error without a file name comes
        # from writing to standard output)
        error = caught.error if isinstance(caught, _OutputFailed) else caught
        reason = error.strerror or " ".join(str(error).split()) or type(error).__name__
        if error.filename:
            _error(f"{error.filename}: {reason}")
        else:
            _quiet_stdout()
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
