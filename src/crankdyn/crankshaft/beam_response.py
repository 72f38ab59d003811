"""Forced response of the crankshaft beam model to the crank-pin forces (analysis).

Excitation: at the pin of every throw the radial and tangential forces of its cylinder(s), each
a sum of orders q of the crankshaft angle theta, F(theta) = Re(c_q exp(i q theta)) (the
convention of :mod:`crankdyn.torsion.excitation`), radial positive toward the crank centre and
tangential positive in the direction of rotation (DESIGN.md). They act in the throw's rotating
frame, so order q at speed Omega excites at omega = q Omega (the model is in the rotating frame
without gyroscopic and centrifugal terms, :mod:`crankdyn.crankshaft.beam_model`).

Steady state (K - omega^2 M + i omega C) U = F, solved for every speed and order at once:

- ``method="modal"`` (default): the lowest modes of (K, M) (:func:`crankdyn.crankshaft.
  beam_modes.solve_lowest_modes`), enough to reach twice the highest excitation frequency;
  modal damping 2 zeta omega_r plus the dashpots projected, Phi^T C Phi (kept coupled: a
  small dense solve per frequency, batched); and the static residual of the modes left out
  (the mode-acceleration correction, R. R. Craig and A. J. Kurdila, *Fundamentals of Structural
  Dynamics*, 2nd ed., Wiley, 2006, ch. 11): G_e F - sum over kept elastic modes of
  phi_r phi_r^T F / omega_r^2, G_e the flexibility on the elastic subspace (the rigid-body
  modes phi_0 removed by inertia relief: F_e = (I - M Phi_0 Phi_0^T) F, K u = F_e with one
  degree of freedom per rigid mode held, u_e = (I - Phi_0 Phi_0^T M) u);
- ``method="direct"``: one sparse LU factorisation per frequency (the reference; the
  dashpots only, no modal damping).

Outputs, each as the amplitude of the signal synthesised from all orders over a working cycle,
max over theta of |sum_q Re(Y_q exp(i q theta))| (for a vector, its largest magnitude):

- the axial vibration u_z of the free end (and its amplitude per order);
- the torsional vibration theta_z of the free end (absolute: it includes the rigid-body
  rotation a net alternating torque gives the whole shaft, the speed fluctuation) and the twist
  free end - flywheel (the elastic part);
- the bending moment at every main bearing: the two components across the shaft of the journal's
  internal moment, the mean of the sections just either side of the bearing;
- the bending moment of every web about its tangential axis (the bending of the throw plane that
  the radial force and the axial vibration cause, the moment of IACS UR M53's nominal web
  bending stress) at its journal and pin ends, the larger of the two, and the nominal stress
  M / (b h^2 / 6);
- the web bending stress from vibration: the same moments less their quasi-static part, the
  static elastic response G_e F to the same forces at every order (for the modal method exactly
  the sum over the kept modes of phi_r phi_r^T F (1 / (omega_r^2 - omega^2 + i omega c_r) -
  1 / omega_r^2), the residual cancelling), synthesised and over b h^2 / 6: the bending that
  the throws' axial and bending vibration add to the quasi-static bending of the throws, the
  part of IACS UR M53.4's additional bending stress that comes from vibration (its 4(3): "where
  axial vibration calculation results of the complete dynamic system are available, the
  calculated figures may be used instead"; KR Rules 2025 Pt 5 Annex 5-3 4(3)).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction
from typing import TYPE_CHECKING

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import ArrayLike, NDArray

from crankdyn.constants import RPM
from crankdyn.crankshaft.beam_model import CrankshaftBeamModel
from crankdyn.crankshaft.beam_modes import solve_lowest_modes
from crankdyn.errors import InputError
from crankdyn.results import Result, array, column, scalar
from crankdyn.summary import derived

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = [
    "BeamResponseResult",
    "beam_response",
    "critical_speeds",
    "load_matrix",
    "recovery_matrices",
]

METHODS = ("modal", "direct")
RIGID_MODES = 12
"""The direct method looks for the model's rigid-body modes among this many lowest modes."""


