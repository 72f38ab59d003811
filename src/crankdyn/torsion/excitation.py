"""Engine excitation of torsional vibration: the harmonic torques of the cylinders at any speed
(analysis).

The cylinder torques are Fourier series in the orders of the crankshaft speed
(:mod:`crankdyn.torsion.orders`: seed 003, 第4章 "曲轴系统的激发力矩", and the V6 paper's eq. 5;
the phase-vector rule of seed 003 section 4.2). :class:`EngineExcitation` samples an engine's
cylinder torque at :data:`SAMPLES` = 7200 equally spaced angles over the cycle (0.1 deg for a
four-stroke cycle) for their coefficients; :class:`UniformExcitation` gives every cylinder the
same torque per order, :class:`SourceExcitation` none (the model's sources act). What a model or
engine file says about its excitation is :class:`~crankdyn.torsion.excitation_spec.ExcitationSpec`;
the harmonic analysis at one speed is :func:`crankdyn.torsion.harmonics.harmonic_analysis`.

Dependence on speed. The inertia part -m_j a R sin(phi + beta)/cos(beta) scales with Omega^2
(a = R Omega^2 f(phi) at constant speed), so its harmonics are Omega^2 times those at 1 rad/s.
The gas part follows the pressure at that speed or load:

- a load curve (speed against peak pressure, IMEP or a plain load factor) scales the absolute
  pressure of the engine's trace by s(Omega) = peak(Omega)/peak(trace) (or IMEP ratio, or the
  factor): the gas torque harmonics are s c_q[p A lever R] - c_q[p_cc A lever R] (the crankcase
  pressure p_cc is not scaled) - the calculation of Mendes et al. (2008), who scale their
  full-load trace by the measured peak-pressure curve;
- or traces at several speeds: the harmonics of each, interpolated linearly in speed;
- or a harmonic-coefficient table (the classical tables of tangential-pressure harmonics
  against mean indicated pressure, e.g. W. Ker Wilson, *Practical Solution of Torsional
  Vibration Problems*, vol. 2, ch. 20): T_q(p_mi) per order, in the sine form
  T_q sin(q theta + psi_q) from firing TDC, so c_q = A R T_q exp(i (psi_q - pi/2)); without
  phases the gas and inertia harmonics of an order are added as if in phase (their amplitudes
  add: the conservative choice; the phase between cylinders comes from the firing angles and is
  exact either way).

Misfire (or cylinder cut-out, the same physics: no combustion in the cylinder, compression kept):
the cylinder's gas pressure is replaced by the motored pressure, polytropic compression and
expansion from the intake pressure (the synthetic model of :mod:`crankdyn.crank.pressure_model`
with no heat release), which needs the compression ratio. Under a load curve the motored
pressure is scaled by the same factor s(Omega) as the firing cylinders' absolute pressure: the
cylinders share the intake manifold, so at part load a misfiring cylinder compresses the same
(lower) charge as its neighbours, whose scaled traces carry that charge's compression.

Computed once per engine. The spectra of the basis signals (the pressure traces', the inertia
torque's at 1 rad/s, the crankcase pressure's, over the cycle grid) depend on the engine and the
excitation spec only, not on the torsional model nor on the misfiring cylinders: the
excitations of equal engines (equal in every field but the torsional model: a TVC's misfire
conditions, a design search's candidates that share the engine and its firing order) share them,
the last :data:`SHARED_ENGINES` engines' kept in the process (read-only arrays).
"""

from __future__ import annotations

import dataclasses
import hashlib
import math
import pickle
from collections import OrderedDict
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Generic, TypeAlias, TypeVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.constants import RPM
from crankdyn.engine.firing import CYCLE_ANGLE, even_firing_interval
from crankdyn.errors import InputError
from crankdyn.results import freeze
from crankdyn.torsion.excitation_spec import CylinderHarmonics, ExcitationSpec
from crankdyn.torsion.orders import (
    Complex,
    check_orders,
    fundamental_order,
    harmonic_index,
    major_orders,
    phase_vectors,
)

if TYPE_CHECKING:
    from crankdyn.crank.pressure import PressureTrace
    from crankdyn.engine.model import Engine
    from crankdyn.torsion.model import TorsionModel

__all__ = [
    "MAJOR_UNDETERMINED",
    "SAMPLES",
    "SHARED_ENGINES",
    "EngineExcitation",
    "SourceExcitation",
    "TabulatedExcitation",
    "UniformExcitation",
    "excitation_for",
    "interp_complex",
    "known_major_orders",
]

SAMPLES = 7200
"""Samples per cycle for the harmonic analysis (FFT length)."""
MAJOR_UNDETERMINED = (
    "major orders undetermined: the model gives no firing order or firing angles, so every "
    "cylinder is excited in phase (an assumption); give [excitation] firing_order or "
    "firing_angles to mark the major orders"
)


