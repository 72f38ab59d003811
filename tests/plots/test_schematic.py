"""The schematic of the mass-elastic system (issue 32) for a branched model: a gearbox whose
wheel drives the propeller and, through a second pinion, a generator (a power take-off), a pump
on a shaft branch of the flywheel, a grounded torsional spring, an elastic coupling, a damper
and a distributed shaft; every mass drawn where its branch puts it, every element drawn."""

from __future__ import annotations

import pytest

from crankdyn.plots.schematic import layout_schematic, plot_schematic
from crankdyn.torsion import Gear, Mass, Shaft, TorsionModel
from crankdyn.torsion.coupling import Coupling
from crankdyn.torsion.dampers import Damper


@pytest.fixture(scope="module")
def model():
    rubber = Coupling(stiffness=3e5, relative_damping=1.0)
    masses = (
        Mass("damper hub", 2.0),
        Mass("crank 1", 5.0, cylinders=(1,)),
        Mass("crank 2", 5.0, cylinders=(2,)),
        Mass("flywheel", 40.0),
        Mass("coupling out", 3.0),
        Mass("pinion", 1.0),
        Mass("wheel", 30.0),
        Mass("propeller", 400.0, role="propeller"),
        Mass("PTO pinion", 0.8),
        Mass("generator", 25.0),
        Mass("pump", 0.5),
    )
    shafts = (
        Shaft(("damper hub", "crank 1"), 4e7),
        Shaft(("crank 1", "crank 2"), 4e7),
        Shaft(("crank 2", "flywheel"), 5e7),
        Shaft(("flywheel", "coupling out"), 3e5, coupling=rubber),
        Shaft(("coupling out", "pinion"), 8e6),
        Shaft(("wheel", "propeller"), 2e7),
        Shaft(("PTO pinion", "generator"), 4e6),
        Shaft(("flywheel", "pump"), 2e4),
        Shaft(("generator", "ground"), 1e3),
    )
    gears = (Gear(("pinion", "wheel"), 0.25), Gear(("wheel", "PTO pinion"), 3.0))
    damper = Damper("viscous damper", "damper hub", 1.0, damping=500.0)
    return TorsionModel(masses, shafts, gears, name="branched line", dampers=(damper,))


def test_layout_puts_every_branch_on_its_own_row(model):
    lay = layout_schematic(model)
    pos = lay.position
    assert set(pos) == {m.name for m in model.masses}
    # the engine's line in row 0, left to right from the free end
    line = ["damper hub", "crank 1", "crank 2", "flywheel", "coupling out", "pinion"]
    assert [pos[n] for n in line] == [(c, 0) for c in range(6)]
    # a mesh steps down: the wheel under its pinion, the propeller to its right
    assert pos["wheel"] == (5, pos["wheel"][1]) and pos["wheel"][1] > 0
    assert pos["propeller"] == (6, pos["wheel"][1])
    # the second mesh and the pump's shaft branch each get a row of their own
    rows = {pos["wheel"][1], pos["PTO pinion"][1], pos["pump"][1]}
    assert len(rows) == 3 and lay.rows == 4
    assert pos["generator"][1] == pos["PTO pinion"][1]
    kinds = sorted(lk.kind for lk in lay.links)
    assert kinds.count("mesh") == 2 and kinds.count("coupling") == 1
    assert any("ground" in (lk.a, lk.b) for lk in lay.links)


def test_the_figure_names_every_mass_and_the_damper(model):
    fig = plot_schematic(model)
    texts = [t.get_text() for ax in fig.axes for t in ax.texts]
    for mass in model.masses:
        assert any(t.startswith(mass.name + "\n") for t in texts), mass.name
    assert any("viscous damper" in t for t in texts)
    assert any(t.startswith("i = 4") for t in texts)  # the reduction 4:1
    assert any(t.startswith("C1") for t in texts) and any(t.startswith("C2") for t in texts)
    fig.canvas.draw()  # draws without error


def test_a_distributed_shaft_is_one_line():
    import crankdyn

    model = crankdyn.Analysis(crankdyn.Engine.example("marine-propulsion")).loaded_model
    lay = layout_schematic(model)
    distributed = [lk for lk in lay.links if lk.kind == "distributed"]
    assert {(lk.a, lk.b) for lk in distributed} == {
        ("thrust collar", "stern tube flange"),
        ("stern tube flange", "propeller"),
    }
    assert not any("/" in name for name in lay.position)  # no element mass drawn
