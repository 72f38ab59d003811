"""The crankshaft of an engine for its fatigue check by IACS UR M53 (domain objects).

What the ``[crankshaft]`` table of an engine file holds (``crankdyn docs engine-file``): the
dimensions of one crank throw in the rule's symbols (UR M53 Fig. 1-3 and 2.1.1; the names of the
fields below, the rule's symbols in brackets), the material, how it was made, its surface
treatment, the engine type for the additional bending stresses (M53.4), the shrink fit of a
semi-built crankshaft (M53.8) and stress concentration factors found by finite elements (M53
Appendix III) where the user has them.

- crankpin diameter D, its axial bore D_BH, crankpin fillet radius R_H and recess T_H;
- journal diameter D_G, its bore D_BG, journal fillet radius R_G and recess T_G;
- web thickness W and web width B (the web's cross-section at its centre, 2.1.2.1);
- pin-journal overlap S = (D + D_G)/2 - R (R the crank radius; negative when the pin and the
  journal do not overlap), given or derived from the engine's crank radius;
- oil bore diameter D_O and its angular position psi in the crankpin (2.1.2.2);
- the distances of the statically determinate throw (2.1.1): L_1 from a main-bearing centre
  to the web centre, L_3 between the main-bearing centres (default the engine's cylinder
  pitch).

Lengths are held in m, strengths in Pa, angles in rad. The validity ranges of the rule's
empirical formulas are *not* checked here: a geometry outside them is legal, and the analysis
names it (:func:`crankdyn.crankshaft.m53.validity`).
"""

from __future__ import annotations

from dataclasses import dataclass

from crankdyn.crank.geometry import check_finite, check_length, check_positive
from crankdyn.crankshaft.beam_inputs import ADDITIONAL_STRESS_SOURCES, BeamInputs
from crankdyn.errors import InputError

__all__ = [
    "CONSTRUCTIONS",
    "ENGINE_TYPES",
    "MANUFACTURE_FACTORS",
    "STRESS_FACTOR_NAMES",
    "SURFACE_TREATMENTS",
    "YOUNGS_MODULUS_STEEL",
    "Crankshaft",
    "CrankshaftGeometry",
    "CrankshaftMaterial",
    "ShrinkFit",
    "StressFactors",
]

ENGINE_TYPES = ("trunk-piston", "crosshead")
"""Engine types of the additional bending stresses (UR M53.4)."""

CONSTRUCTIONS = ("solid", "semi-built")
"""Solid-forged (or cast) crankshafts and semi-built ones with shrunk-in journals (M53.1.2)."""

MANUFACTURE_FACTORS = {
    "continuous-grain-flow": 1.05,
    "free-form": 1.0,
    "cast-cold-rolled": 0.93,
}
"""How the crankshaft was made -> the factor K of the fatigue strength (UR M53.6): 1.05 for
continuous grain flow forged or drop-forged crankshafts, 1.0 for free form forged crankshafts
(without continuous grain flow), 0.93 for cast steel crankshafts with cold rolling of the
fillets by an approved process. Values above 1 apply to the fillets only, never to the oil
bore (M53.6). Verified: KR Rules 2025 Pt 5 Guidance Annex 5-3 6(2)(A), "factor for different
types of crankshafts without surface treatment" (the text UR M53 was read in,
:mod:`crankdyn.crankshaft.m53`)."""

SURFACE_TREATMENTS = (
    "none",
    "induction-hardened",
    "nitrided",
    "cold-rolled",
    "shot-peened",
    "other",
)
"""Surface treatments of the fillets. The rule gives no factor for them: Annex 5-3 6(2)(B)
requires the process to be approved by the society and points to its Appendix V (local
fatigue strengths of induction-hardened, nitrided and cold-formed fillets); Appendix V 2(1)
deals with induction hardening, nitriding, cold rolling and stroke peening only. The
``surface_factor`` of :class:`CrankshaftMaterial` is crankdyn's way of taking the credit the
society accepted; it is not verified against a text."""

