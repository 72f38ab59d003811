"""The study as a domain object: the base document, the parameters and how they vary, the
analysis settings and the figures to keep (read from a study file by
:mod:`crankdyn.io.study_file`; docs/study-file.md).

Monte Carlo draws use inverse-transform sampling (e.g. Devroye, *Non-Uniform Random Variate
Generation*, Springer 1986, section 2.1): a uniform number u in (0, 1) from the seeded PCG64
generator of numpy (``Generator.random``, whose stream numpy keeps stable) is mapped through the
distribution's quantile function F^-1(u):

- uniform on [a, b]: a + u (b - a);
- normal N(mu, sigma): mu + sigma Phi^-1(u), Phi^-1 the standard normal quantile
  (``scipy.special.ndtri``);
- triangular (a, c, b) with mode c: a + sqrt(u (b - a)(c - a)) for u < (c - a)/(b - a), else
  b - sqrt((1 - u)(b - a)(b - c)).

Latin hypercube sampling (McKay, Beckman and Conover, Technometrics 21 (1979) 239-245) puts
one of n samples in each of the n equal-probability strata of every parameter:
u_ij = (pi_j(i) + v_ij)/n with an independent random permutation pi_j per parameter and v
uniform in [0, 1).
"""

from __future__ import annotations

import hashlib
import json
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.errors import InputError
from crankdyn.study.docpath import KeyPath
from crankdyn.study.figures import FIGURES, AnalysisSettings

__all__ = [
    "BASE_KINDS",
    "DISTRIBUTIONS",
    "SAMPLINGS",
    "Base",
    "BaseKind",
    "Distribution",
    "Parameter",
    "StudySpec",
    "column_suffix",
    "document_number",
]

SAMPLINGS = ("random", "latin-hypercube")
"""The Monte Carlo samplings (module docstring)."""


# ---- what a study varies: the base ------------------------------------------------------------


@dataclass(frozen=True)
class BaseKind:
    """A kind of base file a study can vary (:func:`crankdyn.io.study_file.parse_base` reads
    it).

    Parameters
    ----------
    name : str
        Its key in the study file (``engine = ...``).
    docs : str
        The ``crankdyn docs`` topic that documents its format.
    """

    name: str
    docs: str


BASE_KINDS: dict[str, BaseKind] = {
    "engine": BaseKind("engine", "engine-file"),
    "model": BaseKind("model", "torsion-file"),
}
"""The kinds of base file, by name."""


@dataclass(frozen=True)
class Base:
    """The base file of a study, parsed but not interpreted.

    Parameters
    ----------
    kind : str
        A key of :data:`BASE_KINDS`.
    document : dict
        The parsed TOML document (never modified: cases edit deep copies).
    source : str
        How the file is named in messages (``"engine.toml"``, ``"vaz2108 (built-in example)"``).
    base_dir : pathlib.Path or None
        Folder against which the document's relative paths resolve.
    files_digest : str
        SHA-256 of the files the document refers to (pressure traces...), so that the study's
        fingerprint changes when they do.
    files : tuple of (str, bytes)
        (relative path, contents) of the files the document names by relative paths, read
        with the document: what workers on other machines receive.
    """

    kind: str
    document: dict[str, Any] = field(repr=False)
    source: str
    base_dir: Path | None = None
    files_digest: str = ""
    files: tuple[tuple[str, bytes], ...] = field(default=(), repr=False)

    def __post_init__(self) -> None:
        if self.kind not in BASE_KINDS:
            raise InputError(
                f"expected one of {', '.join(BASE_KINDS)}", key="base kind", value=self.kind
            )


# ---- how a parameter varies -------------------------------------------------------------------


def _ndtri(u: ArrayLike) -> NDArray[np.float64]:
    """The standard normal quantile (scipy.special.ndtri, imported when a study samples it)."""
    from scipy.special import ndtri

    return np.asarray(ndtri(u), dtype=float)


def _triangular_ppf(u: ArrayLike, a: float, c: float, b: float) -> NDArray[np.float64]:
    u = np.asarray(u, dtype=float)
    split = (c - a) / (b - a)
    low = a + np.sqrt(u * (b - a) * (c - a))
    high = b - np.sqrt((1.0 - u) * (b - a) * (b - c))
    return np.where(u < split, low, high)


