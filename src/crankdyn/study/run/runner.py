"""Running a study: in one process, on a local process pool, or on a Dask cluster.

The main process expands the cases, opens the output folder (resuming what it holds), hands the
unfinished cases to an executor a few at a time, and appends every finished case to the
journal as it arrives (crankdyn.study.run.journal). At the end, or on Ctrl-C, the results tables
and the HTML summary are rebuilt from the journal.

Executors:

- one process (``workers=1``): the cases run in the main process, one after the other;
- a local pool (the default, ``workers`` processes, all cores when None):
  :class:`concurrent.futures.ProcessPoolExecutor`, its workers forked from this process when it
  runs a single thread (:func:`start_method`; else from a fork server, else spawned); the
  study's shared data (base document, settings, figures) is sent once per worker, each task
  carries only a case's parameter values; workers ignore SIGINT, so a Ctrl-C reaches only the
  main process, which stops handing out cases and ends the workers;
- a Dask cluster (``scheduler="tcp://host:8786"``): the shared data is scattered to the
  cluster once, with the contents of the files the base document names (pressure traces...),
  which the workers write to a temporary folder, so the workers need crankdyn (the same version)
  but not the study's files. A case that kills its worker repeatedly (Dask's KilledWorker) is
  recorded as failed.
"""

from __future__ import annotations

import concurrent.futures as cf
import contextlib
import math
import multiprocessing
import signal
import threading
import time
import uuid
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Protocol

from crankdyn import __version__
from crankdyn.errors import InputError
from crankdyn.extras import require
from crankdyn.results import Result, scalar
from crankdyn.study.cases import Case, expand
from crankdyn.study.figures import FIGURES
from crankdyn.study.run.journal import Journal, StudyFolder
from crankdyn.study.run.worker import (
    ANALYSIS_MODULES,
    Payload,
    evaluate_case,
    import_analyses,
    prepare_worker,
    warm_up,
)
from crankdyn.study.spec import StudySpec
from crankdyn.threads import available_cores

__all__ = [
    "SCHEDULER_TIMEOUT",
    "CaseRunner",
    "StudyRun",
    "available_cpus",
    "payload_of",
    "pool_size",
    "run_study",
    "start_method",
]


@dataclass(frozen=True)
class StudyRun(Result):
    """What a run of a study did (:func:`run_study`).

    Parameters
    ----------
    errors : tuple of (str, int)
        The most common errors of the failed cases: (message, number of cases).
    """

    title = "Study run"
    name: str = scalar("study", "Study", "")
    out: str = scalar("out", "Output folder", "")
    executor: str = scalar("executor", "Ran on", "")
    cases: int = scalar("cases", "Cases in the study", "")
    finished: int = scalar("finished", "Cases finished", "")
    ok: int = scalar("ok", "Cases with results", "")
    failed: int = scalar("failed", "Failed cases", "")
    pending: int = scalar("pending", "Cases not run yet", "")
    skipped: int = scalar("skipped", "Finished before this run (skipped)", "")
    ran: int = scalar("ran", "Cases run now", "")
    elapsed: float = scalar("elapsed_s", "Run time", "s", fmt=".3g")
    rate: float = scalar("cases_per_second", "Cases per second", "1/s", fmt=".4g")
    interrupted: bool = scalar("interrupted", "Interrupted", "")
    damaged: int = scalar("damaged_journal_lines", "Damaged journal lines skipped", "")
    errors: tuple[tuple[str, int], ...] = ()  # most common errors (text, count)


# ---- the shared data --------------------------------------------------------------------------