def known_major_orders(excitation: Excitation, orders: ArrayLike) -> NDArray[np.bool_] | None:
    """:func:`major_orders` of an excitation's firing angles, or None when the excitation does
    not know its cylinders' phases (:mod:`crankdyn.torsion.orders`: a model without firing
    angles).

    Parameters
    ----------
    excitation : Excitation
        An :class:`EngineExcitation`, :class:`UniformExcitation` or :class:`SourceExcitation`.
    orders : array_like
        Orders (dimensionless), shape (orders,).

    Returns
    -------
    numpy.ndarray or None
        Whether each order is major, shape (orders,); None when the phases are an assumption.

    Examples
    --------
    >>> known = UniformExcitation(1.0, np.radians([0.0, 360.0]))
    >>> known_major_orders(known, [0.5, 1.0])
    array([False,  True])
    >>> print(known_major_orders(UniformExcitation(1.0, [0.0, 0.0], phases_known=False), [1.0]))
    None
    """
    if not getattr(excitation, "phases_known", True):
        return None
    return major_orders(excitation.firing_angles, orders)


def _cycle_grid(cycle: str, samples: int = SAMPLES) -> NDArray[np.float64]:
    return np.arange(samples, dtype=float) * (CYCLE_ANGLE[cycle] / samples)


# ---- evaluation ---------------------------------------------------------------------------------
def _check_cylinder_list(numbers: Iterable[int], count: int, key: str) -> tuple[int, ...]:
    out = tuple(int(c) for c in numbers)
    for c in out:
        if not 1 <= c <= count:
            raise InputError(f"the engine has cylinders 1 to {count}", key=key, value=c)
    return out


@dataclass(frozen=True, eq=False)
class UniformExcitation:
    """The same harmonic torque amplitude for every order at every cylinder, phased by the
    firing angles: c_q,i = T exp(-i q Phi_i) (N m). Receptance-type studies (unit torque) and
    models without an engine.

    Parameters
    ----------
    torque : float
        T (N m), > 0.
    firing_angles : array_like
        Firing angle of every cylinder (rad), shape (cylinders,), cylinder 1 first; zeros put
        all in phase.
    cycle : str
        The working cycle, ``"four-stroke"`` or ``"two-stroke"`` (sets the admissible orders).
    note : str
        Text for reports.
    phases_known : bool
        Whether the firing angles are the engine's (False: an assumption, e.g. all in phase for
        a model without a firing order; major orders are then undetermined).

    Raises
    ------
    crankdyn.errors.InputError
        A torque not positive (key ``torque``).

    Examples
    --------
    >>> exc = UniformExcitation(2.0, np.radians([0.0, 360.0]))
    >>> np.round(exc.harmonics([100.0], [0.5, 1.0]), 12)
    array([[[ 2.+0.j, -2.-0.j],
            [ 2.+0.j,  2.+0.j]]])
    """

    torque: float
    firing_angles: NDArray[np.float64]
    cycle: str = "four-stroke"
    note: str = ""
    phases_known: bool = True

    def __post_init__(self) -> None:
        if not (math.isfinite(self.torque) and self.torque > 0.0):
            raise InputError("the torque amplitude must be positive", key="torque")
        object.__setattr__(self, "firing_angles", freeze(np.atleast_1d(self.firing_angles)))

    @property
    def cylinder_count(self) -> int:
        """Number of cylinders (one per firing angle)."""
        return int(self.firing_angles.size)

    @property
    def description(self) -> str:
        """One line describing the excitation, for reports."""
        return f"uniform harmonic torque {self.torque:g} N·m per order at every cylinder"

    def notes(self, speeds: ArrayLike) -> tuple[str, ...]:
        """Notes for reports on the excitation at these speeds.

        Parameters
        ----------
        speeds : array_like
            Crankshaft speeds (rad/s).

        Returns
        -------
        tuple of str
            The excitation's note, if any.
        """
        return (self.note,) if self.note else ()

    def parts(self, speeds: ArrayLike, orders: ArrayLike) -> tuple[Complex, Complex]:
        """(gas, inertia) harmonics: the uniform torque counts as gas, the inertia part is zero.

        Parameters
        ----------
        speeds : array_like
            Crankshaft speeds (rad/s), shape (speeds,).
        orders : array_like
            Orders (dimensionless), shape (orders,), valid for the cycle.

        Returns
        -------
        gas, inertia : numpy.ndarray
            Complex harmonic torques (N m), each of shape (speeds, orders, cylinders).
        """
        speeds = np.atleast_1d(np.asarray(speeds, dtype=float))
        orders = check_orders(orders, self.cycle)
        one = self.torque * phase_vectors(self.firing_angles, orders)
        gas = np.broadcast_to(one, (speeds.size, *one.shape)).copy()
        return gas, np.zeros_like(gas)

    def harmonics(self, speeds: ArrayLike, orders: ArrayLike) -> Complex:
        """Harmonic torque of every cylinder, T exp(-i q Phi_i).

        Parameters
        ----------
        speeds : array_like
            Crankshaft speeds (rad/s), shape (speeds,).
        orders : array_like
            Orders (dimensionless), shape (orders,), valid for the cycle.

        Returns
        -------
        numpy.ndarray
            Complex harmonic torques (N m), shape (speeds, orders, cylinders).
        """
        gas, _ = self.parts(speeds, orders)
        return gas


SHARED_ENGINES = 8
"""How many engines' basis spectra a process keeps (module docstring)."""

_SHARED: OrderedDict[str, dict[str, Any]] = OrderedDict()
_T = TypeVar("_T")


class _Digest:
    """A file that hashes what is written to it."""

    def __init__(self, digest: Any) -> None:
        self.write = digest.update