DISTRIBUTIONS: dict[str, tuple[tuple[str, ...], Callable[..., NDArray[np.float64]]]] = {
    "uniform": (("low", "high"), lambda u, a, b: a + np.asarray(u) * (b - a)),
    "normal": (("mean", "std"), lambda u, mu, sigma: mu + sigma * _ndtri(np.asarray(u))),
    "triangular": (("low", "mode", "high"), _triangular_ppf),
}
"""Distribution name -> (argument names, quantile function F^-1(u, *args))."""


@dataclass(frozen=True)
class Distribution:
    """A random distribution of a numeric parameter (module docstring).

    Parameters
    ----------
    name : str
        A key of :data:`DISTRIBUTIONS`: ``"uniform"``, ``"normal"`` or ``"triangular"``.
    args : tuple of float
        Its arguments in the parameter's unit: (low, high), (mean, std) or (low, mode, high).

    Raises
    ------
    InputError
        If the name is unknown, the arguments are not as many as the distribution's, not
        finite, or out of order.

    Examples
    --------
    The median of a triangular distribution with its mode in the middle:

    >>> Distribution("triangular", (0.0, 1.0, 2.0)).quantile([0.5]).tolist()
    [1.0]
    """

    name: str
    args: tuple[float, ...]

    def __post_init__(self) -> None:
        if self.name not in DISTRIBUTIONS:
            raise InputError(
                f"expected one of {', '.join(DISTRIBUTIONS)}", key="distribution", value=self.name
            )
        names, _ = DISTRIBUTIONS[self.name]
        if len(self.args) != len(names):
            raise InputError(f"expected {', '.join(names)}", key="distribution", value=self.name)
        if not all(math.isfinite(a) for a in self.args):
            raise InputError("the arguments must be finite", key=self.name, value=list(self.args))
        if self.name == "uniform" and not self.args[0] < self.args[1]:
            raise InputError("low must be below high", key="high", value=self.args[1])
        if self.name == "normal" and not self.args[1] > 0.0:
            raise InputError("std must be positive", key="std", value=self.args[1])
        if self.name == "triangular":
            a, c, b = self.args
            if not (a < b and a <= c <= b):
                raise InputError("expected low <= mode <= high, low < high", key="mode", value=c)

    def quantile(self, u: ArrayLike) -> NDArray[np.float64]:
        """The quantile function F^-1(u) (module docstring; Devroye 1986, section 2.1).

        Parameters
        ----------
        u : array_like
            Uniform numbers in [0, 1) (dimensionless).

        Returns
        -------
        numpy.ndarray
            F^-1(u) in the parameter's unit, of u's shape.
        """
        return DISTRIBUTIONS[self.name][1](u, *self.args)


def column_suffix(unit: str) -> str:
    """The unit part of a column name.

    Parameters
    ----------
    unit : str
        A unit as written in the study file (``""`` for a bare number).

    Returns
    -------
    str
        Letters, digits and ``_``: ``"mm"`` -> ``"mm"``, ``"kg*m^2"`` -> ``"kg_m2"``; ``""``
        for a bare number.

    Examples
    --------
    >>> column_suffix("N*m/rad")
    'N_m_per_rad'
    """
    text = unit.replace("**", "^").replace(" ", "")
    text = text.replace("*", "_").replace("·", "_").replace("/", "_per_").replace("^", "")
    return "".join(ch for ch in text if ch.isalnum() or ch in "_-%°µ")


def document_number(number: float, unit: str, integer: bool = False) -> Any:
    """A generated magnitude as written into a document.

    Parameters
    ----------
    number : float
        The magnitude in ``unit``.
    unit : str
        The parameter's unit (``""`` for a bare number).
    integer : bool
        Round to a whole number; default False.

    Returns
    -------
    str or float or int
        ``"136.25 mm"``, or a bare number (a whole one when ``integer``).

    Examples
    --------
    >>> document_number(136.25, "mm"), document_number(3.7, "", integer=True)
    ('136.25 mm', 4)
    """
    value: Any = round(float(number)) if integer else float(number)
    return f"{value!r} {unit}" if unit else value