def payload_of(spec: StudySpec, *, ship_files: bool = False) -> Payload:
    """The data every case shares, sent once to each worker.

    Parameters
    ----------
    spec : crankdyn.study.spec.StudySpec
        The study.
    ship_files : bool
        Include the contents of the files the base document names, as read with the study
        (for workers on other machines); default False.

    Returns
    -------
    crankdyn.study.run.worker.Payload
        The shared data.
    """
    modules = tuple(sorted({FIGURES[name].module for name in spec.figures}))
    base_dir = None if spec.base.base_dir is None else str(spec.base.base_dir)
    return Payload(
        kind=spec.base.kind,
        document=spec.base.document,
        source=spec.base.source,
        base_dir=base_dir,
        remove=spec.remove,
        targets=tuple((p.key, p.paths) for p in spec.parameters),
        settings=spec.settings,
        figures=spec.figures,
        modules=modules,
        files=spec.base.files if ship_files else (),
        bundles=tuple(p.key for p in spec.parameters if p.bundle),
        verdict_rows=spec.verdict_rows,
    )


# ---- executors --------------------------------------------------------------------------------


class _Executor(Protocol):
    capacity: int
    description: str

    def submit(self, case: Case) -> Any: ...

    def wait(self, pending: set[Any]) -> tuple[set[Any], set[Any]]: ...

    def result(self, future: Any, case: Case) -> dict[str, Any]: ...

    def close(self, interrupted: bool) -> None: ...


class _InProcess:
    capacity = 1

    def __init__(self, payload: Payload) -> None:
        self.payload = payload
        self.description = "1 process"
        prepare_worker(payload)

    def submit(self, case: Case) -> cf.Future:
        future: cf.Future = cf.Future()
        future.set_result(evaluate_case(self.payload, case.case_id, case.params))
        return future

    def wait(self, pending: set[Any]) -> tuple[set[Any], set[Any]]:
        return set(pending), set()

    def result(self, future: Any, case: Case) -> dict[str, Any]:
        return future.result()

    def close(self, interrupted: bool) -> None:
        pass


_WORKER_PAYLOAD: Payload | None = None


def _init_local_worker(payload: Payload) -> None:
    global _WORKER_PAYLOAD
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the main process's business
    # a forked worker inherits the command line's SIGTERM handler (crankdyn.cli.main): the pool
    # ends its workers with SIGTERM, which must end them
    for name in ("SIGTERM", "SIGHUP"):
        sig = getattr(signal, name, None)
        if sig is not None and callable(signal.getsignal(sig)):
            signal.signal(sig, signal.SIG_DFL)
    _WORKER_PAYLOAD = payload
    prepare_worker(payload)


def _run_local(case_id: str, params: dict[str, Any]) -> dict[str, Any]:
    assert _WORKER_PAYLOAD is not None
    return evaluate_case(_WORKER_PAYLOAD, case_id, params)


def _noop() -> None:
    return None


def start_method() -> str:
    """How the local pool starts its workers.

    Returns
    -------
    str
        ``"fork"`` where the platform has it and this process runs a single thread (the
        command line: the workers start at once, with everything imported and the unit
        registry built), else ``"forkserver"`` (never fork a multi-threaded process: a lock
        held by another thread would stay locked in the child), else ``"spawn"``.
    """
    methods = multiprocessing.get_all_start_methods()
    if "fork" in methods and threading.active_count() == 1:
        return "fork"
    if "forkserver" in methods:
        return "forkserver"
    return "spawn"


def _mp_context(method: str) -> Any:
    ctx = multiprocessing.get_context(method)
    if method == "forkserver":
        # ignored once the server runs
        ctx.set_forkserver_preload(["crankdyn.study.run.preload", *ANALYSIS_MODULES])
    return ctx


