"""Case: natural frequencies and mode shapes of a free chain of N masses.

crankdyn (``TorsionModel.chain_of`` + ``natural_modes``: LAPACK's tridiagonal eigensolver on the
mass-normalised chain, mode shapes normalised, nodes located) against openTorsion 0.3.2
(``Shaft``/``Disk`` elements into an ``Assembly``, then ``undamped_modal_analysis``, a general
``scipy.linalg.eig(K, M)``) and against ``scipy.linalg.eigh(K, M)`` on the dense matrices
(assembled before the clock starts: the best a dense solver can do). crankdyn's and openTorsion's
times start from the same arrays of inertias and stiffnesses, so both include building their
model.

The chain: N masses with inertias drawn uniformly from 0.05..2 kg m^2 and N - 1 shafts with
stiffnesses from 0.2..5 MN m/rad (seeded, so every run solves the same chain), free at both
ends (one rigid-body mode).

Agreement: the elastic natural frequencies to 1e-9 relative (each against its own value); the
rigid-body mode, which dense solvers return as round-off of order eps * omega_max^2 in omega^2,
as |omega_0^2| <= 1e-9 omega_max^2.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg

from bench.harness import CRANKDYN, AgreementError, Case, Contender, Deviation, Target
from crankdyn.torsion.modal import natural_modes
from crankdyn.torsion.model import TorsionModel

KEY = "chain"
TITLE = "Free chain: natural frequencies and mode shapes"
SIZES = {"full": (10, 100, 1000), "tiny": (10, 40)}
TOLERANCE = 1e-9
OPENTORSION = "openTorsion Assembly.undamped_modal_analysis"
EIGH = "scipy eigh (dense K, M)"


def chain_values(n: int, seed: int = 2026) -> tuple[np.ndarray, np.ndarray]:
    """Inertias (kg m^2, n) and stiffnesses (N m/rad, n - 1) of the benchmark chain."""
    rng = np.random.default_rng(seed + n)
    return rng.uniform(0.05, 2.0, n), rng.uniform(0.2e6, 5e6, n - 1)


def dense_matrices(inertia, stiffness) -> tuple[np.ndarray, np.ndarray]:
    """K and M of a free chain, assembled directly."""
    n = inertia.size
    k = np.zeros((n, n))
    i = np.arange(n - 1)
    k[i, i] += stiffness
    k[i + 1, i + 1] += stiffness
    k[i, i + 1] -= stiffness
    k[i + 1, i] -= stiffness
    return k, np.diag(inertia)


def crankdyn_modes(inertia, stiffness):
    return natural_modes(TorsionModel.chain_of(inertia, stiffness))


def _opentorsion_run(inertia, stiffness):
    try:
        import opentorsion as ot
    except ImportError:
        return None

    def run():
        n = inertia.size
        shafts = [ot.Shaft(i, i + 1, k=float(stiffness[i])) for i in range(n - 1)]
        disks = [ot.Disk(i, float(inertia[i])) for i in range(n)]
        return ot.Assembly(shafts, disk_elements=disks).undamped_modal_analysis()

    return run


def _omega2(result) -> np.ndarray:
    """Sorted omega^2 (rad^2/s^2) from each contender's output."""
    if hasattr(result, "natural_frequency"):
        return np.asarray(result.natural_frequency) ** 2
    lam = result[0]
    return np.sort(np.abs(np.real(lam)))


