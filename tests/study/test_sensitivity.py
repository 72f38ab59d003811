"""Sensitivity measures against their definitions and scipy."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats

from crankdyn.study.sensitivity import average_ranks, main_effect, negligible_spread, spearman


def test_ranks_and_spearman_match_scipy():
    rng = np.random.default_rng(3)
    x = rng.integers(0, 6, 80).astype(float)  # many ties
    y = x**2 + rng.normal(0.0, 3.0, 80)
    np.testing.assert_array_equal(average_ranks(x), stats.rankdata(x))
    assert spearman(x, y) == pytest.approx(stats.spearmanr(x, y).statistic, rel=1e-12)


def test_spearman_of_monotone_and_degenerate_samples():
    x = np.linspace(1.0, 2.0, 9)
    assert spearman(x, np.exp(3 * x)) == pytest.approx(1.0)
    assert spearman(x, -(x**3)) == pytest.approx(-1.0)
    assert math.isnan(spearman(x, np.ones_like(x)))
    assert math.isnan(spearman([1.0, 2.0], [3.0, 4.0]))
    assert spearman([1.0, 2.0, np.nan, 3.0], [1.0, 2.0, 5.0, 3.0]) == pytest.approx(1.0)


def test_main_effect_of_a_full_factorial_design():
    """y = 2 a + b^2 on the full 3 x 2 grid: the main effect of a is the range of the means
    over its levels, 2 (a_max - a_min); b's is b_max^2 - b_min^2."""
    a, b = np.meshgrid([1.0, 2.0, 3.0], [0.0, 2.0], indexing="ij")
    y = 2 * a + b**2
    ea = main_effect(a.ravel(), y.ravel(), numeric=True)
    np.testing.assert_allclose(ea.levels, [1.0, 2.0, 3.0])
    np.testing.assert_allclose(ea.means, [4.0, 6.0, 8.0])
    assert ea.effect == pytest.approx(4.0) and not ea.binned
    eb = main_effect(b.ravel(), y.ravel(), numeric=True)
    assert eb.effect == pytest.approx(4.0)
    assert list(eb.counts) == [3, 3]


def test_main_effect_of_a_continuous_parameter_uses_equal_count_bins():
    x = np.linspace(0.0, 1.0, 100)
    effect = main_effect(x, 10 * x, numeric=True, bins=5)
    assert effect.binned and list(effect.counts) == [20] * 5
    # bin means of a linear function: 10 x the mean x of the lowest and highest bins
    assert effect.effect == pytest.approx(10 * (x[80:].mean() - x[:20].mean()))


def test_main_effect_of_a_categorical_parameter_keeps_first_seen_order():
    labels = ["[1, 3, 4, 2]", "[1, 2, 4, 3]"] * 3
    y = [1.0, 5.0, 2.0, 6.0, np.nan, 7.0]
    effect = main_effect(labels, y, numeric=False)
    assert list(effect.levels) == ["[1, 3, 4, 2]", "[1, 2, 4, 3]"]
    np.testing.assert_allclose(effect.means, [1.5, 6.0])
    assert list(effect.counts) == [2, 3]


def test_negligible_spread():
    assert negligible_spread([102.524062, 102.524062 + 1e-6])
    assert not negligible_spread([100.0, 100.1])
    assert negligible_spread([0.0, 0.0])
    assert not negligible_spread([1.0])
