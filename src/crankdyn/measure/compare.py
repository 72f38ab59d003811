"""The model held against the measurement (analysis and results): the model's forced response
at the measured mass beside the measured orders, the resonance peaks compared, and the damping
identified from a measured resonance written back as a model value.

**Prediction.** :func:`crankdyn.torsion.sweep.forced_response` at the measured speeds (the
steady speed, or every speed bin of a run-up) and on a fine grid over the measured range for
plots, at the mass that carries the wheel, every order and synthesised (the same half-range
synthesis as the measurement's). The wheel must turn with the crankshaft (speed ratio 1): its
orders are then orders of the crank speed.

**Resonance peaks.** For every measured resonance (:mod:`crankdyn.measure.resonance`) the
model's peak of the same order nearest to it: the local maximum of the model's amplitude on the
fine grid, refined by evaluating the response on finer grids around it (four zooms, each 80
times finer) so that neither the grid nor the display moves it; its speed and amplitude beside
the measured ones.

**Damping written back.** The measured resonance with the largest peak is the model's mode with
the nearest natural frequency. The same single-mode fit applied to the model's predicted
response of that order gives the model's damping ratio of the resonance. The value written back
is the loss factor eta that, given to every shaft of the model (replacing the shafts' loss
factors; absolute and relative viscous damping and dampers kept), makes that fit return the
measured damping ratio: found by Brent's method (R. P. Brent, *Algorithms for Minimization
without Derivatives*, Prentice-Hall 1973, ch. 4) on eta, the model's damping ratio rising with
eta (for a mode whose damping is all hysteretic in the shafts, zeta = eta / 2). Identified and
applied the same way, the model then reproduces the measured damping of that resonance; its
peak amplitude with eta is reported beside the measured one as the check of the excitation.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, cast

import numpy as np

from crankdyn.constants import DEG, RPM
from crankdyn.errors import InputError
from crankdyn.measure.resonance import BAND, ResonanceFit, fit_resonance
from crankdyn.results import Result, array, freeze, scalar
from crankdyn.torsion.modal import natural_modes
from crankdyn.torsion.response import ResponseResult
from crankdyn.torsion.sweep import forced_response

if TYPE_CHECKING:
    from crankdyn.measure.orders import OrderSpectrum, OrderTracking
    from crankdyn.torsion.dampers import Damper
    from crankdyn.torsion.excitation import Excitation
    from crankdyn.torsion.model import TorsionModel

__all__ = [
    "DampingEstimate",
    "ModelComparison",
    "ResonancePeak",
    "compare_with_model",
    "with_shaft_loss_factor",
]

HZ = 1.0 / (2.0 * math.pi)
"""Hz per rad/s."""
CURVE_POINTS = 401
"""Speeds of the model's fine curve over the measured range."""
_ZOOMS = 4
_ZOOM_POINTS = 81


def with_shaft_loss_factor(model: TorsionModel, loss_factor: float) -> TorsionModel:
    """The model with every shaft's loss factor set to one value, everything else kept.

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The torsional model.
    loss_factor : float
        The shafts' loss factor eta (dimensionless), >= 0.

    Returns
    -------
    crankdyn.torsion.model.TorsionModel
        A copy with every shaft's ``loss_factor`` replaced.
    """
    shafts = tuple(replace(s, loss_factor=float(loss_factor)) for s in model.shafts)
    return replace(model, shafts=shafts)


def _loss_factors(model: TorsionModel) -> str:
    values = sorted({s.loss_factor for s in model.shafts})
    if not values:
        return "no shafts"
    if len(values) == 1:
        return f"{values[0]:.4g} on every shaft"
    return f"{values[0]:.4g} to {values[-1]:.4g}"


