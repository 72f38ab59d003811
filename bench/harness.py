"""The benchmark harness: cases, contenders, timing, agreement checks and the results table.

A :class:`Case` is one row group of the table: a problem (e.g. "free chain, N = 1000") solved by
crankdyn and by one or more peers (:class:`Contender`). Every contender is called once as a
warm-up (its output is kept for the agreement check; imports, JIT compilation and caches happen
here), then ``repeats`` more times under :func:`time.perf_counter`; the table reports the median.
A case with ``interleave`` set times its contenders in turn (A B, B A, A B, ...: every round
calls each once, the order reversed from one round to the next), so that a change in the
machine's load during the run reaches all of them alike (the whole-process cases, old version
against new).
Garbage collection runs before, and is disabled during, each timed call (as :mod:`timeit` does).
The agreement check compares the peers' outputs with crankdyn's and raises
:class:`AgreementError` (the run stops, loudly) when a deviation exceeds the case's tolerance.
"""

from __future__ import annotations

import gc
import statistics
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

__all__ = [
    "AgreementError",
    "Case",
    "CaseResult",
    "Contender",
    "Deviation",
    "Target",
    "Timing",
    "run_case",
]

CRANKDYN = "crankdyn"


class AgreementError(AssertionError):
    """A peer's result deviates from crankdyn's by more than the case allows."""


@dataclass(frozen=True)
class Contender:
    """One implementation of a case: ``run()`` is the timed call; its return value goes to the
    case's ``check``. ``missing`` says why the contender cannot run (peer not installed)."""

    name: str
    run: Callable[[], Any] | None
    missing: str | None = None
    note: str = ""


@dataclass(frozen=True)
class Deviation:
    """Largest deviation of one peer's result from crankdyn's, and the tolerance."""

    value: float
    tolerance: float
    what: str  # e.g. "relative, frequencies"

    @property
    def ok(self) -> bool:
        return self.value <= self.tolerance


@dataclass(frozen=True)
class Target:
    """A speed target: crankdyn at least ``ratio`` times faster than ``peer`` (ratio 1.0: not
    slower; ratio 0.5: within 2x of it), or, with ``peer`` None, crankdyn's median under
    ``seconds``."""

    peer: str | None
    ratio: float
    text: str
    seconds: float | None = None


@dataclass(frozen=True)
class Case:
    """A benchmark case (see the module docstring).

    ``check(outputs)`` receives {contender name: warm-up output} (crankdyn's always there) and
    returns {peer name: Deviation}; it must also raise :class:`AgreementError` if crankdyn's own
    result fails an independent check (identity, closed form).
    """

    key: str
    title: str
    size: str
    contenders: tuple[Contender, ...]
    check: Callable[[dict[str, Any]], dict[str, Deviation]] | None = None
    targets: tuple[Target, ...] = ()
    repeats: int = 7
    notes: tuple[str, ...] = ()
    extra: Callable[[Any], dict[str, Any]] | None = None  # figures from crankdyn's output
    interleave: bool = False  # time the contenders in turn, round by round (module docstring)


@dataclass(frozen=True)
class Timing:
    name: str
    median: float | None  # s
    runs: int
    missing: str | None = None
    note: str = ""


@dataclass(frozen=True)
class CaseResult:
    case: Case
    timings: dict[str, Timing]
    deviations: dict[str, Deviation] = field(default_factory=dict)
    extra: dict[str, Any] = field(default_factory=dict)  # e.g. peak memory of a process case

    @property
    def crankdyn(self) -> Timing:
        return self.timings[CRANKDYN]

    def ratio(self, peer: str) -> float | None:
        """Peer time over crankdyn time (how many times crankdyn is faster)."""
        mine, theirs = self.crankdyn.median, self.timings[peer].median
        if mine is None or theirs is None or mine <= 0.0:
            return None
        return theirs / mine

    def target_met(self, target: Target) -> bool | None:
        if target.peer is None:
            mine = self.crankdyn.median
            return None if mine is None else mine < float(target.seconds)
        ratio = self.ratio(target.peer)
        return None if ratio is None else ratio >= target.ratio


