"""Firing-order ranking criteria: adjacency, main bearings, free moments, torsional vector sums,
exhaust grouping; priorities and bad input."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from crankdyn.engine.firing import FiringSchemes
from crankdyn.engine.firing_search import (
    Layout,
    arrangement,
    firing_order_search,
    major_orders,
    torsional_orders,
    vector_sums,
)
from crankdyn.engine.model import Cylinders, Engine
from crankdyn.errors import InputError

INLINE6 = Cylinders(count=6, firing_order=(1, 5, 3, 6, 2, 4), pitch=0.12)
LINEAR_MODE = [1.0, 0.9, 0.78, 0.64, 0.48, 0.3]  # a first-mode-like shape, node past cylinder 6


def test_inline4_main_bearing_intervals_by_hand():
    """1-3-4-2 fires 1, 3, 4, 2 at 0, 180, 360, 540: cylinders either side of the bearings
    fire 180 (1|2: 0 vs 540), 360 (2|3: 540 vs 180) and 180 (3|4: 180 vs 360) deg apart."""
    c = arrangement(Cylinders(count=4, firing_order=(1, 3, 4, 2)))
    assert math.degrees(c.main_bearing_min_interval) == pytest.approx(180.0)
    assert c.adjacent_consecutive == 2  # 3-4 and 2-1
    assert c.adjacent_pairs == ("3-4", "2-1")


def test_single_throw_has_no_bearing_criterion():
    assert arrangement(Cylinders(count=1, firing_order=(1,))).main_bearing_min_interval is None


def test_vector_sums_by_hand_and_major_orders():
    phi = np.asarray(INLINE6.firing_angles)
    orders = torsional_orders(6, "four-stroke")
    np.testing.assert_allclose(orders, [0.5, 1, 1.5, 2, 2.5, 3])
    sums = vector_sums(phi, LINEAR_MODE, orders)
    for n, value in zip(orders, sums, strict=True):
        re = sum(b * math.cos(n * p) for b, p in zip(LINEAR_MODE, phi, strict=True))
        im = sum(b * math.sin(n * p) for b, p in zip(LINEAR_MODE, phi, strict=True))
        assert value == pytest.approx(math.hypot(re, im))
    major = major_orders(orders, 6, "four-stroke")
    assert list(orders[major]) == [3.0]
    assert sums[major][0] == pytest.approx(sum(LINEAR_MODE))  # all in phase
    batch = vector_sums(np.stack([phi, phi]), LINEAR_MODE, orders)
    np.testing.assert_allclose(batch, [sums, sums])


def test_torsional_criterion_ranks_by_the_largest_minor_order_sum():
    result = firing_order_search(INLINE6, mode_shape=LINEAR_MODE, priority=["torsional_vector_sum"])
    values = [c.torsional_vector_sum for c in result.candidates]
    assert values == sorted(values)
    best = result.candidates[0]
    minor = {k: v for k, v in best.torsional_vector_sums.items() if k != "3"}
    assert best.torsional_vector_sum == pytest.approx(max(minor.values()))
    # one amplitude per throw gives the same as one per cylinder on an in-line engine
    again = firing_order_search(INLINE6, mode_shape=LINEAR_MODE, torsion_orders=[1.5, 4.5])
    assert set(again.candidates[0].torsional_vector_sums) >= {"1.5", "4.5"}


def test_exhaust_groups_for_pulse_turbocharging():
    """1-5-3-6-2-4 with branches 1-2-3 and 4-5-6: each branch's cylinders fire 240 deg apart."""
    result = firing_order_search(
        INLINE6, exhaust_groups=[[1, 2, 3], [4, 5, 6]], priority=["exhaust_min_interval_deg"]
    )
    by_order = {c.order_text: c for c in result.candidates}
    assert math.degrees(by_order["1-5-3-6-2-4"].exhaust_min_interval) == pytest.approx(240.0)
    assert math.degrees(result.candidates[0].exhaust_min_interval) == pytest.approx(240.0)
    assert math.degrees(result.candidates[-1].exhaust_min_interval) < 240.0


def test_free_moment_criteria_match_the_balance_coefficients():
    inline3 = Cylinders(count=3, firing_order=(1, 2, 3))
    c = arrangement(inline3)
    assert c.free_force_1 == 0.0 and c.free_force_2 == 0.0
    assert c.free_moment_1 == pytest.approx(math.sqrt(3))
    assert c.free_moment_2 == pytest.approx(math.sqrt(3))


def test_any_crankshaft_ranks_balanced_crankshafts_first():
    result = firing_order_search(INLINE6, search="any-crankshaft")
    assert result.count == 120
    best = result.candidates[0]
    assert best.free_moment_1 == 0.0 and best.free_moment_2 == 0.0
    assert best.adjacent_consecutive == 0
    assert result.engine_rank is not None


