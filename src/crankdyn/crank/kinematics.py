"""Slider-crank kinematics, central and offset: exact, second-order and Fourier-series forms.

Numeric core: pure functions of SI floats and numpy arrays, vectorised over the crank angle.

Sources
-------
- Seed 000 (course chapter "Dynamics of the crank-connecting-rod mechanism", section 1): exact and
  approximate displacement, velocity, acceleration, rod angle and its rates, for the central and the
  offset mechanism; dead-centre angles and true stroke of the offset mechanism.
- Seed 002 (Makushev, Polyakova, Batrakov 2010, "Determining piston velocity and acceleration with
  derivatives"): the exact coefficients A = x/R, B = v/(R w) = sin(phi+beta)/cos(beta) and
  C = a/(R w^2) = cos(phi+beta)/cos(beta) + lambda cos^2(phi)/cos^3(beta) (its eqs. 3, 8 and 13);
  the binomial (second-order) formulas (its eqs. 19-21); the mean-piston-speed classes (Table 1).

Geometry (docs/conventions.md): crank centre at the origin, cylinder axis toward the head, the
crank pin at R (sin phi, cos phi), the cylinder axis at lateral offset e, so that
sin(beta) = lambda (sin(phi) - k) with lambda = R/L, k = e/R. The piston displacement x is measured
from TDC toward the crank: x = y_TDC - (R cos(phi) + L cos(beta)), y_TDC = sqrt((R+L)^2 - e^2).
Differentiating at constant w = dphi/dt (beta' = lambda cos(phi)/cos(beta)) gives::

    v = R w sin(phi + beta) / cos(beta)
    a = R w^2 [cos(phi + beta)/cos(beta) + lambda cos^2(phi)/cos^3(beta)]
    j = R w^3 [-sin(phi+beta)/cos(beta) - 3 lambda sin(phi) cos(phi)/cos^3(beta)
               + 3 lambda^2 cos^3(phi) sin(beta)/cos^5(beta)]
    w_L = w lambda cos(phi)/cos(beta)
    e_L = w^2 [-lambda sin(phi)/cos(beta) + lambda^2 cos^2(phi) sin(beta)/cos^3(beta)]

which for k = 0 reduce to seed 000's central forms, e.g. e_L = -lambda w^2 sin(phi) (1 - lambda^2)
/ (1 - lambda^2 sin^2 phi)^(3/2).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.constants import DEG, RPM
from crankdyn.crank.geometry import CrankGeometry, check_step
from crankdyn.errors import InputError
from crankdyn.plausibility import PlausibilityWarning, kinematics_warnings
from crankdyn.results import Result, column, freeze, scalar
from crankdyn.roots import CONVERGE_ERROR, SIGN_ERROR, brentq, brentq_many
from crankdyn.summary import derived

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = [
    "METHODS",
    "SERIES_ORDER",
    "SPEED_CLASSES",
    "CoefficientTable",
    "CrankTerms",
    "Extremum",
    "KinematicsResult",
    "KinematicsSummary",
    "SliderCrankMotion",
    "coefficient_table",
    "complex_step",
    "crank_terms",
    "dead_centres",
    "exact_acceleration",
    "extrema_grid",
    "half_binomial",
    "intake_velocity",
    "kinematics_summary",
    "local_extrema",
    "piston_jerk",
    "piston_kinematics",
    "rod_angular_jerk",
    "series_coefficients",
    "slider_crank_approx",
    "slider_crank_exact",
    "slider_crank_series",
    "speed_class",
]


def _angles(phi: ArrayLike) -> np.ndarray:
    """Crank angles as a float array; complex input is kept (complex-step differentiation)."""
    arr = np.asarray(phi)
    return arr if np.iscomplexobj(arr) else np.asarray(arr, dtype=float)  # no copy if float


class SliderCrankMotion(NamedTuple):
    """Piston and rod motion at a set of crank angles (SI arrays of the same shape).

    Attributes
    ----------
    displacement : numpy.ndarray
        Piston displacement x from TDC toward the crank (m).
    velocity : numpy.ndarray
        Piston velocity dx/dt (m/s).
    acceleration : numpy.ndarray
        Piston acceleration d2x/dt2 (m/s^2).
    rod_angle : numpy.ndarray
        Rod angle beta (rad).
    rod_angular_velocity : numpy.ndarray
        Rod angular velocity dbeta/dt (rad/s).
    rod_angular_acceleration : numpy.ndarray
        Rod angular acceleration d2beta/dt2 (rad/s^2).
    """

    displacement: NDArray[np.float64]
    velocity: NDArray[np.float64]
    acceleration: NDArray[np.float64]
    rod_angle: NDArray[np.float64]
    rod_angular_velocity: NDArray[np.float64]
    rod_angular_acceleration: NDArray[np.float64]


def dead_centres(
    crank_radius: float, rod_length: float, offset: float = 0.0
) -> tuple[float, float, float]:
    """Crank angles of TDC and BDC and the true stroke of an (offset) slider-crank.

    Seed 000 section 1.2: at TDC crank and rod are in line and extended, at BDC folded, so
    sin(phi_TDC) = e/(L+R) and sin(phi_BDC - pi) = e/(L-R), i.e.
    phi_TDC = arcsin(lambda k/(1+lambda)), phi_BDC = pi + arcsin(lambda k/(1-lambda)), and the
    stroke S = sqrt((L+R)^2 - e^2) - sqrt((L-R)^2 - e^2) (>= 2R).

    Parameters
    ----------
    crank_radius, rod_length, offset : float
        R, L, e (m).

    Returns
    -------
    phi_tdc : float
        Crank angle of TDC (rad).
    phi_bdc : float
        Crank angle of BDC (rad).
    stroke : float
        True stroke S (m).

    Examples
    --------
    >>> tdc, bdc, stroke = dead_centres(0.05, 0.2, 0.01)
    >>> round(math.degrees(tdc), 4), round(math.degrees(bdc), 4), round(stroke, 6)
    (2.2924, 183.8226, 0.100134)
    """
    r, l, e = float(crank_radius), float(rod_length), float(offset)
    phi_tdc = math.asin(e / (l + r))
    phi_bdc = math.pi + math.asin(e / (l - r))
    stroke = math.sqrt((l + r) ** 2 - e**2) - math.sqrt((l - r) ** 2 - e**2)
    return phi_tdc, phi_bdc, stroke


class CrankTerms(NamedTuple):
    """Sines and cosines of the crank angle phi, the rod angle beta and phi + beta at a set of
    crank angles (dimensionless arrays of one shape), shared by the kinematics and the forces.

    Attributes
    ----------
    sin_phi, cos_phi : numpy.ndarray
        sin(phi), cos(phi) (dimensionless).
    sin_beta, cos_beta : numpy.ndarray
        sin(beta) = lambda (sin(phi) - k), cos(beta) (dimensionless).
    sin_phi_beta, cos_phi_beta : numpy.ndarray
        sin(phi + beta), cos(phi + beta) (dimensionless).
    """

    sin_phi: NDArray[np.float64]
    cos_phi: NDArray[np.float64]
    sin_beta: NDArray[np.float64]
    cos_beta: NDArray[np.float64]
    sin_phi_beta: NDArray[np.float64]
    cos_phi_beta: NDArray[np.float64]


def crank_terms(phi: ArrayLike, lam: float, k: float = 0.0) -> CrankTerms:
    """The sines and cosines of phi, beta and phi + beta at a set of crank angles.

    sin(beta) = lambda (sin(phi) - k) (module docstring; seed 000 section 1.2); the sums of
    angles are expanded, so no arcsin is taken.

    Parameters
    ----------
    phi : array_like
        Crank angles (rad); complex values are kept (complex-step differentiation).
    lam : float
        Crank-rod ratio lambda = R/L (dimensionless).
    k : float
        Relative offset k = e/R (dimensionless); default 0.

    Returns
    -------
    CrankTerms
        Dimensionless arrays of the shape of ``phi``.
    """
    phi = _angles(phi)
    sin_phi, cos_phi = np.sin(phi), np.cos(phi)
    sin_b = lam * (sin_phi - k)
    cos_b = np.sqrt(1.0 - sin_b * sin_b)
    sin_pb = sin_phi * cos_b + cos_phi * sin_b  # sin(phi + beta)
    cos_pb = cos_phi * cos_b - sin_phi * sin_b  # cos(phi + beta)
    return CrankTerms(sin_phi, cos_phi, sin_b, cos_b, sin_pb, cos_pb)


def slider_crank_exact(
    phi: ArrayLike,
    crank_radius: float,
    rod_length: float,
    offset: float = 0.0,
    omega: float = 1.0,
    *,
    terms: CrankTerms | None = None,
) -> SliderCrankMotion:
    """Exact piston and rod motion (seed 000 section 1, seed 002 eqs. 3, 8, 13).

    The formulas are those of the module docstring: x = y_TDC - (R cos(phi) + L cos(beta)),
    v = R w sin(phi + beta)/cos(beta), a = R w^2 [cos(phi + beta)/cos(beta)
    + lambda cos^2(phi)/cos^3(beta)].

    Parameters
    ----------
    phi : array_like
        Crank angle (rad) from the cylinder axis, positive in the direction of rotation; complex
        angles give complex results (complex-step differentiation, :func:`complex_step`).
    crank_radius, rod_length, offset : float
        R, L, e (m).
    omega : float
        Crank angular speed w (rad/s), constant; default 1.
    terms : CrankTerms or None
        :func:`crank_terms` at these angles for R/L and e/R, when the caller has them already.

    Returns
    -------
    SliderCrankMotion
        Displacement (m), velocity (m/s), acceleration (m/s^2), rod angle (rad), rod angular
        velocity (rad/s) and angular acceleration (rad/s^2), each of the shape of ``phi``.

    Examples
    --------
    At 90 deg the central mechanism's piston speed is R w (seed 000 section 1.1):

    >>> m = slider_crank_exact(math.pi / 2, 0.0355, 0.0355 / 0.26, omega=513.1)
    >>> round(float(m.velocity), 3), round(0.0355 * 513.1, 3)
    (18.215, 18.215)
    """
    r, l, e, w = float(crank_radius), float(rod_length), float(offset), float(omega)
    lam, k = r / l, e / r
    if terms is None:
        terms = crank_terms(phi, lam, k)
    sin_phi, cos_phi, sin_b, cos_b, sin_pb, _ = terms
    beta = np.arcsin(sin_b)
    y_tdc = math.sqrt((l + r) ** 2 - e * e)
    x = y_tdc - (r * cos_phi + l * cos_b)
    v = r * w * sin_pb / cos_b
    a = exact_acceleration(terms, r, lam, w)
    w_rod = w * lam * cos_phi / cos_b
    e_rod = w * w * (-lam * sin_phi / cos_b + lam * lam * cos_phi**2 * sin_b / cos_b**3)
    return SliderCrankMotion(x, v, a, beta, w_rod, e_rod)


def exact_acceleration(terms: CrankTerms, r: float, lam: float, w: float) -> np.ndarray:
    """Exact piston acceleration a = R w^2 [cos(phi + beta)/cos(beta) + lambda cos^2(phi)/
    cos^3(beta)] (seed 000 section 1, seed 002 eq. 13) from the crank terms: the expression
    :func:`slider_crank_exact` evaluates, for a caller that needs the acceleration alone.

    Parameters
    ----------
    terms : CrankTerms
        :func:`crank_terms` at the crank angles for lambda and k.
    r : float
        Crank radius R (m).
    lam : float
        lambda = R/L (dimensionless), computed as ``R / L``.
    w : float
        Crank speed (rad/s).

    Returns
    -------
    numpy.ndarray
        The acceleration (m/s^2), of the shape of the terms.
    """
    return (
        r
        * w
        * w
        * (terms.cos_phi_beta / terms.cos_beta + lam * terms.cos_phi**2 / terms.cos_beta**3)
    )


def piston_jerk(
    phi: ArrayLike,
    crank_radius: float,
    rod_length: float,
    offset: float = 0.0,
    omega: float = 1.0,
) -> NDArray[np.float64]:
    """Exact piston jerk da/dt at constant crank speed (derivative of seed 002 eq. 13).

    j = R w^3 [-sin(phi+beta)/cos(beta) - 3 lambda sin(phi) cos(phi)/cos^3(beta)
    + 3 lambda^2 cos^3(phi) sin(beta)/cos^5(beta)] (module docstring).

    Parameters
    ----------
    phi : array_like
        Crank angle (rad).
    crank_radius, rod_length, offset : float
        R, L, e (m).
    omega : float
        Crank angular speed w (rad/s); default 1.

    Returns
    -------
    numpy.ndarray
        Piston jerk (m/s^3), of the shape of ``phi``.
    """
    phi = _angles(phi)
    r, l, e, w = float(crank_radius), float(rod_length), float(offset), float(omega)
    lam = r / l
    sin_phi, cos_phi = np.sin(phi), np.cos(phi)
    sin_b = lam * (sin_phi - e / r)
    cos_b = np.sqrt(1.0 - sin_b * sin_b)
    sin_pb = sin_phi * cos_b + cos_phi * sin_b
    return (
        r
        * w**3
        * (
            -sin_pb / cos_b
            - 3.0 * lam * sin_phi * cos_phi / cos_b**3
            + 3.0 * lam * lam * cos_phi**3 * sin_b / cos_b**5
        )
    )


def rod_angular_jerk(
    phi: ArrayLike,
    crank_radius: float,
    rod_length: float,
    offset: float = 0.0,
    omega: float = 1.0,
) -> NDArray[np.float64]:
    """Time derivative of the rod angular acceleration, exact, at constant crank speed.

    The derivative of e_L = w^2 [-lambda sin(phi)/cos(beta) + lambda^2 cos^2(phi)
    sin(beta)/cos^3(beta)] (module docstring) with dbeta/dphi = lambda cos(phi)/cos(beta).

    Parameters
    ----------
    phi : array_like
        Crank angle (rad).
    crank_radius, rod_length, offset : float
        R, L, e (m).
    omega : float
        Crank angular speed w (rad/s); default 1.

    Returns
    -------
    numpy.ndarray
        d(e_L)/dt (rad/s^3), of the shape of ``phi``.
    """
    phi = _angles(phi)
    r, l, e, w = float(crank_radius), float(rod_length), float(offset), float(omega)
    lam = r / l
    sin_phi, cos_phi = np.sin(phi), np.cos(phi)
    sin_b = lam * (sin_phi - e / r)
    cos_b = np.sqrt(1.0 - sin_b * sin_b)
    db = lam * cos_phi / cos_b
    return w**3 * (
        -lam * cos_phi / cos_b
        - lam * sin_phi * sin_b * db / cos_b**2
        - 2.0 * lam * lam * cos_phi * sin_phi * sin_b / cos_b**3
        + lam * lam * cos_phi**2 * db * (cos_b**2 + 3.0 * sin_b**2) / cos_b**4
    )


def slider_crank_approx(
    phi: ArrayLike,
    crank_radius: float,
    rod_length: float,
    offset: float = 0.0,
    omega: float = 1.0,
) -> SliderCrankMotion:
    """The seeds' approximate (second-order) formulas.

    Central (seed 000 section 1.1; seed 002 eqs. 19-21), with the offset terms of seed 000
    section 1.2 (u = lambda (sin phi - k))::

        x = R [(1 - cos phi) + lambda/4 (1 - cos 2phi) - lambda k sin phi]
        v = R w [sin phi + lambda/2 sin 2phi - lambda k cos phi]
        a = R w^2 [cos phi + lambda cos 2phi + lambda k sin phi]
        beta = u + u^3/6,   w_L = lambda w cos phi (1 + u^2/2),
        e_L = lambda w^2 [-sin phi (1 + u^2/2) + lambda u cos^2 phi]

    (the rod formulas are the Taylor expansions of arcsin and 1/cos beta; for k = 0,
    e_L = -lambda w^2 sin phi [1 + lambda^2 (1 - 3 cos^2 phi)/2]).

    Parameters
    ----------
    phi : array_like
        Crank angle (rad).
    crank_radius, rod_length, offset : float
        R, L, e (m).
    omega : float
        Crank angular speed w (rad/s); default 1.

    Returns
    -------
    SliderCrankMotion
        Displacement (m), velocity (m/s), acceleration (m/s^2), rod angle (rad), rod angular
        velocity (rad/s) and angular acceleration (rad/s^2).
    """
    phi = _angles(phi)
    r, l, e, w = float(crank_radius), float(rod_length), float(offset), float(omega)
    lam, k = r / l, e / r
    s, c = np.sin(phi), np.cos(phi)
    x = r * ((1.0 - c) + lam / 4.0 * (1.0 - np.cos(2 * phi)) - lam * k * s)
    v = r * w * (s + lam / 2.0 * np.sin(2 * phi) - lam * k * c)
    a = r * w * w * (c + lam * np.cos(2 * phi) + lam * k * s)
    u = lam * (s - k)
    beta = u + u**3 / 6.0
    w_rod = lam * w * c * (1.0 + u * u / 2.0)
    e_rod = lam * w * w * (-s * (1.0 + u * u / 2.0) + lam * u * c * c)
    return SliderCrankMotion(x, v, a, beta, w_rod, e_rod)


def half_binomial(n: int) -> float:
    """The generalised binomial coefficient C(1/2, n) = (1/2)(1/2 - 1)...(1/2 - n + 1) / n!.

    Evaluated as ``scipy.special.binom(0.5, n)`` evaluates it for n < 20 (the product of
    (i + 1/2 - n) over i = 1..n, divided by n!, in that order: the same number to the bit, which
    the tests check), without importing scipy.special (about 0.2 s of a fresh process, paid
    by every study worker); larger n are left to scipy.

    Parameters
    ----------
    n : int
        The lower index, n >= 0.

    Returns
    -------
    float
        C(1/2, n) (dimensionless).

    Examples
    --------
    >>> half_binomial(1), half_binomial(2), half_binomial(3)
    (0.5, -0.125, 0.0625)
    """
    if n >= 20:
        from scipy.special import binom  # imported here: keeps `import crankdyn` light

        return float(binom(0.5, n))
    num, den = 1.0, 1.0
    for i in range(1, n + 1):
        num *= i + 0.5 - n
        den *= i
    return num / den


def series_coefficients(
    lam: float, k: float = 0.0, order: int = 2
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Fourier coefficients of the piston displacement, consistently expanded in lambda.

    The exact displacement is x/R = y_TDC/R - cos(phi) - cos(beta)/lambda with
    cos(beta) = sqrt(1 - u^2) = sum_n c_n u^(2n), c_n = (-1)^n binom(1/2, n),
    u = lambda (sin phi - k).
    Truncating the binomial series after n = N = order/2 keeps every term up to lambda^(2N-1) and
    harmonics up to 2N. For k = 0 only even harmonics remain and the acceleration is
    a/(R w^2) = cos(phi) + A2 cos(2phi) + A4 cos(4phi) + ..., with the classical
    A2 = lambda + lambda^3/4 + 15 lambda^5/128 + ..., A4 = -(lambda^3/4 + 3 lambda^5/16 + ...),
    A6 = 9 lambda^5/128 + ...; order = 2 is the seeds' second-order formula
    (seed 002 eq. 19, seed 000 section 1), and the series converges to the exact motion.

    Parameters
    ----------
    lam, k : float
        lambda = R/L and k = e/R (dimensionless).
    order : int
        Highest harmonic kept; an even number >= 2.

    Returns
    -------
    cos_coeffs, sin_coeffs : numpy.ndarray
        Arrays of length order + 1: x/R = sum_m cos_coeffs[m] cos(m phi) + sin_coeffs[m] sin(m phi)
        (dimensionless; index m is the harmonic order, sin_coeffs[0] = 0).

    Raises
    ------
    ValueError
        If ``order`` is not an even number >= 2 (a programming error; the command line and the
        files check the order first).

    Examples
    --------
    The second harmonic of the acceleration, A2 = 4 |cos_coeffs[2]| = lambda + lambda^3/4 to
    order 4:

    >>> cos_c, sin_c = series_coefficients(0.25, order=4)
    >>> round(float(-4 * cos_c[2]), 6), round(0.25 + 0.25**3 / 4, 6)
    (0.253906, 0.253906)
    """
    if order < 2 or order % 2:
        raise ValueError("order must be an even number >= 2")
    n_max = order // 2
    # Laurent polynomial of u/lambda = sin(phi) - k in z = exp(i phi), exponents -1, 0, 1
    base = np.array([0.5j, -k, -0.5j], dtype=complex)
    total = np.zeros(2 * order + 1, dtype=complex)  # exponents -order..order
    power = np.array([1.0 + 0j])
    for n in range(1, n_max + 1):
        power = np.convolve(np.convolve(power, base), base)  # (sin phi - k)^(2n)
        c_n = (-1.0) ** n * half_binomial(n)
        mid = (power.size - 1) // 2
        total[order - mid : order + mid + 1] += c_n * lam ** (2 * n - 1) * power
    # x/R = y_TDC/R - cos(phi) - [1/lambda + sum_n c_n lambda^(2n-1) (sin phi - k)^(2n)]
    y_tdc = math.sqrt((1.0 + 1.0 / lam) ** 2 - k * k)
    cos_coeffs = np.zeros(order + 1)
    sin_coeffs = np.zeros(order + 1)
    cos_coeffs[0] = y_tdc - 1.0 / lam - total[order].real
    for m in range(1, order + 1):
        s_m = total[order + m]
        cos_coeffs[m] = -2.0 * s_m.real
        sin_coeffs[m] = 2.0 * s_m.imag
    cos_coeffs[1] -= 1.0
    return cos_coeffs, sin_coeffs


