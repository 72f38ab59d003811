"""The figures a study can keep per case: a registry of named scalar results.

A *figure* is one number computed from one variant of the base engine (or model): mean torque,
the largest main-bearing load, a natural frequency... Each is a :class:`Figure` in
:data:`FIGURES`, registered with :func:`register_figure`; its function takes a
:class:`CaseContext` (the variant ``ctx.subject``, the study's analysis settings
``ctx.settings``) and returns a float in SI (NaN when undefined). Every figure takes its numbers
from the case's analysis session ``ctx.analysis`` (:class:`crankdyn.engine.session.Analysis`,
which computes each analysis once per case, with the same defaults as the command line and the
report), so a study's figure is the same number as the report's for the same variant.

Other capabilities extend the registry by adding figures (and any setting their analyses need in
the study file's ``[analysis]`` table, :data:`SETTINGS`). A figure defined in any importable
module works on every worker: the worker imports the module that defines each figure before
running a case.

The figures here are thin views of validated analyses (``torque.engine_torque``,
``bearings.bearing_loads``, ``forces.cylinder_forces``, ``kinematics.piston_kinematics``); the
one formula of their own is the torque non-uniformity (M_max - M_min)/M_mean (seed 000 section
2.4), the largest swing of the total torque over the cycle relative to its mean.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from crankdyn.docs import ref
from crankdyn.errors import InputError

if TYPE_CHECKING:
    from crankdyn.engine.session import Analysis
    from crankdyn.torsion.modal import ModalResult

__all__ = [
    "FIGURES",
    "SETTINGS",
    "AnalysisSettings",
    "CaseContext",
    "Figure",
    "Setting",
    "register_figure",
    "register_setting",
]

SENSES = ("min", "max")
"""A figure's senses of better."""


# ---- analysis settings ([analysis] in the study file) -----------------------------------------


@dataclass(frozen=True)
class Setting:
    """A key of the study file's ``[analysis]`` table.

    Parameters
    ----------
    name : str
        The key.
    kind : str
        A quantity kind of :data:`crankdyn.io.units.KINDS` (read with units), ``"number"``,
        ``"strings"`` (a list of text) or ``"list:<quantity kind>"`` (a list of quantities).
    default : object
        The default in SI (None: no default, the analyses fall back on the engine's or the
        model's own value, e.g. its ``[operating] speed``).
    help : str
        One line for the documentation and ``crankdyn study --list``.
    check : str or None
        The reader's check of a value (default ``"positive"``), or None.
    length : int or None
        The length of a list, or None.
    """

    name: str
    kind: str
    default: Any
    help: str
    check: str | None = "positive"
    length: int | None = None


SETTINGS: dict[str, Setting] = {}
"""The ``[analysis]`` keys, by name (:func:`register_setting`)."""


def register_setting(setting: Setting) -> Setting:
    """Add an ``[analysis]`` key to :data:`SETTINGS`.

    Parameters
    ----------
    setting : Setting
        The key.

    Returns
    -------
    Setting
        The same setting.

    Raises
    ------
    ValueError
        If the name is taken.
    """
    if setting.name in SETTINGS:
        raise ValueError(f"setting {setting.name!r} is already registered")
    SETTINGS[setting.name] = setting
    return setting


@dataclass(frozen=True)
class AnalysisSettings:
    """The study's ``[analysis]`` values; a missing key reads as its default.

    Parameters
    ----------
    values : tuple of (str, object)
        (name, value in SI) of the keys given.

    Raises
    ------
    InputError
        If a name is not in :data:`SETTINGS`.
    """

    values: tuple[tuple[str, Any], ...] = ()

    def __post_init__(self) -> None:
        for name, _ in self.values:
            if name not in SETTINGS:
                raise InputError("unknown analysis setting", key=name)

    def __getitem__(self, name: str) -> Any:
        for key, value in self.values:
            if key == name:
                return value
        return SETTINGS[name].default

    def given(self, name: str) -> bool:
        """Whether the study file gives a key.

        Parameters
        ----------
        name : str
            The key.

        Returns
        -------
        bool
            True when given (not defaulted).
        """
        return any(key == name for key, _ in self.values)

    def to_dict(self) -> dict[str, Any]:
        """The given values.

        Returns
        -------
        dict of str to object
            {name: value in SI}.
        """
        return dict(self.values)


