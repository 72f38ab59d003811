"""The shared pieces of an engine cycle's analyses (issue 16): per-throw sums, the refined
maxima of several quantities at once and the crank train's shared summary grid give the same
numbers, to the bit, as the one-at-a-time forms they replace."""

from __future__ import annotations

import math

import numpy as np
import pytest

import crankdyn
from crankdyn.engine.bearings import bearing_loads
from crankdyn.engine.forces import (
    SUMMARY_STEP,
    crank_train,
    cycle_grid,
    refined_extrema,
    refined_extremum,
    throw_sums,
)
from crankdyn.engine.torque import engine_torque


@pytest.mark.parametrize(
    "throws",
    [(1, 2, 3, 4), (1, 2, 1, 2), (1, 2, 3, 1, 2, 3), (2, 1, 1, 3, 2, 3), (1, 1, 1, 2)],
)
def test_throw_sums_equal_add_at_to_the_bit(throws):
    rng = np.random.default_rng(len(throws) + sum(throws))
    values = rng.normal(size=(len(throws), 50)) * 10.0 ** rng.integers(-3, 4, size=(1, 50))
    values[:, :5] = -0.0  # signed zeros: add.at from zeros makes them +0.0
    values[0, 5] = 1e300
    count = max(throws)
    expected = np.zeros((count, 50))
    np.add.at(expected, np.asarray(throws) - 1, values)
    got = throw_sums(values, throws, count)
    assert np.array_equal(got, expected)
    assert np.array_equal(np.signbit(got), np.signbit(expected))


def test_throw_sums_with_a_throw_without_cylinders():
    values = np.array([[1.0, 2.0], [3.0, 4.0]])
    assert throw_sums(values, (1, 3), 3).tolist() == [[1.0, 2.0], [0.0, 0.0], [3.0, 4.0]]


def test_refined_extrema_equal_refined_extremum_row_by_row():
    grid = np.radians(np.arange(0.0, 721.0, 1.0))
    shifts = np.array([[0.3], [2.0], [5.5]])

    def rows(t):
        return np.cos(3.0 * (t - shifts)) + 0.2 * np.sin(7.0 * t)

    values = rows(grid[None, :])
    best, at = refined_extrema(rows, grid, values, period=4.0 * math.pi)
    for k in range(3):

        def one(t, k=k):
            return rows(np.asarray(t)[None, :])[k]

        value, angle = refined_extremum(one, grid, values[k], period=4.0 * math.pi)
        assert best[k] == value and at[k] == angle


def test_summary_train_and_warnings_are_shared_and_equal_a_fresh_evaluation():
    engine = crankdyn.Engine.example("v8-crossplane")
    speed = 3000.0 * math.pi / 30.0
    step = math.radians(0.5)
    train = crank_train(engine, speed, cycle_grid(engine, step))
    summary = train.summary_train()
    assert summary is train.summary_train()
    fresh = crank_train(engine, speed, cycle_grid(engine, SUMMARY_STEP), pressure=train.trace)
    assert np.array_equal(summary.tangential, fresh.tangential)
    assert train.warnings() is train.warnings()
    torque = engine_torque(engine, speed, step=step, train=train)
    loads = bearing_loads(engine, speed, step=step, train=train)
    alone_t = engine_torque(engine, speed, step=step)
    alone_b = bearing_loads(engine, speed, step=step)
    assert (torque.max_torque, torque.min_torque) == (alone_t.max_torque, alone_t.min_torque)
    assert np.array_equal(loads.max_pin_load, alone_b.max_pin_load)
    assert np.array_equal(loads.max_bearing_load, alone_b.max_bearing_load)


def test_half_binomial_equals_scipy_binom_to_the_bit():
    """C(1/2, n) without scipy.special (crank.kinematics.half_binomial) is scipy's number."""
    from scipy.special import binom

    from crankdyn.crank.kinematics import half_binomial

    for n in range(26):
        assert half_binomial(n) == float(binom(0.5, n)), n


@pytest.mark.parametrize("name", ["inline6-diesel", "v8-crossplane", "vaz2108"])
def test_session_forces_on_the_shared_train_equal_a_call_of_their_own(name):
    """Analysis.forces() reuses the session's crank train (its summary grid and warnings):
    every number equals engine_forces evaluated alone."""
    from crankdyn.engine.forces import engine_forces
    from crankdyn.session import Analysis

    engine = crankdyn.Engine.example(name)
    analysis = Analysis(engine, speed=2500.0 * math.pi / 30.0)
    analysis.torque  # noqa: B018  (the train's summary grid and warnings computed first)
    shared = analysis.forces(2)
    alone = engine_forces(engine, analysis.speed, cylinder=2, step=analysis.step)
    for key, value in vars(alone).items():
        other = getattr(shared, key)
        if isinstance(value, np.ndarray):
            assert np.array_equal(value, other, equal_nan=True), key
        elif key == "warnings":
            assert repr(value) == repr(other)
        else:
            assert value == other, key
