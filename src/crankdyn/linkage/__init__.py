"""Planar linkages: four-bar in closed form, general planar mechanisms, kinetostatics.

- :mod:`.fourbar` — Grashof class, limits, closed-form motion of the four-bar (vectorized).
- :mod:`.planar` — general mechanisms of revolute and prismatic joints, link groups; their parts
  in :mod:`.elements`; positions (closed form for dyads, :mod:`.dyads`, else Newton-Raphson with
  branch control), velocities and accelerations from the constraint Jacobian in :mod:`.solver`;
  the motion and its kinematics result in :mod:`.motion`.
- :mod:`.kinetostatics` — inertia loads and the matrix method [C]{R} = [D]{P} (seed 004).
- :mod:`.virtual_power` — Zhukovsky's lever / virtual power: the driving torque without
  reactions.
- :mod:`.friction` — friction circles and Coulomb friction, efficiency.
"""

from crankdyn.linkage.elements import Driver, Force, Joint, Link, Torque
from crankdyn.linkage.fourbar import (
    FourBar,
    FourBarResult,
    fourbar_analysis,
    fourbar_mechanism,
    grashof_type,
)
from crankdyn.linkage.kinetostatics import KinetostaticsResult, kinetostatics
from crankdyn.linkage.motion import MechanismMotion
from crankdyn.linkage.planar import Mechanism, slider_crank_mechanism

__all__ = [
    "Driver",
    "Force",
    "FourBar",
    "FourBarResult",
    "Joint",
    "KinetostaticsResult",
    "Link",
    "Mechanism",
    "MechanismMotion",
    "Torque",
    "fourbar_analysis",
    "fourbar_mechanism",
    "grashof_type",
    "kinetostatics",
    "slider_crank_mechanism",
]
