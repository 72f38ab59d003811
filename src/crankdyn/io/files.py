"""Reading user files: bounded, UTF-8, with one-line errors naming the file.

Every size is bounded before it is allocated: text files by their bytes (:data:`MAX_TOML_BYTES`,
:data:`MAX_CSV_BYTES`), TOML by its nesting (:data:`MAX_TOML_DEPTH`), NumPy files by their
bytes and by what their headers claim (:func:`read_numpy`: the shape, the type and the
uncompressed size of every array checked against :data:`MAX_ARRAY_VALUES` and
:data:`MAX_ARRAY_BYTES` before an array is made).
"""

from __future__ import annotations

import contextlib
import math
import os
import stat
import tomllib
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import IO, TYPE_CHECKING

from crankdyn.errors import InputError

if TYPE_CHECKING:
    import numpy as np

__all__ = [
    "MAX_ARRAY_BYTES",
    "MAX_ARRAY_VALUES",
    "MAX_CSV_BYTES",
    "MAX_TOML_BYTES",
    "MAX_TOML_DEPTH",
    "NPY_HEADER",
    "check_npy_data",
    "check_regular",
    "display_name",
    "load_toml",
    "npy_array",
    "npy_header",
    "open_regular",
    "parse_toml",
    "read_bytes",
    "read_numpy",
    "read_text",
]

MAX_TOML_BYTES = 1 << 20  # 1 MiB: engine, model, linkage and study files
MAX_CSV_BYTES = 32 << 20  # 32 MiB: pressure traces and other tables
MAX_ARRAY_BYTES = 32 << 20
"""Largest uncompressed size of the arrays of one NumPy file (32 MiB, as a CSV table's bytes),
checked from the headers before any array is made (the limit of the file's own bytes alone
would let a compressed ``.npz`` of 1 MB unpack to gigabytes)."""
MAX_ARRAY_VALUES = MAX_ARRAY_BYTES // 8
"""Most values in the arrays of one NumPy file: 4,194,304 (32 MiB of float64; about the
numbers a 32 MiB CSV table holds)."""
NPY_HEADER = 1 << 16
"""Room for a .npy file's magic and header (bytes; numpy caps it at 10,000)."""


def display_name(path: str | Path) -> str:
    """How a file is named in messages: as the user gave it.

    Parameters
    ----------
    path
        The path as the user gave it (command line or a file's key).

    Returns
    -------
    str
        The name used in the ``file`` of an :class:`~crankdyn.errors.InputError`.

    Examples
    --------
    >>> display_name(Path("engines") / "v8.toml")
    'engines/v8.toml'
    """
    return str(path)


_NONBLOCK = getattr(os, "O_NONBLOCK", 0)


def _refuse_special(mode: int, name: str, what: str) -> None:
    if stat.S_ISDIR(mode):
        raise InputError(f"is a directory, not a {what}", file=name)
    if not stat.S_ISREG(mode):
        kind = (
            "a FIFO"
            if stat.S_ISFIFO(mode)
            else "a socket"
            if stat.S_ISSOCK(mode)
            else "a device"
            if stat.S_ISCHR(mode) or stat.S_ISBLK(mode)
            else "not a file"
        )
        raise InputError(
            f"is not a regular file ({kind}); crankdyn reads {what}s from regular files",
            file=name,
        )


def check_regular(path: str | Path, *, what: str = "file") -> None:
    """Refuse, before anything opens it, an input that is not a regular file: a FIFO (whose
    open would wait for a writer), a device, a socket, a folder; or a missing file.

    Parameters
    ----------
    path
        The input file.
    what
        What the file is, in words, for the message (``"pressure trace"``).

    Raises
    ------
    InputError
        Naming the file and what it is.
    """
    name = display_name(path)
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        raise InputError(f"no such {what}", file=name) from None
    except (OSError, ValueError) as exc:
        reason = getattr(exc, "strerror", None) or exc
        raise InputError(f"cannot read the {what}: {reason}", file=name) from None
    _refuse_special(mode, name, what)


