"""Linkage plots return figures with labelled axes; the animation is a GIF."""

import numpy as np
from matplotlib.figure import Figure

from crankdyn.linkage.fourbar import FourBar, fourbar_analysis
from crankdyn.linkage.kinetostatics import kinetostatics
from crankdyn.linkage.planar import Mechanism, linkage_kinematics
from crankdyn.plots.linkage import animate_mechanism, plot_mechanism


def test_fourbar_plot():
    fb = FourBar(0.0734, 0.12536, 0.1034, 0.10352, coupler_point=(0.06, 0.04))
    fig = fourbar_analysis(fb, np.radians(np.arange(0, 361, 5.0)), 10.0).plot()
    assert isinstance(fig, Figure)
    labels = [ax.get_ylabel() for ax in fig.axes]
    assert "Transmission angle μ (deg)" in labels and "Angular velocity (rad/s)" in labels


def test_kinetostatics_mechanism_and_paths_plots():
    mech = Mechanism.example("slider-crank-friction")
    motion = mech.motion(np.radians(np.arange(0, 361, 10.0)))
    res = kinetostatics(motion)
    fig = res.plot()
    assert any("Driving torque" in ax.get_ylabel() for ax in fig.axes)
    assert isinstance(plot_mechanism(motion, 3, forces=res), Figure)
    assert isinstance(linkage_kinematics(motion).plot(), Figure)


def test_animation_is_a_gif():
    mech = Mechanism.example("fourbar-seed004")
    motion = mech.motion(np.radians(np.arange(0, 360, 90.0)))
    data = animate_mechanism(motion, kinetostatics(motion))
    assert data[:6] == b"GIF89a"
