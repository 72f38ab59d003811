"""Order analysis of a torsiograph signal (analysis and results): the orders of the angular
vibration at a steady speed, and order tracking over a run-up or a run-down.

After :mod:`crankdyn.measure.angle` the vibration v(psi) is known at N equally spaced crank angles
per revolution, over whole working cycles starting on a cycle boundary. For one window of c
whole cycles (L c samples) the discrete Fourier transform gives every order of the cycle exactly
(synchronous sampling):

    V_q = (2 / (L c)) sum_j v_j exp(-i q psi_j),    v(psi) = sum_q Re( V_q exp(i q psi) ),

q = k 2 pi / (c Theta) for bin k (Theta the cycle's crank angle), so the orders 0.5, 1, 1.5, ...
of a four-stroke engine fall on bins and nothing leaks between them: the window is uniform
(rectangular), which is exact for synchronous data (a Hann window would spread each order over
its neighbours, half an order away; R. B. Randall, *Frequency Analysis*, Bruel & Kjaer 1987,
ch. 4 on windows and synchronous sampling). The phase is that of the cosine at the crank angle
psi measured from the reference mark's crank angle, the convention of the model's forced
response (:mod:`crankdyn.torsion.solvers`: theta(t) = Re(X exp(i q Omega t)), crank angle 0 at
cylinder 1's firing TDC), so measured and predicted phases compare directly.

Steady speed: the complex (synchronous) average of V_q over every whole cycle of the record,
each cycle a uniform window (noise and content not locked to the crank average out; the scatter
of the single cycles about the mean is reported).

Order tracking (run-up, run-down): one window at every cycle boundary, c cycles long (default 4,
so that windows overlap by three quarters), with a Hann window w_j = (1 - cos(2 pi j / n)) / 2
and the amplitudes divided by its coherent gain sum(w) / n = 1/2. With c >= 2 the Hann window
is still exact for stationary orders (its transform occupies only the bins next to each order,
which are not orders), while the leakage of an order whose amplitude changes within the window
(a resonance passed during the run-up) into its neighbours falls off as the cube of the
distance instead of linearly: in the built-in run-up, orders above 0.5 mrad come out within
0.5 % next to the 16 mrad order-6 resonance with Hann over 4 cycles, 6 % with uniform one-cycle
windows (Randall 1987, ch. 4; F. J. Harris, "On the use of windows for harmonic analysis with
the discrete Fourier transform", *Proc. IEEE* 66 (1978) 51-83). The window's speed is the crank
angle it spans over the time the mean rotation takes. The windows are complex-averaged in speed
bins (default 10 rpm) for the table, CSV and JSON; resonance peaks and damping fits use every
window (resolved data, independent of the bins). Orders must lie below the wheel's Nyquist order
N/2: the teeth are the samples, and content above N/2 aliases (no filter can prevent it after
the wheel).

The synthesised amplitude is half the peak-to-peak of sum_q Re(V_q exp(i q psi)) over the
analysed orders, found exactly as for the model (:func:`crankdyn.torsion.synthesis.half_range`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.constants import CYCLE_ANGLE, DEG, RPM
from crankdyn.errors import InputError
from crankdyn.measure.angle import (
    AngleDomain,
    angle_domain,
    cycle_length,
    too_short,
    tooth_numbering,
)
from crankdyn.measure.blocks import (
    BLOCK,
    Envelope,
    blocked_analysis,
    blocked_pattern,
    corrected_marks,
    gathered,
)
from crankdyn.measure.figures import (
    MEASURED_FIGURES,
    largest_per_order_table,
    resonance_table,
)
from crankdyn.measure.records import PulseRecord
from crankdyn.measure.resonance import ResonanceFit, fit_resonance
from crankdyn.measure.scan import SEGMENT, ScannedRecord, scan_record
from crankdyn.measure.signals import PreparedPulses, PulseTrain, SpeedSignal, prepare_pulses
from crankdyn.measure.windows import Windows, window_coefficients
from crankdyn.results import Result, array, column, freeze, scalar
from crankdyn.summary import SummaryTable
from crankdyn.torsion.orders import check_orders, fundamental_order, harmonic_index
from crankdyn.torsion.synthesis import half_range

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from crankdyn.torsion.excitation import Excitation
    from crankdyn.torsion.model import TorsionModel

__all__ = [
    "ANALYSES",
    "CACHE",
    "DEFAULT_BIN",
    "STEADY_LIMIT",
    "WINDOWS",
    "OrderSpectrum",
    "OrderTracking",
    "default_orders",
    "find_resonances",
    "order_analysis",
]

ANALYSES = ("auto", "steady", "tracking")
"""The analyses :func:`order_analysis` runs."""
WINDOWS = ("hann", "uniform")
"""The windows of order tracking."""
CACHE = 1 << 22
"""A record analysed block by block is read again for each pass, unless it holds at most this
many pulses (4,194,304: 32 MiB of times), which the first reading keeps."""
DEFAULT_BIN = 10.0 / RPM
"""Default speed bin of order tracking (rad/s): 10 rpm."""
STEADY_LIMIT = 0.02
"""``auto`` treats a record as steady when its cycle speeds stay within this share of the mean."""
SIGNIFICANT = 0.05
"""A resonance is reported when its peak reaches this share of the record's largest order."""
MAX_MISFIT = 0.1
"""Largest relative RMS misfit of the single-mode fit for a reported resonance."""
_CYCLES = {"four-stroke", "two-stroke"}


def default_orders(cycle: str, teeth: int) -> np.ndarray:
    """The orders analysed by default: every order of the cycle up to 12, below N/2.

    Parameters
    ----------
    cycle : str
        ``"four-stroke"`` (orders 0.5, 1, 1.5, ...) or ``"two-stroke"`` (1, 2, ...).
    teeth : int
        Pulses per revolution N.

    Returns
    -------
    numpy.ndarray
        The orders (per revolution), ascending.

    Examples
    --------
    >>> default_orders("two-stroke", 16).tolist()
    [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0]
    >>> q = default_orders("four-stroke", 60)
    >>> q.size, float(q[0]), float(q[-1])
    (24, 0.5, 12.0)
    """
    base = fundamental_order(cycle)
    top = min(12.0, (teeth / 2.0) - base)
    count = math.floor(top / base + 1e-9)
    return base * np.arange(1, count + 1)


