"""Sensitivity of the figures to the parameters, from the finished cases (numeric core).

Two measures, both model-free and cheap enough for any number of cases:

- **main effect** of a parameter on a figure: the mean of the figure over the cases at each
  level of the parameter (its grid values; for a parameter with many distinct values, e.g. a
  Monte Carlo draw, over ``bins`` equal-count bins of its values), and the range of those means
  (largest minus smallest): the one-factor-at-a-time average effect of a full factorial design
  (Montgomery, *Design and Analysis of Experiments*, 8th ed., Wiley 2013, section 5.3, "main
  effects"), which for a Monte Carlo study becomes a binned estimate of the first-order effect
  E[Y | X] (Saltelli et al., *Global Sensitivity Analysis: The Primer*, Wiley 2008, section 1.2);
- **Spearman's rank correlation** rho between a numeric parameter and a figure (the Pearson
  correlation of their ranks, ties given their average rank; Saltelli et al. 2008 section 1.2.5),
  +1 or -1 for any monotone relation, near 0 for none or a non-monotone one.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "NEGLIGIBLE",
    "MainEffect",
    "average_ranks",
    "main_effect",
    "negligible_spread",
    "spearman",
]

MAX_LEVELS = 12
NEGLIGIBLE = 1e-6


def negligible_spread(values) -> bool:
    """Whether the finite values (at least two) differ by at most :data:`NEGLIGIBLE` of their
    largest magnitude: round-off, not an effect (a figure the parameters do not change, such as
    the mean torque of the synthetic pressure model at a fixed IMEP when the rod length varies);
    summaries report such a figure as the same in every case."""
    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v)]
    if v.size < 2:
        return False
    return float(v.max() - v.min()) <= NEGLIGIBLE * float(np.abs(v).max())


def average_ranks(values) -> np.ndarray:
    """Ranks 1..n of the values, tied values sharing the mean of their ranks (the "average"
    method of ``scipy.stats.rankdata``)."""
    v = np.asarray(values, dtype=float)
    order = np.argsort(v, kind="stable")
    sorted_v = v[order]
    # start of each run of equal values
    new = np.concatenate(([True], sorted_v[1:] != sorted_v[:-1]))
    run = np.cumsum(new) - 1
    starts = np.flatnonzero(new)
    ends = np.append(starts[1:], v.size)
    mean_rank = (starts + ends + 1) / 2.0  # ranks start+1 .. end, their mean
    ranks = np.empty(v.size)
    ranks[order] = mean_rank[run]
    return ranks


def spearman(x, y) -> float:
    """Spearman's rank correlation of two equal-length samples (NaN pairs dropped); NaN when
    fewer than 3 pairs remain or either sample is constant."""
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    keep = np.isfinite(x) & np.isfinite(y)
    if keep.sum() < 3:
        return math.nan
    rx, ry = average_ranks(x[keep]), average_ranks(y[keep])
    rx -= rx.mean()
    ry -= ry.mean()
    denominator = math.sqrt(float(np.dot(rx, rx)) * float(np.dot(ry, ry)))
    if denominator == 0.0:
        return math.nan
    return float(np.dot(rx, ry)) / denominator


class MainEffect:
    """Levels of a parameter and the mean of a figure at each (see the module docstring).

    Attributes
    ----------
    levels
        Level labels: the parameter's values (numbers or text), or for binned parameters the
        mean parameter value of each bin.
    means, counts
        Mean of the figure and number of cases per level (levels without a finite figure are
        left out).
    binned
        Whether the levels are bins of a continuous parameter.
    """

    def __init__(self, levels, means, counts, binned: bool):
        self.levels = levels
        self.means = np.asarray(means, dtype=float)
        self.counts = np.asarray(counts, dtype=int)
        self.binned = binned

    @property
    def effect(self) -> float:
        """Range of the level means (the figure's unit); NaN with fewer than two levels."""
        if self.means.size < 2:
            return math.nan
        return float(self.means.max() - self.means.min())


def main_effect(x, y, *, numeric: bool, bins: int = 5) -> MainEffect:
    """The main effect of parameter values ``x`` on figure values ``y`` (module docstring).

    Numeric parameters with more than :data:`MAX_LEVELS` distinct values are grouped into
    ``bins`` bins of (nearly) equal count by rank."""
    y = np.asarray(y, dtype=float)
    ok = np.isfinite(y)
    if numeric:
        xv = np.asarray(x, dtype=float)
        ok &= np.isfinite(xv)
        xv, yv = xv[ok], y[ok]
        distinct = np.unique(xv)
        if distinct.size <= MAX_LEVELS:
            means = [float(yv[xv == level].mean()) for level in distinct]
            counts = [int((xv == level).sum()) for level in distinct]
            return MainEffect(distinct, means, counts, binned=False)
        order = np.argsort(xv, kind="stable")
        groups = np.array_split(order, min(bins, xv.size))
        levels = np.array([xv[g].mean() for g in groups])
        means = [float(yv[g].mean()) for g in groups]
        return MainEffect(levels, means, [g.size for g in groups], binned=True)
    labels = np.asarray(x, dtype=object)[ok]
    yv = y[ok]
    seen: list = []
    for label in labels:
        if label not in seen:
            seen.append(label)
    means = [float(yv[labels == level].mean()) for level in seen]
    counts = [int((labels == level).sum()) for level in seen]
    return MainEffect(np.array(seen, dtype=object), means, counts, binned=False)