register_setting(
    Setting(
        "speed",
        "speed",
        None,
        "Crank speed of the analyses (default: each variant's [operating] speed).",
    )
)
register_setting(
    Setting(
        "step",
        "angle",
        math.radians(1.0),
        "Crank-angle step of the cycle analyses; must divide 360 deg (default 1 deg).",
    )
)


# ---- analyses and figures ---------------------------------------------------------------------


class CaseContext:
    """One variant under evaluation, with its analysis session ``analysis`` (computed lazily,
    each analysis once).

    Parameters
    ----------
    subject : crankdyn.engine.model.Engine or crankdyn.torsion.model.TorsionModel
        The variant.
    settings : AnalysisSettings
        The study's ``[analysis]`` values.
    kind : str
        The base kind, ``"engine"`` (default) or ``"model"``.
    """

    def __init__(self, subject: Any, settings: AnalysisSettings, kind: str = "engine") -> None:
        self.subject = subject
        self.settings = settings
        self.kind = kind
        self._analysis: Analysis | None = None

    @property
    def analysis(self) -> Analysis:
        """The :class:`crankdyn.engine.session.Analysis` of the variant with the study's
        ``[analysis]`` settings (speed, crank-angle step, speed range and step, orders)."""
        if self._analysis is None:
            self._analysis = _session(self)
        return self._analysis


def _session(ctx: CaseContext) -> Analysis:
    from crankdyn.engine.session import Analysis, speed_grid
    from crankdyn.torsion.orders import fundamental_order, order_grid

    s = ctx.settings
    subject = ctx.subject
    model = subject.torsion if ctx.kind == "engine" else subject
    speeds = None
    if s["speed_range"] is not None or s["speed_step"] is not None:
        if s["speed_range"] is not None:
            low, high = s["speed_range"]
            if not high > low:
                raise InputError(
                    "the speed range is empty: its end is not above its start",
                    key="[analysis] speed_range",
                )
        elif model is not None and model.operating is not None:
            low, high = model.operating.low, model.operating.high
        else:
            low = high = None
        if low is not None:
            step = s["speed_step"]
            speeds = speed_grid(low, high) if step is None else speed_grid(low, high, step)
    orders = None
    if s.given("max_order"):
        cycle = subject.cycle if ctx.kind == "engine" else _model_cycle(subject)
        base = fundamental_order(cycle)
        orders = order_grid(base, s["max_order"], base, cycle)
        if model is not None and model.sources:
            from crankdyn.torsion.sources import default_orders

            # the engine's orders and those of the model's sources, up to max_order
            engine = bool(model.cylinder_dofs)
            orders = default_orders(model, cycle, engine=engine, last=s["max_order"])
    return Analysis(
        subject,
        speed=s["speed"],
        speeds=speeds,
        orders=orders,
        step=s["step"],
        speed_hint="[analysis] speed in the study file",
        speeds_hint="[analysis] speed_range in the study file",
    )


def _model_cycle(model: Any) -> str:
    spec = getattr(model, "excitation", None)
    return spec.cycle if spec is not None else "four-stroke"


@dataclass(frozen=True)
class Figure:
    """A named scalar figure of a case.

    Parameters
    ----------
    name : str
        The name used in study files (``"max_main_bearing_load"``).
    key : str
        The results-table column: SI value, unit in the key (``"max_main_bearing_load_N"``).
    label : str
        For tables and plots.
    unit : str
        Display unit (``"kN"``).
    function : callable
        ``function(ctx) -> float`` (SI; NaN when undefined for the variant).
    scale : float
        The factor from the SI value to the display unit (1e-3 for kN); default 1.
    better : str or None
        ``"min"`` or ``"max"`` when smaller or larger is better (the summary's best cases), or
        None.
    si_unit : str or None
        The unit of the SI value in the table (default ``unit`` when ``scale`` is 1).
    subjects : tuple of str
        The base kinds it applies to (``("engine",)``).
    description : str
        One line for ``crankdyn study --list``.

    Raises
    ------
    ValueError
        If ``better`` is not a sense of :data:`SENSES`, or a scaled figure has no
        ``si_unit``.
    """

    name: str
    key: str
    label: str
    unit: str
    function: Callable[[CaseContext], float] = field(repr=False)
    scale: float = 1.0
    better: str | None = None
    si_unit: str | None = None
    subjects: tuple[str, ...] = ("engine",)
    description: str = ""

    def __post_init__(self) -> None:
        if self.better is not None and self.better not in SENSES:
            raise ValueError(f"better must be one of {SENSES} or None")
        if self.si_unit is None:
            if self.scale != 1.0:
                raise ValueError("a scaled figure needs its si_unit")
            object.__setattr__(self, "si_unit", self.unit)

    @property
    def module(self) -> str:
        """The module that defines the figure (imported by workers before a case runs)."""
        return self.function.__module__

    def evaluate(self, ctx: CaseContext) -> float | None:
        """The figure of a case.

        Parameters
        ----------
        ctx : CaseContext
            The case.

        Returns
        -------
        float or None
            The figure in SI (:attr:`si_unit`); None when it is not finite.
        """
        value = float(self.function(ctx))
        return value if math.isfinite(value) else None


