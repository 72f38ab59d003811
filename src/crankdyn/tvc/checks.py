"""The checks of an installation: every component quantity against its limit, made by a table of
check kinds (:data:`CHECK_KINDS`), one small object per kind of component (analysis).

A :class:`Check` is one component quantity (a curve of a forced response) against its
continuous limit, with the transient limit that governs a barred range where the rule permits
one. :func:`model_checks` asks every kind in :data:`CHECK_KINDS` for the checks of a model:

- :class:`M68Shafts`: propulsion shafts against the selected rule set's tau_C and tau_T (the IACS
  UR M68.4 form; C_K from the society's table, C_D, sigma_B capped by the society's cap for the
  material and shaft kind: :mod:`crankdyn.tvc.rulesets`), grouped by the shaft a subdivided
  element belongs to;
- :class:`CrankSpans`: crank spans against the engine builder's permissible vibratory stress or
  torque (``[tvc.crankshaft]``), else against the society's own crankshaft limits where its
  text states them (KR 2025 Pt 5 Ch 4 201 for main engines, 203.1 for generating sets);
- :class:`GeneratorShafts`: the shaft of a generating set's alternator against the society's
  generator-shaft limits where its text states them (KR 2025 Pt 5 Ch 4 203.2);
- :class:`Couplings`: elastic couplings against T_KW (and T_Kmax for a barred range), P_KV and
  T_KN (DIN 740-2, the maker's catalogue);
- :class:`GearHammering`: gear meshes against gear hammering (the vibratory torque at the mesh
  above the mean transmitted torque reverses the tooth load);
- :class:`MachineLimits`: generators and other machines against the maker's vibratory torque,
  angular acceleration and amplitude;
- :class:`DamperHeat`: dampers against the maker's permissible heat load.

Every value a rule gives comes from the rule set selected by ``[tvc] rules`` (``--rules``), and
every check cites it: ``source`` (the rule text and its edition, and how the limit was found)
and ``clause`` (each clause with what it gives, "not verified against the text: value as ..."
where the clause could not be read; :func:`crankdyn.tvc.rulesets.cite_row`). Every front end
(``crankdyn torsion response``, ``crankdyn tvc``, the report) judges a response with these checks
through :func:`crankdyn.tvc.evaluate.evaluate_condition`: one rule, one place. A new kind of
check is one class here, added to :data:`CHECK_KINDS`.

Transient events (:mod:`crankdyn.tvc.events`) are judged by the same checks: a check that
applies to a transient carries an :class:`EventReading` (which elements of the run it reads,
how, and its limits at the speed of the peak and the event's severity), which
:func:`crankdyn.tvc.evaluate.evaluate_event` evaluates: the shafts' vibratory stress against
tau_T, the crank spans' against the builder's transient limit, the couplings' torque against
T_Kmax and T_Kmax1 (normal events) or T_Kmax2 (exceptional ones), the gear meshes' torque
reversals.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, TypeAlias

import numpy as np
from numpy.typing import ArrayLike, NDArray

import crankdyn.tvc.curves as cv
from crankdyn.errors import InputError
from crankdyn.summary import Verdict
from crankdyn.torsion.rules import permissible_continuous, permissible_transient, size_factor
from crankdyn.tvc.rulesets import Clause, cite_row

if TYPE_CHECKING:
    from crankdyn.engine.model import Engine
    from crankdyn.torsion.dampers import Damper
    from crankdyn.torsion.model import Shaft, TorsionModel
    from crankdyn.torsion.response import ResponseResult
    from crankdyn.torsion.transient import TransientResult
    from crankdyn.tvc.result import BarredSpeedRange
    from crankdyn.tvc.spec import TvcSpec

    MeanTorque: TypeAlias = Callable[[ArrayLike], NDArray[np.float64]]
    Curve: TypeAlias = Callable[[ResponseResult], NDArray[np.float64]]
    Limit: TypeAlias = Callable[[NDArray[np.float64]], NDArray[np.float64]]
    TransientCurve: TypeAlias = Callable[[TransientResult, MeanTorque | None], NDArray[np.float64]]
    BarredRows: TypeAlias = Callable[[BarredSpeedRange], list[Verdict]]

__all__ = [
    "CHECK_KINDS",
    "Check",
    "CheckContext",
    "CheckKind",
    "Couplings",
    "CrankSpans",
    "DamperHeat",
    "EventLimit",
    "EventReading",
    "GearHammering",
    "GeneratorShafts",
    "M68Shafts",
    "MachineLimits",
    "mean_torque_function",
    "model_checks",
]


@dataclass(frozen=True)
class EventLimit:
    """One limit of a check in a transient event.

    Parameters
    ----------
    name : str
        Its name in the row (``"tau_T"``, ``"T_Kmax"``, ``"T_Kmax1"``).
    value : float
        The limit (the check's unit).
    source : str
        The rule or maker's document.
    clause : str
        Its clause, or ``""``.
    note : str
        Added to the row's note (e.g. how the speed ratio was taken).
    """

    name: str
    value: float
    source: str
    clause: str = ""
    note: str = ""


@dataclass(frozen=True)
class EventReading:
    """How a check reads the run of a transient event (:func:`crankdyn.tvc.evaluate.
    evaluate_event`).

    Parameters
    ----------
    elements : tuple
        The run's elements it reads: a model shaft's index (the run's element of the same
        index), or a rigid gear's (pinion, wheel).
    factors : tuple of float
        The factor on each element's torque (1/W_p for a nominal stress, K/W_p, or 1).
    vibratory : bool
        Whether the quantity is the vibratory torque (less the quasi-static torque of the mean
        torques: the rules' vibratory stress) instead of the whole torque.
    limits : callable or None
        ``limits(speed, severity)`` -> the limits (:class:`EventLimit`) at the reference speed
        of the peak (rad/s) for an event of ``severity`` (``"normal"``/``"exceptional"``).
    what : str
        The quantity in the row (``"vibratory shear stress |T - T_mean| / W_p"``).
    reversal : bool
        A gear mesh's torque reversal instead of a peak (its drop below the run's mean torque
        against that mean).
    """

    elements: tuple[int | tuple[str, str], ...]
    factors: tuple[float, ...] = ()
    vibratory: bool = False
    limits: Callable[[float, str], list[EventLimit]] | None = None
    what: str = "torque"
    reversal: bool = False


@dataclass(frozen=True, eq=False)
class Check:
    """One component quantity against its limit (module docstring).

    Parameters
    ----------
    component : str
        The component's label (e.g. ``"coupling C1"``, ``"crank span 3"``).
    quantity : str
        What is checked (e.g. ``"synthesised vibratory torque vs T_KW"``).
    unit : str
        The unit of the quantity and its limit (SI: ``"Pa"``, ``"N·m"``, ``"W"``,
        ``"rad/s²"``, ``"rad"``).
    source : str
        The rule text with its edition or the maker's document the limit comes from (IACS UR
        M68, KR Rules 2025, the DIN 740-2 catalogue, the engine builder, ...) and the values
        used.
    curve : callable
        ``curve(r)`` -> the quantity at the speeds of a forced response ``r``
        (:class:`~crankdyn.torsion.response.ResponseResult`), shape (S,), in ``unit``.
    limit : callable
        ``limit(speeds)`` -> the continuous limit at speeds (rad/s), shape (S,), in ``unit``
        (NaN where none applies).
    barred : bool
        Whether the speeds above the limit form barred speed ranges (shafts, crank spans,
        couplings' T_KW); False: the limit holds at every speed of continuous running.
    m68 : bool
        Whether the check is a propulsion shaft's against the rule set's tau_C and tau_T (the
        IACS UR M68.4 form; plots draw it against both).
    transient_limit : callable or None
        ``transient_limit(speeds)`` -> the limit while passing a barred range (rad/s in, the
        unit out; tau_T, T_Kmax less the mean torque); None: no barred range is permitted.
    transient_curve : callable or None
        ``transient_curve(run, mean)`` -> the quantity over the samples of a time-domain run
        (:class:`~crankdyn.torsion.transient.TransientResult`), ``mean`` the mean-torque
        function of the load laws (or None).
    transient_source : str
        The source of the transient limit.
    elements : tuple of int
        The model's shaft indices the quantity is read on (for plots).
    clause : str
        The clauses of ``source`` (``"τ_C: M68.4 (not verified against the text: ...)"``), or
        the maker's data item.
    transient_clause : str
        The clauses of ``transient_source``.
    barred_upper : float or None
        The highest speed ratio n/n_0 a declared barred range may reach (0.8 for propulsion
        shafts: IACS UR M68.4, KR 2025 Pt 5 Ch 4 202.1(2)); None: no such rule.
    barred_source, barred_clause : str
        Where ``barred_upper`` comes from.
    barred_rows : callable or None
        ``barred_rows(b)`` -> the further rows a rule attaches to a declared barred range ``b``
        of this check (LR Pt 5 Ch 6 2.1.3's least tensile strength, KR's keyway note); None.
    event : EventReading or None
        How the check reads a transient event's run; None: it does not apply to events.
    steady : bool
        Whether the check applies to the steady forced response (False: an event-only check,
        e.g. a coupling with T_Kmax but no T_KW).
    """

    component: str
    quantity: str
    unit: str
    source: str
    curve: Curve
    limit: Limit
    barred: bool = False
    m68: bool = False
    transient_limit: Limit | None = None
    transient_curve: TransientCurve | None = None
    transient_source: str = ""
    elements: tuple[int, ...] = ()
    clause: str = ""
    transient_clause: str = ""
    barred_upper: float | None = None
    barred_source: str = ""
    barred_clause: str = ""
    barred_rows: BarredRows | None = None
    event: EventReading | None = None
    steady: bool = True


@dataclass
class CheckContext:
    """What the check kinds read.

    Parameters
    ----------
    model : TorsionModel
        The installation (with its load law's excitation).
    spec : TvcSpec
        The settings.
    rated : float
        The rated speed n_0 (rad/s).
    dampers : sequence of Damper
        The dampers of the condition.
    mean : callable or None
        The mean-torque function of the load laws (:func:`mean_torque_function`), or None.
    notes : list of str
        The notes on what is not checked (appended to).
    engine : Engine or None
        The engine (its cycle, layout and crankshaft for the society's crankshaft limits).
    load : str
        The load law (:data:`crankdyn.tvc.spec.LOADS`): ``"propeller"`` for a propulsion line,
        ``"constant-speed"`` for a generating set.
    """

    model: TorsionModel
    spec: TvcSpec
    rated: float
    dampers: Sequence[Damper]
    mean: MeanTorque | None
    notes: list[str] = field(default_factory=list)
    engine: Engine | None = None
    load: str = "propeller"

    @property
    def generating_set(self) -> bool:
        """Whether the installation is a generating set (constant-speed load)."""
        return self.load == "constant-speed"


class CheckKind:
    """A kind of component check: :meth:`checks` gives the checks of a model (none when the
    model has no such component) and adds a note where a component is not checked."""

    def checks(self, ctx: CheckContext) -> list[Check]:
        """The checks of this kind in the model.

        Parameters
        ----------
        ctx : CheckContext
            The model and what the checks read.

        Returns
        -------
        list of Check
            The checks (none when the model has no such component).
        """
        raise NotImplementedError


HAMMERING = "no rule clause: the tooth load reverses (crankdyn's criterion)"
"""The clause of the gear-hammering rows: a physical criterion, no society's clause."""


def _constant(value: float) -> Limit:
    """A limit that is the same at every speed."""

    def limit(w: ArrayLike) -> NDArray[np.float64]:
        return np.full(np.size(w), value)

    return limit


def shaft_label(shaft: Shaft) -> str:
    """A shaft's label in the verdict table: its name and its ends (the whole shaft's, for an
    element of a subdivided shaft)."""
    ends = shaft.segment_of or shaft.between
    text = f"{ends[0]} - {ends[1]}"
    return f"{shaft.name} ({text})" if shaft.name else text


def labelled(kind: str, name: str) -> str:
    """A component's name with what it is in front, unless the name says it already
    ("coupling C1", but "highly elastic coupling")."""
    return name if kind.split()[-1].lower() in name.lower() else f"{kind} {name}"


def _index_of_shaft(model: TorsionModel, between: Sequence[str]) -> int:
    for s, sh in enumerate(model.shafts):
        if tuple(sh.between) in (tuple(between), tuple(between)[::-1]):
            return s
    raise InputError("no such shaft", key="between", value=list(between))


@dataclass(frozen=True)
class _RuledShaft:
    """One propulsion shaft's data under the selected rule set (SI)."""

    between: tuple[str, str]
    tensile_strength: float  # specified minimum (Pa)
    strength_used: float  # capped (Pa)
    design_factor: float  # C_K
    diameter: float  # (m)
    feature: str | None
    cap: str  # how sigma_B was capped, for the source
    parts: tuple[tuple[str, Clause], ...]  # the clauses of the cap and of C_K


def _ruled_shaft(limit: Any, diameter: float, ctx: CheckContext) -> _RuledShaft:
    """A shaft's sigma_B and C_K from the rule set: the society's cap for its material and
    kind (or the cap given in ``[rules.shaft] tensile_strength_cap``) and the society's C_K of
    its design feature (or the C_K given as a number)."""
    society = ctx.spec.ruleset
    parts: list[tuple[str, Clause]] = []
    if limit.strength_cap is not None:
        cap_value, cap = float(limit.strength_cap), "as given (tensile_strength_cap)"
    else:
        cited = society.strength_caps[(limit.material, limit.kind)]
        cap_value, cap = float(cited.value), f"{limit.material} steel, {limit.kind} shaft"
        parts.append(("σ_B cap", cited.clause))
    if limit.feature is not None and limit.feature in society.design_factors:
        factor = society.design_factors[limit.feature]
        ck = float(factor.value)
        parts.append(("C_K", factor.clause))
    else:
        ck = float(limit.design_factor)
    return _RuledShaft(
        tuple(limit.between),
        float(limit.tensile_strength),
        min(float(limit.tensile_strength), cap_value),
        ck,
        diameter,
        limit.feature,
        cap if limit.tensile_strength > cap_value else "",
        tuple(parts),
    )


class M68Shafts(CheckKind):
    """Propulsion shafts against the rule set's tau_C and tau_T (module docstring), grouped by
    the shaft a subdivided element belongs to: the stress is the largest over its elements."""

    def checks(self, ctx: CheckContext) -> list[Check]:
        rules: Any = ctx.model.rules  # a RuleSet or None (TorsionModel holds it as an object)
        if rules is None:
            return []
        n0 = rules.rated_speed or ctx.rated
        return [self._check(ctx, items, n0) for items in self._groups(ctx, rules).values()]

    @staticmethod
    def _groups(ctx: CheckContext, rules: Any) -> dict[tuple, list[tuple[int, _RuledShaft, float]]]:
        model = ctx.model
        groups: dict[tuple, list[tuple[int, _RuledShaft, float]]] = {}
        shafts = model.shafts
        for shaft_limit in rules.shafts:
            s = _index_of_shaft(model, shaft_limit.between)
            shaft = shafts[s]
            if shaft.geometry is None:
                raise InputError(
                    f'shaft "{shaft.label}" has no diameters: the M68 check needs its '
                    "outer_diameter",
                    file=model.source,
                    key="[rules] shaft",
                    value=list(shaft_limit.between),
                )
            m = _ruled_shaft(shaft_limit, shaft.geometry.outer_diameter, ctx)
            key = (shaft_label(shaft), m.strength_used, m.design_factor, m.diameter)
            groups.setdefault(key, []).append((s, m, shaft.geometry.section_modulus))
        return groups

    @staticmethod
    def _check(ctx: CheckContext, items: list[tuple[int, _RuledShaft, float]], n0: float) -> Check:
        society = ctx.spec.ruleset
        idx = np.array([s for s, _, _ in items])
        moduli = np.array([w for _, _, w in items])
        m = items[0][1]
        label = shaft_label(ctx.model.shafts[int(idx[0])])
        top, barred_top = float(society.overspeed.value), float(society.barred_upper.value)
        cap = f", σ_B capped at {m.strength_used / 1e6:g} MPa ({m.cap})" if m.cap else ""
        feature = f" ({m.feature})" if m.feature else " (as given)"
        c_d = float(size_factor(m.diameter))
        parts = [("τ_C", society.shaft_formula), *m.parts, ("C_D", society.size_factor)]
        source, clause = cite_row(parts)
        t_source, t_clause = cite_row([("τ_T", society.transient_formula), *parts[1:]])
        b_source, b_clause = cite_row([("barred ranges", society.barred_upper.clause)])

        def curve(r: Any) -> NDArray[np.float64]:
            return np.max(np.asarray(r.synthesized_shaft_stress)[:, idx], axis=1)

        def tau_c(w: ArrayLike) -> NDArray[np.float64]:
            lam = np.asarray(w, dtype=float) / n0
            tau = permissible_continuous(lam, m.strength_used, m.design_factor, m.diameter)
            return np.where(lam <= top, tau, np.nan)

        def tau_t(w: ArrayLike) -> NDArray[np.float64]:
            lam = np.asarray(w, dtype=float) / n0
            tau = permissible_transient(lam, tau_c(w), m.design_factor)
            return np.where(lam <= barred_top, tau, np.nan)

        def m68_transient(run: Any, _mean: Any) -> NDArray[np.float64]:
            return np.max(np.abs(run.shaft_torque[:, idx]) / moduli[None, :], axis=1)

        def event_limits(speed: float, _severity: str) -> list[EventLimit]:
            lam = speed / n0
            used = min(lam, barred_top)
            note = (
                ""
                if lam <= barred_top
                else f"λ = {lam:.3g} > {barred_top:g}: τ_T of λ = {barred_top:g}"
            )
            value = float(tau_t(np.array([used * n0]))[0])
            return [EventLimit("τ_T", value, f"{t_source}: τ_T = 1.7 τ_C / √C_K", t_clause, note)]

        return Check(
            component=label,
            quantity="synthesised vibratory shear stress (half range)",
            unit="Pa",
            source=f"{source}: τ_C with σ_B = {m.strength_used / 1e6:g} MPa{cap}, "
            f"C_K = {m.design_factor:g}{feature}, C_D = {c_d:.4f} (d = {m.diameter * 1e3:g} mm)",
            curve=curve,
            limit=tau_c,
            barred=True,
            m68=True,
            transient_limit=tau_t,
            transient_curve=m68_transient,
            transient_source=f"{t_source}: τ_T = 1.7 τ_C / √C_K (λ ≤ {barred_top:g})",
            elements=tuple(int(i) for i in idx),
            clause=clause,
            transient_clause=t_clause,
            barred_upper=barred_top,
            barred_source=b_source,
            barred_clause=b_clause,
            barred_rows=_shaft_barred_rows(ctx, label, m),
            event=EventReading(
                tuple(int(i) for i in idx),
                tuple(float(1.0 / w) for w in moduli),
                vibratory=True,
                limits=event_limits,
                what="vibratory shear stress |T - T_mean| / W_p",
            ),
        )


def _shaft_barred_rows(ctx: CheckContext, label: str, m: _RuledShaft) -> BarredRows | None:
    """The rows a society attaches to a propulsion shaft's barred range: the least tensile
    strength of a shaft whose stresses come close to tau_T (LR Rules for Ships Pt 5 Ch 6
    2.1.3: 500 N/mm^2; crankdyn reads "close" as a barred range being declared, the stress
    above tau_C), and the keyway note (KR 2025 Pt 5 Ch 4 Table 5.4.1 note (2): keyways are in
    general not to be used with a barred speed range); None where the rule set states
    neither."""
    society = ctx.spec.ruleset
    least = society.min_strength_transient
    keyway = society.keyways
    rows_least = least.value is not None
    rows_key = keyway.value is not None and (m.feature or "").startswith("keyway")
    if not (rows_least or rows_key):
        return None

    def rows(b: BarredSpeedRange) -> list[Verdict]:
        out = []
        if rows_least:
            assert least.value is not None
            source, clause = cite_row([("least σ_B", least.clause)])
            out.append(
                Verdict(
                    component=label,
                    condition=b.condition,
                    quantity="specified tensile strength required of a shaft with a barred "
                    "range (least σ_B vs the shaft's σ_B)",
                    worst=float(least.value),
                    limit=m.tensile_strength,
                    unit="Pa",
                    passed=bool(m.tensile_strength >= least.value),
                    source=f"{source}: σ_B ≥ {least.value / 1e6:g} MPa where stresses come "
                    "close to τ_T",
                    clause=clause,
                    speed=b.critical_speed,
                    note="crankdyn reads 'close to the transient limit' as a declared barred "
                    "range (the stress above τ_C)",
                    kind="least tensile strength",
                )
            )
        if rows_key:
            source, clause = cite_row([("keyways", keyway.clause)])
            out.append(
                Verdict(
                    component=label,
                    condition=b.condition,
                    quantity=f"{m.feature} in an installation with a barred speed range",
                    worst=1.0,
                    limit=0.0,
                    unit="",
                    passed=False,
                    source=f"{source}: {keyway.value}",
                    clause=clause,
                    speed=b.critical_speed,
                    margin=-math.inf,
                    note="unless the Society accepts it specially",
                    kind="keyway with a barred range",
                )
            )
        return out

    return rows


class CrankSpans(CheckKind):
    """Crank spans against the engine builder's permissible vibratory stress or torque
    (``[tvc.crankshaft]``; :class:`crankdyn.tvc.limits.CrankshaftLimit`), else against the
    society's own crankshaft limits where its text states them (:class:`SocietyCrankshaft`)."""

    def checks(self, ctx: CheckContext) -> list[Check]:
        shafts = ctx.model.shafts
        crank = ctx.spec.crankshaft
        spans = [s for s, sh in enumerate(shafts) if sh.role == "crankshaft" and not sh.grounded]
        if crank is None:
            return SocietyCrankshaft().spans(ctx, spans) if spans else []
        if not spans:
            ctx.notes.append("[tvc.crankshaft] is given but the model has no crank spans")
        return [self._check(ctx, s) for s in spans]

    @staticmethod
    def _check(ctx: CheckContext, s: int) -> Check:
        crank = ctx.spec.crankshaft
        assert crank is not None  # checks() returned otherwise
        shaft = ctx.model.shafts[s]
        own = shaft.geometry.section_modulus if shaft.geometry is not None else math.nan
        modulus = crank.modulus(own)
        if crank.by_stress and not np.isfinite(modulus):
            raise InputError(
                f'crank span "{shaft.label}" has no diameter for the nominal stress: give '
                "[tvc.crankshaft] diameter",
                file=ctx.model.source,
                key="diameter",
            )
        factor = crank.stress_concentration / modulus if crank.by_stress else 1.0
        value = crank.stress if crank.by_stress else crank.torque
        transient_value = crank.transient_stress if crank.by_stress else crank.transient_torque
        what = "stress" if crank.by_stress else "torque"
        kt = (
            f" × K = {crank.stress_concentration:g}"
            if crank.by_stress and crank.stress_concentration != 1.0
            else ""
        )
        source = (
            f"engine builder: permissible additional vibratory {what}"
            f"{' (' + crank.source + ')' if crank.source else ''}"
        )
        data = f"[tvc.crankshaft] permissible_{what}"

        def span_curve(r: Any) -> NDArray[np.float64]:
            return np.asarray(r.synthesized_shaft_torque)[:, s] * factor

        transient_limit: Limit | None = None
        transient: TransientCurve | None = None
        event: EventReading | None = None
        if transient_value is not None:

            def span_transient(run: Any, _mean: Any) -> NDArray[np.float64]:
                return np.abs(run.shaft_torque[:, s]) * factor

            transient_limit, transient = _constant(transient_value), span_transient
            limit = EventLimit(
                f"the builder's transient {what}",
                transient_value,
                source,
                f"[tvc.crankshaft] transient_{what}",
            )
            event = EventReading(
                (s,),
                (factor,),
                vibratory=True,
                limits=lambda _w, _sev: [limit],
                what=f"vibratory {'nominal stress' if crank.by_stress else 'torque'}",
            )

        assert value is not None  # a CrankshaftLimit holds a stress or a torque
        return Check(
            component=f"crank span {shaft.label}",
            quantity=(
                f"synthesised nominal shear stress{kt}"
                if crank.by_stress
                else "synthesised vibratory torque"
            ),
            unit="Pa" if crank.by_stress else "N·m",
            source=source,
            curve=span_curve,
            limit=_constant(value),
            barred=True,
            transient_limit=transient_limit,
            transient_curve=transient,
            transient_source=source + " (transient)",
            elements=(s,),
            clause=data,
            transient_clause=f"[tvc.crankshaft] transient_{what}",
            event=event,
        )


def _crank_modulus(ctx: CheckContext, s: int) -> tuple[float, str]:
    """W_p of a crank span's nominal stress (m^3) and where its diameter comes from: the
    span's own diameters, else the engine's crankshaft journal (``[crankshaft]``:
    W_p = pi (d^4 - d_i^4) / (16 d)); NaN where neither is given."""
    shaft = ctx.model.shafts[s]
    if shaft.geometry is not None:
        return float(shaft.geometry.section_modulus), "the span's diameter"
    crankshaft = getattr(ctx.engine, "crankshaft", None)
    if crankshaft is not None:
        d, di = crankshaft.geometry.journal_diameter, crankshaft.geometry.journal_bore
        return math.pi * (d**4 - di**4) / (16.0 * d), f"journal d = {d * 1e3:g} mm"
    return math.nan, ""


class SocietyCrankshaft:
    """Crank spans against the society's own crankshaft limits where no engine builder's limit
    is given: KR 2025 Pt 5 Ch 4 201 for main engines (tau_1 = 45 - 24 lambda^2 or
    45 - 29 lambda^2 N/mm^2 to lambda = 1, tau_3 = 21 or 16 + 237 (lambda - 0.8)
    sqrt(lambda - 1) to 1.15, tau_2 = 2 tau_1 while passing a barred range up to 0.8) and 203.1
    for generating sets (21 or 16 N/mm^2 to 1.1 n_0, 90 N/mm^2 while passing a barred range at
    and below 0.9 n_0; crankdyn reads tau_1 as the continuous limit at every speed up to 1.1
    n_0, exceeding it below 0.9 n_0 barring the range), each times the material factor f_m of
    201.4/203.3 where the engine's ``[crankshaft]`` gives its strengths (else 1: "may be
    increased"). The nominal stress is the synthesised torque over W_p of the span (or of the
    engine's journal). Where the society states none (IACS UR M68.1: the crankshaft is UR
    M53's), a note says so."""

    def spans(self, ctx: CheckContext, spans: Sequence[int]) -> list[Check]:
        """The checks of the crank spans (a note where none can be made).

        Parameters
        ----------
        ctx : CheckContext
            The model and what the checks read.
        spans : sequence of int
            The crank spans' shaft indices.

        Returns
        -------
        list of Check
            One per span with a diameter.
        """
        society = ctx.spec.ruleset
        cited = society.genset if ctx.generating_set else society.crankshaft
        if cited is None or cited.value is None:
            where = cited.clause.cite() if cited is not None else society.title
            why = f": {cited.clause.note}" if cited is not None and cited.clause.note else ""
            ctx.notes.append(
                "the crankshaft is not checked: give the engine builder's permissible "
                f"vibratory stress or torque in [tvc.crankshaft] ({society.title} states no "
                f"crankshaft limit in the text read: {where}{why})"
            )
            return []
        group, why = _engine_group(ctx)
        if why:
            ctx.notes.append(why)
        moduli = [_crank_modulus(ctx, s) for s in spans]
        if not all(np.isfinite(w) for w, _ in moduli):
            ctx.notes.append(
                f"crank spans without diameters are not checked against {society.title}'s "
                f"crankshaft limits ({cited.clause.cite()}): give the spans' outer_diameter "
                "or the engine's [crankshaft] journal_diameter"
            )
        limits = (
            _genset_crank_limits(ctx, group)
            if ctx.generating_set
            else _main_crank_limits(ctx, group)
        )
        return [
            _society_span_check(ctx, s, w, where, limits)
            for s, (w, where) in zip(spans, moduli, strict=True)
            if np.isfinite(w)
        ]


@dataclass(frozen=True)
class _SocietyLimits:
    """A society's limits of a component as functions of the speed ratio lambda (Pa), with the
    highest speed ratio of a barred range and the citations."""

    continuous: Callable[[NDArray[np.float64]], NDArray[np.float64]]
    transient: Callable[[NDArray[np.float64]], NDArray[np.float64]]
    barred_upper: float
    cited: tuple[tuple[str, str], tuple[str, str], tuple[str, str]]  # (source, clause) x 3
    text: str  # the limits in words, for the source


def _engine_group(ctx: CheckContext) -> tuple[str, str]:
    """KR's engine group of the crankshaft limits (:func:`crankdyn.tvc.rulesets.engine_group`)
    from the engine's cycle and layout (a vee engine's firing interval from its firing angles),
    and a note where the engine is not known (group B, the lower limits, is used)."""
    from crankdyn.tvc.rulesets import engine_group

    engine = ctx.engine
    if engine is None:
        return "B", (
            "the crankshaft's engine group (KR 2025 Pt 5 Ch 4 201.1) needs the engine's cycle "
            "and layout: group B (the lower limits) is used"
        )
    cylinders = engine.cylinders
    cycle = 4 if cylinders.cycle == "four-stroke" else 2
    vee = cylinders.layout != "inline"
    angles = np.sort(np.degrees(np.asarray(cylinders.firing_angles, dtype=float)))
    steps = np.diff(np.append(angles, angles[0] + 180.0 * cycle))
    interval = float(steps[0]) if vee and np.allclose(steps, steps[0]) else None
    return engine_group(cycle, vee, interval), ""


def _material_factors(ctx: CheckContext) -> tuple[float, float, str]:
    """The material factors f_m (continuous, transient) of KR 2025 Pt 5 Ch 4 201.4/203.3 from
    the engine's ``[crankshaft]`` strengths (1 where none are given: "may be increased"), and
    how they were found. Above 590 N/mm^2 the Society decides the T_s to use: crankdyn uses
    590 (carbon steel forgings' threshold, the lower one), said in the text."""
    from crankdyn.tvc.rulesets import material_factors

    material = getattr(getattr(ctx.engine, "crankshaft", None), "material", None)
    if material is None:
        return 1.0, 1.0, "f_m = 1 (no [crankshaft] strengths)"
    ts = float(material.tensile_strength)
    used = min(ts, 590e6)
    fc, ft = material_factors(ctx.spec.ruleset, used, material.yield_strength or 0.0)
    capped = f", T_s used as {used / 1e6:g} MPa (the Society decides above)" if ts > used else ""
    return float(fc), float(ft), f"f_m = {float(fc):.4g} / {float(ft):.4g}{capped}"


def _main_crank_limits(ctx: CheckContext, group: str) -> _SocietyLimits:
    """KR 2025 Pt 5 Ch 4 201: a main engine's crankshaft (:class:`SocietyCrankshaft`)."""
    from crankdyn.tvc.rulesets import crankshaft_limits

    society = ctx.spec.ruleset
    assert society.crankshaft is not None and society.crankshaft.value is not None
    rule = society.crankshaft.value
    fc, ft, how = _material_factors(ctx)

    def continuous(lam: NDArray[np.float64]) -> NDArray[np.float64]:
        t1, _, t3 = crankshaft_limits(society, lam, group)
        return np.where(lam <= 1.0, t1, t3) * fc

    def transient(lam: NDArray[np.float64]) -> NDArray[np.float64]:
        return crankshaft_limits(society, lam, group)[1] * ft

    c = rule.clauses
    material = [("f_m", c["material"])] if "material" in c else []
    return _SocietyLimits(
        continuous,
        transient,
        float(rule.transient_upper),
        (
            cite_row([("τ_1", c["continuous"]), ("τ_3", c["overspeed"]), *material]),
            cite_row([("τ_2", c["transient"]), *material]),
            cite_row([("barred ranges", c["transient"])]),
        ),
        f"group {group}: τ_1 = {rule.a[group] / 1e6:g} - {rule.b[group] / 1e6:g} λ², "
        f"τ_3 = {rule.c[group] / 1e6:g} + {rule.e / 1e6:g} (λ - 0.8) √(λ - 1) MPa, "
        f"τ_2 = {rule.k:g} τ_1; {how}",
    )


def _genset_crank_limits(ctx: CheckContext, group: str) -> _SocietyLimits:
    """KR 2025 Pt 5 Ch 4 203.1: a generating set's crankshaft (:class:`SocietyCrankshaft`)."""
    society = ctx.spec.ruleset
    assert society.genset is not None and society.genset.value is not None
    rule = society.genset.value
    low, high = rule.window
    fc, ft, how = _material_factors(ctx)
    steady, passing = rule.crankshaft[group] * fc, rule.crankshaft_transient * ft
    upper = society.transient_upper_genset
    top = float(upper.value) if upper is not None and upper.value is not None else low
    c = rule.clauses
    material = [("f_m", c["material"])] if "material" in c else []
    return _SocietyLimits(
        lambda lam: np.where(lam <= high, steady, np.nan),
        lambda lam: np.where(lam <= low, passing, np.nan),
        top,
        (
            cite_row([("τ_1", c["crankshaft"]), *material]),
            cite_row([("τ_2", c["crankshaft"]), *material]),
            cite_row([("barred ranges", upper.clause if upper else c["crankshaft"])]),
        ),
        f"group {group}: τ_1 = {steady / 1e6:.4g} MPa to {high:g} n_0, τ_2 = "
        f"{passing / 1e6:.4g} MPa at and below {low:g} n_0; {how}",
    )


def _society_span_check(
    ctx: CheckContext, s: int, modulus: float, where: str, limits: _SocietyLimits
) -> Check:
    """One crank span against a society's crankshaft limits (:class:`SocietyCrankshaft`)."""
    shaft = ctx.model.shafts[s]
    n0 = ctx.rated
    (source, clause), (t_source, t_clause), (b_source, b_clause) = limits.cited

    def span_stress(r: Any) -> NDArray[np.float64]:
        return np.asarray(r.synthesized_shaft_torque)[:, s] / modulus

    def limit(w: ArrayLike) -> NDArray[np.float64]:
        return limits.continuous(np.asarray(w, dtype=float) / n0)

    def transient_limit(w: ArrayLike) -> NDArray[np.float64]:
        return limits.transient(np.asarray(w, dtype=float) / n0)

    def span_transient(run: Any, _mean: Any) -> NDArray[np.float64]:
        return np.abs(run.shaft_torque[:, s]) / modulus

    def event_limits(speed: float, _severity: str) -> list[EventLimit]:
        lam, top = speed / n0, limits.barred_upper
        value = float(limits.transient(np.array([min(lam, top)]))[0])
        if not np.isfinite(value):
            return []
        note = "" if lam <= top else f"λ = {lam:.3g} > {top:g}: the transient limit of λ = {top:g}"
        return [EventLimit("τ_2", value, f"{t_source}: {limits.text}", t_clause, note)]

    return Check(
        component=f"crank span {shaft.label}",
        quantity="synthesised nominal shear stress (T / W_p)",
        unit="Pa",
        source=f"{source}: {limits.text}; W_p from {where}",
        curve=span_stress,
        limit=limit,
        barred=True,
        transient_limit=transient_limit,
        transient_curve=span_transient,
        transient_source=f"{t_source}: {limits.text}",
        elements=(s,),
        clause=clause,
        transient_clause=t_clause,
        barred_upper=limits.barred_upper,
        barred_source=b_source,
        barred_clause=b_clause,
        event=EventReading(
            (s,),
            (1.0 / modulus,),
            vibratory=True,
            limits=event_limits,
            what="vibratory nominal shear stress |T - T_mean| / W_p",
        ),
    )


class GeneratorShafts(CheckKind):
    """The shafts of a generating set's alternator (a plain shaft with diameters at a mass of
    role ``"alternator"``) against the society's generator-shaft limits where its text states
    them: KR 2025 Pt 5 Ch 4 203.2, 31 N/mm^2 to 1.1 n_0 and 118 N/mm^2 while passing a barred
    range at and below 0.9 n_0 (the material factor f_m of 203.3 is 1: no material is given for
    the shaft). Where the society states none, a note says so (IACS UR M68.1: generator rotor
    shafts are not covered; the alternator maker's limits, ``[mass.limits]``, are checked by
    :class:`MachineLimits`)."""

    def checks(self, ctx: CheckContext) -> list[Check]:
        if not ctx.generating_set:
            return []
        names = {m.name for m in ctx.model.masses if m.role in ("alternator", "generator")}
        shafts = [
            s
            for s, sh in enumerate(ctx.model.shafts)
            if sh.kind not in ("coupling", "mesh")
            and sh.coupling is None
            and names.intersection(sh.between)
            and sh.geometry is not None
        ]
        society = ctx.spec.ruleset
        cited = society.genset
        if not shafts:
            return []
        if cited is None or cited.value is None:
            where = cited.clause.cite() if cited is not None else society.title
            ctx.notes.append(
                f"the alternator shaft is not checked against a society limit: {society.title} "
                f"states none in the text read ({where}); the maker's limits apply"
            )
            return []
        rule = cited.value
        low, high = rule.window
        upper = society.transient_upper_genset
        top = float(upper.value) if upper is not None and upper.value is not None else low
        c = rule.clauses["generator"]
        limits = _SocietyLimits(
            lambda lam: np.where(lam <= high, rule.generator, np.nan),
            lambda lam: np.where(lam <= low, rule.generator_transient, np.nan),
            top,
            (
                cite_row([("τ_1", c)]),
                cite_row([("τ_2", c)]),
                cite_row([("barred ranges", upper.clause if upper else c)]),
            ),
            f"τ_1 = {rule.generator / 1e6:g} MPa to {high:g} n_0, τ_2 = "
            f"{rule.generator_transient / 1e6:g} MPa at and below {low:g} n_0; f_m = 1",
        )
        return [self._check(ctx, s, limits) for s in shafts]

    @staticmethod
    def _check(ctx: CheckContext, s: int, limits: _SocietyLimits) -> Check:
        shaft = ctx.model.shafts[s]
        assert shaft.geometry is not None  # checks() kept the shafts with diameters
        check = _society_span_check(ctx, s, float(shaft.geometry.section_modulus), "", limits)
        (source, _), _, _ = limits.cited
        return dataclasses.replace(
            check,
            component=labelled("alternator shaft", shaft.name or shaft.label),
            source=f"{source}: {limits.text}",
        )


class Couplings(CheckKind):
    """Elastic couplings against the catalogue's T_KW (barred ranges, T_Kmax less the mean
    torque while passing them), P_KV and T_KN (DIN 740-2); in transient events their torque
    against T_Kmax and T_Kmax1 or T_Kmax2."""

    def checks(self, ctx: CheckContext) -> list[Check]:
        out: list[Check] = []
        for s, shaft in enumerate(ctx.model.shafts):
            c = shaft.coupling
            if c is None:
                continue
            label = labelled("coupling", shaft.name or shaft.label)
            maker = f"coupling maker (DIN 740-2){' ' + c.designation if c.designation else ''}"
            if c.vibratory_torque is None and c.power_loss is None:
                ctx.notes.append(f"{label}: no T_KW or P_KV given, not checked")
            if c.vibratory_torque is not None:
                out.append(self._torque(ctx, s, label, maker))
            elif _coupling_event(c, maker) is not None:  # T_Kmax but no T_KW: events only
                out.append(
                    Check(
                        label,
                        "torque in transient events",
                        "N·m",
                        maker,
                        lambda r: np.zeros(np.size(r.speed)),
                        _constant(math.nan),
                        elements=(s,),
                        clause="[[shaft]] maximum_torque (T_Kmax, the catalogue)",
                        event=_coupling_event(c, maker, s),
                        steady=False,
                    )
                )
            if c.power_loss is not None:
                out.append(self._heat(ctx, s, label, maker))
            if c.nominal_torque is not None:
                if ctx.mean is None:
                    ctx.notes.append(
                        f"{label}: no load law, so the mean torque is not checked vs T_KN"
                    )
                else:
                    out.append(self._mean_torque(ctx, s, label, maker))
        return out

    @staticmethod
    def _torque(ctx: CheckContext, s: int, label: str, maker: str) -> Check:
        c = ctx.model.shafts[s].coupling
        assert c is not None and c.vibratory_torque is not None
        mean, t_max = ctx.mean, c.maximum_torque

        def torque(r: Any) -> NDArray[np.float64]:
            return np.asarray(r.synthesized_shaft_torque)[:, s]

        transient_limit: Limit | None = None
        transient: TransientCurve | None = None
        if t_max is not None:

            def coupling_transient_limit(w: ArrayLike) -> Any:
                m = np.abs(mean(w)[:, s]) if mean is not None else 0.0
                return t_max - m

            def coupling_transient(run: Any, _mean: Any) -> NDArray[np.float64]:
                return np.abs(run.shaft_torque[:, s])

            transient_limit, transient = coupling_transient_limit, coupling_transient
        return Check(
            component=label,
            quantity="synthesised vibratory torque vs T_KW",
            unit="N·m",
            source=f"{maker}: T_KW = {c.vibratory_torque / 1e3:g} kN·m",
            clause="[[shaft]] vibratory_torque (T_KW, the catalogue)",
            curve=torque,
            limit=_constant(c.vibratory_torque),
            barred=True,
            transient_limit=transient_limit,
            transient_curve=transient,
            transient_source=(
                f"{maker}: T_Kmax = {t_max / 1e3:g} kN·m less the mean torque"
                if t_max is not None
                else ""
            ),
            transient_clause="[[shaft]] maximum_torque (T_Kmax, the catalogue)",
            elements=(s,),
            event=_coupling_event(c, maker, s),
        )

    @staticmethod
    def _heat(ctx: CheckContext, s: int, label: str, maker: str) -> Check:
        shaft = ctx.model.shafts[s]
        c = shaft.coupling
        assert c is not None and c.power_loss is not None
        names = list(ctx.model.mass_names)
        ends = tuple(names.index(e) for e in shaft.between)
        eta, damping = shaft.loss_factor, shaft.damping

        def power(r: Any) -> NDArray[np.float64]:
            return cv.damping_power(r, s, ends, eta, damping)

        return Check(
            component=label,
            quantity="power loss (damping work per cycle x frequency) vs P_KV",
            unit="W",
            source=f"{maker}: P_KV = {c.power_loss:g} W",
            clause="[[shaft]] power_loss (P_KV, the catalogue)",
            curve=power,
            limit=_constant(c.power_loss),
        )

    @staticmethod
    def _mean_torque(ctx: CheckContext, s: int, label: str, maker: str) -> Check:
        c = ctx.model.shafts[s].coupling
        mean = ctx.mean
        assert c is not None and c.nominal_torque is not None and mean is not None

        def mean_curve(r: Any) -> NDArray[np.float64]:
            return np.abs(mean(r.speed)[:, s])

        return Check(
            component=label,
            quantity="mean torque vs T_KN",
            unit="N·m",
            source=f"{maker}: T_KN = {c.nominal_torque / 1e3:g} kN·m",
            clause="[[shaft]] nominal_torque (T_KN, the catalogue)",
            curve=mean_curve,
            limit=_constant(c.nominal_torque),
        )


def _coupling_event(c: Any, maker: str, s: int = -1) -> EventReading | None:
    """A coupling's reading of an event: its whole torque against T_Kmax and, where the
    catalogue gives them, T_Kmax1 (a normal event) or T_Kmax2 (an exceptional one); None
    without any of them."""
    if c.maximum_torque is None and c.maximum_torque_1 is None and c.maximum_torque_2 is None:
        return None

    def limits(_speed: float, severity: str) -> list[EventLimit]:
        out = []
        if c.maximum_torque is not None:
            clause = "[[shaft]] maximum_torque (T_Kmax, the catalogue)"
            out.append(EventLimit("T_Kmax", c.maximum_torque, maker, clause))
        if severity == "exceptional" and c.maximum_torque_2 is not None:
            note = "T_Kmax2: exceptional transient conditions"
            clause = "[[shaft]] maximum_torque_2 (T_Kmax2, the catalogue)"
            out.append(EventLimit("T_Kmax2", c.maximum_torque_2, maker, clause, note))
        if severity != "exceptional" and c.maximum_torque_1 is not None:
            note = "T_Kmax1: normal transient conditions"
            clause = "[[shaft]] maximum_torque_1 (T_Kmax1, the catalogue)"
            out.append(EventLimit("T_Kmax1", c.maximum_torque_1, maker, clause, note))
        return out

    return EventReading((s,), (1.0,), vibratory=False, limits=limits, what="torque")


class GearHammering(CheckKind):
    """Gear meshes (rigid gear pairs and elastic mesh shafts) against gear hammering: the tooth
    load reverses where the vibratory torque at the mesh exceeds the mean transmitted torque
    (the mean torque from the load law)."""

    def checks(self, ctx: CheckContext) -> list[Check]:
        out = [c for g in ctx.model.gears if (c := self._gear(ctx, g)) is not None]
        mean = ctx.mean
        for s, shaft in enumerate(ctx.model.shafts):
            if shaft.kind != "mesh":
                continue
            label = labelled("gear mesh", shaft.name or shaft.label)
            reading = EventReading((s,), (1.0,), reversal=True, what="mesh torque")
            if mean is None:
                out.append(_event_only(label, reading))
                continue

            def mesh_curve(r: Any, s: int = s) -> NDArray[np.float64]:
                return np.asarray(r.synthesized_shaft_torque)[:, s]

            def mesh_limit(w: ArrayLike, s: int = s) -> NDArray[np.float64]:
                assert mean is not None
                return np.abs(mean(w)[:, s])

            out.append(
                Check(
                    component=label,
                    quantity="synthesised vibratory torque vs the mean torque (hammering)",
                    unit="N·m",
                    source="gear hammering (mean torque from the load law)",
                    clause=HAMMERING,
                    curve=mesh_curve,
                    limit=mesh_limit,
                    event=reading,
                )
            )
        return out

    @staticmethod
    def _gear(ctx: CheckContext, g: Any) -> Check | None:
        if getattr(g, "joint", False):
            return None
        model, mean = ctx.model, ctx.mean
        label = labelled("gear", g.name or g.between[0] + " - " + g.between[1])
        reading = (
            EventReading((tuple(g.between),), (1.0,), reversal=True, what="mesh torque")
            if g.stiffness is None
            else None
        )
        if mean is None:
            ctx.notes.append(f"{label}: no load law, so gear hammering is not checked")
            return _event_only(label, reading) if reading is not None else None
        names = list(model.mass_names)
        shafts = model.shafts
        wheel = g.between[1]
        w_index = names.index(wheel)
        ends: Any = tuple(
            (
                s,
                1 if sh.between[0] == wheel else -1,
                sh.loss_factor,
                sh.damping,
                tuple(names.index(e) for e in sh.between),
            )
            for s, sh in enumerate(shafts)
            if wheel in sh.between
        )
        if any("ground" in shafts[e[0]].between for e in ends) or any(
            wheel in other.between for other in model.gears if other is not g
        ):
            ctx.notes.append(
                f"{label}: the wheel has a grounded shaft or another mesh, not checked"
            )
            return None
        wheel_mass = model.masses[model.index(wheel)]

        def mesh(r: Any) -> NDArray[np.float64]:
            return cv.synthesized(
                r,
                cv.mesh_torque_coefficients(
                    r, w_index, wheel_mass.inertia, ends, wheel_mass.damping
                ),
            )

        def mesh_mean(w: ArrayLike) -> NDArray[np.float64]:
            m = mean(w)
            return np.abs(sum(e[1] * m[:, e[0]] for e in ends))

        return Check(
            component=label,
            quantity="synthesised vibratory torque at the mesh vs the mean torque (hammering)",
            unit="N·m",
            source="gear hammering: the tooth load reverses where the vibratory torque "
            "exceeds the mean transmitted torque (mean torque from the load law)",
            clause=HAMMERING,
            curve=mesh,
            limit=mesh_mean,
            event=reading,
        )


def _event_only(label: str, reading: EventReading) -> Check:
    """A gear mesh's check in transient events only (no load law for the steady one)."""
    return Check(
        label,
        "torque reversal in transient events",
        "N·m",
        "gear hammering: the tooth load reverses where the torque falls through zero",
        lambda r: np.zeros(np.size(r.speed)),
        _constant(math.nan),
        clause=HAMMERING,
        event=reading,
        steady=False,
    )


class MachineLimits(CheckKind):
    """Generators and other machines against the maker's vibratory torque at the rotor,
    angular acceleration and vibratory angle."""

    def checks(self, ctx: CheckContext) -> list[Check]:
        out: list[Check] = []
        names = list(ctx.model.mass_names)
        shafts = ctx.model.shafts
        for machine in ctx.model.masses:
            lim = machine.limits
            if lim is None:
                continue
            label = labelled(machine.role or "machine", machine.name)
            src = f"maker's limit{' (' + lim.source + ')' if lim.source else ''}"
            attached = [s for s, sh in enumerate(shafts) if machine.name in sh.between]
            j = names.index(machine.name)
            if lim.vibratory_torque is not None and attached:
                out.append(
                    Check(
                        label,
                        "synthesised vibratory torque at the rotor",
                        "N·m",
                        src,
                        _rotor_torque(tuple(attached)),
                        _constant(lim.vibratory_torque),
                        clause="[mass.limits] vibratory_torque",
                    )
                )
            if lim.angular_acceleration is not None:
                out.append(
                    Check(
                        label,
                        "synthesised angular acceleration",
                        "rad/s²",
                        src,
                        _acceleration(j),
                        _constant(lim.angular_acceleration),
                        clause="[mass.limits] angular_acceleration",
                    )
                )
            if lim.amplitude is not None:
                out.append(
                    Check(
                        label,
                        "synthesised vibratory angle",
                        "rad",
                        src,
                        _amplitude(j),
                        _constant(lim.amplitude),
                        clause="[mass.limits] amplitude",
                    )
                )
        return out


def _rotor_torque(idx: tuple[int, ...]) -> Curve:
    def rotor_torque(r: Any) -> NDArray[np.float64]:
        return np.max(np.asarray(r.synthesized_shaft_torque)[:, list(idx)], axis=1)

    return rotor_torque


def _acceleration(j: int) -> Curve:
    def accel(r: Any) -> NDArray[np.float64]:
        return cv.synthesized(r, cv.acceleration_coefficients(r, j))

    return accel


def _amplitude(j: int) -> Curve:
    def amp(r: Any) -> NDArray[np.float64]:
        return np.asarray(r.synthesized_amplitude)[:, j]

    return amp


class DamperHeat(CheckKind):
    """Dampers against the maker's permissible heat load (the dissipated power)."""

    def checks(self, ctx: CheckContext) -> list[Check]:
        out: list[Check] = []
        for j, d in enumerate(ctx.dampers):
            if d.permissible_power is None:
                ctx.notes.append(
                    f'damper "{d.name}": no permissible_power given, its heat not checked'
                )
                continue

            def dpower(r: Any, j: int = j) -> NDArray[np.float64]:
                return np.asarray(r.damper_power)[:, j]

            out.append(
                Check(
                    labelled("damper", d.name),
                    "dissipated power vs the permissible heat load",
                    "W",
                    f"damper maker's limit{' (' + d.limit_source + ')' if d.limit_source else ''}",
                    dpower,
                    _constant(d.permissible_power),
                    clause="[[damper]] permissible_power",
                )
            )
        return out


for _kind in (
    M68Shafts,
    CrankSpans,
    GeneratorShafts,
    Couplings,
    GearHammering,
    MachineLimits,
    DamperHeat,
):
    _kind.checks.__doc__ = CheckKind.checks.__doc__  # one description of every kind's method

CHECK_KINDS: tuple[CheckKind, ...] = (
    M68Shafts(),
    CrankSpans(),
    GeneratorShafts(),
    Couplings(),
    GearHammering(),
    MachineLimits(),
    DamperHeat(),
)
"""Every kind of component check, in the verdict table's order."""


def mean_torque_function(model: TorsionModel) -> MeanTorque | None:
    """The mean torques of the load laws.

    Parameters
    ----------
    model : TorsionModel
        The installation.

    Returns
    -------
    callable or None
        ``mean(speeds)`` -> (S, shafts) mean torques (N m) at reference speeds (rad/s); None
        without a load law.
    """
    from crankdyn.torsion.sources import mean_torques

    try:
        mean_torques(model, [1.0])
    except InputError:
        return None

    def mean(speeds: ArrayLike) -> NDArray[np.float64]:
        return np.asarray(mean_torques(model, np.atleast_1d(speeds)).mean_torque)

    return mean


def model_checks(
    model: TorsionModel,
    spec: TvcSpec,
    rated: float,
    dampers: Sequence[Damper],
    *,
    engine: Engine | None = None,
    load: str = "propeller",
) -> tuple[list[Check], list[str]]:
    """Every component check of a model (every kind of :data:`CHECK_KINDS`) and the notes on
    what is not checked.

    Parameters
    ----------
    model : TorsionModel
        The model (with its load law's excitation).
    spec : TvcSpec
        The settings (the rule set, the crankshaft's limit).
    rated : float
        The rated speed n_0 (rad/s).
    dampers : sequence of Damper
        The dampers of the condition.
    engine : Engine or None
        The engine (its cycle, layout and crankshaft, for a society's crankshaft limits).
    load : str
        The load law (``"propeller"``: a propulsion line; ``"constant-speed"``: a generating
        set, whose society limits differ).

    Returns
    -------
    checks : list of Check
        In the order of :data:`CHECK_KINDS`.
    notes : list of str
        Components not checked, and why.
    """
    ctx = CheckContext(
        model, spec, rated, dampers, mean_torque_function(model), engine=engine, load=load
    )
    checks = [c for kind in CHECK_KINDS for c in kind.checks(ctx)]
    return checks, ctx.notes
