"""The beam model of an engine's crankshaft from its engine file, and the pin forces that excite
it (analysis).

:func:`engine_beam_model` builds :mod:`crankdyn.crankshaft.beam_model`'s structure from what the
engine file says:

- **a throw** from the ``[crankshaft]`` geometry of UR M53 (:mod:`crankdyn.crankshaft.geometry`):
  journal and pin diameters and bores, web thickness W and width B, the crank radius R of the
  engine; the journal's length l_j = 2 L_1 - W (L_1, the main-bearing centre to the web centre
  of UR M53 Fig. 1, is half a journal plus half a web, the beam model's web mid-plane) and the
  pin's l_p = L_3 - l_j - 2 W (L_3 the bearing span, default the cylinder pitch);
- **the material**: E_m of ``[crankshaft]`` (default 205 GPa), nu and rho of
  ``[crankshaft.beam]`` (:class:`crankdyn.crankshaft.beam_inputs.BeamInputs`);
- **the rod and piston** of every cylinder on a throw: its rod's big-end mass m_CB rotating with
  the pin and its reciprocating mass m_j (seed 000 section 2.1,
  :func:`crankdyn.engine.forces.engine_masses`); the crank's own unbalance m_k is not added:
  the beam model carries the webs' and the pin's mass;
- **main bearings, counterweights** and the mesh from ``[crankshaft.beam]``;
- **the end bodies and the shaft line** from the engine's ``[torsion]`` model when it is a chain
  with one degree of freedom per throw: the degree of freedom before the first throw is the body
  at the free end (its inertia), the one after the last the flywheel (with whatever shares its
  degree of freedom, a coupling's primary part), the rest of the line a chain of torsional
  inertias and stiffnesses (reflected to the crankshaft's speed, Ker Wilson vol. 1 ch. 3), the
  dampers at the free end as damper rings. Then the beam model's torsional modes correspond one
  to one with the lumped model's, and :func:`crankdyn.crankshaft.beam_modes.compare_torsional_modes`
  says how well the lumped model holds. A branched model, or a chain with more than one degree
  of freedom before the first throw, is attached as far as it can be and the notes say so.

Estimates where the files say nothing (each named in the notes):

- the mass m and the diametral inertia of an end body from its polar inertia J, as a solid
  steel disc whose thickness t is a fifth of its diameter D: J = pi rho t D^4 / 32 gives
  D = (160 J / (pi rho))^(1/5), m = pi rho t D^2 / 4, diametral inertia m (D^2 / 16 + t^2 / 12)
  (the disc's inertias, any dynamics text, e.g. J. L. Meriam and L. G. Kraige, *Engineering
  Mechanics: Dynamics*, table D/4);
- the stub that carries an end body: a journal-section shaft of the length whose torsional
  stiffness G J_p / L in series with half the beam's throw (2 k_t,
  :func:`crankdyn.crankshaft.beam_stiffness.throw_stiffness`) is the lumped model's shaft to
  that body, at most one bearing span (0 when the lumped shaft is stiffer than half a throw);
- rigid supports (:mod:`crankdyn.crankshaft.beam_inputs`).

:func:`pin_force_harmonics` gives the excitation of :func:`crankdyn.crankshaft.beam_response.
beam_response`: the radial and tangential forces of every throw's rods on its pin, as complex
amplitudes of the orders of the crankshaft speed at every speed. The piston force is
P = s(Omega) p A - p_cc A + Omega^2 P_1, the absolute cylinder pressure p scaled by the load law
s(Omega) of the torsional model's excitation (the same load curve as the torsional excitation,
:meth:`crankdyn.torsion.excitation.EngineExcitation.load_factor`: Mendes et al. 2008), the
crankcase pressure p_cc not scaled, and the inertia force P_1 = -m_j a at 1 rad/s scaled by
Omega^2; the tangential and radial forces are T = P sin(phi + beta)/cos(beta) and
Z = P cos(phi + beta)/cos(beta) (seed 000 section 2.2), the rods of one pin summed. Their
Fourier coefficients c_q, F(theta) = Re(sum_q c_q exp(i q theta)), come from the FFT of one
working cycle sampled at :data:`SAMPLES` angles, as the torsional excitation's
(:mod:`crankdyn.torsion.excitation`). The constant big-end centrifugal force is order 0 and
excites nothing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.crankshaft.beam_elements import BeamMaterial, BeamSection
from crankdyn.crankshaft.beam_inputs import RIGID_FACTOR, BeamInputs
from crankdyn.crankshaft.beam_model import (
    CrankshaftBeamGeometry,
    CrankshaftBeamModel,
    EndMass,
    MainBearings,
    ThrowDimensions,
    ThrowMasses,
    TorsionalDamper,
    build_beam_model,
)
from crankdyn.crankshaft.geometry import Crankshaft
from crankdyn.engine.model import Engine
from crankdyn.errors import InputError
from crankdyn.torsion.model import TorsionModel

__all__ = [
    "SAMPLES",
    "EngineBeam",
    "beam_throw_stiffness",
    "disc_of_inertia",
    "engine_beam_model",
    "pin_force_harmonics",
    "throw_dimensions",
    "torsional_rows",
]

SAMPLES = 7200
"""Angles per working cycle of the pin forces' FFT (0.1 deg four-stroke), as the torsional
excitation's (:data:`crankdyn.torsion.excitation.SAMPLES`)."""

