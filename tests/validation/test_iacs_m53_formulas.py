"""IACS UR M53 "Calculation of crankshafts for I.C. engines": every formula worked by hand.

Source: IACS Unified Requirement M53, Rev.2 (January 2011), clauses M53.2 to M53.8 in the
numbering of that text (the Rev.1 text of December 2004 with the FE appendix added; the formulas
as the Indian Register of Shipping's Classification Notes "Calculation of Crankshafts for Internal
Combustion Engines", January 2012, reproduce them). No worked example with numbers was found in
a public text, so two are worked here by hand, each intermediate value printed to 7 significant
digits as a calculation sheet would, in the rule's units (mm, N/mm^2, kN m); every assertion
holds the code to half a unit in the last printed digit.

Example 1 (a medium-speed four-stroke trunk-piston engine, the built-in ``marine-propulsion``
crankshaft): D = 260, D_G = 300, W = 115, B = 480, R_H = 13, R_G = 15, S = 80, D_O = 20 mm, no
bores or recesses; sigma_B = 850 N/mm^2, continuous grain flow (K = 1.05), K_e = 1,
sigma_add = 10 N/mm^2; given half-ranges M_BN = 50 kN m, Q_N = 350 kN, M_BON = 65 kN m,
M_TN = 30 kN m.

Example 2 (a two-stroke crosshead engine with bored pin and journal and recessed fillets):
D = 200, D_G = 220, W = 80, B = 300, R_H = 10, R_G = 12, S = 20, D_BH = 60, D_BG = 50,
T_H = T_G = 2, D_O = 24 mm; sigma_B = 750 N/mm^2, free form forged (K = 1), K_e = 0.8,
sigma_add = 30 N/mm^2; M_BN = 20 kN m, Q_N = 150 kN, M_BON = 15 kN m, M_TN = 12 kN m.

========================  ===========  ===========  ======================================
quantity                  example 1    example 2    clause
========================  ===========  ===========  ======================================
r = R_H/D, r = R_G/D      0.05000000   0.05000000,  M53.3.1
                          0.05769231   0.06000000
s, w, b                   0.3076923    0.1000000    M53.3.1
                          0.4423077    0.4000000
                          1.846154     1.500000
f(s,w) f(w) f(b) f(r)     0.7594002    0.8973861    M53.3.2
                          1.213965     1.129521
                          1.171825     1.003875
                          0.9973346    0.9973346
f(d_G) f(d_H) f(recess)   0.9993000    1.011272
                          0.9978000    1.020178
                          1.000000     1.042400
alpha_B                   2.891334     2.937317     M53.3.2
f(r,s) f(b) f(w)          2.125736     1.995642     M53.3.2
                          1.062332     1.055575
                          1.125563     1.142093
alpha_T                   2.033431     1.924700     M53.3.2
f_B(s,w) f_B(w) f_B(b)    0.7852721    0.9919983    M53.3.3
f_B(r) f_B(d_G) f_B(d_H)  1.211343     1.122818
                          1.183399     1.005750
                          0.9340883    0.9139107
                          1.001200     0.9168313
                          1.002200     0.9457670
beta_B                    2.864095     2.512047     M53.3.3
f_Q(s) f_Q(w) f_Q(b)      1.205166     1.151328     M53.3.3
f_Q(r) f_Q(d_H)           0.9251401    0.9122839
                          1.346154     1.000000
                          0.9534389    0.9458482
                          0.9937000    0.7915870
beta_Q                    4.284177     2.469755     M53.3.3
beta_T                    2.033431     1.886457     M53.3.3
gamma_B, gamma_T          2.752426     2.792640     M53.3.4
                          3.715976     3.712000
W_eqw, F (mm^3, mm^2)     1058000.     320000.0     M53.2.1.2.1
                          55200        24000
W_e, W_P pin / journal    1725520.     779036.4     M53.2.1.2.2, M53.2.2.2
(mm^3)                    3451040.     1558073.
                          5301438.     2085152.
sigma_BFN, sigma_QFN      47.25898     50.00000     M53.2.1.2.1
                          6.340580     5.000000
sigma_BON                 37.66981     19.25456     M53.2.1.2.2
tau_N pin, journal        8.693033     7.701822     M53.2.2.2
                          5.658842     5.754977
sigma_BH, sigma_BG,       136.6415     146.8658     M53.2.1.3, 2.1.4
sigma_BO                  162.5184     137.9511
                          103.6834     53.77104
tau_H, tau_G, sigma_TO    17.67668     14.82369     M53.2.2.3
                          11.50687     10.85652
                          32.30310     28.58916
sigma_V pin, journal,     149.8036     178.7198     M53.5.2
oil bore                  173.6658     169.0005
                          110.8591     63.77533
sigma_DW pin, journal,    277.7778     257.0999     M53.6
oil bore                  271.7974     252.0611
                          268.1030     254.5488
Q pin, journal, oil bore  1.854280     1.438564     M53.7
                          1.565060     1.491481
                          2.418413     3.991336
========================  ===========  ===========  ======================================

Shrink fit (M53.8), worked by hand: D_S = 500, L_S = 300, D_A = 900, D_BG = 100 mm,
M_max = 1200 kN m, mu = 0.2, S_R = 2, sigma_SP = 400, sigma_SW = 300, E_m = 206000 N/mm^2:
1 - 4000 S_R M_max / (mu pi D_S^2 L_S sigma_SP) = 0.4907042, largest D_BG = 350.2514 mm;
Q_A = 0.5555556, Q_S = 0.2000000, sigma_SW D_S / E_m = 0.7281553 mm, the torque's oversize
0.7358065 mm, so Z_min = 0.7358065 mm; Z_max = 1.128155 mm.
"""

