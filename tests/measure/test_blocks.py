"""A record analysed block by block gives the whole record's analysis (crankdyn.measure.blocks):
records split at arbitrary points (the chunks a reader gives, the blocks the analysis cuts)
against the same record analysed whole.

The two compute the same formulas in a different order, so they agree to floating-point
rounding, which the whole-record analysis sets: its mean-rotation filter keeps running sums of
t - line over the record (:func:`crankdyn.measure.angle.cycle_mean`), whose recursive summation
errs by at most u sum_k |S_k| <= u n^2 max|x| (N. J. Higham, *Accuracy and Stability of
Numerical Algorithms*, 2nd ed., SIAM 2002, section 4.2), in each of its four passes. The
tolerances below are that bound, as an angle (times the speed) relative to the largest order:
about 1e-9 for a steady record (t - line is the vibration's time, 1e-5 s), about 1e-4 for a
run-up (t - line is the speed trend's, a tenth of a second; the differences found are 1e-8).
With the running sums exact (integers), a run-up's blocks agree with the whole to 1e-9 too.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import crankdyn.measure.angle as angle
from crankdyn.measure.orders import order_analysis
from crankdyn.measure.records import PulseRecord
from crankdyn.measure.signals import PulseTrain
from crankdyn.measure.synthetic import PrescribedMotion, synthetic_pulses
from tests.conftest import fuzz_examples

RPM = 30.0 / math.pi
ORDERS = np.array([0.5, 1.5, 3.0, 6.0])
X = np.array([1e-3, 2e-3j, 5e-4, 3e-3 * np.exp(0.4j)])
U = 2.0**-53  # the unit roundoff of float64
BLOCK_MIN = 1104  # twice the pad of a 60-tooth wheel's blocks (crankdyn.measure.blocks.layout)


def _errors():
    rng = np.random.default_rng(3)
    e = rng.normal(0.0, 1e-3, 60)
    return e - e.mean()


def _steady(reference_every=2, **kw):
    motion = PrescribedMotion(1500 / RPM, 0.0, ORDERS, X)
    return synthetic_pulses(motion, 60, 6.0, reference_every=reference_every, jitter=2e-8, **kw)


STEADY = _steady(reference_every=1, tooth_errors=_errors(), clock=1e-8)
KEEP = np.arange(STEADY.times.size) % 60 < 58  # a 60-2 wheel
RECORDS = {
    "marks every cycle": (_steady(), {}),
    "marks every revolution, tooth errors found in the record": (
        STEADY,
        {"tooth_correction": "self", "reference_angle": 0.4},
    ),
    "tooth errors given": (STEADY, {"tooth_correction": _errors()}),
    "60-2 wheel": (PulseTrain(STEADY.times[KEEP], 60), {}),
    "60-2 wheel, tooth errors found": (
        PulseTrain(STEADY.times[KEEP], 60),
        {"tooth_correction": "self"},
    ),
    "dropped pulses": (
        PulseTrain(np.delete(STEADY.times, [500, 501, 2000, 8000]), 60, reference=STEADY.reference),
        {},
    ),
    "no mark": (PulseTrain(STEADY.times, 60), {}),
}


def _time_bound(train: PulseTrain) -> float:
    """Higham's bound on the rounding of the whole-record filter's times (s; module
    docstring): four passes, each window the difference of two running sums of n terms."""
    t = train.times
    n = t.size
    line = t[0] + (t[-1] - t[0]) / (n - 1) * np.arange(n)
    return float(4 * 2 * U * n**2 * np.max(np.abs(t - line)) / 120)


def _bound(train: PulseTrain, result) -> float:
    """:func:`_time_bound` as an angle (times the speed), a fraction of the largest order."""
    speed = 2 * math.pi / 60 / np.median(np.diff(train.times))
    return float(_time_bound(train) * speed / np.max(result.amplitude))


def _coefficients(result):
    """The complex orders of every cycle (steady) or window (tracking) and of the result."""
    per = result.cycle_coefficients if result.kind == "steady" else result.window_coefficients
    return np.concatenate([per.ravel(), np.ravel(result.coefficients)])


def _assert_same(whole, blocked, tolerance, speed=1e-12):
    assert type(blocked) is type(whole)
    assert blocked.notes == whole.notes and blocked.reference == whole.reference
    assert blocked.domain is None and blocked.envelope is not None
    scale = float(np.max(whole.amplitude))
    a, b = _coefficients(whole), _coefficients(blocked)
    assert a.shape == b.shape
    assert np.max(np.abs(a - b)) <= tolerance * scale
    assert blocked.speed == pytest.approx(whole.speed, rel=speed)
    if whole.kind == "steady":
        assert blocked.cycles == whole.cycles
        np.testing.assert_allclose(blocked.cycle_vibration, whole.cycle_vibration, rtol=0,
                                   atol=tolerance * scale)  # fmt: skip
        # (the origin of the crank angle follows the marks, located in the tooth errors found)
        np.testing.assert_allclose(blocked.cycle_angle, whole.cycle_angle, rtol=0, atol=1e-12)
        assert blocked.speed_min == pytest.approx(whole.speed_min, rel=1e-12)
    else:
        np.testing.assert_allclose(blocked.window_speed, whole.window_speed, rtol=speed)
    if whole.tooth_errors is not None:
        np.testing.assert_allclose(blocked.tooth_errors, whole.tooth_errors, rtol=0,
                                   atol=tolerance * scale)  # fmt: skip


WHOLE = {name: order_analysis(train, orders=ORDERS, **kw) for name, (train, kw) in RECORDS.items()}


@pytest.mark.parametrize("name", list(RECORDS))
def test_steady_records_in_blocks_are_the_whole_record(name):
    """Each record in chunks of 777, 5000 and 123 pulses and blocks of 2500 tooth positions."""
    train, kw = RECORDS[name]
    whole = WHOLE[name]
    record = PulseRecord.from_train(train, chunk=[777, 5000, 123])
    blocked = order_analysis(record, orders=ORDERS, block=2500, **kw)
    _assert_same(whole, blocked, _bound(train, whole))


@pytest.mark.parametrize("name", ["marks every cycle", "tooth errors given"])
def test_steady_analysis_in_blocks_keeps_only_the_moments(name):
    """``analysis="steady"`` in blocks keeps no per-cycle orders (its memory does not grow with
    them), only their running mean and scatter: the whole record's, which computes them from
    every cycle's orders at once (numpy's mean, then the RMS deviation from it)."""
    train, kw = RECORDS[name]
    whole = order_analysis(train, orders=ORDERS, analysis="steady", **kw)
    record = PulseRecord.from_train(train, chunk=[777, 5000, 123])
    blocked = order_analysis(record, orders=ORDERS, block=2500, analysis="steady", **kw)
    assert blocked.cycle_coefficients is None and whole.cycle_coefficients is not None
    bound = _bound(train, whole) * float(np.max(whole.amplitude))
    assert np.max(np.abs(blocked.coefficients - whole.coefficients)) <= bound
    np.testing.assert_allclose(blocked.scatter, whole.scatter, rtol=0, atol=bound)
    per = whole.cycle_coefficients
    scatter = np.sqrt(np.mean(np.abs(per - per.mean(axis=0)) ** 2, axis=0))
    np.testing.assert_allclose(whole.scatter, scatter, rtol=1e-14, atol=0)
    assert (blocked.speed_min, blocked.speed_max) == pytest.approx(
        (whole.speed_min, whole.speed_max), rel=1e-12
    )


@settings(max_examples=fuzz_examples(12))
@given(
    name=st.sampled_from(sorted(RECORDS)),
    chunks=st.lists(st.integers(1, 30_000), min_size=1, max_size=6),
    block=st.integers(BLOCK_MIN, 8_000),  # (the records hold 8,640 to 9,000 pulses)
)
def test_records_split_anywhere(name, chunks, block):
    """Any chunks and any block size: the same analysis."""
    train, kw = RECORDS[name]
    blocked = order_analysis(
        PulseRecord.from_train(train, chunk=chunks), orders=ORDERS, block=block, **kw
    )
    _assert_same(WHOLE[name], blocked, _bound(train, WHOLE[name]))


RUNUP = synthetic_pulses(
    PrescribedMotion(1500 / RPM, 300 / RPM, ORDERS, X), 60, 8.0, reference_every=2, jitter=2e-8
)


@pytest.mark.parametrize(
    "options",
    [{}, {"window": "uniform", "window_cycles": 1}, {"window": "uniform", "window_cycles": 3}],
)
def test_run_up_in_blocks_is_the_whole_record(options):
    """Order tracking: every window, the bins, the resonances' inputs; within the whole
    record's own rounding (Higham's bound, module docstring)."""
    whole = order_analysis(RUNUP, orders=ORDERS, **options)
    blocked = order_analysis(
        PulseRecord.from_train(RUNUP, chunk=4321), orders=ORDERS, block=3000, **options
    )
    bound = _bound(RUNUP, whole)
    assert 1e-6 < bound < 1e-3  # loose: the running sums of a speed trend
    # a window's speed: its angle over the filter's times, rounded as above, c cycles apart
    window = options.get("window_cycles", 4) * 4 * math.pi / np.max(whole.window_speed)
    _assert_same(whole, blocked, bound, speed=2 * _time_bound(RUNUP) / window)
    np.testing.assert_array_equal(blocked.windows, whole.windows)


def _exact_cycle_mean(x, length):
    """:func:`crankdyn.measure.angle.cycle_mean` with exact running sums: every float as an
    integer multiple of 2**least (the least exponent among them), summed in Python integers,
    each window's total rounded once."""
    x = np.asarray(x, dtype=float)
    mantissa, exponent = np.frexp(x)
    least = int(np.min(exponent)) - 54  # one bit more for the half weights
    ints = np.array(
        [
            int(m * 2**53) << (e - 53 - least)
            for m, e in zip(mantissa.tolist(), exponent.tolist(), strict=True)
        ],
        dtype=object,
    )
    s = np.concatenate([np.array([0], dtype=object), np.cumsum(ints)])
    h, n = length // 2, x.size
    c = np.arange(h, n - h)
    if length % 2:
        total = s[c + h + 1] - s[c - h]
    else:
        total = s[c + h] - s[c - h + 1] + (ints[c - h] + ints[c + h]) // 2  # exact: even ints
    return np.array([math.ldexp(float(v), least) for v in total]) / length, h


