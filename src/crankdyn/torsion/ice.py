"""Propeller ice torque for the shaft line's dynamic analysis (numeric core).

Source: the Finnish-Swedish Ice Class Rules 2017 (Finnish Transport Safety Agency, "Ice Class
Regulations and the Application Thereof", TRAFI/494131/03.04.01.00/2016, in force 1 December
2017; chapter 6, "Propulsion machinery": the design loads, "maximum propeller ice torque applied
to the propeller", and the design of the shaft line, "torque excitation for shaft line dynamic
analysis") and IACS UR I3 "Machinery requirements for Polar Class ships" (Rev.1 2007, Corr.1
2007; the same design ice torque and torque excitation, with the Polar classes' ice
thicknesses). Rev.2 of UR I3 (January 2023) is a complete revision, applied to ships contracted
for construction on or after 1 July 2024 (its first page, read in a public copy): check its
torque excitation against what follows before applying it to such a ship.

Verification (issue 36): the texts were sought in the stored public pages and repositories --
the regulation TRAFI/494131/03.04.01.00/2016 (a public copy: its table of contents only), the
Guidelines for the application of the 2017 FSICR (TRAFI/708629/03.04.01.01/2018: their
opening only), PRS Publication 122/P (2021, which transposes the 2017 FSICR: its contents
only), UR I3 Rev.2 (2023: its first pages only) and the ShaftDesigner paper below (its
abstract only). None of the readable parts holds chapter 6's formulas or the table of cases,
so the formulas, the table of H_ice and the four excitation cases below are transcribed as the
rules state them and as the shaft-line software that implements them applies them (Batrak,
Serdjuchenko and Tarasenko, "Calculation of propulsion shafting transient torsional vibration
induced by ice impacts on the propeller blades", ShaftDesigner, 2017), and are NOT verified
against the texts: their clause numbers are not cited for that reason; check them against the
edition the ship is built to.

Design ice torque Q_max (kN m, the rule's units: D, d, P_0.7, t_0.7 in m, n in rev/s), for an
open propeller

    Q_max = 10.9 (1 - d/D) (P_0.7/D)^0.16 (t_0.7/D)^0.6 (n D)^0.17 D^3          D <= D_limit
    Q_max = 20.7 (1 - d/D) (P_0.7/D)^0.16 (t_0.7/D)^0.6 (n D)^0.17 D^1.9 H_ice^1.1   D > D_limit

and for a ducted one the factors 7.7 and 14.6, with D_limit = 1.8 H_ice; D the propeller
diameter, d the hub's, P_0.7 the pitch at 0.7 R (of a controllable-pitch propeller at the
bollard condition), t_0.7 the blade's maximum thickness at 0.7 R, n the propeller speed at the
bollard condition (not known: the nominal speed for a controllable-pitch propeller or one driven
by a turbine or an electric motor, 0.85 of it for a fixed-pitch propeller driven by a diesel
engine), H_ice the ice thickness of the class (m): IA Super 1.75, IA 1.5, IB 1.2, IC 1.0; PC1
4.0, PC2 3.5, PC3 3.0, PC4 2.5, PC5 2.0, PC6 1.75, PC7 1.5.

Torque excitation: each blade's impact is a half sine over the blade's rotation angle phi
(deg, from the first impact),

    Q(phi) = C_q Q_max sin(phi 180 / alpha_i)   for 0 <= phi mod 360 <= alpha_i, else 0,

the blades' impacts shifted by 360 / Z, summed; the cases (C_q, alpha_i): 1 a single ice block
(0.75, 90 deg), 2 a single block (1.0, 135 deg), 3 two ice blocks 360 / (2 Z) apart (0.5,
45 deg), 4 a single block (0.5, 45 deg). The milling sequence lasts N_Q = 2 H_ice revolutions
(H_ice in m, a number of revolutions), Z N_Q blade impacts. The torque acts against the
propeller's rotation.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.errors import InputError, did_you_mean

__all__ = [
    "ICE_CASES",
    "ICE_THICKNESS",
    "design_ice_torque",
    "ice_torque",
    "milling_revolutions",
]

ICE_THICKNESS: dict[str, float] = {
    "IA Super": 1.75,
    "IA": 1.5,
    "IB": 1.2,
    "IC": 1.0,
    "PC1": 4.0,
    "PC2": 3.5,
    "PC3": 3.0,
    "PC4": 2.5,
    "PC5": 2.0,
    "PC6": 1.75,
    "PC7": 1.5,
}
"""H_ice (m) of every ice class: the Finnish-Swedish classes and IACS UR I3's Polar classes
(module docstring)."""

ICE_CASES: dict[int, tuple[float, float, int]] = {
    1: (0.75, 90.0, 1),
    2: (1.0, 135.0, 1),
    3: (0.5, 45.0, 2),
    4: (0.5, 45.0, 1),
}
"""case -> (C_q, alpha_i (deg), ice blocks): the torque excitation's cases (module docstring)."""


