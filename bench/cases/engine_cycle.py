"""Case: the full working cycle of a V12 at 0.1 deg steps.

crankdyn: ``crank_train`` (piston and rod kinematics, gas and inertia forces, side, rod,
tangential and radial forces of all 12 cylinders), ``engine_torque`` (cylinder, total, gas and
inertia torques, journal and crank-pin torques, mean torque, indicated work) and
``bearing_loads`` (crank-pin loads in the crank frame, main-bearing loads), the last two reusing
the crank train (``train=``). The bare version (:func:`bare_cycle`) writes the same formulas
(seed 000 sections 1 and 2.2-2.3, as docs/theory-kinematics.md and docs/forces.md state them)
directly in numpy, once, with no objects, no validation and no copies: the floor crankdyn is
measured against.

The engine: a 60 deg V12 (bore 85 mm, stroke 79 mm, rod 140 mm; cylinders 1-6 on bank A, 7-12
on bank B, cylinders i and i + 6 on throw i; firing order 1-7-5-11-3-9-6-12-2-8-4-10, evenly
firing) at 6000 rpm with a synthetic pressure trace (crankdyn's Wiebe model, built before the
clock starts and given to both as the engine's trace).

Agreement: every array to 1e-12 of its largest magnitude (load angles compared modulo 360 deg).
"""

from __future__ import annotations

import math

import numpy as np

from bench.harness import CRANKDYN, AgreementError, Case, Contender, Deviation, Target
from crankdyn.crank.geometry import CrankGeometry
from crankdyn.crank.masses import Masses
from crankdyn.crank.pressure_model import WiebePressureModel
from crankdyn.engine.bearings import bearing_loads
from crankdyn.engine.forces import crank_train, cycle_grid, engine_masses
from crankdyn.engine.model import Cylinders, Engine
from crankdyn.engine.torque import engine_torque

KEY = "engine"
TITLE = "V12 engine cycle: kinematics, forces, torques, bearing loads"
STEP = {"full": 0.1, "tiny": 5.0}  # deg
SPEED = 6000.0 * math.pi / 30.0  # rad/s
TOLERANCE = 1e-12
BARE = "bare numpy (same formulas)"


def v12() -> Engine:
    """The benchmark's V12 (module docstring)."""
    geometry = CrankGeometry(bore=0.085, crank_radius=0.0395, rod_length=0.140)
    cylinders = Cylinders(
        count=12,
        firing_order=(1, 7, 5, 11, 3, 9, 6, 12, 2, 8, 4, 10),
        layout="V",
        bank_angle=math.radians(60.0),
    )
    masses = Masses(piston_group=0.50, rod=0.55, rod_cg_from_big_end=0.040, crank_unbalance=0.40)
    trace = WiebePressureModel().trace(geometry, cylinders.cycle, source="Wiebe model")
    return Engine("benchmark V12", geometry, cylinders, masses, pressure=trace)


def crankdyn_cycle(engine: Engine, step: float):
    """The crankdyn user's calls for one full cycle (angles every ``step`` rad)."""
    train = crank_train(engine, SPEED, cycle_grid(engine, step))
    torque = engine_torque(engine, SPEED, step=step, train=train)
    loads = bearing_loads(engine, SPEED, step=step, train=train)
    return train, torque, loads


def bare_inputs(engine: Engine, step: float) -> dict:
    """Plain numbers and arrays for :func:`bare_cycle` (taken before the clock starts)."""
    g, cyl = engine.geometry, engine.cylinders
    masses = engine_masses(engine)
    return {
        "r": g.crank_radius,
        "l": g.rod_length,
        "e": g.offset,
        "area": g.piston_area,
        "p_cc": engine.crankcase_pressure,
        "cycle": engine.cycle_angle,
        "count": max(round(engine.cycle_angle / step), 4),
        "psi": np.asarray(cyl.throw_angles),
        "firing": np.asarray(cyl.firing_angles),
        "alpha": cyl.bank_axis_angles,
        "throw": np.asarray(cyl.throws) - 1,
        "throws": cyl.throw_count,
        "m_j": np.array([m.reciprocating for m in masses]),
        "m_r": np.array([m.rotating for m in masses]),
        "m_cb": np.array([m.rod_big_end or 0.0 for m in masses]),
        "trace_angle": np.asarray(engine.pressure.crank_angle),
        "trace_p": np.asarray(engine.pressure.pressure),
        "w": SPEED,
    }


def _slider(phi, r, l, e):
    lam, k = r / l, e / r
    s, c = np.sin(phi), np.cos(phi)
    sb = lam * (s - k)
    cb = np.sqrt(1.0 - sb * sb)
    return lam, s, c, sb, cb, s * cb + c * sb, c * cb - s * sb


