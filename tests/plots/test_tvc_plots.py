"""The TVC's per-order plot (issue 32): every order's curve is the shaft's order torque over
its section modulus (hand formula), every curve of a panel can be told apart, the legends stand
outside the plot areas and a transient limit above the scale is given in the legend."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from crankdyn.constants import RPM
from crankdyn.io.catalogue import resolve_model_and_engine
from crankdyn.plots.tvc import _per_order
from crankdyn.tvc import tvc


@pytest.fixture(scope="module")
def geared():
    model, engine = resolve_model_and_engine("verdict-geared-line")
    return model, tvc(model, engine, passage=False).conditions[0]


def test_order_curves_are_order_torque_over_the_section_modulus(geared):
    model, condition = geared
    r = condition.response
    fig = condition.plot_orders()
    panel = next(ax for ax in fig.axes if ax.get_title(loc="left") == "coupling secondary - pinion")
    s = next(
        i for i, sh in enumerate(model.shafts) if sh.between == ("coupling secondary", "pinion")
    )
    w_p = math.pi * 0.160**3 / 16.0  # the 160 mm gearbox input shaft: W_p = pi D^3 / 16 (m^3)
    orders = [float(q) for q in r.orders]
    drawn = [line for line in panel.get_lines() if line.get_label().startswith("order ")]
    assert len(drawn) == 5
    for line in drawn:
        q = float(line.get_label().split()[1])
        expected = np.asarray(r.order_shaft_torque)[:, orders.index(q), s] / w_p / 1e6  # MPa
        np.testing.assert_allclose(line.get_ydata(), expected, rtol=1e-9)
        np.testing.assert_allclose(line.get_xdata(), np.asarray(r.speed) * RPM)
        assert ("(major)" in line.get_label()) == (line.get_linestyle() == "-")


def test_every_curve_of_a_panel_can_be_told_apart(geared):
    _model, condition = geared
    fig = condition.plot_orders()
    fig.canvas.draw()
    for ax in fig.axes:
        if not ax.get_lines():
            continue
        styles = [(line.get_color(), line.get_linestyle()) for line in ax.get_lines()]
        assert len(set(styles)) == len(styles), ax.get_title(loc="left")
        legend = ax.get_legend()
        box = legend.get_window_extent()
        assert box.x0 >= ax.get_window_extent().x1 - 1.0  # outside the plot area
        labels = [t.get_text() for t in legend.get_texts()]
        # the transient limits (85-132 MPa) stand above the scale: their values in the legend
        assert any(t.startswith("transient limit\n") and "off scale" in t for t in labels)


def test_orders_of_a_distributed_shaft_at_its_most_loaded_element():
    # two speeds, three shafts; the check reads shafts 1 and 2 (a distributed shaft's elements)
    synth = np.array([[9.0, 4.0, 2.0], [9.0, 1.0, 3.0]])  # (speed, shaft) N m
    order = np.array([[[5.0, 3.0, 1.5], [4.0, 1.0, 0.5]], [[5.0, 0.6, 2.0], [4.0, 0.4, 1.0]]])
    r = SimpleNamespace(synthesized_shaft_torque=synth, order_shaft_torque=order)
    check = SimpleNamespace(elements=(1, 2), unit="Pa")
    values = np.array([4.0, 3.0]) * 1e3  # the largest synthesised torque of the two / W, W = 1e-3
    per = _per_order(r, check, values)
    # speed 1: shaft 1 (4 > 2) carries orders 3 and 1; speed 2: shaft 2 (3 > 1): 2 and 1
    np.testing.assert_allclose(per, np.array([[3.0, 1.0], [2.0, 1.0]]) * 1e3)
    assert _per_order(r, SimpleNamespace(elements=(), unit="Pa"), values) is None
    assert _per_order(r, SimpleNamespace(elements=(1,), unit="W"), values) is None