@dataclass(frozen=True)
class ResonancePeak(Result):
    """One order's measured resonance beside the model's peak of the same order (module
    docstring)."""

    title = "Resonance peak"
    order: float = scalar("order", "Order", "")
    measured_speed: float = scalar("measured_speed_rpm", "Measured peak at", "rpm", RPM, fmt=".1f")
    measured_amplitude: float = scalar("measured_amplitude_rad", "Measured peak", "rad")
    model_speed: float = scalar("model_speed_rpm", "Model peak at", "rpm", RPM, fmt=".1f")
    model_amplitude: float = scalar("model_amplitude_rad", "Model peak", "rad")
    model_peak_inside: bool = scalar("model_peak_inside", "Model peak inside the range", "")
    damping: float = scalar("damping_ratio", "Damping ratio (single-mode fit)", "", fmt=".4g")
    half_power_damping: float | None = scalar(
        "half_power_damping_ratio", "Damping ratio (half-power)", "", fmt=".4g"
    )
    model_damping: float | None = scalar(
        "model_damping_ratio", "Model's damping ratio (same fit)", "", fmt=".4g"
    )
    natural_frequency: float = scalar(
        "natural_frequency_hz", "Natural frequency (fit)", "Hz", HZ, fmt=".2f"
    )

    @property
    def speed_difference(self) -> float:
        """(measured - model) peak speed over the model's (dimensionless)."""
        return self.measured_speed / self.model_speed - 1.0

    @property
    def amplitude_ratio(self) -> float:
        """Measured over model peak amplitude (dimensionless)."""
        return self.measured_amplitude / self.model_amplitude


@dataclass(frozen=True)
class DampingEstimate(Result):
    """The damping identified from the largest measured resonance and the model value that
    reproduces it (module docstring)."""

    title = "Identified damping"
    order: float = scalar("order", "From order", "")
    critical_speed: float = scalar("critical_speed_rpm", "Resonance at", "rpm", RPM, fmt=".1f")
    natural_frequency: float = scalar(
        "natural_frequency_hz", "Measured natural frequency", "Hz", HZ, fmt=".2f"
    )
    mode_frequency: float = scalar(
        "mode_frequency_hz", "Model's nearest natural frequency", "Hz", HZ, fmt=".2f"
    )
    mode_nodes: int = scalar("mode_nodes", "Nodes of that mode", "")
    damping: float = scalar(
        "damping_ratio", "Measured damping ratio (single-mode fit)", "", fmt=".4g"
    )
    half_power_damping: float | None = scalar(
        "half_power_damping_ratio", "Measured damping ratio (half-power)", "", fmt=".4g"
    )
    model_damping: float = scalar(
        "model_damping_ratio", "Model's damping ratio (same fit)", "", fmt=".4g"
    )
    current_loss_factor: str = scalar("model_loss_factor", "Model's shaft loss factors", "")
    loss_factor: float | None = scalar(
        "loss_factor", "Shaft loss factor that reproduces it", "", fmt=".4g"
    )
    measured_peak: float = scalar("measured_peak_rad", "Measured peak", "rad")
    model_peak: float = scalar("model_peak_rad", "Model peak (as given)", "rad")
    corrected_peak: float | None = scalar(
        "corrected_model_peak_rad", "Model peak with that loss factor", "rad"
    )
    advice: str = scalar("apply", "Apply", "")


