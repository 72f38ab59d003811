"""Limits of the torsional vibration calculation (TVC): IACS UR M68 complete, the widening of
barred speed ranges, and the makers' limits of crankshafts (numeric core and domain).

IACS UR M68 ("Dimensions of propulsion shafts and their permissible torsional vibration
stresses"; the text of Corr.2 Nov 2012 / Aug 2014, whose formulas Rev.3 of Feb 2021 keeps; check
the revision your society applies). With lambda = n / n_0, sigma_B the specified minimum tensile
strength (N/mm^2), C_K the design-feature factor and C_D = 0.35 + 0.93 d^-0.2 (d in mm):

- continuous operation (M68.4):
  tau_C = (sigma_B + 160)/18 C_K C_D (3 - 2 lambda^2) for lambda < 0.9, and
  tau_C = (sigma_B + 160)/18 C_K C_D 1.38 for 0.9 <= lambda <= 1.05;
- transient running through a barred speed range: tau_T = 1.7 tau_C / sqrt(C_K), lambda <= 0.8;
- barred speed ranges (stress above tau_C) are permitted only below lambda = 0.8 and only while
  the stress stays below tau_T (M68.4); none between 0.8 and 1.05;
- C_K (the UR's table, :data:`DESIGN_FACTORS`): intermediate shafts with integral coupling flange
  and straight sections 1.0, shrink-fit coupling 1.0, keyway in a tapered connection 0.60, keyway
  in a cylindrical connection 0.45, radial hole 0.50, longitudinal slot 0.30; thrust shafts
  external to engines on both sides of the thrust collar 0.85, in way of a roller thrust bearing
  0.85; propeller shafts with flange-mounted, keyless taper-fitted or key-fitted propellers 0.55,
  between the forward end of the aftmost bearing and the forward stern-tube seal 0.80;
- the cap on sigma_B: the tensile strength used in the formulas may not exceed the material's
  limit, higher actual strengths giving no higher permissible stress (:data:`STRENGTH_CAPS`):
  800 N/mm^2 for alloy steel, 760 N/mm^2 for carbon and carbon-manganese steel intermediate and
  thrust shafts (the general limits of the shafting forgings, e.g. Lloyd's Register Rules for
  Ships Pt 5 Ch 6 2.1.1 and 2.1.4, which implement M68), 600 N/mm^2 for propeller shafts
  (M68's limit for shafts in way of the stern tube). Give ``tensile_strength_cap`` where your
  society's rule states another value.

The least barred range around a critical speed n_c (:data:`WIDENINGS`, chosen by the rule set,
:mod:`crankdyn.tvc.rulesets`): KR 2025 Pt 5 Ch 4 206.1(1) (and, as crankdyn had it, Lloyd's
Register's Pt 5 Ch 8, not read) bars at least

    16 n_c / (18 - lambda_c) <= n <= (18 - lambda_c) n_c / 16,    lambda_c = n_c / n_0;

IACS M68 as crankdyn reads it adds no margin. The tachometer tolerance (the accuracy of the
speed indication) widens every declared range on both sides.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.crank.geometry import check_positive
from crankdyn.errors import InputError
from crankdyn.torsion.rules import (
    STRENGTH_CAPS,
    capped_strength,
    permissible_continuous,
    permissible_transient,
    size_factor,
)

__all__ = [
    "DESIGN_FACTORS",
    "M68",
    "STRENGTH_CAPS",
    "WIDENINGS",
    "CrankshaftLimit",
    "M68Shaft",
    "barred_limits",
    "capped_strength",
    "continuous_limit",
    "transient_limit",
]

M68 = "IACS UR M68 (Corr.2 Nov 2012, Aug 2014 text; formulas kept in Rev.3 Feb 2021), M68.4"
"""The rule text cited in every M68 verdict."""

_MPA = 1e6

DESIGN_FACTORS = {
    "integral flange": 1.0,
    "shrink fit": 1.0,
    "keyway tapered": 0.60,
    "keyway cylindrical": 0.45,
    "radial hole": 0.50,
    "longitudinal slot": 0.30,
    "thrust collar": 0.85,
    "roller thrust bearing": 0.85,
    "propeller flange": 0.55,
    "propeller keyless": 0.55,
    "propeller key": 0.55,
    "stern tube": 0.80,
}
"""C_K of IACS UR M68's table by design feature (module docstring)."""

