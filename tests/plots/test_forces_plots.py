"""Plots of pressure, forces, bearing loads and torque return labelled Figures."""

import math
import sys

import pytest
from matplotlib.figure import Figure

from crankdyn.crank.indicated import pressure_analysis
from crankdyn.crank.pressure_model import default_pressure
from crankdyn.engine.bearings import bearing_loads
from crankdyn.engine.forces import cylinder_forces
from crankdyn.engine.model import Engine
from crankdyn.engine.torque import engine_torque


def _check(fig):
    assert isinstance(fig, Figure)
    axes = [ax for ax in fig.get_axes() if ax.get_visible()]
    assert axes
    for ax in axes:
        if ax.lines:  # a plotted panel (or a panel sharing its axis) names it with a unit
            xs = [a.get_xlabel() for a in ax.get_shared_x_axes().get_siblings(ax)]
            ys = [a.get_ylabel() for a in ax.get_shared_y_axes().get_siblings(ax)]
            assert any("(" in x for x in xs), xs
            assert any("(" in y for y in ys), ys
    fig.canvas.draw()  # lays out without error


class _NoPyplot:
    """A meta-path finder that refuses to import matplotlib.pyplot."""

    def find_spec(self, name, path=None, target=None):
        if name == "matplotlib.pyplot":
            raise ImportError("a plot imported matplotlib.pyplot")
        return None


@pytest.fixture
def no_pyplot(monkeypatch):
    """matplotlib.pyplot cannot be imported while the test runs, whatever else this process
    imported before (openTorsion, for one, imports pyplot): the plots' own imports are held
    to the rule, not the process's history (issue 33)."""
    import matplotlib

    monkeypatch.delitem(sys.modules, "matplotlib.pyplot", raising=False)
    monkeypatch.delattr(matplotlib, "pyplot", raising=False)
    monkeypatch.setattr(sys, "meta_path", [_NoPyplot(), *sys.meta_path])


@pytest.mark.parametrize("name", ["inline6-diesel", "v8-crossplane", "single-cylinder"])
def test_plots(name, no_pyplot):
    eng = Engine.example(name)
    step = math.radians(4)
    forces = cylinder_forces(eng, eng.speed, step=step)
    _check(forces.plot())
    _check(forces.plot_pin_polar())
    _check(bearing_loads(eng, eng.speed, step=step).plot())
    _check(engine_torque(eng, eng.speed, step=step).plot())
    _check(pressure_analysis(default_pressure(eng), eng.geometry).plot())
    assert "matplotlib.pyplot" not in sys.modules
