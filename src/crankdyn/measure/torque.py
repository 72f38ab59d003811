"""Measured shaft torques (strain gauges on a journal or a shaft) analysed by order and held
against the model's torque at that span (domain, analysis and results; seed 003).

Seed 003 (the V6 paper, Yu Xuehua, "发动机曲轴系统扭转振动分析"): strain gauges glued on the crank
journals, their leads taken out through drilled holes, measure the journal torques; the paper
computes the journal torques with its lumped model and compares them with the measured ones
("计算各轴颈的力矩和实测力矩进行比较,分析力矩分布的情况"). A torque record here is the torque of
one span against the crank angle, or against time with a once-per-cycle mark.

**Crank angle of the samples.** An angle-domain record gives it (the crank angle of cylinder 1
from its firing TDC, plus ``reference_angle``); a time-domain record has the times of a mark
passed once per working cycle at the crank angle ``reference_angle`` (e.g. a camshaft TDC
sensor), and between two marks the angle is taken as linear in time (a steady speed within the
cycle).

**Orders.** Over the whole cycles of the record the torque is resampled at L equally spaced crank
angles per cycle (a not-a-knot cubic spline through the samples, whose error falls as the fourth
power of the sample spacing: below 1e-4 of an order's amplitude at 25 samples per period of that
order), and each cycle's discrete Fourier transform gives every order of the cycle exactly
(synchronous sampling, as the torsiograph's orders, :mod:`crankdyn.measure.orders`)::

    T(psi) = T_0 + sum_q Re(T_q exp(i q psi)),   T_q = (2 / L) sum_j T_j exp(-i q psi_j),

complex-averaged over the cycles (content not locked to the crank averages out; the scatter of
the single cycles is reported), with the phase of the cosine at the crank angle from cylinder
1's firing TDC, the convention of the forced response (:mod:`crankdyn.torsion.response`). T_0 is
the mean torque the span transmits.

**The model.** The forced response of the model at the record's mean speed
(:func:`crankdyn.torsion.response.forced_response`) gives the complex torque of the span
between masses a and b, k (theta_b - theta_a) (the model's own sign: positive when b turns ahead
of a), for every order; its half-range synthesis beside the measured one. The record's torque
must have that sign (a gauge wired the other way gives the phases 180 deg apart and the same
amplitudes).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.constants import CYCLE_ANGLE, DEG, RPM
from crankdyn.errors import InputError
from crankdyn.results import Result, column, freeze, scalar
from crankdyn.torsion.excitation import check_orders, fundamental_order, harmonic_index
from crankdyn.torsion.synthesis import half_range

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from crankdyn.torsion.dampers import Damper
    from crankdyn.torsion.excitation import Excitation
    from crankdyn.torsion.model import TorsionModel

__all__ = [
    "TorqueComparison",
    "TorqueRecord",
    "TorqueSpectrum",
    "compare_torque",
    "torque_orders",
]

MIN_SAMPLES_PER_PERIOD = 4
"""Samples of the record per period of the highest order analysed, at least (below it the
spline cannot follow the order: the record is refused)."""
STEADY_LIMIT = 0.02
"""A record whose cycle speeds spread by more than this share of their mean gets a note."""


def _finite(name: str, values: ArrayLike | None) -> NDArray[np.float64] | None:
    if values is None:
        return None
    arr = np.asarray(values, dtype=float)
    if arr.ndim != 1 or not np.all(np.isfinite(arr)):
        raise InputError("expected a one-dimensional array of finite numbers", key=name)
    return freeze(arr)


@dataclass(frozen=True, eq=False)
class TorqueRecord:
    """A measured shaft torque over crank angle, or over time with a once-per-cycle mark.

    Parameters
    ----------
    torque : array_like
        The measured torque (N m) of every sample.
    crank_angle : array_like or None
        Angle domain: the crank angle of every sample (rad), increasing (cumulative over the
        cycles).
    time : array_like or None
        Time domain: the time of every sample (s), increasing; with an angle-domain record,
        optional (it gives the speed).
    reference : array_like or None
        Time domain: the times of the mark passed once per working cycle (s), increasing.
    speed : float or None
        The mean crank speed (rad/s) of an angle-domain record without times; else None (from
        the times).
    source : str
        Where the record came from, for outputs.

    Raises
    ------
    crankdyn.errors.InputError
        Arrays of different lengths or not finite, times or angles not increasing, neither
        crank angles nor times with marks, or a speed that is not positive (names the key).

    Examples
    --------
    >>> psi = np.linspace(0.0, 8 * np.pi, 721)
    >>> record = TorqueRecord(500.0 + 100.0 * np.cos(1.5 * psi), crank_angle=psi, speed=200.0)
    >>> record.domain
    'angle'
    """

    torque: NDArray[np.float64]
    crank_angle: NDArray[np.float64] | None = None
    time: NDArray[np.float64] | None = None
    reference: NDArray[np.float64] | None = None
    speed: float | None = None
    source: str = "torque record"

    def __post_init__(self) -> None:
        torque = _finite("torque", self.torque)
        assert torque is not None
        angle = _finite("crank_angle", self.crank_angle)
        time = _finite("time", self.time)
        marks = _finite("reference", self.reference)
        for name, arr in (("crank_angle", angle), ("time", time)):
            if arr is not None and arr.shape != torque.shape:
                raise InputError(
                    f"expected one value per torque sample ({torque.size})",
                    key=name,
                    value=arr.size,
                )
        for name, arr in (("crank_angle", angle), ("time", time), ("reference", marks)):
            if arr is not None and np.any(np.diff(arr) <= 0.0):
                i = int(np.argmax(np.diff(arr) <= 0.0)) + 1
                raise InputError(f"must increase (sample {i + 1})", key=name, value=float(arr[i]))
        if angle is None and (time is None or marks is None):
            raise InputError(
                "a torque record needs the crank angle of its samples, or their times and the "
                "times of a once-per-cycle mark (reference)",
                key="crank_angle",
            )
        if self.speed is not None and not (math.isfinite(self.speed) and self.speed > 0.0):
            raise InputError("the speed must be positive", key="speed", value=self.speed)
        if torque.size < 8:
            raise InputError("a torque record needs at least 8 samples", key="torque")
        object.__setattr__(self, "torque", torque)
        object.__setattr__(self, "crank_angle", angle)
        object.__setattr__(self, "time", time)
        object.__setattr__(self, "reference", marks)

    @property
    def domain(self) -> str:
        """``"angle"`` (crank angles given) or ``"time"`` (times and a once-per-cycle mark)."""
        return "angle" if self.crank_angle is not None else "time"


@dataclass(frozen=True)
class TorqueComparison(Result):
    """The model's torque at the measured span beside the measured orders
    (:func:`compare_torque`)."""

    title = "Model torque at the span"
    span: str = scalar("span", "Span (a - b)", "")
    model_name: str = scalar("model", "Model", "")
    model_amplitude: NDArray[np.float64] = column("model_amplitude_Nm", "Model torque", "N·m")
    model_phase: NDArray[np.float64] = column("model_phase_deg", "Model phase", "deg", DEG)
    ratio: NDArray[np.float64] = column("measured_over_model", "Measured / model", "")
    model_synthesized: float = scalar(
        "model_synthesized_torque_Nm", "Model's synthesised half-range torque", "N·m"
    )
    synthesized_ratio: float = scalar(
        "synthesized_ratio", "Synthesised torque, measured / model", "", fmt=".4g"
    )


@dataclass(frozen=True)
class TorqueSpectrum(Result):
    """Orders of a measured shaft torque at a steady speed (module docstring): per order the
    amplitude and phase of T(psi) = T_0 + sum Re(T_q exp(i q psi)).

    Parameters
    ----------
    cycle_coefficients : numpy.ndarray or None
        (cycles, Q) complex T_q of every single cycle (N m), for plots and checks.
    """

    title = "Measured torque orders"
    speed: float = scalar("speed_rpm", "Mean speed", "rpm", RPM, fmt=".2f")
    orders: NDArray[np.float64] = column("orders", "Order", "")
    amplitude: NDArray[np.float64] = column("amplitude_Nm", "Torque amplitude", "N·m")
    phase: NDArray[np.float64] = column("phase_deg", "Phase", "deg", DEG)
    scatter: NDArray[np.float64] = column("scatter_Nm", "Cycle-to-cycle scatter (RMS)", "N·m")
    mean_torque: float = scalar("mean_torque_Nm", "Mean torque T_0", "N·m")
    synthesized: float = scalar(
        "synthesized_torque_Nm", "Synthesised half-range vibratory torque", "N·m"
    )
    peak_torque: float = scalar("peak_torque_Nm", "Largest torque of the averaged cycle", "N·m")
    cycles: int = scalar("cycles", "Cycles averaged", "")
    samples: int = scalar("samples_per_cycle", "Resampled angles per cycle", "")
    cycle: str = scalar("cycle", "Cycle", "")
    domain: str = scalar("domain", "Record", "")
    source: str = scalar("signal", "Signal", "")
    notes: tuple[str, ...] | None = scalar("notes", "Notes", "", default=None)
    comparison: TorqueComparison | None = scalar("model", "Model", "", default=None)
    cycle_coefficients: NDArray[np.complex128] | None = field(
        default=None, repr=False, compare=False
    )

    @property
    def coefficients(self) -> NDArray[np.complex128]:
        """Complex amplitudes T_q (N m)."""
        return np.asarray(self.amplitude) * np.exp(1j * np.asarray(self.phase))

    def columns(self) -> dict[str, np.ndarray]:
        """The order columns, and the model's beside them (CSV).

        Returns
        -------
        dict of str to numpy.ndarray
            {key: values} in the unit of the key.
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
        self, model: TorsionModel, excitation: Excitation, span: tuple[str, str], **kw: Any
    ) -> TorqueSpectrum:
        """This analysis with the model's torque at the span attached (:func:`compare_torque`).

        Parameters
        ----------
        model : crankdyn.torsion.model.TorsionModel
            The torsional model.
        excitation : crankdyn.torsion.excitation.Excitation
            Its excitation.
        span : tuple of (str, str)
            The masses (a, b) at the ends of the measured span.
        **kw
            Passed to :func:`compare_torque` (``dampers``).

        Returns
        -------
        TorqueSpectrum
            A copy with ``comparison`` set.
        """
        return replace(self, comparison=compare_torque(self, model, excitation, span, **kw))

    def plot(self, fig: Figure | None = None) -> Figure:
        """Torque amplitude per order, measured and the model's
        (:func:`crankdyn.plots.measure_torque.plot_torque_orders`).

        Parameters
        ----------
        fig : matplotlib.figure.Figure or None
            A figure to draw into; default a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.measure_torque import plot_torque_orders

        return plot_torque_orders(self, fig=fig)


def _sample_angles(
    record: TorqueRecord, cycle_angle: float, reference_angle: float
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64] | None]:
    """The crank angle of every sample (rad from cylinder 1's firing TDC), the torques kept,
    and their times (or None)."""
    torque = np.asarray(record.torque)
    if record.crank_angle is not None:
        return np.asarray(record.crank_angle) + reference_angle, torque, record.time
    assert record.time is not None and record.reference is not None  # (__post_init__)
    t, marks = np.asarray(record.time), np.asarray(record.reference)
    inside = (t >= marks[0]) & (t <= marks[-1])
    if marks.size < 2 or np.count_nonzero(inside) < 8:
        raise InputError(
            "the record holds less than one whole cycle between two marks",
            key="reference",
            value=int(marks.size),
        )
    psi = np.interp(t[inside], marks, reference_angle + cycle_angle * np.arange(marks.size))
    return psi, torque[inside], t[inside]


def torque_orders(
    record: TorqueRecord,
    *,
    cycle: str = "four-stroke",
    orders: ArrayLike | None = None,
    reference_angle: float = 0.0,
    samples: int | None = None,
) -> TorqueSpectrum:
    """Orders of a measured shaft torque (module docstring).

    Parameters
    ----------
    record : TorqueRecord
        The torque (N m) over crank angle (rad) or time (s) with once-per-cycle marks.
    cycle : str
        ``"four-stroke"`` (orders 0.5, 1, 1.5, ...) or ``"two-stroke"``.
    orders : array_like or None
        The orders to report (per revolution); default every order of the cycle up to 12.
    reference_angle : float
        Crank angle of cylinder 1 from its firing TDC at the mark, or at the record's angle 0
        (rad).
    samples : int or None
        Resampled angles per cycle L (a power of two is fastest); default the next power of
        two above twice the record's samples per cycle, at least 256.

    Returns
    -------
    TorqueSpectrum
        Mean torque (N m), amplitude (N m) and phase (rad) per order, complex-averaged over the
        record's whole cycles, with the scatter of the single cycles and the synthesised
        half-range torque.

    Raises
    ------
    crankdyn.errors.InputError
        An unknown cycle, orders that are not of the cycle, less than one whole cycle, or
        samples too sparse for the highest order (fewer than
        :data:`MIN_SAMPLES_PER_PERIOD` per period).

    Examples
    --------
    500 N m with 100 N m of order 1.5 and 40 N m of order 3 leading by 90 deg, over four cycles:

    >>> psi = np.linspace(0.0, 16 * np.pi, 2881)
    >>> torque = 500 + 100 * np.cos(1.5 * psi) + 40 * np.cos(3 * psi + np.pi / 2)
    >>> spectrum = torque_orders(TorqueRecord(torque, crank_angle=psi, speed=200.0),
    ...                          orders=[1.5, 3.0])
    >>> round(spectrum.mean_torque, 6), spectrum.cycles
    (500.0, 4)
    >>> [round(float(a), 6) for a in spectrum.amplitude], round(float(spectrum.phase[1]), 6)
    ([100.0, 40.0], 1.570796)
    """
    from scipy.interpolate import CubicSpline

    if cycle not in CYCLE_ANGLE:
        raise InputError("expected four-stroke or two-stroke", key="cycle", value=cycle)
    theta = CYCLE_ANGLE[cycle]
    base = fundamental_order(cycle)
    q = (
        base * np.arange(1, round(12.0 / base) + 1)
        if orders is None
        else check_orders(orders, cycle)
    )
    psi, torque, times = _sample_angles(record, theta, reference_angle)
    first = math.ceil(psi[0] / theta - 1e-9)
    last = math.floor(psi[-1] / theta + 1e-9)
    cycles = last - first
    if cycles < 1:
        raise InputError(
            f"the record spans {(psi[-1] - psi[0]) * DEG:.4g} deg of crank angle: less than one "
            f"whole working cycle ({theta * DEG:g} deg) from a cycle boundary",
            key="crank_angle",
        )
    in_cycles = (psi >= first * theta - 1e-9) & (psi <= last * theta + 1e-9)
    per_rev = np.count_nonzero(in_cycles) / (cycles * theta / (2.0 * math.pi))
    if per_rev < MIN_SAMPLES_PER_PERIOD * float(np.max(q)):
        raise InputError(
            f"{per_rev:.4g} samples per revolution cannot follow order {float(np.max(q)):g} "
            f"(at least {MIN_SAMPLES_PER_PERIOD} samples per period of the highest order)",
            key="orders",
            value=float(np.max(q)),
        )
    per_cycle = per_rev * theta / (2.0 * math.pi)
    if samples is None:
        samples = max(256, 1 << math.ceil(math.log2(2.0 * per_cycle)))
    if isinstance(samples, bool) or int(samples) < 8:
        raise InputError("expected at least 8 samples per cycle", key="samples", value=samples)
    n = int(samples)
    grid = first * theta + theta * np.arange(cycles * n) / n
    values = CubicSpline(psi, torque)(grid).reshape(cycles, n)
    spectrum = np.fft.rfft(values, axis=1)
    m = harmonic_index(q, cycle)
    if int(np.max(m)) > n // 2 - 1:
        raise InputError("too few samples per cycle for the orders", key="samples", value=n)
    per = spectrum[:, m] * (2.0 / n)
    mean = np.mean(per, axis=0)
    scatter = np.sqrt(np.mean(np.abs(per - mean) ** 2, axis=0))
    average = np.mean(values, axis=0)
    top, low = half_range(mean, m)
    notes = []
    speed = record.speed
    if times is not None:
        t_bound = np.interp(first * theta + theta * np.arange(cycles + 1), psi, times)
        cycle_speed = theta / np.diff(t_bound)
        speed = theta * cycles / float(t_bound[-1] - t_bound[0])
        spread = float((cycle_speed.max() - cycle_speed.min()) / np.mean(cycle_speed))
        if spread > STEADY_LIMIT:
            notes.append(
                f"the cycle speeds spread by {spread:.1%} of their mean: a steady-speed average "
                "blurs orders that change with speed"
            )
    if speed is None:
        raise InputError(
            "an angle-domain record without times needs its mean speed", key="speed", value=None
        )
    return TorqueSpectrum(
        speed=float(speed),
        orders=freeze(q),
        amplitude=freeze(np.abs(mean)),
        phase=freeze(np.angle(mean)),
        scatter=freeze(scatter),
        mean_torque=float(np.mean(values)),
        synthesized=float(0.5 * (top - low)),
        peak_torque=float(np.max(average)),
        cycles=int(cycles),
        samples=n,
        cycle=cycle,
        domain=record.domain,
        source=record.source,
        notes=tuple(notes) or None,
        cycle_coefficients=per,
    )


def compare_torque(
    spectrum: TorqueSpectrum,
    model: TorsionModel,
    excitation: Excitation,
    span: tuple[str, str],
    *,
    dampers: tuple[Damper, ...] | None = None,
) -> TorqueComparison:
    """The model's torque at the measured span beside the measured orders (module docstring).

    Parameters
    ----------
    spectrum : TorqueSpectrum
        The measured orders (N m) and the mean speed (rad/s).
    model : crankdyn.torsion.model.TorsionModel
        The torsional model.
    excitation : crankdyn.torsion.excitation.Excitation
        Its excitation.
    span : tuple of (str, str)
        The masses (a, b) at the ends of the measured span (a shaft of the model).
    dampers : tuple of Damper or None
        The dampers of the response; None: the model's own.

    Returns
    -------
    TorqueComparison
        The model's complex torque per order at the span (N m, phase rad), measured / model
        per order, and the synthesised half-range torques.

    Raises
    ------
    crankdyn.errors.InputError
        No shaft between the two masses (key ``shaft``), or the orders of another cycle than
        the excitation's (key ``cycle``).
    """
    from crankdyn.torsion.sweep import forced_response

    if excitation.cycle != spectrum.cycle:
        raise InputError(
            f"the model's excitation is {excitation.cycle}", key="cycle", value=spectrum.cycle
        )
    response = forced_response(
        model, excitation, [spectrum.speed], spectrum.orders, dampers=dampers, resolve=False
    )
    k = response.shaft_index(tuple(span))
    assert response.shaft_response is not None  # forced_response fills it
    a, b = response.shafts[k]
    torque = np.asarray(response.shaft_response[0, :, k])
    m = harmonic_index(spectrum.orders, spectrum.cycle)
    top, low = half_range(torque, m)
    model_half = float(0.5 * (top - low))
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(np.abs(torque) > 0.0, np.asarray(spectrum.amplitude) / np.abs(torque),
                         np.nan)  # fmt: skip
    return TorqueComparison(
        span=f"{a} - {b}",
        model_name=model.name,
        model_amplitude=freeze(np.abs(torque)),
        model_phase=freeze(np.angle(torque)),
        ratio=freeze(ratio),
        model_synthesized=model_half,
        synthesized_ratio=spectrum.synthesized / model_half if model_half > 0.0 else math.nan,
    )
