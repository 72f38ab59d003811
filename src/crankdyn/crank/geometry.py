"""Slider-crank geometry of one cylinder (domain object).

Conventions (docs/conventions.md, seed 000 section 1): crank radius R, rod length L, crank-rod ratio
lambda = R/L, offset (desaxe) e with k = e/R positive when the cylinder axis is shifted toward the
side the crank pin moves to just after TDC, so that sin(beta) = lambda (sin(phi) - k).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from crankdyn.errors import InputError

__all__ = [
    "LENGTH_RANGE",
    "CrankGeometry",
    "check_finite",
    "check_length",
    "check_positive",
    "check_step",
]

LENGTH_RANGE = (1e-6, 1e3)
"""Lengths crankdyn accepts (m): 1 micrometre to 1 km. Outside it the input is a unit mistake,
and squares and products of such lengths would leave the range of floating point."""


def check_finite(name: str, value: object) -> float:
    """A user value as a finite float.

    Parameters
    ----------
    name : str
        The key the value came from, for the message (e.g. ``"bore"``).
    value : object
        The value as given (any unit: this checks only that it is a finite number).

    Returns
    -------
    float
        ``float(value)``, in the value's unit.

    Raises
    ------
    InputError
        If the value is not a number or not finite.

    Examples
    --------
    >>> check_finite("bore", "0.076")
    0.076
    >>> check_finite("bore", float("nan"))
    Traceback (most recent call last):
    ...
    crankdyn.errors.InputError: bore = nan: the value is not finite
    """
    try:
        number = float(value)  # type: ignore[arg-type]  # anything else is the InputError below
    except (TypeError, ValueError):
        raise InputError("expected a number", key=name, value=value) from None
    if not math.isfinite(number):
        raise InputError("the value is not finite", key=name, value=value)
    return number


def check_positive(name: str, value: object, what: str = "") -> float:
    """A user value as a finite, positive float.

    Parameters
    ----------
    name : str
        The key the value came from, for the message.
    value : object
        The value as given (any unit).
    what : str
        What the value is, for the message (e.g. ``"the bore"``); default "the value".

    Returns
    -------
    float
        ``float(value)`` (> 0), in the value's unit.

    Raises
    ------
    InputError
        If the value is not a finite number or not positive.
    """
    number = check_finite(name, value)
    if number <= 0.0:
        raise InputError(f"{what or 'the value'} must be positive", key=name, value=value)
    return number


def check_length(name: str, value: object, what: str = "") -> float:
    """A user value as a length within :data:`LENGTH_RANGE`.

    Parameters
    ----------
    name : str
        The key the value came from, for the message.
    value : object
        The length as given (m).
    what : str
        What the value is, for the message (e.g. ``"the bore"``); default "the length".

    Returns
    -------
    float
        The length (m), 1e-6 <= value <= 1e3.

    Raises
    ------
    InputError
        If the value is not a finite positive number or lies outside the range (a unit
        mistake).
    """
    number = check_positive(name, value, what)
    low, high = LENGTH_RANGE
    if not low <= number <= high:
        raise InputError(
            f"{what or 'the length'} lies outside the range crankdyn computes with "
            f"(1 micrometre to 1 km); check the unit",
            key=name,
            value=value,
        )
    return number


def check_step(step: float, cycle: float) -> int:
    """The number of steps of a crank-angle step in a cycle; the step must divide the cycle.

    The library never rounds a step silently: the step must divide the cycle to a relative
    1e-9, and the grid may have at most one million points.

    Parameters
    ----------
    step : float
        Crank-angle step (rad), 0 < step <= cycle.
    cycle : float
        Crank angle of the cycle or revolution (rad), e.g. 4 pi for a four-stroke cycle.

    Returns
    -------
    int
        The number of steps, ``cycle / step`` (dimensionless).

    Raises
    ------
    InputError
        If the step is not in (0, cycle], does not divide the cycle, or is too small.

    Examples
    --------
    >>> import math
    >>> check_step(math.radians(0.5), 4 * math.pi)
    1440
    """
    if not (math.isfinite(step) and 0.0 < step <= cycle):
        raise InputError(
            f"the crank-angle step must lie between 0 and {math.degrees(cycle):g} deg",
            key="step",
            value=math.degrees(step),
        )
    count = round(cycle / step)
    if abs(count * step - cycle) > 1e-9 * cycle:
        raise InputError(
            f"the crank-angle step must divide the {math.degrees(cycle):g} deg cycle evenly",
            key="step",
            value=math.degrees(step),
        )
    if count > 1_000_000:
        raise InputError("the step is too small (more than 1000000 points)", key="step")
    return count


@dataclass(frozen=True)
class CrankGeometry:
    """Geometry of a (central or offset) slider-crank.

    Parameters
    ----------
    bore : float
        Cylinder bore D (m).
    crank_radius : float
        Crank radius R (m); the nominal stroke is 2R.
    rod_length : float
        Connecting-rod length L between the pin centres (m); must exceed R + |e|.
    offset : float
        Offset (desaxe) e of the cylinder axis from the crank centre (m), sign as above;
        default 0 (central slider-crank).
    intake_area : float or None
        Flow area of the intake F_in (m^2), for the mean intake gas velocity (seed 002 eq. 10);
        default none.

    Raises
    ------
    InputError
        If a length is not a finite positive number in :data:`LENGTH_RANGE`, the rod is not
        longer than the crank radius, or the offset stops the crank from turning.

    Notes
    -----
    The crank turns through a full revolution only when the rod can reach the cylinder axis at
    every crank angle: max |R sin(phi) - e| = R + |e| < L (seed 000 section 1.2).

    Examples
    --------
    The VAZ-2108 of seed 002 (bore 76 mm, stroke 71 mm, lambda = 0.26):

    >>> g = CrankGeometry.from_stroke(0.076, 0.071, rod_ratio=0.26)
    >>> round(g.rod_length * 1e3, 2), round(g.lam, 2)
    (136.54, 0.26)
    >>> round(g.swept_volume * 1e6, 1)  # cm^3
    322.1
    """

    bore: float
    crank_radius: float
    rod_length: float
    offset: float = 0.0
    intake_area: float | None = None
    _derived: dict[Any, Any] = field(
        default_factory=dict, init=False, repr=False, compare=False
    )  # what analyses of this geometry alone computed once (kinematics summaries)

    def __post_init__(self) -> None:
        bore = check_length("bore", self.bore, "the bore")
        radius = check_length("crank_radius", self.crank_radius, "the crank radius")
        rod = check_length("rod_length", self.rod_length, "the rod length")
        offset = check_finite("offset", self.offset)
        if rod <= radius:
            raise InputError(
                f"the rod ({rod * 1e3:.6g} mm) must be longer than the crank radius "
                f"({radius * 1e3:.6g} mm)",
                key="rod_length",
                value=self.rod_length,
            )
        if abs(offset) >= rod - radius:
            raise InputError(
                f"the offset stops the crank from turning: |e| must be less than L - R = "
                f"{(rod - radius) * 1e3:.6g} mm",
                key="offset",
                value=self.offset,
            )
        if self.intake_area is not None:
            area = check_finite("intake_area", self.intake_area)
            if area <= 0.0:
                raise InputError("the intake area must be positive", key="intake_area",
                                 value=self.intake_area)  # fmt: skip
            object.__setattr__(self, "intake_area", area)
        for name, value in (
            ("bore", bore),
            ("crank_radius", radius),
            ("rod_length", rod),
            ("offset", offset),
        ):
            object.__setattr__(self, name, value)

    @classmethod
    def from_stroke(
        cls,
        bore: float,
        stroke: float,
        rod_length: float | None = None,
        *,
        rod_ratio: float | None = None,
        offset: float = 0.0,
    ) -> CrankGeometry:
        """Build from the nominal stroke S = 2R and either the rod length or lambda = R/L.

        Parameters
        ----------
        bore : float
            Cylinder bore D (m).
        stroke : float
            Nominal stroke S = 2R (m).
        rod_length : float or None
            Connecting-rod length L (m); give it or ``rod_ratio``.
        rod_ratio : float or None
            Crank-rod ratio lambda = R/L (dimensionless, 0 < lambda < 1); give it or
            ``rod_length``.
        offset : float
            Offset (desaxe) e (m); default 0.

        Returns
        -------
        CrankGeometry
            R = S/2 and L = R/lambda when ``rod_ratio`` is given.

        Raises
        ------
        InputError
            If both or neither of ``rod_length`` and ``rod_ratio`` is given, the ratio is not in
            (0, 1), or the geometry is invalid.
        """
        radius = check_positive("stroke", stroke, "the stroke") / 2.0
        if (rod_length is None) == (rod_ratio is None):
            raise InputError("give exactly one of rod_length and rod_ratio", key="rod_length")
        if rod_length is None:
            ratio = check_positive("rod_ratio", rod_ratio, "the rod ratio")
            if ratio >= 1.0:
                raise InputError(
                    "the rod ratio R/L must be less than 1 (the rod must be longer than the crank)",
                    key="rod_ratio",
                    value=rod_ratio,
                )
            rod_length = radius / ratio
        return cls(bore=bore, crank_radius=radius, rod_length=rod_length, offset=offset)

    # ---- derived figures ----------------------------------------------------------------------
    @property
    def lam(self) -> float:
        """Crank-rod ratio lambda = R/L (dimensionless)."""
        return self.crank_radius / self.rod_length

    @property
    def k(self) -> float:
        """Relative offset k = e/R (dimensionless)."""
        return self.offset / self.crank_radius

    @property
    def nominal_stroke(self) -> float:
        """Nominal stroke 2R (m)."""
        return 2.0 * self.crank_radius

    @property
    def stroke(self) -> float:
        """True stroke (m): sqrt((L+R)^2 - e^2) - sqrt((L-R)^2 - e^2) (seed 000 section 1.2)."""
        r, rod, e = self.crank_radius, self.rod_length, self.offset
        return math.sqrt((rod + r) ** 2 - e * e) - math.sqrt((rod - r) ** 2 - e * e)

    @property
    def piston_area(self) -> float:
        """Piston crown area pi D^2 / 4 (m^2)."""
        return math.pi * self.bore**2 / 4.0

    @property
    def swept_volume(self) -> float:
        """Swept (displaced) volume of one cylinder, piston area x true stroke (m^3)."""
        return self.piston_area * self.stroke
