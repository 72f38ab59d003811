"""Declarative reading of TOML tables with one-line errors (shared by every file format).

A :class:`Table` wraps one TOML table. Each accessor reads one key, converts it (quantities through
:mod:`crankdyn.io.units`), checks it, and records the key as known; :meth:`Table.finish` then
rejects any key that was never asked for, with a "did you mean" suggestion. Errors name the file,
the key (with its section, e.g. ``[geometry] bore``) and the value.

Every quantity and number a file gives is also held to the plausible range of its role
(:mod:`crankdyn.io.plausibility`): outside it the table records an
:class:`~crankdyn.plausibility.InputWarning` in :attr:`Table.warnings`, a list the table shares
with its sub-tables, which the file's reader hands to the domain objects it makes
(``input_warnings``).
"""

from __future__ import annotations

import json
import math
import re
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any, Literal, overload

from crankdyn.errors import InputError, closest, did_you_mean
from crankdyn.io.plausibility import check_input, check_speed_range, section_of
from crankdyn.io.units import KINDS, check_si_range, parse_quantity
from crankdyn.plausibility import PlausibilityWarning

__all__ = ["MISSING", "Table"]


class _Missing:
    def __repr__(self) -> str:
        return "MISSING"


MISSING: Any = _Missing()

_BARE_KEY = re.compile(r"[A-Za-z0-9_-]+")

_CHECKS = {
    None: (lambda v: True, ""),
    "positive": (lambda v: v > 0.0, "must be positive"),
    "nonnegative": (lambda v: v >= 0.0, "must not be negative"),
}