def _tangential(d: dict) -> np.ndarray:
    """Tangential forces alone on d's grid (for the mean torque on a finer grid)."""
    r, l, e, w, cycle = d["r"], d["l"], d["e"], d["w"], d["cycle"]
    theta = np.linspace(0.0, cycle, d["count"] + 1)
    phi = theta[None, :] - d["psi"][:, None]
    phase = np.mod(theta[None, :] - d["firing"][:, None], cycle)
    gas = (np.interp(phase, d["trace_angle"], d["trace_p"], period=cycle) - d["p_cc"]) * d["area"]
    lam, _s, c, _sb, cb, spb, cpb = _slider(phi, r, l, e)
    a = r * w * w * (cpb / cb + lam * c**2 / cb**3)
    return (gas - d["m_j"][:, None] * a) / cb * spb


def bare_cycle(d: dict) -> dict:
    """The whole cycle in plain numpy (seed 000 sections 1 and 2.2-2.3; crankdyn's docs)."""
    r, l, e, w, cycle = d["r"], d["l"], d["e"], d["w"], d["cycle"]
    theta = np.linspace(0.0, cycle, d["count"] + 1)
    phi = theta[None, :] - d["psi"][:, None]
    phase = np.mod(theta[None, :] - d["firing"][:, None], cycle)
    p = np.interp(phase, d["trace_angle"], d["trace_p"], period=cycle)
    gas = (p - d["p_cc"]) * d["area"]
    # kinematics (seed 000 section 1; seed 002 eqs. 3, 8, 13)
    lam, s, c, sb, cb, spb, cpb = _slider(phi, r, l, e)
    x = math.sqrt((l + r) ** 2 - e * e) - (r * c + l * cb)
    v = r * w * spb / cb
    a = r * w * w * (cpb / cb + lam * c**2 / cb**3)
    beta = np.arcsin(sb)
    w_rod = w * lam * c / cb
    e_rod = w * w * (-lam * s / cb + lam * lam * c**2 * sb / cb**3)
    # forces (seed 000 section 2.2)
    inertia = -d["m_j"][:, None] * a
    piston = gas + inertia
    rod = piston / cb
    side = rod * sb
    tangential = rod * spb
    radial = rod * cpb
    lever = (1.0 / cb) * spb
    # torques (seed 000 sections 2.2-2.3)
    torque = tangential * r
    total = torque.sum(axis=0)
    throw = d["throw"]
    throw_torque = np.zeros((d["throws"], theta.size))
    np.add.at(throw_torque, throw, torque)
    journal = np.cumsum(throw_torque, axis=0)
    pin_torque = journal - 0.5 * throw_torque
    if cycle / d["count"] <= math.radians(0.1) * (1 + 1e-9):
        mean = float(np.mean(tangential[:, :-1].sum(axis=0))) * r
    else:  # the mean on a 0.1 deg grid when the output grid is coarser (crankdyn.engine.torque)
        fine_count = round(cycle / math.radians(0.1))
        fine_d = {**d, "count": fine_count}
        mean = float(np.mean(_tangential(fine_d)[:, :-1].sum(axis=0))) * r
    # indicated work: trapezoidal p dV on the trace points refined to 0.05 deg
    fine = np.linspace(0.0, cycle, round(cycle / math.radians(0.05)) + 1)[:-1]
    t_w = np.union1d(d["trace_angle"], fine)
    p_w = np.interp(t_w, d["trace_angle"], d["trace_p"], period=cycle)
    x_w = math.sqrt((l + r) ** 2 - e * e) - (r * np.cos(t_w) + l * _slider(t_w, r, l, e)[4])
    dx_w = np.diff(np.append(x_w, x_w[0]))
    work = float(d["area"] * np.sum(0.5 * (p_w + np.roll(p_w, -1)) * dx_w))
    # crank-pin loads (crank frame) and main-bearing loads (engine frame)
    t_pin = np.zeros((d["throws"], theta.size))
    z_pin = np.zeros_like(t_pin)
    np.add.at(t_pin, throw, tangential)
    np.add.at(z_pin, throw, radial - (d["m_cb"] * w * w * r)[:, None])
    alpha = d["alpha"][:, None]
    fx = side * np.cos(alpha) - piston * np.sin(alpha)
    fy = -side * np.sin(alpha) - piston * np.cos(alpha)
    centrifugal = d["m_r"][:, None] * r * w * w
    chi = alpha + phi
    fx = fx + centrifugal * np.sin(chi)
    fy = fy + centrifugal * np.cos(chi)
    hx = np.zeros((d["throws"], theta.size))
    hy = np.zeros_like(hx)
    np.add.at(hx, throw, fx)
    np.add.at(hy, throw, fy)
    zero = np.zeros((1, theta.size))
    bx = 0.5 * (np.vstack([hx, zero]) + np.vstack([zero, hx]))
    by = 0.5 * (np.vstack([hy, zero]) + np.vstack([zero, hy]))
    pin = np.hypot(t_pin, z_pin)
    bearing = np.hypot(bx, by)
    return {
        "displacement": x,
        "velocity": v,
        "acceleration": a,
        "rod_angle": beta,
        "rod_angular_velocity": w_rod,
        "rod_angular_acceleration": e_rod,
        "pressure": p,
        "gas": gas,
        "inertia": inertia,
        "side": side,
        "rod": rod,
        "tangential": tangential,
        "radial": radial,
        "cylinder_torque": torque,
        "total_torque": total,
        "gas_torque": (gas * lever * r).sum(axis=0),
        "inertia_torque": (inertia * lever * r).sum(axis=0),
        "journal_torque": journal,
        "pin_torque": pin_torque,
        "mean_torque": mean,
        "indicated_work": work,
        "pin_tangential": t_pin,
        "pin_radial": z_pin,
        "pin_load": pin,
        "pin_load_angle": np.mod(np.arctan2(t_pin, -z_pin), 2.0 * math.pi),
        "bearing_horizontal": bx,
        "bearing_vertical": by,
        "bearing_load": bearing,
        "bearing_load_angle": np.mod(np.arctan2(bx, by), 2.0 * math.pi),
    }


