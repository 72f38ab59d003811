"""The formulas of IACS UR M53, "Calculation of crankshafts for I.C. engines" (numeric core).

Text read and edition
---------------------
Every formula, coefficient and range here was checked against one readable text of the method:
the Korean Register's *Rules for the Classification of Steel Ships 2025*, Part 5 Guidance,
**Annex 5-3 "Guidance for Calculation of Crankshaft Stress (2)"** (RA-05-E 2025, English), read
as markdown in a public repository (search-index file 68819297975; figures not reproduced). The
Annex follows UR M53 section by section: its items 1 to 8 carry the titles and order of the
UR's sections M53.1 to M53.8 (the UR's Rev.1 table of contents, December 2004, read in a public
copy), and its Appendix III is the UR's FE appendix that Rev.2 (January 2011) added (the UR's
history file, read in a public copy). Its Appendices IV (fatigue tests), V (surface-treated
fillets and oil bores) and VI (SCF of the oil bores by FE) and the items KR marks "(2018)",
"(2021)" and "(2024)" are later; which UR revision (Rev.3 to the current one) each came from was
not read, nor what else those revisions changed: check the text your society applies. This
module cites the UR's clause numbers with the Annex item in brackets, e.g. "M53.3.2 [Annex 5-3
3(2)(A)]".

What the copy read lacks or prints doubtfully, and what crankdyn does there:

- **Item 7 (acceptability criteria) is missing** from the copy. Q = sigma_DW / sigma_V >= 1.15
  is taken from Annex 5-3 Appendix V 3(3) ("compares the equivalent alternating stress and the
  fatigue strength ratio to an acceptability factor of Q >= 1.15 for oil bore outlets, crankpin
  fillets and journal fillets") and the form of Q from Appendix IV 4(3)(A) (Q = sigma_DWOT /
  sigma_v at the oil bore). Appendices I and II (definitions of the factors) are missing too;
  no formula here depends on them.
- **Two coefficients are printed with fewer digits than their neighbours**: f(b) of alpha_T ends
  in "- 0.85 b^3" and f_B(s,w) of beta_B has "- 1.527 w^2", where every other coefficient has
  four decimals. crankdyn uses them as printed. The values -0.857 and -1.5276 that an earlier
  version of this module carried were written from memory and are **not verified against a
  text**; the printed ones give the larger factors (alpha_T larger by 0.007 b^3 / f(b): 0.6 %
  at b = 1.1, 2.2 % at b = 1.5, 6.1 % at b = 2.2; beta_B by less than 0.07 % within the
  ranges), so they err on the safe side.
- The replacement of s < -0.5 by -0.5 is stated for f(s,w) and f(r,s) (3(1)(H)); crankdyn
  also applies it in the journal fillet's f_B(s,w) and f_Q(s), which the text does not name
  (**not verified against a text**; f_Q(s) turns negative below s = -0.6 otherwise).
- The surface treatment's factor (``surface_factor`` of the material) is crankdyn's: the text
  requires the process to be approved and gives guidance (Appendix V), not a factor.

The rule writes its formulas in N/mm^2 and mm; the functions here take and give SI (Pa, m) and
convert where a formula is not dimensionally homogeneous (the fatigue strength, M53.6).
``tests/validation/test_iacs_m53_formulas.py`` checks every function against the text's
formulas evaluated by hand (GNU bc, ``tests/validation/data/iacs_m53_sheet.bc``).

- Nominal stresses (M53.2): the web's alternating bending and compressive stresses
  sigma_BFN = M_BN / W_eqw K_e, sigma_QFN = Q_N / F K_e with W_eqw = B W^2 / 6, F = B W and
  K_e = 0.8 for two-stroke and 1.0 for four-stroke engines (2.1.2.1); the crankpin's at the oil
  bore sigma_BON = M_BON / W_e with W_e = pi/32 (D^4 - D_BH^4)/D (2.1.2.2); the torsional
  tau_N = M_TN / W_P with W_P = pi/16 (D^4 - D_BH^4)/D (crankpin) or pi/16 (D_G^4 - D_BG^4)/D_G
  (journal) (2.2.2); M_BN, Q_N, M_BON and M_TN are half-ranges, half of (largest - smallest).
- Stress concentration factors (M53.3): :func:`crankpin_bending_scf` (alpha_B),
  :func:`crankpin_torsion_scf` (alpha_T), :func:`journal_bending_scf` (beta_B),
  :func:`journal_shear_scf` (beta_Q), :func:`journal_torsion_scf` (beta_T) and
  :func:`oil_bore_scf` (gamma_B, gamma_T), each valid in the ranges of :func:`validity`.
- Stresses in the fillets and at the oil bore (2.1.3, 2.1.4, 2.2.3): sigma_BH = alpha_B
  sigma_BFN, sigma_BG = beta_B sigma_BFN + beta_Q sigma_QFN, sigma_BO = gamma_B sigma_BON,
  tau_H = alpha_T tau_N, tau_G = beta_T tau_N, sigma_TO = gamma_T tau_N.
- Additional bending stress (M53.4), equivalent stress (M53.5), fatigue strength (M53.6),
  acceptability Q = sigma_DW / sigma_V >= 1.15 (M53.7) and the shrink fits of semi-built
  crankshafts (M53.8).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "ADDITIONAL_STRESS",
    "LOCATION_FACTORS",
    "Q_MIN",
    "REFERENCE_DIAMETER",
    "RULE",
    "Ratios",
    "ValidityRange",
    "acceptability",
    "additional_stress",
    "crankpin_bending_scf",
    "crankpin_torsion_scf",
    "equivalent_fillet_stress",
    "equivalent_oil_bore_stress",
    "fatigue_strength",
    "half_range",
    "journal_bending_scf",
    "journal_shear_scf",
    "journal_torsion_scf",
    "ke_factor",
    "maximum_journal_bore",
    "maximum_oversize",
    "minimum_oversize",
    "nominal_web_stresses",
    "oil_bore_scf",
    "pin_section_modulus",
    "polar_section_modulus",
    "size_term",
    "validity",
    "web_section",
]

RULE = "IACS UR M53 (as KR Rules 2025 Pt 5 Annex 5-3)"
"""The rule cited in every M53 verdict, with the text it was read in (module docstring)."""

Q_MIN = 1.15
"""The smallest acceptability factor Q the rule accepts (M53.7; read in Annex 5-3 Appendix V
3(3), "an acceptability factor of Q >= 1.15", item 7 itself missing from the copy read)."""

ADDITIONAL_STRESS = {"trunk-piston": 10e6, "crosshead": 30e6}
"""sigma_add of M53.4 [Annex 5-3 4(1), its table] (Pa): +-10 N/mm^2 for trunk-piston engines,
+-30 N/mm^2 for crosshead engines (its notes: 20 from axial vibration, 10 from misalignment and
bedplate deformation)."""

_AXIAL_CROSSHEAD = 20e6
_MISALIGNMENT_CROSSHEAD = 10e6

_MM = 1e3  # m -> mm
_MPA = 1e6  # N/mm^2 -> Pa
_MIN_RADIUS_MM = 2.0  # M53.6: R_H, R_G, R_X not less than 2 mm

REFERENCE_DIAMETER = (0.736 / 1.073) ** -5 / _MM
"""The diameter (m) at which the size term 0.264 + 1.073 D^-0.2 of the fatigue strength (M53.6,
D in mm) is 1, about 6.59 mm (:func:`size_term`): algebra on the text's formula, for the
limiting-case test; the text attaches no meaning to it."""


# ---- nominal stresses (M53.2) ------------------------------------------------------------------


def half_range(values: ArrayLike, axis: int = -1) -> NDArray[np.float64]:
    """Half of the range of a quantity over the working cycle, (largest - smallest)/2: the
    nominal alternating value of UR M53 2.1.2.1 (M_BN, Q_N), 2.1.2.2 (M_BON) and 2.2.2 (M_TN).

    Verified: Annex 5-3 2(1)(B)(a)(v), X_N = +-1/2 [X_max - X_min], and the same for M_BRFN,
    Q_RFN, M_BON (2(1)(B)(b), (c)) and M_TN (2(2)(A)(e)).

    Parameters
    ----------
    values : array_like
        The quantity over the cycle (its unit), the angles along ``axis``.
    axis : int
        The axis of the angles.

    Returns
    -------
    numpy.ndarray
        The half-range (the quantity's unit).

    Examples
    --------
    >>> float(half_range([-20.0, 100.0, 40.0]))
    60.0
    """
    v = np.asarray(values, dtype=float)
    return 0.5 * (np.max(v, axis=axis) - np.min(v, axis=axis))


def ke_factor(cycle: str) -> float:
    """K_e, the empirical factor for the restraint of the adjacent cranks and bearings (UR M53
    2.1.2.1): 0.8 for two-stroke, 1.0 for four-stroke engines.

    Verified: Annex 5-3 2(1)(B)(b), "K_e = 0.8 for 2-stroke engines, K_e = 1.0 for 4-stroke
    engines".

    Parameters
    ----------
    cycle : str
        ``"two-stroke"`` or ``"four-stroke"``.

    Returns
    -------
    float
        K_e (dimensionless).

    Examples
    --------
    >>> ke_factor("two-stroke"), ke_factor("four-stroke")
    (0.8, 1.0)
    """
    return 0.8 if cycle == "two-stroke" else 1.0


def web_section(web_width: float, web_thickness: float) -> tuple[float, float]:
    """The web's cross-section at its centre (UR M53 2.1.2.1).

    Verified: Annex 5-3 2(1)(B)(b), W_eqw = B W^2 / 6 (mm^3) and F = B W (mm^2), the reference
    section of its Fig 3 (web thickness W, web width B).

    Parameters
    ----------
    web_width : float
        B (m).
    web_thickness : float
        W (m).

    Returns
    -------
    w_eqw : float
        W_eqw = B W^2 / 6, the section modulus for bending in the plane of the throw (m^3).
    area : float
        F = B W (m^2).

    Examples
    --------
    >>> w, f = web_section(0.3, 0.1)
    >>> round(w * 1e9), round(f * 1e6)  # mm^3, mm^2
    (500000, 30000)
    """
    return web_width * web_thickness**2 / 6.0, web_width * web_thickness


def nominal_web_stresses(
    moment: ArrayLike, force: ArrayLike, web_width: float, web_thickness: float, ke: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Nominal alternating bending and compressive stresses of the web (UR M53 2.1.2.1):
    sigma_BFN = M_BN / W_eqw K_e and sigma_QFN = Q_N / F K_e.

    Verified: Annex 5-3 2(1)(B)(b), sigma_BFN = +-M_BRFN / W_eqw 10^3 K_e (M in N m, W_eqw in
    mm^3, so 10^3 converts) and sigma_QFN = +-Q_RFN / F K_e; here in SI, no factor.

    Parameters
    ----------
    moment : array_like
        M_BN, half-range of the bending moment at the web centre (N m).
    force : array_like
        Q_N, half-range of the radial force in the web (N).
    web_width, web_thickness : float
        B and W (m).
    ke : float
        K_e (:func:`ke_factor`; dimensionless).

    Returns
    -------
    sigma_bfn, sigma_qfn : numpy.ndarray
        The stresses (Pa).

    Examples
    --------
    50 kN m and 400 kN on a 300 x 100 mm web of a four-stroke engine:

    >>> s_b, s_q = nominal_web_stresses(50e3, 400e3, 0.3, 0.1, 1.0)
    >>> float(s_b) / 1e6, round(float(s_q) / 1e6, 6)  # N/mm^2
    (100.0, 13.333333)
    """
    w_eqw, area = web_section(web_width, web_thickness)
    m = np.asarray(moment, dtype=float)
    q = np.asarray(force, dtype=float)
    return m / w_eqw * ke, q / area * ke


def pin_section_modulus(diameter: float, bore: float = 0.0) -> float:
    """W_e = pi/32 (D^4 - D_BH^4)/D, the axially bored crankpin's section modulus in bending
    (UR M53 2.1.2.2).

    Verified: Annex 5-3 2(1)(B)(c), W_e = pi/32 [(D^4 - D_BH^4)/D], for sigma_BON =
    +-M_BON / W_e 10^3 with M_BO = M_BTO cos(psi) + M_BRO sin(psi).

    Parameters
    ----------
    diameter : float
        D (m).
    bore : float
        D_BH (m); 0 for a solid pin.

    Returns
    -------
    float
        W_e (m^3).

    Examples
    --------
    >>> round(pin_section_modulus(0.2) * 1e9, 3)  # mm^3
    785398.163
    """
    return math.pi / 32.0 * (diameter**4 - bore**4) / diameter


def polar_section_modulus(diameter: float, bore: float = 0.0) -> float:
    """W_P = pi/16 (D^4 - D_B^4)/D, the polar section modulus of the crankpin or the journal
    (UR M53 2.2.2).

    Verified: Annex 5-3 2(2)(A)(e), W_P = pi/16 ((D^4 - D_BH^4)/D) or pi/16 ((D_G^4 -
    D_BG^4)/D_G), for tau_N = +-M_TN / W_P 10^3.

    Parameters
    ----------
    diameter : float
        D or D_G (m).
    bore : float
        D_BH or D_BG (m); 0 when solid.

    Returns
    -------
    float
        W_P (m^3).

    Examples
    --------
    >>> round(polar_section_modulus(0.2, 0.1) * 1e9, 3)  # mm^3
    1472621.556
    """
    return math.pi / 16.0 * (diameter**4 - bore**4) / diameter


# ---- stress concentration factors (M53.3) --------------------------------------------------------


@dataclass(frozen=True)
class Ratios:
    """The dimensions of a crank throw related to the crankpin diameter D (UR M53.3.1).

    Verified: Annex 5-3 3(1)(G), its table of related dimensions: r = R_H/D and r = R_G/D,
    s = S/D, w = W/D (W_red/D where the web is reduced), b = B/D, d_O = D_O/D, d_G = D_BG/D,
    d_H = D_BH/D, t_H = T_H/D, t_G = T_G/D; and 3(3)(C)(b), r = R_G/D_G for beta_T of a journal
    differing from the crankpin.

    Parameters
    ----------
    r_pin : float
        r = R_H / D (crankpin fillet).
    r_journal : float
        r = R_G / D (journal fillet).
    s : float
        s = S / D (overlap; negative without).
    w : float
        w = W / D (web thickness).
    b : float
        b = B / D (web width).
    d_g : float
        d_G = D_BG / D (journal bore).
    d_h : float
        d_H = D_BH / D (crankpin bore).
    t_h : float
        t_H = T_H / D (crankpin fillet recess).
    t_g : float
        t_G = T_G / D (journal fillet recess).
    d_o : float or None
        d_O = D_O / D (oil bore), None without one.
    r_journal_own : float
        R_G / D_G, the journal fillet related to the journal diameter (beta_T, M53.3.3).
    same_pin_and_journal : bool
        Whether crankpin and journal have the same diameter and fillet radius (then
        beta_T = alpha_T, M53.3.3).

    All dimensionless.
    """

    r_pin: float
    r_journal: float
    s: float
    w: float
    b: float
    d_g: float
    d_h: float
    t_h: float
    t_g: float
    d_o: float | None
    r_journal_own: float
    same_pin_and_journal: bool

    @classmethod
    def of(
        cls,
        *,
        pin_diameter: float,
        journal_diameter: float,
        pin_fillet_radius: float,
        journal_fillet_radius: float,
        overlap: float,
        web_thickness: float,
        web_width: float,
        pin_bore: float = 0.0,
        journal_bore: float = 0.0,
        pin_recess: float = 0.0,
        journal_recess: float = 0.0,
        oil_bore_diameter: float | None = None,
    ) -> Ratios:
        """The ratios of a throw's dimensions (all in m).

        Parameters
        ----------
        pin_diameter, journal_diameter : float
            D and D_G (m).
        pin_fillet_radius, journal_fillet_radius : float
            R_H and R_G (m).
        overlap : float
            S (m).
        web_thickness, web_width : float
            W (or W_red, :func:`crankdyn.crankshaft.strength`) and B (m).
        pin_bore, journal_bore : float
            D_BH and D_BG (m).
        pin_recess, journal_recess : float
            T_H and T_G (m).
        oil_bore_diameter : float or None
            D_O (m).

        Returns
        -------
        Ratios
            The ratios (dimensionless).

        Examples
        --------
        >>> q = Ratios.of(pin_diameter=0.2, journal_diameter=0.2, pin_fillet_radius=0.01,
        ...               journal_fillet_radius=0.01, overlap=0.04, web_thickness=0.08,
        ...               web_width=0.3)
        >>> q.r_pin, q.s, q.w, q.b
        (0.05, 0.2, 0.4, 1.5)
        """
        d = pin_diameter
        return cls(
            r_pin=pin_fillet_radius / d,
            r_journal=journal_fillet_radius / d,
            s=overlap / d,
            w=web_thickness / d,
            b=web_width / d,
            d_g=journal_bore / d,
            d_h=pin_bore / d,
            t_h=pin_recess / d,
            t_g=journal_recess / d,
            d_o=None if oil_bore_diameter is None else oil_bore_diameter / d,
            r_journal_own=journal_fillet_radius / journal_diameter,
            same_pin_and_journal=(
                pin_diameter == journal_diameter and pin_fillet_radius == journal_fillet_radius
            ),
        )


def _s_limited(s: float) -> float:
    """s below -0.5 replaced by -0.5: in f(s,w) and f(r,s) as Annex 5-3 3(1)(H) says (M53.3.1),
    and here also in f_B(s,w) and f_Q(s) of the journal fillet (not verified against a text;
    module docstring)."""
    return max(s, -0.5)


def recess_factor(q: Ratios) -> float:
    """f(recess) = 1 + (t_H + t_G)(1.8 + 3.2 s), not below 1 (UR M53.3.2).

    Verified: Annex 5-3 3(2)(A) and 3(3)(A), (B), f(recess) = 1 + (t_H + t_G)(1.8 + 3.2 s);
    3(1)(H), "if calculated f(recess) < 1 then the factor f(recess) is not to be considered
    (f(recess) = 1)". s is the actual s here (3(1)(H) replaces it in f(s,w) and f(r,s) only).

    Parameters
    ----------
    q : Ratios
        The throw's ratios.

    Returns
    -------
    float
        f(recess) (dimensionless).

    Examples
    --------
    >>> q = Ratios(0.05, 0.05, 0.2, 0.4, 1.5, 0.0, 0.0, 0.01, 0.01, None, 0.05, True)
    >>> round(recess_factor(q), 12)
    1.0488
    """
    return max(1.0 + (q.t_h + q.t_g) * (1.8 + 3.2 * q.s), 1.0)


def crankpin_bending_scf(q: Ratios) -> float:
    """alpha_B, the crankpin fillet's stress concentration factor in bending (UR M53.3.2):

    ::

        alpha_B = 2.6914 f(s,w) f(w) f(b) f(r) f(d_G) f(d_H) f(recess)
        f(s,w)  = -4.1883 + 29.2004 w - 77.5925 w^2 + 91.9454 w^3 - 40.0416 w^4
                  + (1 - s)(9.5440 - 58.3480 w + 159.3415 w^2 - 192.5846 w^3 + 85.2916 w^4)
                  + (1 - s)^2 (-3.8399 + 25.0444 w - 70.5571 w^2 + 87.0328 w^3 - 39.1832 w^4)
        f(w)    = 2.1790 w^0.7171
        f(b)    = 0.6840 - 0.0077 b + 0.1473 b^2
        f(r)    = 0.2081 r^-0.5231          (r = R_H / D)
        f(d_G)  = 0.9993 + 0.27 d_G - 1.0211 d_G^2 + 0.5306 d_G^3
        f(d_H)  = 0.9978 + 0.3145 d_H - 1.5241 d_H^2 + 2.4147 d_H^3

    with s below -0.5 taken as -0.5 and f(recess) (:func:`recess_factor`) not below 1.

    Verified: Annex 5-3 3(2)(A), every coefficient as printed there; 3(1)(H) for s and
    f(recess); r = R_H / D, d_G = D_BG / D, d_H = D_BH / D (3(1)(G)).

    Parameters
    ----------
    q : Ratios
        The throw's ratios.

    Returns
    -------
    float
        alpha_B (dimensionless).
    """
    s, w = _s_limited(q.s), q.w
    u = 1.0 - s
    f_sw = (
        -4.1883
        + 29.2004 * w
        - 77.5925 * w**2
        + 91.9454 * w**3
        - 40.0416 * w**4
        + u * (9.5440 - 58.3480 * w + 159.3415 * w**2 - 192.5846 * w**3 + 85.2916 * w**4)
        + u**2 * (-3.8399 + 25.0444 * w - 70.5571 * w**2 + 87.0328 * w**3 - 39.1832 * w**4)
    )
    f_w = 2.1790 * w**0.7171
    f_b = 0.6840 - 0.0077 * q.b + 0.1473 * q.b**2
    f_r = 0.2081 * q.r_pin**-0.5231
    f_dg = 0.9993 + 0.27 * q.d_g - 1.0211 * q.d_g**2 + 0.5306 * q.d_g**3
    f_dh = 0.9978 + 0.3145 * q.d_h - 1.5241 * q.d_h**2 + 2.4147 * q.d_h**3
    return 2.6914 * f_sw * f_w * f_b * f_r * f_dg * f_dh * recess_factor(q)


def _torsion_terms(r: float, s: float, b: float, w: float) -> float:
    """f(r,s) f(b) f(w) of alpha_T and beta_T (M53.3.2 [Annex 5-3 3(2)(B)], M53.3.3; f(b)'s
    last coefficient -0.85 as printed, module docstring)."""
    s = _s_limited(s)
    f_rs = r ** (-0.322 + 0.1015 * (1.0 - s))
    f_b = 7.8955 - 10.654 * b + 5.3482 * b**2 - 0.85 * b**3
    f_w = w**-0.145
    return f_rs * f_b * f_w


def crankpin_torsion_scf(q: Ratios) -> float:
    """alpha_T, the crankpin fillet's stress concentration factor in torsion (UR M53.3.2):

    ::

        alpha_T = 0.8 f(r,s) f(b) f(w)
        f(r,s)  = r^(-0.322 + 0.1015 (1 - s))      (r = R_H / D)
        f(b)    = 7.8955 - 10.654 b + 5.3482 b^2 - 0.85 b^3
        f(w)    = w^-0.145

    Verified: Annex 5-3 3(2)(B) as printed, with s below -0.5 taken as -0.5 in f(r,s)
    (3(1)(H)). The b^3 coefficient is printed "0.85" (two decimals where the others have
    four); the -0.857 of an earlier version was not from a text. -0.85 gives the larger
    alpha_T (module docstring).

    Parameters
    ----------
    q : Ratios
        The throw's ratios.

    Returns
    -------
    float
        alpha_T (dimensionless).
    """
    return 0.8 * _torsion_terms(q.r_pin, q.s, q.b, q.w)


def journal_bending_scf(q: Ratios) -> float:
    """beta_B, the journal fillet's stress concentration factor in bending (UR M53.3.3):

    ::

        beta_B   = 2.7146 f_B(s,w) f_B(w) f_B(b) f_B(r) f_B(d_G) f_B(d_H) f(recess)
        f_B(s,w) = -1.7625 + 2.9821 w - 1.527 w^2 + (1 - s)(5.1169 - 5.8089 w + 3.1391 w^2)
                   + (1 - s)^2 (-2.1567 + 2.3297 w - 1.2952 w^2)
        f_B(w)   = 2.2422 w^0.7548
        f_B(b)   = 0.5616 + 0.1197 b + 0.1176 b^2
        f_B(r)   = 0.1908 r^-0.5568         (r = R_G / D)
        f_B(d_G) = 1.0012 - 0.6441 d_G + 1.2265 d_G^2
        f_B(d_H) = 1.0022 - 0.1903 d_H + 0.0073 d_H^2

    Verified: Annex 5-3 3(3)(A) as printed (not for semi-built crankshafts). The w^2
    coefficient of f_B(s,w) is printed "1.527" (three decimals where the others have four);
    the -1.5276 of an earlier version was not from a text; the printed value gives the larger
    beta_B, by less than 0.07 % within the ranges (module docstring). s below -0.5 taken as
    -0.5 in f_B(s,w): not verified against a text (3(1)(H) names f(s,w) and f(r,s)).

    Parameters
    ----------
    q : Ratios
        The throw's ratios.

    Returns
    -------
    float
        beta_B (dimensionless).
    """
    s, w = _s_limited(q.s), q.w
    u = 1.0 - s
    f_sw = (
        -1.7625
        + 2.9821 * w
        - 1.527 * w**2
        + u * (5.1169 - 5.8089 * w + 3.1391 * w**2)
        + u**2 * (-2.1567 + 2.3297 * w - 1.2952 * w**2)
    )
    f_w = 2.2422 * w**0.7548
    f_b = 0.5616 + 0.1197 * q.b + 0.1176 * q.b**2
    f_r = 0.1908 * q.r_journal**-0.5568
    f_dg = 1.0012 - 0.6441 * q.d_g + 1.2265 * q.d_g**2
    f_dh = 1.0022 - 0.1903 * q.d_h + 0.0073 * q.d_h**2
    return 2.7146 * f_sw * f_w * f_b * f_r * f_dg * f_dh * recess_factor(q)


def journal_shear_scf(q: Ratios) -> float:
    """beta_Q, the journal fillet's stress concentration factor for the web's radial force
    (UR M53.3.3):

    ::

        beta_Q   = 3.0128 f_Q(s) f_Q(w) f_Q(b) f_Q(r) f_Q(d_H) f(recess)
        f_Q(s)   = 0.4368 + 2.1630 (1 - s) - 1.5212 (1 - s)^2
        f_Q(w)   = w / (0.0637 + 0.9369 w)
        f_Q(b)   = -0.5 + b
        f_Q(r)   = 0.5331 r^-0.2038         (r = R_G / D)
        f_Q(d_H) = 0.9937 - 1.1949 d_H + 1.7373 d_H^2

    Verified: Annex 5-3 3(3)(B) as printed. s below -0.5 taken as -0.5 in f_Q(s): not
    verified against a text (3(1)(H) names f(s,w) and f(r,s); f_Q(s) is negative below
    s = -0.6 without it).

    Parameters
    ----------
    q : Ratios
        The throw's ratios.

    Returns
    -------
    float
        beta_Q (dimensionless).
    """
    u = 1.0 - _s_limited(q.s)
    f_s = 0.4368 + 2.1630 * u - 1.5212 * u**2
    f_w = q.w / (0.0637 + 0.9369 * q.w)
    f_b = -0.5 + q.b
    f_r = 0.5331 * q.r_journal**-0.2038
    f_dh = 0.9937 - 1.1949 * q.d_h + 1.7373 * q.d_h**2
    return 3.0128 * f_s * f_w * f_b * f_r * f_dh * recess_factor(q)


def journal_torsion_scf(q: Ratios) -> float:
    """beta_T, the journal fillet's stress concentration factor in torsion (UR M53.3.3):
    alpha_T when crankpin and journal have the same diameter and fillet radius, else
    0.8 f(r,s) f(b) f(w) of :func:`crankpin_torsion_scf` with the journal fillet related to
    the journal diameter, r = R_G / D_G.

    Verified: Annex 5-3 3(3)(C)(a) "if the diameters and fillet radii of crankpin and
    journal are the same, beta_T = alpha_T" and (b) "... the radius of the journal fillet is
    to be related to the journal diameter: r = R_G / D_G".

    Parameters
    ----------
    q : Ratios
        The throw's ratios.

    Returns
    -------
    float
        beta_T (dimensionless).
    """
    if q.same_pin_and_journal:
        return crankpin_torsion_scf(q)
    return 0.8 * _torsion_terms(q.r_journal_own, q.s, q.b, q.w)


def oil_bore_scf(d_o: float) -> tuple[float, float]:
    """gamma_B and gamma_T, the stress concentration factors at the outlet of the crankpin's
    oil bore (UR M53.3.4): gamma_B = 3 - 5.88 d_O + 34.6 d_O^2, gamma_T = 4 - 6 d_O +
    30 d_O^2 (d_O = D_O / D).

    Verified: Annex 5-3 3(3)(D)(a), (b) (KR numbers the oil bore under item 3(3)); a radially
    drilled oil hole only (3(1)(A)).

    Parameters
    ----------
    d_o : float
        d_O (dimensionless).

    Returns
    -------
    gamma_b, gamma_t : float
        Bending and torsion (dimensionless).

    Examples
    --------
    >>> tuple(round(g, 6) for g in oil_bore_scf(0.1))
    (2.758, 3.7)
    """
    return 3.0 - 5.88 * d_o + 34.6 * d_o**2, 4.0 - 6.0 * d_o + 30.0 * d_o**2


LOCATION_FACTORS = {
    "crankpin fillet": ("alpha_B", "alpha_T"),
    "journal fillet": ("beta_B", "beta_Q", "beta_T"),
    "oil bore": ("gamma_B", "gamma_T"),
}
"""The stress concentration factors of every location UR M53 checks (M53.1.3, M53.3; Annex 5-3
1(2)(B): the fillets between crankpin and web and between journal and web, and the outlets of
the crankpin oil bores)."""


@dataclass(frozen=True)
class ValidityRange:
    """A ratio of the throw against the range of the rule's empirical formulas (M53.3).

    Parameters
    ----------
    name : str
        The ratio's symbol (``"w"``, ``"r (crankpin fillet)"``).
    value : float
        Its value (dimensionless).
    low, high : float
        The range (dimensionless; -inf or inf where open).
    applies_to : str
        The factors the range limits (``"alpha_B, alpha_T"``).
    clause : str
        The clause.
    """

    name: str
    value: float
    low: float
    high: float
    applies_to: str
    clause: str

    def limits(self, location: str) -> bool:
        """Whether the range limits the factors of a location.

        Parameters
        ----------
        location : str
            ``"crankpin fillet"``, ``"journal fillet"`` or ``"oil bore"``.

        Returns
        -------
        bool
            True when one of the location's factors is in :attr:`applies_to`.
        """
        return any(symbol in self.applies_to for symbol in LOCATION_FACTORS[location])

    @property
    def valid(self) -> bool:
        """Whether the value lies in the range (ends included)."""
        return self.low <= self.value <= self.high

    def to_dict(self) -> dict[str, object]:
        """The range as JSON data.

        Returns
        -------
        dict
            ``ratio``, ``value``, ``low``, ``high`` (None where open), ``valid``,
            ``applies_to``, ``clause``.
        """
        return {
            "ratio": self.name,
            "value": self.value,
            "low": None if math.isinf(self.low) else self.low,
            "high": None if math.isinf(self.high) else self.high,
            "valid": self.valid,
            "applies_to": self.applies_to,
            "clause": self.clause,
        }

    def text(self) -> str:
        """The ratio and its range for people: ``"w = 0.85 outside 0.2 <= w <= 0.8"``.

        Returns
        -------
        str
            One phrase.
        """
        if math.isinf(self.low):
            bounds = f"{self.name} <= {self.high:g}"
        elif math.isinf(self.high):
            bounds = f"{self.name} >= {self.low:g}"
        else:
            bounds = f"{self.low:g} <= {self.name} <= {self.high:g}"
        where = "within" if self.valid else "outside"
        return f"{self.name} = {self.value:.4g} {where} {bounds}"


def validity(q: Ratios, *, journal: bool = True) -> list[ValidityRange]:
    """The ranges of the empirical stress concentration factors (UR M53.3.1) with the throw's
    values: s <= 0.5, 0.2 <= w <= 0.8, 1.1 <= b <= 2.2, 0.03 <= r <= 0.13 (crankpin and journal
    fillet), 0 <= d_G <= 0.8, 0 <= d_H <= 0.8, 0 <= d_O <= 0.2. The low end of s is open: the
    rule takes s below -0.5 as -0.5 in f(s,w) and f(r,s).

    Verified: Annex 5-3 3(1)(G), the ranges printed in its table of related dimensions
    (0.03 <= r <= 0.13 for r = R_H/D and r = R_G/D, s <= 0.5, 0.2 <= w <= 0.8, 1.1 <= b <= 2.2,
    0 <= d_O <= 0.2, 0 <= d_G <= 0.8, 0 <= d_H <= 0.8; none for t_H, t_G); 3(1)(H), "low
    range of s can be extended down to large negative values" with s < -0.5 taken as -0.5.
    Which factors each range limits is crankdyn's reading (the table lists the ranges under
    "crankpin fillet" and "journal fillet"; d_O limits the oil bore's).

    Parameters
    ----------
    q : Ratios
        The throw's ratios.
    journal : bool
        Whether the journal fillet is checked (not for a semi-built crankshaft).

    Returns
    -------
    list of ValidityRange
        One per ratio; ``valid`` tells which lie outside.

    Examples
    --------
    >>> q = Ratios(0.05, 0.05, 0.2, 0.85, 1.5, 0.0, 0.0, 0.0, 0.0, 0.1, 0.05, True)
    >>> [v.text() for v in validity(q) if not v.valid]
    ['w = 0.85 outside 0.2 <= w <= 0.8']
    """
    inf = math.inf
    fillets = "alpha_B, alpha_T" + (", beta_B, beta_Q, beta_T" if journal else "")
    out = [
        ValidityRange("s", q.s, -inf, 0.5, fillets, "M53.3.1"),
        ValidityRange("w", q.w, 0.2, 0.8, fillets, "M53.3.1"),
        ValidityRange("b", q.b, 1.1, 2.2, fillets, "M53.3.1"),
        ValidityRange("r (crankpin fillet)", q.r_pin, 0.03, 0.13, "alpha_B, alpha_T", "M53.3.1"),
    ]
    if journal:
        out.append(
            ValidityRange(
                "r (journal fillet)", q.r_journal, 0.03, 0.13, "beta_B, beta_Q, beta_T", "M53.3.1"
            )
        )
    out += [
        ValidityRange("d_G", q.d_g, 0.0, 0.8, fillets, "M53.3.1"),
        ValidityRange("d_H", q.d_h, 0.0, 0.8, fillets, "M53.3.1"),
    ]
    if q.d_o is not None:
        out.append(ValidityRange("d_O", q.d_o, 0.0, 0.2, "gamma_B, gamma_T", "M53.3.1"))
    return out


# ---- additional, equivalent and permissible stresses (M53.4 to M53.7) -------------------------


def additional_stress(engine_type: str, axial_vibration: float | None = None) -> float:
    """sigma_add, the additional bending stress of misalignment, bedplate deformation and
    axial and bending vibration (UR M53.4): 10 N/mm^2 for trunk-piston engines; 30 N/mm^2 for
    crosshead engines, of which 20 from axial vibration, which the calculated value replaces
    where the axial vibration calculation of the whole system gives it.

    Verified: Annex 5-3 4(1) (table and notes: +-30 crosshead = +-20 axial vibration + +-10
    misalignment/bedplate deformation; +-10 trunk piston), 4(2) (+-20 recommended where the
    axial vibration results of the complete dynamic system are not available) and 4(3) (the
    calculated figures may be used instead).

    Parameters
    ----------
    engine_type : str
        ``"trunk-piston"`` or ``"crosshead"``.
    axial_vibration : float or None
        Crosshead engines: the calculated axial vibration stress (Pa), or None for 20 MPa.

    Returns
    -------
    float
        sigma_add (Pa).

    Examples
    --------
    >>> additional_stress("trunk-piston") / 1e6, additional_stress("crosshead", 12e6) / 1e6
    (10.0, 22.0)
    """
    if engine_type == "crosshead":
        axial = _AXIAL_CROSSHEAD if axial_vibration is None else axial_vibration
        return axial + _MISALIGNMENT_CROSSHEAD
    return ADDITIONAL_STRESS[engine_type]


def equivalent_fillet_stress(
    bending: ArrayLike, additional: float, torsion: ArrayLike
) -> NDArray[np.float64]:
    """sigma_V = sqrt((sigma_BH + sigma_add)^2 + 3 tau_H^2) in the crankpin fillet, and the
    same with sigma_BG and tau_G in the journal fillet (UR M53.5.2; von Mises of the
    alternating stresses).

    Verified: Annex 5-3 5(2) and 5(3), and 5(1)(A) (von Mises, bending and torsion time
    phased with their peaks at the same location).

    Parameters
    ----------
    bending : array_like
        sigma_BH or sigma_BG (Pa).
    additional : float
        sigma_add (Pa).
    torsion : array_like
        tau_H or tau_G (Pa).

    Returns
    -------
    numpy.ndarray
        sigma_V (Pa).

    Examples
    --------
    >>> float(equivalent_fillet_stress(20e6, 10e6, 40e6 / math.sqrt(3.0))) / 1e6
    50.0
    """
    b = np.asarray(bending, dtype=float)
    t = np.asarray(torsion, dtype=float)
    return np.sqrt((b + additional) ** 2 + 3.0 * t**2)


def equivalent_oil_bore_stress(bending: ArrayLike, torsion: ArrayLike) -> NDArray[np.float64]:
    """sigma_V = 1/3 sigma_BO [1 + 2 sqrt(1 + 9/4 (sigma_TO / sigma_BO)^2)] at the outlet of
    the crankpin oil bore (UR M53.5.2), written as (sigma_BO + 2 sqrt(sigma_BO^2 +
    9/4 sigma_TO^2)) / 3, the same for sigma_BO > 0 and sigma_TO at sigma_BO = 0.

    Verified: Annex 5-3 5(4) (and 5(1)(B): the largest principal stress of the two fields,
    time phased). The form without the quotient is algebra on it, so that sigma_BO = 0 (no
    bending) is defined.

    Parameters
    ----------
    bending : array_like
        sigma_BO (Pa), >= 0.
    torsion : array_like
        sigma_TO (Pa).

    Returns
    -------
    numpy.ndarray
        sigma_V (Pa).

    Examples
    --------
    >>> float(equivalent_oil_bore_stress(30e6, 0.0)) / 1e6
    30.0
    >>> float(equivalent_oil_bore_stress(0.0, 7e6)) / 1e6
    7.0
    """
    b = np.abs(np.asarray(bending, dtype=float))
    t = np.asarray(torsion, dtype=float)
    return (b + 2.0 * np.sqrt(b**2 + 2.25 * t**2)) / 3.0


def size_term(diameter: float) -> float:
    """0.264 + 1.073 D^-0.2 (D in mm), the size term of the fatigue strength (UR M53.6); 1 at
    :data:`REFERENCE_DIAMETER`.

    Verified: Annex 5-3 6(1) and 6(2)(A), the first two terms of the bracket.

    Parameters
    ----------
    diameter : float
        D or D_G (m).

    Returns
    -------
    float
        The term (dimensionless).

    Examples
    --------
    >>> round(size_term(REFERENCE_DIAMETER), 12)
    1.0
    """
    return 0.264 + 1.073 * (diameter * _MM) ** -0.2


def fatigue_strength(tensile_strength: float, diameter: float, radius: float, k: float) -> float:
    """sigma_DW, the crankshaft's fatigue strength (UR M53.6), in the rule's units (N/mm^2,
    mm):

    ::

        sigma_DW = K (0.42 sigma_B + 39.3) [0.264 + 1.073 D^-0.2 + (785 - sigma_B)/4900
                   + 196/sigma_B sqrt(1/R_X)]

    related to the crankpin diameter D with R_X = R_H in the fillet and R_X = D_O/2 at the oil
    bore, or to the journal diameter D_G with R_G; R_H, R_G and R_X are taken as not less than
    2 mm.

    Verified: Annex 5-3 6(1) (crankpin, R_X = R_H in the fillet area, D_O/2 in the oil bore
    area), 6(2)(A) (journal, R_G; K = 1.05 continuous grain flow forged or drop-forged, 1.0
    free form forged, 0.93 cast steel with approved cold rolling of the fillets, "values
    greater than 1 are only applicable to fatigue strength in fillet area"; "R_H, R_G or R_X
    are to be taken as not less than 2 mm"; sigma_B the minimum tensile strength). Surface
    treatment: 6(2)(B), approved by the society, Appendix V; no factor in the text.

    Parameters
    ----------
    tensile_strength : float
        sigma_B, the specified minimum tensile strength (Pa).
    diameter : float
        D or D_G (m).
    radius : float
        R_H, R_G or D_O/2 (m).
    k : float
        K (:data:`crankdyn.crankshaft.geometry.MANUFACTURE_FACTORS`; at most 1 at the oil
        bore, dimensionless).

    Returns
    -------
    float
        sigma_DW (Pa).

    Examples
    --------
    sigma_B = 800 N/mm^2, D = 200 mm, R_H = 10 mm, K = 1:

    >>> round(fatigue_strength(800e6, 0.2, 0.01, 1.0) / 1e6, 3)
    266.571
    """
    s_b = tensile_strength / _MPA
    d = diameter * _MM
    r = max(radius * _MM, _MIN_RADIUS_MM)
    bracket = 0.264 + 1.073 * d**-0.2 + (785.0 - s_b) / 4900.0 + 196.0 / s_b * math.sqrt(1.0 / r)
    return k * (0.42 * s_b + 39.3) * bracket * _MPA


def acceptability(strength: ArrayLike, equivalent: ArrayLike) -> NDArray[np.float64]:
    """Q = sigma_DW / sigma_V, the acceptability factor (UR M53.7), to be at least
    :data:`Q_MIN` = 1.15; infinite where sigma_V is 0.

    Verified: item 7 of Annex 5-3 is missing from the copy read; Appendix V 3(3) states the
    criterion ("compares the equivalent alternating stress and the fatigue strength ratio to an
    acceptability factor of Q >= 1.15 for oil bore outlets, crankpin fillets and journal
    fillets") and Appendix IV 4(3)(A) writes it as a ratio at the oil bore, Q = sigma_DWOT /
    sigma_v. Q as fatigue strength over equivalent stress is therefore read, not remembered.

    Parameters
    ----------
    strength : array_like
        sigma_DW (Pa).
    equivalent : array_like
        sigma_V (Pa).

    Returns
    -------
    numpy.ndarray
        Q (dimensionless).

    Examples
    --------
    >>> float(acceptability(230e6, 200e6))
    1.15
    """
    s, v = np.broadcast_arrays(
        np.asarray(strength, dtype=float), np.asarray(equivalent, dtype=float)
    )
    q = s / np.where(v > 0.0, v, 1.0)
    return np.where(np.isnan(s) | np.isnan(v), np.nan, np.where(v > 0.0, q, np.inf))


# ---- shrink fits of semi-built crankshafts (M53.8) ---------------------------------------------


def maximum_journal_bore(
    shrink_diameter: float,
    shrink_length: float,
    torque: float,
    pin_yield: float,
    friction: float = 0.2,
    slip_safety: float = 2.0,
) -> float:
    """The largest bore of a shrunk-in journal (UR M53.8.2; in the rule 4000 S_R M_max with
    M_max in N m and lengths in mm):

    ::

        D_BG <= D_S sqrt(1 - 4 S_R M_max / (mu pi D_S^2 L_S sigma_SP))

    so that the shrink pressure holding S_R M_max does not yield the hollow pin at its bore.

    Verified: Annex 5-3 8(2)(A) (S_R not less than 2 and mu not greater than 0.2 unless
    documented by experiments; M_max the absolute maximum of the torque M_Tmax of 2(2)(A);
    sigma_SP the journal pin's minimum yield strength) and 8(2)(B) (to avoid plasticity in
    the hole of the journal pin). Where the condition cannot be met, 8(1)(E): Z_min and Z_max
    are to come from FE calculations (multizone plasticity).

    Parameters
    ----------
    shrink_diameter, shrink_length : float
        D_S and L_S (m).
    torque : float
        M_max, the absolute largest torque of the crank span (N m).
    pin_yield : float
        sigma_SP, the journal pin's minimum yield strength (Pa).
    friction : float
        mu (dimensionless).
    slip_safety : float
        S_R (dimensionless).

    Returns
    -------
    float
        The largest D_BG (m); NaN when even a solid pin yields (the root's argument < 0).

    Examples
    --------
    >>> round(maximum_journal_bore(0.5, 0.3, 1.0e6, 400e6) * 1e3, 3)  # mm
    379.337
    """
    x = 1.0 - 4.0 * slip_safety * torque / (
        friction * math.pi * shrink_diameter**2 * shrink_length * pin_yield
    )
    return shrink_diameter * math.sqrt(x) if x >= 0.0 else math.nan


def minimum_oversize(
    shrink_diameter: float,
    shrink_length: float,
    web_outer_diameter: float,
    journal_bore: float,
    torque: float,
    web_yield: float,
    youngs_modulus: float,
    friction: float = 0.2,
    slip_safety: float = 2.0,
) -> float:
    """Z_min, the necessary smallest oversize of the shrink fit (UR M53.8.3): the greater of

    ::

        Z >= sigma_SW D_S / E_m   and
        Z >= 4 S_R M_max / (mu pi E_m D_S L_S) (1 - Q_A^2 Q_S^2) / ((1 - Q_A^2)(1 - Q_S^2))

    with Q_A = D_S / D_A and Q_S = D_BG / D_S (the rule's 4000 with M_max in N m and mm).

    Verified: Annex 5-3 8(3) ("determined by the greater value"; E_m Young's modulus,
    sigma_SW the web's minimum yield strength, Q_A the web ratio, Q_S the shaft ratio).

    Parameters
    ----------
    shrink_diameter, shrink_length, web_outer_diameter, journal_bore : float
        D_S, L_S, D_A and D_BG (m).
    torque : float
        M_max (N m).
    web_yield : float
        sigma_SW, the web's minimum yield strength (Pa).
    youngs_modulus : float
        E_m (Pa).
    friction, slip_safety : float
        mu and S_R (dimensionless).

    Returns
    -------
    float
        Z_min (m).

    Examples
    --------
    >>> round(minimum_oversize(0.5, 0.3, 0.9, 0.0, 1.0e6, 300e6, 2.05e11) * 1e3, 4)  # mm
    0.7317
    """
    qa = shrink_diameter / web_outer_diameter
    qs = journal_bore / shrink_diameter
    yield_term = web_yield * shrink_diameter / youngs_modulus
    torque_term = (
        4.0
        * slip_safety
        * torque
        / (friction * math.pi * youngs_modulus * shrink_diameter * shrink_length)
        * (1.0 - qa**2 * qs**2)
        / ((1.0 - qa**2) * (1.0 - qs**2))
    )
    return max(yield_term, torque_term)


def maximum_oversize(shrink_diameter: float, web_yield: float, youngs_modulus: float) -> float:
    """Z_max = D_S (sigma_SW / E_m + 0.8/1000), the largest oversize of the shrink fit (UR
    M53.8.4), which bounds the mean stress the fit induces in the journal fillet.

    Verified: Annex 5-3 8(4)(A), (B) ("to restrict the shrinkage induced mean stress in the
    fillet").

    Parameters
    ----------
    shrink_diameter : float
        D_S (m).
    web_yield : float
        sigma_SW (Pa).
    youngs_modulus : float
        E_m (Pa).

    Returns
    -------
    float
        Z_max (m).

    Examples
    --------
    >>> round(maximum_oversize(0.5, 300e6, 2.05e11) * 1e3, 4)  # mm
    1.1317
    """
    return shrink_diameter * (web_yield / youngs_modulus + 0.8e-3)
