"""Plots of crankdyn results: functions that take a result and return a matplotlib Figure.

Figures are created with :class:`matplotlib.figure.Figure` directly (no pyplot state, nothing is
shown); save them with ``fig.savefig(...)`` or let a notebook display them.
"""
