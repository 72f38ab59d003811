"""The torsional vibration calculation (TVC) a classification society asks for (analysis).

For an installation (a torsional model with its engine, couplings, gears, dampers, propeller or
generator) the calculation runs every *running condition* over its speed range, each a resolved
forced response (:func:`crankdyn.torsion.response.forced_response`: every resonance peak refined
to 0.1 %):

- normal firing;
- each single cylinder misfiring (no ignition: the motored pressure,
  :class:`crankdyn.torsion.excitation.EngineExcitation`), the worst cylinder reported for every
  check;
- the damper out of order, where the model has one (the damper left out: a viscous damper
  whose fluid is lost leaves its ring free, which no longer acts on the line);

under the installation's load law: the propeller law (the gas load following the model's load
curve, the propeller's mean torque ~ n^2) or constant speed (a generating set: full load at
every speed of its range).

Every component with a limit is checked against it (:func:`_checks`; the limits and their
sources: :mod:`crankdyn.tvc.limits`, docs/tvc.md): propulsion shafts against IACS UR M68 (tau_C,
tau_T, C_K, C_D, the cap on sigma_B), crank spans against the engine builder's permissible
vibratory stress or torque, elastic couplings against T_KW, T_Kmax, T_KN and P_KV (DIN 740-2,
the maker's catalogue), gear meshes against gear hammering (the vibratory torque at the mesh
above the mean transmitted torque reverses the tooth load), generators against the maker's
vibratory torque, angular acceleration and amplitude, and dampers against the maker's heat load.

Barred speed ranges. Where a component's synthesised response exceeds its continuous limit
the range is bisected to 0.01 rpm on the resolved curve
(:func:`crankdyn.torsion.rules.exceedances`), widened to the society's least range around the
critical speed where the chosen rule says so and by the tachometer tolerance on both sides.
A range is *permitted* when the rule allows one there: for an M68 shaft only below 0.8 n_0 and
only while the stress stays below tau_T; for a coupling while the total torque stays below
T_Kmax; for the crankshaft while it stays below the builder's transient limit (none given: no
barred range permitted). Continuous limits (heat, gear hammering, generator, damper) are
checked over the speeds of continuous running: the condition's range less its barred ranges.

Passage through a barred range: a time-domain run-up (:func:`crankdyn.torsion.transient.
transient_response`, starting in the steady state of its first speed) from 5 % below to 2 %
above the declared range at the acceleration the
engine's torque leaves over the load, J_total dOmega/dt = T_engine - T_load(Omega): the time in
the range is the integral of J dOmega / (T_engine - T_load) over it (trapezoidal rule, 400
points), the run is linear in time with the same duration (the acceleration torque varies little
across a barred range); the largest transient stress (torque) of every component during the run
is checked against its transient limit (tau_T, T_Kmax).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, TypeAlias

import numpy as np
from numpy.typing import ArrayLike, NDArray

import crankdyn.tvc.curves as cv
from crankdyn.constants import RPM
from crankdyn.errors import InputError
from crankdyn.torsion.rules import exceedances
from crankdyn.tvc.limits import M68, WIDENING_SOURCES, M68Shaft, barred_limits
from crankdyn.tvc.result import BarredSpeedRange, ConditionResult, Passage, TvcResult, Verdict
from crankdyn.tvc.spec import TvcSpec

if TYPE_CHECKING:
    from crankdyn.engine.model import Engine
    from crankdyn.torsion.dampers import Damper
    from crankdyn.torsion.excitation import (
        EngineExcitation,
        SourceExcitation,
        UniformExcitation,
    )
    from crankdyn.torsion.model import Shaft, TorsionModel
    from crankdyn.torsion.response import ResponseResult
    from crankdyn.torsion.transient import TransientResult

    Excitation: TypeAlias = EngineExcitation | UniformExcitation | SourceExcitation
    MeanTorque: TypeAlias = Callable[[ArrayLike], NDArray[np.float64]]
    Curve: TypeAlias = Callable[[ResponseResult], NDArray[np.float64]]
    Limit: TypeAlias = Callable[[NDArray[np.float64]], NDArray[np.float64]]
    TransientCurve: TypeAlias = Callable[[TransientResult, MeanTorque | None], NDArray[np.float64]]
    # one condition's (condition, verdicts, barred ranges, response)
    Evaluated: TypeAlias = tuple[
        "_Condition", list[Verdict], list[BarredSpeedRange], ResponseResult
    ]

__all__ = ["Check", "tvc"]

LEAD_IN = 0.05
"""The passage run starts this fraction below the barred range (the start-up transient of the
integration decays before the range)."""
RUN_OUT = 0.02
"""... and ends this fraction above it."""


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
        The rule or maker's document the limit comes from (IACS UR M68.4, DIN 740-2 catalogue,
        engine builder, ...).
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


# ---- the checks of a model ----------------------------------------------------------------------
def _shaft_label(shaft: Shaft) -> str:
    ends = shaft.segment_of or shaft.between
    text = f"{ends[0]} - {ends[1]}"
    return f"{shaft.name} ({text})" if shaft.name else text


def _mean_torque_function(model: TorsionModel) -> MeanTorque | None:
    """mean(speeds) -> (S, shafts) mean torques (N m) from the load laws, or None."""
    from crankdyn.torsion.sources import mean_torques

    try:
        mean_torques(model, [1.0])
    except InputError:
        return None

    def mean(speeds: ArrayLike) -> NDArray[np.float64]:
        return np.asarray(mean_torques(model, np.atleast_1d(speeds)).mean_torque)

    return mean


def _checks(
    model: TorsionModel, spec: TvcSpec, rated: float, dampers: Sequence[Damper]
) -> tuple[list[Check], list[str]]:
    """Every component check of the model (module docstring) and notes on what is not checked."""
    notes: list[str] = []
    checks: list[Check] = []
    mean = _mean_torque_function(model)
    shafts = model.shafts
    # propulsion shafts: IACS UR M68, grouped by the shaft a subdivided element belongs to
    # a RuleSet or None (TorsionModel holds it as an object)
    rules: Any = model.rules
    if rules is not None:
        groups: dict[tuple[str, float, float, float], list[tuple[int, M68Shaft, float]]] = {}
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
            key = (_shaft_label(shaft), m.strength_used, m.design_factor, m.diameter)
            groups.setdefault(key, []).append((s, m, shaft.geometry.section_modulus))
        n0 = rules.rated_speed or rated
        for (label, strength, ck, diameter), items in groups.items():
            idx = np.array([s for s, _, _ in items])
            moduli = np.array([w for _, _, w in items])
            m = items[0][1]
            cap = (
                "" if strength >= m.tensile_strength else f", σ_B capped at {strength / 1e6:g} MPa"
            )
            source = (
                f"{M68}: τ_C with σ_B = {strength / 1e6:g} MPa, C_K = {ck:g}, "
                f"C_D = {m.size_factor:.4f} (d = {diameter * 1e3:g} mm){cap}"
            )

            def curve(r, idx=idx):
                return np.max(np.asarray(r.synthesized_shaft_stress)[:, idx], axis=1)

            def tau_c(w, m=m, n0=n0):
                return m.tau_c(np.asarray(w, dtype=float) / n0)

            def tau_t(w, m=m, n0=n0):
                return m.tau_t(np.asarray(w, dtype=float) / n0)

            def m68_transient(run, _mean, idx=idx, moduli=moduli):
                return np.max(np.abs(run.shaft_torque[:, idx]) / moduli[None, :], axis=1)

            checks.append(
                Check(
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
                )
            )
    # crank spans: the engine builder's limit
    crank = spec.crankshaft
    spans = [s for s, sh in enumerate(shafts) if sh.role == "crankshaft" and not sh.grounded]
    if crank is not None:
        if not spans:
            notes.append("[tvc.crankshaft] is given but the model has no crank spans")
        for s in spans:
            shaft = shafts[s]
            own = shaft.geometry.section_modulus if shaft.geometry is not None else math.nan
            modulus = crank.modulus(own)
            if crank.by_stress and not np.isfinite(modulus):
                raise InputError(
                    f'crank span "{shaft.label}" has no diameter for the nominal stress: give '
                    "[tvc.crankshaft] diameter",
                    file=model.source,
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

            def span_curve(r, s=s, factor=factor):
                return np.asarray(r.synthesized_shaft_torque)[:, s] * factor

            def limit(w, value=value):
                return np.full(np.size(w), value)

            transient_limit: Limit | None = None
            transient: TransientCurve | None = None
            if transient_value is not None:

                def span_transient_limit(w, value=transient_value):
                    return np.full(np.size(w), value)

                def span_transient(run, _mean, s=s, factor=factor):
                    return np.abs(run.shaft_torque[:, s]) * factor

                transient_limit, transient = span_transient_limit, span_transient

            checks.append(
                Check(
                    component=f"crank span {shaft.label}",
                    quantity=(
                        f"synthesised nominal shear stress{kt}"
                        if crank.by_stress
                        else "synthesised vibratory torque"
                    ),
                    unit="Pa" if crank.by_stress else "N·m",
                    source=source,
                    curve=span_curve,
                    limit=limit,
                    barred=True,
                    transient_limit=transient_limit,
                    transient_curve=transient,
                    transient_source=source + " (transient)",
                    elements=(s,),
                )
            )
    elif spans:
        notes.append(
            "the crankshaft is not checked: give the engine builder's permissible vibratory "
            "stress or torque in [tvc.crankshaft]"
        )
    # elastic couplings (DIN 740-2 catalogue limits)
    names = list(model.mass_names)
    for s, shaft in enumerate(shafts):
        c = shaft.coupling
        if c is None:
            continue
        label = _labelled("coupling", shaft.name or shaft.label)
        maker = f"coupling maker (DIN 740-2){' ' + c.designation if c.designation else ''}"
        if c.vibratory_torque is None and c.power_loss is None:
            notes.append(f"{label}: no T_KW or P_KV given, not checked")

        def torque(r, s=s):
            return np.asarray(r.synthesized_shaft_torque)[:, s]

        if c.vibratory_torque is not None:
            t_max = c.maximum_torque

            def limit(w, value=c.vibratory_torque):
                return np.full(np.size(w), value)

            transient_limit = transient = None
            if t_max is not None:

                def coupling_transient_limit(w, s=s, t_max=t_max):
                    m = np.abs(mean(w)[:, s]) if mean is not None else 0.0
                    return t_max - m

                def coupling_transient(run, _mean, s=s):
                    return np.abs(run.shaft_torque[:, s])

                transient_limit, transient = coupling_transient_limit, coupling_transient

            checks.append(
                Check(
                    component=label,
                    quantity="synthesised vibratory torque vs T_KW",
                    unit="N·m",
                    source=f"{maker}: T_KW = {c.vibratory_torque / 1e3:g} kN·m",
                    curve=torque,
                    limit=limit,
                    barred=True,
                    transient_limit=transient_limit,
                    transient_curve=transient,
                    transient_source=(
                        f"{maker}: T_Kmax = {t_max / 1e3:g} kN·m less the mean torque"
                        if t_max is not None
                        else ""
                    ),
                    elements=(s,),
                )
            )
        if c.power_loss is not None:
            a, b = (names.index(e) for e in shaft.between)

            def power(r, s=s, ends=(a, b), eta=shaft.loss_factor, damping=shaft.damping):
                return cv.damping_power(r, s, ends, eta, damping)

            def p_limit(w, value=c.power_loss):
                return np.full(np.size(w), value)

            checks.append(
                Check(
                    component=label,
                    quantity="power loss (damping work per cycle x frequency) vs P_KV",
                    unit="W",
                    source=f"{maker}: P_KV = {c.power_loss:g} W",
                    curve=power,
                    limit=p_limit,
                )
            )
        if c.nominal_torque is not None:
            if mean is None:
                notes.append(f"{label}: no load law, so the mean torque is not checked vs T_KN")
            else:

                def mean_curve(r, s=s):
                    return np.abs(mean(r.speed)[:, s])

                def kn_limit(w, value=c.nominal_torque):
                    return np.full(np.size(w), value)

                checks.append(
                    Check(
                        component=label,
                        quantity="mean torque vs T_KN",
                        unit="N·m",
                        source=f"{maker}: T_KN = {c.nominal_torque / 1e3:g} kN·m",
                        curve=mean_curve,
                        limit=kn_limit,
                    )
                )
    # gear meshes: hammering (vibratory torque at the mesh above the mean torque)
    for g in model.gears:
        if getattr(g, "joint", False):
            continue
        label = _labelled("gear", g.name or g.between[0] + " - " + g.between[1])
        if mean is None:
            notes.append(f"{label}: no load law, so gear hammering is not checked")
            continue
        wheel = g.between[1]
        w_index = names.index(wheel)
        ends = tuple(
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
            notes.append(f"{label}: the wheel has a grounded shaft or another mesh, not checked")
            continue
        wheel_mass = model.masses[model.index(wheel)]

        def mesh(r, w_index=w_index, wm=wheel_mass, ends=ends):
            return cv.synthesized(
                r, cv.mesh_torque_coefficients(r, w_index, wm.inertia, ends, wm.damping)
            )

        def mesh_mean(w, ends=ends):
            m = mean(w)
            return np.abs(sum(e[1] * m[:, e[0]] for e in ends))

        checks.append(
            Check(
                component=label,
                quantity="synthesised vibratory torque at the mesh vs the mean torque (hammering)",
                unit="N·m",
                source="gear hammering: the tooth load reverses where the vibratory torque "
                "exceeds the mean transmitted torque (mean torque from the load law)",
                curve=mesh,
                limit=mesh_mean,
            )
        )
    for s, shaft in enumerate(shafts):
        if shaft.kind == "mesh" and mean is not None:

            def mesh_curve(r, s=s):
                return np.asarray(r.synthesized_shaft_torque)[:, s]

            def mesh_limit(w, s=s):
                return np.abs(mean(w)[:, s])

            checks.append(
                Check(
                    component=_labelled("gear mesh", shaft.name or shaft.label),
                    quantity="synthesised vibratory torque vs the mean torque (hammering)",
                    unit="N·m",
                    source="gear hammering (mean torque from the load law)",
                    curve=mesh_curve,
                    limit=mesh_limit,
                )
            )
    # generators and other machines with the maker's limits
    for machine in model.masses:
        lim = machine.limits
        if lim is None:
            continue
        label = _labelled(machine.role or "machine", machine.name)
        src = f"maker's limit{' (' + lim.source + ')' if lim.source else ''}"
        attached = [s for s, sh in enumerate(shafts) if machine.name in sh.between]
        if lim.vibratory_torque is not None and attached:

            def rotor_torque(r, idx=tuple(attached)):
                return np.max(np.asarray(r.synthesized_shaft_torque)[:, list(idx)], axis=1)

            def vt(w, value=lim.vibratory_torque):
                return np.full(np.size(w), value)

            checks.append(
                Check(
                    label, "synthesised vibratory torque at the rotor", "N·m", src, rotor_torque, vt
                )
            )
        j = names.index(machine.name)
        if lim.angular_acceleration is not None:

            def accel(r, j=j):
                return cv.synthesized(r, cv.acceleration_coefficients(r, j))

            def al(w, value=lim.angular_acceleration):
                return np.full(np.size(w), value)

            checks.append(
                Check(label, "synthesised angular acceleration", "rad/s²", src, accel, al)
            )
        if lim.amplitude is not None:

            def amp(r, j=j):
                return np.asarray(r.synthesized_amplitude)[:, j]

            def aml(w, value=lim.amplitude):
                return np.full(np.size(w), value)

            checks.append(Check(label, "synthesised vibratory angle", "rad", src, amp, aml))
    # dampers: dissipated power against the permissible heat load
    for j, d in enumerate(dampers):
        if d.permissible_power is None:
            notes.append(f'damper "{d.name}": no permissible_power given, its heat not checked')
            continue

        def dpower(r, j=j):
            return np.asarray(r.damper_power)[:, j]

        def dl(w, value=d.permissible_power):
            return np.full(np.size(w), value)

        checks.append(
            Check(
                _labelled("damper", d.name),
                "dissipated power vs the permissible heat load",
                "W",
                f"damper maker's limit{' (' + d.limit_source + ')' if d.limit_source else ''}",
                dpower,
                dl,
            )
        )
    return checks, notes


def _labelled(kind: str, name: str) -> str:
    """A component's name with what it is in front, unless the name says it already
    ("coupling C1", but "highly elastic coupling")."""
    return name if kind.split()[-1].lower() in name.lower() else f"{kind} {name}"


def _index_of_shaft(model: TorsionModel, between: Sequence[str]) -> int:
    for s, sh in enumerate(model.shafts):
        if tuple(sh.between) in (tuple(between), tuple(between)[::-1]):
            return s
    raise InputError("no such shaft", key="between", value=list(between))


# ---- conditions ----------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class _Condition:
    name: str
    kind: str
    excitation: Excitation
    dampers: tuple[Damper, ...]
    low: float
    high: float
    description: str
    misfire: int | None = None


def _load_of(model: TorsionModel, spec: TvcSpec) -> str:
    if spec.load is not None:
        return spec.load
    props = [s for s in model.sources if getattr(s, "kind", None) == "propeller"]
    curve = getattr(getattr(model, "excitation", None), "load_curve", None)
    return "propeller" if props or curve is not None else "constant-speed"


def _with_load(model: TorsionModel, engine: Engine | None, load: str, rated: float) -> TorsionModel:
    """The model with the excitation's load matching the load law: constant speed drops a load
    curve (full load at every speed); the propeller law adds (n/n_0)^2 where none is given."""
    from crankdyn.torsion.excitation_spec import ExcitationSpec, LoadCurve

    exc: Any = model.excitation  # an ExcitationSpec or None (TorsionModel holds it as an object)
    if engine is None:  # a uniform torque or the sources alone: no gas pressure to load
        return model
    if load == "constant-speed" and exc is not None and exc.load_curve is not None:
        return dataclasses.replace(model, excitation=dataclasses.replace(exc, load_curve=None))
    if load == "propeller" and (exc is None or (exc.load_curve is None and not exc.traces)):
        if exc is not None and exc.harmonics is not None:
            return model
        n = np.linspace(0.2, 1.0, 17) * rated
        curve = LoadCurve(n, (n / rated) ** 2, kind="load_factor", source="propeller law (n/n0)^2")
        new = (
            ExcitationSpec(load_curve=curve)
            if exc is None
            else dataclasses.replace(exc, load_curve=curve)
        )
        return dataclasses.replace(model, excitation=new)
    return model


def _conditions(
    model: TorsionModel, engine: Engine | None, spec: TvcSpec, notes: list[str]
) -> list[_Condition]:
    from crankdyn.torsion.excitation import EngineExcitation, excitation_for

    base = excitation_for(model, engine)
    dampers = tuple(model.dampers)
    low, high = spec.range_of("normal", model)
    out = [_Condition("normal firing", "normal", base, dampers, low, high, "all cylinders firing")]
    if spec.misfire and isinstance(base, EngineExcitation):
        try:
            base.__class__(base.engine, base.spec, (1,))._motored_trace  # noqa: B018
        except InputError as exc:
            notes.append(f"misfire not calculated: {exc.message}")
        else:
            low, high = spec.range_of("misfire", model)
            for c in range(1, base.cylinder_count + 1):
                out.append(
                    _Condition(
                        f"misfire cylinder {c}",
                        "misfire",
                        excitation_for(model, engine, misfire=(c,)),
                        dampers,
                        low,
                        high,
                        f"cylinder {c} not firing (motored pressure), the others normal",
                        misfire=c,
                    )
                )
    elif spec.misfire:
        notes.append("misfire not calculated: the excitation is not an engine's pressure")
    if spec.damper_out and dampers:
        low, high = spec.range_of("damper-out", model)
        names = ", ".join(d.name for d in dampers)
        out.append(
            _Condition(
                "damper out of order",
                "damper-out",
                base,
                (),
                low,
                high,
                f"without the damper(s) {names} (a viscous damper's ring runs free)",
            )
        )
    return out


# ---- evaluation of one condition -----------------------------------------------------------------
def _grid(low: float, high: float, step: float) -> NDArray[np.float64]:
    count = max(2, math.floor((high - low) / step * (1 + 1e-12)) + 1)
    grid = low + step * np.arange(count)
    return np.unique(np.concatenate([grid[grid < high], [high]]))


def _evaluate(
    model: TorsionModel,
    cond: _Condition,
    orders: NDArray[np.float64],
    checks: Sequence[Check],
    spec: TvcSpec,
    n0: float,
) -> tuple[list[Verdict], list[BarredSpeedRange], ResponseResult]:
    """(verdicts, barred ranges, response) of one condition."""
    from crankdyn.torsion.sweep import forced_response

    r = forced_response(
        model,
        cond.excitation,
        _grid(cond.low, cond.high, spec.step),
        orders,
        dampers=cond.dampers,
        rules=False,
    )
    tol = spec.tachometer_tolerance
    margins = WIDENING_SOURCES[spec.widening] + (
        f"; tachometer tolerance ±{tol * 100:g} %" if tol else ""
    )
    barred: list[BarredSpeedRange] = []
    found = []  # (check, exceedance, declared start, end)
    for check in checks:
        if not check.barred:
            continue
        for ex in exceedances(r, _column(check.curve), _column(check.limit)):
            lo, hi = barred_limits(ex.peak_speed, n0, spec.widening)
            start = min(ex.start, lo) * (1.0 - tol)
            end = max(ex.end, hi) * (1.0 + tol)
            found.append((check, ex, start, end))
    for check, ex, start, end in found:
        reasons = []
        permitted = True
        if check.m68 and end > 0.8 * n0:
            permitted = False
            reasons.append(
                f"the declared range reaches {end / n0:.3f} n_0 > 0.8 n_0, where M68.4 permits "
                "no barred range"
            )
        if start <= n0 <= end:
            permitted = False
            reasons.append(
                "the declared range contains the rated speed n_0, which cannot be barred"
            )
        if check.transient_limit is None:
            permitted = False
            reasons.append("no transient limit is given for this component")
        else:
            w = cv.resolved_worst(r, check.curve, check.transient_limit, low=ex.start, high=ex.end)
            if w is None or w[0] > w[1]:
                permitted = False
                reasons.append("the steady-state response exceeds the transient limit")
        if ex.open_start or ex.open_end:
            reasons.append("reaches an end of the swept range: sweep further")
        if permitted:
            reasons.append("limit exceeded only where a barred range is permitted: pass quickly")
        barred.append(
            BarredSpeedRange(
                component=check.component,
                condition=cond.name,
                start=start,
                end=end,
                permitted=permitted,
                exceeds_start=ex.start,
                exceeds_end=ex.end,
                critical_speed=ex.peak_speed,
                worst_ratio=ex.peak_ratio,
                reason="; ".join(reasons),
                margins=margins,
            )
        )
    excluded = _merge([(b.start, b.end) for b in barred])
    verdicts: list[Verdict] = []
    curves = {}
    for check in checks:
        worst = cv.resolved_worst(r, check.curve, check.limit, excluded)
        curves[(check.component, check.quantity)] = check
        if worst is None:
            continue
        value, limit, speed = worst
        verdicts.append(
            Verdict(
                component=check.component,
                condition=cond.name,
                quantity=check.quantity + (" (continuous running)" if excluded else ""),
                worst=value,
                limit=limit,
                unit=check.unit,
                margin=1.0 - value / limit,
                passed=bool(value <= limit),
                source=check.source,
                speed=speed,
                kind=check.quantity,
            )
        )
    for b, (check, ex, _s, _e) in zip(barred, found, strict=True):
        label = f"barred range {b.start * RPM:.1f}-{b.end * RPM:.1f} rpm"
        if check.m68:
            # M68.4: no barred range above 0.8 n_0 (the declared range, margins included)
            verdicts.append(
                Verdict(
                    component=check.component,
                    condition=cond.name,
                    quantity=f"end of the declared {label} (λ = n/n_0)",
                    worst=b.end / n0,
                    limit=0.8,
                    unit="",
                    margin=1.0 - b.end / n0 / 0.8,
                    passed=bool(b.end <= 0.8 * n0),
                    source=f"{M68}: barred speed ranges only below λ = 0.8; margins: {margins}",
                    speed=b.end,
                    kind="barred range end",
                )
            )
        if b.start <= n0 <= b.end:
            verdicts.append(
                Verdict(
                    component=check.component,
                    condition=cond.name,
                    quantity=f"start of the declared {label} vs the rated speed (n/n_0)",
                    worst=1.0,
                    limit=b.start / n0,
                    unit="",
                    margin=1.0 - n0 / b.start,
                    passed=False,
                    source="the rated speed cannot lie in a barred range",
                    speed=n0,
                    kind="barred range at n_0",
                )
            )
        if check.transient_limit is None:
            verdicts.append(
                Verdict(
                    component=check.component,
                    condition=cond.name,
                    quantity=f"{label}: no transient limit given",
                    worst=ex.peak,
                    limit=float(check.limit(np.array([ex.peak_speed]))[0]),
                    unit=check.unit,
                    margin=1.0 - ex.peak_ratio,
                    passed=False,
                    source=check.source,
                    speed=ex.peak_speed,
                    note="a barred range needs the component's transient limit",
                    kind="barred range without a transient limit",
                )
            )
            continue
        w = cv.resolved_worst(r, check.curve, check.transient_limit, low=ex.start, high=ex.end)
        value, limit, speed = w if w is not None else (ex.peak, math.nan, ex.peak_speed)
        verdicts.append(
            Verdict(
                component=check.component,
                condition=cond.name,
                quantity=f"steady state in the {label} vs the transient limit",
                worst=value,
                limit=limit,
                unit=check.unit,
                margin=1.0 - value / limit if np.isfinite(limit) else -math.inf,
                passed=bool(np.isfinite(limit) and value <= limit),
                source=check.transient_source,
                speed=speed,
                kind="barred range steady state",
            )
        )
    return verdicts, barred, r


def _passage_cases(
    group: Sequence[Evaluated], barred: Sequence[BarredSpeedRange]
) -> list[tuple[_Condition, list[BarredSpeedRange]]]:
    """(condition, permitted barred ranges) to pass in the time domain: a single condition's
    own; for the misfiring cylinders every united range once, with the cylinder whose own
    range there responds most."""
    permitted = [b for b in barred if b.permitted]
    if len(group) == 1:
        return [(group[0][0], permitted)] if permitted else []
    cases = []
    for u in permitted:
        best, ratio = None, -math.inf
        for cond, _vs, bs, _r in group:
            for b in bs:
                overlaps = b.component == u.component and b.start <= u.end and b.end >= u.start
                if overlaps and b.worst_ratio > ratio:
                    best, ratio = cond, b.worst_ratio
        if best is not None:
            cases.append((best, [u]))
    return cases


def _union(ranges: Sequence[BarredSpeedRange]) -> list[BarredSpeedRange]:
    """The barred ranges of several conditions (the misfiring cylinders) merged per component
    where they overlap: the union of the declared ranges, permitted only where every one is,
    the condition naming the conditions that produce it."""
    out = []
    for component in dict.fromkeys(b.component for b in ranges):
        own = sorted((b for b in ranges if b.component == component), key=lambda b: b.start)
        group: list[BarredSpeedRange] = []
        for b in [*own, None]:
            if b is not None and (not group or b.start <= max(g.end for g in group)):
                group.append(b)
                continue
            worst = max(group, key=lambda g: g.worst_ratio)
            names = list(dict.fromkeys(g.condition for g in group))
            out.append(
                dataclasses.replace(
                    worst,
                    condition=_names(names),
                    start=min(g.start for g in group),
                    end=max(g.end for g in group),
                    exceeds_start=min(g.exceeds_start for g in group),
                    exceeds_end=max(g.exceeds_end for g in group),
                    permitted=all(g.permitted for g in group),
                    reason="; ".join(dict.fromkeys(g.reason for g in group)),
                )
            )
            group = [b] if b is not None else []
    return out


def _names(names: Sequence[str]) -> str:
    """``misfire cylinders 1, 2, 6`` for several misfire conditions, else the names joined."""
    prefix = "misfire cylinder "
    if len(names) > 1 and all(n.startswith(prefix) for n in names):
        numbers = sorted(int(n.removeprefix(prefix)) for n in names)
        return "misfire cylinders " + ", ".join(map(str, numbers))
    return ", ".join(names)


def _merge(intervals: Iterable[tuple[float, float]]) -> list[tuple[float, float]]:
    out: list[list[float]] = []
    for a, b in sorted(intervals):
        if out and a <= out[-1][1]:
            out[-1][1] = max(out[-1][1], b)
        else:
            out.append([a, b])
    return [(a, b) for a, b in out]


# ---- passage through barred ranges ---------------------------------------------------------------
def _column(
    func: Callable[[Any], NDArray[np.float64]],
) -> Callable[[Any], NDArray[np.float64]]:
    """``func`` with its result as one column (speeds x 1), the layout
    :func:`~crankdyn.torsion.rules.exceedances` reads."""
    return lambda x: func(x)[:, None]


def _load_torque(model: TorsionModel, speeds: ArrayLike) -> NDArray[np.float64]:
    """Mean load torque reflected to the reference shaft (N m) at reference speeds (rad/s)."""
    from crankdyn.torsion.sources import HarmonicSource

    n = np.asarray(speeds, dtype=float)
    total = np.zeros(n.shape)
    ratios = model.speed_ratios
    for source in model.sources:
        if not isinstance(source, HarmonicSource) or source.load is None:
            continue  # an engine carries no load law
        r = abs(float(ratios[model.index(source.at)]))
        total = total + r * source.load.at(r * n)
    return total


def _passages(
    model: TorsionModel,
    cond: _Condition,
    orders: NDArray[np.float64],
    checks: Sequence[Check],
    barred: Sequence[BarredSpeedRange],
    spec: TvcSpec,
    n0: float,
    load: str,
    mean: MeanTorque | None,
) -> tuple[list[Passage], list[Verdict], list[str]]:
    """Passage rows, verdicts and notes of one condition's barred ranges (module docstring)."""
    from crankdyn.torsion.solvers import linear_system
    from crankdyn.torsion.transient import transient_response

    passages: list[Passage] = []
    verdicts: list[Verdict] = []
    notes: list[str] = []
    if not barred:
        return passages, verdicts, notes
    inertia = float(np.sum(linear_system(model, cond.dampers).inertia))
    passage_load = spec.passage_load or ("law" if load == "propeller" else "none")

    def load_at(w: ArrayLike) -> NDArray[np.float64]:
        return _load_torque(model, w) if passage_load == "law" else np.zeros(np.size(w))

    rated_torque = float(_load_torque(model, [n0])[0])

    def engine_at(w: ArrayLike) -> NDArray[np.float64]:
        return spec.engine_torque_at(w, rated_torque)

    if spec.engine_torque_curve is None and not float(engine_at([n0])[0]) > 0.0:
        notes.append(
            f"{cond.name}: the passage through the barred ranges is not calculated: give "
            "[tvc] engine_torque (no load law gives the rated torque)"
        )
        return passages, verdicts, notes
    for a, b in _merge([(x.start, x.end) for x in barred]):
        w = np.linspace(a, b, 401)
        spare = engine_at(w) - load_at(w)
        label = f"{a * RPM:.1f}-{b * RPM:.1f} rpm"
        if np.min(spare) <= 0.0:
            verdicts.append(
                Verdict(
                    component="installation",
                    condition=cond.name,
                    quantity=f"acceleration torque through the barred range {label}",
                    worst=float(np.min(spare)),
                    limit=0.0,
                    unit="N·m",
                    margin=-math.inf,
                    passed=False,
                    source="the engine's torque less the load law: the range cannot be passed",
                    kind="acceleration torque",
                )
            )
            continue
        t_in = float(np.trapezoid(inertia / spare, w))
        w0, w1 = a * (1.0 - LEAD_IN), b * (1.0 + RUN_OUT)
        ww = np.linspace(w0, w1, 801)
        duration = float(np.trapezoid(inertia / np.maximum(engine_at(ww) - load_at(ww), 1e-9), ww))
        run = transient_response(
            model,
            cond.excitation,
            orders,
            run_up=(w0, w1),
            duration=duration,
            dampers=cond.dampers,
            samples_per_cycle=360,
            start="steady",
        )
        passages.append(
            Passage(
                condition=cond.name,
                start=a,
                end=b,
                time_in_range=t_in,
                acceleration_torque=float(np.min(spare)),
                run_from=w0,
                run_to=w1,
                duration=duration,
                elements=next(
                    (
                        c.elements
                        for c in checks
                        if c.elements and any(x.component == c.component for x in barred)
                    ),
                    (),
                ),
                note=(
                    f"run-up at J dΩ/dt = T_engine - T_load, J = {inertia:.6g} kg·m², T_engine "
                    + (
                        "from the engine's torque-speed curve"
                        if spec.engine_torque_curve is not None
                        else f"= {float(engine_at([a])[0]) / 1e3:.6g} kN·m"
                    )
                    + ", load: "
                    f"{'the load law' if passage_load == 'law' else 'none (run up unloaded)'}"
                ),
                transient=run,
            )
        )
        inside = run.speed >= a
        for check in checks:
            if check.transient_curve is None or check.transient_limit is None:
                continue
            if not any(x.component == check.component for x in barred):
                continue
            values = check.transient_curve(run, mean)[inside]
            limits = check.transient_limit(run.speed[inside])
            with np.errstate(invalid="ignore", divide="ignore"):
                ratio = np.where(np.isfinite(limits) & (limits > 0), values / limits, np.nan)
            if not np.any(np.isfinite(ratio)):
                continue
            k = int(np.nanargmax(ratio))
            verdicts.append(
                Verdict(
                    component=check.component,
                    condition=cond.name,
                    quantity=f"transient peak passing {label} ({t_in:.3g} s in the range)",
                    worst=float(values[k]),
                    limit=float(limits[k]),
                    unit=check.unit,
                    margin=1.0 - float(ratio[k]),
                    passed=bool(ratio[k] <= 1.0),
                    source=check.transient_source,
                    speed=float(run.speed[inside][k]),
                    kind="transient passage",
                )
            )
    return passages, verdicts, notes


