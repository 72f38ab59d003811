"""The crankshaft's analyses: its fatigue strength by IACS UR M53 and its beam model (coupled
modes, forced response), and the crankshaft rows of the TVC (:class:`CrankshaftAnalyses`, part of
:class:`crankdyn.session.Analysis`).

The M53 check takes its nominal torsional stress from the session's own forced torsional
response, the one the TVC judges (:meth:`~crankdyn.session.torsion.TorsionAnalyses.response`,
its barred ranges from :meth:`~crankdyn.session.torsion.TorsionAnalyses.judged`), and, when the
crankshaft's additional stress comes from the beam model, the beam model's web bending stress
from vibration over the same speed range; the TVC renders the check's verdict rows beside its
own. Every analysis is computed once.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from crankdyn.constants import RPM
from crankdyn.crankshaft.beam_inputs import ADDITIONAL_STRESS_SOURCES
from crankdyn.errors import InputError
from crankdyn.session.core import with_parameters
from crankdyn.session.torsion import TorsionAnalyses

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence

    from crankdyn.crankshaft.beam_engine import EngineBeam
    from crankdyn.crankshaft.beam_modes import BeamModesResult
    from crankdyn.crankshaft.beam_response import BeamResponseResult
    from crankdyn.crankshaft.result import CrankshaftResult
    from crankdyn.engine.model import Engine
    from crankdyn.tvc import TvcResult, TvcSpec

__all__ = ["CrankshaftAnalyses"]


@with_parameters
class CrankshaftAnalyses(TorsionAnalyses):
    """The crankshaft's analyses, each computed once per set of options."""

    def _need_crankshaft(self, what: str) -> Engine:
        engine = self._need_masses(what)
        if engine.crankshaft is None:
            raise InputError(
                f"the engine has no [crankshaft]: {what} needs its dimensions and material "
                "(crankdyn docs engine-file)",
                file=engine.source,
                key="[crankshaft]",
            )
        return engine

    def crankshaft_beam(self) -> EngineBeam:
        """The beam model of the engine's crankshaft with its torsional model's end bodies,
        shaft line and dampers (:func:`crankdyn.crankshaft.beam_engine.engine_beam_model`).

        Returns
        -------
        crankdyn.crankshaft.beam_engine.EngineBeam
            The assembled model and its notes.
        """
        from crankdyn.crankshaft.beam_engine import engine_beam_model

        engine = self._need_crankshaft("the crankshaft's beam model")
        return self._cached("crankshaft_beam", lambda: engine_beam_model(engine, self.model))

    def crankshaft_modes(self, count: int | None = None) -> BeamModesResult:
        """The coupled modes of the crankshaft's beam model, classified by their motion
        (:func:`crankdyn.crankshaft.beam_modes.beam_modes`), a throw's torsional and axial
        stiffness (:func:`crankdyn.crankshaft.beam_stiffness.throw_stiffness`), and the torsional
        modes beside the lumped model's: the session's torsional model (its tuned dampers as
        masses, :func:`crankdyn.torsion.campbell.with_dampers`) when the beam carries the whole
        line, else the lumped chain made from the beam
        (:func:`crankdyn.crankshaft.beam_stiffness.lumped_torsional_chain`).

        Parameters
        ----------
        count : int or None
            Modes to find; default ``[crankshaft.beam] modes`` (24).

        Returns
        -------
        crankdyn.crankshaft.beam_modes.BeamModesResult
            Frequencies (rad/s), motions, energy fractions, the lumped model's frequencies.
        """
        engine = self._need_crankshaft("the crankshaft's modes")
        assert engine.crankshaft is not None  # checked above
        n = engine.crankshaft.beam_inputs.modes if count is None else int(count)
        return self._cached(("crankshaft_modes", n), lambda: self._beam_modes(n))

    def _beam_modes(self, count: int) -> BeamModesResult:
        from dataclasses import replace

        from crankdyn.crankshaft.beam_engine import torsional_rows
        from crankdyn.crankshaft.beam_modes import beam_modes, compare_torsional_modes
        from crankdyn.crankshaft.beam_stiffness import lumped_chain_comparison, throw_stiffness

        beam = self.crankshaft_beam()
        model = beam.model
        modes = beam_modes(model, count)
        g = model.geometry
        stiffness = throw_stiffness(
            g.throw,
            g.material,
            elements=model.elements_per_part,
            theory=model.theory,
            web_rigid_fraction=model.web_rigid_fraction,
        )
        if beam.whole_line and self.model is not None:
            from crankdyn.torsion.campbell import with_dampers
            from crankdyn.torsion.modal import natural_modes

            chain = with_dampers(self.model)
            lumped = natural_modes(chain)
            rows = torsional_rows(model, self.model)
            shapes = None
            if (
                rows is not None
                and chain.dof_names == self.model.dof_names
                and lumped.shapes_dof is not None
                and lumped.shapes_dof.shape == (lumped.natural_frequency.size, rows.shape[0])
            ):
                at = 0.5 * (modes.shapes[rows[:, 0]] + modes.shapes[rows[:, 1]])
                shapes = (at, lumped.shapes_dof.T)
            comparison = compare_torsional_modes(modes, lumped.natural_frequency, shapes=shapes)
            what = f"the torsional model {self.model.name or ''}".rstrip()
        else:
            comparison = lumped_chain_comparison(model, modes)
            what = "the lumped chain made from the beam model"
        modes = modes.with_lumped(comparison, what)
        return replace(
            modes,
            throw_torsional_stiffness=stiffness.torsional,
            throw_axial_stiffness=stiffness.axial,
            notes=(*modes.notes, *beam.notes),
        )

    def crankshaft_response(self) -> BeamResponseResult:
        """The forced response of the crankshaft's beam model to the pins' radial and tangential
        forces over the session's speeds (:func:`crankdyn.crankshaft.beam_response.beam_response`;
        the forces of :func:`crankdyn.crankshaft.beam_engine.pin_force_harmonics` under the load
        law of the torsional model's excitation), the critical speeds of the beam's modes added
        to the grid (:func:`crankdyn.crankshaft.beam_response.critical_speeds`).

        Returns
        -------
        crankdyn.crankshaft.beam_response.BeamResponseResult
            Axial and torsional vibration of the free end, bearing and web moments, the webs'
            bending stress from vibration, per speed.
        """
        return self._cached("crankshaft_response", self._beam_response)

    def _beam_response(self) -> BeamResponseResult:
        from dataclasses import replace

        from crankdyn.crankshaft.beam_engine import pin_force_harmonics
        from crankdyn.crankshaft.beam_response import beam_response, critical_speeds

        engine = self._need_crankshaft("the crankshaft's forced response")
        assert engine.crankshaft is not None  # checked above
        beam = self.crankshaft_beam()
        modes = self.crankshaft_modes()
        orders = self.engine_orders
        grid = self.speeds
        low, high = float(grid[0]), float(grid[-1])
        added = critical_speeds(modes.natural_frequency, orders, low, high)
        speeds = np.union1d(grid, added)
        scale, load_note = self._load_factor(engine, speeds)
        radial, tangential = pin_force_harmonics(engine, speeds, orders, load_factor=scale)
        result = beam_response(
            beam.model,
            speeds,
            orders,
            radial,
            tangential,
            damping_ratio=engine.crankshaft.beam_inputs.damping_ratio,
        )
        notes = [
            *result.notes,
            f"{added.size} critical speeds of the beam model's {modes.mode.size} lowest modes "
            "added to the speed grid",
            load_note,
            *beam.notes,
        ]
        return replace(result, notes=tuple(n for n in notes if n))

    def _load_factor(self, engine: Engine, speeds: np.ndarray) -> tuple[Any, str]:
        """s(Omega) of the loaded torsional model's excitation, and a note where there is
        none the pin forces can follow."""
        from crankdyn.torsion.excitation import EngineExcitation

        model = self.loaded_model
        spec = getattr(model, "excitation", None) if model is not None else None
        if spec is None:
            return None, "pin forces from the engine's cylinder pressure at every speed"
        if spec.traces or spec.harmonics is not None:
            return None, (
                "pin forces from the engine's cylinder pressure at every speed (the [excitation] "
                "traces or harmonic table give torques only)"
            )
        scale = EngineExcitation(engine, spec).load_factor(speeds)
        what = "load curve" if spec.load_curve is not None else "load (full load)"
        return scale, f"pin forces: the cylinder pressure under the torsional excitation's {what}"

    def crankshaft(self, *, additional_stress: str | None = None) -> CrankshaftResult:
        """The crankshaft's fatigue check by IACS UR M53
        (:func:`crankdyn.crankshaft.strength.crankshaft_strength`) at the session's speed (the
        maximum continuous rating), with M_TN of every throw from the session's forced
        torsional response outside its barred ranges
        (:func:`crankdyn.crankshaft.span_torques.nominal_torques`) and sigma_add from the
        rule or from the beam model's web bending stress from vibration
        (:func:`crankdyn.crankshaft.strength.additional_stress_of`).

        Parameters
        ----------
        additional_stress : str or None
            ``"rule"`` or ``"beam"``; default the crankshaft's
            (:attr:`crankdyn.crankshaft.geometry.Crankshaft.additional_stress_source`).

        Returns
        -------
        crankdyn.crankshaft.result.CrankshaftResult
            Q of every fillet and oil bore of every throw with every intermediate quantity, and
            the verdicts.

        Raises
        ------
        InputError
            Without a crankshaft or masses, an unknown source, or ``"beam"`` with an axial
            vibration stress given.
        """
        engine = self._need_crankshaft("the crankshaft's check (UR M53)")
        assert engine.crankshaft is not None  # checked above
        shaft = engine.crankshaft
        source = shaft.additional_stress_source if additional_stress is None else additional_stress
        if source not in ADDITIONAL_STRESS_SOURCES:
            raise InputError(
                f"expected one of {', '.join(ADDITIONAL_STRESS_SOURCES)}",
                key="additional_stress",
                value=source,
            )
        if source == "beam" and shaft.axial_vibration_stress is not None:
            raise InputError(
                "the engine file gives [crankshaft] axial_vibration_stress: the additional stress "
                "cannot also come from the beam model",
                file=engine.source,
                key="additional_stress",
                value=source,
            )
        return self._cached(("crankshaft", source), lambda: self._strength(engine, source))

    def _strength(self, engine: Engine, source: str) -> CrankshaftResult:
        from crankdyn.crankshaft.span_torques import nominal_torques
        from crankdyn.crankshaft.strength import crankshaft_strength

        torque = where = None
        notes: Sequence[str] = ()
        model = self.model
        if model is not None and model.cylinder_dofs:
            judged = self.judged()
            barred = [] if judged is None else [(b.start, b.end) for b in judged.barred_ranges]
            loaded = self.loaded_model
            assert loaded is not None  # a model's loaded model
            torque, where, notes = nominal_torques(engine, loaded, self.response(), barred)
        else:
            notes = ("no [torsion] model with the engine's cylinders: no torsional stress",)
        vibration = None
        vibration_where = ""
        if source == "beam":
            response = self.crankshaft_response()
            figure = response.summary().figure("max_web_vibration_stress_Pa")
            vibration = float(figure.value)
            axial = response.summary().figure("max_free_end_axial_m")
            vibration_where = (
                f"{figure.where}; free-end axial {axial.value * 1e3:.3g} mm {axial.where}"
            )
        return crankshaft_strength(
            engine,
            self.speed,
            torsion_torque=torque,
            torsion_where=where,
            notes=notes,
            vibration_stress=vibration,
            vibration_where=vibration_where,
        )

    def tvc(
        self,
        *,
        spec: TvcSpec | None = None,
        passage: bool = True,
        conditions: Sequence[str] | None = None,
        progress: Callable[[str], None] | None = None,
    ) -> TvcResult:
        """The torsional vibration calculation
        (:meth:`crankdyn.session.torsion.TorsionAnalyses.tvc`) with, when the engine has a
        ``[crankshaft]`` and the calculation runs on the session's own settings, the verdict
        rows of the crankshaft's check (:meth:`crankshaft`, UR M53) added: the TVC renders them,
        the check is made once.

        Parameters
        ----------
        spec, passage, conditions, progress
            As :meth:`crankdyn.session.torsion.TorsionAnalyses.tvc`.

        Returns
        -------
        crankdyn.tvc.TvcResult
            The verdict rows (the crankshaft's last), barred speed ranges (rad/s), passages,
            conditions, modes and the Campbell diagram.
        """
        result = super().tvc(spec=spec, passage=passage, conditions=conditions, progress=progress)
        engine = self.engine
        if spec is not None or engine is None or engine.crankshaft is None:
            return result
        if engine.masses is None:
            return result
        check = self.crankshaft()
        note = (
            f"crankshaft: {check.title}, at {check.speed * RPM:.6g} rpm, M_TN from this "
            "calculation's normal firing"
        )
        return self._cached(
            ("tvc+crankshaft", id(result)),
            lambda: (result, result.with_verdicts(tuple(check.summary_verdicts()), (note,))),
        )[1]
