"""Lloyd's Register against KR: the cap on sigma_B of a carbon-steel intermediate shaft, read from
each text, turns a pass into a fail.

LR Rules for Ships Pt 5 Ch 6 2.1.1 and 2.1.4 (imorules copy): carbon and carbon-manganese steel
400-760 N/mm^2; higher strengths give no higher permissible vibration stress from the formulae
of Pt 5 Ch 8 2.5 (used as 760). KR Rules for Classification of Steel Ships 2025 Pt 5 Ch 4
202.1(1): T_s not above 600 N/mm^2 for carbon steel forgings. LR's Naval Ships rules (January
2023) Vol 2 Pt 5 Ch 1 3.1.1 define C_d = 0.35 + 0.93 d^-0.2 as KR does.

Hand arithmetic, sigma_B = 800 N/mm^2, plain (C_K = 1) 300 mm shaft, C_d = 0.6472068:
  LR: (760 + 160)/18 = 51.11111; lambda = 0.5: 51.11111 x 0.6472068 x 2.5 = 82.6986;
      lambda = 0.95: 51.11111 x 0.6472068 x 1.38 = 45.6497 N/mm^2;
  KR: (600 + 160)/18 = 42.22222; lambda = 0.95: 37.7106 N/mm^2; LR/KR = 920/760 = 1.210526.
  A synthesised stress of 40 N/mm^2 at lambda = 0.95 passes LR (40 < 45.6497) and fails KR
  (40 > 37.7106, and above 0.8 n_0 no barred range is permitted).
The line (a 60 mm shaft, 60^-0.2 = 0.4409301, C_d = 0.35 + 0.93 x 0.4409301 = 0.7600650), for
0.9 <= lambda <= 1.05: LR 51.11111 x 0.7600650 x 1.38 = 53.6099, KR 42.22222 x 0.7600650 x
1.38 = 44.2865 N/mm^2; its order-3 resonance at sqrt(k (1/J_e + 1/J_p))/3 = 598.3 rpm, n_0 =
630 rpm, lambda = 0.950.
Tolerances: the hand values carry 6 significant digits (relative 1e-5).

The same flip on a marine line of engine, elastic coupling, gearbox and propeller
(tests/tvc/data/class-flip-line.toml) through the whole TVC, and the rows LR Pt 5 Ch 6 2.1.3 and
KR Table 5.4.1 note (2) attach to a barred range.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest

from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
from crankdyn.torsion.excitation import UniformExcitation
from crankdyn.torsion.rules import RuleSet as ShaftRules
from crankdyn.torsion.sweep import forced_response
from crankdyn.tvc import rulesets as R
from crankdyn.tvc.analysis import judge
from crankdyn.tvc.checks import model_checks
from crankdyn.tvc.spec import TvcSpec

MPA = 1e6
REL = 1e-5
RPM_ = math.pi / 30


def test_lr_caps_from_pt5_ch6_2_1():
    """LR Rules for Ships Pt 5 Ch 6 2.1.1/2.1.4: 760 N/mm^2 carbon, 800 N/mm^2 alloy; 2.1.3:
    500 N/mm^2 where stresses come close to the transient limit."""
    lr = R.get("lr")
    assert R.capped_strength(lr, 800 * MPA, "carbon", "intermediate") == 760 * MPA
    assert R.capped_strength(lr, 900 * MPA, "alloy", "intermediate") == 800 * MPA
    assert lr.strength_caps[("carbon", "intermediate")].clause.verified
    assert not lr.strength_caps[("carbon", "propeller")].clause.verified  # 3.5.1 not read
    assert lr.min_strength_transient.value == 500 * MPA


def test_tau_c_lr_against_kr_by_hand():
    """LR (760) and KR (600) tau_C of an 800 N/mm^2 carbon-steel intermediate shaft."""
    lam = np.array([0.5, 0.95])
    lr = R.continuous_limit(R.get("lr"), lam, 800 * MPA, 1.0, 0.300)
    kr = R.continuous_limit(R.get("kr"), lam, 800 * MPA, 1.0, 0.300)
    assert lr / MPA == pytest.approx([82.6986, 45.6497], rel=REL)
    assert kr[1] / MPA == pytest.approx(37.7106, rel=REL)
    assert lr[1] / kr[1] == pytest.approx(1.210526, rel=REL)
    stress = 40 * MPA  # at lambda = 0.95
    assert stress < lr[1] and stress > kr[1]


def test_verdict_flips_between_lr_and_kr_on_a_line():
    """The rule check of a two-mass line whose resonance at 0.95 n_0 lies between KR's and LR's
    tau_C: passed under LR, failed under KR (no barred range above 0.8 n_0)."""
    model = TorsionModel(
        masses=(Mass("engine", 2.0, damping=10.9, cylinders=(1,)), Mass("propeller", 6.0)),
        shafts=(Shaft(("engine", "propeller"), 5.3e4, geometry=ShaftGeometry(0.06)),),
    )
    resonance = math.sqrt(5.3e4 * (1 / 2.0 + 1 / 6.0)) / 3.0
    assert resonance / RPM_ == pytest.approx(598.3, abs=0.05)
    n0 = 630 * RPM_
    response = forced_response(
        model,
        UniformExcitation(60.0, [0.0], "two-stroke"),
        np.linspace(400, 660, 27) * RPM_,
        [3.0],
    )
    peak = float(np.max(response.synthesized_shaft_stress))
    assert 44.2865 * MPA < peak < 53.6099 * MPA  # between KR's and LR's tau_C by hand
    spec = TvcSpec(tachometer_tolerance=0.0)
    judged = {}
    for key in ("lr", "kr"):
        limit = R.shaft_limit(R.get(key), ("engine", "propeller"), 800 * MPA)
        ruled = dataclasses.replace(model, rules=ShaftRules(n0, [limit]))
        (check,), _ = model_checks(ruled, spec, n0, [])
        top = float(np.nanmax(check.limit(response.speed[response.speed >= 0.9 * n0])))
        assert top / MPA == pytest.approx(53.6099 if key == "lr" else 44.2865, rel=REL)
        judged[key] = judge(ruled, response, spec)
    lr_rows, lr_barred = judged["lr"]
    assert all(row.passed for row in lr_rows) and not lr_barred
    kr_rows, kr_barred = judged["kr"]
    assert not all(row.passed for row in kr_rows)
    (barred,) = kr_barred
    assert not barred.permitted
    assert barred.start < resonance < barred.end and barred.end > 0.8 * n0


# ---- a marine line of engine, elastic coupling, gearbox and propeller (tests/tvc/data) ----------
FLIP_LINE = Path(__file__).parents[1] / "tvc" / "data" / "class-flip-line.toml"


def test_class_flip_marine_line_passes_lr_and_fails_kr():
    """The class-flip line (a six-cylinder engine, highly elastic coupling, 3:1 gearbox and
    propeller, lightly damped): its carbon-steel intermediate shaft (sigma_B = 800 N/mm^2,
    d = 200 mm, C_K = 1 for integral flanges) for 0.9 <= lambda <= 1.05, by hand:
      200^-0.2 = 0.3465724, C_d = 0.35 + 0.93 x 0.3465724 = 0.6723124;
      LR (760):  51.11111 x 0.6723124 x 1.38 = 47.4204 N/mm^2;
      KR (600):  42.22222 x 0.6723124 x 1.38 = 39.1734 N/mm^2.
    The order-3 resonance of the gearbox mode lies at 0.936 n_0 with about 43 MPa between the
    two: the TVC passes under LR (and IACS M68 as crankdyn reads it, 760 too), fails under KR
    (the stress exceeds tau_C above 0.8 n_0: the declared range, KR's least range 206.1(1) and
    the 2 % tachometer tolerance, holds the rated speed). Tolerances: 6 printed digits (1e-5)."""
    from crankdyn.tvc import tvc

    model = TorsionModel.from_file(FLIP_LINE)
    results = {
        key: tvc(model, spec=dataclasses.replace(model.tvc, rules=key), passage=False)
        for key in ("iacs-m68", "lr", "kr")
    }
    shaft = "intermediate shaft (thrust collar - propeller)"
    lr_row = next(v for v in results["lr"].verdicts if v.component == shaft)
    assert 0.9 * 750 * RPM_ < lr_row.speed < 1.05 * 750 * RPM_  # the worst in 0.9-1.05 n_0
    assert lr_row.limit / MPA == pytest.approx(47.4204, rel=REL)
    assert 39.1734 * MPA < lr_row.worst < 47.4204 * MPA
    assert results["lr"].passed and results["iacs-m68"].passed
    kr = results["kr"]
    assert not kr.passed
    (barred,) = [b for b in kr.barred_ranges if b.component == shaft]
    assert not barred.permitted and barred.start < 750 * RPM_ < barred.end
    assert barred.clause == "barred ranges: Pt 5 Ch 4 202.1(2); least range: Pt 5 Ch 4 206.1(1)"
    spec = dataclasses.replace(model.tvc, rules="kr")
    (check, *_), _ = model_checks(model, spec, 750 * RPM_, [])
    at = np.array([lr_row.speed])
    assert float(check.limit(at)[0]) / MPA == pytest.approx(39.1734, rel=REL)


def test_lr_2_1_3_least_strength_and_kr_keyway_rows():
    """LR Rules for Ships Pt 5 Ch 6 2.1.3: a shaft whose stresses come close to tau_T (crankdyn:
    a declared barred range) needs sigma_B >= 500 N/mm^2 (a 450 N/mm^2 shaft fails, 600
    passes); KR 2025 Pt 5 Ch 4 Table 5.4.1 note (2): a keyway with a barred range fails. The
    built-in verdict-geared-line has barred ranges of both its shafts near 0.79 n_0."""
    from crankdyn.io.catalogue import resolve_model_and_engine
    from crankdyn.session import Analysis
    from crankdyn.torsion.rules import ShaftLimit

    geared, _ = resolve_model_and_engine("verdict-geared-line")
    response = Analysis(geared).response()

    def rows(model, key, kind):
        verdicts, barred = judge(model, response, TvcSpec(rules=key))
        assert barred
        return [v for v in verdicts if v.kind == kind]

    least = rows(geared, "lr", "least tensile strength")
    assert least and all(v.passed and v.worst == 500 * MPA for v in least)
    assert all(v.clause == "least σ_B: Pt 5 Ch 6 2.1.3" for v in least)
    assert not rows(geared, "kr", "least tensile strength")  # KR Ch 4 states none
    weak = dataclasses.replace(
        geared.rules,
        shafts=tuple(
            dataclasses.replace(s, tensile_strength=450 * MPA) for s in geared.rules.shafts
        ),
    )
    assert not any(
        v.passed for v in rows(dataclasses.replace(geared, rules=weak), "lr", least[0].kind)
    )
    keyed = dataclasses.replace(
        geared.rules,
        shafts=tuple(
            ShaftLimit(s.between, s.tensile_strength, feature="keyway tapered", design_factor=0.6)
            for s in geared.rules.shafts
        ),
    )
    keys = rows(dataclasses.replace(geared, rules=keyed), "kr", "keyway with a barred range")
    assert keys and not any(v.passed for v in keys)
    assert all(v.clause == "keyways: Pt 5 Ch 4 Table 5.4.1 note (2)" for v in keys)
    assert not rows(
        dataclasses.replace(geared, rules=keyed), "iacs-m68", "keyway with a barred range"
    )
