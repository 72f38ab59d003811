"""A pressure trace given over volume or piston displacement (a p-V diagram) converted to crank
angle by the exact kinematics (crankdyn.crank.pressure_volume; seed 002 sec. 1): round trips
p(phi) -> p(V) -> p(phi) for central and offset cylinders, four- and two-stroke, from any starting
point of the cycle; the reader and the engine file; the errors name the line."""

import math

import numpy as np
import pytest

from crankdyn.crank.geometry import CrankGeometry
from crankdyn.crank.kinematics import dead_centres, slider_crank_exact
from crankdyn.crank.pressure_model import WiebePressureModel
from crankdyn.crank.pressure_volume import (
    crank_angle_of_displacement,
    identify_strokes,
    trace_from_displacement,
    trace_from_volume,
    volume_at,
)
from crankdyn.errors import InputError

CENTRAL = CrankGeometry(0.076, 0.0355, 0.0355 / 0.26)
OFFSET = CrankGeometry(0.09, 0.045, 0.15, offset=0.008)


@pytest.mark.parametrize("geometry", [CENTRAL, OFFSET], ids=["central", "offset"])
def test_displacement_inverted_over_a_revolution(geometry):
    _tdc, bdc, _s = dead_centres(geometry.crank_radius, geometry.rod_length, geometry.offset)
    tdc = _tdc
    away = np.linspace(tdc, bdc, 721)
    back = np.linspace(bdc - 2 * math.pi, tdc, 721)
    for phi, flag in ((away, True), (back, False)):
        x = slider_crank_exact(phi, geometry.crank_radius, geometry.rod_length, geometry.offset)
        got = crank_angle_of_displacement(x.displacement, geometry, flag)
        inner = slice(5, -5)  # away from the dead centres, where x is flat in phi
        assert np.max(np.abs(got[inner] - phi[inner])) < 1e-9
        assert np.max(np.abs(got - phi)) < 1e-6  # at the dead centres: sqrt(round-off)


@pytest.mark.parametrize("geometry", [CENTRAL, OFFSET], ids=["central", "offset"])
@pytest.mark.parametrize("cycle", ["four-stroke", "two-stroke"])
@pytest.mark.parametrize("start_deg", [0.0, 200.0, 530.0])
def test_round_trip_p_phi_to_p_v_and_back(geometry, cycle, start_deg):
    """The Wiebe model's trace written as a p-V diagram in the order of the cycle, from any point,
    comes back at its own crank angles with its own pressures."""
    eps = 9.5
    trace = WiebePressureModel(compression_ratio=eps).trace(geometry, cycle, step=math.radians(1))
    phi, p = np.asarray(trace.crank_angle), np.asarray(trace.pressure)
    k = int(np.searchsorted(phi, math.radians(start_deg) % trace.cycle_angle))
    order = np.roll(np.arange(phi.size), -k)
    back = trace_from_volume(volume_at(phi[order], geometry, eps), p[order], geometry, eps,
                             cycle=cycle)  # fmt: skip
    assert back.cycle_angle == trace.cycle_angle
    assert back.compression_ratio == eps
    # a point at firing TDC may come back a hair before it (the end of the cycle)
    angle = np.asarray(back.crank_angle)
    wrapped = np.where(angle > trace.cycle_angle - 1e-6, angle - trace.cycle_angle, angle)
    same = np.argsort(wrapped)
    assert np.array_equal(np.asarray(back.pressure)[same], p)
    assert np.max(np.abs(wrapped[same] - phi)) < 2e-7  # rad: round-off grows at dead centres
    # and p(phi) read back anywhere equals the original trace
    grid = np.linspace(0.0, trace.cycle_angle, 5001)
    scale = float(np.max(p))
    assert np.max(np.abs(back.at(grid) - trace.at(grid))) < 1e-6 * scale