YOUNGS_MODULUS_STEEL = 2.05e11
"""E of steel (Pa), the modulus E_m of the shrink-fit formulas (M53.8) unless given. The
shrink-fit clause gives no value; 2.05e5 N/mm^2 is the value Annex 5-3 Appendix III 2(2) and
Appendix VI 2(2) advise for steel ("For steel the following is advised: E = 2.05 10^5 MPa")."""


def _optional_length(name: str, value: float | None) -> float | None:
    return None if value is None else check_length(name, value)


def _nonnegative(name: str, value: object) -> float:
    number = check_finite(name, value)
    if number < 0.0:
        raise InputError("must not be negative", key=name, value=value)
    return number


@dataclass(frozen=True)
class CrankshaftGeometry:
    """The dimensions of one crank throw (UR M53 Fig. 1-3; module docstring).

    Parameters
    ----------
    pin_diameter : float
        D, crankpin diameter (m).
    journal_diameter : float
        D_G, journal diameter (m).
    web_thickness : float
        W, web thickness at its centre (m).
    web_width : float
        B, web width at its centre (m).
    pin_fillet_radius : float
        R_H, fillet radius between crankpin and web (m).
    journal_fillet_radius : float
        R_G, fillet radius between journal and web (m).
    web_centre_distance : float
        L_1, from a main-bearing centre to the web centre (m).
    pin_bore : float
        D_BH, diameter of the crankpin's axial bore (m); 0 for a solid pin.
    journal_bore : float
        D_BG, diameter of the journal's axial bore (m); 0 for a solid journal.
    overlap : float or None
        S, pin-journal overlap (m, negative without overlap); None: (D + D_G)/2 - R from the
        engine's crank radius.
    pin_recess : float
        T_H, recess of the crankpin fillet into the web (m); 0 without.
    journal_recess : float
        T_G, recess of the journal fillet into the web (m); 0 without.
    oil_bore_diameter : float or None
        D_O, diameter of the crankpin's radial oil bore (m); None without one.
    oil_bore_angle : float
        psi, angular position of the oil bore's outlet in the crankpin (rad), measured in the
        crank frame from the direction of rotation toward the crankshaft axis (the outlet's
        bending stress is M_BTO cos(psi) + M_BRO sin(psi) over the pin's section modulus,
        M53 2.1.2.2).
    bearing_span : float or None
        L_3, distance between the centres of the main bearings either side of a throw (m);
        None: the engine's cylinder pitch.

    Raises
    ------
    InputError
        If a length is not positive (bores, recesses and the oil bore's angle: not finite or
        negative), a bore is not smaller than its diameter, or L_1 is not smaller than half
        the bearing span; the key names the field.

    Examples
    --------
    >>> g = CrankshaftGeometry(0.26, 0.30, 0.115, 0.48, 0.013, 0.015, 0.135)
    >>> g.pin_bore, g.overlap is None
    (0.0, True)
    """

    pin_diameter: float
    journal_diameter: float
    web_thickness: float
    web_width: float
    pin_fillet_radius: float
    journal_fillet_radius: float
    web_centre_distance: float
    pin_bore: float = 0.0
    journal_bore: float = 0.0
    overlap: float | None = None
    pin_recess: float = 0.0
    journal_recess: float = 0.0
    oil_bore_diameter: float | None = None
    oil_bore_angle: float = 0.0
    bearing_span: float | None = None

    def __post_init__(self) -> None:
        set_ = object.__setattr__
        for name in (
            "pin_diameter",
            "journal_diameter",
            "web_thickness",
            "web_width",
            "pin_fillet_radius",
            "journal_fillet_radius",
            "web_centre_distance",
        ):
            set_(self, name, check_length(name, getattr(self, name)))
        for name in ("pin_bore", "journal_bore", "pin_recess", "journal_recess"):
            set_(self, name, _nonnegative(name, getattr(self, name)))
        for bore, diameter in (("pin_bore", "pin_diameter"), ("journal_bore", "journal_diameter")):
            if getattr(self, bore) >= getattr(self, diameter):
                raise InputError(
                    f"the bore must be smaller than the {diameter.replace('_', ' ')}",
                    key=bore,
                    value=getattr(self, bore),
                )
        if self.overlap is not None:
            set_(self, "overlap", check_finite("overlap", self.overlap))
        set_(
            self, "oil_bore_diameter", _optional_length("oil_bore_diameter", self.oil_bore_diameter)
        )
        if self.oil_bore_diameter is not None and self.oil_bore_diameter >= self.pin_diameter:
            raise InputError(
                "the oil bore must be smaller than the crankpin diameter",
                key="oil_bore_diameter",
                value=self.oil_bore_diameter,
            )
        set_(self, "oil_bore_angle", check_finite("oil_bore_angle", self.oil_bore_angle))
        set_(self, "bearing_span", _optional_length("bearing_span", self.bearing_span))
        if self.bearing_span is not None:
            self.check_span(self.bearing_span)

    def check_span(self, span: float) -> None:
        """Check L_1 against a bearing span L_3: the web centre lies between a main bearing's
        centre and the crankpin's middle (0 < L_1 < L_3 / 2).

        Parameters
        ----------
        span : float
            L_3 (m).

        Raises
        ------
        InputError
            If L_1 >= L_3 / 2 (key ``web_centre_distance``).
        """
        if self.web_centre_distance >= span / 2.0:
            raise InputError(
                f"the web centre must lie within half the bearing span ({span * 500.0:.6g} mm)",
                key="web_centre_distance",
                value=self.web_centre_distance,
            )

    def pin_journal_overlap(self, crank_radius: float) -> float:
        """S: the overlap given, else (D + D_G)/2 - R (UR M53.3.1 [Annex 5-3 3(1)(G)]:
        S = (D + D_G)/2 - E, E the pin eccentricity, the crank radius).

        Parameters
        ----------
        crank_radius : float
            R, the engine's crank radius (m).

        Returns
        -------
        float
            S (m); negative when pin and journal do not overlap.

        Examples
        --------
        >>> g = CrankshaftGeometry(0.26, 0.30, 0.115, 0.48, 0.013, 0.015, 0.135)
        >>> round(g.pin_journal_overlap(0.2), 12)
        0.08
        """
        if self.overlap is not None:
            return self.overlap
        return (self.pin_diameter + self.journal_diameter) / 2.0 - crank_radius