def critical_speeds(
    natural: ArrayLike, orders: ArrayLike, low: float, high: float
) -> NDArray[np.float64]:
    """The speeds at which an order meets a natural frequency, Omega = omega_r / q, within
    [low, high]: added to a sweep's grid, they resolve the resonance peaks (the peak of a mode
    with damping ratio zeta lies at omega_r sqrt(1 - 2 zeta^2), within zeta^2 of it).

    Parameters
    ----------
    natural : array_like
        Natural frequencies omega_r (rad/s); zeros (rigid-body modes) are skipped.
    orders : array_like
        Orders q (> 0).
    low, high : float
        The speed range (rad/s).

    Returns
    -------
    numpy.ndarray
        The critical speeds (rad/s), sorted, each once.

    Examples
    --------
    >>> critical_speeds([0.0, 100.0, 300.0], [1.0, 2.0], 40.0, 160.0).tolist()
    [50.0, 100.0, 150.0]
    """
    w = np.asarray(natural, dtype=float)
    w = w[w > 0.0]
    q = np.asarray(orders, dtype=float)
    speeds = (w[:, None] / q[None, :]).ravel()
    return np.unique(speeds[(speeds >= low) & (speeds <= high)])


def load_matrix(model: CrankshaftBeamModel) -> sp.csr_matrix:
    """Unit radial and tangential forces at the pin centres.

    Parameters
    ----------
    model : CrankshaftBeamModel
        The model.

    Returns
    -------
    scipy.sparse.csr_matrix
        Shape (size, 2 throws): column 2i the force vector of a unit radial force (N, toward
        the crank centre: -e_r) at pin i, column 2i + 1 of a unit tangential force (+e_t).
    """
    rows, cols, vals = [], [], []
    for i, (node, alpha) in enumerate(zip(model.pin_nodes, model.geometry.pin_angles, strict=True)):
        er = (math.cos(alpha), math.sin(alpha))
        et = (-math.sin(alpha), math.cos(alpha))
        for d in (0, 1):
            rows += [model.dof(int(node), d)] * 2
            cols += [2 * i, 2 * i + 1]
            vals += [-er[d], et[d]]
    return sp.csr_matrix((vals, (rows, cols)), shape=(model.size, 2 * model.geometry.throws))


def _element_rows(
    model: CrankshaftBeamModel, element: int, end: int, comps: list[int]
) -> sp.csr_matrix:
    """Rows mapping global displacements to local end forces of one element (end 0 or 1,
    local components 0..5)."""
    el = model.elements
    t = np.zeros((12, 12))
    for i in range(4):
        t[3 * i : 3 * i + 3, 3 * i : 3 * i + 3] = el.frames[element]
    local = el.local_stiffness[element] @ t @ el.offsets[element]
    nodes = (int(el.node_a[element]), int(el.node_b[element]))
    dofs = [model.dof(nodes[k], d) for k in range(2) for d in range(6)]
    block = local[[6 * end + c for c in comps]]
    out = sp.lil_matrix((len(comps), model.size))
    for j, dof in enumerate(dofs):
        out[:, dof] = block[:, j : j + 1]
    return out.tocsr()


def recovery_matrices(model: CrankshaftBeamModel) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """Linear maps from displacements to the bearing and web bending moments.

    Parameters
    ----------
    model : CrankshaftBeamModel
        The model.

    Returns
    -------
    bearings : scipy.sparse.csr_matrix
        Shape (2 journals, size): the two components (about x, about y; N m) of the internal
        moment at each journal centre, the mean of the sections either side.
    webs : scipy.sparse.csr_matrix
        Shape (2 webs, size): the moment about each web's tangential axis (N m) at its journal
        end and at its pin end (webs in order: throw 1's two, throw 2's...).
    """
    el = model.elements
    bearing_rows = []
    for k, node in enumerate(model.journal_nodes):
        sides = []
        for e in np.flatnonzero(
            (el.kind == "journal") & ((el.node_a == node) | (el.node_b == node))
        ):
            end = 0 if el.node_a[e] == node else 1
            # internal moment: -(end force on the element) at its first end, + at its second
            sign = -1.0 if end == 0 else 1.0
            sides.append(sign * _element_rows(model, int(e), end, [4, 5]))
        if not sides:
            raise ValueError(f"journal {k + 1} has no journal element")
        bearing_rows.append(sum(sides[1:], sides[0]) / len(sides))
    web_rows = []
    webs = np.flatnonzero(el.kind == "web")
    for throw in range(model.geometry.throws):
        for part in (0, 1):
            own = webs[(el.throw[webs] == throw) & (el.part[webs] == part)]
            web_rows.append(-_element_rows(model, int(own[0]), 0, [4]))
            web_rows.append(_element_rows(model, int(own[-1]), 1, [4]))
    return sp.vstack(bearing_rows).tocsr(), sp.vstack(web_rows).tocsr()