WIDENINGS = ("none", "lr")
"""The least barred ranges a rule set may state (:attr:`crankdyn.tvc.rulesets.RuleSet.widening`):
``"none"`` (the range where the stress exceeds tau_C) or ``"lr"`` (at least
16 n_c/(18 - lambda_c) to (18 - lambda_c) n_c/16: KR 2025 Pt 5 Ch 4 206.1(1), and Lloyd's
Register's margin as crankdyn had it)."""


def continuous_limit(
    speed_ratio: ArrayLike, tensile_strength: float, design_factor: float, diameter: float
) -> NDArray[np.float64]:
    """tau_C, the permissible vibratory shear stress for continuous operation (IACS UR M68.4).

    tau_C = (sigma_B + 160)/18 C_K C_D (3 - 2 lambda^2) for lambda < 0.9 and
    (sigma_B + 160)/18 C_K C_D 1.38 for 0.9 <= lambda <= 1.05, sigma_B in N/mm^2, with the size
    factor C_D = 0.35 + 0.93 d^-0.2 (d in mm) (IACS UR M68.4; module docstring;
    :func:`crankdyn.torsion.rules.permissible_continuous`).

    Parameters
    ----------
    speed_ratio : array_like
        lambda = n / n_0 (dimensionless), any shape.
    tensile_strength : float
        sigma_B the formula uses (Pa): the specified minimum tensile strength, capped
        (:func:`capped_strength`).
    design_factor : float
        C_K (dimensionless, :data:`DESIGN_FACTORS`).
    diameter : float
        Outer diameter d of the shaft (m), for C_D.

    Returns
    -------
    numpy.ndarray
        tau_C (Pa, half-range amplitude), the shape of ``speed_ratio``; NaN above lambda = 1.05,
        where the UR sets no limit.

    Examples
    --------
    A 300 mm intermediate shaft, sigma_B = 600 N/mm^2, C_K = 1 (MPa):

    >>> tau = continuous_limit([0.5, 0.95, 1.1], 600e6, 1.0, 0.3)
    >>> [f"{t / 1e6:.6g}" for t in tau]
    ['68.3163', '37.7106', 'nan']
    """
    return permissible_continuous(speed_ratio, tensile_strength, design_factor, diameter)


def transient_limit(
    speed_ratio: ArrayLike, tensile_strength: float, design_factor: float, diameter: float
) -> NDArray[np.float64]:
    """tau_T, the permissible vibratory shear stress while passing a barred speed range (IACS UR
    M68.4).

    tau_T = 1.7 tau_C / sqrt(C_K) for lambda <= 0.8 (IACS UR M68.4; module docstring;
    :func:`crankdyn.torsion.rules.permissible_transient`); no barred range, hence no transient
    limit, above lambda = 0.8.

    Parameters
    ----------
    speed_ratio : array_like
        lambda = n / n_0 (dimensionless), any shape.
    tensile_strength : float
        sigma_B the formula uses (Pa), capped (:func:`capped_strength`).
    design_factor : float
        C_K (dimensionless, :data:`DESIGN_FACTORS`).
    diameter : float
        Outer diameter d of the shaft (m), for C_D.

    Returns
    -------
    numpy.ndarray
        tau_T (Pa, half-range amplitude), the shape of ``speed_ratio``; NaN above lambda = 0.8.

    Examples
    --------
    A keyway in a tapered connection (C_K = 0.60), 300 mm, sigma_B = 600 N/mm^2 (MPa):

    >>> tau = transient_limit([0.5, 0.85], 600e6, 0.60, 0.3)
    >>> [f"{t / 1e6:.6g}" for t in tau]
    ['89.9598', 'nan']
    """
    tau_c = permissible_continuous(speed_ratio, tensile_strength, design_factor, diameter)
    return permissible_transient(speed_ratio, tau_c, design_factor)


