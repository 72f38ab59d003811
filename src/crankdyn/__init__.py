"""crankdyn: dynamics of crank mechanisms."""

__version__ = "0.1.0"