@dataclass(frozen=True)
class BeamResponseResult(Result):
    """Forced response of a crankshaft beam model (:func:`beam_response`; module docstring).

    Parameters
    ----------
    section_modulus : float
        The webs' section modulus b h^2 / 6 (m^3; not exported).
    """

    title = "Crankshaft beam model: forced response"
    speed: np.ndarray = column("speed_rpm", "Speed", "rpm", RPM)
    free_end_axial: np.ndarray = column("free_end_axial_m", "Axial vibration at the free end", "m")
    free_end_torsion: np.ndarray = column(
        "free_end_torsion_rad", "Torsional vibration at the free end", "rad"
    )
    twist: np.ndarray = column("twist_rad", "Twist free end - flywheel", "rad")
    orders: np.ndarray = array("orders", "Orders", "")
    free_end_axial_orders: np.ndarray = array(
        "free_end_axial_by_order_m", "Axial vibration at the free end by order", "m"
    )
    bearing_moment: np.ndarray = array(
        "bearing_moment_Nm", "Bending moment at the main bearings", "N·m"
    )
    web_moment: np.ndarray = array("web_moment_Nm", "Bending moment of the webs", "N·m")
    web_stress: np.ndarray = array("web_stress_Pa", "Nominal bending stress of the webs", "Pa")
    web_vibration_stress: np.ndarray = array(
        "web_vibration_stress_Pa", "Web bending stress from vibration (speed x web)", "Pa"
    )
    method: str = scalar("method", "Method", "", summary=False)
    damping_ratio: float = scalar("damping_ratio", "Modal damping ratio", "", summary=False)
    modes_used: int = scalar("modes_used", "Modes used", "", summary=False)
    mesh: str = scalar("mesh", "Mesh", "", summary=False)
    notes: tuple[str, ...] = scalar("notes", "Notes", "", default=())
    section_modulus: float = field(default=math.nan, repr=False)

    FIGURES = (
        derived(
            "max_free_end_axial",
            "max_free_end_axial_m",
            "Largest axial vibration at the free end",
            "m",
            lambda r: _peak(r, r.free_end_axial, None),
            better="min",
        ),
        derived(
            "max_free_end_torsion",
            "max_free_end_torsion_rad",
            "Largest torsional vibration at the free end",
            "rad",
            lambda r: _peak(r, r.free_end_torsion, None),
            better="min",
        ),
        derived(
            "max_bearing_moment",
            "max_bearing_moment_Nm",
            "Largest bending moment at a main bearing",
            "N·m",
            lambda r: _peak(r, r.bearing_moment, "bearing"),
            better="min",
        ),
        derived(
            "max_web_stress",
            "max_web_stress_Pa",
            "Largest nominal web bending stress",
            "Pa",
            lambda r: _peak(r, r.web_stress, "web"),
            better="min",
        ),
        derived(
            "max_web_vibration_stress",
            "max_web_vibration_stress_Pa",
            "Largest web bending stress from vibration",
            "Pa",
            lambda r: _peak(r, r.web_vibration_stress, "web"),
            reduction="max over speeds and webs",
            better="min",
        ),
    )

    def plot(self, fig: Figure | None = None) -> Figure:
        """The free end's axial vibration and the webs' bending stress against speed
        (:func:`crankdyn.plots.crankshaft.plot_axial_response`).

        Parameters
        ----------
        fig : matplotlib.figure.Figure or None
            A figure to draw into; None makes a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.crankshaft import plot_axial_response

        return plot_axial_response(self, fig=fig)


def _peak(
    r: BeamResponseResult, values: NDArray[np.float64], item: str | None
) -> tuple[float, str] | None:
    """The largest value of a (speed[, item]) array, with where."""
    data = np.asarray(values, dtype=float)
    if data.size == 0 or not np.isfinite(data).any():
        return None
    flat = int(np.nanargmax(data))
    if data.ndim == 1:
        return float(data[flat]), f"at {r.speed[flat] * RPM:.6g} rpm"
    s, i = np.unravel_index(flat, data.shape)
    return float(data[s, i]), f"{item} {i + 1} at {r.speed[s] * RPM:.6g} rpm"


def _cycle(orders: NDArray[np.float64]) -> float:
    """The working cycle (rad): 2 pi times the least common denominator of the orders."""
    den = 1
    for q in orders:
        den = math.lcm(den, Fraction(float(q)).limit_denominator(12).denominator)
    return 2.0 * math.pi * den


def _synthesise(
    y: NDArray[np.complex128], orders: NDArray[np.float64], components: int
) -> NDArray[np.float64]:
    """Largest magnitude over a cycle of sum_q Re(y_q exp(i q theta)).

    y has shape (speeds, orders, outputs); consecutive groups of ``components`` outputs are one
    vector. Returns (speeds, outputs / components)."""
    cycle = _cycle(orders)
    n = max(64, int(16 * np.max(np.abs(orders)) * cycle / (2 * math.pi)))
    theta = np.linspace(0.0, cycle, n, endpoint=False)
    phase = orders[:, None] * theta[None, :]  # (Q, N)
    s, q, o = y.shape
    flat = np.ascontiguousarray(np.swapaxes(y, 1, 2)).reshape(s * o, q)
    # Re(y e^{i q theta}) = Re(y) cos - Im(y) sin: two real products, no complex batch
    signal = (flat.real @ np.cos(phase) - flat.imag @ np.sin(phase)).reshape(s, o, n)
    mag = np.sqrt(np.sum(signal.reshape(s, o // components, components, n) ** 2, axis=2))
    return mag.max(axis=-1)


def _modes_for(
    model: CrankshaftBeamModel, top: float, modes: int | None
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Enough of the lowest modes to reach 2 x the highest excitation frequency (rad/s)."""
    size = model.size
    count = min(size, modes if modes is not None else 30)
    while True:
        lam, phi = solve_lowest_modes(model.stiffness, model.mass, count)
        if modes is not None or count >= size or lam[-1] >= (2.0 * top) ** 2:
            return lam, phi
        count = min(size, 2 * count)


