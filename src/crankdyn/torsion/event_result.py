"""The result of a transient event: speeds and element torques against time, and every
element's extremes (result object of :func:`crankdyn.torsion.event_run.event_response`)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from crankdyn.constants import RPM
from crankdyn.errors import InputError, did_you_mean
from crankdyn.results import Result, array, column, scalar
from crankdyn.summary import Verdict, derived

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from crankdyn.plausibility import PlausibilityWarning

__all__ = ["EventResult", "time_above"]

HZ = 1.0 / (2.0 * math.pi)


def time_above(time: NDArray[np.float64], values: NDArray[np.float64], level: float) -> float:
    """The time (s) a sampled quantity spends above a level, its crossings interpolated
    linearly between the samples.

    Parameters
    ----------
    time : numpy.ndarray
        (T,) increasing times (s).
    values : numpy.ndarray
        (T,) the quantity (any unit).
    level : float
        The level (the quantity's unit).

    Returns
    -------
    float
        Seconds above the level (s).

    Examples
    --------
    >>> time_above(np.array([0.0, 1.0, 2.0]), np.array([0.0, 2.0, 0.0]), 1.0)
    1.0
    """
    t = np.asarray(time, dtype=float)
    y = np.asarray(values, dtype=float) - level
    if t.size < 2:
        return 0.0
    y0, y1 = y[:-1], y[1:]
    dt = np.diff(t)
    both = (y0 > 0.0) & (y1 > 0.0)
    total = float(np.sum(dt[both]))
    up = (y0 <= 0.0) & (y1 > 0.0)
    down = (y0 > 0.0) & (y1 <= 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        total += float(np.sum(dt[up] * y1[up] / (y1[up] - y0[up])))
        total += float(np.sum(dt[down] * y0[down] / (y0[down] - y1[down])))
    return total


@dataclass(frozen=True)
class EventResult(Result):
    """Speeds and element torques of a shaft line through a transient event.

    ``torque`` holds the torque every element transmits (own sense: positive when its first
    mass drives its second, k x twist / |r|; a slipping clutch carries its friction torque),
    ``mass_speed`` every listed mass's speed (own sense), both at the kept samples; the
    extremes (``max_torque``, ``min_torque``) come from every step of the integration, refined
    on the exact solution between the steps (:mod:`crankdyn.torsion.event_run`), whatever was
    kept; so do those of the vibratory torque (``max_vibratory``, ``min_vibratory``): the
    torque less the quasi-static torque of the mean torques (the engines' and the loads',
    without the event's), the quantity IACS UR M68's limits bound. ``element_kinds`` says
    what every element is (``"shaft"``, ``"coupling"``, ``"mesh"``, ``"damper"``, ``"gear"``
    for a rigid gear mesh), ``section_modulus`` its W_p where it has a diameter (NaN
    otherwise), ``limit_torque`` a coupling's T_Kmax from the model (NaN otherwise).

    A run with a cut-off (``max_frequency``: the TVC's) integrates the modes up to it and the
    modes above quasi-statically: ``modes_kept``, ``cutoff_frequency`` (None: every mode),
    ``truncation_bound`` (the dropped modes' dynamic part relative to their quasi-static
    part), ``truncation_torque`` (every element's bound of the truncation error, N m) and
    ``truncation_error`` (its largest) say how (:mod:`crankdyn.torsion.integrator`, "Modal
    truncation").

    The verdicts are not the run's own: the TVC's checks judge it
    (:func:`crankdyn.tvc.events.judge_event`, the one evaluation of every check).

    Parameters
    ----------
    vibratory_torque : numpy.ndarray or None
        (time, element) the vibratory torque at the kept samples (N m; not exported).
    warnings : tuple of crankdyn.plausibility.PlausibilityWarning
        The input warnings of the model's file(s) (:mod:`crankdyn.io.plausibility`), given by
        the analysis session (not exported as a field: ``to_dict`` lists them under
        ``input_warnings``).
    """

    title = "Transient event"
    time: np.ndarray = column("time_s", "Time", "s")
    speed: np.ndarray = column("speed_rpm", "Mean speed (reference)", "rpm", RPM)
    mass_speed: np.ndarray = array("mass_speed_rpm", "Speed (time x mass)", "rpm", RPM)
    torque: np.ndarray = array("torque_Nm", "Torque (time x element)", "N·m")
    max_torque: np.ndarray = array("max_torque_Nm", "Largest torque per element", "N·m")
    min_torque: np.ndarray = array("min_torque_Nm", "Smallest torque per element", "N·m")
    max_time: np.ndarray = array("max_torque_time_s", "Time of the largest torque", "s")
    min_time: np.ndarray = array("min_torque_time_s", "Time of the smallest torque", "s")
    max_vibratory: np.ndarray = array(
        "max_vibratory_torque_Nm", "Largest vibratory torque per element", "N·m"
    )
    min_vibratory: np.ndarray = array(
        "min_vibratory_torque_Nm", "Smallest vibratory torque per element", "N·m"
    )
    max_vibratory_time: np.ndarray = array(
        "max_vibratory_time_s", "Time of the largest vibratory torque", "s"
    )
    min_vibratory_time: np.ndarray = array(
        "min_vibratory_time_s", "Time of the smallest vibratory torque", "s"
    )
    initial_torque: np.ndarray = array("initial_torque_Nm", "Torque before the event", "N·m")
    section_modulus: np.ndarray = array("section_modulus_m3", "Section modulus W_p", "m³")
    limit_torque: np.ndarray = array("limit_torque_Nm", "T_Kmax of the couplings", "N·m")
    event: str = scalar("event", "Event", "")
    kind: str = scalar("event_kind", "Kind of event", "")
    severity: str = scalar("severity", "Severity", "")
    source: str = scalar("source", "Source of the event", "", summary=False)
    masses: tuple[str, ...] = scalar("masses", "Masses", "", summary=False)
    elements: tuple[tuple[str, str], ...] = scalar("elements", "Elements", "", summary=False)
    element_names: tuple[str, ...] = scalar("element_names", "Element names", "", summary=False)
    element_kinds: tuple[str, ...] = scalar("element_kinds", "Element kinds", "", summary=False)
    duration: float = scalar("duration_s", "Duration", "s")
    step: float = scalar("step_s", "Time step", "s")
    step_rule: str = scalar("step_rule", "Step rule", "", summary=False)
    highest_frequency: float = scalar(
        "highest_frequency_hz", "Highest frequency resolved", "Hz", HZ
    )
    stride: int = scalar("stride", "Steps per kept sample", "")
    memory_bound: float = scalar("memory_bound_bytes", "Memory bound of the run", "B")
    switches: tuple[str, ...] = scalar("switches", "Clutch switches", "", summary=False)
    notes: tuple[str, ...] = scalar("notes", "Notes", "")
    model_name: str = scalar("model", "Model", "", summary=False)
    verdicts: tuple[Verdict, ...] = scalar("verdicts", "Verdicts", "", summary=False, default=())
    loaded_from: float = scalar(
        "loaded_from_s", "Gear reversals judged from", "s", summary=False, default=0.0
    )
    modes_kept: int = scalar(
        "modes_kept",
        "Elastic modes integrated in time",
        "",
        default=0,
        description="the elastic modes up to the cut-off frequency (every mode without one)",
    )
    cutoff_frequency: float | None = scalar(
        "cutoff_frequency_hz",
        "Modal cut-off frequency",
        "Hz",
        HZ,
        default=None,
        description="the modes above it respond quasi-statically (residual flexibility)",
    )
    truncation_bound: float = scalar(
        "truncation_bound",
        "Truncation error bound (of the dropped modes' quasi-static part)",
        "",
        default=0.0,
        description="the dropped modes' dynamic part relative to their quasi-static part",
    )
    truncation_error: float = scalar(
        "truncation_error_Nm",
        "Truncation error bound of the element torques",
        "N·m",
        default=0.0,
        description="max over the elements of the bound per element",
    )
    truncation_torque: np.ndarray | None = array(
        "truncation_error_per_element_Nm",
        "Truncation error bound per element",
        "N·m",
        default=None,
    )
    engine_torque: np.ndarray | None = array(
        "engine_torque_Nm", "Engine torque on its governor (at the kept samples)", "N·m",
        default=None,
    )  # fmt: skip
    vibratory_torque: np.ndarray | None = field(default=None, repr=False, compare=False)
    warnings: tuple[PlausibilityWarning, ...] = field(default=(), repr=False, compare=False)

    FIGURES = (
        derived(
            "peak_shaft_torque",
            "peak_shaft_torque_Nm",
            "Largest shaft torque",
            "N·m",
            lambda r: r.largest(("shaft",)),
            reduction="max |T| over the shafts and the run",
            better="min",
        ),
        derived(
            "peak_shaft_stress",
            "peak_shaft_stress_Pa",
            "Largest nominal shaft stress |T| / W_p",
            "Pa",
            lambda r: r.largest(("shaft",), stress=True),
            reduction="max |T| / W_p over the shafts with a diameter and the run",
            better="min",
        ),
        derived(
            "peak_vibratory_shaft_stress",
            "peak_vibratory_shaft_stress_Pa",
            "Largest vibratory shaft stress (beyond the mean torque)",
            "Pa",
            lambda r: r.largest(("shaft",), stress=True, vibratory=True),
            reduction="max |T - T_mean| / W_p over the shafts with a diameter and the run",
            better="min",
        ),
        derived(
            "peak_coupling_torque",
            "peak_coupling_torque_Nm",
            "Largest coupling torque",
            "N·m",
            lambda r: r.largest(("coupling",)),
            reduction="max |T| over the couplings and the run",
            better="min",
        ),
        derived(
            "peak_mesh_torque",
            "peak_mesh_torque_Nm",
            "Largest gear mesh torque",
            "N·m",
            lambda r: r.largest(("mesh", "gear")),
            reduction="max |T| over the gear meshes and the run",
            better="min",
        ),
        derived(
            "time_above_t_kmax",
            "time_above_t_kmax_s",
            "Time above T_Kmax",
            "s",
            lambda r: r.time_above_limits(),
            reduction="max over the couplings with a T_Kmax",
            better="min",
        ),
    )

    # ---- reading ------------------------------------------------------------------------------
    def element_index(self, spec: str | Sequence[str]) -> int:
        """An element by its name (``"intermediate shaft (a - b)"``), its label ``"a - b"`` or
        its two masses.

        Parameters
        ----------
        spec : str or (str, str)
            The element.

        Returns
        -------
        int
            Its index.

        Raises
        ------
        InputError
            For an element the result does not hold (key ``element``, with the nearest).
        """
        if not isinstance(spec, str):
            a, b = spec
            for e, (p, q) in enumerate(self.elements):
                if {p, q} == {a, b}:
                    return e
            spec = f"{a} - {b}"
        labels = [f"{a} - {b}" for a, b in self.elements]
        for names in (self.element_names, labels):
            if spec in names:
                return names.index(spec)
        raise InputError(
            f"no such element{did_you_mean(spec, labels + list(self.element_names))}",
            key="element",
            value=spec,
        )

    def peak(self, e: int) -> float:
        """The largest |torque| of element e over the run (N m).

        Parameters
        ----------
        e : int
            The element.

        Returns
        -------
        float
            (N m).
        """
        return float(max(abs(self.max_torque[e]), abs(self.min_torque[e])))

    def vibratory_peak(self, e: int) -> float:
        """The largest |vibratory torque| of element e over the run (N m): beyond the
        quasi-static torque of the mean torques (class docstring).

        Parameters
        ----------
        e : int
            The element.

        Returns
        -------
        float
            (N m).
        """
        return float(max(abs(self.max_vibratory[e]), abs(self.min_vibratory[e])))

    def vibratory_peak_time(self, e: int) -> float:
        """When element e's largest |vibratory torque| occurs (s).

        Parameters
        ----------
        e : int
            The element.

        Returns
        -------
        float
            (s).
        """
        high = abs(self.max_vibratory[e]) >= abs(self.min_vibratory[e])
        return float(self.max_vibratory_time[e] if high else self.min_vibratory_time[e])

    def peak_time(self, e: int) -> float:
        """When element e's largest |torque| occurs (s).

        Parameters
        ----------
        e : int
            The element.

        Returns
        -------
        float
            (s).
        """
        high = abs(self.max_torque[e]) >= abs(self.min_torque[e])
        return float(self.max_time[e] if high else self.min_time[e])

    def time_above(self, e: int, level: float) -> float:
        """The time element e's |torque| spends above ``level`` (s), from the kept samples
        (:func:`time_above`; resolution: the kept interval, ``stride`` x ``step``).

        Parameters
        ----------
        e : int
            The element.
        level : float
            The level (N m), > 0.

        Returns
        -------
        float
            (s).
        """
        return time_above(self.time, np.abs(self.torque[:, e]), level)

    @property
    def shaft_torque(self) -> NDArray[np.float64]:
        """(time, element) the vibratory torque of every element at the kept samples (N m):
        the model's shafts first, in their order (the reading of the TVC's passage checks, as
        :attr:`crankdyn.torsion.transient.TransientResult.shaft_torque`)."""
        if self.vibratory_torque is None:
            raise ValueError("this run kept no vibratory torques")
        return np.asarray(self.vibratory_torque)

    def samples(self, e: int, *, vibratory: bool = False) -> NDArray[np.float64]:
        """Element e's |torque| (or |vibratory torque|) at the kept samples (N m).

        Parameters
        ----------
        e : int
            The element.
        vibratory : bool
            The vibratory torque instead of the torque.

        Returns
        -------
        numpy.ndarray
            (time,) (N m).
        """
        values = self.vibratory_torque if vibratory else self.torque
        if values is None:
            raise ValueError("this run kept no vibratory torques")
        return np.abs(np.asarray(values)[:, e])

    def time_mean(self, e: int, start: float = 0.0) -> float:
        """Element e's torque averaged over the run from ``start`` (N m; trapezoidal rule on
        the kept samples).

        Parameters
        ----------
        e : int
            The element.
        start : float
            From when (s); default the run's start.

        Returns
        -------
        float
            (N m).
        """
        keep = np.asarray(self.time) >= start
        if not np.any(keep):
            keep[-1] = True
        t, y = np.asarray(self.time)[keep], np.asarray(self.torque)[keep, e]
        span = float(t[-1] - t[0])
        if span <= 0.0:
            return float(y[0])
        return float(np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(t)) / span)

    def reversal(self, e: int) -> tuple[float, float, float, float, int]:
        """A gear mesh's torque reversal: its largest drop below its mean over the run (the
        tooth load reverses where the drop exceeds the mean: gear hammering).

        From ``loaded_from`` (a clutch engagement's first lock; 0 otherwise): before it the
        mesh is being loaded from rest through the slipping clutch (its tooth load builds up
        from zero, no reversal), so the mean and the drop are taken from then on, and the time
        before counts only where the torque fell below zero (a reversal while slipping). The
        drop after ``loaded_from`` is the refined extreme where it lies there, else the kept
        samples' (every ``stride``-th step).

        Parameters
        ----------
        e : int
            The mesh (an elastic mesh's element or a rigid gear's).

        Returns
        -------
        drop : float
            T_mean - min(T) in the mean's direction (N m; the extreme refined between steps).
        mean : float
            The mean over the run (N m).
        when : float
            The time of the lowest torque (s).
        reversed_time : float
            Seconds the torque is reversed (from the kept samples).
        count : int
            Times the torque falls through zero.
        """
        start = float(self.loaded_from)
        mean = self.time_mean(e, start)
        sign = 1.0 if mean >= 0.0 else -1.0
        low = float(self.min_torque[e] if sign > 0 else -self.max_torque[e])
        when = float(self.min_time[e] if sign > 0 else self.max_time[e])
        along = sign * np.asarray(self.torque)[:, e]
        if start > 0.0 and when < start and low >= 0.0:  # the unloaded start: from the lock
            after = np.asarray(self.time) >= start
            k = int(np.argmin(np.where(after, along, np.inf)))
            low, when = float(along[k]), float(self.time[k])
        reversed_time = time_above(self.time, -along, 0.0)
        crossings = int(np.count_nonzero(np.diff(np.signbit(along).astype(int)) == 1))
        return sign * mean - float(low), mean, float(when), reversed_time, crossings

    def largest(
        self, kinds: Sequence[str], *, stress: bool = False, vibratory: bool = False
    ) -> tuple[float, str] | None:
        """The largest |torque| (N m), or |torque| / W_p (Pa), over the elements of ``kinds``
        and the run, and where (the element and the time), or None without such elements.

        Parameters
        ----------
        kinds : sequence of str
            Element kinds (``"shaft"``, ``"coupling"``, ``"mesh"``, ``"gear"``).
        stress : bool
            Divide by W_p (elements with a diameter only).
        vibratory : bool
            The vibratory torque's peaks instead of the torque's.

        Returns
        -------
        (float, str) or None
            The value and where.
        """
        best: tuple[float, int] | None = None
        for e, kind in enumerate(self.element_kinds):
            if kind not in kinds:
                continue
            value = self.vibratory_peak(e) if vibratory else self.peak(e)
            if stress:
                if not np.isfinite(self.section_modulus[e]):
                    continue
                value /= float(self.section_modulus[e])
            if best is None or value > best[0]:
                best = (value, e)
        if best is None:
            return None
        value, e = best
        when = self.vibratory_peak_time(e) if vibratory else self.peak_time(e)
        return value, f"{self.element_names[e]}, t = {when:.4g} s"

    def time_above_limits(self) -> tuple[float, str] | None:
        """The longest time a coupling's |torque| spends above its T_Kmax (s), and which, or
        None without a coupling limit.

        Returns
        -------
        (float, str) or None
            Seconds and the coupling.
        """
        best: tuple[float, int] | None = None
        for e, limit in enumerate(self.limit_torque):
            if np.isfinite(limit):
                value = self.time_above(e, float(limit))
                if best is None or value > best[0]:
                    best = (value, e)
        if best is None:
            return None
        return best[0], self.element_names[best[1]]

    def summary_verdicts(self) -> list[Verdict]:
        """The verdicts of the installation's checks, where the run was judged
        (:func:`crankdyn.tvc.events.judge_event`).

        Returns
        -------
        list of crankdyn.summary.Verdict
            The rows.
        """
        return list(self.verdicts)

    # ---- export -------------------------------------------------------------------------------
    def columns(self) -> dict[str, np.ndarray]:
        """The time columns, then one speed column per mass (``speed_rpm.<mass>``) and one
        torque column per element (``torque_Nm.<a> - <b>``) for the CSV.

        Returns
        -------
        dict of str to numpy.ndarray
            {key: values} in the unit of the key.
        """
        out = super().columns()
        for i, name in enumerate(self.masses):
            out[f"speed_rpm.{name}"] = np.round(self.mass_speed[:, i] * RPM, 9)
        for e, (a, b) in enumerate(self.elements):
            out[f"torque_Nm.{a} - {b}"] = self.torque[:, e]
        return out

    def column_labels(self) -> dict[str, tuple[str, str]]:
        """Label and unit of every column of :meth:`columns`.

        Returns
        -------
        dict of str to (str, str)
            {column key: (label, unit)}.
        """
        out = super().column_labels()
        for name in self.masses:
            out[f"speed_rpm.{name}"] = (f"Speed {name}", "rpm")
        for a, b in self.elements:
            out[f"torque_Nm.{a} - {b}"] = (f"Torque {a} - {b}", "N·m")
        return out

    def plot(self, *, limits: bool = True, fig: Figure | None = None) -> Figure:
        """Shaft torques, coupling torques and speeds against time, with the couplings' T_Kmax
        drawn (:func:`crankdyn.plots.events.plot_event`).

        Parameters
        ----------
        limits : bool
            Whether to draw the limits the result holds.
        fig : matplotlib.figure.Figure or None
            A figure to draw into; default a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.events import plot_event

        return plot_event(self, limits=limits, fig=fig)
