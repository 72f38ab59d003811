"""Masses of the crank train of one cylinder (domain object).

The equivalent-mass models (seed 000 section 2.1) turn these into the reciprocating mass m_j and
the rotating mass m_r used by the force and torque analyses.
"""

from __future__ import annotations

from dataclasses import dataclass

from crankdyn.crank.geometry import check_finite, check_positive
from crankdyn.errors import InputError
from crankdyn.results import Result, scalar

__all__ = [
    "ROD_SPLITS",
    "EquivalentMasses",
    "Masses",
    "crank_unbalance_from_parts",
    "equivalent_mass_model",
    "equivalent_masses",
    "rod_three_mass",
    "rod_two_mass",
]


ROD_SPLITS = ("centre-of-gravity", "thirds")
"""How the rod's mass is split between its ends: by its centre of gravity (the two-mass model,
seed 000 section 2.1), or the rule of thumb m_j = m_piston + m_rod/3 (seed 002 eq. 15: a third at
the small end, two thirds at the big end)."""


def crank_unbalance_from_parts(
    pin: float, web: float, web_radius: float, crank_radius: float
) -> float:
    """The crank's rotating (unbalanced) mass referred to the crank radius from its parts, seed
    000 section 2.1: m_k = m_z + 2 m_w rho / R, the crank pin's mass m_z at the radius R and each
    of the two webs' unbalanced mass m_w at its centre of mass's radius rho (the same centrifugal
    force m w^2 rho as a mass m_w rho / R at the radius R).

    Parameters
    ----------
    pin : float
        The crank pin's mass m_z (kg).
    web : float
        One web's unbalanced mass m_w (kg).
    web_radius : float
        The radius rho of that mass's centre from the crankshaft axis (m).
    crank_radius : float
        R (m).

    Returns
    -------
    float
        m_k (kg).

    Examples
    --------
    >>> round(crank_unbalance_from_parts(0.30, 0.25, 0.030, 0.040), 9)  # 0.30 + 2 x 0.25 x 0.75
    0.675
    """
    return pin + 2.0 * web * web_radius / crank_radius


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
    piston_group : float or None
        Piston with rings, pin and circlips m_p (kg).
    rod : float or None
        Connecting-rod group m_c (kg).
    rod_cg_from_big_end : float or None
        Distance l_B of the rod's centre of gravity from the big-end (crank-pin) centre (m);
        0 < l_B < L.
    rod_inertia : float or None
        Rod moment of inertia about its centre of gravity I_c (kg m^2); enables the 3-mass model.
    crank_unbalance : float
        Unbalanced mass of the crank throw referred to the crank radius m_k (kg) (seed 000:
        m_k = m_z + 2 m_w rho / R); default 0.
    reciprocating, rotating : float or None
        Equivalent reciprocating mass m_j and rotating mass m_r per cylinder (kg), if known.
    rod_split : str
        :data:`ROD_SPLITS`: ``"centre-of-gravity"`` (default; needs ``rod_cg_from_big_end``) or
        ``"thirds"`` (m_rod/3 at the small end, seed 002 eq. 15).

    Raises
    ------
    InputError
        If a mass is negative or not a number, a distance or inertia is not positive, neither
        the components nor the equivalent masses are complete, or the rod must be split without
        its centre of gravity.

    Examples
    --------
    >>> m = Masses(piston_group=0.5, rod=0.6, rod_cg_from_big_end=0.04)
    >>> [round(x, 9) for x in equivalent_masses(m, rod_length=0.16)]  # m_j, m_r (kg)
    [0.65, 0.45]
    """

    piston_group: float | None = None
    rod: float | None = None
    rod_cg_from_big_end: float | None = None
    rod_inertia: float | None = None
    crank_unbalance: float = 0.0
    reciprocating: float | None = None
    rotating: float | None = None
    rod_split: str = "centre-of-gravity"

    def __post_init__(self) -> None:
        for name in ("piston_group", "rod", "crank_unbalance", "reciprocating", "rotating"):
            object.__setattr__(self, name, _nonnegative(name, getattr(self, name)))
        if self.rod_split not in ROD_SPLITS:
            raise InputError(
                f"unknown rod split; choose one of {', '.join(ROD_SPLITS)}",
                key="rod_split",
                value=self.rod_split,
            )
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
        by_cg = self.rod_split == "centre-of-gravity"
        if self.rod and self.rod_cg_from_big_end is None and splits_rod and by_cg:
            raise InputError(
                "the rod's centre of gravity is needed to split its mass",
                key="rod_cg_from_big_end",
            )

    def rod_ends(self, rod_length: float) -> tuple[float, float] | None:
        """The rod's mass at its small and big ends (kg) by :attr:`rod_split`, or None when the
        rod's mass (or, split by the centre of gravity, its centre of gravity) is not given.

        Parameters
        ----------
        rod_length : float
            L (m).

        Returns
        -------
        (float, float) or None
            (m_CA, m_CB).
        """
        if self.rod is None:
            return None
        if self.rod_split == "thirds":
            return self.rod / 3.0, self.rod - self.rod / 3.0
        if self.rod_cg_from_big_end is None:
            return (0.0, 0.0) if self.rod == 0.0 else None
        return rod_two_mass(self.rod, rod_length, self.rod_cg_from_big_end)

    def check_rod(self, rod_length: float) -> None:
        """Check the rod data against the rod length.

        The centre of gravity must lie between the pin centres, 0 < l_B < L, and the 3-mass
        model's condition I_c <= m_c l_A l_B must hold (its centre-of-gravity mass must not be
        negative; seed 000 section 2.1).

        Parameters
        ----------
        rod_length : float
            Rod length L (m).

        Raises
        ------
        InputError
            If either condition fails.
        """
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


def rod_two_mass(rod_mass: float, rod_length: float, cg_from_big_end: float) -> tuple[float, float]:
    """Two-mass rod model (seed 000 section 2.1): masses at the small end A and big end B with
    the same total mass and centre of gravity: m_CA = m_C l_B / L, m_CB = m_C l_A / L, where
    l_B is the CG's distance from the big end and l_A = L - l_B from the small end.

    Parameters
    ----------
    rod_mass : float
        m_C (kg).
    rod_length : float
        L (m).
    cg_from_big_end : float
        l_B (m), 0 < l_B < L.

    Returns
    -------
    m_ca, m_cb : float
        The small-end and big-end masses (kg).

    Examples
    --------
    >>> [round(m, 9) for m in rod_two_mass(0.6, 0.16, 0.04)]
    [0.15, 0.45]
    """
    small = rod_mass * cg_from_big_end / rod_length
    return small, rod_mass - small


def equivalent_masses(masses: Masses, rod_length: float) -> tuple[float, float]:
    """Reciprocating mass m_j and rotating mass m_r of one cylinder, seed 000 section 2.1.

    m_j = m_p + m_CA and m_r = m_k + m_CB with the two-mass rod model (:func:`rod_two_mass`);
    a directly given ``reciprocating`` or ``rotating`` mass takes precedence.

    Parameters
    ----------
    masses : Masses
        The crank-train masses of one cylinder.
    rod_length : float
        Rod length L (m).

    Returns
    -------
    m_j, m_r : float
        Reciprocating and rotating mass (kg).
    """
    small, big = masses.rod_ends(rod_length) or (0.0, 0.0)
    m_j = masses.reciprocating
    if m_j is None:
        m_j = (masses.piston_group or 0.0) + small
    m_r = masses.rotating
    if m_r is None:
        m_r = masses.crank_unbalance + big
    return m_j, m_r


def rod_three_mass(
    rod_mass: float, rod_length: float, cg_from_big_end: float, inertia: float
) -> tuple[float, float, float]:
    """Three-mass rod model (seed 000 section 2.1): masses at the small end A, the big end B and
    the centre of gravity G that keep the rod's mass, centre of gravity *and* moment of inertia::

        m_A + m_B + m_G = m_C,   m_A l_A = m_B l_B,   m_A l_A^2 + m_B l_B^2 = I_C

    whose solution is m_A = I_C / (l_A L), m_B = I_C / (l_B L), m_G = m_C - I_C / (l_A l_B).

    Parameters
    ----------
    rod_mass : float
        m_C (kg).
    rod_length : float
        L (m).
    cg_from_big_end : float
        l_B (m), 0 < l_B < L; l_A = L - l_B.
    inertia : float
        I_C about the centre of gravity (kg m^2), at most m_C l_A l_B (else m_G < 0).

    Returns
    -------
    m_a, m_b, m_g : float
        The small-end, big-end and centre-of-gravity masses (kg).
    """
    lb = float(cg_from_big_end)
    la = float(rod_length) - lb
    small = inertia / (la * rod_length)
    big = inertia / (lb * rod_length)
    return small, big, rod_mass - inertia / (la * lb)


@dataclass(frozen=True)
class EquivalentMasses(Result):
    """Equivalent masses of one cylinder's crank train (seed 000 section 2.1), all in kg.

    The two-mass rod model puts m_CA = m_C l_B / L at the small end and m_CB = m_C l_A / L at the
    big end; then the reciprocating mass is m_j = m_p + m_CA and the rotating mass is
    m_r = m_k + m_CB. On a throw that carries n rods (V engines) the crank's unbalance m_k is
    shared: each cylinder's rotating mass is m_k / n + m_CB, so a throw's rotating mass is the sum
    over its cylinders (m_k + n m_CB). The two-mass model has the rod moment of inertia
    m_C l_A l_B instead of I_C; the rod's inertia couple is then too large by
    dM_C = (m_CA l_A^2 + m_CB l_B^2 - I_C) eps_L = (m_C l_A l_B - I_C) eps_L (seed 000), which the
    three-mass model (:func:`rod_three_mass`) removes.
    """

    title = "Equivalent masses"
    reciprocating: float = scalar(
        "reciprocating_kg", "Reciprocating mass m_j", "kg", name="reciprocating_mass"
    )
    rotating: float = scalar(
        "rotating_kg", "Rotating mass m_r (per cylinder)", "kg", name="rotating_mass_per_cylinder"
    )
    rod_small_end: float | None = scalar(
        "rod_small_end_kg", "Rod small-end mass m_CA", "kg", name="rod_small_end_mass"
    )
    rod_big_end: float | None = scalar(
        "rod_big_end_kg", "Rod big-end mass m_CB", "kg", name="rod_big_end_mass"
    )
    crank: float | None = scalar(
        "crank_kg", "Crank unbalance m_k (per throw)", "kg", name="crank_unbalance_mass"
    )
    inertia_error: float | None = scalar(
        "rod_inertia_error_kg_m2",
        "Two-mass rod inertia error m_C l_A l_B - I_C",
        "kg·m²",
        name="rod_inertia_error",
    )
    three_mass_small_end: float | None = scalar(
        "three_mass_small_end_kg", "3-mass model: small end m_A", "kg"
    )
    three_mass_big_end: float | None = scalar(
        "three_mass_big_end_kg", "3-mass model: big end m_B", "kg"
    )
    three_mass_centre: float | None = scalar(
        "three_mass_centre_kg", "3-mass model: centre of gravity m_G", "kg"
    )
    source: str = scalar("source", "Masses from", "")

    @property
    def pin_mass_known(self) -> bool:
        """Whether the rod's big-end mass m_CB (which loads the crank pin) is known."""
        return self.rod_big_end is not None


