"""The forced response in blocks of speeds (issue 33: memory bounded by blocks of speeds).

A sweep evaluates its speeds in blocks whose working arrays fit a memory budget
(:data:`crankdyn.defaults.RESPONSE_BLOCK_MEMORY`, :meth:`crankdyn.torsion.sweep.Sweep.
block_size`). Every speed is solved and synthesised on its own, so the block size must never
change a number: the resolved response of the marine example (a load-dependent coupling, a
damper, a gearbox) and its verdict rows are the same with one speed per block as with every
speed in one block. The memory of an evaluation is then the arrays it keeps plus one block's
working arrays, whatever the number of speeds (tracemalloc: numpy reports its allocations to
it), where all speeds in one block take several times that.
"""

import dataclasses
import tracemalloc

import numpy as np
import pytest

from crankdyn.defaults import RESPONSE_BLOCK_MEMORY
from crankdyn.errors import InputError
from crankdyn.io.catalogue import resolve_model_and_engine
from crankdyn.session import Analysis
from crankdyn.torsion import Mass, Shaft, TorsionModel
from crankdyn.torsion.excitation import UniformExcitation
from crankdyn.torsion.response import ResponseResult
from crankdyn.torsion.sweep import SYNTHESIS_BUFFERS, WORKING_BYTES, Sweep, forced_response
from crankdyn.tvc.analysis import judge


def _arrays(r: ResponseResult) -> dict[str, np.ndarray]:
    out = {}
    for f in dataclasses.fields(r):
        value = getattr(r, f.name)
        if isinstance(value, np.ndarray):
            out[f.name] = value
    return out


def test_block_size_changes_no_number():
    _model, engine = resolve_model_and_engine("marine-propulsion")
    session = Analysis(engine)
    line, excitation = session.loaded_model, session.excitation()
    whole = forced_response(line, excitation, session.speeds, session.orders, block_memory=1e12)
    fine = forced_response(line, excitation, session.speeds, session.orders, block_memory=1.0)
    assert whole.speed.size > 100  # the grid, the critical speeds and the refinement
    # the same speeds added (a reason names one of the curves that asked for a speed: between
    # curves of equal peaks, e.g. a gear's wheel and pinion, the choice is round-off's)
    assert whole.added_reasons is not None and fine.added_reasons is not None
    assert len(whole.added_reasons) == len(fine.added_reasons)
    a, b = _arrays(whole), _arrays(fine)
    assert a.keys() == b.keys()
    for name in a:  # each speed alone: the same to round-off (batched BLAS sums may differ)
        scale = float(np.nanmax(np.abs(a[name]))) if a[name].size else 0.0
        np.testing.assert_allclose(b[name], a[name], rtol=1e-9, atol=1e-12 * scale, err_msg=name)
    rows_whole, barred_whole = judge(line, whole, engine=engine)
    rows_fine, barred_fine = judge(line, fine, engine=engine)
    assert len(rows_whole) == len(rows_fine) > 0
    for u, v in zip(rows_whole, rows_fine, strict=True):
        assert (u.component, u.quantity, u.passed, u.source, u.clause) == (
            v.component,
            v.quantity,
            v.passed,
            v.source,
            v.clause,
        )
        assert v.worst == pytest.approx(u.worst, rel=1e-9, abs=0)
        assert v.limit == pytest.approx(u.limit, rel=1e-9, abs=0)
    assert [(b.start, b.end) for b in barred_whole] == pytest.approx(
        [(b.start, b.end) for b in barred_fine], rel=1e-9
    )


def _line(n: int) -> TorsionModel:
    rng = np.random.default_rng(3)
    masses = tuple(
        Mass(f"m{i}", float(rng.uniform(0.5, 2.0)), cylinders=(i + 1,) if i < 6 else ())
        for i in range(n)
    )
    shafts = tuple(
        Shaft((f"m{i}", f"m{i + 1}"), float(rng.uniform(2e6, 6e6)), loss_factor=0.03)
        for i in range(n - 1)
    )
    return TorsionModel(masses, shafts, name=f"line {n}")


def _peak(sweep: Sweep, speeds: np.ndarray) -> tuple[int, int]:
    """(bytes kept by the evaluation, peak bytes during it) by tracemalloc."""
    tracemalloc.start()
    try:
        block = sweep.evaluate(speeds)
        kept, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    del block
    return kept, peak


def test_memory_of_an_evaluation_is_bounded_by_one_block():
    model = _line(150)
    excitation = UniformExcitation(500.0, [0.0] * 6, "two-stroke")
    orders = np.arange(1.0, 13.0)
    speeds = np.linspace(20.0, 400.0, 120)
    budget = 4 * 2**20
    small = Sweep(model, excitation, orders, (), None, (), None, budget)
    large = Sweep(model, excitation, orders, (), None, (), None, 1e12)
    assert small.block_size() < speeds.size // 10 and large.block_size() >= speeds.size
    small.evaluate(speeds[:2])  # the system's own arrays made before counting
    large.evaluate(speeds[:2])
    kept, peak = _peak(small, speeds)
    # the bound of docs/benchmarks.md: the kept arrays (16 bytes per speed, order and
    # mass or element: the complex angles and torques; 16 per speed and item: the extremes
    # over the cycle) plus one block's working arrays and the synthesis's buffers
    items = 150 + 149
    stated = 16 * speeds.size * (orders.size + 1) * items + budget + SYNTHESIS_BUFFERS
    assert kept <= stated - budget - SYNTHESIS_BUFFERS + 2**16  # 64 KiB: the speeds, the lists
    assert peak <= stated
    _, peak_whole = _peak(large, speeds)
    assert peak_whole > 2 * stated  # the layout of one block exceeds the bound
    per = WORKING_BYTES * orders.size * (150 + 150 + 149)
    assert peak_whole - kept <= per * speeds.size  # WORKING_BYTES holds what it states


def test_the_budget_is_checked():
    model = _line(3)
    excitation = UniformExcitation(500.0, [0.0] * 3, "two-stroke")
    with pytest.raises(InputError, match="block_memory"):
        forced_response(model, excitation, [100.0, 200.0], [1.0], block_memory=0.0)
    assert RESPONSE_BLOCK_MEMORY == 256 * 2**20
