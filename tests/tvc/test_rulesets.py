"""The rule sets of :mod:`crankdyn.tvc.rulesets`: the registry, the clauses, the
vectorisation, and that ``"iacs-m68"`` and ``"lr"`` reproduce crankdyn's IACS behaviour and LR
margin bit for bit (the hand-worked rule formulas are in tests/validation/test_kr_2025_*.py,
test_lr_kr_verdict_flip.py, test_iacs_m68_*.py)."""

from __future__ import annotations

import numpy as np
import pytest

from crankdyn.constants import RPM
from crankdyn.errors import InputError
from crankdyn.torsion.rules import STRENGTH_CAPS, ShaftLimit, capped_strength
from crankdyn.tvc import limits
from crankdyn.tvc import rulesets as R


def test_registry_keys_and_unknown_key():
    assert R.RULESET_KEYS == ("iacs-m68", "lr", "kr", "dnv", "abs", "bv")
    for key in R.RULESET_KEYS:
        assert R.get(key).key == key
    with pytest.raises(InputError, match='did you mean "kr"') as err:
        R.get("krr")
    assert err.value.key == "rules" and err.value.value == "krr"


def test_iacs_m68_reproduces_the_m68_limits_bit_for_bit():
    """tau_C and tau_T of "iacs-m68" are the M68 functions' values, with crankdyn's caps."""
    rng = np.random.default_rng(3)
    lam = rng.uniform(0.0, 1.1, 200)
    iacs = R.get("iacs-m68")
    for (material, kind), cap in STRENGTH_CAPS.items():
        assert iacs.strength_caps[(material, kind)].value == cap
        for sigma in (450e6, 700e6, 900e6):
            used = capped_strength(sigma, material, kind)
            for ck, d in ((1.0, 0.3), (0.55, 0.62)):
                a = R.continuous_limit(iacs, lam, sigma, ck, d, material, kind)
                b = limits.continuous_limit(lam, used, ck, d)
                np.testing.assert_array_equal(a, b)
                a = R.transient_limit(iacs, lam, sigma, ck, d, material, kind)
                b = limits.transient_limit(lam, used, ck, d)
                np.testing.assert_array_equal(a, b)
    assert R.design_factor(iacs, "keyway tapered") == limits.DESIGN_FACTORS["keyway tapered"]


def test_declared_range_reproduces_the_tvc_margins_bit_for_bit():
    """ "lr" and "iacs-m68" declare the range the TVC declares with widening "lr" / "none":
    min(exceeds start, low) (1 - tol), max(exceeds end, high) (1 + tol)."""
    n0 = 500 / RPM
    for key, widening in (("lr", "lr"), ("iacs-m68", "none")):
        for nc, a, b in ((300 / RPM, 290 / RPM, 305 / RPM), (420 / RPM, 380 / RPM, 460 / RPM)):
            lo, hi = limits.barred_limits(nc, n0, widening)
            expected = (min(a, lo) * (1.0 - 0.02), max(b, hi) * (1.0 + 0.02))
            s, e = R.declared_barred_range(R.get(key), nc, n0, a, b, 0.02)
            assert (float(s), float(e)) == expected


def test_vectorised_over_speed_ratio_and_diameter():
    lam = np.linspace(0.1, 1.0, 7)[:, None]
    d = np.array([0.2, 0.35, 0.5])
    tau = R.continuous_limit(R.get("kr"), lam, 700e6, 1.0, d)
    assert tau.shape == (7, 3)
    for j, dj in enumerate(d):
        np.testing.assert_array_equal(
            tau[:, j], R.continuous_limit(R.get("kr"), lam[:, 0], 700e6, 1.0, dj)
        )
    s, e = R.declared_barred_range(R.get("lr"), np.array([30.0, 40.0]), 52.0)
    assert s.shape == e.shape == (2,)
    lo, hi = limits.barred_limits(np.array([30.0, 40.0]), 52.0)
    assert (float(lo[1]), float(hi[1])) == limits.barred_limits(40.0, 52.0)


def test_unread_societies_hold_m68_values_and_say_so():
    iacs = R.get("iacs-m68")
    for key in ("dnv", "abs", "bv"):
        rules = R.get(key)
        assert rules.basis == "iacs-m68"
        assert len(R.unverified(rules)) == len(rules.clauses())
        assert all("not read" in c.note for _, c in rules.clauses())
        assert rules.strength_caps[("carbon", "intermediate")].value == 760e6
        np.testing.assert_array_equal(
            R.continuous_limit(rules, [0.5, 0.95], 800e6, 1.0, 0.3),
            R.continuous_limit(iacs, [0.5, 0.95], 800e6, 1.0, 0.3),
        )
        assert R.cpp_conditions(rules) == ()
        with pytest.raises(InputError, match="not read"):
            R.crankshaft_limits(rules, 0.5, "A")