DISC_ASPECT = 0.2
"""Thickness / diameter of the steel disc an end body's mass is estimated as (module
docstring)."""


def _crankshaft(engine: Engine) -> Crankshaft:
    if engine.crankshaft is None:
        raise InputError(
            "the engine has no [crankshaft]: the beam model needs its dimensions "
            "(crankdyn docs engine-file)",
            file=engine.source,
            key="[crankshaft]",
        )
    return engine.crankshaft


def throw_dimensions(engine: Engine, crankshaft: Crankshaft | None = None) -> ThrowDimensions:
    """One throw of the beam model from the ``[crankshaft]`` geometry (module docstring):
    l_j = 2 L_1 - W, l_p = L_3 - l_j - 2 W.

    Parameters
    ----------
    engine : crankdyn.engine.Engine
        The engine (its crank radius and cylinder pitch).
    crankshaft : Crankshaft or None
        The crankshaft; default the engine's.

    Returns
    -------
    ThrowDimensions
        The throw (m).

    Raises
    ------
    InputError
        Without a crankshaft or a bearing span, or when L_1, W and L_3 leave no journal or no
        pin (``2 L_1 <= W`` or ``L_3 <= 2 L_1 + W``).

    Examples
    --------
    >>> import crankdyn
    >>> t = throw_dimensions(crankdyn.Engine.example("marine-propulsion"))
    >>> round(t.journal_length, 6), round(t.pin_length, 6), round(t.span, 6)
    (0.155, 0.145, 0.53)
    """
    shaft = crankshaft if crankshaft is not None else _crankshaft(engine)
    return _throw(shaft, engine.geometry.crank_radius, engine.cylinders.pitch, engine.source)


def _throw(
    shaft: Crankshaft, crank_radius: float, pitch: float | None, source: str | None
) -> ThrowDimensions:
    """:func:`throw_dimensions` from the crank radius (m) and the cylinder pitch (m)."""
    g = shaft.geometry
    span = g.bearing_span if g.bearing_span is not None else pitch
    if span is None:
        raise InputError(
            "the bearing span L_3 is unknown: give [crankshaft] bearing_span or the cylinder pitch",
            file=source,
            key="[crankshaft] bearing_span",
        )
    journal = 2.0 * g.web_centre_distance - g.web_thickness
    pin = span - journal - 2.0 * g.web_thickness
    if journal <= 0.0 or pin <= 0.0:
        what = "journal (2 L_1 - W)" if journal <= 0.0 else "crankpin (L_3 - 2 L_1 - W)"
        raise InputError(
            f"L_1, W and L_3 leave no {what} for the beam model",
            file=source,
            key="[crankshaft] web_centre_distance",
            value=g.web_centre_distance,
        )
    return ThrowDimensions(
        journal_diameter=g.journal_diameter,
        journal_length=journal,
        pin_diameter=g.pin_diameter,
        pin_length=pin,
        web_thickness=g.web_thickness,
        web_width=g.web_width,
        crank_radius=crank_radius,
        journal_bore=g.journal_bore,
        pin_bore=g.pin_bore,
    )


