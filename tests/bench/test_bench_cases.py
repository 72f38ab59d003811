"""The benchmark cases (bench/) run once at tiny sizes: crankdyn's side always, checked against
an independent computation (dense eigh, loop closure, the bare-numpy formulas, the dense
dynamic-stiffness residual); the peers (openTorsion, pylinkage) only where installed, which the
test environment need not have. No times are asserted."""

from __future__ import annotations

import math
import time

import bench.cases as case_modules
import numpy as np
import pytest
from bench.harness import CRANKDYN, AgreementError, Case, Contender, Deviation, run_case
from bench.run import markdown, rows, write_docs

CASES = [c for name in case_modules.available() for c in case_modules.load(name).cases("tiny")]
IDS = [f"{c.key}-{c.size}" for c in CASES]


@pytest.fixture(scope="module")
def results():
    return {}


def _run(case: Case, results: dict):
    key = (case.key, case.size)
    if key not in results:
        results[key] = run_case(case, repeats=0)
    return results[key]


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_crankdyn_side_runs_and_passes_its_independent_check(case, results):
    if case.contenders[0].run is None:
        pytest.skip(case.contenders[0].missing)
    result = _run(case, results)
    assert result.crankdyn.median is not None
    independent = [c.name for c in case.contenders[1:] if c.run is not None]
    for name in independent:
        assert result.deviations[name].ok


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_peers_agree_where_installed(case, results):
    missing = [c.missing for c in case.contenders if c.run is None]
    if case.contenders[0].run is None or len(case.contenders) == 1:
        pytest.skip("no peer for this case")
    result = _run(case, results)
    for name, dev in result.deviations.items():
        assert dev.ok, f"{name}: {dev.value:.3g} > {dev.tolerance:.3g}"
    if missing:
        pytest.skip("; ".join(dict.fromkeys(missing)))


def test_agreement_failure_is_loud():
    case = Case(
        key="t",
        title="disagreeing",
        size="1",
        contenders=(Contender(CRANKDYN, lambda: 1.0), Contender("peer", lambda: 2.0)),
        check=lambda out: {"peer": Deviation(abs(out["peer"] - out[CRANKDYN]), 1e-9, "abs")},
    )
    with pytest.raises(AgreementError, match=r"disagreeing .*peer: 1 > 1e-09"):
        run_case(case, repeats=0)


def test_chain_frequencies_match_the_closed_form():
    """The chain case's crankdyn call against omega_r = 2 sqrt(k/J) sin(r pi / 2N) for a
    uniform free chain (an input outside the seeded random chain)."""
    from bench.cases.chain_modes import crankdyn_modes

    n, j, k = 25, 0.3, 2.0e6
    r = crankdyn_modes(np.full(n, j), np.full(n - 1, k))
    expected = 2.0 * math.sqrt(k / j) * np.sin(np.arange(n) * np.pi / (2 * n))
    assert r.natural_frequency[0] == 0.0
    assert np.max(np.abs(r.natural_frequency[1:] / expected[1:] - 1.0)) < 1e-12


def test_fourbar_link_motion_from_joint_arrays():
    """The conversion of joint positions, velocities and accelerations to link angles and
    rates (used for pylinkage's output) gives back crankdyn's own motion."""
    from bench.cases.fourbar import ALPHA2, LENGTHS, OMEGA2, link_motion

    from crankdyn.linkage.fourbar import FourBar

    a, _b, c, d = LENGTHS
    theta2 = np.linspace(0.1, 6.2, 50)
    m = FourBar(*LENGTHS).motion(theta2, OMEGA2, ALPHA2)
    e2, e4 = np.exp(1j * theta2), np.exp(1j * m.theta4)
    joints = [np.zeros_like(e2), np.full_like(e2, d), a * e2, d + c * e4]
    vel = [0 * e2, 0 * e2, 1j * a * OMEGA2 * e2, 1j * c * m.omega4 * e4]
    acc = [
        0 * e2,
        0 * e2,
        a * (1j * ALPHA2 - OMEGA2**2) * e2,
        c * (1j * m.alpha4 - m.omega4**2) * e4,
    ]

    def stack(z):
        return np.stack([np.stack([p.real, p.imag], axis=-1) for p in z], axis=1)

    crank, links = link_motion(stack(joints), stack(vel), stack(acc))
    assert np.allclose(crank, np.angle(e2), atol=1e-12)
    t4, w4, a4 = links["rocker"]
    assert np.allclose(t4, m.theta4, atol=1e-12)
    assert np.allclose(w4, m.omega4, rtol=1e-10)
    assert np.allclose(a4, m.alpha4, rtol=1e-10, atol=1e-9)
    t3, w3, a3 = links["coupler"]
    assert np.allclose(t3, m.theta3, atol=1e-12)
    assert np.allclose(w3, m.omega3, rtol=1e-10)
    assert np.allclose(a3, m.alpha3, rtol=1e-10, atol=1e-9)


