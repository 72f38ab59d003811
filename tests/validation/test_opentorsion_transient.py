"""openTorsion's time-domain test reproduced by crankdyn's exact integrator.

openTorsion (Aalto-Arotor/openTorsion, ``opentorsion/tests/tests.py``,
``test_continuous_2_discrete``) discretises a geared four-disc line (discs of 1, 0.1, 0.1 and
1 kg m^2 with absolute damping 0.5, 0.1, 0.1 and 1 N m s/rad; shafts of 400 and 800 N m/rad
with damping 1 and 0.5 N m s/rad; a 10:60 external gear between the middle discs) at a step of
1e-4 s with a zero-order hold, and prints the state and input matrices Ad = e^(A h) and
Bd = integral_0^h e^(A s) ds B to eight decimals. Its state is (theta_0, theta_12, theta_3) and
their rates, the gear's discs one coordinate in the first gear's frame, the last disc in its
own (turning the other way); its inputs the torques on those coordinates.

crankdyn's propagator (:class:`crankdyn.torsion.integrator.ModalSystem`) gives Ad as the states
one step after unit initial states without forcing, and Bd as the states one step after rest
under a unit torque held over the step (a piecewise-linear forcing with equal ends is a
zero-order hold), in the reflected coordinates of the same model; the transformation to
openTorsion's coordinates is the last disc's signed speed ratio -1/6. The tolerance is half a
unit of the eighth decimal (openTorsion compares the matrices rounded to 8 decimals), plus the
integrator's rounding. openTorsion's transient examples (``examples/transient_simulation.py``,
``car_drivetrain_simulation.py``) plot their results and print no transient values.
"""

from __future__ import annotations

import numpy as np

from crankdyn.torsion import Gear, Mass, Shaft, TorsionModel
from crankdyn.torsion.event_line import line_of
from crankdyn.torsion.integrator import modal_system

AD_PRINTED = [
    [
        9.99998001e-01,
        1.99920804e-06,
        -2.18307721e-10,
        9.99924354e-05,
        5.06456694e-09,
        -1.41886052e-13,
    ],
    [
        1.94516925e-05,
        9.99979468e-01,
        -6.48400342e-06,
        4.92768675e-08,
        9.99450127e-05,
        -4.26851591e-09,
    ],
    [
        -5.61974349e-11,
        -6.66573571e-07,
        9.99996000e-01,
        -1.41886052e-13,
        -4.38708580e-10,
        9.99923671e-05,
    ],
    [
        -3.99772634e-02,
        3.99761684e-02,
        -6.57013549e-06,
        9.99848061e-01,
        1.01936618e-04,
        -4.32450052e-09,
    ],
    [
        3.88955474e-01,
        -4.10564637e-01,
        -1.29654980e-01,
        9.91815739e-04,
        9.98893628e-01,
        -8.75140974e-05,
    ],
    [
        -1.70734961e-06,
        -1.33305134e-02,
        -7.99933245e-02,
        -4.32450052e-09,
        -8.99450446e-06,
        9.99846012e-01,
    ],
]
BD_PRINTED = [
    [4.99974838e-09, 1.63732899e-12, -3.51326010e-18],
    [1.63732899e-12, 4.86308687e-08, -1.40497100e-13],
    [-3.51326010e-18, -1.40497100e-13, 4.99974668e-09],
    [9.99924354e-05, 4.92768675e-08, -1.41886052e-13],
    [4.92768675e-08, 9.72437961e-04, -4.26851591e-09],
    [-1.41886052e-13, -4.26851591e-09, 9.99923671e-05],
]


def test_opentorsion_continuous_2_discrete():
    model = TorsionModel(
        masses=(
            Mass("disc 0", 1.0, damping=0.5),
            Mass("disc 1", 0.1, damping=0.1, role="gear"),
            Mass("disc 2", 0.1, damping=0.1, role="gear"),
            Mass("disc 3", 1.0, damping=1.0),
        ),
        shafts=(
            Shaft(("disc 0", "disc 1"), 400.0, damping=1.0),
            Shaft(("disc 2", "disc 3"), 800.0, damping=0.5),
        ),
        gears=(Gear(("disc 1", "disc 2"), teeth=(10, 60)),),
    )
    line = line_of(model, hysteretic_frequency=1.0)
    system = modal_system(line.inertia, line.stiffness, line.damping, absolute_damping="absolute")
    h = 1e-4
    n = line.size
    ad = np.empty((2 * n, 2 * n))
    for col in range(2 * n):
        state = np.zeros(2 * n)
        state[col] = 1.0
        u, g = system.modal_forcing(np.zeros((2, n)))
        x, v = system.to_physical(system.run(system.to_modal(state[:n], state[n:]), u, g, h))
        ad[:, col] = np.concatenate([x[0], v[0]])
    bd = np.empty((2 * n, n))
    for col in range(n):
        f = np.zeros((2, n))
        f[:, col] = 1.0
        u, g = system.modal_forcing(f)
        x, v = system.to_physical(system.run(system.to_modal(np.zeros(n), np.zeros(n)), u, g, h))
        bd[:, col] = np.concatenate([x[0], v[0]])
    # openTorsion's coordinates: the last disc's own angle, theta_3 = -theta_3,ref / 6
    r = -1.0 / 6.0
    t = np.diag([1.0, 1.0, r, 1.0, 1.0, r])
    forces = np.diag([1.0, 1.0, r])  # a torque on disc 3 acts on the reflected dof as r T
    ad_ot = t @ ad @ np.linalg.inv(t)
    bd_ot = t @ bd @ forces
    assert np.max(np.abs(ad_ot - np.array(AD_PRINTED))) < 0.5e-8 + 1e-12
    assert np.max(np.abs(bd_ot - np.array(BD_PRINTED))) < 0.5e-8 + 1e-12