def _shared_store(engine: Engine, spec: ExcitationSpec | None) -> dict[str, Any]:
    """The basis spectra of an engine and spec (module docstring), shared by equal ones: keyed by
    the digest of their fields' values pickled, the torsional model left out; an engine that
    cannot be pickled keeps its own."""
    digest = hashlib.sha256()
    pickler = pickle.Pickler(_Digest(digest), protocol=5)
    pickler.fast = True  # no memo: equal values give equal bytes whatever objects they share
    try:
        # the fields' values only (astuple: no attribute an object keeps for later use)
        fields = dataclasses.astuple(dataclasses.replace(engine, torsion=None))
        pickler.dump((fields, None if spec is None else dataclasses.astuple(spec)))
    except (pickle.PicklingError, TypeError, AttributeError, ValueError):
        return {}
    key = digest.hexdigest()
    store = _SHARED.get(key)
    if store is None:
        store = _SHARED[key] = {}
        while len(_SHARED) > SHARED_ENGINES:
            _SHARED.popitem(last=False)
    else:
        _SHARED.move_to_end(key)
    return store


class _basis(Generic[_T]):  # a decorator, like cached_property
    """A basis spectrum of :class:`EngineExcitation`: computed on first use and kept in the
    store its engine shares (module docstring), arrays read-only."""

    def __init__(self, func: Callable[[Any], _T]) -> None:
        self.func = func
        self.name = func.__name__
        self.__doc__ = func.__doc__

    def __get__(self, obj: Any, owner: Any = None) -> _T:
        if obj is None:
            return self  # type: ignore[return-value]  # the descriptor itself, as a property's
        store = obj._store
        if self.name not in store:
            value = self.func(obj)
            if isinstance(value, np.ndarray):
                value.flags.writeable = False
            store[self.name] = value
        return store[self.name]


