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
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from crankdyn.constants import RPM
from crankdyn.crank.geometry import check_finite, check_positive
from crankdyn.errors import InputError
from crankdyn.results import Result, array, freeze, scalar

__all__ = [
    "RULE",
    "BarredRange",
    "RuleCheck",
    "RuleSet",
    "ShaftLimit",
    "check_rules",
    "permissible_continuous",
    "permissible_transient",
    "size_factor",
]

RULE = "IACS UR M68 (Aug 2014 text), M68.4"

_MPA = 1e6


def size_factor(diameter) -> np.ndarray:
    """C_D = 0.35 + 0.93 d^-0.2 with d in mm (``diameter`` in m)."""
    d_mm = np.asarray(diameter, dtype=float) * 1e3
    return 0.35 + 0.93 * d_mm**-0.2


def permissible_continuous(speed_ratio, tensile_strength, design_factor, diameter) -> np.ndarray:
    """tau_C (Pa) for continuous operation at speed ratios lambda = n/n_0 (module docstring);
    NaN above lambda = 1.05 (no limit given by the UR).

    Parameters
    ----------
    speed_ratio
        lambda (dimensionless), array.
    tensile_strength
        sigma_B (Pa).
    design_factor
        C_K (dimensionless).
    diameter
        Outer diameter d (m), for C_D.
    """
    lam = np.asarray(speed_ratio, dtype=float)
    base = (tensile_strength / _MPA + 160.0) / 18.0 * design_factor * size_factor(diameter)
    factor = np.where(lam < 0.9, 3.0 - 2.0 * lam**2, 1.38)
    return np.where(lam <= 1.05, base * factor * _MPA, np.nan)


def permissible_transient(speed_ratio, tau_c, design_factor) -> np.ndarray:
    """tau_T = 1.7 tau_C / sqrt(C_K) (Pa) for lambda <= 0.8, NaN above."""
    lam = np.asarray(speed_ratio, dtype=float)
    return np.where(lam <= 0.8, 1.7 * np.asarray(tau_c) / math.sqrt(design_factor), np.nan)


@dataclass(frozen=True)
class ShaftLimit:
    """Material and design factor of one shaft for the rule check.

    Parameters
    ----------
    between
        The shaft's two masses (its outer diameter comes from the shaft's geometry).
    tensile_strength
        Specified minimum tensile strength sigma_B (Pa), > 0.
    design_factor
        C_K (dimensionless), 0 < C_K <= 1.
    """

    between: tuple[str, str]
    tensile_strength: float
    design_factor: float = 1.0

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


@dataclass(frozen=True)
class RuleSet:
    """The rule check's inputs: rated speed n_0 (rad/s; None: the engine's operating speed)
    and the checked shafts."""

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
    """A speed range where the synthesised stress of a shaft exceeds tau_C."""

    shaft: tuple[str, str] = scalar("shaft", "Shaft", "")
    start: float = scalar("start_rpm", "From", "rpm", RPM)
    end: float = scalar("end_rpm", "To", "rpm", RPM)
    max_stress: float = scalar("max_stress_Pa", "Largest stress", "Pa")
    max_ratio: float = scalar("max_stress_to_tau_c", "Largest stress / τ_C", "", fmt=".4g")
    permitted: bool = scalar("permitted", "Permitted as a barred range", "")
    reason: str = scalar("reason", "Why", "")


@dataclass(frozen=True)
class RuleCheck(Result):
    """Synthesised shaft stresses against the IACS UR M68 limits (module docstring)."""

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


def check_rules(result, rules: RuleSet, model=None, rated_speed: float | None = None) -> RuleCheck:
    """Check the synthesised stresses of a :class:`~crankdyn.torsion.response.ResponseResult`
    against M68 (module docstring); ``rated_speed`` (rad/s) serves when the rule set has none."""
    n0 = rules.rated_speed if rules.rated_speed is not None else rated_speed
    if n0 is None:
        raise InputError(
            "the rule check needs the rated speed n_0: give [rules] rated_speed (or the "
            "engine's [operating] speed)",
            key="rated_speed",
        )
    speeds = np.asarray(result.speed)
    lam = speeds / n0
    columns, limits_c, limits_t, labels = [], [], [], []
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
        diameter = model.shafts[s].geometry.outer_diameter if model is not None else None
        tau_c = permissible_continuous(lam, limit.tensile_strength, limit.design_factor, diameter)
        columns.append(result.synthesized_shaft_stress[:, s])
        limits_c.append(tau_c)
        limits_t.append(permissible_transient(lam, tau_c, limit.design_factor))
        labels.append(result.shafts[s])
    stress = np.column_stack(columns)
    tau_c = np.column_stack(limits_c)
    tau_t = np.column_stack(limits_t)
    with np.errstate(invalid="ignore"):
        exceeds = stress > tau_c
    barred = []
    for j, label in enumerate(labels):
        runs = _runs(exceeds[:, j])
        for a, b in runs:
            seg = slice(a, b + 1)
            ratio = float(np.max(stress[seg, j] / tau_c[seg, j]))
            above = bool(np.any(lam[seg] > 0.8))
            with np.errstate(invalid="ignore"):
                over_t = bool(np.any(~(stress[seg, j] <= tau_t[seg, j])))
            reason = (
                "reaches above 0.8 n_0, where no barred range is permitted"
                if above
                else "exceeds τ_T for transient operation"
                if over_t
                else "τ_C exceeded below 0.8 n_0 and τ_T kept: pass through quickly"
            )
            barred.append(
                BarredRange(
                    shaft=label,
                    start=float(speeds[a]),
                    end=float(speeds[b]),
                    max_stress=float(np.max(stress[seg, j])),
                    max_ratio=ratio,
                    permitted=not (above or over_t),
                    reason=reason,
                )
            )
    notes = []
    if np.any(lam > 1.05):
        notes.append("speeds above 1.05 n_0 are not checked (the rule gives no limit there)")
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


def _runs(mask) -> list[tuple[int, int]]:
    """(first, last) indices of the runs of True in a 1-D mask."""
    m = np.concatenate([[False], np.asarray(mask, dtype=bool), [False]])
    edges = np.flatnonzero(np.diff(m.astype(int)))
    return [(int(a), int(b) - 1) for a, b in zip(edges[::2], edges[1::2], strict=True)]
