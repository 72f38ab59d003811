"""Permissible torsional vibration stresses of propulsion shafts after IACS UR M68 (analysis).

Source: IACS Unified Requirement M68, "Dimensions of propulsion shafts and their permissible
torsional vibration stresses", section M68.4, in the text revised in August 2014 (Rev.1 with
Corr.2 of November 2012 incorporated; the current revision, Rev.3 of February 2021, keeps these
formulas as far as we could check). Check the revision your classification society applies. The
UR covers intermediate, thrust and propeller shafts of traditional straight forged design; it
does not cover engine crankshafts (IACS UR M53).

With the speed ratio lambda = n / n_0 (n_0 the rated speed), the specified minimum tensile
strength sigma_B of the shaft material (N/mm^2), the factor C_K for the shaft's design features
(1.0 for plain sections with integral flanges or shrink-fit couplings, 0.60 for keyways in
tapered connections, 0.45 in cylindrical connections, 0.50 at radial holes, ...; the UR's table)
and the size factor C_D = 0.35 + 0.93 d^-0.2 (d the shaft's outer diameter in mm), the
permissible half-range amplitude of the torsional vibration stress is

- for continuous operation
      tau_C = (sigma_B + 160)/18 C_K C_D (3 - 2 lambda^2)    for lambda < 0.9,
      tau_C = (sigma_B + 160)/18 C_K C_D 1.38                 for 0.9 <= lambda <= 1.05;
- for transient running through a barred speed range (lambda <= 0.8)
      tau_T = 1.7 tau_C / sqrt(C_K).

Speeds where the synthesised stress (all orders, the nominal stress of the plain section, half
the peak-to-peak range; the UR's basis) exceeds tau_C form *barred speed ranges*; they are
acceptable only below lambda = 0.8 and only while the stress stays below tau_T. Above
lambda = 1.05 the UR sets no limit (not checked). The UR also caps sigma_B used in the formula
(see its text): give the value the UR allows for your material.

Grid independence. The check runs on the resolved response (the resonance peaks refined to
0.1 %, :mod:`crankdyn.torsion.resolve`); the local maxima of stress / tau_C that come within 1 %
of the limit are refined further (to 1e-6), so a tangency is decided by the curve, not by the
grid; and the ends of every barred range are bisected on the synthesised stress minus tau_C to
0.01 rpm (all ends at once per round). :func:`exceedances` is the same machinery for any curve
of a response against any limit curve (couplings, gears, ... against their own limits).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.constants import RPM
from crankdyn.crank.geometry import check_finite, check_positive
from crankdyn.errors import InputError
from crankdyn.results import Result, array, freeze, scalar
from crankdyn.torsion.resolve import bisect_crossings, merge_speeds, refinement_speeds

if TYPE_CHECKING:
    from crankdyn.torsion.model import TorsionModel
    from crankdyn.torsion.response import ResponseResult

__all__ = [
    "RULE",
    "SPEED_TOLERANCE",
    "STRENGTH_CAPS",
    "BarredRange",
    "Exceedance",
    "RuleCheck",
    "RuleSet",
    "ShaftLimit",
    "capped_strength",
    "check_rules",
    "exceedances",
    "permissible_continuous",
    "permissible_transient",
    "size_factor",
]

RULE = "IACS UR M68 (Aug 2014 text), M68.4"
"""The rule and section the check applies (module docstring)."""

_MPA = 1e6

SPEED_TOLERANCE = 0.01 / RPM
"""Width (rad/s) to which the ends of a range above a limit are bisected: 0.01 rpm."""
_NEAR_LIMIT = 0.99  # local maxima of curve / limit above this are refined to _TANGENCY
_TANGENCY = 1e-6


STRENGTH_CAPS = {
    ("carbon", "intermediate"): 760e6,
    ("carbon", "thrust"): 760e6,
    ("carbon", "propeller"): 600e6,
    ("alloy", "intermediate"): 800e6,
    ("alloy", "thrust"): 800e6,
    ("alloy", "propeller"): 600e6,
}
"""Largest sigma_B (Pa) the M68 formulas may use, by (material, shaft kind): 760 N/mm^2 for
carbon and carbon-manganese steel intermediate and thrust shafts, 800 N/mm^2 for alloy steel,
600 N/mm^2 for propeller shafts (sources: :mod:`crankdyn.tvc.limits`)."""


def capped_strength(
    tensile_strength: float, material: str, kind: str, cap: float | None = None
) -> float:
    """sigma_B the M68 formulas use: the specified minimum tensile strength, at most the cap.

    IACS UR M68.4 (module docstring; the caps :data:`STRENGTH_CAPS`).

    Parameters
    ----------
    tensile_strength : float
        Specified minimum tensile strength of the material (Pa).
    material : str
        ``"carbon"`` or ``"alloy"``.
    kind : str
        ``"intermediate"``, ``"thrust"`` or ``"propeller"``.
    cap : float or None
        The cap (Pa) where the society states another value; None: :data:`STRENGTH_CAPS`.

    Returns
    -------
    float
        sigma_B (Pa).

    Examples
    --------
    >>> capped_strength(900e6, "carbon", "propeller") / 1e6  # capped at 600 N/mm^2
    600.0
    >>> capped_strength(700e6, "alloy", "intermediate") / 1e6
    700.0
    """
    limit = cap if cap is not None else STRENGTH_CAPS[(material, kind)]
    return min(float(tensile_strength), float(limit))


def size_factor(diameter: ArrayLike) -> NDArray[np.float64]:
    """The size factor C_D = 0.35 + 0.93 d^-0.2 with d in mm (IACS UR M68.4).

    Parameters
    ----------
    diameter : float or array_like
        Outer diameter d of the shaft (m).

    Returns
    -------
    numpy.ndarray
        C_D (dimensionless), of the shape of ``diameter``.

    Examples
    --------
    >>> round(float(size_factor(0.3)), 9)  # 0.35 + 0.93 x 300^-0.2
    0.64720677
    """
    d_mm = np.asarray(diameter, dtype=float) * 1e3
    return 0.35 + 0.93 * d_mm**-0.2


def permissible_continuous(
    speed_ratio: ArrayLike,
    tensile_strength: float | NDArray[np.float64],
    design_factor: float | NDArray[np.float64],
    diameter: ArrayLike,
) -> NDArray[np.float64]:
    """Permissible stress tau_C for continuous operation (IACS UR M68.4; module docstring).

    tau_C = (sigma_B + 160)/18 C_K C_D (3 - 2 lambda^2) below lambda = 0.9, with the factor
    1.38 for 0.9 <= lambda <= 1.05 (sigma_B in N/mm^2, tau_C in N/mm^2).

    Parameters
    ----------
    speed_ratio : array_like
        lambda = n / n_0 (dimensionless).
    tensile_strength : float or numpy.ndarray
        sigma_B (Pa), capped (:func:`capped_strength`); broadcast against ``speed_ratio``.
    design_factor : float or numpy.ndarray
        C_K (dimensionless).
    diameter : float or array_like
        Outer diameter d (m), for C_D (:func:`size_factor`).

    Returns
    -------
    numpy.ndarray
        tau_C (Pa), the half-range amplitude of the vibratory shear stress; NaN above
        lambda = 1.05 (no limit given by the UR).

    Examples
    --------
    sigma_B = 600 N/mm^2, a plain 300 mm shaft (C_K = 1): at lambda = 0.5 the factor is
    3 - 2 x 0.25 = 2.5, at lambda = 1 it is 1.38.

    >>> tau_c = permissible_continuous([0.5, 1.0, 1.1], 600e6, 1.0, 0.3)
    >>> np.round(tau_c / 1e6, 4).tolist()
    [68.3163, 37.7106, nan]
    """
    lam = np.asarray(speed_ratio, dtype=float)
    base = (tensile_strength / _MPA + 160.0) / 18.0 * design_factor * size_factor(diameter)
    factor = np.where(lam < 0.9, 3.0 - 2.0 * lam**2, 1.38)
    return np.where(lam <= 1.05, base * factor * _MPA, np.nan)


def permissible_transient(
    speed_ratio: ArrayLike, tau_c: ArrayLike, design_factor: ArrayLike
) -> NDArray[np.float64]:
    """Permissible stress tau_T = 1.7 tau_C / sqrt(C_K) for transient running through a barred
    speed range (IACS UR M68.4; module docstring).

    Parameters
    ----------
    speed_ratio : array_like
        lambda = n / n_0 (dimensionless).
    tau_c : array_like
        tau_C at those speed ratios (Pa; :func:`permissible_continuous`).
    design_factor : float or array_like
        C_K (dimensionless).

    Returns
    -------
    numpy.ndarray
        tau_T (Pa) for lambda <= 0.8, NaN above (no barred range permitted there).

    Examples
    --------
    >>> tau_t = permissible_transient([0.5, 0.9], [68.0e6, 40.0e6], 0.5)
    >>> np.round(tau_t / 1e6, 3).tolist()  # 1.7 x 68 / sqrt(0.5)
    [163.483, nan]
    """
    lam = np.asarray(speed_ratio, dtype=float)
    return np.where(lam <= 0.8, 1.7 * np.asarray(tau_c) / np.sqrt(design_factor), np.nan)


@dataclass(frozen=True)
class ShaftLimit:
    """Material and design factor of one shaft for the rule check.

    Parameters
    ----------
    between : (str, str)
        The shaft's two masses (its outer diameter comes from the shaft's geometry).
    tensile_strength : float
        Specified minimum tensile strength sigma_B (Pa), > 0.
    design_factor : float
        C_K (dimensionless), 0 < C_K <= 1.
    material : str
        ``"carbon"`` (carbon and carbon-manganese steel, default) or ``"alloy"``, for the cap on
        sigma_B (:data:`STRENGTH_CAPS`).
    kind : str
        ``"intermediate"`` (default), ``"thrust"`` or ``"propeller"`` shaft, for the cap.
    strength_cap : float or None
        The largest sigma_B (Pa) the formulas may use, where the society states another value
        than the default cap; None: the cap of the material and kind.
    feature : str or None
        The design feature C_K was taken from (a key of
        :data:`crankdyn.tvc.limits.DESIGN_FACTORS`), for reports; None: given as a number.

    Raises
    ------
    InputError
        Naming the key and value: ``between`` not two names, a tensile strength or cap that
        is not positive, C_K outside (0, 1], an unknown ``material`` or ``kind``.

    Examples
    --------
    >>> limit = ShaftLimit(("gearbox", "propeller"), 900e6, 0.6, kind="propeller")
    >>> limit.strength_used / 1e6  # the cap of a carbon-steel propeller shaft
    600.0
    """

    between: tuple[str, str]
    tensile_strength: float
    design_factor: float = 1.0
    material: str = "carbon"
    kind: str = "intermediate"
    strength_cap: float | None = None
    feature: str | None = None

    @property
    def strength_used(self) -> float:
        """sigma_B (Pa) in the formulas: the tensile strength, at most the cap (M68;
        :func:`capped_strength`)."""
        return capped_strength(self.tensile_strength, self.material, self.kind, self.strength_cap)

    def __post_init__(self) -> None:
        ends = tuple(self.between) if isinstance(self.between, (list, tuple)) else ()
        if len(ends) != 2 or any(not isinstance(e, str) for e in ends):
            raise InputError("expected the names of two masses", key="between", value=ends)
        object.__setattr__(self, "between", ends)
        object.__setattr__(
            self,
            "tensile_strength",
            check_positive("tensile_strength", self.tensile_strength, "the tensile strength"),
        )
        ck = check_finite("design_factor", self.design_factor)
        if not 0.0 < ck <= 1.0:
            raise InputError(
                "the design-feature factor C_K must lie in 0 < C_K <= 1",
                key="design_factor",
                value=self.design_factor,
            )
        object.__setattr__(self, "design_factor", ck)
        if self.material not in ("carbon", "alloy"):
            raise InputError("expected carbon or alloy", key="material", value=self.material)
        if self.kind not in ("intermediate", "thrust", "propeller"):
            raise InputError(
                "expected intermediate, thrust or propeller", key="kind", value=self.kind
            )
        if self.strength_cap is not None:
            object.__setattr__(
                self,
                "strength_cap",
                check_positive("tensile_strength_cap", self.strength_cap, "the cap"),
            )


@dataclass(frozen=True)
class RuleSet:
    """The rule check's inputs: the rated speed and the checked shafts.

    Parameters
    ----------
    rated_speed : float or None
        Rated speed n_0 (rad/s), > 0; None: the engine's operating speed.
    shafts : tuple of ShaftLimit
        The checked shafts, at least one.

    Raises
    ------
    InputError
        Naming the key and value: a rated speed that is not positive (``rated_speed``), no
        shaft (``shaft``).

    Examples
    --------
    >>> rules = RuleSet(104.72, [ShaftLimit(("engine", "propeller"), 600e6)])
    >>> len(rules.shafts), rules.shafts[0].design_factor
    (1, 1.0)
    """

    rated_speed: float | None
    shafts: tuple[ShaftLimit, ...]

    def __post_init__(self) -> None:
        if self.rated_speed is not None:
            object.__setattr__(
                self,
                "rated_speed",
                check_positive("rated_speed", self.rated_speed, "the rated speed"),
            )
        object.__setattr__(self, "shafts", tuple(self.shafts))
        if not self.shafts:
            raise InputError("name at least one shaft to check ([[rules.shaft]])", key="shaft")


@dataclass(frozen=True)
class BarredRange(Result):
    """A speed range where the synthesised stress of a shaft exceeds tau_C (IACS UR M68.4:
    permitted below 0.8 n_0 while the stress stays below tau_T; :func:`check_rules`).

    Examples
    --------
    >>> import math
    >>> from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
    >>> from crankdyn.torsion.excitation import UniformExcitation
    >>> from crankdyn.torsion.response import forced_response
    >>> model = TorsionModel(
    ...     masses=(Mass("engine", 2.0, damping=5.0, cylinders=(1,)), Mass("propeller", 6.0)),
    ...     shafts=(Shaft(("engine", "propeller"), 5.3e4, geometry=ShaftGeometry(0.06)),),
    ... )
    >>> rpm = math.pi / 30
    >>> response = forced_response(
    ...     model, UniformExcitation(60.0, [0.0], "two-stroke"),
    ...     np.linspace(200, 1050, 86) * rpm, [3.0], rules=False,
    ... )
    >>> rules = RuleSet(1000 * rpm, [ShaftLimit(("engine", "propeller"), 600e6)])
    >>> barred = check_rules(response, rules, model).barred_ranges[0]
    >>> round(barred.start / rpm, 1), round(barred.end / rpm, 1), barred.permitted
    (595.2, 601.5, True)
    """

    shaft: tuple[str, str] = scalar("shaft", "Shaft", "")
    start: float = scalar("start_rpm", "From", "rpm", RPM)
    end: float = scalar("end_rpm", "To", "rpm", RPM)
    max_stress: float = scalar("max_stress_Pa", "Largest stress", "Pa")
    max_ratio: float = scalar("max_stress_to_tau_c", "Largest stress / τ_C", "", fmt=".4g")
    permitted: bool = scalar("permitted", "Permitted as a barred range", "")
    reason: str = scalar("reason", "Why", "")
    peak_speed: float | None = scalar(
        "max_stress_speed_rpm", "Largest stress at", "rpm", RPM, default=None
    )
    open_start: bool = scalar(
        "starts_below_sweep", "Starts below the swept range", "", default=False
    )
    open_end: bool = scalar("ends_above_sweep", "Ends above the swept range", "", default=False)


@dataclass(frozen=True)
class RuleCheck(Result):
    """Synthesised shaft stresses against the IACS UR M68 limits (module docstring).

    Examples
    --------
    >>> import math
    >>> from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
    >>> from crankdyn.torsion.excitation import UniformExcitation
    >>> from crankdyn.torsion.response import forced_response
    >>> model = TorsionModel(
    ...     masses=(Mass("engine", 2.0, damping=5.0, cylinders=(1,)), Mass("propeller", 6.0)),
    ...     shafts=(Shaft(("engine", "propeller"), 5.3e4, geometry=ShaftGeometry(0.06)),),
    ... )
    >>> rpm = math.pi / 30
    >>> response = forced_response(
    ...     model, UniformExcitation(60.0, [0.0], "two-stroke"),
    ...     np.linspace(200, 1050, 86) * rpm, [3.0], rules=False,
    ... )
    >>> rules = RuleSet(1000 * rpm, [ShaftLimit(("engine", "propeller"), 600e6)])
    >>> check = check_rules(response, rules, model)
    >>> check.passed, len(check.barred_ranges), check.stress.shape == check.tau_c.shape
    (True, 1, True)
    """

    title = "Rule check"
    rule: str = scalar("rule", "Rule", "")
    rated_speed: float = scalar("rated_speed_rpm", "Rated speed n_0", "rpm", RPM)
    shafts: tuple[tuple[str, str], ...] = scalar("shafts", "Checked shafts", "")
    speed: np.ndarray = array("speed_rpm", "Speed", "rpm", RPM)
    stress: np.ndarray = array("stress_Pa", "Synthesised stress (speed x shaft)", "Pa")
    tau_c: np.ndarray = array("tau_c_Pa", "Permissible, continuous τ_C", "Pa")
    tau_t: np.ndarray = array("tau_t_Pa", "Permissible, transient τ_T", "Pa")
    exceeds: np.ndarray = array("exceeds_continuous", "Stress above τ_C", "")
    barred_ranges: tuple[BarredRange, ...] = scalar("barred_speed_ranges", "Barred ranges", "")
    passed: bool = scalar("passed", "Passed", "")
    notes: tuple[str, ...] | None = scalar("notes", "Notes", "")

    def max_ratio(self) -> tuple[float, str] | None:
        """The largest synthesised stress over tau_C, with the shaft and speed where it occurs
        (None without checked shafts)."""
        ratio = np.asarray(self.stress) / np.asarray(self.tau_c)
        if ratio.size == 0 or not np.isfinite(ratio).any():
            return None
        i, j = np.unravel_index(int(np.nanargmax(ratio)), ratio.shape)
        shaft = " - ".join(self.shafts[j])
        return float(ratio[i, j]), f"{shaft} at {self.speed[i] * RPM:.6g} rpm"


@dataclass(frozen=True)
class Exceedance:
    """A speed range where a response curve exceeds its limit (:func:`exceedances`).

    ``start`` and ``end`` (rad/s) are bisected crossings, or the swept range's ends where the
    curve is above the limit there (``open_start``, ``open_end``); ``peak`` is the curve's
    largest sampled value inside (its peak resolved), ``peak_ratio`` the largest curve / limit,
    ``peak_speed`` (rad/s) where the curve peaks; ``rows`` the rows of the response's speeds
    inside the range.

    Parameters
    ----------
    column : int
        The curve's column (of the ``curve`` and ``limit`` arrays).
    start, end : float
        The range's ends (rad/s).
    open_start, open_end : bool
        The range starts below (ends above) the swept range.
    peak : float
        The curve's largest value inside (the curve's unit).
    peak_ratio : float
        The largest curve / limit inside (dimensionless).
    peak_speed : float
        Where the curve peaks (rad/s).
    rows : numpy.ndarray
        The rows (int) of the response's speeds inside the range.
    """

    column: int
    start: float
    end: float
    open_start: bool
    open_end: bool
    peak: float
    peak_ratio: float
    peak_speed: float
    rows: np.ndarray


def exceedances(
    result: ResponseResult,
    curve: Callable[[ResponseResult], ArrayLike],
    limit: Callable[[NDArray[np.float64]], ArrayLike],
    *,
    width: float = SPEED_TOLERANCE,
) -> tuple[Exceedance, ...]:
    """Where a curve of a response exceeds a limit curve, with the ends of every range found by
    bisection (module docstring).

    The local maxima of curve / limit within 1 % of 1 are refined by successive parabolic
    interpolation (:func:`crankdyn.torsion.resolve.refinement_speeds`), the ends of every
    range bisected (:func:`crankdyn.torsion.resolve.bisect_crossings`).

    Parameters
    ----------
    result : crankdyn.torsion.response.ResponseResult
        The response, resolved for grid-independent answers; without an evaluator
        (``result.at``) the ends are the outermost samples above the limit.
    curve : callable
        ``curve(r)`` -> (S, k): the curves of a response ``r`` (e.g. the synthesised stress of
        some shafts, Pa).
    limit : callable
        ``limit(speeds)`` -> (S, k): the limits at speeds (rad/s) in the curves' unit, NaN
        where there is none.
    width : float
        The ends are bisected to brackets this narrow (rad/s; default 0.01 rpm).

    Returns
    -------
    tuple of Exceedance
        Sorted by column, then speed.

    Examples
    --------
    The order-3 resonance of an engine and a propeller on a 60 mm shaft, at
    sqrt(k (1/J_e + 1/J_p)) / 3 = 598.3 rpm, against tau_C of M68 for n_0 = 1000 rpm:

    >>> import math
    >>> from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
    >>> from crankdyn.torsion.excitation import UniformExcitation
    >>> from crankdyn.torsion.response import forced_response
    >>> model = TorsionModel(
    ...     masses=(Mass("engine", 2.0, damping=5.0, cylinders=(1,)), Mass("propeller", 6.0)),
    ...     shafts=(Shaft(("engine", "propeller"), 5.3e4, geometry=ShaftGeometry(0.06)),),
    ... )
    >>> rpm = math.pi / 30
    >>> response = forced_response(
    ...     model, UniformExcitation(60.0, [0.0], "two-stroke"),
    ...     np.linspace(200, 1050, 86) * rpm, [3.0], rules=False,
    ... )
    >>> def tau_c(w):
    ...     return permissible_continuous(w[:, None] / (1000 * rpm), 600e6, 1.0, 0.06)
    >>> (ex,) = exceedances(response, lambda r: r.synthesized_shaft_stress, tau_c)
    >>> round(ex.start / rpm, 1), round(ex.peak_speed / rpm), round(ex.end / rpm, 1)
    (595.2, 598, 601.5)
    """
    speed = np.asarray(result.speed, dtype=float)
    values = np.asarray(curve(result), dtype=float)
    limits = np.asarray(limit(speed), dtype=float)
    columns = values.shape[1]
    can_evaluate = getattr(result, "evaluator", None) is not None
    # near-limit local maxima of curve / limit, refined to decide tangencies by the curve
    if can_evaluate and speed.size >= 3:
        for _ in range(60):
            with np.errstate(divide="ignore", invalid="ignore"):
                ratio = np.where(np.isfinite(limits) & (limits > 0.0), values / limits, 0.0)
            new, _ = refinement_speeds(
                speed,
                ratio,
                scale=np.ones(columns),
                tolerance=_TANGENCY,
                threshold=np.full(columns, _NEAR_LIMIT),
            )
            if new.size == 0:
                break
            speed, first = merge_speeds(speed, new)
            values = np.concatenate([values, curve(result.at(new))])[first]
            limits = np.concatenate([limits, limit(new)])[first]
    with np.errstate(invalid="ignore"):
        above = values > limits
    out = []
    ends = []  # (index into out, which end, low, high, column, rising)
    for col in range(columns):
        for a, b in _runs(above[:, col]):
            seg = slice(a, b + 1)
            with np.errstate(divide="ignore", invalid="ignore"):
                ratio = values[seg, col] / limits[seg, col]
            k = a + int(np.argmax(values[seg, col]))
            out.append(
                Exceedance(
                    column=col,
                    start=float(speed[a]),
                    end=float(speed[b]),
                    open_start=a == 0,
                    open_end=b == speed.size - 1,
                    peak=float(values[k, col]),
                    peak_ratio=float(np.nanmax(ratio)),
                    peak_speed=float(speed[k]),
                    rows=np.flatnonzero((result.speed >= speed[a]) & (result.speed <= speed[b])),
                )
            )
            if a > 0:
                ends.append((len(out) - 1, "start", speed[a - 1], speed[a], col, True))
            if b < speed.size - 1:
                ends.append((len(out) - 1, "end", speed[b], speed[b + 1], col, False))
    if ends and can_evaluate:
        cols = np.array([e[4] for e in ends])

        def excess(speeds: NDArray[np.float64], which: NDArray[np.intp]) -> NDArray[np.float64]:
            r = result.at(speeds)
            v = np.asarray(curve(r), dtype=float)[np.arange(speeds.size), cols[which]]
            lim = np.asarray(limit(speeds), dtype=float)[np.arange(speeds.size), cols[which]]
            return np.where(np.isfinite(lim), v - lim, -np.inf)

        found = bisect_crossings(
            excess,
            [e[2] for e in ends],
            [e[3] for e in ends],
            [e[5] for e in ends],
            width,
        )
        for (index, which, *_), speed_at in zip(ends, found, strict=True):
            end_at: dict[str, Any] = {which: float(speed_at)}
            out[index] = dataclasses.replace(out[index], **end_at)
    return tuple(out)


def check_rules(
    result: ResponseResult,
    rules: RuleSet,
    model: TorsionModel | None = None,
    rated_speed: float | None = None,
) -> RuleCheck:
    """Check the synthesised shaft stresses of a response against IACS UR M68.4.

    Barred ranges come from :func:`exceedances` on the synthesised stress against tau_C
    (:func:`permissible_continuous`): their ends bisected to 0.01 rpm, so the verdict and the
    ranges do not depend on the grid of a resolved response. A range is permitted below
    0.8 n_0 while the stress stays below tau_T (:func:`permissible_transient`).

    Parameters
    ----------
    result : crankdyn.torsion.response.ResponseResult
        The forced response, with the shafts' section moduli (their diameters).
    rules : RuleSet
        The rated speed and the checked shafts.
    model : crankdyn.torsion.model.TorsionModel or None
        The model the response is of, for the shafts' outer diameters (C_D); None: no size
        factor can be computed (tau_C NaN).
    rated_speed : float or None
        n_0 (rad/s) when the rule set has none (the engine's operating speed).

    Returns
    -------
    RuleCheck
        Stress, tau_C and tau_T (Pa) per speed and checked shaft, the barred ranges and the
        verdict.

    Raises
    ------
    InputError
        Naming the key and value: no rated speed (``rated_speed``), a checked shaft without
        diameters (``[rules] shaft`` and its two masses), a shaft not in the model
        (:meth:`~crankdyn.torsion.response.ResponseResult.shaft_index`).

    Examples
    --------
    >>> import math
    >>> from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
    >>> from crankdyn.torsion.excitation import UniformExcitation
    >>> from crankdyn.torsion.response import forced_response
    >>> model = TorsionModel(
    ...     masses=(Mass("engine", 2.0, damping=5.0, cylinders=(1,)), Mass("propeller", 6.0)),
    ...     shafts=(Shaft(("engine", "propeller"), 5.3e4, geometry=ShaftGeometry(0.06)),),
    ... )
    >>> rpm = math.pi / 30
    >>> response = forced_response(
    ...     model, UniformExcitation(60.0, [0.0], "two-stroke"),
    ...     np.linspace(200, 1050, 86) * rpm, [3.0], rules=False,
    ... )
    >>> rules = RuleSet(1000 * rpm, [ShaftLimit(("engine", "propeller"), 600e6)])
    >>> check = check_rules(response, rules, model)
    >>> check.passed, [b.reason for b in check.barred_ranges]
    (True, ['τ_C exceeded below 0.8 n_0 and τ_T kept: pass through quickly'])
    """
    n0 = rules.rated_speed if rules.rated_speed is not None else rated_speed
    if n0 is None:
        raise InputError(
            "the rule check needs the rated speed n_0: give [rules] rated_speed (or the "
            "engine's [operating] speed)",
            key="rated_speed",
        )
    speeds = np.asarray(result.speed)
    lam = speeds / n0
    shaft_rows: list[int] = []
    labels: list[tuple[str, str]] = []
    strength_list: list[float] = []
    factor_list: list[float] = []
    diameter_list: list[float | None] = []
    for limit in rules.shafts:
        s = result.shaft_index(limit.between)
        modulus = result.section_modulus[s] if result.section_modulus is not None else np.nan
        if not np.isfinite(modulus):
            raise InputError(
                f'shaft "{limit.between[0]} - {limit.between[1]}" has no diameters: the rule '
                "check needs its outer_diameter (and inner_diameter)",
                key="[rules] shaft",
                value=list(limit.between),
            )
        geometry = model.shafts[s].geometry if model is not None else None
        diameter = geometry.outer_diameter if geometry is not None else None
        shaft_rows.append(s)
        labels.append(result.shafts[s])
        strength_list.append(limit.strength_used)
        factor_list.append(limit.design_factor)
        diameter_list.append(diameter)
    index = np.array(shaft_rows)
    strengths = np.array(strength_list)
    factors = np.array(factor_list)
    diameters = np.array(diameter_list, dtype=float)

    def tau_c_at(w: ArrayLike) -> NDArray[np.float64]:
        ratio = np.asarray(w, dtype=float)[:, None] / n0
        return permissible_continuous(ratio, strengths, factors, diameters)

    def tau_t_at(w: ArrayLike) -> NDArray[np.float64]:
        ratio = np.asarray(w, dtype=float)[:, None] / n0
        return permissible_transient(ratio, tau_c_at(w), factors[None, :])

    def stress_of(r: ResponseResult) -> NDArray[np.float64]:
        return np.asarray(r.synthesized_shaft_stress)[:, index]

    stress = stress_of(result)
    tau_c = tau_c_at(speeds)
    tau_t = tau_t_at(speeds)
    with np.errstate(invalid="ignore"):
        exceeds = stress > tau_c
    barred = []
    for ex in exceedances(result, stress_of, tau_c_at):
        j = ex.column
        rows = ex.rows
        above = bool(ex.end > 0.8 * n0)
        with np.errstate(invalid="ignore"):
            over_t = bool(np.any(~(stress[rows, j] <= tau_t[rows, j]))) if rows.size else False
        reason = (
            "reaches above 0.8 n_0, where no barred range is permitted"
            if above
            else "exceeds τ_T for transient operation"
            if over_t
            else "τ_C exceeded below 0.8 n_0 and τ_T kept: pass through quickly"
        )
        barred.append(
            BarredRange(
                shaft=labels[j],
                start=ex.start,
                end=ex.end,
                max_stress=ex.peak,
                max_ratio=ex.peak_ratio,
                permitted=not (above or over_t),
                reason=reason,
                peak_speed=ex.peak_speed,
                open_start=ex.open_start,
                open_end=ex.open_end,
            )
        )
    notes = []
    if np.any(lam > 1.05):
        notes.append("speeds above 1.05 n_0 are not checked (the rule gives no limit there)")
    if any(b.open_start or b.open_end for b in barred):
        notes.append(
            "a barred range reaches an end of the swept range: sweep further to find its end"
        )
    return RuleCheck(
        rule=RULE,
        rated_speed=n0,
        shafts=tuple(labels),
        speed=freeze(speeds),
        stress=freeze(stress),
        tau_c=freeze(tau_c),
        tau_t=freeze(tau_t),
        exceeds=freeze(exceeds, dtype=bool),
        barred_ranges=tuple(barred),
        passed=all(b.permitted for b in barred),
        notes=tuple(notes) or None,
    )


def _runs(mask: ArrayLike) -> list[tuple[int, int]]:
    """(first, last) indices of the runs of True in a 1-D mask."""
    m = np.concatenate([[False], np.asarray(mask, dtype=bool), [False]])
    edges = np.flatnonzero(np.diff(m.astype(int)))
    return [(int(a), int(b) - 1) for a, b in zip(edges[::2], edges[1::2], strict=True)]