def slider_crank_series(
    phi: ArrayLike,
    crank_radius: float,
    rod_length: float,
    offset: float = 0.0,
    omega: float = 1.0,
    order: int = 2,
) -> SliderCrankMotion:
    """Piston motion from the lambda-series of :func:`series_coefficients`, to a given order.

    Velocity and acceleration are the exact derivatives of the truncated series. The rod
    quantities are the exact ones (the series concerns the piston motion).

    Parameters
    ----------
    phi : array_like
        Crank angle (rad).
    crank_radius, rod_length, offset : float
        R, L, e (m).
    omega : float
        Crank angular speed w (rad/s); default 1.
    order : int
        Highest harmonic of the series, an even number >= 2; default 2 (the seeds'
        second-order formula).

    Returns
    -------
    SliderCrankMotion
        Displacement (m), velocity (m/s), acceleration (m/s^2) of the series, and the exact rod
        angle (rad), angular velocity (rad/s) and angular acceleration (rad/s^2).
    """
    phi = _angles(phi)
    r, w = float(crank_radius), float(omega)
    cos_c, sin_c = series_coefficients(r / float(rod_length), float(offset) / r, order)
    m = np.arange(cos_c.size)
    mphi = np.multiply.outer(phi, m)
    cos_m, sin_m = np.cos(mphi), np.sin(mphi)
    x = r * (cos_m @ cos_c + sin_m @ sin_c)
    v = r * w * (-sin_m @ (m * cos_c) + cos_m @ (m * sin_c))
    a = -r * w * w * (cos_m @ (m * m * cos_c) + sin_m @ (m * m * sin_c))
    exact = slider_crank_exact(phi, crank_radius, rod_length, offset, omega)
    return SliderCrankMotion(
        x, v, a, exact.rod_angle, exact.rod_angular_velocity, exact.rod_angular_acceleration
    )