@dataclass(frozen=True)
class ModelComparison(Result):
    """The model's prediction at the measured mass (module docstring): per order and
    synthesised at the measured speed(s), a fine curve for plots, the resonance peaks compared
    and the identified damping.

    Parameters
    ----------
    orders : numpy.ndarray or None
        The measured orders (per revolution), the columns of ``amplitude``.
    steady : bool
        The measurement is at a steady speed (one row), not a run-up or run-down.
    """

    title = "Model vs measurement"
    name: str = scalar("name", "Model", "")
    mass: str = scalar("mass", "At mass", "")
    excitation: str = scalar("excitation", "Excitation", "")
    amplitude: np.ndarray = array("amplitude_rad", "Model amplitude (speed x order)", "rad")
    phase: np.ndarray = array("phase_deg", "Model phase (speed x order)", "deg", DEG)
    synthesized: np.ndarray = array(
        "synthesized_amplitude_rad", "Model synthesised half-range amplitude", "rad"
    )
    curve_speed: np.ndarray | None = array(
        "curve_speed_rpm", "Speeds of the fine curve", "rpm", RPM, default=None
    )
    curve_amplitude: np.ndarray | None = array(
        "curve_amplitude_rad",
        "Model amplitude on the fine curve (speed x order)",
        "rad",
        default=None,
    )
    curve_synthesized: np.ndarray | None = array(
        "curve_synthesized_amplitude_rad",
        "Model synthesised amplitude on the fine curve",
        "rad",
        default=None,
    )
    peaks: tuple[ResonancePeak, ...] = scalar("resonances", "Resonance peaks", "", default=())
    damping: DampingEstimate | None = scalar("damping", "Identified damping", "", default=None)
    notes: tuple[str, ...] | None = scalar("notes", "Notes", "", default=None)
    model_at_peak: float | None = scalar(
        "model_at_measured_peak_rad",
        "Model synthesised amplitude where the measured one is largest",
        "rad",
        default=None,
        summary=False,
    )
    orders: np.ndarray | None = None
    steady: bool = False

    def columns(self) -> dict[str, np.ndarray]:
        """The model's columns beside the measured ones (CSV).

        Returns
        -------
        dict of str to numpy.ndarray
            Steady: ``model_amplitude_rad`` (rad) and ``model_phase_deg`` (deg) per order; a
            run-up: ``model_synthesized_amplitude_rad`` and ``model_order_<q>_amplitude_rad``
            (rad) per speed bin.
        """
        out: dict[str, np.ndarray] = {}
        if self.steady:
            out["model_amplitude_rad"] = np.asarray(self.amplitude[0])
            out["model_phase_deg"] = np.asarray(self.phase[0]) * DEG
            return out
        out["model_synthesized_amplitude_rad"] = np.asarray(self.synthesized)
        for i, q in enumerate(() if self.orders is None else self.orders):
            out[f"model_order_{q:g}_amplitude_rad"] = np.asarray(self.amplitude[:, i])
        return out

    def column_labels(self) -> dict[str, tuple[str, str]]:
        """Label and unit of every column of :meth:`columns`.

        Returns
        -------
        dict of str to (str, str)
            {column key: (label, unit)}.
        """
        out = {}
        for key in self.columns():
            if key == "model_amplitude_rad":
                out[key] = ("Model amplitude", "rad")
            elif key == "model_phase_deg":
                out[key] = ("Model phase", "deg")
            elif key == "model_synthesized_amplitude_rad":
                out[key] = ("Model synthesised", "rad")
            else:
                out[key] = (f"Model order {key.split('_')[2]}", "rad")
        return out


def _response(model, excitation, speeds, orders, dampers):
    # the model at exactly the measured speeds (no resolution: compared point by point)
    return forced_response(
        model, excitation, np.asarray(speeds, dtype=float), orders, dampers=dampers, resolve=False
    )


def _mass_column(result: ResponseResult, at: str) -> int:
    return result.mass_index(at)


def _model_peak(model, excitation, order, mass, speeds, amplitude, near, dampers):
    """The model's peak of one order nearest to ``near`` (rad/s): (speed, amplitude, inside)."""
    a = np.asarray(amplitude)
    inner = np.flatnonzero((a[1:-1] >= a[:-2]) & (a[1:-1] >= a[2:])) + 1
    if inner.size == 0:
        j = int(np.argmax(a))
        return float(speeds[j]), float(a[j]), False
    j = int(inner[np.argmin(np.abs(speeds[inner] - near))])
    lo, hi = speeds[j - 1], speeds[j + 1]
    best = (float(speeds[j]), float(a[j]))
    for _ in range(_ZOOMS):
        grid = np.linspace(lo, hi, _ZOOM_POINTS)
        r = _response(model, excitation, grid, [order], dampers)
        amp = r.amplitude[:, 0, mass]
        k = int(np.argmax(amp))
        best = (float(grid[k]), float(amp[k]))
        step = grid[1] - grid[0]
        lo, hi = grid[k] - step, grid[k] + step
    return best[0], best[1], True


def _model_fit(
    model: TorsionModel,
    excitation: Excitation,
    order: float,
    mass: int,
    centre: float,
    width: float,
    dampers: Sequence[Damper] | None,
) -> ResonanceFit | None:
    """The single-mode fit of the model's own response of one order around ``centre``
    (rad/s), sampled at 241 speeds over +-2 BAND half-bandwidths ``width`` (rad/s); wider and
    narrower spans are tried when the model's resonance is much broader or sharper than that."""
    for factor in (1.0, 3.0, 0.2, 10.0, 0.04):
        span = 2.0 * BAND * width * factor
        speeds = np.linspace(max(centre - span, 1e-3 * centre), centre + span, 241)
        r = _response(model, excitation, speeds, [order], dampers)
        values = r.mass_response[:, 0, mass]
        if not np.all(np.isfinite(values)):
            continue
        fit = fit_resonance(order, speeds, values)
        if fit is not None:
            return fit
    return None


