"""The rules a society states of the installation as a whole rather than of a component's
response (analysis): where the major criticals of the one-node mode may lie (KR 2025 Pt 5 Ch 4
204), and the notes on what the society asks to be calculated that the TVC did not (misfire,
controllable-pitch propellers, the calculation's upper speed; docs/tvc.md, "Rule sets").

Both are evaluated here once for every front end: the rows join the normal-firing condition's
verdicts in ``crankdyn tvc`` (:func:`crankdyn.tvc.tvc`) and in ``crankdyn torsion response``
(:func:`crankdyn.tvc.analysis.judge`, :meth:`crankdyn.session.Analysis.judged`), so the two
commands give the same rows.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from crankdyn.constants import RPM
from crankdyn.summary import Verdict
from crankdyn.tvc.rulesets import cite_row, cpp_conditions

if TYPE_CHECKING:
    from crankdyn.engine.model import Engine
    from crankdyn.torsion.model import TorsionModel
    from crankdyn.tvc.spec import TvcSpec

__all__ = ["application", "installation_verdicts", "major_orders", "rule_notes"]


def application(load: str) -> str:
    """The rule sets' application of an installation by its load law: ``"propulsion"`` for the
    propeller law, ``"generator"`` for constant speed (a generating set).

    Parameters
    ----------
    load : str
        The load law (:data:`crankdyn.tvc.spec.LOADS`).

    Returns
    -------
    str
        ``"propulsion"`` or ``"generator"``.

    Examples
    --------
    >>> application("propeller"), application("constant-speed")
    ('propulsion', 'generator')
    """
    return "generator" if load == "constant-speed" else "propulsion"


def major_orders(cylinders: int, cycle: str) -> tuple[float, ...]:
    """The major orders of an in-line engine's one-node mode the rules name: the n-th and
    n/2-th for a four-stroke engine, the n-th for a two-stroke engine (n cylinders; KR 2025
    Pt 5 Ch 4 204).

    Parameters
    ----------
    cylinders : int
        The number of cylinders n.
    cycle : str
        ``"four-stroke"`` or ``"two-stroke"``.

    Returns
    -------
    tuple of float
        The orders (multiples of the crankshaft speed), increasing.

    Examples
    --------
    >>> major_orders(6, "four-stroke"), major_orders(5, "two-stroke")
    ((3.0, 6.0), (5.0,))
    """
    n = float(cylinders)
    return (n / 2.0, n) if cycle == "four-stroke" else (n,)


def _one_node_frequency(model: TorsionModel) -> float | None:
    """The natural frequency (rad/s) of the model's lowest mode with one node, or None."""
    from crankdyn.torsion.modal import natural_modes

    modes = natural_modes(model)
    ones = np.flatnonzero((np.asarray(modes.node_count) == 1) & (modes.natural_frequency > 0.0))
    return float(modes.natural_frequency[ones[0]]) if ones.size else None