def _check(outputs: dict) -> dict[str, Deviation]:
    mine = _omega2(outputs[CRANKDYN])
    result = outputs[CRANKDYN]
    # crankdyn's own identities: a free chain has omega_0 = 0 exactly, the modal inertia and
    # stiffness of every mode give back its frequency
    if mine[0] != 0.0:
        raise AgreementError("crankdyn: the rigid-body mode of a free chain is not 0")
    out = {}
    for name, value in outputs.items():
        if name == CRANKDYN:
            continue
        theirs = _omega2(value)
        if theirs.shape != mine.shape:
            raise AgreementError(f"{name}: {theirs.size} modes, crankdyn {mine.size}")
        rigid = abs(theirs[0]) / mine[-1]
        if rigid > TOLERANCE:
            raise AgreementError(f"{name}: rigid-body omega^2 {theirs[0]:.3g} is not ~0")
        freq = np.sqrt(theirs[1:])
        dev = float(np.max(np.abs(freq - np.asarray(result.natural_frequency[1:])) / freq))
        out[name] = Deviation(dev, TOLERANCE, "relative, natural frequencies")
    return out


def cases(size: str = "full") -> list[Case]:
    out = []
    for n in SIZES[size]:
        inertia, stiffness = chain_values(n)
        k, m = dense_matrices(inertia, stiffness)
        ot_run = _opentorsion_run(inertia, stiffness)
        contenders = (
            Contender(CRANKDYN, lambda j=inertia, s=stiffness: crankdyn_modes(j, s)),
            Contender(
                OPENTORSION,
                ot_run,
                missing=None if ot_run else "opentorsion not installed",
            ),
            Contender(EIGH, lambda k=k, m=m: scipy.linalg.eigh(k, m)),
        )
        targets = ()
        if n >= 1000:
            targets = (
                Target(OPENTORSION, 100.0, ">= 100x openTorsion"),
                Target(EIGH, 1.0, "faster than dense eigh"),
            )
        out.append(
            Case(
                key=KEY,
                title=TITLE,
                size=f"N = {n}",
                contenders=contenders,
                check=_check,
                targets=targets,
                repeats=15 if n < 1000 else 5,
            )
        )
    return out + limit_cases(size)


# ---- against the limit: LAPACK dstevd + normalising (bench/bare.py), dense eigh at N = 10 -------
BARE = "dstevd + normalising (bare)"
LIMIT_SIZES = {"full": (10, 100, 1000), "tiny": (10, 40)}


def limit_cases(size: str = "full") -> list[Case]:
    """crankdyn's ``natural_modes`` on a built model (the solve and its result: shapes,
    nodes counted, modal inertias) against the least a solver must do: ``dstevd`` and the
    shapes normalised (within 1.5x from N = 100); at N = 10 the fixed cost against a dense
    ``eigh`` (within 2x)."""
    from bench.bare import chain_modes

    out = []
    for n in LIMIT_SIZES[size]:
        inertia, stiffness = chain_values(n)
        model = TorsionModel.chain_of(inertia, stiffness)
        k, m = dense_matrices(inertia, stiffness)

        def check(outputs: dict, inertia=inertia, stiffness=stiffness) -> dict:
            mine = np.asarray(outputs[CRANKDYN].natural_frequency)
            devs = {}
            for name, value in outputs.items():
                if name == CRANKDYN:
                    continue
                theirs = np.sqrt(np.abs(np.sort(np.asarray(value[0]))))
                dev = float(np.max(np.abs(theirs[1:] - mine[1:]) / mine[1:]))
                devs[name] = Deviation(dev, TOLERANCE, "relative, natural frequencies")
            return devs

        if n < 100:
            peer = Contender(EIGH, lambda k=k, m=m: scipy.linalg.eigh(k, m))
            target = Target(EIGH, 0.5, "fixed cost within 2x of dense eigh")
        else:
            peer = Contender(BARE, lambda j=inertia, s=stiffness: chain_modes(j, s))
            target = Target(BARE, 1.0 / 1.5, "within 1.5x of it")
        out.append(
            Case(
                key=f"{KEY}-limit",
                title="Chain modes against the limit (model built)",
                size=f"N = {n}",
                contenders=(Contender(CRANKDYN, lambda model=model: natural_modes(model)), peer),
                check=check,
                targets=(target,) if size == "full" or n >= 100 else (),
                repeats=15 if n < 1000 else 5,
                interleave=True,  # a ratio to the limit: both under the same load
            )
        )
    return out
