"""A crank throw's equivalent torsional and axial stiffness from the beam model, and the lumped
torsional chain of a beam model (analysis).

Stiffness of one throw (a static solve of the beam model of one crank span, main journal centre
A to main journal centre B, :mod:`crankdyn.crankshaft.beam_model`): a unit torque about the shaft
axis (or a unit force along it) at B, the other end held; k_t = T / theta_z(B), k_a =
F / u_z(B). ``supported=True`` holds the shaft as its main bearings do: A is fixed in
translation and in rotation about the axis, B in translation across the shaft, both free to tilt;
``supported=False`` clamps A and leaves B free (a cantilever). The equivalent length is the
length of plain journal-section shaft with the same torsional stiffness, l_e = G J_j / k_t.

Empirical torsional stiffness of a throw, for comparison, with the journal diameter D_j, bore d_j
and length l_j, the pin's D_p, d_p, l_p, the web thickness h and width b and the crank radius R:

- Carter (B. C. Carter, "An empirical formula for crankshaft stiffness in torsion", Engineering
  126 (1928) 36; :func:`crankdyn.torsion.equivalent.carter_throw_stiffness`)::

      k = (pi G / 32) / [(l_j + 0.8 h)/(D_j^4 - d_j^4) + 0.75 l_p/(D_p^4 - d_p^4) + 1.5 R/(h b^3)]

- Ker Wilson (W. Ker Wilson, *Practical Solution of Torsional Vibration Problems*, 3rd ed.,
  vol. 1, Chapman & Hall, 1956, the crankshaft-stiffness chapter; tabulated beside Carter's,
  Tuplin's and the BICERA formula in A. Nestorides, *A Handbook on Torsional Vibration*, BICERA,
  Cambridge University Press, 1958)::

      k = (pi G / 32) / [(l_j + 0.4 D_j)/(D_j^4 - d_j^4) + (l_p + 0.4 D_p)/(D_p^4 - d_p^4)
                         + (R - 0.2 (D_j + D_p))/(h b^3)]

  Quoted from the secondary literature: the search of this project found no scan of the printed
  page to check the coefficients against.

Both are empirical fits to measured crankshafts of their time; their spread on one throw is a
measure of what an equivalent stiffness can claim.

The lumped chain of a beam model (:func:`lumped_torsional_chain`): one mass per throw (and for
the free-end body, the flywheel, the damper ring and the shaft line), its inertia the share of
the beam model's rigid-rotation kinetic energy r^T M r of the nodes of its throw (the nodes on a
journal centre split half and half, the end stubs with their end bodies), and the throw's beam
stiffness k_t between neighbouring throws; an end body is joined to its end throw by its stub
(G J_j / L) in series with half a span (2 k_t).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse.linalg as spla
from numpy.typing import NDArray

from crankdyn.crankshaft.beam_elements import BeamMaterial, BeamSection
from crankdyn.crankshaft.beam_model import (
    CrankshaftBeamGeometry,
    CrankshaftBeamModel,
    ThrowDimensions,
    build_beam_model,
)
from crankdyn.crankshaft.beam_modes import (
    BeamModesResult,
    TorsionalComparison,
    compare_torsional_modes,
)
from crankdyn.results import Result, scalar
from crankdyn.torsion.equivalent import CrankThrowGeometry, carter_throw_stiffness

__all__ = [
    "LumpedChain",
    "ThrowStiffness",
    "carter_stiffness",
    "lumped_chain_comparison",
    "lumped_torsional_chain",
    "throw_stiffness",
    "wilson_stiffness",
]


def carter_stiffness(throw: ThrowDimensions, shear_modulus: float) -> float:
    """Torsional stiffness of one throw by Carter's formula (N m/rad; module docstring).

    Parameters
    ----------
    throw : ThrowDimensions
        The throw (m).
    shear_modulus : float
        G (Pa).

    Returns
    -------
    float
        k (N m/rad).

    Examples
    --------
    >>> t = ThrowDimensions(0.1, 0.05, 0.08, 0.04, 0.025, 0.12, 0.06)
    >>> f"{carter_stiffness(t, 80e9):.6g}"
    '2.23394e+06'
    """
    g = CrankThrowGeometry(
        journal_diameter=throw.journal_diameter,
        journal_length=throw.journal_length,
        pin_diameter=throw.pin_diameter,
        pin_length=throw.pin_length,
        web_thickness=throw.web_thickness,
        web_width=throw.web_width,
        shear_modulus=shear_modulus,
        journal_bore=throw.journal_bore,
        pin_bore=throw.pin_bore,
    )
    return carter_throw_stiffness(throw.crank_radius, g)


def wilson_stiffness(throw: ThrowDimensions, shear_modulus: float) -> float:
    """Torsional stiffness of one throw by Ker Wilson's formula (N m/rad; module docstring).

    Parameters
    ----------
    throw : ThrowDimensions
        The throw (m).
    shear_modulus : float
        G (Pa).

    Returns
    -------
    float
        k (N m/rad).

    Examples
    --------
    >>> t = ThrowDimensions(0.1, 0.05, 0.08, 0.04, 0.025, 0.12, 0.06)
    >>> f"{wilson_stiffness(t, 80e9):.6g}"
    '2.44416e+06'
    """
    t = throw
    journal = t.journal_diameter**4 - t.journal_bore**4
    pin = t.pin_diameter**4 - t.pin_bore**4
    web = t.crank_radius - 0.2 * (t.journal_diameter + t.pin_diameter)
    compliance = (
        (t.journal_length + 0.4 * t.journal_diameter) / journal
        + (t.pin_length + 0.4 * t.pin_diameter) / pin
        + web / (t.web_thickness * t.web_width**3)
    )
    return math.pi * shear_modulus / 32.0 / compliance


@dataclass(frozen=True)
class ThrowStiffness(Result):
    """Equivalent stiffness of one crank throw from its beam model (:func:`throw_stiffness`)."""

    title = "Crank throw stiffness (beam model)"
    torsional: float = scalar("torsional_stiffness_Nm_per_rad", "Torsional stiffness", "N·m/rad")
    axial: float = scalar("axial_stiffness_N_per_m", "Axial stiffness", "N/m")
    equivalent_length: float = scalar(
        "equivalent_length_m", "Equivalent length (journal section)", "m"
    )
    carter: float = scalar("carter_stiffness_Nm_per_rad", "Carter's formula", "N·m/rad")
    wilson: float = scalar("wilson_stiffness_Nm_per_rad", "Ker Wilson's formula", "N·m/rad")
    supported: bool = scalar("supported", "Held as in its bearings", "", summary=False)
    mesh: str = scalar("mesh", "Mesh", "", summary=False)


def _single_throw(
    throw: ThrowDimensions, material: BeamMaterial, **options: object
) -> CrankshaftBeamModel:
    geometry = CrankshaftBeamGeometry(throw, (0.0,), material)
    return build_beam_model(geometry, **options)  # type: ignore[arg-type]


def _static(model: CrankshaftBeamModel, fixed: list[int], load: int) -> float:
    """Displacement at ``load`` under a unit load there, the ``fixed`` degrees of freedom held."""
    free = np.setdiff1d(np.arange(model.size), fixed)
    k = model.stiffness[free][:, free].tocsc()
    f = np.zeros(free.size)
    where = int(np.searchsorted(free, load))
    f[where] = 1.0
    u = spla.spsolve(k, f)
    return float(u[where])


def throw_stiffness(
    throw: ThrowDimensions,
    material: BeamMaterial,
    *,
    supported: bool = True,
    elements: int = 4,
    theory: str = "timoshenko",
    web_rigid_fraction: float = 0.0,
    web_stiffness_scale: float = 1.0,
    pin_stiffness_scale: float = 1.0,
) -> ThrowStiffness:
    """Equivalent torsional and axial stiffness of one crank throw (module docstring).

    Parameters
    ----------
    throw : ThrowDimensions
        The throw (m).
    material : BeamMaterial
        E, nu (G = E / (2 (1 + nu))) and rho.
    supported : bool
        Held as its main bearings hold it (True) or as a cantilever (False).
    elements : int
        Elements per journal half, web and pin half (default 4).
    theory : {"timoshenko", "euler-bernoulli"}
        Beam theory.
    web_rigid_fraction : float
        Rigid fraction f of the webs (dimensionless; :mod:`crankdyn.crankshaft.beam_model`).
    web_stiffness_scale, pin_stiffness_scale : float
        Factors on the webs' and the pins' E and G (dimensionless).

    Returns
    -------
    ThrowStiffness
        k_t (N m/rad), k_a (N/m), l_e (m) and the empirical formulas' k_t.

    Examples
    --------
    >>> t = ThrowDimensions(0.1, 0.05, 0.08, 0.04, 0.025, 0.12, 0.06)
    >>> s = throw_stiffness(t, BeamMaterial(208e9, 0.3, 7850.0), supported=False)
    >>> round(s.torsional / s.carter, 3), round(s.equivalent_length, 4)  # l_e (m)
    (0.978, 0.3596)
    """
    model = _single_throw(
        throw,
        material,
        elements=elements,
        theory=theory,
        web_rigid_fraction=web_rigid_fraction,
        web_stiffness_scale=web_stiffness_scale,
        pin_stiffness_scale=pin_stiffness_scale,
    )
    a, b = (int(n) for n in model.journal_nodes)
    dof = model.dof
    if supported:
        fixed = [dof(a, 0), dof(a, 1), dof(a, 2), dof(a, 5), dof(b, 0), dof(b, 1)]
    else:
        fixed = [dof(a, d) for d in range(6)]
    kt = 1.0 / _static(model, fixed, dof(b, 5))
    ka = 1.0 / _static(model, fixed, dof(b, 2))
    g = material.shear_modulus
    journal = BeamSection.circular(throw.journal_diameter, throw.journal_bore, 0.0)
    return ThrowStiffness(
        torsional=kt,
        axial=ka,
        equivalent_length=g * journal.torsion_constant / kt,
        carter=carter_stiffness(throw, g),
        wilson=wilson_stiffness(throw, g),
        supported=supported,
        mesh=model.mesh_note,
    )


@dataclass(frozen=True)
class LumpedChain:
    """A lumped torsional chain made from a beam model (:func:`lumped_torsional_chain`).

    Parameters
    ----------
    names : tuple of str
        The masses, from the free end.
    inertias : numpy.ndarray
        Their inertias about the shaft axis (kg m^2).
    stiffnesses : numpy.ndarray
        The shafts between neighbours (N m/rad), one fewer.
    throw_stiffness : float
        The throw's beam stiffness k_t used between throws (N m/rad).
    """

    names: tuple[str, ...]
    inertias: NDArray[np.float64]
    stiffnesses: NDArray[np.float64]
    throw_stiffness: float


def _throw_inertias(model: CrankshaftBeamModel, first: int, last: int) -> NDArray[np.float64]:
    """Shares of r^T M r by chain position first..last (integers; module docstring): a node at
    a journal centre (position k + 1/2) half to each side, the end bodies' polar inertia to the
    end positions."""
    r = model.rigid_rotation()
    energy = r * (model.mass @ r)
    per_node = np.zeros(model.node_xyz.shape[0])
    idx = model.dof_index
    np.add.at(per_node, np.nonzero(idx >= 0)[0], energy[idx[idx >= 0]])
    # the end bodies' own inertia goes whole to their chain masses, wherever their node is
    g = model.geometry
    ends = []
    for body, node, slot in (
        (g.free_end, model.free_end_node, first),
        (g.flywheel, model.flywheel_node, last),
    ):
        if body is not None:
            per_node[node] -= body.polar_inertia
            ends.append((slot, body.polar_inertia))
    c = np.clip(model.throw_of_node, first, last)
    half = np.isclose(c - np.floor(c), 0.5)
    below = np.where(half, np.floor(c), np.rint(c)).astype(int) - first
    above = np.where(half, np.ceil(c), np.rint(c)).astype(int) - first
    out = np.zeros(last - first + 1)
    np.add.at(out, below, 0.5 * per_node)
    np.add.at(out, above, 0.5 * per_node)
    for slot, inertia in ends:
        out[slot - first] += inertia
    return out


def lumped_torsional_chain(model: CrankshaftBeamModel, *, supported: bool = True) -> LumpedChain:
    """The lumped torsional chain equivalent to a beam model (module docstring).

    Parameters
    ----------
    model : CrankshaftBeamModel
        The beam model.
    supported : bool
        Throw stiffness held as in its bearings (:func:`throw_stiffness`).

    Returns
    -------
    LumpedChain
        Names, inertias (kg m^2) and stiffnesses (N m/rad), for
        ``crankdyn.torsion.TorsionModel.chain_of``.
    """
    g = model.geometry
    t = g.throw
    kt = throw_stiffness(
        t,
        g.material,
        supported=supported,
        elements=model.elements_per_part,
        theory=model.theory,
        web_rigid_fraction=model.web_rigid_fraction,
        web_stiffness_scale=model.web_stiffness_scale,
        pin_stiffness_scale=model.pin_stiffness_scale,
    ).torsional
    n = g.throws
    first = -1 if g.free_end is not None else 0
    last = n if g.flywheel is not None else n - 1
    shares = _throw_inertias(model, first, last)
    names = [f"throw {i + 1}" for i in range(n)]
    inertias = list(shares[int(g.free_end is not None) :][:n])
    stiff = [kt] * (n - 1)
    gj = (
        g.material.shear_modulus
        * BeamSection.circular(t.journal_diameter, t.journal_bore, 0.0).torsion_constant
    )
    if g.free_end is not None:
        names.insert(0, "free end")
        inertias.insert(0, shares[0])
        stiff.insert(0, 1.0 / (g.free_end.distance / gj + 0.5 / kt))
    if g.flywheel is not None:
        names.append("flywheel")
        inertias.append(shares[-1])
        stiff.append(1.0 / (g.flywheel.distance / gj + 0.5 / kt))
    if g.damper is not None:
        names.insert(0, "damper ring")
        inertias.insert(0, g.damper.ring_inertia)
        stiff.insert(0, g.damper.stiffness)
    for k, (inertia, stiffness) in enumerate(g.shaft_line):
        names.append(f"shaft line {k + 1}")
        inertias.append(inertia)
        stiff.append(stiffness)
    return LumpedChain(tuple(names), np.array(inertias), np.array(stiff), kt)


def lumped_chain_comparison(
    model: CrankshaftBeamModel, modes: BeamModesResult, *, supported: bool = True
) -> TorsionalComparison:
    """The beam model's torsional modes against the lumped chain made from it: how well the
    lumped model holds (:func:`lumped_torsional_chain`, solved by
    :func:`crankdyn.torsion.modal.natural_modes`; paired by
    :func:`crankdyn.crankshaft.beam_modes.compare_torsional_modes`).

    Parameters
    ----------
    model : CrankshaftBeamModel
        The beam model.
    modes : BeamModesResult
        Its modes (:func:`crankdyn.crankshaft.beam_modes.beam_modes`).
    supported : bool
        Throw stiffness held as in its bearings (:func:`throw_stiffness`).

    Returns
    -------
    TorsionalComparison
        Beam and chain frequencies (rad/s, exported in Hz) and chain / beam - 1.
    """
    from crankdyn.torsion.modal import natural_modes
    from crankdyn.torsion.model import TorsionModel

    chain = lumped_torsional_chain(model, supported=supported)
    lumped = natural_modes(TorsionModel.chain_of(chain.inertias, chain.stiffnesses))
    return compare_torsional_modes(modes, lumped.natural_frequency)