from __future__ import annotations

import math
from decimal import Decimal

import numpy as np
import pytest

from crankdyn.crank.geometry import CrankGeometry
from crankdyn.crankshaft import m53
from crankdyn.crankshaft.geometry import Crankshaft, CrankshaftGeometry, CrankshaftMaterial
from crankdyn.crankshaft.loads import ThrowLoads
from crankdyn.crankshaft.strength import assess
from crankdyn.engine.model import Cylinders, Engine

MM = 1e-3
MPA = 1e6


def printed(text: str):
    """A value printed on the sheet, as pytest.approx to half a unit of its last digit."""
    exponent = Decimal(text).as_tuple().exponent
    assert isinstance(exponent, int)
    return pytest.approx(float(text), rel=0.0, abs=0.5 * 10.0**exponent)


EXAMPLE_1 = dict(
    pin_diameter=260 * MM,
    journal_diameter=300 * MM,
    pin_fillet_radius=13 * MM,
    journal_fillet_radius=15 * MM,
    overlap=80 * MM,
    web_thickness=115 * MM,
    web_width=480 * MM,
    oil_bore_diameter=20 * MM,
)
EXAMPLE_2 = dict(
    pin_diameter=200 * MM,
    journal_diameter=220 * MM,
    pin_fillet_radius=10 * MM,
    journal_fillet_radius=12 * MM,
    overlap=20 * MM,
    web_thickness=80 * MM,
    web_width=300 * MM,
    pin_bore=60 * MM,
    journal_bore=50 * MM,
    pin_recess=2 * MM,
    journal_recess=2 * MM,
    oil_bore_diameter=24 * MM,
)
SHEET = {
    1: {
        "alpha_b": "2.891334",
        "alpha_t": "2.033431",
        "beta_b": "2.864095",
        "beta_q": "4.284177",
        "beta_t": "2.033431",
        "gamma": ("2.752426", "3.715976"),
        "sections": ("1058000.", "55200", "1725520.", "3451040.", "5301438."),
        "nominal": ("47.25898", "6.340580", "37.66981", "8.693033", "5.658842"),
        "bending": ("136.6415", "162.5184", "103.6834"),
        "torsion": ("17.67668", "11.50687", "32.30310"),
        "equivalent": ("149.8036", "173.6658", "110.8591"),
        "strength": ("277.7778", "271.7974", "268.1030"),
        "q": ("1.854280", "1.565060", "2.418413"),
    },
    2: {
        "alpha_b": "2.937317",
        "alpha_t": "1.924700",
        "beta_b": "2.512047",
        "beta_q": "2.469755",
        "beta_t": "1.886457",
        "gamma": ("2.792640", "3.712000"),
        "sections": ("320000.0", "24000", "779036.4", "1558073.", "2085152."),
        "nominal": ("50.00000", "5.000000", "19.25456", "7.701822", "5.754977"),
        "bending": ("146.8658", "137.9511", "53.77104"),
        "torsion": ("14.82369", "10.85652", "28.58916"),
        "equivalent": ("178.7198", "169.0005", "63.77533"),
        "strength": ("257.0999", "252.0611", "254.5488"),
        "q": ("1.438564", "1.491481", "3.991336"),
    },
}
PARTS = {
    # (f(s,w), f(w), f(b), f(r), f(d_G), f(d_H), f(recess)) of alpha_B, as printed
    1: ("0.7594002", "1.213965", "1.171825", "0.9973346", "0.9993000", "0.9978000", "1.000000"),
    2: ("0.8973861", "1.129521", "1.003875", "0.9973346", "1.011272", "1.020178", "1.042400"),
}