# ---- extrema ----------------------------------------------------------------------------------


@dataclass(frozen=True)
class Extremum:
    """A local extremum of a periodic function of the crank angle.

    Parameters
    ----------
    kind : str
        ``"max"`` or ``"min"``.
    angle : float
        Crank angle (rad), 0 <= angle < 2 pi.
    value : float
        Function value there (the function's SI unit).
    """

    kind: str
    angle: float
    value: float


def complex_step(
    f: Callable[[np.ndarray], ArrayLike], h: float = 1e-30
) -> Callable[[ArrayLike], NDArray[np.float64]]:
    """Derivative of a real-analytic vectorised f by the complex step Im f(x + ih) / h.

    Exact to machine precision (no subtractive cancellation); every core function here accepts
    complex angles for this purpose (Squire and Trapp 1998, SIAM Review 40, 110-112).

    Parameters
    ----------
    f : callable
        A vectorised, real-analytic function of the crank angle (rad) that accepts complex
        arguments.
    h : float
        The imaginary step (rad); default 1e-30.

    Returns
    -------
    callable
        df/dx at real angles x (rad): the unit of f per radian.

    Examples
    --------
    >>> d = complex_step(np.sin)
    >>> float(d(0.0))
    1.0
    """
    return lambda x: np.imag(f(np.asarray(x, dtype=float) + 1j * h)) / h


