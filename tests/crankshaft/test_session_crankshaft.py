"""The crankshaft's analyses in the session (crankdyn.session.crankshaft): M53 from the forced
torsional response the TVC judges, the beam model's additional stress, the modes beside the
lumped model's, every analysis computed once, and the crankshaft rows of the TVC."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import crankdyn
from crankdyn.errors import InputError


@pytest.fixture(scope="module")
def session():
    return crankdyn.Analysis(crankdyn.Engine.example("marine-propulsion"))


def test_m_tn_is_the_largest_torque_of_the_spans_beside_each_throw(session):
    result = session.crankshaft()
    response = session.response()
    judged = session.judged()
    speeds = response.speed
    keep = np.ones(speeds.size, bool)
    for b in judged.barred_ranges:
        keep &= ~((speeds >= b.start) & (speeds <= b.end))
    torque = response.synthesized_shaft_torque[keep]
    for t in range(6):
        mass = f"throw {t + 1}"
        columns = [j for j, pair in enumerate(response.shafts) if mass in pair]
        assert result.torsion_torque[t] == np.max(torque[:, columns])
    assert result.torsion_given and len(result.torsion_where) == 6
    assert "M_TN from (2.2.2)" in [c.label for c in result.summary().tables[0].columns]


def test_computed_once(session):
    session.crankshaft()
    session.crankshaft_modes()
    before = session.computed()
    assert session.crankshaft() is session.crankshaft()
    assert session.crankshaft_modes() is session.crankshaft_modes()
    assert session.computed() == before
    assert before.count("crankshaft") == 1 and before.count("response") == 1


def test_the_beam_models_additional_stress(session):
    rule = session.crankshaft(additional_stress="rule")
    beam = session.crankshaft(additional_stress="beam")
    vib = session.crankshaft_response().summary().figure("max_web_vibration_stress_Pa").value
    assert rule.additional == 10e6 and rule.vibration_stress is None
    assert beam.vibration_stress == vib
    assert beam.additional == max(10e6, vib)  # trunk piston (crankdyn's choice)
    assert "beam model" in beam.additional_source
    assert all(beam.additional_source in v.note for v in beam.summary_verdicts()
               if v.kind != "oil bore")  # fmt: skip
    # the oil bore has no additional stress (M53.5): its Q does not change
    np.testing.assert_array_equal(beam.q_oil, rule.q_oil)
    with pytest.raises(InputError) as info:
        session.crankshaft(additional_stress="fe")
    assert info.value.key == "additional_stress"


def test_the_modes_beside_the_lumped_model(session):
    modes = session.crankshaft_modes()
    lumped = session.modes.natural_frequency
    paired = np.isfinite(modes.lumped_frequency)
    assert paired.sum() >= 4
    # paired by shape (no tuned damper): each with a distinct elastic lumped mode, MAC >= 1/2
    chosen = modes.lumped_frequency[paired]
    assert np.isin(chosen, lumped[1:]).all() and np.unique(chosen).size == chosen.size
    assert np.all(modes.lumped_mac[paired] >= 0.5)
    # the shaft line's modes beyond the elastic coupling are modelled alike in both models: a
    # beam mode at a lumped mode's frequency (to 1e-9) is paired with it, whatever the order
    # (the k-th with the k-th crossed two pairs near 470 Hz)
    beam = modes.natural_frequency
    same = [(i, f) for i, b in enumerate(beam) for f in lumped[1:] if abs(f - b) < 1e-9 * f]
    assert len(same) >= 4
    for i, f in same:
        assert modes.lumped_frequency[i] == f
    assert "MAC" in modes.summary().tables[-1].caption
    assert modes.throw_torsional_stiffness > 0 and modes.throw_axial_stiffness > 0
    assert modes.summary().figure("lumped_model_largest_difference").value >= 0.0


def test_the_tvc_shows_the_crankshafts_rows(session):
    tvc = session.tvc(passage=False, conditions=("normal",))
    rows = [v.to_dict() for v in session.crankshaft().summary_verdicts()]
    assert [v.to_dict() for v in tvc.verdicts[-len(rows) :]] == rows
    assert any("UR M53" in n for n in tvc.notes)
    assert tvc.passed == (all(v.passed for v in tvc.verdicts))


def test_without_a_crankshaft_or_a_torsional_model():
    engine = crankdyn.Engine.example("inline6-diesel")
    with pytest.raises(InputError) as info:
        crankdyn.Analysis(engine).crankshaft()
    assert info.value.key == "[crankshaft]"
    marine = crankdyn.Engine.example("marine-propulsion")
    alone = crankdyn.Analysis(dataclasses.replace(marine, torsion=None)).crankshaft()
    assert not alone.torsion_given and any("no torsional stress" in n for n in alone.notes)