def ratios(n: int) -> m53.Ratios:
    return m53.Ratios.of(**(EXAMPLE_1 if n == 1 else EXAMPLE_2))


@pytest.mark.parametrize("n", [1, 2])
def test_ratios(n):
    """UR M53.3.1: the dimensions related to the crankpin diameter D."""
    q = ratios(n)
    expected = {
        1: ("0.05000000", "0.05769231", "0.3076923", "0.4423077", "1.846154", "0.07692308"),
        2: ("0.05000000", "0.06000000", "0.1000000", "0.4000000", "1.500000", "0.1200000"),
    }[n]
    got = (q.r_pin, q.r_journal, q.s, q.w, q.b, q.d_o)
    for value, text in zip(got, expected, strict=True):
        assert value == printed(text)


@pytest.mark.parametrize("n", [1, 2])
def test_crankpin_fillet_scf(n):
    """UR M53.3.2: alpha_B = 2.6914 f(s,w) f(w) f(b) f(r) f(d_G) f(d_H) f(recess) and
    alpha_T = 0.8 f(r,s) f(b) f(w); the sheet's product of its printed parts is its alpha_B."""
    q = ratios(n)
    assert m53.crankpin_bending_scf(q) == printed(SHEET[n]["alpha_b"])
    assert m53.crankpin_torsion_scf(q) == printed(SHEET[n]["alpha_t"])
    product = 2.6914 * math.prod(float(p) for p in PARTS[n])
    assert product == pytest.approx(float(SHEET[n]["alpha_b"]), rel=4e-6)  # 7 factors rounded
    assert m53.recess_factor(q) == printed(PARTS[n][6])


@pytest.mark.parametrize("n", [1, 2])
def test_journal_fillet_scf(n):
    """UR M53.3.3: beta_B, beta_Q and beta_T (with r = R_G / D_G, the journal differing from
    the crankpin in both examples)."""
    q = ratios(n)
    assert m53.journal_bending_scf(q) == printed(SHEET[n]["beta_b"])
    assert m53.journal_shear_scf(q) == printed(SHEET[n]["beta_q"])
    assert m53.journal_torsion_scf(q) == printed(SHEET[n]["beta_t"])