@dataclass(frozen=True)
class Parameter:
    """One varied key of the base document.

    Parameters
    ----------
    path : crankdyn.study.docpath.KeyPath
        The key path (:mod:`crankdyn.study.docpath`).
    also : tuple of KeyPath
        Further key paths set to the same value in every case (one quantity that appears in
        two places of the file, e.g. a flywheel's inertia in ``[flywheel]`` and in the
        torsional model).
    values : tuple or None
        The values of a grid parameter as written into the document (unit strings, numbers,
        lists, text), or None for a random parameter.
    numbers : tuple of float or None
        For a numeric parameter, its values' magnitudes in ``unit`` (the grid values, or None
        for a random one); None for a categorical parameter.
    unit : str or None
        The unit of a numeric parameter (``""`` for bare numbers); None when categorical.
    distribution : Distribution or None
        The distribution of a random (Monte Carlo) parameter.
    integer : bool
        Write generated values as whole numbers (a range of whole numbers).
    bundle : bool
        Every value is a *bundle*: a dict {key path text: value} that sets several keys of the
        document at once, each to its own value (a catalogue coupling sets a shaft's stiffness
        and torques and its two masses' inertias); ``path`` and ``also`` are every key path
        the bundles set, and a bundle leaves the paths it does not name as the base has them.
        Default False: every path takes the same value.
    names : tuple of str or None
        The values' names in tables (a bundle's catalogue name), or None for their text.

    Raises
    ------
    InputError
        If not exactly one of ``values`` and ``distribution`` is given, a distribution is
        given to a categorical parameter, or a bundle is not a dict of the parameter's paths.
    """

    path: KeyPath
    values: tuple[Any, ...] | None = None
    also: tuple[KeyPath, ...] = ()
    numbers: tuple[float, ...] | None = None
    unit: str | None = None
    distribution: Distribution | None = None
    integer: bool = False
    bundle: bool = False
    names: tuple[str, ...] | None = None

    def __post_init__(self) -> None:
        if (self.values is None) == (self.distribution is None):
            raise InputError(
                "give either values (a list or a range) or a distribution", key=self.path.text
            )
        if self.distribution is not None and self.unit is None:
            raise InputError("a distribution needs a numeric parameter", key=self.path.text)
        if self.bundle:
            known = {p.text for p in self.paths}
            for value in self.values or ():
                if not isinstance(value, dict) or not set(value) <= known:
                    raise InputError(
                        "a bundle is a table of the parameter's key paths",
                        key=self.path.text,
                        value=value,
                    )
        if self.names is not None and len(self.names) != len(self.values or ()):
            raise InputError("one name per value", key=self.path.text, value=list(self.names))

    def assignments(self, value: Any) -> dict[KeyPath, Any]:
        """The document values one of the parameter's values sets.

        Parameters
        ----------
        value : object
            A value of the parameter as written into the document (a bundle: a dict).

        Returns
        -------
        dict of KeyPath to object
            Every path the value sets: all of :attr:`paths` to ``value``, or for a bundle the
            paths it names to their own values.
        """
        if self.bundle:
            return {p: value[p.text] for p in self.paths if p.text in value}
        return dict.fromkeys(self.paths, value)

    @property
    def key(self) -> str:
        """The parameter's name: its (first) key path."""
        return self.path.text

    @property
    def paths(self) -> tuple[KeyPath, ...]:
        """Every key path the parameter sets."""
        return (self.path, *self.also)

    @property
    def is_random(self) -> bool:
        """Whether it is a random (Monte Carlo) parameter."""
        return self.distribution is not None

    @property
    def is_numeric(self) -> bool:
        """Whether it is numeric (has a unit, ``""`` for bare numbers)."""
        return self.unit is not None

    @property
    def column(self) -> str:
        """Results-table column: the key, with the unit appended (``geometry.rod_length_mm``)."""
        if self.unit:
            return f"{self.key}_{column_suffix(self.unit)}"
        return self.key

    def document_value(self, number: float) -> Any:
        """A generated magnitude as written into the document (:func:`document_number`).

        Parameters
        ----------
        number : float
            The magnitude in the parameter's unit.

        Returns
        -------
        str or float or int
            The value for the document.
        """
        return document_number(number, self.unit or "", self.integer)


# ---- the study --------------------------------------------------------------------------------


