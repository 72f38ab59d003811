"""Study files (TOML) and the built-in example studies; see docs/study-file.md.

A study file names a base engine, the keys of it to vary (by their TOML path, with values in the
file's units), the analysis settings and the figures to keep. Reading it checks everything that
can be checked before a case runs: the base parses, every key path fits the base document, the
values of a parameter agree in unit, and a parameter does not name a key the engine file does
not know (tried on the first case). Whether a particular variant is a valid engine is left to
the case: a bad variant becomes a failed case with the engine file's own message.
"""

from __future__ import annotations

import hashlib
import math
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from crankdyn.errors import InputError, did_you_mean
from crankdyn.io.examples import example_names, example_path
from crankdyn.io.files import display_name, load_toml
from crankdyn.io.schema import Table
from crankdyn.io.units import BARE_SPEED, convert_magnitude, split_quantity
from crankdyn.study.docpath import apply_values, check_path, parse_path, referenced_files
from crankdyn.study.figures import FIGURES, SETTINGS, AnalysisSettings
from crankdyn.study.spec import (
    BASE_KINDS,
    DISTRIBUTIONS,
    SAMPLINGS,
    Base,
    Distribution,
    Parameter,
    StudySpec,
    document_number,
)

if TYPE_CHECKING:
    from crankdyn.engine.model import Engine
    from crankdyn.torsion.model import TorsionModel

__all__ = [
    "load_study",
    "parse_base",
    "parse_study",
]

MAX_RANGE_VALUES = 100_000


def load_study(path: str | Path) -> StudySpec:
    """Load a study file (TOML; format in docs/study-file.md, ``crankdyn docs study-file``).

    Parameters
    ----------
    path
        The study file; a relative base file is looked for beside it.

    Returns
    -------
    StudySpec
        The study: its base, parameters (values in the file's units, numbers in a common unit
        per parameter), sampling, analysis settings and figures.

    Raises
    ------
    InputError
        As :func:`parse_study`, or for an unreadable or malformed file; naming the file, the
        key and the value.
    """
    return _load(Path(path), display_name(path))


def _load(path: Path, name: str) -> StudySpec:
    data = load_toml(path, what="study file")
    return parse_study(data, file=name, base_dir=path.parent, default_name=path.stem)


# ---- the base ---------------------------------------------------------------------------------


def _base(root: Table) -> Base:
    kinds = tuple(BASE_KINDS)
    if not any(k in root.data for k in kinds):
        raise root.error(
            kinds[0],
            f"missing; name the {' or '.join(kinds)} file to vary (or a built-in example), "
            'e.g. engine = "engine.toml"',
        )
    kind = root.exclusive(*kinds)
    assert kind is not None  # one of them is there (above)
    spec = root.string(kind)
    if not spec.strip():
        raise root.error(kind, f"expected the {kind} file's name or a built-in example's", spec)
    folder = root.base_dir or Path(".")
    candidate = Path(spec).expanduser()
    if not candidate.is_absolute():
        candidate = folder / candidate
    looks_like_path = spec.endswith(".toml") or "/" in spec or "\\" in spec
    if not _exists(candidate) and not looks_like_path:
        example, what = _EXAMPLES_OF[kind]
        names = example_names(example)
        if spec not in names:
            raise root.error(
                kind,
                f"no such file or built-in {what} (examples: {', '.join(names)})"
                + did_you_mean(spec, names),
                spec,
            )
        candidate = example_path(spec, example)
        source = f"{spec} (built-in {what})"
    else:
        if not _exists(candidate):
            shown = str(candidate) if str(candidate).isprintable() else ascii(str(candidate))
            raise root.error(kind, f"no such {kind} file (looked for {shown})", spec)
        root.input_file(kind, f"{kind} file")  # a FIFO, a device or a folder is refused
        source = display_name(candidate if Path(spec).is_absolute() else Path(spec))
        if root.base_dir is not None and not Path(spec).is_absolute():
            source = _relative_display(candidate)
    document = load_toml(candidate, what=f"{kind} file")
    digest, files = _files(document, candidate.parent)
    return Base(
        kind=kind,
        document=document,
        source=source,
        base_dir=candidate.parent,
        files_digest=digest,
        files=files,
    )