def extrema_grid(n: int = 1440) -> NDArray[np.float64]:
    """The grid on which :func:`local_extrema` brackets the extrema: 0 to 2 pi, n + 1 points.

    Parameters
    ----------
    n : int
        Intervals per revolution; default 1440.

    Returns
    -------
    numpy.ndarray
        The angles (rad), both ends included.
    """
    return np.linspace(0.0, 2.0 * math.pi, n + 1)


def local_extrema(
    f: Callable[[np.ndarray], ArrayLike],
    df: Callable[[np.ndarray], ArrayLike] | None = None,
    n: int = 1440,
    *,
    elementwise: bool = True,
    grid_slopes: ArrayLike | None = None,
) -> list[Extremum]:
    """Local extrema over one revolution of a smooth 2 pi-periodic f, from the zeros of df.

    Sign changes of the derivative df on an n-point grid bracket the extrema; each is
    refined with Brent's method to machine precision (Brent 1973, ch. 4;
    :func:`crankdyn.roots.brentq`), and classed by the signs of df 1e-6 rad either side.

    Parameters
    ----------
    f, df : callable
        Vectorised callables of the crank angle (rad); df defaults to the complex-step derivative
        of f (f must then accept complex angles).
    n : int
        Grid points per revolution (the bracket width is 2 pi / n); default 1440.
    elementwise : bool
        True (default) when f's and df's value at an angle does not depend on the other angles of
        the array (numpy's elementwise arithmetic and functions): the brackets are then refined
        together, one call of df per Brent iteration (:func:`crankdyn.roots.brentq_many`), the
        checks either side take one call and the values another; the same numbers to the bit
        as one angle at a time. False for a matrix product over the angles (a BLAS kernel may
        sum in another order for another number of rows, :func:`slider_crank_series`): one
        angle at a time.
    grid_slopes : array_like or None
        df on the grid ``linspace(0, 2 pi, n + 1)``, when the caller has it already (e.g. one
        evaluation of a motion serving several of its quantities, :func:`kinematics_summary`);
        default: ``df`` evaluated on the grid here.

    Returns
    -------
    list of Extremum
        Sorted by angle; angles in rad, values in the unit of f.

    Raises
    ------
    RuntimeError
        When Brent's method does not converge in 100 iterations (not seen for a smooth f).

    Examples
    --------
    >>> [(x.kind, round(math.degrees(x.angle), 6)) for x in local_extrema(np.sin)]
    [('max', 90.0), ('min', 270.0)]
    """
    if df is None:
        df = complex_step(f)
    grid = extrema_grid(n)
    d = np.array(df(grid) if grid_slopes is None else grid_slopes, dtype=float)
    if d.shape != grid.shape:
        raise ValueError(f"grid_slopes must hold {n + 1} values, one per grid point")
    d[-1] = d[0]  # the revolution ends where it starts: one derivative there, not two round-offs
    d0, d1 = d[:-1], d[1:]
    # the intervals that hold a zero: signs, not d0 * d1 (it may underflow)
    bracketed = (d0 == 0.0) | (((d0 < 0.0) != (d1 < 0.0)) & (d1 != 0.0))
    starts = np.flatnonzero(bracketed)
    if starts.size == 0:
        return []
    roots = grid[starts]  # a zero of df on the grid is the root
    search = d[starts] != 0.0
    i = starts[search]
    if elementwise:
        found = brentq_many(df, grid[i], grid[i + 1], xtol=1e-14)
        if (found.status == CONVERGE_ERROR).any():
            raise RuntimeError("Brent's method did not converge in 100 iterations")
        # same signs: at 2 pi the derivative is round-off of the one at 0, the root is the end
        # of the revolution
        roots[search] = np.where(found.status == SIGN_ERROR, grid[i + 1], found.root)

        def at(g: Callable[[np.ndarray], ArrayLike], x: NDArray[np.float64]) -> np.ndarray:
            return np.asarray(g(x))

    else:

        def at(g: Callable[[np.ndarray], ArrayLike], x: NDArray[np.float64]) -> np.ndarray:
            return np.array([np.asarray(g(np.array([t])))[0] for t in x.tolist()])

        def slope(t: float) -> float:
            return float(at(df, np.array([t]))[0])

        for j, k in zip(np.flatnonzero(search).tolist(), i.tolist(), strict=True):
            try:
                roots[j] = brentq(slope, grid[k], grid[k + 1], xtol=1e-14)
            except ValueError:  # as above: the end of the revolution
                roots[j] = grid[k + 1]
    sides = at(df, np.concatenate([roots - 1e-6, roots + 1e-6]))  # df either side, one call
    before, after, values = sides[: roots.size], sides[roots.size :], at(f, roots)
    out: list[Extremum] = []
    for root, b, a, value in zip(roots.tolist(), before, after, values, strict=True):
        if b > 0.0 > a:
            kind = "max"
        elif b < 0.0 < a:
            kind = "min"
        else:
            continue  # a stationary point that is not an extremum
        angle = float(np.mod(root, 2.0 * math.pi))
        if any(abs(angle - x.angle) < 1e-9 for x in out):
            continue
        out.append(Extremum(kind, angle, float(value)))
    out.sort(key=lambda x: x.angle)
    return out