def _time(run: Callable[[], Any], repeats: int, budget: float) -> tuple[Any, float, int]:
    """Warm-up call (output kept), then up to ``repeats`` timed calls; stops early once the
    timed calls have used ``budget`` seconds (at least three calls when a call is quicker than
    the budget). Returns (output, median seconds, timed calls). ``repeats`` 0 (the tests' smoke
    runs): the single call's time, warm-up included."""
    start = time.perf_counter()
    output = run()
    first = time.perf_counter() - start
    if repeats <= 0:
        return output, first, 1
    times: list[float] = []
    spent = 0.0
    for _ in range(repeats):
        gc.collect()  # garbage of earlier calls is not charged to this one
        gc.disable()  # as timeit does: no collector pass over unrelated objects in the timing
        try:
            start = time.perf_counter()
            run()
            elapsed = time.perf_counter() - start
        finally:
            gc.enable()
        times.append(elapsed)
        spent += elapsed
        if spent > budget and len(times) >= 3:
            break
    return output, statistics.median(times), len(times)


def _time_interleaved(
    runs: dict[str, Callable[[], Any]], repeats: int, budget: float
) -> dict[str, tuple[Any, float, int]]:
    """:func:`_time` for several contenders at once: every warm-up call first, then rounds of
    one timed call each, the order reversed every other round; stops once the timed calls have
    used ``budget`` seconds (at least three rounds). {name: (output, median, calls)}."""
    outputs: dict[str, Any] = {}
    times: dict[str, list[float]] = {name: [] for name in runs}
    for name, run in runs.items():
        start = time.perf_counter()
        outputs[name] = run()
        times[name].append(time.perf_counter() - start)
    if repeats <= 0:
        return {name: (outputs[name], times[name][0], 1) for name in runs}
    for name in runs:
        times[name].clear()
    order = list(runs)
    spent = 0.0
    for round_ in range(repeats):
        for name in order if round_ % 2 == 0 else order[::-1]:
            gc.collect()
            gc.disable()
            try:
                start = time.perf_counter()
                runs[name]()
                elapsed = time.perf_counter() - start
            finally:
                gc.enable()
            times[name].append(elapsed)
            spent += elapsed
        if spent > budget and round_ >= 2:
            break
    return {name: (outputs[name], statistics.median(t), len(t)) for name, t in times.items()}


def run_case(
    case: Case,
    *,
    repeats: int | None = None,
    budget: float = 60.0,
    check: bool = True,
    log: Callable[[str], None] | None = None,
) -> CaseResult:
    """Run every contender of a case (warm-up + repeats), then check agreement.

    Raises
    ------
    AgreementError
        When a peer deviates beyond tolerance, or crankdyn fails its own check.
    """
    outputs: dict[str, Any] = {}
    timings: dict[str, Timing] = {}
    n = case.repeats if repeats is None else repeats
    if case.interleave:
        ready = {c.name: c.run for c in case.contenders if c.run is not None}
        if log:
            log(f"{case.title} [{case.size}]: {', '.join(ready)} (interleaved)")
        timed = _time_interleaved(ready, n, budget)
    for c in case.contenders:
        if c.run is None:
            timings[c.name] = Timing(c.name, None, 0, c.missing, c.note)
            continue
        if case.interleave:
            out, median, runs = timed[c.name]
        else:
            if log:
                log(f"{case.title} [{case.size}]: {c.name}")
            out, median, runs = _time(c.run, n, budget)
        outputs[c.name] = out
        timings[c.name] = Timing(c.name, median, runs, None, c.note)
    deviations: dict[str, Deviation] = {}
    if check and case.check is not None:
        deviations = case.check(outputs)
        bad = {k: d for k, d in deviations.items() if not d.ok}
        if bad:
            text = "; ".join(
                f"{k}: {d.value:.3g} > {d.tolerance:.3g} ({d.what})" for k, d in bad.items()
            )
            raise AgreementError(f"{case.title} [{case.size}]: results disagree: {text}")
    extra = {}
    if case.extra is not None and CRANKDYN in outputs:
        extra = case.extra(outputs[CRANKDYN])
    return CaseResult(case, timings, deviations, extra)


def relative_deviation(value, reference, scale=None) -> float:
    """max |value - reference| / scale, scale defaulting to max |reference| (numpy arrays)."""
    import numpy as np

    value = np.asarray(value, dtype=float)
    reference = np.asarray(reference, dtype=float)
    if value.shape != reference.shape:
        raise AgreementError(f"shapes differ: {value.shape} and {reference.shape}")
    if not (np.all(np.isfinite(value)) and np.all(np.isfinite(reference))):
        raise AgreementError("a result holds values that are not finite")
    if scale is None:
        scale = float(np.max(np.abs(reference))) if reference.size else 1.0
    if reference.size == 0:
        return 0.0
    return float(np.max(np.abs(value - reference)) / scale)
