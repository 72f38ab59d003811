"""Measured torsional vibration: order analysis of synthetic torsiograph signals whose content is
known exactly (issue 20).

Every signal is built from a prescribed angular motion theta = psi + sum_q Re(X_q exp(i q psi))
(:mod:`crankdyn.measure.synthetic`: a steady speed or a constant acceleration, the pulse times
solved to 1e-13 rad), then spoiled as a real torsiograph's would be: tooth-spacing errors of the
wheel (random, 1 mrad RMS, plus an eccentricity of 2 mrad), timing jitter (20 ns RMS) and the
quantisation of a 100 MHz counter. The analysis must return the prescribed amplitudes within 1 %
and phases within 1 deg, and the damping ratio of a single-mode resonance within 2 %
(the issue's tolerances; the achieved errors are a factor of ten or more smaller, the remainder
being the timing noise and, in run-ups, the change of speed within a window).
"""

import math

import numpy as np
import pytest

from crankdyn.measure.orders import order_analysis
from crankdyn.measure.signals import PulseTrain, SpeedSignal
from crankdyn.measure.synthetic import PrescribedMotion, synthetic_pulses
from crankdyn.torsion import Mass, Shaft, TorsionModel
from crankdyn.torsion.excitation import UniformExcitation

RPM = 30.0 / math.pi
TEETH = 60
ORDERS = np.array([0.5, 1.0, 1.5, 2.0, 3.0, 4.5, 6.0, 9.0])
AMPLITUDES = np.array([1.0, 0.5, 3.0, 0.8, 2.0, 4.0, 10.0, 0.6]) * 1e-3
PHASES = np.radians([10.0, -120.0, 75.0, 170.0, -45.0, 30.0, -160.0, 95.0])
X = AMPLITUDES * np.exp(1j * PHASES)
JITTER, CLOCK = 20e-9, 1e-8


def _wheel_errors():
    rng = np.random.default_rng(7)
    j = np.arange(TEETH)
    errors = rng.normal(0.0, 1e-3, TEETH) + 2e-3 * np.sin(2 * math.pi * j / TEETH + 0.4)
    return errors - errors.mean()


def _check(result, amplitude_tol=0.01, phase_tol_deg=1.0, mask=None):
    got = result.coefficients
    mask = np.ones(ORDERS.size, dtype=bool) if mask is None else mask
    rel = np.abs(np.abs(got) - AMPLITUDES) / AMPLITUDES
    phase = np.degrees(np.abs(np.angle(got / X)))
    assert np.all(rel[mask] < amplitude_tol), rel
    assert np.all(phase[mask] < phase_tol_deg), phase


def test_steady_orders_exact_without_noise():
    """The method itself (no noise, a perfect wheel): errors at the level of the resampling."""
    motion = PrescribedMotion(1500 / RPM, 0.0, ORDERS, X)
    result = order_analysis(synthetic_pulses(motion, TEETH, 2.0, reference_every=2), orders=ORDERS)
    assert result.kind == "steady"
    assert result.speed * RPM == pytest.approx(1500.0, rel=1e-9)
    _check(result, amplitude_tol=1e-3, phase_tol_deg=0.02)


def test_steady_orders_with_wheel_errors_jitter_and_quantisation_calibrated():
    """Tooth errors removed with a calibration record of the same wheel (a coast-down without
    vibration, 1200 to 600 rpm), then the measurement at 1500 rpm."""
    errors = _wheel_errors()
    motion = PrescribedMotion(1500 / RPM, 0.0, ORDERS, X)
    signal = synthetic_pulses(
        motion,
        TEETH,
        3.0,
        tooth_errors=errors,
        reference_every=2,
        jitter=JITTER,
        clock=CLOCK,
        seed=1,
    )
    raw = order_analysis(signal, orders=ORDERS)
    assert np.max(np.abs(np.abs(raw.coefficients) - AMPLITUDES) / AMPLITUDES) > 0.05  # spoiled
    quiet = PrescribedMotion(1200 / RPM, -200 / RPM, ORDERS, 0.0 * X)
    calibration = synthetic_pulses(
        quiet,
        TEETH,
        3.0,
        tooth_errors=errors,
        reference_every=2,
        jitter=JITTER,
        clock=CLOCK,
        seed=2,
    )
    result = order_analysis(signal, orders=ORDERS, tooth_correction=calibration)
    _check(result)
    # the wheel's errors themselves, recovered from the calibration record
    assert np.max(np.abs(result.tooth_errors - errors)) < 2e-5


