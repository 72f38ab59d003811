"""Running one case, wherever it runs: in the main process, a local worker process or a Dask
worker.

:func:`evaluate_case` never raises for a bad variant or a failing analysis: it returns a record
with ``status = "failed"`` and the error on one line (an :class:`~crankdyn.errors.InputError`'s
own text, else the exception's type and message), so the study goes on. Only interrupts
(KeyboardInterrupt, SystemExit) pass through.
"""

from __future__ import annotations

import atexit
import dataclasses
import hashlib
import importlib
import math
import os
import shutil
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from crankdyn.errors import InputError
from crankdyn.io.study_file import parse_base
from crankdyn.study.docpath import KeyPath, apply_values
from crankdyn.study.figures import FIGURES, AnalysisSettings, CaseContext, case_verdicts

__all__ = [
    "ANALYSIS_MODULES",
    "Payload",
    "evaluate_case",
    "import_analyses",
    "prepare_worker",
    "verdicts_of_record",
    "warm_up",
]

ANALYSIS_MODULES = (
    "crankdyn.session",
    "crankdyn.engine.forces",
    "crankdyn.engine.torque",
    "crankdyn.engine.bearings",
    "crankdyn.crank.indicated",
    "crankdyn.torsion.excitation",
    "numpy.ma",  # numpy's unique() imports it at its first call (the indicated work's)
)
"""The analyses a study case runs, which the command line imports only when a case first needs
them: imported before the local pool's workers are forked (each would otherwise import them at
its first case, about 0.05 s apiece) and by the workers' warm-up (fork server, Dask)."""


@dataclass(frozen=True)
class Payload:
    """What every case of a study shares, sent once to each worker.

    Parameters
    ----------
    kind : str
        The base kind (:data:`crankdyn.study.spec.BASE_KINDS`).
    document : dict
        The parsed base document.
    source : str
        How the base file is named in messages.
    base_dir : str or None
        The folder its relative paths resolve against, when the files are not shipped.
    remove : tuple of KeyPath
        Keys deleted from the document before the parameters are applied.
    targets : tuple of (str, tuple of KeyPath)
        (parameter key, the paths it sets).
    bundles : tuple of str
        The keys of the parameters whose values are bundles (dicts of key path text to value:
        :attr:`crankdyn.study.spec.Parameter.bundle`).
    verdict_rows : bool
        Keep every case's verdict rows in its record (:attr:`crankdyn.study.spec.StudySpec.
        verdict_rows`).
    settings : crankdyn.study.figures.AnalysisSettings
        The ``[analysis]`` values.
    figures : tuple of str
        The figures to compute.
    modules : tuple of str
        The modules defining the figures (imported before a case runs).
    files : tuple of (str, bytes)
        (relative path, contents) of the files the document names, for remote workers.
    """

    kind: str
    document: dict[str, Any]
    source: str
    base_dir: str | None
    remove: tuple[KeyPath, ...]
    targets: tuple[tuple[str, tuple[KeyPath, ...]], ...]  # (parameter key, paths it sets)
    settings: AnalysisSettings
    figures: tuple[str, ...]
    modules: tuple[str, ...]  # modules defining the figures (imported before a case runs)
    files: tuple[tuple[str, bytes], ...] = ()  # (relative path, bytes) for remote workers
    bundles: tuple[str, ...] = ()  # parameters whose values set several keys each
    verdict_rows: bool = False  # keep every case's verdict rows in its record

    def assignments(self, params: dict[str, Any]) -> dict[KeyPath, Any]:
        """The document values a case sets.

        Parameters
        ----------
        params : dict of str to object
            Parameter key -> value as written into the document (a bundle: a dict of key path
            text to value).

        Returns
        -------
        dict of KeyPath to object
            Every key path the case sets, with its value (None: the key is removed,
            :func:`crankdyn.study.docpath.apply_values`).
        """
        values: dict[KeyPath, Any] = {}
        for key, paths in self.targets:
            if key not in params:  # left as the base has it (a design search's base design)
                continue
            value = params[key]
            if key in self.bundles:
                values.update((p, value[p.text]) for p in paths if p.text in value)
            else:
                values.update(dict.fromkeys(paths, value))
        return values


def warm_up() -> str:
    """Import the analyses and build the unit registry in this process (run on every Dask
    worker before the first case).

    Returns
    -------
    str
        The crankdyn version, checked against the client's.
    """
    import crankdyn.study.run.preload  # noqa: F401

    import_analyses()
    from crankdyn import __version__

    return __version__


def prepare_worker(payload: Payload) -> None:
    """Import the modules that define the payload's figures (a worker started by spawn,
    forkserver or on a cluster knows only the built-in ones until then).

    Parameters
    ----------
    payload : Payload
        The study's shared part.
    """
    for module in payload.modules:
        importlib.import_module(module)


def import_analyses() -> None:
    """Import :data:`ANALYSIS_MODULES` in this process."""
    for module in ANALYSIS_MODULES:
        importlib.import_module(module)


_MATERIALISED: dict[str, str] = {}


