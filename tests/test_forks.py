"""Work done beside this process in a forked child (crankdyn.forks): the result is the one this
process would compute, whatever happens to the child; the TVC's events run beside its
conditions give the same calculation as run after them."""

from __future__ import annotations

import os
import time

import numpy as np
import pytest

from crankdyn.forks import Beside, can_fork, room_for_a_copy
from crankdyn.threads import free_cores

needs_fork = pytest.mark.skipif(not can_fork(), reason="no safe fork here (Linux only)")


@needs_fork
def test_the_result_comes_from_the_child():
    parent = os.getpid()
    work = Beside(lambda: (os.getpid(), [1.5, "two", {"three": 3}]))
    assert work.forked
    pid, value = work.result()
    assert work.from_child and pid != parent and value == [1.5, "two", {"three": 3}]
    assert not work.forked  # the child waited for


@needs_fork
def test_arrays_come_back_through_their_own_buffers():
    """Arrays travel out of band (pickle protocol 5): the same values, order and dtype, read-only
    where they were (the results' frozen arrays stay frozen), writable where they were; a
    strided view and plain objects as usual."""
    import numpy as np

    from crankdyn.results import freeze

    frozen = freeze(np.arange(2e5).reshape(400, 500))
    fortran = np.asfortranarray(np.linspace(0.0, 1.0, 6000).reshape(60, 100))
    strided = np.arange(20)[::3]
    work = Beside(lambda: {"frozen": frozen, "fortran": fortran, "strided": strided, "n": "x"})
    found = work.result()
    assert work.from_child
    np.testing.assert_array_equal(found["frozen"], frozen)
    np.testing.assert_array_equal(found["fortran"], fortran)
    np.testing.assert_array_equal(found["strided"], strided)
    assert not found["frozen"].flags.writeable and found["fortran"].flags.writeable
    assert found["fortran"].flags.f_contiguous and found["n"] == "x"


def test_a_result_cut_short_is_not_taken():
    """A child that ends part way through writing its result: the parent reads no value from it
    (EOFError, caught by Beside.result, which then computes the function itself)."""
    import io
    import struct

    import numpy as np

    from crankdyn.forks import _pickled, _unpickled

    whole = b"".join(bytes(part) for part in _pickled({"a": np.arange(1000.0), "b": [1, 2]}))
    value = _unpickled(io.BufferedReader(io.BytesIO(whole)))[0]
    np.testing.assert_array_equal(value["a"], np.arange(1000.0))
    assert _unpickled(io.BufferedReader(io.BytesIO(b""))) == []
    for cut in (4, 20, len(whole) - 8):
        with pytest.raises((struct.error, EOFError)):
            _unpickled(io.BufferedReader(io.BytesIO(whole[:cut])))


@needs_fork
def test_a_failure_in_the_child_is_computed_here():
    """An exception, or a result that does not pickle: the function is run here (its own
    exception raised here, with this process's traceback)."""
    calls = []

    def failing():
        calls.append(os.getpid())
        raise ValueError("bad input")

    work = Beside(failing)
    with pytest.raises(ValueError, match="bad input"):
        work.result()
    assert calls == [os.getpid()]  # the child's call left no trace here; this one ran here
    work = Beside(lambda: lambda: None)  # a function does not pickle
    assert callable(work.result())


def test_not_forked_when_not_wanted():
    work = Beside(lambda: os.getpid(), fork=False)
    assert not work.forked and work.result() == os.getpid()


@needs_fork
def test_close_stops_a_child_still_computing():
    work = Beside(lambda: time.sleep(60))
    pid = work._pid
    started = time.monotonic()
    work.close()
    assert time.monotonic() - started < 10
    with pytest.raises(ChildProcessError):
        os.waitpid(pid, os.WNOHANG)  # reaped


@needs_fork
def test_an_exception_here_stops_the_child():
    """The TVC holds its events' child in a ``with``: an interrupt (KeyboardInterrupt, the
    command line's SIGTERM handler's exception) while the conditions run stops it."""
    with pytest.raises(KeyboardInterrupt), Beside(lambda: time.sleep(60)) as work:
        pid = work._pid
        raise KeyboardInterrupt
    with pytest.raises(ChildProcessError):
        os.waitpid(pid, os.WNOHANG)


