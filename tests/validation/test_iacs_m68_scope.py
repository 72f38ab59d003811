"""IACS UR M68 (Corr.2 Nov 2012 / Aug 2014 text), M68.1 "Scope", read from a public copy: the UR
covers intermediate, thrust and propeller shafts of traditional straight forged design and
explicitly not diesel engine crankshafts (see M53) nor generator rotor shafts. The
``"iacs-m68"`` rule set therefore states no crankshaft or generating-set limit, and asking for
one names the clause (the TVC takes the engine builder's and the makers' limits instead).
M68.3/M68.4 could not be read: those clauses are marked unverified.
"""

from __future__ import annotations

import pytest

from crankdyn.errors import InputError
from crankdyn.tvc import rulesets as R


def test_m68_1_scope_excludes_crankshafts_and_generator_rotors():
    """IACS UR M68.1: crankshafts are M53's; generator rotor shafts are not covered."""
    iacs = R.get("iacs-m68")
    assert iacs.scope.verified and "M53" in iacs.scope.note
    assert iacs.crankshaft is not None and iacs.crankshaft.value is None
    assert iacs.crankshaft.clause.clause == "M68.1" and iacs.crankshaft.clause.verified
    with pytest.raises(InputError, match=r"M68\.1") as err:
        R.crankshaft_limits(iacs, 0.5, "A")
    assert err.value.key == "rules"
    with pytest.raises(InputError, match=r"M68\.1"):
        R.genset_limits(iacs, 1.0, "generator")


def test_m68_4_clauses_marked_unread():
    """M68.3/M68.4 could not be read: tau_C, tau_T, C_D, the caps and the C_K table cite M68
    as not verified (the formulas are those KR 2025 Pt 5 Ch 4 202.1 prints)."""
    iacs = R.get("iacs-m68")
    assert not iacs.shaft_formula.verified and "KR" in iacs.shaft_formula.note
    assert "not verified" in iacs.shaft_formula.cite()
    assert not iacs.strength_caps[("carbon", "intermediate")].clause.verified
    names = {name for name, _ in R.unverified(iacs)}
    assert {"shaft_formula", "transient_formula", "size_factor"} <= names
    assert "scope" not in names
