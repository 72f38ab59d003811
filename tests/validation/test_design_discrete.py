"""On a small discrete space (six catalogue couplings x two firing orders of a three-throw
line) the design search's best equals the brute-force best found by hand: every combination
written into the model document here (the catalogue's data-sheet values as model-file keys),
read with the model-file reader and judged by the session's TVC condition
(:meth:`crankdyn.Analysis.judged`), the feasible one with the widest worst margin chosen.
Differential evolution (the choices integer-encoded) finds the same best; the local pool of two
processes gives the same result as one process; a second run of the same search reads every
candidate back from the journal. Exact equality: the same variant is the same computation."""

from __future__ import annotations

import copy
import csv
import dataclasses
import itertools
from pathlib import Path

import pytest

from crankdyn.design.search import run_search
from crankdyn.io.design_file import load_design
from crankdyn.io.engine_file import parse_model_file
from crankdyn.io.files import load_toml
from crankdyn.session import Analysis
from crankdyn.study.run.design import run_design
from crankdyn.study.run.runner import CaseRunner

DATA = Path(__file__).parent / "data"
ORDERS = ([1, 2, 3], [1, 3, 2])


def brute_force() -> tuple[tuple[str, tuple[int, ...]], float]:
    """The best (coupling size, firing order) and its worst margin, by hand."""
    base = load_toml(DATA / "small_coupling_line.toml")
    with open(DATA / "small_couplings.csv", encoding="utf-8") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    best = None
    for row, order in itertools.product(rows, ORDERS):
        doc = copy.deepcopy(base)
        coupling = doc["shaft"][4]
        assert coupling["name"] == "elastic coupling"
        coupling.update(
            dynamic_stiffness=f"{row['C_Tdyn [kN*m/rad]']} kN*m/rad",
            relative_damping=float(row["psi"]),
            nominal_torque=f"{row['T_KN [kN*m]']} kN*m",
            vibratory_torque=f"{row['T_KW [kN*m]']} kN*m",
            maximum_torque=f"{row['T_Kmax [kN*m]']} kN*m",
            power_loss=f"{row['P_KV [kW]']} kW",
            designation=row["size"],
        )
        doc["mass"][4]["inertia"] = f"{row['J_primary [kg*m^2]']} kg*m^2"
        doc["mass"][5]["inertia"] = f"{row['J_secondary [kg*m^2]']} kg*m^2"
        doc["excitation"]["firing_order"] = order
        model = parse_model_file(doc, file="by hand", base_dir=DATA)
        try:
            judged = Analysis(model, speed_step=load_design_step()).judged()
        except Exception:  # a variant the analysis refuses is no design (a failed case)
            continue
        if judged is None or not judged.passed:
            continue
        margin = min(v.margin for v in judged.verdicts)
        if best is None or margin > best[1]:
            best = ((row["size"], tuple(order)), margin)
    assert best is not None
    return best


def load_design_step() -> float:
    """The design file's [analysis] speed_step, 20 rpm (rad/s)."""
    import math

    return 20.0 * 2.0 * math.pi / 60.0


def identity(candidate) -> tuple[str, tuple[int, ...]]:
    """(coupling size, firing order) of a candidate."""
    numbers = candidate.case.numbers
    size = next(v for k, v in numbers.items() if k.startswith("shaft["))
    order = candidate.case.params["excitation.firing_order"]
    return size, tuple(order)


def table(folder: Path) -> list[dict[str, str]]:
    """The results table without the run times (which differ between runs)."""
    with open(folder / "results.csv", encoding="utf-8") as f:
        return [{k: v for k, v in row.items() if k != "elapsed_s"} for row in csv.DictReader(f)]


@pytest.fixture(scope="module")
def by_hand():
    return brute_force()


def test_exhaustive_search_equals_the_brute_force_best(by_hand, tmp_path):
    space = load_design(DATA / "small_coupling_design.toml")
    assert space.method() == "exhaustive" and space.discrete_count == 12
    with CaseRunner(space.study, tmp_path / "x", workers=1) as runner:
        method, candidates, _ = run_search(space, runner.run)
    assert method == "exhaustive" and len(candidates) == 12
    best = candidates[0]
    assert identity(best) == by_hand[0]
    assert best.objectives[0] == by_hand[1]


def test_differential_evolution_finds_the_same_best(by_hand, tmp_path):
    space = load_design(DATA / "small_coupling_design.toml")
    de = dataclasses.replace(space.search, method="differential-evolution")
    space = dataclasses.replace(space, search=de)
    with CaseRunner(space.study, tmp_path / "de", workers=1) as runner:
        method, candidates, _ = run_search(space, runner.run)
    assert method == "differential-evolution"
    assert identity(candidates[0]) == by_hand[0]
    assert candidates[0].objectives[0] == by_hand[1]


def test_local_pool_gives_the_same_best_and_a_rerun_resumes(by_hand, tmp_path):
    space = load_design(DATA / "small_coupling_design.toml")
    one = run_design(space, tmp_path / "one", workers=1)
    pool = run_design(space, tmp_path / "pool", workers=2)
    assert identity(one.best) == identity(pool.best) == by_hand[0]
    # the sensitivity's main effect of the coupling: the range of its mean objective over the
    # candidates that ran, by hand from the candidates
    sens = one.sensitivity()
    assert sens is not None and sens.rows[0][0] == "coupling"
    by_size: dict[str, list[float]] = {}
    for c in one.candidates:
        if c.ok:
            by_size.setdefault(identity(c)[0], []).append(c.objectives[0])
    means = [sum(v) / len(v) for v in by_size.values()]
    assert sens.rows[0][1] == pytest.approx(max(means) - min(means), rel=1e-12)
    assert one.best_objective == pool.best_objective == by_hand[1]
    assert table(tmp_path / "pool") == table(tmp_path / "one")
    again = []
    with CaseRunner(space.study, tmp_path / "pool", workers=2) as runner:
        _, candidates, _ = run_search(space, runner.run)
        again.append(runner.ran)
    assert again == [0]  # every candidate read back from the journal
    assert identity(candidates[0]) == by_hand[0]


def test_dask_cluster_with_two_workers_gives_the_same_best(by_hand, tmp_path):
    distributed = pytest.importorskip("distributed")
    space = load_design(DATA / "small_coupling_design.toml")
    with distributed.LocalCluster(
        n_workers=2,
        threads_per_worker=1,
        processes=False,
        protocol="tcp",
        host="127.0.0.1",
        dashboard_address=None,
    ) as cluster:
        result = run_design(space, tmp_path / "dask", scheduler=cluster.scheduler_address)
    assert identity(result.best) == by_hand[0]
    assert result.best_objective == by_hand[1]