# ---- piston speed classes (seed 002 Table 1) -----------------------------------------------------

SPEED_CLASSES: tuple[tuple[float, str], ...] = (
    (6.0, "low-speed"),
    (9.0, "medium-speed"),
    (12.0, "high-speed"),
    (math.inf, "very high-speed"),
)
"""Upper bounds (m/s) of the mean-piston-speed classes of seed 002 Table 1: low-speed 5-6 m/s,
medium 6-9, high 9-12, very high above 12 (below 5 m/s is also classed low-speed)."""


def speed_class(mean_piston_speed: float) -> str:
    """Speed class of an engine from its mean piston speed (seed 002 Table 1).

    Parameters
    ----------
    mean_piston_speed : float
        Mean piston speed c_m = S n / 30 (m/s).

    Returns
    -------
    str
        ``"low-speed"``, ``"medium-speed"``, ``"high-speed"`` or ``"very high-speed"``
        (:data:`SPEED_CLASSES`).

    Examples
    --------
    >>> speed_class(11.6)
    'high-speed'
    """
    for bound, name in SPEED_CLASSES:
        if mean_piston_speed <= bound:
            return name
    return SPEED_CLASSES[-1][1]


# ---- analysis: result objects --------------------------------------------------------------

METHODS = ("exact", "approx", "series")
"""The kinematics methods: exact, the seeds' second-order formulas, the lambda-series."""

SERIES_ORDER = 4
"""Highest harmonic of the λ-series (``method="series"``) by default, in the library and the
command line alike."""


def _motion_function(method: str, order: int) -> Callable[..., SliderCrankMotion]:
    if method == "exact":
        return slider_crank_exact
    if method == "approx":
        return slider_crank_approx
    if method == "series":
        return lambda phi, r, l, e, w: slider_crank_series(phi, r, l, e, w, order)
    raise ValueError(f"unknown method {method!r}; expected one of {', '.join(METHODS)}")


@dataclass(frozen=True)
class AccelerationExtremum(Result):
    """One local extremum of the piston acceleration (a row of
    :attr:`KinematicsSummary.acceleration_extrema`)."""

    kind: str = scalar("kind", "Extremum", "")
    crank_angle: float = scalar("crank_angle_deg", "Crank angle", "deg", DEG)
    acceleration: float = scalar("acceleration_m_s2", "Acceleration", "m/s²")


def _larger_magnitude(a: float, at_a: float, b: float, at_b: float) -> tuple[float, str]:
    """The larger of |a| and |b| with the crank angle (rad) where it occurs, as a key figure's
    value and where."""
    value, at = (abs(a), at_a) if abs(a) >= abs(b) else (abs(b), at_b)
    return value, f"at {math.degrees(at):.1f}°"


