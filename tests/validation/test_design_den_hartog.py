"""The design search recovers Den Hartog's optimum damped vibration absorber and the optimum
damping of a Lanchester (untuned viscous) damper.

J. P. Den Hartog, *Mechanical Vibrations*, 4th ed., McGraw-Hill 1956, section 3.3: for a main
mass J on a spring K (undamped) with an auxiliary mass j = mu J on a spring k and a dashpot c,
the largest response of the main mass over frequency is least for the tuning
f = omega_a / omega_n = 1 / (1 + mu) and the damping ratio
zeta = c / (2 j omega_n) = sqrt(3 mu / (8 (1 + mu)^3)). The search (differential evolution on
the study runner, every candidate a case read by the model-file reader) minimises the study
figure ``max_free_end_amplitude`` (the main mass's largest amplitude over the speed range, one
excitation order) over k and c. Tolerance 1 % (issue 39): Den Hartog's zeta is the optimum of
the equal-peaks approximation, the exact minimax optimum lies 0.23 % above it for mu = 0.05
(Nishihara and Asami, J. Vib. Acoust. 124 (2002) 576-582; checked below by an independent
closed-form minimisation), so 1 % holds both. The response itself is checked against the
closed-form receptance of the two-degree-of-freedom system (independent method).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from crankdyn.design.search import run_search
from crankdyn.io.design_file import load_design
from crankdyn.study.run.runner import CaseRunner

DATA = Path(__file__).parent / "data"
MU = 0.05
J_MAIN = 1.0  # kg m^2
OMEGA_N = 2.0 * math.pi * 10.0  # rad/s: sqrt(K/J), K = (2 pi 10 Hz)^2 N m/rad


def receptance_peak(k: float, c: float) -> float:
    """The main mass's largest amplitude per unit torque (rad/(N m)) over 0.5-1.5 omega_n, from
    the closed-form receptance (k + i c w - j w^2) / ((K - J w^2)(k - j w^2 + i c w)
    - j w^2 (k + i c w)) on a grid of 2e5 points (independent of crankdyn's solver)."""
    j = MU * J_MAIN
    big_k = J_MAIN * OMEGA_N**2
    w = np.linspace(0.5, 1.5, 200_001) * OMEGA_N
    x = (k + 1j * c * w - j * w**2) / (
        (big_k - J_MAIN * w**2) * (k - j * w**2 + 1j * c * w) - j * w**2 * (k + 1j * c * w)
    )
    return float(np.abs(x).max())


def test_differential_evolution_finds_den_hartogs_tuning_and_damping(tmp_path):
    space = load_design(DATA / "den_hartog_design.toml")
    with CaseRunner(space.study, tmp_path / "search", workers=1) as runner:
        method, candidates, _ = run_search(space, runner.run)
    assert method == "differential-evolution"
    best = candidates[0]
    assert best.feasible
    k = best.case.numbers["damper[1].stiffness"]  # N m/rad (the range's unit)
    c = best.case.numbers["damper[1].damping"]  # N m s/rad
    j = MU * J_MAIN
    f = math.sqrt(k / j) / OMEGA_N
    zeta = c / (2.0 * j * OMEGA_N)
    f_den_hartog = 1.0 / (1.0 + MU)
    zeta_den_hartog = math.sqrt(3.0 * MU / (8.0 * (1.0 + MU) ** 3))
    assert abs(f / f_den_hartog - 1.0) < 0.01
    assert abs(zeta / zeta_den_hartog - 1.0) < 0.01
    # the objective is the main mass's response: the closed form's peak at the optimum (1 N m)
    assert best.objectives[0] == pytest.approx(receptance_peak(k, c), rel=1e-3)


def test_the_exact_minimax_optimum_lies_within_one_percent_of_den_hartogs():
    """The independent check behind the tolerance: minimising the closed-form peak itself."""
    from scipy.optimize import minimize

    j = MU * J_MAIN

    def peak(p):
        f, zeta = p
        return receptance_peak(j * (f * OMEGA_N) ** 2, 2.0 * j * OMEGA_N * zeta)

    f0 = 1.0 / (1.0 + MU)
    z0 = math.sqrt(3.0 * MU / (8.0 * (1.0 + MU) ** 3))
    r = minimize(peak, [f0, z0], method="Nelder-Mead", options={"xatol": 1e-7, "fatol": 1e-12})
    assert abs(r.x[0] / f0 - 1.0) < 1e-3
    assert abs(r.x[1] / z0 - 1.0) < 0.01


def test_differential_evolution_finds_the_lanchester_dampers_optimum_damping(tmp_path):
    """The untuned viscous (Lanchester) damper: a free ring j = mu J coupled to the main mass by
    viscous damping c alone. Den Hartog (1956, the untuned viscous damper) gives the optimum
    c / (2 j omega_n) = 1 / sqrt(2 (1 + mu)(2 + mu)) and the smallest largest amplitude
    (1 + 2/mu) T/K; both checked independently by minimising the closed-form receptance
    (below). Tolerances: 1 % on the damping (the peak is flat near the optimum), 0.1 % on the
    amplitude (crankdyn resolves a peak to 0.1 %)."""
    mu, stiffness = 0.1, J_MAIN * OMEGA_N**2
    space = load_design(DATA / "lanchester_design.toml")
    with CaseRunner(space.study, tmp_path / "search", workers=1) as runner:
        _, candidates, _ = run_search(space, runner.run)
    best = candidates[0]
    c = best.case.numbers["damper[1].damping"]  # N m s/rad
    zeta = c / (2.0 * mu * J_MAIN * OMEGA_N)
    assert zeta == pytest.approx(1.0 / math.sqrt(2.0 * (1.0 + mu) * (2.0 + mu)), rel=0.01)
    assert best.objectives[0] * stiffness == pytest.approx(1.0 + 2.0 / mu, rel=1e-3)


def test_the_lanchester_formulas_against_the_closed_form_receptance():
    from scipy.optimize import minimize_scalar

    mu = 0.1
    j = mu * J_MAIN
    w = np.linspace(0.3, 1.5, 400_001) * OMEGA_N
    big_k = J_MAIN * OMEGA_N**2

    def peak(c: float) -> float:
        icw = 1j * c * w
        x = 1.0 / ((big_k - J_MAIN * w**2) + icw * (-j * w**2) / (icw - j * w**2))
        return float(np.abs(x).max())

    r = minimize_scalar(peak, bounds=(0.5, 20.0), method="bounded", options={"xatol": 1e-9})
    zeta = r.x / (2.0 * j * OMEGA_N)
    assert zeta == pytest.approx(1.0 / math.sqrt(2.0 * (1.0 + mu) * (2.0 + mu)), rel=1e-3)
    assert r.fun * big_k == pytest.approx(1.0 + 2.0 / mu, rel=1e-6)


def test_a_second_run_of_the_same_seeded_search_reads_every_candidate_back(tmp_path):
    """Seeded differential evolution proposes the same candidates again, which the journal
    holds: the rerun computes none and finds the same best (resumable)."""
    space = load_design(DATA / "lanchester_design.toml")
    ran, best = [], []
    for _ in range(2):
        with CaseRunner(space.study, tmp_path / "search", workers=1) as runner:
            _, candidates, _ = run_search(space, runner.run)
            ran.append(runner.ran)
        best.append((candidates[0].case.case_id, candidates[0].objectives))
    assert ran[0] == len(candidates) and ran[1] == 0
    assert best[0] == best[1]
