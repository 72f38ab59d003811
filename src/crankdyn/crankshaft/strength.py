"""The crankshaft's fatigue check by IACS UR M53 from the engine's crank train (analysis).

:func:`crankshaft_strength` takes the engine (its ``[crankshaft]``, geometry, masses and cylinder
pressure at the maximum continuous rating) and the alternating torque of every crank span from
the forced torsional response, and follows the rule (:mod:`crankdyn.crankshaft.m53` for each
formula and its clause):

1. the throw loads by the statically determinate method and their half-ranges
   (:func:`crankdyn.crankshaft.loads.throw_loads`, M53.2.1.1);
2. the nominal stresses (2.1.2.1, 2.1.2.2, 2.2.2): web bending and compression, the crankpin's
   bending at the oil bore, the torsion of crankpin and journal;
3. the stress concentration factors (M53.3), the user's FE factors where given (Appendix III),
   and the ratios against the empirical formulas' ranges: a location whose empirical factor is
   used outside its range is named (``extrapolated``) and its verdict fails;
4. the stresses in the fillets and at the oil bore (2.1.3, 2.1.4, 2.2.3), the additional bending
   stress (M53.4), the equivalent stress (M53.5), the fatigue strength (M53.6), Q (M53.7);
5. for a semi-built crankshaft the shrink fit (M53.8) with the largest torque of a crank span
   M_max estimated as the largest quasi-static torque through a main journal plus the largest
   alternating torque given.

The nominal torsional stress of the rule (2.2.2) is the largest the forced vibration calculation
gives over the speed range, at the crankshaft's most loaded mass point; given per crank span
here, each throw is checked with its own span's, so the smallest Q over the throws is the rule's
(the bending is the same for every throw of an engine with identical cylinders).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.crank.pressure import PressureTrace
from crankdyn.crankshaft import m53
from crankdyn.crankshaft.geometry import Crankshaft
from crankdyn.crankshaft.loads import ThrowLoads, throw_loads
from crankdyn.crankshaft.result import CrankshaftResult
from crankdyn.engine.model import Engine
from crankdyn.errors import InputError
from crankdyn.plausibility import PlausibilityWarning, merge_warnings
from crankdyn.results import freeze

__all__ = [
    "TENSILE_STRENGTH_RANGE",
    "additional_stress_of",
    "assess",
    "crankshaft_strength",
    "crankshaft_warnings",
]

TENSILE_STRENGTH_RANGE = (400e6, 1000e6)
"""(low, high) of the specified minimum tensile strength of crankshaft steels (Pa): carbon and
carbon-manganese steel castings and forgings from 400 N/mm^2, alloy steel forgings up to
1000 N/mm^2 (Lloyd's Register, Rules for Inland Waterways Ships, July 2022, Pt 5 Ch 2 2.1.1,
crankshaft materials)."""
TENSILE_STRENGTH_SOURCE = "LR Rules, Inland Waterways Ships 2022, Pt 5 Ch 2 2.1.1"

_SAME_LENGTH = 1e-3  # m: an overlap or span given that differs more from the engine's is named


def _torque_input(
    engine: Engine,
    crankshaft: Crankshaft,
    torsion_torque: ArrayLike | None,
    torsion_stress: ArrayLike | None,
) -> NDArray[np.float64] | None:
    """M_TN per throw (N m) from the torque or the stress given, or None."""
    if torsion_torque is not None and torsion_stress is not None:
        raise InputError("give the torsional torque or the stress, not both", key="torsion_stress")
    given = torsion_torque if torsion_stress is None else torsion_stress
    if given is None:
        return None
    key = "torsion_torque" if torsion_stress is None else "torsion_stress"
    count = engine.cylinders.throw_count
    values = np.asarray(given, dtype=float)
    if values.ndim == 0:
        values = np.full(count, float(values))
    if values.shape != (count,):
        raise InputError(
            f"expected one value per crank span ({count})", key=key, value=values.tolist()
        )
    if not np.all(np.isfinite(values)) or np.any(values < 0.0):
        raise InputError(
            "the alternating torsional values are half-ranges: finite and not negative",
            key=key,
            value=values.tolist(),
        )
    if torsion_stress is not None:
        g = crankshaft.geometry
        values = values * m53.polar_section_modulus(g.pin_diameter, g.pin_bore)
    return values


def crankshaft_warnings(engine: Engine, crankshaft: Crankshaft) -> list[PlausibilityWarning]:
    """Legal but unlikely inputs of the crankshaft: a tensile strength outside
    :data:`TENSILE_STRENGTH_RANGE`, an overlap S or a bearing span L_3 given that differs by
    more than 1 mm from the engine's (S = (D + D_G)/2 - R, L_3 = the cylinder pitch).

    Parameters
    ----------
    engine : crankdyn.engine.Engine
        The engine.
    crankshaft : Crankshaft
        Its crankshaft.

    Returns
    -------
    list of crankdyn.plausibility.PlausibilityWarning
        The warnings.
    """
    out = []
    sb = crankshaft.material.tensile_strength
    low, high = TENSILE_STRENGTH_RANGE
    if not low <= sb <= high:
        side = "below" if sb < low else "above"
        out.append(
            PlausibilityWarning(
                "crankshaft_tensile_strength",
                "Crankshaft tensile strength",
                sb,
                "Pa",
                low,
                high,
                TENSILE_STRENGTH_SOURCE,
                f"the crankshaft's tensile strength {sb / 1e6:.4g} MPa is {side} the "
                f"{low / 1e6:.0f}-{high / 1e6:.0f} MPa of crankshaft steels "
                f"({TENSILE_STRENGTH_SOURCE}); check the unit",
            )
        )
    g = crankshaft.geometry
    derived = (g.pin_diameter + g.journal_diameter) / 2.0 - engine.geometry.crank_radius
    pairs: list[tuple[str, float | None, float | None, str]] = [
        ("overlap", g.overlap, derived, "(D + D_G)/2 - R"),
        ("bearing_span", g.bearing_span, engine.cylinders.pitch, "the cylinder pitch"),
    ]
    for key, given, expected, what in pairs:
        if given is None or expected is None or abs(given - expected) <= _SAME_LENGTH:
            continue
        out.append(
            PlausibilityWarning(
                f"crankshaft_{key}",
                f"Crankshaft {key.replace('_', ' ')}",
                given,
                "m",
                expected,
                expected,
                "UR M53 Fig. 1-3",
                f"the crankshaft's {key.replace('_', ' ')} {given * 1e3:.6g} mm differs from "
                f"{what}, {expected * 1e3:.6g} mm; check the drawing",
            )
        )
    return out


def crankshaft_strength(
    engine: Engine,
    speed: float | None = None,
    *,
    torsion_torque: ArrayLike | None = None,
    torsion_stress: ArrayLike | None = None,
    crankshaft: Crankshaft | None = None,
    pressure: PressureTrace | None = None,
    vibration_stress: float | None = None,
    vibration_where: str = "",
    torsion_where: Sequence[str] | None = None,
    notes: Sequence[str] = (),
) -> CrankshaftResult:
    """The fatigue check of the engine's crankshaft by IACS UR M53 (module docstring).

    Parameters
    ----------
    engine : crankdyn.engine.Engine
        The engine (masses required; its ``crankshaft`` unless ``crankshaft`` is given).
    speed : float or None
        The speed of the maximum continuous rating (rad/s); None: the engine's speed.
    torsion_torque : array_like or None
        M_TN, the nominal alternating torque (half-range, N m) of every crank span, the
        largest over the speed range (2.2.2; e.g. the synthesised shaft torque of the forced
        response); one value per throw, or one for all. None: no torsion (Q from bending
        alone, said in the verdicts' condition).
    torsion_stress : array_like or None
        Instead of ``torsion_torque``: tau_N referred to the crankpin (Pa), M_TN / W_P with
        the crankpin's W_P.
    crankshaft : Crankshaft or None
        The crankshaft; default the engine's.
    pressure : PressureTrace or None
        The cylinder pressure at that speed; default the engine's trace or synthetic model.
    vibration_stress : float or None
        The web bending stress from axial and bending vibration of a calculation of the whole
        system (Pa; e.g. the beam model's,
        :attr:`crankdyn.crankshaft.beam_response.BeamResponseResult.web_vibration_stress`), in
        place of the rule's allowance for it (M53.4(3); :func:`additional_stress_of`); None:
        the rule's values.
    vibration_where : str
        Where it comes from, for the result's source of sigma_add.
    torsion_where : sequence of str or None
        Where each throw's M_TN comes from (shaft and speed), for the nominal stresses' table.
    notes : sequence of str
        Notes of the caller (e.g. how M_TN was found), added to the result's.

    Returns
    -------
    CrankshaftResult
        Nominal stresses, factors, equivalent stresses, fatigue strengths, Q per throw and
        location, the shrink fit of a semi-built crankshaft, and the verdicts.

    Raises
    ------
    InputError
        If the engine has no crankshaft, masses or speed, the bearing span is unknown (no
        ``bearing_span`` and no cylinder pitch), L_1 is not within half of it, or the torsional
        values are not one non-negative number per crank span.

    Examples
    --------
    >>> import crankdyn
    >>> engine = crankdyn.Engine.example("marine-propulsion")
    >>> result = crankshaft_strength(engine, torsion_torque=30e3)
    >>> q, where = result.smallest_q()  # every throw's bending is the same
    >>> round(q, 2), where.split(", ")[1]
    (1.64, 'journal fillet')
    """
    shaft = _shaft(engine, crankshaft)
    speed = engine.speed if speed is None else speed
    if speed is None:
        raise InputError(
            "give the speed of the maximum continuous rating ([operating] speed)", key="speed"
        )
    g = shaft.geometry
    span = g.bearing_span if g.bearing_span is not None else engine.cylinders.pitch
    if span is None:
        raise InputError(
            "the bearing span L_3 is unknown: give [crankshaft] bearing_span or the cylinder pitch",
            file=engine.source,
            key="[crankshaft] bearing_span",
        )
    g.check_span(span)
    _torque_input(engine, shaft, torsion_torque, torsion_stress)  # checked before the work
    loads = throw_loads(
        engine,
        speed,
        bearing_span=span,
        web_centre_distance=g.web_centre_distance,
        oil_bore_angle=g.oil_bore_angle,
        pressure=pressure,
    )
    return assess(
        engine,
        loads,
        speed=speed,
        torsion_torque=torsion_torque,
        torsion_stress=torsion_stress,
        crankshaft=shaft,
        vibration_stress=vibration_stress,
        vibration_where=vibration_where,
        torsion_where=torsion_where,
        notes=notes,
    )


def _shaft(engine: Engine, crankshaft: Crankshaft | None) -> Crankshaft:
    """The crankshaft given, else the engine's; an InputError without either."""
    shaft = crankshaft if crankshaft is not None else engine.crankshaft
    if shaft is None:
        raise InputError(
            "the engine has no [crankshaft]: the M53 check needs its dimensions and material "
            "(crankdyn docs engine-file)",
            file=engine.source,
            key="[crankshaft]",
        )
    return shaft


def _web_thickness(engine: Engine, shaft: Crankshaft) -> tuple[float, str | None]:
    """W, or W_red = W - (T_H - R_H) of a semi-built two-stroke crankshaft whose crankpin
    recess is deeper than its fillet radius (M53.3.1 [Annex 5-3 3(1)(G)]: "in the case of
    2 stroke semi-built crankshafts: when T_H > R_H, the web thickness must be considered as
    equal to W_red = W - (T_H - R_H)"), with a note. The text's table also writes
    w = W_red/D "for crankshafts without overlap"; W_red is defined for the case above only,
    so crankdyn reduces W there and nowhere else."""
    g = shaft.geometry
    if shaft.semi_built and engine.cycle == "two-stroke" and g.pin_recess > g.pin_fillet_radius:
        reduced = g.web_thickness - (g.pin_recess - g.pin_fillet_radius)
        return reduced, (
            f"web thickness taken as W_red = W - (T_H - R_H) = {reduced * 1e3:.4g} mm "
            "(semi-built two-stroke crankshaft, M53.3.1)"
        )
    return g.web_thickness, None


def _factors(
    shaft: Crankshaft, q: m53.Ratios
) -> tuple[dict[str, float | None], list[tuple[str, str]], list[str]]:
    """The SCFs (the user's where given), the locations extrapolated with why, and notes."""
    user = shaft.factors
    empirical: dict[str, float | None] = {
        "alpha_b": m53.crankpin_bending_scf(q),
        "alpha_t": m53.crankpin_torsion_scf(q),
        "beta_b": None,
        "beta_q": None,
        "beta_t": None,
        "gamma_b": None,
        "gamma_t": None,
    }
    if not shaft.semi_built:
        empirical["beta_b"] = m53.journal_bending_scf(q)
        empirical["beta_q"] = m53.journal_shear_scf(q)
        empirical["beta_t"] = m53.journal_torsion_scf(q)
    if q.d_o is not None:
        empirical["gamma_b"], empirical["gamma_t"] = m53.oil_bore_scf(q.d_o)
    given = user.given() if user is not None else ()
    factors = {
        name: (getattr(user, name) if name in given else value) for name, value in empirical.items()
    }
    notes = []
    if given:
        source = f" ({user.source})" if user is not None and user.source else ""
        notes.append(f"stress concentration factors given{source}: {', '.join(given)}")
    locations = {
        "crankpin fillet": ("alpha_b", "alpha_t"),
        "journal fillet": ("beta_b", "beta_q", "beta_t"),
        "oil bore": ("gamma_b", "gamma_t"),
    }
    extrapolated = []
    ranges = m53.validity(q, journal=not shaft.semi_built)
    for location, names in locations.items():
        if factors[names[0]] is None or all(n in given for n in names):
            continue
        bad = [v for v in ranges if not v.valid and v.limits(location)]
        if bad:
            reason = "; ".join(v.text() for v in bad)
            extrapolated.append((location, reason))
            notes.append(
                f"{location}: empirical factors outside their range ({reason}): not the "
                "rule's; give FE factors (M53 Appendix III)"
            )
    return factors, extrapolated, notes


def assess(
    engine: Engine,
    loads: ThrowLoads,
    *,
    speed: float,
    torsion_torque: ArrayLike | None = None,
    torsion_stress: ArrayLike | None = None,
    crankshaft: Crankshaft | None = None,
    vibration_stress: float | None = None,
    vibration_where: str = "",
    torsion_where: Sequence[str] | None = None,
    notes: Sequence[str] = (),
) -> CrankshaftResult:
    """Steps 2 to 5 of the check (module docstring) on throw loads already found, e.g. by
    :func:`crankdyn.crankshaft.loads.throw_loads` (as :func:`crankshaft_strength` does) or
    given from another calculation of the same half-ranges.

    Parameters
    ----------
    engine : crankdyn.engine.Engine
        The engine (its cycle, crank radius and throws; its crankshaft unless given).
    loads : ThrowLoads
        The throw loads: half-ranges M_BN (N m), Q_N (N), M_BON (N m) per throw, the largest
        journal torque (N m) and the curves.
    speed : float
        The speed of the maximum continuous rating (rad/s), for the verdicts.
    torsion_torque, torsion_stress : array_like or None
        As :func:`crankshaft_strength` (N m, or Pa referred to the crankpin).
    crankshaft : Crankshaft or None
        The crankshaft; default the engine's.
    vibration_stress, vibration_where, torsion_where, notes
        As :func:`crankshaft_strength` (Pa, text).

    Returns
    -------
    CrankshaftResult
        The check.

    Raises
    ------
    InputError
        If the engine has no crankshaft or the torsional values are not one non-negative
        number per crank span.
    """
    shaft = _shaft(engine, crankshaft)
    torque = _torque_input(engine, shaft, torsion_torque, torsion_stress)
    g, mat = shaft.geometry, shaft.material
    given_notes = tuple(notes)
    notes = list(given_notes)
    web, web_note = _web_thickness(engine, shaft)
    if web_note:
        notes.append(web_note)
    q = m53.Ratios.of(
        pin_diameter=g.pin_diameter,
        journal_diameter=g.journal_diameter,
        pin_fillet_radius=g.pin_fillet_radius,
        journal_fillet_radius=g.journal_fillet_radius,
        overlap=g.pin_journal_overlap(engine.geometry.crank_radius),
        web_thickness=web,
        web_width=g.web_width,
        pin_bore=g.pin_bore,
        journal_bore=g.journal_bore,
        pin_recess=g.pin_recess,
        journal_recess=g.journal_recess,
        oil_bore_diameter=g.oil_bore_diameter,
    )
    factors, extrapolated, factor_notes = _factors(shaft, q)
    notes += factor_notes
    count = engine.cylinders.throw_count
    m_tn = np.zeros(count) if torque is None else torque
    if torque is None:
        notes.append("no torsional stress given: Q of bending alone (not the complete check)")
    ke = m53.ke_factor(engine.cycle)
    add, add_source = additional_stress_of(shaft, vibration_stress, vibration_where)
    stresses = _stresses(shaft, web, ke, factors, loads, m_tn, add)
    strengths = _strengths(shaft)
    if mat.surface_factor > 1.0:
        notes.append(
            f"fillets' fatigue strength raised by the {mat.surface_treatment} surface "
            f"treatment's factor {mat.surface_factor:g} (accepted by the society from tests; "
            "crankdyn's factor, not a formula of M53: its Appendix V gives local strengths)"
        )
    equivalent = stresses["equivalent"]
    qs = [
        m53.acceptability(math.nan if s is None else s, equivalent[:, j])
        for j, s in enumerate(strengths)
    ]
    fit = _shrink_fit(shaft, loads, m_tn) if shaft.semi_built else {}
    if shaft.semi_built:
        notes.append(
            "semi-built: no journal fillet check (M53.3.3); M_max of the shrink fit is the "
            "largest quasi-static journal torque plus the largest alternating torque given"
        )
    return CrankshaftResult(
        crank_angle=freeze(loads.theta),
        web_moment=freeze(loads.web_moment),
        web_force=freeze(loads.web_force),
        oil_bore_moment=freeze(loads.oil_bore_moment),
        moment_half_range=freeze(loads.moment_half_range),
        force_half_range=freeze(loads.force_half_range),
        oil_bore_half_range=freeze(loads.oil_bore_half_range),
        torsion_torque=freeze(m_tn),
        sigma_bfn=freeze(stresses["sigma_bfn"]),
        sigma_qfn=freeze(stresses["sigma_qfn"]),
        sigma_bon=freeze(stresses["sigma_bon"]),
        tau_pin=freeze(stresses["tau_pin"]),
        tau_journal=freeze(stresses["tau_journal"]),
        bending=freeze(stresses["bending"]),
        torsion=freeze(stresses["torsion"]),
        equivalent=freeze(stresses["equivalent"]),
        q_pin=freeze(qs[0]),
        q_journal=freeze(qs[1]),
        q_oil=freeze(qs[2]),
        alpha_b=float(factors["alpha_b"] or math.nan),
        alpha_t=float(factors["alpha_t"] or math.nan),
        beta_b=factors["beta_b"],
        beta_q=factors["beta_q"],
        beta_t=factors["beta_t"],
        gamma_b=factors["gamma_b"],
        gamma_t=factors["gamma_t"],
        additional=add,
        additional_source=add_source,
        vibration_stress=vibration_stress,
        torsion_where=None if torsion_where is None else tuple(torsion_where),
        strength_pin=float(strengths[0] or math.nan),
        strength_journal=strengths[1],
        strength_oil=strengths[2],
        factor_k=mat.factor_k,
        ke=ke,
        speed=float(speed),
        q_required=m53.Q_MIN,
        notes=tuple(notes) or None,
        validity=tuple(m53.validity(q, journal=not shaft.semi_built)),
        extrapolated=tuple(extrapolated),
        torsion_given=torque is not None,
        # the engine file's input warnings first: a verdict on them is never a clean pass
        warnings=merge_warnings(engine.input_warnings, crankshaft_warnings(engine, shaft)),
        max_torque=fit.get("max_torque"),
        max_journal_bore=fit.get("max_journal_bore"),
        min_oversize=fit.get("min_oversize"),
        max_oversize=fit.get("max_oversize"),
        oversize=fit.get("oversize"),
        journal_bore=fit.get("journal_bore"),
    )


def _stresses(
    shaft: Crankshaft,
    web: float,
    ke: float,
    factors: dict[str, float | None],
    loads: ThrowLoads,
    m_tn: NDArray[np.float64],
    add: float,
) -> dict[str, NDArray[np.float64]]:
    """The nominal stresses (2.1.2, 2.2.2), the stresses in the fillets and at the oil bore
    (2.1.3, 2.1.4, 2.2.3; throw x location) and the equivalent stresses (M53.4 sigma_add
    ``add``, M53.5)."""
    g = shaft.geometry
    s_bfn, s_qfn = m53.nominal_web_stresses(
        loads.moment_half_range, loads.force_half_range, g.web_width, web, ke
    )
    s_bon = loads.oil_bore_half_range / m53.pin_section_modulus(g.pin_diameter, g.pin_bore)
    tau_pin = m_tn / m53.polar_section_modulus(g.pin_diameter, g.pin_bore)
    tau_journal = m_tn / m53.polar_section_modulus(g.journal_diameter, g.journal_bore)
    nan = np.full(m_tn.shape, math.nan)

    def times(name: str, values: NDArray[np.float64]) -> NDArray[np.float64]:
        f = factors[name]
        return nan if f is None else f * values

    bending = np.column_stack(
        [
            times("alpha_b", s_bfn),
            times("beta_b", s_bfn) + times("beta_q", s_qfn),
            times("gamma_b", s_bon),
        ]
    )
    torsion = np.column_stack(
        [times("alpha_t", tau_pin), times("beta_t", tau_journal), times("gamma_t", tau_pin)]
    )
    equivalent = np.column_stack(
        [
            m53.equivalent_fillet_stress(bending[:, 0], add, torsion[:, 0]),
            m53.equivalent_fillet_stress(bending[:, 1], add, torsion[:, 1]),
            m53.equivalent_oil_bore_stress(bending[:, 2], torsion[:, 2]),
        ]
    )
    return {
        "sigma_bfn": s_bfn,
        "sigma_qfn": s_qfn,
        "sigma_bon": s_bon,
        "tau_pin": tau_pin,
        "tau_journal": tau_journal,
        "bending": bending,
        "torsion": torsion,
        "equivalent": equivalent,
    }


def additional_stress_of(
    shaft: Crankshaft, vibration_stress: float | None = None, where: str = ""
) -> tuple[float, str]:
    """sigma_add (M53.4) and where it comes from.

    Without a calculated vibration stress, the rule's: +-10 N/mm^2 for trunk-piston engines,
    +-30 N/mm^2 for crosshead engines of which 20 from axial vibration, replaced by the
    crankshaft's ``axial_vibration_stress`` where given (M53.4 [Annex 5-3 4(1)-(3)],
    :func:`crankdyn.crankshaft.m53.additional_stress`). With the web bending stress from
    vibration sigma_vib of a calculation of the whole system (the beam model's):

    - crosshead engines: sigma_vib + 10 N/mm^2, the calculated figure in place of the 20 of
      axial vibration (4(3): "where axial vibration calculation results of the complete dynamic
      system are available, the calculated figures may be used instead"), the 10 of
      misalignment and bedplate deformation kept (4(1), notes);
    - trunk-piston engines: max(10 N/mm^2, sigma_vib). The rule's +-10 covers misalignment,
      bedplate deformation and axial and bending vibration together and splits off no axial
      part (4(1)); crankdyn keeps it unless the calculated vibration alone exceeds it
      (crankdyn's choice, not a formula of the rule: it never lowers the rule's value).

    Parameters
    ----------
    shaft : Crankshaft
        The crankshaft (its engine type and axial vibration stress).
    vibration_stress : float or None
        sigma_vib (Pa), or None.
    where : str
        Where sigma_vib comes from (e.g. ``"beam model, web 3 at 727 rpm"``).

    Returns
    -------
    value : float
        sigma_add (Pa).
    source : str
        Which value was used and its clause, for the result's rows.

    Examples
    --------
    >>> from crankdyn.crankshaft.geometry import CrankshaftGeometry, CrankshaftMaterial
    >>> g = CrankshaftGeometry(0.26, 0.30, 0.115, 0.48, 0.013, 0.015, 0.135)
    >>> shaft = Crankshaft(g, CrankshaftMaterial(850e6), engine_type="crosshead")
    >>> additional_stress_of(shaft)[0] / 1e6, additional_stress_of(shaft, 4e6)[0] / 1e6
    (30.0, 14.0)
    """
    rule = m53.additional_stress(shaft.engine_type, shaft.axial_vibration_stress)
    at = f", {where}" if where else ""
    if vibration_stress is None:
        if shaft.axial_vibration_stress is not None:
            return rule, (
                f"M53.4(3): {shaft.axial_vibration_stress / 1e6:.4g} MPa axial vibration "
                "given + 10 MPa misalignment"
            )
        return rule, f"rule M53.4: ±{rule / 1e6:.4g} MPa ({shaft.engine_type})"
    vib = float(vibration_stress)
    if shaft.engine_type == "crosshead":
        value = vib + m53.additional_stress("crosshead", 0.0)
        return value, (
            f"M53.4(3): {vib / 1e6:.4g} MPa from vibration (beam model{at}) + 10 MPa misalignment"
        )
    if vib > rule:
        return vib, (
            f"beam model: {vib / 1e6:.4g} MPa from vibration{at}, above the rule's "
            f"±{rule / 1e6:.4g} MPa (M53.4; crankdyn takes the larger)"
        )
    return rule, (
        f"rule M53.4: ±{rule / 1e6:.4g} MPa (trunk piston), above the beam model's "
        f"{vib / 1e6:.4g} MPa from vibration{at}"
    )


def _strengths(shaft: Crankshaft) -> list[float | None]:
    """sigma_DW of the crankpin fillet, the journal fillet (None when semi-built) and the oil
    bore (None without one; K at most 1 and no surface credit there, M53.6)."""
    g, mat = shaft.geometry, shaft.material
    k, sb = mat.factor_k, mat.tensile_strength
    pin = m53.fatigue_strength(sb, g.pin_diameter, g.pin_fillet_radius, k) * mat.surface_factor
    journal = (
        None
        if shaft.semi_built
        else m53.fatigue_strength(sb, g.journal_diameter, g.journal_fillet_radius, k)
        * mat.surface_factor
    )
    oil = (
        None
        if g.oil_bore_diameter is None
        else m53.fatigue_strength(sb, g.pin_diameter, g.oil_bore_diameter / 2.0, min(k, 1.0))
    )
    return [pin, journal, oil]


def _shrink_fit(
    shaft: Crankshaft, loads: ThrowLoads, m_tn: NDArray[np.float64]
) -> dict[str, float | None]:
    """The shrink-fit figures of a semi-built crankshaft (M53.8)."""
    fit = shaft.shrink_fit
    assert fit is not None  # semi-built (checked by Crankshaft)
    mat = shaft.material
    pin_yield = fit.pin_yield_strength or mat.yield_strength
    web_yield = fit.web_yield_strength or mat.yield_strength
    assert pin_yield is not None and web_yield is not None  # checked by Crankshaft
    m_max = loads.max_journal_torque + float(np.max(m_tn, initial=0.0))
    bore = shaft.geometry.journal_bore
    return {
        "max_torque": m_max,
        "max_journal_bore": m53.maximum_journal_bore(
            fit.diameter, fit.length, m_max, pin_yield, fit.friction, fit.slip_safety
        ),
        "min_oversize": m53.minimum_oversize(
            fit.diameter,
            fit.length,
            fit.web_outer_diameter,
            bore,
            m_max,
            web_yield,
            mat.youngs_modulus,
            fit.friction,
            fit.slip_safety,
        ),
        "max_oversize": m53.maximum_oversize(fit.diameter, web_yield, mat.youngs_modulus),
        "oversize": fit.oversize,
        "journal_bore": bore,
    }
