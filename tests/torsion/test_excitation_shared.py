"""The engine excitation's basis spectra are computed once per engine (issue 39, item 5: what
does not change between candidates is reused): excitations of equal engines, whatever their
torsional model or misfiring cylinders, share them; a different firing order does not; the
shared harmonics equal those computed from nothing, to the bit."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import crankdyn.torsion.excitation as excitation
from crankdyn.io.catalogue import resolve_model_and_engine
from crankdyn.torsion.excitation import SHARED_ENGINES, EngineExcitation

SPEEDS = np.linspace(30.0, 80.0, 7)  # rad/s
ORDERS = np.arange(0.5, 12.01, 0.5)


@pytest.fixture
def engine():
    _model, engine = resolve_model_and_engine("marine-propulsion")
    return engine


def _fresh(engine, misfire=()):
    """The harmonics computed with no shared spectra (the store emptied first)."""
    excitation._SHARED.clear()
    return EngineExcitation(engine, engine.torsion.excitation, misfire).parts(SPEEDS, ORDERS)


def test_equal_engines_share_the_spectra_whatever_their_model(engine):
    expected = _fresh(engine)
    expected_misfire = _fresh(engine, (2,))
    excitation._SHARED.clear()
    _model, again = resolve_model_and_engine("marine-propulsion")  # parsed afresh: equal, new
    other_line = dataclasses.replace(again, torsion=None)
    a = EngineExcitation(engine, engine.torsion.excitation)
    b = EngineExcitation(other_line, engine.torsion.excitation, (2,))
    gas, inertia = a.parts(SPEEDS, ORDERS)
    assert b._trace_spectrum is a._trace_spectrum  # computed once, for both
    assert b._inertia_spectrum is a._inertia_spectrum
    assert not a._trace_spectrum.flags.writeable
    gas_b, inertia_b = b.parts(SPEEDS, ORDERS)
    got = (gas, inertia, gas_b, inertia_b)
    for mine, want in zip(got, (*expected, *expected_misfire), strict=True):
        assert np.array_equal(mine, want)  # the same numbers as from nothing, to the bit


def test_another_firing_order_has_its_own_spectra(engine):
    excitation._SHARED.clear()
    order = (1, 4, 2, 6, 3, 5)
    cylinders = dataclasses.replace(engine.cylinders, firing_order=order, throw_angles=None)
    other = dataclasses.replace(engine, cylinders=cylinders)
    a = EngineExcitation(engine, engine.torsion.excitation)
    b = EngineExcitation(other, engine.torsion.excitation)
    assert b._trace_spectrum is not a._trace_spectrum
    assert not np.allclose(a.parts(SPEEDS, ORDERS)[0], b.parts(SPEEDS, ORDERS)[0])
    assert len(excitation._SHARED) == 2


def test_the_process_keeps_a_bounded_number_of_engines(engine):
    excitation._SHARED.clear()
    for k in range(SHARED_ENGINES + 3):
        other = dataclasses.replace(engine, crankcase_pressure=1e5 + k)
        EngineExcitation(other, engine.torsion.excitation)._inertia_spectrum  # noqa: B018
    assert len(excitation._SHARED) == SHARED_ENGINES
