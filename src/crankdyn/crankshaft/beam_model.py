"""A beam model of a crankshaft: journals, webs and pins as 3-D beams (domain and builder).

The crankshaft is modelled as a space frame along its centre lines, the classic reduction of the
crank throw to beams (X. Lei, G. Zhang, J. Chen, X. Song and G. Dong, "A simplified model for
vibration analysis of diesel engine crankshaft system", J. Shanghai Jiaotong Univ. (Sci.) E-11
(2006) 99-103: the crankshaft body as a spatial rigid frame of Timoshenko beam elements, the main
bearings as linear springs; H. Okamura, A. Shinno, T. Yamanaka, A. Suzuki and K. Sogabe, "Simple
modeling and analysis for crankshaft three-dimensional vibrations, Part 1", ASME J. Vib. Acoust.
117 (1995) 70-79, the throw as jointed beams):

- the **journals** and **pins** are beams on their axes; a journal runs from its centre (where
  the main bearing acts) to the mid-plane of the web, a pin from one web's mid-plane to the
  other's, so each carries half the web thickness at its ends;
- each **web** is a beam in the throw plane, in the web's mid-plane, from the journal axis to the
  pin axis (length the crank radius R, rectangular section of width b and thickness h). With a
  rigid fraction f > 0 the parts inside f D_j / 2 of the journal axis and f D_p / 2 of the pin
  axis are rigid links (rigid end offsets, :mod:`crankdyn.crankshaft.beam_elements`) and the
  flexible web is R - f (D_j + D_p) / 2 long, the reduced web length of the empirical formulas
  (f = 0.4 in Ker Wilson's, :mod:`crankdyn.crankshaft.beam_stiffness`); the default f = 0 is the
  centre-line frame of Lei et al. (2006). A pin-journal overlap (D_j + D_p) / 2 - R > 0 leaves
  the frame unchanged (it is reported, :attr:`ThrowDimensions.overlap`);
- **counterweights** are rigid masses on the webs' journal-side nodes, their centre of mass at
  the given radius opposite the pin;
- the **rod and piston**: the rotating mass m_r at the pin centre in all three directions, and
  half the reciprocating mass m_j / 2 in the two directions across the shaft. The piston moves
  along the cylinder axis, which turns relative to the throw once a revolution: the mean of
  m_j (e . d)^2 over a revolution is m_j / 2 for every transverse direction d (to first order in
  the rod ratio), the m_j / 2 of the classical equivalent torsional system (seed 000 section 2.1;
  W. Ker Wilson, *Practical Solution of Torsional Vibration Problems*, vol. 1, ch. 3;
  :mod:`crankdyn.torsion.equivalent`), so the torsional inertia of a throw is the lumped model's
  (m_r + m_j / 2) R^2. The piston does not follow the pin along the shaft axis;
- **main bearings** are springs to ground at the journal centres: radial (both transverse
  directions), tilting (both rotations across the shaft) and, at the thrust bearing, axial;
- the **damper or pulley** and the **flywheel** are rigid bodies (mass, polar and diametral
  inertia) at the ends of stub shafts of the journal's section; the **shaft line** beyond the
  flywheel is a chain of torsional inertias and stiffnesses (degrees of freedom theta_z only);
  a viscous torsional damper is a ring inertia coupled to the free end by a spring and a dashpot.

Axes: z along the shaft axis from the free end to the flywheel, x and y across; rotation about
+z is the direction of rotation (clockwise seen from the free end, DESIGN.md). The model stands at
one crank angle; pin i points along (cos alpha_i, sin alpha_i, 0) (for an in-line engine at
crankshaft angle 0, alpha_i = -psi_i with psi_i the throw angle of cylinder i). The model is in
the rotating frame without gyroscopic and centrifugal terms, with isotropic bearings.

Mesh: every journal half, web, pin half and stub is divided into ``elements`` equal beam
elements (default 2); :func:`build_beam_model` states the count in the model
(:attr:`CrankshaftBeamModel.mesh_note`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike, NDArray

from crankdyn.crank.geometry import check_finite, check_positive
from crankdyn.crankshaft.beam_elements import (
    BeamMaterial,
    BeamSection,
    assemble,
    element_frames,
    global_element_matrices,
    local_element_matrices,
    offset_matrices,
    point_mass_matrix,
)
from crankdyn.crankshaft.beam_inputs import THEORIES
from crankdyn.errors import InputError

__all__ = [
    "THEORIES",
    "CrankshaftBeamGeometry",
    "CrankshaftBeamModel",
    "ElementTable",
    "EndMass",
    "MainBearings",
    "ThrowDimensions",
    "ThrowMasses",
    "TorsionalDamper",
    "build_beam_model",
]


def _nonnegative(name: str, value: object) -> float:
    v = check_finite(name, value)
    if v < 0.0:
        raise InputError("must not be negative", key=name, value=v)
    return v


@dataclass(frozen=True)
class ThrowDimensions:
    """Dimensions of one crank throw (m).

    Parameters
    ----------
    journal_diameter, journal_length : float
        Main journal diameter D_j and length l_j (m), > 0.
    pin_diameter, pin_length : float
        Crank pin diameter D_p and length l_p (m), > 0.
    web_thickness, web_width : float
        Web thickness h (along the shaft) and width b (across the throw) (m), > 0.
    crank_radius : float
        Crank radius R, journal axis to pin axis (m), > 0.
    journal_bore, pin_bore : float
        Bores d_j, d_p (m), 0 <= d < D.

    Raises
    ------
    crankdyn.errors.InputError
        A dimension not positive, a bore outside [0, D) (names the key).

    Examples
    --------
    >>> t = ThrowDimensions(0.1, 0.05, 0.08, 0.04, 0.025, 0.12, 0.06)
    >>> round(t.span, 4), round(t.overlap, 4)
    (0.14, 0.03)
    """

    journal_diameter: float
    journal_length: float
    pin_diameter: float
    pin_length: float
    web_thickness: float
    web_width: float
    crank_radius: float
    journal_bore: float = 0.0
    pin_bore: float = 0.0

    def __post_init__(self) -> None:
        for name in (
            "journal_diameter",
            "journal_length",
            "pin_diameter",
            "pin_length",
            "web_thickness",
            "web_width",
            "crank_radius",
        ):
            object.__setattr__(self, name, check_positive(name, getattr(self, name)))
        for bore, outer in (("journal_bore", "journal_diameter"), ("pin_bore", "pin_diameter")):
            value = _nonnegative(bore, getattr(self, bore))
            if value >= getattr(self, outer):
                raise InputError(
                    f"the bore must be smaller than the {outer.replace('_', ' ')}",
                    key=bore,
                    value=value,
                )
            object.__setattr__(self, bore, value)

    @property
    def span(self) -> float:
        """Distance between neighbouring main journal centres, l_j + 2 h + l_p (m)."""
        return self.journal_length + 2.0 * self.web_thickness + self.pin_length

    @property
    def overlap(self) -> float:
        """Pin-journal overlap (D_j + D_p) / 2 - R (m); positive when they overlap."""
        return 0.5 * (self.journal_diameter + self.pin_diameter) - self.crank_radius


@dataclass(frozen=True)
class ThrowMasses:
    """Masses carried by one throw.

    Parameters
    ----------
    rotating_mass : float
        Rotating mass of the rod(s) at the pin centre m_r (kg), >= 0 (both rods of a V-engine
        throw together).
    reciprocating_mass : float
        Reciprocating mass m_j (kg), >= 0 (module docstring: m_j / 2 across the shaft).
    counterweight_mass : float
        Counterweight mass of the throw (kg), >= 0, split equally between its two webs.
    counterweight_radius : float
        Radius of the counterweights' centre of mass from the shaft axis, opposite the pin (m),
        >= 0.
    """

    rotating_mass: float = 0.0
    reciprocating_mass: float = 0.0
    counterweight_mass: float = 0.0
    counterweight_radius: float = 0.0

    def __post_init__(self) -> None:
        for name in (
            "rotating_mass",
            "reciprocating_mass",
            "counterweight_mass",
            "counterweight_radius",
        ):
            object.__setattr__(self, name, _nonnegative(name, getattr(self, name)))


@dataclass(frozen=True)
class MainBearings:
    """Main bearings as springs at every journal centre.

    Parameters
    ----------
    radial_stiffness : float
        Radial stiffness, in both directions across the shaft (N/m), >= 0.
    tilting_stiffness : float
        Tilting stiffness about both axes across the shaft (N m/rad), >= 0.
    axial_stiffness : float
        Axial stiffness of the thrust bearing (N/m), >= 0.
    thrust_journal : int or None
        The journal with the thrust bearing, 1-based from the free end; None for none.
    """

    radial_stiffness: float
    tilting_stiffness: float = 0.0
    axial_stiffness: float = 0.0
    thrust_journal: int | None = None

    def __post_init__(self) -> None:
        for name in ("radial_stiffness", "tilting_stiffness", "axial_stiffness"):
            object.__setattr__(self, name, _nonnegative(name, getattr(self, name)))
        if self.thrust_journal is not None and self.thrust_journal < 1:
            raise InputError(
                "journals are numbered from 1", key="thrust_journal", value=self.thrust_journal
            )


@dataclass(frozen=True)
class EndMass:
    """A rigid body at one end of the crankshaft (damper hub or pulley, flywheel).

    Parameters
    ----------
    mass : float
        Mass (kg), >= 0.
    polar_inertia : float
        Inertia about the shaft axis (kg m^2), >= 0.
    diametral_inertia : float
        Inertia about an axis across the shaft through its centre (kg m^2), >= 0.
    distance : float
        Length of the stub shaft (the journal's section) from the end journal's centre (m),
        >= 0; 0 attaches the body at the journal centre.
    """

    mass: float
    polar_inertia: float
    diametral_inertia: float = 0.0
    distance: float = 0.0

    def __post_init__(self) -> None:
        for name in ("mass", "polar_inertia", "diametral_inertia", "distance"):
            object.__setattr__(self, name, _nonnegative(name, getattr(self, name)))


@dataclass(frozen=True)
class TorsionalDamper:
    """A viscous torsional damper: a ring coupled to the free end by a spring and a dashpot.

    Parameters
    ----------
    ring_inertia : float
        Inertia of the ring (kg m^2), > 0.
    stiffness : float
        Torsional stiffness between hub and ring (N m/rad), >= 0.
    damping : float
        Torsional damping between hub and ring (N m s/rad), >= 0.
    """

    ring_inertia: float
    stiffness: float
    damping: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "ring_inertia", check_positive("ring_inertia", self.ring_inertia))
        for name in ("stiffness", "damping"):
            object.__setattr__(self, name, _nonnegative(name, getattr(self, name)))


@dataclass(frozen=True)
class CrankshaftBeamGeometry:
    """A crankshaft for the beam model (SI; module docstring).

    Parameters
    ----------
    throw : ThrowDimensions
        The dimensions of every throw (m).
    pin_angles : tuple of float
        Angular position alpha_i of each pin about +z (rad), one per throw from the free end.
    material : BeamMaterial
        The crankshaft material.
    bearings : MainBearings or None
        Main bearings at every journal (n_throws + 1 of them), or None (free).
    masses : ThrowMasses or tuple of ThrowMasses
        The same for every throw, or one per throw.
    free_end : EndMass or None
        Damper hub or pulley at the free end.
    flywheel : EndMass or None
        The flywheel.
    shaft_line : tuple of (float, float)
        (inertia kg m^2, stiffness N m/rad) of each further torsional mass beyond the flywheel,
        the stiffness being that of the shaft that joins it to the previous one.
    damper : TorsionalDamper or None
        A viscous torsional damper at the free end.
    axial_damping : float
        Axial dashpot to ground at the free end (N s/m), >= 0 (an axial vibration damper).

    Raises
    ------
    crankdyn.errors.InputError
        No throw, a count of masses other than the throws', a shaft-line inertia or stiffness
        not positive, a thrust journal beyond the last.
    """

    throw: ThrowDimensions
    pin_angles: tuple[float, ...]
    material: BeamMaterial
    bearings: MainBearings | None = None
    masses: ThrowMasses | tuple[ThrowMasses, ...] = field(default_factory=ThrowMasses)
    free_end: EndMass | None = None
    flywheel: EndMass | None = None
    shaft_line: tuple[tuple[float, float], ...] = ()
    damper: TorsionalDamper | None = None
    axial_damping: float = 0.0

    def __post_init__(self) -> None:
        angles = tuple(check_finite("pin_angles", a) for a in np.atleast_1d(self.pin_angles))
        if not angles:
            raise InputError("expected at least one throw", key="pin_angles")
        object.__setattr__(self, "pin_angles", angles)
        masses = self.masses
        if isinstance(masses, ThrowMasses):
            masses = (masses,) * len(angles)
        masses = tuple(masses)
        if len(masses) != len(angles):
            raise InputError(
                f"expected one entry per throw ({len(angles)})", key="masses", value=len(masses)
            )
        object.__setattr__(self, "masses", masses)
        line = tuple(
            (check_positive("inertia", j), check_positive("stiffness", k))
            for j, k in self.shaft_line
        )
        object.__setattr__(self, "shaft_line", line)
        object.__setattr__(self, "axial_damping", _nonnegative("axial_damping", self.axial_damping))
        b = self.bearings
        if b is not None and b.thrust_journal is not None and b.thrust_journal > len(angles) + 1:
            raise InputError(
                f"the crankshaft has {len(angles) + 1} journals",
                key="thrust_journal",
                value=b.thrust_journal,
            )

    @property
    def throws(self) -> int:
        """Number of throws."""
        return len(self.pin_angles)

    @property
    def throw_masses(self) -> tuple[ThrowMasses, ...]:
        """The masses of each throw."""
        return self.masses  # type: ignore[return-value]  # normalised in __post_init__


@dataclass(frozen=True, eq=False)
class ElementTable:
    """The beam elements of a model (arrays over elements).

    Parameters
    ----------
    node_a, node_b : numpy.ndarray
        The elements' nodes (int, shape (n,)).
    kind : numpy.ndarray
        "journal", "pin", "web" or "stub" (str, shape (n,)).
    throw : numpy.ndarray
        The throw (0-based) of each journal half, web and pin element; -1 for stubs (int).
    part : numpy.ndarray
        Which web of its throw (0 the free-end side, 1 the flywheel side) for webs; the journal
        (0-based) for journal halves; -1 otherwise (int).
    frames : numpy.ndarray
        Local frames, shape (n, 3, 3) (rows e1, e2, e3).
    offsets : numpy.ndarray
        Rigid-link transformations, shape (n, 12, 12).
    local_stiffness : numpy.ndarray
        Local stiffness matrices, shape (n, 12, 12).
    section_modulus_y : numpy.ndarray
        Section modulus for bending about the local y' axis (m^3), shape (n,): pi D^3 (1 -
        (d/D)^4) / 32 for journals, pins and stubs, b h^2 / 6 for webs.
    """

    node_a: NDArray[np.int_]
    node_b: NDArray[np.int_]
    kind: NDArray[np.str_]
    throw: NDArray[np.int_]
    part: NDArray[np.int_]
    frames: NDArray[np.float64]
    offsets: NDArray[np.float64]
    local_stiffness: NDArray[np.float64]
    section_modulus_y: NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class CrankshaftBeamModel:
    """The assembled beam model of a crankshaft (:func:`build_beam_model`).

    Parameters
    ----------
    geometry : CrankshaftBeamGeometry
        What it was built from.
    stiffness, mass : scipy.sparse.csr_matrix
        K and M over the active degrees of freedom (N/m, N, N m/rad; kg, kg m, kg m^2).
    damping : scipy.sparse.csr_matrix or None
        The discrete dashpots' damping matrix (N s/m ...), or None without any.
    node_xyz : numpy.ndarray
        Node positions (m), shape (nodes, 3).
    dof_index : numpy.ndarray
        Active index of each node's six degrees of freedom, -1 where inactive, shape (nodes, 6).
    elements : ElementTable
        The beam elements.
    journal_nodes, pin_nodes : numpy.ndarray
        Nodes at the journal centres (throws + 1) and the pin centres (throws).
    web_axis_nodes : numpy.ndarray
        The nodes on the shaft axis at the mid-planes of each throw's two webs, shape
        (throws, 2).
    throw_of_node : numpy.ndarray
        Float position of each node in throw units: the throw whose span holds it (0-based),
        with a journal centre at k - 0.5 for journal k; the stubs and ends below -0.5 or above
        throws - 0.5 (for splitting the inertia between throws).
    free_end_node, flywheel_node : int
        The nodes of the end bodies (the end journal centres when the stubs have no length).
    extra_nodes : tuple of int
        The damper ring's and the shaft line's nodes (theta_z only), in order.
    elements_per_part : int
        Elements per journal half, web, pin half and stub.
    theory : str
        "timoshenko" or "euler-bernoulli".
    web_rigid_fraction : float
        The webs' rigid fraction f (module docstring).
    web_stiffness_scale, pin_stiffness_scale : float
        Factors on the webs' and the pins' E and G (1 for the material).
    """

    geometry: CrankshaftBeamGeometry
    stiffness: sp.csr_matrix
    mass: sp.csr_matrix
    damping: sp.csr_matrix | None
    node_xyz: NDArray[np.float64]
    dof_index: NDArray[np.int_]
    elements: ElementTable
    journal_nodes: NDArray[np.int_]
    pin_nodes: NDArray[np.int_]
    web_axis_nodes: NDArray[np.int_]
    throw_of_node: NDArray[np.float64]
    free_end_node: int
    flywheel_node: int
    extra_nodes: tuple[int, ...]
    elements_per_part: int
    theory: str
    web_rigid_fraction: float
    web_stiffness_scale: float
    pin_stiffness_scale: float

    @property
    def size(self) -> int:
        """Number of active degrees of freedom."""
        return int(self.stiffness.shape[0])

    @property
    def mesh_note(self) -> str:
        """The mesh and beam theory in words."""
        return (
            f"{len(self.elements.node_a)} {self.theory} beam elements, {self.elements_per_part} "
            f"per journal half, web, pin half and stub; {self.size} degrees of freedom"
        )

    def dof(self, node: int, name: int) -> int:
        """The active index of one degree of freedom.

        Parameters
        ----------
        node : int
            The node.
        name : int
            0..5 for u_x, u_y, u_z, theta_x, theta_y, theta_z.

        Returns
        -------
        int
            Its index in K and M.

        Raises
        ------
        ValueError
            If it is not active.
        """
        index = int(self.dof_index[node, name])
        if index < 0:
            raise ValueError(f"degree of freedom {name} of node {node} is not active")
        return index

    def rigid_rotation(self) -> NDArray[np.float64]:
        """The rigid rotation of the whole model by 1 rad about +z, as a displacement vector:
        theta_z = 1 and u = e_z x r at every node (m, rad).

        Returns
        -------
        numpy.ndarray
            Shape (size,).
        """
        per_node = np.zeros((self.node_xyz.shape[0], 6))
        per_node[:, 0] = -self.node_xyz[:, 1]
        per_node[:, 1] = self.node_xyz[:, 0]
        per_node[:, 5] = 1.0
        out = np.zeros(self.size)
        active = self.dof_index >= 0
        out[self.dof_index[active]] = per_node[active]
        return out


class _Builder:
    """Nodes and elements accumulated while building (internal)."""

    def __init__(self, material: BeamMaterial) -> None:
        self.material = material
        self.xyz: list[NDArray[np.float64]] = []
        self.where: list[float] = []
        self.el: dict[str, list[Any]] = {
            k: []
            for k in (
                "a",
                "b",
                "kind",
                "throw",
                "part",
                "section",
                "ref",
                "oa",
                "ob",
                "length",
                "axis",
                "modulus",
            )
        }

    def node(self, xyz: ArrayLike, where: float) -> int:
        self.xyz.append(np.asarray(xyz, dtype=float))
        self.where.append(where)
        return len(self.xyz) - 1

    def line(
        self,
        a: int,
        b: int,
        n: int,
        section: BeamSection,
        modulus: float,
        *,
        kind: str,
        throw: int,
        part: int,
        ref: ArrayLike,
        offsets: tuple[NDArray[np.float64], NDArray[np.float64]] | None = None,
    ) -> None:
        """n elements from node a to node b (ends at the nodes, or offset by rigid links)."""
        oa, ob = offsets if offsets is not None else (np.zeros(3), np.zeros(3))
        pa, pb = self.xyz[a] + oa, self.xyz[b] + ob
        wa, wb = self.where[a], self.where[b]
        nodes = [a]
        for k in range(1, n):
            t = k / n
            nodes.append(self.node(pa + t * (pb - pa), wa + t * (wb - wa)))
        nodes.append(b)
        for k in range(n):
            self.el["a"].append(nodes[k])
            self.el["b"].append(nodes[k + 1])
            self.el["oa"].append(oa if k == 0 else np.zeros(3))
            self.el["ob"].append(ob if k == n - 1 else np.zeros(3))
            self.el["length"].append(float(np.linalg.norm(pb - pa)) / n)
            self.el["axis"].append(pb - pa)
            self.el["kind"].append(kind)
            self.el["throw"].append(throw)
            self.el["part"].append(part)
            self.el["section"].append(section)
            self.el["ref"].append(np.asarray(ref, dtype=float))
            self.el["modulus"].append(modulus)


def _sections(
    throw: ThrowDimensions, nu: float
) -> tuple[BeamSection, BeamSection, BeamSection, tuple[float, float, float]]:
    """Journal, pin and web sections and their section moduli (m^3)."""
    j = BeamSection.circular(throw.journal_diameter, throw.journal_bore, nu)
    p = BeamSection.circular(throw.pin_diameter, throw.pin_bore, nu)
    w = BeamSection.rectangular(throw.web_width, throw.web_thickness, nu)
    wj = 2.0 * j.second_moment_y / throw.journal_diameter
    wp = 2.0 * p.second_moment_y / throw.pin_diameter
    ww = throw.web_width * throw.web_thickness**2 / 6.0
    return j, p, w, (wj, wp, ww)


def _frame(
    g: CrankshaftBeamGeometry, n: int, fraction: float
) -> tuple[_Builder, NDArray[np.int_], NDArray[np.int_], list[tuple[int, int, float]]]:
    """Nodes and elements of journals, webs and pins; the counterweight nodes (each throw's
    two web nodes on the axis, in order)."""
    t = g.throw
    b = _Builder(g.material)
    js, ps, ws, (wj, wp, ww) = _sections(t, g.material.poisson_ratio)
    across = (1.0, 0.0, 0.0)
    journals = [b.node((0.0, 0.0, 0.0), -0.5)]
    pins: list[int] = []
    cw: list[tuple[int, int, float]] = []  # (node, throw, angle of the pin)
    if fraction * 0.5 * (t.journal_diameter + t.pin_diameter) >= t.crank_radius:
        raise InputError(
            "the rigid parts of the web leave no flexible length (f (D_j + D_p) / 2 >= R)",
            key="web_rigid_fraction",
            value=fraction,
        )
    for i, alpha in enumerate(g.pin_angles):
        z0 = i * t.span
        er = np.array([math.cos(alpha), math.sin(alpha), 0.0])
        et = np.array([-math.sin(alpha), math.cos(alpha), 0.0])
        zw = (
            z0 + 0.5 * t.journal_length + 0.5 * t.web_thickness,
            z0 + 0.5 * t.journal_length + 1.5 * t.web_thickness + t.pin_length,
        )
        rim = t.crank_radius * er
        axis_nodes = [b.node((0.0, 0.0, z), i - 0.25 + 0.5 * k) for k, z in enumerate(zw)]
        pin_ends = [
            b.node(rim + np.array([0.0, 0.0, z]), i - 0.25 + 0.5 * k) for k, z in enumerate(zw)
        ]
        centre = b.node(rim + np.array([0.0, 0.0, 0.5 * (zw[0] + zw[1])]), float(i))
        pins.append(centre)
        b.line(journals[-1], axis_nodes[0], n, js, wj, kind="journal", throw=i, part=i, ref=across)
        offsets = (fraction * 0.5 * t.journal_diameter * er, -fraction * 0.5 * t.pin_diameter * er)
        for k in range(2):
            b.line(
                axis_nodes[k],
                pin_ends[k],
                n,
                ws,
                ww,
                kind="web",
                throw=i,
                part=k,
                ref=et,
                offsets=offsets,
            )
            cw.append((axis_nodes[k], i, alpha))
        b.line(pin_ends[0], centre, n, ps, wp, kind="pin", throw=i, part=-1, ref=across)
        b.line(centre, pin_ends[1], n, ps, wp, kind="pin", throw=i, part=-1, ref=across)
        journals.append(b.node((0.0, 0.0, z0 + t.span), i + 0.5))
        b.line(
            axis_nodes[1], journals[-1], n, js, wj, kind="journal", throw=i, part=i + 1, ref=across
        )
    return b, np.array(journals), np.array(pins), cw


def build_beam_model(
    geometry: CrankshaftBeamGeometry,
    *,
    elements: int = 2,
    theory: str = "timoshenko",
    web_rigid_fraction: float = 0.0,
    web_stiffness_scale: float = 1.0,
    pin_stiffness_scale: float = 1.0,
) -> CrankshaftBeamModel:
    """Build and assemble the beam model of a crankshaft (module docstring).

    Parameters
    ----------
    geometry : CrankshaftBeamGeometry
        The crankshaft (SI).
    elements : int
        Elements per journal half, web, pin half and stub (>= 1; default 2).
    theory : {"timoshenko", "euler-bernoulli"}
        Beam theory of every element.
    web_rigid_fraction : float
        f: the rigid parts of each web, f D_j / 2 and f D_p / 2 from the journal and pin axes
        (dimensionless, 0 <= f; default 0, the centre-line frame).
    web_stiffness_scale : float
        Factor on the webs' E and G (dimensionless, > 0; default 1). A large factor makes the
        webs rigid (the lumped-chain comparison).
    pin_stiffness_scale : float
        Factor on the pins' E and G (dimensionless, > 0; default 1).

    Returns
    -------
    CrankshaftBeamModel
        K, M (and the dashpots' C) over the active degrees of freedom, nodes and elements.

    Raises
    ------
    crankdyn.errors.InputError
        For elements below 1, an unknown theory, a negative or too large rigid fraction, a
        stiffness scale not positive.

    Examples
    --------
    A two-throw crankshaft in rigid-ish bearings:

    >>> from crankdyn.crankshaft.beam_elements import BeamMaterial
    >>> g = CrankshaftBeamGeometry(
    ...     ThrowDimensions(0.1, 0.05, 0.08, 0.04, 0.025, 0.12, 0.06), (0.0, math.pi),
    ...     BeamMaterial(210e9, 0.3, 7850.0),
    ...     MainBearings(1e9, thrust_journal=1, axial_stiffness=1e9))
    >>> m = build_beam_model(g)
    >>> m.size, len(m.journal_nodes)
    (150, 3)
    """
    if int(elements) != elements or elements < 1:
        raise InputError("expected a whole number of at least 1", key="elements", value=elements)
    if theory not in THEORIES:
        raise InputError(f"expected one of {', '.join(THEORIES)}", key="theory", value=theory)
    fraction = _nonnegative("web_rigid_fraction", web_rigid_fraction)
    scale = (
        check_positive("web_stiffness_scale", web_stiffness_scale),
        check_positive("pin_stiffness_scale", pin_stiffness_scale),
    )
    g = geometry
    b, journals, pins, cw = _frame(g, int(elements), fraction)
    t = g.throw
    js, _, _, (wj, _, _) = _sections(t, g.material.poisson_ratio)
    ends = []
    for body, journal, sign, where in (
        (g.free_end, journals[0], -1.0, -1.0),
        (g.flywheel, journals[-1], 1.0, g.throws),
    ):
        node = int(journal)
        if body is not None and body.distance > 0.0:
            node = b.node(b.xyz[journal] + (0.0, 0.0, sign * body.distance), where)
            a_, b_ = (node, int(journal)) if sign < 0 else (int(journal), node)
            b.line(
                a_, b_, int(elements), js, wj, kind="stub", throw=-1, part=-1, ref=(1.0, 0.0, 0.0)
            )
        ends.append(node)
    beam_nodes = len(b.xyz)
    extra: list[int] = []
    z_end = b.xyz[ends[1]][2]
    if g.damper is not None:
        extra.append(b.node(b.xyz[ends[0]] - (0.0, 0.0, 0.1 * t.span), -1.5))
    for k in range(len(g.shaft_line)):
        extra.append(b.node((0.0, 0.0, z_end + (k + 1) * t.span), g.throws + 1.0 + k))
    return _assemble(
        g, b, journals, pins, cw, ends, extra, beam_nodes, int(elements), theory, fraction, scale
    )


def _assemble(
    g: CrankshaftBeamGeometry,
    b: _Builder,
    journals: NDArray[np.int_],
    pins: NDArray[np.int_],
    cw: list[tuple[int, int, float]],
    ends: list[int],
    extra: list[int],
    beam_nodes: int,
    elements: int,
    theory: str,
    fraction: float,
    scale: tuple[float, float],
) -> CrankshaftBeamModel:
    """K, M and C of the accumulated model, restricted to the active degrees of freedom."""
    el = b.el
    nodes = len(b.xyz)
    timo = theory == "timoshenko"
    kind = np.array(el["kind"])
    k_loc, m_loc = local_element_matrices(
        np.array(el["length"]),
        g.material,
        el["section"],
        shear=timo,
        rotary_inertia=timo,
        stiffness_scale=np.where(kind == "web", scale[0], np.where(kind == "pin", scale[1], 1.0)),
    )
    frames = element_frames(np.array(el["axis"]), np.array(el["ref"]))
    offsets = offset_matrices(np.array(el["oa"]), np.array(el["ob"]))
    a, bb = np.array(el["a"]), np.array(el["b"])
    dofs = np.concatenate([6 * a[:, None] + np.arange(6), 6 * bb[:, None] + np.arange(6)], axis=1)
    size = 6 * nodes
    K = assemble(size, dofs, global_element_matrices(k_loc, frames, offsets))
    M = assemble(size, dofs, global_element_matrices(m_loc, frames, offsets))
    M = M + _attached_masses(g, pins, cw, ends, size, b)
    K = K + _bearings(g, journals, size)
    K, M, C = _torsional_extras(g, ends, extra, size, K, M)
    active = np.zeros((nodes, 6), dtype=bool)
    active[:beam_nodes] = True
    active[extra, 5] = True
    dof_index = np.full((nodes, 6), -1)
    dof_index[active] = np.arange(int(active.sum()))
    keep = np.flatnonzero(active.ravel())
    restrict = lambda x: x[keep][:, keep].tocsr()  # noqa: E731
    table = ElementTable(
        a,
        bb,
        kind,
        np.array(el["throw"]),
        np.array(el["part"]),
        frames,
        offsets,
        k_loc,
        np.array(el["modulus"]),
    )
    return CrankshaftBeamModel(
        geometry=g,
        stiffness=restrict(K),
        mass=restrict(M),
        damping=None if C is None else restrict(C),
        node_xyz=np.array(b.xyz),
        dof_index=dof_index,
        elements=table,
        journal_nodes=journals,
        pin_nodes=pins,
        web_axis_nodes=np.array([node for node, _, _ in cw]).reshape(-1, 2),
        throw_of_node=np.array(b.where),
        free_end_node=ends[0],
        flywheel_node=ends[1],
        extra_nodes=tuple(extra),
        elements_per_part=elements,
        theory=theory,
        web_rigid_fraction=fraction,
        web_stiffness_scale=scale[0],
        pin_stiffness_scale=scale[1],
    )


def _attached_masses(
    g: CrankshaftBeamGeometry,
    pins: NDArray[np.int_],
    cw: list[tuple[int, int, float]],
    ends: list[int],
    size: int,
    b: _Builder,
) -> sp.csr_matrix:
    """Rod, piston, counterweight and end-body mass matrices (module docstring)."""
    nodes: list[int] = []
    mass: list[NDArray[np.float64]] = []
    offset: list[NDArray[np.float64]] = []
    inertia: list[NDArray[np.float64]] = []
    for pin, m in zip(pins, g.throw_masses, strict=True):
        across = m.rotating_mass + 0.5 * m.reciprocating_mass
        nodes.append(int(pin))
        mass.append(np.array([across, across, m.rotating_mass]))
        offset.append(np.zeros(3))
        inertia.append(np.zeros((3, 3)))
    for node, throw, alpha in cw:
        m = g.throw_masses[throw]
        nodes.append(node)
        mass.append(np.full(3, 0.5 * m.counterweight_mass))
        offset.append(-m.counterweight_radius * np.array([math.cos(alpha), math.sin(alpha), 0.0]))
        inertia.append(np.zeros((3, 3)))
    for body, node in ((g.free_end, ends[0]), (g.flywheel, ends[1])):
        if body is None:
            continue
        nodes.append(node)
        mass.append(np.full(3, body.mass))
        offset.append(np.zeros(3))
        inertia.append(
            np.diag([body.diametral_inertia, body.diametral_inertia, body.polar_inertia])
        )
    blocks = point_mass_matrix(np.array(mass), np.array(offset), np.array(inertia))
    dofs = 6 * np.array(nodes)[:, None] + np.arange(6)
    return assemble(size, dofs, blocks)


def _bearings(g: CrankshaftBeamGeometry, journals: NDArray[np.int_], size: int) -> sp.csr_matrix:
    """Main bearing springs to ground at the journal centres."""
    diag = np.zeros(size)
    brg = g.bearings
    if brg is not None:
        base = 6 * journals
        diag[base + 0] += brg.radial_stiffness
        diag[base + 1] += brg.radial_stiffness
        diag[base + 3] += brg.tilting_stiffness
        diag[base + 4] += brg.tilting_stiffness
        if brg.thrust_journal is not None:
            diag[base[brg.thrust_journal - 1] + 2] += brg.axial_stiffness
    return sp.diags(diag).tocsr()


def _torsional_extras(
    g: CrankshaftBeamGeometry,
    ends: list[int],
    extra: list[int],
    size: int,
    K: sp.csr_matrix,
    M: sp.csr_matrix,
) -> tuple[sp.csr_matrix, sp.csr_matrix, sp.csr_matrix | None]:
    """Damper ring and shaft line (theta_z springs and inertias), and the dashpots."""
    pairs: list[tuple[int, int, float, float]] = []  # (node, node, k, c)
    inertias: list[tuple[int, float]] = []
    queue = list(extra)
    if g.damper is not None:
        ring = queue.pop(0)
        pairs.append((ends[0], ring, g.damper.stiffness, g.damper.damping))
        inertias.append((ring, g.damper.ring_inertia))
    previous = ends[1]
    for (inertia, stiffness), node in zip(g.shaft_line, queue, strict=True):
        pairs.append((previous, node, stiffness, 0.0))
        inertias.append((node, inertia))
        previous = node
    unit = np.array([[1.0, -1.0], [-1.0, 1.0]])
    c_blocks = None
    if pairs:
        dofs = np.array([[6 * p + 5, 6 * q + 5] for p, q, _, _ in pairs])
        K = K + assemble(size, dofs, np.array([k * unit for _, _, k, _ in pairs]))
        if any(c > 0.0 for *_, c in pairs):
            c_blocks = assemble(size, dofs, np.array([c * unit for *_, c in pairs]))
    if inertias:
        idx = np.array([6 * n + 5 for n, _ in inertias])
        M = (
            M
            + sp.coo_matrix(
                (np.array([j for _, j in inertias]), (idx, idx)), shape=(size, size)
            ).tocsr()
        )
    if g.axial_damping > 0.0:
        ax = sp.coo_matrix(
            ([g.axial_damping], ([6 * ends[0] + 2], [6 * ends[0] + 2])), shape=(size, size)
        ).tocsr()
        c_blocks = ax if c_blocks is None else c_blocks + ax
    return K, M, c_blocks
