"""The nominal alternating torque of every crank throw for UR M53 from the forced torsional
response (analysis).

UR M53.2.2.2 [KR Rules 2025 Pt 5 Annex 5-3 2(2)(A)]: the largest and smallest torques "are to
be ascertained for every mass point of the complete dynamic system and for the entire speed
range by means of a harmonic synthesis of the forced vibrations" (orders 0.5 to 12 of four-stroke
engines, 1 to 15 of two-stroke engines, (a)); M_TN = 1/2 (M_Tmax - M_Tmin) (e); "the nominal
alternating torsional stress considered in further calculations is the highest calculated
value ... occurring at the most torsionally loaded mass point of the crankshaft system. Where
barred speed ranges exist, the torsional stresses within these ranges are not to be considered"
(f).

:func:`nominal_torques` takes the synthesised half-range torque of every shaft of the forced
response (:attr:`crankdyn.torsion.response.ResponseResult.synthesized_shaft_torque`, the
response the TVC judges) and gives every throw the largest over the speeds outside the barred
ranges of the shafts either side of its mass (the crank spans that carry its journals and its
pin), with the shaft and the speed where it occurs. Checked throw by throw with its own M_TN,
the smallest Q over the throws is the rule's, which uses the most loaded mass point's for all
(the bending is the same for every throw of an engine with identical cylinders).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from crankdyn.constants import RPM
from crankdyn.engine.model import Engine
from crankdyn.errors import InputError
from crankdyn.torsion.model import TorsionModel

if TYPE_CHECKING:
    from crankdyn.torsion.response import ResponseResult

__all__ = ["RULE_ORDERS", "nominal_torques"]

RULE_ORDERS = {"four-stroke": (0.5, 12.0), "two-stroke": (1.0, 15.0)}
"""The orders of the harmonic synthesis of UR M53.2.2.2 [Annex 5-3 2(2)(A)(a)]."""


def nominal_torques(
    engine: Engine,
    model: TorsionModel,
    response: ResponseResult,
    barred: Sequence[tuple[float, float]] = (),
) -> tuple[NDArray[np.float64], tuple[str, ...], tuple[str, ...]]:
    """M_TN of every throw from the forced torsional response (module docstring).

    Parameters
    ----------
    engine : crankdyn.engine.Engine
        The engine (which cylinders sit on which throw).
    model : TorsionModel
        The torsional model of the response (which masses carry which cylinders).
    response : crankdyn.torsion.response.ResponseResult
        The forced response (its synthesised half-range shaft torques, N m).
    barred : sequence of (float, float)
        Barred speed ranges (rad/s), left out.

    Returns
    -------
    torque : numpy.ndarray
        M_TN of every throw (N m), shape (throws,).
    where : tuple of str
        The crank span and the speed of each (``"throw 2 - throw 3 at 612.4 rpm"``).
    notes : tuple of str
        How they were found (orders short of the rule's, barred ranges left out).

    Raises
    ------
    InputError
        If a throw's cylinders sit on no mass of the model, or every speed is barred.

    Examples
    --------
    >>> import crankdyn
    >>> a = crankdyn.Analysis(crankdyn.Engine.example("marine-propulsion"))
    >>> m_tn, where, notes = nominal_torques(a.engine, a.loaded_model, a.response())
    >>> m_tn.shape, where[0].split(" at ")[0]
    ((6,), 'throw 1 - throw 2')
    """
    cyl = engine.cylinders
    speeds = np.asarray(response.speed, dtype=float)
    keep = np.ones(speeds.size, dtype=bool)
    for low, high in barred:
        keep &= ~((speeds >= low) & (speeds <= high))
    if not keep.any():
        raise InputError(
            "every speed of the forced response lies in a barred speed range: no nominal "
            "torsional stress for UR M53",
            key="speeds",
        )
    torque = np.asarray(response.synthesized_shaft_torque, dtype=float)[keep]
    shafts = response.shafts
    out = np.zeros(cyl.throw_count)
    where = []
    for t in range(1, cyl.throw_count + 1):
        on = {i + 1 for i, k in enumerate(cyl.throws) if k == t}
        names = {m.name for m in model.masses if on & set(m.cylinders)}
        columns = [j for j, pair in enumerate(shafts) if names & set(pair)]
        if not columns:
            raise InputError(
                f"no shaft of the torsional model joins the mass of throw {t} (cylinders "
                f"{', '.join(map(str, sorted(on)))}): no nominal torsional stress for UR M53",
                file=getattr(model, "source", None),
            )
        values = torque[:, columns]
        s, j = np.unravel_index(int(np.argmax(values)), values.shape)
        out[t - 1] = values[s, j]
        pair = shafts[columns[j]]
        where.append(f"{pair[0]} - {pair[1]} at {speeds[keep][s] * RPM:.6g} rpm")
    notes = [
        "M_TN of every throw: the largest synthesised half-range torque over the speed range "
        "of the crank spans either side of it, from the forced response the TVC judges "
        "(normal firing; M53.2.2.2)"
    ]
    if barred:
        text = ", ".join(f"{lo * RPM:.6g}-{hi * RPM:.6g} rpm" for lo, hi in barred)
        notes.append(f"barred speed ranges left out of M_TN (M53.2.2.2 (f)): {text}")
    first, last = RULE_ORDERS[engine.cycle]
    orders = np.asarray(response.orders, dtype=float)
    if orders.size and (orders.min() > first or orders.max() < last):
        notes.append(
            f"the harmonic synthesis used orders {orders.min():g} to {orders.max():g}; UR M53 "
            f"asks for {first:g} to {last:g} ({engine.cycle}; give --orders)"
        )
    return out, tuple(where), tuple(notes)
