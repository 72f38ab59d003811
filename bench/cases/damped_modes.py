"""Case: damped (complex) modes of a damped free chain of N masses (issue 33).

crankdyn: ``crankdyn.torsion.damped.damped_modes`` on a built model (every mode by the Rayleigh
functional iteration on the chain's tridiagonal pencil from its undamped mode, O(N) a step,
with the checks, the labels, the overdamped pairs and the normalised complex mode shapes)
against ``scipy.linalg.eig`` of the dense 2N x 2N state-space matrix [[0, I], [-M^-1 K,
-M^-1 C]] (the linearisation that crankdyn solved before issue 33 and openTorsion's
``modal_analysis`` solves; assembled before the clock starts, eigenvalues and eigenvectors, no
labelling: the least a dense solver does).

The chain: the chain case's inertias and stiffnesses (``bench.cases.chain_modes.chain_values``),
an absolute damper of 0..20 N m s/rad at every mass and a relative one of 0..50 N m s/rad on
every shaft (seeded): lightly damped except the lowest modes, the first of them overdamped at
N = 1000 (zeta up to 2.5).

Agreement: each of crankdyn's eigenvalues (and each overdamped mode's second real eigenvalue,
omega_n^2 / lambda) is one of the dense solution's within 1e3 eps kappa_r |lambda_r|, kappa_r its
condition number (Tisseur 2000; tests/torsion/test_damped_structured.py); crankdyn's own
independent check: every eigenpair's backward error in the quadratic problem, computed here from
the dense matrices, at most 1e-13.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg

from bench.cases.chain_modes import chain_values
from bench.harness import CRANKDYN, AgreementError, Case, Contender, Deviation, Target
from crankdyn.torsion.damped import damped_modes
from crankdyn.torsion.model import Mass, Shaft, TorsionModel
from crankdyn.torsion.quadratic import ChainPencil, condition_numbers

KEY = "damped"
TITLE = "Damped free chain: damped modes"
SIZES = {"full": (100, 500, 1000), "tiny": (12, 40)}
DENSE = "scipy eig (dense 2N state space)"
_EPS = float(np.finfo(float).eps)


def damped_chain(n: int, seed: int = 2026) -> TorsionModel:
    """The benchmark's damped free chain of ``n`` masses (module docstring)."""
    inertia, stiffness = chain_values(n, seed)
    rng = np.random.default_rng(seed + 7 * n)
    absolute, relative = rng.uniform(0.0, 20.0, n), rng.uniform(0.0, 50.0, n - 1)
    names = [str(i + 1) for i in range(n)]
    masses = tuple(Mass(a, j, damping=c) for a, j, c in zip(names, inertia, absolute, strict=True))
    shafts = tuple(
        Shaft((names[i], names[i + 1]), stiffness[i], damping=relative[i]) for i in range(n - 1)
    )
    return TorsionModel(masses=masses, shafts=shafts, name=f"damped chain {n}")


def state_space(model: TorsionModel) -> np.ndarray:
    """[[0, I], [-M^-1 K, -M^-1 C]] of ``model`` (dense)."""
    n = model.dof_count
    m = model.dof_inertia
    a = np.zeros((2 * n, 2 * n))
    a[:n, n:] = np.eye(n)
    a[n:, :n] = -model.stiffness_matrix() / m[:, None]
    a[n:, n:] = -model.damping_matrix() / m[:, None]
    return a


def _check(model: TorsionModel):
    k, c, m = model.stiffness_matrix(), model.damping_matrix(), model.dof_inertia
    norms = (m.max(), np.abs(c).sum(1).max(), np.abs(k).sum(1).max())

    def check(outputs: dict) -> dict:
        r = outputs[CRANKDYN]
        lam = (r.eigenvalue_real + 1j * r.eigenvalue_imag)[1:]
        x = np.ascontiguousarray(r.mode_shapes[1:])
        # crankdyn's own: every pair's backward error in the QEP, from the dense matrices
        res = (lam[:, None] ** 2 * m) * x + lam[:, None] * (x @ c) + x @ k
        scale = (np.abs(lam) ** 2 * norms[0] + np.abs(lam) * norms[1] + norms[2]) * np.linalg.norm(
            x, axis=1
        )
        eta = np.linalg.norm(res, axis=1) / scale
        if eta.max() > 1e-13:
            raise AgreementError(f"crankdyn: backward error {eta.max():.2g} > 1e-13")
        kappa = condition_numbers(ChainPencil.of(model.chain), lam, np.ones(lam.size), x)
        over = r.damped_frequency[1:] == 0.0
        values = np.r_[lam, r.natural_frequency[1:][over] ** 2 / lam[over]]
        units = _EPS * np.r_[kappa, kappa[over]]  # eps kappa_r per eigenvalue
        out = {}
        for name, value in outputs.items():
            if name == CRANKDYN:
                continue
            dense = value[0]  # scipy's eigenvalues
            dev = np.array([np.min(np.abs(dense - v)) / abs(v) for v in values])
            out[name] = Deviation(
                float(np.max(dev / units)), 1e3, "eigenvalues, relative, in units of eps kappa_r"
            )
        return out

    return check


def cases(size: str = "full") -> list[Case]:
    out = []
    for n in SIZES[size]:
        model = damped_chain(n)
        a = state_space(model)
        _ = model.chain  # the model's arrays built before the clock, as the dense side's matrix
        out.append(
            Case(
                key=KEY,
                title=TITLE,
                size=f"N = {n}",
                contenders=(
                    Contender(CRANKDYN, lambda model=model: damped_modes(model)),
                    Contender(DENSE, lambda a=a: scipy.linalg.eig(a)),
                ),
                check=_check(model),
                targets=(Target(DENSE, 1.0, "faster than the dense eig"),) if n >= 500 else (),
                repeats=7 if n < 1000 else 3,
                interleave=True,
            )
        )
    return out
