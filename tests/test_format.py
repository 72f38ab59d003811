"""crankdyn.format: numbers for people (engineering units, digits, round-off as 0)."""

from __future__ import annotations

import math

import pytest

from crankdyn.format import clean, column, number, quantity, unit_label


@pytest.mark.parametrize(
    ("value", "unit", "text"),
    [
        (1.89441e6, "Pa", "1.894 MPa"),  # IMEP, not 1.89441e+06 Pa
        (130.3e3, "N", "130.3 kN"),
        (0.137, "m", "137 mm"),
        (247.2e3, "W", "247.2 kW"),
        (216.58, "Hz", "216.6 Hz"),
        (2.5e6, "N·m/rad", "2.5 MN·m/rad"),
        (6000.000000000001, "rpm", "6000 rpm"),
        (0.0467, "kg·m²", "0.0467 kg·m²"),
    ],
)
def test_quantity(value, unit, text):
    assert quantity(value, unit) == text


def test_number_digits_and_roundoff():
    assert number(12345.6) == "12346"  # integer digits are kept, no exponent
    assert number(0.0500, 2) == "0.05"
    assert number(1.393e-14, scale=2.0) == "0"  # round-off beside values of order 1
    assert number(1.393e-14) == "1.393e-14"  # without a reference it is a number
    assert number(-0.0) == "0" and number(None) == "-" and number(math.nan) == "-"
    assert number(3.2e-7) == "3.2e-07"
    assert quantity(1e-11, "N·m", scale=1e3) == "0 kN·m"  # the column's unit, round-off 0
    assert quantity(1.89441e6, "Pa", to="bar") == "18.94 bar"


def test_column_and_clean():
    factor, unit, scale = column([0.0, 1.2e6, 2.5e6, None], "N·m/rad")
    assert (factor, unit, scale) == (1e6, "MN·m/rad", 2.5)
    assert unit_label("Stiffness", unit) == "Stiffness (MN·m/rad)"
    assert unit_label("Loss factor", "") == "Loss factor"
    assert clean(1000 + 20 * 250.00000000000003) == 6000.0
    assert clean(0.1 + 0.2) == 0.3
