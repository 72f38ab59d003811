"""Driving torque without joint reactions: Zhukovsky's lever / the principle of virtual power.

Seed 004 sec. 3.6 ("茹可夫斯基杠杆法"): with the inertia loads added (D'Alembert) the mechanism is
in equilibrium, so by the principle of virtual displacements sum_i P_i v_i cos(a_i) = 0 over all
loads. Zhukovsky's lever turns the velocity polygon through 90 deg and applies every force at the
image of its point: since the image of v is R90 v, the moment of P about the pole is
(R90 v) x P = -v . P, so the moments about the pole balance exactly when the powers do — the
rotated velocity polygon is a rigid lever in equilibrium. A couple M on a link turning at omega
contributes M omega (a pair of forces on the lever). The balancing torque M_b on the crank
(omega_1) therefore is

    M_b omega_1 + sum_links (P_G . v_G + M omega) + sum_forces (P . v_P) = 0          (1)

Velocities enter only as ratios, so crankdyn uses the velocity coefficients per unit crank speed
(omega_1 = 1): the method works for a crank at rest too (a quasi-static balance). Joint reactions
never appear, which makes this an independent check of the matrix method (:mod:`.kinetostatics`;
the two agree to round-off for a frictionless mechanism). Friction is not a load of the ideal
mechanism and is not included.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:  # pragma: no cover
    from crankdyn.linkage.kinetostatics import KnownLoads
    from crankdyn.linkage.motion import MechanismMotion

__all__ = ["lever_moments", "virtual_power_driving_torque"]


def lever_moments(loads: KnownLoads) -> NDArray[np.float64]:
    """Moments of the known loads about the pole of Zhukovsky's lever (seed 004 sec. 3.6).

    For a force component, the moment of the force placed at the image R90 v of its point's
    velocity; for a couple, -M omega.

    Parameters
    ----------
    loads : crankdyn.linkage.kinetostatics.KnownLoads
        The known loads and their virtual velocities.

    Returns
    -------
    numpy.ndarray
        (N, p) moments (N m per unit crank speed), minus the powers of the loads.
    """
    # For a force component P_x at a point with velocity (v_x, v_y), the lever image is
    # (-v_y, v_x) and its moment about the pole is (-v_y) P_y - v_x P_x; summed over the
    # x and y entries of one force this is -(v . P). A couple's entry holds omega in W.
    return -loads.W * loads.P


def virtual_power_driving_torque(
    motion: MechanismMotion, loads: KnownLoads
) -> tuple[NDArray[np.float64], NDArray[np.float64] | None]:
    """The balancing (driving) torque on the crank by virtual power, eq. (1).

    Parameters
    ----------
    motion : crankdyn.linkage.motion.MechanismMotion
        The mechanism's motion.
    loads : crankdyn.linkage.kinetostatics.KnownLoads
        The known loads (inertia, gravity, applied).

    Returns
    -------
    torque : numpy.ndarray
        (N,) M_b (N m).
    force : numpy.ndarray or None
        (N,) the balancing force (N) when the driver balances with a force at a crank point,
        else None.
    """
    mech = motion.mechanism
    total = np.sum(lever_moments(loads), axis=1)  # = -(power of the known loads) per unit speed
    crank_rate = motion.link_state(mech.crank, "qp")[:, 2]  # 1 by the driver constraint
    d = mech.driver
    if d.balancing_point is None:
        return total / crank_rate, None
    u = d.balancing_unit(motion.crank_angle)
    v = motion.point(d.balancing_point, link=mech.crank, which="qp")
    with np.errstate(divide="ignore", invalid="ignore"):
        force = total / np.sum(v * u, axis=1)
    pivot = motion.point(mech.joint(d.joint).point, link=mech.crank)
    arm = motion.point(d.balancing_point, link=mech.crank) - pivot
    return force * (arm[:, 0] * u[:, 1] - arm[:, 1] * u[:, 0]), force