@overload
def barred_limits(
    critical_speed: float, rated_speed: float, widening: str = "lr"
) -> tuple[float, float]: ...


@overload
def barred_limits(
    critical_speed: NDArray[np.float64], rated_speed: float, widening: str = "lr"
) -> tuple[NDArray[np.float64], NDArray[np.float64]]: ...


def barred_limits(
    critical_speed: float | NDArray[np.float64], rated_speed: float, widening: str = "lr"
) -> tuple[Any, Any]:
    """The least barred speed range a society's rule sets around a critical speed.

    ``"lr"`` (Lloyd's Register Rules for Ships Pt 5 Ch 8 2.5; module docstring; the same formula
    as KR Rules for Classification of Steel Ships 2025 Pt 5 Ch 4 206.1(1)):
    16 n_c / (18 - lambda_c) <= n <= (18 - lambda_c) n_c / 16 with lambda_c = n_c / n_0;
    ``"none"`` (IACS UR M68.4, no added margin): the critical speed alone.

    Parameters
    ----------
    critical_speed : float or numpy.ndarray
        The critical speed n_c (rad/s); an array gives arrays.
    rated_speed : float
        The rated speed n_0 (rad/s).
    widening : str
        One of :data:`WIDENINGS` (default ``"lr"``).

    Returns
    -------
    low, high : float or numpy.ndarray
        The least range (rad/s) to bar, floats for a float ``critical_speed``.

    Examples
    --------
    A critical speed at 300 rpm, rated speed 500 rpm (rpm):

    >>> from crankdyn.constants import RPM
    >>> low, high = barred_limits(300 / RPM, 500 / RPM)
    >>> f"{low * RPM:.6g}", f"{high * RPM:.6g}"
    ('275.862', '326.25')
    >>> barred_limits(31.4, 52.4, "none")
    (31.4, 31.4)
    >>> low, high = barred_limits(np.array([300.0, 400.0]) / RPM, 500 / RPM)
    >>> (low * RPM).round(3).tolist()
    [275.862, 372.093]
    """
    w = np.asarray(critical_speed, dtype=float)
    if widening == "none":
        low, high = w.copy(), w.copy()
    else:
        lam = w / float(rated_speed)
        low, high = 16.0 * w / (18.0 - lam), (18.0 - lam) * w / 16.0
    if w.ndim == 0:
        return float(low), float(high)
    return low, high


@dataclass(frozen=True)
class M68Shaft:
    """One propulsion shaft's IACS UR M68 data, resolved (SI units).

    Parameters
    ----------
    between : tuple of str
        The names of the two masses the shaft connects.
    tensile_strength : float
        The specified minimum tensile strength sigma_B of the material (Pa).
    design_factor : float
        C_K of the shaft's design feature (dimensionless, :data:`DESIGN_FACTORS`).
    diameter : float
        Outer diameter d (m), for the size factor C_D.
    strength_used : float
        sigma_B the M68 formulas use (Pa): ``tensile_strength`` capped
        (:func:`capped_strength`, :data:`STRENGTH_CAPS`).
    feature : str or None
        The design feature's name (a key of :data:`DESIGN_FACTORS`), None where C_K was given.

    Examples
    --------
    >>> shaft = M68Shaft(("gearbox", "propeller"), 800e6, 1.0, 0.3, 760e6)
    >>> round(shaft.size_factor, 6)
    0.647207
    >>> f"{shaft.tau_c([0.5])[0] / 1e6:.6g} MPa"
    '82.6986 MPa'
    """

    between: tuple[str, str]
    tensile_strength: float
    design_factor: float
    diameter: float
    strength_used: float
    feature: str | None = None

    def tau_c(self, speed_ratio: ArrayLike) -> NDArray[np.float64]:
        """tau_C of this shaft for continuous operation (IACS UR M68.4, :func:`continuous_limit`).

        Parameters
        ----------
        speed_ratio : array_like
            lambda = n / n_0 (dimensionless), any shape.

        Returns
        -------
        numpy.ndarray
            tau_C (Pa), the shape of ``speed_ratio``; NaN above lambda = 1.05.
        """
        return continuous_limit(speed_ratio, self.strength_used, self.design_factor, self.diameter)

    def tau_t(self, speed_ratio: ArrayLike) -> NDArray[np.float64]:
        """tau_T of this shaft while passing a barred range (IACS UR M68.4,
        :func:`transient_limit`).

        Parameters
        ----------
        speed_ratio : array_like
            lambda = n / n_0 (dimensionless), any shape.

        Returns
        -------
        numpy.ndarray
            tau_T (Pa), the shape of ``speed_ratio``; NaN above lambda = 0.8.
        """
        return transient_limit(speed_ratio, self.strength_used, self.design_factor, self.diameter)

    @property
    def size_factor(self) -> float:
        """C_D = 0.35 + 0.93 d^-0.2, d in mm (IACS UR M68.4; dimensionless)."""
        return float(size_factor(self.diameter))