FIGURES: dict[str, Figure] = {}
"""The figures, by name (:func:`register_figure`)."""


def register_figure(figure: Figure) -> Figure:
    """Add a figure to :data:`FIGURES`.

    Parameters
    ----------
    figure : Figure
        The figure.

    Returns
    -------
    Figure
        The same figure.

    Raises
    ------
    ValueError
        If the name or the column key is taken.
    """
    if figure.name in FIGURES:
        raise ValueError(f"figure {figure.name!r} is already registered")
    if any(f.key == figure.key for f in FIGURES.values()):
        raise ValueError(f"figure column {figure.key!r} is already used")
    FIGURES[figure.name] = figure
    return figure


def _figure(
    name: str,
    key: str,
    label: str,
    unit: str,
    function: Callable[[CaseContext], float],
    *,
    scale: float = 1.0,
    si: str | None = None,
    better: str | None = None,
    description: str = "",
) -> Figure:
    return register_figure(
        Figure(
            name=name,
            key=key,
            label=label,
            unit=unit,
            function=function,
            scale=scale,
            si_unit=si,
            better=better,
            description=description or label,
        )
    )


# ---- engine figures (the session's kinematics, forces, bearing loads, torque) ------------


def torque_nonuniformity(max_torque: float, min_torque: float, mean_torque: float) -> float:
    """Torque non-uniformity (M_max - M_min)/M_mean (dimensionless; seed 000 section 2.4), NaN
    when the mean torque is zero."""
    if mean_torque == 0.0:
        return math.nan
    return (max_torque - min_torque) / mean_torque