def _positive(name: str, value: float) -> float:
    v = float(value)
    if not (math.isfinite(v) and v > 0.0):
        raise InputError("must be a positive number", key=name, value=value)
    return v


def ice_thickness(ice_class: str) -> float:
    """H_ice (m) of an ice class (:data:`ICE_THICKNESS`).

    Parameters
    ----------
    ice_class : str
        ``"IA Super"``, ``"IA"``, ``"IB"``, ``"IC"`` or ``"PC1"`` ... ``"PC7"``.

    Returns
    -------
    float
        H_ice (m).

    Raises
    ------
    InputError
        For an unknown class (key ``ice_class``, with the nearest).

    Examples
    --------
    >>> ice_thickness("IA")
    1.5
    """
    if ice_class not in ICE_THICKNESS:
        raise InputError(
            f"expected one of {', '.join(ICE_THICKNESS)}{did_you_mean(ice_class, ICE_THICKNESS)}",
            key="ice_class",
            value=ice_class,
        )
    return ICE_THICKNESS[ice_class]


def design_ice_torque(
    *,
    diameter: float,
    hub_diameter: float,
    pitch: float,
    thickness: float,
    speed: float,
    ice_thickness: float,
    ducted: bool = False,
) -> float:
    """The design ice torque Q_max on the propeller (module docstring).

    Parameters
    ----------
    diameter : float
        D, the propeller diameter (m), > 0.
    hub_diameter : float
        d, the hub diameter (m), 0 <= d < D.
    pitch : float
        P_0.7, the pitch at 0.7 R (m), > 0.
    thickness : float
        t_0.7, the blade's maximum thickness at 0.7 R (m), > 0.
    speed : float
        n, the propeller speed at the bollard condition (rad/s), > 0.
    ice_thickness : float
        H_ice (m), > 0 (:data:`ICE_THICKNESS`).
    ducted : bool
        A ducted propeller (factors 7.7 and 14.6) instead of an open one (10.9 and 20.7).

    Returns
    -------
    float
        Q_max (N m).

    Raises
    ------
    InputError
        For a value that is not positive or a hub not smaller than the propeller, naming the
        key.

    Examples
    --------
    An open propeller, D = 4 m, d = 1.2 m, P_0.7 = 3.2 m, t_0.7 = 0.08 m, 120 rpm, class IA
    (D <= D_limit = 2.7 m does not hold: the second formula):

    >>> q = design_ice_torque(diameter=4.0, hub_diameter=1.2, pitch=3.2, thickness=0.08,
    ...                       speed=120 * 2 * np.pi / 60, ice_thickness=1.5)
    >>> round(q / 1e3, 3)  # kN m
    41.431
    """
    d_ = _positive("diameter", diameter)
    hub = float(hub_diameter)
    if not (math.isfinite(hub) and 0.0 <= hub < d_):
        raise InputError(
            "the hub diameter must lie between 0 and the propeller's",
            key="hub_diameter",
            value=hub_diameter,
        )
    p = _positive("pitch", pitch)
    t = _positive("thickness", thickness)
    n = _positive("speed", speed) / (2.0 * math.pi)  # rev/s
    h = _positive("ice_thickness", ice_thickness)
    common = (1.0 - hub / d_) * (p / d_) ** 0.16 * (t / d_) ** 0.6 * (n * d_) ** 0.17
    if d_ <= 1.8 * h:
        q = (7.7 if ducted else 10.9) * common * d_**3
    else:
        q = (14.6 if ducted else 20.7) * common * d_**1.9 * h**1.1
    return q * 1e3