@dataclass(frozen=True)
class CrankshaftMaterial:
    """The crankshaft's material, how it was made and its surface treatment (UR M53.6).

    Parameters
    ----------
    tensile_strength : float
        sigma_B, specified minimum tensile strength (Pa).
    yield_strength : float or None
        Specified minimum yield strength (Pa), for the shrink fits of a semi-built crankshaft
        (M53.8: sigma_SP of the journal pin, sigma_SW of the web); None when not needed.
    manufacture : str
        A key of :data:`MANUFACTURE_FACTORS` (the factor K): ``"continuous-grain-flow"``,
        ``"free-form"`` (default) or ``"cast-cold-rolled"``.
    surface_treatment : str
        One of :data:`SURFACE_TREATMENTS` (default ``"none"``).
    surface_factor : float
        Fatigue enhancement of the surface treatment in the fillets (dimensionless, >= 1):
        what the class society accepted from documented tests; 1 (default) takes no credit.
        It multiplies sigma_DW of the fillets: crankdyn's convention, not a formula of the
        rule (:data:`SURFACE_TREATMENTS`; not verified against a text).
    youngs_modulus : float
        E_m (Pa), for the shrink fits; default 205 GPa (:data:`YOUNGS_MODULUS_STEEL`).

    Raises
    ------
    InputError
        If a strength or the modulus is not positive, the yield strength is not below the
        tensile strength, a choice is unknown, or the surface factor is below 1 or given
        (above 1) without a surface treatment; the key names the field.
    """

    tensile_strength: float
    yield_strength: float | None = None
    manufacture: str = "free-form"
    surface_treatment: str = "none"
    surface_factor: float = 1.0
    youngs_modulus: float = YOUNGS_MODULUS_STEEL

    def __post_init__(self) -> None:
        set_ = object.__setattr__
        set_(
            self,
            "tensile_strength",
            check_positive("tensile_strength", self.tensile_strength, "the tensile strength"),
        )
        if self.yield_strength is not None:
            ys = check_positive("yield_strength", self.yield_strength, "the yield strength")
            if ys >= self.tensile_strength:
                raise InputError(
                    "the yield strength must be below the tensile strength",
                    key="yield_strength",
                    value=self.yield_strength,
                )
            set_(self, "yield_strength", ys)
        if self.manufacture not in MANUFACTURE_FACTORS:
            raise InputError(
                f"expected one of {', '.join(MANUFACTURE_FACTORS)}",
                key="manufacture",
                value=self.manufacture,
            )
        if self.surface_treatment not in SURFACE_TREATMENTS:
            raise InputError(
                f"expected one of {', '.join(SURFACE_TREATMENTS)}",
                key="surface_treatment",
                value=self.surface_treatment,
            )
        factor = check_finite("surface_factor", self.surface_factor)
        if factor < 1.0:
            raise InputError(
                "the surface treatment's fatigue factor is at least 1 (1 takes no credit)",
                key="surface_factor",
                value=self.surface_factor,
            )
        if factor > 1.0 and self.surface_treatment == "none":
            raise InputError(
                "a fatigue factor above 1 needs the surface treatment that gives it",
                key="surface_factor",
                value=self.surface_factor,
            )
        set_(self, "surface_factor", factor)
        set_(
            self,
            "youngs_modulus",
            check_positive("youngs_modulus", self.youngs_modulus, "the modulus"),
        )

    @property
    def factor_k(self) -> float:
        """K of the fatigue strength (dimensionless; :data:`MANUFACTURE_FACTORS`, M53.6)."""
        return MANUFACTURE_FACTORS[self.manufacture]