def installation_verdicts(
    model: TorsionModel,
    spec: TvcSpec,
    rated: float,
    *,
    engine: Engine | None = None,
    load: str = "propeller",
    condition: str = "normal firing",
) -> list[Verdict]:
    """The rows of the rules on the installation as a whole: every major critical of the
    one-node mode against the society's window of speed ratios where none may lie (KR 2025
    Pt 5 Ch 4 204: 0.8 <= lambda <= 1.1 for propulsion, 0.9 <= lambda <= 1.1 for generating
    sets, "except when an approval is specifically obtained"), for an in-line engine (a vee
    engine: no row). None where the rule set states no window or the model has no cylinders.

    The critical speed of order q is n_c = omega_1 / q (omega_1 the one-node mode's natural
    frequency, rad/s; speeds of the model's reference shaft, the crankshaft's), lambda_c =
    n_c / n_0. A row passes where lambda_c lies outside the window; its ``limit`` is the
    window's nearer end, its margin the distance outside the window over that end (negative
    inside).

    Parameters
    ----------
    model : TorsionModel
        The installation.
    spec : TvcSpec
        The settings (the rule set).
    rated : float
        n_0 (rad/s).
    engine : Engine or None
        The engine (its number of cylinders, cycle and layout); None: the model's cylinders
        and its ``[excitation]`` cycle, an in-line engine assumed.
    load : str
        The load law (:func:`application`).
    condition : str
        The condition's name, for the rows.

    Returns
    -------
    list of crankdyn.summary.Verdict
        One row per major order.

    Examples
    --------
    A two-mass line, J = 1 and 3 kg m^2 on k = 1e5 N m/rad: omega_1 = sqrt(k (1/1 + 1/3))
    = 365.148 rad/s; one four-stroke cylinder on the first mass (majors 0.5 and 1),
    n_0 = 400 rad/s under KR: order 1 at lambda = 0.913 lies in 0.8-1.1:

    >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
    >>> from crankdyn.tvc.spec import TvcSpec
    >>> model = TorsionModel((Mass("a", 1.0, cylinders=(1,)), Mass("b", 3.0)),
    ...                      (Shaft(("a", "b"), stiffness=1e5),))
    >>> rows = installation_verdicts(model, TvcSpec(rules="kr"), 400.0)
    >>> [(round(v.worst, 4), v.passed) for v in rows]
    [(1.8257, True), (0.9129, False)]
    >>> installation_verdicts(model, TvcSpec(rules="iacs-m68"), 400.0)
    []
    """
    society = spec.ruleset
    cited = society.major_criticals.get(application(load))
    cylinders = len(model.cylinder_dofs)
    if cited is None or cylinders == 0:
        return []
    if engine is not None:
        count, cycle = engine.cylinders.count, engine.cylinders.cycle
        if engine.cylinders.layout != "inline":
            return []
    else:
        exc = getattr(model, "excitation", None)
        count, cycle = cylinders, str(getattr(exc, "cycle", "four-stroke"))
    omega = _one_node_frequency(model)
    if omega is None:
        return []
    low, high = cited.value
    source, clause = cite_row([("major criticals", cited.clause)])
    rows = []
    for q in major_orders(count, cycle):
        nc = omega / q
        lam = nc / rated
        inside = low <= lam <= high
        edge = low if abs(lam - low) <= abs(lam - high) else high
        margin = (low - lam) / low if lam < low else (lam - high) / high
        if inside:
            margin = -min(lam - low, high - lam) / edge
        rows.append(
            Verdict(
                component=f"one-node mode ({omega / (2 * np.pi):.4g} Hz)",
                condition=condition,
                quantity=f"major critical of order {q:g} at {nc * RPM:.1f} rpm (λ = n_c/n_0) "
                f"outside {low:g}-{high:g}",
                worst=float(lam),
                limit=float(edge),
                unit="",
                passed=not inside,
                source=f"{source}: no major critical of the one-node mode of an in-line "
                f"engine within {low:g} ≤ λ ≤ {high:g} ({application(load)})",
                clause=clause,
                speed=float(nc),
                note="unless specifically approved by the Society" if inside else "",
                margin=float(margin),
                kind=f"major critical order {q:g}",
            )
        )
    return rows


def rule_notes(
    spec: TvcSpec,
    *,
    rated: float,
    high: float,
    misfire: bool,
    propeller: bool,
) -> list[str]:
    """What the society asks to be calculated that the calculation did not do, each with its
    clause: a misfiring cylinder (KR 2025 Pt 5 Ch 4 102.1(4), 206.1(3)), the full and zero pitch
    of a controllable-pitch propeller (206.1(2): crankdyn calculates the model's propeller law,
    full pitch), the speed range up to the rule's upper ratio (102.1(2): 1.2 n_0); and how
    many values of the rule set could not be verified against its text.

    Parameters
    ----------
    spec : TvcSpec
        The settings (the rule set).
    rated : float
        n_0 (rad/s).
    high : float
        The highest speed calculated (rad/s).
    misfire : bool
        Whether a misfiring cylinder was calculated.
    propeller : bool
        Whether the installation drives a propeller.

    Returns
    -------
    list of str
        The notes.

    Examples
    --------
    >>> from crankdyn.tvc.spec import TvcSpec
    >>> notes = rule_notes(TvcSpec(rules="kr"), rated=100.0, high=105.0, misfire=True,
    ...                    propeller=False)
    >>> notes[0][:60]
    'Korean Register (KR) asks for the calculation up to 1.2 n_0 '
    >>> rule_notes(TvcSpec(rules="kr"), rated=100.0, high=125.0, misfire=True, propeller=False)
    []
    """
    society = spec.ruleset
    notes = []
    upper = society.calculation_upper.value
    if upper is not None and high < upper * rated * (1.0 - 1e-9):
        notes.append(
            f"{society.title} asks for the calculation up to {upper:g} n_0 = "
            f"{upper * rated * RPM:.1f} rpm ({society.calculation_upper.clause.cite()}); the "
            f"speeds calculated end at {high * RPM:.1f} rpm: give [tvc] speed_range"
        )
    if society.misfire.value and not misfire:
        notes.append(
            f"{society.title} asks for a misfiring cylinder to be calculated "
            f"({society.misfire.clause.cite()}); it was not"
        )
    pitches = cpp_conditions(society)
    if pitches and propeller:
        notes.append(
            f"{society.title} asks for a controllable-pitch propeller to be calculated at "
            f"{' and '.join(pitches)} ({society.cpp.clause.cite()}): crankdyn calculates the "
            "model's propeller law (full pitch); for a controllable-pitch propeller, calculate "
            "zero pitch as a model whose propeller load and excitation are those at zero pitch"
        )
    missing = [name for name, c in society.clauses() if not c.verified]
    if missing:
        notes.append(
            f"{len(missing)} values of {society.title}'s rule set could not be verified "
            "against its text; the rows citing them say so (crankdyn docs tvc, 'Rule sets')"
        )
    return notes