@dataclass(frozen=True)
class CrankshaftLimit:
    """The engine builder's permissible additional vibratory load of the crankshaft, checked at
    every crank span (shafts of role ``"crankshaft"``).

    IACS UR M68 does not cover crankshafts (their dimensions are IACS UR M53's); the engine
    builder states the permissible additional vibratory stress or torque, which the TVC checks
    the synthesised response of every span against (docs/tvc.md).

    Parameters
    ----------
    stress : float or None
        Permissible vibratory shear stress amplitude (Pa), or None.
    torque : float or None
        Permissible vibratory torque amplitude (N m), or None (one of the two is required).
    diameter : float or None
        Journal (or pin) diameter for the nominal stress tau = K T / W_p, W_p = pi d^3/16 (m);
        None: the span's own diameters.
    stress_concentration : float
        K, the stated stress concentration factor on the nominal stress (dimensionless, >= 1,
        default 1).
    transient_stress, transient_torque : float or None
        Permissible values while passing a barred range (Pa, N m; None: no barred range is
        permitted for the crankshaft).
    source : str or None
        The engine builder's document.

    Raises
    ------
    InputError
        Naming the key ``permissible_stress`` when neither or both of ``stress`` and ``torque``
        are given; naming the key and its value when a value is not positive or the stress
        concentration factor is below 1.

    Examples
    --------
    >>> limit = CrankshaftLimit(stress=30e6, diameter=0.2, source="maker's TVC data sheet")
    >>> limit.by_stress, f"{limit.modulus(1e-3):.6g}"
    (True, '0.0015708')
    >>> CrankshaftLimit(torque=1e4, stress_concentration=0.5)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    crankdyn.errors.InputError: stress_concentration = 0.5: a stress concentration ... at least 1
    """

    stress: float | None = None
    torque: float | None = None
    diameter: float | None = None
    stress_concentration: float = 1.0
    transient_stress: float | None = None
    transient_torque: float | None = None
    source: str | None = None

    def __post_init__(self) -> None:
        if (self.stress is None) == (self.torque is None):
            raise InputError(
                "give the permissible vibratory stress or torque of the crankshaft (one of them)",
                key="permissible_stress",
            )
        for key in ("stress", "torque", "diameter", "transient_stress", "transient_torque"):
            value = getattr(self, key)
            if value is not None:
                object.__setattr__(self, key, check_positive(key, value, "the value"))
        k = check_positive("stress_concentration", self.stress_concentration, "the factor")
        if k < 1.0:
            raise InputError(
                "a stress concentration factor is at least 1", key="stress_concentration", value=k
            )
        object.__setattr__(self, "stress_concentration", k)

    @property
    def by_stress(self) -> bool:
        """Whether the limit is a stress (Pa) rather than a torque (N m)."""
        return self.stress is not None

    def modulus(self, shaft_modulus: float) -> float:
        """The polar section modulus W_p of the nominal stress tau = T / W_p.

        Parameters
        ----------
        shaft_modulus : float
            The crank span's own W_p (m^3), used where no ``diameter`` is given.

        Returns
        -------
        float
            W_p = pi d^3 / 16 of ``diameter`` (m^3; the torsion of a solid circular shaft), else
            ``shaft_modulus``.
        """
        if self.diameter is not None:
            return math.pi * self.diameter**3 / 16.0
        return shaft_modulus