def _check_orders(orders: ArrayLike | None, cycle: str, teeth: int) -> np.ndarray:
    q = default_orders(cycle, teeth) if orders is None else check_orders(orders, cycle)
    high = q[q >= teeth / 2.0]
    if high.size:
        raise InputError(
            f"order {high[0]:g} is at or above the wheel's Nyquist order {teeth / 2:g} "
            f"({teeth} pulses per revolution): content there aliases",
            key="orders",
            value=float(high[0]),
        )
    if q.size == 0:
        raise InputError(f"no order of the cycle lies below {teeth / 2:g}", key="orders")
    return q


def _reference_text(
    prep: PreparedPulses | ScannedRecord, cycle: str, reference_angle: float
) -> tuple[str, list[str]]:
    notes: list[str] = []
    if prep.reference_index is None:
        notes.append(
            "no reference mark: phases are relative to the first pulse"
            + (" and the four-stroke cycle's start is arbitrary" if cycle == "four-stroke" else "")
        )
        return "first pulse", notes
    where = "the gap of the missing teeth" if prep.missing_tooth else "the reference mark"
    text = f"{where} at crank angle {reference_angle * DEG:g} deg"
    if cycle == "four-stroke" and prep.reference_period == prep.teeth:
        notes.append(
            "the reference is once per revolution: the four-stroke cycle starts at the first "
            "mark, so the phases of the half orders are known up to 180 deg"
        )
    return text, notes


def _calibration_errors(
    calibration: PulseTrain | PulseRecord, cycle: str, fraction: float, block: int = BLOCK
) -> np.ndarray:
    """Tooth errors (rad) from a calibration record of the same wheel (its mean over
    revolutions), numbered from its reference mark and aligned with the measurement's."""
    if isinstance(calibration, PulseTrain) and calibration.times.size > block:
        calibration = PulseRecord.from_train(calibration, chunk=SEGMENT)
    if isinstance(calibration, PulseRecord):
        calibration = gathered(calibration, block) or calibration
    prep: PreparedPulses | ScannedRecord = (
        scan_record(calibration)
        if isinstance(calibration, PulseRecord)
        else prepare_pulses(calibration)
    )
    if prep.reference_index is None:
        raise InputError(
            "the calibration record needs the reference mark (or a missing-tooth gap) to number "
            "the teeth",
            file=calibration.source,
            key="reference",
        )
    _, _, frac = tooth_numbering(prep)
    shift = 0
    delta = frac - fraction
    if delta > 0.5:
        shift = 1
    elif delta < -0.5:
        shift = -1
    if abs(delta - shift) > 0.25:
        raise InputError(
            f"the reference mark sits {abs(delta - shift):.2f} tooth pitches apart in the "
            "calibration record and the measurement: not the same wheel and mark?",
            file=calibration.source,
            key="reference",
        )
    if isinstance(prep, ScannedRecord):  # a long record, block by block
        length = cycle_length(CYCLE_ANGLE[cycle], prep.teeth)
        short = too_short(prep.positions, length)
        if short is not None:
            raise short.within(file=calibration.source)
        _, origin, _ = tooth_numbering(prep)
        return -blocked_pattern(prep, length, (origin + shift) % prep.teeth, block)
    _, errors = angle_domain(prep, CYCLE_ANGLE[cycle], estimate_teeth=True, tooth_shift=shift)
    if errors is None:  # estimate_teeth returns them
        raise ValueError("no tooth errors estimated")
    return errors


def _to_pulses(
    signal: PulseTrain | SpeedSignal | PulseRecord, resolution: int | None, block: int = BLOCK
) -> PulseTrain | PulseRecord:
    """The pulses to analyse, the wheel's size checked against the record for every kind of
    signal: a speed signal's resampling is bounded (:meth:`SpeedSignal.to_pulses`), a pulse
    record must hold one revolution of its wheel at least (a record read in chunks: gathered
    into a pulse train when it is short, :func:`crankdyn.measure.blocks.gathered`)."""
    if isinstance(signal, SpeedSignal):
        return signal.to_pulses(resolution)
    if isinstance(signal, PulseRecord):
        train = gathered(signal, block)
        if train is None:
            return signal
        signal = train
    if isinstance(signal, PulseTrain):
        _check_wheel(signal, signal.times.size)
        return signal
    raise TypeError(f"expected a PulseTrain or a SpeedSignal, got {type(signal).__name__}")


def _check_wheel(signal: PulseTrain | PulseRecord, pulses: int) -> None:
    """A pulse record must hold one revolution of its wheel at least."""
    if signal.teeth > pulses:
        raise InputError(
            f"the record holds {pulses:,} pulses, less than one revolution of a "
            f"wheel with {signal.teeth:,} pulses per revolution",
            file=signal.source,
            key="teeth",
            value=signal.teeth,
        )


def _windows(
    domain: AngleDomain, orders: ArrayLike, cycle_angle: float, cycles: int, shape: str = "uniform"
) -> Windows:
    """The windows of ``cycles`` cycles over a record's angle domain
    (:func:`crankdyn.measure.windows.window_coefficients`)."""
    length = domain.samples_per_cycle
    if domain.cycles < cycles:
        raise _too_few_cycles(domain.cycles, cycles)
    per = domain.vibration[: domain.cycles * length].reshape(domain.cycles, length)
    return window_coefficients(
        per, 0, float(domain.angle[0]), domain.boundary_times, orders, cycle_angle, cycles, shape
    )


def _too_few_cycles(have: int, cycles: int) -> InputError:
    """The error of a record with fewer whole cycles than one window's."""
    return InputError(
        f"the record holds {have} whole cycles after filtering, fewer than the "
        f"{cycles} of one window",
        key="window",
    )