@dataclass(frozen=True)
class KinematicsSummary(Result):
    """Summary figures of the slider-crank motion at one speed (seed 000 section 1, seed 002)."""

    title = "Slider-crank kinematics"
    method: str = scalar("method", "Method", "")
    speed: float = scalar("speed_rpm", "Speed", "rpm", RPM)
    lam: float = scalar("lambda", "Crank-rod ratio λ = R/L", "", fmt=".5g", name="rod_ratio")
    k: float = scalar("offset_ratio", "Offset ratio k = e/R", "", fmt=".5g", name="offset_ratio")
    stroke: float = scalar("stroke_m", "Stroke", "m", headline=True)
    tdc_crank_angle: float = scalar("tdc_crank_angle_deg", "TDC crank angle", "deg", DEG)
    bdc_crank_angle: float = scalar("bdc_crank_angle_deg", "BDC crank angle", "deg", DEG)
    mean_piston_speed: float = scalar(
        "mean_piston_speed_m_s", "Mean piston speed c_m", "m/s", checked="mean_piston_speed",
        headline=True, better="min",
    )  # fmt: skip
    speed_class: str = scalar("speed_class", "Speed class (seed 002 Table 1)", "")
    max_velocity: float = scalar("max_velocity_m_s", "Max piston speed", "m/s", headline=True)
    crank_angle_at_max_velocity: float = scalar(
        "crank_angle_at_max_velocity_deg", "Crank angle at max speed", "deg", DEG
    )
    velocity_ratio: float = scalar("max_to_mean_velocity", "v_max / c_m", "", fmt=".4g")
    min_velocity: float = scalar("min_velocity_m_s", "Min piston speed (return)", "m/s")
    crank_angle_at_min_velocity: float = scalar(
        "crank_angle_at_min_velocity_deg", "Crank angle at min speed", "deg", DEG
    )
    max_acceleration: float = scalar(
        "max_acceleration_m_s2", "Max acceleration", "m/s²", checked="piston_acceleration",
        headline=True,
    )  # fmt: skip
    crank_angle_at_max_acceleration: float = scalar(
        "crank_angle_at_max_acceleration_deg", "Crank angle at max acceleration", "deg", DEG
    )
    min_acceleration: float = scalar("min_acceleration_m_s2", "Min acceleration", "m/s²")
    crank_angle_at_min_acceleration: float = scalar(
        "crank_angle_at_min_acceleration_deg", "Crank angle at min acceleration", "deg", DEG
    )
    acceleration_extrema: tuple[AccelerationExtremum, ...] = scalar(
        "acceleration_extrema", "Acceleration extrema", ""
    )
    max_rod_angle: float = scalar("max_rod_angle_deg", "Max rod angle", "deg", DEG, headline=True)
    min_rod_angle: float = scalar("min_rod_angle_deg", "Min rod angle", "deg", DEG)
    max_rod_angular_velocity: float = scalar(
        "max_rod_angular_velocity_rad_s", "Max rod angular velocity", "rad/s"
    )
    min_rod_angular_velocity: float = scalar(
        "min_rod_angular_velocity_rad_s", "Min rod angular velocity", "rad/s"
    )
    max_rod_angular_acceleration: float = scalar(
        "max_rod_angular_acceleration_rad_s2", "Max rod angular acceleration", "rad/s²"
    )
    min_rod_angular_acceleration: float = scalar(
        "min_rod_angular_acceleration_rad_s2", "Min rod angular acceleration", "rad/s²"
    )
    intake_velocity: float | None = scalar(
        "intake_velocity_m_s", "Mean intake gas velocity V_in = c_m F_p/F_in", "m/s",
        description="Seed 002 eq. 10: the mean gas velocity in the intake of area F_in, for its "
        "pressure loss (with [geometry] intake_area)",
        default=None,
    )  # fmt: skip

    FIGURES = (
        derived(
            "max_piston_speed", "max_piston_speed_m_s", "Max piston speed |v|", "m/s",
            lambda s: _larger_magnitude(
                s.max_velocity, s.crank_angle_at_max_velocity,
                s.min_velocity, s.crank_angle_at_min_velocity,
            ),
            reduction="largest magnitude of the speed's extrema", better="min",
        ),
        derived(
            "max_piston_acceleration", "max_piston_acceleration_m_s2",
            "Max piston acceleration |a|", "m/s²",
            lambda s: _larger_magnitude(
                s.max_acceleration, s.crank_angle_at_max_acceleration,
                s.min_acceleration, s.crank_angle_at_min_acceleration,
            ),
            reduction="largest magnitude of the acceleration's extrema", better="min",
            check="piston_acceleration",
        ),
    )  # fmt: skip

    def plausibility(self, fuel: str | None = None) -> tuple[PlausibilityWarning, ...]:
        """The plausibility warnings of the mean piston speed and the largest piston
        acceleration (:func:`crankdyn.plausibility.kinematics_warnings`).

        Parameters
        ----------
        fuel : str or None
            ``"petrol"``, ``"diesel"`` or None: the engine type whose typical acceleration is
            checked against.

        Returns
        -------
        tuple of crankdyn.plausibility.PlausibilityWarning
            The warnings (none for a typical engine).
        """
        return kinematics_warnings(
            self.mean_piston_speed,
            max(abs(self.max_acceleration), abs(self.min_acceleration)),
            fuel,
        )


@dataclass(frozen=True)
class KinematicsResult(Result):
    """Piston and rod motion over one revolution, with its summary.

    The arrays are held in SI (angles in rad); the exports convert angles to degrees under
    ``_deg`` keys. Made by :func:`piston_kinematics`. The time column is t = phi / w from the
    crank angle at the constant speed (seed 002 eq. 1: phi = w t = 6 n t, phi in degrees and n
    in rpm).

    Parameters
    ----------
    geometry : CrankGeometry or None
        The geometry analysed (not exported).
    warnings : tuple of crankdyn.plausibility.PlausibilityWarning
        Plausibility warnings of the mean piston speed and the largest piston acceleration.
    """

    title = "Slider-crank kinematics"
    crank_angle: NDArray[np.float64] = column("crank_angle_deg", "Crank angle", "deg", DEG)
    displacement: NDArray[np.float64] = column("displacement_m", "Piston displacement", "m")
    velocity: NDArray[np.float64] = column("velocity_m_s", "Piston velocity", "m/s")
    acceleration: NDArray[np.float64] = column("acceleration_m_s2", "Piston acceleration", "m/s²")
    rod_angle: NDArray[np.float64] = column("rod_angle_deg", "Rod angle", "deg", DEG)
    rod_angular_velocity: NDArray[np.float64] = column(
        "rod_angular_velocity_rad_s", "Rod angular velocity", "rad/s"
    )
    rod_angular_acceleration: NDArray[np.float64] = column(
        "rod_angular_acceleration_rad_s2", "Rod angular acceleration", "rad/s²"
    )
    time: NDArray[np.float64] = column("time_s", "Time t = φ/ω (φ = 6 n t)", "s")
    extrema: KinematicsSummary = scalar("summary", "Summary", "")
    geometry: CrankGeometry | None = field(default=None, repr=False)
    warnings: tuple[PlausibilityWarning, ...] = field(default=(), repr=False, compare=False)

    def plot(self, fig: Figure | None = None) -> Figure:
        """Piston and rod motion vs crank angle.

        Parameters
        ----------
        fig : matplotlib.figure.Figure or None
            A figure to draw into; None makes a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure (never shown: save it or display it in a notebook).
        """
        from crankdyn.plots.kinematics import plot_kinematics

        return plot_kinematics(self, fig=fig)


