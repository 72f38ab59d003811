"""Reading user files: bounded, UTF-8, with one-line errors naming the file."""

from __future__ import annotations

import tomllib
from pathlib import Path

from crankdyn.errors import InputError

__all__ = ["MAX_CSV_BYTES", "MAX_TOML_BYTES", "display_name", "load_toml", "read_text"]

MAX_TOML_BYTES = 1 << 20  # 1 MiB: engine, model, linkage and study files
MAX_CSV_BYTES = 32 << 20  # 32 MiB: pressure traces and other tables


def display_name(path: str | Path) -> str:
    """How a file is named in messages: as the user gave it."""
    return str(path)


def read_text(path: str | Path, *, limit: int, what: str = "file") -> str:
    """Read a UTF-8 text file of at most ``limit`` bytes.

    Raises
    ------
    InputError
        If the file is missing, a directory, unreadable, larger than the limit, or not UTF-8.
    """
    name = display_name(path)
    p = Path(path)
    try:
        with p.open("rb") as handle:
            data = handle.read(limit + 1)
    except FileNotFoundError:
        raise InputError(f"no such {what}", file=name) from None
    except IsADirectoryError:
        raise InputError(f"is a directory, not a {what}", file=name) from None
    except OSError as exc:
        raise InputError(f"cannot read the {what}: {exc.strerror or exc}", file=name) from None
    if len(data) > limit:
        raise InputError(
            f"the {what} is larger than the {limit // (1 << 20)} MiB crankdyn reads", file=name
        )
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data[: exc.start].count(b"\n") + 1
        raise InputError(
            f"the {what} is not UTF-8 text (byte 0x{data[exc.start]:02x} on line {line})",
            file=name,
        ) from None
    return text.removeprefix("\ufeff")


def load_toml(path: str | Path, *, what: str = "file") -> dict:
    """Parse a TOML file (bounded read); syntax errors become one-line InputErrors."""
    text = read_text(path, limit=MAX_TOML_BYTES, what=what)
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        message = " ".join(str(exc).split())
        raise InputError(f"invalid TOML: {message}", file=display_name(path)) from None