class _LocalPool:
    def __init__(self, payload: Payload, workers: int) -> None:
        self.workers = workers
        self.capacity = 2 * workers
        self.description = f"local pool of {workers} processes"
        method = start_method()
        if method == "fork":  # the workers inherit the analyses instead of importing them each
            import_analyses()
        self.pool = cf.ProcessPoolExecutor(
            max_workers=workers,
            mp_context=_mp_context(method),
            initializer=_init_local_worker,
            initargs=(payload,),
        )
        if method == "fork":  # start every worker now, before this process starts a thread
            self.pool.submit(_noop).result()

    def submit(self, case: Case) -> cf.Future:
        return self.pool.submit(_run_local, case.case_id, case.params)

    def wait(self, pending: set[Any]) -> tuple[set[Any], set[Any]]:
        done, not_done = cf.wait(pending, return_when=cf.FIRST_COMPLETED)
        return done, not_done

    def result(self, future: Any, case: Case) -> dict[str, Any]:
        try:
            return future.result()
        except cf.process.BrokenProcessPool:
            raise _PoolBroken("a worker process died unexpectedly (out of memory?)") from None

    def close(self, interrupted: bool) -> None:
        if interrupted:
            processes = list(getattr(self.pool, "_processes", {}).values() or [])
            self.pool.shutdown(wait=False, cancel_futures=True)
            for process in processes:  # the running cases are not finished: end them now
                with contextlib.suppress(Exception):
                    process.terminate()
            for process in processes:
                with contextlib.suppress(Exception):
                    process.join(timeout=5)
        else:
            self.pool.shutdown(wait=True, cancel_futures=True)


class _PoolBroken(Exception):
    pass


def _check_address(address: str) -> None:
    """Refuse an address Dask cannot parse before a client is made (a client that fails in its
    constructor cannot be closed and stalls the interpreter's exit)."""
    from distributed.comm.addressing import parse_address, parse_host_port

    try:
        protocol, location = parse_address(address, strict=False)
        if protocol in ("tcp", "tls", "ws", "wss"):
            parse_host_port(location)
    except (ValueError, TypeError) as exc:
        raise InputError(
            f"expected a Dask scheduler address such as tcp://10.0.0.5:8786 ({exc})",
            key="--scheduler",
            value=address,
        ) from None


SCHEDULER_TIMEOUT = 10.0
"""Seconds crankdyn waits for a Dask scheduler to take the connection and answer (each step of
making the client: the connection, the handshake, the registration, the list of workers)."""
WORKER_TIMEOUT = 60.0
"""Seconds crankdyn waits for the Dask workers to import crankdyn and report its version."""


def _probe_scheduler(address: str, timeout: float) -> None:
    """Connect to the scheduler and wait for its handshake, within ``timeout`` s.

    A Dask client waits for the handshake of a server that accepts the connection without a
    bound (``distributed.comm.core.connect``): a server that accepts and never answers (a
    stalled scheduler, another program on the port) would hold ``crankdyn study`` forever. The
    probe runs the same connection under ``asyncio.wait_for``.
    """
    import asyncio

    from distributed.comm import connect
    from distributed.comm.addressing import parse_address

    if parse_address(address, strict=False)[0] != "tcp":
        return  # other protocols need the client's security settings; the client's bounds apply

    async def probe() -> None:
        comm = await asyncio.wait_for(connect(address, timeout=timeout), timeout)
        await comm.close()

    try:
        asyncio.run(probe())
    except TimeoutError:
        raise InputError(
            f"the Dask scheduler accepted the connection but did not answer within {timeout:g} s "
            "(is a Dask scheduler of the same version listening there?)",
            key="--scheduler",
            value=address,
        ) from None
    except OSError as exc:  # refused, unreachable, closed (CommClosedError)
        reason = " ".join(str(exc).split()) or type(exc).__name__
        raise InputError(
            f"cannot connect to the Dask scheduler: {reason}", key="--scheduler", value=address
        ) from None
    except Exception as exc:  # e.g. bytes that are not Dask's protocol: a MemoryError
        raise InputError(
            "the server did not answer as a Dask scheduler does "
            f"({type(exc).__name__} in the handshake)",
            key="--scheduler",
            value=address,
        ) from None


def _evaluate_on_cluster(payload: Payload, case_id: str, params: dict[str, Any]) -> dict[str, Any]:
    return evaluate_case(payload, case_id, params)


