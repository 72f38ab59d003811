"""Measured torsional vibration: torsiograph signals, angle-domain order analysis, and the model
held against the measurement (docs/measurement.md).

- :mod:`crankdyn.measure.signals`: pulse trains (toothed wheel, encoder) and speed signals; gap
  and reference checks and repairs;
- :mod:`crankdyn.measure.angle`: mean rotation, angular vibration at equal crank angles, tooth
  corrections (numeric core);
- :mod:`crankdyn.measure.orders`: orders at a steady speed and order tracking over a run-up;
- :mod:`crankdyn.measure.resonance`: resolved peaks, half-power bandwidth, single-mode fit;
- :mod:`crankdyn.measure.compare`: the model's forced response beside the measurement, peaks
  compared, damping written back;
- :mod:`crankdyn.measure.synthetic` and :mod:`crankdyn.measure.examples`: signals from a
  prescribed motion, the built-in simulated records.
"""

from crankdyn.measure.orders import OrderSpectrum, OrderTracking, order_analysis
from crankdyn.measure.signals import PulseTrain, SpeedSignal

__all__ = ["OrderSpectrum", "OrderTracking", "PulseTrain", "SpeedSignal", "order_analysis"]
