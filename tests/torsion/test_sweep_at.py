"""``ResponseResult.at`` keeps its last answers (the TVC's checks of a condition each ask for
the same range ends): a repeated request is the same immutable answer, equal to the answer of a
fresh sweep; long grids and old answers are not kept."""

from __future__ import annotations

import numpy as np

from crankdyn.torsion.excitation import UniformExcitation
from crankdyn.torsion.model import Mass, Shaft, TorsionModel
from crankdyn.torsion.sweep import AT_KEPT, AT_SPEEDS, forced_response


def _response():
    model = TorsionModel(
        (Mass("a", 1.0, cylinders=(1,)), Mass("b", 3.0)),
        (Shaft(("a", "b"), stiffness=1e5, loss_factor=0.1),),
    )
    return forced_response(model, UniformExcitation(100.0, [0.0]), np.linspace(100, 400, 31), [1.0])


def test_a_repeated_request_is_the_kept_answer_and_equals_a_fresh_one():
    r = _response()
    first = r.at([180.0, 250.0])
    assert r.at([180.0, 250.0]) is first
    fresh = _response().at([180.0, 250.0])
    assert np.array_equal(first.synthesized_shaft_torque, fresh.synthesized_shaft_torque)
    assert np.array_equal(first.amplitude, fresh.amplitude)
    assert r.at([180.0]) is not first  # other speeds: another answer


def test_long_grids_and_old_answers_are_not_kept():
    r = _response()
    grid = np.linspace(110.0, 390.0, AT_SPEEDS + 1)
    assert r.at(grid) is not r.at(grid)
    first = r.at([150.0])
    for k in range(AT_KEPT):
        r.at([200.0 + k])
    assert r.at([150.0]) is not first