def milling_revolutions(ice_thickness: float) -> float:
    """N_Q = 2 H_ice, the propeller revolutions of the milling sequence (H_ice in m; module
    docstring).

    Parameters
    ----------
    ice_thickness : float
        H_ice (m), > 0.

    Returns
    -------
    float
        N_Q (revolutions).

    Examples
    --------
    >>> milling_revolutions(1.5)
    3.0
    """
    return 2.0 * _positive("ice_thickness", ice_thickness)


def ice_torque(
    angle: ArrayLike, *, q_max: float, case: int, blades: int, revolutions: float
) -> NDArray[np.float64]:
    """The ice torque against the rotation at propeller angles ``angle`` (module docstring):
    the blades' half-sine impacts, 360 / Z apart, during ``revolutions`` revolutions.

    Parameters
    ----------
    angle : array_like
        phi, the propeller's rotation since the first impact (rad); 0 before it (phi < 0).
    q_max : float
        Q_max (N m), > 0 (:func:`design_ice_torque`).
    case : {1, 2, 3, 4}
        The excitation case (:data:`ICE_CASES`).
    blades : int
        Z, the number of blades, >= 1.
    revolutions : float
        N_Q, the revolutions of the sequence (:func:`milling_revolutions`), > 0: a blade's
        impact that starts within them is completed.

    Returns
    -------
    numpy.ndarray
        The torque (N m), >= 0, against the rotation, the shape of ``angle``.

    Raises
    ------
    InputError
        For an unknown case, a number of blades below 1, or a torque or number of revolutions
        that is not positive.

    Examples
    --------
    Case 1, 4 blades: each blade's impact peaks at 45 deg of its passage, 0.75 Q_max.

    >>> q = ice_torque(np.radians([45.0, 90.0, 135.0]), q_max=100.0, case=1, blades=4,
    ...                revolutions=3.0)
    >>> np.round(q, 9).tolist()  # at 90 deg the second blade starts
    [75.0, 0.0, 75.0]
    """
    if case not in ICE_CASES:
        raise InputError("expected an ice case 1, 2, 3 or 4", key="case", value=case)
    if isinstance(blades, bool) or int(blades) != blades or blades < 1:
        raise InputError("expected a whole number of blades from 1", key="blades", value=blades)
    qm = _positive("q_max", q_max)
    nq = _positive("revolutions", revolutions)
    cq, alpha, blocks = ICE_CASES[case]
    z = int(blades)
    phi = np.degrees(np.asarray(angle, dtype=float))
    out = np.zeros(phi.shape)
    shifts = [0.0] if blocks == 1 else [0.0, 360.0 / (2.0 * z)]
    for k in range(z):
        for s in shifts:
            local = phi - k * 360.0 / z - s  # this blade-block's rotation since its first impact
            start = np.floor(local / 360.0) * 360.0  # the start of its current passage
            within = local - start
            first = start + k * 360.0 / z + s  # the passage's start on the propeller
            active = (local >= 0.0) & (first < nq * 360.0) & (within <= alpha)
            out += np.where(active, cq * qm * np.sin(np.radians(within * 180.0 / alpha)), 0.0)
    return out
