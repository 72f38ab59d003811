"""Steady-state forced torsional response over a speed range: the result (results).

:func:`crankdyn.torsion.sweep.forced_response` solves the dynamic-stiffness equation
D(q Omega) X = F (:mod:`crankdyn.torsion.solvers`; seed 003, the V6 paper's eqs. 1, 2 and 6) at
every speed and order of a resolved sweep (:mod:`crankdyn.torsion.sweep`) and returns a
:class:`ResponseResult`; :meth:`ResponseResult.peak` gives the largest value of any quantity and
its speed, :meth:`ResponseResult.relative_angle` the angle between two masses
(:class:`RelativeAngle`).

Outputs. Per speed, order and mass the complex amplitude (the actual angle of a geared mass is
its reflected angle times its speed ratio); the vibratory torque of every shaft, the elastic
torque k (theta_b - theta_a) for a shaft between masses a and b (actual stiffness and angles);
the nominal shear stress tau = |T| / W_p with the polar section modulus W_p = pi (D^4 - d^4) /
(16 D) where the shaft's diameters are known. Synthesised over all orders:

- the sum of the order amplitudes sum_q |X_q| (the "vibratory torque" of Mendes et al. 2008,
  an upper bound: every order at its peak at once);
- the time-domain synthesis x(theta) = sum_q Re(X_q exp(i q theta)) over one working cycle (or,
  with sources' orders that are not the engine's, over the orders' common period), its
  peak-to-peak value and half of it, the half-range amplitude that IACS UR M68 limits ("the
  synthesis of all harmonic orders present"). The extremes are found on a grid of at least
  8 points per period of the highest order; every crest of the grid within the grid's error
  bound of its extreme is refined by Newton's method on x'(theta) = 0
  (:func:`crankdyn.torsion.synthesis.half_range`). Orders without a common period (index above
  8192) are bounded by the sum of their amplitudes, their supremum (Kronecker's theorem;
  :func:`crankdyn.torsion.sources.synthesize`).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Any, cast

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.constants import RPM
from crankdyn.errors import InputError, did_you_mean
from crankdyn.results import Result, array, freeze, scalar
from crankdyn.summary import SummaryColumn, SummaryTable, derived
from crankdyn.torsion.resolve import MAX_ROUNDS, TOLERANCE, merge_speeds, refinement_speeds
from crankdyn.torsion.sources import synthesis_index, synthesize_at

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from crankdyn.plausibility import PlausibilityWarning
    from crankdyn.torsion.sweep import Sweep

__all__ = [
    "QUANTITIES",
    "Peak",
    "RelativeAngle",
    "ResponseResult",
]

_UNIT_KEYS = {"rad": "rad", "N·m": "Nm", "Pa": "Pa", "W": "W"}

QUANTITIES = {
    # name: (item kind, unit, per order, label)
    "amplitude": ("mass", "rad", True, "angular amplitude"),
    "synthesized_amplitude": ("mass", "rad", False, "synthesised half-range amplitude"),
    "order_sum_amplitude": ("mass", "rad", False, "sum of order amplitudes"),
    "peak_to_peak": ("mass", "rad", False, "peak-to-peak angle"),
    "order_shaft_torque": ("shaft", "N·m", True, "shaft torque"),
    "shaft_torque": ("shaft", "N·m", False, "vibratory torque, sum of orders"),
    "synthesized_shaft_torque": ("shaft", "N·m", False, "synthesised half-range torque"),
    "order_shaft_stress": ("shaft", "Pa", True, "nominal shear stress"),
    "shaft_stress": ("shaft", "Pa", False, "nominal shear stress, sum of orders"),
    "synthesized_shaft_stress": ("shaft", "Pa", False, "synthesised half-range shear stress"),
    "damper_power": ("damper", "W", False, "damper power"),
}
"""The quantities :meth:`ResponseResult.peak` knows: (item kind, unit, per order, label)."""


@dataclass(frozen=True)
class Peak(Result):
    """The largest value of a response quantity over the resolved speed range (its speed in
    rad/s, exported in rpm; the value in SI, its unit in ``unit`` and in the JSON key).

    Examples
    --------
    >>> from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
    >>> from crankdyn.torsion.excitation import UniformExcitation
    >>> from crankdyn.torsion.sweep import forced_response
    >>> model = TorsionModel(
    ...     masses=(Mass("m", 1.0, damping=20.0, cylinders=(1,)),),
    ...     shafts=(Shaft(("ground", "m"), 1e6, geometry=ShaftGeometry(0.05)),),
    ... )
    >>> excitation = UniformExcitation(100.0, [0.0], "two-stroke")
    >>> response = forced_response(model, excitation, np.arange(500.0, 1500.0, 130.0), [1.0])
    >>> peak = response.peak("synthesized_shaft_torque")
    >>> peak.item, round(peak.value), peak.unit
    ('ground - m', 5000, 'N·m')
    """

    title = "Peak"
    quantity: str = scalar("quantity", "Quantity", "")
    item: str | None = scalar("item", "Of", "")
    order: float | None = scalar("order", "Order", "", fmt=".4g")
    value: float = scalar("value", "Largest value", "")
    unit: str = scalar("unit", "Unit", "")
    speed: float = scalar("speed_rpm", "At speed", "rpm", RPM, fmt=".6g")
    on_grid: bool = scalar("on_grid", "On the user's speed grid", "")

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict, the value's key naming its unit (``value_rad``, ``value_Nm``,
        ``value_Pa``, ``value_W``).

        Returns
        -------
        dict
            The fields in their exported units (:meth:`crankdyn.results.Result.to_dict`; the
            speed in rpm).
        """
        out = super().to_dict()
        out[f"value_{_UNIT_KEYS.get(self.unit, self.unit)}"] = out.pop("value")
        return out

    def describe(self, scale: float = 1.0, unit: str | None = None, digits: int = 4) -> str:
        """The peak in words: ``"<value> <unit> at <speed> rpm"``.

        Parameters
        ----------
        scale : float
            Factor from the SI value to the unit shown (e.g. 1e3 for mrad).
        unit : str or None
            The unit shown; default the SI unit (``unit``).
        digits : int
            Significant digits of the value.

        Returns
        -------
        str
            The value times ``scale`` with ``digits`` significant digits, its unit and the
            speed (rpm, one decimal).

        Examples
        --------
        >>> from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
        >>> from crankdyn.torsion.excitation import UniformExcitation
        >>> from crankdyn.torsion.sweep import forced_response
        >>> model = TorsionModel(
        ...     masses=(Mass("m", 1.0, damping=20.0, cylinders=(1,)),),
        ...     shafts=(Shaft(("ground", "m"), 1e6, geometry=ShaftGeometry(0.05)),),
        ... )
        >>> excitation = UniformExcitation(100.0, [0.0], "two-stroke")
        >>> response = forced_response(model, excitation, np.arange(500.0, 1500.0, 130.0), [1.0])
        >>> response.peak("amplitude").describe(1e3, "mrad")
        '5 mrad at 9549.3 rpm'
        """
        return f"{self.value * scale:.{digits}g} {unit or self.unit} at {self.speed * RPM:.1f} rpm"


