"""The engine: cylinders, crank arrangement, geometry, masses, pressure (domain objects).

Conventions (docs/conventions.md; seed 000 sections 2.3): cylinders are numbered from the free end
to the flywheel; the crankshaft turns clockwise seen from the free end; the crankshaft angle theta
is 0 when cylinder 1 is at firing TDC; cylinder i's own crank angle is theta - psi_i where psi_i is
its throw angle. V engines: bank A is the left bank seen from the free end, bank B the right; the
bank axes lie at -gamma/2 (A) and +gamma/2 (B) from the vertical, measured clockwise, so on a shared
throw the bank-B cylinder reaches TDC gamma after the bank-A cylinder.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from crankdyn.crank.geometry import CrankGeometry, check_finite, check_positive
from crankdyn.crank.masses import Masses
from crankdyn.crank.pressure import ATMOSPHERE, PressureTrace
from crankdyn.crankshaft.geometry import Crankshaft
from crankdyn.engine.firing import (
    CYCLE_ANGLE,
    VArrangement,
    check_firing_order,
    even_firing_throw_angles,
    firing_angles,
)
from crankdyn.engine.force_model import ForceModel
from crankdyn.errors import InputError
from crankdyn.torsion.model import TorsionModel

if TYPE_CHECKING:
    from crankdyn.plausibility import PlausibilityWarning

FUELS = ("petrol", "diesel")
"""Engine types by ignition: spark-ignition (petrol, gas) and compression-ignition (diesel)."""
ASPIRATIONS = ("natural", "turbocharged")
"""Air supply: naturally aspirated, or pressure-charged (turbo- or supercharged)."""

__all__ = ["CYCLES", "LAYOUTS", "BalanceInputs", "Cylinders", "Engine", "FlywheelInputs"]

CYCLES = ("four-stroke", "two-stroke")
LAYOUTS = ("inline", "V")
TWO_PI = 2.0 * math.pi
_ANGLE_TOL = 1e-7


def _same_angle(a: float, b: float) -> bool:
    d = math.remainder(a - b, TWO_PI)
    return abs(d) < _ANGLE_TOL


@dataclass(frozen=True)
class Cylinders:
    """Cylinder arrangement: count, layout, firing order and crank arrangement.

    Parameters
    ----------
    count : int
        Number of cylinders Z.
    firing_order : sequence of int
        Cylinder numbers in firing order (a permutation of 1..Z; rotated to start at 1).
    cycle : str
        ``"four-stroke"`` (default) or ``"two-stroke"``.
    throw_angles : sequence of float or None
        Throw angle psi_i of every cylinder (rad): crankshaft rotation from cylinder 1's TDC to
        cylinder i's TDC, 0 <= psi_i < 2 pi, psi_1 = 0. Derived for even firing from the firing
        order when not given (:func:`~crankdyn.engine.firing.even_firing_throw_angles`).
    layout : str
        ``"inline"`` (default) or ``"V"``.
    bank_angle : float
        V angle gamma between the banks (rad); 0 for inline engines.
    banks : sequence of str or None
        Bank of every cylinder, ``"A"`` or ``"B"`` (V engines; default: the first half of the
        cylinders on bank A, the second half on bank B).
    throws : sequence of int or None
        Crank throw (1-based, from the free end) of every cylinder (default: inline, cylinder i on
        throw i; V, cylinders i and i + Z/2 on throw i).
    pitch : float or None
        Axial spacing of the throws (m), or None when unknown.

    Raises
    ------
    InputError
        If the count, cycle, layout, firing order, throw angles, banks, throws, bank angle or
        pitch is invalid, the firing order does not fit the crankshaft, or two cylinders of one
        throw disagree on its position (each message names the key).

    Notes
    -----
    After construction ``firing_order``, ``throw_angles``, ``banks`` and ``throws`` are tuples,
    never None (derived where not given).

    Examples
    --------
    An inline-6 firing 1-5-3-6-2-4 (the throw angles follow for even firing):

    >>> import math
    >>> c = Cylinders(6, (1, 5, 3, 6, 2, 4))
    >>> [round(math.degrees(a)) for a in c.throw_angles]
    [0, 120, 240, 240, 120, 0]
    >>> [round(math.degrees(a)) for a in c.firing_angles]
    [0, 480, 240, 600, 120, 360]
    """

    count: int
    firing_order: tuple[int, ...]
    cycle: str = "four-stroke"
    # None on input: derived in __post_init__ (the __init__ below tells the type checker)
    throw_angles: tuple[float, ...] = None  # type: ignore[assignment]
    layout: str = "inline"
    bank_angle: float = 0.0
    banks: tuple[str, ...] = None  # type: ignore[assignment]
    throws: tuple[int, ...] = None  # type: ignore[assignment]
    pitch: float | None = None

    if TYPE_CHECKING:  # what the constructor accepts; the fields hold the normalised values

        def __init__(
            self,
            count: int,
            firing_order: Sequence[int],
            cycle: str = "four-stroke",
            throw_angles: Sequence[float] | NDArray[np.float64] | None = None,
            layout: str = "inline",
            bank_angle: float = 0.0,
            banks: Sequence[str] | None = None,
            throws: Sequence[int] | None = None,
            pitch: float | None = None,
        ) -> None: ...

    def __post_init__(self) -> None:
        count = self.count
        if isinstance(count, bool) or not isinstance(count, (int, np.integer)) or count < 1:
            raise InputError(
                "the cylinder count must be a whole number >= 1", key="count", value=count
            )
        count = int(count)
        if self.cycle not in CYCLES:
            raise InputError(f"expected one of {', '.join(CYCLES)}", key="cycle", value=self.cycle)
        if self.layout not in LAYOUTS:
            raise InputError(
                f"expected one of {', '.join(LAYOUTS)}", key="layout", value=self.layout
            )
        order = check_firing_order(self.firing_order, count)
        set_ = object.__setattr__
        set_(self, "count", count)
        set_(self, "firing_order", order)

        # layout: banks, throws, bank angle
        if self.layout == "inline":
            if self.bank_angle not in (0, 0.0):
                raise InputError(
                    "an inline engine has no bank angle", key="bank_angle", value=self.bank_angle
                )
            banks = ("A",) * count if self.banks is None else tuple(self.banks)
            if set(banks) != {"A"}:
                raise InputError("an inline engine has one bank, A", key="banks", value=list(banks))
            throws = tuple(range(1, count + 1)) if self.throws is None else tuple(self.throws)
        else:
            gamma = check_finite("bank_angle", self.bank_angle)
            if not 0.0 < gamma < math.pi:
                raise InputError(
                    "the bank angle of a V engine must lie between 0 and 180 deg",
                    key="bank_angle",
                    value=self.bank_angle,
                )
            set_(self, "bank_angle", gamma)
            if (self.banks is None or self.throws is None) and count % 2:
                raise InputError(
                    "a V engine with an odd number of cylinders needs banks and throws "
                    "given cylinder by cylinder",
                    key="banks" if self.banks is None else "throws",
                )
            half = count // 2
            banks = ("A",) * half + ("B",) * half if self.banks is None else tuple(self.banks)
            throws = (
                tuple(list(range(1, half + 1)) * 2) if self.throws is None else tuple(self.throws)
            )
        if len(banks) != count or not set(banks) <= {"A", "B"}:
            raise InputError(
                f'expected {count} entries, each "A" or "B"', key="banks", value=list(banks)
            )
        try:
            throws = tuple(int(t) for t in throws)
        except (TypeError, ValueError):
            raise InputError("expected throw numbers", key="throws", value=list(throws)) from None
        if (
            len(throws) != count
            or min(throws) < 1
            or sorted(set(throws)) != list(range(1, max(throws) + 1))
        ):
            raise InputError(
                f"expected {count} throw numbers, using every throw from 1 up",
                key="throws",
                value=list(throws),
            )
        for t in set(throws):
            on_throw = [banks[i] for i in range(count) if throws[i] == t]
            if len(on_throw) != len(set(on_throw)):
                raise InputError(
                    f"throw {t} carries two cylinders of the same bank",
                    key="throws",
                    value=list(throws),
                )
        set_(self, "banks", banks)
        set_(self, "throws", throws)

        # throw angles
        if self.throw_angles is None:
            psi = even_firing_throw_angles(order, self.cycle)
            derived = True
        else:
            psi = np.array([check_finite("throw_angles", a) for a in self.throw_angles])
            derived = False
            if psi.size != count:
                raise InputError(
                    f"expected {count} throw angles, one per cylinder",
                    key="throw_angles",
                    value=list(self.throw_angles),
                )
            bad = (psi < 0.0) | (psi >= TWO_PI)
            if np.any(bad):
                i = int(np.argmax(bad))
                message = f"throw angles must lie in 0 <= psi < 360 deg (cylinder {i + 1})"
                if psi[i] >= TWO_PI:
                    message += f'; bare numbers are radians, did you mean "{psi[i]:g} deg"?'
                raise InputError(message, key="throw_angles", value=list(self.throw_angles))
            if abs(psi[0]) > _ANGLE_TOL:
                raise InputError(
                    "cylinder 1's throw angle must be 0 (angles are measured from its TDC)",
                    key="throw_angles",
                    value=list(self.throw_angles),
                )
        set_(self, "throw_angles", tuple(float(a) for a in psi))
        firing_angles(order, psi, self.cycle)  # raises if the order does not fit

        if self.pitch is not None:
            set_(self, "pitch", check_positive("pitch", self.pitch, "the pitch"))

        # V engines: cylinders on one throw must agree on the throw's position
        positions = self._cylinder_throw_positions()
        for t in set(throws):
            idx = [i for i in range(count) if throws[i] == t]
            for i in idx[1:]:
                if not _same_angle(positions[i], positions[idx[0]]):
                    a, b = idx[0], i
                    hint = " (derived from the firing order; give throw_angles)" if derived else ""
                    raise InputError(
                        f"cylinders {a + 1} (bank {banks[a]}) and {b + 1} (bank {banks[b]}) share "
                        f"throw {t}, so their TDCs must be {math.degrees(self.bank_angle):.6g} deg "
                        f"apart{hint}",
                        key="throw_angles",
                        value=[round(math.degrees(x), 6) for x in psi],
                    )

    @classmethod
    def from_arrangement(
        cls, arrangement: VArrangement, cycle: str, pitch: float | None = None
    ) -> Cylinders:
        """The cylinders of a V engine's arrangement.

        Parameters
        ----------
        arrangement : crankdyn.engine.firing.VArrangement
            From :func:`~crankdyn.engine.firing.v_alternating`: firing order, throw angles
            (rad), banks, throws and bank angle (rad).
        cycle : str
            ``"four-stroke"`` or ``"two-stroke"``.
        pitch : float or None
            Axial spacing of the throws (m), or None when unknown.

        Returns
        -------
        Cylinders
            A V engine's cylinders.

        Raises
        ------
        InputError
            If the arrangement does not make a valid set of cylinders.

        Examples
        --------
        A 90 deg V8 with a flat crank, each bank firing 1-3-4-2 (seed 000 section 2.3):

        >>> import math
        >>> from crankdyn.engine.firing import v_alternating
        >>> v8 = Cylinders.from_arrangement(
        ...     v_alternating((1, 3, 4, 2), math.radians(90), "four-stroke"), "four-stroke"
        ... )
        >>> v8.firing_order
        (1, 5, 3, 7, 4, 8, 2, 6)
        """
        return cls(
            count=len(arrangement.firing_order),
            firing_order=tuple(arrangement.firing_order),
            cycle=cycle,
            throw_angles=tuple(arrangement.throw_angles),
            layout="V",
            bank_angle=arrangement.bank_angle,
            banks=tuple(arrangement.banks),
            throws=tuple(arrangement.throws),
            pitch=pitch,
        )

    # ---- derived arrangement ------------------------------------------------------------------
    @property
    def bank_axis_angles(self) -> NDArray[np.float64]:
        """Angle alpha_i of every cylinder's axis from the vertical (rad, clockwise seen from the
        free end): 0 inline, -gamma/2 bank A, +gamma/2 bank B."""
        if self.layout == "inline":
            return np.zeros(self.count)
        half = self.bank_angle / 2.0
        return np.array([-half if b == "A" else half for b in self.banks])

    def _cylinder_throw_positions(self) -> np.ndarray:
        alpha = self.bank_axis_angles
        return np.mod(alpha - np.asarray(self.throw_angles) - alpha[0], TWO_PI)

    @property
    def throw_count(self) -> int:
        """Number of crank throws."""
        return max(self.throws)

    @property
    def throw_positions(self) -> NDArray[np.float64]:
        """Angular position of every throw at theta = 0 (rad, clockwise seen from the free end,
        relative to throw of cylinder 1): the crank end view (seed 000 section 2.3)."""
        positions = self._cylinder_throw_positions()
        out = np.empty(self.throw_count)
        for i, t in enumerate(self.throws):
            out[t - 1] = positions[i]
        return out

    @cached_property
    def firing_angles(self) -> NDArray[np.float64]:
        """Firing angle Phi_i of every cylinder (rad), 0 <= Phi_i < cycle angle."""
        return firing_angles(self.firing_order, self.throw_angles, self.cycle)

    @property
    def axial_positions(self) -> NDArray[np.float64] | None:
        """Axial position of every cylinder's throw from throw 1 (m), or None without a pitch."""
        if self.pitch is None:
            return None
        return (np.asarray(self.throws, dtype=float) - 1.0) * self.pitch


