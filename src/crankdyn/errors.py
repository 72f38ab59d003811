"""The one error type for user mistakes.

Every mistake in user input (a file, a key, a value, a command-line option) raises
:class:`InputError`. Its text is a single line that names where the mistake is (file, key) and
what was found and expected, e.g.::

    engine.toml: [geometry] bore = "76 kg": expected a length (e.g. "76 mm"), got a mass

Domain objects raise it with ``key`` set to their field name; the file loaders add the file and
the section (:meth:`InputError.within`). The command line prints it on one line and exits with
status 2. Anything else that escapes is a bug and keeps its traceback.
"""

from __future__ import annotations

import math
from collections.abc import Iterable

__all__ = ["InputError", "closest", "did_you_mean", "format_value"]

_MAX_VALUE_CHARS = 60


def format_value(value: object) -> str:
    """Render a user value as it would appear in a TOML file, shortened to one short line.

    Parameters
    ----------
    value : object
        The value as the user gave it.

    Returns
    -------
    str
        TOML-like text (strings quoted, booleans lower case), control characters escaped, at
        most 60 characters.

    Examples
    --------
    >>> format_value("76 kg"), format_value([1, True])
    ('"76 kg"', '[1, true]')
    """
    if isinstance(value, str):
        text = '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    elif isinstance(value, bool):
        text = "true" if value else "false"
    elif isinstance(value, float):
        text = repr(value) if math.isfinite(value) else str(value)
    elif isinstance(value, (list, tuple)):
        text = "[" + ", ".join(format_value(v) for v in value) + "]"
    elif isinstance(value, dict):
        text = "{" + ", ".join(f"{k} = {format_value(v)}" for k, v in value.items()) + "}"
    else:
        text = repr(value)
    text = _one_line(text)  # no newlines, ever
    if len(text) > _MAX_VALUE_CHARS:
        text = text[: _MAX_VALUE_CHARS - 3] + "..."
    return text


def did_you_mean(word: object, candidates: Iterable[object], cutoff: float = 0.6) -> str:
    """The one "did you mean" hint of crankdyn.

    Parameters
    ----------
    word : object
        What the user wrote.
    candidates : iterable
        The names that exist.
    cutoff : float
        Least similarity (difflib's ratio, 0 to 1) of a match; default 0.6.

    Returns
    -------
    str
        ``' (did you mean "x"?)'`` for the closest candidate, else ``""``.

    Examples
    --------
    >>> did_you_mean("crank_radus", ["bore", "crank_radius"])
    ' (did you mean "crank_radius"?)'
    """
    match = closest(word, candidates, cutoff)
    return f' (did you mean "{match}"?)' if match is not None else ""


def closest(word: object, candidates: Iterable[object], cutoff: float = 0.6) -> str | None:
    """The candidate closest to a word.

    Parameters
    ----------
    word : object
        What the user wrote.
    candidates : iterable
        The names that exist.
    cutoff : float
        Least similarity (difflib's ratio, 0 to 1); default 0.6.

    Returns
    -------
    str or None
        The closest candidate (as text), or None when none is similar enough.
    """
    import difflib

    match = difflib.get_close_matches(str(word), [str(c) for c in candidates], n=1, cutoff=cutoff)
    return match[0] if match else None


_NO_VALUE = object()


def _no_controls(text: str) -> str:
    """Control characters (a name's ESC, BEL) shown escaped; other text as it is."""
    if text.isprintable():
        return text
    import unicodedata

    return "".join(
        repr(ch)[1:-1] if unicodedata.category(ch) == "Cc" or ch in "\u2028\u2029" else ch
        for ch in text
    )


def _one_line(text: str) -> str:
    """Control characters shown escaped, so that a message is always one line."""
    if text.isprintable():
        return text
    return "".join(ch if ch.isprintable() else repr(ch)[1:-1] for ch in text)


class InputError(ValueError):
    """A mistake in user input, reported on one line.

    Parameters
    ----------
    message : str
        What is wrong and what was expected, e.g. ``"must be longer than the crank radius"``.
    file : str or None
        The file the value came from, if any.
    key : str or None
        The key (or command-line option) that holds the value, e.g. ``"[geometry] bore"``.
    value : object
        The offending value as the user wrote it (omitted: no value is shown).

    Examples
    --------
    >>> str(InputError("expected a length", file="engine.toml", key="[geometry] bore",
    ...                value="76 kg"))
    'engine.toml: [geometry] bore = "76 kg": expected a length'
    """

    def __init__(
        self,
        message: str,
        *,
        file: str | None = None,
        key: str | None = None,
        value: object = _NO_VALUE,
    ) -> None:
        self.message = _no_controls(" ".join(str(message).split()))
        self.file = None if file is None else _one_line(str(file))
        self.key = None if key is None else _one_line(str(key))
        self.value = value
        super().__init__(str(self))

    @property
    def has_value(self) -> bool:
        """Whether the error carries the offending value (None may be a value)."""
        return self.value is not _NO_VALUE

    def within(self, *, file: str | None = None, section: str | None = None) -> InputError:
        """This error with a file and a section prefix added where they are missing.

        Parameters
        ----------
        file : str or None
            The file the error belongs to (kept when the error names another file).
        section : str or None
            The TOML section, e.g. ``"[geometry]"``, put before the key.

        Returns
        -------
        InputError
            A new error.

        Examples
        --------
        >>> str(InputError("must be positive", key="bore").within(file="e.toml",
        ...                                                        section="[geometry]"))
        'e.toml: [geometry] bore: must be positive'
        """
        key = self.key
        if self.file is not None and file is not None and self.file != file:
            section = None  # the error belongs to another file (e.g. a trace named by this one)
        if section and key and not key.startswith("["):
            key = f"{section} {key}"
        elif section and not key:
            key = section
        return InputError(
            self.message,
            file=self.file if self.file is not None else file,
            key=key,
            value=self.value,
        )

    def __str__(self) -> str:
        where = []
        if self.file:
            where.append(self.file)
        if self.key:
            item = self.key
            if self.has_value:
                item += f" = {format_value(self.value)}"
            where.append(item)
        elif self.has_value:
            where.append(format_value(self.value))
        return ": ".join([*where, self.message])

    def __reduce__(self) -> tuple[object, ...]:  # picklable for process pools (not the sentinel)
        value = self.value if self.has_value else None
        return (_rebuild, (self.message, self.file, self.key, self.has_value, value))


def _rebuild(
    message: str, file: str | None, key: str | None, has_value: bool, value: object
) -> InputError:
    if has_value:
        return InputError(message, file=file, key=key, value=value)
    return InputError(message, file=file, key=key)