def piston_kinematics(
    geometry: CrankGeometry,
    speed: float,
    angles: ArrayLike | None = None,
    *,
    step: float = math.radians(1.0),
    method: str = "exact",
    order: int = SERIES_ORDER,
    fuel: str | None = None,
    summary: KinematicsSummary | None = None,
) -> KinematicsResult:
    """Slider-crank kinematics of one cylinder at a constant crank speed.

    Parameters
    ----------
    geometry : CrankGeometry
        The crank geometry (SI).
    speed : float
        Crank speed w (rad/s).
    angles : array_like or None
        Crank angles (rad); default 0 to 2 pi inclusive every ``step``.
    step : float
        Angle step (rad) of the default grid; it must divide 2 pi. Default 1 deg.
    method : str
        ``"exact"`` (default), ``"approx"`` (seed 000/002 second-order formulas) or
        ``"series"`` (the lambda-series to harmonic ``order``, :func:`series_coefficients`).
    order : int
        Series order (even, >= 2) for ``method="series"``; default :data:`SERIES_ORDER`.
    fuel : str or None
        ``"petrol"``, ``"diesel"`` or None: the engine type whose typical piston acceleration
        the plausibility check uses (:func:`crankdyn.plausibility.kinematics_warnings`).
    summary : KinematicsSummary or None
        The summary, when it is known already: that of the same geometry, speed, method and
        order on any grid (the summary does not depend on the grid), e.g. the analysis
        session's rows on a display grid; default: computed here.

    Returns
    -------
    KinematicsResult
        Arrays over the crank angle and the :class:`KinematicsSummary`; the summary's extrema
        are those of the chosen method's formulas, found from the zeros of their exact
        (complex-step) derivatives; ``warnings`` holds the plausibility warnings of the mean
        piston speed and the largest piston acceleration.

    Raises
    ------
    InputError
        If ``step`` does not divide the revolution, or the speed is not positive and finite
        (key ``speed``).

    Examples
    --------
    The VAZ-2108 of seed 002 at 4900 rpm (stroke 71 mm, lambda = 0.26):

    >>> import crankdyn
    >>> engine = crankdyn.Engine.example("vaz2108")
    >>> k = piston_kinematics(engine.geometry, 4900 * math.pi / 30)
    >>> s = k.extrema
    >>> round(s.mean_piston_speed, 2), s.speed_class
    (11.6, 'high-speed')
    >>> round(s.max_velocity, 2), round(math.degrees(s.crank_angle_at_max_velocity), 2)
    (18.82, 76.27)
    >>> w = 4900 * math.pi / 30  # at TDC, a = R w^2 (1 + lambda) (m/s^2)
    >>> round(s.max_acceleration, 6) == round(0.0355 * w**2 * 1.26, 6)
    True
    """
    motion = _motion_function(method, order)
    r, l, e, w = geometry.crank_radius, geometry.rod_length, geometry.offset, float(speed)
    if not (math.isfinite(w) and w > 0.0):  # as kinematics_summary, before the arrays
        raise InputError("the speed must be positive", key="speed", value=speed)
    if angles is None:
        count = check_step(step, 2.0 * math.pi)
        angles = np.linspace(0.0, 2.0 * math.pi, count + 1)
    phi = np.asarray(angles, dtype=float)
    m = motion(phi, r, l, e, w)
    if summary is None:
        summary = kinematics_summary(geometry, w, method=method, order=order)
    return KinematicsResult(
        crank_angle=freeze(phi),
        displacement=freeze(m.displacement),
        velocity=freeze(m.velocity),
        acceleration=freeze(m.acceleration),
        rod_angle=freeze(m.rod_angle),
        rod_angular_velocity=freeze(m.rod_angular_velocity),
        rod_angular_acceleration=freeze(m.rod_angular_acceleration),
        time=freeze(phi / w),
        extrema=summary,
        geometry=geometry,
        warnings=summary.plausibility(fuel),
    )


def kinematics_summary(
    geometry: CrankGeometry, speed: float, *, method: str = "exact", order: int = SERIES_ORDER
) -> KinematicsSummary:
    """The summary figures of the slider-crank motion at one speed (those of
    :func:`piston_kinematics`, which does not depend on its grid).

    Computed once per geometry object, speed, method and order and kept with the geometry
    (an immutable object): the analysis session's kinematics and the plausibility check of the
    forces (:func:`crankdyn.engine.forces.engine_warnings`) share the one summary.

    Parameters
    ----------
    geometry : CrankGeometry
        The crank geometry (SI).
    speed : float
        Crank speed w (rad/s).
    method : str
        ``"exact"`` (default), ``"approx"`` or ``"series"`` (:data:`METHODS`).
    order : int
        Series order for ``method="series"``; default :data:`SERIES_ORDER`.

    Returns
    -------
    KinematicsSummary
        Extrema from the zeros of the method's exact (complex-step) derivatives.

    Raises
    ------
    InputError
        If the speed is not positive and finite (key ``speed``).
    """
    w = float(speed)
    if not (math.isfinite(w) and w > 0.0):
        raise InputError("the speed must be positive", key="speed", value=speed)
    key = ("kinematics summary", method, int(order), w.hex())
    memo = geometry._derived
    found = memo.get(key)
    if found is None:
        found = memo[key] = _summary(_motion_function(method, order), geometry, w, method)
    assert isinstance(found, KinematicsSummary)
    return found


