"""KR Rules for Classification of Steel Ships 2025 (RA-05-E), Pt 5 Ch 4 "Torsional vibration of
shaftings", worked by hand from the text (a markdown transcription of the 2025 rules in a public
repository, read whole: 101-206) against :mod:`crankdyn.tvc.rulesets` ("kr").

Hand arithmetic (d in mm; 300^-0.2 = 0.3195772, 500^-0.2 = 0.2885400):
  C_d(300 mm) = 0.35 + 0.93 x 0.3195772 = 0.6472068;  C_d(500 mm) = 0.35 + 0.93 x 0.2885400
  = 0.6183422.
  202.1(1), carbon steel T_s = 800 N/mm^2 used as 600: (600 + 160)/18 = 42.22222;
    300 mm, C_k = 1, lambda = 0.5: 42.22222 x 0.6472068 x 2.5 = 68.3163 N/mm^2;
    lambda = 0.95: 42.22222 x 0.6472068 x 1.38 = 37.7106 N/mm^2.
  Low alloy intermediate shaft T_s = 900 used as 800: (800 + 160)/18 = 53.33333;
    300 mm, lambda = 0.95: 53.33333 x 0.6472068 x 1.38 = 47.6344 N/mm^2.
  Low alloy propeller shaft T_s = 900 used as 600, C_k = 0.55, 500 mm, lambda = 0.5:
    42.22222 x 0.55 = 23.22222; x 0.6183422 = 14.35928; x 2.5 = 35.8982 N/mm^2;
    202.1(2): tau_2 = 1.7 x 35.8982 / sqrt(0.55) = 61.0269 / 0.7416198 = 82.2887 N/mm^2.
  201.1: group A, lambda = 0.5: 45 - 24 x 0.25 = 39; lambda = 0.9: 45 - 24 x 0.81 = 25.56;
    group B, lambda = 0.9: 45 - 29 x 0.81 = 21.51.
  201.2: tau_2 = 2 tau_1 for lambda <= 0.8; group A at 0.5: 2 x 39 = 78, group B
    2 x (45 - 29 x 0.25) = 2 x 37.75 = 75.5.
  201.3: tau_3(1.1), group A: 237 x 0.3 = 71.1; sqrt(0.1) = 0.3162278; 71.1 x 0.3162278
    = 22.48379; 21 + 22.48379 = 43.48379; group B 38.48379 (tau_3(1) = 21 and 16 = tau_1(1)).
  201.4: T_s = 550: 1 + 2/3 x (550/440 - 1) = 1 + 2/3 x 0.25 = 1.166667; Y = 300: 300/225
    = 1.333333; low alloy T_s = 800: 800/440 = 1.818182, 1 + 2/3 x 0.818182 = 1.545455.
  203.1: crankshaft 21 (A) / 16 (B) N/mm^2 in 0.9-1.1, 90 at and below 0.9; 203.2 generator
    shaft 31 and 118; with T_s = 550: 21 x 1.166667 = 24.5.
  206.1(1): N_c = 400 rpm, N_0 = 500 rpm, lambda = 0.8: 16 x 400 / 17.2 = 372.093 rpm,
    17.2 x 400 / 16 = 430.0 rpm; with a 2 % tachometer tolerance 372.093 x 0.98 = 364.651,
    430.0 x 1.02 = 438.6 rpm.
Tolerances: the hand values carry 6 or 7 significant digits (relative 1e-5).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from crankdyn.constants import RPM
from crankdyn.errors import InputError
from crankdyn.tvc import rulesets as R

MPA = 1e6
REL = 1e-5
KR = R.get("kr")


def test_kr_202_tau_1_carbon_steel_capped_at_600():
    """KR 2025 Pt 5 Ch 4 202.1(1): T_s not above 600 N/mm^2 for carbon steel forgings."""
    assert R.capped_strength(KR, 800 * MPA, "carbon", "intermediate") == 600 * MPA
    assert R.capped_strength(KR, 800 * MPA, "carbon", "thrust") == 600 * MPA
    assert R.capped_strength(KR, 500 * MPA, "carbon", "intermediate") == 500 * MPA
    tau = R.continuous_limit(KR, np.array([0.5, 0.95]), 800 * MPA, 1.0, 0.300)
    assert tau[0] / MPA == pytest.approx(68.3163, rel=REL)
    assert tau[1] / MPA == pytest.approx(37.7106, rel=REL)
    assert np.isnan(R.continuous_limit(KR, 1.06, 800 * MPA, 1.0, 0.300))  # only to 1.05


def test_kr_202_tau_1_alloy_intermediate_800_propeller_600():
    """KR 2025 Pt 5 Ch 4 202.1(1): low alloy 800 N/mm^2 in intermediate and thrust shafts, 600
    in propeller and stern tube shafts."""
    tau = R.continuous_limit(KR, 0.95, 900 * MPA, 1.0, 0.300, "alloy", "intermediate")
    assert tau / MPA == pytest.approx(47.6344, rel=REL)
    assert R.capped_strength(KR, 900 * MPA, "alloy", "thrust") == 800 * MPA
    assert R.capped_strength(KR, 900 * MPA, "alloy", "propeller") == 600 * MPA
    tau_p = R.continuous_limit(KR, 0.5, 900 * MPA, 0.55, 0.500, "alloy", "propeller")
    assert tau_p / MPA == pytest.approx(35.8982, rel=REL)


def test_kr_202_tau_2_transient_below_0_8():
    """KR 2025 Pt 5 Ch 4 202.1(2): tau_2 = 1.7 tau_1 / sqrt(C_k) below 80 % of the rated
    speed."""
    tau_t = R.transient_limit(
        KR, np.array([0.5, 0.85]), 900 * MPA, 0.55, 0.500, "alloy", "propeller"
    )
    assert tau_t[0] / MPA == pytest.approx(82.2887, rel=REL)
    assert np.isnan(tau_t[1])
    assert KR.barred_upper.value == 0.8


def test_kr_table_5_4_1_design_factors():
    """KR 2025 Pt 5 Ch 4 Table 5.4.1 (C_k)."""
    expected = {
        "integral flange": 1.0,
        "shrink fit": 1.0,
        "keyway tapered": 0.6,
        "keyway cylindrical": 0.45,
        "radial hole": 0.50,
        "longitudinal slot": 0.30,
        "thrust collar": 0.85,
        "roller thrust bearing": 0.85,
        "propeller key": 0.55,
        "stern tube": 0.8,
    }
    for feature, ck in expected.items():
        assert R.design_factor(KR, feature) == ck
    assert "barred speed range" in (KR.keyways.value or "")  # note (2)


def test_kr_201_crankshaft_limits_by_hand():
    """KR 2025 Pt 5 Ch 4 201.1-201.3: tau_1 = 45 - 24 (29) lambda^2, tau_2 = 2 tau_1 to 0.8,
    tau_3 = 21 (16) + 237 (lambda - 0.8) sqrt(lambda - 1) to 1.15."""
    lam = np.array([0.5, 0.9, 1.0, 1.1, 1.2])
    a1, a2, a3 = R.crankshaft_limits(KR, lam, "A")
    b1, b2, b3 = R.crankshaft_limits(KR, lam, "B")
    assert a1[0] / MPA == pytest.approx(39.0, rel=REL)
    assert a1[1] / MPA == pytest.approx(25.56, rel=REL)
    assert b1[1] / MPA == pytest.approx(21.51, rel=REL)
    assert a2[0] / MPA == pytest.approx(78.0, rel=REL)
    assert b2[0] / MPA == pytest.approx(75.5, rel=REL)  # 2 x (45 - 29 x 0.25)
    assert np.isnan(a2[1])  # no barred range above 0.8
    assert a1[2] / MPA == pytest.approx(21.0, rel=REL) and b1[2] / MPA == pytest.approx(16.0)
    assert a3[2] == pytest.approx(a1[2]) and b3[2] == pytest.approx(b1[2])  # continuous at 1
    assert a3[3] / MPA == pytest.approx(43.48379, rel=REL)
    assert b3[3] / MPA == pytest.approx(38.48379, rel=REL)
    assert np.isnan(a1[3]) and np.isnan(a3[4])  # tau_1 to 1.0, tau_3 to 1.15
    assert R.engine_group(4) == "A" and R.engine_group(2) == "B"
    assert R.engine_group(4, vee=True, firing_interval=45.0) == "A"
    assert R.engine_group(4, vee=True, firing_interval=90.0) == "B"


def test_kr_201_4_material_factor_by_hand():
    """KR 2025 Pt 5 Ch 4 201.4: f_m = 1 + 2/3 (T_s/440 - 1) on tau_1, tau_3 (T_s > 440);
    f_m = Y/225 on tau_2 (Y > 225); T_s above 590 (carbon) / 835 (low alloy): the Society."""
    fc, ft = R.material_factors(KR, np.array([550e6, 400e6, 600e6]), 300e6)
    assert fc[0] == pytest.approx(1.166667, rel=REL)
    assert fc[1] == 1.0
    assert np.isnan(fc[2])  # carbon steel above 590 N/mm^2
    assert ft[0] == pytest.approx(1.333333, rel=REL)
    fa, _ = R.material_factors(KR, 800e6, 200e6, "alloy")
    assert float(fa) == pytest.approx(1.545455, rel=REL)
    t1, t2, _ = R.crankshaft_limits(KR, 0.5, "A", 550e6, 300e6)
    assert float(t1) / MPA == pytest.approx(39.0 * 1.166667, rel=REL)
    assert float(t2) / MPA == pytest.approx(78.0 * 1.333333, rel=REL)


def test_kr_203_generating_sets_by_hand():
    """KR 2025 Pt 5 Ch 4 203.1-203.3: crankshaft 21/16 N/mm^2 and generator shaft 31 N/mm^2
    from 0.9 to 1.1 n_0; 90 and 118 N/mm^2 at and below 0.9 n_0; times f_m."""
    lam = np.array([0.5, 0.9, 1.0, 1.1, 1.15])
    ca, ta = R.genset_limits(KR, lam, "crankshaft", "A")
    cb, _ = R.genset_limits(KR, lam, "crankshaft", "B")
    cg, tg = R.genset_limits(KR, lam, "generator")
    assert np.isnan(ca[0]) and ca[1] / MPA == 21.0 and ca[3] / MPA == 21.0 and np.isnan(ca[4])
    assert cb[2] / MPA == 16.0
    assert ta[0] / MPA == 90.0 and ta[1] / MPA == 90.0 and np.isnan(ta[2])
    assert cg[2] / MPA == 31.0 and tg[0] / MPA == 118.0
    cm, _ = R.genset_limits(KR, 1.0, "crankshaft", "A", tensile_strength=550e6)
    assert float(cm) / MPA == pytest.approx(24.5, rel=REL)
    # a barred range of a generating set may reach 0.9 n_0 (203.1(2)), of propulsion 0.8
    assert bool(R.barred_range_permitted(KR, 60.0, 90.0, 100.0, "generator"))
    assert not bool(R.barred_range_permitted(KR, 60.0, 90.0, 100.0, "propulsion"))


def test_kr_204_major_criticals():
    """KR 2025 Pt 5 Ch 4 204: no major critical in 0.8 <= lambda <= 1.1 (propulsion) or
    0.9 <= lambda <= 1.1 (generators)."""
    speeds = np.array([79.0, 80.0, 85.0, 110.0, 111.0])
    assert R.major_critical_permitted(KR, speeds, 100.0).tolist() == [
        True,
        False,
        False,
        False,
        True,
    ]
    assert R.major_critical_permitted(KR, speeds, 100.0, "generator").tolist() == [
        True,
        True,
        True,
        False,
        True,
    ]


def test_kr_206_barred_range_by_hand():
    """KR 2025 Pt 5 Ch 4 206.1(1): 16 N_c/(18 - lambda) <= N <= (18 - lambda) N_c/16; 206.3
    the tachometer accuracy (no value stated: crankdyn's 2 %)."""
    s, e = R.declared_barred_range(KR, 400 / RPM, 500 / RPM, tolerance=0.0)
    assert float(s) * RPM == pytest.approx(372.093, rel=REL)
    assert float(e) * RPM == pytest.approx(430.0, rel=REL)
    assert KR.tachometer.value is None and R.tachometer_tolerance(KR) == 0.02
    s, e = R.declared_barred_range(KR, 400 / RPM, 500 / RPM)
    assert float(s) * RPM == pytest.approx(364.651, rel=REL)
    assert float(e) * RPM == pytest.approx(438.6, rel=REL)
    # a wider exceedance than the least range is kept
    s, e = R.declared_barred_range(KR, 400 / RPM, 500 / RPM, 360 / RPM, 440 / RPM, 0.0)
    assert (float(s) * RPM, float(e) * RPM) == pytest.approx((360.0, 440.0), rel=1e-12)


def test_kr_206_cpp_and_misfire():
    """KR 2025 Pt 5 Ch 4 206.1(2): both full and zero pitch; 102.1(4), 206.1(3): one cylinder
    misfiring; 102.1(2): calculations to 120 % of the rated speed."""
    assert R.cpp_conditions(KR) == ("full pitch", "zero pitch")
    assert KR.misfire.value is True
    assert KR.calculation_upper.value == 1.2
    assert KR.overspeed.value == 1.05
    assert math.isfinite(R.continuous_limit(KR, KR.overspeed.value, 600e6, 1.0, 0.3))


def test_kr_every_clause_read():
    """Every value of the KR rule set cites a clause of Pt 5 Ch 4 that was read."""
    assert R.unverified(KR) == ()
    assert all("Pt 5 Ch 4" in c.clause for _, c in KR.clauses())
    with pytest.raises(InputError, match="group"):
        R.crankshaft_limits(KR, 0.5, "C")


# ---- the same clauses in the TVC's checks (crankdyn.tvc.checks, crankdyn.tvc.installation) ----
def _spans_model(load_kw: dict | None = None):
    """Two crank masses on a 200 mm crank span and an alternator on a 120 mm shaft."""
    from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel

    return TorsionModel(
        (
            Mass("throw 1", 10.0, cylinders=(1,)),
            Mass("throw 2", 10.0, cylinders=(2,)),
            Mass("alternator", 40.0, role="alternator"),
        ),
        (
            Shaft(("throw 1", "throw 2"), 50e6, geometry=ShaftGeometry(0.2), role="crankshaft"),
            Shaft(("throw 2", "alternator"), 3e6, geometry=ShaftGeometry(0.12)),
        ),
        **(load_kw or {}),
    )


def test_kr_201_in_the_tvc_crank_span_check():
    """KR 2025 Pt 5 Ch 4 201 as the TVC's crank-span check (no engine builder's limit, no engine:
    group B): tau_1 = 45 - 29 lambda^2 (lambda = 0.5: 37.75 MPa), tau_3 = 16 + 237 (lambda -
    0.8) sqrt(lambda - 1) (lambda = 1.1: 38.48379 MPa), tau_2 = 2 tau_1 (75.5 MPa) up to 0.8,
    where a barred range may reach; the nominal stress T / W_p, W_p = pi 0.2^3/16; each row
    cites 201.1-201.4. IACS UR M68 states none (M68.1: UR M53's): a note, no row."""
    from crankdyn.tvc.checks import model_checks
    from crankdyn.tvc.spec import TvcSpec

    model, n0 = _spans_model(), 100.0
    checks, notes = model_checks(model, TvcSpec(rules="kr"), n0, ())
    (span,) = [c for c in checks if c.component.startswith("crank span")]
    lam = np.array([0.5, 1.1, 1.2])
    limit = span.limit(lam * n0)
    assert limit[0] / MPA == pytest.approx(37.75, rel=REL)
    assert limit[1] / MPA == pytest.approx(38.48379, rel=REL) and np.isnan(limit[2])
    assert span.transient_limit(np.array([0.5 * n0]))[0] / MPA == pytest.approx(75.5, rel=REL)
    assert span.barred_upper == 0.8
    assert span.clause == "τ_1: Pt 5 Ch 4 201.1; τ_3: Pt 5 Ch 4 201.3; f_m: Pt 5 Ch 4 201.4"
    assert "group B" in span.source and any("group B" in n for n in notes)

    class R1:
        synthesized_shaft_torque = np.array([[1000.0, 0.0]])

    w_p = math.pi * 0.2**3 / 16.0
    assert span.curve(R1())[0] == pytest.approx(1000.0 / w_p, rel=1e-12)
    checks, notes = model_checks(model, TvcSpec(rules="iacs-m68"), n0, ())
    assert not [c for c in checks if c.component.startswith("crank span")]
    assert any("crankshafts are IACS UR M53's" in n for n in notes)


def test_kr_203_in_the_tvc_generating_set():
    """KR 2025 Pt 5 Ch 4 203 for a generating set (constant-speed load): the crank span at 16
    MPa (group B) to 1.1 n_0, 90 MPa while passing at and below 0.9 n_0 (203.1); the alternator
    shaft at 31 MPa and 118 MPa (203.2); a barred range may reach 0.9 n_0."""
    from crankdyn.tvc.checks import model_checks
    from crankdyn.tvc.spec import TvcSpec

    model, n0 = _spans_model(), 100.0
    checks, _ = model_checks(model, TvcSpec(rules="kr"), n0, (), load="constant-speed")
    span = next(c for c in checks if c.component.startswith("crank span"))
    shaft = next(c for c in checks if c.component.startswith("alternator shaft"))
    lam = np.array([0.5, 1.0, 1.1, 1.15])
    assert (span.limit(lam * n0)[:3] / MPA).tolist() == [16.0, 16.0, 16.0]
    assert np.isnan(span.limit(lam * n0)[3])
    assert span.transient_limit(np.array([0.9, 0.95]) * n0)[0] / MPA == 90.0
    assert np.isnan(span.transient_limit(np.array([0.95 * n0]))[0])
    assert (shaft.limit(lam * n0)[:3] / MPA).tolist() == [31.0, 31.0, 31.0]
    assert shaft.transient_limit(np.array([0.5 * n0]))[0] / MPA == 118.0
    assert span.barred_upper == shaft.barred_upper == 0.9
    assert "Pt 5 Ch 4 203.2" in shaft.clause and "Pt 5 Ch 4 203.1" in span.clause


def test_kr_204_in_the_tvc_major_critical_rows():
    """KR 2025 Pt 5 Ch 4 204 as rows of the normal-firing condition: two masses, J = 1 and 3
    kg m^2 on k = 1e5 N m/rad, omega_1 = sqrt(k (1 + 1/3)) = 365.148 rad/s; one four-stroke
    cylinder (majors 0.5 and 1); n_0 = 400 rad/s: order 1 at lambda = 0.912871 lies within
    0.8-1.1 (failed), order 0.5 at 1.825742 outside; a generating set's window 0.9-1.1."""
    from crankdyn.torsion import Mass, Shaft, TorsionModel
    from crankdyn.tvc.installation import installation_verdicts
    from crankdyn.tvc.spec import TvcSpec

    model = TorsionModel(
        (Mass("a", 1.0, cylinders=(1,)), Mass("b", 3.0)), (Shaft(("a", "b"), stiffness=1e5),)
    )
    omega = math.sqrt(1e5 * (1.0 + 1.0 / 3.0))
    assert omega == pytest.approx(365.148, rel=REL)
    half, one = installation_verdicts(model, TvcSpec(rules="kr"), 400.0)
    assert half.worst == pytest.approx(1.825742, rel=REL) and half.passed
    assert one.worst == pytest.approx(0.912871, rel=REL) and not one.passed
    assert one.clause == "major criticals: Pt 5 Ch 4 204" and one.speed == pytest.approx(omega)
    gen = installation_verdicts(model, TvcSpec(rules="kr"), 400.0, load="constant-speed")
    assert gen[1].limit == 0.9 and "0.9" in gen[1].quantity
