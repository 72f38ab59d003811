"""crankdyn: dynamics of crank mechanisms.

The entry points, for a notebook or a script::

    import crankdyn

    engine = crankdyn.Engine.example("inline6-diesel")    # or crankdyn.Engine.from_file(...)
    a = crankdyn.Analysis(engine)                         # every analysis, computed once
    a.torque                                              # a result: numbers, .plot(), .to_csv()
    a.forces().plot()
    a.modes.frequencies_hz
    crankdyn.examples()                                   # the built-in examples

- :class:`Engine` (and :class:`Cylinders`): the multi-cylinder engine;
- :class:`TorsionModel`: a lumped torsional model (an engine's ``[torsion]`` section, or a shaft
  line of its own);
- :class:`Mechanism` and :class:`FourBar`: planar linkages;
- :class:`Analysis`: the analysis session of an engine or a torsional model;
- :func:`examples` and :func:`example`: the built-in engines, models, linkages and studies.

The names are imported on first use, so ``import crankdyn`` (and the command line's start-up)
stays light.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from crankdyn.io.catalogue import ExampleInfo

__version__ = "0.1.0"

__all__ = [
    "Analysis",
    "Cylinders",
    "Engine",
    "FourBar",
    "InputError",
    "Mechanism",
    "TorsionModel",
    "example",
    "examples",
]

_LAZY = {
    "Analysis": "crankdyn.session",
    "Cylinders": "crankdyn.engine.model",
    "Engine": "crankdyn.engine.model",
    "FourBar": "crankdyn.linkage.fourbar",
    "InputError": "crankdyn.errors",
    "Mechanism": "crankdyn.linkage.planar",
    "TorsionModel": "crankdyn.torsion.model",
}


def examples(kind: str | None = None) -> list[ExampleInfo]:
    """The built-in examples, each with its name, kind, title and a short description.

    Parameters
    ----------
    kind : str or None
        Only the examples of this kind: ``"engine"``, ``"model"``, ``"linkage"`` or
        ``"study"``; None for all.

    Returns
    -------
    list of crankdyn.io.catalogue.ExampleInfo
        The catalogue entries; load one with :func:`example`.
    """
    from crankdyn.io.catalogue import catalogue

    return catalogue(kind)


def example(name: str) -> Any:
    """A built-in example by name.

    Parameters
    ----------
    name : str
        The example's name, as :func:`examples` lists it (e.g. ``"inline6-diesel"``).

    Returns
    -------
    Engine, TorsionModel, Mechanism or StudySpec
        The loaded example.
    """
    from crankdyn.io.catalogue import load_example

    return load_example(name)


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        import importlib

        value = getattr(importlib.import_module(_LAZY[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'crankdyn' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