def order_analysis(
    signal: PulseTrain | SpeedSignal | PulseRecord,
    *,
    cycle: str = "four-stroke",
    orders: ArrayLike | None = None,
    analysis: str = "auto",
    window_cycles: int = 4,
    bin_width: float | None = None,
    reference_angle: float = 0.0,
    tooth_correction: str | PulseTrain | PulseRecord | ArrayLike | None = None,
    resolution: int | None = None,
    window: str = "hann",
    block: int = BLOCK,
) -> OrderSpectrum | OrderTracking:
    """Orders of the angular vibration at the measured point (module docstring).

    Parameters
    ----------
    signal : PulseTrain, SpeedSignal or PulseRecord
        The record (times in s, speeds in rad/s). A record of more than
        :data:`~crankdyn.measure.blocks.BLOCK` pulses (a pulse train, or a
        :class:`~crankdyn.measure.records.PulseRecord` read in chunks, of any length) is
        analysed block by block in bounded memory (:mod:`crankdyn.measure.blocks`; the same
        numbers to rounding, without the ``domain`` of the result, which holds the
        per-cycle ``envelope`` instead).
    cycle : str
        ``"four-stroke"`` (orders 0.5, 1, 1.5, ...) or ``"two-stroke"``.
    orders : array_like or None
        Orders to report (per revolution; multiples of the cycle's fundamental order, below
        N/2); default every order up to 12 (:func:`default_orders`).
    analysis : str
        ``"steady"``, ``"tracking"`` (run-up or run-down) or ``"auto"``: tracking when the
        cycles' mean speeds spread by more than :data:`STEADY_LIMIT` of their mean.
    window_cycles : int
        Cycles per window of order tracking (c >= 1; windows step by one cycle); default 4.
    window : str
        Window of order tracking: ``"hann"`` (default; needs c >= 2) or ``"uniform"``.
        A steady-speed analysis always uses uniform one-cycle windows (exact for stationary
        orders).
    bin_width : float or None
        Speed bin of order tracking (rad/s); default :data:`DEFAULT_BIN`.
    reference_angle : float
        Crank angle at the reference mark (rad), e.g. the angle of cylinder 1's firing TDC
        as seen from the mark; for a missing-tooth wheel, at the first tooth after the gap.
    tooth_correction : str, PulseTrain, PulseRecord, array_like or None
        None; ``"self"`` (this record's mean over revolutions, :mod:`crankdyn.measure.angle`);
        a calibration :class:`PulseTrain` (or record) of the same wheel and mark; or the tooth
        errors (rad, N values numbered from the mark).
    resolution : int or None
        Angle samples per revolution when ``signal`` is a speed signal (default
        :meth:`SpeedSignal.default_teeth`).
    block : int
        Records of more pulses than this are analysed block by block, in blocks of this many
        tooth positions (default :data:`~crankdyn.measure.blocks.BLOCK`, 262,144: the working
        memory of a block is about 240 bytes per tooth position).

    Returns
    -------
    OrderSpectrum or OrderTracking
        Per order the amplitude (rad) and phase (rad; deg in exports) of the angular
        vibration: at the mean speed (steady), or per speed bin and per window (tracking).

    Raises
    ------
    InputError
        For an unknown cycle, analysis or window, a bad count of cycles, speed bin, order or
        tooth correction, and for a record that cannot be analysed (the message says why).

    Examples
    --------
    A steady 100 rad/s with 1 mrad of order 1.5 in phase with the crank angle and 2 mrad of
    order 3 leading by 90 deg, on a 60-tooth wheel with a once-per-cycle reference at crank
    angle 0 (:mod:`crankdyn.measure.synthetic`):

    >>> from crankdyn.measure.synthetic import PrescribedMotion, synthetic_pulses
    >>> motion = PrescribedMotion(100.0, 0.0, np.array([1.5, 3.0]), np.array([1e-3, 2e-3j]))
    >>> spectrum = order_analysis(
    ...     synthetic_pulses(motion, 60, 1.5, reference_every=2), orders=[1.5, 3.0]
    ... )
    >>> spectrum.kind, spectrum.cycles, round(spectrum.speed, 6)
    ('steady', 6, 100.0)
    >>> [round(float(a) * 1e3, 6) for a in spectrum.amplitude]  # mrad
    [1.0, 2.0]
    >>> [round(float(p), 4) for p in np.degrees(spectrum.phase)]
    [0.0, 90.0]
    """
    options = {
        "cycle": cycle,
        "analysis": analysis,
        "window_cycles": window_cycles,
        "window": window,
        "bin_width": bin_width,
        "reference_angle": reference_angle,
    }
    for check in _OPTION_CHECKS:
        check.apply(options)
    settings = _Settings(
        cycle, analysis, int(window_cycles), window, _bin_width(options), reference_angle
    )
    if isinstance(block, bool) or not isinstance(block, (int, np.integer)) or block < 1:
        raise InputError(
            "expected a whole number of tooth positions, >= 1", key="block", value=block
        )
    pulses = _to_pulses(signal, resolution, int(block))
    if isinstance(pulses, PulseTrain) and pulses.times.size > block:
        pulses = PulseRecord.from_train(pulses, chunk=SEGMENT)
    if isinstance(pulses, PulseRecord):
        record = pulses.cached(CACHE)  # read once when it is short enough
        return _blocked(record, orders, settings, tooth_correction, int(block))
    return _whole_record(pulses, signal, orders, settings, tooth_correction)


