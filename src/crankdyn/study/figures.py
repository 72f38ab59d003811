"""The figures a study can keep per case: the key figures of the session's analyses.

A *figure* is one number of one variant of the base engine (or model): mean torque, the largest
main-bearing load, a natural frequency... It is a key figure declared once by its result class
(:mod:`crankdyn.summary`: a scalar field or a figure of its ``FIGURES``), with the label, unit
and value every other front end shows; :data:`FIGURES` holds, by name, the numeric key figures
of every analysis of :data:`crankdyn.session.ANALYSES` (:func:`register_figure` adds others).
A figure's function takes a :class:`CaseContext` (the variant ``ctx.subject``, the study's
``[analysis]`` settings ``ctx.settings``) and returns its value (NaN when undefined) from the
case's analysis session ``ctx.analysis`` (:class:`crankdyn.session.Analysis`, with the study's
settings: speed, crank-angle step, speed range and step, highest order, the flywheel's target,
the relative angle's masses), so a study's figure is the same number as the report's and the
command line's for the same variant.

A figure defined in any importable module works on every worker: the worker imports the module
that defines each figure before running a case.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from crankdyn.defaults import DEFAULTS
from crankdyn.errors import InputError
from crankdyn.session import ANALYSES, Analysed

if TYPE_CHECKING:
    from crankdyn.session import Analysis
    from crankdyn.summary import FigureSpec, Verdict

__all__ = [
    "FIGURES",
    "SETTINGS",
    "TVC",
    "TVC_FIGURES",
    "AnalysisSettings",
    "CaseContext",
    "Figure",
    "Setting",
    "case_verdicts",
    "figures_markdown",
    "reads_whole_tvc",
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
        DEFAULTS["step"].value,
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
        """The :class:`crankdyn.session.Analysis` of the variant with the study's
        ``[analysis]`` settings (speed, crank-angle step, speed range and step, orders)."""
        if self._analysis is None:
            self._analysis = _session(self)
        return self._analysis


def reads_whole_tvc(figures: Sequence[str]) -> bool:
    """Whether figures read the whole TVC's verdict rows (``worst_margin``, ``failed_rows``:
    every condition's) rather than the normal-firing condition's.

    Parameters
    ----------
    figures : sequence of str
        Names of study figures.

    Returns
    -------
    bool
        True when one of them is a whole-TVC figure.

    Examples
    --------
    >>> reads_whole_tvc(["failed_rows"]), reads_whole_tvc(["condition_passed"])
    (True, False)
    """
    return "worst_margin" in figures or "failed_rows" in figures


def case_verdicts(ctx: CaseContext, figures: Sequence[str]) -> tuple[Verdict, ...]:
    """The verdict rows a case's figures read: every condition's (the whole TVC,
    :meth:`crankdyn.session.Analysis.tvc`) when they include ``worst_margin`` or
    ``failed_rows``, else the normal-firing condition's (:meth:`crankdyn.session.Analysis.
    judged`; none without a rule check). The session's analyses: computed once for the figures
    and the rows.

    Parameters
    ----------
    ctx : CaseContext
        The case.
    figures : sequence of str
        The names of the figures the study computes.

    Returns
    -------
    tuple of crankdyn.summary.Verdict
        The rows.
    """
    if reads_whole_tvc(figures):
        return tuple(ctx.analysis.tvc().verdicts)
    judged = ctx.analysis.judged()
    return () if judged is None else tuple(judged.verdicts)


def _session(ctx: CaseContext) -> Analysis:
    """The variant's analysis session with the study's ``[analysis]`` settings; every default
    the study does not set is the session's own (:data:`crankdyn.defaults.DEFAULTS`)."""
    from crankdyn.session import Analysis

    s = ctx.settings
    try:
        return Analysis(
            ctx.subject,
            speed=s["speed"],
            speed_range=s["speed_range"],
            speed_step=s["speed_step"],
            max_order=s["max_order"] if s.given("max_order") else None,
            step=s["step"],
            delta=s["delta"],
            relative=s["relative"],
            barred_band=s["barred_band"],
        )
    except InputError as exc:
        if exc.key in ("speed_range", "speed_step", "speed"):
            raise InputError(exc.message, key=f"[analysis] {exc.key}", value=exc.value) from None
        raise


def _model_cycle(model: Any) -> str:
    spec = getattr(model, "excitation", None)
    return spec.cycle if spec is not None else "four-stroke"


register_setting(
    Setting(
        "delta",
        "number",
        None,
        "Target degree of cyclic irregularity for the flywheel figures (default: the engine's "
        "[flywheel] delta or inertia).",
    )
)

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
        DEFAULTS["max_order"].value,
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


@dataclass(frozen=True)
class Figure:
    """A named scalar figure of a case.

    Parameters
    ----------
    name : str
        The name used in study files (``"max_main_bearing_load"``).
    key : str
        The results-table column, the unit in the key (``"max_main_bearing_load_N"``): the
        key figure's key.
    label : str
        For tables and plots.
    unit : str
        The unit of the value (the key's).
    function : callable
        ``function(ctx) -> float`` in ``unit`` (NaN when undefined for the variant).
    better : str or None
        ``"min"`` or ``"max"`` when smaller or larger is better (the summary's best cases), or
        None.
    subjects : tuple of str
        The base kinds it applies to (``("engine",)``).
    description : str
        One line for ``crankdyn study --list``.

    Raises
    ------
    ValueError
        If ``better`` is not a sense of :data:`SENSES`.
    """

    name: str
    key: str
    label: str
    unit: str
    function: Callable[[CaseContext], float] = field(repr=False)
    better: str | None = None
    subjects: tuple[str, ...] = ("engine",)
    description: str = ""

    def __post_init__(self) -> None:
        if self.better is not None and self.better not in SENSES:
            raise ValueError(f"better must be one of {SENSES} or None")

    @property
    def si_unit(self) -> str:
        """The unit of the values in the results table (the key's)."""
        return self.unit

    @property
    def module(self) -> str:
        """The module that defines the figure (imported by workers before a case runs)."""
        return self.function.__module__

    def display(self, values: Any) -> tuple[float, str]:
        """(factor, unit) that show ``values`` (in :attr:`unit`) in one engineering unit, as
        every front end shows numbers (:func:`crankdyn.display.engineering_unit`).

        Parameters
        ----------
        values : array_like
            The figure's values (in :attr:`unit`).

        Returns
        -------
        factor : float
            From :attr:`unit` to the display unit.
        unit : str
            The display unit.
        """
        from crankdyn.display import engineering_unit

        arr = np.asarray(values, dtype=float)
        finite = np.abs(arr[np.isfinite(arr)])
        shown, factor = engineering_unit(float(finite.max()) if finite.size else 0.0, self.unit)
        return factor, shown

    def evaluate(self, ctx: CaseContext) -> float | None:
        """The figure of a case.

        Parameters
        ----------
        ctx : CaseContext
            The case.

        Returns
        -------
        float or None
            The figure in :attr:`unit`; None when it is not finite.
        """
        try:
            value = float(self.function(ctx))
        except InputError as exc:
            raise _study_error(exc) from None
        return value if math.isfinite(value) else None


_SETTING_KEYS = {
    "speeds": "speed_range",
    "speed_range": "speed_range",
    "speed_step": "speed_step",
    "relative": "relative",
    "delta": "delta",
    "step": "step",
    "max_order": "max_order",
}
"""The session's keywords that are [analysis] keys of a study file (the errors name the key as
the study file writes it)."""


def _study_error(exc: InputError) -> InputError:
    """An error of the session in the study file's words: a missing speed names
    ``[analysis] speed``; a setting's key is written ``[analysis] <key>``."""
    if exc.key == "speed" and exc.message.startswith("no speed"):
        return InputError(
            "no speed: give [analysis] speed in the study file or [operating] speed in the "
            "engine file",
            file=exc.file,
        )
    if exc.key in _SETTING_KEYS and exc.file is None:
        extra: dict[str, Any] = {"value": exc.value} if exc.has_value else {}
        return InputError(exc.message, key=f"[analysis] {_SETTING_KEYS[exc.key]}", **extra)
    return exc


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


def _figure(analysed: Analysed, spec: FigureSpec, description: str) -> Figure:
    """The study figure of a result's declared figure (its name, key, label, unit and sense)."""
    return Figure(
        name=spec.name,
        key=spec.key,
        label=spec.label,
        unit=spec.unit,
        function=_reader(analysed, spec),
        better=spec.better,
        subjects=analysed.subjects,
        description=description,
    )


def _reader(analysed: Analysed, spec: FigureSpec) -> Callable[[CaseContext], float]:
    """``f(ctx)``: the key figure ``spec`` of the case's analysis, NaN where it does not
    apply."""

    def value(ctx: CaseContext) -> float:
        result = analysed.of(ctx.analysis)
        got = None if result is None else spec.value(result)
        if (got is None or got[0] is None) and spec.unavailable:
            raise InputError(spec.unavailable, key=spec.name)
        return math.nan if got is None or got[0] is None else float(got[0])

    return value


def _register_analyses() -> None:
    """Every numeric key figure of the session's analyses (:data:`crankdyn.session.ANALYSES`),
    each once: a key two analyses share (the speed, the peak pressure) is the same quantity
    (the same label and unit: checked), kept from the first."""
    labels: dict[str, tuple[str, str]] = {}
    for analysed in ANALYSES:
        for spec in analysed.result_class().figure_specs():
            known = labels.get(spec.key)
            if known is not None:
                if known != (spec.label, spec.unit):
                    raise ValueError(f"key figure {spec.key!r} is declared twice differently")
                continue
            labels[spec.key] = (spec.label, spec.unit)
            register_figure(_figure(analysed, spec, spec.description or spec.label))


_register_analyses()


# ---- the whole TVC (every condition, the passages): the design search's figures ---------------

TVC = Analysed("tvc", "crankdyn.tvc.result.TvcResult", ("engine", "model"))
"""The session's whole TVC (:meth:`crankdyn.session.Analysis.tvc`: every running condition and
the passages through the barred ranges, as ``crankdyn tvc`` writes it); its declared figures
:data:`TVC_FIGURES` are study figures."""
TVC_FIGURES = ("worst_margin", "failed_rows", "barred_width_in_band")
"""The TVC's key figures kept as study figures (declared by :class:`crankdyn.tvc.TvcResult`;
``barred_width_in_band`` with the setting ``barred_band``, which the session hands to the TVC's
settings)."""

register_setting(
    Setting(
        "barred_band",
        "list:speed",
        None,
        "Speed band [low, high] for the figure barred_width_in_band (a design search's "
        "constraint: no barred speed range inside it).",
        length=2,
    )
)


def _register_tvc() -> None:
    """:data:`TVC_FIGURES`."""
    for spec in TVC.result_class().figure_specs():
        if spec.name in TVC_FIGURES:
            own = spec.description not in ("", spec.label)
            register_figure(
                _figure(
                    TVC,
                    spec,
                    spec.description
                    if own
                    else "over every condition of crankdyn tvc (normal firing, each misfire, "
                    "damper out of order, the passages)",
                )
            )


_register_tvc()


def figures_markdown() -> str:
    """The table of every figure of :data:`FIGURES` as docs/study-file.md lists it (one row per
    figure, grouped by the analysis that declares it), generated from the declarations so the
    page never falls behind them.

    Returns
    -------
    str
        A Markdown table: figure, column (the results table's key, SI), better, what.
    """
    owner: dict[str, str] = {}
    for analysed in (*ANALYSES, TVC):
        for spec in analysed.result_class().figure_specs():
            owner.setdefault(spec.name, analysed.name)
    lines = ["| figure | column | analysis | better | what |", "|---|---|---|---|---|"]
    for name, f in FIGURES.items():
        if not f.module.startswith("crankdyn."):
            continue
        what = f.label if f.description in ("", f.label) else f"{f.label}: {f.description}"
        what = what.replace("|", "\\|")
        lines.append(
            f"| `{name}` | `{f.key}` | {owner.get(name, '')} | {f.better or ''} | {what} |"
        )
    return "\n".join(lines) + "\n"
