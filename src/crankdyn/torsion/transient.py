"""Time-domain torsional vibration driven by the engine torque (analysis).

The lumped model's equations of motion (:mod:`crankdyn.torsion.response`) are integrated in
time for the vibratory angles theta relative to the crankshaft's mean rotation phi(t)
(reflected, rad):

    M theta'' + (C + H / omega_h) theta' + K theta = T(t),
    T(t) = sum_q Re( F_q(Omega(t)) exp(i q phi(t)) ),

with F_q the cylinders' and the excitation sources' harmonic torques on their masses at the
current speed (:mod:`crankdyn.torsion.excitation`,
:func:`crankdyn.torsion.sources.assemble_forcing`; the same orders as the frequency-domain
solution, so the
steady state of a run at constant speed must equal the sum of the orders' steady-state
responses; with enough orders T(t) is the engine's torque waveform less its mean). The mean torque
and, in a run-up, the inertia torque of the mean acceleration are taken by the load (a
quasi-static twist that is not part of the vibration). Hysteretic damping has no exact
time-domain form; the loss factors enter as viscous damping eta k / omega_h at the frequency
omega_h (default: the lowest elastic natural frequency, where resonance makes damping matter
most); the frequency-domain solution with ``hysteretic_frequency = omega_h`` is the same linear
system.

Speed: constant Omega, or a linear run-up Omega(t) = Omega_0 + (Omega_1 - Omega_0) t / t_end with
phi(t) = Omega_0 t + (Omega_1 - Omega_0) t^2 / (2 t_end); the harmonic torques at Omega(t) are
interpolated from a grid of speeds.

Integration (``method``): by default ``"modal"``, the undamped modes up to a cut-off frequency
omega_c (8 times the highest excitation frequency unless given) integrated exactly between
samples of a cubic hold of the torque, the modes above omega_c taken quasi-steadily
(:mod:`crankdyn.torsion.modal_run`): the work grows linearly with the number of masses, with no
Python call per step, and the result states omega_c and the estimate of the truncation error
(the change of the shaft torques when omega_c is halved, relative to the largest). At constant
speed the quasi-steady part is exact, so a run started in the steady state stays there. The
name of a ``scipy.integrate.solve_ivp`` method (``"DOP853"``, Dormand-Prince of order 8, after
Hairer, Norsett and Wanner 1993; ``"Radau"``...) integrates the first-order system
y' = A y + B T(t) of every degree of freedom instead (the reference: a Python call per step,
the step limited by the highest natural frequency).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.errors import InputError, did_you_mean
from crankdyn.results import Result, array, column, freeze, scalar
from crankdyn.summary import SummaryColumn, SummaryTable
from crankdyn.torsion.excitation import interp_complex
from crankdyn.torsion.solvers import LinearSystem, linear_system
from crankdyn.torsion.sources import assemble_forcing, check_model_orders

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from crankdyn.torsion.dampers import Damper
    from crankdyn.torsion.excitation import Excitation
    from crankdyn.torsion.model import TorsionModel

__all__ = ["TransientResult", "transient_response"]

from crankdyn.constants import CYCLE_ANGLE, DEG, RPM


@dataclass(frozen=True)
class TransientResult(Result):
    """Angles and shaft torques against time (module docstring).

    ``angle`` holds the vibratory angle of every listed mass (the model's masses, then the
    damper rings; the actual angle of a geared mass, its reflected angle times its speed
    ratio), ``shaft_torque`` the elastic torque k (theta_b - theta_a) of every shaft and damper
    coupling (actual stiffness and angles), both against ``time``.

    Examples
    --------
    >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
    >>> from crankdyn.torsion.excitation import UniformExcitation
    >>> model = TorsionModel(
    ...     masses=(Mass("m", 1.0, damping=20.0, cylinders=(1,)),),
    ...     shafts=(Shaft(("ground", "m"), 1e6),),
    ... )
    >>> run = transient_response(
    ...     model, UniformExcitation(100.0, [0.0], "two-stroke"), [1.0], speed=900.0, cycles=2
    ... )
    >>> run.angle.shape, run.masses, run.shafts
    ((1441, 1), ('m',), (('ground', 'm'),))
    >>> sorted(run.columns())[:4]
    ['angle_rad.m', 'crank_angle_deg', 'shaft_torque_Nm.ground - m', 'speed_rpm']
    """

    title = "Time-domain response"
    time: np.ndarray = column("time_s", "Time", "s")
    speed: np.ndarray = column("speed_rpm", "Speed", "rpm", RPM)
    crank_angle: np.ndarray = column("crank_angle_deg", "Crank angle", "deg", DEG)
    angle: np.ndarray = array("angle_rad", "Vibratory angle (time x mass)", "rad")
    shaft_torque: np.ndarray = array("shaft_torque_Nm", "Shaft torque (time x shaft)", "N·m")
    masses: tuple[str, ...] = scalar("masses", "Masses", "")
    shafts: tuple[tuple[str, str], ...] = scalar("shafts", "Shafts", "")
    orders: np.ndarray = array("orders", "Orders", "")
    hysteretic_frequency: float = scalar(
        "hysteretic_frequency_hz", "Loss factors as viscous at", "Hz", 1.0 / (2.0 * math.pi)
    )
    method: str = scalar("method", "Integrator", "")
    model_name: str = scalar("model", "Model", "", summary=False)
    modal_cutoff: float | None = scalar(
        "modal_cutoff_hz",
        "Modes integrated in time up to",
        "Hz",
        1.0 / (2.0 * math.pi),
        default=None,
    )
    modes_integrated: int | None = scalar(
        "modes_integrated", "Modes integrated in time", "", default=None
    )
    truncation_error: float | None = scalar(
        "truncation_error",
        "Modal truncation error (estimate, of the largest torque)",
        "",
        better="min",
        description="the largest change of a shaft torque when the cut-off frequency is halved, "
        "relative to the largest shaft torque of the run",
        default=None,
    )
    cycle_angle: float = scalar(
        "cycle_angle_deg", "Working cycle", "deg", DEG, summary=False, default=4.0 * math.pi
    )

    def summary_tables(self) -> list[SummaryTable]:
        """The shaft torques per shaft: the half range (max - min) / 2 over the last working
        cycle (the vibratory torque amplitude once the start has died out) and the largest
        |T| over the whole run (the start's transient included).

        Returns
        -------
        list of crankdyn.summary.SummaryTable
            One table, a row per shaft and damper coupling (N m).
        """
        last = self.last_cycle(self.cycle_angle)
        torque = self.shaft_torque
        half = 0.5 * (np.max(torque[last], axis=0) - np.min(torque[last], axis=0))
        largest = np.max(np.abs(torque), axis=0)
        rows = tuple(
            (f"{a} - {b}", float(half[s]), float(largest[s]))
            for s, (a, b) in enumerate(self.shafts)
        )
        return [
            SummaryTable(
                "shaft_torques",
                f"{self.model_name}: shaft torques, last cycle",
                (
                    SummaryColumn("shaft", "Shaft"),
                    SummaryColumn("half_range_Nm", "Half range", "N·m"),
                    SummaryColumn("largest_abs_Nm", "Largest |T| over the run", "N·m"),
                ),
                rows,
                caption=f"{self.time.size} samples to {self.time[-1]:.4g} s; loss factors "
                f"as viscous at {self.hysteretic_frequency / (2 * math.pi):.4g} Hz",
            )
        ]

    def last_cycle(self, cycle_angle: float) -> np.ndarray:
        """Mask of the samples in the last working cycle.

        Parameters
        ----------
        cycle_angle : float
            The working cycle's crank angle (rad): 4 pi for a four-stroke engine, 2 pi for a
            two-stroke one.

        Returns
        -------
        numpy.ndarray
            (T,) bool, True where the crank angle lies less than ``cycle_angle`` before the
            last sample's (one period, its first point, the repeat of the last, left out).

        Examples
        --------
        >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
        >>> from crankdyn.torsion.excitation import UniformExcitation
        >>> model = TorsionModel(
        ...     masses=(Mass("m", 1.0, damping=20.0, cylinders=(1,)),),
        ...     shafts=(Shaft(("ground", "m"), 1e6),),
        ... )
        >>> run = transient_response(
        ...     model, UniformExcitation(100.0, [0.0], "two-stroke"), [1.0], speed=900.0, cycles=2
        ... )
        >>> int(run.last_cycle(2 * np.pi).sum())  # 720 samples per cycle
        720
        """
        return self.crank_angle >= self.crank_angle[-1] - cycle_angle * (1 - 1e-12)

    def columns(self) -> dict[str, np.ndarray]:
        """The time columns, and one column per mass (``angle_rad.<mass>``) and per shaft
        (``shaft_torque_Nm.<a> - <b>``) for the CSV.

        Returns
        -------
        dict of str to numpy.ndarray
            {key: values} in the unit of the key (:meth:`crankdyn.results.Result.columns`).
        """
        out = super().columns()
        for i, name in enumerate(self.masses):
            out[f"angle_rad.{name}"] = self.angle[:, i]
        for s, (a, b) in enumerate(self.shafts):
            out[f"shaft_torque_Nm.{a} - {b}"] = self.shaft_torque[:, s]
        return out

    def column_labels(self) -> dict[str, tuple[str, str]]:
        """Label and unit of every column of :meth:`columns`.

        Returns
        -------
        dict of str to (str, str)
            {column key: (label, unit)}.
        """
        out = super().column_labels()
        for _i, name in enumerate(self.masses):
            out[f"angle_rad.{name}"] = (f"Angle {name}", "rad")
        for a, b in self.shafts:
            out[f"shaft_torque_Nm.{a} - {b}"] = (f"Torque {a} - {b}", "N·m")
        return out

    def plot(self, shaft: tuple[str, str] | None = None, fig: Figure | None = None) -> Figure:
        """Shaft torque against time (and speed for a run-up)
        (:func:`crankdyn.plots.torsion_response.plot_transient`).

        Parameters
        ----------
        shaft : (str, str) or None
            The shaft's two ends (mass names); default every shaft.
        fig : matplotlib.figure.Figure or None
            A figure to draw into; default a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.torsion_response import plot_transient

        return plot_transient(self, shaft=shaft, fig=fig)


def transient_response(
    model: TorsionModel,
    excitation: Excitation,
    orders: ArrayLike,
    *,
    speed: float | None = None,
    run_up: tuple[float, float] | None = None,
    duration: float | None = None,
    cycles: float | None = None,
    samples_per_cycle: int = 720,
    dampers: Sequence[Damper] | None = None,
    hysteretic_frequency: float | None = None,
    method: str = "modal",
    rtol: float = 1e-8,
    atol: float | None = None,
    start: str = "rest",
    max_frequency: float | None = None,
) -> TransientResult:
    """Integrate the model's response to the engine torque in time.

    The equations and the forcing are those of the module docstring: seed 003 (the V6 paper's
    eq. 1), integrated in truncated modal coordinates (:mod:`crankdyn.torsion.modal_run`) or by
    ``scipy.integrate.solve_ivp`` (module docstring).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The torsional model (masses carrying cylinders are the excitation points).
    excitation : EngineExcitation or UniformExcitation
        The cylinders' excitation (:func:`crankdyn.torsion.excitation.excitation_for`).
    orders : array_like
        (Q,) orders of the crankshaft speed (multiples of the cycle's fundamental order, or
        orders of the model's sources), as for
        :func:`~crankdyn.torsion.response.forced_response`.
    speed : float or None
        Constant crankshaft speed (rad/s), > 0; or
    run_up : (float, float) or None
        (start, end) speeds (rad/s), > 0, of a linear run-up over ``duration``.
    duration : float or None
        Simulated time (s), > 0 (required for a run-up); or
    cycles : float or None
        Number of working cycles at constant speed (the duration then is
        ``cycles`` x cycle angle / speed).
    samples_per_cycle : int
        Output samples per working cycle at the mean speed (default 720).
    dampers : sequence of Damper or None
        Dampers to add (:class:`~crankdyn.torsion.dampers.Damper`); None: the model's own
        (``model.dampers``); ``()``: none.
    hysteretic_frequency : float or None
        omega_h (rad/s) for the loss factors as viscous damping eta k / omega_h; default the
        lowest elastic natural frequency (1 rad/s when there is none).
    method : str
        ``"modal"`` (default: module docstring) or a ``solve_ivp`` method (``"DOP853"``,
        ``"RK45"``, ``"Radau"``, ...).
    rtol : float
        The relative accuracy (dimensionless, 0 < rtol < 1; default 1e-8): the modal method's
        cubic hold at the highest excitation frequency, or ``solve_ivp``'s rtol.
    atol : float or None
        ``solve_ivp``'s absolute tolerance (rad and rad/s; default 1e-12); the modal method
        has none.
    start : str
        ``"rest"`` (default): no vibration at t = 0; ``"steady"``: the steady state at the
        starting speed, theta(0) = Re sum_q X_q and theta'(0) = Re sum_q i q Omega_0 X_q with
        X_q the frequency-domain solution of the same equations (the loss factors as viscous
        damping at omega_h), so that a run-up starts without a start-up transient.
    max_frequency : float or None
        omega_c (rad/s) of the modal method, > 0: the modes up to it are integrated in time,
        the rest taken quasi-steadily; default 8 times the highest excitation frequency
        (:data:`crankdyn.torsion.modal_run.CUTOFF_FACTOR`).

    Returns
    -------
    TransientResult
        Time (s), speed (rad/s), crank angle (rad), the masses' vibratory angles (rad) and the
        shafts' torques (N m) at the output samples; for the modal method omega_c, the number
        of modes integrated in time and the estimate of the truncation error.

    Raises
    ------
    InputError
        Naming the key and value: neither or both of ``speed`` and ``run_up``, a speed that is
        not positive and finite, neither ``duration`` nor ``cycles`` at constant speed, a run-up
        without a duration, a duration that is not positive, a ``start`` other than ``rest``
        or ``steady``, an unknown method, rtol outside (0, 1), atol given to the modal method,
        a cut-off that is not positive, or orders the model cannot take (``check_model_orders``).

    Examples
    --------
    One damped mass on a grounded shaft, started in its steady state at 900 rad/s: the
    amplitude over the last cycle is that of the single damped mass (seed 003,
    B = T / |k - omega^2 J + i omega c|).

    >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
    >>> from crankdyn.torsion.excitation import UniformExcitation
    >>> model = TorsionModel(
    ...     masses=(Mass("m", 1.0, damping=20.0, cylinders=(1,)),),
    ...     shafts=(Shaft(("ground", "m"), 1e6),),
    ... )
    >>> run = transient_response(
    ...     model, UniformExcitation(100.0, [0.0], "two-stroke"), [1.0],
    ...     speed=900.0, cycles=2, start="steady",
    ... )
    >>> last = run.last_cycle(2 * np.pi)
    >>> amplitude = float(np.max(np.abs(run.angle[last, 0])))
    >>> round(amplitude / (100.0 / abs(1e6 - 900.0**2 + 900j * 20.0)), 5)
    1.0
    """
    w0, w1, duration, cycle_angle = _run_speeds(excitation, speed, run_up, duration, cycles)
    _check_method(method, rtol, atol, max_frequency, start)
    orders = check_model_orders(model, excitation, orders)
    system = linear_system(model, model.dampers if dampers is None else dampers)
    if hysteretic_frequency is None:
        hysteretic_frequency = _lowest_elastic(model)
    grid = np.array([w0]) if w0 == w1 else np.linspace(min(w0, w1), max(w0, w1), 201)
    # the cylinders' and the sources' harmonic torques, as in the forced response
    forcing, _notes = assemble_forcing(model, system, excitation, grid, orders)  # (G, Q, n)
    mean = 0.5 * (w0 + w1)
    count = max(math.ceil(duration * mean / cycle_angle * samples_per_cycle), 2)
    t = np.linspace(0.0, duration, count + 1)
    extra: dict[str, float | int] = {}
    if method == "modal":
        theta, torque, extra = _modal(
            system, forcing, grid, orders, (w0, w1), duration, hysteretic_frequency, start,
            count, max_frequency, rtol,
        )  # fmt: skip
    else:
        t, theta = _integrate(
            system, forcing, grid, orders, (w0, w1), duration, hysteretic_frequency, start,
            t, method, rtol, 1e-12 if atol is None else atol,
        )  # fmt: skip
        torque = _element_torques(system, theta)
    rate = (w1 - w0) / duration
    angles = theta[:, system.mass_dof] * system.mass_ratio[None, :]
    return TransientResult(
        time=freeze(t),
        speed=freeze(w0 + rate * t),
        crank_angle=freeze(w0 * t + 0.5 * rate * t * t),
        angle=freeze(angles),
        shaft_torque=freeze(torque),
        masses=system.mass_names,
        shafts=system.element_labels,
        orders=freeze(orders),
        hysteretic_frequency=float(hysteretic_frequency),
        method=method,
        model_name=model.name,
        cycle_angle=CYCLE_ANGLE[excitation.cycle],
        **extra,  # type: ignore[arg-type]  # the modal method's fields, each of its own type
    )


METHODS = ("modal", "DOP853", "RK45", "RK23", "Radau", "BDF", "LSODA")
"""The integration methods: the modal one and ``scipy.integrate.solve_ivp``'s."""


def _check_method(
    method: str, rtol: float, atol: float | None, cutoff: float | None, start: str
) -> None:
    """One-line errors for the integration settings (:func:`transient_response`)."""
    if start not in ("rest", "steady"):
        raise InputError("expected rest or steady", key="start", value=start)
    if method not in METHODS:
        raise InputError(
            f"unknown integration method{did_you_mean(method, METHODS)}",
            key="method",
            value=method,
        )
    if not (math.isfinite(rtol) and 0.0 < rtol < 1.0):
        raise InputError("the relative tolerance must lie between 0 and 1", key="rtol", value=rtol)
    if method == "modal" and atol is not None:
        raise InputError(
            "the modal method has no absolute tolerance (give rtol, or a solve_ivp method)",
            key="atol",
            value=atol,
        )
    if cutoff is not None and not (math.isfinite(cutoff) and cutoff > 0.0):
        raise InputError(
            "the cut-off frequency must be positive", key="max_frequency", value=cutoff
        )
    if method != "modal" and cutoff is not None:
        raise InputError(
            "the cut-off frequency applies to the modal method only",
            key="max_frequency",
            value=cutoff,
        )


def _modal(
    system: LinearSystem,
    forcing: NDArray[np.complex128],
    grid: NDArray[np.float64],
    orders: NDArray[np.float64],
    speeds: tuple[float, float],
    duration: float,
    hysteretic_frequency: float,
    start: str,
    count: int,
    cutoff: float | None,
    rtol: float,
) -> tuple[NDArray[np.float64], NDArray[np.float64], dict[str, float | int]]:
    """The modal method's angles (T, n) (rad), element torques (T, E) (N m) and the result's
    fields omega_c, modes integrated and the truncation error estimate
    (:func:`crankdyn.torsion.modal_run.harmonic_run`; the estimate relative to the largest
    element torque)."""
    from crankdyn.torsion.modal_run import harmonic_run

    run = harmonic_run(
        system, forcing, grid, orders, speeds, duration, hysteretic_frequency, start, count,
        cutoff=cutoff, rtol=rtol,
    )  # fmt: skip
    change = _element_torques(system, run.change)
    torque = _element_torques(system, run.angles)
    top = float(np.max(np.abs(torque), initial=0.0))
    error = float(np.max(np.abs(change), initial=0.0)) / top if top else 0.0
    return (
        run.angles,
        torque,
        {"modal_cutoff": run.cutoff, "modes_integrated": run.modes, "truncation_error": error},
    )


def _lowest_elastic(model: TorsionModel) -> float:
    """The lowest elastic natural frequency of ``model`` (rad/s), 1 rad/s when there is none
    (the default omega_h of :func:`transient_response`)."""
    from crankdyn.torsion.modal import natural_modes

    modes = natural_modes(model)
    elastic = modes.natural_frequency[modes.natural_frequency > 0.0]
    return float(elastic[0]) if elastic.size else 1.0


def _element_torques(system: LinearSystem, theta: NDArray[np.float64]) -> NDArray[np.float64]:
    """The elastic torque k (theta_b - theta_a) of every shaft and damper coupling (actual
    stiffness and angles, N m) at every sample, from the reflected angles (T, n) (rad)."""
    ends = system.element_dofs
    ta = np.where(ends[:, 0] >= 0, theta[:, np.maximum(ends[:, 0], 0)], 0.0)
    tb = np.where(ends[:, 1] >= 0, theta[:, np.maximum(ends[:, 1], 0)], 0.0)
    out: NDArray[np.float64] = (system.element_stiffness / system.element_ratio) * (tb - ta)
    return out


def _run_speeds(
    excitation: Excitation,
    speed: float | None,
    run_up: tuple[float, float] | None,
    duration: float | None,
    cycles: float | None,
) -> tuple[float, float, float, float]:
    """(start speed, end speed, duration, cycle angle) of a run, checked (one-line errors as
    :func:`transient_response` lists them)."""
    if (speed is None) == (run_up is None):
        raise InputError("give a constant speed or a run-up (start and end speeds)", key="speed")
    cycle_angle = 4.0 * math.pi if excitation.cycle == "four-stroke" else 2.0 * math.pi
    if speed is not None:
        if not (math.isfinite(speed) and speed > 0.0):
            raise InputError("the speed must be positive", key="speed", value=speed)
        w0 = w1 = float(speed)
        if duration is None:
            if cycles is None or not cycles > 0:
                raise InputError("give the duration or the number of cycles", key="cycles")
            duration = cycles * cycle_angle / w0
    else:
        assert run_up is not None  # exactly one of speed and run_up (checked above)
        w0, w1 = (float(v) for v in run_up)
        if not (w0 > 0.0 and w1 > 0.0 and math.isfinite(w0) and math.isfinite(w1)):
            raise InputError("run-up speeds must be positive", key="run_up", value=run_up)
        if duration is None:
            raise InputError("a run-up needs its duration", key="duration")
    if not (math.isfinite(duration) and duration > 0.0):
        raise InputError("the duration must be positive", key="duration", value=duration)
    return w0, w1, float(duration), cycle_angle


def _integrate(
    system: LinearSystem,
    forcing: NDArray[np.complex128],
    grid: NDArray[np.float64],
    orders: NDArray[np.float64],
    speeds: tuple[float, float],
    duration: float,
    hysteretic_frequency: float,
    start: str,
    t_eval: NDArray[np.float64],
    method: str,
    rtol: float,
    atol: float,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(times, angles (T, n)) of the first-order system y' = A y + B T(t) integrated by
    ``solve_ivp`` from rest or the steady state (module docstring)."""
    n = system.size
    w0, w1 = speeds
    mass = system.inertia
    damping = system.damping + system.hysteretic / hysteretic_frequency
    inv_m = 1.0 / mass
    a_lower = np.hstack([-inv_m[:, None] * system.stiffness, -inv_m[:, None] * damping])
    rate = (w1 - w0) / duration

    def rhs(t: float, y: NDArray[np.float64]) -> NDArray[np.float64]:
        w = w0 + rate * t
        f = forcing[0] if grid.size == 1 else interp_complex(np.array([w]), grid, forcing)[0]
        torque = np.real(np.exp(1j * orders * (w0 * t + 0.5 * rate * t * t)) @ f)
        acc = a_lower @ y + inv_m * torque
        return np.concatenate([y[n:], acc])

    y0 = np.zeros(2 * n)
    if start == "steady":
        omega0 = orders * w0
        start_forcing = forcing[0] if w0 <= w1 else forcing[-1]
        x0 = system.solve(omega0, start_forcing, hysteretic_frequency)  # (Q, n) complex
        y0 = np.concatenate(
            [np.real(np.sum(x0, axis=0)), np.real(np.sum(1j * omega0[:, None] * x0, axis=0))]
        )
    from scipy.integrate import solve_ivp  # imported here: keeps the start-up light

    sol = solve_ivp(rhs, (0.0, duration), y0, method=method, t_eval=t_eval, rtol=rtol, atol=atol)
    if not sol.success:  # pragma: no cover - scipy's own failure
        raise RuntimeError(sol.message)
    return sol.t, sol.y[:n].T