def _recorded(cls, made):
    """``cls`` with every instance made appended to ``made``."""

    class Recorded(cls):
        def __init__(self, *args, **kwargs):
            super().__init__(*args, **kwargs)
            made.append(self)

    return Recorded


@needs_fork
@pytest.mark.slow
def test_tvc_events_beside_the_conditions_give_the_same_calculation(monkeypatch):
    """The genset's TVC (its events: a start and a load step) with the events run in a child
    while the conditions run here, and all in this process: the same result, to the bit (the
    child computes from the same state with the same code)."""
    import crankdyn.tvc.analysis as analysis
    from crankdyn.io.catalogue import resolve_model_and_engine
    from crankdyn.tvc.analysis import tvc

    made = []
    monkeypatch.setattr(analysis, "Beside", _recorded(Beside, made))
    model, engine = resolve_model_and_engine("genset-1500")
    beside = tvc(model, engine, passage=False, beside=True)
    assert [w.from_child for w in made] == [True]  # the events came from the child
    here = tvc(model, engine, passage=False, beside=False)
    assert beside.events and [e.name for e in beside.events] == [e.name for e in here.events]
    assert beside.to_json() == here.to_json()
    for a, b in zip(beside.events, here.events, strict=True):
        assert a.to_json() == b.to_json()


def test_when_the_tvc_forks(monkeypatch):
    """Two processors free now (CRANKDYN_THREADS caps them: 1 keeps one process), and room in
    memory for a copy of this process (this small test process: room on any machine that runs
    the suite)."""
    monkeypatch.delenv("CRANKDYN_THREADS", raising=False)
    assert free_cores(2, 1) == 2 and free_cores(4, 4) == 1
    monkeypatch.setenv("CRANKDYN_THREADS", "1")
    assert free_cores(2, 1) == 1
    monkeypatch.setenv("CRANKDYN_THREADS", "3")
    assert free_cores(8, 1) == 3
    if os.path.exists("/proc/meminfo"):
        assert room_for_a_copy() is True


def _once_the_child_has_claimed(monkeypatch, analysis, made):
    """This process judges its first condition only once the child has claimed one (however
    loaded the machine: the child may start late); the child's judging is left as it is."""
    parent = os.getpid()
    judge = analysis._judge

    def waiting(run, cond, respond):
        if os.getpid() == parent:
            deadline = time.monotonic() + 120.0
            while made[-1]._ends[1] == made[-1].size and time.monotonic() < deadline:
                time.sleep(0.005)
        return judge(run, cond, respond)

    monkeypatch.setattr(analysis, "_judge", waiting)
    return judge


@needs_fork
def test_the_child_takes_conditions_from_the_end_once_its_events_are_done(monkeypatch):
    """With its events done at once (none), the child beside the conditions claims them from
    the end while this process claims them from the start (crankdyn.tvc.claims): every
    condition computed once, on one side or the other, the result the same as all of them
    computed here, to the bit (of the misfiring cylinders only the worst keeps its response,
    wherever it was computed)."""
    import crankdyn.tvc.analysis as analysis
    import crankdyn.tvc.events as events
    from crankdyn.io.catalogue import resolve_model_and_engine
    from crankdyn.tvc.analysis import tvc
    from crankdyn.tvc.claims import Claims

    made = []

    monkeypatch.setattr(analysis, "Claims", _recorded(Claims, made))
    monkeypatch.setattr(events, "event_conditions", lambda *args: [])
    judge = _once_the_child_has_claimed(monkeypatch, analysis, made)
    model, engine = resolve_model_and_engine("genset-1500")
    beside = tvc(model, engine, passage=False, beside=True)
    monkeypatch.setattr(analysis, "_judge", judge)
    start, end = made[0]._ends[:]
    assert made[0].size >= 3 and start == end  # every condition claimed ...
    assert end < made[0].size  # ... some by the child
    here = tvc(model, engine, passage=False, beside=False)
    assert made[1]._ends[:] == [made[1].size, made[1].size]  # all of them here
    assert beside.to_json() == here.to_json()
    for a, b in zip(beside.condition_results, here.condition_results, strict=True):
        assert (a.response is None) == (b.response is None)
        if a.response is not None:
            assert np.array_equal(a.response.speed, b.response.speed)
            assert np.array_equal(a.response.shaft_response, b.response.shaft_response)


