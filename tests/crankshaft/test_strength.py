"""The UR M53 check of an engine: limiting cases, the formulas' ranges, semi-built crankshafts,
user factors, inputs and the summary."""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest

import crankdyn
from crankdyn.crankshaft import m53
from crankdyn.crankshaft.geometry import ShrinkFit, StressFactors
from crankdyn.crankshaft.strength import crankshaft_strength
from crankdyn.errors import InputError

MPA = 1e6


@pytest.fixture(scope="module")
def engine():
    return crankdyn.Engine.example("marine-propulsion")


def with_shaft(engine, **changes):
    """The engine with its crankshaft's geometry, material or top-level fields changed."""
    shaft = engine.crankshaft
    g = {k: v for k, v in changes.items() if k in shaft.geometry.__dataclass_fields__}
    m = {k: v for k, v in changes.items() if k in shaft.material.__dataclass_fields__}
    top = {k: v for k, v in changes.items() if k not in g and k not in m}
    shaft = dataclasses.replace(
        shaft,
        geometry=dataclasses.replace(shaft.geometry, **g),
        material=dataclasses.replace(shaft.material, **m),
        **top,
    )
    return dataclasses.replace(engine, crankshaft=shaft)


@pytest.fixture(scope="module")
def bending_only(engine):
    return crankshaft_strength(engine)


def test_zero_torsion_gives_q_of_bending_alone(bending_only):
    """UR M53.5 with tau = 0: sigma_V = sigma_B + sigma_add in the fillets and sigma_BO at the
    oil bore, so Q = sigma_DW / (alpha_B sigma_BFN + sigma_add) etc."""
    r = bending_only
    add = 10 * MPA
    assert r.q_pin == pytest.approx(r.strength_pin / (r.alpha_b * r.sigma_bfn + add), rel=1e-12)
    journal = r.beta_b * r.sigma_bfn + r.beta_q * r.sigma_qfn + add
    assert r.q_journal == pytest.approx(r.strength_journal / journal, rel=1e-12)
    assert r.q_oil == pytest.approx(r.strength_oil / (r.gamma_b * r.sigma_bon), rel=1e-12)
    assert not r.torsion_given
    assert any("no torsional stress" in n for n in r.notes)
    assert all("bending only" in v.condition for v in r.summary_verdicts())


def test_torsion_lowers_q_and_stress_input_is_the_torque_over_w_p(engine, bending_only):
    """UR M53.2.2.2: tau_N = M_TN / W_P; a stress given for the crankpin is the torque times
    the crankpin's W_P, and any torsion lowers every Q."""
    torque = np.linspace(20e3, 45e3, 6)
    by_torque = crankshaft_strength(engine, torsion_torque=torque)
    g = engine.crankshaft.geometry
    stress = torque / m53.polar_section_modulus(g.pin_diameter)
    by_stress = crankshaft_strength(engine, torsion_stress=stress)
    np.testing.assert_allclose(by_stress.q_table(), by_torque.q_table(), rtol=1e-12)
    assert np.all(by_torque.q_table() < bending_only.q_table())
    # the throw with the largest torque has the smallest Q (same bending on every throw)
    q, where = by_torque.smallest_q()
    assert where.startswith("throw 6")
    assert q == pytest.approx(np.nanmin(by_torque.q_table()))


def test_size_term_at_the_reference_diameter():
    """UR M53.6 [Annex 5-3 6(1)]: the size term 0.264 + 1.073 D^-0.2 is 1 at
    D = (0.736/1.073)^-5 mm (algebra), so with sigma_B = 785 N/mm^2 and a vanishing notch term
    sigma_DW = K (0.42 sigma_B + 39.3)."""
    assert pytest.approx(6.585815, abs=5e-7) == m53.REFERENCE_DIAMETER * 1e3
    assert m53.size_term(m53.REFERENCE_DIAMETER) == pytest.approx(1.0, abs=1e-14)
    radius = 1e3  # m: the notch term 196/sigma_B sqrt(1/R_X) is 196/785 * 1e-3 (R_X in mm)
    smooth = m53.fatigue_strength(785e6, m53.REFERENCE_DIAMETER, radius, 1.05)
    notch = 196 / 785 * math.sqrt(1 / (radius * 1e3))
    assert smooth == pytest.approx(1.05 * (0.42 * 785 + 39.3) * (1 + notch) * MPA, rel=1e-14)
    # larger diameters are weaker
    assert m53.size_term(0.3) < m53.size_term(0.1) < 1.0


def test_fillet_radius_taken_as_at_least_2_mm():
    """UR M53.6 [Annex 5-3 6(2)(A)]: R_H, R_G and R_X are taken as not less than 2 mm."""
    assert m53.fatigue_strength(800e6, 0.2, 0.001, 1.0) == m53.fatigue_strength(
        800e6, 0.2, 0.002, 1.0
    )
    assert m53.fatigue_strength(800e6, 0.2, 0.003, 1.0) < m53.fatigue_strength(
        800e6, 0.2, 0.002, 1.0
    )