def _peak_of(
    values: ArrayLike,
    speed: np.ndarray,
    on_grid: np.ndarray,
    labels: Sequence[str] | None,
    orders: np.ndarray | None,
    quantity: str,
    unit: str,
    item_label: Callable[[int], str] | None,
) -> Peak:
    """Peak of values (S, Q, I) or (S, I) over speed (and order and item) -> Peak."""
    v = np.asarray(values, dtype=float)
    finite = np.where(np.isfinite(v), v, -np.inf)
    if not np.any(np.isfinite(v)):
        raise InputError(f"no finite values of {quantity}", key="quantity", value=quantity)
    k = int(np.argmax(finite))
    idx = np.unravel_index(k, v.shape)
    order = None
    if v.ndim == 3 and orders is not None:
        order = float(orders[idx[1]])
    if labels is not None:
        item = labels[int(idx[-1])]
    elif item_label is not None:
        item = item_label(int(idx[-1]))
    else:  # pragma: no cover - every caller gives labels or a labeller
        raise ValueError("the peak's item needs labels or a labeller")
    return Peak(
        quantity=quantity,
        item=item,
        order=order,
        value=float(v[idx]),
        unit=unit,
        speed=float(speed[idx[0]]),
        on_grid=bool(on_grid[idx[0]]),
    )


@dataclass(frozen=True)
class RelativeAngle(Result):
    """The relative angle between two masses over the speed range (per order and synthesised),
    e.g. pulley - flywheel, the V6 paper's criterion (seed 003). On a resolved response its
    peaks are resolved too (:meth:`ResponseResult.relative_angle`), so its speeds may add to the
    response's.

    Examples
    --------
    >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
    >>> from crankdyn.torsion.excitation import UniformExcitation
    >>> from crankdyn.torsion.sweep import forced_response
    >>> two = TorsionModel(
    ...     masses=(Mass("a", 1.0, damping=10.0, cylinders=(1,)), Mass("b", 3.0)),
    ...     shafts=(Shaft(("a", "b"), 3e4),),
    ... )
    >>> response = forced_response(
    ...     two, UniformExcitation(100.0, [0.0], "two-stroke"), [100.0, 150.0], [1.0],
    ...     resolve=False,
    ... )
    >>> relative = response.relative_angle("a", "b")
    >>> relative.amplitude.shape, relative.peak().item
    ((2, 1), 'a - b')
    """

    title = "Relative angle"
    between: tuple[str, str] = scalar("between", "Between", "")
    speed: np.ndarray = array("speed_rpm", "Speed", "rpm", RPM)
    amplitude: np.ndarray = array("amplitude_rad", "Amplitude per order", "rad")
    order_sum: np.ndarray = array("order_sum_amplitude_rad", "Sum of order amplitudes", "rad")
    synthesized: np.ndarray = array(
        "synthesized_amplitude_rad", "Synthesised half-range amplitude", "rad"
    )
    orders: np.ndarray | None = array("orders", "Orders", "", default=None)
    on_grid: np.ndarray | None = array("on_grid", "On the user's speed grid", "", default=None)

    FIGURES = (
        derived(
            "max_relative_angle", "max_relative_angle_rad",
            "Largest relative angle (synthesised)", "rad",
            lambda r: _peak_figure(r.peak("synthesized")),
            reduction="max over the resolved speeds", better="min", headline=True,
        ),
    )  # fmt: skip

    def peak(self, quantity: str = "synthesized", order: float | None = None) -> Peak:
        """The largest relative angle and its speed.

        Parameters
        ----------
        quantity : str
            ``"synthesized"`` (default, the half-range amplitude of the synthesis),
            ``"order_sum"`` or ``"amplitude"`` (per order).
        order : float or None
            For ``"amplitude"``: the order; None: the largest over all orders.

        Returns
        -------
        Peak
            The value (rad) and its speed (rad/s).

        Raises
        ------
        InputError
            Naming the key and value: an unknown ``quantity``, an ``order`` not among the
            response's or given for a quantity summed over the orders.

        Examples
        --------
        >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
        >>> from crankdyn.torsion.excitation import UniformExcitation
        >>> from crankdyn.torsion.sweep import forced_response
        >>> two = TorsionModel(
        ...     masses=(Mass("a", 1.0, damping=10.0, cylinders=(1,)), Mass("b", 3.0)),
        ...     shafts=(Shaft(("a", "b"), 3e4),),
        ... )
        >>> response = forced_response(
        ...     two, UniformExcitation(100.0, [0.0], "two-stroke"), [100.0, 150.0], [1.0],
        ...     resolve=False,
        ... )
        >>> found = response.relative_angle("a", "b").peak("amplitude", order=1.0)
        >>> found.quantity, found.order, found.speed
        ('relative_amplitude', 1.0, 150.0)
        """
        on_grid = self.on_grid if self.on_grid is not None else np.ones(self.speed.size, bool)
        label = f"{self.between[0]} - {self.between[1]}"
        if quantity == "amplitude":
            values = np.asarray(self.amplitude)
            orders = np.asarray(self.orders)
            if order is not None:
                k = _order_index(orders, order)
                values, orders = values[:, [k]], orders[[k]]
            return _peak_of(
                values[:, :, None],
                self.speed,
                on_grid,
                [label],
                orders,
                "relative_amplitude",
                "rad",
                None,
            )
        if order is not None:
            raise InputError("only the per-order amplitude has an order", key="order", value=order)
        field_ = {"synthesized": self.synthesized, "order_sum": self.order_sum}.get(quantity)
        if field_ is None:
            raise InputError(
                "expected synthesized, order_sum or amplitude", key="quantity", value=quantity
            )
        return _peak_of(
            np.asarray(field_)[:, None],
            self.speed,
            on_grid,
            [label],
            None,
            f"relative_{quantity}",
            "rad",
            None,
        )