@dataclass(frozen=True, eq=False)
class EngineExcitation:
    """The gas and inertia torques of an engine's cylinders (module docstring).

    Parameters
    ----------
    engine : crankdyn.engine.model.Engine
        The engine (its masses are required for the inertia part).
    spec : ExcitationSpec or None
        Load curve, traces at speeds or harmonic table, and misfiring cylinders; None for the
        engine's trace at every speed.
    misfire : tuple of int
        Misfiring cylinders, 1-based (in addition to ``spec.misfire``).

    Raises
    ------
    crankdyn.errors.InputError
        A misfiring cylinder the engine does not have (key ``misfire``), or a harmonic table
        without a mean indicated pressure (key ``harmonics``, naming the engine file).
    """

    engine: Engine
    spec: ExcitationSpec | None = None
    misfire: tuple[int, ...] = ()

    def __post_init__(self) -> None:
        object.__setattr__(self, "_store", _shared_store(self.engine, self.spec))
        count = self.engine.cylinders.count
        both = tuple(self.misfire) + (self.spec.misfire if self.spec else ())
        object.__setattr__(
            self, "misfire", tuple(sorted(set(_check_cylinder_list(both, count, "misfire"))))
        )
        if self.spec is not None and self.spec.harmonics is not None:
            self._table_imep_source()  # fail early without an IMEP

    # ---- properties ---------------------------------------------------------------------------
    @property
    def cycle(self) -> str:
        """The engine's working cycle, ``"four-stroke"`` or ``"two-stroke"``."""
        return self.engine.cycle

    @property
    def firing_angles(self) -> NDArray[np.float64]:
        """Firing angle of every cylinder (rad), cylinder 1 first."""
        return np.asarray(self.engine.cylinders.firing_angles, dtype=float)

    @property
    def cylinder_count(self) -> int:
        """Number of cylinders of the engine."""
        return self.engine.cylinders.count

    @property
    def description(self) -> str:
        """One line describing the excitation (pressure source, load, misfire), for reports."""
        spec = self.spec
        if spec is not None and spec.harmonics is not None:
            gas = f"harmonic table {spec.harmonics.source or ''}".strip()
        elif spec is not None and spec.traces:
            gas = f"pressure traces at {len(spec.traces)} speeds"
        else:
            gas = f"pressure trace {self._trace.source or ''}".strip()
            if spec is not None and spec.load_curve is not None:
                gas += f" scaled by the {spec.load_curve.kind.replace('_', ' ')} curve"
                if spec.load_curve.source:
                    gas += f" {spec.load_curve.source}"
        text = f"{self.engine.name}: gas ({gas}) and inertia torques"
        if self.misfire:
            text += f"; cylinder(s) {', '.join(map(str, self.misfire))} misfiring (motored)"
        return text

    def breakpoints(self) -> NDArray[np.float64]:
        """Speeds where the excitation is not smooth in speed: the points of a load curve
        (interpolated linearly) or of the traces at several speeds. A resolved forced response
        samples them, so a peak at such a kink is found exactly.

        Returns
        -------
        numpy.ndarray
            The speeds (rad/s), shape (points,); empty without a load curve or traces.
        """
        spec = self.spec
        points: list[NDArray[np.float64]] = []
        if spec is not None and spec.load_curve is not None:
            points.append(np.asarray(spec.load_curve.speed, dtype=float))
        if spec is not None and spec.traces:
            points.append(np.array([t.speed for t in spec.traces], dtype=float))
        return np.concatenate(points) if points else np.zeros(0)

    def notes(self, speeds: ArrayLike) -> tuple[str, ...]:
        """Notes for reports on the excitation at these speeds: speeds outside the load curve or
        the traces, a synthetic pressure trace, a harmonic table without phases.

        Parameters
        ----------
        speeds : array_like
            Crankshaft speeds (rad/s).

        Returns
        -------
        tuple of str
            The notes (empty when there is nothing to say).
        """
        out = []
        curve = self.spec.load_curve if self.spec else None
        if curve is not None and curve.outside(speeds):
            out.append(
                f"speeds outside the load curve ({curve.speed[0] * RPM:.0f}-"
                f"{curve.speed[-1] * RPM:.0f} rpm) use its end values"
            )
        if self.spec is not None and self.spec.traces:
            w = [t.speed for t in self.spec.traces]
            s = np.asarray(speeds)
            if np.any(s < w[0] * (1 - 1e-9)) or np.any(s > w[-1] * (1 + 1e-9)):
                out.append("speeds outside the traces' speeds use the nearest trace")
        if self.engine.pressure is None and (
            self.spec is None or (not self.spec.traces and self.spec.harmonics is None)
        ):
            out.append("no pressure trace: synthetic Wiebe model with default parameters")
        table = self.spec.harmonics if self.spec else None
        if table is not None and table.phase is None:
            out.append(
                "the harmonic table has no phases: gas and inertia harmonics added in phase "
                "(amplitudes add, conservative)"
            )
        return tuple(out)

    # ---- spectra of the basis signals (computed once) -----------------------------------------
    @_basis
    def _trace(self) -> PressureTrace:
        from crankdyn.crank.pressure_model import default_pressure

        return default_pressure(self.engine)

    @_basis
    def _theta(self) -> NDArray[np.float64]:
        return _cycle_grid(self.cycle)

    @_basis
    def _lever(self) -> NDArray[np.float64]:
        """R sin(phi + beta)/cos(beta) (m) of every cylinder over the cycle grid."""
        from crankdyn.engine.forces import rod_forces

        g, cyl = self.engine.geometry, self.engine.cylinders
        phi = self._theta[None, :] - np.asarray(cyl.throw_angles)[:, None]
        return rod_forces(np.ones_like(phi), phi, g.lam, g.k)[2] * g.crank_radius

    @_basis
    def _phase(self) -> NDArray[np.float64]:
        """Every cylinder's angle from its firing TDC over the grid (rad)."""
        return np.mod(self._theta[None, :] - self.firing_angles[:, None], self.engine.cycle_angle)

    def _pressure_spectrum(self, trace: PressureTrace) -> Complex:
        """rfft of p A R lever (absolute pressure) of every cylinder, shape (Z, N/2+1)."""
        area = self.engine.geometry.piston_area
        return np.fft.rfft(trace.at(self._phase) * area * self._lever, axis=-1)

    @_basis
    def _crankcase_spectrum(self) -> Complex:
        area = self.engine.geometry.piston_area
        return np.fft.rfft(self.engine.crankcase_pressure * area * self._lever, axis=-1)

    @_basis
    def _inertia_spectrum(self) -> Complex:
        """rfft of the inertia torque at 1 rad/s, shape (Z, N/2+1)."""
        from crankdyn.crank.kinematics import slider_crank_exact
        from crankdyn.engine.forces import engine_masses

        g, cyl = self.engine.geometry, self.engine.cylinders
        m_j = np.array([m.reciprocating for m in engine_masses(self.engine)])[:, None]
        phi = self._theta[None, :] - np.asarray(cyl.throw_angles)[:, None]
        a = slider_crank_exact(phi, g.crank_radius, g.rod_length, g.offset, 1.0).acceleration
        return np.fft.rfft(-m_j * a * self._lever, axis=-1)

    @_basis
    def _trace_spectrum(self) -> Complex:
        return self._pressure_spectrum(self._trace)

    @_basis
    def _speed_trace_spectra(self) -> Complex:
        traces = self.spec.traces if self.spec is not None else ()
        return np.stack([self._pressure_spectrum(t.trace) for t in traces])

    @_basis
    def _motored_trace(self) -> PressureTrace:
        from crankdyn.crank.pressure_model import WiebePressureModel

        trace = self._trace
        eps = trace.compression_ratio
        if eps is None:
            raise InputError(
                "a misfiring cylinder is motored (compression without combustion), which needs "
                "the compression ratio: give [pressure] compression_ratio",
                file=self.engine.source,
                key="misfire",
                value=list(self.misfire),
            )
        p_in = float(trace.at(np.array([self.engine.cycle_angle - math.pi]))[0])
        model = WiebePressureModel(compression_ratio=eps, fuel_energy=0.0, intake_pressure=p_in)
        return model.trace(self.engine.geometry, self.cycle, source="motored")

    @_basis
    def _motored_spectrum(self) -> Complex:
        return self._pressure_spectrum(self._motored_trace)

    # ---- load ----------------------------------------------------------------------------------
    def load_factor(self, speeds: ArrayLike) -> NDArray[np.float64]:
        """Scale s(Omega) of the absolute pressure at every speed (module docstring; Mendes et
        al. 2008): the load curve's peak pressure over the trace's, its IMEP over the trace's,
        or the load factor itself; 1 without a load curve (or with an IMEP curve feeding a
        harmonic table).

        Parameters
        ----------
        speeds : array_like
            Crankshaft speeds (rad/s), shape (speeds,) or a scalar.

        Returns
        -------
        numpy.ndarray
            The scale (dimensionless), shape (speeds,).

        Raises
        ------
        crankdyn.errors.InputError
            An IMEP curve scaling a trace whose IMEP is not positive (key ``load_curve``).
        """
        speeds = np.atleast_1d(np.asarray(speeds, dtype=float))
        spec = self.spec
        curve = spec.load_curve if spec else None
        if curve is None or (
            spec is not None and spec.harmonics is not None and curve.kind == "imep"
        ):
            return np.ones(speeds.size)
        value = curve.at(speeds)
        if curve.kind == "load_factor":
            return value
        if curve.kind == "peak_pressure":
            return value / self._trace.peak[0]
        from crankdyn.crank.indicated import indicated_work

        imep = indicated_work(self._trace, self.engine.geometry) / self.engine.geometry.swept_volume
        if not imep > 0.0:
            raise InputError(
                "the trace's IMEP is not positive, so an IMEP curve cannot scale it",
                key="load_curve",
            )
        return value / imep

    def _table_imep_source(self) -> Callable[[ArrayLike], NDArray[np.float64]]:
        spec = self.spec
        if spec is not None and spec.load_curve is not None and spec.load_curve.kind == "imep":
            return spec.load_curve.at
        if spec is not None and spec.imep is not None:
            imep = spec.imep
            return lambda s: np.full(np.size(s), imep)
        raise InputError(
            "a harmonic table needs the mean indicated pressure: give imep, or a load curve "
            "of IMEP against speed",
            file=self.engine.source,
            key="harmonics",
        )

    def imep(self, speeds: ArrayLike) -> NDArray[np.float64] | None:
        """Mean indicated pressure at every speed for a harmonic table, else None.

        Parameters
        ----------
        speeds : array_like
            Crankshaft speeds (rad/s), shape (speeds,) or a scalar.

        Returns
        -------
        numpy.ndarray or None
            The IMEP (Pa) that enters the harmonic table, shape (speeds,); None without a table.
        """
        if self.spec is None or self.spec.harmonics is None:
            return None
        return self._table_imep_source()(np.atleast_1d(np.asarray(speeds, dtype=float)))

    # ---- harmonics ------------------------------------------------------------------------------
    def parts(self, speeds: ArrayLike, orders: ArrayLike) -> tuple[Complex, Complex]:
        """(gas, inertia) harmonic torques of every cylinder, phased by the firing angles: the
        FFT of the cylinder torques over the cycle (seed 003 ch. 4; module docstring), the
        inertia part scaled by Omega^2, the gas part by the load, traces or table.

        Parameters
        ----------
        speeds : array_like
            Crankshaft speeds (rad/s), shape (speeds,) or a scalar.
        orders : array_like
            Orders (dimensionless), shape (orders,), multiples of the fundamental order below
            1800 (four-stroke) or 3600 (two-stroke).

        Returns
        -------
        gas, inertia : numpy.ndarray
            Complex harmonic torques (N m), each of shape (speeds, orders, cylinders).

        Raises
        ------
        crankdyn.errors.InputError
            Orders that do not fit the cycle or are not resolved (key ``orders``), a misfire
            without a compression ratio (key ``misfire``, naming the engine file).
        """
        speeds = np.atleast_1d(np.asarray(speeds, dtype=float))
        orders = check_orders(orders, self.cycle)
        m = harmonic_index(orders, self.cycle)
        if np.any(m >= SAMPLES // 2):
            raise InputError(
                f"orders above {SAMPLES // 2 * fundamental_order(self.cycle):g} are not resolved",
                key="orders",
            )
        scale = 2.0 / SAMPLES
        inertia1 = (self._inertia_spectrum[:, m] * scale).T  # (Q, Z)
        inertia = speeds[:, None, None] ** 2 * inertia1[None]
        cc = (self._crankcase_spectrum[:, m] * scale).T
        spec = self.spec
        if spec is not None and spec.harmonics is not None:
            gas = self._table_gas(speeds, orders, inertia)
        elif spec is not None and spec.traces:
            w = np.array([t.speed for t in spec.traces])
            base = np.transpose(self._speed_trace_spectra[:, :, m] * scale, (0, 2, 1)) - cc
            gas = interp_complex(speeds, w, base)  # (S, Q, Z)
        else:
            p = (self._trace_spectrum[:, m] * scale).T
            s = self.load_factor(speeds)
            gas = s[:, None, None] * p[None] - cc[None]
        if self.misfire:
            idx = np.asarray(self.misfire) - 1
            motored = (self._motored_spectrum[:, m] * scale).T  # (Q, Z), absolute pressure
            if spec is not None and spec.harmonics is None and not spec.traces:
                # a load curve scales the absolute pressure of every cylinder alike: the
                # misfiring cylinder shares the intake manifold (module docstring)
                motored = self.load_factor(speeds)[:, None, None] * motored[None]
            else:
                motored = np.broadcast_to(motored, (speeds.size, *motored.shape))
            gas = np.array(gas, copy=True)
            gas[:, :, idx] = motored[:, :, idx] - cc[None, :, idx]
        return gas, inertia

    def _table_gas(
        self, speeds: NDArray[np.float64], orders: NDArray[np.float64], inertia: Complex
    ) -> Complex:
        table = self.spec.harmonics if self.spec is not None else None
        assert table is not None  # parts() calls this with a harmonic table only
        imep = self._table_imep_source()(speeds)
        g = self.engine.geometry
        t = table.coefficients(orders, imep) * g.piston_area * g.crank_radius  # (S, Q)
        if table.phase is None:
            # in phase with the inertia harmonic of cylinder 1's own cycle (conservative)
            own = inertia[:, :, 0] * np.exp(1j * orders * self.firing_angles[0])[None, :]
            unit = np.where(np.abs(own) > 0.0, own / np.where(own == 0, 1, np.abs(own)), 1.0)
            t = np.abs(t) * unit
        return t[:, :, None] * phase_vectors(self.firing_angles, orders)[None]

    def harmonics(self, speeds: ArrayLike, orders: ArrayLike) -> Complex:
        """Harmonic torque of every cylinder, gas + inertia (:meth:`parts`).

        Parameters
        ----------
        speeds : array_like
            Crankshaft speeds (rad/s), shape (speeds,) or a scalar.
        orders : array_like
            Orders (dimensionless), shape (orders,).

        Returns
        -------
        numpy.ndarray
            Complex harmonic torques (N m), shape (speeds, orders, cylinders).
        """
        gas, inertia = self.parts(speeds, orders)
        return gas + inertia


def interp_complex(x: ArrayLike, xp: NDArray[np.float64], fp: Complex) -> Complex:
    """Linear interpolation along the first axis of fp (held at the ends), vectorised.

    Parameters
    ----------
    x : array_like
        Where to interpolate (unit of ``xp``), shape (points,).
    xp : numpy.ndarray
        Abscissae (e.g. speeds in rad/s), increasing, shape (n,).
    fp : numpy.ndarray
        Values, complex, shape (n, ...).

    Returns
    -------
    numpy.ndarray
        Interpolated values, shape (points, ...).

    Examples
    --------
    >>> interp_complex([0.5, 2.0], np.array([0.0, 1.0]), np.array([0j, 2 + 2j]))
    array([1.+1.j, 2.+2.j])
    """
    x = np.asarray(x, dtype=float)
    if len(xp) == 1:
        return np.broadcast_to(fp[0], (x.size, *fp.shape[1:])).copy()
    i = np.clip(np.searchsorted(xp, x) - 1, 0, len(xp) - 2)
    t = np.clip((x - xp[i]) / (xp[i + 1] - xp[i]), 0.0, 1.0)
    t = t.reshape((-1,) + (1,) * (fp.ndim - 1))
    return (1.0 - t) * fp[i] + t * fp[i + 1]


@dataclass(frozen=True, eq=False)
class TabulatedExcitation:
    """The cylinders' harmonic torques from the engine builder's table of one cylinder's
    coefficients per order, firing and misfiring (a model file without an engine:
    :class:`~crankdyn.torsion.excitation_spec.CylinderHarmonics`), phased by the firing angles:
    c_q,i = c_q exp(-i q Phi_i) (the phase-vector rule of seed 003 section 4.2), the misfiring
    cylinders' from the table's misfire coefficients. The table holds each cylinder's whole
    torque (gas and inertia) at its speeds; :meth:`parts` returns it as the gas part, the
    inertia part zero.

    Parameters
    ----------
    table : CylinderHarmonics
        The coefficients of one cylinder.
    firing_angles : array_like
        Firing angle of every cylinder (rad), cylinder 1 first.
    cycle : str
        ``"four-stroke"`` or ``"two-stroke"``.
    misfire : tuple of int
        The misfiring cylinders (1-based).
    note : str
        Text for reports (how the firing angles were found).
    phases_known : bool
        Whether the firing angles are the engine's (False: an assumption).

    Raises
    ------
    crankdyn.errors.InputError
        A misfiring cylinder the model does not have (key ``misfire``) or a table without
        misfire coefficients (key ``misfire``, naming the file), an order of the table that the
        cycle has not (key ``order``, naming the file).

    Examples
    --------
    Two cylinders 360 deg apart, an order-0.5 torque of 100 sin(theta/2) N m each (c = -100 i),
    40 sin(theta/2) N m misfiring: the second cylinder's phase vector exp(-i pi) = -1.

    >>> from crankdyn.torsion.excitation_spec import CylinderHarmonics
    >>> table = CylinderHarmonics(order=[0.5], normal=[-100j], misfire=[-40j])
    >>> exc = TabulatedExcitation(table, np.radians([0.0, 360.0]))
    >>> np.round(exc.harmonics([50.0], [0.5]).imag, 9).tolist()
    [[[-100.0, 100.0]]]
    >>> off = TabulatedExcitation(table, np.radians([0.0, 360.0]), misfire=(2,))
    >>> np.round(off.harmonics([50.0], [0.5]).imag, 9).tolist()
    [[[-100.0, 40.0]]]
    """

    table: CylinderHarmonics
    firing_angles: NDArray[np.float64]
    cycle: str = "four-stroke"
    misfire: tuple[int, ...] = ()
    note: str = ""
    phases_known: bool = True

    def __post_init__(self) -> None:
        angles = freeze(np.atleast_1d(np.asarray(self.firing_angles, dtype=float)))
        object.__setattr__(self, "firing_angles", angles)
        misfire = _check_cylinder_list(self.misfire, angles.size, "misfire")
        object.__setattr__(self, "misfire", tuple(sorted(set(misfire))))
        if self.misfire:
            self.table.at([1.0], self.table.order[:1], misfiring=True)  # raises without them
        try:
            check_orders(self.table.order, self.cycle)
        except InputError as exc:
            raise InputError(
                f"the table's orders do not fit the {self.cycle} cycle ({exc.message})",
                file=self.table.source,
                key="order",
            ) from None

    @property
    def cylinder_count(self) -> int:
        """Number of cylinders (one per firing angle)."""
        return int(self.firing_angles.size)

    @property
    def description(self) -> str:
        """One line describing the excitation, for reports."""
        text = f"the cylinders' harmonic torques from the table {self.table.source or ''}"
        text = text.rstrip()
        if self.misfire:
            text += f"; cylinder(s) {', '.join(map(str, self.misfire))} misfiring (the table's)"
        return text

    def breakpoints(self) -> NDArray[np.float64]:
        """The table's speeds (rad/s): the coefficients are linear between them, so a resolved
        response samples them.

        Returns
        -------
        numpy.ndarray
            The speeds (rad/s); empty for a table without speeds.
        """
        return np.zeros(0) if self.table.speed is None else np.array(self.table.speed)

    def notes(self, speeds: ArrayLike) -> tuple[str, ...]:
        """Notes for reports: how the firing angles were found, and speeds outside the table's
        (the coefficients held at its ends).

        Parameters
        ----------
        speeds : array_like
            Crankshaft speeds (rad/s).

        Returns
        -------
        tuple of str
            The notes.
        """
        out = [self.note] if self.note else []
        w = np.atleast_1d(np.asarray(speeds, dtype=float))
        s = self.table.speed
        if s is not None and s.size and w.size and (w.min() < s[0] or w.max() > s[-1]):
            out.append(
                f"speeds outside the harmonic table's {s[0] * RPM:.6g}-{s[-1] * RPM:.6g} rpm: its "
                "coefficients held at its ends"
            )
        return tuple(out)

    def parts(self, speeds: ArrayLike, orders: ArrayLike) -> tuple[Complex, Complex]:
        """(gas, inertia) harmonic torques: the table's (the whole cylinder torque) as gas, the
        inertia part zero (class docstring).

        Parameters
        ----------
        speeds : array_like
            Crankshaft speeds (rad/s), shape (speeds,) or a scalar.
        orders : array_like
            Orders (dimensionless), shape (orders,), valid for the cycle; an order the table
            does not hold is 0.

        Returns
        -------
        gas, inertia : numpy.ndarray
            Complex harmonic torques (N m), each of shape (speeds, orders, cylinders).
        """
        speeds = np.atleast_1d(np.asarray(speeds, dtype=float))
        orders = check_orders(orders, self.cycle)
        phase = phase_vectors(self.firing_angles, orders)[None]  # (1, Q, Z)
        gas = self.table.at(speeds, orders)[:, :, None] * phase
        if self.misfire:
            idx = np.asarray(self.misfire) - 1
            off = self.table.at(speeds, orders, misfiring=True)[:, :, None] * phase[:, :, idx]
            gas[:, :, idx] = off
        return gas, np.zeros_like(gas)

    def harmonics(self, speeds: ArrayLike, orders: ArrayLike) -> Complex:
        """Harmonic torque of every cylinder, c_q exp(-i q Phi_i) (:meth:`parts`).

        Parameters
        ----------
        speeds : array_like
            Crankshaft speeds (rad/s), shape (speeds,).
        orders : array_like
            Orders (dimensionless), shape (orders,).

        Returns
        -------
        numpy.ndarray
            Complex harmonic torques (N m), shape (speeds, orders, cylinders).
        """
        return self.parts(speeds, orders)[0]


# ---- engine-less excitation ----------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class SourceExcitation:
    """The excitation of a model whose masses carry no cylinders: only its sources act (the
    interface of :class:`~crankdyn.torsion.excitation.UniformExcitation`, with no cylinder).

    Parameters
    ----------
    cycle : str
        ``"four-stroke"`` or ``"two-stroke"``.

    Examples
    --------
    >>> SourceExcitation().harmonics([10.0, 20.0], [1.0]).shape
    (2, 1, 0)
    """

    cycle: str = "four-stroke"

    @property
    def firing_angles(self) -> NDArray[np.float64]:
        """No firing angles (rad): an empty array."""
        return np.zeros(0)

    @property
    def cylinder_count(self) -> int:
        """No cylinders: 0."""
        return 0

    @property
    def description(self) -> str:
        """One line describing the excitation, for reports."""
        return "the model's excitation sources (no engine cylinders)"

    def notes(self, speeds: ArrayLike) -> tuple[str, ...]:
        """Notes for reports: none.

        Parameters
        ----------
        speeds : array_like
            Crankshaft speeds (rad/s).

        Returns
        -------
        tuple of str
            An empty tuple.
        """
        return ()

    def parts(self, speeds: ArrayLike, orders: ArrayLike) -> tuple[Complex, Complex]:
        """(gas, inertia) harmonics of no cylinder.

        Parameters
        ----------
        speeds : array_like
            Crankshaft speeds (rad/s), shape (speeds,).
        orders : array_like
            Orders (dimensionless), shape (orders,).

        Returns
        -------
        gas, inertia : numpy.ndarray
            Complex zeros (N m), each of shape (speeds, orders, 0).
        """
        s = np.atleast_1d(np.asarray(speeds, dtype=float))
        q = np.atleast_1d(np.asarray(orders, dtype=float))
        zero = np.zeros((s.size, q.size, 0), dtype=complex)
        return zero, zero.copy()

    def harmonics(self, speeds: ArrayLike, orders: ArrayLike) -> Complex:
        """Harmonic torques of no cylinder.

        Parameters
        ----------
        speeds : array_like
            Crankshaft speeds (rad/s), shape (speeds,).
        orders : array_like
            Orders (dimensionless), shape (orders,).

        Returns
        -------
        numpy.ndarray
            Complex zeros (N m), shape (speeds, orders, 0).
        """
        return self.parts(speeds, orders)[0]


Excitation: TypeAlias = (
    UniformExcitation | EngineExcitation | SourceExcitation | TabulatedExcitation
)
"""The excitation of a torsional model (:func:`excitation_for`): every kind has ``cycle``,
``firing_angles``, ``cylinder_count``, ``description``, ``notes``, ``parts`` and ``harmonics``."""


def excitation_for(
    model: TorsionModel,
    engine: Engine | None = None,
    *,
    misfire: Sequence[int] = (),
    torque: float | None = None,
) -> Excitation:
    """The excitation of a torsional model: the engine's cylinder torques when an engine is
    given (or attached), else the model's ``[excitation]`` (uniform torque, default 1 N m).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The model; its masses' ``cylinders`` are the excitation points.
    engine : crankdyn.engine.model.Engine or None
        The engine whose cylinder torques excite the model; None for the model's own engine
        (``[[engine]]``, the first) or, without one, its ``[excitation]`` table.
    misfire : sequence of int
        Misfiring cylinders (1-based); needs an engine, or a harmonic table with misfire
        coefficients.
    torque : float or None
        Forces a uniform excitation of that amplitude (N m) even with an engine (its firing
        angles are kept).

    Returns
    -------
    Excitation
        An :class:`EngineExcitation`, for a model without an engine whose ``[excitation]``
        gives the cylinders' harmonic table a :class:`TabulatedExcitation` (misfire from its
        misfire coefficients), a :class:`UniformExcitation`, or for a model with
        excitation sources but no cylinders a :class:`SourceExcitation` (its sources act,
        :mod:`crankdyn.torsion.sources`).

    Raises
    ------
    crankdyn.errors.InputError
        A model with no cylinder and no source (naming the model file), a misfire without an
        engine or a harmonic table with misfire coefficients (key ``misfire``), firing angles
        not one per cylinder (key ``firing_angles``).
    """
    spec = getattr(model, "excitation", None)
    cylinders = sorted(model.cylinder_dofs)
    if engine is None:
        engine = getattr(model, "engine", None)
    if not cylinders and getattr(model, "sources", None):
        if misfire:
            raise InputError(
                "a misfire needs engine cylinders on the model", key="misfire", value=list(misfire)
            )
        return SourceExcitation(spec.cycle if spec is not None else "four-stroke")
    if not cylinders:
        raise InputError(
            "the model has no excitation point: no mass carries a cylinder (give cylinders = "
            "[...] on the crank-throw masses)",
            file=model.source,
        )
    if engine is not None and torque is None:
        return EngineExcitation(engine, spec, tuple(misfire))
    table = spec.cylinder_harmonics if spec is not None and engine is None else None
    if table is not None and torque is None:
        cycle = spec.cycle if spec is not None else "four-stroke"
        angles, note = _model_firing_angles(spec, max(cylinders), cycle)
        return TabulatedExcitation(table, angles, cycle, tuple(misfire), note, not note)
    if misfire:
        raise InputError(
            "a misfire needs the engine's pressure (an engine file with a [torsion] section)",
            key="misfire",
            value=list(misfire),
        )
    count = max(cylinders)
    known = True
    if engine is not None:
        angles = np.asarray(engine.cylinders.firing_angles, dtype=float)
        cycle, note = engine.cycle, ""
    else:
        cycle = spec.cycle if spec is not None else "four-stroke"
        angles, note = _model_firing_angles(spec, count, cycle)
        known = not note
    if torque is None:
        torque = spec.torque if spec is not None and spec.torque is not None else 1.0
    return UniformExcitation(torque, angles, cycle, note, phases_known=known)


def _model_firing_angles(
    spec: ExcitationSpec | None, count: int, cycle: str
) -> tuple[NDArray[np.float64], str]:
    """Firing angles of an engine-less model's cylinders and a note on where they came from."""
    if spec is not None and spec.firing_angles is not None:
        angles = np.asarray(spec.firing_angles, dtype=float)
        if angles.size != count:
            raise InputError(
                f"expected {count} firing angles (cylinders 1 to {count})",
                key="firing_angles",
                value=angles.size,
            )
        return angles, ""
    if spec is not None and spec.firing_order is not None:
        from crankdyn.engine.firing import check_firing_order

        order = check_firing_order(spec.firing_order, count)
        interval = even_firing_interval(count, cycle)
        angles = np.empty(count)
        for k, c in enumerate(order):
            angles[c - 1] = k * interval
        return angles, ""
    return np.zeros(count), MAJOR_UNDETERMINED
