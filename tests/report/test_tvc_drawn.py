"""The TVC report's figures drawn while the next sections are made (`crankdyn tvc`, `crankdyn
design`): every section is handed over as it is made, in the report's order, and the folder
written is the one write_report writes from the finished report (the same PNG files, byte for
byte)."""

from __future__ import annotations

import pytest

from crankdyn.report.tvc import build_tvc_report
from crankdyn.report.write import write_drawn, write_report
from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
from crankdyn.torsion.campbell import OperatingRange
from crankdyn.torsion.excitation import ExcitationSpec
from crankdyn.torsion.rules import RuleSet, ShaftLimit
from crankdyn.tvc import TvcSpec, tvc


@pytest.fixture(scope="module")
def result():
    model = TorsionModel(
        (Mass("crank", 1.0, cylinders=(1,)), Mass("propeller", 3.0)),
        (
            Shaft(
                ("crank", "propeller"),
                stiffness=1e5,
                loss_factor=0.1,
                geometry=ShaftGeometry(0.05),
                name="intermediate shaft",
            ),
        ),
        excitation=ExcitationSpec(torque=100.0),
        operating=OperatingRange(100.0, 400.0, rated=400.0),
        rules=RuleSet(None, (ShaftLimit(("crank", "propeller"), 600e6),)),
    )
    return tvc(model, spec=TvcSpec(overspeed=False), orders=[1.0, 2.0])


def test_every_section_is_handed_over_as_it_is_made(result):
    seen = []
    report = build_tvc_report(result, built=lambda section: seen.append(section.key))
    assert seen == [s.key for s in report.sections]
    assert "verdicts" in seen and "condition-1" in seen


def test_drawn_while_made_writes_the_same_folder(result, tmp_path):
    drawn = write_drawn(lambda built: build_tvc_report(result, built=built), tmp_path / "a")
    plain = write_report(build_tvc_report(result), tmp_path / "b")
    names = sorted(p.name for p in (drawn / "plots").iterdir())
    assert names == sorted(p.name for p in (plain / "plots").iterdir())
    assert any(n.endswith(".png") for n in names)
    for name in names:
        if name.endswith(".png"):
            assert (drawn / "plots" / name).read_bytes() == (plain / "plots" / name).read_bytes()
    assert sorted(p.name for p in drawn.iterdir()) == sorted(p.name for p in plain.iterdir())