_figure(
    "mean_torque",
    "mean_torque_Nm",
    "Mean indicated torque",
    "N·m",
    lambda c: c.analysis.torque.mean_torque,
    better="max",
)
_figure(
    "indicated_power",
    "indicated_power_W",
    "Indicated power",
    "kW",
    lambda c: c.analysis.torque.indicated_power,
    scale=1e-3,
    si="W",
    better="max",
)
_figure(
    "imep",
    "imep_Pa",
    "IMEP",
    "bar",
    lambda c: c.analysis.torque.imep,
    scale=1e-5,
    si="Pa",
    better="max",
    description="Indicated mean effective pressure",
)
_figure(
    "peak_pressure",
    "peak_pressure_Pa",
    "Peak cylinder pressure",
    "bar",
    lambda c: c.analysis.torque.peak_pressure,
    scale=1e-5,
    si="Pa",
    better="min",
)
_figure(
    "max_torque",
    "max_torque_Nm",
    "Max total torque",
    "N·m",
    lambda c: c.analysis.torque.max_torque,
)
_figure(
    "min_torque",
    "min_torque_Nm",
    "Min total torque",
    "N·m",
    lambda c: c.analysis.torque.min_torque,
)
_figure(
    "torque_nonuniformity",
    "torque_nonuniformity",
    "Torque non-uniformity (M_max − M_min)/M_mean",
    "",
    lambda c: torque_nonuniformity(
        c.analysis.torque.max_torque,
        c.analysis.torque.min_torque,
        c.analysis.torque.mean_torque,
    ),
    better="min",
)
_figure(
    "max_crank_pin_load",
    "max_crank_pin_load_N",
    "Max crank-pin load (largest of the throws)",
    "kN",
    lambda c: float(max(c.analysis.bearings().max_pin_load)),
    scale=1e-3,
    si="N",
    better="min",
)
_figure(
    "max_mean_crank_pin_load",
    "max_mean_crank_pin_load_N",
    "Mean crank-pin load (largest of the throws)",
    "kN",
    lambda c: float(max(c.analysis.bearings().mean_pin_load)),
    scale=1e-3,
    si="N",
    better="min",
)
_figure(
    "max_main_bearing_load",
    "max_main_bearing_load_N",
    "Max main-bearing load (largest of the bearings)",
    "kN",
    lambda c: float(max(c.analysis.bearings().max_bearing_load)),
    scale=1e-3,
    si="N",
    better="min",
)
_figure(
    "max_mean_main_bearing_load",
    "max_mean_main_bearing_load_N",
    "Mean main-bearing load (largest of the bearings)",
    "kN",
    lambda c: float(max(c.analysis.bearings().mean_bearing_load)),
    scale=1e-3,
    si="N",
    better="min",
)
_figure(
    "max_side_force",
    "max_side_force_N",
    "Max piston side force",
    "kN",
    lambda c: c.analysis.forces().max_side_force,
    scale=1e-3,
    si="N",
    better="min",
)
_figure(
    "max_rod_compression",
    "max_rod_compression_N",
    "Max rod compression",
    "kN",
    lambda c: c.analysis.forces().max_rod_compression,
    scale=1e-3,
    si="N",
    better="min",
)
_figure(
    "max_rod_tension",
    "max_rod_tension_N",
    "Max rod tension",
    "kN",
    lambda c: c.analysis.forces().max_rod_tension,
    scale=1e-3,
    si="N",
    better="min",
)
_figure(
    "mean_piston_speed",
    "mean_piston_speed_m_s",
    "Mean piston speed",
    "m/s",
    lambda c: c.analysis.kinematics().summary.mean_piston_speed,
    better="min",
)
_figure(
    "max_piston_speed",
    "max_piston_speed_m_s",
    "Max piston speed |v|",
    "m/s",
    lambda c: max(
        abs(c.analysis.kinematics().summary.max_velocity),
        abs(c.analysis.kinematics().summary.min_velocity),
    ),
    better="min",
)
_figure(
    "max_piston_acceleration",
    "max_piston_acceleration_m_s2",
    "Max piston acceleration |a|",
    "m/s²",
    lambda c: max(
        abs(c.analysis.kinematics().summary.max_acceleration),
        abs(c.analysis.kinematics().summary.min_acceleration),
    ),
    better="min",
)


# ---- balance and flywheel (crankdyn.engine.balance, crankdyn.engine.flywheel) -----------------

register_setting(
    Setting(
        "delta",
        "number",
        None,
        "Target degree of cyclic irregularity for the flywheel figures (default: the engine's "
        "[flywheel] delta or inertia).",
    )
)

BALANCE_ORDERS = (1, 2, 4, 6)


def _order(ctx: CaseContext, order: int) -> Any:
    return next(o for o in ctx.analysis.balance().orders if o.order == order)


def _nan_if_none(value: float | None) -> float:
    return math.nan if value is None else float(value)


def _free_force(n: int) -> Callable[[CaseContext], float]:
    return lambda c: _order(c, n).free_force


def _free_moment(n: int) -> Callable[[CaseContext], float]:
    return lambda c: _nan_if_none(_order(c, n).free_moment)


for _n in BALANCE_ORDERS:
    _figure(
        f"free_force_{_n}",
        f"free_force_{_n}_N",
        f"Free force, order {_n} (reciprocating masses)",
        "N",
        _free_force(_n),
        better="min",
        description=f"Largest free force of the reciprocating masses of order {_n} over a "
        "revolution",
    )
    _figure(
        f"free_moment_{_n}",
        f"free_moment_{_n}_Nm",
        f"Free moment, order {_n} (reciprocating masses)",
        "N·m",
        _free_moment(_n),
        better="min",
        description=f"Largest free moment of the reciprocating masses of order {_n} about the "
        "middle of the engine (needs [cylinders] pitch)",
    )
