"""The response of a shaft line to a transient event (analysis).

The reflected equations of the line (:mod:`crankdyn.torsion.event_line`), in absolute angles of
the degrees of freedom (a grounded model: angles relative to a frame turning at the mean
speed),

    M x'' + C x' + K x = T_mean(t) + T_harmonic(t) + T_event(t),

are integrated by the exact modal integrator of :mod:`crankdyn.torsion.integrator` (the
forcing sampled and taken linear between the samples), segment by segment: the forcing's jumps
and kinks (an impact's start and end, a fault, a ramp's end) fall on samples. The terms:

- T_mean: the engines' torque and the load laws' (the engines carry the loads at a constant
  speed; along a start or a stop the engines' torque of the rigid-body equation,
  :func:`crankdyn.torsion.event_line.speed_profile`): the line's mean speed follows from them;
- T_harmonic: the cylinders' and the sources' harmonic torques at the mean speed and crank
  angle (:func:`crankdyn.torsion.sources.assemble_forcing`, interpolated over a grid of 201
  speeds), when an excitation is given; the run then starts in their steady state;
- T_event: the event's torque at its mass (:mod:`crankdyn.torsion.events`).

A clutch engagement changes the system: while its halves slip the element between them is
replaced by the friction torque, and the speeds meeting (slip -> stick) or the element's torque
exceeding the friction torque (stick -> slip) is found by event detection: a sign change of the
slip speed (or of |T| - T_friction) between two samples is bracketed and its instant found to
1e-12 s by Brent's method on the exact solution within the step; the run continues from there
in the other system.

A clutch engagement's mean torques are taken from the run itself (:class:`_Sampled`): the
engine on its speed governor (:mod:`crankdyn.torsion.event_governor`) and the load laws at
every loaded mass's own speed, sampled every governor sample time and held between samples; the
samples are cuts of the run, so the forcing stays piecewise linear and the integration exact.
The halves' first lock is kept (``loaded_from`` of the result: gear reversals are judged from
it, :meth:`crankdyn.torsion.event_result.EventResult.reversal`).

Step rule (module constants): the step h is the smallest of a tenth of the period of the
highest natural frequency of interest (default every mode of the model: the integration is
exact for any step, the step is what resolves the response in time) and a fortieth of the
period of the highest frequency the forcing holds (the orders' at the highest speed, the
event's own), and 1/200 of the run. The largest and smallest torque of every element are found
on every step (whatever is stored) and refined on the exact solution within the two steps
around them (41 points each, then a parabola), at the few dofs each element's torque reads.

Modal truncation: with ``max_frequency`` only the modes up to it are integrated, those above
follow the forcing quasi-statically (:mod:`crankdyn.torsion.integrator`, "Modal truncation"),
each step O(N x kept modes); the bound of the error is reported with the result
(:func:`_truncation`: every element's bound in N m, the cut-off, the modes kept, a note).

Memory: the run is integrated in blocks of at most :data:`BLOCK_BYTES` of working arrays, and
at most ``max_samples`` samples are kept (every ``stride``-th step, and the switching instants
and the last): the bound is ``max_samples`` x (masses + elements + 2) x 8 bytes plus a block,
reported with the result.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.errors import InputError
from crankdyn.roots import brentq
from crankdyn.torsion.event_line import (
    Harmonics,
    Line,
    Profile,
    constant_profile,
    harmonics_of,
    line_of,
    speed_profile,
)
from crankdyn.torsion.events import ClutchEngagement, SpeedChange
from crankdyn.torsion.integrator import (
    ModalState,
    ModalSystem,
    linear_recurrence,
    loaded,
    modal_system,
)

if TYPE_CHECKING:
    from crankdyn.torsion.dampers import Damper
    from crankdyn.torsion.event_governor import GovernorRun
    from crankdyn.torsion.event_result import EventResult
    from crankdyn.torsion.events import Event, TorqueEvent
    from crankdyn.torsion.excitation import Excitation
    from crankdyn.torsion.model import TorsionModel

__all__ = ["BLOCK_BYTES", "FORCE_POINTS", "MODE_POINTS", "event_response", "truncation_factor"]

MODE_POINTS = 10
"""Steps per period of the highest natural frequency of interest."""
FORCE_POINTS = 40
"""Steps per period of the highest frequency of the forcing."""
BLOCK_BYTES = 8 * 2**20
"""The working arrays of one block of steps (bytes)."""
REFINE_POINTS = 41
"""Points per step on which a peak is refined."""
MAX_SWITCHES = 1000
"""Most slip-stick switches of a clutch in one run."""

Torques = Callable[[NDArray[np.float64], NDArray[np.float64]], NDArray[np.float64]]
Forcing = Callable[[NDArray[np.float64]], NDArray[np.float64]]


@dataclass(eq=False)
class _Mode:
    """One linear system the run is in: its propagator, its own forcing and how its elements'
    torques read (a clutch's element slipping carries the friction torque)."""

    key: str
    system: ModalSystem
    extra: Forcing | None = None
    offset: NDArray[np.float64] | None = None  # (E,) torque subtracted from k twist / |r|
    friction: tuple[int, float, Callable[[NDArray[np.float64]], NDArray[np.float64]]] | None = None
    watch: Callable[[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]], Any] | None = (
        None
    )
    switch: Callable[[float, NDArray[np.float64], NDArray[np.float64]], _Mode] | None = None


def _element_torques(
    line: Line,
    mode: _Mode,
    t: NDArray[np.float64],
    x: NDArray[np.float64],
    v: NDArray[np.float64],
    f: NDArray[np.float64],
) -> NDArray[np.float64]:
    """(L, E + G) torques the elements and the rigid gear meshes transmit (own sense, N m) at
    samples t (L,), angles x, rates v and generalised torques f (L, n)."""
    ends = line.element_dofs
    xa = np.where(ends[:, 0] >= 0, x[:, np.maximum(ends[:, 0], 0)], 0.0)
    xb = np.where(ends[:, 1] >= 0, x[:, np.maximum(ends[:, 1], 0)], 0.0)
    out = line.element_stiffness * (xa - xb) / line.element_ratio
    if mode.offset is not None:
        out = out - mode.offset
    if mode.friction is not None:
        e, sign, capacity = mode.friction
        out[:, e] = sign * capacity(t)
    if not line.gears:
        return out
    meshes = np.empty((t.size, len(line.gears)))
    for i, g in enumerate(line.gears):
        d = g.dof
        system = mode.system
        accel = (f[:, d] - x @ system.stiffness[d] - v @ system.damping[d]) / line.inertia[d]
        meshes[:, i] = g.inertia * g.ratio * accel + sum(s * out[:, e] for e, s in g.elements)
    return np.concatenate([out, meshes], axis=1)


def _quasi_static(
    line: Line, mode: _Mode, t: NDArray[np.float64], mean: NDArray[np.float64]
) -> NDArray[np.float64]:
    """(L, E + G) the elements' torques under the mean torques alone, quasi-statically (the
    static twist of :meth:`ModalSystem.static`; the free bodies accelerating as a whole)."""
    x = mode.system.static(mean)
    plain = _Mode(mode.key, mode.system)
    return _element_torques(line, plain, t, x, np.zeros_like(x), mean)


def _series(
    line: Line,
    mode: _Mode,
    t: NDArray[np.float64],
    x: NDArray[np.float64],
    v: NDArray[np.float64],
    force: Forcing,
    mean: Forcing,
) -> NDArray[np.float64]:
    """(L, 2 (E + G)): the torques, then their vibratory part (less the quasi-static torques
    of the mean torques) at samples t."""
    total = _element_torques(line, mode, t, x, v, force(t))
    return np.concatenate([total, total - _quasi_static(line, mode, t, mean(t))], axis=1)