def _whole_record(
    pulses: PulseTrain,
    signal: PulseTrain | SpeedSignal | PulseRecord,
    orders: ArrayLike | None,
    settings: _Settings,
    tooth_correction: str | PulseTrain | PulseRecord | ArrayLike | None,
) -> OrderSpectrum | OrderTracking:
    """The analysis of a record held whole (:func:`order_analysis`, up to ``block`` pulses):
    the angle domain of every pulse, the per-cycle orders, then the steady spectrum or the
    tracking windows."""
    q = _check_orders(orders, settings.cycle, pulses.teeth)
    prep = prepare_pulses(pulses)
    notes = list(prep.notes)
    if isinstance(signal, SpeedSignal):
        notes.insert(
            0,
            f"speed signal integrated to the shaft angle and resampled at {pulses.teeth} "
            "angles per revolution",
        )
    reference, more = _reference_text(prep, settings.cycle, settings.reference_angle)
    notes.extend(more)
    _, _, fraction = tooth_numbering(prep)
    cycle_angle = CYCLE_ANGLE[settings.cycle]
    errors, estimate, correction = _tooth_correction(
        tooth_correction, prep, settings.cycle, fraction
    )
    domain, estimated = angle_domain(
        prep,
        cycle_angle,
        reference_angle=settings.reference_angle,
        tooth_errors=errors,
        estimate_teeth=estimate,
    )
    tooth_errors: np.ndarray | None = estimated if estimated is not None else errors
    if estimated is not None:
        notes.append(_estimated_teeth_note(estimated, q))
    per_cycle = _windows(domain, q, cycle_angle, 1)
    length = domain.samples_per_cycle
    # the averaged cycle, its crank angles from the cycle's boundary and the mean speed
    average = np.mean(domain.vibration[: domain.cycles * length].reshape(domain.cycles, -1), axis=0)
    start = math.floor(domain.angle[0] / cycle_angle + 1e-9) * cycle_angle
    angle_span = cycle_angle * domain.cycles
    mean = np.mean(per_cycle.coefficients, axis=0)
    cycles = _Cycles(
        per_cycle,
        per_cycle.speed,
        mean,
        np.sqrt(np.mean(np.abs(per_cycle.coefficients - mean) ** 2, axis=0)),
        domain.cycles,
        length,
        float(angle_span / (domain.boundary_times[-1] - domain.boundary_times[0])),
        average,
        domain.angle[:length] - start,
    )
    common = _common(q, prep.teeth, settings, reference, correction, tooth_errors, pulses.source)
    common["domain"] = domain
    kind = _kind(settings, per_cycle.speed, notes)
    if kind == "steady":
        return _steady_spectrum(cycles, q, notes, common, settings)
    win = (
        per_cycle
        if settings.window_cycles == 1 and settings.window == "uniform"
        else _windows(domain, q, cycle_angle, settings.window_cycles, settings.window)
    )
    return _order_tracking(win, q, settings, notes, common)


@dataclass(frozen=True)
class _Settings:
    """The options of :func:`order_analysis` (checked)."""

    cycle: str
    analysis: str
    window_cycles: int
    window: str
    bin_width: float
    reference_angle: float

    @property
    def cycle_angle(self) -> float:
        """The crank angle of a working cycle (rad)."""
        return CYCLE_ANGLE[self.cycle]


@dataclass(frozen=True)
class _Cycles:
    """What the steady-speed analysis takes from the whole cycles of a record."""

    per_cycle: Windows | None  # None: not kept (a steady analysis in blocks)
    speeds: np.ndarray  # of each cycle (rad/s)
    mean: np.ndarray  # the cycles' mean orders (rad)
    scatter: np.ndarray  # their RMS scatter about it (rad)
    count: int
    length: int
    speed: float  # rad/s
    average: np.ndarray  # rad
    angle: np.ndarray  # rad from the cycle's boundary


def _common(
    q: np.ndarray,
    teeth: int,
    settings: _Settings,
    reference: str,
    correction: str,
    tooth_errors: np.ndarray | None,
    source: str,
) -> dict[str, Any]:
    """The fields both results share."""
    return {
        "orders": freeze(q),
        "teeth": teeth,
        "cycle": settings.cycle,
        "reference": reference,
        "tooth_correction": correction,
        "tooth_errors": None if tooth_errors is None else freeze(tooth_errors),
        "source": source,
    }


def _kind(settings: _Settings, speeds: np.ndarray, notes: list[str]) -> str:
    """``steady`` or ``tracking`` (``auto``: by the spread of the cycles' speeds, rad/s); a
    note when a steady analysis blurs a spread."""
    spread = (np.max(speeds) - np.min(speeds)) / np.mean(speeds)
    kind = settings.analysis
    if kind == "auto":
        kind = "tracking" if spread > STEADY_LIMIT else "steady"
    if kind == "steady" and spread > STEADY_LIMIT:
        notes.append(
            f"the cycle speeds spread by {spread:.1%} of their mean: a steady-speed average "
            "blurs orders that change with speed (try --analysis tracking)"
        )
    return kind


def _blocked(
    record: PulseRecord,
    orders: ArrayLike | None,
    settings: _Settings,
    tooth_correction: str | PulseTrain | PulseRecord | ArrayLike | None,
    block: int,
) -> OrderSpectrum | OrderTracking:
    """:func:`order_analysis` of a record longer than :data:`~crankdyn.measure.blocks.BLOCK`
    pulses, block by block (:mod:`crankdyn.measure.blocks`): the same checks in the same order,
    the same numbers to rounding, in bounded memory."""
    found: list[np.ndarray] = []

    def before_repairs(pulses: int) -> None:  # as the whole record's: its size, the orders
        _check_wheel(record, pulses)
        found.append(_check_orders(orders, settings.cycle, record.teeth))

    scan = scan_record(record, before_repairs)
    q = found[0]
    notes = list(scan.notes)
    reference, more = _reference_text(scan, settings.cycle, settings.reference_angle)
    notes.extend(more)
    _, tooth_origin, fraction = tooth_numbering(scan)
    errors, estimate, correction = _tooth_correction(
        tooth_correction, scan, settings.cycle, fraction, block
    )
    length = cycle_length(settings.cycle_angle, scan.teeth)
    short = too_short(scan.positions, length)
    if short is not None:
        raise short
    estimated = kappa = None
    if estimate:
        estimated = errors = -blocked_pattern(scan, length, tooth_origin, block)
        notes.append(_estimated_teeth_note(estimated, q))
    if errors is not None and scan.reference_index is not None:
        kappa = corrected_marks(scan, errors, tooth_origin)
    blocks = blocked_analysis(
        scan,
        q,
        settings.cycle_angle,
        reference_angle=settings.reference_angle,
        tooth_errors=errors,
        kappa=kappa,
        window_cycles=settings.window_cycles,
        window=settings.window,
        tracking=settings.analysis != "steady",
        block=block,
        keep_cycles=settings.analysis != "steady",
    )
    common = _common(q, scan.teeth, settings, reference, correction, errors, record.source)
    common["envelope"] = blocks.envelope
    cycles = _Cycles(
        blocks.per_cycle,
        blocks.cycle_speed,
        blocks.mean,
        blocks.scatter,
        blocks.cycles,
        blocks.length,
        blocks.speed,
        blocks.average,
        blocks.cycle_angle,
    )
    if _kind(settings, blocks.cycle_speed, notes) == "steady":
        return _steady_spectrum(cycles, q, notes, common, settings)
    uniform = settings.window_cycles == 1 and settings.window == "uniform"
    if uniform and blocks.per_cycle is not None:
        win = blocks.per_cycle
    elif blocks.windows is None or blocks.cycles < settings.window_cycles:
        raise _too_few_cycles(blocks.cycles, settings.window_cycles)
    else:
        win = blocks.windows
    return _order_tracking(win, q, settings, notes, common)