# ---- the calculation --------------------------------------------------------------------------
def tvc(
    model: TorsionModel,
    engine: Engine | None = None,
    spec: TvcSpec | None = None,
    *,
    passage: bool = True,
    orders: ArrayLike | None = None,
) -> TvcResult:
    """The torsional vibration calculation of an installation (module docstring).

    Every running condition's resolved forced response, checked component by component
    against its limit: propulsion shafts against IACS UR M68.4 (tau_C, tau_T, barred ranges
    only below 0.8 n_0), elastic couplings against the catalogue's T_KW, T_Kmax, T_KN and P_KV
    (DIN 740-2), crank spans, gears, machines and dampers against their makers' limits; the
    barred ranges widened by the chosen rule (Lloyd's Register Rules for Ships Pt 5 Ch 8 2.5,
    or none) and the tachometer tolerance; the passage through them in the time domain.

    Parameters
    ----------
    model : TorsionModel
        The torsional model (an engine file's [torsion] with its shaft line, or a model file).
    engine : Engine or None
        The engine whose cylinders excite it, or None (the model's own engine or excitation).
    spec : TvcSpec or None
        The TVC settings; None: the model's ``[tvc]`` or the defaults.
    passage : bool
        Whether to run the time-domain passage through the barred ranges (default True).
    orders : array_like or None
        The excitation orders (multiples of the crankshaft speed); None: the cycle's harmonics
        to 12 with the orders of the model's sources
        (:func:`crankdyn.torsion.sources.default_orders`).

    Returns
    -------
    TvcResult
        ``verdicts`` (every component x condition), ``barred_ranges``, ``passages``,
        ``condition_results`` (with their responses), ``modes`` and ``campbell``.

    Raises
    ------
    InputError
        Naming the model's file and the key ``rated_speed`` where no rated speed n_0 is given
        (``[rules]``, ``[operating]`` or the engine's speed), ``speed_range`` where no condition
        has a speed range, ``[rules] shaft`` (with the shaft's masses) where an M68 shaft has
        no diameter, ``diameter`` where a crank span has none for the nominal stress; and the
        errors of the forced response (orders, speeds).

    Examples
    --------
    Two masses, J_1 = 1 and J_2 = 3 kg m^2, on a 50 mm intermediate shaft (k = 1e5 N m/rad,
    loss factor 0.1, sigma_B = 600 N/mm^2, C_K = 1), a harmonic torque of 100 N m per order
    (orders 1 and 2) on the first mass, n_0 = 400 rad/s:

    >>> from crankdyn.torsion.campbell import OperatingRange
    >>> from crankdyn.torsion.excitation import ExcitationSpec
    >>> from crankdyn.torsion.model import Mass, Shaft, ShaftGeometry, TorsionModel
    >>> from crankdyn.torsion.rules import RuleSet, ShaftLimit
    >>> model = TorsionModel(
    ...     (Mass("crank", 1.0, cylinders=(1,)), Mass("propeller", 3.0)),
    ...     (Shaft(("crank", "propeller"), stiffness=1e5, loss_factor=0.1,
    ...            geometry=ShaftGeometry(0.05), name="intermediate shaft"),),
    ...     excitation=ExcitationSpec(torque=100.0),
    ...     operating=OperatingRange(100.0, 400.0, rated=400.0),
    ...     rules=RuleSet(None, (ShaftLimit(("crank", "propeller"), 600e6),)),
    ... )
    >>> result = tvc(model, orders=[1.0, 2.0])
    >>> result.passed, [c.name for c in result.conditions]
    (True, ['normal firing'])

    The worst stress is the order-1 resonance at omega_n = sqrt(k (1/J_1 + 1/J_2)) = 365.148
    rad/s, where k |dtheta| = T J_2 / (J_1 + J_2) / eta = 750 N m, over W_p = pi d^3/16:
    30.558 MPa, against tau_C = (600 + 160)/18 C_D 1.38 (lambda = 0.91):

    >>> (row,) = result.verdicts
    >>> f"{row.worst / 1e6:.3f} MPa <= {row.limit / 1e6:.3f} MPa at {row.speed:.3f} rad/s"
    '30.558 MPa <= 45.174 MPa at 365.148 rad/s'
    """
    from crankdyn.torsion.campbell import campbell
    from crankdyn.torsion.modal import natural_modes
    from crankdyn.torsion.sources import default_orders

    spec = spec or getattr(model, "tvc", None) or TvcSpec()
    engine = engine or getattr(model, "engine", None)
    notes: list[str] = []
    # a RuleSet and an OperatingRange, or None (TorsionModel holds them as objects)
    rules: Any = model.rules
    operating: Any = model.operating
    rated = None
    if rules is not None and rules.rated_speed is not None:
        rated = rules.rated_speed
    elif operating is not None and operating.rated is not None:
        rated = operating.rated
    elif engine is not None:
        rated = engine.speed
    if rated is None:
        raise InputError(
            "the TVC needs the rated speed n_0: give [operating] rated_speed",
            file=model.source,
            key="rated_speed",
        )
    load = _load_of(model, spec)
    model = _with_load(model, engine, load, rated)
    conditions = _conditions(model, engine, spec, notes)
    base = conditions[0].excitation
    if orders is None:
        orders = default_orders(model, base.cycle, engine=base.cylinder_count > 0)
    orders = np.asarray(orders, dtype=float)
    mean = _mean_torque_function(model)
    all_checks = {}
    for cond in conditions:
        key = cond.dampers
        if key not in all_checks:
            checks, check_notes = _checks(model, spec, rated, cond.dampers)
            all_checks[key] = checks
            if cond.kind == "normal":
                notes.extend(check_notes)
    results = []
    for cond in conditions:
        verdicts, barred, r = _evaluate(model, cond, orders, all_checks[cond.dampers], spec, rated)
        results.append((cond, verdicts, barred, r))
    # misfire: every cylinder calculated; every check reports its worst cylinder
    kept = [x for x in results if x[0].kind != "misfire"]
    misfires = [x for x in results if x[0].kind == "misfire"]
    groups = [[x] for x in kept]
    if misfires:
        groups.append(misfires)
    order_of = {"normal": 0, "misfire": 1, "damper-out": 2}
    groups.sort(key=lambda g: order_of[g[0][0].kind])
    condition_results = []
    verdicts_all: list[Verdict] = []
    barred_all: list[BarredSpeedRange] = []
    passages_all: list[Passage] = []
    for group in groups:
        cond0 = group[0][0]
        checks = all_checks[cond0.dampers]
        if len(group) == 1:
            name, description = cond0.name, cond0.description
            verdicts = list(group[0][1])
            response = group[0][3]
        else:
            worst_of: dict = {}
            for _cond, vs, _barred, _r in group:
                for v in vs:
                    row = (v.component, v.kind or v.quantity)
                    if row not in worst_of or v.margin < worst_of[row].margin:
                        worst_of[row] = v
            verdicts = list(worst_of.values())
            overall = min(group, key=lambda x: min((v.margin for v in x[1]), default=math.inf))
            response = overall[3]
            name = "misfire (worst cylinder per check)"
            description = (
                f"each of the {len(group)} cylinders not firing in turn (motored pressure); every "
                "check reports its worst cylinder (named in its condition); the plots show "
                f"{overall[0].name}, the worst overall"
            )
            notes.append(
                f"misfire: every cylinder calculated ({len(group)} conditions); each check "
                "reports the cylinder with its smallest margin"
            )
        barred = [b for _c, _v, bs, _r in group for b in bs]
        if len(group) > 1:
            barred = _union(barred)
        passages = []
        if passage:
            for cond, bs in _passage_cases(group, barred):
                found, more, pnotes = _passages(
                    model, cond, orders, checks, bs, spec, rated, load, mean
                )
                passages.extend(found)
                verdicts.extend(more)
                notes.extend(pnotes)
        verdicts_all.extend(verdicts)
        barred_all.extend(barred)
        passages_all.extend(passages)
        condition_results.append(
            ConditionResult(
                name=name,
                kind=cond0.kind,
                low=cond0.low,
                high=cond0.high,
                description=description,
                verdicts=tuple(verdicts),
                barred_ranges=tuple(barred),
                passages=tuple(passages),
                response=response,
                curves={(c.component, c.quantity): c for c in checks},
            )
        )
    low = min(c.low for c in conditions)
    high = max(c.high for c in conditions)
    modes = natural_modes(model)
    try:
        diagram = campbell(model, orders, (low, high), excitation=base)
    except InputError as exc:  # pragma: no cover - the same inputs ran the responses
        diagram = None
        notes.append(f"Campbell diagram not drawn: {exc.message}")
    if not verdicts_all:
        notes.append("no component has a limit: nothing was checked")
    return TvcResult(
        model_name=model.name,
        rated_speed=rated,
        load=load,
        passed=bool(verdicts_all) and all(v.passed for v in verdicts_all),
        verdicts=tuple(verdicts_all),
        barred_ranges=tuple(barred_all),
        passages=tuple(passages_all),
        conditions=tuple(condition_results),
        notes=tuple(notes),
        tachometer_tolerance=spec.tachometer_tolerance,
        widening=spec.widening,
        model=model,
        engine=engine,
        modes=modes,
        campbell=diagram,
        spec=spec,
        condition_results=tuple(condition_results),
    )
