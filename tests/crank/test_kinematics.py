"""Kinematics identities: derivatives, offset limits, series convergence, dead centres."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from crankdyn.crank.geometry import CrankGeometry
from crankdyn.crank.kinematics import (
    complex_step,
    dead_centres,
    piston_jerk,
    piston_kinematics,
    rod_angular_jerk,
    series_coefficients,
    slider_crank_approx,
    slider_crank_exact,
    slider_crank_series,
)

PHI = np.linspace(0.0, 2 * math.pi, 721)


@st.composite
def geometries(draw):
    radius = draw(st.floats(0.01, 0.5))
    lam = draw(st.floats(0.05, 0.9))
    rod = radius / lam
    k = draw(st.floats(-0.95, 0.95)) * (rod - radius) / radius
    return radius, rod, k * radius


def _fd(f, phi, h=1e-5):
    return (f(phi + h) - f(phi - h)) / (2 * h)


@settings(max_examples=40, deadline=None)
@given(geometries(), st.floats(1.0, 1000.0))
def test_rates_are_time_derivatives(geom, w):
    """v = dx/dt, a = dv/dt, jerk = da/dt; rod: w_L = dbeta/dt, e_L = dw_L/dt (finite
    differences with step 1e-5 rad: truncation ~1e-10 relative; at lambda = 0.9 the rod is nearly
    perpendicular to the axis and the tolerance allows for the larger higher derivatives)."""
    r, l, e = geom

    def m(p):
        return slider_crank_exact(p, r, l, e, w)

    def at(i):
        return lambda p: m(p)[i]

    scale = {i: np.max(np.abs(m(PHI)[i])) + 1e-300 for i in range(6)}
    checks = [(0, 1), (1, 2), (3, 4), (4, 5)]
    for src, dst in checks:
        derivative = _fd(at(src), PHI) * w
        np.testing.assert_allclose(derivative, m(PHI)[dst], rtol=0, atol=2e-5 * scale[dst])
    jerk = piston_jerk(PHI, r, l, e, w)
    np.testing.assert_allclose(_fd(at(2), PHI) * w, jerk, atol=2e-5 * np.abs(jerk).max())
    rj = rod_angular_jerk(PHI, r, l, e, w)
    np.testing.assert_allclose(_fd(at(5), PHI) * w, rj, atol=2e-5 * np.abs(rj).max())


def test_analytic_jerks_match_complex_step():
    r, l, e, w = 0.05, 0.16, 0.012, 300.0
    cs = complex_step(lambda p: slider_crank_exact(p, r, l, e, w).acceleration)
    np.testing.assert_allclose(
        cs(PHI) * w, piston_jerk(PHI, r, l, e, w), rtol=1e-12, atol=1e-9 * w**3 * r
    )
    cs = complex_step(lambda p: slider_crank_exact(p, r, l, e, w).rod_angular_acceleration)
    np.testing.assert_allclose(
        cs(PHI) * w, rod_angular_jerk(PHI, r, l, e, w), rtol=1e-12, atol=1e-9 * w**3
    )


def test_approx_rates_are_derivatives_of_approx_displacement():
    r, l, e, w = 0.04, 0.15, 0.006, 200.0

    def x(p):
        return slider_crank_approx(p, r, l, e, w).displacement

    m = slider_crank_approx(PHI, r, l, e, w)
    np.testing.assert_allclose(_fd(x, PHI) * w, m.velocity, atol=1e-8 * np.abs(m.velocity).max())
    v = complex_step(lambda p: slider_crank_approx(p, r, l, e, w).velocity)
    np.testing.assert_allclose(v(PHI) * w, m.acceleration, rtol=1e-12, atol=1e-9)


@settings(max_examples=30, deadline=None)
@given(geometries())
def test_offset_tends_to_central(geom):
    """As e -> 0 every quantity tends to the central mechanism's (linearly in e)."""
    r, l, _ = geom
    central = slider_crank_exact(PHI, r, l, 0.0, 1.0)
    for e in (1e-3 * r, 1e-5 * r):
        off = slider_crank_exact(PHI, r, l, e, 1.0)
        for a, b in zip(off, central, strict=True):
            scale = np.abs(b).max() + r
            assert np.abs(a - b).max() < 50 * (e / r) * scale