@contextlib.contextmanager
def open_regular(path: str | Path, *, what: str = "file") -> Iterator[IO[bytes]]:
    """Open a regular file for reading in binary, checked as :func:`read_bytes` checks it (a
    FIFO, a device, a socket or a folder refused before it is opened, and again on the open
    file), for a file read in pieces of bounded size.

    Parameters
    ----------
    path
        The input file.
    what
        What the file is, in words, for the message.

    Yields
    ------
    typing.IO of bytes
        The open file; an OS error while it is read becomes an InputError naming the file.

    Raises
    ------
    InputError
        If the file is missing, a directory, not a regular file or unreadable.
    """
    name = display_name(path)
    try:
        check_regular(path, what=what)
        fd = os.open(path, os.O_RDONLY | _NONBLOCK | getattr(os, "O_CLOEXEC", 0))
        handle = os.fdopen(fd, "rb")
    except InputError:
        raise
    except FileNotFoundError:
        raise InputError(f"no such {what}", file=name) from None
    except IsADirectoryError:
        raise InputError(f"is a directory, not a {what}", file=name) from None
    except (OSError, ValueError) as exc:
        reason = getattr(exc, "strerror", None) or exc
        raise InputError(f"cannot read the {what}: {reason}", file=name) from None
    with handle:
        try:
            _refuse_special(os.fstat(handle.fileno()).st_mode, name, what)
            yield handle
        except OSError as exc:  # a read failing (the consumer's own errors pass through)
            reason = getattr(exc, "strerror", None) or exc
            raise InputError(f"cannot read the {what}: {reason}", file=name) from None


def read_bytes(path: str | Path, *, limit: int, what: str = "file") -> bytes:
    """Read a regular file of at most ``limit`` bytes.

    Parameters
    ----------
    path
        The input file.
    limit
        Largest size read (bytes), e.g. :data:`MAX_TOML_BYTES` or :data:`MAX_CSV_BYTES`.
    what
        What the file is, in words, for the message.

    Returns
    -------
    bytes
        The whole content of the file.

    Raises
    ------
    InputError
        If the file is missing, a directory, not a regular file (a FIFO, a device), unreadable
        or larger than the limit.
    """
    name = display_name(path)
    try:
        check_regular(path, what=what)
        # opened without blocking and checked again on the open file: a FIFO put in its place
        # meanwhile is refused instead of blocking the open until a writer comes
        fd = os.open(path, os.O_RDONLY | _NONBLOCK | getattr(os, "O_CLOEXEC", 0))
        with os.fdopen(fd, "rb") as handle:
            _refuse_special(os.fstat(handle.fileno()).st_mode, name, what)
            data = handle.read(limit + 1)
    except InputError:
        raise
    except FileNotFoundError:
        raise InputError(f"no such {what}", file=name) from None
    except IsADirectoryError:
        raise InputError(f"is a directory, not a {what}", file=name) from None
    except (OSError, ValueError) as exc:
        reason = getattr(exc, "strerror", None) or exc
        raise InputError(f"cannot read the {what}: {reason}", file=name) from None
    if len(data) > limit:
        raise InputError(
            f"the {what} is larger than the {limit // (1 << 20)} MiB crankdyn reads", file=name
        )
    return data


def read_text(path: str | Path, *, limit: int, what: str = "file") -> str:
    """Read a UTF-8 text file of at most ``limit`` bytes (:func:`read_bytes`).

    Parameters
    ----------
    path
        The input file.
    limit
        Largest size read (bytes).
    what
        What the file is, in words, for the message.

    Returns
    -------
    str
        The decoded text, without a leading byte-order mark.

    Raises
    ------
    InputError
        If the file is missing, a directory, not a regular file (a FIFO, a device), unreadable,
        larger than the limit, or not UTF-8 (naming the byte and its line).
    """
    name = display_name(path)
    data = read_bytes(path, limit=limit, what=what)
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
    """Parse a TOML file (bounded read, at most :data:`MAX_TOML_BYTES`).

    Parameters
    ----------
    path
        The TOML file (engine, torsional model, linkage or study file).
    what
        What the file is, in words, for the message.

    Returns
    -------
    dict
        The parsed document (values as TOML gives them: units are still in the strings).

    Raises
    ------
    InputError
        As :func:`read_text` and :func:`parse_toml`, naming the file.
    """
    text = read_text(path, limit=MAX_TOML_BYTES, what=what)
    return parse_toml(text, file=display_name(path))


def parse_toml(text: str, *, file: str | None = None) -> dict:
    """Parse TOML text; a syntax error, or nesting deeper than :data:`MAX_TOML_DEPTH` (arrays
    and tables within each other), becomes a one-line InputError.

    Parameters
    ----------
    text
        The TOML text.
    file
        The file's name for messages (None: the text came from elsewhere).

    Returns
    -------
    dict
        The parsed document.

    Raises
    ------
    InputError
        On a syntax error (tomllib's message on one line, with its line and column) or nesting
        deeper than :data:`MAX_TOML_DEPTH`, naming ``file``.

    Examples
    --------
    >>> parse_toml('bore = "86 mm"')
    {'bore': '86 mm'}
    >>> parse_toml("bore = ", file="e.toml")
    Traceback (most recent call last):
    ...
    crankdyn.errors.InputError: e.toml: invalid TOML: Invalid value (at end of document)
    """
    try:
        document = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        message = " ".join(str(exc).split())
        raise InputError(f"invalid TOML: {message}", file=file) from None
    except RecursionError:  # tomllib parses nested arrays and inline tables recursively
        raise InputError(_TOO_DEEP, file=file) from None
    if _depth(document) > MAX_TOML_DEPTH:
        raise InputError(_TOO_DEEP, file=file)
    return document