def _bin_width(options: dict[str, Any]) -> float:
    """The speed bin of order tracking (rad/s): ``bin_width``, default :data:`DEFAULT_BIN`."""
    width = options["bin_width"]
    return DEFAULT_BIN if width is None else float(width)


def _whole_cycles(value: Any) -> bool:
    """Whether a count of cycles is a whole number >= 1 (not a bool)."""
    return not (isinstance(value, bool) or int(value) != value or value < 1)


@dataclass(frozen=True)
class _OptionCheck:
    """One check of :func:`order_analysis`'s options: an InputError with ``message``, ``key``
    and the value shown (``value`` of the options; none when None) where ``fails``."""

    key: str
    message: str
    fails: Callable[[dict[str, Any]], bool]
    value: Callable[[dict[str, Any]], Any] | None = None

    def apply(self, options: dict[str, Any]) -> None:
        """Raise the InputError when the options fail the check."""
        if not self.fails(options):
            return
        if self.value is None:
            raise InputError(self.message, key=self.key)
        raise InputError(self.message, key=self.key, value=self.value(options))


_OPTION_CHECKS = (
    _OptionCheck(
        "cycle",
        "expected four-stroke or two-stroke",
        lambda o: o["cycle"] not in _CYCLES,
        lambda o: o["cycle"],
    ),
    _OptionCheck(
        "analysis",
        f"expected one of {', '.join(ANALYSES)}",
        lambda o: o["analysis"] not in ANALYSES,
        lambda o: o["analysis"],
    ),
    _OptionCheck(
        "window",
        "expected a whole number of cycles, >= 1",
        lambda o: not _whole_cycles(o["window_cycles"]),
        lambda o: o["window_cycles"],
    ),
    _OptionCheck(
        "window",
        f"expected one of {', '.join(WINDOWS)}",
        lambda o: o["window"] not in WINDOWS,
        lambda o: o["window"],
    ),
    _OptionCheck(
        "window-cycles",
        "a Hann window needs at least 2 cycles (over one cycle it would mix each order with "
        "its neighbours half an order away)",
        lambda o: o["window"] == "hann" and int(o["window_cycles"]) < 2,
        lambda o: int(o["window_cycles"]),
    ),
    _OptionCheck(
        "bin",
        "the speed bin must be positive",
        lambda o: not (math.isfinite(_bin_width(o)) and _bin_width(o) > 0.0),
        lambda o: _bin_width(o) * RPM,
    ),
    _OptionCheck(
        "reference_angle",
        "the reference angle must be finite",
        lambda o: not math.isfinite(o["reference_angle"]),
    ),
)
"""The checks of :func:`order_analysis`'s options, in the order they are made."""


def _tooth_correction(
    tooth_correction: str | PulseTrain | PulseRecord | ArrayLike | None,
    prep: PreparedPulses | ScannedRecord,
    cycle: str,
    fraction: Any,
    block: int = BLOCK,
) -> tuple[np.ndarray | None, bool, str]:
    """(tooth errors (rad) or None, whether to estimate them from the record, the correction in
    words) of :func:`order_analysis`'s ``tooth_correction``; InputError when it does not fit
    the record."""
    errors = None
    estimate = False
    correction = "none"
    if isinstance(tooth_correction, str):
        if tooth_correction != "self":
            raise InputError(
                "expected self, a calibration record or tooth errors",
                key="tooth_correction",
                value=tooth_correction,
            )
        estimate = True
        correction = "mean of this record over its revolutions"
    elif isinstance(tooth_correction, (PulseTrain, PulseRecord)):
        if prep.reference_index is None:
            raise InputError(
                "a calibration record needs the reference mark (or a missing-tooth gap) in the "
                "measurement too, to number the teeth",
                key="tooth_correction",
            )
        if tooth_correction.teeth != prep.teeth:
            raise InputError(
                f"the calibration record has {tooth_correction.teeth} teeth, the measurement "
                f"{prep.teeth}",
                key="tooth_correction",
            )
        errors = _calibration_errors(tooth_correction, cycle, fraction, block)
        correction = f"from the calibration record {tooth_correction.source}"
    elif tooth_correction is not None:
        errors = np.asarray(tooth_correction, dtype=float)
        if errors.shape != (prep.teeth,) or not np.all(np.isfinite(errors)):
            raise InputError(f"expected {prep.teeth} finite tooth errors", key="tooth_errors")
        correction = "given tooth errors"
    return errors, estimate, correction


def _estimated_teeth_note(estimated: np.ndarray, q: np.ndarray) -> str:
    """The note on tooth errors estimated from the record itself: the pattern holds the integer
    orders' mean too; removed at the tooth angles instead of the crank angles, it leaves a
    cross-talk of about m |P_m| (relative) in the others."""
    spectrum = np.abs(np.fft.rfft(estimated)) * (2.0 / estimated.size)
    m = np.arange(spectrum.size)
    engine = (m >= 1) & (m <= np.max(q))
    bound = float(np.sum(m[engine] * spectrum[engine]))
    return (
        "tooth-spacing errors taken as this record's mean over revolutions: the integer "
        "orders lose their mean over the record (they cannot be told from the wheel's "
        f"errors); the half orders keep a cross-talk of up to {bound:.2%} of their amplitude "
        "(a calibration record avoids both)"
    )