class _Dask:
    def __init__(self, payload: Payload, address: str) -> None:
        try:
            from distributed import Client, as_completed
        except ImportError:  # pragma: no cover - a dependency of crankdyn
            raise InputError(
                "needs dask[distributed] (pip install 'dask[distributed]')",
                key="--scheduler",
                value=address,
            ) from None
        _check_address(address)
        _probe_scheduler(address, SCHEDULER_TIMEOUT)
        import dask

        try:
            with dask.config.set({"distributed.comm.timeouts.connect": f"{SCHEDULER_TIMEOUT}s"}):
                self.client = Client(address, timeout=SCHEDULER_TIMEOUT, set_as_default=False)
        except (OSError, TimeoutError, ValueError, TypeError) as exc:
            reason = " ".join(str(exc).split()) or type(exc).__name__
            raise InputError(
                f"cannot connect to the Dask scheduler: {reason}", key="--scheduler", value=address
            ) from None
        try:
            self._check_workers(address)
            nthreads = self.client.nthreads(callback_timeout=SCHEDULER_TIMEOUT)
            threads = sum(nthreads.values())
            self.capacity = max(16, 4 * threads)
            workers = len(nthreads)
            self.description = f"Dask cluster at {address} ({workers} workers, {threads} threads)"
            self.payload = self.client.scatter(payload, hash=False)
            self.completed = as_completed(loop=self.client.loop)
        except BaseException:
            self.client.close()
            raise

    def _check_workers(self, address: str) -> None:
        try:
            versions = self.client.run(warm_up, callback_timeout=WORKER_TIMEOUT)
        except TimeoutError:
            raise InputError(
                f"the Dask workers did not answer within {WORKER_TIMEOUT:g} s (importing "
                "crankdyn on each of them); check that they run and can reach the scheduler",
                key="--scheduler",
                value=address,
            ) from None
        except Exception as exc:
            raise InputError(
                "a Dask worker has no crankdyn installed (install the same crankdyn "
                f"version, {__version__}, on every worker): {' '.join(str(exc).split())}",
                key="--scheduler",
                value=address,
            ) from None
        for worker, version in versions.items():
            if version != __version__:
                raise InputError(
                    f"Dask worker {worker} runs crankdyn {version}, this crankdyn is "
                    f"{__version__}; install the same version on every worker",
                    key="--scheduler",
                    value=address,
                )

    def submit(self, case: Case) -> Any:
        future = self.client.submit(
            _evaluate_on_cluster,
            self.payload,
            case.case_id,
            case.params,
            key=f"crankdyn-case-{case.case_id}-{uuid.uuid4().hex[:8]}",
            pure=False,
        )
        self.completed.add(future)
        return future

    def wait(self, pending: set[Any]) -> tuple[set[Any], set[Any]]:
        done = {next(self.completed)}
        return done, set(pending) - done

    def result(self, future: Any, case: Case) -> dict[str, Any]:
        from distributed import KilledWorker

        try:
            return future.result()
        except KilledWorker:
            return {
                "case_id": case.case_id,
                "params": case.params,
                "status": "failed",
                "figures": {},
                "error": "the case killed the Dask workers that ran it (KilledWorker)",
                "elapsed_s": None,
            }

    def close(self, interrupted: bool) -> None:
        with contextlib.suppress(Exception):
            self.client.close()


def _executor(
    payload_for: Callable[[bool], Payload], workers: int | None, scheduler: str | None, cases: int
) -> _Executor:
    if scheduler is not None:
        if workers is not None:
            raise InputError(
                "--workers sets the size of the local pool; with --scheduler the cluster's "
                "workers run the cases",
                key="--workers",
                value=workers,
            )
        return _Dask(payload_for(True), scheduler)
    if workers is not None and (
        isinstance(workers, bool) or not isinstance(workers, int) or workers < 1
    ):
        raise InputError("expected a number of processes >= 1", key="--workers", value=workers)
    count, note = pool_size(workers, cases)
    executor: _InProcess | _LocalPool
    if count == 1:
        executor = _InProcess(payload_for(False))
    else:
        executor = _LocalPool(payload_for(False), count)
    if note:
        executor.description += f" ({note})"
    return executor


