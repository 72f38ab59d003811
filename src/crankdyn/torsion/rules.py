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

The check itself (the shafts' synthesised stresses against these limits, the barred ranges
and their permission) is one of the installation's checks, evaluated in one place for every
front end: :class:`crankdyn.tvc.checks.M68Shafts`, :func:`crankdyn.tvc.evaluate.
evaluate_condition`. This module holds the rule's formulas, its inputs (:class:`RuleSet`,
:class:`ShaftLimit`) and :func:`exceedances`.

Grid independence. :func:`exceedances` runs on the resolved response (the resonance peaks
refined to 0.1 %, :mod:`crankdyn.torsion.resolve`); the local maxima of curve / limit that come
within 1 % of the limit are refined further (to 1e-6), so a tangency is decided by the curve,
not by the grid; and the ends of every range are bisected on the curve minus the limit to
0.01 rpm (all ends at once per round), for any curve of a response against any limit curve
(shafts, couplings, gears, ... against their own limits).
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
from crankdyn.torsion.resolve import bisect_crossings, merge_speeds, refinement_speeds

if TYPE_CHECKING:
    from crankdyn.torsion.response import ResponseResult

__all__ = [
    "RULE",
    "SPEED_TOLERANCE",
    "STRENGTH_CAPS",
    "Exceedance",
    "RuleSet",
    "ShaftLimit",
    "capped_strength",
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
    >>> from crankdyn.torsion.sweep import forced_response
    >>> model = TorsionModel(
    ...     masses=(Mass("engine", 2.0, damping=5.0, cylinders=(1,)), Mass("propeller", 6.0)),
    ...     shafts=(Shaft(("engine", "propeller"), 5.3e4, geometry=ShaftGeometry(0.06)),),
    ... )
    >>> rpm = math.pi / 30
    >>> response = forced_response(
    ...     model, UniformExcitation(60.0, [0.0], "two-stroke"),
    ...     np.linspace(200, 1050, 86) * rpm, [3.0],
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


def _runs(mask: ArrayLike) -> list[tuple[int, int]]:
    """(first, last) indices of the runs of True in a 1-D mask."""
    m = np.concatenate([[False], np.asarray(mask, dtype=bool), [False]])
    edges = np.flatnonzero(np.diff(m.astype(int)))
    return [(int(a), int(b) - 1) for a, b in zip(edges[::2], edges[1::2], strict=True)]