@dataclass(frozen=True)
class ShrinkFit:
    """The shrink fit of a semi-built crankshaft's journal in its web (UR M53.8, Fig. 5).

    Parameters
    ----------
    diameter : float
        D_S, shrink diameter (m).
    length : float
        L_S, length of the shrink fit (m).
    web_outer_diameter : float
        D_A, outside diameter of the web or twice the smallest distance from the journal's
        centre line to the web's outer contour, whichever is less (m; Annex 5-3 8(1)(B)).
    oversize : float or None
        Z, the actual diametral oversize of the fit (m), checked against Z_min and Z_max; None
        to give the limits only.
    friction : float
        mu, coefficient of static friction (dimensionless); default 0.2, "a value not greater
        than 0.2 is to be taken unless documented by experiments" (M53.8.2 [Annex 5-3
        8(2)(A)]).
    slip_safety : float
        S_R, safety factor against slipping (dimensionless); default 2, "a value not less than
        2 is to be taken unless documented by experiments" (M53.8.2 [Annex 5-3 8(2)(A)]).
    pin_yield_strength : float or None
        sigma_SP, minimum yield strength of the journal pin (Pa); None: the material's.
    web_yield_strength : float or None
        sigma_SW, minimum yield strength of the web (Pa); None: the material's.

    Raises
    ------
    InputError
        If a length, mu or a strength is not positive, S_R is below 1, or the web's outer
        diameter is not larger than the shrink diameter; the key names the field.
    """

    diameter: float
    length: float
    web_outer_diameter: float
    oversize: float | None = None
    friction: float = 0.2
    slip_safety: float = 2.0
    pin_yield_strength: float | None = None
    web_yield_strength: float | None = None

    def __post_init__(self) -> None:
        set_ = object.__setattr__
        for name in ("diameter", "length", "web_outer_diameter"):
            set_(self, name, check_length(name, getattr(self, name)))
        if self.web_outer_diameter <= self.diameter:
            raise InputError(
                "the web's outer diameter must be larger than the shrink diameter",
                key="web_outer_diameter",
                value=self.web_outer_diameter,
            )
        set_(self, "oversize", _optional_length("oversize", self.oversize))
        set_(self, "friction", check_positive("friction", self.friction, "the friction"))
        safety = check_finite("slip_safety", self.slip_safety)
        if safety < 1.0:
            raise InputError("must be at least 1", key="slip_safety", value=self.slip_safety)
        set_(self, "slip_safety", safety)
        for name in ("pin_yield_strength", "web_yield_strength"):
            if getattr(self, name) is not None:
                set_(self, name, check_positive(name, getattr(self, name), "the strength"))


