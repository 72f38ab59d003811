"""The one catalogue of built-in examples and the resolution of command-line arguments.

Every kind of input (engine, torsional model, linkage, study) is found the same way: a path to a
file, or the name of a built-in example (:mod:`crankdyn.io.examples` locates the files).
:func:`load_example` loads any example by name; ``resolve_*`` turn an ENGINE, MODEL_OR_ENGINE,
LINKAGE or STUDY argument into the object, with one-line errors that list the examples and
suggest the nearest name.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from crankdyn.constants import RPM
from crankdyn.docs import ref
from crankdyn.errors import InputError, did_you_mean
from crankdyn.io.engine_file import load_engine, parse_engine, parse_model_file
from crankdyn.io.examples import EXAMPLE_KINDS, example_kind, example_names, example_path
from crankdyn.io.files import display_name, load_toml

if TYPE_CHECKING:
    from crankdyn.engine.model import Engine
    from crankdyn.linkage.planar import Mechanism
    from crankdyn.study.spec import StudySpec
    from crankdyn.torsion.model import TorsionModel

__all__ = [
    "ExampleInfo",
    "catalogue",
    "load_example",
    "load_torsion_model",
    "resolve",
    "resolve_engine",
    "resolve_linkage",
    "resolve_model_and_engine",
    "resolve_study",
    "resolve_torsion",
]


def _built_in(name: str, kind: str) -> str:
    return f"{name} (built-in {EXAMPLE_KINDS[kind][1]})"


def load_example(name: str, kind: str | None = None) -> Any:
    """The built-in example ``name``: an Engine, a TorsionModel, a Mechanism or a StudySpec (of
    ``kind`` when given).

    Parameters
    ----------
    name
        The example's name (``crankdyn examples`` lists them).
    kind
        A key of :data:`crankdyn.io.examples.EXAMPLE_KINDS` the example must be of, or None.

    Returns
    -------
    Engine, TorsionModel, Mechanism or StudySpec
        The example, read by its file reader (every quantity in SI).

    Raises
    ------
    InputError
        For an unknown name (listing the examples, with a did-you-mean), naming the key and
        the value.

    Examples
    --------
    >>> load_example("single-cylinder").cylinders.count
    1
    """
    path = example_path(name, kind)
    found = example_kind(name)
    assert found is not None  # example_path found it (type checker)
    data = load_toml(path, what=f"{EXAMPLE_KINDS[found][1]} file")
    source = _built_in(name, found)
    if found == "engine":
        return parse_engine(data, file=source, base_dir=path.parent)
    if found == "model":
        return parse_model_file(data, file=source, base_dir=path.parent)
    if found == "linkage":
        from crankdyn.io.linkage_file import parse_linkage  # the linkage solvers: on demand

        return parse_linkage(data, file=source)
    if found == "design":
        from crankdyn.io.design_file import parse_design  # the design search: on demand

        return parse_design(data, file=source, base_dir=path.parent, default_name=name)
    from crankdyn.io.study_file import parse_study  # scipy and the study registry: on demand

    return parse_study(data, file=source, base_dir=path.parent, default_name=name)


def load_torsion_model(path: str | Path) -> TorsionModel:
    """A torsional model from a model file (with the engines its ``[[engine]]`` entries join),
    an engine file's [torsion] section, or a mass-elastic table (``.csv``,
    :mod:`crankdyn.io.mass_elastic`).

    Parameters
    ----------
    path
        The model file, engine file or mass-elastic table.

    Returns
    -------
    TorsionModel
        The model, every quantity in SI.

    Raises
    ------
    InputError
        For an engine file without [torsion], or any error of the file's reader; naming the
        file, the key and the value.
    """
    model, _engine = _model_file(Path(path))
    return model


def _model_file(path: Path) -> tuple[TorsionModel, Engine | None]:
    if path.suffix.lower() == ".csv":
        from crankdyn.io.mass_elastic import read_mass_elastic

        return read_mass_elastic(path, display_name(path)), None
    data = load_toml(path, what="model file")
    if "geometry" in data:  # an engine file
        engine = parse_engine(data, file=display_name(path), base_dir=path.parent)
        return _engine_torsion(engine), engine
    model = parse_model_file(
        data, file=display_name(path), base_dir=path.parent, default_name=path.stem
    )
    return model, None


def _engine_torsion(engine: Engine) -> TorsionModel:
    if engine.torsion is None:
        raise InputError(
            f"the engine has no [torsion] section ({ref('torsion-file')})", file=engine.source
        )
    return engine.torsion


def _looks_like_path(spec: str) -> bool:
    try:
        exists = Path(spec).exists()
    except (OSError, ValueError):
        exists = False
    return exists or spec.endswith((".toml", ".csv")) or "/" in spec or "\\" in spec


def _unknown(spec: str, kinds: tuple[str, ...]) -> InputError:
    names = [n for k in kinds for n in example_names(k)]
    if len(kinds) == 1:
        what = f"or built-in {EXAMPLE_KINDS[kinds[0]][1]} (examples: {', '.join(names)})"
    else:
        parts = [f"built-in {_SHORT[k]} ({', '.join(example_names(k))})" for k in kinds]
        what = ", " + " or ".join(parts)
    return InputError(
        f"no such file {what}{did_you_mean(spec, names)}".replace(" ,", ","), file=spec
    )


_SHORT = {"engine": "engine", "model": "model", "linkage": "linkage", "study": "study"}


def resolve_engine(spec: str) -> Engine:
    """An ENGINE argument: a path to an engine file, or a built-in example engine's name.

    Parameters
    ----------
    spec
        The argument as given.

    Returns
    -------
    Engine
        The engine, every quantity in SI.

    Raises
    ------
    InputError
        For neither a file nor a built-in engine (listing the examples, with a did-you-mean),
        or any error of the engine file.
    """
    if _looks_like_path(spec):
        return load_engine(Path(spec))
    if example_kind(spec) == "engine":
        return load_example(spec, "engine")
    raise _unknown(spec, ("engine",))


def resolve_model_and_engine(spec: str) -> tuple[TorsionModel, Engine | None]:
    """A MODEL_OR_ENGINE argument as (torsional model, engine or None): a model or engine file,
    a mass-elastic table (.csv), a built-in torsional model, or a built-in engine with a
    [torsion] section. A model file that joins engines (``[[engine]]``) is a model (its first
    engine is the model's ``engine``, which excites it).

    Parameters
    ----------
    spec
        The argument as given.

    Returns
    -------
    tuple of (TorsionModel, Engine or None)
        The torsional model (SI) and the engine whose [torsion] section it is (None for a
        model file or table).

    Raises
    ------
    InputError
        For neither a file nor a built-in model or engine, an engine without [torsion], or
        any error of the file's reader.
    """
    if _looks_like_path(spec):
        return _model_file(Path(spec))
    kind = example_kind(spec)
    if kind == "model":
        model: TorsionModel = load_example(spec, "model")
        return model, None
    if kind == "engine":
        engine: Engine = load_example(spec, "engine")
        return _engine_torsion(engine), engine
    raise _unknown(spec, ("model", "engine"))


def resolve_torsion(spec: str) -> TorsionModel:
    """A MODEL_OR_ENGINE argument as the torsional model alone.

    Parameters
    ----------
    spec
        The argument as given.

    Returns
    -------
    TorsionModel
        The model (:func:`resolve_model_and_engine`).

    Raises
    ------
    InputError
        As :func:`resolve_model_and_engine`.
    """
    return resolve_model_and_engine(spec)[0]


def resolve_linkage(spec: str) -> Mechanism:
    """A LINKAGE argument: a path to a linkage file, or a built-in linkage's name.

    Parameters
    ----------
    spec
        The argument as given.

    Returns
    -------
    Mechanism
        The linkage, every quantity in SI.

    Raises
    ------
    InputError
        For neither a file nor a built-in linkage, or any error of the linkage file.
    """
    if _looks_like_path(spec):
        from crankdyn.io.linkage_file import load_linkage

        return load_linkage(Path(spec))
    if example_kind(spec) == "linkage":
        return load_example(spec, "linkage")
    raise _unknown(spec, ("linkage",))


def resolve_study(spec: str) -> StudySpec:
    """A STUDY argument: a path to a study file, or a built-in example study's name.

    Parameters
    ----------
    spec
        The argument as given.

    Returns
    -------
    StudySpec
        The study.

    Raises
    ------
    InputError
        For neither a file nor a built-in study, or any error of the study file.
    """
    if _looks_like_path(spec):
        from crankdyn.io.study_file import load_study

        return load_study(Path(spec))
    if example_kind(spec) == "study":
        return load_example(spec, "study")
    raise _unknown(spec, ("study",))


_RESOLVERS = {
    "engine": resolve_engine,
    "model": resolve_torsion,
    "linkage": resolve_linkage,
    "study": resolve_study,
}


def resolve(spec: str, kind: str) -> Any:
    """Any argument by kind (``"engine"``, ``"model"``, ``"linkage"``, ``"study"``).

    Parameters
    ----------
    spec
        The argument as given.
    kind
        Which kind of argument it is.

    Returns
    -------
    Engine, TorsionModel, Mechanism or StudySpec
        What the kind's resolver returns.

    Raises
    ------
    InputError
        As the kind's resolver.
    """
    return _RESOLVERS[kind](spec)


@dataclass(frozen=True)
class ExampleInfo:
    """One line of the catalogue: name, kind, title and a short description.

    Parameters
    ----------
    name
        The example's name.
    kind
        A key of :data:`crankdyn.io.examples.EXAMPLE_KINDS`.
    title
        The name the example's file gives.
    description
        One line on what it is (layout, size, speed in rpm, what it holds).
    """

    name: str
    kind: str
    title: str
    description: str


def catalogue(kind: str | None = None) -> list[ExampleInfo]:
    """Every built-in example (of ``kind``), each loaded to describe it.

    Parameters
    ----------
    kind
        A key of :data:`crankdyn.io.examples.EXAMPLE_KINDS`, or None for every kind.

    Returns
    -------
    list of ExampleInfo
        One per example, by kind and then by name.
    """
    out = []
    for k in EXAMPLE_KINDS if kind is None else (kind,):
        for name in example_names(k):
            obj = load_example(name, k)
            out.append(ExampleInfo(name, k, *_describe(obj, k)))
    return out


def _describe(obj: Any, kind: str) -> tuple[str, str]:
    if kind == "engine":
        c, g = obj.cylinders, obj.geometry
        layout = f"{c.count} {c.layout}" + (
            f" {math.degrees(c.bank_angle):.0f}°" if c.layout == "V" else ""
        )
        speed = f", {obj.speed * RPM:.0f} rpm" if obj.speed else ""
        parts = [
            f"{layout}, {obj.cycle}",
            f"{g.bore * 1e3:g} x {g.nominal_stroke * 1e3:g} mm{speed}",
        ]
        if obj.pressure is not None:
            parts.append("pressure trace")
        if obj.torsion is not None:
            parts.append(f"torsional model of {obj.torsion.mass_count} masses")
        return obj.name, "; ".join(parts)
    if kind == "model":
        shape = "chain" if obj.is_chain else "branched"
        ends = "free" if obj.is_free else "grounded"
        return obj.name, f"{obj.mass_count} masses, {shape}, {ends}"
    if kind == "linkage":
        groups = "; ".join(f"{g.kind} {'-'.join(g.links)}" for g in obj.link_groups())
        return obj.name, f"{len(obj.links)} links, {len(obj.joints)} joints: {groups}"
    if kind == "design":
        study = obj.study
        return study.name, (
            f"searches {study.base.source}: {len(obj.choices)} choices, {len(obj.ranges)} ranges"
        )
    return obj.name, f"varies {obj.base.source}: {obj.case_count} cases"