def test_journal_torsion_scf_of_an_equal_journal_is_alpha_t():
    """UR M53.3.3: beta_T = alpha_T when crankpin and journal have the same diameter and
    fillet radius."""
    q = m53.Ratios.of(
        **{**EXAMPLE_2, "journal_diameter": 200 * MM, "journal_fillet_radius": 10 * MM}
    )
    assert q.same_pin_and_journal
    assert m53.journal_torsion_scf(q) == m53.crankpin_torsion_scf(q)


@pytest.mark.parametrize("n", [1, 2])
def test_oil_bore_scf(n):
    """UR M53.3.4: gamma_B = 3 - 5.88 d_O + 34.6 d_O^2, gamma_T = 4 - 6 d_O + 30 d_O^2."""
    g_b, g_t = m53.oil_bore_scf(ratios(n).d_o)
    assert g_b == printed(SHEET[n]["gamma"][0])
    assert g_t == printed(SHEET[n]["gamma"][1])


@pytest.mark.parametrize("n", [1, 2])
def test_section_moduli(n):
    """UR M53.2.1.2.1 (W_eqw = B W^2/6, F = B W), 2.1.2.2 (W_e = pi/32 (D^4 - D_BH^4)/D) and
    2.2.2 (W_P = pi/16 (D^4 - D_B^4)/D) in mm^3 and mm^2."""
    e = EXAMPLE_1 if n == 1 else EXAMPLE_2
    w_eqw, area = m53.web_section(e["web_width"], e["web_thickness"])
    got = (
        w_eqw / MM**3,
        area / MM**2,
        m53.pin_section_modulus(e["pin_diameter"], e.get("pin_bore", 0.0)) / MM**3,
        m53.polar_section_modulus(e["pin_diameter"], e.get("pin_bore", 0.0)) / MM**3,
        m53.polar_section_modulus(e["journal_diameter"], e.get("journal_bore", 0.0)) / MM**3,
    )
    for value, text in zip(got, SHEET[n]["sections"], strict=True):
        assert value == printed(text)


def example_engine(n: int) -> Engine:
    """A one-throw engine carrying the example's crankshaft."""
    e = EXAMPLE_1 if n == 1 else EXAMPLE_2
    geometry = CrankshaftGeometry(**e, web_centre_distance=0.1 if n == 1 else 0.08)
    material = CrankshaftMaterial(
        850e6 if n == 1 else 750e6,
        manufacture="continuous-grain-flow" if n == 1 else "free-form",
    )
    shaft = Crankshaft(geometry, material, "trunk-piston" if n == 1 else "crosshead")
    cycle = "four-stroke" if n == 1 else "two-stroke"
    return Engine(
        f"M53 example {n}",
        CrankGeometry.from_stroke(0.32, 0.4, rod_ratio=0.25),
        Cylinders(1, (1,), cycle=cycle),
        crankshaft=shaft,
    )


def example_loads(n: int) -> ThrowLoads:
    m_bn, q_n, m_bon = (50e3, 350e3, 65e3) if n == 1 else (20e3, 150e3, 15e3)
    zero = np.zeros((1, 1))
    return ThrowLoads(
        theta=np.zeros(1),
        web_moment=zero,
        web_force=zero,
        oil_bore_moment=zero,
        moment_half_range=np.array([m_bn]),
        force_half_range=np.array([q_n]),
        oil_bore_half_range=np.array([m_bon]),
        max_journal_torque=0.0,
    )


def example_result(n: int):
    return assess(
        example_engine(n),
        example_loads(n),
        speed=75.0,
        torsion_torque=[30e3 if n == 1 else 12e3],
    )


@pytest.mark.parametrize("n", [1, 2])
def test_nominal_stresses(n):
    """UR M53.2.1.2.1 sigma_BFN = M_BN / W_eqw K_e and sigma_QFN = Q_N / F K_e (K_e 1.0
    four-stroke, 0.8 two-stroke); 2.1.2.2 sigma_BON = M_BON / W_e; 2.2.2 tau_N = M_TN / W_P of
    the crankpin and of the journal."""
    r = example_result(n)
    got = (r.sigma_bfn[0], r.sigma_qfn[0], r.sigma_bon[0], r.tau_pin[0], r.tau_journal[0])
    for value, text in zip(got, SHEET[n]["nominal"], strict=True):
        assert value / MPA == printed(text)
    assert r.ke == (1.0 if n == 1 else 0.8)


