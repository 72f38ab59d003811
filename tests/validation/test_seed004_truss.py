"""Seed 004 sec. 3.4 (静定平面桁架): the methods of joints and of sections for a statically
determinate plane truss, tested on a textbook truss with published answers.

F. P. Beer, E. R. Johnston et al., *Vector Mechanics for Engineers: Statics*, chapter 6, the
sample problem "Determine the forces in members EF and GI of the truss shown" (tests/validation/
data/beer_johnston_truss.toml gives its geometry and loads): the published reactions
J = 33 kips up, B_x = 16 kips to the left, B_y = 23 kips up, and F_EF = 5 kips C (found there
by a section through EF and two more members, sum F_y of the left part: 23 - 28 - F_EF = 0).
The values are exact for the round data: the tolerance is 0.005 kips, half the last digit of the
book's three figures. The force in GI comes from the section the book passes through GI, HI and
HJ, moments about H (where HI and HJ meet) of the right part: 33 kips x 8 ft - 16 kips x 10 ft
+ 10 ft x F_GI = 0, F_GI = -10.4 kips (10.4 kips C), written out here by hand.
"""

from pathlib import Path

import numpy as np
import pytest

from crankdyn.io.truss_file import load_truss
from crankdyn.linkage.truss import member_forces, truss_analysis

DATA = Path(__file__).parent / "data" / "beer_johnston_truss.toml"
KIP = 4448.2216152605  # N (lbf x 1000)
FT = 0.3048  # m


def _force(result, name):
    return float(result.force[list(result.member).index(name)]) / KIP


def _section(result, name):
    return float(result.force_sections[list(result.member).index(name)]) / KIP


def test_beer_johnston_reactions_and_ef():
    result = truss_analysis(load_truss(DATA))
    reactions = dict(zip(result.reactions.component, result.reactions.joints / KIP, strict=True))
    assert reactions["J"] == pytest.approx(33.0, abs=0.005)
    assert reactions["B x"] == pytest.approx(-16.0, abs=0.005)
    assert reactions["B y"] == pytest.approx(23.0, abs=0.005)
    # F_EF = 5 kips C, by joints and by sections
    assert _force(result, "E-F") == pytest.approx(-5.0, abs=0.005)
    assert _section(result, "E-F") == pytest.approx(-5.0, abs=0.005)


def test_beer_johnston_gi_by_the_books_section():
    result = truss_analysis(load_truss(DATA))
    by_hand = -(33.0 * 8.0 - 16.0 * 10.0) / 10.0  # moments about H of the right part
    assert _force(result, "G-I") == pytest.approx(by_hand, abs=0.005)
    assert _section(result, "G-I") == pytest.approx(by_hand, abs=0.005)
    assert str(result.state[list(result.member).index("G-I")]) == "compression"


def test_joints_and_sections_agree_and_the_matrix_form_agrees():
    truss = load_truss(DATA)
    result = truss_analysis(truss)
    assert not np.any(np.isnan(result.force_sections))  # every member has its section
    scale = float(np.max(np.abs(result.force)))
    assert result.method_difference < 1e-9 * scale
    assert result.closure < 1e-9 * scale
    # every joint's equations solved at once (the matrix form) gives the same forces
    all_at_once = member_forces(truss)
    assert np.allclose(all_at_once[: len(truss.members)], result.force, rtol=0, atol=1e-9 * scale)
    assert np.allclose(result.reactions.all_at_once, result.reactions.joints, atol=1e-9 * scale)


def test_zero_force_members_by_the_seeds_rules_carry_nothing():
    # seed 004 sec. 3.4.2 case 1: joint A, unloaded and unsupported, two members not in line
    result = truss_analysis(load_truss(DATA))
    assert set(result.zero_force_members) == {"A-B", "A-C"}
    for name in result.zero_force_members:
        assert _force(result, name) == 0.0