def compare_with_model(
    measured: OrderSpectrum | OrderTracking,
    model: TorsionModel,
    excitation: Excitation,
    at: str,
    *,
    dampers: Sequence[Damper] | None = None,
) -> ModelComparison:
    """The model's forced response at mass ``at`` beside a measurement (module docstring).

    Parameters
    ----------
    measured : OrderSpectrum or OrderTracking
        The measured orders (:func:`crankdyn.measure.orders.order_analysis`).
    model : crankdyn.torsion.model.TorsionModel
        The torsional model.
    excitation : crankdyn.torsion.excitation.Excitation
        Its excitation (:func:`crankdyn.torsion.excitation.excitation_for`).
    at : str
        The mass that carries the measured wheel.
    dampers : sequence of crankdyn.torsion.dampers.Damper or None
        As for :func:`~crankdyn.torsion.sweep.forced_response` (None: the model's own).

    Returns
    -------
    ModelComparison
        The model's amplitudes (rad) and phases (rad) at the measured speeds, and for a run-up
        the fine curve, the resonance peaks (rpm, rad) and the identified damping.

    Raises
    ------
    InputError
        If the measurement and the excitation have different cycles, or the mass does not turn
        with the crankshaft (or is not in the model).
    """
    if excitation.cycle != measured.cycle:
        raise InputError(
            f"the signal was analysed as {measured.cycle}, the model's excitation is "
            f"{excitation.cycle}",
            key="cycle",
            value=measured.cycle,
        )
    if at in model.mass_names:
        ratio = float(model.speed_ratios[model.index(at)])
        if abs(ratio - 1.0) > 1e-9:
            raise InputError(
                f'mass "{at}" turns at {ratio:g} times the crankshaft speed; the wheel must turn '
                "with the crankshaft (its orders are orders of the crank speed)",
                key="--at",
                value=at,
            )
    orders = np.asarray(measured.orders)
    steady = measured.kind == "steady"
    speeds = np.atleast_1d(np.asarray(measured.speed, dtype=float))
    result = _response(model, excitation, speeds, orders, dampers)
    i = _mass_column(result, at)
    x = result.mass_response[:, :, i]
    notes = list(result.notes or ())
    common = {
        "name": model.name,
        "mass": at,
        "excitation": result.excitation,
        "amplitude": freeze(np.abs(x)),
        "phase": freeze(np.angle(x)),
        "synthesized": freeze(result.synthesized_amplitude[:, i]),
        "orders": orders,
    }
    if steady:
        at_peak = float(result.synthesized_amplitude[0, i])
        return ModelComparison(
            steady=True, notes=tuple(notes) or None, model_at_peak=at_peak, **common
        )
    tracking = cast("OrderTracking", measured)  # not steady: an order tracking
    top = float(tracking.window_speed[int(np.argmax(tracking.window_synthesized))])
    there = _response(model, excitation, [top], orders, dampers)
    at_peak = float(there.synthesized_amplitude[0, i])
    lo, hi = float(np.min(tracking.window_speed)), float(np.max(tracking.window_speed))
    grid = np.linspace(lo, hi, CURVE_POINTS)
    curve = _response(model, excitation, grid, orders, dampers)
    peaks = []
    for fit in tracking.resonances or ():
        j = int(np.argmin(np.abs(orders - fit.order)))
        speed, amp, inside = _model_peak(
            model,
            excitation,
            fit.order,
            i,
            grid,
            curve.amplitude[:, j, i],
            fit.peak_speed,
            dampers,
        )
        model_fit = (
            _model_fit(model, excitation, fit.order, i, speed, fit.damping * speed, dampers)
            if inside
            else None
        )
        peaks.append(
            ResonancePeak(
                order=fit.order,
                measured_speed=fit.peak_speed,
                measured_amplitude=fit.peak_amplitude,
                model_speed=speed,
                model_amplitude=amp,
                model_peak_inside=inside,
                damping=fit.damping,
                half_power_damping=fit.half_power_damping,
                model_damping=None if model_fit is None else model_fit.damping,
                natural_frequency=fit.natural_frequency,
            )
        )
        if not inside:
            notes.append(f"order {fit.order:g}: the model has no peak inside the measured range")
    damping = _identify(measured, model, excitation, at, i, peaks, dampers, notes)
    return ModelComparison(
        curve_speed=freeze(grid),
        curve_amplitude=freeze(curve.amplitude[:, :, i]),
        curve_synthesized=freeze(curve.synthesized_amplitude[:, i]),
        peaks=tuple(peaks),
        damping=damping,
        notes=tuple(notes) or None,
        model_at_peak=at_peak,
        **common,
    )