def parse_base(
    kind: str,
    document: dict[str, Any],
    *,
    file: str | None = None,
    base_dir: Path | None = None,
) -> Engine | TorsionModel:
    """The analysed object (an Engine or a TorsionModel) of a study's base ``document`` of
    ``kind`` (a key of :data:`crankdyn.study.spec.BASE_KINDS`), read with its file reader.

    Parameters
    ----------
    kind
        ``"engine"`` or ``"model"``.
    document
        The base file's parsed TOML (possibly with a case's values applied).
    file
        The base file's name for messages.
    base_dir
        The folder relative file names in the document are taken from.

    Returns
    -------
    Engine or TorsionModel
        The analysed object, in SI.

    Raises
    ------
    InputError
        Whatever the engine or model file reader raises, naming the file, key and value.
    """
    from crankdyn.io.engine_file import parse_engine, parse_model_file

    readers: dict[str, Callable[..., Engine | TorsionModel]] = {
        "engine": parse_engine,
        "model": parse_model_file,
    }
    reader = readers[kind]
    return reader(document, file=file, base_dir=base_dir)


def _exists(path: Path, *, file: bool = False) -> bool:
    """Whether a user-named path exists (is a file); a name the system cannot take (too long,
    a NUL byte) does not."""
    try:
        return path.is_file() if file else path.exists()
    except (OSError, ValueError):
        return False


_EXAMPLES_OF = {  # base kind -> (its example kind, what the examples are called)
    "engine": ("engine", "example"),
    "model": ("model", "model"),
}


def _relative_display(path: Path) -> str:
    try:
        return str(path.resolve().relative_to(Path.cwd().resolve()))
    except ValueError:
        return str(path)


def _files(document: dict, folder: Path) -> tuple[str, tuple[tuple[str, bytes], ...]]:
    """The files the document names (crankdyn.study.docpath.referenced_files): the SHA-256
    over all of them, so that editing a pressure trace changes the study's fingerprint, and
    the contents of those named by relative paths, for workers on other machines."""
    digest = hashlib.sha256()
    files = []
    for text, path in referenced_files(document, folder):
        try:
            data = path.read_bytes()
        except OSError:
            continue
        digest.update(text.encode("utf-8") + b"\0" + hashlib.sha256(data).digest())
        if not Path(text).expanduser().is_absolute():
            files.append((text, data))
    return digest.hexdigest(), tuple(files)


# ---- parameters -------------------------------------------------------------------------------


def _numeric(
    t: Table, key: str, items: list[Any], *, unit: str | None = None
) -> tuple[list[float], str] | None:
    """(magnitudes in a common unit, unit) of numeric items, or None when one is not numeric.
    ``unit`` fixes the unit (else the first item's)."""
    split = []
    for item in items:
        parsed = split_quantity(item, key=t.label(key), file=t.file)
        if parsed is None:
            return None
        split.append((parsed, item))
    if unit is None:
        unit = split[0][0][1]
    numbers = [
        convert_magnitude(m, u, unit, key=t.label(key), file=t.file, value=item)
        for (m, u), item in split
    ]
    return numbers, unit


def _round(x: float) -> float:
    return float(f"{x:.12g}")


def _range(t: Table) -> tuple[tuple[float, ...], str, bool]:
    bounds = t.raw("range")
    if not isinstance(bounds, list) or len(bounds) != 2:
        raise t.error("range", 'expected [low, high], e.g. ["120 mm", "150 mm"]', bounds)
    numeric = _numeric(t, "range", bounds)
    if numeric is None:
        raise t.error(
            "range", 'expected two numbers or quantities, e.g. ["120 mm", "150 mm"]', bounds
        )
    (low, high), unit = numeric
    if not low < high:
        raise t.error("range", "the first value must be below the second", bounds)
    which = t.exclusive("steps", "step")
    spacing = t.string("spacing", "linear", choices=("linear", "log"))
    integer = all(isinstance(b, int) and not isinstance(b, bool) for b in bounds)
    if which == "steps":
        steps = t.integer("steps", minimum=2, maximum=MAX_RANGE_VALUES)
        if spacing == "log":
            if low <= 0.0:
                raise t.error("spacing", "a log range needs positive bounds", spacing)
            values: NDArray[Any] = np.geomspace(low, high, steps)
        else:
            values = np.linspace(low, high, steps)
        integer = integer and all(float(v).is_integer() for v in values)
    else:
        if spacing == "log":
            raise t.error("spacing", "a log range takes steps (a count), not step", spacing)
        raw_step = t.raw("step")
        step_numeric = _numeric(t, "step", [raw_step], unit=unit)
        if step_numeric is None:
            raise t.error("step", "expected a number or a quantity like the range's", raw_step)
        step = step_numeric[0][0]
        if not step > 0.0:
            raise t.error("step", "must be positive", raw_step)
        count = math.floor((high - low) / step * (1 + 1e-12)) + 1
        if count > MAX_RANGE_VALUES:
            raise t.error("step", f"makes more than {MAX_RANGE_VALUES} values", raw_step)
        if count < 2:
            raise t.error("step", "is larger than the range", raw_step)
        values = low + step * np.arange(count)
        integer = integer and isinstance(raw_step, int) and not isinstance(raw_step, bool)
    numbers = tuple(_round(v) for v in values)
    return numbers, unit, integer


