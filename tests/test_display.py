"""crankdyn.display: the one number formatter (engineering units, digits, round-off as 0) and the
notebook views built with it."""

from __future__ import annotations

import math

import numpy as np
import pytest

from crankdyn.display import (
    clean,
    column_text,
    engineering_unit,
    format_value,
    mass_elastic_tables,
    number,
    quantity,
    torsion_model_html,
    unit_label,
)
from crankdyn.engine.model import Engine


@pytest.mark.parametrize(
    ("value", "unit", "text"),
    [
        (1.89441e6, "Pa", "1.8944 MPa"),  # IMEP, not 1.89441e+06 Pa
        (130.3e3, "N", "130.3 kN"),
        (0.137, "m", "137 mm"),
        (247.2e3, "W", "247.2 kW"),
        (216.58, "Hz", "216.58 Hz"),
        (2.5e6, "N·m/rad", "2.5 MN·m/rad"),
        (2.5e6, "Nm/rad", "2.5 MN·m/rad"),  # the ASCII spelling is the same unit
        (6000.000000000001, "rpm", "6000 rpm"),
        (0.0467, "kg·m²", "0.0467 kg·m²"),
        (None, "N", "-"),
    ],
)
def test_quantity(value, unit, text):
    assert quantity(value, unit) == text


def test_number_digits_and_roundoff():
    assert number(12345.6) == "12346"  # integer digits are kept, no exponent
    assert number(123456.7) == "123457"
    assert number(0.0500, 2) == "0.05"
    assert number(1.393e-14, reference=2.0) == "0"  # round-off beside values of order 1
    assert number(1.393e-14) == "1.393e-14"  # without a reference it is a number
    assert number(-0.0) == "0" and number(None) == "-" and number(math.nan) == "-"
    assert number(3.2e-7) == "3.2e-07"
    assert number(True) == "yes" and number(np.int64(7)) == "7" and number("text") == "text"


def test_format_value_follows_its_reference():
    assert format_value(1.89441e6, "Pa") == ("1.8944", "MPa")
    assert format_value(130733.0, "N") == ("130.73", "kN")
    assert format_value(1.393e-14, "N", reference=5e4) == ("0", "kN")
    # beside a larger value the unit is the reference's: a range reads 0.9-1.8 MPa
    assert format_value(0.9e6, "Pa", reference=1.8e6) == ("0.9", "MPa")
    assert quantity(1e-11, "N·m", reference=1e3) == "0 kN·m"  # the column's unit, round-off 0
    assert quantity(1.89441e6, "Pa", to="bar") == "18.944 bar"
    assert quantity(1.89441e6, "Pa", 4) == "1.894 MPa"
    with pytest.raises(ValueError, match="unknown display unit"):
        quantity(1.0, "Pa", to="psi")


def test_engineering_unit_puts_the_magnitude_between_1_and_1000():
    assert engineering_unit(1.89e6, "Pa") == ("MPa", 1e-6)
    assert engineering_unit(5e-6, "m") == ("µm", 1e6)
    assert engineering_unit(0.0, "N") == ("N", 1.0)
    assert engineering_unit(300.0, "rpm") == ("rpm", 1.0)


def test_column_text_aligned_and_per_cell():
    texts, unit = column_text([0.0, 1.2e-12, 130733.2, -5000.0], "N")
    assert unit == "kN" and texts == ["0", "0", "130.73", "-5.00"]
    texts, unit = column_text(np.arange(0.0, 40.0, 10.0), "deg")
    assert texts == ["0", "10", "20", "30"] and unit == "deg"
    # values that span decades keep their digits cell by cell; None and NaN read '-'
    texts, unit = column_text([0.0467, 12.5, None, 1e-14, math.nan], "kg·m²", aligned=False)
    assert texts == ["0.0467", "12.5", "-", "0", "-"] and unit == "kg·m²"
    texts, unit = column_text([0.0, 1.2e6, 2.5e6, None], "N·m/rad")
    assert (texts, unit) == (["0", "1.2", "2.5", "-"], "MN·m/rad")


def test_unit_label_and_clean():
    assert unit_label("Stiffness", "MN·m/rad") == "Stiffness (MN·m/rad)"
    assert unit_label("Loss factor", "") == "Loss factor"
    assert clean(1000 + 20 * 250.00000000000003) == 6000.0
    assert clean(0.1 + 0.2) == 0.3


def test_the_notebook_shows_the_reports_mass_elastic_tables():
    """One view of a torsional model: the notebook's HTML holds every cell of the report's
    mass-elastic tables, every inertia to five significant digits."""
    model = Engine.example("inline6-diesel").torsion
    tables = mass_elastic_tables(model)
    names = [t[0] for t in tables]
    assert names[:2] == ["torsion_masses", "torsion_shafts"]
    masses = tables[0]
    assert len(masses[3]) == model.mass_count  # every mass, one row each
    column = masses[2].index("Moment of inertia J (kg·m²)")
    for row, mass in zip(masses[3], model.masses, strict=True):
        assert float(row[column]) == pytest.approx(mass.inertia, rel=5e-5)
    html = torsion_model_html(model)
    for _name, _title, header, rows, _caption in tables:
        for cell in [*header, *(c for r in rows for c in r)]:
            assert cell.replace("&", "&amp;") in html or cell in html


def test_mass_elastic_tables_use_the_class_forms_units():
    """Issue 32: one unit per column, the class forms' (kg·m², MN·m/rad, mm), whatever the
    magnitudes: a row never mixes mm and m."""
    model = Engine.example("marine-propulsion").torsion
    tables = {t[0]: t for t in mass_elastic_tables(model)}
    header, rows = tables["torsion_shafts"][2], tables["torsion_shafts"][3]
    assert "Stiffness k (MN·m/rad)" in header
    assert "Outer diameter (mm)" in header and "Length (mm)" in header
    d = header.index("Outer diameter (mm)")
    k = header.index("Stiffness k (MN·m/rad)")
    shaft = next(s for s in model.shafts if s.geometry is not None)
    row = rows[list(model.shafts).index(shaft)]
    assert float(row[d]) == pytest.approx(shaft.geometry.outer_diameter * 1e3, rel=5e-5)
    assert float(row[k]) == pytest.approx(shaft.stiffness / 1e6, rel=5e-5)
    assert "Moment of inertia J (kg·m²)" in tables["torsion_masses"][2]