@settings(max_examples=40, deadline=None)
@given(geometries())
def test_dead_centres_and_true_stroke(geom):
    """At the dead centres the piston velocity vanishes; x(TDC) = 0 and x(BDC) = stroke; the true
    stroke exceeds 2R for an offset engine and equals it for a central one."""
    r, l, e = geom
    tdc, bdc, stroke = dead_centres(r, l, e)
    m = slider_crank_exact(np.array([tdc, bdc]), r, l, e, 1.0)
    np.testing.assert_allclose(m.velocity, 0.0, atol=1e-12 * r)
    assert m.displacement[0] == pytest.approx(0.0, abs=1e-12 * r)
    assert m.displacement[1] == pytest.approx(stroke, rel=1e-12)
    assert stroke >= 2 * r * (1 - 1e-14)  # equality to round-off for e -> 0
    x = slider_crank_exact(PHI, r, l, e, 1.0).displacement
    assert x.min() >= -1e-12 * r and x.max() <= stroke * (1 + 1e-12)


def test_offset_dead_centre_formulas_seed000():
    """Seed 000 section 1.2: phi_TDC = arcsin(lambda k/(1 + lambda)),
    phi_BDC = 180 deg + arcsin(lambda k/(1 - lambda))."""
    r, l, e = 0.05, 0.18, 0.01
    lam, k = r / l, e / r
    tdc, bdc, _ = dead_centres(r, l, e)
    assert tdc == pytest.approx(math.asin(lam * k / (1 + lam)), rel=1e-14)
    assert bdc == pytest.approx(math.pi + math.asin(lam * k / (1 - lam)), rel=1e-14)


def test_series_classical_coefficients():
    """A2 = lambda + lambda^3/4 + 15 lambda^5/128, A4 = -(lambda^3/4 + 3 lambda^5/16),
    A6 = 9 lambda^5/128 (the series to order 6 keeps terms up to lambda^5)."""
    lam = 0.3
    c, s = series_coefficients(lam, 0.0, 6)
    a = [-(m * m) * c[m] for m in range(7)]
    assert a[1] == pytest.approx(1.0, rel=1e-15)
    assert a[2] == pytest.approx(lam + lam**3 / 4 + 15 * lam**5 / 128, rel=1e-14)
    assert a[4] == pytest.approx(-(lam**3 / 4 + 3 * lam**5 / 16), rel=1e-14)
    assert a[6] == pytest.approx(9 * lam**5 / 128, rel=1e-14)
    assert np.all(s == 0.0) and np.all(c[3::2] == 0.0)


def test_series_order2_is_the_seeds_second_order_formula():
    """Central: the order-2 series equals the approximate formulas exactly."""
    r, l, w = 0.035, 0.135, 500.0
    s2 = slider_crank_series(PHI, r, l, 0.0, w, order=2)
    ap = slider_crank_approx(PHI, r, l, 0.0, w)
    for a, b in zip(s2[:3], ap[:3], strict=True):
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-12 * np.abs(b).max())


@pytest.mark.parametrize("e", [0.0, 0.008])
def test_series_converges_to_exact(e):
    """The error falls geometrically with the order (about lambda^2 per step) to round-off."""
    r, l, w = 0.05, 0.16, 100.0
    exact = slider_crank_exact(PHI, r, l, e, w)
    errors = []
    for order in (2, 4, 8, 16, 32):
        s = slider_crank_series(PHI, r, l, e, w, order)
        errors.append(np.abs(s.acceleration - exact.acceleration).max() / (r * w * w))
    assert all(b < a for a, b in itertools.pairwise(errors))
    assert errors[-1] < 1e-12


