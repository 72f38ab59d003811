"""Force polygons of the link groups (crankdyn.linkage.polygon; seed 004 sec. 2)."""

import numpy as np
import pytest

from crankdyn.errors import InputError
from crankdyn.linkage.kinetostatics import kinetostatics
from crankdyn.linkage.planar import Mechanism
from crankdyn.linkage.polygon import force_polygons
from crankdyn.plots.linkage_statics import plot_force_polygons


def conveyor(angles, friction=True):
    mech = Mechanism.example("conveyor-seed004")
    return mech, kinetostatics(mech.motion(angles), friction=friction)


def test_the_conveyors_groups_in_the_seeds_order_and_closed_over_a_turn():
    _mech, result = conveyor(np.radians(np.arange(0.0, 360.0, 15.0)))
    for i in range(result.crank_angle.size):
        polygons = force_polygons(result, i)
        # the seed's order: group 4-5 (link, slider), then 2-3 (coupler, rocker), the crank last
        assert [p.group.split(": ")[1] for p in polygons] == [
            "link, slider", "coupler, rocker", "crank",
        ]  # fmt: skip
        for p in polygons:
            assert p.closure <= 1e-9 * p.scale
            assert np.allclose(p.vertices[-1], 0.0, atol=1e-9 * p.scale)


def test_the_slider_polygon_holds_the_seeds_five_forces():
    # P_r + G_5 + F_I5 + R_45 + R_65 = 0 (seed 004 sec. 2), where the slider moves left
    _mech, result = conveyor([0.3], friction=False)
    slider = force_polygons(result)[0]
    labels = list(slider.labels)
    assert labels[:2] == ["weight of slider", "inertia force of slider"]
    assert any(label.startswith("R E") for label in labels)
    assert any(label.startswith("R guide") for label in labels)
    weight = slider.forces[0]
    assert weight == pytest.approx([0.0, -20.0 * 9.81])


def test_index_outside_and_the_figure():
    _mech, result = conveyor([0.1, 0.2])
    with pytest.raises(InputError, match="position"):
        force_polygons(result, 2)
    fig = plot_force_polygons(force_polygons(result, 1), "conveyor")
    assert len(fig.axes) == 3
