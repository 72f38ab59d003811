"""Expanding a study into cases: grid order and count, stable ids, Monte Carlo draws (checked
against scipy.stats' quantile functions and by their sample statistics), Latin hypercube."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats

from crankdyn.study.cases import case_id, draw_uniform, expand
from crankdyn.study.docpath import parse_path
from crankdyn.study.spec import Base, Distribution, Parameter, StudySpec


def grid_param(key, values, numbers=None, unit=None):
    return Parameter(parse_path(key), values=tuple(values), numbers=numbers, unit=unit)


def random_param(key, name, args, unit="mm"):
    return Parameter(parse_path(key), unit=unit, distribution=Distribution(name, args))


BASE = Base("engine", {"name": "x"}, "engine.toml")


def spec(parameters, **kw):
    return StudySpec(
        name="t", base=BASE, parameters=tuple(parameters), figures=("mean_torque",), **kw
    )


def test_grid_is_the_cartesian_product_last_parameter_fastest():
    s = spec(
        [
            grid_param("a.x", ["1 mm", "2 mm", "3 mm"], (1.0, 2.0, 3.0), "mm"),
            grid_param("b.y", [[1, 2], [2, 1]]),
        ]
    )
    cases = expand(s)
    assert len(cases) == s.case_count == 6
    assert [c.params["a.x"] for c in cases] == ["1 mm"] * 2 + ["2 mm"] * 2 + ["3 mm"] * 2
    assert [c.numbers["b.y"] for c in cases] == ["[1, 2]", "[2, 1]"] * 3
    assert [c.index for c in cases] == list(range(6))
    assert len({c.case_id for c in cases}) == 6
    assert all(c.sample is None for c in cases)


def test_case_ids_depend_only_on_the_values():
    assert case_id({"a.x": "1 mm", "b.y": [1, 2]}) == case_id({"b.y": [1, 2], "a.x": "1 mm"})
    assert case_id({"a.x": "1 mm"}) != case_id({"a.x": "1.0 mm"})
    assert len(case_id({"a": 1})) == 16


def test_monte_carlo_is_reproducible_and_shared_across_the_grid():
    params = [
        grid_param("a.x", [1, 2], (1.0, 2.0), ""),
        random_param("c.z", "normal", (100.0, 2.0)),
    ]
    s = spec(params, samples=5, seed=7)
    first, again = expand(s), expand(s)
    assert [c.params for c in first] == [c.params for c in again]
    assert len(first) == 10
    draws = [c.numbers["c.z"] for c in first]
    assert draws[:5] == draws[5:]  # common random numbers at every grid point
    assert [c.sample for c in first] == [0, 1, 2, 3, 4] * 2
    assert first[0].params["c.z"] == f"{draws[0]!r} mm"
    other = expand(spec(params, samples=5, seed=8))
    assert [c.numbers["c.z"] for c in other] != draws


def test_more_random_samples_extend_the_same_stream():
    params = [random_param("c.z", "uniform", (0.0, 1.0))]
    few = [c.case_id for c in expand(spec(params, samples=4, seed=3))]
    many = [c.case_id for c in expand(spec(params, samples=9, seed=3))]
    assert many[:4] == few


@pytest.mark.parametrize(
    ("name", "args", "frozen"),
    [
        ("uniform", (2.0, 5.0), stats.uniform(loc=2.0, scale=3.0)),
        ("normal", (10.0, 0.5), stats.norm(loc=10.0, scale=0.5)),
        ("triangular", (1.0, 1.5, 4.0), stats.triang(c=0.5 / 3.0, loc=1.0, scale=3.0)),
        ("triangular", (1.0, 1.0, 4.0), stats.triang(c=0.0, loc=1.0, scale=3.0)),
    ],
)
def test_quantile_functions_match_scipy(name, args, frozen):
    u = np.linspace(0.001, 0.999, 301)
    got = Distribution(name, args).quantile(u)
    np.testing.assert_allclose(got, frozen.ppf(u), rtol=1e-12, atol=1e-12)


def test_sample_statistics_of_the_draws():
    """10000 normal draws: mean within 4 standard errors, standard deviation within 4 % (the
    sampling error of s is about sigma / sqrt(2 n) = 0.7 %)."""
    n = 10_000
    u = draw_uniform(n, 1, seed=11)[:, 0]
    x = Distribution("normal", (50.0, 2.0)).quantile(u)
    assert abs(x.mean() - 50.0) < 4 * 2.0 / math.sqrt(n)
    assert abs(x.std(ddof=1) / 2.0 - 1.0) < 0.04
    assert stats.kstest(u, "uniform").pvalue > 1e-3


def test_latin_hypercube_has_one_sample_per_stratum():
    n, d = 20, 3
    u = draw_uniform(n, d, seed=5, sampling="latin-hypercube")
    assert u.shape == (n, d)
    assert np.all((u >= 0.0) & (u < 1.0))
    for j in range(d):
        assert sorted(np.floor(u[:, j] * n).astype(int)) == list(range(n))


@pytest.mark.parametrize(
    ("name", "args", "key"),
    [
        ("uniform", (2.0, 2.0), "high"),
        ("normal", (1.0, 0.0), "std"),
        ("triangular", (1.0, 5.0, 4.0), "mode"),
        ("normal", (1.0,), "distribution"),
        ("lognormal", (1.0, 2.0), "distribution"),
    ],
)
def test_bad_distributions(name, args, key):
    from crankdyn.errors import InputError

    with pytest.raises(InputError) as info:
        Distribution(name, args)
    assert info.value.key == key