def beam_throw_stiffness(
    crankshaft: Crankshaft, crank_radius: float, pitch: float | None, source: str | None = None
) -> float:
    """The torsional stiffness of one crank span (N m/rad) from the beam model of its throw, for
    the lumped torsional model (``[torsion.throws] stiffness = "beam"``, docs/crankshaft.md).

    One throw of the ``[crankshaft]`` geometry (:func:`throw_dimensions`), held as its main
    bearings hold it, with the mesh, beam theory and rigid web fraction of
    ``[crankshaft.beam]`` (:func:`crankdyn.crankshaft.beam_stiffness.throw_stiffness`): the
    throw stiffness the beam model's modes report, in place of an empirical formula (Carter's,
    Ker Wilson's) or a given value.

    Parameters
    ----------
    crankshaft : Crankshaft
        The engine file's ``[crankshaft]``.
    crank_radius : float
        The crank radius (m).
    pitch : float or None
        The cylinder pitch (m), the bearing span L_3 unless ``[crankshaft] bearing_span`` is given.
    source : str or None
        The file, for messages.

    Returns
    -------
    float
        k_t (N m/rad).

    Raises
    ------
    InputError
        As :func:`throw_dimensions`.

    Examples
    --------
    >>> import crankdyn
    >>> e = crankdyn.Engine.example("marine-propulsion")
    >>> assert e.crankshaft is not None
    >>> k = beam_throw_stiffness(e.crankshaft, e.geometry.crank_radius, e.cylinders.pitch)
    >>> round(k / 1e6, 2)  # MN m/rad, the "Torsional stiffness of a throw" of crankshaft modes
    74.09
    """
    from crankdyn.crankshaft.beam_stiffness import throw_stiffness

    inputs: BeamInputs = crankshaft.beam_inputs
    throw = _throw(crankshaft, crank_radius, pitch, source)
    material = BeamMaterial(
        crankshaft.material.youngs_modulus, inputs.poisson_ratio, inputs.density
    )
    return throw_stiffness(
        throw,
        material,
        elements=inputs.elements,
        theory=inputs.theory,
        web_rigid_fraction=inputs.web_rigid_fraction,
    ).torsional


def disc_of_inertia(polar_inertia: float, density: float) -> tuple[float, float]:
    """Mass and diametral inertia of a solid disc of thickness D / 5 with this polar inertia
    (module docstring).

    Parameters
    ----------
    polar_inertia : float
        J (kg m^2), >= 0.
    density : float
        rho (kg/m^3), > 0.

    Returns
    -------
    mass : float
        m (kg).
    diametral_inertia : float
        About a diameter through its centre (kg m^2).

    Examples
    --------
    >>> m, jd = disc_of_inertia(420.0, 7850.0)
    >>> round(m), round(jd, 1)
    (2250, 221.2)
    """
    if polar_inertia <= 0.0:
        return 0.0, 0.0
    d = (polar_inertia / (math.pi * density * DISC_ASPECT / 32.0)) ** 0.2
    t = DISC_ASPECT * d
    mass = math.pi * density * t * d * d / 4.0
    return mass, mass * (d * d / 16.0 + t * t / 12.0)


@dataclass(frozen=True, eq=False)
class EngineBeam:
    """The beam model of an engine's crankshaft and how it was made (:func:`engine_beam_model`).

    Parameters
    ----------
    model : CrankshaftBeamModel
        The assembled model.
    whole_line : bool
        Whether the beam model carries the engine's whole torsional model (its torsional modes
        then pair with the lumped model's).
    notes : tuple of str
        What was estimated or left out.
    """

    model: CrankshaftBeamModel
    whole_line: bool
    notes: tuple[str, ...]


@dataclass
class _Line:
    """What of the torsional model the beam carries (internal)."""

    free_end: float | None = None  # polar inertia (kg m^2)
    free_end_shaft: float | None = None  # N m/rad
    flywheel: float | None = None
    flywheel_shaft: float | None = None
    shaft_line: tuple[tuple[float, float], ...] = ()
    damper: TorsionalDamper | None = None
    whole: bool = False


