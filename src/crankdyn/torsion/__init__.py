"""Crankshaft torsional vibration: lumped models and free vibration.

- :mod:`crankdyn.torsion.model`: the lumped model (masses, shafts, gears, ends) and its matrices;
- :mod:`crankdyn.torsion.equivalent`: the equivalent system of an engine's crank throws;
- :mod:`crankdyn.torsion.modal`: natural frequencies and mode shapes (structured eigen solver);
- :mod:`crankdyn.torsion.holzer`: Holzer's method (table, residual curve, frequencies);
- :mod:`crankdyn.torsion.transfer`: the transfer-matrix method for chains;
- :mod:`crankdyn.torsion.closed_form`: closed forms for one, two, three and N equal masses.
"""

from crankdyn.torsion.model import GROUND, Gear, Mass, Shaft, ShaftGeometry, TorsionModel

__all__ = ["GROUND", "Gear", "Mass", "Shaft", "ShaftGeometry", "TorsionModel"]