def _elastic_static(
    model: CrankshaftBeamModel,
    lam: NDArray[np.float64],
    phi: NDArray[np.float64],
    loads: sp.csr_matrix,
) -> NDArray[np.float64]:
    """G_e B: the static deflection of the elastic subspace under the loads, the rigid-body
    modes (lam = 0 among ``phi``) removed by inertia relief (module docstring; size x loads)."""
    rigid = lam == 0.0
    b = loads.toarray()
    p0 = phi[:, rigid]
    m = model.mass
    held: list[int] = []
    for k in range(p0.shape[1]):
        order = np.argsort(-np.abs(p0[:, k]))
        held.append(int(next(i for i in order if i not in held)))
    fe = b - (m @ p0) @ (p0.T @ b)
    free = np.setdiff1d(np.arange(model.size), held)
    u = np.zeros_like(fe)
    lu = spla.splu(model.stiffness[free][:, free].tocsc())
    u[free] = lu.solve(fe[free])
    u -= p0 @ (p0.T @ (m @ u))
    return u


def _residual(
    static: NDArray[np.float64],
    lam: NDArray[np.float64],
    phi: NDArray[np.float64],
    loads: sp.csr_matrix,
) -> NDArray[np.float64]:
    """Static residual of the modes left out, G_e B - sum phi phi^T B / lambda (size x loads)."""
    rigid = lam == 0.0
    el = phi[:, ~rigid]
    return static - el @ ((el.T @ loads.toarray()) / lam[~rigid][:, None])