def _forcing(
    line: Line,
    profile: Profile,
    events: Sequence[tuple[int, TorqueEvent]],
    harmonics: Harmonics | None,
    *,
    mean: bool,
    engine: Forcing | None = None,
) -> tuple[Forcing, Forcing]:
    """(f, f_mean): the generalised torques (L, n) at times (L,), and their mean part;
    ``engine`` further mean torques (L, n) sampled from the run (a clutch's governed engine
    and loads, :class:`_Sampled`)."""

    def mean_part(t: NDArray[np.float64]) -> NDArray[np.float64]:
        f = np.zeros((t.size, line.size))
        if mean:
            f += (profile.drive(t) - profile.brake(t))[:, None] * line.drive[None, :]
            if profile.loads:
                f += line.load_forcing(profile.speed(t))
        if engine is not None:
            f += engine(t)
        return f

    def total(t: NDArray[np.float64]) -> NDArray[np.float64]:
        f = mean_part(t)
        if harmonics is not None:
            f += harmonics(profile.speed(t), profile.angle(t)) * profile.scale(t)[:, None]
        for index, event in events:
            f += line.at_mass(index, event.torque(t))
        return f

    return total, mean_part


# ---- the clutch: two systems and the switches between them ------------------------------------
def _clutch_modes(
    line: Line, event: ClutchEngagement, absolute_damping: str, cutoff: float | None = None
) -> tuple[_Mode, int, ModalSystem]:
    """The slipping mode of a clutch engagement (its switch builds the locked one), the
    element, and the locked system."""
    e = line.element(event.between)
    a, b = (int(v) for v in line.element_dofs[e])
    r = float(line.element_ratio[e])
    k_e, c_e = float(line.element_stiffness[e]), float(line.element_damping[e])
    k_slip = line.stiffness - line.element_matrix(e, k_e)
    c_slip = line.damping - line.element_matrix(e, c_e)
    slip_system = modal_system(
        line.inertia, k_slip, c_slip, absolute_damping=absolute_damping, max_frequency=cutoff
    )
    lock_system = modal_system(
        line.inertia,
        line.stiffness,
        line.damping,
        absolute_damping=absolute_damping,
        max_frequency=cutoff,
    )
    direction = np.zeros(line.size)
    direction[a], direction[b] = -r, r  # the friction on a (slip a faster than b: -|r| T)
    switches = [0]

    def slipping(sign: float) -> _Mode:
        def extra(t: NDArray[np.float64]) -> NDArray[np.float64]:
            return (sign * event.friction(t))[:, None] * direction[None, :]

        def watch(t: NDArray[np.float64], x: NDArray[np.float64], v: NDArray[np.float64]) -> Any:
            return -sign * (v[:, a] - v[:, b])  # reaches 0 when the speeds meet

        def switch(t: float, x: NDArray[np.float64], v: NDArray[np.float64]) -> _Mode:
            cap = float(event.friction(np.array([t]))[0])
            # the element put back carrying the friction torque of this instant
            delta = (x[a] - x[b]) - sign * cap * r / k_e
            return locked(delta, sign)

        return _Mode("slip", slip_system, extra, None, (e, sign, event.friction), watch, switch)

    def locked(delta: float, sign: float) -> _Mode:
        offset = np.zeros(line.element_stiffness.size)
        offset[e] = k_e * delta / r
        const = np.zeros(line.size)
        const[a], const[b] = k_e * delta, -k_e * delta
        tol = 1e-9 * event.max_torque

        def extra(t: NDArray[np.float64]) -> NDArray[np.float64]:
            return np.broadcast_to(const, (t.size, line.size)).copy()

        def watch(t: NDArray[np.float64], x: NDArray[np.float64], v: NDArray[np.float64]) -> Any:
            torque = (k_e * (x[:, a] - x[:, b] - delta) + c_e * (v[:, a] - v[:, b])) / r
            return np.abs(torque) - event.friction(t) - tol

        def switch(t: float, x: NDArray[np.float64], v: NDArray[np.float64]) -> _Mode:
            switches[0] += 1
            if switches[0] > MAX_SWITCHES:
                raise InputError(
                    f"the clutch slips and sticks more than {MAX_SWITCHES} times (chatter): "
                    "give a longer rise time or a larger torque",
                    key="rise_time",
                )
            torque = (k_e * (x[a] - x[b] - delta) + c_e * (v[a] - v[b])) / r
            return slipping(1.0 if torque > 0.0 else -1.0)

        return _Mode("locked", lock_system, extra, offset, None, watch, switch)

    sign = 1.0 if event.speeds[0] > event.speeds[1] else -1.0
    return slipping(sign), e, lock_system