def available_cpus() -> int:
    """The processors this process may run on.

    Returns
    -------
    int
        Its CPU affinity's count where the system tells it, else the machine's count (>= 1).
    """
    return available_cores()  # (one definition: crankdyn.threads)


def pool_size(workers: int | None, cases: int) -> tuple[int, str]:
    """Processes of the local pool: the workers asked for, capped at the available processors
    and at the number of cases (more processes would only wait, each holding its memory).

    Parameters
    ----------
    workers : int or None
        Processes asked for (``--workers``); None for every available processor.
    cases : int
        Cases to run.

    Returns
    -------
    count : int
        Processes to start (>= 1).
    note : str
        What was capped and why; empty when nothing was.
    """
    cpus = available_cpus()
    wanted = cpus if workers is None else workers
    count = max(1, min(wanted, cpus, cases))
    if workers is None or count == workers:
        return count, ""
    reasons = []
    if cases < workers:
        reasons.append(f"{cases} case{'s' if cases != 1 else ''} to run")
    if cpus < workers:
        reasons.append(f"{cpus} processor{'s' if cpus != 1 else ''} available")
    return count, f"--workers {workers} capped at {count}: {' and '.join(reasons)}"


# ---- the run ----------------------------------------------------------------------------------


Progress = Callable[[int, int, dict[str, Any]], None]
"""``progress(finished_now, to_run, record)``, called after every finished case."""


def _drive(
    executor: _Executor,
    todo: list[Case],
    journal: Journal,
    records: dict[str, dict[str, Any]],
    progress: Progress | None,
    count: list[int],
    meanwhile: Callable[[], None] | None = None,
) -> None:
    """Hand out the cases, record each as it finishes (``count[0]`` counts them);
    ``meanwhile()`` runs once the first cases are handed to workers of their own (not in this
    process), before the first is waited for."""
    queue = iter(todo)
    pending: set[Any] = set()
    owner: dict[Any, Case] = {}

    def fill() -> None:
        while len(pending) < executor.capacity:
            case = next(queue, None)
            if case is None:
                return
            future = executor.submit(case)
            owner[future] = case
            pending.add(future)

    fill()
    if meanwhile is not None and not isinstance(executor, _InProcess):
        meanwhile()
    while pending:
        done, pending = executor.wait(pending)
        for future in done:
            case = owner.pop(future)
            record = executor.result(future, case)
            journal.append(record)
            records[case.case_id] = record
            count[0] += 1
            if progress is not None:
                progress(count[0], len(todo), record)
        fill()