def _steady_spectrum(
    cycles: _Cycles,
    q: np.ndarray,
    notes: list[str],
    common: dict[str, Any],
    settings: _Settings,
) -> OrderSpectrum:
    """The steady-speed analysis (module docstring): the complex (synchronous) average of the
    one-cycle windows, its synthesis and the averaged cycle's angle and speed."""
    per_cycle, cycle_angle = cycles.per_cycle, settings.cycle_angle
    mean, scatter = cycles.mean, cycles.scatter
    speed = cycles.speed
    top, low = half_range(mean, harmonic_index(q, settings.cycle))
    avg = cycles.average
    # instantaneous speed of the averaged cycle: Omega (1 + dv/dpsi), dv/dpsi spectrally
    spec = np.fft.rfft(avg)
    k = np.arange(spec.size)
    dv = np.fft.irfft(1j * k * (2.0 * math.pi / cycle_angle) * spec, n=avg.size)
    return OrderSpectrum(
        speed=float(speed),
        amplitude=freeze(np.abs(mean)),
        phase=freeze(np.angle(mean)),
        scatter=freeze(scatter),
        synthesized=float(0.5 * (top - low)),
        cycles=int(cycles.count),
        speed_min=float(np.min(cycles.speeds)),
        speed_max=float(np.max(cycles.speeds)),
        window=f"uniform (rectangular) over 1 cycle ({cycle_angle * DEG:g} deg), "
        f"synchronous: {cycles.length} samples per cycle",
        averaging=f"complex (synchronous) average of {cycles.count} cycles",
        cycle_angle=freeze(cycles.angle),
        cycle_vibration=freeze(avg),
        cycle_speed=freeze(speed * (1.0 + dv)),
        notes=tuple(notes),
        cycle_coefficients=None if per_cycle is None else per_cycle.coefficients,
        **common,
    )


def _order_tracking(
    win: Windows,
    q: np.ndarray,
    settings: _Settings,
    notes: list[str],
    common: dict[str, Any],
) -> OrderTracking:
    """Order tracking over the windows ``win`` (module docstring): their complex average in
    speed bins of the settings' width (rad/s), the synthesis and the resonances."""
    harmonic = harmonic_index(q, settings.cycle)
    cycle_angle, window_cycles = settings.cycle_angle, settings.window_cycles
    window, width = settings.window, settings.bin_width
    trend = np.polyfit(np.arange(win.speed.size), win.speed, 1)[0] if win.speed.size > 1 else 0
    label = "run-up" if trend >= 0 else "run-down"
    cell = np.floor(win.speed / width).astype(np.int64)
    cells, inverse, counts = np.unique(cell, return_inverse=True, return_counts=True)
    sums = np.zeros((cells.size, q.size), dtype=complex)
    np.add.at(sums, inverse, win.coefficients)
    speed_sum = np.zeros(cells.size)
    np.add.at(speed_sum, inverse, win.speed)
    coeff = sums / counts[:, None]
    top, low = half_range(coeff, harmonic)
    wtop, wlow = half_range(win.coefficients, harmonic)
    span = f"{window_cycles} cycle{'s' if window_cycles > 1 else ''}"
    resonances = find_resonances(q, win.speed, win.coefficients)
    return OrderTracking(
        kind=label,
        speed=freeze(speed_sum / counts),
        windows=freeze(counts, dtype=int),
        amplitude=freeze(np.abs(coeff)),
        phase=freeze(np.angle(coeff)),
        synthesized=freeze(0.5 * (top - low)),
        window_speed=freeze(win.speed),
        window_amplitude=freeze(np.abs(win.coefficients)),
        window_phase=freeze(np.angle(win.coefficients)),
        window_synthesized=freeze(0.5 * (wtop - wlow)),
        window_cycles=window_cycles,
        bin_width=width,
        resonances=resonances,
        window=f"{'Hann' if window == 'hann' else 'uniform (rectangular)'} over {span} "
        f"({window_cycles * cycle_angle * DEG:g} deg), synchronous, stepping by one cycle"
        + (", amplitudes divided by the coherent gain 0.5" if window == "hann" else ""),
        averaging=f"complex average of the windows in {width * RPM:g} rpm speed bins "
        f"({win.speed.size} windows in {cells.size} bins); peaks and fits use every window",
        notes=tuple(notes),
        window_coefficients=win.coefficients,
        **common,
    )


def find_resonances(
    orders: NDArray[np.float64], speeds: NDArray[np.float64], coefficients: NDArray[np.complex128]
) -> tuple[ResonanceFit, ...]:
    """The resonance of every order that has one inside the sweep
    (:func:`crankdyn.measure.resonance.fit_resonance`).

    An order's resonance is kept when its peak reaches :data:`SIGNIFICANT` of the largest order
    amplitude of the record, the single-mode fit matches the windows in its band to
    :data:`MAX_MISFIT` (relative RMS), and its critical speed lies inside the sweep.

    Parameters
    ----------
    orders : numpy.ndarray
        The orders q (per revolution), Q of them.
    speeds : numpy.ndarray
        Mean crank speed of every window (rad/s), W of them.
    coefficients : numpy.ndarray
        (W, Q) complex amplitudes of the orders in the windows (rad).

    Returns
    -------
    tuple of crankdyn.measure.resonance.ResonanceFit
        One per order with a resonance, in the order of ``orders``.

    Examples
    --------
    A sweep through a single mode of order 6 (omega_n = 600 rad/s, zeta = 0.02), the order
    1.5 beside it flat:

    >>> from crankdyn.measure.resonance import single_mode
    >>> speeds = np.linspace(90.0, 110.0, 201)
    >>> x6 = single_mode(6 * speeds, 600.0, 0.02, 3600.0, 0.0)
    >>> values = np.stack([np.full(201, 1e-4 + 0j), x6], axis=1)
    >>> (fit,) = find_resonances(np.array([1.5, 6.0]), speeds, values)
    >>> fit.order, round(fit.critical_speed, 6), round(fit.damping, 6)
    (6.0, 100.0, 0.02)
    """
    amplitude = np.abs(coefficients)
    largest = float(np.max(amplitude)) if amplitude.size else 0.0
    out = []
    for j, q in enumerate(orders):
        if np.max(amplitude[:, j]) < SIGNIFICANT * largest:
            continue
        fit = fit_resonance(float(q), speeds, coefficients[:, j])
        if fit is None or fit.misfit > MAX_MISFIT:
            continue
        if not np.min(speeds) < fit.critical_speed < np.max(speeds):
            continue
        out.append(fit)
    return tuple(out)


# ---- results ----------------------------------------------------------------------------------
def _order_label(q: float) -> str:
    return f"{q:g}"


