"""``crankdyn torsion transient MODEL --event KIND -p KEY=VALUE ...``: one transient event
(:mod:`crankdyn.torsion.event_run`), its key figures, its verdicts (the TVC's checks,
:func:`crankdyn.tvc.events.judge_event`) and its time histories.

The event's keys are those of a ``[[tvc.event]]`` table (:mod:`crankdyn.io.event_spec`), given
as ``-p KEY=VALUE``: quantities with their units (``-p "torque=60 kN*m"``), a bare speed in
rpm as everywhere on the command line, a list comma-separated (``-p speeds=350,0``,
``-p "between=coupling secondary,pinion"``). The line runs with the session's model, its
excitation and orders (the engine's and the sources' harmonic torques), at ``--speed``.
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING, Any

from crankdyn.errors import InputError

if TYPE_CHECKING:
    from crankdyn.cli.writer import Output
    from crankdyn.session import Analysis

__all__ = ["event_params", "run_event"]

_NUMBER = re.compile(r"^[-+]?(\d+(\.\d*)?|\.\d+)([eE][-+]?\d+)?$")


def _value(text: str, speed: bool) -> Any:
    """A parameter's text as a TOML value: true/false, a whole number, a number, a list
    (comma-separated) of those, or the text; a bare number for a speed in rpm."""
    text = text.strip()
    if text.lower() in ("true", "false"):
        return text.lower() == "true"
    if "," in text:
        return [_value(part, speed) for part in text.split(",")]
    if _NUMBER.match(text):
        if speed:
            return f"{text} rpm"
        return int(text) if re.fullmatch(r"[-+]?\d+", text) else float(text)
    return text


def event_params(kind: str, params: tuple[str, ...]) -> dict[str, Any]:
    """The ``-p KEY=VALUE`` pairs of an event as a table (:mod:`crankdyn.io.event_spec`).

    Parameters
    ----------
    kind : str
        The event's kind (``--event``).
    params : tuple of str
        The ``KEY=VALUE`` texts.

    Returns
    -------
    dict
        {"kind": kind, key: value}.

    Raises
    ------
    InputError
        For a pair without ``=`` or a key given twice (key ``-p``).

    Examples
    --------
    >>> event_params("clutch", ("speeds=350,0", "torque=60 kN*m", "rise_time=0.5"))
    {'kind': 'clutch', 'speeds': ['350 rpm', '0 rpm'], 'torque': '60 kN*m', 'rise_time': 0.5}
    """
    from crankdyn.io.event_spec import SPEED_KEYS

    out: dict[str, Any] = {"kind": kind}
    for pair in params:
        key, sep, text = pair.partition("=")
        key = key.strip()
        if not sep or not key:
            raise InputError("expected KEY=VALUE", key="-p", value=pair)
        if key in out:
            raise InputError(f"{key} is given twice", key="-p", value=pair)
        if key in ("between", "at", "drive_at", "name", "file", "ice_class", "severity"):
            out[key] = text.strip()
        else:
            out[key] = _value(text, key in SPEED_KEYS)
    return out


def _judged(session: Analysis, model: Any, result: Any) -> Any:
    """The run with the verdict rows of the installation's checks (the TVC's one evaluation,
    :func:`crankdyn.tvc.events.judge_event`); as it is without a rated speed."""
    from crankdyn.tvc.analysis import rated_speed
    from crankdyn.tvc.events import judge_event

    try:
        rated = rated_speed(model, session.engine)
    except InputError:
        return result
    return judge_event(model, result, session.tvc_spec, rated)


def run_event(
    session: Analysis,
    kind: str,
    params: tuple[str, ...],
    *,
    speed: float | None,
    duration: float | None,
    out: Output,
    plot_path: str | None,
    force: bool,
    no_fail: bool = False,
) -> int:
    """Run one event on the session's model and write its summary, verdicts and histories.

    Parameters
    ----------
    session : crankdyn.session.Analysis
        The session (its model, excitation and orders).
    kind : str
        The event's kind.
    params : tuple of str
        Its ``KEY=VALUE`` pairs.
    speed : float or None
        The speed before the event (rad/s); default the session's, where it has one.
    duration : float or None
        The run's duration (s); default the event's.
    out : crankdyn.cli.writer.Output
        The writer.
    plot_path : str or None
        The figure file, or None.
    force : bool
        Whether existing files may be replaced.
    no_fail : bool
        ``--no-fail``: status 0 whatever the verdict.

    Returns
    -------
    int
        The exit status: 1 where a verdict of the event failed (unless ``no_fail``), else 0
        (:func:`crankdyn.cli.common.verdict_status` of the result's summary).
    """
    from crankdyn.cli.common import save_figure, verdict_status
    from crankdyn.cli.writer import summary_blocks
    from crankdyn.io.event_spec import event_from_table
    from crankdyn.torsion.event_run import event_response
    from crankdyn.torsion.events import ClutchEngagement, SpeedChange

    model = session.loaded_model
    if model is None:
        raise InputError("the event needs a torsional model", key="MODEL_OR_ENGINE")
    event = event_from_table(event_params(kind, params), model=model, section="--event")
    excitation = None
    if not isinstance(event, ClutchEngagement):
        try:
            excitation = session.excitation()
        except InputError:
            excitation = None  # a model without cylinders or sources: the event alone
    if speed is None and not isinstance(event, (ClutchEngagement, SpeedChange)):
        speed = session.speed
    result = session.with_input_warnings(
        event_response(
            model,
            event,
            speed=speed,
            duration=duration,
            excitation=excitation,
            orders=session.orders if excitation is not None else None,
        )
    )
    result = _judged(session, model, result)
    out.write(blocks=summary_blocks(result), json_data=result, csv_text=result.to_csv())
    if plot_path:
        save_figure(result.plot(), plot_path, force)
    return verdict_status(result.summary().passed, no_fail)