def test_the_strokes_are_told_apart_by_the_pressure_at_tdc():
    phi = np.radians(np.arange(0.0, 720.0, 5.0))
    x = slider_crank_exact(phi, CENTRAL.crank_radius, CENTRAL.rod_length).displacement
    p = 1e5 * (1.0 + 40.0 * np.exp(-((phi / 0.5) ** 2)))  # high only at firing TDC
    stroke, away, firing = identify_strokes(x, p)
    assert firing == 0
    # expansion 0-180, exhaust 180-360, intake 360-540, compression 540-720 deg
    expected = np.minimum((np.degrees(phi) // 180).astype(int), 3)
    assert np.array_equal(stroke, expected)
    assert np.array_equal(away, expected % 2 == 0)
    # the same points with the high pressure at the other TDC: firing TDC moves there
    _s, _a, other = identify_strokes(x, np.roll(p, 72))
    assert other == 72


def test_errors_name_the_point():
    phi = np.radians(np.arange(0.0, 720.0, 10.0))
    x = slider_crank_exact(phi, CENTRAL.crank_radius, CENTRAL.rod_length).displacement
    p = 1e5 * (1.0 + 40.0 * np.exp(-((phi / 0.5) ** 2)))
    wild = x.copy()
    wild[7] = 0.2  # far beyond the 71 mm stroke
    with pytest.raises(InputError, match="outside the stroke") as err:
        trace_from_displacement(wild, p, CENTRAL)
    assert err.value.key == "point 8"
    back = x.copy()
    back[[5, 6]] = back[[6, 5]]  # two points swapped within the expansion stroke
    with pytest.raises(InputError, match="turns back within the expansion stroke"):
        trace_from_displacement(back, p, CENTRAL)
    with pytest.raises(InputError, match="passes TDC 1 time"):
        trace_from_displacement(x[:36], p[:36], CENTRAL)  # one revolution only
    with pytest.raises(InputError, match="compression ratio"):
        trace_from_volume(x, p, CENTRAL, 1.0)


def test_engine_file_reads_a_p_v_diagram(tmp_path):
    from crankdyn.engine.model import Engine

    geometry = CrankGeometry.from_stroke(0.076, 0.071, rod_ratio=0.26)
    eps = 9.9
    trace = WiebePressureModel(compression_ratio=eps).trace(geometry, "four-stroke")
    phi = np.asarray(trace.crank_angle)
    start = int(np.searchsorted(phi, math.radians(360.0)))  # from the start of intake
    idx = np.roll(np.arange(phi.size), -start)
    volume = volume_at(phi[idx], geometry, eps)
    pressure = trace.pressure[idx]
    rows = "\n".join(
        f"{float(v) * 1e6!r},{float(q) / 1e5!r}" for v, q in zip(volume, pressure, strict=True)
    )
    (tmp_path / "pv.csv").write_text("volume_cm3,pressure_bar\n" + rows + "\n", encoding="utf-8")
    engine_text = (
        'name = "pv"\ncycle = "four-stroke"\n[geometry]\nbore = "76 mm"\nstroke = "71 mm"\n'
        'rod_ratio = 0.26\n[pressure]\nfile = "pv.csv"\ncompression_ratio = 9.9\n'
    )
    (tmp_path / "pv.toml").write_text(engine_text, encoding="utf-8")
    engine = Engine.from_file(tmp_path / "pv.toml")
    got = engine.pressure
    assert got is not None and got.compression_ratio == eps
    grid = np.linspace(0.0, 4 * math.pi, 2001)
    assert np.max(np.abs(got.at(grid) - trace.at(grid))) < 1e-6 * float(np.max(trace.pressure))
    # without the compression ratio the volume cannot be placed: the key is named
    (tmp_path / "pv.toml").write_text(engine_text.replace("compression_ratio = 9.9\n", ""))
    with pytest.raises(InputError, match="compression ratio") as err:
        Engine.from_file(tmp_path / "pv.toml")
    assert "pv.csv" in str(err.value)
    # a point against the cycle's order names its line
    lines = ["volume_cm3,pressure_bar", *rows.splitlines()]
    lines[100], lines[101] = lines[101], lines[100]
    (tmp_path / "pv.csv").write_text("\n".join(lines) + "\n", encoding="utf-8")
    (tmp_path / "pv.toml").write_text(engine_text, encoding="utf-8")
    with pytest.raises(InputError, match="turns back") as err:
        Engine.from_file(tmp_path / "pv.toml")
    assert "line 102 = " in str(err.value)  # the second of the two swapped points