def test_series_matches_fft_of_exact_motion():
    """The lambda-series coefficients at high order equal the Fourier coefficients of the exact
    displacement computed by FFT (independent method)."""
    r, l, e = 1.0, 3.2, 0.3
    n = 256
    phi = 2 * math.pi * np.arange(n) / n
    x = slider_crank_exact(phi, r, l, e).displacement
    spec = np.fft.rfft(x) / n
    cos_c, sin_c = series_coefficients(r / l, e / r, 40)
    np.testing.assert_allclose(cos_c[0], spec[0].real, atol=1e-13)
    np.testing.assert_allclose(cos_c[1:21], 2 * spec[1:21].real, atol=1e-13)
    np.testing.assert_allclose(sin_c[1:21], -2 * spec[1:21].imag, atol=1e-13)


def test_summary_offset_engine():
    """An offset engine: TDC/BDC angles from seed 000, max speed at a zero of the acceleration,
    extrema of the acceleration at zeros of the jerk."""
    g = CrankGeometry(0.08, 0.04, 0.14, 0.004)
    w = 400.0
    res = piston_kinematics(g, w)
    s = res.extrema
    tdc, bdc, stroke = dead_centres(g.crank_radius, g.rod_length, g.offset)
    assert s.tdc_crank_angle == pytest.approx(tdc) and s.bdc_crank_angle == pytest.approx(bdc)
    assert s.stroke == pytest.approx(stroke)
    a_at_vmax = slider_crank_exact(s.crank_angle_at_max_velocity, 0.04, 0.14, 0.004, w)
    assert abs(float(a_at_vmax.acceleration)) < 1e-8 * w * w * 0.04
    assert s.max_velocity >= res.velocity.max() - 1e-12
    assert s.min_velocity <= res.velocity.min() + 1e-12
    for x in s.acceleration_extrema:
        assert abs(float(piston_jerk(x.crank_angle, 0.04, 0.14, 0.004, w))) < 1e-6 * w**3 * 0.04
    assert s.max_rod_angle == pytest.approx(math.asin(g.lam * (1 - g.k)))
    assert s.min_rod_angle == pytest.approx(math.asin(g.lam * (-1 - g.k)))
    # offset: the two strokes differ in their peak speeds
    assert s.max_velocity != pytest.approx(-s.min_velocity, rel=1e-6)


def test_central_rod_extrema_closed_forms():
    """Seed 000 section 1.4: rod angular velocity extremes +-lambda w at 0/180 deg, angular
    acceleration extremes -+lambda w^2 / sqrt(1 - lambda^2) at 90/270 deg."""
    lam, w = 0.3, 250.0
    s = piston_kinematics(CrankGeometry(0.1, 0.05, 0.05 / lam), w).extrema
    assert s.max_rod_angular_velocity == pytest.approx(lam * w, rel=1e-12)
    assert s.min_rod_angular_velocity == pytest.approx(-lam * w, rel=1e-12)
    assert s.max_rod_angular_acceleration == pytest.approx(lam * w * w / math.sqrt(1 - lam**2))
    assert s.max_rod_angle == pytest.approx(math.asin(lam))


def test_result_export_keys_and_units():
    res = piston_kinematics(
        CrankGeometry(0.076, 0.0355, 0.0355 / 0.26), 4900 * math.pi / 30, step=math.radians(10)
    )
    d = res.to_dict()
    for key in (
        "crank_angle_deg",
        "displacement_m",
        "velocity_m_s",
        "acceleration_m_s2",
        "rod_angle_deg",
        "rod_angular_velocity_rad_s",
        "rod_angular_acceleration_rad_s2",
    ):
        assert len(d[key]) == 37
    assert d["crank_angle_deg"][9] == pytest.approx(90.0)
    assert d["summary"]["speed_rpm"] == pytest.approx(4900.0)
    csv_text = res.to_csv()
    assert csv_text.splitlines()[0].startswith("crank_angle_deg,displacement_m,")
    assert len(csv_text.splitlines()) == 38
    assert "<table>" in res._repr_html_()
    with pytest.raises(ValueError):
        res.velocity[0] = 1.0  # result arrays are read-only