_figure(
    "rotating_free_force",
    "rotating_free_force_N",
    "Free force of the rotating masses and counterweights",
    "N",
    lambda c: c.analysis.balance().rotating.free_force,
    better="min",
)
_figure(
    "rotating_free_moment",
    "rotating_free_moment_Nm",
    "Free moment of the rotating masses and counterweights",
    "N·m",
    lambda c: _nan_if_none(c.analysis.balance().rotating.free_moment),
    better="min",
)
_figure(
    "first_order_free_moment",
    "first_order_free_moment_Nm",
    "First-order free moment, reciprocating and rotating",
    "N·m",
    lambda c: _nan_if_none(c.analysis.balance().first_order_total.free_moment),
    better="min",
)
_figure(
    "excess_work",
    "excess_work_J",
    "Largest excess work ΔE",
    "J",
    lambda c: c.analysis.flywheel(delta=c.settings["delta"]).excess_work,
    better="min",
    description="Energy swing of the torque curve (needs [flywheel] delta or inertia, or "
    "[analysis] delta)",
)
_figure(
    "excess_work_coefficient",
    "excess_work_coefficient",
    "Excess-work coefficient ξ = ΔE/(M_m Θ)",
    "",
    lambda c: _nan_if_none(c.analysis.flywheel(delta=c.settings["delta"]).excess_work_coefficient),
    better="min",
)
_figure(
    "flywheel_inertia",
    "flywheel_inertia_kgm2",
    "Flywheel inertia for the target δ",
    "kg·m²",
    lambda c: c.analysis.flywheel(delta=c.settings["delta"]).flywheel_inertia,
    better="min",
    description="Flywheel needed for the target degree of cyclic irregularity ([analysis] "
    "delta or [flywheel] delta)",
)
_figure(
    "cyclic_irregularity",
    "cyclic_irregularity",
    "Degree of cyclic irregularity δ",
    "",
    lambda c: c.analysis.flywheel(delta=c.settings["delta"]).speed_fluctuation,
    better="min",
    description="δ = (ω_max − ω_min)/ω_m with the engine's flywheel ([flywheel] inertia) or "
    "the one sized for the target δ",
)


# ---- torsional vibration (crankdyn.torsion) -----------------------------------------------------

NATURAL_FREQUENCY_MODES = (1, 2, 3)


def natural_frequency(modes: ModalResult, n: int) -> float:
    """The natural frequency of elastic mode ``n``; elastic modes are numbered from 1, a free
    model's rigid-body mode is 0 (:meth:`crankdyn.torsion.modal.ModalResult.index`).

    Parameters
    ----------
    modes : crankdyn.torsion.modal.ModalResult
        The model's modes.
    n : int
        1 for the first elastic mode.

    Returns
    -------
    float
        The frequency (Hz); NaN when the model has fewer modes.
    """
    if not 1 <= n <= int(modes.mode[-1]):
        return math.nan
    return float(modes.frequencies_hz[modes.index(n)])


def _natural_frequency_of(n: int) -> Callable[[CaseContext], float]:
    return lambda c: natural_frequency(c.analysis.modes, n)


for _n in NATURAL_FREQUENCY_MODES:
    register_figure(
        Figure(
            name=f"natural_frequency_{_n}",
            key=f"natural_frequency_{_n}_Hz",
            label=f"Natural frequency of elastic mode {_n}",
            unit="Hz",
            function=_natural_frequency_of(_n),
            subjects=("engine", "model"),
            description=f"Torsional natural frequency of the {_n}. elastic mode (engine: its "
            "[torsion] model)",
        )
    )


# ---- forced torsional response (crankdyn.torsion.response) --------------------------------------

register_setting(
    Setting(
        "speed_range",
        "list:speed",
        None,
        "Speed range [low, high] of the forced-response figures (default: the torsional "
        "model's [operating] speed_range).",
        length=2,
    )
)
register_setting(
    Setting(
        "speed_step",
        "speed",
        None,
        "Speed step of the forced-response figures (default 10 rpm, as the command line and the "
        "report).",
    )
)
register_setting(
    Setting(
        "max_order",
        "number",
        12.0,
        "Highest excitation order of the forced response (default 12; from the cycle's lowest "
        "order, 0.5 four-stroke, 1 two-stroke).",
    )
)
register_setting(
    Setting(
        "relative",
        "strings",
        None,
        "The two masses of the relative-angle figure (default: the first and the last mass "
        'of the torsional model, e.g. ["pulley", "flywheel"]).',
        check=None,
        length=2,
    )
)


def _relative_pair(ctx: CaseContext, model: Any) -> tuple[str, str]:
    pair = ctx.settings["relative"]
    if pair is None:
        names = model.mass_names
        return names[0], names[-1]
    return tuple(pair)