def test_overlap_below_minus_half_and_recess_floor():
    """UR M53.3.1 [Annex 5-3 3(1)(H)]: s below -0.5 is taken as -0.5 in f(s,w) and f(r,s)
    (and, crankdyn's reading, not the text's, in the journal's f_B(s,w) and f_Q(s)); f(recess)
    below 1 is taken as 1."""
    base = dict(
        r_pin=0.05,
        r_journal=0.05,
        w=0.4,
        b=1.5,
        d_g=0.0,
        d_h=0.0,
        t_h=0.0,
        t_g=0.0,
        d_o=None,
        r_journal_own=0.05,
        same_pin_and_journal=True,
    )
    deep = m53.Ratios(s=-0.8, **base)
    half = m53.Ratios(s=-0.5, **base)
    assert m53.crankpin_bending_scf(deep) == m53.crankpin_bending_scf(half)
    assert m53.crankpin_torsion_scf(deep) == m53.crankpin_torsion_scf(half)
    assert m53.journal_bending_scf(deep) == m53.journal_bending_scf(half)
    assert m53.journal_shear_scf(deep) == m53.journal_shear_scf(half)
    recessed = m53.Ratios(s=-0.8, **{**base, "t_h": 0.02, "t_g": 0.02})
    assert 1.0 + 0.04 * (1.8 + 3.2 * -0.8) < 1.0
    assert m53.recess_factor(recessed) == 1.0
    # s below -0.5 lies within the range (its low end is open)
    assert all(v.valid for v in m53.validity(deep) if v.name == "s")


def test_geometry_outside_the_ranges_is_named_and_fails(engine):
    """UR M53.3.1 [Annex 5-3 3(1)(G)]: w = W/D above 0.8 leaves the fillets' empirical
    factors; the result names the ratio, and the fillets' verdicts fail (the oil bore's stays
    the rule's)."""
    thick = with_shaft(engine, web_thickness=0.23)  # w = 0.885
    r = crankshaft_strength(thick, torsion_torque=30e3)
    assert [loc for loc, _ in r.extrapolated] == ["crankpin fillet", "journal fillet"]
    assert any("w = 0.8846 outside 0.2 <= w <= 0.8" in n for n in r.notes)
    verdicts = r.summary_verdicts()
    fillets = [v for v in verdicts if "fillet" in v.component]
    assert fillets and not any(v.passed for v in fillets)
    assert all("Appendix III" in v.note and "w = 0.8846" in v.note for v in fillets)
    assert all(v.passed for v in verdicts if "oil bore" in v.component)
    assert np.all(r.q_pin > m53.Q_MIN)  # the failure is the formula's range, not Q
    table = {t.key: t for t in r.summary().tables}["m53_validity"]
    assert table.rows[1][:5] == ("w", 0.23 / 0.26, 0.2, 0.8, False)


def test_user_factors_replace_the_empirical_ones(engine):
    """M53 Appendix III: factors found by FE replace the formulas and their ranges."""
    factors = StressFactors(alpha_b=2.5, alpha_t=1.6, source="FE report 17")
    thick = with_shaft(engine, web_thickness=0.23, factors=factors)
    r = crankshaft_strength(thick, torsion_torque=30e3)
    assert r.alpha_b == 2.5 and r.alpha_t == 1.6
    assert [loc for loc, _ in r.extrapolated] == ["journal fillet"]
    assert r.bending[:, 0] == pytest.approx(2.5 * r.sigma_bfn)
    assert any("FE report 17" in n for n in r.notes)
    pin = [v for v in r.summary_verdicts() if v.component.endswith("crankpin fillet")]
    assert all(v.passed for v in pin)


def test_crosshead_additional_stress(engine):
    """UR M53.4: +-30 N/mm^2 for crosshead engines, of which the calculated axial vibration
    stress replaces the 20."""
    r = crankshaft_strength(with_shaft(engine, engine_type="crosshead"))
    assert r.additional == 30 * MPA
    r = crankshaft_strength(
        with_shaft(engine, engine_type="crosshead", axial_vibration_stress=12 * MPA)
    )
    assert r.additional == 22 * MPA


def test_manufacture_factor_and_surface_treatment(engine, bending_only):
    """UR M53.6: K = 1.05 applies to the fillets only; a surface treatment's documented factor
    raises the fillets' fatigue strength, not the oil bore's."""
    base = bending_only
    assert base.factor_k == 1.05
    g = engine.crankshaft.geometry
    assert base.strength_oil == pytest.approx(
        m53.fatigue_strength(850e6, g.pin_diameter, g.oil_bore_diameter / 2, 1.0)
    )
    treated = crankshaft_strength(
        with_shaft(engine, surface_treatment="induction-hardened", surface_factor=1.2)
    )
    assert treated.strength_pin == pytest.approx(1.2 * base.strength_pin)
    assert treated.strength_journal == pytest.approx(1.2 * base.strength_journal)
    assert treated.strength_oil == base.strength_oil