def test_steady_half_orders_with_the_records_own_tooth_correction():
    """Without a calibration record the mean over revolutions removes the wheel's errors from
    the half orders (they cancel over two revolutions); integer orders and tooth errors cannot
    be told apart in one steady record, so only the half orders are checked, on a record whose
    integer orders are small (the integer orders' removal at the tooth angles leaves a
    cross-talk of about m A_m in the half orders, which the note bounds)."""
    small = np.where(ORDERS % 1.0 == 0.0, 0.05, 1.0) * X
    motion = PrescribedMotion(1500 / RPM, 0.0, ORDERS, small)
    signal = synthetic_pulses(
        motion,
        TEETH,
        3.0,
        tooth_errors=_wheel_errors(),
        reference_every=2,
        jitter=JITTER,
        clock=CLOCK,
        seed=3,
    )
    result = order_analysis(signal, orders=ORDERS, tooth_correction="self")
    half = ORDERS % 1.0 == 0.5
    _check(result, mask=half)
    (note,) = [n for n in result.notes if "integer orders" in n]
    # a large integer order: the cross-talk exceeds 1 % and the note says so
    loud = order_analysis(
        synthetic_pulses(
            PrescribedMotion(1500 / RPM, 0.0, ORDERS, X), TEETH, 3.0, reference_every=2, seed=3
        ),
        orders=ORDERS,
        tooth_correction="self",
    )
    got = loud.coefficients[half]
    worst = float(np.max(np.abs(np.abs(got) - AMPLITUDES[half]) / AMPLITUDES[half]))
    (note,) = [n for n in loud.notes if "cross-talk" in n]
    bound = float(note.split("up to ")[1].split("%")[0]) / 100
    assert 0.01 < worst < bound


@pytest.mark.parametrize(("start", "rate"), [(1200.0, 200.0), (2400.0, -200.0)])
def test_run_up_and_run_down_orders(start, rate):
    """Constant order amplitudes over a 200 rpm/s sweep: every window recovers them."""
    motion = PrescribedMotion(start / RPM, rate / RPM, ORDERS, X)
    signal = synthetic_pulses(
        motion, TEETH, 5.0, reference_every=2, jitter=JITTER, clock=CLOCK, seed=4
    )
    result = order_analysis(signal, orders=ORDERS)
    assert result.kind == ("run-up" if rate > 0 else "run-down")
    w = result.window_coefficients
    rel = np.abs(np.abs(w) - AMPLITUDES) / AMPLITUDES
    assert np.max(rel) < 0.01
    assert np.max(np.degrees(np.abs(np.angle(w / X)))) < 1.0
    # the first and last two cycles feed the mean-rotation filter, and a window's speed is its
    # mean over 4 cycles: the windows span the sweep less about 4 cycles at either end
    cycle = 2 * 60 / min(start, start + 5 * rate)  # s, at the slow end
    margin = 6.0 * abs(rate) * cycle
    assert result.window_speed.min() * RPM < min(start, start + 5 * rate) + margin
    assert result.window_speed.max() * RPM > max(start, start + 5 * rate) - margin


def test_speed_signal_orders():
    """A sampled speed (20 kHz) of the same motion, integrated to the angle: the orders within
    1 % and 1 deg (the reference column fixes the phase)."""
    motion = PrescribedMotion(1500 / RPM, 0.0, ORDERS, X)
    t = np.arange(0.0, 3.0, 1.0 / 20000.0)
    psi = motion.speed * t
    slope = np.sum(np.real(1j * ORDERS * X * np.exp(1j * psi[:, None] * ORDERS)), axis=1)
    speed = motion.speed * (1.0 + slope)
    marks = motion.time_at(motion.solve(4 * math.pi * np.arange(1, 20)))
    result = order_analysis(SpeedSignal(t, speed, reference=marks), orders=ORDERS, resolution=120)
    _check(result)


def test_missing_tooth_wheel_orders():
    """A 60-2 wheel: the gap marks the revolution (the crank angle of the first tooth after it
    given) and the two missing pulses are interpolated."""
    motion = PrescribedMotion(1500 / RPM, 0.0, ORDERS, X)
    full = synthetic_pulses(
        motion, TEETH, 3.0, reference_every=1, tooth_offset=0.0, jitter=JITTER, clock=CLOCK, seed=5
    )
    # tooth k sits at 2 pi k / N from the mark: drop teeth 58 and 59 of every revolution
    ref = full.reference
    k = np.round(np.interp(full.times, ref, np.arange(ref.size)) * TEETH).astype(int)
    keep = (k % TEETH) < TEETH - 2
    signal = PulseTrain(full.times[keep], TEETH)
    first_after_gap = full.times[keep][np.flatnonzero(np.diff(np.flatnonzero(keep)) > 1)[0] + 1]
    # the crank angle of that tooth: the revolution mark (0) of its revolution
    result = order_analysis(signal, orders=ORDERS, analysis="steady")
    assert any("60-2 wheel" in n for n in result.notes)
    # the cycle starts at the first mark: half orders may come out 180 deg off
    turn = round(float(np.interp(first_after_gap, ref, np.arange(ref.size))))
    flip = np.where((ORDERS % 1.0 == 0.5) & (turn % 2 == 1), -1.0, 1.0)
    got = result.coefficients * flip
    assert np.all(np.abs(np.abs(got) - AMPLITUDES) / AMPLITUDES < 0.01)
    assert np.all(np.degrees(np.abs(np.angle(got / X))) < 1.0)