class Table:
    """One table of a TOML document.

    Parameters
    ----------
    data
        The parsed table.
    file
        The file name for messages.
    name
        The section as the user wrote it, e.g. ``"[geometry]"``; ``""`` for the top level.
    base_dir
        Directory against which relative paths in the table are resolved.
    warnings
        The list the table records its plausibility warnings in (a sub-table shares its
        parent's); default a new one.

    Attributes
    ----------
    warnings : list of crankdyn.plausibility.InputWarning
        The values read so far that lie outside the plausible range of their role
        (:func:`crankdyn.io.plausibility.check_input`), of this table and its sub-tables.
    """

    def __init__(
        self,
        data: Any,
        *,
        file: str | None,
        name: str = "",
        base_dir: Path | None = None,
        warnings: list[PlausibilityWarning] | None = None,
    ):
        if not isinstance(data, dict):
            raise InputError("expected a table", file=file, key=name or None, value=data)
        self.data = data
        self.file = file
        self.name = name
        self.base_dir = base_dir
        self.warnings: list[PlausibilityWarning] = [] if warnings is None else warnings
        self._known: set[str] = set()

    # ---- messages -----------------------------------------------------------------------------
    def label(self, key: str) -> str:
        """How a key is named in messages: ``[section] key`` (quoted as TOML writes keys that
        are not bare).

        Parameters
        ----------
        key
            The key in this table.

        Returns
        -------
        str
            The label.

        Examples
        --------
        >>> Table({}, file="e.toml", name="[geometry]").label("bore")
        '[geometry] bore'
        >>> Table({}, file="e.toml").label("a b")
        '"a b"'
        """
        shown = key if _BARE_KEY.fullmatch(key) else json.dumps(key)
        return f"{self.name} {shown}" if self.name else shown

    def error(self, key: str | None, message: str, value: Any = MISSING) -> InputError:
        """An InputError for a key of this table (value omitted when MISSING).

        Parameters
        ----------
        key
            The key in this table, or None for the table itself.
        message
            What is wrong, in one line.
        value
            The value as the user wrote it (omitted when MISSING).

        Returns
        -------
        InputError
            The error (for the caller to raise), naming the file, ``[section] key`` and value.

        Examples
        --------
        >>> print(Table({}, file="e.toml", name="[geometry]").error("bore", "must be positive", -1))
        e.toml: [geometry] bore = -1: must be positive
        """
        label = self.label(key) if key else (self.name or None)
        if value is MISSING:
            return InputError(message, file=self.file, key=label)
        return InputError(message, file=self.file, key=label, value=value)

    @contextmanager
    def context(self) -> Iterator[None]:
        """Add this table's file and section to InputErrors raised inside (e.g. by domain
        objects validating themselves, which name only their own field).

        Yields
        ------
        None
            Control to the ``with`` block.

        Raises
        ------
        InputError
            The error raised inside, with this table's file and section added.
        """
        try:
            yield
        except InputError as exc:
            raise exc.within(file=self.file, section=self.name or None) from None

    # ---- presence -----------------------------------------------------------------------------
    def has(self, key: str) -> bool:
        """Whether the key is present (and records it as known).

        Parameters
        ----------
        key
            The key in this table.

        Returns
        -------
        bool
            True when the table holds it.
        """
        self._known.add(key)
        return key in self.data

    def raw(self, key: str, default: Any = MISSING, *, expected: str = "a value") -> Any:
        """The raw value, or default; a missing key without default is an error.

        Parameters
        ----------
        key
            The key in this table.
        default
            Returned as it is when the key is absent (None for an optional key); without it a
            missing key is an error.
        expected
            What the key should hold, for the message of a missing key.

        Returns
        -------
        Any
            The value as parsed from TOML, or ``default``.

        Raises
        ------
        InputError
            Naming the file, the key (``[section] key``) and the value as written.
        """
        self._known.add(key)
        if key in self.data:
            return self.data[key]
        if default is MISSING:
            # a near-miss spelling in the file is the likelier mistake than a missing key
            others = [k for k in self.data if k not in self._known]
            close = closest(key, others, cutoff=0.75)
            if close is not None:
                raise self.error(close, f'unknown key (did you mean "{key}"?)', self.data[close])
            raise self.error(key, f"missing; expected {expected}")
        return default

    @overload
    def exclusive(self, *keys: str, required: Literal[True] = ...) -> str: ...

    @overload
    def exclusive(self, *keys: str, required: bool) -> str | None: ...

    def exclusive(self, *keys: str, required: bool = True) -> str | None:
        """Which one of several alternative keys is given (e.g. stroke or crank_radius).

        Parameters
        ----------
        *keys
            The alternative keys.
        required
            Whether one of them must be given.

        Returns
        -------
        str or None
            The key given; None when none is and ``required`` is false.

        Raises
        ------
        InputError
            When more than one is given, or none and ``required`` (a near-miss spelling is
            named), naming the file and the key.
        """
        present = [k for k in keys if self.has(k)]
        if len(present) > 1:
            raise self.error(
                present[1], f"give only one of {', '.join(keys)}", self.data[present[1]]
            )
        if not present:
            if required:
                # as in raw(): a near-miss spelling is the likelier mistake than a missing key
                others = [k for k in self.data if k not in self._known]
                for key in keys:
                    close = closest(key, others, cutoff=0.75)
                    if close is not None:
                        raise self.error(
                            close, f'unknown key (did you mean "{key}"?)', self.data[close]
                        )
                raise self.error(keys[0], f"missing; give one of {', '.join(keys)}")
            return None
        return present[0]

    # ---- typed accessors ----------------------------------------------------------------------
    def quantity(
        self, key: str, kind: str, default: Any = MISSING, *, check: str | None = None
    ) -> Any:
        """A physical quantity in SI (unit string or bare SI number); optional sign check.

        Parameters
        ----------
        key
            The key in this table.
        kind
            A key of :data:`crankdyn.io.units.KINDS` (``"length"``, ``"speed"``...).
        default
            Returned as it is when the key is absent (None for an optional key); without it a
            missing key is an error.
        check
            ``"positive"``, ``"nonnegative"`` or None: the sign the SI value must have.

        Returns
        -------
        float or the default
            The value in the SI unit of ``kind`` (m, rad/s, Pa...), or ``default``.

        Examples
        --------
        >>> Table({"bore": "86 mm"}, file="e.toml").quantity("bore", "length")
        0.086

        Raises
        ------
        InputError
            Naming the file, the key (``[section] key``) and the value as written.
        """
        value = self.raw(
            key, default, expected=f'{KINDS[kind].name} such as "{KINDS[kind].example}"'
        )
        if value is default and key not in self.data:
            return value
        number = parse_quantity(value, kind, key=self.label(key), file=self.file)
        self._check(key, value, number, check)
        self.plausible(key, kind, number, value)
        return number

    def quantity_list(
        self,
        key: str,
        kind: str,
        default: Any = MISSING,
        *,
        length: int | None = None,
        check: str | None = None,
    ) -> Any:
        """A list of quantities in SI.

        Parameters
        ----------
        key
            The key in this table.
        kind
            A key of :data:`crankdyn.io.units.KINDS`.
        default
            Returned as it is when the key is absent (None for an optional key); without it a
            missing key is an error.
        length
            The number of entries required, or None for any (at least one).
        check
            ``"positive"``, ``"nonnegative"`` or None: the sign the SI value must have.

        Returns
        -------
        tuple of float, or the default
            The values in the SI unit of ``kind``, or ``default``.

        Raises
        ------
        InputError
            Naming the file, the key (``[section] key``) and the value as written.
        """
        value = self.raw(key, default, expected=f"a list of {KINDS[kind].name}s")
        if value is default and key not in self.data:
            return value
        if not isinstance(value, list) or not value:
            raise self.error(key, f"expected a list of {KINDS[kind].name}s", value)
        if length is not None and len(value) != length:
            raise self.error(key, f"expected {length} values, got {len(value)}", value)
        out = []
        for item in value:
            number = parse_quantity(item, kind, key=self.label(key), file=self.file)
            self._check(key, value, number, check)
            out.append(number)
        for number, item in zip(out, value, strict=True):  # a warning per implausible item
            self.plausible(key, kind, number, item)
        return tuple(out)

    def item(self, key: str, value: Any, kind: str) -> float:
        """One item of a key's value (a row of a table written as a list of lists, e.g.
        ``stiffness_table``'s torques) in SI, checked against the plausible range of the
        key's role (:meth:`plausible`) as :meth:`quantity` checks a key.

        Parameters
        ----------
        key
            The key in this table (named in messages).
        value
            The item as written (``"25 kN*m"``).
        kind
            A key of :data:`crankdyn.io.units.KINDS`.

        Returns
        -------
        float
            The value in the SI unit of ``kind``.

        Raises
        ------
        InputError
            Naming the file, the key (``[section] key``) and the item as written.
        """
        number = parse_quantity(value, kind, key=self.label(key), file=self.file)
        self.plausible(key, kind, number, value)
        return number

    def plausible(self, key: str, kind: str, value: float, written: Any) -> bool:
        """Hold a value read from this table to the plausible range of its role
        (:func:`crankdyn.io.plausibility.check_input`), recording a warning in
        :attr:`warnings` when it lies outside.

        Parameters
        ----------
        key
            The key in this table.
        kind
            Its kind (a key of :data:`crankdyn.io.units.KINDS`, ``"ratio"`` for a number).
        value
            The value (SI).
        written
            The value as written.

        Returns
        -------
        bool
            True when the value is plausible (no warning).
        """
        found = check_input(
            value,
            kind,
            key,
            section=section_of(self.name),
            label=self.label(key),
            file=self.file,
            written=written,
        )
        if found is not None and found not in self.warnings:
            self.warnings.append(found)
        return found is None

    def speed_range(self, key: str, pair: Any, rated: float | None, written: Any = MISSING) -> None:
        """Hold a speed range's upper end to the rated speed
        (:func:`crankdyn.io.plausibility.check_speed_range`), recording a warning in
        :attr:`warnings` when it ends far from n_0 (a speed in the wrong unit).

        Parameters
        ----------
        key
            The range's key in this table.
        pair
            (low, high) in rad/s, or None (nothing is checked).
        rated
            The rated speed n_0 (rad/s), or None (nothing is checked).
        written
            The range as written; default the table's value of ``key``.
        """
        if pair is None or rated is None:
            return
        shown = self.data.get(key) if written is MISSING else written
        found = check_speed_range(
            pair[1], rated, label=self.label(key), file=self.file, written=shown
        )
        if found is not None and found not in self.warnings:
            self.warnings.append(found)

    def number(
        self,
        key: str,
        default: Any = MISSING,
        *,
        check: str | None = None,
        minimum: float | None = None,
        maximum: float | None = None,
        integer: bool = False,
    ) -> Any:
        """A plain number (int or float in the file); optional range.

        Parameters
        ----------
        key
            The key in this table.
        default
            Returned as it is when the key is absent (None for an optional key); without it a
            missing key is an error.
        check
            ``"positive"``, ``"nonnegative"`` or None: the sign the SI value must have.
        minimum, maximum
            Bounds the number must lie within (same unit as written), or None.
        integer
            Whether it must be a whole number (then not held to the SI range).

        Returns
        -------
        float, int or the default
            The number (an int when ``integer``), or ``default``.

        Raises
        ------
        InputError
            Naming the file, the key (``[section] key``) and the value as written.
        """
        what = "a whole number" if integer else "a number"
        value = self.raw(key, default, expected=what)
        if value is default and key not in self.data:
            return value
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise self.error(key, f"expected {what}", value)
        if integer and not isinstance(value, int):
            raise self.error(key, f"expected {what}", value)
        if not math.isfinite(value):
            raise self.error(key, "the value is not finite", value)
        if not integer and not check_si_range(float(value)):
            raise self.error(
                key, "lies outside the range crankdyn computes with (1e-12 to 1e12)", value
            )
        self._check(key, value, float(value), check)
        if minimum is not None and value < minimum:
            raise self.error(key, f"must be at least {minimum:g}", value)
        if maximum is not None and value > maximum:
            raise self.error(key, f"must be at most {maximum:g}", value)
        if integer:
            return int(value)
        self.plausible(key, "ratio", float(value), value)
        return float(value)

    def integer(
        self,
        key: str,
        default: Any = MISSING,
        *,
        minimum: int | None = None,
        maximum: int | None = None,
    ) -> Any:
        """A whole number.

        Parameters
        ----------
        key
            The key in this table.
        default
            Returned as it is when the key is absent (None for an optional key); without it a
            missing key is an error.
        minimum, maximum
            Bounds it must lie within, or None.

        Returns
        -------
        int or the default
            The number, or ``default``.

        Raises
        ------
        InputError
            Naming the file, the key (``[section] key``) and the value as written.
        """
        return self.number(key, default, minimum=minimum, maximum=maximum, integer=True)

    def integer_list(self, key: str, default: Any = MISSING, *, length: int | None = None) -> Any:
        """A list of whole numbers.

        Parameters
        ----------
        key
            The key in this table.
        default
            Returned as it is when the key is absent (None for an optional key); without it a
            missing key is an error.
        length
            The number of entries required, or None for any (at least one).

        Returns
        -------
        tuple of int, or the default
            The numbers, or ``default``.

        Raises
        ------
        InputError
            Naming the file, the key (``[section] key``) and the value as written.
        """
        value = self.raw(key, default, expected="a list of whole numbers")
        if value is default and key not in self.data:
            return value
        if (
            not isinstance(value, list)
            or not value
            or any(isinstance(v, bool) or not isinstance(v, int) for v in value)
        ):
            raise self.error(key, "expected a list of whole numbers", value)
        if length is not None and len(value) != length:
            raise self.error(key, f"expected {length} numbers, got {len(value)}", value)
        return tuple(value)

    def string(
        self, key: str, default: Any = MISSING, *, choices: tuple[str, ...] | None = None
    ) -> Any:
        """A string, optionally one of ``choices`` (with a suggestion for near misses).

        Parameters
        ----------
        key
            The key in this table.
        default
            Returned as it is when the key is absent (None for an optional key); without it a
            missing key is an error.
        choices
            The strings allowed, or None for any.

        Returns
        -------
        str or the default
            The string, or ``default``.

        Raises
        ------
        InputError
            Naming the file, the key (``[section] key``) and the value as written.
        """
        expected = f"one of {', '.join(repr(c) for c in choices)}" if choices else "a string"
        value = self.raw(key, default, expected=expected)
        if value is default and key not in self.data:
            return value
        if not isinstance(value, str):
            raise self.error(key, f"expected {expected}", value)
        if choices and value not in choices:
            raise self.error(key, f"expected {expected}{did_you_mean(value, choices)}", value)
        return value

    def string_list(
        self,
        key: str,
        default: Any = MISSING,
        *,
        length: int | None = None,
        choices: tuple[str, ...] | None = None,
    ) -> Any:
        """A list of strings.

        Parameters
        ----------
        key
            The key in this table.
        default
            Returned as it is when the key is absent (None for an optional key); without it a
            missing key is an error.
        length
            The number of entries required, or None for any.
        choices
            The strings allowed in it, or None for any.

        Returns
        -------
        tuple of str, or the default
            The strings, or ``default``.

        Raises
        ------
        InputError
            Naming the file, the key (``[section] key``) and the value as written.
        """
        value = self.raw(key, default, expected="a list of strings")
        if value is default and key not in self.data:
            return value
        if not isinstance(value, list) or any(not isinstance(v, str) for v in value):
            raise self.error(key, "expected a list of strings", value)
        if length is not None and len(value) != length:
            raise self.error(key, f"expected {length} entries, got {len(value)}", value)
        if choices:
            for v in value:
                if v not in choices:
                    raise self.error(
                        key,
                        f"entries must be one of {', '.join(choices)}{did_you_mean(v, choices)}",
                        value,
                    )
        return tuple(value)

    def boolean(self, key: str, default: Any = MISSING) -> bool:
        """true or false.

        Parameters
        ----------
        key
            The key in this table.
        default
            The value when the key is absent; without it a missing key is an error.

        Returns
        -------
        bool
            The value.

        Raises
        ------
        InputError
            Naming the file, the key (``[section] key``) and the value as written.
        """
        value = self.raw(key, default, expected="true or false")
        if not isinstance(value, bool):
            raise self.error(key, "expected true or false", value)
        return value

    def path(self, key: str, default: Any = MISSING) -> Path:
        """A file path, resolved relative to the directory of the file that names it.

        Parameters
        ----------
        key
            The key in this table.
        default
            Returned as it is when the key is absent (None for an optional key); without it a
            missing key is an error.

        Returns
        -------
        Path
            The path (``~`` expanded; a relative one taken from the table's ``base_dir``), or
            ``default``.

        Raises
        ------
        InputError
            Naming the file, the key (``[section] key``) and the value as written.
        """
        value = self.string(key, default)
        if value is default and key not in self.data:
            return value
        if not value.strip():
            raise self.error(key, "expected a file name", value)
        p = Path(value).expanduser()
        if not p.is_absolute() and self.base_dir is not None:
            p = self.base_dir / p
        return p

    def input_file(self, key: str, what: str) -> Path:
        """The path of an input file this table names (:meth:`path`), which must be a regular
        file: a missing file, a folder, a FIFO (whose open would wait for a writer) or a device
        is refused here, naming the key, before anything opens it.

        Parameters
        ----------
        key
            The key in this table.
        what
            What the file is, in words, for the message.

        Returns
        -------
        Path
            The file's path.

        Raises
        ------
        InputError
            Naming the file, the key (``[section] key``) and the value as written.
        """
        from crankdyn.io.files import check_regular

        p = self.path(key)
        try:
            check_regular(p, what=what)
        except InputError as exc:
            if not p.exists():
                raise self.error(key, f"no such {what} (looked for {p})", self.data[key]) from None
            raise self.error(key, f"{p} {exc.message}", self.data[key]) from None
        return p

    @overload
    def table(self, key: str, *, required: Literal[True]) -> Table: ...

    @overload
    def table(self, key: str, *, required: bool = False) -> Table | None: ...

    def table(self, key: str, *, required: bool = False) -> Table | None:
        """A sub-table ``[key]`` (None when absent and not required).

        Parameters
        ----------
        key
            The key in this table.
        required
            Whether a missing sub-table is an error.

        Returns
        -------
        Table or None
            The sub-table (named ``[section.key]`` in messages), or None.

        Raises
        ------
        InputError
            Naming the file, the key (``[section] key``) and the value as written.
        """
        self._known.add(key)
        if key not in self.data:
            if required:
                raise self.error(None, f"missing table [{self._sub(key)}]")
            return None
        name = f"[{self._sub(key)}]"
        if not isinstance(self.data[key], dict):
            raise InputError(
                f"expected a table [{self._sub(key)}]",
                file=self.file,
                key=key,
                value=self.data[key],
            )
        return Table(
            self.data[key],
            file=self.file,
            name=name,
            base_dir=self.base_dir,
            warnings=self.warnings,
        )

    def tables(self, key: str, *, required: bool = False) -> list[Table]:
        """An array of tables ``[[key]]``; entries are named ``[[key]] #n`` in messages.

        Parameters
        ----------
        key
            The key in this table.
        required
            Whether a missing array is an error.

        Returns
        -------
        list of Table
            The entries (empty when absent and not required).

        Raises
        ------
        InputError
            Naming the file, the key (``[section] key``) and the value as written.
        """
        self._known.add(key)
        if key not in self.data:
            if required:
                raise self.error(None, f"missing [[{self._sub(key)}]] entries")
            return []
        items = self.data[key]
        if not isinstance(items, list) or any(not isinstance(i, dict) for i in items):
            raise InputError(
                f"expected [[{self._sub(key)}]] tables", file=self.file, key=key, value=items
            )
        return [
            Table(
                item,
                file=self.file,
                name=f"[[{self._sub(key)}]] #{n}",
                base_dir=self.base_dir,
                warnings=self.warnings,
            )
            for n, item in enumerate(items, start=1)
        ]

    def finish(self, *, also_known: tuple[str, ...] = ()) -> None:
        """Reject keys that were never read, suggesting the nearest known key.

        Parameters
        ----------
        also_known
            Keys to accept although they were not read here.

        Raises
        ------
        InputError
            For the first unknown key, naming the file, the key and its value.
        """
        known = self._known | set(also_known)
        for key in self.data:
            if key not in known:
                raise self.error(
                    key, f"unknown key{did_you_mean(key, sorted(known))}", self.data[key]
                )

    # ---- helpers ------------------------------------------------------------------------------
    def _sub(self, key: str) -> str:
        inner = self.name.strip("[]").split(" ")[0] if self.name else ""
        return f"{inner}.{key}" if inner else key

    def _check(self, key: str, value: Any, number: float, check: str | None) -> None:
        test, message = _CHECKS[check]
        if not test(number):
            raise self.error(key, message, value)