def test_clauses_cover_every_value():
    kr = R.get("kr")
    names = [name for name, _ in kr.clauses()]
    assert "strength_caps carbon/intermediate" in names
    assert "design_factors stern tube" in names
    assert "crankshaft overspeed" in names and "genset generator" in names
    assert "major_criticals generator" in names
    cite = kr.shaft_formula.cite()
    assert cite.startswith("KR Rules for Classification of Steel Ships 2025 (RA-05-E), Pt 5 Ch 4")


def test_shaft_limit_carries_the_society_cap():
    limit = R.shaft_limit(R.get("kr"), ("a", "b"), 800e6, feature="keyway tapered")
    assert isinstance(limit, ShaftLimit)
    assert limit.strength_used == 600e6 and limit.design_factor == 0.6
    assert R.shaft_limit(R.get("lr"), ("a", "b"), 800e6).strength_used == 760e6
    with pytest.raises(InputError, match="kind"):
        R.shaft_limit(R.get("kr"), ("a", "b"), 800e6, kind="stern")
    with pytest.raises(InputError, match='did you mean "keyway tapered"'):
        R.design_factor(R.get("kr"), "keyway taperd")


def test_barred_range_permitted_and_tachometer():
    kr = R.get("kr")
    n0 = 100.0
    ok = R.barred_range_permitted(kr, [50.0, 50.0, 95.0], [80.0, 80.1, 105.0], n0)
    assert ok.tolist() == [True, False, False]
    assert R.tachometer_tolerance(kr, 0.0) == 0.0
    with pytest.raises(InputError, match="generating sets"):
        R.barred_range_permitted(R.get("lr"), 50.0, 80.0, n0, "generator")
    with pytest.raises(InputError, match="application"):
        R.barred_range_permitted(kr, 50.0, 80.0, n0, "auxiliary")
    with pytest.raises(InputError, match="window"):
        R.major_critical_permitted(R.get("lr"), 90.0, n0)


def test_citation_of_an_unread_society():
    cite = R.get("abs").shaft_formula.cite()
    assert cite.startswith("ABS Rules for Building and Classing Marine Vessels Pt 4 Ch 3 (4-3-2), ")
    assert "not verified: not read" in cite


def test_values_are_named_as_the_clauses():
    """Every value of :func:`values` names a clause of :meth:`RuleSet.clauses` (the formula
    citations carry no value of their own)."""
    for key in R.RULESET_KEYS:
        rules = R.get(key)
        clause_names = {name for name, _ in rules.clauses()}
        names = set(R.values(rules))
        assert names <= clause_names
        assert clause_names - names >= {"scope", "shaft_formula", "size_factor"}
    crank = R.values(R.get("kr"))["crankshaft"]
    assert crank.clauses == {} and crank.a == {"A": 45e6, "B": 45e6}


def test_differences_between_the_societies():
    """The values a switch of ``rules`` changes (docs/tvc.md, "Where the sets differ"): LR
    against IACS M68 the margin and LR 2.1.3's 500 N/mm^2; KR against both the carbon-steel cap
    (202.1(1)), CPP (206.1(2)), misfire (206.1(3)), keyways (Table 5.4.1 note (2)), 1.2 n_0
    (102.1(2)), crankshafts (201), gensets (203) and major criticals (204); DNV, ABS and BV none
    (IACS M68's values, unverified)."""
    get = R.get
    assert R.differences(get("iacs-m68"), get("lr")) == ("widening", "min_strength_transient")
    kr_only = {
        "strength_caps carbon/intermediate",
        "strength_caps carbon/thrust",
        "cpp",
        "misfire",
        "keyways",
        "calculation_upper",
        "crankshaft",
        "genset",
        "transient_upper_genset",
        "major_criticals propulsion",
        "major_criticals generator",
    }
    assert set(R.differences(get("iacs-m68"), get("kr"))) == kr_only | {"widening"}
    assert set(R.differences(get("lr"), get("kr"))) == kr_only | {"min_strength_transient"}
    for key in ("dnv", "abs", "bv"):
        assert R.differences(get("iacs-m68"), get(key)) == ()
    for a in R.RULESET_KEYS:
        assert R.differences(get(a), get(a)) == ()
        for b in R.RULESET_KEYS:
            assert set(R.differences(get(a), get(b))) == set(R.differences(get(b), get(a)))
    # the rows whose values differ are exactly the rows whose limits differ
    lr, kr = get("lr"), get("kr")
    assert R.capped_strength(lr, 800e6) != R.capped_strength(kr, 800e6)
    assert R.capped_strength(lr, 900e6, "alloy") == R.capped_strength(kr, 900e6, "alloy")
    assert R.capped_strength(lr, 800e6, kind="propeller") == R.capped_strength(
        kr, 800e6, kind="propeller"
    )
