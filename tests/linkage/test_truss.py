"""The truss module (crankdyn.linkage.truss): determinacy checks, the seed's rules for zero-force
members and the K joint, a compound truss solved together, a truss without a section check."""

import math

import numpy as np
import pytest

from crankdyn.errors import InputError
from crankdyn.io.truss_file import parse_truss
from crankdyn.linkage.truss import Truss, TrussLoad, TrussSupport, member_forces, truss_analysis


def triangle(load=(0.0, -600.0)):
    return Truss(
        ("A", "B", "C"),
        [(0.0, 0.0), (8.0, 0.0), (4.0, 3.0)],
        (("A", "B"), ("A", "C"), ("B", "C")),
        (TrussSupport("A"), TrussSupport("B", "roller")),
        (TrussLoad("C", load),),
    )


def test_a_3_4_5_triangle_by_hand():
    # apex load P = 600 N: each strut carries P/2 / sin(atan(3/4)) = 300 / 0.6 = 500 N C, the
    # tie the horizontal part 500 x 0.8 = 400 N T
    result = truss_analysis(triangle())
    assert list(result.force) == pytest.approx([400.0, -500.0, -500.0], abs=1e-9)
    assert list(result.force_sections) == pytest.approx([400.0, -500.0, -500.0], abs=1e-9)


def test_determinacy_is_checked():
    with pytest.raises(InputError, match="statically indeterminate"):
        Truss(
            ("A", "B", "C"),
            [(0.0, 0.0), (8.0, 0.0), (4.0, 3.0)],
            (("A", "B"), ("A", "C"), ("B", "C")),
            (TrussSupport("A"), TrussSupport("B")),
        )
    with pytest.raises(InputError, match="a mechanism"):
        Truss(
            ("A", "B", "C"),
            [(0.0, 0.0), (8.0, 0.0), (4.0, 3.0)],
            (("A", "C"), ("B", "C")),
            (TrussSupport("A"), TrussSupport("B", "roller")),
        )
    with pytest.raises(InputError, match='no joint named "D"'):
        Truss(
            ("A", "B", "C"),
            [(0.0, 0.0), (8.0, 0.0), (4.0, 3.0)],
            (("A", "B"), ("A", "D"), ("B", "C")),
            (TrussSupport("A"), TrussSupport("B", "roller")),
        )


def test_a_geometrically_unstable_truss_is_refused():
    # three joints in line: m + r = 2 j, but the middle joint can move across the line
    truss = Truss(
        ("A", "B", "C"),
        [(0.0, 0.0), (1.0, 0.0), (2.0, 0.0)],
        (("A", "B"), ("B", "C"), ("A", "C")),
        (TrussSupport("A"), TrussSupport("C", "roller")),
        (TrussLoad("B", (0.0, -1.0)),),
    )
    with pytest.raises(InputError, match="geometrically unstable"):
        truss_analysis(truss)


def test_the_three_rules_of_the_seed_hold_in_the_solution():
    # a Pratt-like truss with an unloaded K joint: seed 004 sec. 3.4.2 cases 2 and 3
    h = 1.0
    nodes = ("L0", "L1", "L2", "L3", "L4", "U1", "U2", "U3")
    xy = [(0, 0), (1, 0), (2, 0), (3, 0), (4, 0), (1, h), (2, h), (3, h)]
    members = (
        ("L0", "L1"), ("L1", "L2"), ("L2", "L3"), ("L3", "L4"),
        ("U1", "U2"), ("U2", "U3"), ("L0", "U1"), ("U3", "L4"),
        ("L1", "U1"), ("L2", "U2"), ("L3", "U3"), ("L1", "U2"), ("L3", "U2"),
    )  # fmt: skip
    truss = Truss(
        nodes, xy, members,
        (TrussSupport("L0"), TrussSupport("L4", "roller")),
        (TrussLoad("U1", (0.0, -10.0)), TrussLoad("U3", (0.0, -30.0))),
    )  # fmt: skip
    result = truss_analysis(truss)
    force = dict(zip(result.member, result.force, strict=True))
    # case 2: joint L2, unloaded, L1-L2 and L2-L3 in line: the third member L2-U2 carries nothing
    assert "L2-U2" in result.zero_force_members
    assert force["L2-U2"] == 0.0
    assert force["L1-L2"] == pytest.approx(force["L2-L3"], rel=1e-12)
    # case 3: U2 is a K joint (U1-U2, U2-U3 in line; L1-U2 and L3-U2 below at 45 deg each)
    # once L2-U2 is known to be zero: the two diagonals carry equal and opposite forces
    assert force["L1-U2"] == pytest.approx(-force["L3-U2"], rel=1e-12)
    assert result.method_difference < 1e-9 * max(abs(f) for f in force.values())


def test_more_than_three_reactions_joints_only():
    # two pins and m = 2 j - 4: the whole truss does not fix the reactions, no section check
    truss = Truss(
        ("A", "B", "C"),
        [(0.0, 0.0), (4.0, 0.0), (2.0, 2.0)],
        (("A", "C"), ("B", "C")),
        (TrussSupport("A"), TrussSupport("B")),
        (TrussLoad("C", (0.0, -100.0)),),
    )
    result = truss_analysis(truss)
    # symmetric two-bar frame: each bar 50 sqrt(2) N in compression
    assert list(result.force) == pytest.approx([-50 * math.sqrt(2)] * 2, rel=1e-12)
    assert np.all(np.isnan(result.force_sections))
    assert any("no section check" in n for n in result.notes)
    assert member_forces(truss)[:2] == pytest.approx(list(result.force), rel=1e-12)


def test_the_file_format_names_the_key():
    data = {
        "nodes": {"A": ["0 m", "0 m"], "B": ["4 m", "0 m"], "C": ["2 m", "1.5 m"]},
        "members": [{"between": ["A", "B"]}, {"between": ["A", "C"]}, {"between": ["B", "C"]}],
        "supports": [{"node": "A"}, {"node": "B", "kind": "roller"}],
        "loads": [{"node": "C", "force": ["0 kN", "-1 kN"]}],
    }
    truss = parse_truss(data, file="t.toml")
    assert truss.coordinates[2].tolist() == [2.0, 1.5] and truss.load_vector[5] == -1000.0
    bad = dict(data, supports=[{"node": "A", "direction": "10 deg"}, {"node": "B", "kind": "x"}])
    with pytest.raises(InputError, match="direction") as err:
        parse_truss(bad, file="t.toml")
    assert "t.toml" in str(err.value)