# ---- storing the samples and the peaks --------------------------------------------------------
@dataclass(eq=False)
class _Window:
    """What refines a peak: the exact solution within the steps around a sample."""

    mode: _Mode
    t0: float
    step: float
    states: list[ModalState]  # at the window's samples
    u: NDArray[np.complex128]  # (samples, m)
    g: NDArray[np.float64]  # (samples, b)
    f: NDArray[np.float64]  # (samples, n) the generalised torques (N m)
    force: Forcing
    mean: Forcing

    def at(
        self, s: int, taus: ArrayLike, dofs: NDArray[np.int_]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """(t, x, v) at times ``taus`` (s) into the window's step s, the angles and rates at
        ``dofs`` only (the exact solution; the modes left out quasi-statically under the
        forcing's first-order hold)."""
        system = self.mode.system
        tau = np.asarray(taus, dtype=float)
        st = system.within(
            self.states[s], self.u[s], self.u[s + 1], self.g[s], self.g[s + 1], self.step, tau
        )
        slope = (self.f[s + 1] - self.f[s]) / self.step
        force = self.f[s][None, :] + tau[:, None] * slope[None, :]
        rate = np.broadcast_to(slope, force.shape)
        x, v = system.to_physical(st, dofs, force, rate)
        return self.t0 + s * self.step + tau, x, v


@dataclass(eq=False)
class _Recorder:
    """The kept samples (every stride-th) and every element's extremes over every step."""

    line: Line
    stride: int
    frame: Callable[[NDArray[np.float64]], NDArray[np.float64]]
    count: int = 0
    times: list[NDArray[np.float64]] = field(default_factory=list)
    speeds: list[NDArray[np.float64]] = field(default_factory=list)
    torques: list[NDArray[np.float64]] = field(default_factory=list)
    vibratory: list[NDArray[np.float64]] = field(default_factory=list)
    mean: list[NDArray[np.float64]] = field(default_factory=list)
    high: NDArray[np.float64] | None = None
    low: NDArray[np.float64] | None = None
    high_at: NDArray[np.float64] | None = None
    low_at: NDArray[np.float64] | None = None
    windows: dict[tuple[int, int], _Window] = field(default_factory=dict)
    residual: NDArray[np.float64] | None = None
    coupling: NDArray[np.float64] | None = None
    rate: NDArray[np.float64] | None = None
    kicks: NDArray[np.float64] | None = None
    paces: tuple[NDArray[np.float64], NDArray[np.float64]] | None = None
    _reaches: dict[int, NDArray[np.float64]] = field(default_factory=dict)

    def pace(self, f: NDArray[np.float64], rates: NDArray[np.float64]) -> None:
        """Track every dof's largest torque (N m) and rate of torque (N m/s)."""
        top, speed = np.max(np.abs(f), axis=0), np.max(np.abs(rates), axis=0)
        if self.paces is not None:
            top, speed = np.maximum(self.paces[0], top), np.maximum(self.paces[1], speed)
        self.paces = (top, speed)

    def frequency(self) -> float:
        """The forcing's own pace (rad/s): the largest over the dofs of the largest rate of
        torque over the largest torque (omega of a sine, pi / T of a half sine of length T)."""
        if self.paces is None:
            return 0.0
        top, speed = self.paces
        loaded = top > 0.0
        return float(np.max(speed[loaded] / top[loaded], initial=0.0))

    def _twist(self, system: ModalSystem, x: NDArray[np.float64]) -> NDArray[np.float64]:
        """(L, E + G) |k twist / r| of every element (N m) under angles x (L, n) of the modes
        left out; a gear mesh's: the sum over its elements, and its wheel's inertia torque
        of the elastic torque K x at the wheel (the modes' accelerations are omega^2 times
        their displacements: their dynamic part's share of the inertia torque)."""
        line = self.line
        ends = line.element_dofs
        xa = np.where(ends[:, 0] >= 0, x[:, np.maximum(ends[:, 0], 0)], 0.0)
        xb = np.where(ends[:, 1] >= 0, x[:, np.maximum(ends[:, 1], 0)], 0.0)
        out = np.abs(line.element_stiffness * (xa - xb) / line.element_ratio)
        meshes = np.empty((x.shape[0], len(line.gears)))
        for i, g in enumerate(line.gears):
            inertia = abs(g.inertia * g.ratio) / line.inertia[g.dof]
            meshes[:, i] = inertia * np.abs(x @ system.stiffness[g.dof])
            meshes[:, i] += sum(abs(s) * out[:, e] for e, s in g.elements)
        return np.concatenate([out, meshes], axis=1)

    def dropped(self, system: ModalSystem, x: NDArray[np.float64], kind: str) -> None:
        """Track every element's largest torque (N m) under the angles x (L, n): of the modes
        left out (``"residual"``: their quasi-static part R f; ``"rate"``: R f', N m/s), or
        of the kept modes' response to the damping force of R f' (``"coupling"``)."""
        top = np.max(self._twist(system, x), axis=0)
        old = getattr(self, kind)
        setattr(self, kind, top if old is None else np.maximum(old, top))

    def kick(
        self,
        system: ModalSystem,
        jump: NDArray[np.float64] | None,
        bend: NDArray[np.float64] | None,
        angles: tuple[NDArray[np.float64], NDArray[np.float64]] | None = None,
    ) -> None:
        """Add the dynamic part a jump (N m) and a change of slope (N m/s) of the forcing (n,)
        start in the modes left out (module docstring of :mod:`crankdyn.torsion.integrator`):
        at most their quasi-static torque R jump and R bend / omega_d; or that of ``angles``
        (two (n,) twists, rad) the dropped modes start from."""
        assert system.residual is not None
        if angles is not None:
            add = np.sum(self._twist(system, np.stack(angles)), axis=0)
        else:
            # every dropped mode rings on its own: sum_j |T_e(phi_j)| |phi_j^T g| / omega_j^2
            # <= sqrt(t_e^T R t_e) sqrt(g^T R g) (Cauchy-Schwarz), g the jump, then the bend
            # over omega_d (a kink rings 1 / omega_j of its slope's static part)
            assert jump is not None and bend is not None
            g = np.stack([jump, bend / system.lowest_dropped])
            cols = loaded(g)
            rc = system.residual.columns(cols)[cols]
            energy = np.einsum("ki,ij,kj->k", g[:, cols], rc, g[:, cols])
            add = self._reach(system) * float(np.sum(np.sqrt(np.maximum(energy, 0.0))))
        self.kicks = add if self.kicks is None else self.kicks + add

    def spread(self, system: ModalSystem, f: NDArray[np.float64], kind: str) -> None:
        """Track every element's sqrt(t_e^T R t_e) sqrt(f^T R f) (N m) over the samples f
        (L, n) of the forcing (``"residual"``) or of its rates (``"rate"``, N m/s): the bound
        of sum_j |T_e(phi_j)| |phi_j^T f| / omega_j^2 over the dropped modes (Cauchy-Schwarz),
        every mode's dynamic part taken at its own worst."""
        assert system.residual is not None
        cols = loaded(f)
        rc = system.residual.columns(cols)[cols]
        energy = float(np.max(np.einsum("ki,ij,kj->k", f[:, cols], rc, f[:, cols]), initial=0.0))
        top = self._reach(system) * math.sqrt(max(energy, 0.0))
        old = getattr(self, kind)
        setattr(self, kind, top if old is None else np.maximum(old, top))

    def _reach(self, system: ModalSystem) -> NDArray[np.float64]:
        """sqrt(t_e^T R t_e) of every element (N m per sqrt(N m rad)): t_e its torque's
        pattern k_e (e_a - e_b) / r_e; a gear mesh's: the sum over its elements (R in full,
        once per system: n solves of the factorised shifted stiffness)."""
        assert system.residual is not None
        key = id(system)
        if key not in self._reaches:
            line = self.line
            r = system.residual.columns(np.arange(line.size))
            a, b = line.element_dofs[:, 0], line.element_dofs[:, 1]
            aa, bb = np.maximum(a, 0), np.maximum(b, 0)
            ra = np.where(a >= 0, r[aa, aa], 0.0)
            rb = np.where(b >= 0, r[bb, bb], 0.0)
            rab = np.where((a >= 0) & (b >= 0), r[aa, bb], 0.0)
            k = line.element_stiffness / line.element_ratio
            reach = np.sqrt(np.maximum(k * k * (ra + rb - 2.0 * rab), 0.0))
            meshes = [sum(abs(s) * reach[e] for e, s in g.elements) for g in line.gears]
            self._reaches[key] = np.concatenate([reach, np.asarray(meshes, dtype=float)])
        return self._reaches[key]

    def add(
        self,
        t: NDArray[np.float64],
        x: NDArray[np.float64],
        v: NDArray[np.float64],
        torque: NDArray[np.float64],
        window: Callable[[int], _Window | None],
        *,
        keep_last: bool = False,
    ) -> None:
        """Samples t (K,) with their angles, rates and element torques; ``window(k)`` the
        refinement window of sample k (or None)."""
        line = self.line
        index = self.count + np.arange(t.size)
        keep = index % self.stride == 0
        if keep_last:
            keep[-1] = True
        self.count += t.size
        if np.any(keep):
            frame = self.frame(t[keep])
            vk = v[keep][:, line.mass_dof] + frame[:, None]
            self.times.append(t[keep])
            self.speeds.append(vk * line.mass_ratio[None, :])
            self.torques.append(torque[keep][:, : torque.shape[1] // 2])
            self.vibratory.append(torque[keep][:, torque.shape[1] // 2 :])
            total = float(np.sum(line.inertia))
            self.mean.append(v[keep] @ line.inertia / total + frame)
        made: dict[int, _Window | None] = {}  # one window per sample, shared by its peaks
        for sign, attr in ((1.0, "high"), (-1.0, "low")):
            values = sign * torque
            k = np.argmax(values, axis=0)
            best = values[k, np.arange(values.shape[1])]
            old = getattr(self, attr)
            better = np.ones(best.size, bool) if old is None else best > sign * old
            if not np.any(better):
                continue
            new = (sign * best).copy() if old is None else np.where(better, sign * best, old)
            at = t[k] if old is None else np.where(better, t[k], getattr(self, attr + "_at"))
            setattr(self, attr, new)
            setattr(self, attr + "_at", at)
            for e in np.flatnonzero(better):
                j = int(k[e])
                w = made[j] if j in made else made.setdefault(j, window(j))
                key = (int(e), 0 if sign > 0 else 1)
                if w is None:
                    self.windows.pop(key, None)
                else:
                    self.windows[key] = w


def _refine(line: Line, rec: _Recorder) -> None:
    """Every element's extremes on the exact solution within the steps around them (module
    docstring): the windows shared by several extremes (an impact loads many elements at
    once) evaluated once, at the dofs their elements' torques read only."""
    width = line.element_stiffness.size + len(line.gears)
    groups: dict[tuple[int, float, float], list[tuple[int, int, _Window]]] = {}
    for (e, which), w in rec.windows.items():
        groups.setdefault((id(w.mode), w.t0, w.step), []).append((e, which, w))
    taus = np.linspace(0.0, 1.0, REFINE_POINTS)
    for items in groups.values():
        w = items[0][2]
        columns = sorted({e for e, _which, _w in items})
        dofs = _dofs_of(line, w.mode, [c % width for c in columns])
        ts, vals = [], []
        for s in range(len(w.states) - 1):
            t, x, v = w.at(s, taus * w.step, dofs)
            ts.append(t)
            vals.append(_columns(line, w.mode, t, x, v, dofs, columns, w.force, w.mean))
        _refine_group(rec, w, items, np.concatenate(ts), np.concatenate(vals), columns, dofs)


def _refine_group(
    rec: _Recorder,
    w: _Window,
    items: list[tuple[int, int, _Window]],
    t_all: NDArray[np.float64],
    series_all: NDArray[np.float64],
    columns: list[int],
    dofs: NDArray[np.int_],
) -> None:
    """The extremes of one window's columns: the best point of each, then the vertex of the
    parabola through it and its neighbours, evaluated on the solution."""
    assert rec.high is not None and rec.low is not None
    assert rec.high_at is not None and rec.low_at is not None
    found: list[list[float]] = []
    vertices: list[tuple[int, float]] = []
    for i, (e, which, _w) in enumerate(items):
        sign = 1.0 if which == 0 else -1.0
        v_all = sign * series_all[:, columns.index(e)]
        k = int(np.argmax(v_all))
        found.append([float(v_all[k]), float(t_all[k])])
        if 0 < k < v_all.size - 1:  # the vertex of a parabola through the three best points
            y0, y1, y2 = v_all[k - 1], v_all[k], v_all[k + 1]
            den = y0 - 2.0 * y1 + y2
            if den < 0.0:
                step = t_all[k + 1] - t_all[k]
                vertices.append((i, float(t_all[k] + 0.5 * (y0 - y2) / den * step)))
    last = len(w.states) - 2
    for i, vertex in vertices:  # one at a time: the products of the whole-state refinement
        e, which, _w = items[i]
        s = min(int((vertex - w.t0) // w.step), last)
        _t, x, v = w.at(s, [vertex - w.t0 - s * w.step], dofs)
        t = np.array([vertex])
        value = _columns(rec.line, w.mode, t, x, v, dofs, [e], w.force, w.mean)[0, 0]
        if (1.0 if which == 0 else -1.0) * float(value) > found[i][0]:
            found[i] = [(1.0 if which == 0 else -1.0) * float(value), vertex]
    for (e, which, _w), (best, at) in zip(items, found, strict=True):
        sign = 1.0 if which == 0 else -1.0
        target, times_at = (rec.high, rec.high_at) if sign > 0 else (rec.low, rec.low_at)
        if best > sign * target[e]:  # best is in sign x torque
            target[e] = sign * best
            times_at[e] = at


def _dofs_of(line: Line, mode: _Mode, elements: Sequence[int]) -> NDArray[np.int_]:
    """The dofs the torques of ``elements`` (indices of the elements, then the gear meshes)
    read: an element's two ends; a gear mesh's dof, its stiffness and damping neighbours and
    its elements' ends."""
    n_el = line.element_stiffness.size
    out: set[int] = set()
    for e in elements:
        if e < n_el:
            out.update(int(d) for d in line.element_dofs[e] if d >= 0)
            continue
        g = line.gears[e - n_el]
        out.add(g.dof)
        out.update(np.flatnonzero(mode.system.stiffness[g.dof]).tolist())
        out.update(np.flatnonzero(mode.system.damping[g.dof]).tolist())
        for ee, _s in g.elements:
            out.update(int(d) for d in line.element_dofs[ee] if d >= 0)
    return np.array(sorted(out), dtype=int)


def _torque_columns(
    line: Line,
    mode: _Mode,
    t: NDArray[np.float64],
    x: NDArray[np.float64],
    v: NDArray[np.float64],
    dofs: NDArray[np.int_],
    elements: Sequence[int],
    f: NDArray[np.float64] | None,
) -> dict[int, NDArray[np.float64]]:
    """The torques of ``elements`` (as :func:`_element_torques`) from the angles and rates at
    ``dofs`` (T, len(dofs)) only; f (T, n) the generalised torques (gear meshes only)."""
    n_el = line.element_stiffness.size
    pos = np.full(line.size, -1)
    pos[dofs] = np.arange(dofs.size)
    out: dict[int, NDArray[np.float64]] = {}

    def element(e: int) -> NDArray[np.float64]:
        if e not in out:
            a, b = (int(d) for d in line.element_dofs[e])
            xa = x[:, pos[a]] if a >= 0 else np.zeros(t.size)
            xb = x[:, pos[b]] if b >= 0 else np.zeros(t.size)
            value = line.element_stiffness[e] * (xa - xb) / line.element_ratio[e]
            if mode.offset is not None:
                value = value - mode.offset[e]
            if mode.friction is not None and mode.friction[0] == e:
                value = mode.friction[1] * mode.friction[2](t) * np.ones(t.size)
            out[e] = value
        return out[e]

    for e in elements:
        if e < n_el:
            element(e)
            continue
        g = line.gears[e - n_el]
        assert f is not None
        d, system = g.dof, mode.system
        # the whole rows (zeros elsewhere): the products of _element_torques to the digit
        xf, vf = np.zeros((t.size, line.size)), np.zeros((t.size, line.size))
        xf[:, dofs], vf[:, dofs] = x, v
        accel = (f[:, d] - xf @ system.stiffness[d] - vf @ system.damping[d]) / line.inertia[d]
        out[e] = g.inertia * g.ratio * accel + sum(s * element(ee) for ee, s in g.elements)
    return out


def _columns(
    line: Line,
    mode: _Mode,
    t: NDArray[np.float64],
    x: NDArray[np.float64],
    v: NDArray[np.float64],
    dofs: NDArray[np.int_],
    columns: Sequence[int],
    force: Forcing,
    mean: Forcing,
) -> NDArray[np.float64]:
    """(T, len(columns)) the columns of :func:`_series` (the torques, then the vibratory
    torques) from the angles and rates at ``dofs`` only: the quasi-static twist there from the
    static flexibility's columns of the loaded dofs."""
    n_el = line.element_stiffness.size
    width = n_el + len(line.gears)
    wanted = sorted({c % width for c in columns})
    gears = any(c >= n_el for c in wanted)
    totals = _torque_columns(line, mode, t, x, v, dofs, wanted, force(t) if gears else None)
    statics: dict[int, NDArray[np.float64]] = {}
    if any(c >= width for c in columns):
        m = mean(t)
        cols = loaded(m)
        xs = m[:, cols] @ mode.system.flexibility(cols)[dofs].T
        vib = sorted({c - width for c in columns if c >= width})
        plain = _Mode(mode.key, mode.system)
        statics = _torque_columns(line, plain, t, xs, np.zeros_like(xs), dofs, vib, m)
    out = np.empty((t.size, len(columns)))
    for i, c in enumerate(columns):
        out[:, i] = totals[c] if c < width else totals[c - width] - statics[c - width]
    return out


# ---- the march through the segments -----------------------------------------------------------
@dataclass(eq=False)
class _Run:
    """The run's fixed parts: the line, the forcing, the step, the cuts, the recorder."""

    line: Line
    forcing: Forcing
    mean: Forcing
    end: float
    step: float
    cuts: NDArray[np.float64]
    block: int
    recorder: _Recorder
    switches: list[str] = field(default_factory=list)
    sampled: _Sampled | None = None
    locked_at: float | None = None
    last: tuple[NDArray[np.float64], NDArray[np.float64]] | None = None
    coupled: tuple[int, NDArray[np.complex128]] | None = None
    switched: tuple[NDArray[np.float64], NDArray[np.float64]] | None = None


def _coupled(
    run: _Run, system: ModalSystem, rates: NDArray[np.float64], h: float
) -> NDArray[np.float64]:
    """(L, n) the kept modes' response to the damping force of the dropped modes'
    quasi-static rates alone, -Phi_k^T C R f' (carried by the run, :meth:`ModalSystem.
    modal_forcing`): the dropped modes' dynamic part, at most beta times their quasi-static
    part, drives the kept modes through the damping by at most beta times this response."""
    assert system.residual is not None
    uc = -system.residual.coupling(rates) @ system.input_gain.T
    a, b0, b1 = system.coefficients(h)
    start = np.zeros(a.size, dtype=complex)
    if run.coupled is not None and run.coupled[0] == id(system):
        start = run.coupled[1]
    w = linear_recurrence(a, b0 * uc[:-1] + b1 * uc[1:], start)
    run.coupled = (id(system), w[-1])
    bodies = np.zeros((w.shape[0], system.bodies.shape[1]))
    x, _v = system.to_physical(ModalState(w, bodies, bodies))
    return x


def _kick(
    run: _Run, system: ModalSystem, force: Forcing, t: float, f: NDArray[np.float64], h: float
) -> None:
    """At a segment's start t: the forcing's jump and change of slope there (its value and
    slope at the end of the segment before, or, at the start and after a switch, its own
    left-hand values: a clutch's element put back carries the friction torque, no jump) into
    the bound of the modes left out (:meth:`_Recorder.kick`); after a switch, the dropped
    modes' start (quasi-static in the new system, not the state reached): the difference of
    the angles, and of the rates over omega_d, oscillates at most with its own amplitude."""
    if run.switched is not None:
        xs, vs = run.switched
        x, v = system.to_physical(system.to_modal(xs, vs), None, f[:1], ((f[1] - f[0]) / h)[None])
        run.recorder.kick(system, None, None, (x[0] - xs, (v[0] - vs) / system.lowest_dropped))
        run.switched = None
    if run.last is None:
        left = force(np.array([np.nextafter(t, -np.inf), t - h]))
        run.last = (left[0], (left[0] - left[1]) / h)
    before, slope = run.last
    run.recorder.kick(system, f[0] - before, (f[1] - f[0]) / h - slope)


def _mode_forcing(run: _Run, mode: _Mode) -> Forcing:
    """The generalised torques (L, n) of the run in a mode (its own terms added)."""
    if mode.extra is None:
        return run.forcing
    extra = mode.extra

    def force(t: NDArray[np.float64]) -> NDArray[np.float64]:
        return run.forcing(t) + extra(t)

    return force


def _state_at(start: ModalState, w: ModalState, j: int) -> ModalState:
    """The modal state of a block's sample j (0 the block's start)."""
    if j == 0:
        return start
    return ModalState(w.w[j - 1], w.r[j - 1], w.rd[j - 1])


def _windows(
    mode: _Mode,
    run: _Run,
    force: Forcing,
    start: ModalState,
    w: ModalState,
    times: NDArray[Any],
    f: NDArray[np.float64],
    u: Any,
    g: Any,
    h: float,
) -> Callable[[int], _Window | None]:
    """window(k) for the block's sample k + 1 (k indexes the block's samples 1..L)."""

    def window(k: int) -> _Window:
        s = k + 1
        last = min(s + 1, times.size - 1)
        states = [_state_at(start, w, j) for j in range(s - 1, last + 1)]
        span = slice(s - 1, last + 1)
        return _Window(
            mode, float(times[s - 1]), h, states, u[span], g[span], f[span], force, run.mean
        )

    return window


def _crossing(
    run: _Run,
    mode: _Mode,
    prev: ModalState,
    times: NDArray[Any],
    f: NDArray[np.float64],
    u: Any,
    g: Any,
    j: int,
    h: float,
) -> tuple[float, NDArray[np.float64], NDArray[np.float64]]:
    """The instant in step (j - 1 -> j) where the mode's watched value reaches 0, and the
    angles and rates there (Brent's method on the exact solution within the step)."""
    system = mode.system
    watch = mode.watch
    assert watch is not None
    slope = (f[j] - f[j - 1]) / h

    def state(tau: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        st = system.within(prev, u[j - 1], u[j], g[j - 1], g[j], h, [tau])
        return system.to_physical(st, None, (f[j - 1] + tau * slope)[None], slope[None])

    def value(tau: float) -> float:
        x, v = state(tau)
        return float(np.asarray(watch(np.array([times[j - 1] + tau]), x, v))[0])

    tau = 0.0 if value(0.0) >= 0.0 else brentq(value, 0.0, h, xtol=1e-15 + 1e-12 * h)
    x, v = state(tau)
    run.last = (f[j - 1] + tau * slope, slope)
    return float(times[j - 1] + tau), x[0], v[0]


def _segment(
    run: _Run, mode: _Mode, t: float, stop: float, state: ModalState, final: bool
) -> tuple[float, _Mode, ModalState]:
    """Integrate from t to stop in ``mode``; returns (t, mode, state) where it ended (a switch
    ends a segment early)."""
    line, system = run.line, mode.system
    count = max(1, math.ceil((stop - t) / run.step - 1e-9))
    h = (stop - t) / count
    done = 0
    while done < count:
        n = min(run.block, count - done)
        times = np.asarray(t + h * np.arange(n + 1), dtype=np.float64)
        last = done + n == count
        if last:
            times[-1] = stop
        tf = times.copy()  # the forcing's one-sided values at the segment's ends
        if done == 0:
            tf[0] = np.nextafter(times[0], np.inf)
        if last:
            tf[-1] = np.nextafter(stop, -np.inf)
        force = _mode_forcing(run, mode)
        f = force(tf)
        if done == 0 and system.residual is not None:
            _kick(run, system, force, t, f, h)
        run.last = (f[-1], (f[-1] - f[-2]) / h)
        slopes = np.diff(f, axis=0) / h  # of the steps; at the samples their mean
        rates = np.concatenate([slopes[:1], 0.5 * (slopes[:-1] + slopes[1:]), slopes[-1:]])
        u, g = system.modal_forcing(f, rates if system.residual is not None else None)
        w = system.run(state, u, g, h)
        x, v = system.to_physical(w, None, f[1:], slopes)
        if system.residual is not None:
            run.recorder.spread(system, f[1:], "residual")
            run.recorder.spread(system, rates[1:], "rate")
            run.recorder.pace(f, rates)
            run.recorder.dropped(system, _coupled(run, system, rates, h), "coupling")
        tk = times[1:]
        hit = None
        if mode.watch is not None:
            found = np.flatnonzero(np.asarray(mode.watch(tk, x, v)) >= 0.0)
            hit = int(found[0]) + 1 if found.size else None

        def series(tt: Any, xx: Any, vv: Any, force: Forcing = force) -> Any:
            return _series(line, mode, tt, xx, vv, force, run.mean)

        windows = _windows(mode, run, force, state, w, times, f, u, g, h)
        if hit is None:
            run.recorder.add(tk, x, v, series(tk, x, v), windows, keep_last=last and final)
            state, t, done = w.last(), float(times[-1]), done + n
            continue
        prev = _state_at(state, w, hit - 1)
        if hit > 1:
            k = hit - 1
            run.recorder.add(tk[:k], x[:k], v[:k], series(tk[:k], x[:k], v[:k]), windows)
        ts, xs, vs = _crossing(run, mode, prev, times, f, u, g, hit, h)
        tsa = np.array([ts])
        run.recorder.add(
            tsa,
            xs[None],
            vs[None],
            series(tsa, xs[None], vs[None]),
            lambda _k: None,
            keep_last=True,
        )
        assert mode.switch is not None
        new = mode.switch(ts, xs, vs)
        run.switches.append(f"{mode.key} -> {new.key} at {ts:.6g} s")
        if new.key == "locked" and run.locked_at is None:
            run.locked_at = ts
        run.last, run.switched = None, (xs, vs)
        return ts, new, new.system.to_modal(xs, vs)
    return t, mode, state


def _march(run: _Run, mode: _Mode, x0: NDArray[np.float64], v0: NDArray[np.float64]) -> None:
    """Integrate the whole run, segment by segment (module docstring)."""
    t = 0.0
    state = mode.system.to_modal(x0, v0)
    t0 = np.array([np.nextafter(0.0, np.inf)])
    first = _series(run.line, mode, t0, x0[None], v0[None], _mode_forcing(run, mode), run.mean)
    run.recorder.add(np.array([0.0]), x0[None], v0[None], first, lambda _k: None)
    while t < run.end * (1.0 - 1e-12):
        if run.sampled is not None and run.sampled.due(t):
            _x, v = mode.system.to_physical(state)
            run.sampled.sample(t, v + run.recorder.frame(np.array([t]))[0])
        later = run.cuts[run.cuts > t + 1e-9 * run.step]
        stop = float(later[0]) if later.size else run.end
        t, mode, state = _segment(run, mode, t, stop, state, final=stop >= run.end)


# ---- the analysis -----------------------------------------------------------------------------
def _initial(
    line: Line,
    mode: _Mode,
    static: NDArray[np.float64],
    body_speed: Callable[[NDArray[np.int_]], float],
    harmonics: Harmonics | None,
    profile: Profile,
) -> tuple[NDArray[np.float64], NDArray[np.float64], bool]:
    """(x0, v0, absolute): the static twist under the mean torques, the steady state of the
    harmonic torques, the free bodies at their speeds; ``absolute`` False for a model without
    free bodies (its angles are relative to a frame turning at the mean speed)."""
    system = mode.system
    x0 = system.static(static)
    v0 = np.zeros(line.size)
    bodies = [np.flatnonzero(system.bodies[:, c]) for c in range(system.bodies.shape[1])]
    for dofs in bodies:
        v0[dofs] = body_speed(dofs)
    w0 = float(profile.speed(np.array([0.0]))[0])
    if harmonics is not None and w0 > 0.0:
        f = harmonics.forcing[0] if harmonics.grid.size == 1 else None
        if f is None:
            pos = np.interp(w0, harmonics.grid, np.arange(harmonics.grid.size, dtype=float))
            c = min(int(pos), harmonics.grid.size - 2)
            f = (1.0 - (pos - c)) * harmonics.forcing[c] + (pos - c) * harmonics.forcing[c + 1]
        omega = harmonics.orders * w0
        amp = system.harmonic(f * float(profile.scale(np.array([0.0]))[0]), omega)
        x0 = x0 + np.sum(amp, axis=0).real
        v0 = v0 + np.sum(1j * omega[:, None] * amp, axis=0).real
    return x0, v0, bool(bodies)


def _duration(
    mode: _Mode,
    event: Any,
    given: float | None,
    profile: Profile,
    systems: Sequence[ModalSystem] = (),
) -> float:
    """The run's duration (s): the given one, the event's, or the event's last breakpoint and
    20 periods of the line's lowest elastic mode (a clutch: 40). A line with no elastic mode in
    the state it starts in (a clutch's two halves free while it slips) takes the lowest of the
    run's other systems (the locked line), and 1 rad/s only when none has one."""
    if given is not None:
        if not (math.isfinite(given) and given > 0.0):
            raise InputError("the duration must be positive", key="duration", value=given)
        return float(given)
    if profile.end is not None:
        return profile.end
    if isinstance(event, SpeedChange):
        return event.hold + event.ramp_time + 5.0 * event.governor_time
    own = None if isinstance(event, ClutchEngagement) else event.default_duration()
    if own is not None:
        return float(own)
    freq = mode.system.natural_frequency
    if not np.any(freq > 0.0):
        freq = np.concatenate([np.asarray(s.natural_frequency) for s in systems] or [freq])
    lowest = float(np.min(freq[freq > 0.0])) if np.any(freq > 0.0) else 1.0
    periods = 40.0 if isinstance(event, ClutchEngagement) else 20.0
    return max(event.breakpoints(), default=0.0) + periods * 2.0 * math.pi / lowest


def _step(
    systems: Sequence[ModalSystem],
    forcing_frequency: float,
    max_frequency: float | None,
    duration: float,
    force_points: int,
) -> tuple[float, float, str]:
    """(h, the highest frequency resolved (rad/s), the rule in words): module docstring."""
    top = 0.0
    for s in systems:
        w = s.natural_frequency
        if max_frequency is not None:
            w = w[w <= max_frequency]
        top = max(top, float(np.max(w, initial=0.0)))
    h_mode = 2.0 * math.pi / (MODE_POINTS * top) if top > 0.0 else math.inf
    h_force = (
        2.0 * math.pi / (force_points * forcing_frequency) if forcing_frequency > 0 else math.inf
    )
    h = min(h_mode, h_force, duration / 200.0)
    rule = (
        f"h = {h:.4g} s: the smallest of T/{MODE_POINTS} of the highest mode of interest "
        f"({top / (2 * math.pi):.5g} Hz), T/{force_points} of the forcing's highest frequency "
        f"({forcing_frequency / (2 * math.pi):.5g} Hz) and 1/200 of the run"
    )
    return h, max(top, forcing_frequency), rule


def event_response(
    model: TorsionModel,
    event: Event,
    *,
    speed: float | None = None,
    duration: float | None = None,
    excitation: Excitation | None = None,
    orders: ArrayLike | None = None,
    dampers: Sequence[Damper] | None = None,
    hysteretic_frequency: float | None = None,
    max_frequency: float | None = None,
    max_samples: int = 20001,
    mean_torques: bool = True,
    absolute_damping: str = "vibration",
    force_points: int = FORCE_POINTS,
    truncate: bool = True,
) -> EventResult:
    """The line's speeds and element torques through a transient event (module docstring).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The model.
    event : Event
        The event (:mod:`crankdyn.torsion.events`).
    speed : float or None
        The reference speed the line runs at before the event (rad/s), >= 0 (a start, stop or
        ramp has its own; a clutch its halves'); default 0 (at rest).
    duration : float or None
        The run (s), > 0; default the event's (the event and 20 periods of the lowest mode).
    excitation : Excitation or None
        The cylinders' excitation (:func:`crankdyn.torsion.excitation.excitation_for`) to add
        the engine's and the sources' harmonic torques; None: none.
    orders : array_like or None
        The orders of the harmonic torques (with ``excitation``).
    dampers : sequence of Damper or None
        Dampers to add; None: the model's own.
    hysteretic_frequency : float or None
        omega_h (rad/s) for the loss factors as viscous damping; default the lowest elastic
        natural frequency.
    max_frequency : float or None
        The highest natural frequency of interest (rad/s): the modes up to it are integrated,
        those above quasi-statically (:mod:`crankdyn.torsion.integrator`, "Modal truncation";
        the bound reported with the result; with ``truncate`` False it sets the step only);
        default every mode, exactly.
    max_samples : int
        The most samples kept (>= 2); the extremes come from every step.
    mean_torques : bool
        Whether the engines' and the load laws' mean torques act.
    absolute_damping : {"vibration", "absolute"}
        How the masses' absolute damping acts (:func:`crankdyn.torsion.integrator.
        modal_system`).
    force_points : int
        Steps per period of the forcing's highest frequency (default 40).
    truncate : bool
        Whether ``max_frequency`` truncates the modes (default True); False: every mode is
        integrated, the cut-off only sets the step.

    Returns
    -------
    EventResult
        Time (s), speeds (rad/s), element torques (N m), the extremes.

    Raises
    ------
    InputError
        Naming the key: an unknown mass, a clutch between masses no element joins, a speed
        or duration that is not positive, an ice impact without a speed, orders the model
        cannot take.

    Examples
    --------
    A torque suddenly applied to an undamped two-mass line twists its shaft to twice the
    static twist (Thomson 1993, sec. 4.2): T_shaft, max = 2 T J2 / (J1 + J2).

    >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
    >>> from crankdyn.torsion.events import StepTorque
    >>> line = TorsionModel(masses=(Mass("a", 2.0), Mass("b", 3.0)),
    ...                     shafts=(Shaft(("a", "b"), 1e4),))
    >>> run = event_response(line, StepTorque("a", 100.0))
    >>> round(run.peak(0), 6), round(2 * 100.0 * 3.0 / 5.0, 6)
    (120.0, 120.0)
    """
    from crankdyn.torsion.event_result import EventResult

    if max_frequency is not None and not (math.isfinite(max_frequency) and max_frequency > 0.0):
        raise InputError(
            "the highest frequency must be positive", key="max_frequency", value=max_frequency
        )
    if isinstance(max_samples, bool) or int(max_samples) < 2:
        raise InputError("expected at least 2 samples", key="max_samples", value=max_samples)
    line = line_of(model, dampers, hysteretic_frequency)
    w0 = 0.0 if speed is None else float(speed)
    if not (math.isfinite(w0) and w0 >= 0.0):
        raise InputError("the speed must not be negative", key="speed", value=speed)
    if isinstance(event, SpeedChange):
        profile = speed_profile(line, event, duration)
    else:
        clutch = isinstance(event, ClutchEngagement)  # its loads: sampled at its masses' speeds
        profile = constant_profile(line, w0, loads=mean_torques and not clutch)
    mode, systems, torque_events, body_speed = _setup(
        model, line, event, w0, profile, absolute_damping, max_frequency if truncate else None
    )
    harmonics = (
        harmonics_of(model, line, excitation, orders if orders is not None else [], profile)
        if excitation is not None
        else None
    )
    sampled = _sampled(line, event, mean_torques)
    forcing, mean_part = _forcing(
        line, profile, torque_events, harmonics, mean=mean_torques, engine=sampled
    )
    main = event if isinstance(event, (ClutchEngagement, SpeedChange)) else torque_events[0][1]
    t_end = _duration(mode, main, duration, profile, systems)
    frequency = max((ev.frequency() for _i, ev in torque_events), default=0.0)
    if harmonics is not None:
        frequency = max(frequency, float(np.max(np.abs(harmonics.orders))) * profile.high)
    step, top, rule = _step(systems, frequency, max_frequency, t_end, force_points)
    cuts = _cuts(event, torque_events, profile, t_end, step, sampled)
    static = mean_part(np.array([0.0]))[0]
    for index, ev in torque_events:  # a torque held from the start is in the static twist
        static += line.at_mass(index, ev.torque(np.array([np.nextafter(0.0, -np.inf)])))[0]
    x0, v0, absolute = _initial(line, mode, static, body_speed, harmonics, profile)
    frame = (lambda t: np.zeros(np.shape(t))) if absolute else profile.speed
    if sampled is not None and isinstance(event, ClutchEngagement) and event.governor:
        # the governor starts from the engine's speed and torque
        sensed = float(line.drive @ v0 + frame(np.array([0.0]))[0])
        sampled.governor = event.governor.start(sensed, event.drive_torque)
    n_steps = t_end / step + cuts.size + 1
    stride = max(1, math.ceil(n_steps / (int(max_samples) - 1)))
    n_el = line.element_stiffness.size
    per_step = 8 * (4 * line.size + 4 * systems[0].eigenvalues.size + 3 * n_el + line.mass_dof.size)
    per_step += 0 if harmonics is None else 16 * harmonics.orders.size
    block = int(np.clip(BLOCK_BYTES // max(per_step, 1), 64, 16384))
    recorder = _Recorder(line, stride, frame)
    run = _Run(line, forcing, mean_part, t_end, step, cuts, block, recorder)
    run.sampled = sampled
    _march(run, mode, x0, v0)
    _refine(line, recorder)
    rows = int(max_samples) + cuts.size + len(run.switches) + 2
    kept = 8 * rows * (line.mass_dof.size + n_el + len(line.gears) + 2)
    result = _result(
        EventResult, model, line, event, recorder, run, t_end, step, top, rule, stride,
        float(kept + block * per_step), _truncation(systems, recorder, run, frequency),
    )  # fmt: skip
    return result


def _truncation(
    systems: Sequence[ModalSystem], rec: _Recorder, run: _Run, frequency: float
) -> dict[str, Any]:
    """The modal truncation's fields of the result (:mod:`crankdyn.torsion.integrator`,
    "Modal truncation"): the modes kept, the cut-off, beta (:func:`truncation_factor`: the
    dropped modes' dynamic part relative to their quasi-static part under forcing up to the
    forcing's highest frequency, their damping bounded by :func:`_damping_lag`), and every
    element's bound (N m): beta times its largest quasi-static torque of the dropped modes and
    its largest torque of the kept modes' response to their damping force (:func:`_coupled`),
    plus the dropped modes' lag behind their quasi-static part (the bound of c_j / omega_j^2
    times the torque of R f'), plus what the forcing's jumps and kinks at the segments' starts
    add (:meth:`_Recorder.kick`)."""
    kept = max(int(s.modes.shape[1]) for s in systems)
    if all(s.residual is None for s in systems):
        return {"modes_kept": kept, "note": None}
    lowest = min(s.lowest_dropped for s in systems)
    cutoff = max(s.cutoff for s in systems if s.residual is not None)
    dropped = max(s.dropped for s in systems)
    frequency = max(frequency, rec.frequency())
    lag = _damping_lag(rec.line, lowest)
    beta = truncation_factor(frequency, lowest, lag * lowest**2)
    width = rec.line.element_stiffness.size + len(rec.line.gears)
    residual, coupling, rate, kicks = (
        np.zeros(width) if v is None else v
        for v in (rec.residual, rec.coupling, rec.rate, rec.kicks)
    )
    # the dropped modes' own damping force on their quasi-static rates, c_j R f' / omega_j^2:
    # the lag of a damped mode behind its quasi-static part
    per_element = beta * (residual + coupling) + lag * rate + kicks
    note = (
        f"modal truncation: the {kept} elastic modes up to {cutoff / (2 * math.pi):.4g} Hz "
        f"integrated, the {dropped} above (from {lowest / (2 * math.pi):.4g} Hz) "
        "quasi-statically (residual flexibility); their dynamic part at most "
        f"{beta:.3g} of their quasi-static part under forcing up to "
        f"{frequency / (2 * math.pi):.4g} Hz, plus the forcing's jumps' and kinks': every "
        f"element torque within {float(np.max(per_element)):.4g} N·m of the all-mode run"
    )
    return {
        "modes_kept": kept,
        "cutoff_frequency": float(cutoff),
        "truncation_bound": float(beta),
        "truncation_error": float(np.max(per_element)),
        "truncation_torque": per_element,
        "note": note,
    }


def _damping_lag(line: Line, lowest: float) -> float:
    """A bound of c_j / omega_j^2 (s) over the modes left out (omega_j >= ``lowest``, rad/s;
    c_j = phi_j^T C phi_j): the elements with stiffness give at most their own c_e / k_e
    (Rayleigh's quotient of C_e <= tau K), the rest of C (the masses' absolute damping, the
    dampers' dashpots without stiffness) at most its largest absolute row sum of
    M^-1/2 C M^-1/2 (Gershgorin's theorem) over omega_j^2."""
    k, c = line.element_stiffness, line.element_damping
    stiff = k > 0.0
    tau = float(np.max(c[stiff] / k[stiff], initial=0.0))
    rest = np.array(line.damping, dtype=float)
    ends = line.element_dofs[stiff & (c != 0.0)]
    values = c[stiff & (c != 0.0)]
    for (a, b), sign in (((0, 0), 1.0), ((1, 1), 1.0), ((0, 1), -1.0), ((1, 0), -1.0)):
        ok = (ends[:, a] >= 0) & (ends[:, b] >= 0)
        np.add.at(rest, (ends[ok, a], ends[ok, b]), -sign * values[ok])
    scale = 1.0 / np.sqrt(line.inertia)
    radius = float(np.max(np.sum(np.abs(rest) * scale[:, None] * scale[None, :], axis=1)))
    return tau + radius / lowest**2


def truncation_factor(forcing: float, lowest: float, damping: float = 0.0) -> float:
    """The largest dynamic part of a dropped mode relative to its quasi-static part, under
    harmonic forcing up to ``forcing`` (rad/s): |H / H_qs - 1| =
    |omega_f^2 - i omega_f c| / |omega_d^2 - omega_f^2 + i omega_f c| for a mode omega_d >=
    ``lowest`` with modal damping c <= ``damping`` (1/s) (the steady state of
    q'' + c q' + omega_d^2 q = p; Craig and Kurdila 2006, sec. 14.5, the mode-acceleration
    method's residual), largest at omega_d = ``lowest``, c = ``damping`` for r^2 =
    (omega_f / omega_d)^2 < 1/2; r^2 / (1 - r^2) undamped.

    Parameters
    ----------
    forcing : float
        omega_f (rad/s).
    lowest : float
        omega_d (rad/s).
    damping : float
        The bound of the dropped modes' modal damping c (1/s).

    Returns
    -------
    float
        (dimensionless); inf when omega_f >= omega_d.

    Examples
    --------
    >>> round(truncation_factor(1.0, 4.0), 6), round(1 / 15, 6)
    (0.066667, 0.066667)
    """
    r2 = (forcing / lowest) ** 2 if lowest > 0.0 else math.inf
    if not r2 < 1.0:
        return math.inf
    x2 = (forcing * damping / lowest**2) ** 2
    base = math.sqrt((r2 * r2 + x2) / ((1.0 - r2) ** 2 + x2))
    if r2 <= 0.5:
        return base
    return max(base, r2 / (1.0 - r2))


@dataclass(eq=False)
class _Sampled:
    """The mean torques a clutch engagement takes from the run itself, held between samples
    every ``period`` (module docstring): the governed engine's torque, shared as the mean
    torques are, and the load laws with every loaded mass at its own speed (the halves turn at
    their own speeds: the load laws cannot be taken at one mean speed)."""

    line: Line
    period: float
    before: NDArray[np.float64]  # (n,) held before the first sample
    loads: bool
    governor: GovernorRun | None = None
    times: list[float] = field(default_factory=list)
    held: list[NDArray[np.float64]] = field(default_factory=list)
    next_time: float = 0.0

    def due(self, t: float) -> bool:
        """Whether a sample falls at t (s)."""
        return t >= self.next_time - 1e-9 * self.period

    def sample(self, t: float, rates: NDArray[np.float64]) -> None:
        """Sample at t (s) the dofs' absolute rates (n,) (rad/s) and hold the torques."""
        line = self.line
        f = np.zeros(line.size)
        if self.governor is not None:
            f += self.governor.sample(t, float(line.drive @ rates)) * line.drive
        if self.loads:
            f += line.load_torques(rates)
        self.times.append(float(t))
        self.held.append(f)
        self.next_time = self.period * (round(t / self.period) + 1)

    def __call__(self, t: NDArray[np.float64]) -> NDArray[np.float64]:
        """(L, n) the held generalised torques at times (L,) (N m)."""
        index = np.searchsorted(np.array(self.times), np.asarray(t), side="right")
        used, where = np.unique(index, return_inverse=True)  # a segment holds one or two
        values = np.stack([self.before if i == 0 else self.held[i - 1] for i in used])
        return values[where.reshape(np.shape(index))]


def _sampled(line: Line, event: Any, mean: bool) -> _Sampled | None:
    """The sampled mean torques of a clutch engagement (its governor's sample time, or the
    default's without one), or None for other events."""
    from crankdyn.torsion.event_governor import GOVERNOR_SAMPLE_TIME

    if not isinstance(event, ClutchEngagement):
        return None
    governed = event.governor is not None
    if not (governed or (mean and line.loads)):
        return None
    period = event.governor.sample_time if event.governor is not None else GOVERNOR_SAMPLE_TIME
    before = (event.drive_torque if governed else 0.0) * line.drive
    return _Sampled(line, period, before, bool(mean and line.loads))


def _setup(
    model: TorsionModel,
    line: Line,
    event: Any,
    w0: float,
    profile: Profile,
    absolute_damping: str,
    cutoff: float | None = None,
) -> tuple[_Mode, list[ModalSystem], list[tuple[int, Any]], Callable[[NDArray[np.int_]], float]]:
    """(the first mode, every system the run may be in, the torque events at their masses, the
    free bodies' starting speeds) of an event."""
    torque_events: list[tuple[int, Any]] = []
    w_start = float(profile.speed(np.array([0.0]))[0])

    def body_speed(dofs: NDArray[np.int_]) -> float:
        return w_start

    if isinstance(event, ClutchEngagement):
        mode, clutch_e, lock_system = _clutch_modes(line, event, absolute_damping, cutoff)
        a, b = (int(v) for v in line.element_dofs[clutch_e])
        r = float(line.element_ratio[clutch_e])

        def halves(dofs: NDArray[np.int_]) -> float:
            if a in dofs:
                return event.speeds[0] / r
            if b in dofs:
                return event.speeds[1] / r
            return w0

        if event.drive_torque != 0.0 and event.governor is None:
            from crankdyn.torsion.events import StepTorque

            at = event.drive_at or next(
                (m.name for m in model.masses if m.cylinders), model.masses[0].name
            )
            torque_events.append((line.mass(at, "drive_at"), StepTorque(at, event.drive_torque)))
        return mode, [mode.system, lock_system], torque_events, halves
    system = modal_system(
        line.inertia,
        line.stiffness,
        line.damping,
        absolute_damping=absolute_damping,
        max_frequency=cutoff,
    )
    if not isinstance(event, SpeedChange):
        index = line.mass(event.at)
        torque_events.append((index, event.prepared(float(line.mass_ratio[index]) * w0)))
    return _Mode("line", system), [system], torque_events, body_speed


def _cuts(
    event: Any,
    torque_events: Sequence[tuple[int, Any]],
    profile: Profile,
    end: float,
    step: float,
    sampled: _Sampled | None = None,
) -> NDArray[np.float64]:
    """The segments' ends: the forcing's breakpoints inside the run, a quarter step apart."""
    points: list[float] = list(profile.breakpoints)
    if isinstance(event, ClutchEngagement):
        points += list(event.breakpoints())
        if sampled is not None:  # the samples of its mean torques: they jump there
            dt = sampled.period
            points += list(dt * np.arange(1, math.floor(end / dt * (1 + 1e-12)) + 1))
    for _i, ev in torque_events:
        points += list(ev.breakpoints())
    out: list[float] = []
    for p in sorted(points):
        if step / 4.0 < p < end - step / 4.0 and (not out or p - out[-1] > step / 4.0):
            out.append(p)
    return np.array(out, dtype=float)


_KINDS = {
    "StepTorque": "suddenly applied torque",
    "TabulatedTorque": "tabulated torque",
    "ShortCircuit": "short circuit",
    "IceImpact": "ice impact",
    "ClutchEngagement": "clutch engagement",
}


def _result(
    cls: type[EventResult],
    model: TorsionModel,
    line: Line,
    event: Any,
    rec: _Recorder,
    run: _Run,
    duration: float,
    step: float,
    top: float,
    rule: str,
    stride: int,
    memory: float,
    truncation: dict[str, Any],
) -> EventResult:
    """The result of a run (module docstring)."""
    from crankdyn.results import freeze, frozen

    assert rec.high is not None and rec.low is not None
    assert rec.high_at is not None and rec.low_at is not None
    n_el = line.element_stiffness.size
    half = rec.high.size // 2
    limits = np.full(n_el + len(line.gears), np.nan)
    for e, shaft in enumerate(model.shafts):
        if shaft.coupling is not None and shaft.coupling.maximum_torque is not None:
            limits[e] = shaft.coupling.maximum_torque
    notes = [
        f"loss factors as viscous damping at {line.hysteretic_frequency / (2 * math.pi):.4g} Hz",
        "element torques are elastic: k x twist / |r| (a slipping clutch: its friction torque)",
    ]
    if line.gears:
        notes.append(
            "a rigid gear's mesh torque: the wheel's inertia torque and its shafts' torques "
            "(external torques at the wheel left out)"
        )
    if isinstance(event, SpeedChange) and event.fuel_cut is not None:
        notes.append("after the fuel cut the cylinders' harmonic torques are left out")
    extra = dict(truncation)
    if extra.pop("note") is not None:
        notes.append(str(truncation["note"]))
    if extra.get("truncation_torque") is not None:
        extra["truncation_torque"] = freeze(extra["truncation_torque"])
    times = np.concatenate(rec.times)
    engine_torque = None
    governor = run.sampled.governor if run.sampled is not None else None
    if run.sampled is not None and run.sampled.loads:
        notes.append(
            f"the load laws at every loaded mass's own speed, sampled every "
            f"{run.sampled.period:.4g} s"
        )
    if governor is not None:
        g = governor.governor
        engine_torque = freeze(governor.torque(times))
        notes.append(
            f"the engine on its speed governor: sampled PI, k_p = {g.gain:.4g} per unit, "
            f"T_i = {g.integral_time:.4g} s, droop {g.droop:.4g}, sample time "
            f"{g.sample_time:.4g} s, set speed {governor.set_speed:.6g} rad/s, its torque "
            "limited by the engine's torque-speed curve"
        )
    kind = event.kind if isinstance(event, SpeedChange) else _KINDS[type(event).__name__]
    return cls(
        time=freeze(times),
        # the recorded series joined here: made read-only, not copied again
        speed=frozen(np.concatenate(rec.mean)),
        mass_speed=frozen(np.concatenate(rec.speeds)),
        torque=frozen(np.concatenate(rec.torques)),
        vibratory_torque=frozen(np.concatenate(rec.vibratory)),
        max_torque=freeze(rec.high[:half]),
        min_torque=freeze(rec.low[:half]),
        max_time=freeze(rec.high_at[:half]),
        min_time=freeze(rec.low_at[:half]),
        max_vibratory=freeze(rec.high[half:]),
        min_vibratory=freeze(rec.low[half:]),
        max_vibratory_time=freeze(rec.high_at[half:]),
        min_vibratory_time=freeze(rec.low_at[half:]),
        initial_torque=freeze(rec.torques[0][0]),
        event=event.name,
        kind=kind,
        severity=event.severity,
        source=event.source,
        masses=line.mass_names,
        elements=line.element_labels + tuple(g.between for g in line.gears),
        element_names=line.element_names + tuple(f"gear mesh {g.name}" for g in line.gears),
        duration=float(duration),
        step=float(step),
        step_rule=rule,
        highest_frequency=float(top),
        stride=int(stride),
        memory_bound=float(memory),
        switches=tuple(run.switches),
        notes=tuple(notes),
        model_name=model.name,
        element_kinds=line.element_kinds + ("gear",) * len(line.gears),
        section_modulus=freeze(
            np.concatenate([line.section_modulus, np.full(len(line.gears), np.nan)])
        ),
        limit_torque=freeze(limits),
        engine_torque=engine_torque,
        loaded_from=float(run.locked_at or 0.0),
        **extra,
    )
