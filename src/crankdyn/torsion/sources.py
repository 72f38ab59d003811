"""Excitation at any mass and any order: propellers, electric machines, tabulated sources and
further engines; the mean torque along the line from the load laws (domain and numeric core).

Orders. A source acting on mass m produces harmonic torques at orders p of *that mass's* speed
(a 4-blade propeller: p = 4, 8, ...). The mass turns at |r_m| times the reference speed Omega
(:attr:`crankdyn.torsion.model.TorsionModel.speed_ratios`), so its angle is
phi_m = |r_m| phi + phi_0 and

    T_m(t) = sum_p Re( c_p exp(i p phi_m) ) = sum_p Re( c_p exp(i p phi_0) exp(i q phi) ),
    q = p |r_m|,

an excitation at the reference order q = p |r_m| (W. Ker Wilson, *Practical Solution of
Torsional Vibration Problems*, vol. 1, ch. 3: every geared branch is referred to one speed). A
torque T on a mass turning at |r| times the reference speed does the work of |r| T on the
reflected coordinate (virtual work: delta W = T delta phi_m = |r| T delta phi), so it enters the
reflected equations as |r| T; torques are given positive in the direction of rotation of the mass
they act on (docs/conventions.md), whatever the sense of rotation beyond a reversing mesh.

Sources (:class:`HarmonicSource`):

- a **propeller** with z blades: harmonic torques at the blade orders p = k z (k = 1, 2, ...),
  each given as an amplitude in N m or as a fraction of the propeller's mean torque Q(n), which
  follows the propeller law Q = Q_0 (n / n_0)^2 (the torque of a fixed-pitch propeller at a
  constant advance ratio, K_Q constant: Q = K_Q rho n^2 D^5; e.g. J. Carlton, *Marine Propellers
  and Propulsion*, 3rd ed. 2012, ch. 6), so its harmonics grow as n^2;
- an **electric machine** with p_p pole pairs: torque harmonics at the electrical harmonics h of
  the supply frequency, f = h f_e with f_e = p_p n: mechanical orders h p_p (e.g. the 6th and 12th
  harmonics of an inverter-fed machine);
- a **general source**: orders with amplitudes and phases, constant or tabulated against the
  speed of the mass (interpolated linearly, held at the table's ends).

Further engines (:class:`EngineSource`, a twin-input gearbox): an engine's cylinder torques
(:class:`crankdyn.torsion.excitation.EngineExcitation`) at the orders of its own crankshaft,
phased by its firing phase phi_0 (its crank angle when the reference engine's cylinder 1 is at
firing TDC): c_p exp(i p phi_0).

Mean torque along the line. Each source may carry a load law (mean load torque Q(n) against the
speed of its mass, opposing the rotation). The engines supply the sum: engine e carries the
share s_e / sum s of the total reflected load sum_l |r_l| Q_l, spread evenly over its cylinders'
masses. The mean twist X of the reflected model then solves the static equilibrium
K X = F (F_m = |r_m| T_m; a free model is held at its reference mass, the torques being in
balance) and every element carries the mean torque k_ref (X_a - X_b) / |r_a|, in the sense of
rotation of its first mass, positive when it transmits torque from its first mass to its second
(no gear losses). This is the torque the coupling and gear checks compare with (DIN 740-2
T_KN; gear hammering where the vibratory torque exceeds it).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from functools import reduce
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.errors import InputError
from crankdyn.results import Result, array, freeze, scalar
from crankdyn.torsion.excitation import Excitation, SourceExcitation, known_major_orders
from crankdyn.torsion.orders import Complex, fundamental_order, order_grid

if TYPE_CHECKING:
    from crankdyn.torsion.model import TorsionModel
    from crankdyn.torsion.solvers import LinearSystem

__all__ = [
    "SOURCE_KINDS",
    "EngineSource",
    "HarmonicSource",
    "LoadLaw",
    "MeanTorqueResult",
    "SourceExcitation",
    "assemble_forcing",
    "check_model_orders",
    "default_orders",
    "electric_machine",
    "engine_orders_mask",
    "forcing_notes",
    "line_major",
    "mean_torques",
    "order_sources",
    "propeller",
    "source_breakpoints",
    "source_orders",
    "synthesis_index",
    "synthesize",
    "synthesize_at",
]

from crankdyn.constants import RPM

SOURCE_KINDS = ("propeller", "machine", "source")
_ORDER_TOL = 1e-9
MAX_SYNTHESIS_INDEX = 8192
"""Largest harmonic index of the common period over which the orders are synthesised in the
time domain (module :func:`synthesis_index`)."""


# ---- load laws -----------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class LoadLaw:
    """Mean load torque against the speed of its mass (opposing the rotation).

    Q(n) = Q_0 (n / n_0)^e: e = 2 the propeller law, e = 0 constant torque, e = -1 constant
    power; or a table of Q against n (interpolated linearly, held at its ends).

    Parameters
    ----------
    torque : float or None
        Q_0 (N m), >= 0, at ``speed``.
    speed : float or None
        n_0 (rad/s) of the mass, > 0.
    exponent : float
        e (dimensionless), between -10 and 10.
    table_speed, table_torque : array_like or None
        Instead of the law: speeds (rad/s, increasing) and torques (N m, >= 0), shape (points,).

    Raises
    ------
    crankdyn.errors.InputError
        Both a law and a table, a table of mismatched, non-finite, non-increasing or negative
        values (key ``load``), a law without torque or speed, a negative torque, a speed not
        positive or an exponent out of range (keys ``torque``, ``speed``, ``exponent``).

    Examples
    --------
    The propeller law, 100 kN m at 10 rad/s:

    >>> law = LoadLaw(100e3, 10.0)
    >>> law.at([5.0, 10.0])
    array([ 25000., 100000.])
    >>> law.describe()
    'propeller law: 100 kN·m at 95.493 rpm'
    """

    torque: float | None = None
    speed: float | None = None
    exponent: float = 2.0
    table_speed: NDArray[np.float64] | None = None
    table_torque: NDArray[np.float64] | None = None

    def __post_init__(self) -> None:
        if self.table_speed is not None or self.table_torque is not None:
            if self.torque is not None:
                raise InputError("give the law or a table, not both", key="torque")
            s = np.asarray(self.table_speed, dtype=float)
            q = np.asarray(self.table_torque, dtype=float)
            if s.ndim != 1 or s.shape != q.shape or s.size < 1:
                raise InputError("the load table needs as many speeds as torques", key="load")
            if not (np.all(np.isfinite(s)) and np.all(np.isfinite(q))):
                raise InputError("the load table holds values that are not finite", key="load")
            if np.any(s <= 0.0) or np.any(np.diff(s) <= 0.0):
                raise InputError(
                    "the load table's speeds must be positive and increase", key="load"
                )
            if np.any(q < 0.0):
                raise InputError("the load table's torques must not be negative", key="load")
            object.__setattr__(self, "table_speed", freeze(s))
            object.__setattr__(self, "table_torque", freeze(q))
            return
        if self.torque is None or self.speed is None:
            raise InputError("a load law needs the torque (or power) at a speed", key="torque")
        if not (math.isfinite(self.torque) and self.torque >= 0.0):
            raise InputError(
                "the load torque must not be negative", key="torque", value=self.torque
            )
        if not (math.isfinite(self.speed) and self.speed > 0.0):
            raise InputError("the speed must be positive", key="speed", value=self.speed)
        if not math.isfinite(self.exponent) or abs(self.exponent) > 10.0:
            raise InputError("expected an exponent between -10 and 10", key="exponent")

    def at(self, speeds: ArrayLike) -> NDArray[np.float64]:
        """The mean load torque Q(n) at speeds of the mass.

        Parameters
        ----------
        speeds : array_like
            Speeds n of the mass (rad/s).

        Returns
        -------
        numpy.ndarray
            Q (N m), same shape.
        """
        n = np.asarray(speeds, dtype=float)
        if self.table_speed is not None:
            assert self.table_torque is not None  # set together (__post_init__)
            return np.interp(n, self.table_speed, self.table_torque)
        assert self.torque is not None and self.speed is not None  # a law (__post_init__)
        return self.torque * (n / self.speed) ** self.exponent

    def describe(self) -> str:
        """One line describing the law, for reports.

        Returns
        -------
        str
            The law's name, Q_0 (kN m) and n_0 (rpm), or the table's size.
        """
        if self.table_speed is not None:
            return f"tabulated load ({self.table_speed.size} points)"
        assert self.torque is not None and self.speed is not None  # a law (__post_init__)
        names = {2.0: "propeller law", 0.0: "constant torque", -1.0: "constant power"}
        law = names.get(self.exponent, f"Q ∝ n^{self.exponent:g}")
        return f"{law}: {self.torque / 1e3:.6g} kN·m at {self.speed * RPM:.6g} rpm"


# ---- harmonic sources ---------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class HarmonicSource:
    """Harmonic torques at one mass, at orders of that mass's speed (module docstring).

    Parameters
    ----------
    at : str
        The mass it acts on.
    orders : array_like
        Orders p_k of the mass's speed (dimensionless, > 0, distinct), shape (K,).
    amplitude : array_like or None
        Amplitudes (N m, >= 0): shape (K,), or (T, K) against ``speed``; or None with
        ``fraction``.
    fraction : array_like or None
        Amplitudes as fractions of the mean torque of ``load`` (dimensionless, >= 0), shape (K,).
    phase : array_like or None
        Phases (rad): T = Re(c exp(i p phi_m)), c = A exp(i psi); shape (K,) or (T, K); default 0.
    speed : array_like or None
        Speeds of the mass (rad/s, increasing) of tabulated amplitudes and phases, shape (T,).
    load : LoadLaw or None
        The mean load torque law of the mass (for ``fraction`` and the mean torque along the line).
    kind : str
        ``"propeller"``, ``"machine"`` or ``"source"``.
    name : str
        For reports (default: the kind and the mass).

    Raises
    ------
    crankdyn.errors.InputError
        No mass name (key ``at``), an unknown kind, orders not positive or not distinct (key
        ``orders``), table speeds not positive or increasing (key ``speed``), both or neither of
        amplitudes and fractions, arrays of the wrong shape or out of range (keys
        ``amplitudes``, ``fractions``, ``phases``), fractions without a load law.

    Examples
    --------
    >>> src = HarmonicSource("prop", [4.0, 8.0], amplitude=[1000.0, 200.0], phase=[0.0, np.pi])
    >>> np.round(src.coefficients([10.0]), 9)
    array([[1000.+0.j, -200.+0.j]])
    >>> src.describe()
    'source at prop: orders 4, 8 of its speed, N·m 1000, 200'
    """

    at: str
    orders: np.ndarray
    amplitude: np.ndarray | None = None
    fraction: np.ndarray | None = None
    phase: np.ndarray | None = None
    speed: np.ndarray | None = None
    load: LoadLaw | None = None
    kind: str = "source"
    name: str = ""

    def __post_init__(self) -> None:
        if not isinstance(self.at, str) or not self.at.strip():
            raise InputError("expected the name of a mass", key="at", value=self.at)
        if self.kind not in SOURCE_KINDS:
            raise InputError(f"expected one of {', '.join(SOURCE_KINDS)}", key="kind")
        p = np.atleast_1d(np.asarray(self.orders, dtype=float))
        if p.ndim != 1 or p.size == 0:
            raise InputError("expected at least one order", key="orders")
        if not np.all(np.isfinite(p)) or np.any(p <= 0.0):
            bad = p[~(np.isfinite(p) & (p > 0.0))][0]
            raise InputError("orders must be positive", key="orders", value=float(bad))
        if np.unique(np.round(p / _ORDER_TOL)).size != p.size:
            raise InputError("orders must be distinct", key="orders", value=p.tolist())
        object.__setattr__(self, "orders", freeze(p))
        rows = None
        if self.speed is not None:
            s = np.atleast_1d(np.asarray(self.speed, dtype=float))
            if s.ndim != 1 or not np.all(np.isfinite(s)) or np.any(s <= 0.0):
                raise InputError("the table's speeds must be positive", key="speed")
            if np.any(np.diff(s) <= 0.0):
                raise InputError("the table's speeds must increase strictly", key="speed")
            object.__setattr__(self, "speed", freeze(s))
            rows = s.size
        if (self.amplitude is None) == (self.fraction is None):
            raise InputError(
                "give the amplitudes (torques) or the fractions of the mean torque, one of them",
                key="amplitudes",
            )
        shape = (p.size,) if rows is None else (rows, p.size)
        if self.amplitude is not None:
            a = np.asarray(self.amplitude, dtype=float)
            if a.shape != shape:
                raise InputError(
                    f"expected {p.size} amplitudes, one per order"
                    + ("" if rows is None else f", at each of {rows} speeds"),
                    key="amplitudes",
                    value=a.tolist(),
                )
            if not np.all(np.isfinite(a)) or np.any(a < 0.0):
                raise InputError("amplitudes must be finite and >= 0", key="amplitudes")
            object.__setattr__(self, "amplitude", freeze(a))
        else:
            f = np.asarray(self.fraction, dtype=float)
            if f.shape != (p.size,):
                raise InputError(
                    f"expected {p.size} fractions, one per order", key="fractions", value=f.tolist()
                )
            if not np.all(np.isfinite(f)) or np.any(f < 0.0) or np.any(f > 10.0):
                raise InputError(
                    "fractions of the mean torque must lie between 0 and 10 (0.05 is 5 %)",
                    key="fractions",
                    value=f.tolist(),
                )
            if self.load is None:
                raise InputError(
                    "amplitudes as fractions of the mean torque need the load law (the torque "
                    "or power at a speed)",
                    key="fractions",
                )
            object.__setattr__(self, "fraction", freeze(f))
        ph = np.zeros(shape) if self.phase is None else np.asarray(self.phase, dtype=float)
        if ph.shape == (p.size,) and rows is not None:
            ph = np.broadcast_to(ph, shape)
        if ph.shape != shape or not np.all(np.isfinite(ph)):
            raise InputError(f"expected {p.size} finite phases, one per order", key="phases")
        object.__setattr__(self, "phase", freeze(ph))
        if not self.name:
            object.__setattr__(self, "name", f"{self.kind} at {self.at}")

    def mass_names(self) -> tuple[str, ...]:
        """The masses the source acts on.

        Returns
        -------
        tuple of str
            The one mass ``at``.
        """
        return (self.at,)

    def coefficients(self, speeds: ArrayLike) -> Complex:
        """Complex amplitudes c_k = A_k exp(i psi_k) at speeds of the mass: the amplitudes
        (tabulated ones interpolated linearly, held at the ends) or the fractions of the load
        law's mean torque, the phases interpolated on the unit circle (module docstring).

        Parameters
        ----------
        speeds : array_like
            Speeds of the mass (rad/s), shape (S,) or a scalar.

        Returns
        -------
        numpy.ndarray
            Complex amplitudes (N m), shape (S, K).
        """
        n = np.atleast_1d(np.asarray(speeds, dtype=float))
        phase = self.phase
        assert phase is not None  # set by __post_init__
        amp: NDArray[np.float64]
        if self.fraction is not None:
            assert self.load is not None  # required with fractions (__post_init__)
            amp = self.load.at(n)[:, None] * self.fraction[None, :]
        elif self.speed is not None:
            assert self.amplitude is not None  # amplitudes when no fractions (__post_init__)
            amp = _interp_rows(n, self.speed, self.amplitude)
        else:
            assert self.amplitude is not None  # amplitudes when no fractions (__post_init__)
            amp = np.broadcast_to(self.amplitude, (n.size, self.orders.size))
        if self.speed is not None and phase.ndim == 2:
            z = _interp_rows(n, self.speed, np.exp(1j * phase))
            unit: Complex = np.where(np.abs(z) > 0.0, z / np.where(z == 0, 1.0, np.abs(z)), 1.0)
        else:
            unit = np.exp(1j * np.broadcast_to(phase, (self.orders.size,)))[None, :]
        return amp * unit

    def describe(self) -> str:
        """One line describing the source (orders, amplitudes, load law), for reports.

        Returns
        -------
        str
            The description.
        """
        orders = ", ".join(f"{p:g}" for p in self.orders[:6]) + (
            ", ..." if self.orders.size > 6 else ""
        )
        if self.fraction is not None:
            how = "fractions " + ", ".join(f"{f:g}" for f in self.fraction[:6]) + " of Q"
        elif self.speed is not None:
            how = f"tabulated at {self.speed.size} speeds"
        else:
            assert self.amplitude is not None  # amplitudes when no fractions (__post_init__)
            how = "N·m " + ", ".join(f"{a:.4g}" for a in self.amplitude[:6])
        text = f"{self.name}: orders {orders} of its speed, {how}"
        if self.load is not None:
            text += f"; {self.load.describe()}"
        return text


def _interp_rows(x: NDArray[np.float64], xp: NDArray[np.float64], fp: np.ndarray) -> np.ndarray:
    """Linear interpolation of the rows of fp (T, K) at x (held at the ends), vectorised."""
    if xp.size == 1:
        return np.broadcast_to(fp[0], (x.size, fp.shape[1])).copy()
    i = np.clip(np.searchsorted(xp, x) - 1, 0, xp.size - 2)
    t = np.clip((x - xp[i]) / (xp[i + 1] - xp[i]), 0.0, 1.0)[:, None]
    return (1.0 - t) * fp[i] + t * fp[i + 1]


def propeller(
    at: str,
    blades: int,
    *,
    fractions: ArrayLike | None = None,
    torques: ArrayLike | None = None,
    phases: ArrayLike | None = None,
    load: LoadLaw | None = None,
    name: str = "",
) -> HarmonicSource:
    """A propeller with ``blades`` blades: harmonic torques at the blade orders k z, k = 1 ...
    (one per entry of ``fractions`` (of the mean torque) or ``torques`` (N m)); the mean torque
    from ``load`` (e.g. the propeller law LoadLaw(Q0, n0, 2), Q = K_Q rho n^2 D^5: Carlton
    2012, ch. 6; module docstring).

    Parameters
    ----------
    at : str
        The mass the propeller acts on.
    blades : int
        Number of blades z, >= 1.
    fractions : array_like or None
        Blade-order amplitudes as fractions of the mean torque Q(n) (dimensionless), shape (K,);
        needs ``load``.
    torques : array_like or None
        Blade-order amplitudes (N m), shape (K,), instead of ``fractions``.
    phases : array_like or None
        Phases (rad), shape (K,); default 0.
    load : LoadLaw or None
        The mean load torque law.
    name : str
        For reports (default: "propeller (z blades) at MASS").

    Returns
    -------
    HarmonicSource
        The source, at orders z, 2 z, ... K z of the propeller's speed.

    Raises
    ------
    crankdyn.errors.InputError
        A number of blades that is not a whole number >= 1 (key ``blades``), no amplitudes (key
        ``fractions``), or the errors of :class:`HarmonicSource`.

    Examples
    --------
    >>> prop = propeller("prop", 4, fractions=[0.05, 0.01], load=LoadLaw(100e3, 10.0))
    >>> prop.orders
    array([4., 8.])
    >>> np.abs(prop.coefficients([10.0]))
    array([[5000., 1000.]])
    """
    if isinstance(blades, bool) or not isinstance(blades, (int, np.integer)) or blades < 1:
        raise InputError("expected the number of blades (a whole number >= 1)", key="blades")
    given = fractions if fractions is not None else torques
    count = len(np.atleast_1d(given)) if given is not None else 0
    if count == 0:
        raise InputError(
            "give the blade-order amplitudes (fractions of the mean torque, or torques)",
            key="fractions",
        )
    return HarmonicSource(
        at=at,
        orders=float(blades) * np.arange(1, count + 1),
        amplitude=None if torques is None else np.atleast_1d(torques),
        fraction=None if fractions is None else np.atleast_1d(fractions),
        phase=None if phases is None else np.atleast_1d(phases),
        load=load,
        kind="propeller",
        name=name or f"propeller ({blades} blades) at {at}",
    )


def electric_machine(
    at: str,
    pole_pairs: int,
    harmonics: ArrayLike,
    *,
    fractions: ArrayLike | None = None,
    torques: ArrayLike | None = None,
    phases: ArrayLike | None = None,
    load: LoadLaw | None = None,
    name: str = "",
) -> HarmonicSource:
    """An electric machine with ``pole_pairs`` pole pairs: torque harmonics at the electrical
    harmonics h (of the supply frequency f_e = p_p n), mechanical orders h p_p (module
    docstring).

    Parameters
    ----------
    at : str
        The mass the machine acts on.
    pole_pairs : int
        Number of pole pairs p_p, >= 1.
    harmonics : array_like
        Electrical harmonics h (dimensionless, e.g. 6 and 12), shape (K,).
    fractions : array_like or None
        Amplitudes as fractions of the mean torque (dimensionless), shape (K,); needs ``load``.
    torques : array_like or None
        Amplitudes (N m), shape (K,), instead of ``fractions``.
    phases : array_like or None
        Phases (rad), shape (K,); default 0.
    load : LoadLaw or None
        The mean load torque law.
    name : str
        For reports (default: "electric machine (p_p pole pairs) at MASS").

    Returns
    -------
    HarmonicSource
        The source, at mechanical orders h p_p of the machine's speed.

    Raises
    ------
    crankdyn.errors.InputError
        A number of pole pairs that is not a whole number >= 1 (key ``pole_pairs``), or the
        errors of :class:`HarmonicSource`.

    Examples
    --------
    >>> electric_machine("gen", 2, [6, 12], torques=[300.0, 50.0]).orders
    array([12., 24.])
    """
    if (
        isinstance(pole_pairs, bool)
        or not isinstance(pole_pairs, (int, np.integer))
        or pole_pairs < 1
    ):
        raise InputError(
            "expected the number of pole pairs (a whole number >= 1)", key="pole_pairs"
        )
    h = np.atleast_1d(np.asarray(harmonics, dtype=float))
    return HarmonicSource(
        at=at,
        orders=h * pole_pairs,
        amplitude=None if torques is None else np.atleast_1d(torques),
        fraction=None if fractions is None else np.atleast_1d(fractions),
        phase=None if phases is None else np.atleast_1d(phases),
        load=load,
        kind="machine",
        name=name or f"electric machine ({pole_pairs} pole pairs) at {at}",
    )


@dataclass(frozen=True, eq=False)
class EngineSource:
    """A further engine's cylinder torques on the model's masses (module docstring).

    Parameters
    ----------
    name : str
        The engine, for reports.
    excitation : crankdyn.torsion.excitation.Excitation
        Its :class:`~crankdyn.torsion.excitation.EngineExcitation` (or a uniform excitation).
    cylinders : tuple of (int, str)
        (cylinder number, mass name) of every cylinder placed on the model.
    phase : float
        Its crank angle (rad) when the reference engine's cylinder 1 is at firing TDC.
    share : float
        Its share of the load's mean torque (relative weight, dimensionless), > 0.

    Raises
    ------
    crankdyn.errors.InputError
        No cylinder placed (key ``engine``), a phase not finite (key ``phase``) or a share
        not positive (key ``share``).

    Examples
    --------
    >>> from crankdyn.torsion.excitation import UniformExcitation
    >>> twin = EngineSource("B", UniformExcitation(1.0, [0.0, np.pi]), ((1, "b1"), (2, "b2")))
    >>> twin.mass_names()
    ('b1', 'b2')
    """

    name: str
    excitation: Excitation
    cylinders: tuple[tuple[int, str], ...]
    phase: float = 0.0
    share: float = 1.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "cylinders", tuple((int(c), str(m)) for c, m in self.cylinders))
        if not self.cylinders:
            raise InputError(f'engine "{self.name}" places no cylinder on the model', key="engine")
        if not math.isfinite(self.phase):
            raise InputError("the firing phase must be finite", key="phase", value=self.phase)
        if not (math.isfinite(self.share) and self.share > 0.0):
            raise InputError("the load share must be positive", key="share", value=self.share)

    kind = "engine"
    load = None

    def mass_names(self) -> tuple[str, ...]:
        """The masses carrying the engine's cylinders, in the order first placed.

        Returns
        -------
        tuple of str
            The mass names, each once.
        """
        return tuple(dict.fromkeys(m for _c, m in self.cylinders))

    def describe(self) -> str:
        """One line describing the engine (cylinders, firing phase, excitation), for reports.

        Returns
        -------
        str
            The description.
        """
        return (
            f"{self.name}: {len(self.cylinders)} cylinders, firing phase "
            f"{math.degrees(self.phase):.6g}°; {self.excitation.description}"
        )


# ---- orders --------------------------------------------------------------------------------------
def _fits(values: NDArray[np.float64], base: float) -> NDArray[np.bool_]:
    m = values / base
    return np.abs(m - np.round(m)) <= _ORDER_TOL * np.maximum(m, 1.0)


def engine_orders_mask(orders: ArrayLike, cycle: str) -> NDArray[np.bool_]:
    """Whether each order is a harmonic of the engine's working cycle (a multiple of 0.5 for a
    four-stroke, of 1 for a two-stroke engine;
    :func:`~crankdyn.torsion.orders.fundamental_order`).

    Parameters
    ----------
    orders : array_like
        Orders of the engine's speed (dimensionless).
    cycle : str
        ``"four-stroke"`` or ``"two-stroke"``.

    Returns
    -------
    numpy.ndarray
        True where the order is a multiple of the fundamental order (to a relative 1e-9), same
        shape.

    Examples
    --------
    >>> engine_orders_mask([0.5, 1.0, 1.25], "four-stroke")
    array([ True,  True, False])
    """
    return _fits(np.asarray(orders, dtype=float), fundamental_order(cycle))


def source_orders(
    model: TorsionModel,
) -> list[tuple[HarmonicSource | EngineSource, NDArray[np.float64]]]:
    """(source, its orders in the reference speed q = p |r_m|) of every harmonic source of the
    model (for engine sources: the first 24 harmonics of their cycle; module docstring, Ker
    Wilson vol. 1 ch. 3).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The model (its ``sources`` and speed ratios).

    Returns
    -------
    list of (HarmonicSource or EngineSource, numpy.ndarray)
        Every source with its orders of the reference speed (dimensionless), shape (K,).
    """
    out: list[tuple[HarmonicSource | EngineSource, np.ndarray]] = []
    for source in model.sources:
        r = float(model.speed_ratios[model.index(source.mass_names()[0])])
        if isinstance(source, EngineSource):
            base = fundamental_order(source.excitation.cycle)
            out.append((source, base * np.arange(1, 25) * r))
        else:
            out.append((source, source.orders * r))
    return out


def check_model_orders(
    model: TorsionModel,
    excitation: Excitation | None,
    orders: ArrayLike,
    *,
    key: str = "orders",
) -> NDArray[np.float64]:
    """Validate orders (of the reference speed) for a model: finite, positive, distinct, and
    each either a harmonic of the engine's cycle (when cylinders excite the model) or an order
    at which one of the model's sources acts (q = p |r_m|, module docstring).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The model (its sources).
    excitation : Excitation or None
        The excitation of the cylinders on the masses
        (:func:`~crankdyn.torsion.excitation.excitation_for`); None for none.
    orders : array_like
        Orders of the reference speed (dimensionless), shape (Q,).
    key : str
        The input key named in an error message.

    Returns
    -------
    numpy.ndarray
        The orders as floats, engine orders snapped to their exact multiples; shape (Q,).

    Raises
    ------
    crankdyn.errors.InputError
        No order, an order not positive, excited by nothing or given twice (names ``key`` and
        the order, listing the sources' orders); a model with no excitation at all (names the
        model file).
    """
    q = np.atleast_1d(np.asarray(orders, dtype=float))
    if q.ndim != 1 or q.size == 0:
        raise InputError("expected at least one order", key=key)
    if not np.all(np.isfinite(q)) or np.any(q <= 0.0):
        bad = q[~(np.isfinite(q) & (q > 0.0))][0]
        raise InputError("orders must be positive", key=key, value=float(bad))
    engine = excitation is not None and excitation.cylinder_count > 0
    cycle = excitation.cycle if excitation is not None else "four-stroke"
    ok = engine_orders_mask(q, cycle) if engine else np.zeros(q.size, dtype=bool)
    if engine:  # keep the engine's orders on their exact multiples
        base = fundamental_order(cycle)
        q = np.where(ok, np.round(q / base) * base, q)
    for source, qs in source_orders(model):
        if isinstance(source, EngineSource):
            r = qs[0] / fundamental_order_of(source)
            ok |= engine_orders_mask(q / r, source.excitation.cycle)
            continue
        near = np.abs(q[:, None] - qs[None, :]) <= _ORDER_TOL * np.maximum(qs[None, :], 1.0)
        ok |= np.any(near, axis=1)
    if not np.all(ok):
        bad = float(q[~ok][0])
        others = []
        for source, qs in source_orders(model):
            if not isinstance(source, EngineSource):
                listed = ", ".join(f"{v:.6g}" for v in qs[:4]) + (", ..." if qs.size > 4 else "")
                others.append(f"the {source.name} ({listed})")
        if not engine and not others:
            raise InputError(
                "the model has no excitation: no mass carries a cylinder and there is no "
                "excitation source",
                file=model.source,
            )
        if engine:
            base = fundamental_order(cycle)
            if others:
                text = (
                    f"order {bad:g} does not fit the {cycle} cycle (multiples of {base:g}) and "
                    f"is no order of {'; '.join(others)}"
                )
            else:
                text = (
                    f"order {bad:g} does not fit the {cycle} cycle: orders are multiples of "
                    f"{base:g}"
                )
        else:
            text = f"order {bad:g} is no order of {'; '.join(others)}"
        raise InputError(text, key=key, value=bad)
    scaled = np.round(q / _ORDER_TOL)
    if np.unique(scaled).size != q.size:
        raise InputError("orders must be distinct", key=key)
    return q


def fundamental_order_of(source: EngineSource) -> float:
    """Fundamental order of a further engine's cycle, in its own speed.

    Parameters
    ----------
    source : EngineSource
        The engine.

    Returns
    -------
    float
        0.5 for a four-stroke, 1 for a two-stroke engine (dimensionless).
    """
    return fundamental_order(source.excitation.cycle)


def default_orders(
    model: TorsionModel, cycle: str, *, engine: bool = True, last: float = 12.0
) -> NDArray[np.float64]:
    """The default orders of a model (reference speed), ascending: the engine's harmonics up to
    ``last`` (when cylinders excite it) and every order of its harmonic sources (engine sources:
    their harmonics up to ``last`` in their own speed).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The model (its sources).
    cycle : str
        The engine's cycle, ``"four-stroke"`` or ``"two-stroke"``.
    engine : bool
        Whether cylinders on the masses excite the model.
    last : float
        Highest engine order (dimensionless).

    Returns
    -------
    numpy.ndarray
        The distinct orders (dimensionless), ascending.

    Raises
    ------
    crankdyn.errors.InputError
        A model with no excitation (no engine, no source; names the model file).
    """
    parts = []
    if engine:
        base = fundamental_order(cycle)
        parts.append(order_grid(base, last, base, cycle))
    for source, qs in source_orders(model):
        if isinstance(source, EngineSource):
            base = fundamental_order_of(source)
            r = qs[0] / base
            parts.append(base * np.arange(1, math.floor(last / base + 1e-9) + 1) * r)
        else:
            parts.append(qs)
    if not parts:
        raise InputError(
            "the model has no excitation: no mass carries a cylinder and there is no excitation "
            "source",
            file=model.source,
        )
    q = np.sort(np.concatenate(parts))
    keep = np.concatenate([[True], np.diff(q) > _ORDER_TOL * np.maximum(q[1:], 1.0)])
    return q[keep]


def order_sources(
    model: TorsionModel, excitation: Excitation | None, orders: ArrayLike
) -> list[str]:
    """What excites each order (reference speed): ``"engine"`` for the harmonics of the cycle of
    the cylinders on the masses, and the names of the sources acting at it, joined by ", ".

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The model (its sources).
    excitation : Excitation or None
        The excitation of the cylinders on the masses; None for none.
    orders : array_like
        Orders of the reference speed (dimensionless), shape (Q,).

    Returns
    -------
    list of str
        One entry per order (empty when nothing acts at it).
    """
    q = np.asarray(orders, dtype=float)
    names: list[list[str]] = [[] for _ in range(q.size)]
    if excitation is not None and excitation.cylinder_count > 0:
        for j in np.flatnonzero(engine_orders_mask(q, excitation.cycle)):
            names[j].append("engine")
    for source, qs in source_orders(model):
        if isinstance(source, EngineSource):
            hit = engine_orders_mask(
                q / (qs[0] / fundamental_order_of(source)), source.excitation.cycle
            )
        else:
            hit = np.any(
                np.abs(q[:, None] - qs[None, :]) <= _ORDER_TOL * np.maximum(qs[None, :], 1.0),
                axis=1,
            )
        for j in np.flatnonzero(hit):
            names[j].append(source.name)
    return [", ".join(n) for n in names]


def line_major(excitation: Excitation, orders: ArrayLike) -> NDArray[np.bool_] | None:
    """Major-order marking (:func:`~crankdyn.torsion.orders.major_orders`) restricted to the
    engine's own orders: an order that is not a harmonic of the cycle is not an engine order,
    so never major (a propeller's blade orders, a machine's harmonics).

    Parameters
    ----------
    excitation : Excitation
        The excitation of the cylinders on the masses.
    orders : array_like
        Orders of the reference speed (dimensionless), shape (Q,).

    Returns
    -------
    numpy.ndarray or None
        Whether each order is major, shape (Q,); None when an engine order is among the orders
        but the excitation does not know its cylinders' phases (a model without firing angles:
        :data:`~crankdyn.torsion.excitation.MAJOR_UNDETERMINED`); all False for a model
        without cylinders.

    Examples
    --------
    >>> from crankdyn.torsion.excitation import UniformExcitation
    >>> line_major(UniformExcitation(1.0, np.radians([0.0, 360.0])), [1.0, 1.5, 4.0, 4.2])
    array([ True, False,  True, False])
    """
    q = np.asarray(orders, dtype=float)
    if excitation.cylinder_count == 0:
        return np.zeros(q.size, dtype=bool)
    fits = engine_orders_mask(q, excitation.cycle)
    out = np.zeros(q.size, dtype=bool)
    if np.any(fits):
        major = known_major_orders(excitation, q[fits])
        if major is None:
            return None
        out[fits] = major
    return out


def source_breakpoints(model: TorsionModel) -> NDArray[np.float64]:
    """Reference speeds where a source's excitation is not smooth in the speed: the points of
    its tables (amplitudes and phases against the speed, a tabulated load law, a further
    engine's load curve or traces), each converted from the speed of its mass (n / |r|). A
    resolved forced response samples them (:mod:`crankdyn.torsion.resolve`).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The model (its sources and speed ratios).

    Returns
    -------
    numpy.ndarray
        The speeds (rad/s, reference speed), unsorted, possibly repeated; empty without tables.
    """
    points = []
    for source in model.sources:
        r = float(model.speed_ratios[model.index(source.mass_names()[0])])
        if isinstance(source, EngineSource):
            found = getattr(source.excitation, "breakpoints", None)
            if found is not None:
                points.append(np.asarray(found(), dtype=float) / r)
            continue
        if source.speed is not None:
            points.append(np.asarray(source.speed, dtype=float) / r)
        load = source.load
        if load is not None and load.table_speed is not None:
            points.append(np.asarray(load.table_speed, dtype=float) / r)
    return np.concatenate(points) if points else np.zeros(0)


# ---- time-domain synthesis over a common period --------------------------------------------------
def _fraction(value: float) -> Fraction | None:
    f = Fraction(value).limit_denominator(100_000)
    return f if abs(float(f) - value) <= _ORDER_TOL * max(abs(value), 1.0) else None


def synthesis_index(orders: ArrayLike, cycle: str) -> NDArray[np.int_] | None:
    """Integer harmonic indices m_k of the orders over their common period: q_k = m_k b with b
    the largest order dividing every q_k and the cycle's fundamental order (0.5 or 1), so that
    x(phi) = sum_k Re(c_k exp(i m_k phi)) over phi = b theta in [0, 2 pi) covers every
    combination of phases. For the engine's orders alone b is the fundamental order and m_k the
    usual index.

    Parameters
    ----------
    orders : array_like
        Orders of the reference speed (dimensionless), shape (K,).
    cycle : str
        The engine's cycle, ``"four-stroke"`` or ``"two-stroke"``.

    Returns
    -------
    numpy.ndarray or None
        The indices m_k, shape (K,); None when the orders have no common period with m_k up to
        :data:`MAX_SYNTHESIS_INDEX` (then the synthesis is bounded by the sum of the
        amplitudes, :func:`synthesize`).

    Examples
    --------
    >>> synthesis_index([0.5, 1.0, 3.0], "four-stroke")
    array([1, 2, 6])
    >>> synthesis_index([1.0, 4.0 / 3.0], "two-stroke")
    array([3, 4])
    >>> print(synthesis_index([1.0, np.sqrt(2.0)], "two-stroke"))
    None
    """
    q = np.asarray(orders, dtype=float)
    base = fundamental_order(cycle)
    if np.all(_fits(q, base)):
        return np.round(q / base).astype(int)
    maybe = [_fraction(v) for v in q.tolist()] + [Fraction(base).limit_denominator(10)]
    fractions = [f for f in maybe if f is not None]
    if len(fractions) != len(maybe):
        return None
    num = reduce(math.gcd, (f.numerator for f in fractions))
    den = reduce(lambda a, b: a * b // math.gcd(a, b), (f.denominator for f in fractions))
    b = Fraction(num, den)
    index = [f / b for f in fractions[:-1]]
    if any(m.denominator != 1 for m in index) or max(index) > MAX_SYNTHESIS_INDEX:
        return None
    return np.array([int(m) for m in index], dtype=int)


def synthesize(
    coefficients: ArrayLike, orders: ArrayLike, cycle: str
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(max, min) over time of x = sum_k Re(c_k exp(i q_k theta)) for complex coefficients: over
    the orders' common period (:func:`synthesis_index`,
    :func:`crankdyn.torsion.synthesis.half_range`), or +/- the sum of |c_k| when they have none
    (the supremum of a sum of incommensurate harmonics, which comes arbitrarily close to every
    phase combination: Kronecker's theorem).

    Parameters
    ----------
    coefficients : array_like
        Complex amplitudes c_k (any unit, e.g. N m or rad), shape (..., K).
    orders : array_like
        Their orders q_k of the reference speed (dimensionless), shape (K,).
    cycle : str
        The engine's cycle, ``"four-stroke"`` or ``"two-stroke"``.

    Returns
    -------
    max, min : numpy.ndarray
        Largest and smallest value of x over time (unit of the coefficients), shape (...).

    Examples
    --------
    >>> top, low = synthesize([[1.0 + 0j, 1.0 + 0j]], [1.0, 2.0], "two-stroke")
    >>> round(float(top[0]), 9), round(float(low[0]), 9)
    (2.0, -1.125)
    """
    return synthesize_at(coefficients, synthesis_index(orders, cycle))


def synthesize_at(
    coefficients: ArrayLike, index: ArrayLike | None
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """:func:`synthesize` with the harmonic indices of :func:`synthesis_index` computed once.

    Parameters
    ----------
    coefficients : array_like
        Complex amplitudes c_k (any unit), shape (..., K).
    index : array_like or None
        The integer indices m_k of :func:`synthesis_index`, shape (K,); None: the orders have
        no common period, the bound +/- sum |c_k|.

    Returns
    -------
    max, min : numpy.ndarray
        Largest and smallest value over time (unit of the coefficients), shape (...).

    Examples
    --------
    >>> top, low = synthesize_at([[3.0 + 0j, 1.0 + 0j]], None)
    >>> top, low
    (array([4.]), array([-4.]))
    """
    from crankdyn.torsion.synthesis import half_range

    if index is not None:
        return half_range(coefficients, index)
    bound = np.sum(np.abs(np.asarray(coefficients)), axis=-1)
    return bound, -bound


# ---- forcing ------------------------------------------------------------------------------------
def _incidence(
    model: TorsionModel, system: LinearSystem, owners: dict[int, str], count: int
) -> NDArray[np.float64]:
    """(count, n) incidence: cylinder c (1-based) on mass ``owners[c]`` -> its dof, |r|."""
    out = np.zeros((count, system.size))
    ratios = model.speed_ratios
    for c, name in owners.items():
        i = model.index(name)
        out[c - 1, int(system.mass_dof[i])] = float(ratios[i])
    return out


def assemble_forcing(
    model: TorsionModel,
    system: LinearSystem,
    excitation: Excitation,
    speeds: ArrayLike,
    orders: ArrayLike,
) -> tuple[Complex, list[str]]:
    """The harmonic torques on the degrees of freedom of ``system`` (the model's linear system
    with its dampers), from the cylinders on the masses (``excitation``) and every source of the
    model, each reflected to the reference speed as |r| T (virtual work; Ker Wilson vol. 1
    ch. 3; module docstring).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The torsional model.
    system : crankdyn.torsion.solvers.LinearSystem
        :func:`crankdyn.torsion.solvers.linear_system` of the model.
    excitation : Excitation
        The engine excitation of the cylinders on the masses (or a uniform or source-only one).
    speeds : array_like
        Reference speeds (rad/s), shape (S,).
    orders : array_like
        Orders of the reference speed (dimensionless), shape (Q,), checked by
        :func:`check_model_orders`.

    Returns
    -------
    forcing : numpy.ndarray
        Complex harmonic torques (N m, reflected), shape (S, Q, dofs).
    notes : list of str
        The notes of :func:`forcing_notes`.

    Raises
    ------
    crankdyn.errors.InputError
        The errors of :func:`forcing_notes`.
    """
    speeds = np.asarray(speeds, dtype=float)
    orders = np.asarray(orders, dtype=float)
    forcing = np.zeros((speeds.size, orders.size, system.size), dtype=complex)
    notes = list(forcing_notes(model, excitation, speeds, orders))
    count = excitation.cylinder_count
    if model.cylinder_dofs and count:
        owners = {c: m.name for m in model.masses for c in m.cylinders}
        fit = engine_orders_mask(orders, excitation.cycle)
        if np.any(fit):
            incidence = _incidence(model, system, owners, count)
            forcing[:, fit, :] += excitation.harmonics(speeds, orders[fit]) @ incidence
    for source in model.sources:
        if isinstance(source, EngineSource):
            _add_engine(forcing, model, system, source, speeds, orders)
        else:
            _add_harmonic(forcing, model, system, source, speeds, orders)
    return forcing, notes


def forcing_notes(
    model: TorsionModel, excitation: Excitation, speeds: ArrayLike, orders: ArrayLike
) -> tuple[str, ...]:
    """Check the excitation points of a model (cylinders on its masses, sources) against the
    excitation, and give the notes of :func:`assemble_forcing` without assembling the forcing:
    the excitation's own notes (e.g. speeds beyond a load curve), cylinders on no mass, further
    engines' notes, and a synthesis bounded by the sum of the amplitudes.

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The torsional model.
    excitation : Excitation
        The excitation of the cylinders on the masses.
    speeds : array_like
        Reference speeds (rad/s), shape (S,).
    orders : array_like
        Orders of the reference speed (dimensionless), shape (Q,).

    Returns
    -------
    tuple of str
        The notes.

    Raises
    ------
    crankdyn.errors.InputError
        A model with no excitation point, or a mass carrying a cylinder the excitation does not
        have (key ``cylinders``; both name the model file); a further engine whose masses turn
        at different speeds (key ``engine``).
    """
    speeds = np.asarray(speeds, dtype=float)
    notes: list[str] = []
    count = excitation.cylinder_count
    cyl = model.cylinder_dofs
    if not cyl and not model.sources:
        raise InputError(
            "the model has no excitation point: no mass carries a cylinder (give cylinders = "
            "[...] on the crank-throw masses)",
            file=model.source,
        )
    if cyl and count:
        beyond = [c for c in cyl if c > count]
        if beyond:
            raise InputError(
                f"a mass carries cylinder {beyond[0]} but the excitation has {count} cylinders",
                file=model.source,
                key="cylinders",
            )
        notes.extend(excitation.notes(speeds))
        unplaced = [c for c in range(1, count + 1) if c not in cyl]
        if unplaced:
            notes.append(
                f"cylinder(s) {', '.join(map(str, unplaced))} act on no mass of the model and "
                "are left out"
            )
    for source in model.sources:
        if isinstance(source, EngineSource):
            r = _engine_ratio(model, source)
            notes.extend(f"{source.name}: {n}" for n in source.excitation.notes(r * speeds))
    if synthesis_index(orders, excitation.cycle) is None:
        notes.append(
            "the orders have no common period short enough to synthesise: the synthesised "
            "values are the sums of the order amplitudes (their supremum)"
        )
    return tuple(notes)


def _add_harmonic(
    forcing: Complex,
    model: TorsionModel,
    system: LinearSystem,
    source: HarmonicSource,
    speeds: NDArray[np.float64],
    orders: NDArray[np.float64],
) -> None:
    i = model.index(source.at)
    r = float(model.speed_ratios[i])
    p = orders / r
    near = np.abs(p[:, None] - source.orders[None, :]) <= _ORDER_TOL * np.maximum(
        source.orders[None, :], 1.0
    )
    hit = np.flatnonzero(np.any(near, axis=1))
    if hit.size == 0:
        return
    k = np.argmax(near[hit], axis=1)
    c = source.coefficients(r * speeds)  # (S, K)
    forcing[:, hit, int(system.mass_dof[i])] += r * c[:, k]


def _engine_ratio(model: TorsionModel, source: EngineSource) -> float:
    """The speed ratio |r| of a further engine's masses (one: its crankshaft has no gear)."""
    names = source.mass_names()
    ratios = {float(model.speed_ratios[model.index(n)]) for n in names}
    if max(ratios) - min(ratios) > 1e-9 * max(ratios):
        raise InputError(
            f'the masses of engine "{source.name}" turn at different speeds: its crankshaft '
            "must not contain a gear",
            key="engine",
            value=source.name,
        )
    return ratios.pop()


def _add_engine(
    forcing: Complex,
    model: TorsionModel,
    system: LinearSystem,
    source: EngineSource,
    speeds: NDArray[np.float64],
    orders: NDArray[np.float64],
) -> None:
    ex = source.excitation
    r = _engine_ratio(model, source)
    p = orders / r
    fit = engine_orders_mask(p, ex.cycle)
    if not np.any(fit):
        return
    owners = dict(source.cylinders)
    count = ex.cylinder_count
    incidence = _incidence(model, system, owners, count)
    h = ex.harmonics(r * speeds, p[fit])  # (S, Qf, Z)
    h = h * np.exp(1j * p[fit] * source.phase)[None, :, None]
    forcing[:, fit, :] += h @ incidence


# ---- mean torque along the line ------------------------------------------------------------------
@dataclass(frozen=True)
class MeanTorqueResult(Result):
    """Mean torque of every element (shaft, coupling, elastic mesh) against the speed, from the
    load laws (:func:`mean_torques`; module docstring): positive when the element transmits
    torque from its first mass to its second, in the sense of rotation of its first mass."""

    title = "Mean torque along the line"
    speed: NDArray[np.float64] = array("speed_rpm", "Speed", "rpm", RPM)
    shafts: tuple[tuple[str, str], ...] = scalar("shafts", "Shafts", "")
    mean_torque: NDArray[np.float64] = array("mean_torque_Nm", "Mean torque (speed x shaft)", "N·m")
    load_torque: NDArray[np.float64] = array(
        "load_torque_Nm", "Mean load torque on every mass (speed x mass)", "N·m"
    )
    masses: tuple[str, ...] = scalar("masses", "Masses", "")
    loads: tuple[str, ...] = scalar("loads", "Load laws", "")

    def columns(self) -> dict[str, np.ndarray]:
        """The speed and the mean torque of every element, as columns in export units.

        Returns
        -------
        dict of str to numpy.ndarray
            ``speed_rpm`` (rpm) and ``mean_torque_Nm.A - B`` (N m) for the element between
            masses A and B.
        """
        out = {"speed_rpm": np.asarray(self.speed) * RPM}
        for s, (a, b) in enumerate(self.shafts):
            out[f"mean_torque_Nm.{a} - {b}"] = self.mean_torque[:, s]
        return out

    def column_labels(self) -> dict[str, tuple[str, str]]:
        """Label and unit of every column of :meth:`columns`.

        Returns
        -------
        dict of str to (str, str)
            {column key: (label, unit)}.
        """
        out = {"speed_rpm": ("Speed", "rpm")}
        for a, b in self.shafts:
            out[f"mean_torque_Nm.{a} - {b}"] = (f"Mean torque {a} - {b}", "N·m")
        return out


def mean_torques(model: TorsionModel, speeds: ArrayLike) -> MeanTorqueResult:
    """Mean torque of every element from the sources' load laws: the engines share the total
    reflected load, and the static equilibrium K X = F of the reflected model gives every
    element's torque k (X_a - X_b) / |r_a| (module docstring).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The model; its sources carry the load laws.
    speeds : array_like
        Reference speeds (rad/s), shape (S,) or a scalar.

    Returns
    -------
    MeanTorqueResult
        The mean torque of every element (N m) and the load on every mass (N m) at every speed.

    Raises
    ------
    crankdyn.errors.InputError
        A model with no load law, or with loads but no engine to drive them (names the model
        file).
    """
    speeds = np.atleast_1d(np.asarray(speeds, dtype=float))
    ratios = model.speed_ratios
    n_m = model.mass_count
    external = np.zeros((speeds.size, n_m))  # own-sense mean torque on every mass
    loads = []
    for source in model.sources:
        if not isinstance(source, HarmonicSource) or source.load is None:
            continue  # an engine carries no load law
        i = model.index(source.at)
        external[:, i] -= source.load.at(ratios[i] * speeds)
        loads.append(f"{source.name}: {source.load.describe()}")
    if not loads:
        raise InputError(
            "the model has no load law: give the propeller's (or machine's) power or torque at "
            "a speed to have the mean torque along the line",
            file=model.source,
        )
    total = -np.sum(external * ratios[None, :], axis=1)  # reflected total load (N m at ref.)
    drivers = []  # (share, masses)
    primary = [m.name for m in model.masses if m.cylinders]
    if primary:
        drivers.append((1.0, primary))
    for source in model.sources:
        if isinstance(source, EngineSource):
            drivers.append((source.share, list(source.mass_names())))
    if not drivers:
        raise InputError(
            "the model's loads have no engine to drive them: no mass carries a cylinder",
            file=model.source,
        )
    weight = sum(w for w, _ in drivers)
    for w, names in drivers:
        for name in names:
            i = model.index(name)
            external[:, i] += total * (w / weight) / len(names) / ratios[i]
    # static equilibrium of the reflected model: K X = F, held at the reference dof
    forcing = np.zeros((speeds.size, model.dof_count))
    np.add.at(forcing.T, model.mass_dof, (external * ratios[None, :]).T)
    x = np.zeros_like(forcing)
    factor = model.static_factor  # K factorised once per model (every speed, every call)
    if factor is not None:
        import scipy.linalg

        keep, lu = factor
        if np.any(np.diag(lu[0]) == 0.0):
            raise np.linalg.LinAlgError("Singular matrix")  # as numpy.linalg.solve
        x[:, keep] = scipy.linalg.lu_solve(lu, forcing[:, keep].T, check_finite=False).T
    ends = model.shaft_dofs
    xa = np.where(ends[:, 0] >= 0, x[:, np.maximum(ends[:, 0], 0)], 0.0)
    xb = np.where(ends[:, 1] >= 0, x[:, np.maximum(ends[:, 1], 0)], 0.0)
    k_ref = model._shaft_values()[0]
    index = [
        model.index(b[0] if b[0] != "ground" else b[1]) for b in (s.between for s in model.shafts)
    ]
    r_a = ratios[np.array(index, dtype=int)] if index else np.zeros(0)
    torque = k_ref * (xa - xb) / r_a if index else np.zeros((speeds.size, 0))
    return MeanTorqueResult(
        speed=freeze(speeds),
        shafts=tuple((s.between[0], s.between[1]) for s in model.shafts),
        mean_torque=freeze(torque),
        load_torque=freeze(-np.minimum(external, 0.0)),
        masses=model.mass_names,
        loads=tuple(loads),
    )