# ---- inputs of the engine's analyses (tables of the engine file) ---------------------------


@dataclass(frozen=True)
class BalanceInputs:
    """Balance inputs of an engine (the ``[balance]`` table of the engine file).

    Parameters
    ----------
    counterweight_ratio : float
        c: counterweight unbalance of every throw as a fraction of the throw's rotating
        unbalance m_r,t R (dimensionless; 0 = no counterweights, 1 = each throw's rotating mass
        balanced on the throw).
    reciprocating_balance_ratio : float
        b: share of the throw's reciprocating mass added to its counterweight (dimensionless;
        the balance factor of single-cylinder and twin engines; 0.5 turns a single cylinder's
        first-order force into a rotating force of half the size).
    rod_offset : float
        Axial offset of the bank-B rod from the bank-A rod on a shared V throw (m, positive
        toward the flywheel); each rod sits half of it either side of the throw's middle.
    power : float or None
        Engine power at the analysis speed (W), for the power-related unbalance; None when
        unknown.

    Raises
    ------
    InputError
        If a ratio is negative or not a number, or the power is not positive.
    """

    counterweight_ratio: float = 0.0
    reciprocating_balance_ratio: float = 0.0
    rod_offset: float = 0.0
    power: float | None = None

    def __post_init__(self) -> None:
        for name in ("counterweight_ratio", "reciprocating_balance_ratio"):
            value = check_finite(name, getattr(self, name))
            if value < 0.0:
                raise InputError("must not be negative", key=name, value=getattr(self, name))
            object.__setattr__(self, name, value)
        object.__setattr__(self, "rod_offset", check_finite("rod_offset", self.rod_offset))
        if self.power is not None:
            power = check_finite("power", self.power)
            if power <= 0.0:
                raise InputError("the power must be positive", key="power", value=self.power)
            object.__setattr__(self, "power", power)


