"""Case: forced response of a branched shaft line (issue 37 item 2).

The model: the built-in ``marine-propulsion`` line (six-throw engine, flywheel, highly elastic
coupling, 25:80 reduction gearbox, intermediate and propeller shafts subdivided, propeller)
with a power take-off branch at the gearbox: an 80:30 PTO pinion meshing with the wheel, a
shaft and a shaft generator (38 degrees of freedom, a tree: the wheel's degree of freedom has
three neighbours). 300..800 rpm, 5000 speeds, orders 0.5..12 in steps of 0.5 (24 orders):
120,000 excitation frequencies, a unit torque at every throw. Loss factors as viscous damping
eta k / omega_h at omega_h = 2 pi 50 rad/s for both contenders (openTorsion has no hysteretic
damping).

crankdyn: ``crankdyn.torsion.solvers.steady_state`` (the tree eliminated from the leaves inward,
batched over all frequencies: :mod:`crankdyn.torsion.tree`). openTorsion 0.3.2: the same model
as an ``Assembly`` (``TorsionModel.to_opentorsion``: disks, shafts and gear pairs) and
``Assembly.ss_response`` with the excitation in its reduced (gear-constrained) coordinates,
T^T F (made before the clock; it inverts the receptance at each frequency in a Python loop).
The limit: a bare in-place elimination of the same tree over all frequencies
(``bench/bare.py: tree_elimination``; the order and the rows' constant parts made before the
clock).

Agreement: the amplitudes of every mass (openTorsion's T q, crankdyn's actual angles) to 1e-9
of the largest at each frequency, in magnitude (openTorsion's gears turn every wheel the
opposite way, its coordinates' signs differ); the bare elimination's complex amplitudes to
1e-9; crankdyn's own residual (K - w^2 M + i w C) X = F at 25 frequencies.
"""

from __future__ import annotations

import math

import numpy as np

from bench.harness import CRANKDYN, AgreementError, Case, Contender, Deviation, Target

KEY = "branched"
TITLE = "Forced response, branched marine line with PTO"
SIZES = {"full": 5000, "tiny": 40}  # speeds from 300 to 800 rpm
ORDERS = np.arange(1, 25) * 0.5
HYSTERETIC = 2.0 * math.pi * 50.0  # rad/s
TOLERANCE = 1e-9
OPENTORSION = "openTorsion Assembly.ss_response"
BARE = "bare in-place tree elimination"


def model():
    """The marine-propulsion line with a PTO branch at the gearbox (module docstring)."""
    from crankdyn.io.catalogue import resolve_model_and_engine
    from crankdyn.torsion import Mass, Shaft, TorsionModel
    from crankdyn.torsion.elements import Gear

    line, _ = resolve_model_and_engine("marine-propulsion")
    masses = (*line.masses, Mass("pto pinion", 2.5, role="gear"), Mass("generator", 40.0))
    shafts = (*line.shafts, Shaft(("pto pinion", "generator"), 3e6, damping=80.0))
    gears = (*line.gears, Gear(("wheel", "pto pinion"), 80 / 30))
    return TorsionModel(masses, shafts, gears, name="marine line with PTO")


def problem(size: str):
    """(model, omega (speeds x orders) rad/s, forcing (dofs,) N m on the throws)."""
    m = model()
    rpm = np.linspace(300.0, 800.0, SIZES[size])
    omega = (rpm * math.pi / 30.0)[:, None] * ORDERS[None, :]
    forcing = np.zeros(m.dof_count)
    for dof in m.cylinder_dofs.values():
        forcing[dof] = 1.0
    return m, omega, forcing


def bare_inputs(system):
    """(order, parent, inertia, up, diagonal) of the tree for :func:`bench.bare.tree_elimination`:
    a breadth-first walk from the degree of freedom with the most links, reversed."""
    n = system.size
    links = system.links
    neighbours: list[list[tuple[int, int]]] = [[] for _ in range(n)]
    for e, (a, b) in enumerate(links.tolist()):
        neighbours[a].append((b, e))
        neighbours[b].append((a, e))
    root = max(range(n), key=lambda i: len(neighbours[i]))
    walk, up_of, towards = [root], {root: -1}, {root: -1}
    for i in walk:
        for j, e in neighbours[i]:
            if j not in up_of:
                up_of[j], towards[j] = e, i
                walk.append(j)
    order = walk[::-1]
    position = {dof: k for k, dof in enumerate(order)}
    parent = np.array([position[towards[i]] for i in order[:-1]])
    up = system.link_values[:, [up_of[i] for i in order[:-1]]]
    diagonal = system.ground_values.copy()
    np.add.at(diagonal.T, links[:, 0], system.link_values.T)
    np.add.at(diagonal.T, links[:, 1], system.link_values.T)
    diagonal = diagonal[:, order]
    return np.array(order), parent, system.inertia[order], up, diagonal


