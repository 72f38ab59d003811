"""The checks of an installation: every component quantity against its limit, made by a table of
check kinds (:data:`CHECK_KINDS`), one small object per kind of component (analysis).

A :class:`Check` is one component quantity (a curve of a forced response) against its
continuous limit, with the transient limit that governs a barred range where the rule permits
one. :func:`model_checks` asks every kind in :data:`CHECK_KINDS` for the checks of a model:

- :class:`M68Shafts`: propulsion shafts against IACS UR M68.4 (tau_C, tau_T, C_K, C_D, the cap on
  sigma_B: :mod:`crankdyn.tvc.limits`), grouped by the shaft a subdivided element belongs to;
- :class:`CrankSpans`: crank spans against the engine builder's permissible vibratory stress or
  torque (``[tvc.crankshaft]``);
- :class:`Couplings`: elastic couplings against T_KW (and T_Kmax for a barred range), P_KV and
  T_KN (DIN 740-2, the maker's catalogue);
- :class:`GearHammering`: gear meshes against gear hammering (the vibratory torque at the mesh
  above the mean transmitted torque reverses the tooth load);
- :class:`MachineLimits`: generators and other machines against the maker's vibratory torque,
  angular acceleration and amplitude;
- :class:`DamperHeat`: dampers against the maker's permissible heat load.

Every front end (``crankdyn torsion response``, ``crankdyn tvc``, the report) judges a response
with these checks through :func:`crankdyn.tvc.evaluate.evaluate_condition`: one rule, one place.
A new kind of check is one class here, added to :data:`CHECK_KINDS`.

Transient events (:mod:`crankdyn.tvc.events`) are judged by the same checks: a check that
applies to a transient carries an :class:`EventReading` (which elements of the run it reads,
how, and its limits at the speed of the peak and the event's severity), which
:func:`crankdyn.tvc.evaluate.evaluate_event` evaluates: the shafts' vibratory stress against
tau_T, the crank spans' against the builder's transient limit, the couplings' torque against
T_Kmax and T_Kmax1 (normal events) or T_Kmax2 (exceptional ones), the gear meshes' torque
reversals.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, TypeAlias

import numpy as np
from numpy.typing import ArrayLike, NDArray

import crankdyn.tvc.curves as cv
from crankdyn.errors import InputError
from crankdyn.tvc.limits import M68, M68Shaft

if TYPE_CHECKING:
    from crankdyn.torsion.dampers import Damper
    from crankdyn.torsion.model import Shaft, TorsionModel
    from crankdyn.torsion.response import ResponseResult
    from crankdyn.torsion.transient import TransientResult
    from crankdyn.tvc.spec import TvcSpec

    MeanTorque: TypeAlias = Callable[[ArrayLike], NDArray[np.float64]]
    Curve: TypeAlias = Callable[[ResponseResult], NDArray[np.float64]]
    Limit: TypeAlias = Callable[[NDArray[np.float64]], NDArray[np.float64]]
    TransientCurve: TypeAlias = Callable[[TransientResult, MeanTorque | None], NDArray[np.float64]]

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
    "M68Shafts",
    "MachineLimits",
    "mean_torque_function",
    "model_checks",
]

M68_CLAUSE = "M68.4"
"""The clause of IACS UR M68 the shaft limits and barred-range rules come from."""
COUPLING_MAKER = "DIN 740-2 (coupling maker's catalogue)"
"""The source of a coupling's maximum torques."""
HAMMERING = "gear hammering: the tooth load reverses where the torque falls through zero"
"""The criterion of a gear mesh's torque reversal in a transient event."""


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
        The rule or maker's document the limit comes from (IACS UR M68 with its edition,
        DIN 740-2 catalogue, engine builder, ...) and the values used.
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
        Whether the check is IACS UR M68's (no barred range above 0.8 n_0, M68.4).
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
        The clause of ``source`` (``"M68.4"``), or ``""``.
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
    """

    model: TorsionModel
    spec: TvcSpec
    rated: float
    dampers: Sequence[Damper]
    mean: MeanTorque | None
    notes: list[str] = field(default_factory=list)


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


class M68Shafts(CheckKind):
    """Propulsion shafts against IACS UR M68.4 (module docstring), grouped by the shaft a
    subdivided element belongs to: the stress is the largest over its elements."""

    def checks(self, ctx: CheckContext) -> list[Check]:
        rules: Any = ctx.model.rules  # a RuleSet or None (TorsionModel holds it as an object)
        if rules is None:
            return []
        n0 = rules.rated_speed or ctx.rated
        return [
            self._check(label, items, n0) for label, items in self._groups(ctx.model, rules).items()
        ]

    @staticmethod
    def _groups(model: TorsionModel, rules: Any) -> dict[tuple, list[tuple[int, M68Shaft, float]]]:
        groups: dict[tuple, list[tuple[int, M68Shaft, float]]] = {}
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
            m = M68Shaft(
                tuple(shaft_limit.between),
                shaft_limit.tensile_strength,
                shaft_limit.design_factor,
                shaft.geometry.outer_diameter,
                shaft_limit.strength_used,
                shaft_limit.feature,
            )
            key = (shaft_label(shaft), m.strength_used, m.design_factor, m.diameter)
            groups.setdefault(key, []).append((s, m, shaft.geometry.section_modulus))
        return groups

    @staticmethod
    def _check(key: tuple, items: list[tuple[int, M68Shaft, float]], n0: float) -> Check:
        label, strength, ck, diameter = key
        idx = np.array([s for s, _, _ in items])
        moduli = np.array([w for _, _, w in items])
        m = items[0][1]
        cap = "" if strength >= m.tensile_strength else f", σ_B capped at {strength / 1e6:g} MPa"
        source = (
            f"{M68}: τ_C with σ_B = {strength / 1e6:g} MPa, C_K = {ck:g}, "
            f"C_D = {m.size_factor:.4f} (d = {diameter * 1e3:g} mm){cap}"
        )

        def curve(r: Any) -> NDArray[np.float64]:
            return np.max(np.asarray(r.synthesized_shaft_stress)[:, idx], axis=1)

        def tau_c(w: ArrayLike) -> NDArray[np.float64]:
            return m.tau_c(np.asarray(w, dtype=float) / n0)

        def tau_t(w: ArrayLike) -> NDArray[np.float64]:
            return m.tau_t(np.asarray(w, dtype=float) / n0)

        def m68_transient(run: Any, _mean: Any) -> NDArray[np.float64]:
            return np.max(np.abs(run.shaft_torque[:, idx]) / moduli[None, :], axis=1)

        def event_limits(speed: float, _severity: str) -> list[EventLimit]:
            lam = speed / n0
            used = min(lam, 0.8)
            note = "" if lam <= 0.8 else f"λ = {lam:.3g} > 0.8: τ_T of λ = 0.8 (M68.4)"
            value = float(m.tau_t(np.array([used]))[0])
            return [EventLimit("τ_T", value, f"{M68}: τ_T = 1.7 τ_C / √C_K", M68_CLAUSE, note)]

        return Check(
            component=label,
            quantity="synthesised vibratory shear stress (half range)",
            unit="Pa",
            source=source,
            curve=curve,
            limit=tau_c,
            barred=True,
            m68=True,
            transient_limit=tau_t,
            transient_curve=m68_transient,
            transient_source=f"{M68}: τ_T = 1.7 τ_C / √C_K (λ ≤ 0.8)",
            elements=tuple(int(i) for i in idx),
            event=EventReading(
                tuple(int(i) for i in idx),
                tuple(float(1.0 / w) for w in moduli),
                vibratory=True,
                limits=event_limits,
                what="vibratory shear stress |T - T_mean| / W_p",
            ),
        )


class CrankSpans(CheckKind):
    """Crank spans against the engine builder's permissible vibratory stress or torque
    (``[tvc.crankshaft]``; :class:`crankdyn.tvc.limits.CrankshaftLimit`)."""

    def checks(self, ctx: CheckContext) -> list[Check]:
        shafts = ctx.model.shafts
        crank = ctx.spec.crankshaft
        spans = [s for s, sh in enumerate(shafts) if sh.role == "crankshaft" and not sh.grounded]
        if crank is None:
            if spans:
                ctx.notes.append(
                    "the crankshaft is not checked: give the engine builder's permissible "
                    "vibratory stress or torque in [tvc.crankshaft]"
                )
            return []
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

        def span_curve(r: Any) -> NDArray[np.float64]:
            return np.asarray(r.synthesized_shaft_torque)[:, s] * factor

        transient_limit: Limit | None = None
        transient: TransientCurve | None = None
        event: EventReading | None = None
        if transient_value is not None:

            def span_transient(run: Any, _mean: Any) -> NDArray[np.float64]:
                return np.abs(run.shaft_torque[:, s]) * factor

            transient_limit, transient = _constant(transient_value), span_transient
            limit = EventLimit(f"the builder's transient {what}", transient_value, source)
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
            event=event,
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
            out.append(EventLimit("T_Kmax", c.maximum_torque, maker))
        if severity == "exceptional" and c.maximum_torque_2 is not None:
            note = "T_Kmax2: exceptional transient conditions"
            out.append(EventLimit("T_Kmax2", c.maximum_torque_2, maker, note=note))
        if severity != "exceptional" and c.maximum_torque_1 is not None:
            note = "T_Kmax1: normal transient conditions"
            out.append(EventLimit("T_Kmax1", c.maximum_torque_1, maker, note=note))
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
        HAMMERING,
        lambda r: np.zeros(np.size(r.speed)),
        _constant(math.nan),
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
                )
            )
        return out


for _kind in (M68Shafts, CrankSpans, Couplings, GearHammering, MachineLimits, DamperHeat):
    _kind.checks.__doc__ = CheckKind.checks.__doc__  # one description of every kind's method

CHECK_KINDS: tuple[CheckKind, ...] = (
    M68Shafts(),
    CrankSpans(),
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
    model: TorsionModel, spec: TvcSpec, rated: float, dampers: Sequence[Damper]
) -> tuple[list[Check], list[str]]:
    """Every component check of a model (every kind of :data:`CHECK_KINDS`) and the notes on
    what is not checked.

    Parameters
    ----------
    model : TorsionModel
        The model (with its load law's excitation).
    spec : TvcSpec
        The settings (the crankshaft's limit).
    rated : float
        The rated speed n_0 (rad/s).
    dampers : sequence of Damper
        The dampers of the condition.

    Returns
    -------
    checks : list of Check
        In the order of :data:`CHECK_KINDS`.
    notes : list of str
        Components not checked, and why.
    """
    ctx = CheckContext(model, spec, rated, dampers, mean_torque_function(model))
    checks = [c for kind in CHECK_KINDS for c in kind.checks(ctx)]
    return checks, ctx.notes