def _summary(
    motion: Callable[..., SliderCrankMotion], geometry: CrankGeometry, w: float, method: str
) -> KinematicsSummary:
    r, l, e = geometry.crank_radius, geometry.rod_length, geometry.offset
    phi_tdc, phi_bdc, stroke = dead_centres(r, l, e)
    mean_speed = stroke * abs(w) / math.pi  # c_m = S n / 30 (seed 002 eq. 9)

    def quantity(index: int) -> Callable[[NDArray[np.float64]], NDArray[np.float64]]:
        return lambda p: motion(p, r, l, e, w)[index]

    def pick(extrema: list[Extremum], kind: str) -> Extremum:
        # the largest maximum (smallest minimum); of equal ones (symmetry) the first by angle
        chosen = [x for x in extrema if x.kind == kind]
        best = (max if kind == "max" else min)(x.value for x in chosen)
        scale = max(abs(x.value) for x in extrema) or 1.0
        return next(x for x in chosen if abs(x.value - best) <= 1e-9 * scale)

    # every quantity's complex-step derivative on the bracketing grid from one evaluation of
    # the motion (what complex_step(quantity(i))(grid) computes for each i, to the bit)
    step = 1e-30  # complex_step's default
    on_grid = motion(extrema_grid() + 1j * step, r, l, e, w)

    def extrema(index: int, elementwise: bool = True) -> list[Extremum]:
        slopes = np.imag(on_grid[index]) / step
        return local_extrema(quantity(index), elementwise=elementwise, grid_slopes=slopes)

    # the series' piston motion is a matrix product over the angles: one angle at a time
    piston = method != "series"
    v_ext = extrema(1, piston)
    a_ext = extrema(2, piston)
    vmax, vmin = pick(v_ext, "max"), pick(v_ext, "min")
    amax, amin = pick(a_ext, "max"), pick(a_ext, "min")
    rod_rate = extrema(4)
    rod_acc = extrema(5)
    beta = motion(np.array([math.pi / 2, 3 * math.pi / 2]), r, l, e, w).rod_angle
    return KinematicsSummary(
        method=method,
        speed=w,
        lam=geometry.lam,
        k=geometry.k,
        stroke=stroke,
        tdc_crank_angle=phi_tdc,
        bdc_crank_angle=phi_bdc,
        mean_piston_speed=mean_speed,
        speed_class=speed_class(mean_speed),
        max_velocity=vmax.value,
        crank_angle_at_max_velocity=vmax.angle,
        velocity_ratio=vmax.value / mean_speed if mean_speed > 0 else math.nan,
        min_velocity=vmin.value,
        crank_angle_at_min_velocity=vmin.angle,
        max_acceleration=amax.value,
        crank_angle_at_max_acceleration=amax.angle,
        min_acceleration=amin.value,
        crank_angle_at_min_acceleration=amin.angle,
        acceleration_extrema=tuple(AccelerationExtremum(x.kind, x.angle, x.value) for x in a_ext),
        max_rod_angle=float(max(beta)),
        min_rod_angle=float(min(beta)),
        max_rod_angular_velocity=pick(rod_rate, "max").value,
        min_rod_angular_velocity=pick(rod_rate, "min").value,
        max_rod_angular_acceleration=pick(rod_acc, "max").value,
        min_rod_angular_acceleration=pick(rod_acc, "min").value,
        intake_velocity=intake_velocity(mean_speed, geometry),
    )


def intake_velocity(mean_speed: float, geometry: CrankGeometry) -> float | None:
    """The mean gas velocity in the intake, seed 002 eq. 10: V_in = c_m F_p / F_in, from the mean
    piston speed c_m, the piston area F_p and the intake's area F_in (continuity of the charge
    drawn in by the piston), for the intake's pressure loss.

    Parameters
    ----------
    mean_speed : float
        c_m (m/s).
    geometry : CrankGeometry
        Its bore and ``intake_area`` (m^2).

    Returns
    -------
    float or None
        V_in (m/s); None without an intake area.

    Examples
    --------
    Bore 76 mm, c_m = 11.6 m/s, an intake of 12 cm^2: 11.6 x 45.36 / 12 = 43.85 m/s.

    >>> g = CrankGeometry(0.076, 0.0355, 0.1365, intake_area=12e-4)
    >>> round(intake_velocity(11.6, g), 2)
    43.85
    """
    if geometry.intake_area is None:
        return None
    return mean_speed * geometry.piston_area / geometry.intake_area


@dataclass(frozen=True)
class CoefficientTable(Result):
    """Dimensionless piston-motion coefficients vs crank angle for several lambda values.

    A = x/R, B = v/(R w), C = a/(R w^2) of seed 002 (eqs. 3, 8, 13) and seed 000 section 1; row i of
    each 2-D array belongs to ``lambdas[i]``.
    """

    title = "Piston motion coefficients"
    crank_angle: NDArray[np.float64] = column("crank_angle_deg", "Crank angle", "deg", DEG)
    displacement: NDArray[np.float64] = column("displacement_coefficient", "A = x/R", "")
    velocity: NDArray[np.float64] = column("velocity_coefficient", "B = v/(Rω)", "")
    acceleration: NDArray[np.float64] = column("acceleration_coefficient", "C = a/(Rω²)", "")
    lambdas: NDArray[np.float64] = scalar("lambda", "λ = R/L", "", fmt=".5g")
    method: str = scalar("method", "Method", "")

    def columns(self) -> dict[str, np.ndarray]:
        """The columns of the CSV export, named after their lambda.

        Returns
        -------
        dict of str to numpy.ndarray
            ``crank_angle_deg`` (deg) and ``A_0.26``, ``B_0.26``, ``C_0.26``... (dimensionless),
            one column per coefficient and lambda.
        """
        out = {"crank_angle_deg": self.crank_angle * DEG}
        for letter, values in (
            ("A", self.displacement),
            ("B", self.velocity),
            ("C", self.acceleration),
        ):
            for lam, row in zip(self.lambdas, values, strict=True):
                out[f"{letter}_{lam:.5g}"] = row
        return out

    def column_labels(self) -> dict[str, tuple[str, str]]:
        """Label and unit of every column of :meth:`columns`.

        Returns
        -------
        dict of str to (str, str)
            {column key: (label, unit)}.
        """
        labels = {"crank_angle_deg": ("Crank angle", "deg")}
        for letter in "ABC":
            for lam in self.lambdas:
                labels[f"{letter}_{lam:.5g}"] = (f"{letter} (λ={lam:.4g})", "")
        return labels


def coefficient_table(
    lambdas: ArrayLike,
    angles: ArrayLike,
    *,
    offset_ratio: float = 0.0,
    method: str = "exact",
    order: int = SERIES_ORDER,
) -> CoefficientTable:
    """The seeds' coefficient tables: A, B, C vs crank angle for each lambda (R = 1, w = 1).

    Parameters
    ----------
    lambdas : array_like
        Crank-rod ratios (dimensionless), each 0 < lambda < 1.
    angles : array_like
        Crank angles (rad).
    offset_ratio : float
        k = e/R (dimensionless), the same for every lambda; default 0.
    method : str
        As for :func:`piston_kinematics`.
    order : int
        As for :func:`piston_kinematics`.

    Returns
    -------
    CoefficientTable
        A = x/R, B = v/(R w) and C = a/(R w^2) (dimensionless), one row per lambda.

    Examples
    --------
    Seed 002's Table 2 (lambda = 1/3.8, coefficients printed to two decimals):

    >>> t = coefficient_table([1 / 3.8], np.radians([0, 30, 60, 90]))
    >>> for name in ("displacement", "velocity", "acceleration"):
    ...     print(np.round(getattr(t, name)[0], 2))
    [0.   0.17 0.6  1.13]
    [0.   0.61 0.98 1.  ]
    [ 1.26  1.    0.37 -0.27]
    """
    motion = _motion_function(method, order)
    phi = np.asarray(angles, dtype=float)
    lam = np.atleast_1d(np.asarray(lambdas, dtype=float))
    rows = [motion(phi, 1.0, 1.0 / x, offset_ratio, 1.0) for x in lam]
    return CoefficientTable(
        crank_angle=freeze(phi),
        displacement=freeze([m.displacement for m in rows]),
        velocity=freeze([m.velocity for m in rows]),
        acceleration=freeze([m.acceleration for m in rows]),
        lambdas=freeze(lam),
        method=method,
    )
