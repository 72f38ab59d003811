"""Linkage plots return figures with labelled axes; the animation is a GIF."""

import dataclasses
import io

import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from crankdyn.linkage.fourbar import FourBar, fourbar_analysis
from crankdyn.linkage.kinetostatics import kinetostatics
from crankdyn.linkage.motion import linkage_kinematics
from crankdyn.linkage.planar import Mechanism
from crankdyn.plots.linkage import (
    FORCE_LABEL,
    JOINT_LABEL,
    animate_mechanism,
    plot_mechanism,
    plot_paths,
)

LINKAGES = ("fourbar-seed004", "conveyor-seed004", "slider-crank-friction")


def _drawn(fig):
    if not isinstance(fig.canvas, FigureCanvasAgg):
        FigureCanvasAgg(fig)
    fig.canvas.draw()
    return fig.canvas.get_renderer()


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


def test_animation_dpi_sets_the_frame_size():
    from PIL import Image

    mech = Mechanism.example("fourbar-seed004")
    motion = mech.motion(np.radians(np.arange(0, 360, 120.0)))
    sizes = {}
    for dpi in (40, 80):
        with Image.open(io.BytesIO(animate_mechanism(motion, dpi=dpi))) as gif:
            sizes[dpi] = gif.size
            assert gif.n_frames == 3
    # the 6.4 x 5.2 inch figure at dpi dots per inch
    assert sizes == {40: (256, 208), 80: (512, 416)}
    with pytest.raises(ValueError, match="dpi"):
        animate_mechanism(motion, dpi=0)


def _long_named(mech, name):
    return dataclasses.replace(mech, name=name)


@pytest.mark.parametrize("linkage", LINKAGES)
def test_mechanism_drawing_title_inside_and_labels_apart(linkage):
    mech = Mechanism.example(linkage)
    name = f"{mech.name}, drawn for the design review of the conveyor line, second revision"
    motion = _long_named(mech, name).motion(mech.crank_angle_drawn + np.linspace(0, 2 * np.pi, 73))
    for fig in (plot_mechanism(motion, 0, forces=kinetostatics(motion)), plot_paths(motion)):
        renderer = _drawn(fig)
        title = fig.get_suptitle()
        assert name.split()[0] in title
        box = fig._suptitle.get_window_extent(renderer)
        assert fig.bbox.x0 <= box.x0 and box.x1 <= fig.bbox.x1 and box.y1 <= fig.bbox.y1
        ax = fig.axes[0]
        joints = [t for t in ax.texts if t.get_gid() == JOINT_LABEL]
        forces = [t for t in ax.texts if t.get_gid() == FORCE_LABEL]
        assert joints
        for f in forces:
            fbox = f.get_window_extent(renderer)
            for j in joints:
                assert not fbox.overlaps(j.get_window_extent(renderer)), (
                    f.get_text(),
                    j.get_text(),
                )
