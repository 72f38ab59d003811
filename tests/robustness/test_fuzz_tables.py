"""Every CSV table reader checks magnitudes and cell counts (issue 17, point 2): pressure traces,
load curves, harmonic tables and (issue 33) mass-elastic tables share crankdyn.io.csv_tables,
whose columns lie within the SI range every other quantity has (1e-12 to 1e12, or 0) and whose
rows hold no more cells than the header names (a decimal comma, ``30,1``, would otherwise be
read as 30 with a stray cell)."""

from __future__ import annotations

import math
import re
from importlib import resources
from types import SimpleNamespace

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from crankdyn.errors import InputError
from crankdyn.io.mass_elastic import read_mass_elastic
from crankdyn.io.torsion_tables import read_harmonic_table, read_load_curve
from crankdyn.io.traces import read_pressure_trace
from tests.conftest import fuzz_examples

EXAMPLES = resources.files("crankdyn") / "examples"
TRACE = (EXAMPLES / "mendes2008_pressure.csv").read_text(encoding="utf-8")
LOAD_CURVE = (EXAMPLES / "mendes2008_peak_pressure.csv").read_text(encoding="utf-8")
HARMONICS = (
    "order,imep_MPa,amplitude_MPa,phase_deg\n"
    "0.5,0.2,0.05,10\n1,0.2,0.08,20\n1.5,0.2,0.04,30\n"
    "0.5,1.0,0.15,12\n1,1.0,0.21,22\n1.5,1.0,0.12,31\n"
)
MASS_ELASTIC = (
    "name,inertia [kg*m^2],damping [N*m*s/rad],cylinders,stiffness [N*m/rad],loss_factor,"
    "gear_ratio\n"
    "disc 1,62.5,2,1,217146.8842,0.02,\ndisc 2,125,,2,217146.8842,,2\ndisc 3,187.5,,,,,\n"
)


def read_mass_elastic_arrays(path):
    """The mass-elastic table's numbers as arrays (SI), for the range check of :func:`check`."""
    model = read_mass_elastic(path)
    return SimpleNamespace(
        inertia=np.array([m.inertia for m in model.masses]),
        damping=np.array([m.damping for m in model.masses]),
        stiffness=np.array([s.stiffness for s in model.shafts]),
        loss_factor=np.array([s.loss_factor for s in model.shafts]),
        ratio=np.array([s.ratio for s in model.shafts]),
    )


READERS = {
    "trace": (TRACE, lambda p: read_pressure_trace(p, firing_tdc=math.radians(360.0))),
    "load curve": (LOAD_CURVE, read_load_curve),
    "harmonics": (HARMONICS, read_harmonic_table),
    # issue 33: the mass-elastic table skipped the SI range check (1e-15 kg m^2 accepted)
    "mass-elastic": (MASS_ELASTIC, read_mass_elastic_arrays),
}


def data_lines(text: str) -> list[int]:
    """Indices of the data rows (after the header) of a CSV text's lines."""
    lines = text.splitlines()
    rows = [i for i, line in enumerate(lines) if line.strip() and not line.startswith("#")]
    return rows[1:]


edits = st.one_of(
    # a value scaled by a power of ten, as a unit mistake or a typo would
    st.tuples(st.just("scale"), st.integers(-330, 330)),
    # a decimal comma in one cell (30.1 -> 30,1), or one cell more
    st.tuples(st.just("comma"), st.integers(0, 5)),
    st.tuples(st.just("extra"), st.sampled_from(["5", "", "x", " ", "1e3"])),
)


def mutate(text: str, row: int, column: int, edit) -> str:
    lines = text.splitlines()
    targets = data_lines(text)
    i = targets[row % len(targets)]
    cells = lines[i].split(",")
    column %= len(cells)
    kind, arg = edit
    if kind == "scale":
        cells[column] = f"{cells[column]}e{arg}"
    elif kind == "comma":
        whole = cells[column].split(".")[0] or "0"
        cells[column] = f"{whole},{arg}"
    else:
        cells.append(arg)
    lines[i] = ",".join(cells)
    return "\n".join(lines) + "\n"


def check(reader: str, path, text: str) -> None:
    """A result whose every value is within the SI range, or one line naming the file and the
    line of the offending cell."""
    path.write_text(text, encoding="utf-8")
    try:
        result = READERS[reader][1](path)
    except InputError as exc:
        message = str(exc)
        assert "\n" not in message
        assert message.startswith(f"{path}: "), message
        return
    for value in vars(result).values():
        if isinstance(value, np.ndarray) and value.dtype.kind == "f":
            finite = value[np.isfinite(value)]
            magnitude = np.abs(finite[finite != 0.0])
            assert np.all((magnitude >= 1e-12) & (magnitude <= 1e12)), (reader, value)


@pytest.mark.parametrize("reader", sorted(READERS))
@settings(max_examples=fuzz_examples(40))
@given(row=st.integers(0, 200), column=st.integers(0, 6), edit=edits)
@example(row=4, column=1, edit=("scale", 300))
@example(row=4, column=1, edit=("scale", -300))
@example(row=4, column=1, edit=("comma", 5))
def test_fuzz_tables(tmp_path_factory, reader, row, column, edit):
    text = READERS[reader][0]
    path = tmp_path_factory.mktemp("table") / "table.csv"
    check(reader, path, mutate(text, row, column, edit))


def test_trailing_commas_are_not_cells(tmp_path):
    """Spreadsheets end rows with a separator: an empty last cell is not a value."""
    text = re.sub(r"(?m)^(\d.*)$", r"\1,", TRACE)
    path = tmp_path / "t.csv"
    path.write_text(text, encoding="utf-8")
    trace = read_pressure_trace(path, firing_tdc=math.radians(360.0))
    assert trace.pressure.max() == pytest.approx(15.2e6, rel=0.01)


@pytest.mark.parametrize(
    ("pressure", "message"),
    [
        (
            "1e300",
            "line 5 = \"1e300\": 1e+306 Pa in column 'pressure_MPa' lies outside the range "
            "crankdyn computes with (1e-12 to 1e12 in SI units, or 0); check the unit",
        ),
        (
            "1e-300",
            "line 5 = \"1e-300\": 1e-294 Pa in column 'pressure_MPa' lies outside the range "
            "crankdyn computes with (1e-12 to 1e12 in SI units, or 0); check the unit",
        ),
        (
            "30,1,5",
            'line 5 = "0.000000,30,1,5": 4 cells, but the header names 2 columns: column 3 has '
            "no name (a decimal comma? write 30.1, not 30,1)",
        ),
    ],
)
def test_the_issues_traces(cli, tmp_path, pressure, message):
    """The issue's reproductions through `crankdyn forces`: a trace of 1e300 MPa (gas forces of
    8.7e303 N before), 1e-300 MPa (an IMEP of 1.6e-310 Pa) and a decimal comma (read as 1 MPa)."""
    lines = TRACE.splitlines()
    lines[4] = f"0.000000,{pressure}"
    (tmp_path / "trace.csv").write_text("\n".join(lines) + "\n", encoding="utf-8")
    engine = (EXAMPLES / "inline6-diesel.toml").read_text(encoding="utf-8")
    engine = engine.replace("mendes2008_pressure.csv", "trace.csv")
    (tmp_path / "engine.toml").write_text(engine, encoding="utf-8")
    run = cli("forces", tmp_path / "engine.toml", "--format", "json")
    assert run.status == 2 and run.out == ""
    assert run.err == f"crankdyn: error: {tmp_path / 'trace.csv'}: {message}\n"
