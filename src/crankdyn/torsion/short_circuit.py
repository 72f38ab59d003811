"""Air-gap torque of a synchronous generator's sudden short circuit (numeric core).

The machine data are those of its data sheet (IEC 60034-4-1:2018, "Methods for determining
electrically excited synchronous machine quantities from tests", the sudden three-phase
short-circuit test; the same quantities enter IEC 60909-0:2016, "Short-circuit currents in
three-phase a.c. systems - Calculation of currents", for the generator's contribution): the
direct-axis subtransient, transient and synchronous reactances X''_d, X'_d, X_d (per unit), the
short-circuit time constants T''_d, T'_d and the armature (aperiodic) time constant T_a (s). The
short-circuit current of the test has the form (IEC 60034-4-1, the sudden short-circuit
current's components)

    i(t) = sqrt(2) E [ (1/X''_d - 1/X'_d) e^(-t/T''_d) + (1/X'_d - 1/X_d) e^(-t/T'_d) + 1/X_d ]
           cos(omega t + alpha)  -  sqrt(2) (E / X''_d) e^(-t/T_a) cos(alpha),

an alternating component whose envelope relative to its initial value is

    e(t) = X''_d [ (1/X''_d - 1/X'_d) e^(-t/T''_d) + (1/X'_d - 1/X_d) e^(-t/T'_d) + 1/X_d ]

(1 at t = 0, X''_d / X_d in the steady short circuit), and an aperiodic one decaying with T_a.

The air-gap torque (in per unit on the rated apparent power, speed 1 per unit) is the power the
internal EMF drives into the fault, sum over the phases of e_k i_k, with the EMF behind X''_d
falling like the alternating current it drives (its flux decays with the rotor's, e(t)), and
the resistance losses left out (classic constant-flux-linkage analysis; E. W. Kimbark, *Power
System Stability*, vol. III, *Synchronous Machines*, Wiley 1956, the chapter on the torques of
short circuits; C. Concordia, *Synchronous Machines*, Wiley 1951; neither text was at hand, the
derivation below is complete):

- **three-phase** fault from no load: e_k = sqrt(2) E sin(omega t + theta_k), the currents
  i_k = (sqrt(2) E / X''_d) [cos(theta_k) - cos(omega t + theta_k)] with
  theta_k = alpha + 2 pi k / 3; the products of the alternating parts cancel over the three
  phases, sum_k sin(omega t + theta_k) cos(theta_k) = (3/2) sin(omega t) for every fault
  instant alpha, so

      T_3(t) = T_b (E^2 / X''_d) e(t) e^(-t/T_a) sin(omega t);

- **two-phase** (line-to-line) fault, the negative-sequence reactance X_2 = X''_d: the
  line-to-line EMF sqrt(3) sqrt(2) E sin(omega t + alpha) drives through 2 X''_d the current
  (sqrt(3) sqrt(2) E / (2 X''_d)) [cos(alpha) - cos(omega t + alpha)], whose product with the
  EMF, on the same base (3/2 E^2), is

      T_2(t) = T_b (E^2 / X''_d) [ e(t) e^(-t/T_a) cos(alpha) sin(omega t + alpha)
                                   - (1/2) e(t)^2 sin(2 omega t + 2 alpha) ],

  largest for alpha = 0: max of sin x - (1/2) sin 2x = 3 sqrt(3) / 4 = 1.299 at x = 2 pi / 3,
  the classic "1.3 times the three-phase peak" (without the decays).

Verification (issue 36): IEC 60034-4-1:2018 and IEC 60909-0:2016 are not public; neither
they nor a transcription could be found in the stored pages and repositories, so their clause
numbers are not cited and the current components above are the textbook form of the sudden
three-phase short-circuit current the standard's test evaluates (its definitions of X''_d, X'_d,
X_d, T''_d, T'_d and T_a), not read in the standard. What the derivation leaves out, and the
literature on air-gap torques names (the torque holds unidirectional, fundamental-frequency
and second-harmonic components, all decaying: the abstract of the AIEE paper on the shaft
stresses of turbine generators during short circuits, read in a public index): the
unidirectional torque of the armature resistance's losses (small: the resistance is left out)
and, in the three-phase fault, the second harmonic of subtransient saliency (X''_q differing
from X''_d: taken equal here); the two-phase fault's decays are taken as the three-phase ones
(its negative-sequence reactance X_2 = X''_d). The formulas below are checked against their
own derivation worked by hand (tests/validation/test_events_rule_formulas.py) and against the
phase power of the currents integrated numerically from the circuit equation v = L di/dt
(tests/validation/test_short_circuit_phase_power.py), not against a standard.

T_b = S_r / Omega_m = T_r / cos(phi_r) is the torque base (rated apparent power over the
mechanical synchronous speed: the rated torque over the rated power factor) and E the internal
EMF before the fault in per unit (1 at no load and rated voltage; IEC 60909-0's voltage factor
c_max = 1.1 for the largest currents). omega is the electrical angular frequency (2 pi f_line).
The torque is the electromagnetic torque on the rotor, positive against the rotation (a
generator's braking torque).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.errors import InputError

__all__ = ["envelope", "short_circuit_torque", "two_phase_peak_factor"]


def _positive(name: str, value: float) -> float:
    v = float(value)
    if not (math.isfinite(v) and v > 0.0):
        raise InputError("must be a positive number", key=name, value=value)
    return v


def envelope(
    t: ArrayLike, xd2: float, xd1: float, xd: float, td2: float, td1: float
) -> NDArray[np.float64]:
    """e(t): the short-circuit current's alternating envelope relative to its initial value
    (module docstring; IEC 60034-4-1:2018's sudden short-circuit current).

    Parameters
    ----------
    t : array_like
        Time since the fault (s), >= 0.
    xd2, xd1, xd : float
        X''_d, X'_d, X_d (per unit), 0 < X''_d <= X'_d <= X_d.
    td2, td1 : float
        T''_d, T'_d (s), > 0.

    Returns
    -------
    numpy.ndarray
        e(t) (dimensionless): 1 at t = 0, X''_d / X_d for t -> infinity.

    Examples
    --------
    >>> round(float(envelope(0.0, 0.12, 0.25, 2.0, 0.02, 0.4)), 12)
    1.0
    >>> round(float(envelope(1e3, 0.12, 0.25, 2.0, 0.02, 0.4)), 12)  # X''_d / X_d
    0.06
    """
    t = np.asarray(t, dtype=float)
    return xd2 * (
        (1.0 / xd2 - 1.0 / xd1) * np.exp(-t / td2)
        + (1.0 / xd1 - 1.0 / xd) * np.exp(-t / td1)
        + 1.0 / xd
    )


def short_circuit_torque(
    t: ArrayLike,
    *,
    phases: int,
    frequency: float,
    base_torque: float,
    xd2: float,
    xd1: float,
    xd: float,
    td2: float,
    td1: float,
    ta: float,
    voltage: float = 1.0,
    angle: float = 0.0,
) -> NDArray[np.float64]:
    """The air-gap torque T_3(t) or T_2(t) of a sudden short circuit (module docstring).

    Parameters
    ----------
    t : array_like
        Time since the fault (s); the torque is 0 before it (t < 0).
    phases : {2, 3}
        A two-phase (line-to-line) or a three-phase fault.
    frequency : float
        omega, the electrical angular frequency (rad/s), > 0 (2 pi x 50 Hz).
    base_torque : float
        T_b = T_r / cos(phi_r) (N m), > 0.
    xd2, xd1, xd : float
        X''_d <= X'_d <= X_d (per unit), > 0.
    td2, td1, ta : float
        T''_d, T'_d, T_a (s), > 0.
    voltage : float
        E, the internal EMF before the fault (per unit), > 0; default 1.
    angle : float
        alpha, the fault instant (rad) on the line-to-line EMF of a two-phase fault (0: the
        largest torque); no effect on a three-phase one.

    Returns
    -------
    numpy.ndarray
        The torque (N m), positive against the rotation, the shape of ``t``.

    Raises
    ------
    InputError
        For phases other than 2 or 3, a value that is not positive, or reactances out of
        order (X''_d > X'_d or X'_d > X_d), naming the key.

    Examples
    --------
    Three-phase, a quarter period after the fault, no decay (time constants far longer):
    T_b E^2 / X''_d = 1000 / 0.1 = 10 kN m.

    >>> w = 2 * np.pi * 50.0
    >>> t3 = short_circuit_torque(0.25 / 50.0, phases=3, frequency=w, base_torque=1000.0,
    ...                           xd2=0.1, xd1=0.1, xd=0.1, td2=1e9, td1=1e9, ta=1e9)
    >>> round(float(t3), 6)
    10000.0
    >>> t2 = short_circuit_torque(1.0 / 150.0, phases=2, frequency=w, base_torque=1000.0,
    ...                           xd2=0.1, xd1=0.1, xd=0.1, td2=1e9, td1=1e9, ta=1e9)
    >>> round(float(t2) / 10000.0, 6)  # 3 sqrt(3) / 4 at omega t = 2 pi / 3
    1.299038
    """
    if phases not in (2, 3):
        raise InputError("expected 2 (line-to-line) or 3 (three-phase)", key="phases", value=phases)
    w = _positive("frequency", frequency)
    tb = _positive("rated_torque", base_torque)
    x2, x1, x0 = (_positive(k, v) for k, v in (("xd2", xd2), ("xd1", xd1), ("xd", xd)))
    if not x2 <= x1 <= x0:
        raise InputError("expected X''d <= X'd <= Xd", key="xd2", value=f"{x2:g}, {x1:g}, {x0:g}")
    t2_, t1_, ta_ = (_positive(k, v) for k, v in (("td2", td2), ("td1", td1), ("ta", ta)))
    e0 = _positive("voltage", voltage)
    t = np.asarray(t, dtype=float)
    tt = np.maximum(t, 0.0)
    env = envelope(tt, x2, x1, x0, t2_, t1_)
    dc = np.exp(-tt / ta_)
    scale = tb * e0 * e0 / x2
    if phases == 3:
        out = scale * env * dc * np.sin(w * tt)
    else:
        a = float(angle)
        out = scale * (
            env * dc * math.cos(a) * np.sin(w * tt + a)
            - 0.5 * env * env * np.sin(2.0 * (w * tt + a))
        )
    return np.where(t < 0.0, 0.0, out)


def two_phase_peak_factor() -> float:
    """The largest value of sin x - (1/2) sin 2x, 3 sqrt(3) / 4 at x = 2 pi / 3: the two-phase
    fault's peak torque over the three-phase one's, without the decays (module docstring).

    Returns
    -------
    float
        3 sqrt(3) / 4 (dimensionless).

    Examples
    --------
    >>> round(two_phase_peak_factor(), 6)
    1.299038
    """
    return 3.0 * math.sqrt(3.0) / 4.0