def _parameter(t: Table, base_document: dict) -> Parameter:
    raw_key = t.raw("key", expected='a key path such as "geometry.rod_length"')
    texts = raw_key if isinstance(raw_key, list) and raw_key else [raw_key]
    paths = [parse_path(text, file=t.file, key=t.label("key")) for text in texts]
    for path in paths:
        check_path(base_document, path, file=t.file, key=t.label("key"))
    path, also = paths[0], tuple(paths[1:])
    which = t.exclusive("values", "range", "distribution")
    if which == "values":
        items = t.raw("values")
        if not isinstance(items, list) or not items:
            raise t.error("values", "expected a non-empty list of values", items)
        for i, item in enumerate(items):
            if item in items[:i]:
                raise t.error("values", "a value is given twice", item)
        numeric = _numeric(t, "values", items)
        t.finish()
        if numeric is None:
            return Parameter(path=path, also=also, values=tuple(items))
        numbers, unit = numeric
        return Parameter(
            path=path, also=also, values=tuple(items), numbers=tuple(numbers), unit=unit
        )
    if which == "range":
        range_numbers, unit, integer = _range(t)
        t.finish()
        values = tuple(document_number(n, unit, integer) for n in range_numbers)
        return Parameter(
            path=path, also=also, values=values, numbers=range_numbers, unit=unit, integer=integer
        )
    name = t.string("distribution", choices=tuple(DISTRIBUTIONS))
    arg_names = DISTRIBUTIONS[name][0]
    raw = [t.raw(a, expected="a number or a quantity") for a in arg_names]
    numeric = _numeric(t, arg_names[0], raw)
    if numeric is None:
        bad = next(a for a, r in zip(arg_names, raw, strict=True) if split_quantity(r) is None)
        raise t.error(bad, "expected a number or a quantity", t.data[bad])
    args, unit = numeric
    t.finish()
    with t.context():
        try:
            distribution = Distribution(name, tuple(args))
        except InputError as exc:
            if exc.key in t.data:
                raise t.error(exc.key, exc.message, t.data[exc.key]) from None
            raise
        return Parameter(path=path, also=also, unit=unit, distribution=distribution)


# ---- the whole file ---------------------------------------------------------------------------


def _settings(t: Table | None) -> tuple[AnalysisSettings, tuple[str, ...]]:
    if t is None:
        raise InputError(
            'missing table [analysis]; it names the figures to keep, e.g. figures = ["mean_torque"]'
        )
    values = []
    for name, setting in SETTINGS.items():
        if setting.kind == "number":
            value = t.number(name, None, check=setting.check)
        elif setting.kind == "strings":
            value = t.string_list(name, None, length=setting.length)
        elif setting.kind.startswith("list:"):
            value = t.quantity_list(
                name, setting.kind[5:], None, length=setting.length, check=setting.check
            )
        else:
            value = t.quantity(name, setting.kind, None, check=setting.check)
        if value is not None:
            values.append((name, value))
    step = dict(values).get("step")
    if step is not None:
        count = 2.0 * math.pi / step
        if abs(count - round(count)) > 1e-9 * count:
            raise t.error("step", "must divide 360 deg (e.g. 0.5, 1, 2 or 5 deg)", t.data["step"])
    names = t.string_list("figures")
    if not names:
        raise t.error("figures", "name at least one figure", names)
    for i, name in enumerate(names):
        if name not in FIGURES:
            raise t.error(
                "figures",
                f"unknown figure{did_you_mean(name, FIGURES)} (crankdyn study --list shows them)",
                name,
            )
        if name in names[:i]:
            raise t.error("figures", "a figure is named twice", name)
    t.finish()
    return AnalysisSettings(tuple(values)), tuple(names)