def run_study(
    spec: StudySpec,
    out: str | Path,
    *,
    workers: int | None = None,
    scheduler: str | None = None,
    force: bool = False,
    retry_failed: bool = False,
    progress: Progress | None = None,
    summary: bool = True,
    on_start: Callable[[int, int, str], None] | None = None,
) -> StudyRun:
    """Run (or resume) a study into the folder ``out``.

    Parameters
    ----------
    spec : crankdyn.study.spec.StudySpec
        The study.
    out : str or pathlib.Path
        Output folder (:mod:`crankdyn.study.run.journal` for the rules on an existing one).
    workers : int or None
        Processes of the local pool (default: all cores; 1 runs the cases in this process).
    scheduler : str or None
        Address of a Dask scheduler to run on instead of the local pool
        (``"tcp://host:8786"``).
    force : bool
        Discard the results a folder holds and start over.
    retry_failed : bool
        Run the cases that failed in an earlier run again.
    progress : callable or None
        ``progress(finished_now, to_run, record)`` after every finished case.
    summary : bool
        Write the HTML summary (the tables are always written); default True.
    on_start : callable or None
        ``on_start(to_run, already_finished, executor_description)`` before the first case.

    Returns
    -------
    StudyRun
        Counts and timing (s, cases/s); ``interrupted`` when Ctrl-C stopped the run (what
        finished is kept).

    Raises
    ------
    InputError
        If the study extra is missing, the folder cannot be used, the workers or the scheduler
        are wrong or unreachable, or a worker process died (the finished cases are kept).
    """
    require("studies", "pyarrow", *(("distributed",) if scheduler else ()))
    from crankdyn.study.run.results import CaseTable, import_writers, write_outputs

    cases = expand(spec)
    info = {
        "name": spec.name,
        "source": spec.source,
        "base": spec.base.source,
        "crankdyn_version": __version__,
    }
    with StudyFolder(out, spec.fingerprint(), force=force, info=info) as folder:
        records, damaged = folder.records()
        seen: set[str] = set()
        todo = []
        for case in cases:
            if case.case_id in seen:
                continue
            seen.add(case.case_id)
            record = records.get(case.case_id)
            if record is None or (retry_failed and record.get("status") == "failed"):
                todo.append(case)
        skipped = len(seen) - len(todo)
        interrupted = False
        broken = None
        count = [0]
        description = "nothing to run"
        start = time.perf_counter()
        if todo:

            def payload_for(ship: bool) -> Payload:
                return payload_of(spec, ship_files=ship)

            try:
                executor = _executor(payload_for, workers, scheduler, len(todo))
            except BaseException:
                folder.discard_if_unused()
                raise
            description = executor.description
            if on_start is not None:
                on_start(len(todo), skipped, description)
            journal = Journal(folder.journal_path)
            try:
                _drive(
                    executor,
                    todo,
                    journal,
                    records,
                    progress,
                    count,
                    meanwhile=lambda: import_writers(summary),
                )
            except KeyboardInterrupt:
                interrupted = True
            except _PoolBroken as exc:
                broken = str(exc)
                interrupted = True
            finally:
                journal.close()
                executor.close(interrupted)
        elif on_start is not None:
            on_start(0, skipped, description)
        elapsed = time.perf_counter() - start
        ran = count[0]
        if todo:  # the journal is the record (an interrupt may fall between write and count)
            records, damaged = folder.records()
        table = CaseTable.build(spec, cases, records)
        write_outputs(spec, table, folder.path, summary=summary, run_info={"elapsed_s": elapsed})
        run = StudyRun(
            name=spec.name,
            out=str(folder.path),
            executor=description,
            cases=len(seen),
            finished=table.finished,
            ok=table.ok,
            failed=table.failed,
            pending=len(seen) - table.finished,
            skipped=skipped,
            ran=ran,
            elapsed=elapsed,
            rate=ran / elapsed if elapsed > 0 and ran else math.nan,
            interrupted=interrupted,
            damaged=damaged,
            errors=table.common_errors(),
        )
    if broken is not None:
        raise InputError(
            f"{broken}; the {run.finished} finished cases are kept, run the study again to resume",
            file=str(folder.path),
        )
    return run