def _check_crankdyn(system, omega, forcing, x) -> None:
    """crankdyn's residual of the dense dynamic-stiffness equation at 25 frequencies."""
    flat_w = omega.reshape(-1)
    flat_x = x.reshape(-1, x.shape[-1])
    for j in np.linspace(0, flat_w.size - 1, 25).astype(int):
        d = system.matrix(flat_w[j], HYSTERETIC)
        residual = d @ flat_x[j] - forcing
        scale = np.max(np.abs(d)) * np.max(np.abs(flat_x[j]))
        if np.max(np.abs(residual)) > 1e-12 * scale:
            raise AgreementError(f"crankdyn: response residual {np.max(np.abs(residual)):.3g}")


def cases(size: str = "full") -> list[Case]:
    from bench.bare import tree_elimination
    from crankdyn.torsion.solvers import linear_system, steady_state

    m, omega, forcing = problem(size)
    system = linear_system(m)
    if system.tree is None:
        raise AgreementError("the branched benchmark model is not a tree")
    full = np.broadcast_to(forcing, (*omega.shape, forcing.size))
    flat = omega.reshape(-1)
    label = f"{m.dof_count} dofs, {omega.shape[0]} speeds x {ORDERS.size} orders"
    try:
        assembly = m.to_opentorsion(hysteretic_frequency=HYSTERETIC)
        transform = assembly.T(assembly.E()) if assembly.gear_elements else np.eye(m.dof_count)
        physical = np.zeros(len(m.masses))  # unit torques at the throws' masses (ratio 1)
        for i, mass in enumerate(m.masses):
            if mass.cylinders:
                physical[i] = 1.0
        reduced = transform.T @ physical
        excitation = np.broadcast_to(reduced[:, None], (reduced.size, flat.size)).astype(complex)
        ot_missing = None
    except ImportError:
        assembly, ot_missing = None, "opentorsion not installed"

    def mine():
        return steady_state(m, omega, full, hysteretic_frequency=HYSTERETIC)

    def check(outputs: dict) -> dict[str, Deviation]:
        x = np.asarray(outputs[CRANKDYN])
        _check_crankdyn(system, omega, forcing, x)
        out = {}
        if OPENTORSION in outputs:
            flat_x = x.reshape(-1, x.shape[-1])
            actual = np.abs(flat_x[:, system.mass_dof] * system.mass_ratio)  # (F, masses)
            theirs = np.abs(transform @ outputs[OPENTORSION][0]).T
            scale = np.max(theirs, axis=-1)
            dev = float(np.max(np.max(np.abs(actual - theirs), axis=-1) / scale))
            out[OPENTORSION] = Deviation(dev, TOLERANCE, "|amplitudes| of the masses, relative")
        return out

    inputs = bare_inputs(system)
    up, diagonal = _viscous_rows(inputs[3], inputs[4])

    def bare():
        return tree_elimination(inputs[1], inputs[2], up, diagonal, flat, forcing[inputs[0]])

    def check_bare(outputs: dict) -> dict[str, Deviation]:
        x = np.asarray(outputs[CRANKDYN]).reshape(-1, system.size)
        _check_crankdyn(system, omega, forcing, x)
        theirs = np.empty_like(x)
        theirs[:, inputs[0]] = outputs[BARE].T
        scale = np.max(np.abs(theirs), axis=-1)
        dev = float(np.max(np.max(np.abs(x - theirs), axis=-1) / scale))
        return {BARE: Deviation(dev, TOLERANCE, "complex amplitudes, relative to the peak")}

    return [
        Case(
            key=KEY,
            title=TITLE,
            size=label,
            contenders=(
                Contender(CRANKDYN, mine),
                Contender(
                    OPENTORSION,
                    (lambda: assembly.ss_response(excitation, flat)) if assembly else None,
                    missing=ot_missing,
                ),
            ),
            check=check,
            targets=(Target(OPENTORSION, 30.0, ">= 30x openTorsion"),),
            repeats=3,
        ),
        Case(
            key=f"{KEY}-limit",
            title="Branched forced response against its limit",
            size=label,
            contenders=(Contender(CRANKDYN, mine), Contender(BARE, bare)),
            check=check_bare,
            targets=(Target(BARE, 0.5, "within 2x of it"),),
            repeats=5,
            interleave=True,  # a ratio to the limit: both under the same load
        ),
    ]


def _viscous_rows(up, diagonal):
    """The rows (k, c, eta k) with the loss factors as viscous damping eta k / omega_h."""
    up = np.array(up, dtype=float)
    diagonal = np.array(diagonal, dtype=float)
    up[1] += up[2] / HYSTERETIC
    diagonal[1] += diagonal[2] / HYSTERETIC
    up[2] = 0.0
    diagonal[2] = 0.0
    return up, diagonal