def _line(model: TorsionModel | None, throws: int, notes: list[str]) -> _Line:
    """The end bodies, the shaft line and the damper of a chain model (module docstring)."""
    out = _Line()
    if model is None:
        notes.append("no [torsion] model: the beam model has no end bodies or shaft line")
        return out
    chain = model.chain
    dofs = sorted(set(model.cylinder_dofs.values()))
    first = dofs[0] if dofs else -1
    if chain is None or dofs != list(range(first, first + throws)):
        notes.append(
            "the torsional model is not a chain with one degree of freedom per throw: the beam "
            "model has no end bodies or shaft line; its torsional modes are compared with the "
            "lumped chain made from it"
        )
        return out
    last = first + throws - 1
    whole = first <= 1
    if first >= 1:
        out.free_end = float(chain.inertia[first - 1])
        out.free_end_shaft = float(chain.stiffness[first - 1])
    if first > 1:
        notes.append(
            f"the torsional model's {first - 1} degree(s) of freedom beyond the free-end body "
            "are not in the beam model"
        )
    if last + 1 < chain.size:
        out.flywheel = float(chain.inertia[last + 1])
        out.flywheel_shaft = float(chain.stiffness[last])
        out.shaft_line = tuple(
            (float(chain.inertia[j]), float(chain.stiffness[j - 1]))
            for j in range(last + 2, chain.size)
        )
    if np.any(chain.ground_stiffness > 0.0):
        notes.append("the torsional model's shafts to ground are not in the beam model")
        whole = False
    names = model.dof_names
    for d in model.dampers:
        at = next((i for i, n in enumerate(names) if d.at in n.split(" + ")), None)
        if first >= 1 and at == first - 1 and out.damper is None:
            out.damper = TorsionalDamper(d.inertia, d.stiffness, d.damping)
        else:
            notes.append(
                f"the damper {d.name} is not in the beam model (only one, at the free end)"
            )
            whole = whole and d.kind != "tuned"
    out.whole = whole
    return out


def torsional_rows(model: CrankshaftBeamModel, torsion: TorsionModel) -> NDArray[np.int_] | None:
    """The beam model's theta_z degrees of freedom at each degree of freedom of the torsional
    chain it carries (:func:`engine_beam_model`, module docstring), for pairing modes by shape
    (:func:`crankdyn.crankshaft.beam_modes.compare_torsional_modes`).

    The body at the free end and the flywheel are their nodes, a throw the mean of its two web
    mid-planes' axis nodes, the shaft line its torsional nodes (after a damper ring).

    Parameters
    ----------
    model : CrankshaftBeamModel
        The beam model built with ``torsion``.
    torsion : TorsionModel
        The torsional model.

    Returns
    -------
    numpy.ndarray or None
        Indices, shape (the chain's degrees of freedom, 2): a row's two entries are averaged
        (the same index twice for one node); None when ``torsion`` is not a chain whose degrees
        of freedom the beam model carries one to one.
    """
    chain = torsion.chain
    throws = model.geometry.throws
    dofs = sorted(set(torsion.cylinder_dofs.values()))
    first = dofs[0] if dofs else -1
    if chain is None or first > 1 or dofs != list(range(first, first + throws)):
        return None
    line = list(model.extra_nodes[1 if model.geometry.damper is not None else 0 :])
    after = chain.size - first - throws
    if after != (1 + len(line) if after else 0):
        return None
    end, wheel = model.free_end_node, model.flywheel_node
    nodes = [(end, end)] if first == 1 else []
    nodes += [(int(a), int(b)) for a, b in model.web_axis_nodes]
    if after:
        nodes += [(wheel, wheel)] + [(n, n) for n in line]
    return np.array([[model.dof(a, 5), model.dof(b, 5)] for a, b in nodes], dtype=int)


def _stub(
    given: float | None,
    lumped: float | None,
    kt: float,
    gj: float,
    span: float,
    what: str,
    notes: list[str],
) -> float:
    """The stub's length (m): given, else matching the lumped shaft (module docstring)."""
    if given is not None or lumped is None:
        return 0.0 if given is None else given
    compliance = 1.0 / lumped - 0.5 / kt
    if compliance <= 0.0:
        notes.append(
            f"the {what} sits at the end journal's centre: the torsional model's shaft to it "
            f"({lumped:.4g} N·m/rad) is stiffer than half a throw of the beam ({2 * kt:.4g})"
        )
        return 0.0
    length = gj * compliance
    if length > span:
        notes.append(
            f"the {what}'s stub is one bearing span long: a longer one would match the torsional "
            f"model's shaft to it ({gj * compliance:.4g} m)"
        )
        return span
    return length