def crankdyn_arrays(output) -> dict:
    """crankdyn's results under the bare version's names (the curves; the summary figures, the
    largest and mean loads of the whole cycle found on crankdyn's own grid and refined between
    its points, are not the benchmark grid's and are not compared)."""
    train, torque, loads = output
    m = train.motion
    return {
        "displacement": m.displacement,
        "velocity": m.velocity,
        "acceleration": m.acceleration,
        "rod_angle": m.rod_angle,
        "rod_angular_velocity": m.rod_angular_velocity,
        "rod_angular_acceleration": m.rod_angular_acceleration,
        "pressure": train.pressure,
        "gas": train.gas,
        "inertia": train.inertia,
        "side": train.side,
        "rod": train.rod,
        "tangential": train.tangential,
        "radial": train.radial,
        "cylinder_torque": torque.cylinder_torque,
        "total_torque": torque.total_torque,
        "gas_torque": torque.gas_torque,
        "inertia_torque": torque.inertia_torque,
        "journal_torque": torque.journal_torque,
        "pin_torque": torque.pin_torque,
        "mean_torque": torque.mean_torque,
        "indicated_work": torque.indicated_work,
        "pin_tangential": loads.pin_tangential,
        "pin_radial": loads.pin_radial,
        "pin_load": loads.pin_load,
        "pin_load_angle": loads.pin_load_angle,
        "bearing_horizontal": loads.bearing_horizontal,
        "bearing_vertical": loads.bearing_vertical,
        "bearing_load": loads.bearing_load,
        "bearing_load_angle": loads.bearing_load_angle,
    }


def compare(mine: dict, bare: dict) -> float:
    """Largest deviation over all quantities, each relative to its largest magnitude (angles
    modulo a turn)."""
    worst = 0.0
    for name, ref in bare.items():
        got = np.asarray(mine[name], dtype=float)
        ref = np.asarray(ref, dtype=float)
        if got.shape != ref.shape:
            raise AgreementError(f"{name}: shape {got.shape}, bare {ref.shape}")
        diff = got - ref
        if name.endswith("_angle") and name != "rod_angle":
            diff = np.remainder(diff + math.pi, 2.0 * math.pi) - math.pi
        scale = float(np.max(np.abs(ref))) or 1.0
        worst = max(worst, float(np.max(np.abs(diff))) / scale)
    return worst


def _check_identities(output) -> None:
    """Independent checks of crankdyn's result: the mean inertia torque over a cycle is zero
    (it does no work at constant speed), and the mean torque times the cycle angle equals the
    cylinders' indicated work (M_i Theta = Z W_i)."""
    train, torque, _loads = output
    total_inertia = np.mean(torque.inertia_torque[:-1])
    if abs(total_inertia) > 1e-9 * np.max(np.abs(torque.inertia_torque)):
        raise AgreementError(f"crankdyn: mean inertia torque {total_inertia:.3g} N m is not 0")
    engine = train.engine
    work = engine.cylinders.count * torque.indicated_work
    mean_work = torque.mean_torque * engine.cycle_angle
    if abs(mean_work - work) > 2e-3 * abs(work):  # the torque grid's rectangle rule vs p dV
        raise AgreementError(f"crankdyn: mean torque x cycle {mean_work:.6g} J != Z W_i {work:.6g}")


def cases(size: str = "full") -> list[Case]:
    engine = v12()
    step = math.radians(STEP[size])
    inputs = bare_inputs(engine, step)

    def check(outputs: dict) -> dict[str, Deviation]:
        _check_identities(outputs[CRANKDYN])
        mine = crankdyn_arrays(outputs[CRANKDYN])
        return {
            name: Deviation(compare(mine, value), TOLERANCE, "relative to each array's peak")
            for name, value in outputs.items()
            if name != CRANKDYN
        }

    return [
        Case(
            key=KEY,
            title=TITLE,
            size=f"{STEP[size]:g} deg, {inputs['count'] + 1} angles x 12 cylinders",
            contenders=(
                Contender(CRANKDYN, lambda: crankdyn_cycle(engine, step)),
                Contender(BARE, lambda: bare_cycle(inputs)),
            ),
            check=check,
            targets=(Target(BARE, 0.5, "within 2x of the bare version"),),
            repeats=15,
            interleave=True,  # a ratio of two tens of milliseconds: both under the same load
        )
    ]
