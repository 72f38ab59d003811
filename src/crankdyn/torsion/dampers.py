"""Torsional vibration dampers: the damper as part of the system, and its design (domain and
analysis).

A damper is a seismic ring of inertia J_d joined to a hub mass of the shaft line (the hub's own
inertia belongs to that mass) by

- a viscous fluid film only: the untuned viscous (Houdaille, Lanchester) damper, torque
  c (theta_hub - theta_ring)' between ring and hub;
- a rubber element: the tuned (rubber) damper, stiffness k_d, with viscous damping c_d and/or a
  loss factor eta_d (seed 003, the V6 engine's viscous-rubber damper, Kd and Cd; seed 003
  "扭转振动的消减措施" and "减振器的设计").

Design by Den Hartog (J. P. Den Hartog, *Mechanical Vibrations*, 4th ed., McGraw-Hill 1956,
sections 3.9-3.10, the damped vibration absorber and the untuned viscous damper), for the mode
r to be damped. The shaft line is reduced to the single-degree-of-freedom system that has that
mode's frequency and energy as seen at the hub: with the mode shape phi scaled to phi_hub = 1,

    J_e = sum_i J_i phi_i^2,    k_e = omega_r^2 J_e,    mass ratio mu = J_d / J_e.

- Tuned damper, optimum tuning and damping (the two fixed points of the response curve at
  equal height, the curve horizontal at them)::

      f_opt = omega_d / omega_r = 1 / (1 + mu),   omega_d = sqrt(k_d / J_d),
      (c / c_c)_opt = sqrt(3 mu / (8 (1 + mu)^3)),   c_c = 2 J_d omega_r,

  and the largest dynamic magnification at the hub is sqrt(1 + 2/mu).
- Untuned viscous damper (k_d = 0): all response curves pass through one fixed point, at the
  frequency ratio sqrt(2/(2 + mu)) with magnification 1 + 2/mu; the optimum damping makes the
  curve horizontal there::

      (c / c_c)_opt = 1 / sqrt(2 (1 + mu)(2 + mu)),   c_c = 2 J_d omega_r.

The damper's mean power dissipation at a harmonic twist of amplitude Delta (ring relative to
hub) at frequency omega is P = (1/2) omega (omega c + eta k_d) |Delta|^2 (W), summed over the
orders (the orders are distinct frequencies, so their powers add).

Multi-stage dampers and the resonances they add (seed 003, "装多级扭转减振器的发动机曲轴系统扭振
分析"): a multi-stage rubber damper is several rings, each on its own rubber element, on one hub
(the model's dampers with the same ``at``: they act in parallel on the hub; a ring mounted on
another ring is not modelled). Each tuned stage adds a degree of freedom and so a natural
mode; the seed finds that dampers chosen to minimise the resonance peaks under single harmonic
excitations do control the first resonance of the crankshaft, but "cause resonances at other
engine speeds (in essence, the damper's own natural vibration excited)". :func:`damper_modes`
reports every natural mode of the undamped system with its tuned rings (as
:func:`crankdyn.torsion.campbell.with_dampers` builds it) with the share of its kinetic energy
held by the rings, sum_rings J phi^2 / sum J phi^2 (phi the mode shape, J the reflected
inertias); a mode whose rings hold more than half of it is a damper mode, and its critical
speeds n_c = omega_r / q inside the operating range are the resonances the dampers add. For an
undamped main mass J on k with rings J_i on k_i at it, the natural frequencies are the roots in
lambda = omega^2 of (k + sum k_i - lambda J) prod (k_i - lambda J_i) - sum_i k_i^2 prod_{j != i}
(k_j - lambda J_j) = 0 (Den Hartog 1956, sec. 3.2, the undamped absorber extended to several;
tested).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.constants import RPM
from crankdyn.crank.geometry import check_finite, check_positive
from crankdyn.errors import InputError
from crankdyn.results import Result, column, freeze, scalar

if TYPE_CHECKING:
    from crankdyn.torsion.campbell import CriticalSpeed
    from crankdyn.torsion.excitation import Excitation
    from crankdyn.torsion.modal import ModalResult
    from crankdyn.torsion.model import TorsionModel

__all__ = [
    "DAMPER_MODE_SHARE",
    "Damper",
    "DamperDesign",
    "DamperModes",
    "damper_modes",
    "design_damper",
    "equivalent_single_mass",
    "optimum_tuned",
    "optimum_viscous",
]

HZ = 1.0 / (2.0 * math.pi)
DAMPER_MODE_SHARE = 0.5
"""A mode is a damper mode when its tuned rings hold more than this share of its kinetic
energy (module docstring)."""


@dataclass(frozen=True)
class Damper:
    """A torsional vibration damper: a ring joined to a hub mass (module docstring).

    Parameters
    ----------
    name : str
        Name of the ring in outputs (unique among the masses).
    at : str
        The hub: the mass the damper is mounted on.
    inertia : float
        Ring inertia J_d (kg m^2), > 0.
    stiffness : float
        Stiffness of the rubber element k_d (N m/rad), >= 0; 0 for a viscous damper.
    damping : float
        Viscous damping between ring and hub c_d (N m s/rad), >= 0.
    loss_factor : float
        Loss factor of the rubber element eta_d (dimensionless), >= 0.
    permissible_power : float or None
        The damper maker's permissible heat load (W, mean dissipated power), > 0, or None; kept
        for the TVC's damper check (:mod:`crankdyn.tvc`).
    limit_source : str or None
        Where the permissible power comes from (the maker's document), for reports.

    Raises
    ------
    InputError
        Naming the key and value: an empty ``name`` or ``at``, an inertia that is not positive,
        a negative or non-finite stiffness, damping or loss factor, a permissible power that
        is not positive, neither damping nor stiffness (key ``damping``), or a loss factor
        without a stiffness.

    Examples
    --------
    >>> ring = Damper("ring", "pulley", 0.1, stiffness=1e4, damping=2.0, loss_factor=0.1)
    >>> ring.kind, Damper("visc", "pulley", 0.2, damping=30.0).kind
    ('tuned', 'viscous')
    """

    name: str
    at: str
    inertia: float
    stiffness: float = 0.0
    damping: float = 0.0
    loss_factor: float = 0.0
    permissible_power: float | None = None
    limit_source: str | None = None

    def __post_init__(self) -> None:
        for key in ("name", "at"):
            value = getattr(self, key)
            if not isinstance(value, str) or not value.strip():
                raise InputError("expected a non-empty name", key=key, value=value)
        object.__setattr__(
            self, "inertia", check_positive("inertia", self.inertia, "the ring's inertia")
        )
        for key in ("stiffness", "damping", "loss_factor"):
            v = check_finite(key, getattr(self, key))
            if v < 0.0:
                raise InputError("must not be negative", key=key, value=getattr(self, key))
            object.__setattr__(self, key, v)
        if self.permissible_power is not None:
            object.__setattr__(
                self,
                "permissible_power",
                check_positive("permissible_power", self.permissible_power, "the power"),
            )
        if self.stiffness == 0.0 and self.damping == 0.0:
            raise InputError(
                "a damper needs damping (viscous) or a stiffness (tuned rubber damper); with "
                "neither the ring is not connected",
                key="damping",
            )
        if self.stiffness == 0.0 and self.loss_factor > 0.0:
            raise InputError(
                "a loss factor needs the rubber's stiffness",
                key="loss_factor",
                value=self.loss_factor,
            )

    @property
    def kind(self) -> str:
        """``"viscous"`` (no stiffness) or ``"tuned"``."""
        return "viscous" if self.stiffness == 0.0 else "tuned"

    def complex_stiffness(self, omega: ArrayLike) -> NDArray[np.complexfloating]:
        """Complex stiffness k_d + i (omega c_d + eta_d k_d) between ring and hub.

        Seed 003 (the V6 engine's viscous-rubber damper, Kd and Cd); the loss factor as
        hysteretic damping, exact in the frequency domain (module docstring).

        Parameters
        ----------
        omega : float or array_like
            Vibration frequencies (rad/s).

        Returns
        -------
        numpy.ndarray
            The complex stiffness (N m/rad), of the shape of ``omega``.

        Examples
        --------
        >>> ring = Damper("ring", "pulley", 0.1, stiffness=1e4, damping=2.0, loss_factor=0.1)
        >>> complex(ring.complex_stiffness(100.0))  # 1e4 + i (100 x 2 + 0.1 x 1e4)
        (10000+1200j)
        """
        w = np.asarray(omega, dtype=float)
        return self.stiffness + 1j * (w * self.damping + self.loss_factor * self.stiffness)

    def power(self, omega: ArrayLike, twist: ArrayLike) -> NDArray[np.float64]:
        """Mean power dissipated at a harmonic twist, (1/2) omega (omega c + eta k) |twist|^2.

        The work of the damping torque over a cycle, pi (omega c + eta k) |twist|^2, times
        omega / (2 pi) cycles per second (module docstring).

        Parameters
        ----------
        omega : float or array_like
            Vibration frequencies (rad/s).
        twist : float or array_like
            Amplitudes of the ring's twist relative to the hub (rad, complex or real),
            broadcast against ``omega``.

        Returns
        -------
        numpy.ndarray
            The mean dissipated power (W).

        Examples
        --------
        >>> ring = Damper("ring", "pulley", 0.1, stiffness=1e4, damping=2.0, loss_factor=0.1)
        >>> float(ring.power(100.0, 0.01))  # 0.5 x 100 x 1200 x 1e-4
        6.0
        """
        w = np.asarray(omega, dtype=float)
        return 0.5 * w * (w * self.damping + self.loss_factor * self.stiffness) * np.abs(twist) ** 2


# ---- design -------------------------------------------------------------------------------------
def optimum_tuned(mass_ratio: float) -> tuple[float, float, float]:
    """Den Hartog's optimum tuned absorber for a mass ratio mu.

    Den Hartog (1956), sec. 3.9 (the two fixed points at equal height, the curve horizontal
    at them; module docstring).

    Parameters
    ----------
    mass_ratio : float
        mu = J_d / J_e (dimensionless), > 0.

    Returns
    -------
    tuple of float
        (tuning ratio omega_d/omega_r = 1/(1+mu), damping ratio c/(2 J_d omega_r) =
        sqrt(3 mu/(8 (1+mu)^3)), largest magnification sqrt(1 + 2/mu)), all dimensionless.

    Raises
    ------
    InputError
        Naming the key ``mass_ratio`` and its value when it is not positive and finite.

    Examples
    --------
    >>> [round(v, 6) for v in optimum_tuned(0.1)]
    [0.909091, 0.167852, 4.582576]
    """
    mu = check_positive("mass_ratio", mass_ratio, "the mass ratio")
    return (
        1.0 / (1.0 + mu),
        math.sqrt(3.0 * mu / (8.0 * (1.0 + mu) ** 3)),
        math.sqrt(1.0 + 2.0 / mu),
    )


def optimum_viscous(mass_ratio: float) -> tuple[float, float, float]:
    """Den Hartog's optimum untuned viscous damper for a mass ratio mu.

    Den Hartog (1956), sec. 3.10 (every response curve through one fixed point, the optimum
    curve horizontal there; module docstring).

    Parameters
    ----------
    mass_ratio : float
        mu = J_d / J_e (dimensionless), > 0.

    Returns
    -------
    tuple of float
        (frequency ratio of the fixed point sqrt(2/(2+mu)), damping ratio c/(2 J_d omega_r) =
        1/sqrt(2 (1+mu)(2+mu)), magnification at the fixed point 1 + 2/mu), all
        dimensionless.

    Raises
    ------
    InputError
        Naming the key ``mass_ratio`` and its value when it is not positive and finite.

    Examples
    --------
    >>> [round(v, 6) for v in optimum_viscous(0.25)]
    [0.942809, 0.421637, 9.0]
    """
    mu = check_positive("mass_ratio", mass_ratio, "the mass ratio")
    return (
        math.sqrt(2.0 / (2.0 + mu)),
        1.0 / math.sqrt(2.0 * (1.0 + mu) * (2.0 + mu)),
        1.0 + 2.0 / mu,
    )


def equivalent_single_mass(
    model: TorsionModel, at: str, mode: int, modes: ModalResult | None = None
) -> tuple[float, float]:
    """The single-degree-of-freedom system of one mode as seen at a mass.

    J_e = sum J_i phi_i^2 with the mode shape scaled to phi_at = 1, and the mode's natural
    frequency: the main system of Den Hartog's (1956, secs. 3.9-3.10) absorber (module
    docstring).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The lumped model.
    at : str
        The hub mass.
    mode : int
        The mode's number (elastic modes from 1, as
        :func:`~crankdyn.torsion.modal.natural_modes` numbers them; docs/conventions.md).
    modes : crankdyn.torsion.modal.ModalResult or None
        The model's natural modes, if already computed; default computed here.

    Returns
    -------
    tuple of float
        (J_e (kg m^2, at the hub's own speed), omega_r (rad/s)).

    Raises
    ------
    InputError
        Naming the key and value: ``mode`` not a mode number of the model, or the rigid-body
        mode; ``at`` not a mass of the model, or at a node of the mode.

    Examples
    --------
    Two equal masses J = 1 kg m^2 on two equal shafts k = 1e6 N m/rad from ground: mode 1
    has omega^2 = (3 - sqrt 5)/2 k/J and, seen at the free end, phi = (0.618, 1), so
    J_e = 1 + 0.618^2.

    >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
    >>> two = TorsionModel(
    ...     masses=(Mass("a", 1.0), Mass("b", 1.0)),
    ...     shafts=(Shaft(("ground", "a"), 1e6), Shaft(("a", "b"), 1e6)),
    ... )
    >>> j_e, omega = equivalent_single_mass(two, "b", 1)
    >>> round(j_e, 9), round(omega**2 / ((3 - math.sqrt(5)) / 2 * 1e6), 9)
    (1.381966011, 1.0)
    """
    from crankdyn.torsion.modal import natural_modes

    modes = natural_modes(model) if modes is None else modes
    if isinstance(mode, bool) or not isinstance(mode, (int, np.integer)):
        raise InputError("expected a mode number", key="mode", value=mode)
    r = modes.index(mode)
    omega = float(modes.natural_frequency[r])
    if omega <= 0.0:
        raise InputError(
            "the rigid-body mode cannot be damped by a damper; choose an elastic mode",
            key="mode",
            value=mode,
        )
    hub = model.index(at)
    dof = model.mass_dof
    shape_dof = np.zeros(model.dof_count)
    shape_dof[dof] = modes.mode_shapes[r]  # reflected amplitudes, per dof
    at_hub = shape_dof[dof[hub]]
    if abs(at_hub) < 1e-6 * np.max(np.abs(shape_dof)):
        raise InputError(
            f'"{at}" lies at a node of mode {mode}: a damper there cannot damp it',
            key="at",
            value=at,
        )
    phi = shape_dof / at_hub
    j_e = float(np.sum(model.dof_inertia * phi**2)) / float(model.speed_ratios[hub] ** 2)
    return j_e, omega


@dataclass(frozen=True)
class DamperDesign(Result):
    """Optimum damper for one mode (Den Hartog; module docstring).

    Examples
    --------
    >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
    >>> model = TorsionModel(masses=(Mass("m", 1.0),), shafts=(Shaft(("ground", "m"), 1e6),))
    >>> design = design_damper(model, "m", 1, 0.1)
    >>> design.kind, round(design.mass_ratio, 12), round(design.tuning_ratio, 9)
    ('tuned', 0.1, 0.909090909)
    """

    title = "Damper design"
    kind: str = scalar("kind", "Damper", "")
    at: str = scalar("at", "Mounted on", "")
    mode: int = scalar("mode", "Mode damped", "")
    natural_frequency: float = scalar("natural_frequency_hz", "Natural frequency", "Hz", HZ)
    equivalent_inertia: float = scalar(
        "equivalent_inertia_kg_m2", "Equivalent inertia of the mode at the hub J_e", "kg·m²"
    )
    ring_inertia: float = scalar("ring_inertia_kg_m2", "Ring inertia J_d", "kg·m²")
    mass_ratio: float = scalar("mass_ratio", "Mass ratio μ = J_d/J_e", "")
    tuning_ratio: float | None = scalar(
        "tuning_ratio", "Optimum tuning ω_d/ω_r = 1/(1+μ)", "", fmt=".5g"
    )
    stiffness: float = scalar("stiffness_Nm_per_rad", "Optimum rubber stiffness k_d", "N·m/rad")
    damping_ratio: float = scalar("damping_ratio", "Optimum damping c/(2 J_d ω_r)", "", fmt=".5g")
    damping: float = scalar("damping_Nms_per_rad", "Optimum damping c", "N·m·s/rad")
    magnification: float = scalar(
        "magnification", "Largest dynamic magnification at the hub", "", fmt=".5g"
    )

    def damper(self, name: str = "damper ring") -> Damper:
        """The designed damper.

        Parameters
        ----------
        name : str
            The ring's name in outputs (default ``"damper ring"``).

        Returns
        -------
        Damper
            Ring inertia, stiffness and viscous damping of the design on its hub (no loss
            factor).

        Examples
        --------
        >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
        >>> model = TorsionModel(masses=(Mass("m", 1.0),), shafts=(Shaft(("ground", "m"), 1e6),))
        >>> ring = design_damper(model, "m", 1, 0.1, kind="viscous").damper()
        >>> ring.kind, ring.at, round(ring.damping, 6)  # 2 J_d omega_r / sqrt(2 x 1.1 x 2.1)
        ('viscous', 'm', 93.048421)
        """
        return Damper(name, self.at, self.ring_inertia, self.stiffness, self.damping)


def design_damper(
    model: TorsionModel,
    at: str,
    mode: int,
    ring_inertia: float,
    kind: str = "tuned",
    modes: ModalResult | None = None,
) -> DamperDesign:
    """Optimum tuned or viscous damper for one mode of a model.

    The mode reduced to J_e and omega_r at the hub (:func:`equivalent_single_mass`), then Den
    Hartog's (1956) optima, secs. 3.9 (:func:`optimum_tuned`: k_d = J_d (f omega_r)^2) and
    3.10 (:func:`optimum_viscous`: k_d = 0), with c = 2 zeta J_d omega_r.

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The lumped model.
    at : str
        The hub mass the damper is mounted on.
    mode : int
        The mode to damp (elastic modes from 1).
    ring_inertia : float
        Ring inertia J_d (kg m^2), > 0.
    kind : str
        ``"tuned"`` (default, a rubber damper) or ``"viscous"`` (untuned).
    modes : crankdyn.torsion.modal.ModalResult or None
        The model's natural modes, if already computed.

    Returns
    -------
    DamperDesign
        The mass ratio, the optimum tuning (tuned only), stiffness (N m/rad), damping ratio,
        damping (N m s/rad) and the largest magnification at the hub.

    Raises
    ------
    InputError
        Naming the key and value: a ``kind`` other than tuned or viscous, a ring inertia that
        is not positive, and as :func:`equivalent_single_mass` (``mode``, ``at``).

    Examples
    --------
    One mass J = 1 kg m^2 on k = 1e6 N m/rad (omega_r = 1000 rad/s), a 0.1 kg m^2 ring: the
    tuned optimum k_d = J_d (omega_r / (1 + mu))^2.

    >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
    >>> model = TorsionModel(masses=(Mass("m", 1.0),), shafts=(Shaft(("ground", "m"), 1e6),))
    >>> design = design_damper(model, "m", 1, 0.1)
    >>> round(design.stiffness / (0.1 * (1000 / 1.1) ** 2), 12), round(design.magnification, 6)
    (1.0, 4.582576)
    """
    if kind not in ("tuned", "viscous"):
        raise InputError('expected "tuned" or "viscous"', key="kind", value=kind)
    j_d = check_positive("ring_inertia", ring_inertia, "the ring's inertia")
    j_e, omega = equivalent_single_mass(model, at, mode, modes)
    mu = j_d / j_e
    if kind == "tuned":
        tuning, zeta, peak = optimum_tuned(mu)
        k = j_d * (tuning * omega) ** 2
    else:
        _, zeta, peak = optimum_viscous(mu)
        tuning, k = None, 0.0
    return DamperDesign(
        kind=kind,
        at=at,
        mode=int(mode),
        natural_frequency=omega,
        equivalent_inertia=j_e,
        ring_inertia=j_d,
        mass_ratio=mu,
        tuning_ratio=tuning,
        stiffness=k,
        damping_ratio=zeta,
        damping=2.0 * zeta * j_d * omega,
        magnification=peak,
    )


@dataclass(frozen=True)
class DamperResonances(Result):
    """The critical speeds of the damper modes inside the operating range (:func:`damper_modes`):
    n_c = omega_r / q (seed 003 ch. 5)."""

    title = "Resonances of the damper modes"
    mode: NDArray[np.int_] = column("mode", "Mode", "")
    order: NDArray[np.float64] = column("order", "Order", "")
    speed: NDArray[np.float64] = column("speed_rpm", "Critical speed", "rpm", RPM)
    natural_frequency: NDArray[np.float64] = column(
        "natural_frequency_hz", "Natural frequency", "Hz", HZ
    )
    major: NDArray[np.str_] = column("major", "Major order", "")


@dataclass(frozen=True)
class DamperModes(Result):
    """The natural modes of a shaft line with its tuned damper stages and the resonances the
    dampers add (:func:`damper_modes`; module docstring).

    Parameters
    ----------
    critical_speeds : tuple of crankdyn.torsion.campbell.CriticalSpeed
        The damper modes' critical speeds (rad/s) as objects (not exported: ``resonances``
        holds them).
    """

    title = "Damper modes"
    model_name: str = scalar("model", "Model", "")
    rings: tuple[str, ...] = scalar("rings", "Tuned damper rings", "")
    mode: NDArray[np.int_] = column("mode", "Mode", "")
    natural_frequency: NDArray[np.float64] = column(
        "natural_frequency_hz", "Natural frequency", "Hz", HZ
    )
    ring_share: NDArray[np.float64] = column("ring_energy_share", "Rings' share of the energy", "")
    damper_mode: NDArray[np.str_] = column("damper_mode", "Damper mode", "")
    without_dampers: NDArray[np.float64] = column(
        "natural_frequency_without_dampers_hz", "Without the dampers (same mode number)", "Hz", HZ
    )
    damper_mode_count: int = scalar("damper_modes", "Damper modes", "")
    lowest_damper_mode: float | None = scalar(
        "lowest_damper_mode_hz", "Lowest damper mode", "Hz", HZ
    )
    added_resonances: int = scalar(
        "added_resonances", "Resonances of damper modes in the operating range", ""
    )
    resonances: DamperResonances = scalar("resonances", "Critical speeds of the damper modes", "")
    notes: tuple[str, ...] | None = scalar("notes", "Notes", "", default=None)
    critical_speeds: tuple[CriticalSpeed, ...] = field(default=(), repr=False, compare=False)


def damper_modes(
    model: TorsionModel,
    orders: ArrayLike,
    speed_range: tuple[float, float] | None = None,
    *,
    excitation: Excitation | None = None,
) -> DamperModes:
    """The natural modes of ``model`` with its tuned damper stages, the rings' share of each
    mode's energy, and the critical speeds of the damper modes in the operating range (seed 003,
    multi-stage dampers; module docstring).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The torsional model with its dampers (several on one hub: the stages of a multi-stage
        damper).
    orders : array_like
        The orders to consider (dimensionless).
    speed_range : tuple of (float, float) or None
        (low, high) (rad/s); default the model's operating range.
    excitation : crankdyn.torsion.excitation.Excitation or None
        For the major orders (:func:`crankdyn.torsion.campbell.campbell`).

    Returns
    -------
    DamperModes
        Every elastic mode with dampers (frequency in rad/s, exported in Hz), the rings' share
        of its energy, whether it is a damper mode (``"yes"``/``"no"``), the same-numbered
        mode's frequency without the dampers, and the critical speeds (rad/s) of the damper
        modes inside the range
        (``resonances``; ``critical_speeds`` the same as
        :class:`~crankdyn.torsion.campbell.CriticalSpeed` objects).

    Raises
    ------
    crankdyn.errors.InputError
        As :func:`crankdyn.torsion.campbell.campbell` (no speed range, orders not of the
        model's excitation).

    Examples
    --------
    A 1 kg m^2 mass on 1e6 N m/rad (1000 rad/s) with a 0.05 kg m^2 stage tuned to 2000 rad/s:
    the stage adds a mode near 2000 rad/s that it holds nearly all of.

    >>> from crankdyn.torsion import Mass, Shaft, TorsionModel
    >>> model = TorsionModel(
    ...     masses=(Mass("hub", 1.0),), shafts=(Shaft(("ground", "hub"), 1e6),),
    ...     dampers=(Damper("stage 1", "hub", 0.05, stiffness=0.05 * 2000.0**2),),
    ... )
    >>> result = damper_modes(model, [1.0], (100.0, 2500.0))
    >>> [round(float(s), 3) for s in result.ring_share], [str(d) for d in result.damper_mode]
    ([0.079, 0.921], ['no', 'yes'])
    >>> [round(c.speed, 1) for c in result.critical_speeds]
    [2064.3]
    """
    from crankdyn.torsion.campbell import campbell, with_dampers
    from crankdyn.torsion.modal import natural_modes

    full = with_dampers(model)
    tuned = tuple(d.name for d in model.dampers if d.kind == "tuned")
    notes = []
    viscous = [d.name for d in model.dampers if d.kind == "viscous"]
    if viscous:
        notes.append(
            f"untuned viscous rings ({', '.join(viscous)}) add no undamped mode and are left out"
        )
    if not tuned:
        notes.append("the model has no tuned damper: no damper mode")
    modes = natural_modes(full)
    bare = natural_modes(dataclasses.replace(model, dampers=()))
    elastic = np.flatnonzero(modes.natural_frequency > 0.0)
    inertia = np.array([m.inertia for m in full.masses]) * np.asarray(full.speed_ratios) ** 2
    shapes = np.asarray(modes.mode_shapes)[elastic]
    energy = inertia * shapes**2
    ring_idx = [full.index(name) for name in tuned]
    share = energy[:, ring_idx].sum(axis=1) / energy.sum(axis=1)
    is_damper = share > DAMPER_MODE_SHARE
    numbers = np.asarray(modes.mode)[elastic]
    bare_f = dict(
        zip(np.asarray(bare.mode).tolist(), np.asarray(bare.natural_frequency), strict=True)
    )
    without = np.array([bare_f.get(int(r), np.nan) for r in numbers])
    diagram = campbell(model, orders, speed_range, excitation=excitation)
    damper_numbers = set(numbers[is_damper].tolist())
    rows = tuple(c for c in diagram.critical_speeds if c.mode in damper_numbers)
    lowest = float(np.min(modes.natural_frequency[elastic][is_damper])) if is_damper.any() else None
    return DamperModes(
        model_name=model.name,
        rings=tuned,
        mode=freeze(numbers, dtype=int),
        natural_frequency=freeze(modes.natural_frequency[elastic]),
        ring_share=freeze(share),
        damper_mode=freeze(np.where(is_damper, "yes", "no"), dtype=str),
        without_dampers=freeze(without),
        damper_mode_count=int(np.count_nonzero(is_damper)),
        lowest_damper_mode=lowest,
        added_resonances=len(rows),
        resonances=DamperResonances(
            mode=freeze([c.mode for c in rows], dtype=int),
            order=freeze([c.order for c in rows]),
            speed=freeze([c.speed for c in rows]),
            natural_frequency=freeze([c.natural_frequency for c in rows]),
            major=freeze(
                ["undetermined" if c.major is None else "yes" if c.major else "no" for c in rows],
                dtype=str,
            ),
        ),
        notes=tuple(notes) or None,
        critical_speeds=rows,
    )