def _end_body(
    inertia: float | None,
    mass: float | None,
    distance: float,
    density: float,
    what: str,
    notes: list[str],
) -> EndMass | None:
    if inertia is None and mass is None:
        return None
    j = inertia or 0.0
    est_mass, diametral = disc_of_inertia(j, density)
    if mass is None:
        mass = est_mass
        notes.append(
            f"the {what}'s mass {mass:.4g} kg estimated from its inertia {j:.4g} kg·m² (a steel "
            "disc one fifth as thick as its diameter; give [crankshaft.beam] "
            f"{what.replace(' ', '_')}_mass)"
        )
    else:
        diametral = diametral * (mass / est_mass) if est_mass > 0.0 else 0.0
    return EndMass(mass, j, diametral, distance)


def engine_beam_model(engine: Engine, model: TorsionModel | None = None) -> EngineBeam:
    """The beam model of the engine's crankshaft (module docstring).

    Parameters
    ----------
    engine : crankdyn.engine.Engine
        The engine: its ``[crankshaft]`` (and ``[crankshaft.beam]``), masses and throws.
    model : TorsionModel or None
        Its torsional model (the end bodies, the shaft line, the dampers); default the engine's
        ``[torsion]``.

    Returns
    -------
    EngineBeam
        The assembled model, whether it carries the whole torsional line, and the notes.

    Raises
    ------
    InputError
        Without a crankshaft, masses or bearing span, or with a thrust journal beyond the last.

    Examples
    --------
    >>> import crankdyn
    >>> beam = engine_beam_model(crankdyn.Engine.example("marine-propulsion"))
    >>> beam.whole_line, len(beam.model.journal_nodes)
    (True, 7)
    """
    from crankdyn.crankshaft.beam_stiffness import throw_stiffness
    from crankdyn.engine.forces import engine_masses

    shaft = _crankshaft(engine)
    inputs: BeamInputs = shaft.beam_inputs
    throw = throw_dimensions(engine, shaft)
    material = BeamMaterial(shaft.material.youngs_modulus, inputs.poisson_ratio, inputs.density)
    notes: list[str] = []
    cyl = engine.cylinders
    masses = engine_masses(engine)
    per_throw = []
    for t in range(1, cyl.throw_count + 1):
        on = [m for m, k in zip(masses, cyl.throws, strict=True) if k == t]
        per_throw.append(
            ThrowMasses(
                rotating_mass=sum(m.rod_big_end or 0.0 for m in on),
                reciprocating_mass=sum(m.reciprocating for m in on),
                counterweight_mass=inputs.counterweight_mass,
                counterweight_radius=(
                    engine.geometry.crank_radius
                    if inputs.counterweight_radius is None
                    else inputs.counterweight_radius
                ),
            )
        )
    journal = BeamSection.circular(throw.journal_diameter, throw.journal_bore, 0.0)
    e = material.youngs_modulus
    span = throw.span
    radial = inputs.bearing_radial_stiffness
    if radial is None:
        radial = RIGID_FACTOR * 48.0 * e * journal.second_moment_y / span**3
    axial = inputs.thrust_axial_stiffness
    if axial is None:
        axial = RIGID_FACTOR * e * journal.area / span
    thrust = cyl.throw_count + 1 if inputs.thrust_journal is None else inputs.thrust_journal
    rigid = [
        key
        for key in ("bearing_radial_stiffness", "thrust_axial_stiffness")
        if getattr(inputs, key) is None
    ]
    if rigid:
        notes.append(
            "main bearings taken as rigid supports (UR M53's statically determinate throw; 100 "
            f"times the shaft's stiffness): give [crankshaft.beam] {' and '.join(rigid)}"
        )
    torsion = model if model is not None else engine.torsion
    line = _line(torsion, cyl.throw_count, notes)
    kt = throw_stiffness(
        throw,
        material,
        elements=inputs.elements,
        theory=inputs.theory,
        web_rigid_fraction=inputs.web_rigid_fraction,
    ).torsional
    gj = material.shear_modulus * journal.torsion_constant
    ends = {}
    for what, inertia, lumped, mass, given in (
        ("free end", line.free_end, line.free_end_shaft, inputs.free_end_mass,
         inputs.free_end_distance),
        ("flywheel", line.flywheel, line.flywheel_shaft, inputs.flywheel_mass,
         inputs.flywheel_distance),
    ):  # fmt: skip
        distance = _stub(given, lumped, kt, gj, span, what, notes)
        ends[what] = _end_body(inertia, mass, distance, inputs.density, what, notes)
    geometry = CrankshaftBeamGeometry(
        throw=throw,
        pin_angles=tuple(float(a) for a in cyl.throw_positions),
        material=material,
        bearings=MainBearings(radial, inputs.bearing_tilting_stiffness, axial, thrust),
        masses=tuple(per_throw),
        free_end=ends["free end"],
        flywheel=ends["flywheel"],
        shaft_line=line.shaft_line,
        damper=line.damper,
        axial_damping=inputs.axial_damping,
    )
    built = build_beam_model(
        geometry,
        elements=inputs.elements,
        theory=inputs.theory,
        web_rigid_fraction=inputs.web_rigid_fraction,
    )
    return EngineBeam(built, line.whole, tuple(notes))


