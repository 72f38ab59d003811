"""Unit parsing at the boundary."""

from __future__ import annotations

import math

import pytest

from crankdyn.errors import InputError
from crankdyn.io.units import KINDS, parse_quantity


@pytest.mark.parametrize(
    "text, kind, si",
    [
        ("76 mm", "length", 0.076),
        ("73.4mm", "length", 0.0734),
        ("4900 rpm", "speed", 4900 * math.pi / 30),
        ("10rad/s", "speed", 10.0),
        ("81.6667 Hz", "speed", 81.6667 * 2 * math.pi),  # Hz for a shaft speed: rev/s
        ("4900 rpm", "frequency", 4900 / 60),
        ("0.167 kg*m^2", "inertia", 0.167),
        ("0.167 kg·m²", "inertia", 0.167),
        ("160 kN*m/rad", "torsional_stiffness", 160e3),
        ("70 N*m*s/rad", "torsional_damping", 70.0),
        ("180 deg", "angle", math.pi),
        ("15 MPa", "pressure", 15e6),
        ("80 GPa", "pressure", 80e9),
        ("2.1e-3 kg*m^2", "inertia", 2.1e-3),
        (0.5, "length", 0.5),
        ("0.5", "length", 0.5),
        ("5 %", "ratio", 0.05),
    ],
)
def test_parse(text, kind, si):
    assert parse_quantity(text, kind) == pytest.approx(si, rel=1e-12)


def test_every_kind_example_parses():
    for key, kind in KINDS.items():
        assert math.isfinite(parse_quantity(kind.example, key))


def test_default_unit_for_bare_numbers():
    assert parse_quantity("4900", "speed", default_unit="rpm") == pytest.approx(4900 * math.pi / 30)
    assert parse_quantity(10, "angle", default_unit="deg") == pytest.approx(math.radians(10))
    assert parse_quantity("1 rad", "angle", default_unit="deg") == 1.0


@pytest.mark.parametrize(
    "value, kind, fragment",
    [
        ("76 kg", "length", 'expected a length (e.g. "76 mm"), got a mass'),
        ("1 rpm", "torque", "got a rotational speed"),
        ("76 foo", "length", "unknown unit"),
        ("9^9^9^9 m", "length", "unknown unit"),
        ("2**99 m", "length", "unknown unit"),
        ("__import__('os') m", "length", "expected a number with a unit"),
        ("", "length", "empty value"),
        (True, "length", "expected a length"),
        ([1], "length", "expected a length"),
        ("1e999 m", "length", "not finite"),
        (float("nan"), "length", "not finite"),
        ("12 m", "angle", "expected an angle"),
    ],
)
def test_errors_are_one_line_with_key_and_value(value, kind, fragment):
    with pytest.raises(InputError) as info:
        parse_quantity(value, kind, key="[geometry] bore", file="e.toml")
    text = str(info.value)
    assert text.startswith("e.toml: [geometry] bore = ")
    assert fragment in text
    assert "\n" not in text


@pytest.mark.parametrize("value", ["1e16 mm", "1e-16 m", 1e200, "5e20 N*m/rad", -1e-300])
def test_values_outside_the_computable_range(value):
    """Beyond 1e-12..1e12 in SI a value is a unit mistake (and would overflow later)."""
    kind = "torsional_stiffness" if "rad" in str(value) else "length"
    with pytest.raises(InputError, match="outside the range crankdyn computes with"):
        parse_quantity(value, kind, key="k")


def test_zero_and_ordinary_extremes_pass():
    assert parse_quantity(0, "length") == 0.0
    assert parse_quantity("2e11 Pa", "pressure") == 2e11
    assert parse_quantity("1e-8 kg*m^2", "inertia") == pytest.approx(1e-8)


def _pint_entry(unit: str):
    """What pint makes of a unit: (magnitude of one unit in its kinds' SI unit, or rad/s or Hz
    for a speed or a frequency; the kinds it measures; angular or not)."""
    from crankdyn.io.units import _dimensionality, registry

    ureg = registry()
    units = ureg.parse_units(unit)
    angular = "radian" in str(ureg.get_root_units(units)[1])
    per_angle = dict(ureg.get_root_units(units)[1]._units).get("radian", 0) == -1
    kinds = tuple(
        k
        for k, v in KINDS.items()
        if units.dimensionality == _dimensionality(v.dimensionality)
        and v.per_angle in (None, per_angle)  # a torque is no torsional stiffness (per radian)
    )
    target = {"speed": "rad/s" if angular else "Hz", "frequency": "rad/s" if angular else "Hz"}
    factors = {
        float(
            ureg.Quantity(1.0, units)
            .to(target.get(k, KINDS[k].si_unit or "dimensionless"))
            .magnitude
        )
        for k in kinds
    }
    assert len(factors) == 1
    return factors.pop(), kinds, angular


def test_common_units_are_what_pint_makes_of_them():
    """COMMON_UNITS (the start-up's pint-free path) holds pint's own factors and kinds; a unit
    is added by printing ``_pint_entry(unit)`` into the table."""
    from crankdyn.io.units import _ANGULAR, COMMON_UNITS

    for unit, (factor, kinds) in COMMON_UNITS.items():
        pint_factor, pint_kinds, angular = _pint_entry(unit)
        assert (factor, kinds) == (pint_factor, pint_kinds), unit
        assert (unit in _ANGULAR) == (angular and bool({"speed", "frequency"} & set(kinds))), unit


def test_common_units_give_the_same_number_as_pint(monkeypatch):
    """Every kind, every common unit, magnitudes over twelve decades: the table's value equals
    pint's to the last bit, and a unit of the wrong kind fails with pint's message."""
    import numpy as np

    from crankdyn.io import units as module

    rng = np.random.default_rng(16)
    values = [76.0, 4900.0, 0.167, *rng.uniform(-1e3, 1e3, 5), *(10 ** rng.uniform(-6, 6, 8))]
    fast = {}
    for unit in module.COMMON_UNITS:
        for kind in KINDS:
            for v in values:
                try:
                    fast[unit, kind, v] = module._unit_value(float(v), unit, kind)
                except ValueError as exc:
                    fast[unit, kind, v] = str(exc)
    monkeypatch.setattr(module, "COMMON_UNITS", {})
    for (unit, kind, v), got in fast.items():
        try:
            expected = module._unit_value(float(v), unit, kind)
        except ValueError as exc:
            expected = str(exc)
        assert got == expected, (unit, kind, v)


def test_a_built_in_example_reads_without_pint():
    """The start-up's promise: an example written in the common units never imports pint."""
    import subprocess
    import sys

    code = (
        "import sys; from crankdyn.io.catalogue import resolve_engine; resolve_engine('vaz2108');"
        "print('pint' in sys.modules)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