def _modal(
    model: CrankshaftBeamModel,
    omega: NDArray[np.float64],
    forces: NDArray[np.complex128],
    recover: sp.csr_matrix,
    zeta: float,
    modes: int | None,
) -> tuple[NDArray[np.complex128], NDArray[np.complex128], int]:
    """Outputs (speeds, orders, outputs) by modal superposition with the residual, and their
    quasi-static part (the static elastic response to the same forces)."""
    loads = load_matrix(model)
    lam, phi = _modes_for(model, float(np.max(np.abs(omega))), modes)
    wr = np.sqrt(lam)
    out_phi = np.asarray(recover @ phi)  # (outputs, m)
    modal_load = (loads.T @ phi).T  # (m, 2n)
    p = forces @ modal_load.T
    c_modal = np.diag(2.0 * zeta * wr)
    if model.damping is not None:
        c_modal = c_modal + phi.T @ (model.damping @ phi)
    if np.count_nonzero(c_modal - np.diag(np.diag(c_modal))) == 0:
        denom = (
            lam[None, None, :] - omega[..., None] ** 2 + 1j * omega[..., None] * np.diag(c_modal)
        )
        eta = p / denom
    else:
        eta = np.empty_like(p)
        flat_w, flat_p = omega.ravel(), p.reshape(-1, lam.size)
        out = eta.reshape(-1, lam.size)
        for lo in range(0, flat_w.size, 256):  # chunks of frequencies: memory, not speed
            w = flat_w[lo : lo + 256]
            h = np.diag(lam)[None] - (w**2)[:, None, None] * np.eye(lam.size)[None]
            h = h + 1j * w[:, None, None] * c_modal[None]
            out[lo : lo + 256] = np.linalg.solve(h, flat_p[lo : lo + 256][..., None])[..., 0]
    static = _elastic_static(model, lam, phi, loads)
    residual = np.asarray(recover @ _residual(static, lam, phi, loads))  # (outputs, 2n)
    y = eta @ out_phi.T + forces @ residual.T
    return y, forces @ np.asarray(recover @ static).T, lam.size


def _direct(
    model: CrankshaftBeamModel,
    omega: NDArray[np.float64],
    forces: NDArray[np.complex128],
    recover: sp.csr_matrix,
) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
    """Outputs by one sparse LU per frequency (the reference), and their quasi-static part."""
    loads = load_matrix(model)
    k, m = model.stiffness.tocsc(), model.mass.tocsc()
    c = model.damping.tocsc() if model.damping is not None else None
    s, q = omega.shape
    y = np.empty((s, q, recover.shape[0]), dtype=complex)
    for i in range(s):
        for j in range(q):
            w = omega[i, j]
            a = (k - w * w * m).astype(complex)
            if c is not None:
                a = a + 1j * w * c
            u = spla.splu(a.tocsc()).solve(loads @ forces[i, j])
            y[i, j] = recover @ u
    lam, phi = solve_lowest_modes(model.stiffness, model.mass, min(model.size, RIGID_MODES))
    static = np.asarray(recover @ _elastic_static(model, lam, phi, loads))
    return y, forces @ static.T


