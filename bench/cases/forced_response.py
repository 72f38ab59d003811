"""Case: forced response of the seed 003 V6 model over a speed sweep.

The seed 003 V6 engine model (nine masses from the damper ring to the flywheel, Yu Xuehua 2008,
Table 2; crankdyn's example ``seed003-v6``: absolute damping at the six throws, the damper's
rubber as a damped shaft), 500..6000 rpm every 1 rpm (5501 speeds), orders 0.5..12 in steps of
0.5 (24 orders): 132,024 excitation frequencies omega = q Omega, with a unit torque (1 N m, all
in phase) at every throw.

crankdyn: ``crankdyn.torsion.solvers.steady_state`` (the complex amplitudes of every mass at
every frequency: the dynamic stiffness D(omega) = K - omega^2 M + i omega C of the chain solved
for all frequencies at once by a batched tridiagonal elimination). openTorsion 0.3.2: the same
chain as ``Disk`` and ``Shaft`` elements with the same damping, ``Assembly.ss_response`` fed
the same frequencies and excitation (it inverts the 9 x 9 receptance at each frequency in a
Python loop). Both start from a built model; crankdyn's time includes assembling its linear
system.

Agreement: the complex amplitudes to 1e-9 of the largest amplitude at each frequency.
"""

from __future__ import annotations

import math

import numpy as np

from bench.harness import CRANKDYN, AgreementError, Case, Contender, Deviation, Target

KEY = "response"
TITLE = "Forced response, seed 003 V6 (9 masses)"
SIZES = {"full": (500.0, 6000.0, 1.0), "tiny": (500.0, 6000.0, 250.0)}  # rpm: start, stop, step
ORDERS = np.arange(1, 25) * 0.5
TOLERANCE = 1e-9
OPENTORSION = "openTorsion Assembly.ss_response"
MODEL = "seed003-v6"


def _steady_state():
    try:
        from crankdyn.torsion.solvers import steady_state
    except ImportError:
        return None
    return steady_state


def problem(size: str):
    """(model, omega (speeds x orders, rad/s), forcing (dofs,) N m)."""
    from crankdyn.torsion.model import TorsionModel

    model = TorsionModel.example(MODEL)
    start, stop, step = SIZES[size]
    rpm = np.arange(start, stop + step / 2, step)
    omega = (rpm * math.pi / 30.0)[:, None] * ORDERS[None, :]
    forcing = np.zeros(model.dof_count)
    for dof in model.cylinder_dofs.values():
        forcing[dof] = 1.0
    return model, omega, forcing


def opentorsion_assembly(model):
    """The model as openTorsion elements (a chain in dof order, no gears)."""
    import opentorsion as ot

    chain = model.chain
    n = chain.size
    disks = [
        ot.Disk(i, float(chain.inertia[i]), c=float(chain.ground_damping[i])) for i in range(n)
    ]
    shafts = [
        ot.Shaft(i, i + 1, k=float(chain.stiffness[i]), c=float(chain.damping[i]))
        for i in range(n - 1)
    ]
    if np.any(chain.ground_stiffness) or np.any(chain.hysteretic):
        raise ValueError("the benchmark model has no grounded shafts and no loss factors")
    return ot.Assembly(shafts, disk_elements=disks)


def _check(outputs: dict) -> dict[str, Deviation]:
    mine = np.asarray(outputs[CRANKDYN])
    if not np.all(np.isfinite(mine)):
        raise AgreementError("crankdyn: the response holds values that are not finite")
    out = {}
    for name, value in outputs.items():
        if name == CRANKDYN:
            continue
        theirs = np.asarray(value[0]).T.reshape(mine.shape)  # (dofs, freqs) -> (.., dofs)
        scale = np.max(np.abs(theirs), axis=-1)
        dev = float(np.max(np.max(np.abs(mine - theirs), axis=-1) / scale))
        out[name] = Deviation(dev, TOLERANCE, "complex amplitudes, relative to the peak")
    return out


def _check_crankdyn(model, omega, forcing, x) -> None:
    """Independent check of crankdyn's amplitudes at a few frequencies: the residual of the
    dense dynamic-stiffness equation (K - w^2 M + i w C) X = F (a long chain's by the product
    with its three diagonals, from the model's chain arrays: no dense N x N matrix)."""
    flat_w = omega.reshape(-1)
    flat_x = x.reshape(-1, x.shape[-1])
    long = model.dof_count > 1000
    if not long:
        k, m, c = model.stiffness_matrix(), model.mass_matrix(), model.damping_matrix()
    for j in np.linspace(0, flat_w.size - 1, 25).astype(int):
        w = flat_w[j]
        if long:
            residual = _chain_product(model.chain, w, flat_x[j]) - forcing
        else:
            residual = (k - w * w * m + 1j * w * c) @ flat_x[j] - forcing
        if np.max(np.abs(residual)) > 1e-8 * np.max(np.abs(forcing)):
            raise AgreementError(f"crankdyn: response residual {np.max(np.abs(residual)):.3g}")


def _chain_product(chain, w: float, x: np.ndarray) -> np.ndarray:
    """D(w) x for a free chain with absolute and shaft damping (its arrays: inertia, stiffness,
    damping, ground_damping): each shaft's torque (k + i w c)(x_a - x_b) on both its ends."""
    if np.any(chain.ground_stiffness) or np.any(chain.hysteretic):
        raise ValueError("the benchmark's long chains have no grounded shafts or loss factors")
    out = (-w * w * chain.inertia + 1j * w * chain.ground_damping) * x
    torque = (chain.stiffness + 1j * w * chain.damping) * (x[:-1] - x[1:])
    out[:-1] += torque
    out[1:] -= torque
    return out


