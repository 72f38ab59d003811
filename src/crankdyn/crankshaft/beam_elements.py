"""Three-dimensional beam elements with six degrees of freedom per node (numeric core).

Each node has the translations u_x, u_y, u_z and the rotations theta_x, theta_y, theta_z (m,
rad), in that order. An element joins two nodes along its local axis x' (unit vector e1); its
cross-section has principal axes y' (e2) and z' (e3 = e1 x e2). In local coordinates the element
uncouples into four problems:

- axial (u_x'), two-node linear element: K = E A / L [[1, -1], [-1, 1]],
  M = rho A L / 6 [[2, 1], [1, 2]];
- torsion (theta_x'), the same with G J / L and rho I_p L / 6 (J the torsion constant, I_p =
  I_y' + I_z' the polar moment of the area, which gives the section's rotary inertia);
- bending in the x'-y' plane (v, theta_z' = dv/dx) and in the x'-z' plane (w, theta_y' =
  -dw/dx), two-node Timoshenko elements with cubic interpolation consistent with the shear
  deformation. With the shear parameter Phi = 12 E I / (kappa G A L^2) (I the second moment
  about the bending axis, kappa the shear coefficient) the stiffness is::

      K = E I / ((1 + Phi) L^3) [[ 12,   6L,        -12,  6L       ],
                                 [ 6L,  (4+Phi)L^2, -6L, (2-Phi)L^2],
                                 [-12,  -6L,         12, -6L       ],
                                 [ 6L,  (2-Phi)L^2, -6L, (4+Phi)L^2]]

  (J. S. Przemieniecki, *Theory of Matrix Structural Analysis*, McGraw-Hill, 1968, ch. 5);
  the consistent mass is the translational part rho A L / (1 + Phi)^2 [...] plus the rotary
  part rho I / ((1 + Phi)^2 L) [...] of Przemieniecki (1968, ch. 11; the same matrices in
  M. I. Friswell et al., *Dynamics of Rotating Machines*, Cambridge University Press, 2010,
  ch. 5, and in the shaft element of ROSS), written out in ``_bending``. Phi = 0 gives the
  Euler-Bernoulli element, and dropping the rotary part the classical Euler-Bernoulli beam
  without rotary inertia.

Shear coefficients (G. R. Cowper, "The shear coefficient in Timoshenko's beam theory", J. Appl.
Mech. 33 (1966) 335-340, Table 1): hollow circle with m = d / D,
kappa = 6 (1 + nu) (1 + m^2)^2 / ((7 + 6 nu) (1 + m^2)^2 + (20 + 12 nu) m^2); rectangle
kappa = 10 (1 + nu) / (12 + 11 nu). Torsion constant of a b x h rectangle (b >= h):
J = b h^3 (1/3 - 0.21 (h/b) (1 - (h/b)^4 / 12)) (W. C. Young and R. G. Budynas, *Roark's
Formulas for Stress and Strain*, 7th ed., McGraw-Hill, 2002, Table 10.7 case 4).

Global matrices are K_g = T^T K T with T = diag(L, L, L, L), L the 3 x 3 matrix whose rows are
e1, e2, e3. An element end at a point offset by e from its node (a rigid link, e.g. from the
crank-pin axis to the web) takes the node's motion u + theta x e: K_node = O^T K_g O with
O = [[I, -[e]x], [0, I]] per end ([e]x the cross-product matrix; W. McGuire, R. H. Gallagher and
R. D. Ziemian, *Matrix Structural Analysis*, 2nd ed., Wiley, 2000, rigid end offsets).
Assembly is sparse (``scipy.sparse``), all elements at once.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike, NDArray

from crankdyn.crank.geometry import check_finite, check_positive
from crankdyn.errors import InputError

__all__ = [
    "DOF_NAMES",
    "BeamMaterial",
    "BeamSection",
    "assemble",
    "element_frames",
    "global_element_matrices",
    "local_element_matrices",
    "offset_matrices",
    "point_mass_matrix",
]

DOF_NAMES = ("u_x", "u_y", "u_z", "theta_x", "theta_y", "theta_z")
"""The six degrees of freedom of a node, in order (m, m, m, rad, rad, rad)."""


@dataclass(frozen=True)
class BeamMaterial:
    """An isotropic, linear elastic material.

    Parameters
    ----------
    youngs_modulus : float
        Young's modulus E (Pa), > 0.
    poisson_ratio : float
        Poisson's ratio nu (dimensionless), 0 <= nu < 0.5; the shear modulus is
        G = E / (2 (1 + nu)).
    density : float
        Density rho (kg/m^3), > 0.

    Raises
    ------
    crankdyn.errors.InputError
        A modulus or density not positive, or nu outside [0, 0.5) (names the key).

    Examples
    --------
    >>> steel = BeamMaterial(210e9, 0.3, 7850.0)
    >>> round(steel.shear_modulus / 1e9, 4)
    80.7692
    """

    youngs_modulus: float
    poisson_ratio: float
    density: float

    def __post_init__(self) -> None:
        object.__setattr__(
            self, "youngs_modulus", check_positive("youngs_modulus", self.youngs_modulus)
        )
        object.__setattr__(self, "density", check_positive("density", self.density))
        nu = check_finite("poisson_ratio", self.poisson_ratio)
        if not 0.0 <= nu < 0.5:
            raise InputError("must lie in [0, 0.5)", key="poisson_ratio", value=nu)
        object.__setattr__(self, "poisson_ratio", nu)

    @property
    def shear_modulus(self) -> float:
        """G = E / (2 (1 + nu)) (Pa)."""
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))


@dataclass(frozen=True)
class BeamSection:
    """Properties of a beam cross-section in its principal axes (SI).

    Parameters
    ----------
    area : float
        Area A (m^2).
    second_moment_y, second_moment_z : float
        Second moments of area I_y', I_z' about the local y' and z' axes (m^4).
    torsion_constant : float
        Torsion constant J (m^4): G J is the torsional rigidity.
    shear_coefficient : float
        Shear coefficient kappa (dimensionless), the same in both directions.
    """

    area: float
    second_moment_y: float
    second_moment_z: float
    torsion_constant: float
    shear_coefficient: float

    @property
    def polar_moment(self) -> float:
        """I_p = I_y' + I_z' (m^4): the section's rotary inertia per unit length and density."""
        return self.second_moment_y + self.second_moment_z

    @classmethod
    def circular(cls, diameter: float, bore: float, poisson_ratio: float) -> BeamSection:
        """A solid or hollow circle.

        A = pi (D^2 - d^2) / 4, I = pi (D^4 - d^4) / 64, J = 2 I; kappa by Cowper (1966) for the
        hollow circle (module docstring).

        Parameters
        ----------
        diameter : float
            Outer diameter D (m), > 0.
        bore : float
            Bore d (m), 0 <= d < D.
        poisson_ratio : float
            nu (dimensionless).

        Returns
        -------
        BeamSection
            The section.

        Examples
        --------
        >>> s = BeamSection.circular(0.1, 0.0, 0.3)
        >>> round(s.area * 1e4, 4), round(s.shear_coefficient, 4)  # 6 (1 + nu) / (7 + 6 nu)
        (78.5398, 0.8864)
        """
        d4, b4 = diameter**4, bore**4
        second = math.pi * (d4 - b4) / 64.0
        m2 = (bore / diameter) ** 2
        nu = poisson_ratio
        kappa = 6.0 * (1.0 + nu) * (1.0 + m2) ** 2
        kappa /= (7.0 + 6.0 * nu) * (1.0 + m2) ** 2 + (20.0 + 12.0 * nu) * m2
        area = math.pi * (diameter**2 - bore**2) / 4.0
        return cls(area, second, second, 2.0 * second, kappa)

    @classmethod
    def rectangular(cls, width: float, thickness: float, poisson_ratio: float) -> BeamSection:
        """A rectangle of width b along y' and thickness h along z'.

        A = b h, I_y' = b h^3 / 12, I_z' = h b^3 / 12, J by Roark (7th ed., Table 10.7 case 4)
        and kappa by Cowper (1966) (module docstring).

        Parameters
        ----------
        width : float
            b, along the local y' axis (m), > 0.
        thickness : float
            h, along the local z' axis (m), > 0.
        poisson_ratio : float
            nu (dimensionless).

        Returns
        -------
        BeamSection
            The section.

        Examples
        --------
        >>> s = BeamSection.rectangular(0.12, 0.03, 0.3)
        >>> round(s.torsion_constant / (0.12 * 0.03**3), 4)  # beta, b / h = 4 (Roark: 0.281)
        0.2809
        """
        long, short = max(width, thickness), min(width, thickness)
        ratio = short / long
        beta = 1.0 / 3.0 - 0.21 * ratio * (1.0 - ratio**4 / 12.0)
        kappa = 10.0 * (1.0 + poisson_ratio) / (12.0 + 11.0 * poisson_ratio)
        return cls(
            width * thickness,
            width * thickness**3 / 12.0,
            thickness * width**3 / 12.0,
            beta * long * short**3,
            kappa,
        )