def equivalent_mass_model(
    masses: Masses, rod_length: float, rods_per_throw: int = 1
) -> EquivalentMasses:
    """Equivalent masses of one cylinder from its :class:`Masses` (seed 000 section 2.1).

    Parameters
    ----------
    masses : Masses
        The crank-train masses of one cylinder.
    rod_length : float
        L (m).
    rods_per_throw : int
        Number of rods on the cylinder's throw (2 on a V engine's shared pin); the crank
        unbalance is shared between them. Default 1.

    Returns
    -------
    EquivalentMasses
        A directly given ``reciprocating`` or ``rotating`` mass takes precedence over the one
        derived from the components; the rod split and the three-mass model are reported when
        the rod's mass and centre of gravity (and its moment of inertia) are known; all in kg
        (the inertia error in kg m^2).

    Raises
    ------
    InputError
        If the rod data do not fit the rod length (:meth:`Masses.check_rod`).
    """
    masses.check_rod(rod_length)
    three: tuple[float | None, float | None, float | None] = (None, None, None)
    error = None
    ends = masses.rod_ends(rod_length)
    small, big = ends if ends is not None else (None, None)
    by_cg = masses.rod_split == "centre-of-gravity"
    if by_cg and masses.rod and masses.rod_cg_from_big_end is not None and masses.rod_inertia:
        three = rod_three_mass(
            masses.rod, rod_length, masses.rod_cg_from_big_end, masses.rod_inertia
        )
        lb = masses.rod_cg_from_big_end
        error = masses.rod * (rod_length - lb) * lb - masses.rod_inertia
    m_j = masses.reciprocating
    if m_j is None:
        m_j = (masses.piston_group or 0.0) + (small or 0.0)
    m_r = masses.rotating
    crank = None
    if m_r is None:
        crank = masses.crank_unbalance
        m_r = crank / rods_per_throw + (big or 0.0)
    given = [k for k in ("reciprocating", "rotating") if getattr(masses, k) is not None]
    model = "two-mass rod model" if by_cg else "rod split m_rod/3 : 2 m_rod/3 (seed 002 eq. 15)"
    source = "given " + " and ".join(given) if given else f"components ({model})"
    return EquivalentMasses(
        reciprocating=float(m_j),
        rotating=float(m_r),
        rod_small_end=small,
        rod_big_end=big,
        crank=crank,
        inertia_error=error,
        three_mass_small_end=three[0],
        three_mass_big_end=three[1],
        three_mass_centre=three[2],
        source=source,
    )