@pytest.mark.parametrize("n", [1, 2])
def test_fillet_and_oil_bore_stresses(n):
    """UR M53.2.1.3 sigma_BH = alpha_B sigma_BFN, sigma_BG = beta_B sigma_BFN + beta_Q
    sigma_QFN; 2.1.4 sigma_BO = gamma_B sigma_BON; 2.2.3 tau_H = alpha_T tau_N,
    tau_G = beta_T tau_N, sigma_TO = gamma_T tau_N."""
    r = example_result(n)
    for j in range(3):
        assert r.bending[0, j] / MPA == printed(SHEET[n]["bending"][j])
        assert r.torsion[0, j] / MPA == printed(SHEET[n]["torsion"][j])


@pytest.mark.parametrize("n", [1, 2])
def test_additional_and_equivalent_stresses(n):
    """UR M53.4: sigma_add 10 N/mm^2 (trunk piston) or 30 N/mm^2 (crosshead); M53.5.2:
    sigma_V = sqrt((sigma_B + sigma_add)^2 + 3 tau^2) in the fillets and
    1/3 sigma_BO [1 + 2 sqrt(1 + 9/4 (sigma_TO/sigma_BO)^2)] at the oil bore."""
    r = example_result(n)
    assert r.additional / MPA == (10.0 if n == 1 else 30.0)
    for j in range(3):
        assert r.equivalent[0, j] / MPA == printed(SHEET[n]["equivalent"][j])


@pytest.mark.parametrize("n", [1, 2])
def test_fatigue_strength(n):
    """UR M53.6: sigma_DW = K (0.42 sigma_B + 39.3) [0.264 + 1.073 D^-0.2 + (785 - sigma_B)/4900
    + 196/sigma_B sqrt(1/R_X)], R_X = R_H, R_G or D_O/2, K at most 1 at the oil bore."""
    r = example_result(n)
    for value, text in zip(r.strengths(), SHEET[n]["strength"], strict=True):
        assert value / MPA == printed(text)


@pytest.mark.parametrize("n", [1, 2])
def test_acceptability(n):
    """UR M53.7: Q = sigma_DW / sigma_V, at least 1.15 (both examples pass everywhere)."""
    r = example_result(n)
    for j, text in enumerate(SHEET[n]["q"]):
        assert r.q_table()[0, j] == printed(text)
    assert all(v.passed for v in r.summary_verdicts())
    assert {v.clause for v in r.summary_verdicts()} == {"M53.7"}


def test_shrink_fit():
    """UR M53.8.2 (largest journal bore), 8.3 (Z_min, the greater of the two conditions) and
    8.4 (Z_max) of the sheet's semi-built journal."""
    args = dict(shrink_diameter=0.5, shrink_length=0.3, torque=1.2e6, friction=0.2, slip_safety=2.0)
    bore = m53.maximum_journal_bore(**args, pin_yield=400e6)
    assert bore / MM == printed("350.2514")
    z_min = m53.minimum_oversize(
        **args, web_outer_diameter=0.9, journal_bore=0.1, web_yield=300e6, youngs_modulus=2.06e11
    )
    assert z_min / MM == printed("0.7358065")
    z_yield = m53.minimum_oversize(
        **{**args, "torque": 1.0},
        web_outer_diameter=0.9,
        journal_bore=0.1,
        web_yield=300e6,
        youngs_modulus=2.06e11,
    )
    assert z_yield / MM == printed("0.7281553")  # the yield condition governs a small torque
    assert m53.maximum_oversize(0.5, 300e6, 2.06e11) / MM == printed("1.128155")
