"""The arrays of large results are read-only without a copy made for it (crankdyn.results.frozen):
the forced response's and the event run's arrays computed for the result are made read-only in
place; none of them is a view whose base could still be written."""

from __future__ import annotations

import numpy as np
import pytest

from crankdyn.results import freeze, frozen
from crankdyn.torsion import Mass, Shaft, TorsionModel
from crankdyn.torsion.event_run import event_response
from crankdyn.torsion.events import StepTorque
from crankdyn.torsion.excitation import UniformExcitation
from crankdyn.torsion.sweep import forced_response


def _read_only(arr):
    assert isinstance(arr, np.ndarray) and not arr.flags.writeable
    with pytest.raises(ValueError):
        arr.flat[0] = 1.0
    base = arr.base
    while base is not None:  # a view's every base is read-only too
        if isinstance(base, np.ndarray):
            assert not base.flags.writeable
        base = getattr(base, "base", None)


def test_frozen_keeps_an_owned_array_and_copies_anything_else():
    owned = np.arange(5.0) * 0.25
    assert frozen(owned) is owned and not owned.flags.writeable
    whole = np.arange(6.0)
    part = frozen(whole[2:])
    assert part.base is None and whole.flags.writeable
    ints = np.arange(3)
    assert frozen(ints).dtype == float and ints.flags.writeable
    listed = frozen([1.0, 2.0])  # type: ignore[arg-type]
    assert np.array_equal(listed, freeze([1.0, 2.0]))


def test_response_and_event_arrays_are_read_only():
    model = TorsionModel(
        (Mass("a", 1.0, cylinders=(1,)), Mass("b", 3.0)),
        (Shaft(("a", "b"), stiffness=1e5, loss_factor=0.1),),
    )
    excitation = UniformExcitation(100.0, [0.0], "two-stroke")
    r = forced_response(model, excitation, np.linspace(100.0, 400.0, 31), [1.0, 2.0])
    for name in (
        "amplitude",
        "synthesized_amplitude",
        "peak_to_peak",
        "order_sum_amplitude",
        "order_shaft_torque",
        "shaft_torque",
        "synthesized_shaft_torque",
        "shaft_stress",
        "synthesized_shaft_stress",
    ):
        _read_only(getattr(r, name))
    run = event_response(model, StepTorque("a", 100.0))
    for name in ("time", "speed", "mass_speed", "torque", "vibratory_torque", "max_torque"):
        _read_only(getattr(run, name))