MAX_TOML_DEPTH = 32
"""Deepest nesting of arrays and tables crankdyn reads: its formats nest a few levels; the bound
keeps every later step (copies, messages) far from Python's recursion limit."""
_TOO_DEEP = f"invalid TOML: arrays and tables nest deeper than {MAX_TOML_DEPTH} levels"


def _depth(value: object) -> int:
    """Nesting depth of parsed TOML (a scalar is 0), without recursion."""
    deepest = 0
    stack = [(value, 0)]
    while stack:
        item, depth = stack.pop()
        children: Iterable[object]
        if isinstance(item, dict):
            children = item.values()
        elif isinstance(item, list):
            children = item
        else:
            continue
        depth += 1
        deepest = max(deepest, depth)
        if deepest > MAX_TOML_DEPTH:
            return deepest
        stack.extend((child, depth) for child in children)
    return deepest


# ---- NumPy files ---------------------------------------------------------------------------------


def npy_header(handle: IO[bytes], name: str, key: str) -> tuple[tuple[int, ...], bool, np.dtype]:
    """The header of a ``.npy`` file (or archive member) read from ``handle``, checked: a
    version numpy writes, numbers (no objects, no pickles). The handle is left at the data.

    Parameters
    ----------
    handle
        The open file, at its start.
    name
        The file as named in messages.
    key
        The array, for messages (``"array"``, or an archive member's name).

    Returns
    -------
    tuple
        (shape, Fortran order, dtype) as the header claims them.

    Raises
    ------
    InputError
        For a header numpy cannot read, or an array that is not numbers.
    """
    from numpy.lib import format as npy

    try:
        version = npy.read_magic(handle)
        if version == (1, 0):
            shape, fortran, dtype = npy.read_array_header_1_0(handle)
        elif version == (2, 0):
            shape, fortran, dtype = npy.read_array_header_2_0(handle)
        else:
            raise ValueError(f"format version {version[0]}.{version[1]} is not read")
    except (ValueError, TypeError, SyntaxError, EOFError, OverflowError) as exc:
        detail = " ".join(str(exc).split())[:80]
        raise InputError(f"not a readable NumPy .npy file ({detail})", file=name, key=key) from None
    if dtype.hasobject or dtype.kind not in "fiu":
        raise InputError("expected numbers", file=name, key=key, value=str(dtype))
    return tuple(int(n) for n in shape), bool(fortran), dtype


def check_npy_data(shape: tuple[int, ...], dtype: np.dtype, held: int, name: str, key: str) -> int:
    """The data bytes a header claims, checked against the ``held`` bytes after it (a
    truncated file refused before anything is read).

    Parameters
    ----------
    shape, dtype
        As the header claims them.
    held
        The bytes the file (or member) holds after its header.
    name, key
        The file and the array, for messages.

    Returns
    -------
    int
        The values the header claims.

    Raises
    ------
    InputError
        When the file holds less data than the header claims.
    """
    count = math.prod(shape)  # Python integers: no overflow
    size = count * dtype.itemsize
    if held < size:
        raise InputError(
            f"the header claims shape {tuple(shape)} ({size:,} bytes of data) and the file "
            f"holds {held:,} (truncated?)",
            file=name,
            key=key,
        )
    return count


