"""Pulse trains and speed signals: checks, repairs and conversions; bad input on one line."""

import math

import numpy as np
import pytest

from crankdyn.errors import InputError
from crankdyn.measure.orders import order_analysis
from crankdyn.measure.signals import PulseTrain, SpeedSignal, prepare_pulses
from crankdyn.measure.synthetic import PrescribedMotion, synthetic_pulses

RPM = 30.0 / math.pi


def _steady(seconds=1.0, teeth=60, **kw):
    motion = PrescribedMotion(1500 / RPM, 0.0, np.array([3.0]), np.array([2e-3]))
    return synthetic_pulses(motion, teeth, seconds, **kw)


def test_non_increasing_times_name_the_sample():
    times = np.array([0.0, 0.001, 0.002, 0.002, 0.004])
    with pytest.raises(InputError, match=r"sample 4 has 0\.002 s after 0\.002 s"):
        PulseTrain(times, 60)
    with pytest.raises(InputError, match="line 6 has"):
        PulseTrain(times, 60, lines=np.arange(3, 8))


@pytest.mark.parametrize("teeth", [0, 3, 2.5, True])
def test_teeth_must_be_a_whole_number_of_at_least_four(teeth):
    with pytest.raises(InputError):
        PulseTrain(np.arange(10.0), teeth)


def test_spurious_pulse_is_an_error_naming_its_place():
    t = _steady().times
    bad = np.sort(np.append(t, 0.5 * (t[100] + t[101]) + 1e-6))
    with pytest.raises(InputError, match="a spurious pulse: the interval ending at sample 102"):
        prepare_pulses(PulseTrain(bad, 60))


def test_dropped_pulses_interpolated_and_said():
    t = _steady().times
    prep = prepare_pulses(PulseTrain(np.delete(t, [200, 201, 900]), 60))
    assert prep.times.size == t.size
    assert np.count_nonzero(prep.filled) == 3
    assert prep.notes == ("3 dropped pulses (before sample 201, sample 899) interpolated",)
    assert np.max(np.abs(prep.times - t)) < 1e-7  # the interpolated times


def test_three_dropped_in_a_row_is_an_error():
    t = _steady().times
    with pytest.raises(InputError, match="3 pulses are missing before sample 201"):
        prepare_pulses(PulseTrain(np.delete(t, [200, 201, 202]), 60))


def test_too_many_dropped_pulses_is_an_error():
    t = _steady().times
    with pytest.raises(InputError, match="too many to interpolate safely"):
        prepare_pulses(PulseTrain(np.delete(t, np.arange(50, 1400, 50)), 60))


def test_an_interval_that_is_not_a_whole_number_of_pitches_is_an_error():
    t = _steady().times.copy()
    t[300:] += 0.7 * (t[1] - t[0])
    with pytest.raises(InputError, match=r"1\.70 times its neighbours'"):
        prepare_pulses(PulseTrain(t, 60))


def test_reference_that_does_not_divide_is_an_error():
    train = _steady(teeth=60, reference_every=1)
    with pytest.raises(InputError, match="which --teeth 58 does not divide"):
        prepare_pulses(PulseTrain(train.times, 58, reference=train.reference))


def test_reference_with_a_missing_pulse_between_marks():
    train = _steady(teeth=60, reference_every=1)
    bad = np.delete(train.times, np.arange(100, 400, 100))  # three isolated pulses
    bad = np.delete(bad, [600])  # and another whose gap is hidden by a speed change
    prep = prepare_pulses(PulseTrain(bad, 60, reference=train.reference))
    assert prep.reference_period == 60
    assert np.allclose(np.diff(prep.reference_index), 60.0, atol=1e-3)


def test_reference_count_mismatch_names_the_marks():
    train = _steady(teeth=60, reference_every=1)
    ref = train.reference.copy()
    ref[3] += 3 * (train.times[1] - train.times[0])  # a mark three teeth late
    with pytest.raises(InputError, match=r"63\.0 pulses between the references at .* expected 60"):
        prepare_pulses(PulseTrain(train.times, 60, reference=ref))


def test_missing_tooth_wheel_detected():
    train = _steady(seconds=1.0, teeth=36, reference_every=1, tooth_offset=0.0)
    k = np.round(np.interp(train.times, train.reference, np.arange(train.reference.size)) * 36)
    keep = (k.astype(int) % 36) != 35
    prep = prepare_pulses(PulseTrain(train.times[keep], 36))
    assert prep.missing_tooth
    assert prep.reference_period == 36
    assert "a 36-1 wheel" in prep.notes[0]


def test_speed_signal_to_pulses_at_constant_speed_plus_a_sine():
    """omega = W (1 + e cos(w t)) integrates to theta = W t + W e sin(w t) / w exactly; the
    pulse times solve theta = 2 pi k / N."""
    big_w, e, w = 150.0, 0.01, 2 * math.pi * 40.0
    t = np.linspace(0.0, 1.0, 20001)
    signal = SpeedSignal(t, big_w * (1 + e * np.cos(w * t)))
    pulses = signal.to_pulses(90)
    theta = big_w * pulses.times + big_w * e * np.sin(w * pulses.times) / w
    assert np.max(np.abs(theta - 2 * math.pi * np.arange(pulses.times.size) / 90)) < 1e-9


def test_speed_signal_must_be_positive():
    with pytest.raises(InputError, match="the speed must be positive: sample 3"):
        SpeedSignal(np.arange(5.0), np.array([1.0, 2.0, 0.0, 1.0, 1.0]))


def test_short_record_is_an_error():
    with pytest.raises(InputError, match="at least 6 are needed"):
        order_analysis(_steady(seconds=0.3))


@pytest.mark.parametrize(
    ("kw", "message"),
    [
        ({"orders": [30.0]}, "at or above the wheel's Nyquist order 30"),
        ({"orders": [0.25]}, "does not fit the four-stroke cycle"),
        ({"analysis": "fast"}, "expected one of auto, steady, tracking"),
        ({"window": "hann", "window_cycles": 1}, "a Hann window needs at least 2 cycles"),
        ({"tooth_correction": "mean"}, "expected self, a calibration record"),
        ({"cycle": "six-stroke"}, "expected four-stroke or two-stroke"),
    ],
)
def test_bad_analysis_options(kw, message):
    with pytest.raises(InputError, match=message):
        order_analysis(_steady(), **kw)
