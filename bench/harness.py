"""The benchmark harness: cases, contenders, timing, agreement checks and the results table.

A :class:`Case` is one row group of the table: a problem (e.g. "free chain, N = 1000") solved by
crankdyn and by one or more peers (:class:`Contender`). Every contender is called once as a
warm-up (imports, JIT compilation and caches happen here); the agreement check runs on these
outputs, which are then released, and only then is each contender timed, ``repeats`` more times
under :func:`time.perf_counter`; the table reports the median. Outputs held through the
timings (pylinkage's, crankdyn's own) left glibc's heap so that every later 2.5 MB call of the
six-bar faulted some 200 fresh pages in again (1.9 ms a call instead of 1.1 ms), which a
program of its own does not pay.
A case with ``interleave`` set times its contenders in turn (A B, B A, A B, ...: every round
calls each once, the order reversed from one round to the next), so that a change in the
machine's load during the run reaches all of them alike (the whole-process cases, old version
against new).
Calls quicker than :data:`BATCH_SECONDS` are timed in batches (as :mod:`timeit` does), the median
taken over the batches' times per call. Garbage collection runs before, and is disabled during,
each timing (as :mod:`timeit` does).
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


BATCH_SECONDS = 0.02
"""Calls quicker than this are timed in batches lasting about this long (:func:`_batch`)."""

MAX_BATCH = 10_000
"""Most calls in one batch."""


def _batch(run: Callable[[], Any]) -> tuple[int, float | None]:
    """(calls per timing of ``run``, the time of a timed probe call that counts as the first
    timing or None): one call when a call (timed after the warm-up) takes
    :data:`BATCH_SECONDS` or more, otherwise enough for a batch of about that long, as
    :mod:`timeit`'s ``autorange`` does. A lone call of a few microseconds or milliseconds right
    after the collector has walked the benchmark's whole heap (the peers, numba) runs on cold
    caches, and would measure the cache refill (tens to hundreds of microseconds, the same for
    every contender) rather than the call; a batch measures the call."""
    probe = _timed(run, 1)
    if probe >= BATCH_SECONDS:
        return 1, probe
    return max(1, min(MAX_BATCH, int(BATCH_SECONDS / max(probe, 1e-9)) + 1)), None


def _timed(run: Callable[[], Any], number: int) -> float:
    """Seconds per call of ``number`` calls of ``run``, the collector run before and off during
    them (as :mod:`timeit` does)."""
    gc.collect()  # garbage of earlier calls is not charged to these
    gc.disable()  # no collector pass over unrelated objects in the timing
    try:
        start = time.perf_counter()
        for _ in range(number):
            run()
        elapsed = time.perf_counter() - start
    finally:
        gc.enable()
    return elapsed / number


def _time(run: Callable[[], Any], repeats: int, budget: float) -> tuple[float, int]:
    """Up to ``repeats`` timings of a contender already warmed up (each of one call, or of a
    batch of quick calls: :func:`_batch`); stops early once the timings have used ``budget``
    seconds (at least three when a call is quicker than the budget). Returns (median seconds
    per call, timings)."""
    number, probe = _batch(run)
    times = [] if probe is None else [probe]
    spent = sum(times)
    while len(times) < repeats and not (spent > budget and len(times) >= 3):
        per_call = _timed(run, number)
        times.append(per_call)
        spent += per_call * number
    return statistics.median(times), len(times)


def _time_interleaved(
    runs: dict[str, Callable[[], Any]], repeats: int, budget: float
) -> dict[str, tuple[float, int]]:
    """:func:`_time` for several contenders (warmed up) at once: rounds of one timing each, the
    order reversed every other round; stops once the timings have used ``budget`` seconds (at
    least three rounds). {name: (median, timings)}."""
    numbers: dict[str, int] = {}
    times: dict[str, list[float]] = {}
    for name, run in runs.items():  # the probes: the first round when they are single calls
        numbers[name], probe = _batch(run)
        times[name] = [] if probe is None else [probe]
    order = list(runs)
    spent = sum(sum(t) for t in times.values())
    for round_ in range(1, repeats + 1):
        for name in order if round_ % 2 == 0 else order[::-1]:
            if len(times[name]) >= repeats:
                continue
            per_call = _timed(runs[name], numbers[name])
            times[name].append(per_call)
            spent += per_call * numbers[name]
        if all(len(t) >= repeats for t in times.values()) or (spent > budget and round_ >= 2):
            break
    return {name: (statistics.median(t), len(t)) for name, t in times.items()}


def run_case(
    case: Case,
    *,
    repeats: int | None = None,
    budget: float = 60.0,
    check: bool = True,
    log: Callable[[str], None] | None = None,
) -> CaseResult:
    """Run every contender of a case once (the warm-up), check agreement on those outputs,
    release them, then time every contender (``repeats`` timings).

    Raises
    ------
    AgreementError
        When a peer deviates beyond tolerance, or crankdyn fails its own check.
    """
    n = case.repeats if repeats is None else repeats
    ready = {c.name: c.run for c in case.contenders if c.run is not None}
    outputs: dict[str, Any] = {}
    firsts: dict[str, float] = {}
    for name, run in ready.items():  # the warm-ups: imports, compilation, caches; the outputs
        if log:
            log(f"{case.title} [{case.size}]: {name} (warm-up)")
        start = time.perf_counter()
        outputs[name] = run()
        firsts[name] = time.perf_counter() - start
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
    del outputs  # released before the timings (module docstring)
    timed: dict[str, tuple[float, int]] = {}
    if n <= 0:  # the tests' smoke runs: the warm-up's time
        timed = {name: (first, 1) for name, first in firsts.items()}
    elif case.interleave:
        if log:
            log(f"{case.title} [{case.size}]: {', '.join(ready)} (interleaved)")
        timed = _time_interleaved(ready, n, budget)
    else:
        for name, run in ready.items():
            if log:
                log(f"{case.title} [{case.size}]: {name}")
            timed[name] = _time(run, n, budget)
    timings: dict[str, Timing] = {}
    for c in case.contenders:
        if c.run is None:
            timings[c.name] = Timing(c.name, None, 0, c.missing, c.note)
        else:
            median, runs = timed[c.name]
            timings[c.name] = Timing(c.name, median, runs, None, c.note)
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