STRESS_FACTOR_NAMES = ("alpha_b", "alpha_t", "beta_b", "beta_q", "beta_t", "gamma_b", "gamma_t")
"""The stress concentration factors of UR M53.3, in its symbols."""


@dataclass(frozen=True)
class StressFactors:
    """Stress concentration factors given by the user, e.g. found by finite elements after UR
    M53 Appendix III (fillets) or measured; each replaces the rule's empirical formula (and its
    validity range) where given.

    Parameters
    ----------
    alpha_b, alpha_t : float or None
        Crankpin fillet, bending and torsion (dimensionless).
    beta_b, beta_q, beta_t : float or None
        Journal fillet, bending, shear and torsion (dimensionless).
    gamma_b, gamma_t : float or None
        Oil bore outlet, bending and torsion (dimensionless).
    source : str
        Where they come from (the FE report), for the notes.

    Raises
    ------
    InputError
        If a factor is below 1 or not finite (key: its name).
    """

    alpha_b: float | None = None
    alpha_t: float | None = None
    beta_b: float | None = None
    beta_q: float | None = None
    beta_t: float | None = None
    gamma_b: float | None = None
    gamma_t: float | None = None
    source: str = ""

    def __post_init__(self) -> None:
        for name in STRESS_FACTOR_NAMES:
            value = getattr(self, name)
            if value is None:
                continue
            number = check_finite(name, value)
            if number < 1.0 and name != "beta_q":
                raise InputError(
                    "a stress concentration factor is at least 1", key=name, value=value
                )
            if number <= 0.0:
                raise InputError("must be positive", key=name, value=value)
            object.__setattr__(self, name, number)

    def given(self) -> tuple[str, ...]:
        """The names of the factors given.

        Returns
        -------
        tuple of str
            Names from :data:`STRESS_FACTOR_NAMES`.
        """
        return tuple(n for n in STRESS_FACTOR_NAMES if getattr(self, n) is not None)