def beam_response(
    model: CrankshaftBeamModel,
    speeds: ArrayLike,
    orders: ArrayLike,
    radial: ArrayLike,
    tangential: ArrayLike,
    *,
    damping_ratio: float = 0.02,
    method: str = "modal",
    modes: int | None = None,
) -> BeamResponseResult:
    """Steady-state response of a crankshaft beam model to the pin forces (module docstring).

    Parameters
    ----------
    model : CrankshaftBeamModel
        The model.
    speeds : array_like
        Crankshaft speeds Omega (rad/s), shape (S,), > 0.
    orders : array_like
        Orders q (dimensionless), shape (Q,), > 0.
    radial, tangential : array_like
        Complex amplitudes c_q of the radial and tangential pin forces (N), shape (Q, throws)
        or (S, Q, throws).
    damping_ratio : float
        Modal damping ratio zeta of every mode (dimensionless, >= 0; modal method only).
    method : {"modal", "direct"}
        Modal superposition with the residual, or a sparse solve per frequency.
    modes : int or None
        Modes to use (modal method); None: enough to reach twice the highest excitation
        frequency.

    Returns
    -------
    BeamResponseResult
        Free-end axial and torsional vibration, twist, bearing and web moments per speed.

    Raises
    ------
    crankdyn.errors.InputError
        For speeds or orders not positive, forces of another shape, an unknown method, modal
        damping with the direct method.
    """
    speed = np.atleast_1d(np.asarray(speeds, dtype=float))
    order = np.atleast_1d(np.asarray(orders, dtype=float))
    if not (np.all(np.isfinite(speed)) and np.all(speed > 0.0)):
        raise InputError("speeds must be positive", key="speeds")
    if not (np.all(np.isfinite(order)) and np.all(order > 0.0)):
        raise InputError("orders must be positive", key="orders")
    if method not in METHODS:
        raise InputError(f"expected one of {', '.join(METHODS)}", key="method", value=method)
    if damping_ratio < 0.0 or (method == "direct" and damping_ratio != 0.0):
        raise InputError(
            "expected >= 0, and 0 with the direct method (its damping is the dashpots')",
            key="damping_ratio",
            value=damping_ratio,
        )
    n = model.geometry.throws
    shape = (speed.size, order.size, n)
    try:
        z = np.broadcast_to(np.asarray(radial, dtype=complex), shape)
        t = np.broadcast_to(np.asarray(tangential, dtype=complex), shape)
    except ValueError:
        raise InputError(
            f"expected forces of shape (orders, throws) = ({order.size}, {n}) or "
            f"(speeds, orders, throws)",
            key="radial",
        ) from None
    forces = np.stack([z, t], axis=-1).reshape(speed.size, order.size, 2 * n)
    omega = speed[:, None] * order[None, :]
    bearings, webs = recovery_matrices(model)
    free, fly = model.free_end_node, model.flywheel_node
    points = sp.csr_matrix(
        (
            [1.0, 1.0, 1.0, -1.0],
            (
                [0, 1, 2, 2],
                [model.dof(free, 2), model.dof(free, 5), model.dof(free, 5), model.dof(fly, 5)],
            ),
        ),
        shape=(3, model.size),
    )
    recover = sp.vstack([points, bearings, webs]).tocsr()
    if method == "modal":
        y, y_static, used = _modal(model, omega, forces, recover, damping_ratio, modes)
    else:
        (y, y_static), used = _direct(model, omega, forces, recover), 0
    nb = bearings.shape[0]
    scalars = _synthesise(y[..., :3], order, 1)
    bearing = _synthesise(y[..., 3 : 3 + nb], order, 2)
    web_ends = _synthesise(y[..., 3 + nb :], order, 1)
    web = web_ends.reshape(speed.size, -1, 2).max(axis=-1)
    vibration_ends = _synthesise((y - y_static)[..., 3 + nb :], order, 1)
    vibration = vibration_ends.reshape(speed.size, -1, 2).max(axis=-1)
    g = model.geometry.throw
    modulus = g.web_width * g.web_thickness**2 / 6.0
    return BeamResponseResult(
        speed=speed,
        free_end_axial=scalars[:, 0],
        free_end_torsion=scalars[:, 1],
        twist=scalars[:, 2],
        orders=order,
        free_end_axial_orders=np.abs(y[..., 0]),
        bearing_moment=bearing,
        web_moment=web,
        web_stress=web / modulus,
        web_vibration_stress=vibration / modulus,
        method=method,
        damping_ratio=float(damping_ratio),
        modes_used=used,
        mesh=model.mesh_note,
        notes=("Amplitudes of the signals synthesised from all orders over a working cycle.",),
        section_modulus=modulus,
    )
