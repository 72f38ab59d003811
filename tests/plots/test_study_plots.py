"""Plots of parameter studies render, with labelled axes and the expected panels."""

from __future__ import annotations

import io

import numpy as np
from matplotlib.figure import Figure

from crankdyn.plots.study import Series, plot_distributions, plot_sensitivity


def _png(fig: Figure) -> bytes:
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=60)
    return buffer.getvalue()


def test_sensitivity_grid():
    rng = np.random.default_rng(2)
    a = np.repeat([0.24, 0.26, 0.28], 4)
    order = np.array(["[1, 3, 4, 2]", "[1, 2, 4, 3]"] * 6, dtype=object)
    mc = rng.normal(76.0, 0.5, 12)
    y1 = 1e4 * a + rng.normal(0, 10, 12)
    y2 = np.full(12, 102.524) + 1e-9 * a  # the same in every case
    fig = plot_sensitivity(
        [Series("Max load", "kN", y1), Series("Mean torque", "N·m", y2)],
        [
            Series("geometry.rod_ratio", "", a),
            Series("cylinders.firing_order", "", order, numeric=False),
            Series("geometry.bore", "mm", mc),
        ],
    )
    assert isinstance(fig, Figure)
    axes = fig.axes
    assert len(axes) == 6
    assert axes[0].get_ylabel() == "Max load (kN)"
    assert axes[3].get_xlabel() == "geometry.rod_ratio"
    assert axes[5].get_xlabel() == "geometry.bore (mm)"
    texts = [t.get_text() for ax in axes for t in ax.texts]
    assert "the same in every case" in texts and any(t.startswith("ρ = +") for t in texts)
    assert [t.get_text() for t in axes[4].get_xticklabels()] == ["[1, 3, 4, 2]", "[1, 2, 4, 3]"]
    assert _png(fig).startswith(b"\x89PNG")


def test_distributions():
    rng = np.random.default_rng(4)
    fig = plot_distributions(
        [
            Series("Max load", "kN", rng.normal(60, 1, 50)),
            Series("Tension", "kN", np.full(50, np.nan)),
        ]
    )
    assert fig.axes[0].get_xlabel() == "Max load (kN)"
    assert fig.axes[0].get_ylabel() == "cases"
    assert _png(fig).startswith(b"\x89PNG")


def test_sensitivity_fixed_layout_keeps_labels_inside():
    """The grid is laid out once (no layout engine): every label inside the figure, no two
    panels' labels over each other, the panels the same size."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    a = np.repeat([0.22, 0.24, 0.26], 4)
    order = np.array(["[1, 3, 4, 2]", "[1, 2, 4, 3]"] * 6, dtype=object)
    fig = plot_sensitivity(
        [
            Series("Max main-bearing load (largest of the bearings)", "kN", 15.8 + a),
            Series("Max piston acceleration |a|", "m/s²", 14900.0 + 1e4 * a),
        ],
        [Series("geometry.rod_ratio", "", a), Series("firing_order", "", order, numeric=False)],
    )
    assert fig.get_layout_engine() is None
    renderer = FigureCanvasAgg(fig).get_renderer()
    page = fig.bbox
    boxes = [ax.get_tightbbox(renderer) for ax in fig.axes]
    for box in boxes:
        assert page.x0 <= box.x0 and box.x1 <= page.x1 and page.y0 <= box.y0 and box.y1 <= page.y1
    for i, one in enumerate(boxes):
        for other in boxes[i + 1 :]:
            assert not one.overlaps(other)
    sizes = {
        (round(ax.get_position().width, 9), round(ax.get_position().height, 9)) for ax in fig.axes
    }
    assert len(sizes) == 1
    title = fig._suptitle.get_window_extent(renderer)
    assert title.y1 <= page.y1 and all(title.y0 >= box.y1 for box in boxes[:2])
