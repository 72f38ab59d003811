"""The shaft line of a transient event: its matrices, elements, loads and drivers, and the
mean-speed history the event runs along (numeric core of :mod:`crankdyn.torsion.event_run`).

Degrees of freedom, reflection and dampers are those of :func:`crankdyn.torsion.response.
linear_system`; the loss factors enter as viscous damping eta k / omega_h (as the time-domain
run of :mod:`crankdyn.torsion.transient`). Torques at masses are taken in each mass's own sense
of rotation (positive drives it) and enter the reflected equations as |r| T (virtual work; Ker
Wilson, *Practical Solution of Torsional Vibration Problems*, vol. 1, ch. 3); the torque an
element transmits is T = k (x_a - x_b) / |r| (its reflected stiffness and angles, positive when
its first mass drives its second: the sign of :func:`crankdyn.torsion.sources.mean_torques`).

Mean torques: the loads are the model's load laws at the mass's speed (:class:`crankdyn.
torsion.sources.LoadLaw`), the engines share the reflected total as
:func:`crankdyn.torsion.sources.mean_torques` shares it (the cylinders' masses evenly, further
engines by their share; a model without either is driven at its first mass).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.errors import InputError, did_you_mean
from crankdyn.torsion.events import SpeedChange
from crankdyn.torsion.solvers import linear_system
from crankdyn.torsion.sources import EngineSource, HarmonicSource, LoadLaw

if TYPE_CHECKING:
    from crankdyn.torsion.dampers import Damper
    from crankdyn.torsion.excitation import Excitation
    from crankdyn.torsion.model import TorsionModel

__all__ = [
    "GearMesh",
    "Harmonics",
    "Line",
    "Profile",
    "constant_profile",
    "harmonics_of",
    "line_of",
    "speed_profile",
]


@dataclass(frozen=True, eq=False)
class Line:
    """A model's reflected matrices and elements for the time domain (module docstring).

    Parameters
    ----------
    inertia : numpy.ndarray
        (n,) of every degree of freedom (kg m^2).
    stiffness : numpy.ndarray
        (n, n) K (N m/rad).
    damping : numpy.ndarray
        (n, n) C with the loss factors as viscous damping at omega_h (N m s/rad).
    mass_dof : numpy.ndarray
        (N,) dof of every listed mass (the model's, then the damper rings), int.
    mass_ratio : numpy.ndarray
        (N,) |r| of every listed mass (dimensionless).
    mass_names : tuple of str
        The listed masses.
    element_dofs : numpy.ndarray
        (E, 2) dofs of every element's ends (shafts, then damper couplings), -1 = ground.
    element_stiffness : numpy.ndarray
        (E,) reflected k (N m/rad).
    element_damping : numpy.ndarray
        (E,) reflected viscous c + eta k / omega_h (N m s/rad).
    element_ratio : numpy.ndarray
        (E,) |r| of every element's masses.
    element_labels : tuple of (str, str)
        Every element's ends.
    element_names : tuple of str
        Every element's name for people (``"intermediate shaft (a - b)"``).
    element_kinds : tuple of str
        ``"shaft"``, ``"coupling"``, ``"mesh"`` or ``"damper"``.
    section_modulus : numpy.ndarray
        (E,) W_p of shafts with a diameter (m^3), NaN otherwise.
    drive : numpy.ndarray
        (n,) the share of the reflected engine torque every dof takes (sums to 1).
    loads : tuple of (int, LoadLaw)
        (listed mass, its load law) of every loaded mass.
    hysteretic_frequency : float
        omega_h (rad/s).
    gears : tuple of GearMesh
        The rigid gear meshes (their torque from the wheel's balance, :class:`GearMesh`).
    system : crankdyn.torsion.response.LinearSystem
        The linear system the line was built from.
    """

    inertia: NDArray[np.float64]
    stiffness: NDArray[np.float64]
    damping: NDArray[np.float64]
    mass_dof: NDArray[np.int_]
    mass_ratio: NDArray[np.float64]
    mass_names: tuple[str, ...]
    element_dofs: NDArray[np.int_]
    element_stiffness: NDArray[np.float64]
    element_damping: NDArray[np.float64]
    element_ratio: NDArray[np.float64]
    element_labels: tuple[tuple[str, str], ...]
    element_names: tuple[str, ...]
    element_kinds: tuple[str, ...]
    section_modulus: NDArray[np.float64]
    drive: NDArray[np.float64]
    loads: tuple[tuple[int, LoadLaw], ...]
    hysteretic_frequency: float
    gears: tuple[GearMesh, ...]
    system: object = field(repr=False)

    @property
    def size(self) -> int:
        """Number of degrees of freedom n."""
        return int(self.inertia.size)

    def mass(self, name: str, key: str = "at") -> int:
        """The index of a listed mass by name.

        Parameters
        ----------
        name : str
            The mass's name.
        key : str
            The key to name in an error.

        Returns
        -------
        int
            Its index among the listed masses.

        Raises
        ------
        InputError
            For an unknown name, with the nearest.
        """
        if name not in self.mass_names:
            raise InputError(
                f'no mass named "{name}"{did_you_mean(name, self.mass_names)}', key=key, value=name
            )
        return self.mass_names.index(name)

    def element(self, ends: Sequence[str], key: str = "between") -> int:
        """The index of the element between two masses (either order).

        Parameters
        ----------
        ends : (str, str)
            Its masses.
        key : str
            The key to name in an error.

        Returns
        -------
        int
            Its index.

        Raises
        ------
        InputError
            When no element joins them, or one of them is ground.
        """
        a, b = ends
        for e, (p, q) in enumerate(self.element_labels):
            if {p, q} == {a, b}:
                if "ground" in (p, q):
                    break
                return e
        raise InputError(
            "expected two masses that a shaft or coupling of the model joins",
            key=key,
            value=[a, b],
        )

    def element_matrix(self, e: int, value: float) -> NDArray[np.float64]:
        """value [[1, -1], [-1, 1]] at element e's dofs, an (n, n) matrix.

        Parameters
        ----------
        e : int
            The element.
        value : float
            The stiffness or damping (reflected).

        Returns
        -------
        numpy.ndarray
            (n, n).
        """
        out = np.zeros((self.size, self.size))
        a, b = (int(v) for v in self.element_dofs[e])
        for i, j, s in ((a, a, 1.0), (b, b, 1.0), (a, b, -1.0), (b, a, -1.0)):
            if i >= 0 and j >= 0:
                out[i, j] += s * value
        return out

    def at_mass(self, index: int, torque: NDArray[np.float64]) -> NDArray[np.float64]:
        """Generalised torques (L, n) of an own-sense torque (L,) at listed mass ``index``.

        Parameters
        ----------
        index : int
            The listed mass.
        torque : numpy.ndarray
            (L,) torques (N m, own sense).

        Returns
        -------
        numpy.ndarray
            (L, n) |r| T at its dof (N m).
        """
        out = np.zeros((np.size(torque), self.size))
        out[:, int(self.mass_dof[index])] = self.mass_ratio[index] * np.asarray(torque)
        return out

    def total_load(self, speed: NDArray[np.float64]) -> NDArray[np.float64]:
        """The reflected total load sum |r| Q(|r| Omega) at reference speeds (rad/s) (N m).

        Parameters
        ----------
        speed : numpy.ndarray
            Reference speeds (rad/s), >= 0.

        Returns
        -------
        numpy.ndarray
            (N m at the reference), the shape of ``speed``.
        """
        speed = np.asarray(speed, dtype=float)
        out = np.zeros(speed.shape)
        for i, law in self.loads:
            r = self.mass_ratio[i]
            out += r * _load_at(law, r * speed)
        return out

    def load_forcing(self, speed: NDArray[np.float64]) -> NDArray[np.float64]:
        """Generalised load torques (L, n) at reference speeds (L,) (N m).

        Parameters
        ----------
        speed : numpy.ndarray
            (L,) reference speeds (rad/s).

        Returns
        -------
        numpy.ndarray
            (L, n): -|r| Q(|r| Omega) at every loaded mass's dof.
        """
        out = np.zeros((np.size(speed), self.size))
        for i, law in self.loads:
            r = self.mass_ratio[i]
            out[:, int(self.mass_dof[i])] -= r * _load_at(law, r * np.asarray(speed))
        return out

    def load_torques(self, rates: NDArray[np.float64]) -> NDArray[np.float64]:
        """Generalised load torques (n,) with every loaded mass at its own speed.

        Parameters
        ----------
        rates : numpy.ndarray
            (n,) the degrees of freedom's absolute reflected rates (rad/s).

        Returns
        -------
        numpy.ndarray
            (n,): -|r| Q(|r| v) at every loaded mass's dof (N m), the mass's speed held at 0
            or above.
        """
        out = np.zeros(self.size)
        for i, law in self.loads:
            r, d = float(self.mass_ratio[i]), int(self.mass_dof[i])
            out[d] -= r * float(_load_at(law, np.array([r * max(float(rates[d]), 0.0)]))[0])
        return out


def _load_at(law: LoadLaw, speed: NDArray[np.float64]) -> NDArray[np.float64]:
    """Q at the mass's speeds, which are held above 1e-6 rad/s (a constant-power law is
    infinite at rest)."""
    return law.at(np.maximum(np.asarray(speed, dtype=float), 1e-6))


def _drive_weights(model: TorsionModel, mass_dof: NDArray[np.int_], n: int) -> NDArray[np.float64]:
    """The share of the reflected engine torque at every dof (module docstring)."""
    drivers: list[tuple[float, list[str]]] = []
    primary = [m.name for m in model.masses if m.cylinders]
    if primary:
        drivers.append((1.0, primary))
    for source in model.sources:
        if isinstance(source, EngineSource):
            drivers.append((source.share, list(source.mass_names())))
    if not drivers:
        drivers.append((1.0, [model.masses[0].name]))
    out = np.zeros(n)
    weight = sum(w for w, _ in drivers)
    for w, names in drivers:
        for name in names:
            out[int(mass_dof[model.index(name)])] += w / weight / len(names)
    return out


def line_of(
    model: TorsionModel,
    dampers: Sequence[Damper] | None = None,
    hysteretic_frequency: float | None = None,
) -> Line:
    """The time-domain line of a model (module docstring).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The model.
    dampers : sequence of Damper or None
        Dampers to add; None: the model's own.
    hysteretic_frequency : float or None
        omega_h (rad/s) for the loss factors; default the lowest elastic natural frequency
        (1 rad/s when there is none).

    Returns
    -------
    Line
        Its matrices and elements.
    """
    from crankdyn.torsion.modal import natural_modes

    system = linear_system(model, model.dampers if dampers is None else tuple(dampers))
    if hysteretic_frequency is None:
        modes = natural_modes(model)
        elastic = modes.natural_frequency[modes.natural_frequency > 0.0]
        hysteretic_frequency = float(elastic[0]) if elastic.size else 1.0
    wh = float(hysteretic_frequency)
    r_el = np.abs(system.element_ratio)
    damping: list[float] = []
    names: list[str] = []
    kinds: list[str] = []
    modulus: list[float] = []
    for s in model.shafts:
        r2 = float(r_el[len(damping)]) ** 2
        k_ref = float(system.element_stiffness[len(damping)])
        damping.append(s.damping * r2 + s.loss_factor * k_ref / wh)
        ends = s.segment_of or s.between
        label = f"{ends[0]} - {ends[1]}"
        if s.segment_of:
            label = f"{s.between[0]} - {s.between[1]}"
        names.append(f"{s.name} ({label})" if s.name else label)
        kinds.append(s.kind)
        modulus.append(s.geometry.section_modulus if s.geometry is not None else math.nan)
    for d in system.dampers:
        r2 = float(r_el[len(damping)]) ** 2
        damping.append((d.damping + d.loss_factor * d.stiffness / wh) * r2)
        names.append(f"damper {d.name} ({d.at} - {d.name})")
        kinds.append("damper")
        modulus.append(math.nan)
    loads = tuple(
        (model.index(src.at), src.load)
        for src in model.sources
        if isinstance(src, HarmonicSource) and src.load is not None
    )
    return Line(
        inertia=np.asarray(system.inertia, dtype=float),
        stiffness=np.asarray(system.stiffness, dtype=float),
        damping=np.asarray(system.damping + system.hysteretic / wh, dtype=float),
        mass_dof=np.asarray(system.mass_dof, dtype=int),
        mass_ratio=np.abs(np.asarray(system.mass_ratio, dtype=float)),
        mass_names=tuple(system.mass_names),
        element_dofs=np.asarray(system.element_dofs, dtype=int),
        element_stiffness=np.asarray(system.element_stiffness, dtype=float),
        element_damping=np.array(damping, dtype=float),
        element_ratio=r_el,
        element_labels=tuple(system.element_labels),
        element_names=tuple(names),
        element_kinds=tuple(kinds),
        section_modulus=np.array(modulus, dtype=float),
        drive=_drive_weights(model, np.asarray(system.mass_dof), system.size),
        loads=loads,
        hysteretic_frequency=wh,
        gears=_gear_meshes(
            model, tuple(system.element_labels), np.asarray(system.mass_dof), system.mass_ratio
        ),
        system=system,
    )


@dataclass(frozen=True)
class GearMesh:
    """A rigid gear mesh, its torque read from its wheel's balance: the torque the pinion
    passes to the wheel (own sense of the wheel) is J_w alpha_w plus what the wheel's elements
    carry away, T = J_w alpha_w + sum s_e T_e (s_e = +1 where the wheel is the element's first
    mass, -1 where its second); external torques at the wheel itself are left out.

    Parameters
    ----------
    name : str
        The gear's name for people.
    between : (str, str)
        Pinion and wheel.
    dof : int
        The meshing wheels' degree of freedom.
    inertia : float
        J_w, the wheel's own inertia (kg m^2).
    ratio : float
        |r_w| of the wheel.
    elements : tuple of (int, float)
        (element, s_e) of every element at the wheel.
    """

    name: str
    between: tuple[str, str]
    dof: int
    inertia: float
    ratio: float
    elements: tuple[tuple[int, float], ...]


def _gear_meshes(
    model: TorsionModel,
    line_labels: Sequence[tuple[str, str]],
    mass_dof: NDArray[np.int_],
    ratio: NDArray[np.float64],
) -> tuple[GearMesh, ...]:
    """The rigid gear meshes of a model (joints of bolted masses left out)."""
    out = []
    for g in model.gears:
        if g.joint or g.stiffness is not None:
            continue
        wheel = g.between[1]
        i = model.index(wheel)
        elements = tuple(
            (e, 1.0 if a == wheel else -1.0)
            for e, (a, b) in enumerate(line_labels)
            if wheel in (a, b)
        )
        name = g.name or f"{g.between[0]} - {wheel}"
        out.append(
            GearMesh(
                name,
                (g.between[0], wheel),
                int(mass_dof[i]),
                float(model.masses[i].inertia),
                float(abs(ratio[i])),
                elements,
            )
        )
    return tuple(out)


# ---- the mean-speed history --------------------------------------------------------------------
Curve = Callable[[NDArray[np.float64]], NDArray[np.float64]]


@dataclass(frozen=True, eq=False)
class Profile:
    """The mean speed of the line, its angle and the engine's torque against time.

    Parameters
    ----------
    speed : callable
        Omega(t): the reference speed (rad/s) at times (s).
    angle : callable
        phi(t) = integral of Omega (rad): the crank angle of the harmonic torques.
    drive : callable
        The reflected engine torque T_e(t) (N m).
    brake : callable
        The reflected braking torque (N m), >= 0.
    scale : callable
        The factor on the cylinders' harmonic torques (1 firing, 0 after a fuel cut).
    low, high : float
        The smallest and largest speed of the history (rad/s).
    end : float or None
        When the history ends (an emergency stop reaching its end speed), or None.
    loads : bool
        Whether the load laws act.
    breakpoints : tuple of float
        Times (s) where the history kinks.
    """

    speed: Curve
    angle: Curve
    drive: Curve
    brake: Curve
    scale: Curve
    low: float
    high: float
    end: float | None = None
    loads: bool = True
    breakpoints: tuple[float, ...] = ()


def _const(value: float) -> Curve:
    def f(t: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.full(np.shape(t), value)

    return f


def constant_profile(line: Line, speed: float, *, loads: bool = True) -> Profile:
    """A constant speed: the engines carry the loads (no mean acceleration).

    Parameters
    ----------
    line : Line
        The line.
    speed : float
        Omega (rad/s), >= 0.
    loads : bool
        Whether the load laws act.

    Returns
    -------
    Profile
        Omega(t) = speed, phi = speed t.
    """
    total = float(line.total_load(np.array(speed))) if loads else 0.0

    def angle(t: NDArray[np.float64]) -> NDArray[np.float64]:
        return speed * np.asarray(t, dtype=float)

    return Profile(
        _const(speed), angle, _const(total), _const(0.0), _const(1.0), speed, speed, loads=loads
    )


def speed_profile(line: Line, event: SpeedChange, duration: float | None) -> Profile:
    """The mean speed of a start, stop, emergency stop or ramp: the rigid-body equation
    J Omega' = T_e - T_L(Omega) - T_brake with the governor and the torque curve of the event
    (:class:`crankdyn.torsion.events.SpeedChange`), integrated by scipy's ``solve_ivp`` (RK45,
    rtol 1e-10) with its dense output.

    Parameters
    ----------
    line : Line
        The line (J = the sum of its reflected inertias; its load laws).
    event : crankdyn.torsion.events.SpeedChange
        The event.
    duration : float or None
        The run's duration (s); None: the event's (its ramp and five governor time constants;
        an emergency stop until its end speed).

    Returns
    -------
    Profile
        The history.

    Raises
    ------
    InputError
        An emergency stop that does not reach its end speed within an hour (no load and no
        brake), naming ``duration``.
    """
    from scipy.integrate import solve_ivp  # imported here: keeps the start-up light

    j_total = float(np.sum(line.inertia))
    tau = event.governor_time
    cut = event.fuel_cut
    loads = event.load

    def engine(t: NDArray[np.float64], w: NDArray[np.float64]) -> NDArray[np.float64]:
        """T_e at times t and speeds w, vectorised (class docstring of SpeedChange)."""
        w = np.maximum(w, 0.0)
        load = line.total_load(w) if loads else np.zeros(w.shape)
        want = load + j_total * (event.set_rate(t) + (event.set_speed(t) - w) / tau)
        out = np.clip(want, 0.0, event.max_torque(w))
        return np.where(t >= cut, 0.0, out) if cut is not None else out

    def brake(t: NDArray[np.float64]) -> NDArray[np.float64]:
        t = np.asarray(t, dtype=float)
        return np.where(t >= cut, event.brake_torque, 0.0) if cut is not None else 0.0 * t

    def rhs(t: float, y: NDArray[np.float64]) -> list[float]:
        w = np.array([float(y[0])])
        ts = np.array([t])
        load = line.total_load(np.maximum(w, 0.0)) if loads else 0.0 * w
        net = float((engine(ts, w) - load - brake(ts))[0])
        if w[0] <= 0.0 and net < 0.0:
            net = 0.0
        return [net / j_total, float(w[0])]

    natural = event.hold + event.ramp_time + 5.0 * tau
    t_end = duration if duration is not None else (3600.0 if cut is not None else natural)
    events = []
    if cut is not None:

        def reached(t: float, y: NDArray[np.float64]) -> float:
            return float(y[0]) - event.end_speed

        reached.terminal = True  # type: ignore[attr-defined]
        reached.direction = -1  # type: ignore[attr-defined]
        events.append(reached)
    max_step = min(tau / 4.0, event.ramp_time / 20.0 if event.ramp_time > 0 else np.inf)
    sol = solve_ivp(
        rhs,
        (0.0, t_end),
        [event.start_speed, 0.0],
        method="RK45",
        rtol=1e-10,
        atol=1e-9,
        dense_output=True,
        events=events or None,
        max_step=max_step,
    )
    if not sol.success:  # pragma: no cover - scipy's own failure
        raise RuntimeError(sol.message)
    end = float(sol.t[-1])
    if cut is not None and duration is None and sol.status != 1:
        raise InputError(
            "the line does not coast down to the end speed within an hour: give a brake "
            "torque, a load law or the duration",
            key="duration",
        )
    dense = sol.sol

    def speed(t: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.asarray(dense(np.clip(np.asarray(t, dtype=float), 0.0, end))[0])

    def angle(t: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.asarray(dense(np.clip(np.asarray(t, dtype=float), 0.0, end))[1])

    def drive(t: NDArray[np.float64]) -> NDArray[np.float64]:
        t = np.asarray(t, dtype=float)
        return engine(t, speed(t))

    def scale(t: NDArray[np.float64]) -> NDArray[np.float64]:
        t = np.asarray(t, dtype=float)
        return np.where(t >= cut, 0.0, 1.0) if cut is not None else np.ones(t.shape)

    samples = speed(np.linspace(0.0, end, 2001))
    return Profile(
        speed,
        angle,
        drive,
        brake,
        scale,
        float(np.min(samples)),
        float(np.max(samples)),
        end=end if cut is not None and duration is None else None,
        loads=loads,
        breakpoints=tuple(b for b in event.breakpoints() if b > 0.0),
    )


@dataclass(eq=False)
class Harmonics:
    """Re sum_q F_q(Omega) e^{i q phi}: the harmonic torques (N m) on a line's degrees of
    freedom at mean speeds and crank angles, F interpolated linearly over the speed grid; only
    the degrees of freedom a torque acts on (the cylinders' and the sources' masses: a few of
    a long line's) are computed, the others are 0.

    Parameters
    ----------
    grid : numpy.ndarray
        Mean speeds (rad/s), shape (G,).
    forcing : numpy.ndarray
        Complex harmonic torques (N m), shape (G, Q, n): per speed, order and degree of freedom.
    orders : numpy.ndarray
        The orders q (multiples of the crankshaft speed), shape (Q,).
    """

    grid: NDArray[np.float64]
    forcing: NDArray[np.complex128]  # (G, Q, n)
    orders: NDArray[np.float64]
    excited: NDArray[np.intp] = field(init=False)
    compact: NDArray[np.complex128] = field(init=False)  # (G, Q, excited)

    def __post_init__(self) -> None:
        self.excited = np.flatnonzero(np.any(self.forcing != 0.0, axis=(0, 1)))
        self.compact = np.ascontiguousarray(self.forcing[:, :, self.excited])

    def __call__(self, speed: NDArray[np.float64], angle: NDArray[np.float64]) -> NDArray[Any]:
        """The torques (N m), shape (L, n), at mean speeds (rad/s) and crank angles (rad), (L,).

        Parameters
        ----------
        speed : numpy.ndarray
            Mean speeds (rad/s), shape (L,).
        angle : numpy.ndarray
            Crank angles (rad), shape (L,).

        Returns
        -------
        numpy.ndarray
            The harmonic torques on every degree of freedom (N m), shape (L, n).
        """
        phase = np.exp(1j * angle[:, None] * self.orders[None, :])  # (L, Q)
        out = np.zeros((speed.size, self.forcing.shape[2]))
        if self.grid.size == 1:
            out[:, self.excited] = (phase @ self.compact[0]).real
            return out
        pos = np.interp(speed, self.grid, np.arange(self.grid.size, dtype=float))
        cell = np.minimum(pos.astype(int), self.grid.size - 2)
        frac = (pos - cell)[:, None]
        part = np.empty((speed.size, self.excited.size))
        for c in np.unique(cell):  # a handful of grid cells per block
            sel = cell == c
            p = phase[sel]
            f0, f1 = self.compact[c], self.compact[c + 1]
            part[sel] = ((p * (1.0 - frac[sel])) @ f0 + (p * frac[sel]) @ f1).real
        out[:, self.excited] = part
        return out


def harmonics_of(
    model: TorsionModel,
    line: Line,
    excitation: Excitation,
    orders: ArrayLike,
    profile: Profile,
) -> Harmonics:
    """The harmonic torques of the cylinders and sources over the profile's speeds (201 speeds
    across its range, or its one speed).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The model.
    line : Line
        Its line (:func:`line_of`).
    excitation : crankdyn.torsion.excitation.Excitation
        The cylinders' excitation.
    orders : array_like
        The orders (multiples of the crankshaft speed).
    profile : Profile
        The event's mean-speed history.

    Returns
    -------
    Harmonics
        The torques, callable at mean speeds and crank angles.

    Raises
    ------
    crankdyn.errors.InputError
        The profile's speeds are not above 0, or an order is not one of the model's.
    """
    from crankdyn.torsion.sources import assemble_forcing, check_model_orders

    orders = check_model_orders(model, excitation, orders)
    low, high = max(profile.low, 1e-3 * max(profile.high, 1e-9)), profile.high
    if not high > 0.0:
        raise InputError("the harmonic torques need a speed above 0", key="speed")
    grid = np.array([high]) if high - low <= 1e-12 * high else np.linspace(low, high, 201)
    forcing, _notes = assemble_forcing(model, line.system, excitation, grid, orders)  # type: ignore[arg-type]
    return Harmonics(grid, forcing, np.asarray(orders, dtype=float))
