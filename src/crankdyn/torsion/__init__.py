"""Crankshaft torsional vibration: lumped models, free and forced vibration.

- :mod:`crankdyn.torsion.model`: the lumped model (masses, shafts, gears, ends) and its matrices;
- :mod:`crankdyn.torsion.equivalent`: the equivalent system of an engine's crank throws;
- :mod:`crankdyn.torsion.modal`: natural frequencies and mode shapes (structured eigen solver);
- :mod:`crankdyn.torsion.holzer`: Holzer's method (table, residual curve, frequencies);
- :mod:`crankdyn.torsion.transfer`: the transfer-matrix method for chains;
- :mod:`crankdyn.torsion.closed_form`: closed forms for one, two, three and N equal masses.
- :mod:`crankdyn.torsion.excitation`: engine excitation, harmonic analysis, major orders;
- :mod:`crankdyn.torsion.sweep`: steady-state forced response over a speed range, resolved;
- :mod:`crankdyn.torsion.solvers`: the linear system and its batched (chain) solves;
- :mod:`crankdyn.torsion.response`: the forced response's result (peaks, relative angles);
- :mod:`crankdyn.torsion.dampers`: viscous and tuned dampers, Den Hartog's optima;
- :mod:`crankdyn.torsion.campbell`: critical speeds and the Campbell diagram;
- :mod:`crankdyn.torsion.rules`: permissible stresses after IACS UR M68;
- :mod:`crankdyn.torsion.transient`: time-domain response (constant speed, run-up);
- :mod:`crankdyn.torsion.coupling`: elastic couplings from catalogue data;
- :mod:`crankdyn.torsion.distributed`: distributed-mass shafts by subdivision;
- :mod:`crankdyn.torsion.sources`: excitation at any mass and order (propellers, electric
  machines, tables, further engines) and the mean torque along the line;
- :mod:`crankdyn.torsion.driveline`: engines joined to shaft lines;
- :mod:`crankdyn.torsion.damped`: damped (complex) modes and modal damping;
- :mod:`crankdyn.torsion.opentorsion`: conversion to and from openTorsion assemblies.
"""

from crankdyn.torsion.coupling import Coupling
from crankdyn.torsion.elements import GROUND, Gear, Mass, MassLimits, Shaft, ShaftGeometry
from crankdyn.torsion.model import TorsionModel

__all__ = [
    "GROUND",
    "Coupling",
    "Gear",
    "Mass",
    "MassLimits",
    "Shaft",
    "ShaftGeometry",
    "TorsionModel",
]