def npy_array(data: bytes, name: str, key: str) -> np.ndarray:
    """The array of a ``.npy`` file's bytes, its header checked before anything is allocated:
    a version numpy writes, numbers (no objects, no pickles), at most
    :data:`MAX_ARRAY_VALUES` values and :data:`MAX_ARRAY_BYTES` bytes, and the data the header
    claims present in full.

    Parameters
    ----------
    data
        The file's (or archive member's) bytes.
    name, key
        The file and the array, for messages.

    Returns
    -------
    numpy.ndarray
        A read-only view of ``data`` (no copy), of the header's shape and type.

    Raises
    ------
    InputError
        For an unreadable header, an array that is not numbers, a claim beyond the bounds or
        more data than the bytes hold.
    """
    import io

    import numpy as np

    handle = io.BytesIO(data)
    shape, fortran, dtype = npy_header(handle, name, key)
    count = math.prod(shape)  # Python integers: no overflow
    size = count * dtype.itemsize
    widest = max(shape, default=0)  # (0, 10**18): empty, yet unshapeable
    if count > MAX_ARRAY_VALUES or size > MAX_ARRAY_BYTES or widest > MAX_ARRAY_VALUES:
        raise InputError(
            f"the header claims shape {tuple(shape)}: {count:,} values ({size:,} bytes); "
            f"crankdyn reads at most {MAX_ARRAY_VALUES:,} values ({MAX_ARRAY_BYTES >> 20} MiB) "
            "from a NumPy file",
            file=name,
            key=key,
        )
    start = handle.tell()
    check_npy_data(shape, dtype, len(data) - start, name, key)
    flat = np.frombuffer(data, dtype=dtype, count=count, offset=start)
    return flat.reshape(shape, order="F" if fortran else "C")


def read_numpy(
    path: str | Path, *, names: Iterable[str] | None = None, what: str = "signal file"
) -> np.ndarray | dict[str, np.ndarray]:
    """Read a NumPy ``.npy`` file (one array) or ``.npz`` archive (named arrays), every size
    bounded before it is allocated: the file's bytes (:data:`MAX_CSV_BYTES`), an archive's
    members (only ``names``), their declared uncompressed sizes, and every array's header
    (shape and type: numbers only, at most :data:`MAX_ARRAY_VALUES` values and
    :data:`MAX_ARRAY_BYTES` bytes in all). Pickled objects are never loaded.

    Parameters
    ----------
    path
        The ``.npy`` or ``.npz`` file (by its suffix).
    names
        The array names an archive may hold (each as ``NAME.npy`` in the zip); None: any.
        Ignored for ``.npy``.
    what
        What the file is, in words, for the messages.

    Returns
    -------
    numpy.ndarray or dict of str to numpy.ndarray
        The array of a ``.npy`` file, or ``{name: array}`` of an archive (read-only arrays of
        numbers, as the file holds them).

    Raises
    ------
    InputError
        On an unreadable, oversized or malformed file, an archive member not in ``names``, an
        array that is not numbers, or a header that claims more than the bounds (naming the
        file, the array and the claimed shape) or more data than the file holds.
    """
    import io
    import zipfile
    import zlib

    name = display_name(path)
    if Path(path).suffix.lower() != ".npz":
        data = read_bytes(path, limit=MAX_ARRAY_BYTES + NPY_HEADER, what=what)
        return npy_array(data, name, "array")
    data = read_bytes(path, limit=MAX_CSV_BYTES, what=what)
    allowed = None if names is None else list(names)
    arrays: dict[str, np.ndarray] = {}
    try:
        with zipfile.ZipFile(io.BytesIO(data)) as archive:
            members = archive.infolist()
            for info in members:
                key = info.filename.removesuffix(".npy")
                if allowed is not None and key not in allowed:
                    raise InputError(
                        f"unknown array {key!r} (the archive may hold {', '.join(allowed)})",
                        file=name,
                    )
            declared = sum(info.file_size for info in members)
            if declared > MAX_ARRAY_BYTES + len(members) * NPY_HEADER:
                raise InputError(
                    f"the archive unpacks to {declared:,} bytes; crankdyn reads at most "
                    f"{MAX_ARRAY_BYTES >> 20} MiB of arrays from a NumPy file",
                    file=name,
                )
            total = 0
            for info in members:
                key = info.filename.removesuffix(".npy")
                with archive.open(info) as member:  # stops at the declared size
                    raw = member.read(MAX_ARRAY_BYTES + NPY_HEADER + 1)
                array = npy_array(raw, name, key)
                total += array.size
                if total > MAX_ARRAY_VALUES:
                    raise InputError(
                        f"the arrays hold more than {MAX_ARRAY_VALUES:,} values, the most "
                        "crankdyn reads from a NumPy file",
                        file=name,
                        key=key,
                    )
                arrays[key] = array
    except InputError:
        raise
    except (zipfile.BadZipFile, zlib.error, OSError, EOFError, ValueError) as exc:
        detail = " ".join(str(exc).split())[:80]
        raise InputError(f"not a readable NumPy .npz file ({detail})", file=name) from None
    except (NotImplementedError, RuntimeError) as exc:  # a compression method, an encryption
        detail = " ".join(str(exc).split())[:80]
        raise InputError(f"not a readable NumPy .npz file ({detail})", file=name) from None
    return arrays