def test_run_up_in_blocks_with_exact_sums(monkeypatch):
    """With the filter's running sums exact, the whole record and its blocks agree to the
    rounding of the times themselves (u t Omega / A: 1e-10 here) times the splines'
    amplification: 1e-9 of the largest order."""
    monkeypatch.setattr(angle, "cycle_mean", _exact_cycle_mean)
    whole = order_analysis(RUNUP, orders=ORDERS)
    blocked = order_analysis(PulseRecord.from_train(RUNUP, chunk=4321), orders=ORDERS, block=3000)
    _assert_same(whole, blocked, 1e-9)


def test_long_pulse_trains_are_analysed_in_blocks():
    """A pulse train longer than the block is analysed block by block (no domain, the
    envelope instead), the record read in chunks whatever its source."""
    train, _ = RECORDS["marks every cycle"]
    result = order_analysis(train, orders=ORDERS, block=4000)
    assert result.domain is None and result.envelope.angle.size == result.cycles
    assert np.all(result.envelope.speed_low <= result.envelope.speed_high)
    assert np.all(result.envelope.vibration_low < result.envelope.vibration_high)
    whole = WHOLE["marks every cycle"]
    assert np.max(whole.domain.vibration) == pytest.approx(
        np.max(result.envelope.vibration_high), rel=1e-9
    )
    assert order_analysis(train, orders=ORDERS).domain is not None  # the default block: whole


def test_marks_read_after_their_pulses_are_located():
    """Marks that come with the last chunk (after the pulses around them) are located by one
    more reading of the record: the same analysis."""
    train, _ = RECORDS["marks every cycle"]

    def read():
        from crankdyn.measure.records import PulseChunk

        for start in range(0, train.times.size, 3000):
            last = start + 3000 >= train.times.size
            yield PulseChunk(train.times[start : start + 3000],
                             reference=train.reference if last else None)  # fmt: skip

    blocked = order_analysis(PulseRecord(read, 60, "late"), orders=ORDERS, block=2500)
    _assert_same(WHOLE["marks every cycle"], blocked, _bound(train, WHOLE["marks every cycle"]))
