"""The 3-D beam elements (crankdyn.crankshaft.beam_elements) against closed-form frequencies of
uniform beams, with the discretisation error stated and the convergence rate checked.

Sources and what is compared:

- Axial and torsional vibration of a uniform bar (R. D. Blevins, *Formulas for Natural Frequency
  and Mode Shape*, Van Nostrand Reinhold, 1979, ch. 8): free-free f_n = n c / (2 L),
  clamped-free f_n = (2n - 1) c / (4 L), c = sqrt(E / rho) or sqrt(G / rho) (circular section,
  J = I_p). The linear element with consistent mass has the exact discrete dispersion relation
  omega_h^2 = (6 c^2 / h^2) (1 - cos k h) / (2 + cos k h) (from the assembled interior equation
  for u_j = cos k x_j; T. J. R. Hughes, *The Finite Element Method*, Dover, 2000, ch. 9): the
  finite-element frequencies equal it to round-off, and their error against the exact bar is the
  dispersion error (k h)^2 / 24 + O(h^4) that the relation gives (stated per case).
- Euler-Bernoulli bending (Blevins 1979, Table 8-1): f = (beta L)^2 / (2 pi L^2) sqrt(E I /
  (rho A)), beta L = 4.73004074, 7.85320462, 10.9956078 (free-free and clamped-clamped),
  1.87510407, 4.69409113, 7.85475744 (clamped-free). Cubic Hermite elements with consistent mass
  converge as h^4: the error halves 16 times per halving of h (checked between 3.8 and 4.3 in the
  exponent), and at 32 elements it is below 1e-7 (stated: the printed beta L has 9 digits).
- Timoshenko bending, simply supported: the closed form of S. Timoshenko ("On the correction for
  shear of the differential equation for transverse vibrations of prismatic bars", Phil. Mag. 41
  (1921) 744-746; in S. M. Han, H. Benaroya and T. Wei, "Dynamics of transversely vibrating
  beams using four engineering theories", J. Sound Vib. 225 (1999) 935-988, sec. 5): with
  k = n pi / L the determinant of [[rho A w^2 - kappa G A k^2, kappa G A k], [kappa G A k,
  rho I w^2 - E I k^2 - kappa G A]] vanishes (a quadratic in w^2; the lower root).
- Timoshenko bending, clamped-free, free-free and clamped-clamped: the exact solution of
  Timoshenko's equations by the transfer matrix expm(A(omega) L) of the first-order system in
  (w, psi, M, V) and the frequency determinant of the boundary conditions (an independent
  method: no discretisation), roots by Brent's method.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.linalg
from scipy.optimize import brentq

from crankdyn.crankshaft.beam_elements import (
    BeamMaterial,
    BeamSection,
    assemble,
    element_frames,
    global_element_matrices,
    local_element_matrices,
)

STEEL = BeamMaterial(210e9, 0.3, 7850.0)
LENGTH = 1.0
SLENDER = BeamSection.circular(0.05, 0.0, 0.3)  # L / D = 20
STOCKY = BeamSection.circular(0.2, 0.0, 0.3)  # L / D = 5: shear and rotary inertia matter

# local degrees of freedom of each family in a node (u_x' axial, theta_x' torsion, v/theta_z')
FAMILY = {"axial": [0], "torsion": [3], "bending": [1, 5]}


def _frequencies(section, n, family, bc, *, shear=True, rotary=True, count=4):
    """Lowest natural frequencies (Hz) of a straight beam of n elements, one family of degrees
    of freedom kept, with boundary conditions bc = (left, right) in {"free", "clamped",
    "pinned"}."""
    k, m = local_element_matrices(
        np.full(n, LENGTH / n), STEEL, section, shear=shear, rotary_inertia=rotary
    )
    frames = element_frames(np.tile([1.0, 0, 0], (n, 1)), np.tile([0, 1.0, 0], (n, 1)))
    dofs = np.arange(n)[:, None] * 6 + np.arange(12)[None, :]
    K = assemble(6 * (n + 1), dofs, global_element_matrices(k, frames)).toarray()
    M = assemble(6 * (n + 1), dofs, global_element_matrices(m, frames)).toarray()
    keep = [6 * j + d for j in range(n + 1) for d in FAMILY[family]]
    held = set()
    for node, kind in ((0, bc[0]), (n, bc[1])):
        if kind == "clamped":
            held.update(6 * node + d for d in FAMILY[family])
        elif kind == "pinned":
            held.add(6 * node + FAMILY[family][0])
    keep = [d for d in keep if d not in held]
    lam = scipy.linalg.eigh(K[np.ix_(keep, keep)], M[np.ix_(keep, keep)], eigvals_only=True)
    f = np.sqrt(np.clip(lam, 0.0, None)) / (2 * math.pi)
    rigid = 0 if "clamped" in bc else (2 if family == "bending" and bc == ("free", "free") else 1)
    if "pinned" in bc:
        rigid = 0
    return f[rigid : rigid + count]


def _dispersion(c, k, h):
    """omega_h (rad/s) of linear consistent-mass elements for wave number k (rad/m)."""
    return math.sqrt(6 * c**2 / h**2 * (1 - math.cos(k * h)) / (2 + math.cos(k * h)))


@pytest.mark.parametrize("family,modulus", [("axial", "E"), ("torsion", "G")])
@pytest.mark.parametrize("bc", ["free-free", "clamped-free"])
def test_bar_axial_and_torsion_closed_form(family, modulus, bc):
    n = 40
    h = LENGTH / n
    c = math.sqrt((STEEL.youngs_modulus if modulus == "E" else STEEL.shear_modulus) / STEEL.density)
    fe = _frequencies(
        SLENDER, n, family, ("free", "free") if bc == "free-free" else ("clamped", "free")
    )
    modes = np.arange(1, fe.size + 1)
    k = modes * math.pi / LENGTH if bc == "free-free" else (2 * modes - 1) * math.pi / (2 * LENGTH)
    exact = c * k / (2 * math.pi)
    discrete = np.array([_dispersion(c, kk, h) for kk in k]) / (2 * math.pi)
    # the finite elements are exactly the discrete dispersion relation
    np.testing.assert_allclose(fe, discrete, rtol=1e-9)
    # stated discretisation error against the bar: (k h)^2 / 24 to leading order
    error = fe / exact - 1.0
    # (40 elements, first mode: 2.6e-4 free-free, 6.4e-5 clamped-free)
    np.testing.assert_allclose(error, (k * h) ** 2 / 24, rtol=0.01)


BLEVINS = {
    ("free", "free"): (4.73004074, 7.85320462, 10.9956078),
    ("clamped", "clamped"): (4.73004074, 7.85320462, 10.9956078),
    ("clamped", "free"): (1.87510407, 4.69409113, 7.85475744),
}


@pytest.mark.parametrize("bc", list(BLEVINS))
def test_euler_bernoulli_blevins_and_convergence(bc):
    s = SLENDER
    scale = math.sqrt(STEEL.youngs_modulus * s.second_moment_z / (STEEL.density * s.area))
    exact = np.array([b**2 * scale / (2 * math.pi * LENGTH**2) for b in BLEVINS[bc]])
    f = {
        n: _frequencies(s, n, "bending", bc, shear=False, rotary=False, count=3)
        for n in (8, 16, 32)
    }
    errors = {n: np.abs(f[n] / exact - 1.0) for n in f}
    rate = np.log2(errors[8] / errors[16])
    assert np.all((rate > 3.8) & (rate < 4.3)), rate
    # stated discretisation error at 32 elements: 3e-7 (mode 1), 2.5e-6 (2), 1e-5 (3)
    assert np.all(errors[32] < [1e-6, 1e-5, 2e-5]), errors[32]
    # h^4 extrapolation against Blevins's beta L to its printed digits (9: 1e-8 in f)
    richardson = f[32] + (f[32] - f[16]) / 15.0
    assert abs(richardson[0] / exact[0] - 1.0) < 1e-8


def _timoshenko_ss(section, n_mode):
    """Lower root (Hz) of the simply supported Timoshenko beam's frequency equation: the
    determinant written out, rho A rho I w^4 - (rho A (E I k^2 + kGA) + rho I kGA k^2) w^2
    + kGA E I k^4 = 0."""
    s, E, G, rho = section, STEEL.youngs_modulus, STEEL.shear_modulus, STEEL.density
    k = n_mode * math.pi / LENGTH
    a, I, kg = s.area, s.second_moment_z, s.shear_coefficient * G * s.area
    qa = rho * a * rho * I
    qb = -(rho * a * (E * I * k**2 + kg) + rho * I * kg * k**2)
    qc = kg * E * I * k**4
    w2 = (-qb - math.sqrt(qb * qb - 4 * qa * qc)) / (2 * qa)
    return math.sqrt(w2) / (2 * math.pi)


def test_timoshenko_simply_supported_closed_form():
    exact = np.array([_timoshenko_ss(STOCKY, n) for n in (1, 2, 3)])
    f = {n: _frequencies(STOCKY, n, "bending", ("pinned", "pinned"), count=3) for n in (16, 32, 64)}
    errors = {n: np.abs(f[n] / exact - 1.0) for n in f}
    # the shear-dominated element converges as h^2 once elements are shorter than the depth
    rate = np.log2(errors[32] / errors[64])
    assert np.all((rate > 1.9) & (rate < 2.1)), rate
    richardson = f[64] + (f[64] - f[32]) / 3.0
    np.testing.assert_allclose(richardson, exact, rtol=2e-6)
    # shear and rotary inertia lower the stocky beam's first frequency below Euler-Bernoulli's
    # (by 4.5 % at L / D = 5)
    eb = (
        math.pi
        / (2 * LENGTH**2)
        * math.sqrt(STEEL.youngs_modulus * STOCKY.second_moment_z / (STEEL.density * STOCKY.area))
    )
    assert exact[0] < eb


def _transfer(section, omega):
    s, E, G, rho = section, STEEL.youngs_modulus, STEEL.shear_modulus, STEEL.density
    kg = s.shear_coefficient * G * s.area
    a = np.array(
        [
            [0.0, 1.0, 0.0, 1.0 / kg],
            [0.0, 0.0, 1.0 / (E * s.second_moment_z), 0.0],
            [0.0, -rho * s.second_moment_z * omega**2, 0.0, -1.0],
            [-rho * s.area * omega**2, 0.0, 0.0, 0.0],
        ]
    )
    return scipy.linalg.expm(a * LENGTH)


_ROWS = {"free": [2, 3], "clamped": [0, 1]}  # conditions that vanish
_UNKNOWN = {"free": [0, 1], "clamped": [2, 3]}  # state left unknown at x = 0


def _exact_timoshenko(section, bc, count):
    def det(f):
        t = _transfer(section, 2 * math.pi * f)
        return np.linalg.det(t[np.ix_(_ROWS[bc[1]], _UNKNOWN[bc[0]])])

    grid = np.linspace(1.0, 6000.0, 12000)
    values = np.array([det(f) for f in grid])
    roots = [
        brentq(det, grid[i], grid[i + 1], xtol=1e-12, rtol=1e-14)
        for i in np.flatnonzero(np.sign(values[:-1]) != np.sign(values[1:]))
    ]
    return np.array(roots[:count])


@pytest.mark.slow
@pytest.mark.parametrize("bc", [("clamped", "free"), ("free", "free"), ("clamped", "clamped")])
def test_timoshenko_exact_transfer_matrix(bc):
    exact = _exact_timoshenko(STOCKY, bc, 3)
    assert exact.size == 3
    f = {n: _frequencies(STOCKY, n, "bending", bc, count=3) for n in (16, 32, 64)}
    errors = {n: np.abs(f[n] / exact - 1.0) for n in f}
    # stated discretisation error at 32 elements (h = 0.16 D): 4e-6 to 1.2e-4 (mode 1),
    # up to 1.9e-3 (mode 3); the element converges as h^2 once shear dominates it
    assert np.all(errors[32] < [2e-4, 1e-3, 3e-3]), errors[32]
    rate = np.log2(errors[32] / errors[64])
    assert np.all((rate > 1.9) & (rate < 2.1)), rate
    richardson = f[64] + (f[64] - f[32]) / 3.0
    np.testing.assert_allclose(richardson, exact, rtol=2e-6)
