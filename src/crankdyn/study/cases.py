"""The cases of a study: the grid (Cartesian product of the grid parameters' values) times the
Monte Carlo samples (draws of the random parameters, the same draws at every grid point, so that
grid variants are compared under common random numbers).

Every case has a stable id, the first 16 hex digits of the SHA-256 of its parameter values as
written into the document (canonical JSON, keys sorted): the same variant has the same id in
every run, which is what lets a rerun skip finished cases and a grown study reuse the cases it
shares with the smaller one.
"""

from __future__ import annotations

import hashlib
import itertools
import json
from dataclasses import dataclass
from typing import Any

import numpy as np

from crankdyn.study.spec import Distribution, Parameter, StudySpec

__all__ = ["MAX_CASES", "Case", "case_id", "draw_uniform", "expand"]

MAX_CASES = 1_000_000
"""The most cases one study runs."""


@dataclass(frozen=True)
class Case:
    """One variant of the base.

    Parameters
    ----------
    index : int
        Position in the study's order (grid points in file order, the last parameter
        fastest; the samples within each grid point).
    case_id : str
        Stable id (module docstring).
    params : dict of str to object
        Key path -> value as written into the document.
    numbers : dict of str to object
        Key path -> the value in the parameter's unit (numeric parameters) or its text
        (categorical ones), for the results table.
    sample : int or None
        Monte Carlo sample number (0-based), or None without random parameters.
    """

    index: int
    case_id: str
    params: dict[str, Any]
    numbers: dict[str, Any]
    sample: int | None = None


def case_id(params: dict[str, Any]) -> str:
    """The stable id of a case from its parameter values (module docstring).

    Parameters
    ----------
    params : dict of str to object
        Key path -> value as written into the document (JSON-serialisable).

    Returns
    -------
    str
        16 hex digits of the SHA-256 of the canonical JSON.

    Examples
    --------
    >>> case_id({"geometry.rod_length": "136 mm"})
    '89f700090cc3a3de'
    """
    text = json.dumps(params, sort_keys=True, separators=(",", ":"), ensure_ascii=False)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:16]


def draw_uniform(samples: int, dims: int, seed: int, sampling: str = "random") -> np.ndarray:
    """Uniform numbers in [0, 1) from numpy's PCG64 generator.

    Plain random draws (row by row, so the first n of a larger study are the draws of a study
    of n samples), or a Latin hypercube (McKay, Beckman and Conover 1979;
    :mod:`crankdyn.study.spec`).

    Parameters
    ----------
    samples : int
        Draws n.
    dims : int
        Random parameters.
    seed : int
        The generator's seed.
    sampling : str
        ``"random"`` (default) or ``"latin-hypercube"``.

    Returns
    -------
    numpy.ndarray
        (samples, dims) numbers in [0, 1) (dimensionless).

    Examples
    --------
    A Latin hypercube puts one draw in each quarter of [0, 1) for every parameter:

    >>> u = draw_uniform(4, 2, seed=1, sampling="latin-hypercube")
    >>> np.sort(np.floor(u * 4), axis=0).T.tolist()
    [[0.0, 1.0, 2.0, 3.0], [0.0, 1.0, 2.0, 3.0]]
    """
    rng = np.random.default_rng(seed)
    if sampling == "random":
        return rng.random((samples, dims))
    v = rng.random((samples, dims))
    strata = np.column_stack([rng.permutation(samples) for _ in range(dims)])
    return (strata.reshape(samples, dims) + v) / samples


def label(value: Any) -> str:
    """A categorical value as shown in tables: TOML-like text, lists in brackets.

    Parameters
    ----------
    value : object
        The value as written into the document.

    Returns
    -------
    str
        The text.

    Examples
    --------
    >>> label([1, 5, 3, "x"]), label(True)
    ('[1, 5, 3, "x"]', 'true')
    """
    if isinstance(value, str):
        return value
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, list):
        return (
            "["
            + ", ".join(label(v) if not isinstance(v, str) else json.dumps(v) for v in value)
            + "]"
        )
    if isinstance(value, dict):
        return json.dumps(value, sort_keys=True, default=str)
    return str(value)


def _grid_entry(p: Parameter, i: int) -> tuple[Any, Any]:
    assert p.values is not None  # a grid parameter
    value = p.values[i]
    if p.is_numeric:
        assert p.numbers is not None  # a numeric grid parameter has its magnitudes
        return value, p.numbers[i]
    number = p.names[i] if p.names is not None else label(value)
    return value, number


def _distribution(p: Parameter) -> Distribution:
    assert p.distribution is not None  # a random parameter
    return p.distribution


def expand(spec: StudySpec) -> list[Case]:
    """Every case of the study, in order (module docstring).

    Parameters
    ----------
    spec : crankdyn.study.spec.StudySpec
        The study.

    Returns
    -------
    list of Case
        The grid points in file order (the last parameter fastest), the Monte Carlo samples
        within each.

    Raises
    ------
    InputError
        If the study has more than :data:`MAX_CASES` cases.
    """
    from crankdyn.errors import InputError

    count = spec.case_count
    if count > MAX_CASES:
        raise InputError(
            f"the study has {count} cases, more than the {MAX_CASES} crankdyn runs in one study",
            file=spec.source,
        )
    grid = spec.grid_parameters
    random = spec.random_parameters
    samples = 0
    if random:
        assert spec.samples is not None and spec.seed is not None  # StudySpec requires them
        samples = spec.samples
        u = draw_uniform(samples, len(random), spec.seed, spec.sampling)
        draws = [_distribution(p).quantile(u[:, j]) for j, p in enumerate(random)]
    cases: list[Case] = []
    for point in itertools.product(*(range(len(p.values or ())) for p in grid)):
        base_params: dict[str, Any] = {}
        base_numbers: dict[str, Any] = {}
        for p, i in zip(grid, point, strict=True):
            base_params[p.key], base_numbers[p.key] = _grid_entry(p, i)
        for s in range(samples) if random else (None,):
            params = dict(base_params)
            numbers = dict(base_numbers)
            if s is not None:
                for j, p in enumerate(random):
                    value = p.document_value(draws[j][s])
                    params[p.key] = value
                    numbers[p.key] = float(draws[j][s])
            ordered = {p.key: params[p.key] for p in spec.parameters}
            cases.append(
                Case(
                    index=len(cases),
                    case_id=case_id(ordered),
                    params=ordered,
                    numbers={p.key: numbers[p.key] for p in spec.parameters},
                    sample=s,
                )
            )
    return cases