def max_relative_angle(ctx: CaseContext) -> float:
    """Largest synthesised (half-range) relative angle between the two masses over the speed
    range (rad)."""
    model = ctx.analysis.model
    a, b = _relative_pair(ctx, model)
    try:
        relative = ctx.analysis.relative_angle(a, b)
    except InputError as exc:
        raise InputError(exc.message, key="[analysis] relative", value=[a, b]) from None
    return float(relative.peak("synthesized").value)


def _model_shafts(ctx: CaseContext) -> list[tuple[str, str]]:
    """The model's own shafts (the damper couplings follow them in a response)."""
    model = ctx.analysis.model
    assert model is not None  # the response was computed: there is a model
    return [s.between for s in model.shafts]


def _largest_peak(result: Any, quantity: str, shafts: list[tuple[str, str]]) -> float:
    """The largest resolved peak of a per-shaft quantity over ``shafts``
    (:meth:`crankdyn.torsion.response.ResponseResult.peak`)."""
    return max(result.peak(quantity, shaft).value for shaft in shafts)


def max_shaft_torque(ctx: CaseContext) -> float:
    """Largest synthesised vibratory torque over the resolved speed range and the model's
    shafts (N m)."""
    return _largest_peak(ctx.analysis.response(), "synthesized_shaft_torque", _model_shafts(ctx))


def max_shaft_stress(ctx: CaseContext) -> float:
    """Largest synthesised nominal shear stress over the resolved speed range and the shafts
    with diameters (Pa)."""
    result = ctx.analysis.response()
    modulus = np.asarray(result.section_modulus)
    known = [s for s in _model_shafts(ctx) if np.isfinite(modulus[result.shaft_index(s)])]
    if not known:
        raise InputError(
            "no shaft of the torsional model has diameters (outer_diameter): no stress",
            key="max_shaft_stress",
        )
    return _largest_peak(result, "synthesized_shaft_stress", known)


def max_stress_ratio(ctx: CaseContext) -> float:
    """Largest synthesised stress over the permissible continuous stress tau_C of the rule
    check (IACS UR M68), over the speeds and the checked shafts (dimensionless)."""
    result = ctx.analysis.response()
    check: Any = result.rule_check  # a crankdyn.torsion.rules.RuleCheck
    if check is None:
        raise InputError(
            f"the torsional model has no [rules] ({ref('torsion-file')}): no rule check",
            key="max_stress_ratio",
        )
    return float(np.max(np.asarray(check.stress) / np.asarray(check.tau_c)))


def max_damper_power(ctx: CaseContext) -> float:
    """Largest power dissipated in a damper over the speed range (W)."""
    result = ctx.analysis.response()
    if result.damper_power is None:
        raise InputError("the torsional model has no damper", key="max_damper_power")
    return float(result.peak("damper_power").value)


for _name, _key, _label, _unit, _function, _scale, _si in (
    (
        "max_relative_angle",
        "max_relative_angle_rad",
        "Largest relative angle (synthesised)",
        "mrad",
        max_relative_angle,
        1e3,
        "rad",
    ),
    (
        "max_free_end_amplitude",
        "max_free_end_amplitude_rad",
        "Largest amplitude of the first mass (synthesised)",
        "mrad",
        lambda c: float(
            c.analysis.response()
            .peak("synthesized_amplitude", c.analysis.model.mass_names[0])
            .value
        ),
        1e3,
        "rad",
    ),
    (
        "max_shaft_torque",
        "max_shaft_torque_Nm",
        "Largest vibratory shaft torque (synthesised)",
        "N·m",
        max_shaft_torque,
        1.0,
        "N·m",
    ),
    (
        "max_shaft_stress",
        "max_shaft_stress_Pa",
        "Largest shaft shear stress (synthesised)",
        "MPa",
        max_shaft_stress,
        1e-6,
        "Pa",
    ),
    (
        "max_stress_ratio",
        "max_stress_ratio",
        "Largest shaft stress / permissible τ_C (IACS UR M68)",
        "",
        max_stress_ratio,
        1.0,
        "",
    ),
    (
        "max_damper_power",
        "max_damper_power_W",
        "Largest damper power",
        "W",
        max_damper_power,
        1.0,
        "W",
    ),
):
    register_figure(
        Figure(
            name=_name,
            key=_key,
            label=_label,
            unit=_unit,
            function=_function,
            scale=_scale,
            si_unit=_si,
            better="min",
            subjects=("engine", "model"),
            description=_label + " over the speed range (forced torsional response)",
        )
    )