def test_table_and_docs_block_are_rewritten_between_markers(tmp_path, results):
    case = next(c for c in CASES if c.key == "engine")
    result = _run(case, results)
    assert rows([result])[0][0] == case.title
    info = {"CPU": "test"}
    memory = [
        {
            "what": "probe",
            "peak_rss_mb": 10.0,
            "imports_rss_mb": 5.0,
            "traced_peak_mb": 1.0,
            "target_mb": 200.0,
            "target_text": "< 200 MB",
        }
    ]
    doc = tmp_path / "benchmarks.md"
    doc.write_text("# Benchmarks\n\nIntro.\n\n## Parameter studies\n\nKeep me.\n")
    write_docs(doc, markdown([result], memory, info))
    first = doc.read_text()
    assert "Intro." in first and "Keep me." in first and "| probe | 10 MB |" in first
    write_docs(doc, markdown([result], memory, {"CPU": "other"}))
    second = doc.read_text()
    assert second.count("bench:begin") == 1 and "- CPU: other" in second
    assert "- CPU: test" not in second and "Keep me." in second


def test_quick_calls_are_timed_in_batches_and_slow_ones_one_by_one(monkeypatch):
    """A call quicker than BATCH_SECONDS is timed in batches (timeit's method: the caches stay
    warm, the collector runs once per batch); a slow call's timed probe counts as its first
    timing (no extra call); both ways, ``repeats`` timings and the warm-up's output."""
    import bench.harness as harness

    monkeypatch.setattr(harness, "BATCH_SECONDS", 0.005)
    calls = {"quick": 0, "slow": 0}

    def quick():
        calls["quick"] += 1
        return "q"

    def slow():
        calls["slow"] += 1
        time.sleep(0.006)
        return "s"

    median, timings = harness._time(quick, 5, budget=60.0)
    assert timings == 5
    assert calls["quick"] > 1 + 5  # the probe, and 5 batches of several calls
    assert 0.0 < median < 0.005
    median, timings = harness._time(slow, 5, budget=60.0)
    assert (timings, calls["slow"]) == (5, 5)  # the probe is the first timing, 4 more
    assert median >= 0.006
    calls.update(quick=0, slow=0)
    both = harness._time_interleaved({"quick": quick, "slow": slow}, 4, budget=60.0)
    assert {k: v[1] for k, v in both.items()} == {"quick": 4, "slow": 4}
    assert calls["slow"] == 4 and calls["quick"] > 1 + 4


def test_outputs_are_checked_then_released_before_any_timing():
    """run_case calls every contender once, checks agreement on those outputs and drops them
    before the first timing (held, large outputs changed the allocator's state for the timed
    calls); a disagreement stops the case before anything is timed."""
    import gc
    import weakref

    import bench.harness as harness

    class Output:
        pass

    kept: list[weakref.ref] = []
    seen: list[bool] = []

    def make():
        out = Output()
        if kept:  # a timed call: every warm-up output is gone by now
            gc.collect()
            seen.append(all(ref() is None for ref in kept))
        else:
            kept.append(weakref.ref(out))
        return out

    def check(outputs):
        assert set(outputs) == {CRANKDYN}
        return {"x": Deviation(0.0, 1.0, "x")}

    case = Case("k", "title", "size", (Contender(CRANKDYN, make),), check=check, repeats=3)
    result = harness.run_case(case)
    assert result.timings[CRANKDYN].runs == 3 and seen and all(seen)

    timed = []

    def disagree(outputs):
        return {"x": Deviation(2.0, 1.0, "x")}

    case = Case(
        "k", "title", "size", (Contender(CRANKDYN, lambda: timed.append(1)),), check=disagree
    )
    with pytest.raises(AgreementError):
        harness.run_case(case, repeats=3)
    assert timed == [1]  # the warm-up only


def test_tvc_line_generator_scales_the_marine_example(tmp_path):
    """bench.tvc_line: the marine example as shipped has 38 masses (its shafts subdivided to
    150 Hz); asked for more, the subdivision frequency rises until the line has at least that
    many, within a few masses (each shaft gains one element at a time)."""
    from bench.tvc_line import write_line

    _, base = write_line(tmp_path / "base", 38)
    assert base == 38
    _, count = write_line(tmp_path / "more", 80)
    assert 80 <= count <= 83


def test_tvc_scaling_exponents_of_a_power_law():
    """bench.cases.tvc_scaling.exponents: times that grow exactly as N^1.5 give 1.5 for the
    pair and for the least-squares fit (the median of each size's runs)."""
    from bench.cases.tvc_scaling import exponents

    times = {n: [2.0 * n**1.5, 2.0 * n**1.5 * 1.1, 2.0 * n**1.5 * 0.9] for n in (38, 100, 1000)}
    pair, fitted = exponents(times, 38, 1000)
    assert pair == pytest.approx(1.5, rel=1e-12)
    assert fitted == pytest.approx(1.5, rel=1e-12)