def _identify(measured, model, excitation, at, mass, peaks, dampers, notes):
    """The damping estimate of the largest measured resonance (module docstring)."""
    usable = [p for p in peaks if p.model_peak_inside and p.model_damping is not None]
    if not usable:
        if peaks:
            notes.append(
                "no measured resonance has a model peak to compare: damping not written back"
            )
        return None
    peak = max(usable, key=lambda p: p.measured_amplitude)
    fit = next(f for f in measured.resonances if f.order == peak.order)
    modes = natural_modes(model)
    freq = np.asarray(modes.natural_frequency)
    elastic = np.flatnonzero(freq > 0.0)
    m = int(elastic[np.argmin(np.abs(freq[elastic] - fit.natural_frequency))])
    target = fit.damping
    centre, width = peak.model_speed, target * peak.model_speed

    def zeta(eta: float) -> float:
        variant = with_shaft_loss_factor(model, eta)
        f = _model_fit(variant, excitation, fit.order, mass, centre, max(width, 1e-9), dampers)
        if f is None:
            raise _NoFit
        return f.damping

    eta = corrected = None
    try:
        try:
            bottom = 0.0
            low = zeta(bottom) - target
        except _NoFit:  # no other damping: an undamped resonance, no peak to fit at eta = 0
            bottom = 0.2 * target
            low = zeta(bottom) - target
        if low > 0.0:
            notes.append(
                f"the model's other damping alone gives a damping ratio of {low + target:.4g} at "
                f"order {fit.order:g}, above the measured {target:.4g}: no shaft loss factor "
                "reproduces it (reduce the viscous or damper damping)"
            )
        else:
            high = max(4.0 * target, 0.01)
            above = zeta(high) - target
            while above < 0.0 and high < 2.0:
                high *= 2.0
                above = zeta(high) - target
            if above >= 0.0:
                from scipy.optimize import brentq  # imported here: keeps the start-up light

                eta = float(brentq(lambda e: zeta(e) - target, bottom, high, xtol=1e-7, rtol=1e-10))
                variant = with_shaft_loss_factor(model, eta)
                lo, hi = centre * (1 - 3 * target), centre * (1 + 3 * target)
                grid = np.linspace(lo, hi, 81)
                rr = _response(variant, excitation, grid, [fit.order], dampers)
                _s, corrected, _inside = _model_peak(
                    variant,
                    excitation,
                    fit.order,
                    mass,
                    grid,
                    rr.amplitude[:, 0, mass],
                    centre,
                    dampers,
                )
    except _NoFit:
        notes.append("the model's resonance could not be fitted: damping not written back")
    if eta is None:
        advice = "keep the model's damping (see the notes)"
    else:
        advice = (
            f"loss_factor = {eta:.4g} on every [[shaft]] of the model (now "
            f"{_loss_factors(model)}): reproduces the measured damping ratio {target:.4g} of "
            f"order {fit.order:g} at {fit.critical_speed * RPM:.0f} rpm"
        )
    return DampingEstimate(
        order=fit.order,
        critical_speed=fit.critical_speed,
        natural_frequency=fit.natural_frequency,
        mode_frequency=float(freq[m]),
        mode_nodes=int(modes.node_count[m]),
        damping=target,
        half_power_damping=fit.half_power_damping,
        model_damping=float(peak.model_damping),
        current_loss_factor=_loss_factors(model),
        loss_factor=eta,
        measured_peak=fit.peak_amplitude,
        model_peak=peak.model_amplitude,
        corrected_peak=corrected,
        advice=advice,
    )


class _NoFit(Exception):
    pass
