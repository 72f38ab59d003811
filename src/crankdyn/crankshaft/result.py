"""The result of the crankshaft's fatigue check by IACS UR M53 (:class:`CrankshaftResult`).

Its summary (:mod:`crankdyn.summary`) holds the key figures (the stress concentration factors,
the additional stress, the fatigue strengths, the smallest acceptability factor of each location
and where), two tables (the nominal stresses of every throw; every throw's crankpin fillet,
journal fillet and oil bore with each intermediate quantity and its clause), the validity of the
empirical formulas, the shrink fit of a semi-built crankshaft, and the verdicts: one per throw
and location, Q >= 1.15 (M53.7) written as the equivalent stress against sigma_DW / 1.15, and
the shrink-fit limits (M53.8). The verdicts are made here and nowhere else
(:meth:`CrankshaftResult.summary_verdicts`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from crankdyn.constants import DEG, RPM
from crankdyn.crankshaft.m53 import RULE, ValidityRange
from crankdyn.plausibility import PlausibilityWarning
from crankdyn.results import Result, array, column, scalar
from crankdyn.summary import SummaryColumn, SummaryTable, Verdict, derived, reduced

__all__ = ["LOCATIONS", "QUANTITIES", "CrankshaftResult"]

LOCATIONS = ("crankpin fillet", "journal fillet", "oil bore")
"""The locations UR M53 checks in every throw (M53.1.3)."""

_FACTORS = {
    "crankpin fillet": ("alpha_b", "alpha_t"),
    "journal fillet": ("beta_b", "beta_t"),
    "oil bore": ("gamma_b", "gamma_t"),
}


@dataclass(frozen=True)
class CrankshaftResult(Result):
    """The fatigue check of a crankshaft by IACS UR M53 at one speed
    (:func:`crankdyn.crankshaft.strength.crankshaft_strength`; module docstring).

    Arrays per throw are numbered from the free end; a location that does not apply (the
    journal fillet of a semi-built crankshaft, the oil bore of a pin without one) holds NaN.

    Parameters
    ----------
    validity : tuple of crankdyn.crankshaft.m53.ValidityRange
        The throw's ratios against the ranges of the empirical factors (M53.3).
    extrapolated : tuple of (str, str)
        The locations whose empirical factors were used outside their ranges, with the ratios
        outside (their verdicts fail: the rule's formulas do not apply there).
    torsion_given : bool
        Whether a torsional stress was given (else Q is that of bending alone).
    torsion_where : tuple of str or None
        Where each throw's M_TN comes from (the crank span and the speed), or None.
    warnings : tuple of crankdyn.plausibility.PlausibilityWarning
        Legal but unlikely inputs.
    """

    title = "Crankshaft fatigue strength (IACS UR M53)"
    crank_angle: NDArray[np.float64] = column("crank_angle_deg", "Crank angle θ", "deg", DEG)
    web_moment: NDArray[np.float64] = column(
        "web_bending_moment_Nm", "Web bending moment M_BRF (free-end web)", "N·m"
    )
    web_force: NDArray[np.float64] = column(
        "web_radial_force_N", "Web radial force Q_RF (free-end web)", "N"
    )
    oil_bore_moment: NDArray[np.float64] = column(
        "oil_bore_bending_moment_Nm", "Oil bore bending moment M_BO", "N·m"
    )
    moment_half_range: NDArray[np.float64] = array(
        "nominal_web_moment_Nm", "M_BN, web bending moment half-range", "N·m"
    )
    force_half_range: NDArray[np.float64] = array(
        "nominal_web_force_N", "Q_N, web radial force half-range", "N"
    )
    oil_bore_half_range: NDArray[np.float64] = array(
        "nominal_oil_bore_moment_Nm", "M_BON, oil bore bending moment half-range", "N·m"
    )
    torsion_torque: NDArray[np.float64] = array(
        "nominal_torque_Nm", "M_TN, alternating torque half-range", "N·m"
    )
    sigma_bfn: NDArray[np.float64] = array(
        "sigma_bfn_Pa", "σ_BFN, nominal web bending stress", "Pa"
    )
    sigma_qfn: NDArray[np.float64] = array(
        "sigma_qfn_Pa", "σ_QFN, nominal web compressive stress", "Pa"
    )
    sigma_bon: NDArray[np.float64] = array(
        "sigma_bon_Pa", "σ_BON, nominal oil bore bending stress", "Pa"
    )
    tau_pin: NDArray[np.float64] = array(
        "tau_n_crankpin_Pa", "τ_N, nominal torsional stress (crankpin)", "Pa"
    )
    tau_journal: NDArray[np.float64] = array(
        "tau_n_journal_Pa", "τ_N, nominal torsional stress (journal)", "Pa"
    )
    bending: NDArray[np.float64] = array(
        "bending_stress_Pa", "σ_BH, σ_BG, σ_BO (throw x location)", "Pa"
    )
    torsion: NDArray[np.float64] = array(
        "torsional_stress_Pa", "τ_H, τ_G, σ_TO (throw x location)", "Pa"
    )
    equivalent: NDArray[np.float64] = array(
        "equivalent_stress_Pa", "σ_V, equivalent alternating stress (throw x location)", "Pa"
    )
    q_pin: NDArray[np.float64] = array(
        "q_crankpin_fillet", "Acceptability factor Q, crankpin fillet", ""
    )
    q_journal: NDArray[np.float64] = array(
        "q_journal_fillet", "Acceptability factor Q, journal fillet", ""
    )
    q_oil: NDArray[np.float64] = array("q_oil_bore", "Acceptability factor Q, oil bore", "")
    alpha_b: float = scalar(
        "alpha_b", "α_B, crankpin fillet bending SCF", "", fmt=".4f", name="scf_alpha_b"
    )
    alpha_t: float = scalar(
        "alpha_t", "α_T, crankpin fillet torsion SCF", "", fmt=".4f", name="scf_alpha_t"
    )
    beta_b: float | None = scalar(
        "beta_b", "β_B, journal fillet bending SCF", "", fmt=".4f", name="scf_beta_b"
    )
    beta_q: float | None = scalar(
        "beta_q", "β_Q, journal fillet shear SCF", "", fmt=".4f", name="scf_beta_q"
    )
    beta_t: float | None = scalar(
        "beta_t", "β_T, journal fillet torsion SCF", "", fmt=".4f", name="scf_beta_t"
    )
    gamma_b: float | None = scalar(
        "gamma_b", "γ_B, oil bore bending SCF", "", fmt=".4f", name="scf_gamma_b"
    )
    gamma_t: float | None = scalar(
        "gamma_t", "γ_T, oil bore torsion SCF", "", fmt=".4f", name="scf_gamma_t"
    )
    additional: float = scalar(
        "sigma_add_Pa", "σ_add, additional bending stress", "Pa", name="additional_bending_stress"
    )
    strength_pin: float = scalar(
        "sigma_dw_crankpin_fillet_Pa",
        "σ_DW, fatigue strength, crankpin fillet",
        "Pa",
        name="fatigue_strength_crankpin_fillet",
    )
    strength_journal: float | None = scalar(
        "sigma_dw_journal_fillet_Pa",
        "σ_DW, fatigue strength, journal fillet",
        "Pa",
        name="fatigue_strength_journal_fillet",
    )
    strength_oil: float | None = scalar(
        "sigma_dw_oil_bore_Pa",
        "σ_DW, fatigue strength, oil bore",
        "Pa",
        name="fatigue_strength_oil_bore",
    )
    factor_k: float = scalar(
        "factor_k", "K, manufacture factor", "", fmt=".3g", name="manufacture_factor_k"
    )
    ke: float = scalar(
        "factor_ke", "K_e, web restraint factor", "", fmt=".3g", name="web_restraint_factor_ke"
    )
    speed: float = scalar("speed_rpm", "Speed", "rpm", RPM)
    q_required: float = scalar("q_required", "Smallest acceptable Q", "", fmt=".3g", summary=False)
    max_torque: float | None = scalar(
        "shrink_fit_torque_Nm",
        "M_max, largest torque of a crank span",
        "N·m",
        default=None,
        name="shrink_fit_torque",
    )
    max_journal_bore: float | None = scalar(
        "max_journal_bore_m",
        "Largest journal bore D_BG (shrink fit)",
        "m",
        default=None,
        name="shrink_fit_max_journal_bore",
    )
    min_oversize: float | None = scalar(
        "min_oversize_m",
        "Z_min, smallest oversize of the shrink fit",
        "m",
        default=None,
        name="shrink_fit_min_oversize",
    )
    max_oversize: float | None = scalar(
        "max_oversize_m",
        "Z_max, largest oversize of the shrink fit",
        "m",
        default=None,
        name="shrink_fit_max_oversize",
    )
    oversize: float | None = scalar(
        "oversize_m", "Z, oversize of the shrink fit", "m", default=None, summary=False
    )
    journal_bore: float | None = scalar(
        "journal_bore_m", "D_BG, journal bore", "m", default=None, summary=False
    )
    additional_source: str = scalar(
        "sigma_add_source", "σ_add from", "", default="rule M53.4", summary=False
    )
    vibration_stress: float | None = scalar(
        "sigma_vibration_Pa",
        "σ_vib, web bending from vibration (beam model)",
        "Pa",
        default=None,
        name="m53_vibration_stress",
    )
    rule: str = scalar("rule", "Rule", "", default=RULE)
    notes: tuple[str, ...] | None = scalar("notes", "Notes", "", default=None)
    validity: tuple[ValidityRange, ...] = field(default=(), repr=False, compare=False)
    extrapolated: tuple[tuple[str, str], ...] = field(default=(), repr=False, compare=False)
    torsion_given: bool = field(default=True, repr=False, compare=False)
    torsion_where: tuple[str, ...] | None = field(default=None, repr=False, compare=False)
    warnings: tuple[PlausibilityWarning, ...] = field(default=(), repr=False, compare=False)

    FIGURES = (
        reduced(
            "q_pin",
            "min",
            over="throw",
            name="min_q_crankpin_fillet",
            key="min_q_crankpin_fillet",
            label="Smallest Q, crankpin fillet",
            better="max",
        ),
        reduced(
            "q_journal",
            "min",
            over="throw",
            name="min_q_journal_fillet",
            key="min_q_journal_fillet",
            label="Smallest Q, journal fillet",
            better="max",
        ),
        reduced(
            "q_oil",
            "min",
            over="throw",
            name="min_q_oil_bore",
            key="min_q_oil_bore",
            label="Smallest Q, oil bore",
            better="max",
        ),
        derived(
            "min_acceptability_factor",
            "min_acceptability_factor",
            "Smallest acceptability factor Q",
            "",
            lambda r: r.smallest_q(),
            reduction="min over throws and locations",
            better="max",
        ),
    )

    # ---- derived views ------------------------------------------------------------------------
    @property
    def throw_count(self) -> int:
        """Number of crank throws."""
        return int(np.asarray(self.q_pin).size)

    def q_table(self) -> NDArray[np.float64]:
        """Q of every throw and location, shape (throws, 3) in the order of :data:`LOCATIONS`
        (NaN where a location does not apply).

        Returns
        -------
        numpy.ndarray
            Q (dimensionless).
        """
        return np.column_stack([self.q_pin, self.q_journal, self.q_oil])

    def smallest_q(self) -> tuple[float, str] | None:
        """The smallest Q over every throw and location, and where.

        Returns
        -------
        (float, str) or None
            Q (dimensionless) and ``"throw 3, crankpin fillet"``; None when nothing applies.
        """
        q = self.q_table()
        if not np.isfinite(q).any():
            return None
        i, j = np.unravel_index(np.nanargmin(np.where(np.isfinite(q), q, np.nan)), q.shape)
        return float(q[i, j]), f"throw {i + 1}, {LOCATIONS[j]}"

    def strengths(self) -> tuple[float, float, float]:
        """sigma_DW of the crankpin fillet, journal fillet and oil bore (Pa; NaN where a
        location does not apply).

        Returns
        -------
        tuple of float
            In the order of :data:`LOCATIONS`.
        """
        return (
            self.strength_pin,
            math.nan if self.strength_journal is None else self.strength_journal,
            math.nan if self.strength_oil is None else self.strength_oil,
        )

    # ---- summary ------------------------------------------------------------------------------
    def summary_tables(self) -> list[SummaryTable]:
        """The nominal stresses of every throw, every throw's locations with their intermediate
        quantities and clauses, and the validity of the empirical factors.

        Returns
        -------
        list of crankdyn.summary.SummaryTable
            ``m53_nominal``, ``m53_locations``, ``m53_validity``.
        """
        return [self._nominal_table(), self._locations_table(), self._validity_table()]

    def _nominal_table(self) -> SummaryTable:
        cols: tuple[SummaryColumn, ...] = (
            SummaryColumn("throw", "Throw"),
            SummaryColumn("nominal_web_moment_Nm", "M_BN (2.1.2.1)", "N·m"),
            SummaryColumn("nominal_web_force_N", "Q_N (2.1.2.1)", "N"),
            SummaryColumn("sigma_bfn_Pa", "σ_BFN (2.1.2.1)", "Pa"),
            SummaryColumn("sigma_qfn_Pa", "σ_QFN (2.1.2.1)", "Pa"),
            SummaryColumn("nominal_oil_bore_moment_Nm", "M_BON (2.1.2.2)", "N·m"),
            SummaryColumn("sigma_bon_Pa", "σ_BON (2.1.2.2)", "Pa"),
            SummaryColumn("nominal_torque_Nm", "M_TN (2.2.2)", "N·m"),
            SummaryColumn("tau_n_crankpin_Pa", "τ_N crankpin (2.2.2)", "Pa"),
            SummaryColumn("tau_n_journal_Pa", "τ_N journal (2.2.2)", "Pa"),
        )
        where = self.torsion_where
        if where is not None:
            cols = (*cols, SummaryColumn("torque_from", "M_TN from (2.2.2)"))
        rows = tuple(
            (
                t + 1,
                *(
                    _cell(np.asarray(a)[t])
                    for a in (
                        self.moment_half_range,
                        self.force_half_range,
                        self.sigma_bfn,
                        self.sigma_qfn,
                        self.oil_bore_half_range,
                        self.sigma_bon,
                        self.torsion_torque,
                        self.tau_pin,
                        self.tau_journal,
                    )
                ),
                *(() if where is None else (where[t],)),
            )
            for t in range(self.throw_count)
        )
        return SummaryTable(
            "m53_nominal",
            "Nominal alternating stresses (UR M53.2)",
            cols,
            rows,
            caption="Half-ranges over the working cycle; each throw simply supported between "
            "its main bearings (M53.2.1.1).",
        )

    def _locations_table(self) -> SummaryTable:
        cols = (
            SummaryColumn("throw", "Throw"),
            SummaryColumn("location", "Location"),
            SummaryColumn("scf_bending", "SCF bending (M53.3)"),
            SummaryColumn("scf_torsion", "SCF torsion (M53.3)"),
            SummaryColumn("bending_stress_Pa", "Bending (2.1.3/2.1.4)", "Pa"),
            SummaryColumn("torsional_stress_Pa", "Torsion (2.2.3)", "Pa"),
            SummaryColumn("sigma_add_Pa", "σ_add (M53.4)", "Pa"),
            SummaryColumn("equivalent_stress_Pa", "σ_V (M53.5)", "Pa"),
            SummaryColumn("fatigue_strength_Pa", "σ_DW (M53.6)", "Pa"),
            SummaryColumn("q", "Q (M53.7)"),
        )
        strengths = self.strengths()
        rows = []
        for t in range(self.throw_count):
            for j, location in enumerate(LOCATIONS):
                q = float(self.q_table()[t, j])
                if not math.isfinite(q):
                    continue
                b_name, t_name = _FACTORS[location]
                rows.append(
                    (
                        t + 1,
                        location,
                        getattr(self, b_name),
                        getattr(self, t_name),
                        float(np.asarray(self.bending)[t, j]),
                        float(np.asarray(self.torsion)[t, j]),
                        0.0 if location == "oil bore" else self.additional,
                        float(np.asarray(self.equivalent)[t, j]),
                        strengths[j],
                        q,
                    )
                )
        return SummaryTable(
            "m53_locations",
            "Fillets and oil bores (UR M53.3 to M53.7)",
            cols,
            tuple(rows),
            caption=f"Q = σ_DW / σ_V, at least {self.q_required:g} (M53.7); σ_add from "
            f"{self.additional_source}.",
        )

    def _validity_table(self) -> SummaryTable:
        cols = (
            SummaryColumn("ratio", "Ratio"),
            SummaryColumn("value", "Value"),
            SummaryColumn("low", "Lowest"),
            SummaryColumn("high", "Highest"),
            SummaryColumn("within", "Within"),
            SummaryColumn("factors", "Limits"),
            SummaryColumn("clause", "Clause"),
        )
        rows = tuple(
            (
                v.name,
                v.value,
                None if math.isinf(v.low) else v.low,
                None if math.isinf(v.high) else v.high,
                v.valid,
                v.applies_to,
                v.clause,
            )
            for v in self.validity
        )
        return SummaryTable(
            "m53_validity",
            "Ranges of the empirical stress concentration factors (UR M53.3)",
            cols,
            rows,
            caption="Ratios to the crankpin diameter D; factors outside their range are not "
            "the rule's (give FE factors, M53 Appendix III).",
        )

    def summary_verdicts(self) -> list[Verdict]:
        """The rule's checks (module docstring): Q >= 1.15 at every throw's crankpin fillet,
        journal fillet (solid crankshafts) and oil bore (M53.7), as sigma_V against
        sigma_DW / 1.15; the largest journal bore and the oversize of a semi-built
        crankshaft's shrink fit (M53.8).

        Returns
        -------
        list of crankdyn.summary.Verdict
            One per throw and location, then the shrink fit's.
        """
        condition = f"MCR {self.speed * RPM:.6g} rpm"
        if not self.torsion_given:
            condition += ", bending only (no torsional stress given)"
        out = []
        strengths = self.strengths()
        for t in range(self.throw_count):
            for j, location in enumerate(LOCATIONS):
                q = float(self.q_table()[t, j])
                if not math.isfinite(q):
                    continue
                reason = dict(self.extrapolated).get(location)
                limit = strengths[j] / self.q_required
                note = f"Q = {q:.4g}"
                if location != "oil bore":
                    note += f"; σ_add {self.additional / 1e6:.4g} MPa: {self.additional_source}"
                if reason is not None:
                    note += (
                        f"; the empirical factors do not apply ({reason}): give FE factors "
                        "(M53 Appendix III)"
                    )
                out.append(
                    Verdict(
                        component=f"throw {t + 1} {location}",
                        condition=condition,
                        quantity=(f"σ_V vs σ_DW / {self.q_required:g} (Q >= {self.q_required:g})"),
                        worst=float(np.asarray(self.equivalent)[t, j]),
                        limit=limit,
                        unit="Pa",
                        passed=bool(reason is None and q >= self.q_required),
                        source=self.rule,
                        clause="M53.7",
                        speed=self.speed,
                        note=note,
                        kind=location,
                    )
                )
        out += self._shrink_fit_verdicts(condition)
        return out

    def _shrink_fit_verdicts(self, condition: str) -> list[Verdict]:
        out: list[Verdict] = []
        if self.max_journal_bore is None:
            return out
        bore = self.journal_bore or 0.0
        ok = math.isfinite(self.max_journal_bore) and bore <= self.max_journal_bore
        out.append(
            Verdict(
                component="shrink fit",
                condition=condition,
                quantity="journal bore D_BG vs the largest bore",
                worst=bore,
                limit=self.max_journal_bore,
                unit="m",
                passed=bool(ok),
                source=self.rule,
                clause="M53.8.2",
                note="" if math.isfinite(self.max_journal_bore) else "even a solid pin yields",
                kind="shrink fit bore",
            )
        )
        if self.oversize is not None and self.min_oversize is not None:
            out.append(
                Verdict(
                    component="shrink fit",
                    condition=condition,
                    quantity="required oversize Z_min vs the oversize Z",
                    worst=self.min_oversize,
                    limit=self.oversize,
                    unit="m",
                    passed=self.oversize >= self.min_oversize,
                    source=self.rule,
                    clause="M53.8.3",
                    kind="shrink fit minimum oversize",
                )
            )
        if self.oversize is not None and self.max_oversize is not None:
            out.append(
                Verdict(
                    component="shrink fit",
                    condition=condition,
                    quantity="oversize Z vs Z_max",
                    worst=self.oversize,
                    limit=self.max_oversize,
                    unit="m",
                    passed=self.oversize <= self.max_oversize,
                    source=self.rule,
                    clause="M53.8.4",
                    kind="shrink fit maximum oversize",
                )
            )
        return out

    def quantities_table(self) -> SummaryTable:
        """Every quantity of the check, one row each: per throw its nominal loads, per throw and
        location the nominal stresses, the stress concentration factors, the stresses, the
        additional and equivalent stresses, the fatigue strength and Q, each with its unit and
        clause (:data:`QUANTITIES`; the JSON's ``quantities``, the command line's CSV).

        Returns
        -------
        crankdyn.summary.SummaryTable
            ``m53_quantities``: throw, location, quantity, symbol, value (SI), unit, clause.
        """
        rows = []
        strengths = self.strengths()
        for t in range(self.throw_count):
            for j, location in enumerate(("throw", *LOCATIONS)):
                if j and not math.isfinite(float(self.q_table()[t, j - 1])):
                    continue
                for symbol, words, unit, clause, value in _quantities(self, t, location):
                    rows.append((t + 1, location, words, symbol, _cell(value), unit, clause))
                if j:
                    rows.append(
                        (t + 1, location, "fatigue strength", "σ_DW", strengths[j - 1], "Pa",
                         "M53.6")
                    )  # fmt: skip
                    rows.append(
                        (t + 1, location, "acceptability factor", "Q",
                         float(self.q_table()[t, j - 1]), "", "M53.7")
                    )  # fmt: skip
        return SummaryTable(
            "m53_quantities",
            "Every quantity of the check (UR M53)",
            (
                SummaryColumn("throw", "Throw"),
                SummaryColumn("location", "Location"),
                SummaryColumn("quantity", "Quantity"),
                SummaryColumn("symbol", "Symbol"),
                SummaryColumn("value", "Value (SI)"),
                SummaryColumn("unit", "Unit"),
                SummaryColumn("clause", "Clause"),
            ),
            tuple(rows),
            caption=f"{self.rule}; values in SI units.",
        )

    def to_dict(self) -> dict[str, Any]:
        """The result as JSON data (:meth:`crankdyn.results.Result.to_dict`) with the validity
        of the empirical factors, every quantity with its unit and clause
        (:meth:`quantities_table`), where each throw's M_TN comes from, and the verdict rows.

        Returns
        -------
        dict
            SI values, units in the keys.
        """
        out = super().to_dict()
        out["validity"] = [v.to_dict() for v in self.validity]
        out["quantities"] = self.quantities_table().to_dict()["rows"]
        if self.torsion_where is not None:
            out["nominal_torque_from"] = list(self.torsion_where)
        out["verdicts"] = [v.to_dict() for v in self.summary_verdicts()]
        return out


QUANTITIES = {
    "throw": (
        ("M_BN", "web bending moment half-range", "N·m", "M53.2.1.2.1", "moment_half_range"),
        ("Q_N", "web radial force half-range", "N", "M53.2.1.2.1", "force_half_range"),
        ("M_TN", "alternating torque half-range", "N·m", "M53.2.2.2", "torsion_torque"),
    ),
    "crankpin fillet": (
        ("σ_BFN", "nominal web bending stress", "Pa", "M53.2.1.2.1", "sigma_bfn"),
        ("α_B", "bending stress concentration factor", "", "M53.3.2", "alpha_b"),
        ("σ_BH", "bending stress in the fillet", "Pa", "M53.2.1.3", "bending"),
        ("τ_N", "nominal torsional stress (crankpin)", "Pa", "M53.2.2.2", "tau_pin"),
        ("α_T", "torsion stress concentration factor", "", "M53.3.2", "alpha_t"),
        ("τ_H", "torsional stress in the fillet", "Pa", "M53.2.2.3", "torsion"),
        ("σ_add", "additional bending stress", "Pa", "M53.4", "additional"),
        ("σ_V", "equivalent alternating stress", "Pa", "M53.5", "equivalent"),
    ),
    "journal fillet": (
        ("σ_BFN", "nominal web bending stress", "Pa", "M53.2.1.2.1", "sigma_bfn"),
        ("σ_QFN", "nominal web compressive stress", "Pa", "M53.2.1.2.1", "sigma_qfn"),
        ("β_B", "bending stress concentration factor", "", "M53.3.3", "beta_b"),
        ("β_Q", "compression stress concentration factor", "", "M53.3.3", "beta_q"),
        ("σ_BG", "bending stress in the fillet", "Pa", "M53.2.1.3", "bending"),
        ("τ_N", "nominal torsional stress (journal)", "Pa", "M53.2.2.2", "tau_journal"),
        ("β_T", "torsion stress concentration factor", "", "M53.3.3", "beta_t"),
        ("τ_G", "torsional stress in the fillet", "Pa", "M53.2.2.3", "torsion"),
        ("σ_add", "additional bending stress", "Pa", "M53.4", "additional"),
        ("σ_V", "equivalent alternating stress", "Pa", "M53.5", "equivalent"),
    ),
    "oil bore": (
        ("M_BON", "oil bore bending moment half-range", "N·m", "M53.2.1.2.2",
         "oil_bore_half_range"),
        ("σ_BON", "nominal oil bore bending stress", "Pa", "M53.2.1.2.2", "sigma_bon"),
        ("γ_B", "bending stress concentration factor", "", "M53.3.4", "gamma_b"),
        ("σ_BO", "bending stress at the outlet", "Pa", "M53.2.1.4", "bending"),
        ("τ_N", "nominal torsional stress (crankpin)", "Pa", "M53.2.2.2", "tau_pin"),
        ("γ_T", "torsion stress concentration factor", "", "M53.3.4", "gamma_t"),
        ("σ_TO", "torsional stress at the outlet", "Pa", "M53.2.2.3", "torsion"),
        ("σ_V", "equivalent alternating stress", "Pa", "M53.5", "equivalent"),
    ),
}  # fmt: skip
"""The rows of :meth:`CrankshaftResult.quantities_table` by location: symbol, words, unit,
clause and the field holding the value (per throw, per throw and location, or one for all)."""

_BY_LOCATION = {"bending", "torsion", "equivalent"}


def _quantities(
    r: CrankshaftResult, throw: int, location: str
) -> list[tuple[str, str, str, str, float]]:
    """(symbol, words, unit, clause, value) of one throw's location."""
    out = []
    j = LOCATIONS.index(location) if location in LOCATIONS else -1
    for symbol, words, unit, clause, name in QUANTITIES[location]:
        raw = getattr(r, name)
        if raw is None:
            continue
        data = np.asarray(raw, dtype=float)
        if name in _BY_LOCATION:
            value = float(data[throw, j])
        elif data.ndim == 1:
            value = float(data[throw])
        else:
            value = float(data)
        out.append((symbol, words, unit, clause, value))
    return out


def _cell(value: float) -> float | None:
    v = float(value)
    return v if math.isfinite(v) else None
