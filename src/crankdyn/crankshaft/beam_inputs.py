"""What the engine file's ``[crankshaft.beam]`` says about the crankshaft's beam model (domain).

The beam model of the crankshaft (:mod:`crankdyn.crankshaft.beam_model`) is built from the
``[crankshaft]`` geometry of UR M53 (:mod:`crankdyn.crankshaft.geometry`), the engine's masses
and its ``[torsion]`` model (:mod:`crankdyn.crankshaft.beam_engine`); this table holds what
neither gives: the material's Poisson's ratio and density, the main bearings' stiffnesses, the
counterweights, the masses of the end bodies, the mesh and the damping of the forced response.
Every key has a default, so an engine with a ``[crankshaft]`` section has a beam model without
this table (``crankdyn docs crankshaft``).

Defaults and where they come from:

- Poisson's ratio 0.3 of steel: the value UR M53's FE appendix advises (KR Rules 2025 Pt 5
  Annex 5-3 Appendix III 2(2), "For steel the following is advised: E = 2.05 10^5 MPa and
  nu = 0.3"); the density 7850 kg/m^3, the usual value of carbon and low-alloy steels
  (crankdyn's default: give the material's);
- main bearings: effectively rigid supports at the journal centres, free to tilt, the supports
  of UR M53's statically determinate throw (M53.2.1.1 [Annex 5-3 2(1)(A)(a)]: a single
  crankthrow "supported in the centre of adjacent main journals"): a radial stiffness 100 times
  the bending stiffness 48 E I / L_3^3 of a journal-section beam over one bearing span and a
  thrust bearing 100 times the axial stiffness E A / L_3 of a journal over one span, at the
  journal next to the flywheel (:data:`RIGID_FACTOR`; crankdyn's idealisation, not measured
  bearing data: give the bearing maker's stiffnesses where known);
- no counterweights; the end bodies' masses and the stubs that carry them estimated by
  :mod:`crankdyn.crankshaft.beam_engine` (said in the result's notes);
- two elements per journal half, web, pin half and stub (the mesh error of the lowest modes
  below 2e-4 against eight, ``tests/crankshaft/test_beam_modes.py``), Timoshenko beams, 2 %
  modal damping in the forced response (the default of
  :func:`crankdyn.crankshaft.beam_response.beam_response`).
"""

from __future__ import annotations

from dataclasses import dataclass

from crankdyn.crank.geometry import check_finite, check_positive
from crankdyn.errors import InputError

__all__ = [
    "ADDITIONAL_STRESS_SOURCES",
    "DENSITY_STEEL",
    "POISSON_RATIO_STEEL",
    "RIGID_FACTOR",
    "THEORIES",
    "BeamInputs",
]

POISSON_RATIO_STEEL = 0.3
"""nu of steel (dimensionless): UR M53's FE appendix [Annex 5-3 Appendix III 2(2)]."""

DENSITY_STEEL = 7850.0
"""Density of carbon and low-alloy steels (kg/m^3), the usual value (crankdyn's default)."""

RIGID_FACTOR = 100.0
"""A default bearing is this many times stiffer than the shaft it holds (module docstring): the
rigid supports of UR M53's statically determinate throw, within 1 % of them for the throw's
bending (crankdyn's idealisation)."""

ADDITIONAL_STRESS_SOURCES = ("rule", "beam")
"""Where UR M53's additional bending stress from vibration comes from: the rule's values
(M53.4) or the beam model's forced response (M53.4(3): "where axial vibration calculation
results of the complete dynamic system are available, the calculated figures may be used
instead")."""

THEORIES = ("timoshenko", "euler-bernoulli")
"""Beam theories: Timoshenko (shear deformation and rotary inertia) or Euler-Bernoulli (neither)."""


def _nonnegative(name: str, value: object) -> float:
    number = check_finite(name, value)
    if number < 0.0:
        raise InputError("must not be negative", key=name, value=value)
    return number