@dataclass(frozen=True)
class FlywheelInputs:
    """Flywheel inputs of an engine (the ``[flywheel]`` table of the engine file).

    Parameters
    ----------
    delta : float or None
        Target degree of cyclic irregularity (dimensionless, 0 < delta < 1), or None.
    inertia : float or None
        Moment of inertia of an existing flywheel (kg m^2), to find the delta it gives, or None.
    other_inertia : float
        I_3: other parts turning with the crankshaft (damper, pulley, gears, clutch) (kg m^2).
    density : float or None
        Flywheel material density (kg/m^3), for the sizing; None to skip it.
    max_diameter : float or None
        Largest outer diameter the flywheel may have (m); None to skip the sizing.
    inner_diameter : float or None
        Inner diameter of the rim (m), for a rim-type flywheel; None sizes a solid disc only.

    Raises
    ------
    InputError
        If a value is not positive (``other_inertia``: negative), delta is not below 1, or the
        rim's inner diameter is not below ``max_diameter``.
    """

    delta: float | None = None
    inertia: float | None = None
    other_inertia: float = 0.0
    density: float | None = None
    max_diameter: float | None = None
    inner_diameter: float | None = None

    def __post_init__(self) -> None:
        for name in ("delta", "inertia", "density", "max_diameter", "inner_diameter"):
            value = getattr(self, name)
            if value is None:
                continue
            number = check_finite(name, value)
            if number <= 0.0:
                raise InputError("must be positive", key=name, value=value)
            object.__setattr__(self, name, number)
        if self.delta is not None and self.delta >= 1.0:
            raise InputError(
                "the degree of cyclic irregularity is a small fraction (e.g. 0.01 or 1/100)",
                key="delta",
                value=self.delta,
            )
        other = check_finite("other_inertia", self.other_inertia)
        if other < 0.0:
            raise InputError("must not be negative", key="other_inertia", value=other)
        object.__setattr__(self, "other_inertia", other)
        if (
            self.inner_diameter is not None
            and self.max_diameter is not None
            and self.inner_diameter >= self.max_diameter
        ):
            raise InputError(
                "the rim's inner diameter must be smaller than max_diameter",
                key="inner_diameter",
                value=self.inner_diameter,
            )