@dataclass(frozen=True)
class StudySpec:
    """A parameter study (docs/study-file.md).

    Parameters
    ----------
    name : str
        For reports.
    base : Base
        The base file varied.
    parameters : tuple of Parameter
        The varied keys, in file order: the grid parameters span a Cartesian product; the
        random ones are drawn ``samples`` times, the same draws for every grid point.
    figures : tuple of str
        Names of :data:`crankdyn.study.figures.FIGURES` kept per case.
    settings : crankdyn.study.figures.AnalysisSettings
        The ``[analysis]`` values (SI).
    remove : tuple of KeyPath
        Keys deleted from the base document before the parameters are applied.
    samples : int or None
        Monte Carlo: number of draws.
    seed : int or None
        Monte Carlo: the generator's seed.
    sampling : str
        Monte Carlo: ``"random"`` (default) or ``"latin-hypercube"``.
    best : tuple of (str, str)
        (figure, "min" or "max") overriding a figure's own sense of better.
    source : str or None
        The study file, for messages.
    verdict_rows : bool
        Keep each case's verdict rows in its journal record (:func:`crankdyn.study.figures.
        case_verdicts`): a design search tables its best designs' rows from them instead of
        analysing them again. Default False.

    Raises
    ------
    InputError
        If there is no parameter, a key is varied twice, no figure is named or one is unknown
        or does not apply to the base, a Monte Carlo study lacks samples or seed, or the
        sampling is unknown.
    """

    name: str
    base: Base
    parameters: tuple[Parameter, ...]
    figures: tuple[str, ...]
    settings: AnalysisSettings = AnalysisSettings()
    remove: tuple[KeyPath, ...] = ()
    samples: int | None = None
    seed: int | None = None
    sampling: str = "random"
    best: tuple[tuple[str, str], ...] = ()
    source: str | None = field(default=None, compare=False)
    verdict_rows: bool = False

    def __post_init__(self) -> None:
        if not self.parameters:
            raise InputError("a study needs at least one [[parameter]]", key="parameter")
        keys = [path.text for p in self.parameters for path in p.paths]
        for i, key in enumerate(keys):
            if key in keys[:i]:
                raise InputError("the key is varied twice", key="parameter key", value=key)
        if not self.figures:
            raise InputError("name at least one figure", key="figures")
        for name in self.figures:
            if name not in FIGURES:
                raise InputError("unknown figure", key="figures", value=name)
            if self.base.kind not in FIGURES[name].subjects:
                raise InputError(
                    f"the figure does not apply to a base {self.base.kind}",
                    key="figures",
                    value=name,
                )
        if self.random_parameters:
            if self.samples is None or self.samples < 1:
                raise InputError("a Monte Carlo study needs samples >= 1", key="samples")
            if self.seed is None:
                raise InputError("a Monte Carlo study needs a seed", key="seed")
        if self.sampling not in SAMPLINGS:
            raise InputError(
                f"expected one of {', '.join(SAMPLINGS)}", key="sampling", value=self.sampling
            )

    @property
    def grid_parameters(self) -> tuple[Parameter, ...]:
        """The parameters with listed values, in file order."""
        return tuple(p for p in self.parameters if not p.is_random)

    @property
    def random_parameters(self) -> tuple[Parameter, ...]:
        """The parameters with a distribution, in file order."""
        return tuple(p for p in self.parameters if p.is_random)

    @property
    def case_count(self) -> int:
        """Number of cases: grid points x Monte Carlo samples."""
        count = math.prod(len(p.values or ()) for p in self.grid_parameters)
        return count * ((self.samples or 0) if self.random_parameters else 1)

    def better(self, figure: str) -> str | None:
        """Whether smaller or larger values of a figure are better.

        Parameters
        ----------
        figure : str
            A figure's name.

        Returns
        -------
        str or None
            ``"min"`` or ``"max"`` (the study's ``best``, else the figure's own sense), or None.
        """
        for name, sense in self.best:
            if name == figure:
                return sense
        return FIGURES[figure].better

    def fingerprint(self) -> str:
        """SHA-256 of everything a case's figures depend on besides its parameter values: the
        base document and the files it names, the removed keys, the analysis settings, the
        figures and the crankdyn version. Two runs with the same fingerprint may share finished
        cases (a case is identified by its parameter values).

        Returns
        -------
        str
            64 hex digits.
        """
        from crankdyn import __version__

        content = {
            "kind": self.base.kind,
            "document": self.base.document,
            "files": self.base.files_digest,
            "remove": [p.text for p in self.remove],
            "settings": self.settings.to_dict(),
            "figures": list(self.figures),
            "crankdyn": __version__,
        }
        text = json.dumps(content, sort_keys=True, default=str, separators=(",", ":"))
        return hashlib.sha256(text.encode("utf-8")).hexdigest()