@dataclass(frozen=True)
class BeamInputs:
    """The ``[crankshaft.beam]`` table: the beam model's own inputs (SI; module docstring).

    Parameters
    ----------
    poisson_ratio : float
        nu of the crankshaft's material (dimensionless, 0 <= nu < 0.5); default 0.3.
    density : float
        Its density (kg/m^3); default 7850.
    bearing_radial_stiffness : float or None
        Radial stiffness of every main bearing, both directions across the shaft (N/m); None:
        effectively rigid (module docstring).
    bearing_tilting_stiffness : float
        Tilting stiffness of every main bearing (N m/rad); default 0 (free to tilt).
    thrust_axial_stiffness : float or None
        Axial stiffness of the thrust bearing (N/m); None: effectively rigid.
    thrust_journal : int or None
        The journal with the thrust bearing, 1 the free end's; None: the last (next to the
        flywheel).
    counterweight_mass : float
        Counterweight mass of every throw (kg), split between its two webs; default 0.
    counterweight_radius : float or None
        Radius of the counterweights' centre of mass, opposite the pin (m); None: the crank
        radius.
    free_end_mass, flywheel_mass : float or None
        Mass of the body at the free end (damper hub, pulley) and of the flywheel (kg); None:
        estimated from their inertia (:mod:`crankdyn.crankshaft.beam_engine`).
    free_end_distance, flywheel_distance : float or None
        Length of the journal-section stub from the end journal's centre to that body (m);
        None: the stub whose torsional stiffness in series with half a throw is the torsional
        model's shaft to that body.
    axial_damping : float
        An axial vibration damper at the free end (N s/m); default 0.
    elements : int
        Beam elements per journal half, web, pin half and stub (>= 1); default 2.
    theory : str
        ``"timoshenko"`` (default) or ``"euler-bernoulli"``.
    web_rigid_fraction : float
        The webs' rigid end zones f (dimensionless; :mod:`crankdyn.crankshaft.beam_model`);
        default 0.
    modes : int
        Modes listed by the modal analysis (>= 1); default 24.
    damping_ratio : float
        Modal damping ratio of the forced response (dimensionless, >= 0); default 0.02.

    Raises
    ------
    InputError
        A stiffness, mass or length negative or not finite, a thrust journal below 1, a whole
        number that is not one, an unknown theory (the key names the field).

    Examples
    --------
    >>> b = BeamInputs(thrust_journal=1, counterweight_mass=120.0)
    >>> b.elements, b.poisson_ratio, b.thrust_journal
    (2, 0.3, 1)
    """

    poisson_ratio: float = POISSON_RATIO_STEEL
    density: float = DENSITY_STEEL
    bearing_radial_stiffness: float | None = None
    bearing_tilting_stiffness: float = 0.0
    thrust_axial_stiffness: float | None = None
    thrust_journal: int | None = None
    counterweight_mass: float = 0.0
    counterweight_radius: float | None = None
    free_end_mass: float | None = None
    flywheel_mass: float | None = None
    free_end_distance: float | None = None
    flywheel_distance: float | None = None
    axial_damping: float = 0.0
    elements: int = 2
    theory: str = "timoshenko"
    web_rigid_fraction: float = 0.0
    modes: int = 24
    damping_ratio: float = 0.02

    def __post_init__(self) -> None:
        set_ = object.__setattr__
        nu = check_finite("poisson_ratio", self.poisson_ratio)
        if not 0.0 <= nu < 0.5:
            raise InputError("must lie in [0, 0.5)", key="poisson_ratio", value=self.poisson_ratio)
        set_(self, "poisson_ratio", nu)
        set_(self, "density", check_positive("density", self.density, "the density"))
        for name in (
            "bearing_radial_stiffness",
            "thrust_axial_stiffness",
            "counterweight_radius",
            "free_end_mass",
            "flywheel_mass",
            "free_end_distance",
            "flywheel_distance",
        ):
            if getattr(self, name) is not None:
                set_(self, name, _nonnegative(name, getattr(self, name)))
        for name in (
            "bearing_tilting_stiffness",
            "counterweight_mass",
            "axial_damping",
            "web_rigid_fraction",
            "damping_ratio",
        ):
            set_(self, name, _nonnegative(name, getattr(self, name)))
        for name in ("elements", "modes"):
            value = getattr(self, name)
            if isinstance(value, bool) or int(value) != value or value < 1:
                raise InputError("expected a whole number of at least 1", key=name, value=value)
            set_(self, name, int(value))
        if self.thrust_journal is not None:
            journal = self.thrust_journal
            if isinstance(journal, bool) or int(journal) != journal or journal < 1:
                raise InputError(
                    "journals are numbered from 1 (the free end's)",
                    key="thrust_journal",
                    value=journal,
                )
            set_(self, "thrust_journal", int(journal))
        if self.theory not in THEORIES:
            raise InputError(
                f"expected one of {', '.join(THEORIES)}", key="theory", value=self.theory
            )

    def defaulted(self) -> tuple[str, ...]:
        """The inputs left to crankdyn's estimates (None), for the result's notes.

        Returns
        -------
        tuple of str
            Field names.
        """
        return tuple(
            name
            for name in (
                "bearing_radial_stiffness",
                "thrust_axial_stiffness",
                "free_end_mass",
                "flywheel_mass",
                "free_end_distance",
                "flywheel_distance",
            )
            if getattr(self, name) is None
        )