def test_dropped_pulses_interpolated():
    motion = PrescribedMotion(1500 / RPM, 0.0, ORDERS, X)
    full = synthetic_pulses(
        motion, TEETH, 3.0, reference_every=2, jitter=JITTER, clock=CLOCK, seed=6
    )
    keep = np.ones(full.times.size, dtype=bool)
    keep[[1000, 2500, 2501]] = False  # one pulse, then two in a row
    signal = PulseTrain(full.times[keep], TEETH, reference=full.reference)
    result = order_analysis(signal, orders=ORDERS)
    assert any("3 dropped pulses" in n and "interpolated" in n for n in result.notes)
    _check(result)


# ---- damping of a single-mode resonance ---------------------------------------------------------
J, K_SHAFT, ZETA = 0.05, 1.0e5, 0.02
OMEGA_N = math.sqrt(K_SHAFT / J)


def _single_mode(omega):
    """Order 6 of a viscously damped single mass under a constant 1 N m torque (rad)."""
    w = 6.0 * np.asarray(omega)
    c = 2.0 * ZETA * math.sqrt(K_SHAFT * J)
    six = 1.0 / (K_SHAFT - J * w * w + 1j * c * w)
    return np.stack([np.full_like(six, 2e-4), six * 40.0], axis=1)  # order 3 steady beside it


@pytest.mark.parametrize(("start", "rate"), [(1900.0, 60.0), (2450.0, -60.0)])
def test_single_mode_damping_recovered(start, rate):
    """A run-up (and a run-down) through the resonance of order 6 with an order 3 beside it:
    zeta by the single-mode fit and by the half-power bandwidth within 2 %, the natural
    frequency within 0.1 %."""
    motion = PrescribedMotion(start / RPM, rate / RPM, np.array([3.0, 6.0]), _single_mode)
    signal = synthetic_pulses(
        motion, TEETH, 550.0 / abs(rate), reference_every=2, jitter=JITTER, clock=CLOCK, seed=8
    )
    result = order_analysis(signal, orders=[3.0, 6.0])
    (fit,) = result.resonances
    assert fit.order == 6.0
    assert fit.damping == pytest.approx(ZETA, rel=0.02)
    assert fit.half_power_damping == pytest.approx(ZETA, rel=0.02)
    assert fit.natural_frequency == pytest.approx(OMEGA_N, rel=1e-3)
    peak = 40.0 / (2.0 * ZETA * math.sqrt(1 - ZETA**2) * K_SHAFT)
    assert fit.peak_amplitude == pytest.approx(peak, rel=0.01)


def test_loss_factor_written_back_reproduces_the_measured_resonance():
    """A single grounded mass with hysteretic damping eta = 0.04 is "measured"; analysed with
    the same model given eta = 0.02, the loss factor written back is 0.04 within 2 %, and the
    model's peak with it matches the measured peak."""

    def model(eta):
        return TorsionModel(
            masses=(Mass("disc", J, cylinders=(1,)),),
            shafts=(Shaft(("ground", "disc"), K_SHAFT, loss_factor=eta),),
        )

    excitation = UniformExcitation(40.0, [0.0], "four-stroke")
    truth = model(0.04)
    from crankdyn.torsion.sweep import forced_response

    grid = np.arange(1950.0, 2550.0, 2.0) / RPM
    response = forced_response(truth, excitation, grid, [6.0], resolve=False).mass_response[:, 0, 0]
    from scipy.interpolate import CubicSpline

    spline = CubicSpline(grid, response[:, None], axis=0)
    motion = PrescribedMotion(2000 / RPM, 50 / RPM, np.array([6.0]), spline)
    signal = synthetic_pulses(
        motion, TEETH, 9.0, reference_every=2, jitter=JITTER, clock=CLOCK, seed=9
    )
    result = order_analysis(signal, orders=[6.0]).with_model(model(0.02), excitation, "disc")
    estimate = result.comparison.damping
    assert estimate.loss_factor == pytest.approx(0.04, rel=0.02)
    assert estimate.damping == pytest.approx(0.02, rel=0.02)  # zeta = eta / 2 at resonance
    assert estimate.corrected_peak == pytest.approx(estimate.measured_peak, rel=0.01)
    assert estimate.model_peak > 1.5 * estimate.measured_peak  # the model as given: too sharp
    assert estimate.mode_nodes == 0 and estimate.mode_frequency == pytest.approx(OMEGA_N)