def _peak_figure(peak: Peak | None) -> tuple[float, str] | None:
    """A peak as a key figure's value and where: ``"cylinder 6 - flywheel at 2165 rpm"``."""
    if peak is None:
        return None
    where = f"at {peak.speed * RPM:.6g} rpm"
    return peak.value, f"{peak.item} {where}" if peak.item else where


def _order_index(orders: ArrayLike, order: float) -> int:
    q = np.asarray(orders, dtype=float)
    hit = np.flatnonzero(np.abs(q - float(order)) <= 1e-9 * max(1.0, abs(float(order))))
    if hit.size == 0:
        listed = ", ".join(f"{x:g}" for x in q[:12])
        raise InputError(
            f"order {float(order):g} is not among the response's orders ({listed}"
            + (", ..." if q.size > 12 else "")
            + ")",
            key="order",
            value=order,
        )
    return int(hit[0])


@dataclass(frozen=True)
class ResponseResult(Result):
    """Forced response over a speed range (module docstring): per speed, order and mass the
    angular amplitude; synthesised amplitudes; vibratory torque and nominal shear stress of
    every shaft; damper power; rule check.

    ``speed`` holds the user's grid and, on a resolved sweep (the default), the speeds added to
    resolve every resonance peak (``on_grid`` tells them apart; ``added_speeds`` and
    ``added_reasons`` say why each was added). :meth:`peak` gives the largest value of any
    quantity and its speed on the resolved curve.

    Parameters
    ----------
    mass_response : numpy.ndarray or None
        (S, Q, N) complex amplitudes of the listed masses' actual angles (rad), not exported.
    shaft_response : numpy.ndarray or None
        (S, Q, E) complex torques of the shafts and damper couplings (N m), not exported.
    section_modulus : numpy.ndarray or None
        (E,) polar section modulus W_p of every element (m^3), NaN where the diameters are
        unknown.
    evaluator : crankdyn.torsion.sweep.Sweep or None
        The sweep that evaluates the same response at other speeds (:meth:`at`); None on a
        result read back from a file.
    warnings : tuple of crankdyn.plausibility.PlausibilityWarning
        The input warnings of the model's file(s) (:mod:`crankdyn.io.plausibility`), given by
        the analysis session (not exported as a field: ``to_dict`` lists them under
        ``input_warnings``).

    Examples
    --------
    One damped mass J = 1 kg m^2 on k = 1e6 N m/rad, c = 20 N m s/rad, excited by 100 N m at
    order 1 of a two-stroke engine, swept on a 130 rad/s grid:

    >>> from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
    >>> from crankdyn.torsion.excitation import UniformExcitation
    >>> from crankdyn.torsion.sweep import forced_response
    >>> model = TorsionModel(
    ...     masses=(Mass("m", 1.0, damping=20.0, cylinders=(1,)),),
    ...     shafts=(Shaft(("ground", "m"), 1e6, geometry=ShaftGeometry(0.05)),),
    ... )
    >>> excitation = UniformExcitation(100.0, [0.0], "two-stroke")
    >>> response = forced_response(model, excitation, np.arange(500.0, 1500.0, 130.0), [1.0])
    >>> int(response.on_grid.sum()), response.speed.size  # the grid, and speeds added
    (8, 14)
    >>> response.amplitude.shape  # speed x order x mass
    (14, 1, 1)
    """

    title = "Forced response"
    speed: np.ndarray = array("speed_rpm", "Speed", "rpm", RPM)
    orders: np.ndarray = array("orders", "Orders", "")
    major: np.ndarray | None = array("major_orders", "Major order", "")
    """None when the excitation has no firing angles (major orders undetermined)."""
    masses: tuple[str, ...] = scalar("masses", "Masses", "", summary=False)
    shafts: tuple[tuple[str, str], ...] = scalar("shafts", "Shafts", "", summary=False)
    amplitude: np.ndarray = array("amplitude_rad", "Amplitude (speed x order x mass)", "rad")
    synthesized_amplitude: np.ndarray = array(
        "synthesized_amplitude_rad", "Synthesised half-range amplitude (speed x mass)", "rad"
    )
    peak_to_peak: np.ndarray = array("peak_to_peak_rad", "Peak-to-peak angle", "rad")
    order_sum_amplitude: np.ndarray = array(
        "order_sum_amplitude_rad", "Sum of order amplitudes (speed x mass)", "rad"
    )
    order_shaft_torque: np.ndarray = array(
        "order_shaft_torque_Nm", "Shaft torque (speed x order x shaft)", "N·m"
    )
    shaft_torque: np.ndarray = array(
        "shaft_torque_Nm", "Vibratory torque, sum of orders (speed x shaft)", "N·m"
    )
    synthesized_shaft_torque: np.ndarray = array(
        "synthesized_shaft_torque_Nm", "Synthesised half-range shaft torque", "N·m"
    )
    shaft_stress: np.ndarray = array(
        "shaft_stress_Pa", "Nominal shear stress, sum of orders (speed x shaft)", "Pa"
    )
    synthesized_shaft_stress: np.ndarray = array(
        "synthesized_shaft_stress_Pa", "Synthesised half-range shear stress", "Pa"
    )
    damper_power: np.ndarray | None = array(
        "damper_power_W", "Damper power (speed x damper)", "W", default=None
    )
    dampers: tuple[str, ...] | None = scalar("dampers", "Dampers", "", default=None, summary=False)
    model_name: str = scalar("model", "Model", "", default="", summary=False)
    excitation: str = scalar("excitation", "Excitation", "", default="", summary=False)
    cycle: str = scalar("cycle", "Cycle", "", default="four-stroke")
    on_grid: np.ndarray | None = array("on_grid", "On the user's speed grid", "", default=None)
    added_speeds: np.ndarray | None = array(
        "added_speeds_rpm", "Speeds added to resolve the peaks", "rpm", RPM, default=None
    )
    added_reasons: tuple[str, ...] | None = scalar(
        "added_speed_reasons", "Why each speed was added", "", default=None, summary=False
    )
    resolved: bool = scalar("resolved", "Peaks resolved", "", default=False)
    tolerance: float | None = scalar(
        "peak_tolerance", "Peaks resolved to (relative)", "", default=None, summary=False
    )
    notes: tuple[str, ...] | None = scalar("notes", "Notes", "", default=None)
    mass_response: np.ndarray | None = field(default=None, repr=False, compare=False)
    shaft_response: np.ndarray | None = field(default=None, repr=False, compare=False)
    section_modulus: np.ndarray | None = field(default=None, repr=False, compare=False)
    evaluator: Sweep | None = field(default=None, repr=False, compare=False)
    """Evaluates the same response at other speeds (:meth:`at`)."""
    warnings: tuple[PlausibilityWarning, ...] = field(default=(), repr=False, compare=False)

    # ---- access -------------------------------------------------------------------------------
    @cached_property
    def _mass_index(self) -> dict[str, int]:
        return {name: i for i, name in enumerate(self.masses)}

    def mass_index(self, name: str) -> int:
        """Index of a mass (or damper ring) by name.

        Parameters
        ----------
        name : str
            The mass's or ring's name.

        Returns
        -------
        int
            Its column in the per-mass arrays.

        Raises
        ------
        InputError
            Naming the key ``mass`` and the value (with the nearest names) when there is no
            such mass.

        Examples
        --------
        >>> from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
        >>> from crankdyn.torsion.excitation import UniformExcitation
        >>> from crankdyn.torsion.sweep import forced_response
        >>> model = TorsionModel(
        ...     masses=(Mass("m", 1.0, damping=20.0, cylinders=(1,)),),
        ...     shafts=(Shaft(("ground", "m"), 1e6, geometry=ShaftGeometry(0.05)),),
        ... )
        >>> excitation = UniformExcitation(100.0, [0.0], "two-stroke")
        >>> response = forced_response(model, excitation, np.arange(500.0, 1500.0, 130.0), [1.0])
        >>> response.mass_index("m")
        0
        """
        try:
            return self._mass_index[name]
        except KeyError:
            raise InputError(
                f'no mass named "{name}"{did_you_mean(name, self._mass_index)}',
                key="mass",
                value=name,
            ) from None

    def shaft_index(self, spec: str | Sequence[str]) -> int:
        """Index of a shaft (or damper coupling) by its ends.

        Parameters
        ----------
        spec : str or (str, str)
            The ends as ``(a, b)`` or ``"a - b"``, in either order.

        Returns
        -------
        int
            Its column in the per-shaft arrays.

        Raises
        ------
        InputError
            Naming the key ``shaft`` and the value (with the nearest names) when there is no
            such shaft.

        Examples
        --------
        >>> from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
        >>> from crankdyn.torsion.excitation import UniformExcitation
        >>> from crankdyn.torsion.sweep import forced_response
        >>> model = TorsionModel(
        ...     masses=(Mass("m", 1.0, damping=20.0, cylinders=(1,)),),
        ...     shafts=(Shaft(("ground", "m"), 1e6, geometry=ShaftGeometry(0.05)),),
        ... )
        >>> excitation = UniformExcitation(100.0, [0.0], "two-stroke")
        >>> response = forced_response(model, excitation, np.arange(500.0, 1500.0, 130.0), [1.0])
        >>> response.shaft_index("m - ground"), response.shaft_index(("ground", "m"))
        (0, 0)
        """
        if isinstance(spec, str):
            parts = tuple(p.strip() for p in spec.split(" - ")) if " - " in spec else (spec,)
        else:
            parts = tuple(spec)
        for i, (a, b) in enumerate(self.shafts):
            if parts in ((a, b), (b, a)):
                return i
        labels = [f"{a} - {b}" for a, b in self.shafts]
        text = " - ".join(parts)
        raise InputError(f'no shaft "{text}"{did_you_mean(text, labels)}', key="shaft", value=text)

    def _on_grid(self) -> NDArray[np.bool_]:
        return self.on_grid if self.on_grid is not None else np.ones(self.speed.size, bool)

    def at(self, speeds: ArrayLike) -> ResponseResult:
        """The same response (model, excitation, orders, dampers) at exactly ``speeds``,
        without resolution or rule check.

        Parameters
        ----------
        speeds : array_like
            Crankshaft speeds (rad/s), > 0.

        Returns
        -------
        ResponseResult
            The response at those speeds, in their order.

        Raises
        ------
        ValueError
            When the result has no evaluator (read back from a file).
        InputError
            Naming the key ``speeds`` and the value (rpm) of a speed that is not positive.

        Examples
        --------
        At the undamped natural frequency the single mass's amplitude is T / (c omega):

        >>> from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
        >>> from crankdyn.torsion.excitation import UniformExcitation
        >>> from crankdyn.torsion.sweep import forced_response
        >>> model = TorsionModel(
        ...     masses=(Mass("m", 1.0, damping=20.0, cylinders=(1,)),),
        ...     shafts=(Shaft(("ground", "m"), 1e6, geometry=ShaftGeometry(0.05)),),
        ... )
        >>> excitation = UniformExcitation(100.0, [0.0], "two-stroke")
        >>> response = forced_response(model, excitation, np.arange(500.0, 1500.0, 130.0), [1.0])
        >>> round(float(response.at([1000.0]).amplitude[0, 0, 0]), 12)
        0.005
        """
        if self.evaluator is None:
            raise ValueError("this result cannot be evaluated at other speeds")
        return self.evaluator.at(speeds)

    # ---- peaks ----------------------------------------------------------------------------------
    def peak(
        self,
        quantity: str,
        item: str | Sequence[str] | None = None,
        order: float | None = None,
    ) -> Peak:
        """The largest value of a quantity over the speed range and its speed.

        Parameters
        ----------
        quantity : str
            A name of :data:`QUANTITIES` (the field names: ``"synthesized_shaft_stress"``,
            ``"amplitude"``, ...).
        item : str, (str, str) or None
            The mass (or damper ring), shaft (``(a, b)`` or ``"a - b"``) or damper; None: the
            largest over all of them (shafts without diameters left out of stresses).
        order : float or None
            For the per-order quantities (``amplitude``, ``order_shaft_torque``,
            ``order_shaft_stress``): the order; None: the largest over all orders.

        Returns
        -------
        Peak
            The value in the quantity's SI unit (rad, N m, Pa, W) and its speed (rad/s). On a
            resolved response (the default of :func:`~crankdyn.torsion.sweep.forced_response`)
            the peak is resolved to ``tolerance``: a finer sweep changes it by less than that.

        Raises
        ------
        InputError
            Naming the key and value: an unknown ``quantity``, ``item`` or ``order``, an order
            given for a quantity summed over the orders, a quantity with no finite value.

        Examples
        --------
        The peak of a single damped mass, T / (c sqrt(k/J - (c/2J)^2)) (seed 003, the single
        damped mass), found between the grid's speeds to the tolerance 0.1 %:

        >>> import math
        >>> from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
        >>> from crankdyn.torsion.excitation import UniformExcitation
        >>> from crankdyn.torsion.sweep import forced_response
        >>> model = TorsionModel(
        ...     masses=(Mass("m", 1.0, damping=20.0, cylinders=(1,)),),
        ...     shafts=(Shaft(("ground", "m"), 1e6, geometry=ShaftGeometry(0.05)),),
        ... )
        >>> excitation = UniformExcitation(100.0, [0.0], "two-stroke")
        >>> response = forced_response(model, excitation, np.arange(500.0, 1500.0, 130.0), [1.0])
        >>> found = response.peak("amplitude", "m")
        >>> exact = 100.0 / (20.0 * math.sqrt(1e6 - 100.0))
        >>> abs(found.value / exact - 1.0) < 1e-3, found.on_grid
        (True, False)
        """
        spec = QUANTITIES.get(quantity)
        if spec is None:
            raise InputError(
                f"expected one of {', '.join(QUANTITIES)}", key="quantity", value=quantity
            )
        kind, unit, per_order, _ = spec
        values = self._quantity_values(quantity)
        if values is None:
            raise InputError(f"the response has no {quantity}", key="quantity", value=quantity)
        orders = np.asarray(self.orders)
        if per_order and order is not None:
            k = _order_index(self.orders, order)
            values, orders = values[:, [k]], orders[[k]]
        elif order is not None:
            raise InputError(
                f"{quantity} is summed over the orders: give no order", key="order", value=order
            )
        if kind == "mass":
            labels = list(self.masses)
            index = None if item is None else self.mass_index(cast(str, item))
        elif kind == "shaft":
            labels = [f"{a} - {b}" for a, b in self.shafts]
            index = None if item is None else self.shaft_index(item)
        else:
            labels = list(self.dampers or ())
            index = None
            if item is not None:
                if item not in labels:
                    raise InputError(f'no damper named "{item}"', key="damper", value=item)
                index = labels.index(item)
        if index is not None:
            values = values[..., [index]]
            labels = [labels[index]]
        return _peak_of(values, self.speed, self._on_grid(), labels, orders, quantity, unit, None)

    def _quantity_values(self, quantity: str) -> np.ndarray | None:
        if quantity == "order_shaft_stress":
            return np.asarray(self.order_shaft_torque) / np.asarray(self.section_modulus)
        return getattr(self, quantity)

    def peaks(self) -> tuple[Peak, ...]:
        """The peaks of the summed and synthesised quantities of every mass, shaft (stresses
        where the diameters are known) and damper: the figures of the response tables.

        Returns
        -------
        tuple of Peak
            Per mass the synthesised and order-sum amplitudes (rad), per shaft the torques
            (N m) and stresses (Pa), per damper the power (W); quantities without a finite
            value left out.

        Examples
        --------
        >>> from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
        >>> from crankdyn.torsion.excitation import UniformExcitation
        >>> from crankdyn.torsion.sweep import forced_response
        >>> model = TorsionModel(
        ...     masses=(Mass("m", 1.0, damping=20.0, cylinders=(1,)),),
        ...     shafts=(Shaft(("ground", "m"), 1e6, geometry=ShaftGeometry(0.05)),),
        ... )
        >>> excitation = UniformExcitation(100.0, [0.0], "two-stroke")
        >>> response = forced_response(model, excitation, np.arange(500.0, 1500.0, 130.0), [1.0])
        >>> [p.quantity for p in response.peaks()][:3]
        ['synthesized_amplitude', 'order_sum_amplitude', 'shaft_torque']
        """
        wanted: list[tuple[str, str | tuple[str, str]]] = [
            (q, name)
            for name in self.masses
            for q in ("synthesized_amplitude", "order_sum_amplitude")
        ]
        for s, shaft in enumerate(self.shafts):
            quantities = ["shaft_torque", "synthesized_shaft_torque"]
            if self.section_modulus is not None and np.isfinite(self.section_modulus[s]):
                quantities += ["shaft_stress", "synthesized_shaft_stress"]
            wanted += [(q, shaft) for q in quantities]
        wanted += [("damper_power", name) for name in self.dampers or ()]
        out = []
        for q, item in wanted:
            try:
                out.append(self.peak(q, item))
            except InputError:  # no finite value (an undamped system exactly at resonance)
                continue
        return tuple(out)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (module docstring), with ``peaks``: :meth:`peaks`.

        Returns
        -------
        dict
            The fields in their exported units (:meth:`crankdyn.results.Result.to_dict`:
            speeds in rpm) and the peaks' dicts (:meth:`Peak.to_dict`).
        """
        out = super().to_dict()
        out["peaks"] = [p.to_dict() for p in self.peaks()]
        return out

    def relative_angle(self, a: str, b: str) -> RelativeAngle:
        """Relative angle theta_a - theta_b per order and synthesised.

        On a resolved response its peaks are resolved as well: speeds are added where they
        need it (the pairs given to :func:`~crankdyn.torsion.sweep.forced_response` as
        ``relative`` need none).

        Parameters
        ----------
        a, b : str
            The two masses (or damper rings).

        Returns
        -------
        RelativeAngle
            Per speed (rad/s) and order the amplitude, the sum of the order amplitudes and the
            synthesised half-range amplitude (rad).

        Raises
        ------
        InputError
            Naming the key ``mass`` and the value of an unknown mass.
        ValueError
            When the result holds no complex amplitudes (read back from a file).

        Examples
        --------
        >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
        >>> from crankdyn.torsion.excitation import UniformExcitation
        >>> from crankdyn.torsion.sweep import forced_response
        >>> two = TorsionModel(
        ...     masses=(Mass("a", 1.0, damping=10.0, cylinders=(1,)), Mass("b", 3.0)),
        ...     shafts=(Shaft(("a", "b"), 3e4),),
        ... )
        >>> response = forced_response(
        ...     two, UniformExcitation(100.0, [0.0], "two-stroke"), [100.0, 150.0], [1.0],
        ...     resolve=False,
        ... )
        >>> response.relative_angle("a", "b").between
        ('a', 'b')
        """
        if self.mass_response is None:
            raise ValueError("this result holds no complex amplitudes (read from a file?)")
        i, j = self.mass_index(a), self.mass_index(b)
        speed = np.asarray(self.speed)
        on_grid = self._on_grid()
        diff = self.mass_response[:, :, i] - self.mass_response[:, :, j]
        index = synthesis_index(self.orders, self.cycle)
        top, low = synthesize_at(diff, index)
        if self.resolved and self.evaluator is not None:
            for _ in range(MAX_ROUNDS):
                amp = np.abs(diff)
                values = np.column_stack([amp, amp.sum(axis=1), 0.5 * (top - low)])
                new, _ = refinement_speeds(speed, values, tolerance=self.tolerance or TOLERANCE)
                if new.size == 0:
                    break
                x = self.evaluator.evaluate(new).x
                more = x[:, :, i] - x[:, :, j]
                t2, l2 = synthesize_at(more, index)
                speed, first = merge_speeds(speed, new)
                diff = np.concatenate([diff, more])[first]
                top = np.concatenate([top, t2])[first]
                low = np.concatenate([low, l2])[first]
                on_grid = np.concatenate([on_grid, np.zeros(new.size, bool)])[first]
        return RelativeAngle(
            between=(a, b),
            speed=freeze(speed),
            amplitude=freeze(np.abs(diff)),
            order_sum=freeze(np.sum(np.abs(diff), axis=1)),
            synthesized=freeze(0.5 * (top - low)),
            orders=freeze(self.orders),
            on_grid=freeze(on_grid, dtype=bool),
        )

    def plot(
        self,
        what: str = "amplitude",
        item: str | Sequence[str] | None = None,
        fig: Figure | None = None,
        **kw: Any,
    ) -> Figure:
        """Response against speed per order and synthesised
        (:func:`crankdyn.plots.torsion_response.plot_response`).

        Parameters
        ----------
        what : str
            ``"amplitude"`` (mass ``item``, default the first), ``"torque"`` or ``"stress"``
            (shaft ``item``, default the one with the largest torque), ``"relative"``
            (``item = (a, b)``).
        item : str, (str, str) or None
            The mass, shaft or pair drawn.
        fig : matplotlib.figure.Figure or None
            A figure to draw into; default a new one.
        **kw
            Passed to :func:`~crankdyn.plots.torsion_response.plot_response`.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.torsion_response import plot_response

        return plot_response(self, what=what, item=item, fig=fig, **kw)

    # ---- the summary's tables: the peaks of every mass and shaft, the speeds added ------------
    def _peaks(
        self, quantity: str, items: Sequence[Any]
    ) -> list[tuple[float | None, float | None]]:
        """(value, speed in rpm) of the resolved peak of ``quantity`` for each item; (None,
        None) where the item has no finite value."""
        out: list[tuple[float | None, float | None]] = []
        for item in items:
            try:
                p = self.peak(quantity, item)
            except InputError:
                out.append((None, None))
                continue
            out.append((p.value, round(p.speed * RPM, 1)))
        return out

    def summary_tables(self) -> list[SummaryTable]:
        """The largest synthesised and order-sum values of every mass and shaft on the
        resolved curve (:meth:`peak`), with their speeds; the speeds added to resolve the
        peaks and why (each critical speed on its row, the others counted by kind).

        Returns
        -------
        list of crankdyn.summary.SummaryTable
            The tables.
        """
        rows: list[tuple[Any, ...]] = []
        for name, (a, sa), (b, sb) in zip(
            self.masses,
            self._peaks("synthesized_amplitude", self.masses),
            self._peaks("order_sum_amplitude", self.masses),
            strict=True,
        ):
            rows.append((name, a, sa, b, sb))
        masses = SummaryTable(
            "mass_peaks",
            f"{self.model_name}: angular amplitudes",
            (
                SummaryColumn("mass", "Mass"),
                SummaryColumn("synthesized_amplitude_rad", "Largest synthesised amplitude", "rad"),
                SummaryColumn("at_rpm", "At speed", "rpm"),
                SummaryColumn("order_sum_amplitude_rad", "Largest sum of orders", "rad"),
                SummaryColumn("order_sum_at_rpm", "At speed", "rpm"),
            ),
            tuple(rows),
        )
        stress = self._peaks("synthesized_shaft_stress", self.shafts)
        shaft_rows: list[tuple[Any, ...]] = []
        for k, ((t, st), (u, su)) in enumerate(
            zip(
                self._peaks("shaft_torque", self.shafts),
                self._peaks("synthesized_shaft_torque", self.shafts),
                strict=True,
            )
        ):
            ends = " - ".join(self.shafts[k])
            shaft_rows.append((ends, t, st, u, su, stress[k][0]))
        shafts = SummaryTable(
            "shaft_peaks",
            "Vibratory torque and stress",
            (
                SummaryColumn("shaft", "Shaft"),
                SummaryColumn("shaft_torque_Nm", "Largest sum of orders", "N·m"),
                SummaryColumn("at_rpm", "At speed", "rpm"),
                SummaryColumn("synthesized_shaft_torque_Nm", "Largest synthesised torque", "N·m"),
                SummaryColumn("synthesized_at_rpm", "At speed", "rpm"),
                SummaryColumn("synthesized_shaft_stress_Pa", "Largest synthesised stress", "Pa"),
            ),
            tuple(shaft_rows),
            caption=f"excitation: {self.excitation}" if self.excitation else "",
        )
        out = [masses, shafts]
        added = self._added_table()
        if added is not None:
            out.append(added)
        return out

    def _added_table(self) -> SummaryTable | None:
        """The speeds added to the grid to resolve the peaks and why (each is listed in the
        JSON, ``added_speeds_rpm`` and ``added_speed_reasons``)."""
        added = self.added_speeds
        if added is None or not len(added):
            return None
        rows: list[tuple[str, str]] = []
        groups: dict[str, list[float]] = {}
        for w, why in zip(np.asarray(added), self.added_reasons or (), strict=True):
            if why.startswith("critical speed"):
                rows.append((f"{w * RPM:.1f}", why))
            else:
                groups.setdefault(why.split(":")[0], []).append(float(w))
        for kind, speeds in groups.items():
            rows.append(
                (
                    f"{len(speeds)} from {min(speeds) * RPM:.1f} to {max(speeds) * RPM:.1f}",
                    f"{kind} (each listed in the JSON: added_speeds_rpm)",
                )
            )
        return SummaryTable(
            "added_speeds",
            f"Speeds added to resolve the peaks ({len(added)})",
            (SummaryColumn("speed_rpm", "Speed (rpm)"), SummaryColumn("why", "Why")),
            tuple(rows),
        )

    # ---- the key figures (crankdyn.summary): peaks on the resolved curve --------------------
    @property
    def model_shafts(self) -> tuple[tuple[str, str], ...]:
        """The model's own shafts (the dampers' couplings, which follow them, left out)."""
        return self.shafts[: len(self.shafts) - len(self.dampers or ())]

    def largest_peak(self, quantity: str, items: Sequence[Any] | None = None) -> Peak | None:
        """The largest resolved peak of a synthesised quantity over items (default: the model's
        own shafts for a shaft quantity, every mass for an amplitude); None where no item has
        a finite value (no diameters for a stress, an undamped line at a resonance).

        Parameters
        ----------
        quantity : str
            A quantity of :meth:`peak` (``"synthesized_shaft_torque"``...).
        items : sequence or None
            The masses or shafts.

        Returns
        -------
        Peak or None
            The largest peak, naming its item and speed.
        """
        if items is None:
            items = self.model_shafts if "shaft" in quantity else self.masses
        found = []
        for item in items:
            try:
                found.append(self.peak(quantity, item))
            except InputError:  # no finite value of this item
                continue
        return max(found, key=lambda p: p.value) if found else None

    def most_loaded_shaft(self) -> tuple[str, str]:
        """The model's shaft with the largest synthesised vibratory torque over the resolved
        sweep: the shaft a torque plot shows by default.

        Returns
        -------
        (str, str)
            The shaft's two masses.

        Raises
        ------
        InputError
            If no shaft has a finite torque.
        """
        peak = self.largest_peak("synthesized_shaft_torque")
        if peak is None or peak.item is None:
            raise InputError("no shaft has a finite vibratory torque", key="torque")
        return cast("tuple[str, str]", tuple(self.shafts[self.shaft_index(peak.item)]))

    def most_stressed_shaft(self) -> tuple[str, str]:
        """The model's shaft (with diameters) with the largest synthesised shear stress over the
        resolved sweep: the shaft a stress plot shows by default.

        Returns
        -------
        (str, str)
            The shaft's two masses.

        Raises
        ------
        InputError
            If no shaft has diameters.
        """
        peak = self.largest_peak("synthesized_shaft_stress")
        if peak is None or peak.item is None:
            raise InputError(
                "no shaft of the torsional model has diameters (outer_diameter): no stress",
                key="stress",
            )
        return cast("tuple[str, str]", tuple(self.shafts[self.shaft_index(peak.item)]))

    FIGURES = (
        derived(
            "max_shaft_torque", "max_shaft_torque_Nm",
            "Largest vibratory shaft torque (synthesised)", "N·m",
            lambda r: _peak_figure(r.largest_peak("synthesized_shaft_torque")),
            reduction="max over the shafts and the resolved speeds", better="min",
            headline=True,
        ),
        derived(
            "max_shaft_stress", "max_shaft_stress_Pa",
            "Largest shaft shear stress (synthesised)", "Pa",
            lambda r: _peak_figure(r.largest_peak("synthesized_shaft_stress")),
            reduction="max over the shafts with diameters and the resolved speeds",
            better="min", headline=True,
            unavailable="no shaft of the torsional model has diameters (outer_diameter): no "
            "stress",
        ),
        derived(
            "max_free_end_amplitude", "max_free_end_amplitude_rad",
            "Largest amplitude of the first mass (synthesised)", "rad",
            lambda r: _peak_figure(r.largest_peak("synthesized_amplitude", r.masses[:1])),
            reduction="max over the resolved speeds", better="min",
        ),
        derived(
            "max_damper_power", "max_damper_power_W", "Largest damper power", "W",
            lambda r: None if r.damper_power is None else _peak_figure(r.peak("damper_power")),
            reduction="max over the dampers and the resolved speeds", better="min",
            unavailable="the torsional model has no damper",
        ),
    )  # fmt: skip

    # ---- CSV: one row per speed -----------------------------------------------------------------
    def columns(self) -> dict[str, np.ndarray]:
        """One row per speed, every speed (the peaks included); ``on_grid`` is 1 on the user's
        grid, 0 at the speeds added to resolve the peaks.

        Returns
        -------
        dict of str to numpy.ndarray
            {key: values}: the speed (rpm), ``on_grid``, and per mass and shaft the summed and
            synthesised amplitudes (rad), torques (N m) and stresses (Pa, where the diameters
            are known), in the unit the key names.

        Examples
        --------
        >>> from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
        >>> from crankdyn.torsion.excitation import UniformExcitation
        >>> from crankdyn.torsion.sweep import forced_response
        >>> model = TorsionModel(
        ...     masses=(Mass("m", 1.0, damping=20.0, cylinders=(1,)),),
        ...     shafts=(Shaft(("ground", "m"), 1e6, geometry=ShaftGeometry(0.05)),),
        ... )
        >>> excitation = UniformExcitation(100.0, [0.0], "two-stroke")
        >>> response = forced_response(model, excitation, np.arange(500.0, 1500.0, 130.0), [1.0])
        >>> list(response.columns())[:3]
        ['speed_rpm', 'on_grid', 'synthesized_amplitude_rad.m']
        """
        out = {"speed_rpm": np.asarray(self.speed) * RPM}
        out["on_grid"] = self._on_grid().astype(int)
        for i, name in enumerate(self.masses):
            out[f"synthesized_amplitude_rad.{name}"] = self.synthesized_amplitude[:, i]
        for i, name in enumerate(self.masses):
            out[f"order_sum_amplitude_rad.{name}"] = self.order_sum_amplitude[:, i]
        for s, (a, b) in enumerate(self.shafts):
            out[f"shaft_torque_Nm.{a} - {b}"] = self.shaft_torque[:, s]
        for s, (a, b) in enumerate(self.shafts):
            out[f"synthesized_shaft_torque_Nm.{a} - {b}"] = self.synthesized_shaft_torque[:, s]
        for s, (a, b) in enumerate(self.shafts):
            if np.all(np.isfinite(self.shaft_stress[:, s])):
                out[f"shaft_stress_Pa.{a} - {b}"] = self.shaft_stress[:, s]
                out[f"synthesized_shaft_stress_Pa.{a} - {b}"] = self.synthesized_shaft_stress[:, s]
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
            if key == "speed_rpm":
                out[key] = ("Speed", "rpm")
                continue
            if key == "on_grid":
                out[key] = ("On the speed grid", "")
                continue
            head, name = key.split(".", 1)
            unit = head.rsplit("_", 1)[1].replace("Nm", "N·m")
            out[key] = (f"{head.rsplit('_', 1)[0].replace('_', ' ')} {name}", unit)
        return out
