"""Masses of the crank train of one cylinder (domain object).

The equivalent-mass models (seed 000 section 2.1) turn these into the reciprocating mass m_j and
the rotating mass m_r used by the force and torque analyses.
"""

from __future__ import annotations

from dataclasses import dataclass

from crankdyn.errors import InputError
from crankdyn.geometry import check_finite, check_positive

__all__ = ["Masses", "equivalent_masses", "rod_two_mass"]


def _nonnegative(name: str, value: float | None) -> float | None:
    if value is None:
        return None
    number = check_finite(name, value)
    if number < 0.0:
        raise InputError("a mass must not be negative", key=name, value=value)
    return number


@dataclass(frozen=True)
class Masses:
    """Masses of one cylinder's crank train.

    Either the components are given (piston group, rod with its centre of gravity and optionally
    its moment of inertia, crank unbalance), or the equivalent masses directly (``reciprocating``
    and ``rotating``), as engine builders often quote them; a given equivalent mass takes
    precedence over the one derived from the components.

    Parameters
    ----------
    piston_group
        Piston with rings, pin and circlips m_p (kg).
    rod
        Connecting-rod group m_c (kg).
    rod_cg_from_big_end
        Distance l_B of the rod's centre of gravity from the big-end (crank-pin) centre (m);
        0 < l_B < L.
    rod_inertia
        Rod moment of inertia about its centre of gravity I_c (kg m^2); enables the 3-mass model.
    crank_unbalance
        Unbalanced mass of the crank throw referred to the crank radius m_k (kg) (seed 000:
        m_k = m_z + 2 m_w rho / R).
    reciprocating, rotating
        Equivalent reciprocating mass m_j and rotating mass m_r per cylinder (kg), if known.
    """

    piston_group: float | None = None
    rod: float | None = None
    rod_cg_from_big_end: float | None = None
    rod_inertia: float | None = None
    crank_unbalance: float = 0.0
    reciprocating: float | None = None
    rotating: float | None = None

    def __post_init__(self) -> None:
        for name in ("piston_group", "rod", "crank_unbalance", "reciprocating", "rotating"):
            object.__setattr__(self, name, _nonnegative(name, getattr(self, name)))
        if self.rod_cg_from_big_end is not None:
            object.__setattr__(
                self,
                "rod_cg_from_big_end",
                check_positive("rod_cg_from_big_end", self.rod_cg_from_big_end, "the distance"),
            )
        if self.rod_inertia is not None:
            object.__setattr__(
                self,
                "rod_inertia",
                check_positive("rod_inertia", self.rod_inertia, "the moment of inertia"),
            )
        has_components = self.piston_group is not None and self.rod is not None
        if not has_components and (self.reciprocating is None or self.rotating is None):
            missing = "piston_group" if self.piston_group is None else "rod"
            raise InputError(
                "give the components (piston_group, rod, rod_cg_from_big_end) or the equivalent "
                "masses (reciprocating, rotating)",
                key=missing,
            )
        splits_rod = self.reciprocating is None or self.rotating is None
        if self.rod and self.rod_cg_from_big_end is None and splits_rod:
            raise InputError(
                "the rod's centre of gravity is needed to split its mass",
                key="rod_cg_from_big_end",
            )

    def check_rod(self, rod_length: float) -> None:
        """Check the rod data against the rod length L (m): 0 < l_B < L, and the 3-mass model's
        condition I_c <= m_c l_A l_B (its centre-of-gravity mass must not be negative)."""
        lb = self.rod_cg_from_big_end
        if lb is None:
            return
        if lb >= rod_length:
            raise InputError(
                f"the rod's centre of gravity must lie between the pin centres "
                f"(0 < l_B < L = {rod_length * 1e3:.6g} mm)",
                key="rod_cg_from_big_end",
                value=lb,
            )
        if self.rod_inertia is not None and self.rod:
            la = rod_length - lb
            limit = self.rod * la * lb
            if self.rod_inertia > limit * (1 + 1e-12):
                raise InputError(
                    f"the rod's moment of inertia exceeds m_c l_A l_B = {limit:.6g} kg*m^2: "
                    "the 3-mass rod model would need a negative mass at the centre of gravity",
                    key="rod_inertia",
                    value=self.rod_inertia,
                )


def rod_two_mass(rod_mass: float, rod_length: float, cg_from_big_end: float):
    """Two-mass rod model (seed 000 section 2.1): masses at the small end A and big end B with
    the same total mass and centre of gravity: m_CA = m_C l_B / L, m_CB = m_C l_A / L, where
    l_B is the CG's distance from the big end and l_A = L - l_B from the small end.

    Returns
    -------
    tuple of float
        (m_CA, m_CB) in kg.
    """
    small = rod_mass * cg_from_big_end / rod_length
    return small, rod_mass - small


def equivalent_masses(masses: Masses, rod_length: float) -> tuple[float, float]:
    """Reciprocating mass m_j and rotating mass m_r of one cylinder (kg), seed 000 section 2.1:
    m_j = m_p + m_CA and m_r = m_k + m_CB with the two-mass rod model; a directly given
    ``reciprocating`` or ``rotating`` mass takes precedence."""
    small = big = 0.0
    if masses.rod and masses.rod_cg_from_big_end is not None:
        small, big = rod_two_mass(masses.rod, rod_length, masses.rod_cg_from_big_end)
    m_j = masses.reciprocating
    if m_j is None:
        m_j = (masses.piston_group or 0.0) + small
    m_r = masses.rotating
    if m_r is None:
        m_r = masses.crank_unbalance + big
    return m_j, m_r