class CaseRunner:
    """Cases evaluated batch by batch on one executor and one study folder: what an optimiser
    needs (:mod:`crankdyn.design`), which chooses the next cases from the results of the last.

    The folder is opened as :func:`run_study` opens it (the same fingerprint resumes, another
    study is refused unless ``force``); :meth:`run` returns the journal's record of every case
    of a batch, running on the executor (one process, the local pool or the Dask cluster,
    started at the first batch that has something to run) only the cases the journal does not
    hold. Use it as a context manager: leaving it closes the journal, the executor and the
    folder.

    Parameters
    ----------
    spec : crankdyn.study.spec.StudySpec
        The study whose payload (base document, settings, figures) the cases share; its own
        parameters name the keys a case sets (its cases need not be the spec's grid).
    out : str or pathlib.Path
        The output folder.
    workers, scheduler, force
        As for :func:`run_study`.
    batch : int
        The size of a batch (caps the local pool, as the case count does in a study).
    progress : callable or None
        ``progress(finished_now, to_run, record)`` after every case run.
    on_start : callable or None
        ``on_start(to_run, already_finished, executor_description)`` when the executor starts.
    """

    def __init__(
        self,
        spec: StudySpec,
        out: str | Path,
        *,
        workers: int | None = None,
        scheduler: str | None = None,
        force: bool = False,
        batch: int = 1,
        progress: Progress | None = None,
        on_start: Callable[[int, int, str], None] | None = None,
    ) -> None:
        require("studies", "pyarrow", *(("distributed",) if scheduler else ()))
        self.spec = spec
        self.workers = workers
        self.scheduler = scheduler
        self.batch = max(1, batch)
        self.progress = progress
        self.on_start = on_start
        info = {"name": spec.name, "source": spec.source, "base": spec.base.source}
        info["crankdyn_version"] = __version__
        self.folder = StudyFolder(out, spec.fingerprint(), force=force, info=info)
        self.records, self.damaged = self.folder.records()
        self.skipped = 0
        self.ran = 0
        self.elapsed = 0.0
        self.description = "nothing to run"
        self._executor: _Executor | None = None
        self._journal: Journal | None = None

    def __enter__(self) -> CaseRunner:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close(interrupted=exc[0] is not None)

    @property
    def path(self) -> Path:
        """The output folder."""
        return self.folder.path

    def _start(self, to_run: int) -> None:
        def payload_for(ship: bool) -> Payload:
            return payload_of(self.spec, ship_files=ship)

        self._executor = _executor(payload_for, self.workers, self.scheduler, self.batch)
        self.description = self._executor.description
        self._journal = Journal(self.folder.journal_path)
        if self.on_start is not None:
            self.on_start(to_run, len(self.records), self.description)

    def run(self, cases: list[Case]) -> list[dict[str, Any]]:
        """The records of a batch of cases, running those the journal does not hold.

        Parameters
        ----------
        cases : list of crankdyn.study.cases.Case
            The batch (a case id given twice runs once).

        Returns
        -------
        list of dict
            The journal record of every case (:func:`crankdyn.study.run.worker.evaluate_case`),
            in the batch's order.

        Raises
        ------
        KeyboardInterrupt
            On Ctrl-C (the finished cases are in the journal).
        InputError
            If a worker process died (the finished cases are kept).
        """
        todo: list[Case] = []
        seen: set[str] = set()
        for case in cases:
            if case.case_id in self.records or case.case_id in seen:
                continue
            seen.add(case.case_id)
            todo.append(case)
        self.skipped += len({c.case_id for c in cases} - seen)
        if todo:
            if self._executor is None:
                self._start(len(todo))
            assert self._executor is not None and self._journal is not None
            count = [0]
            start = time.perf_counter()
            try:
                _drive(self._executor, todo, self._journal, self.records, self.progress, count)
            except _PoolBroken as exc:
                raise InputError(
                    f"{exc}; the finished cases are kept, run again to resume",
                    file=str(self.folder.path),
                ) from None
            finally:
                self.elapsed += time.perf_counter() - start
                self.ran += count[0]
        return [self.records[case.case_id] for case in cases]

    def close(self, interrupted: bool = False) -> None:
        """Close the journal, end the executor and release the folder.

        Parameters
        ----------
        interrupted : bool
            End running cases at once (Ctrl-C) instead of waiting for them.
        """
        if self._journal is not None:
            self._journal.close()
            self._journal = None
        if self._executor is not None:
            self._executor.close(interrupted)
            self._executor = None
        self.folder.close()