def _bending(
    length: NDArray[np.float64],
    ei: NDArray[np.float64],
    phi: NDArray[np.float64],
    rho_a: NDArray[np.float64],
    rho_i: NDArray[np.float64],
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(K, M), each (n, 4, 4), of the bending element in the x'-y' plane (v1, th1, v2, th2)
    with theta = dv/dx (Przemieniecki 1968; module docstring). rho_i = 0 drops the rotary
    inertia."""
    L, p = length, phi
    L2 = L * L
    c = (ei / ((1.0 + p) * L**3))[:, None, None]
    k = np.empty((L.size, 4, 4))
    k[:, 0] = np.stack([12.0 + 0 * L, 6 * L, -12.0 + 0 * L, 6 * L], axis=1)
    k[:, 1] = np.stack([6 * L, (4 + p) * L2, -6 * L, (2 - p) * L2], axis=1)
    k[:, 2] = np.stack([-12.0 + 0 * L, -6 * L, 12.0 + 0 * L, -6 * L], axis=1)
    k[:, 3] = np.stack([6 * L, (2 - p) * L2, -6 * L, (4 + p) * L2], axis=1)
    k *= c
    # translational inertia
    a = 13 / 35 + 7 * p / 10 + p * p / 3
    b = (11 / 210 + 11 * p / 120 + p * p / 24) * L
    cc = 9 / 70 + 3 * p / 10 + p * p / 6
    d = (13 / 420 + 3 * p / 40 + p * p / 24) * L
    e = (1 / 105 + p / 60 + p * p / 120) * L2
    f = (1 / 140 + p / 60 + p * p / 120) * L2
    mt = np.empty((L.size, 4, 4))
    mt[:, 0] = np.stack([a, b, cc, -d], axis=1)
    mt[:, 1] = np.stack([b, e, d, -f], axis=1)
    mt[:, 2] = np.stack([cc, d, a, -b], axis=1)
    mt[:, 3] = np.stack([-d, -f, -b, e], axis=1)
    mt *= (rho_a * L / (1.0 + p) ** 2)[:, None, None]
    # rotary inertia
    g = 6 / 5 + 0 * L
    h = (1 / 10 - p / 2) * L
    i = (2 / 15 + p / 6 + p * p / 3) * L2
    j = (1 / 30 + p / 6 - p * p / 6) * L2
    mr = np.empty((L.size, 4, 4))
    mr[:, 0] = np.stack([g, h, -g, h], axis=1)
    mr[:, 1] = np.stack([h, i, -h, -j], axis=1)
    mr[:, 2] = np.stack([-g, -h, g, -h], axis=1)
    mr[:, 3] = np.stack([h, -j, -h, i], axis=1)
    mr *= (rho_i / ((1.0 + p) ** 2 * L))[:, None, None]
    return k, mt + mr


_AXIAL = np.array([0, 6])
_TORSION = np.array([3, 9])
_PLANE_XY = np.array([1, 5, 7, 11])  # v, theta_z'
_PLANE_XZ = np.array([2, 4, 8, 10])  # w, theta_y' = -dw/dx
_FLIP = np.array([1.0, -1.0, 1.0, -1.0])


def local_element_matrices(
    length: ArrayLike,
    material: BeamMaterial,
    section: BeamSection | list[BeamSection],
    *,
    shear: bool = True,
    rotary_inertia: bool = True,
    stiffness_scale: ArrayLike = 1.0,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Stiffness and consistent mass of beam elements in local coordinates (module docstring).

    Parameters
    ----------
    length : array_like
        Element lengths L (m), shape (n,), each > 0.
    material : BeamMaterial
        E (Pa), nu and rho (kg/m^3).
    section : BeamSection or list of BeamSection
        One section for all, or one per element.
    shear : bool
        Timoshenko shear deformation (True) or none (Phi = 0, Euler-Bernoulli).
    rotary_inertia : bool
        Include the rotary inertia of bending (True) or not (classical Euler-Bernoulli).
    stiffness_scale : array_like
        Factor on E and G per element (dimensionless; 1 for the material as it is; a large
        factor makes an element rigid in every mode of deformation).

    Returns
    -------
    K, M : numpy.ndarray
        Shape (n, 12, 12): stiffness (N/m, N, N m/rad in the blocks of the local degrees of
        freedom) and mass (kg, kg m, kg m^2).

    Examples
    --------
    Axial and torsional stiffness of a 1 m steel rod of 10 mm diameter (E A / L, G J / L):

    >>> steel = BeamMaterial(210e9, 0.3, 7850.0)
    >>> k, m = local_element_matrices([1.0], steel, BeamSection.circular(0.01, 0.0, 0.3))
    >>> round(float(k[0, 0, 0]) / 1e6, 4), round(float(k[0, 3, 3]), 3)
    (16.4934, 79.295)
    """
    L = np.atleast_1d(np.asarray(length, dtype=float))
    n = L.size
    sections = [section] * n if isinstance(section, BeamSection) else list(section)
    if len(sections) != n:
        raise ValueError("one section per element")
    A = np.array([s.area for s in sections])
    Iy = np.array([s.second_moment_y for s in sections])
    Iz = np.array([s.second_moment_z for s in sections])
    J = np.array([s.torsion_constant for s in sections])
    kap = np.array([s.shear_coefficient for s in sections])
    scale = np.broadcast_to(np.asarray(stiffness_scale, dtype=float), (n,))
    E = material.youngs_modulus * scale
    G = material.shear_modulus * scale
    rho = material.density
    K = np.zeros((n, 12, 12))
    M = np.zeros((n, 12, 12))
    bar = np.array([[1.0, -1.0], [-1.0, 1.0]])
    lump = np.array([[2.0, 1.0], [1.0, 2.0]]) / 6.0
    K[:, _AXIAL[:, None], _AXIAL] = (E * A / L)[:, None, None] * bar
    M[:, _AXIAL[:, None], _AXIAL] = (rho * A * L)[:, None, None] * lump
    K[:, _TORSION[:, None], _TORSION] = (G * J / L)[:, None, None] * bar
    M[:, _TORSION[:, None], _TORSION] = (rho * (Iy + Iz) * L)[:, None, None] * lump
    for idx, second, flip in ((_PLANE_XY, Iz, None), (_PLANE_XZ, Iy, _FLIP)):
        phi = 12.0 * E * second / (kap * G * A * L * L) if shear else np.zeros(n)
        rot = rho * second if rotary_inertia else np.zeros(n)
        kb, mb = _bending(L, E * second, phi, rho * A, rot)
        if flip is not None:
            kb = kb * flip[:, None] * flip[None, :]
            mb = mb * flip[:, None] * flip[None, :]
        K[:, idx[:, None], idx] = kb
        M[:, idx[:, None], idx] = mb
    return K, M


def element_frames(axis: ArrayLike, reference: ArrayLike) -> NDArray[np.float64]:
    """Local frames of elements: rows e1 (the axis), e2, e3 = e1 x e2.

    e2 is the reference direction made orthogonal to the axis (Gram-Schmidt).

    Parameters
    ----------
    axis : array_like
        Element axis directions, shape (n, 3) (any length, not zero).
    reference : array_like
        Directions of the local y' axis, shape (n, 3), not parallel to the axis.

    Returns
    -------
    numpy.ndarray
        Shape (n, 3, 3): frame[i] has rows e1, e2, e3 (global components, unit vectors).

    Examples
    --------
    >>> element_frames([[0, 0, 2.0]], [[1.0, 0, 0]])[0].tolist()
    [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
    """
    e1 = np.atleast_2d(np.asarray(axis, dtype=float))
    e1 = e1 / np.linalg.norm(e1, axis=1, keepdims=True)
    ref = np.atleast_2d(np.asarray(reference, dtype=float))
    e2 = ref - np.sum(ref * e1, axis=1, keepdims=True) * e1
    e2 = e2 / np.linalg.norm(e2, axis=1, keepdims=True)
    e3 = np.cross(e1, e2)
    return np.stack([e1, e2, e3], axis=1)


def _skew(e: NDArray[np.float64]) -> NDArray[np.float64]:
    """[e]x of each row of e, shape (n, 3, 3): [e]x v = e x v."""
    out = np.zeros((e.shape[0], 3, 3))
    out[:, 0, 1], out[:, 0, 2] = -e[:, 2], e[:, 1]
    out[:, 1, 0], out[:, 1, 2] = e[:, 2], -e[:, 0]
    out[:, 2, 0], out[:, 2, 1] = -e[:, 1], e[:, 0]
    return out


def offset_matrices(offset_a: ArrayLike, offset_b: ArrayLike) -> NDArray[np.float64]:
    """Rigid-link transformations O of elements whose ends are offset from their nodes.

    The end displacement is u + theta x e (module docstring).

    Parameters
    ----------
    offset_a, offset_b : array_like
        Offsets e from the first and the second node to the element's ends (m), shape (n, 3).

    Returns
    -------
    numpy.ndarray
        Shape (n, 12, 12): element-end displacements = O @ node displacements.

    Examples
    --------
    A rotation of 0.01 rad about z moves an end offset 0.1 m along x by 1 mm along y:

    >>> o = offset_matrices([[0.1, 0, 0]], [[0, 0, 0]])[0]
    >>> (o[:6, :6] @ [0, 0, 0, 0, 0, 0.01])[:3].round(6).tolist()
    [0.0, 0.001, 0.0]
    """
    out = np.zeros((np.shape(offset_a)[0], 12, 12))
    out[:, range(12), range(12)] = 1.0
    out[:, 0:3, 3:6] = -_skew(np.atleast_2d(np.asarray(offset_a, dtype=float)))
    out[:, 6:9, 9:12] = -_skew(np.atleast_2d(np.asarray(offset_b, dtype=float)))
    return out


def global_element_matrices(
    local: NDArray[np.float64],
    frames: NDArray[np.float64],
    offsets: NDArray[np.float64] | None = None,
) -> NDArray[np.float64]:
    """Element matrices in global node coordinates: O^T T^T X T O (module docstring).

    Parameters
    ----------
    local : numpy.ndarray
        Local matrices, shape (n, 12, 12) (any unit).
    frames : numpy.ndarray
        Local frames, shape (n, 3, 3) (:func:`element_frames`).
    offsets : numpy.ndarray or None
        Rigid-link transformations, shape (n, 12, 12) (:func:`offset_matrices`), or None.

    Returns
    -------
    numpy.ndarray
        Shape (n, 12, 12), in the units of ``local``.
    """
    n = local.shape[0]
    t = np.zeros((n, 12, 12))
    for i in range(4):
        t[:, 3 * i : 3 * i + 3, 3 * i : 3 * i + 3] = frames
    if offsets is not None:
        t = t @ offsets
    return np.transpose(t, (0, 2, 1)) @ local @ t


def point_mass_matrix(
    mass: ArrayLike, offset: ArrayLike, inertia: ArrayLike | None = None
) -> NDArray[np.float64]:
    """6 x 6 mass matrices of rigid bodies attached to nodes at an offset.

    The body's centre moves as u + theta x e, so M = O^T diag(m I, J_c) O =
    [[m I, -m [e]x], [m [e]x, J_c - m [e]x [e]x]] (the parallel-axis theorem).

    Parameters
    ----------
    mass : array_like
        Masses m (kg), shape (n,); or shape (n, 3), one per translation direction (a mass that
        follows the node in some directions only).
    offset : array_like
        Offsets e of the centres of mass from the nodes (m), shape (n, 3).
    inertia : array_like or None
        Inertia tensors J_c about the centres of mass (kg m^2), shape (n, 3, 3); None for point
        masses.

    Returns
    -------
    numpy.ndarray
        Shape (n, 6, 6) (kg, kg m, kg m^2).

    Examples
    --------
    A 2 kg point 0.1 m from the axis adds m r^2 = 0.02 kg m^2 about z:

    >>> round(float(point_mass_matrix([2.0], [[0.1, 0, 0]])[0, 5, 5]), 6)
    0.02
    """
    e = np.atleast_2d(np.asarray(offset, dtype=float))
    n = e.shape[0]
    m = np.asarray(mass, dtype=float)
    diag = np.broadcast_to(m[:, None] if m.ndim == 1 else m, (n, 3))
    body = np.zeros((n, 6, 6))
    body[:, [0, 1, 2], [0, 1, 2]] = diag
    if inertia is not None:
        body[:, 3:, 3:] = np.asarray(inertia, dtype=float)
    o = offset_matrices(e, np.zeros_like(e))[:, :6, :6]
    return np.transpose(o, (0, 2, 1)) @ body @ o


def assemble(size: int, dofs: NDArray[np.int_], blocks: NDArray[np.float64]) -> sp.csr_matrix:
    """Sparse sum of element blocks into a global matrix.

    Parameters
    ----------
    size : int
        Number of degrees of freedom.
    dofs : numpy.ndarray
        Global indices of each block's rows and columns, shape (n, k).
    blocks : numpy.ndarray
        The blocks, shape (n, k, k) (any unit).

    Returns
    -------
    scipy.sparse.csr_matrix
        Shape (size, size), duplicates summed.

    Examples
    --------
    >>> a = assemble(3, np.array([[0, 1], [1, 2]]), np.ones((2, 2, 2)))
    >>> a.toarray().tolist()
    [[1.0, 1.0, 0.0], [1.0, 2.0, 1.0], [0.0, 1.0, 1.0]]
    """
    k = dofs.shape[1]
    rows = np.broadcast_to(dofs[:, :, None], (dofs.shape[0], k, k)).ravel()
    cols = np.broadcast_to(dofs[:, None, :], (dofs.shape[0], k, k)).ravel()
    return sp.coo_matrix((blocks.ravel(), (rows, cols)), shape=(size, size)).tocsr()