@dataclass(frozen=True)
class OrderSpectrum(Result):
    """Orders of the angular vibration at a steady speed (module docstring): per order the
    amplitude and phase of v(psi) = sum Re(V_q exp(i q psi)) at the measured point.

    Parameters
    ----------
    cycle_coefficients : numpy.ndarray or None
        (cycles, Q) complex V_q of every single cycle (rad), for plots and checks; None for a
        record analysed block by block with ``analysis="steady"``, which keeps only their mean
        and scatter (its memory does not grow by 16 bytes per order per cycle).
    domain : crankdyn.measure.angle.AngleDomain or None
        The resampled angular vibration the orders come from (not exported); None for a
        record analysed block by block.
    envelope : crankdyn.measure.blocks.Envelope or None
        The trace per cycle of a record analysed block by block (not exported), else None.
    """

    title = "Measured orders (steady speed)"
    speed: float = scalar("speed_rpm", "Mean speed", "rpm", RPM, fmt=".2f")
    orders: np.ndarray = column("orders", "Order", "")
    amplitude: np.ndarray = column("amplitude_rad", "Amplitude", "rad")
    phase: np.ndarray = column("phase_deg", "Phase", "deg", DEG)
    scatter: np.ndarray = column("scatter_rad", "Cycle-to-cycle scatter (RMS)", "rad")
    synthesized: float = scalar(
        "synthesized_amplitude_rad", "Synthesised half-range amplitude", "rad"
    )
    cycles: int = scalar("cycles", "Cycles averaged", "")
    speed_min: float = scalar("speed_min_rpm", "Slowest cycle", "rpm", RPM, fmt=".2f")
    speed_max: float = scalar("speed_max_rpm", "Fastest cycle", "rpm", RPM, fmt=".2f")
    teeth: int = scalar("teeth", "Pulses per revolution", "")
    cycle: str = scalar("cycle", "Cycle", "")
    window: str = scalar("window", "Window", "")
    averaging: str = scalar("averaging", "Averaging", "")
    reference: str = scalar("reference", "Phase reference", "")
    tooth_correction: str = scalar("tooth_correction", "Tooth-spacing correction", "")
    source: str = scalar("signal", "Signal", "")
    tooth_errors: np.ndarray | None = array(
        "tooth_errors_deg", "Tooth-spacing errors", "deg", DEG, default=None
    )
    cycle_angle: np.ndarray | None = array(
        "cycle_angle_deg", "Crank angle of the averaged cycle", "deg", DEG, default=None
    )
    cycle_vibration: np.ndarray | None = array(
        "cycle_vibration_rad", "Angular vibration of the averaged cycle", "rad", default=None
    )
    cycle_speed: np.ndarray | None = array(
        "cycle_speed_rpm", "Instantaneous speed of the averaged cycle", "rpm", RPM, default=None
    )
    notes: tuple[str, ...] = scalar("notes", "Notes", "", default=())  # always in the JSON
    comparison: Result | None = scalar("model", "Model", "", default=None)
    cycle_coefficients: np.ndarray | None = field(default=None, repr=False, compare=False)
    domain: AngleDomain | None = field(default=None, repr=False, compare=False)
    envelope: Envelope | None = field(default=None, repr=False, compare=False)

    kind = "steady"
    FIGURES = MEASURED_FIGURES

    @property
    def coefficients(self) -> NDArray[np.complex128]:
        """Complex amplitudes V_q (rad)."""
        return self.amplitude * np.exp(1j * self.phase)

    def columns(self) -> dict[str, np.ndarray]:
        """The order columns, and the model's beside them (CSV).

        Returns
        -------
        dict of str to numpy.ndarray
            {key: values} in the unit of the key (:meth:`crankdyn.results.Result.columns`).
        """
        out = super().columns()
        if self.comparison is not None:
            out.update(self.comparison.columns())
        return out

    def column_labels(self) -> dict[str, tuple[str, str]]:
        """Label and unit of every column of :meth:`columns`.

        Returns
        -------
        dict of str to (str, str)
            {column key: (label, unit)}.
        """
        out = super().column_labels()
        if self.comparison is not None:
            out.update(self.comparison.column_labels())
        return out

    def with_model(
        self,
        model: TorsionModel,
        excitation: Excitation,
        at: str,
        **kw: Any,
    ) -> OrderSpectrum:
        """This analysis with the model's prediction at mass ``at`` attached
        (:func:`crankdyn.measure.compare.compare_with_model`).

        Parameters
        ----------
        model : crankdyn.torsion.model.TorsionModel
            The torsional model.
        excitation : crankdyn.torsion.excitation.Excitation
            Its excitation (:func:`crankdyn.torsion.excitation.excitation_for`).
        at : str
            The mass that carries the measured wheel.
        **kw
            Passed to :func:`~crankdyn.measure.compare.compare_with_model` (``dampers``).

        Returns
        -------
        OrderSpectrum
            A copy with ``comparison`` set.
        """
        from crankdyn.measure.compare import compare_with_model

        return replace(self, comparison=compare_with_model(self, model, excitation, at, **kw))

    def plot(self, what: str = "orders", fig: Figure | None = None) -> Figure:
        """A figure of the analysis (:func:`crankdyn.plots.measure.plot_measurement`).

        Parameters
        ----------
        what : str
            ``"orders"`` (default): amplitude per order (with the model's); ``"trace"``:
            angular vibration and instantaneous speed over the averaged cycle.
        fig : matplotlib.figure.Figure or None
            A figure to draw into; default a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.measure import plot_measurement

        return plot_measurement(self, what=what, fig=fig)


@dataclass(frozen=True)
class OrderTracking(Result):
    """Order tracking over a run-up or run-down (module docstring): per speed bin and order the
    amplitude and phase of the angular vibration at the measured point; per window the same,
    unbinned (``window_*``).

    Parameters
    ----------
    window_coefficients : numpy.ndarray or None
        (W, Q) complex V_q of every window (rad), for the resonance fits and plots.
    domain : crankdyn.measure.angle.AngleDomain or None
        The resampled angular vibration the orders come from (not exported); None for a
        record analysed block by block.
    envelope : crankdyn.measure.blocks.Envelope or None
        The trace per cycle of a record analysed block by block (not exported), else None.
    """

    title = "Measured orders (order tracking)"
    FIGURES = MEASURED_FIGURES
    kind: str = scalar("kind", "Record", "")
    speed: np.ndarray = column("speed_rpm", "Speed", "rpm", RPM)
    windows: np.ndarray = column("windows", "Windows", "")
    synthesized: np.ndarray = column(
        "synthesized_amplitude_rad", "Synthesised half-range amplitude", "rad"
    )
    orders: np.ndarray = array("orders", "Orders", "")
    amplitude: np.ndarray = array("amplitude_rad", "Amplitude (speed x order)", "rad")
    phase: np.ndarray = array("phase_deg", "Phase (speed x order)", "deg", DEG)
    window_speed: np.ndarray = array("window_speed_rpm", "Speed of every window", "rpm", RPM)
    window_amplitude: np.ndarray = array(
        "window_amplitude_rad", "Amplitude of every window (window x order)", "rad"
    )
    window_phase: np.ndarray = array(
        "window_phase_deg", "Phase of every window (window x order)", "deg", DEG
    )
    window_synthesized: np.ndarray = array(
        "window_synthesized_amplitude_rad", "Synthesised amplitude of every window", "rad"
    )
    window_cycles: int = scalar("window_cycles", "Cycles per window", "")
    bin_width: float = scalar("bin_width_rpm", "Speed bin", "rpm", RPM, fmt=".4g")
    teeth: int = scalar("teeth", "Pulses per revolution", "")
    cycle: str = scalar("cycle", "Cycle", "")
    window: str = scalar("window", "Window", "")
    averaging: str = scalar("averaging", "Averaging", "")
    reference: str = scalar("reference", "Phase reference", "")
    tooth_correction: str = scalar("tooth_correction", "Tooth-spacing correction", "")
    source: str = scalar("signal", "Signal", "")
    tooth_errors: np.ndarray | None = array(
        "tooth_errors_deg", "Tooth-spacing errors", "deg", DEG, default=None
    )
    resonances: tuple[ResonanceFit, ...] = scalar("resonances", "Resonances", "", default=())
    notes: tuple[str, ...] = scalar("notes", "Notes", "", default=())  # always in the JSON
    comparison: Result | None = scalar("model", "Model", "", default=None)
    window_coefficients: np.ndarray | None = field(default=None, repr=False, compare=False)
    domain: AngleDomain | None = field(default=None, repr=False, compare=False)
    envelope: Envelope | None = field(default=None, repr=False, compare=False)

    def summary_tables(self) -> list[SummaryTable]:
        """The largest bin per order (:func:`crankdyn.measure.figures.largest_per_order_table`)
        and the fitted resonances, beside the model's peaks where it was held against one
        (:func:`crankdyn.measure.figures.resonance_table`).

        Returns
        -------
        list of crankdyn.summary.SummaryTable
            The largest bin per order, then the resonances (none without fits).
        """
        return [*largest_per_order_table(self), *resonance_table(self)]

    @property
    def coefficients(self) -> NDArray[np.complex128]:
        """Complex amplitudes V_q per speed bin (rad), (bins x orders)."""
        return self.amplitude * np.exp(1j * self.phase)

    def order_index(self, order: float) -> int:
        """Index of an analysed order.

        Parameters
        ----------
        order : float
            The order q (per revolution), within 1e-9 of an analysed one.

        Returns
        -------
        int
            Its index in :attr:`orders`.

        Raises
        ------
        InputError
            If the order was not analysed (one line listing those that were).
        """
        hit = np.flatnonzero(np.isclose(self.orders, order, rtol=0, atol=1e-9))
        if not hit.size:
            listed = ", ".join(_order_label(q) for q in self.orders)
            raise InputError(
                f"order {order:g} was not analysed (orders: {listed})", key="order", value=order
            )
        return int(hit[0])

    def with_model(
        self,
        model: TorsionModel,
        excitation: Excitation,
        at: str,
        **kw: Any,
    ) -> OrderTracking:
        """This analysis with the model's prediction at mass ``at``, the resonance peaks and the
        identified damping attached (:func:`crankdyn.measure.compare.compare_with_model`).

        Parameters
        ----------
        model : crankdyn.torsion.model.TorsionModel
            The torsional model.
        excitation : crankdyn.torsion.excitation.Excitation
            Its excitation (:func:`crankdyn.torsion.excitation.excitation_for`).
        at : str
            The mass that carries the measured wheel.
        **kw
            Passed to :func:`~crankdyn.measure.compare.compare_with_model` (``dampers``).

        Returns
        -------
        OrderTracking
            A copy with ``comparison`` set.
        """
        from crankdyn.measure.compare import compare_with_model

        return replace(self, comparison=compare_with_model(self, model, excitation, at, **kw))

    def columns(self) -> dict[str, np.ndarray]:
        """The speed-bin columns, every order's amplitude and phase, and the model's (CSV).

        Returns
        -------
        dict of str to numpy.ndarray
            {key: values} in the unit of the key: ``order_<q>_amplitude_rad`` (rad) and
            ``order_<q>_phase_deg`` (deg) per order.
        """
        out = super().columns()
        for i, q in enumerate(self.orders):
            out[f"order_{_order_label(q)}_amplitude_rad"] = self.amplitude[:, i]
        for i, q in enumerate(self.orders):
            out[f"order_{_order_label(q)}_phase_deg"] = self.phase[:, i] * DEG
        if self.comparison is not None:
            out.update(self.comparison.columns())
        return out

    def column_labels(self) -> dict[str, tuple[str, str]]:
        """Label and unit of every column of :meth:`columns`.

        Returns
        -------
        dict of str to (str, str)
            {column key: (label, unit)}.
        """
        out = super().column_labels()
        for q in self.orders:
            out[f"order_{_order_label(q)}_amplitude_rad"] = (f"Order {q:g}", "rad")
        for q in self.orders:
            out[f"order_{_order_label(q)}_phase_deg"] = (f"Phase {q:g}", "deg")
        if self.comparison is not None:
            out.update(self.comparison.column_labels())
        return out

    def plot(self, what: str = "orders", fig: Figure | None = None, **kw: Any) -> Figure:
        """A figure of the analysis (:func:`crankdyn.plots.measure.plot_measurement`).

        Parameters
        ----------
        what : str
            ``"orders"`` (default): amplitude against speed per order and synthesised (with
            the model's prediction); ``"map"``: colour map of order amplitudes over speed;
            ``"fit"``: the resonance fits; ``"trace"``: instantaneous speed and vibration over
            crank angle.
        fig : matplotlib.figure.Figure or None
            A figure to draw into; default a new one.
        **kw
            Passed on: ``orders``, the orders to draw in ``"orders"`` (default the six
            largest).

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.measure import plot_measurement

        return plot_measurement(self, what=what, fig=fig, **kw)