def test_engine_rank_and_top():
    e = Engine.example("v8-crossplane")
    result = firing_order_search(e.cylinders, top=3)
    assert len(result.candidates) == 3 and result.count == 8
    full = firing_order_search(e.cylinders)
    assert full.candidates[full.engine_rank - 1].firing_order == e.cylinders.firing_order
    assert all(c.v_scheme == "interposed" for c in full.candidates)


def test_uneven_engine_lists_every_order_by_evenness():
    v6 = Cylinders(
        count=6,
        firing_order=(1, 4, 2, 5, 3, 6),
        layout="V",
        bank_angle=math.radians(90),
        throw_angles=tuple(np.radians([0, 240, 120, 90, 330, 210])),
    )
    result = firing_order_search(v6)
    assert result.even_count == 0 and result.count > 1
    best = result.candidates[0]
    assert best.order_text == "1-4-2-5-3-6"
    np.testing.assert_allclose(np.degrees(best.firing_intervals), [90, 150] * 3)
    assert best.v_scheme == "alternating"
    assert firing_order_search(v6, include_uneven=False).count == 0


def test_csv_and_ranked_list():
    result = firing_order_search(INLINE6)
    lines = result.to_csv().splitlines()
    assert lines[0].startswith("rank,firing_order,firing_intervals_deg,interval_deviation_deg")
    assert len(lines) == 5
    ranked = result.ranked_list()
    assert ranked[0]["firing_order"] == list(result.candidates[0].firing_order)


@pytest.mark.parametrize(
    ("kwargs", "fragment"),
    [
        ({"priority": ["nonsense"]}, "unknown or unavailable criterion"),
        ({"priority": ["torsional_vector_sum"]}, "needs a mode shape"),
        ({"torsion_orders": [1.5]}, "need a mode shape"),
        ({"mode_shape": [1.0, 2.0]}, "expected 6 amplitudes"),
        ({"mode_shape": [0.0] * 6}, "not all zero"),
        ({"mode_shape": [1.0] * 6, "torsion_orders": [-1.0]}, "positive"),
        ({"exhaust_groups": [[1]]}, "at least two"),
        ({"exhaust_groups": [[1, 2], [2, 3]]}, "each at most once"),
        ({"exhaust_groups": [[1, 9]]}, "cylinders 1..6"),
        ({"search": "everything"}, "expected one of"),
    ],
)
def test_bad_input(kwargs, fragment):
    with pytest.raises(InputError, match=fragment):
        firing_order_search(INLINE6, **kwargs)


def test_layout_helpers():
    layout = Layout.of(Engine.example("v8-crossplane").cylinders)
    adj = layout.adjacent()
    assert adj[1, 3] and adj[2, 4] and not adj[1, 2] and not adj[1, 5]
    pairs = layout.bearing_pairs()
    assert all(abs(layout.throws[i] - layout.throws[j]) == 1 for i, j in pairs)
    s = FiringSchemes.empty(8, "four-stroke")
    assert len(s) == 0


def test_first_mode_shape_from_a_torsional_model():
    """Three equal discs on equal shafts, free-free, cylinders on the outer two: the first
    elastic mode is (1, 0, -1) (closed form), so the cylinders' amplitudes are 1 and -1."""
    from crankdyn.engine.firing_search import first_mode_shape
    from crankdyn.torsion.elements import Mass, Shaft
    from crankdyn.torsion.model import TorsionModel

    model = TorsionModel(
        masses=(
            Mass("a", 1.0, cylinders=(1,)),
            Mass("b", 1.0),
            Mass("c", 1.0, cylinders=(2,)),
        ),
        shafts=(Shaft(("a", "b"), 1e4), Shaft(("b", "c"), 1e4)),
    )
    beta = first_mode_shape(model, 2)
    assert abs(beta[0]) == pytest.approx(1.0) and beta[1] == pytest.approx(-beta[0])
    two = Cylinders(count=2, firing_order=(1, 2))
    result = firing_order_search(two, mode_shape=beta)
    # 1 and 2 fire 360 deg apart: at order 0.5 the opposite amplitudes add (|1 - (-1)| = 2)
    assert result.candidates[0].torsional_vector_sums["0.5"] == pytest.approx(2.0)


def test_first_mode_shape_of_the_inline6_model(cli):
    e = Engine.example("inline6-diesel")
    from crankdyn.engine.firing_search import first_mode_shape
    from crankdyn.torsion.modal import natural_modes

    beta = first_mode_shape(e.torsion, 6)
    modes = natural_modes(e.torsion)
    shape = modes.mode_shapes[1 if modes.free else 0]
    for c in range(1, 7):
        i = next(k for k, m in enumerate(e.torsion.masses) if c in m.cylinders)
        assert beta[c - 1] == shape[i]
    run = cli("firing-orders", "inline6-diesel", "--mode-shape", "torsion", "--format", "json")
    assert run.status == 0, run
    assert all("torsional_vector_sum" in d for d in json.loads(run.out))
    run = cli("firing-orders", "vaz2108", "--mode-shape", "torsion")
    assert run.status == 2 and "[torsion]" in run.err