def test_summary_of_a_denormal_offset():
    # the derivative's values at the bracket ends multiply to an underflow (0.0) when the offset
    # is denormal: the extremum at TDC must still be bracketed by their signs
    from crankdyn.crank.geometry import CrankGeometry
    from crankdyn.crank.kinematics import piston_kinematics

    g = CrankGeometry(bore=0.08, crank_radius=0.04, rod_length=0.16, offset=0.04 * 1.2e-270)
    s = piston_kinematics(g, 100.0).extrema
    centred = piston_kinematics(CrankGeometry(bore=0.08, crank_radius=0.04, rod_length=0.16), 100.0)
    assert s.max_rod_angular_velocity == pytest.approx(centred.extrema.max_rod_angular_velocity)
    assert s.max_acceleration == pytest.approx(centred.extrema.max_acceleration)


def test_time_column_is_phi_over_6n_seed002():
    """Seed 002 eq. 1: phi = w t = 6 n t (phi in degrees, n in rpm, t in s). By hand at
    4900 rpm: phi = 90 deg at t = 90 / (6 x 4900) = 3.0612245e-3 s; a revolution takes
    60 / 4900 = 1.2244898e-2 s. The forces' time column follows the same law on their cycle."""
    import crankdyn

    engine = crankdyn.Engine.example("vaz2108")
    w = 4900 * math.pi / 30
    k = piston_kinematics(engine.geometry, w)
    t = dict(zip(np.round(np.degrees(k.crank_angle), 9), k.time, strict=True))
    assert t[90.0] == pytest.approx(90 / (6 * 4900), rel=1e-12)
    assert t[360.0] == pytest.approx(60 / 4900, rel=1e-12)
    assert "time_s" in k.to_csv().splitlines()[0].split(",")
    from crankdyn.session import Analysis

    forces = Analysis(engine, speed=w).forces()
    np.testing.assert_allclose(
        forces.time, np.degrees(forces.crank_angle) / (6 * 4900), rtol=1e-12, atol=0
    )


def test_intake_gas_velocity_seed002_eq10():
    """Seed 002 eq. 10: V_in = c_m F_p / F_in. By hand for bore 76 mm, stroke 71 mm at 4900 rpm
    and an intake of 12 cm^2: c_m = S n / 30 = 11.59667 m/s, F_p = pi 0.076^2 / 4 =
    4.536460e-3 m^2, V_in = 11.59667 x 4.536460e-3 / 12e-4 = 43.8398 m/s (6 digits)."""
    from crankdyn.io.engine_file import parse_engine
    from crankdyn.session import Analysis

    doc = {
        "name": "intake",
        "geometry": {"bore": "76 mm", "stroke": "71 mm", "rod_ratio": 0.26,
                     "intake_area": "12 cm^2"},
        "operating": {"speed": "4900 rpm"},
    }  # fmt: skip
    engine = parse_engine(doc, file="e.toml")
    summary = Analysis(engine).kinematics().extrema
    assert summary.mean_piston_speed == pytest.approx(11.59667, rel=1e-6)
    assert summary.intake_velocity == pytest.approx(43.8398, rel=1e-5)
    figures = {f.key: f.value for f in summary.key_figures()}
    assert figures["intake_velocity_m_s"] == pytest.approx(43.8398, rel=1e-5)
    no_intake = parse_engine({**doc, "geometry": {"bore": "76 mm", "stroke": "71 mm",
                                                  "rod_ratio": 0.26}}, file="e.toml")  # fmt: skip
    assert Analysis(no_intake).kinematics().extrema.intake_velocity is None
