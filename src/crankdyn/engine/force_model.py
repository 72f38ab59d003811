"""Optional forces on the crank train beside the gas and inertia forces (domain object and
numeric core): the weights of the moving parts and the piston's friction.

Seed 000 section 2 lists the forces acting on the crank mechanism: the gas force, the inertia
forces, **gravity**, the reaction torque of the load with the supports' reactions, and the
**friction** of the relative motion. crankdyn's forces (:mod:`crankdyn.engine.forces`) take the
gas and inertia forces always, and these two when the engine file's ``[forces]`` table asks for
them (both off by default: at running speed they are small beside the others, which is why the
seed's analysis leaves them out):

- **Gravity** (g = 9.80665 m/s^2, the standard acceleration of gravity, CGPM 1901). The engine
  frame has "up" as the vertical (docs/conventions.md): a cylinder's axis leans alpha from it
  (its bank angle), its crank points chi = alpha + phi from it. The reciprocating mass's weight
  has the component m_j g cos(alpha) along the cylinder axis toward the crank (it adds to P; its
  component across the axis, m_j g sin(alpha), bears on the liner directly and does not reach
  the crank); the rotating mass's weight m_r g, at the crank radius, has the tangential
  component m_r g sin(chi) in the direction of rotation and the radial component m_r g cos(chi)
  toward the crank centre, which add to T and Z. Together they are the torque -dV/dtheta of the
  parts' potential energy V = g sum (m_j y_piston + m_r y_crank) (tested so).
- **Piston friction** as a stated model (Coulomb friction, off by default): the ring pack
  presses with a constant force F_ring, and the skirt slides with the coefficient mu on the
  piston's side force N; the friction force opposes the piston's velocity,
  F_f = -sgn(v) (F_ring + mu |N|), v = R w sin(phi + beta)/cos(beta). (Ring-pack and skirt
  friction are the piston assembly's two parts in J. B. Heywood, *Internal Combustion Engine
  Fundamentals*, McGraw-Hill 1988, ch. 13.5; Coulomb's law is their boundary-lubrication
  limit.) As N = P tan(beta) depends on P = P_0 + F_f, the force is solved exactly: with
  s = sgn(v) and c = mu |tan(beta)| < 1, P = (P_0 - s F_ring) / (1 + s c sgn(P_0 - s F_ring)).
  Bearing friction is not modelled (the crank's bearings are not part of this model).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.crank.geometry import check_finite
from crankdyn.errors import InputError

__all__ = ["ForceModel", "G", "piston_force_with_friction"]

G = 9.80665
"""Standard acceleration of gravity (m/s^2; 3rd CGPM, 1901)."""


@dataclass(frozen=True)
class ForceModel:
    """Which optional forces act on the crank train (the engine file's ``[forces]``; module
    docstring).

    Parameters
    ----------
    gravity : bool
        Whether the moving parts' weights act (default False).
    ring_friction : float
        The ring pack's Coulomb friction force F_ring (N, >= 0; default 0).
    skirt_friction : float
        The skirt's Coulomb coefficient mu on the side force (dimensionless, 0 <= mu < 1;
        default 0).

    Raises
    ------
    InputError
        A negative friction force, or mu outside [0, 1).

    Examples
    --------
    >>> ForceModel(gravity=True).active, ForceModel().active
    (True, False)
    """

    gravity: bool = False
    ring_friction: float = 0.0
    skirt_friction: float = 0.0

    def __post_init__(self) -> None:
        ring = check_finite("ring_friction", self.ring_friction)
        if ring < 0.0:
            raise InputError("a friction force must not be negative", key="ring_friction",
                             value=self.ring_friction)  # fmt: skip
        mu = check_finite("skirt_friction", self.skirt_friction)
        if not 0.0 <= mu < 1.0:
            raise InputError("the skirt's friction coefficient must lie in [0, 1)",
                             key="skirt_friction", value=self.skirt_friction)  # fmt: skip
        object.__setattr__(self, "ring_friction", ring)
        object.__setattr__(self, "skirt_friction", mu)

    @property
    def friction(self) -> bool:
        """Whether the piston's friction acts."""
        return self.ring_friction > 0.0 or self.skirt_friction > 0.0

    @property
    def active(self) -> bool:
        """Whether any optional force acts."""
        return self.gravity or self.friction

    def describe(self) -> str:
        """What acts, for notes (``"gravity; piston friction (F_ring = 40 N, mu = 0.05)"``).

        Returns
        -------
        str
            The description, or ``""``.
        """
        parts = ["gravity"] if self.gravity else []
        if self.friction:
            parts.append(
                f"piston friction (F_ring = {self.ring_friction:g} N, μ = {self.skirt_friction:g})"
            )
        return "; ".join(parts)


def piston_force_with_friction(
    p0: ArrayLike,
    sin_phi_beta: ArrayLike,
    tan_beta: ArrayLike,
    ring: float,
    mu: float,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The force along the cylinder axis with the piston's friction, solved exactly (module
    docstring): P = P_0 + F_f with F_f = -sgn(v) (F_ring + mu |P tan(beta)|).

    Parameters
    ----------
    p0 : array_like
        The axial force without friction P_0 (N, positive toward the crank).
    sin_phi_beta : array_like
        sin(phi + beta), whose sign is the piston velocity's (v = R w sin(phi + beta) /
        cos(beta), positive toward the crank).
    tan_beta : array_like
        tan(beta) (dimensionless).
    ring : float
        F_ring (N).
    mu : float
        The skirt's coefficient (dimensionless, < 1).

    Returns
    -------
    piston : numpy.ndarray
        P (N).
    friction : numpy.ndarray
        F_f (N).

    Examples
    --------
    Moving toward the crank (s = 1) with P_0 = 1000 N, F_ring = 50 N, mu = 0.1, tan(beta) = 0.25:
    P = 950 / 1.025 = 926.829 N; check: F_f = -(50 + 0.1 x 926.829 x 0.25) = -73.171 N.

    >>> p, f = piston_force_with_friction(1000.0, 1.0, 0.25, 50.0, 0.1)
    >>> round(float(p), 3), round(float(f), 3)
    (926.829, -73.171)
    """
    p0 = np.asarray(p0, dtype=float)
    s = np.sign(np.asarray(sin_phi_beta, dtype=float))
    c = mu * np.abs(np.asarray(tan_beta, dtype=float))
    q = p0 - s * ring
    piston = q / (1.0 + s * c * np.sign(q))
    return piston, piston - p0
