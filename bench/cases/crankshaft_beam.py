"""Case: the lowest coupled modes of a 12-throw crankshaft beam model (issue 38).

crankdyn (``beam_modes``: one sparse LU of K - sigma M and ARPACK's shift-invert Lanczos for the
lowest 20 modes, mass-normalised shapes, the kinetic-energy classification of every mode) against
``scipy.linalg.eigh(K, M, subset_by_index=[0, 19])`` on the same matrices made dense before the
clock starts (the best a dense solver can do: the lowest 20 eigenpairs only). Both start from the
assembled matrices; building the model (a few ms) is outside the clock for both.

The crankshaft: 12 throws of a 100 mm journal, 80 mm pin, 60 mm crank radius (a V24's or an
in-line twelve's proportions: the example throw of crankdyn.torsion.equivalent), rods and
counterweights, damper hub and flywheel, main bearings of 5e8 N/m radial, 1e6 N m/rad tilting
and a thrust bearing; 2 and 4 elements per journal half, web and pin half (894 and 1782 degrees
of freedom).

Agreement: the elastic natural frequencies to 1e-8 relative; the rigid-body torsional mode as
|omega_0^2| <= 1e-6 omega_max^2 in the dense solver's output (round-off), exactly 0 in crankdyn's.
Target (issue 38): crankdyn under 1 s on 2 cores, and faster than the dense solver.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.linalg

from bench.harness import CRANKDYN, AgreementError, Case, Contender, Deviation, Target
from crankdyn.crankshaft.beam_elements import BeamMaterial
from crankdyn.crankshaft.beam_model import (
    CrankshaftBeamGeometry,
    EndMass,
    MainBearings,
    ThrowDimensions,
    ThrowMasses,
    build_beam_model,
)
from crankdyn.crankshaft.beam_modes import beam_modes

KEY = "crankshaft-beam"
TITLE = "Crankshaft beam model: lowest 20 coupled modes"
SIZES = {"full": ((12, 2), (12, 4)), "tiny": ((2, 1),)}
COUNT = 20
TOLERANCE = 1e-8
EIGH = "scipy eigh (dense K, M, lowest 20)"


def crankshaft(throws: int, elements: int):
    """The benchmark crankshaft's beam model."""
    angles = tuple(-(k % 3) * 2 * math.pi / 3 for k in range(throws))
    g = CrankshaftBeamGeometry(
        ThrowDimensions(0.1, 0.05, 0.08, 0.04, 0.025, 0.12, 0.06),
        angles,
        BeamMaterial(210e9, 0.3, 7850.0),
        MainBearings(5e8, 1e6, 5e8, thrust_journal=2),
        masses=ThrowMasses(1.5, 1.2, 2.0, 0.05),
        free_end=EndMass(5.0, 0.05, 0.03, 0.05),
        flywheel=EndMass(20.0, 0.8, 0.4, 0.05),
    )
    return build_beam_model(g, elements=elements)


def _check(outputs: dict) -> dict[str, Deviation]:
    mine = outputs[CRANKDYN]
    lam = mine.natural_frequency**2
    if lam[0] != 0.0 or np.any(lam[1:] <= 0.0):
        raise AgreementError("crankdyn: expected exactly one rigid-body mode")
    out = {}
    for name, value in outputs.items():
        if name == CRANKDYN:
            continue
        theirs = np.asarray(value[0])
        if abs(theirs[0]) > 1e-6 * theirs[-1]:
            raise AgreementError(f"{name}: rigid-body omega^2 {theirs[0]:.3g} is not ~0")
        dev = float(np.max(np.abs(np.sqrt(theirs[1:]) / mine.natural_frequency[1:] - 1.0)))
        out[name] = Deviation(dev, TOLERANCE, "relative, elastic natural frequencies")
    return out


def cases(size: str = "full") -> list[Case]:
    out = []
    for throws, elements in SIZES[size]:
        model = crankshaft(throws, elements)
        k, m = model.stiffness.toarray(), model.mass.toarray()
        count = min(COUNT, model.size - 2)
        out.append(
            Case(
                key=KEY,
                title=TITLE,
                size=f"{throws} throws, {model.size} dof",
                contenders=(
                    Contender(CRANKDYN, lambda model=model, c=count: beam_modes(model, c)),
                    Contender(
                        EIGH,
                        lambda k=k, m=m, c=count: scipy.linalg.eigh(
                            k, m, subset_by_index=[0, c - 1]
                        ),
                    ),
                ),
                check=_check,
                targets=(
                    Target(None, 0.0, "under 1 s", seconds=1.0),
                    Target(EIGH, 1.0, "faster than dense eigh; under 1 s"),
                )
                if size == "full"
                else (),
                repeats=5,
            )
        )
    return out
