"""The formulas of the rule sets, vectorised over speed ratio and diameter (numpy broadcasting):
tau_C and tau_T under each society's caps, the C_K table, the declared barred range (least range,
tachometer tolerance), where a barred range and a major critical may lie, controllable-pitch
propellers, and the crankshaft and generating-set limits where the society states them
(docs/tvc.md, "Rule sets"). Each function cites the clauses its values come from; the values
themselves are the :class:`~crankdyn.tvc.rulesets.model.RuleSet`'s, each with its clause.

They reuse :mod:`crankdyn.torsion.rules` (tau_C, tau_T, C_D) and :mod:`crankdyn.tvc.limits` (the
least barred range); the ``"iacs-m68"`` and ``"lr"`` sets reproduce crankdyn's IACS behaviour and
LR margin bit for bit.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.errors import InputError, did_you_mean
from crankdyn.torsion.rules import ShaftLimit, permissible_continuous, permissible_transient
from crankdyn.tvc.limits import barred_limits
from crankdyn.tvc.rulesets.model import (
    DEFAULT_TACHOMETER_TOLERANCE,
    CrankshaftRule,
    RuleSet,
)

__all__ = [
    "barred_range_permitted",
    "capped_strength",
    "continuous_limit",
    "cpp_conditions",
    "crankshaft_limits",
    "declared_barred_range",
    "design_factor",
    "engine_group",
    "genset_limits",
    "major_critical_permitted",
    "material_factors",
    "shaft_limit",
    "tachometer_tolerance",
    "transient_limit",
]

_MPA = 1e6


def capped_strength(
    rules: RuleSet,
    tensile_strength: ArrayLike,
    material: str = "carbon",
    kind: str = "intermediate",
) -> NDArray[np.float64]:
    """sigma_B the society's formula uses: the specified minimum tensile strength, at most the
    society's cap for the material and shaft kind (:attr:`RuleSet.strength_caps`; KR 2025 Pt 5
    Ch 4 202.1(1), LR Pt 5 Ch 6 2.1.1/2.1.4, IACS UR M68.3).

    Parameters
    ----------
    rules : RuleSet
    tensile_strength : float or array_like
        Specified minimum tensile strength (Pa).
    material : str
        ``"carbon"`` (carbon and carbon-manganese steel) or ``"alloy"``.
    kind : str
        ``"intermediate"``, ``"thrust"`` or ``"propeller"`` (KR: propeller and stern tube shafts).

    Returns
    -------
    numpy.ndarray
        sigma_B (Pa), the shape of ``tensile_strength``.

    Raises
    ------
    InputError
        Naming ``material`` or ``kind`` when unknown.

    Examples
    --------
    >>> from crankdyn.tvc.rulesets import get

    >>> [float(capped_strength(get(k), 800e6)) / 1e6 for k in ("kr", "lr")]
    [600.0, 760.0]
    """
    if material not in ("carbon", "alloy"):
        raise InputError("expected carbon or alloy", key="material", value=material)
    if kind not in ("intermediate", "thrust", "propeller"):
        raise InputError("expected intermediate, thrust or propeller", key="kind", value=kind)
    cap = rules.strength_caps[(material, kind)].value
    return np.minimum(np.asarray(tensile_strength, dtype=float), cap)


def continuous_limit(
    rules: RuleSet,
    speed_ratio: ArrayLike,
    tensile_strength: ArrayLike,
    design_factor: ArrayLike,
    diameter: ArrayLike,
    material: str = "carbon",
    kind: str = "intermediate",
) -> NDArray[np.float64]:
    """The society's tau_C for continuous running of a propulsion shaft.

    tau_C = (sigma_B + 160)/18 C_K C_D (3 - 2 lambda^2) below lambda = 0.9, the factor 1.38 from
    0.9 to 1.05 (sigma_B in N/mm^2 capped by :func:`capped_strength`, C_D = 0.35 + 0.93 d^-0.2,
    d in mm): KR 2025 Pt 5 Ch 4 202.1(1), IACS UR M68.4 (:attr:`RuleSet.shaft_formula`);
    :func:`crankdyn.torsion.rules.permissible_continuous`.

    Parameters
    ----------
    rules : RuleSet
    speed_ratio : array_like
        lambda = n / n_0 (dimensionless).
    tensile_strength : float or array_like
        Specified minimum tensile strength (Pa), before the cap.
    design_factor : float or array_like
        C_K (dimensionless).
    diameter : float or array_like
        Outer diameter (m).
    material, kind : str
        For the cap (:func:`capped_strength`).

    Returns
    -------
    numpy.ndarray
        tau_C (Pa), broadcast over the arguments; NaN above lambda = 1.05.

    Examples
    --------
    >>> from crankdyn.tvc.rulesets import get

    Carbon steel of 800 N/mm^2, a plain 300 mm intermediate shaft at lambda = 0.95 (MPa):

    >>> tau = [continuous_limit(get(k), 0.95, 800e6, 1.0, 0.3) for k in ("kr", "lr")]
    >>> [round(float(t) / 1e6, 4) for t in tau]
    [37.7106, 45.6497]
    """
    sigma = capped_strength(rules, tensile_strength, material, kind)
    ck = np.asarray(design_factor, dtype=float)
    return permissible_continuous(speed_ratio, sigma, ck, diameter)


def transient_limit(
    rules: RuleSet,
    speed_ratio: ArrayLike,
    tensile_strength: ArrayLike,
    design_factor: ArrayLike,
    diameter: ArrayLike,
    material: str = "carbon",
    kind: str = "intermediate",
) -> NDArray[np.float64]:
    """The society's tau_T while passing a barred range: 1.7 tau_C / sqrt(C_K) up to
    lambda = 0.8 (KR 2025 Pt 5 Ch 4 202.1(2), IACS UR M68.4; :attr:`RuleSet.transient_formula`,
    :func:`crankdyn.torsion.rules.permissible_transient`).

    Parameters
    ----------
    rules : RuleSet
    speed_ratio : array_like
        lambda = n / n_0 (dimensionless).
    tensile_strength : float or array_like
        Specified minimum tensile strength (Pa), before the cap.
    design_factor : float or array_like
        C_K (dimensionless).
    diameter : float or array_like
        Outer diameter (m).
    material, kind : str
        For the cap.

    Returns
    -------
    numpy.ndarray
        tau_T (Pa), broadcast; NaN above lambda = 0.8.

    Examples
    --------
    >>> from crankdyn.tvc.rulesets import get

    C_K = 0.6, 300 mm, capped at 600: 1.7 x 40.9898 / sqrt(0.6) (MPa):

    >>> round(float(transient_limit(get("kr"), 0.5, 800e6, 0.6, 0.3)) / 1e6, 3)
    89.96
    """
    tau_c = continuous_limit(
        rules, speed_ratio, tensile_strength, design_factor, diameter, material, kind
    )
    return permissible_transient(speed_ratio, tau_c, design_factor)


def design_factor(rules: RuleSet, feature: str) -> float:
    """C_K of a design feature in the society's table (:attr:`RuleSet.design_factors`).

    Parameters
    ----------
    rules : RuleSet
    feature : str
        A key of :data:`crankdyn.tvc.limits.DESIGN_FACTORS`.

    Returns
    -------
    float
        C_K (dimensionless).

    Raises
    ------
    InputError
        Naming the key ``feature`` with the closest feature.

    Examples
    --------
    >>> from crankdyn.tvc.rulesets import get

    >>> design_factor(get("kr"), "keyway cylindrical")
    0.45
    """
    return _factor(rules, feature)


def _factor(rules: RuleSet, feature: str) -> float:
    if feature not in rules.design_factors:
        raise InputError(
            f"expected one of {', '.join(rules.design_factors)}"
            f"{did_you_mean(feature, rules.design_factors)}",
            key="feature",
            value=feature,
        )
    return float(rules.design_factors[feature].value)


def shaft_limit(
    rules: RuleSet,
    between: tuple[str, str],
    tensile_strength: float,
    design_factor: float = 1.0,
    material: str = "carbon",
    kind: str = "intermediate",
    feature: str | None = None,
) -> ShaftLimit:
    """The :class:`crankdyn.torsion.rules.ShaftLimit` of a shaft under the society's cap, for
    the TVC's shaft check (:class:`crankdyn.tvc.checks.M68Shafts`).

    Parameters
    ----------
    rules : RuleSet
    between : (str, str)
        The shaft's two masses.
    tensile_strength : float
        Specified minimum tensile strength (Pa).
    design_factor : float
        C_K (dimensionless), used where ``feature`` is None.
    material, kind : str
        For the cap (:func:`capped_strength`).
    feature : str or None
        A design feature: C_K from the society's table (:func:`design_factor`).

    Returns
    -------
    ShaftLimit
        With ``strength_cap`` the society's cap.

    Examples
    --------
    >>> from crankdyn.tvc.rulesets import get

    >>> shaft_limit(get("kr"), ("a", "b"), 800e6).strength_used / 1e6
    600.0
    """
    ck = design_factor if feature is None else _factor(rules, feature)
    capped_strength(rules, tensile_strength, material, kind)  # validates material and kind
    return ShaftLimit(
        tuple(between),  # type: ignore[arg-type]
        tensile_strength,
        ck,
        material=material,
        kind=kind,
        strength_cap=rules.strength_caps[(material, kind)].value,
        feature=feature,
    )


def tachometer_tolerance(rules: RuleSet, given: float | None = None) -> float:
    """The tachometer tolerance that widens a declared barred range on both sides.

    ``given`` (the user's ``tachometer_tolerance``) where given, else the value the rule set's
    text states (:attr:`RuleSet.tachometer`), else :data:`DEFAULT_TACHOMETER_TOLERANCE` (no
    text read states one; KR 2025 Pt 5 Ch 4 206.3 asks for the accuracy to be regarded).

    Parameters
    ----------
    rules : RuleSet
    given : float or None
        The user's value (fraction of the speed).

    Returns
    -------
    float
        Fraction of the speed.

    Examples
    --------
    >>> from crankdyn.tvc.rulesets import get

    >>> tachometer_tolerance(get("kr")), tachometer_tolerance(get("kr"), 0.01)
    (0.02, 0.01)
    """
    if given is not None:
        return float(given)
    stated = rules.tachometer.value
    return float(stated) if stated is not None else DEFAULT_TACHOMETER_TOLERANCE


def declared_barred_range(
    rules: RuleSet,
    critical_speed: ArrayLike,
    rated_speed: float,
    exceeds_start: ArrayLike | None = None,
    exceeds_end: ArrayLike | None = None,
    tolerance: float | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The barred range to declare around a critical speed: the range where the limit is
    exceeded, widened to the society's least range (:attr:`RuleSet.widening`; KR 2025 Pt 5 Ch 4
    206.1(1), LR's margin: 16 n_c/(18 - lambda_c) to (18 - lambda_c) n_c/16), then by the
    tachometer tolerance on both sides (:func:`tachometer_tolerance`):
    start = min(exceeds_start, low) (1 - tol), end = max(exceeds_end, high) (1 + tol).

    Parameters
    ----------
    rules : RuleSet
    critical_speed : float or array_like
        n_c (rad/s): the speed of the largest response in the range.
    rated_speed : float
        n_0 (rad/s).
    exceeds_start, exceeds_end : float or array_like or None
        Where the limit is exceeded (rad/s); None: the critical speed.
    tolerance : float or None
        The tachometer tolerance (fraction); None: :func:`tachometer_tolerance` of the rules.

    Returns
    -------
    start, end : numpy.ndarray
        The declared range (rad/s), broadcast over the arguments.

    Examples
    --------
    >>> from crankdyn.tvc.rulesets import get

    n_c = 500 rpm, n_0 = 750 rpm, no tolerance (rpm): KR's least range
    16 x 500 / 17.3333 = 461.538 to 17.3333 x 500 / 16 = 541.667:

    >>> from crankdyn.constants import RPM
    >>> s, e = declared_barred_range(get("kr"), 500 / RPM, 750 / RPM, tolerance=0.0)
    >>> round(float(s) * RPM, 3), round(float(e) * RPM, 3)
    (461.538, 541.667)
    """
    nc = np.asarray(critical_speed, dtype=float)
    lo, hi = barred_limits(nc, rated_speed, rules.widening.value)
    a = nc if exceeds_start is None else np.asarray(exceeds_start, dtype=float)
    b = nc if exceeds_end is None else np.asarray(exceeds_end, dtype=float)
    tol = tachometer_tolerance(rules) if tolerance is None else float(tolerance)
    return np.minimum(a, lo) * (1.0 - tol), np.maximum(b, hi) * (1.0 + tol)


def barred_range_permitted(
    rules: RuleSet,
    start: ArrayLike,
    end: ArrayLike,
    rated_speed: float,
    application: str = "propulsion",
) -> NDArray[np.bool_]:
    """Whether a declared barred range is permitted where it lies: it ends at or below the
    society's highest speed ratio of a barred range (propulsion shafts 0.8: KR 2025 Pt 5 Ch 4
    202.1(2), IACS UR M68.4; generating sets 0.9: KR 203.1(2), 203.2(2)) and does not contain
    the rated speed. The stress against tau_T is a separate check.

    Parameters
    ----------
    rules : RuleSet
    start, end : float or array_like
        The declared range (rad/s).
    rated_speed : float
        n_0 (rad/s).
    application : str
        ``"propulsion"`` or ``"generator"``.

    Returns
    -------
    numpy.ndarray of bool
        Broadcast over ``start`` and ``end``.

    Raises
    ------
    InputError
        Naming ``application`` when unknown, or ``rules`` where the rule set states no limit
        for generating sets.

    Examples
    --------
    >>> from crankdyn.tvc.rulesets import get

    >>> barred_range_permitted(get("kr"), [300.0, 300.0], [400.0, 460.0], 500.0).tolist()
    [True, False]
    >>> bool(barred_range_permitted(get("kr"), 300.0, 450.0, 500.0, "generator"))
    True
    """
    if application == "propulsion":
        upper = rules.barred_upper.value
    elif application == "generator":
        cited = rules.transient_upper_genset
        if cited is None or cited.value is None:
            raise InputError(
                f"{rules.title}: no barred-range limit for generating sets in the text read "
                f"({cited.clause.cite() if cited else 'none'})",
                key="rules",
                value=rules.key,
            )
        upper = cited.value
    else:
        raise InputError("expected propulsion or generator", key="application", value=application)
    s = np.asarray(start, dtype=float)
    e = np.asarray(end, dtype=float)
    n0 = float(rated_speed)
    return (e <= upper * n0) & ~((s <= n0) & (n0 <= e))


def cpp_conditions(rules: RuleSet) -> tuple[str, ...]:
    """The pitch settings of a controllable-pitch propeller the society asks to calculate
    (KR 2025 Pt 5 Ch 4 206.1(2): both full and zero pitch); empty where the text read states
    none (:attr:`RuleSet.cpp` cites why).

    Parameters
    ----------
    rules : RuleSet

    Returns
    -------
    tuple of str

    Examples
    --------
    >>> from crankdyn.tvc.rulesets import get

    >>> cpp_conditions(get("kr")), cpp_conditions(get("lr"))
    (('full pitch', 'zero pitch'), ())
    """
    return tuple(rules.cpp.value)


def major_critical_permitted(
    rules: RuleSet,
    critical_speed: ArrayLike,
    rated_speed: float,
    application: str = "propulsion",
) -> NDArray[np.bool_]:
    """Whether a major critical of the one-node mode may lie at a speed: outside the society's
    window (KR 2025 Pt 5 Ch 4 204: 0.8 <= lambda <= 1.1 for propulsion, 0.9 <= lambda <= 1.1 for
    generators, unless specially approved).

    Parameters
    ----------
    rules : RuleSet
    critical_speed : float or array_like
        The major critical (rad/s).
    rated_speed : float
        n_0 (rad/s).
    application : str
        ``"propulsion"`` or ``"generator"``.

    Returns
    -------
    numpy.ndarray of bool
        True outside the window (the window's ends belong to it).

    Raises
    ------
    InputError
        Naming ``rules`` where the text read states no window for the application.

    Examples
    --------
    >>> from crankdyn.tvc.rulesets import get

    >>> major_critical_permitted(get("kr"), [85.0, 95.0, 112.0], 100.0, "generator").tolist()
    [True, False, True]
    """
    if application not in rules.major_criticals:
        raise InputError(
            f"{rules.title}: no window for major criticals of {application} shafting in the "
            "text read",
            key="rules",
            value=rules.key,
        )
    low, high = rules.major_criticals[application].value
    lam = np.asarray(critical_speed, dtype=float) / float(rated_speed)
    return ~((lam >= low) & (lam <= high))


def engine_group(cycle: int, vee: bool = False, firing_interval: float | None = None) -> str:
    """KR's engine group of the crankshaft and generating-set limits (KR 2025 Pt 5 Ch 4
    201.1(1)/(2); :data:`ENGINE_GROUPS`): ``"A"`` for 4-stroke in-line engines and 4-stroke
    vee engines firing at 45° or 60° intervals, ``"B"`` for 2-stroke engines and other 4-stroke
    vee engines.

    Parameters
    ----------
    cycle : int
        2 or 4 (strokes per cycle).
    vee : bool
        A vee engine.
    firing_interval : float or None
        The vee engine's firing interval (deg).

    Returns
    -------
    str
        ``"A"`` or ``"B"``.

    Raises
    ------
    InputError
        Naming ``cycle`` when neither 2 nor 4.

    Examples
    --------
    >>> engine_group(4), engine_group(4, vee=True, firing_interval=60), engine_group(2)
    ('A', 'A', 'B')
    """
    if cycle not in (2, 4):
        raise InputError("expected 2 or 4 strokes", key="cycle", value=cycle)
    if cycle == 2:
        return "B"
    if not vee:
        return "A"
    if firing_interval is not None and any(
        math.isclose(firing_interval, x, abs_tol=1e-9) for x in (45.0, 60.0)
    ):
        return "A"
    return "B"


def material_factors(
    rules: RuleSet,
    tensile_strength: ArrayLike,
    yield_strength: ArrayLike,
    material: str = "carbon",
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """KR's material factors on the crankshaft and generator-shaft limits (KR 2025 Pt 5 Ch 4
    201.4, 203.3): for T_s above 440 N/mm^2, f_m = 1 + 2/3 (T_s/440 - 1) on the continuous
    (and overspeed) limits; for Y above 225 N/mm^2, f_m = Y/225 on the transient limit; 1
    otherwise ("may be increased"). Above 590 N/mm^2 (carbon steel forgings) or 835 N/mm^2
    (low alloy) the Society decides the T_s to use: NaN.

    Parameters
    ----------
    rules : RuleSet
    tensile_strength, yield_strength : float or array_like
        Specified minimum tensile and yield strengths (Pa).
    material : str
        ``"carbon"`` or ``"alloy"``.

    Returns
    -------
    f_continuous, f_transient : numpy.ndarray
        Dimensionless, broadcast.

    Raises
    ------
    InputError
        Naming ``rules`` where the rule set has no crankshaft rule with a material factor.

    Examples
    --------
    >>> from crankdyn.tvc.rulesets import get

    T_s = 550, Y = 300 N/mm^2: 1 + 2/3 x (1.25 - 1) = 1.16667, 300/225 = 1.33333:

    >>> fc, ft = material_factors(get("kr"), 550e6, 300e6)
    >>> round(float(fc), 5), round(float(ft), 5)
    (1.16667, 1.33333)
    """
    _crank_rule(rules)
    if material not in ("carbon", "alloy"):
        raise InputError("expected carbon or alloy", key="material", value=material)
    ts = np.asarray(tensile_strength, dtype=float) / _MPA
    y = np.asarray(yield_strength, dtype=float) / _MPA
    limit = 590.0 if material == "carbon" else 835.0
    fc = np.where(ts > 440.0, 1.0 + 2.0 / 3.0 * (ts / 440.0 - 1.0), 1.0)
    fc = np.where(ts > limit, np.nan, fc)
    ft = np.where(y > 225.0, y / 225.0, 1.0)
    fc_b, ft_b = np.broadcast_arrays(fc, ft)
    return np.array(fc_b, dtype=float), np.array(ft_b, dtype=float)


def _crank_rule(rules: RuleSet) -> CrankshaftRule:
    cited = rules.crankshaft
    if cited is None or cited.value is None:
        where = cited.clause.cite() if cited is not None else rules.title
        raise InputError(
            f"{rules.title} states no crankshaft limit in the text read ({where}): give the "
            "engine builder's limit ([tvc.crankshaft])",
            key="rules",
            value=rules.key,
        )
    return cited.value


def crankshaft_limits(
    rules: RuleSet,
    speed_ratio: ArrayLike,
    group: str,
    tensile_strength: ArrayLike | None = None,
    yield_strength: ArrayLike | None = None,
    material: str = "carbon",
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """The society's crankshaft limits of a main engine (:class:`CrankshaftRule`; KR 2025 Pt 5
    Ch 4 201): tau_1 = 45 - 24 lambda^2 (group A) or 45 - 29 lambda^2 (group B) N/mm^2 for
    0 <= lambda <= 1; tau_2 = 2 tau_1 for lambda <= 0.8; tau_3 = 21 (A) or 16 (B)
    + 237 (lambda - 0.8) sqrt(lambda - 1) N/mm^2 for 1 <= lambda <= 1.15; each times the
    material factor (:func:`material_factors`) where the strengths are given.

    Parameters
    ----------
    rules : RuleSet
    speed_ratio : array_like
        lambda = n / n_0 (dimensionless).
    group : str
        ``"A"`` or ``"B"`` (:func:`engine_group`).
    tensile_strength, yield_strength : float or array_like or None
        Specified minimum strengths (Pa) for the material factor; None: factor 1.
    material : str
        ``"carbon"`` or ``"alloy"``.

    Returns
    -------
    tau_1, tau_2, tau_3 : numpy.ndarray
        Continuous, transient and above-rated limits (Pa), NaN outside their ranges.

    Raises
    ------
    InputError
        Naming ``rules`` where the rule set states no crankshaft limit (IACS UR M68.1: the
        crankshaft is M53's), ``group`` when unknown.

    Examples
    --------
    >>> from crankdyn.tvc.rulesets import get

    Group A at lambda = 0.5: 45 - 24 x 0.25 = 39 N/mm^2, tau_2 = 78:

    >>> t1, t2, t3 = crankshaft_limits(get("kr"), [0.5, 1.1], "A")
    >>> (t1 / 1e6).round(4).tolist(), (t2 / 1e6).round(4).tolist(), (t3 / 1e6).round(4).tolist()
    ([39.0, nan], [78.0, nan], [nan, 43.4838])
    """
    rule = _crank_rule(rules)
    if group not in rule.a:
        raise InputError(f"expected one of {', '.join(rule.a)}", key="group", value=group)
    lam = np.asarray(speed_ratio, dtype=float)
    tau1 = rule.a[group] - rule.b[group] * lam**2
    tau1 = np.where((lam >= 0.0) & (lam <= 1.0), tau1, np.nan)
    tau2 = np.where(lam <= rule.transient_upper, rule.k * tau1, np.nan)
    with np.errstate(invalid="ignore"):
        tau3 = rule.c[group] + rule.e * (lam - 0.8) * np.sqrt(lam - 1.0)
    tau3 = np.where((lam >= 1.0) & (lam <= rule.overspeed_upper), tau3, np.nan)
    if tensile_strength is not None or yield_strength is not None:
        ts = 0.0 if tensile_strength is None else tensile_strength
        y = 0.0 if yield_strength is None else yield_strength
        fc, ft = material_factors(rules, ts, y, material)
        tau1, tau2, tau3 = tau1 * fc, tau2 * ft, tau3 * fc
    return tau1, tau2, tau3


def genset_limits(
    rules: RuleSet,
    speed_ratio: ArrayLike,
    component: str,
    group: str | None = None,
    tensile_strength: ArrayLike | None = None,
    yield_strength: ArrayLike | None = None,
    material: str = "carbon",
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The society's generating-set limits (:class:`GensetRule`; KR 2025 Pt 5 Ch 4 203): from
    0.9 to 1.1 n_0 the crankshaft 21 (group A) or 16 (group B) N/mm^2 and the generator shaft
    31 N/mm^2; at and below 0.9 n_0, while passing, 90 and 118 N/mm^2; each times the material
    factor (203.3, :func:`material_factors`) where the strengths are given.

    Parameters
    ----------
    rules : RuleSet
    speed_ratio : array_like
        lambda = n / n_0 (dimensionless; n_0 the full-load speed).
    component : str
        ``"crankshaft"`` or ``"generator"``.
    group : str or None
        ``"A"`` or ``"B"`` for the crankshaft (:func:`engine_group`).
    tensile_strength, yield_strength : float or array_like or None
        Specified minimum strengths (Pa) for the material factor; None: factor 1.
    material : str
        ``"carbon"`` or ``"alloy"``.

    Returns
    -------
    continuous, transient : numpy.ndarray
        Limits (Pa), NaN outside their speed ranges.

    Raises
    ------
    InputError
        Naming ``rules`` where the rule set states no generating-set limit (IACS UR M68.1:
        generator rotor shafts are not covered), ``component`` or ``group`` when unknown.

    Examples
    --------
    >>> from crankdyn.tvc.rulesets import get

    >>> c, t = genset_limits(get("kr"), [0.5, 1.0], "generator")
    >>> (c / 1e6).tolist(), (t / 1e6).tolist()
    ([nan, 31.0], [118.0, nan])
    """
    cited = rules.genset
    rule = cited.value if cited is not None else None
    if rule is None:
        where = cited.clause.cite() if cited is not None else rules.title
        raise InputError(
            f"{rules.title} states no generating-set limit in the text read ({where}): give "
            "the makers' limits ([mass.limits], [tvc.crankshaft])",
            key="rules",
            value=rules.key,
        )
    if component == "crankshaft":
        if group is None or group not in rule.crankshaft:
            raise InputError(
                f"expected one of {', '.join(rule.crankshaft)}", key="group", value=group
            )
        steady, passing = rule.crankshaft[group], rule.crankshaft_transient
    elif component == "generator":
        steady, passing = rule.generator, rule.generator_transient
    else:
        raise InputError("expected crankshaft or generator", key="component", value=component)
    lam = np.asarray(speed_ratio, dtype=float)
    low, high = rule.window
    cont = np.where((lam >= low) & (lam <= high), steady, np.nan)
    trans = np.where(lam <= low, passing, np.nan)
    if tensile_strength is not None or yield_strength is not None:
        ts = 0.0 if tensile_strength is None else tensile_strength
        y = 0.0 if yield_strength is None else yield_strength
        fc, ft = material_factors(rules, ts, y, material)
        cont, trans = cont * fc, trans * ft
    return cont, trans
