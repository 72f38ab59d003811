"""crankdyn.plots.style and the plots that use it tell the truth (issue 14, point 8): curves that
coincide are said to coincide, periodic polars are closed, legends cover nothing and stay inside
the figure. (Linkage drawings: test_linkage_plots.py; a plot's resolution does not follow the
table's --step: tests/cli/test_linkage_cli.py and tests/cli/test_forces_cli.py.)"""

from __future__ import annotations

import math

import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg

from crankdyn.engine.bearings import bearing_loads
from crankdyn.engine.flywheel import engine_flywheel
from crankdyn.engine.torque import engine_torque
from crankdyn.io.catalogue import load_example
from crankdyn.linkage.fourbar import FourBar, fourbar_analysis
from crankdyn.linkage.kinetostatics import kinetostatics
from crankdyn.linkage.planar import Mechanism
from crankdyn.plots.style import closed, coinciding, identical, number_ranges


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


def test_only_tick_labels_that_may_hold_words_are_walked():
    """plain_text asks an axis for its ticks (which runs its locator and makes ticks) only where
    the formatter may write words: names (FixedFormatter), a function's text; not numbers
    (ScalarFormatter: digits, sign and point, never a `$`), nothing (NullFormatter) or mathtext
    (log axes)."""
    import matplotlib.ticker as ticker

    from crankdyn.plots.style import _writes_words, new_figure, plain_text

    assert not _writes_words(ticker.ScalarFormatter())
    assert not _writes_words(ticker.NullFormatter())
    assert not _writes_words(ticker.LogFormatterSciNotation())
    assert not _writes_words(ticker.ScalarFormatter(useMathText=True))
    assert _writes_words(ticker.FixedFormatter(["a"]))
    assert _writes_words(ticker.FuncFormatter(lambda x, pos: "$x$"))

    fig, axes = new_figure(1, 2)
    left, right = axes[0]
    left.plot([0.0, 1.0], [0.0, 2.0])
    right.set_xticks([0, 1], labels=["$a$", "b"])
    calls = []
    locator = left.xaxis.get_major_locator()
    original = type(locator).__call__
    left.xaxis.set_major_locator(
        type(
            "Counting",
            (type(locator),),
            {"__call__": lambda self: calls.append(1) or original(self)},
        )()
    )
    plain_text(fig)
    assert calls == []  # the number axis was not asked for its ticks
    assert [t.get_parse_math() for t in right.get_xticklabels()] == [False, False]