@dataclass(frozen=True)
class Crankshaft:
    """An engine's crankshaft for the fatigue check by IACS UR M53 (module docstring).

    Parameters
    ----------
    geometry : CrankshaftGeometry
        The dimensions of a crank throw.
    material : CrankshaftMaterial
        Material, manufacture and surface treatment.
    engine_type : str
        ``"trunk-piston"`` (default) or ``"crosshead"``: the additional bending stress of
        M53.4.
    construction : str
        ``"solid"`` (default) or ``"semi-built"`` (then ``shrink_fit`` is required and the
        journal fillet check does not apply, M53.3.3).
    shrink_fit : ShrinkFit or None
        The journal's shrink fit of a semi-built crankshaft.
    factors : StressFactors or None
        Stress concentration factors replacing the empirical ones (M53 Appendix III).
    axial_vibration_stress : float or None
        Crosshead engines: the additional bending stress from axial vibration (Pa) where the
        axial vibration calculation of the whole system gives it; None: the rule's 20 MPa
        (M53.4).
    beam : BeamInputs or None
        The ``[crankshaft.beam]`` table: the beam model's own inputs
        (:mod:`crankdyn.crankshaft.beam_inputs`); None: its defaults.
    additional_stress : str or None
        Where M53.4's additional bending stress from vibration comes from: ``"rule"`` (its
        values) or ``"beam"`` (the beam model's forced response, M53.4(3)); None: ``"beam"``
        when the ``[crankshaft.beam]`` table is given, else ``"rule"``.

    Raises
    ------
    InputError
        If a choice is unknown, a semi-built crankshaft has no shrink fit (or a solid one has
        one), the axial vibration stress is given for a trunk-piston engine, negative or
        together with ``additional_stress = "beam"``.
    """

    geometry: CrankshaftGeometry
    material: CrankshaftMaterial
    engine_type: str = "trunk-piston"
    construction: str = "solid"
    shrink_fit: ShrinkFit | None = None
    factors: StressFactors | None = None
    axial_vibration_stress: float | None = None
    beam: BeamInputs | None = None
    additional_stress: str | None = None

    def __post_init__(self) -> None:
        if self.additional_stress is not None:
            if self.additional_stress not in ADDITIONAL_STRESS_SOURCES:
                raise InputError(
                    f"expected one of {', '.join(ADDITIONAL_STRESS_SOURCES)}",
                    key="additional_stress",
                    value=self.additional_stress,
                )
            if self.additional_stress == "beam" and self.axial_vibration_stress is not None:
                raise InputError(
                    "give the axial vibration stress or take it from the beam model "
                    '(additional_stress = "beam"), not both',
                    key="axial_vibration_stress",
                    value=self.axial_vibration_stress,
                )
        if self.engine_type not in ENGINE_TYPES:
            raise InputError(
                f"expected one of {', '.join(ENGINE_TYPES)}",
                key="engine_type",
                value=self.engine_type,
            )
        if self.construction not in CONSTRUCTIONS:
            raise InputError(
                f"expected one of {', '.join(CONSTRUCTIONS)}",
                key="construction",
                value=self.construction,
            )
        if self.construction == "semi-built" and self.shrink_fit is None:
            raise InputError(
                "a semi-built crankshaft needs its shrink fit ([crankshaft.shrink_fit])",
                key="shrink_fit",
            )
        if self.construction == "solid" and self.shrink_fit is not None:
            raise InputError(
                'a shrink fit belongs to a semi-built crankshaft (construction = "semi-built")',
                key="shrink_fit",
            )
        if self.axial_vibration_stress is not None:
            if self.engine_type != "crosshead":
                raise InputError(
                    "the axial vibration stress is part of a crosshead engine's additional "
                    "stress (M53.4)",
                    key="axial_vibration_stress",
                    value=self.axial_vibration_stress,
                )
            value = _nonnegative("axial_vibration_stress", self.axial_vibration_stress)
            object.__setattr__(self, "axial_vibration_stress", value)
        if self.shrink_fit is not None and self.material.yield_strength is None:
            fit = self.shrink_fit
            if fit.pin_yield_strength is None or fit.web_yield_strength is None:
                raise InputError(
                    "the shrink-fit checks need the yield strength of the journal pin and the "
                    "web (give the material's yield_strength)",
                    key="yield_strength",
                )

    @property
    def semi_built(self) -> bool:
        """Whether the crankshaft is semi-built."""
        return self.construction == "semi-built"

    @property
    def additional_stress_source(self) -> str:
        """``"beam"`` or ``"rule"``: :attr:`additional_stress`, else ``"beam"`` when the
        ``[crankshaft.beam]`` table is given and no axial vibration stress, else ``"rule"``."""
        if self.additional_stress is not None:
            return self.additional_stress
        if self.beam is not None and self.axial_vibration_stress is None:
            return "beam"
        return "rule"

    @property
    def beam_inputs(self) -> BeamInputs:
        """The beam model's inputs: :attr:`beam`, else the defaults."""
        return self.beam if self.beam is not None else BeamInputs()