def test_two_stroke_web_factor():
    """UR M53.2.1.2.1: K_e = 0.8 for two-stroke engines lowers the web's nominal stresses."""
    assert m53.ke_factor("two-stroke") == 0.8
    s4 = m53.nominal_web_stresses(1e4, 1e5, 0.3, 0.1, m53.ke_factor("four-stroke"))
    s2 = m53.nominal_web_stresses(1e4, 1e5, 0.3, 0.1, m53.ke_factor("two-stroke"))
    assert s2[0] == pytest.approx(0.8 * s4[0]) and s2[1] == pytest.approx(0.8 * s4[1])


def test_semi_built_crankshaft(engine):
    """UR M53.3.3 and M53.8: no journal fillet check; the shrink fit's largest bore and
    oversize limits, with M_max the largest journal torque plus the largest alternating one."""
    fit = ShrinkFit(diameter=0.42, length=0.2, web_outer_diameter=0.7, oversize=0.55e-3)
    semi = with_shaft(engine, construction="semi-built", shrink_fit=fit, journal_bore=0.08)
    r = crankshaft_strength(semi, torsion_torque=30e3)
    assert np.all(np.isnan(r.q_journal)) and r.beta_b is None and r.strength_journal is None
    quasi_static = crankshaft_strength(semi).max_torque
    assert r.max_torque == pytest.approx(quasi_static + 30e3)
    assert r.max_journal_bore == pytest.approx(
        m53.maximum_journal_bore(0.42, 0.2, r.max_torque, 650e6)
    )
    assert r.min_oversize == pytest.approx(
        m53.minimum_oversize(0.42, 0.2, 0.7, 0.08, r.max_torque, 650e6, 2.05e11)
    )
    assert r.max_oversize == pytest.approx(m53.maximum_oversize(0.42, 650e6, 2.05e11))
    fits = [v for v in r.summary_verdicts() if v.component == "shrink fit"]
    assert [v.clause for v in fits] == ["M53.8.2", "M53.8.3", "M53.8.4"]
    assert [v.passed for v in fits] == [
        r.max_journal_bore >= 0.08,
        r.min_oversize <= 0.55e-3,
        r.max_oversize >= 0.55e-3,
    ]
    assert not [v for v in r.summary_verdicts() if "journal fillet" in v.component]


def test_summary_and_exports(engine):
    """One verdict per throw and location (M53.7), the figures with where, JSON and CSV."""
    r = crankshaft_strength(engine, torsion_torque=30e3)
    s = r.summary()
    assert len(s.verdicts) == 6 * 3
    assert {v.source for v in s.verdicts} == {m53.RULE}
    v = s.verdicts[0]
    assert v.limit == pytest.approx(r.strength_pin / 1.15)
    assert v.margin == pytest.approx(1 - 1.15 / r.q_pin[0])
    q, where = r.smallest_q()
    figure = s.figure("min_acceptability_factor")
    assert figure.value == q and figure.where == where
    assert {t.key for t in s.tables} == {"m53_nominal", "m53_locations", "m53_validity"}
    locations = {t.key: t for t in s.tables}["m53_locations"]
    assert len(locations.rows) == 18
    text = json.dumps(r.to_dict(), allow_nan=False)
    assert '"validity"' in text
    assert json.loads(json.dumps(s.to_dict(), allow_nan=False))["passed"] is True
    assert r.to_csv().splitlines()[0].startswith("crank_angle_deg")


def test_plausibility_warnings(engine):
    """A tensile strength outside the crankshaft steels' 400-1000 MPa and an overlap given that
    differs from (D + D_G)/2 - R are named."""
    r = crankshaft_strength(
        with_shaft(engine, tensile_strength=85e6, yield_strength=None, overlap=0.06)
    )
    keys = {w.key for w in r.warnings}
    assert keys == {"crankshaft_tensile_strength", "crankshaft_overlap"}
    assert not crankshaft_strength(engine).warnings


@pytest.mark.parametrize(
    ("kwargs", "key"),
    [
        ({"torsion_torque": [1.0, 2.0]}, "torsion_torque"),
        ({"torsion_torque": -5.0}, "torsion_torque"),
        ({"torsion_torque": float("nan")}, "torsion_torque"),
        ({"torsion_torque": 1.0, "torsion_stress": 1.0}, "torsion_stress"),
    ],
)
def test_bad_torsion_inputs(engine, kwargs, key):
    with pytest.raises(InputError) as info:
        crankshaft_strength(engine, **kwargs)
    assert info.value.key == key


def test_missing_inputs(engine):
    with pytest.raises(InputError, match=r"no \[crankshaft\]"):
        crankshaft_strength(dataclasses.replace(engine, crankshaft=None))
    no_pitch = dataclasses.replace(
        engine, cylinders=dataclasses.replace(engine.cylinders, pitch=None)
    )
    with pytest.raises(InputError, match="bearing span"):
        crankshaft_strength(no_pitch)
    with pytest.raises(InputError, match="maximum continuous rating"):
        crankshaft_strength(dataclasses.replace(engine, speed=None))
    with pytest.raises(InputError) as info:
        with_shaft(engine, web_centre_distance=0.3)  # beyond half the 530 mm pitch
    assert info.value.key == "web_centre_distance"
    assert math.isfinite(crankshaft_strength(engine, 700 * math.pi / 30).q_pin[0])