def cases(size: str = "full") -> list[Case]:
    steady_state = _steady_state()
    model, omega, forcing = problem(size)
    n_speeds = omega.shape[0]
    label = f"{n_speeds} speeds x {ORDERS.size} orders"
    if steady_state is None:
        missing = "crankdyn.torsion.solvers not in this checkout (issue 6)"
        return [Case(KEY, TITLE, label, (Contender(CRANKDYN, None, missing=missing),), repeats=0)]
    try:
        assembly = opentorsion_assembly(model)
        ot_missing = None
    except ImportError:
        assembly, ot_missing = None, "opentorsion not installed"
    flat = omega.reshape(-1)
    excitation = np.broadcast_to(forcing[:, None], (forcing.size, flat.size)).astype(complex)
    full = np.broadcast_to(forcing, (*omega.shape, forcing.size))

    def crankdyn_run():
        return steady_state(model, omega, full)

    def check(outputs: dict) -> dict[str, Deviation]:
        _check_crankdyn(model, omega, forcing, np.asarray(outputs[CRANKDYN]))
        return _check(outputs)

    return [
        Case(
            key=KEY,
            title=TITLE,
            size=label,
            contenders=(
                Contender(CRANKDYN, crankdyn_run),
                Contender(
                    OPENTORSION,
                    (lambda: assembly.ss_response(excitation, flat)) if assembly else None,
                    missing=ot_missing,
                ),
            ),
            check=check,
            targets=(Target(OPENTORSION, 30.0, ">= 30x openTorsion"),),
            repeats=5,
        ),
        *limit_cases(size),
    ]


# ---- against the limit: a bare in-place Thomas elimination (bench/bare.py) ---------------------
BARE = "bare in-place Thomas elimination"
LIMIT_SIZES = {
    "full": ((MODEL, 20000, 48), ("chain-200", 5501, 24), ("chain-10000", 101, 12)),
    "tiny": ((MODEL, 40, 6), ("chain-200", 11, 3), ("chain-2000", 3, 2)),
}
LIMIT_RATIO = 1.5  # crankdyn within 1.5x of the limit


def limit_problem(which: str, speeds: int, orders: int):
    """(model, omega (speeds x orders) rad/s, forcing (dofs,) N m): the V6 model, or a free chain
    ``chain-N`` of N masses with absolute and shaft damping (seeded with N), 500..6000 rpm,
    orders 0.5 apart from 0.5 (or 0.25 apart from 0.25 for 48 orders)."""
    from crankdyn.torsion.elements import Mass, Shaft
    from crankdyn.torsion.model import TorsionModel

    if which == MODEL:
        model = TorsionModel.example(MODEL)
    else:
        n = int(which.split("-")[1])
        rng = np.random.default_rng(n)
        inertia, absolute = rng.uniform(0.05, 2.0, n), rng.uniform(0.0, 20.0, n)
        stiffness, relative = rng.uniform(2e5, 5e6, n - 1), rng.uniform(0.0, 5.0, n - 1)
        masses = tuple(
            Mass(f"m{i}", float(inertia[i]), damping=float(absolute[i])) for i in range(n)
        )
        shafts = tuple(
            Shaft((f"m{i}", f"m{i + 1}"), float(stiffness[i]), damping=float(relative[i]))
            for i in range(n - 1)
        )
        model = TorsionModel(masses, shafts, name=which)
    rpm = np.linspace(500.0, 6000.0, speeds)
    step = 0.25 if orders > 24 else 0.5
    omega = (rpm * math.pi / 30.0)[:, None] * (np.arange(1, orders + 1) * step)[None, :]
    forcing = np.zeros(model.dof_count)
    forcing[:: max(1, model.dof_count // 6)] = 1.0
    return model, omega, forcing


def limit_cases(size: str = "full") -> list[Case]:
    from bench.bare import thomas

    steady_state = _steady_state()
    out = []
    for which, speeds, orders in LIMIT_SIZES[size]:
        model, omega, forcing = limit_problem(which, speeds, orders)
        chain = model.chain
        full = np.broadcast_to(forcing, (*omega.shape, forcing.size))
        flat = omega.reshape(-1)

        def mine(model=model, omega=omega, full=full):
            return steady_state(model, omega, full)

        def bare(chain=chain, flat=flat, forcing=forcing):
            return thomas(
                chain.inertia, chain.stiffness, chain.damping, chain.ground_damping, flat, forcing
            )

        def check(outputs: dict, omega=omega, forcing=forcing, model=model) -> dict:
            x = np.asarray(outputs[CRANKDYN])
            _check_crankdyn(model, omega, forcing, x)
            theirs = outputs[BARE].T.reshape(x.shape)
            scale = np.max(np.abs(theirs), axis=-1)
            dev = float(np.max(np.max(np.abs(x - theirs), axis=-1) / scale))
            return {BARE: Deviation(dev, TOLERANCE, "complex amplitudes, relative to the peak")}

        out.append(
            Case(
                key=f"{KEY}-limit",
                title="Forced response against its limit",
                size=f"{model.dof_count} masses x {speeds} speeds x {orders} orders",
                contenders=(Contender(CRANKDYN, mine), Contender(BARE, bare)),
                check=check,
                targets=(Target(BARE, 1.0 / LIMIT_RATIO, f"within {LIMIT_RATIO:g}x of it"),),
                repeats=5,
                interleave=True,  # a ratio to the limit: both under the same load
            )
        )
    return out
