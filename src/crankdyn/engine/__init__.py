"""The multi-cylinder engine: the domain model (:class:`Engine`, :class:`Cylinders`), firing
orders and their search, forces, bearing loads, torque, balance and the flywheel."""

from crankdyn.engine.model import Cylinders, Engine

__all__ = ["Cylinders", "Engine"]