def _base_dir(payload: Payload) -> Path | None:
    """The folder the base document's relative paths resolve against: its own folder, or on a
    worker that received the files with the payload, a temporary copy of them (made once per
    worker process and removed at its exit)."""
    if not payload.files:
        return None if payload.base_dir is None else Path(payload.base_dir)
    digest = hashlib.sha256()
    for text, data in payload.files:
        digest.update(text.encode("utf-8") + b"\0" + hashlib.sha256(data).digest())
    key = digest.hexdigest()
    if key not in _MATERIALISED:
        root = Path(tempfile.mkdtemp(prefix="crankdyn-study-"))
        atexit.register(shutil.rmtree, root, True)
        # deep enough that "../x" paths stay inside the temporary folder
        depth = max(os.path.normpath(text).split(os.sep).count("..") for text, _ in payload.files)
        base = root.joinpath(*(["base"] * (depth + 1)))
        for text, data in payload.files:
            target = Path(os.path.normpath(base / text))
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_bytes(data)
        _MATERIALISED[key] = str(base)
    return Path(_MATERIALISED[key])


def _one_line(text: str) -> str:
    return " ".join(str(text).split())


def evaluate_case(payload: Payload, case_id: str, params: dict[str, Any]) -> dict[str, Any]:
    """Apply a case to the base document, parse it with the base file's reader and compute the
    figures (module docstring: a failing case is recorded, not raised).

    Parameters
    ----------
    payload : Payload
        The study's shared part.
    case_id : str
        The case's id (:func:`crankdyn.study.cases.case_id`).
    params : dict of str to object
        Parameter key -> value as written into the document.

    Returns
    -------
    dict of str to object
        The journal record (:mod:`crankdyn.study.run.journal`): ``case_id``, ``params``,
        ``status`` (``"ok"`` or ``"failed"``), ``figures`` (SI, None where not finite),
        ``error`` (one line or None) and ``elapsed_s`` (s); with ``payload.verdict_rows``
        also ``verdicts``, the case's verdict rows (:func:`verdicts_of_record` reads them).
    """
    start = time.perf_counter()
    figures: dict[str, float | None] = {}
    rows: list[dict[str, Any]] = []
    error = None
    try:
        prepare_worker(payload)
        document = apply_values(payload.document, payload.assignments(params), payload.remove)
        base_dir = _base_dir(payload)
        subject = parse_base(payload.kind, document, file=payload.source, base_dir=base_dir)
        ctx = CaseContext(subject, payload.settings, payload.kind)
        for name in payload.figures:
            figures[name] = FIGURES[name].evaluate(ctx)
        if payload.verdict_rows:  # the session's analyses, computed once for the figures
            rows = [_verdict_record(v) for v in case_verdicts(ctx, payload.figures)]
    except InputError as exc:
        error = _one_line(str(exc))
    except Exception as exc:  # an analysis failing on a variant: recorded, the study goes on
        error = _one_line(f"{type(exc).__name__}: {exc}") or type(exc).__name__
    elapsed = time.perf_counter() - start
    record: dict[str, Any] = {
        "case_id": case_id,
        "params": params,
        "status": "failed" if error else "ok",
        "figures": {} if error else {k: _finite(v) for k, v in figures.items()},
        "error": error,
        "elapsed_s": round(elapsed, 6),
    }
    if payload.verdict_rows and not error:
        record["verdicts"] = rows
    return record


_NUMBERS = ("worst", "limit", "speed", "margin", "error_bound")
"""The float fields of a verdict row, written as text where not finite (the journal is strict
JSON)."""


def _verdict_record(verdict: Any) -> dict[str, Any]:
    """A verdict row (:class:`crankdyn.summary.Verdict`) as a JSON object."""
    row = dataclasses.asdict(verdict)
    for key in _NUMBERS:
        value = row.get(key)
        if isinstance(value, float) and not math.isfinite(value):
            row[key] = repr(value)  # "nan", "inf", "-inf"
    return row


def verdicts_of_record(record: dict[str, Any]) -> tuple[Any, ...] | None:
    """The verdict rows a case's record keeps (:attr:`Payload.verdict_rows`), or None when it
    keeps none (a study that does not ask for them, a failed case, a journal of an earlier
    version).

    Parameters
    ----------
    record : dict
        A journal record (:func:`evaluate_case`).

    Returns
    -------
    tuple of crankdyn.summary.Verdict or None
        The rows, as the case's analysis gave them.

    Examples
    --------
    >>> import json, math
    >>> from crankdyn.summary import Verdict
    >>> rows = [Verdict("shaft", "normal", "stress", 2e7, 5e7, "Pa", True, "rule"),
    ...         Verdict("gear", "normal", "reversal", math.nan, 1.0, "", False, "rule"),
    ...         Verdict("span", "ice", "peak", 4e7, 5e7, "Pa", True, "rule", error_bound=math.inf)]
    >>> text = json.dumps({"verdicts": [_verdict_record(v) for v in rows]}, allow_nan=False)
    >>> back = verdicts_of_record(json.loads(text))
    >>> back[0] == rows[0], back[0].margin, math.isnan(back[1].worst), back[1].passed
    (True, 0.6, True, False)
    >>> back[2] == rows[2], back[2].undecided
    (True, True)
    """
    from crankdyn.summary import Verdict

    rows = record.get("verdicts")
    if rows is None:
        return None
    out = []
    for row in rows:
        values = dict(row)
        for key in _NUMBERS:  # (a record of an earlier version may lack error_bound)
            if isinstance(values.get(key), str):
                values[key] = float(values[key])
        out.append(Verdict(**values))
    return tuple(out)


def _finite(value: float | None) -> float | None:
    return value if value is not None and math.isfinite(value) else None