@needs_fork
def test_a_condition_the_failed_child_had_claimed_is_computed_here(monkeypatch):
    """The child fails on the first condition it claims (:class:`crankdyn.forks.Beside` then
    computes its function here): the condition it had claimed is computed here, once, and the
    result is the one computed all here."""
    import crankdyn.tvc.analysis as analysis
    import crankdyn.tvc.events as events
    from crankdyn.io.catalogue import resolve_model_and_engine
    from crankdyn.tvc.analysis import tvc
    from crankdyn.tvc.claims import Claims

    made = []

    parent = os.getpid()
    judge = analysis._judge
    judged = []

    def failing(run, cond, respond):
        if os.getpid() != parent:
            raise RuntimeError("the child fails")
        judged.append(cond.name)
        return judge(run, cond, respond)

    monkeypatch.setattr(analysis, "Claims", _recorded(Claims, made))
    monkeypatch.setattr(analysis, "_judge", failing)
    monkeypatch.setattr(events, "event_conditions", lambda *args: [])
    _once_the_child_has_claimed(monkeypatch, analysis, made)
    model, engine = resolve_model_and_engine("genset-1500")
    beside = tvc(model, engine, passage=False, beside=True)
    assert made[0]._ends[1] < made[0].size  # the child had claimed one
    monkeypatch.setattr(analysis, "_judge", failing)
    there = list(judged)
    judged.clear()
    here = tvc(model, engine, passage=False, beside=False)
    assert len(there) >= 3 and sorted(there) == sorted(judged)  # each once, none left out
    assert beside.to_json() == here.to_json()


def test_claims_without_shared_memory_stay_in_this_process(monkeypatch):
    """Where shared memory or semaphores are missing (some sandboxes), the claims are this
    process's alone and the TVC starts no child (it would compute every condition again): the
    same calculation, all here."""
    import multiprocessing

    import crankdyn.tvc.analysis as analysis
    import crankdyn.tvc.claims as claims_module
    from crankdyn.io.catalogue import resolve_model_and_engine
    from crankdyn.tvc.analysis import tvc

    def missing(*args, **kwargs):
        raise OSError(38, "Function not implemented")

    monkeypatch.setattr(claims_module.multiprocessing, "Array", missing)
    local = claims_module.Claims([1, 2, 3])
    assert not local.shared
    assert (local.front(), local.back(), local.front(), local.back()) == (1, 3, 2, None)
    made = []
    monkeypatch.setattr(analysis, "Beside", _recorded(Beside, made))
    model, engine = resolve_model_and_engine("genset-1500")
    alone = tvc(model, engine, passage=False, beside=True)
    assert [w.from_child for w in made] == [False]
    monkeypatch.setattr(claims_module.multiprocessing, "Array", multiprocessing.Array)
    assert alone.to_json() == tvc(model, engine, passage=False, beside=False).to_json()


@needs_fork
def test_the_childs_pipe_holds_a_mebibyte():
    """The pipe a child writes its result to is widened to 1 MiB where the system allows it
    (``F_SETPIPE_SZ``), and a result many times that arrives whole."""
    import fcntl

    from crankdyn.forks import widen_pipe

    read, write = os.pipe()
    try:
        widen_pipe(write)
        size = fcntl.fcntl(write, fcntl.F_GETPIPE_SZ)
        with open("/proc/sys/fs/pipe-max-size", encoding="ascii") as handle:
            allowed = int(handle.read())
        assert size == min(1 << 20, allowed) or size == 1 << 16
    finally:
        os.close(read)
        os.close(write)
    big = np.arange(3_000_000, dtype=float)  # 24 MB: two dozen pipe buffers
    found = Beside(lambda: big).result()
    np.testing.assert_array_equal(found, big)