def parse_study(
    data: dict,
    *,
    file: str | None = None,
    base_dir: Path | None = None,
    default_name: str = "study",
) -> StudySpec:
    """Build a StudySpec from a parsed study document (module docstring for the checks).

    Parameters
    ----------
    data
        The parsed study document (a dict as from tomllib).
    file
        The study file's name for messages.
    base_dir
        The folder the base file and other relative names are looked for in (None: the
        working folder).
    default_name
        The study's name when the document gives none.

    Returns
    -------
    StudySpec
        The study, checked as far as it can be before a case runs.

    Raises
    ------
    InputError
        For a missing or unknown base file or example, a base that does not parse, a key path
        that does not fit the base, values that disagree in unit, a bad range, distribution,
        sampling or figure, or a parameter naming a key the base's reader does not know;
        naming the file, the key and the value.
    """
    root = Table(data, file=file, base_dir=base_dir)
    name = root.string("name", default_name)
    base = _base(root)
    try:
        parse_base(base.kind, base.document, file=base.source, base_dir=base.base_dir)
    except InputError as exc:
        raise exc.within(file=base.source) from None
    remove = tuple(
        parse_path(text, file=file, key=root.label("remove"))
        for text in root.string_list("remove", [])
    )
    for path in remove:
        if path.parts[-1][1] is not None:
            raise root.error("remove", "name a key, not an entry of an array", path.text)
        check_path(base.document, path, must_exist=True, file=file, key=root.label("remove"))
    trimmed = apply_values(base.document, {}, remove)
    entries = root.tables("parameter", required=True)
    parameters: list[Parameter] = []
    for t in entries:
        p = _parameter(t, trimmed)
        taken = {path.text for q in parameters for path in q.paths}
        mine = [path.text for path in p.paths]
        for i, text in enumerate(mine):
            if text in taken or text in mine[:i]:
                raise t.error("key", "the key is varied twice", text)
        parameters.append(p)
    settings, figures = _settings(root.table("analysis"))
    mc = root.table("monte_carlo")
    samples = seed = None
    sampling = "random"
    if mc is not None:
        samples = mc.integer("samples", minimum=1, maximum=1_000_000)
        seed = mc.integer("seed", minimum=0)
        sampling = mc.string("sampling", "random", choices=SAMPLINGS)
        mc.finish()
    random = [p for p in parameters if p.is_random]
    if random and mc is None:
        raise root.error(
            None,
            f"parameter {random[0].key} has a distribution: give [monte_carlo] samples and seed",
        )
    if mc is not None and not random:
        raise mc.error(None, "no parameter has a distribution, so there is nothing to sample")
    best = _best(root.table("best"), figures)
    if settings.given("speed"):
        for t, p in zip(entries, parameters, strict=True):
            if p.key == "operating.speed":
                raise t.error(
                    "key",
                    "the speed is varied here and fixed by [analysis] speed; keep one",
                    p.key,
                )
    root.finish(also_known=tuple(BASE_KINDS))
    with root.context():
        spec = StudySpec(
            name=name,
            base=base,
            parameters=tuple(parameters),
            figures=figures,
            settings=settings,
            remove=remove,
            samples=samples,
            seed=seed,
            sampling=sampling,
            best=best,
            source=file,
        )
    _probe(spec, entries)
    return spec


def _best(t: Table | None, figures: tuple[str, ...]) -> tuple[tuple[str, str], ...]:
    if t is None:
        return ()
    out = []
    for key in list(t.data):
        if key not in figures:
            raise t.error(
                key, f"is not among the figures kept{did_you_mean(key, figures)}", t.data[key]
            )
        out.append((key, t.string(key, choices=("min", "max"))))
    t.finish()
    return tuple(out)


def _refuse_bare_speed(spec: StudySpec, entries: list[Table], exc: InputError) -> None:
    """A parameter that varies a speed with bare numbers, refused at its values as the base
    file refuses a bare speed (:data:`crankdyn.io.units.BARE_SPEED`)."""
    for t, p in zip(entries, spec.parameters, strict=True):
        for path in p.paths:
            name = path.parts[-1][0]
            if exc.key and exc.key.split(" ")[-1].strip('"') == name:
                which = next((k for k in ("values", "range") if k in t.data), "key")
                raise t.error(which, BARE_SPEED, t.data[which]) from None


def _probe(spec: StudySpec, entries: list[Table]) -> None:
    """Stop before running when a parameter names a key the base file's reader does not know,
    or varies a speed with bare numbers (tried on the first case: every case would fail the
    same way)."""
    first = {
        path: p.values[0]
        if p.values is not None
        # a parameter without values has a distribution (Parameter's invariant)
        else p.document_value(p.distribution.quantile(0.5))  # type: ignore[union-attr, arg-type]
        for p in spec.parameters
        for path in p.paths
    }
    document = apply_values(spec.base.document, first, spec.remove)
    try:
        parse_base(spec.base.kind, document, file=spec.base.source, base_dir=spec.base.base_dir)
    except InputError as exc:
        if exc.message == BARE_SPEED:  # a speed varied as bare numbers: every case fails
            _refuse_bare_speed(spec, entries, exc)
        if not exc.message.startswith("unknown key"):
            return  # a property of that variant, recorded when the case runs
        for t, p in zip(entries, spec.parameters, strict=True):
            for path in p.paths:
                name = path.parts[-1][0]
                if exc.key and exc.key.split(" ")[-1].strip('"') == name:
                    raise t.error(
                        "key",
                        f"the {spec.base.kind} file has no such key ({exc.message})",
                        path.text,
                    ) from None
        raise InputError(
            f"a parameter names a key the {spec.base.kind} file does not know: {exc}",
            file=spec.source,
        ) from None