def pin_force_harmonics(
    engine: Engine,
    speeds: ArrayLike,
    orders: ArrayLike,
    *,
    load_factor: ArrayLike | None = None,
) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
    """Radial and tangential pin forces of every throw as harmonics of the crankshaft angle
    (module docstring).

    Parameters
    ----------
    engine : crankdyn.engine.Engine
        The engine (masses required; its pressure trace or synthetic model).
    speeds : array_like
        Crankshaft speeds Omega (rad/s), shape (S,).
    orders : array_like
        Orders q (per revolution), harmonics of the cycle, shape (Q,).
    load_factor : array_like or None
        s(Omega), the scale of the absolute cylinder pressure at every speed (dimensionless,
        shape (S,)); None: 1.

    Returns
    -------
    radial, tangential : numpy.ndarray
        Complex amplitudes c_q (N), shape (S, Q, throws); radial positive toward the crank
        centre, tangential in the direction of rotation.

    Raises
    ------
    InputError
        Without masses, or orders that do not fit the cycle.

    Examples
    --------
    >>> import crankdyn
    >>> e = crankdyn.Engine.example("marine-propulsion")
    >>> z, t = pin_force_harmonics(e, [50.0, 100.0], [1.0, 2.0])
    >>> z.shape, t.dtype.kind  # speeds x orders x throws, complex
    ((2, 2, 6), 'c')
    """
    from crankdyn.engine.forces import crank_train, rod_forces
    from crankdyn.torsion.orders import check_orders, harmonic_index

    speed = np.atleast_1d(np.asarray(speeds, dtype=float))
    q = check_orders(orders, engine.cycle)
    m = harmonic_index(q, engine.cycle)
    theta = np.linspace(0.0, engine.cycle_angle, SAMPLES, endpoint=False)
    train = crank_train(engine, 1.0, theta)
    g = engine.geometry
    _, _, lever_t, lever_r = rod_forces(np.ones_like(train.phi), train.phi, g.lam, g.k)
    area = g.piston_area
    parts = np.stack(
        [
            train.pressure * area,  # absolute pressure, scaled by the load
            np.full_like(train.pressure, engine.crankcase_pressure * area),
            train.inertia,  # at 1 rad/s
        ]
    )  # (3, Z, N)
    spectra = np.fft.rfft(parts[:, None] * np.stack([lever_r, lever_t])[None], axis=-1)
    c = spectra[..., m] * (2.0 / SAMPLES)  # (3, 2, Z, Q)
    s = np.ones(speed.size) if load_factor is None else np.asarray(load_factor, dtype=float)
    weights = np.stack([s, -np.ones(speed.size), speed**2], axis=1)  # (S, 3)
    per_cylinder = np.einsum("sp,pfzq->fsqz", weights, c)  # (2, S, Q, Z)
    count = engine.cylinders.throw_count
    out = np.zeros((2, speed.size, q.size, count), dtype=complex)
    for i, t in enumerate(engine.cylinders.throws):  # a handful of cylinders
        out[..., t - 1] += per_cylinder[..., i]
    return out[0], out[1]
