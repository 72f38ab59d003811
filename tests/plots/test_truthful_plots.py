"""Plots that tell the truth (issue 14, point 8): curves that coincide are said to coincide,
periodic polars are closed, legends and labels cover nothing, titles stay inside the figure,
and a plot's resolution does not follow the table's --step."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg

from crankdyn.engine.bearings import bearing_loads
from crankdyn.engine.flywheel import engine_flywheel
from crankdyn.engine.torque import engine_torque
from crankdyn.io.engine_file import load_example
from crankdyn.linkage.fourbar import FourBar, fourbar_analysis
from crankdyn.linkage.kinetostatics import kinetostatics
from crankdyn.linkage.planar import Mechanism
from crankdyn.plots.linkage import FORCE_LABEL, JOINT_LABEL, plot_mechanism, plot_paths
from crankdyn.plots.style import closed, coinciding, identical, number_ranges

LINKAGES = ("fourbar-seed004", "conveyor-seed004", "slider-crank-friction")


@pytest.fixture(scope="module")
def inline6():
    return load_example("inline6-diesel")


def _drawn(fig):
    if not isinstance(fig.canvas, FigureCanvasAgg):
        FigureCanvasAgg(fig)
    fig.canvas.draw()
    return fig.canvas.get_renderer()


def _data_lines(ax):
    """The curves of an axes (lines of more than two points: not the zero and reference lines
    across it, not single markers)."""
    return [line for line in ax.get_lines() if len(line.get_xdata()) > 2]


# ---- helpers --------------------------------------------------------------------------------


def test_coinciding_finds_shifted_copies_only():
    t = np.linspace(0.0, 2 * np.pi, 360, endpoint=False)
    c = np.exp(1j * t) * (1.0 + 0.3 * np.cos(3 * t))
    groups = coinciding(np.array([c, np.roll(c, 120), 1.01 * c, np.roll(1.01 * c, 7)]))
    assert groups == [[0, 1], [2, 3]]  # a 1 % larger curve is drawn apart


def test_identical_and_ranges():
    a = np.sin(np.linspace(0, 6, 50))
    assert identical(np.array([a, 2 * a, a + 1e-9, a])) == [[0, 2, 3], [1]]
    assert number_ranges([6, 1, 2, 3, 5]) == "1-3, 5-6"
    assert closed([1.0, 2.0, 3.0]).tolist() == [1.0, 2.0, 3.0, 1.0]
    assert closed([1.0, 2.0, 1.0]).tolist() == [1.0, 2.0, 1.0]


# ---- bearing polars ---------------------------------------------------------------------------


def test_identical_crank_pin_polars_are_one_labelled_curve(inline6):
    fig = bearing_loads(inline6, inline6.speed).plot()
    pin = next(ax for ax in fig.axes if "Tangential" in ax.get_xlabel())
    curves = [line for line in pin.get_lines() if line.get_label() and "throw" in line.get_label()]
    assert [c.get_label() for c in curves] == ["throws 1-6 (identical)"]
    assert pin.get_legend() is not None
    assert [t.get_text() for t in pin.get_legend().get_texts()] == ["throws 1-6 (identical)"]


@pytest.mark.parametrize("grid", ["inclusive", "exclusive"])
def test_polar_curves_are_closed(inline6, grid):
    if grid == "inclusive":
        loads = bearing_loads(inline6, inline6.speed, step=math.radians(2.0))
    else:  # a full cycle without its end point
        loads = bearing_loads(inline6, inline6.speed, np.radians(np.arange(0.0, 720.0, 2.0)))
    fig = loads.plot()
    polars = [
        line
        for ax in fig.axes
        for line in ax.get_lines()
        if line.get_label().startswith(("throw", "bearing"))
    ]
    assert len(polars) == 1 + loads.bearing_load.shape[0]
    for line in polars:
        x, y = line.get_xdata(), line.get_ydata()
        assert (x[0], y[0]) == (x[-1], y[-1]), line.get_label()


# ---- legends, titles and labels ----------------------------------------------------------------


def _figures(inline6):
    fb = FourBar(0.0734, 0.12536, 0.1034, 0.10352, coupler_point=(0.06, 0.04))
    mech = Mechanism.example("slider-crank-friction")
    motion = mech.motion(np.radians(np.arange(0.0, 360.5, 1.0)))
    return {
        "flywheel": engine_flywheel(inline6, inline6.speed, delta=0.01).plot(),
        "torque": engine_torque(inline6, inline6.speed).plot(),
        "bearings": bearing_loads(inline6, inline6.speed).plot(),
        "fourbar": fourbar_analysis(fb, np.radians(np.arange(0.0, 360.5, 2.0)), 10.0).plot(),
        "kinetostatics": kinetostatics(motion).plot(),
    }


def test_legends_cover_no_curve_and_stay_in_the_figure(inline6):
    for name, fig in _figures(inline6).items():
        renderer = _drawn(fig)
        page = fig.bbox
        for ax in fig.axes:
            legend = ax.get_legend()
            if legend is None:
                continue
            box = legend.get_window_extent(renderer)
            assert page.x0 - 1 <= box.x0 and box.x1 <= page.x1 + 1, (name, ax.get_ylabel())
            assert page.y0 - 1 <= box.y0 and box.y1 <= page.y1 + 1, (name, ax.get_ylabel())
            # no point of any curve of the figure lies under the legend
            for other in fig.axes:
                for line in _data_lines(other):
                    xy = line.get_transform().transform(line.get_xydata())
                    inside = (
                        (xy[:, 0] > box.x0)
                        & (xy[:, 0] < box.x1)
                        & (xy[:, 1] > box.y0)
                        & (xy[:, 1] < box.y1)
                    )
                    assert not inside.any(), (name, ax.get_ylabel(), line.get_label())


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


# ---- resolution ------------------------------------------------------------------------------


@pytest.fixture
def captured(monkeypatch):
    """The figures the linkage commands save (instead of writing them)."""
    import crankdyn.cli.linkage as linkage_cli

    figures = []
    monkeypatch.setattr(linkage_cli, "save_figure", lambda fig, path, force: figures.append(fig))
    return figures


def _torque_line(fig):
    ax = next(ax for ax in fig.axes if ax.get_ylabel() == "Driving torque (N·m)")
    return next(line for line in ax.get_lines() if line.get_label().startswith("matrix method"))


def test_linkage_forces_plot_does_not_follow_the_table_step(cli, captured, tmp_path):
    for step in ("10", "30"):
        run = cli("linkage", "forces", "slider-crank-friction", "--step", step, "--plot", "f.png")
        assert run.status == 0, run
    coarse, coarser = (_torque_line(fig) for fig in captured)
    assert len(coarse.get_xdata()) == len(coarser.get_xdata()) >= 1441
    np.testing.assert_array_equal(coarse.get_ydata(), coarser.get_ydata())
    # the slider's resistance reverses at the dead centre: the plotted torque falls there within
    # one plot step (0.25 deg), not over the 10 deg of the table grid
    x, y = coarse.get_xdata(), coarse.get_ydata()
    near = (x > 170.0) & (x < 180.0)
    assert np.max(y[near]) > 10 * np.min(np.abs(y[(x > 179.0) & (x < 181.0)])) + 1.0


def test_fourbar_plot_does_not_follow_the_table_step(cli, captured):
    args = ("linkage", "fourbar", "--crank", "73.4mm", "--coupler", "125.36mm")
    args += ("--rocker", "103.4mm", "--ground", "103.52mm", "--plot", "f.png")
    for step in ("10", "45"):
        assert cli(*args, "--step", step).status == 0
    assert cli(*args, "--angle", "30").status == 0
    sizes = {
        len(
            next(ax for ax in fig.axes if "Transmission" in ax.get_ylabel())
            .get_lines()[0]
            .get_xdata()
        )
        for fig in captured
    }
    assert sizes == {1441}
