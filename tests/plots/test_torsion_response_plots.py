"""The forced-response figures: labelled axes with units, legends, no pyplot."""

import math

import numpy as np
import pytest

from crankdyn.engine.model import Engine
from crankdyn.session import Analysis
from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
from crankdyn.torsion.campbell import campbell
from crankdyn.torsion.excitation import UniformExcitation, excitation_for
from crankdyn.torsion.harmonics import harmonic_analysis
from crankdyn.torsion.rules import RuleSet, ShaftLimit
from crankdyn.torsion.sweep import forced_response
from crankdyn.torsion.transient import transient_response

RPM = math.pi / 30


@pytest.fixture(scope="module")
def diesel():
    engine = Engine.example("inline6-diesel")
    ex = excitation_for(engine.torsion, engine)
    r = forced_response(engine.torsion, ex, np.arange(1000, 2501, 50) * RPM, np.arange(1, 25) / 2)
    return engine, ex, r


@pytest.mark.parametrize(
    ("what", "item", "unit"),
    [
        ("amplitude", "pulley", "mrad"),
        ("relative", ("pulley", "flywheel"), "mrad"),
        ("torque", ("cylinder 6", "flywheel"), "kN·m"),
    ],
)
def test_response_plot(diesel, what, item, unit):
    fig = diesel[2].plot(what, item)
    ax = fig.axes[0]
    assert ax.get_xlabel() == "Engine speed (rpm)"
    assert ax.get_ylabel().endswith(f"({unit})")
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert "synthesised (half range)" in labels and "order 6 (major)" in labels


def test_campbell_and_harmonics_plots(diesel):
    engine, ex, _ = diesel
    c = campbell(engine.torsion, np.arange(1, 25) / 2, excitation=ex)
    fig = c.plot()
    ax = fig.axes[0]
    assert ax.get_ylabel() == "Frequency (Hz)"
    assert any("major" in t.get_text() for t in ax.get_legend().get_texts())
    h = harmonic_analysis(ex, 2000 * RPM, np.arange(1, 13) / 2)
    assert h.plot().axes[0].get_ylabel() == "Harmonic torque amplitude (N·m)"


def test_stress_limit_and_transient_plots():
    model = TorsionModel(
        masses=(Mass("engine", 2.0, damping=5.0, cylinders=(1,)), Mass("propeller", 6.0)),
        shafts=(Shaft(("engine", "propeller"), 5.3e4, geometry=ShaftGeometry(0.06)),),
        rules=RuleSet(1000 * RPM, (ShaftLimit(("engine", "propeller"), 600e6),)),
    )
    ex = UniformExcitation(60.0, [0.0], "two-stroke")
    session = Analysis(model, speeds=np.linspace(300, 1000, 141) * RPM, orders=[3.0])
    fig = session.judged(torque=60.0).plot_stress_limits()  # the checks' own curves and limits
    labels = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert labels[:3] == [
        "synthesised stress (half range)",
        "τ_C continuous",
        "τ_T transient (λ ≤ 0.8)",
    ]
    assert "declared barred range" in labels and "found (stress above τ_C)" in labels
    assert fig.axes[0].get_ylabel() == "Shear stress (MPa)"
    run = transient_response(model, ex, [3.0], run_up=(400 * RPM, 800 * RPM), duration=0.5)
    fig = run.plot()
    assert fig.axes[0].get_xlabel() == "Time (s)" and len(fig.axes) == 2