def check_engine_cylinders(model: TorsionModel, cylinders: Cylinders) -> None:
    """Check a torsional model's cylinders against the engine's.

    Every cylinder number a mass carries must exist, and the cylinders of one crank throw must
    sit on one mass.

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The engine's torsional model.
    cylinders : Cylinders
        The engine's cylinders.

    Raises
    ------
    InputError
        If either rule is broken.
    """
    owner: dict[int, str] = {}
    for m in model.masses:
        for c in m.cylinders:
            if c > cylinders.count:
                raise InputError(
                    f'mass "{m.name}" carries cylinder {c} but the engine has '
                    f"{cylinders.count} cylinders",
                    key="cylinders",
                    value=list(m.cylinders),
                )
            owner[c] = m.name
    for c, name in owner.items():
        throw = cylinders.throws[c - 1]
        for d in range(1, cylinders.count + 1):
            if d != c and cylinders.throws[d - 1] == throw and owner.get(d, name) != name:
                raise InputError(
                    f"cylinders {c} and {d} share crank throw {throw} but sit on the masses "
                    f'"{name}" and "{owner[d]}"',
                    key="cylinders",
                )


@dataclass(frozen=True)
class Engine:
    """A reciprocating engine: identical cylinders on one crankshaft.

    Parameters
    ----------
    name : str
        Name for reports.
    geometry : CrankGeometry
        Crank geometry shared by all cylinders.
    cylinders : Cylinders
        Count, layout, firing order and crank arrangement (holds the cycle).
    masses : Masses or None
        Crank-train masses of one cylinder, or None.
    pressure : PressureTrace or None
        Cylinder pressure over the cycle, or None (the synthetic model with its defaults,
        :func:`crankdyn.crank.pressure_model.default_pressure`).
    crankcase_pressure : float
        Pressure under the piston (Pa, absolute); the gas force is (p - p_crankcase) A.
        Default 1 atm.
    speed : float or None
        Operating speed (rad/s), or None.
    torsion : crankdyn.torsion.model.TorsionModel or None
        Lumped torsional model of the shaft line (masses carrying cylinders numbered as the
        engine's), or None.
    mechanical_efficiency : float or None
        eta_m (dimensionless, 0 < eta_m <= 1) for effective torque and power, or None.
    balance : BalanceInputs or None
        Counterweights, V rod offset and power for the balance analysis, or None.
    flywheel : FlywheelInputs or None
        Target irregularity, flywheel, other inertias and material for the flywheel analysis,
        or None.
    source : str or None
        The file the engine came from, for messages.
    fuel : str or None
        ``"petrol"`` (spark ignition) or ``"diesel"`` (compression ignition), or None when not
        stated; selects the typical ranges of the plausibility warnings
        (:mod:`crankdyn.plausibility`).
    aspiration : str or None
        ``"natural"`` or ``"turbocharged"`` (any pressure charging), or None when not stated.
    crankshaft : crankdyn.crankshaft.geometry.Crankshaft or None
        Dimensions, material and type of the crankshaft for its fatigue check by IACS UR M53
        (:func:`crankdyn.crankshaft.strength.crankshaft_strength`), or None.
    forces : crankdyn.engine.force_model.ForceModel or None
        The optional forces on the crank train (gravity, piston friction; ``[forces]``), or
        None: the gas and inertia forces alone.
    input_warnings : tuple of crankdyn.plausibility.InputWarning
        The values of the engine file that lie outside the plausible range of their role
        (:mod:`crankdyn.io.plausibility`); every result of an analysis session on the engine
        carries them, and its verdicts cannot read a clean "passed".

    Raises
    ------
    InputError
        If the name is empty, the fuel or aspiration unknown, the rod data do not fit the rod
        length, the crankcase pressure negative, the speed or efficiency out of range, the
        torsional model's cylinders do not fit the engine's, the pressure trace covers
        another cycle, or the crankshaft's web centre does not lie within half the cylinder
        pitch (its bearing span when none is given).

    Examples
    --------
    >>> from crankdyn.crank.geometry import CrankGeometry
    >>> from crankdyn.crank.masses import Masses
    >>> engine = Engine(
    ...     "twin",
    ...     CrankGeometry.from_stroke(0.08, 0.07, rod_ratio=0.28),
    ...     Cylinders(2, (1, 2), throw_angles=(0.0, math.pi)),
    ...     masses=Masses(reciprocating=0.4, rotating=0.3),
    ... )
    >>> round(engine.displacement * 1e6, 1)  # cm^3
    703.7
    """

    name: str
    geometry: CrankGeometry
    cylinders: Cylinders
    masses: Masses | None = None
    pressure: PressureTrace | None = None
    crankcase_pressure: float = ATMOSPHERE
    speed: float | None = None
    torsion: TorsionModel | None = None
    mechanical_efficiency: float | None = None
    balance: BalanceInputs | None = None
    flywheel: FlywheelInputs | None = None
    source: str | None = field(default=None, compare=False)
    fuel: str | None = None
    aspiration: str | None = None
    crankshaft: Crankshaft | None = None
    forces: ForceModel | None = None
    input_warnings: tuple[PlausibilityWarning, ...] = field(default=(), compare=False, repr=False)

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name.strip():
            raise InputError("the engine needs a name", key="name", value=self.name)
        for key, choices in (("fuel", FUELS), ("aspiration", ASPIRATIONS)):
            value = getattr(self, key)
            if value is not None and value not in choices:
                raise InputError(f"expected one of {', '.join(choices)}", key=key, value=value)
        if self.masses is not None:
            self.masses.check_rod(self.geometry.rod_length)
        check_finite("crankcase_pressure", self.crankcase_pressure)
        if self.crankcase_pressure < 0.0:
            raise InputError(
                "an absolute pressure cannot be negative",
                key="crankcase_pressure",
                value=self.crankcase_pressure,
            )
        if self.speed is not None:
            check_positive("speed", self.speed, "the speed")
        if self.torsion is not None:
            check_engine_cylinders(self.torsion, self.cylinders)
        if self.mechanical_efficiency is not None:
            eta = check_positive(
                "mechanical_efficiency", self.mechanical_efficiency, "the mechanical efficiency"
            )
            if eta > 1.0:
                raise InputError(
                    "the mechanical efficiency must lie in 0 < eta <= 1",
                    key="mechanical_efficiency",
                    value=eta,
                )
        if (
            self.crankshaft is not None
            and self.crankshaft.geometry.bearing_span is None
            and self.cylinders.pitch is not None
        ):
            self.crankshaft.geometry.check_span(self.cylinders.pitch)
        if self.pressure is not None:
            expected = CYCLE_ANGLE[self.cycle]
            if abs(self.pressure.cycle_angle - expected) > 1e-9:
                raise InputError(
                    f"the pressure trace covers {math.degrees(self.pressure.cycle_angle):.0f} deg "
                    f"but a {self.cycle} cycle is {math.degrees(expected):.0f} deg",
                    key="file",
                )

    @property
    def cycle(self) -> str:
        """``"four-stroke"`` or ``"two-stroke"``."""
        return self.cylinders.cycle

    @property
    def cycle_angle(self) -> float:
        """Crank angle of one working cycle (rad): 4 pi four-stroke, 2 pi two-stroke."""
        return CYCLE_ANGLE[self.cycle]

    @property
    def displacement(self) -> float:
        """Total swept volume of all cylinders (m^3)."""
        return self.cylinders.count * self.geometry.swept_volume

    def _repr_html_(self) -> str:
        """The engine's data and its mass-elastic system (notebooks)."""
        from crankdyn.display import engine_html

        return engine_html(self)

    @classmethod
    def from_file(cls, path: str | Path) -> Engine:
        """Load an engine description file (TOML; ``crankdyn docs engine-file``).

        Parameters
        ----------
        path : str or pathlib.Path
            The engine file.

        Returns
        -------
        Engine
            The engine, in SI.

        Raises
        ------
        InputError
            If the file cannot be read or holds a mistake (the message names file, key and
            value).
        """
        from crankdyn.io.engine_file import load_engine  # boundary layer, imported on demand

        return load_engine(path)

    @classmethod
    def example(cls, name: str) -> Engine:
        """A built-in example engine by name (``crankdyn examples`` lists them).

        Parameters
        ----------
        name : str
            The example's name, e.g. ``"inline6-diesel"``.

        Returns
        -------
        Engine
            The engine.

        Raises
        ------
        InputError
            If there is no engine example of that name.

        Examples
        --------
        >>> engine = Engine.example("inline6-diesel")
        >>> engine.cylinders.count, engine.cycle
        (6, 'four-stroke')
        """
        from crankdyn.io.catalogue import load_example

        return load_example(name, "engine")
