"""Harmonic analysis of an engine's cylinder torque at one speed (analysis and result).

Per order the single-cylinder amplitude (gas, inertia, total) and phase, the Fourier
coefficients of seed 003 ch. 4 and eq. 5 (:mod:`crankdyn.torsion.orders`), the phase-vector sum
over the cylinders and whether the order is major, and with a model's modes the relative
amplitude sums (seed 003 section 4.2; Ker Wilson vol. 2) of the excitation
(:mod:`crankdyn.torsion.excitation`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.constants import DEG, RPM
from crankdyn.errors import InputError
from crankdyn.results import Result, array, freeze, scalar
from crankdyn.torsion.orders import (
    check_orders,
    major_orders,
    phase_vector_sums,
    relative_amplitude_sums,
)

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from crankdyn.torsion.excitation import Excitation
    from crankdyn.torsion.modal import ModalResult
    from crankdyn.torsion.model import TorsionModel

__all__ = ["HarmonicResult", "cylinder_amplitudes", "harmonic_analysis"]


@dataclass(frozen=True)
class HarmonicResult(Result):
    """Harmonic analysis of the cylinder torque at one speed: per order the single-cylinder
    amplitude (gas, inertia, total), phase, the phase-vector sum over the cylinders and whether
    the order is major; with a model, the relative amplitude sums over its modes
    (:func:`harmonic_analysis`; module docstring)."""

    title = "Torque harmonics"
    orders: NDArray[np.float64] = array("orders", "Order", "")
    amplitude: NDArray[np.float64] = array("amplitude_Nm", "Single-cylinder amplitude", "N·m")
    gas_amplitude: NDArray[np.float64] = array("gas_amplitude_Nm", "Gas part", "N·m")
    inertia_amplitude: NDArray[np.float64] = array("inertia_amplitude_Nm", "Inertia part", "N·m")
    phase: NDArray[np.float64] = array("phase_deg", "Phase from firing TDC", "deg", DEG)
    phase_sum: NDArray[np.float64] | None = array(
        "phase_vector_sum", "Phase-vector sum |Σ e^(-iqΦ)|", ""
    )
    """None when the firing angles are unknown (:mod:`crankdyn.torsion.orders`)."""
    major: NDArray[np.bool_] | None = array("major", "Major order", "")
    """None when the firing angles are unknown (:mod:`crankdyn.torsion.orders`)."""
    engine_amplitude: NDArray[np.float64] = array(
        "engine_amplitude_Nm", "All cylinders |Σ c|", "N·m"
    )
    relative_amplitude_sums: NDArray[np.float64] | None = array(
        "relative_amplitude_sums", "Relative amplitude sums (mode x order)", ""
    )
    modes: NDArray[np.int_] | None = array("modes", "Modes", "")
    speed: float = scalar("speed_rpm", "Speed", "rpm", RPM)
    cylinders: int = scalar("cylinders", "Cylinders", "")
    firing_angles: NDArray[np.float64] = array("firing_angles_deg", "Firing angles", "deg", DEG)
    source: str = scalar("excitation", "Excitation", "")
    notes: tuple[str, ...] | None = scalar("notes", "Notes", "")

    def plot(self, fig: Figure | None = None) -> Figure:
        """Bar chart of the single-cylinder harmonics per order.

        Parameters
        ----------
        fig : matplotlib.figure.Figure or None
            A figure to draw into; None makes a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.torsion_response import plot_harmonics

        return plot_harmonics(self, fig=fig)


def harmonic_analysis(
    excitation: Excitation,
    speed: float,
    orders: ArrayLike,
    modes: ModalResult | None = None,
    model: TorsionModel | None = None,
) -> HarmonicResult:
    """Harmonic analysis of the excitation at one speed: the Fourier coefficients of the
    cylinder torque (seed 003 ch. 4 and eq. 5), the phase-vector sums and major orders (seed 003
    section 4.2) and, with modes, the relative amplitude sums (module docstring).

    Parameters
    ----------
    excitation : Excitation
        An :class:`~crankdyn.torsion.excitation.EngineExcitation` or
        :class:`~crankdyn.torsion.excitation.UniformExcitation`.
    speed : float
        Crankshaft speed (rad/s), > 0.
    orders : array_like
        Orders to list (dimensionless), shape (orders,).
    modes : crankdyn.torsion.modal.ModalResult or None
        Optionally the modes of ``model`` for the relative amplitude sums (elastic modes; each
        mode's shape normalised to a largest amplitude of 1 over the cylinder masses).
    model : crankdyn.torsion.model.TorsionModel or None
        The model of ``modes`` (which mass carries which cylinder).

    Returns
    -------
    HarmonicResult
        Per order the single-cylinder amplitudes (N m), phase (rad), phase-vector sum, major
        flag and the engine's total amplitude (N m).

    Raises
    ------
    crankdyn.errors.InputError
        A speed not positive (key ``speed``) or orders that do not fit the cycle (key
        ``orders``).

    Examples
    --------
    >>> from crankdyn.torsion.excitation import UniformExcitation
    >>> exc = UniformExcitation(1.0, np.radians([0.0, 540.0, 180.0, 360.0]))
    >>> res = harmonic_analysis(exc, 100.0, [1.0, 2.0])
    >>> res.major, np.round(res.engine_amplitude, 12)
    (array([False,  True]), array([0., 4.]))
    """
    if not (math.isfinite(speed) and speed > 0.0):
        raise InputError("the speed must be positive", key="speed", value=speed)
    orders = check_orders(orders, excitation.cycle)
    gas, inertia = excitation.parts(np.array([speed]), orders)
    angles = excitation.firing_angles
    # cylinder 1's own harmonic (measured from its firing TDC)
    own = np.exp(1j * orders * angles[0])
    total = (gas + inertia)[0]
    one = total[:, 0] * own
    known = getattr(excitation, "phases_known", True)
    sums = rel = mode_numbers = None
    if modes is not None and model is not None and known:
        elastic = np.flatnonzero(modes.natural_frequency > 0.0)
        beta = cylinder_amplitudes(modes, model, excitation.cylinder_count)[elastic]
        rel = relative_amplitude_sums(beta, angles, orders)
        mode_numbers = modes.mode[elastic]
    sums = phase_vector_sums(angles, orders)
    return HarmonicResult(
        orders=freeze(orders),
        amplitude=freeze(np.abs(one)),
        gas_amplitude=freeze(np.abs(gas[0][:, 0])),
        inertia_amplitude=freeze(np.abs(inertia[0][:, 0])),
        phase=freeze(np.angle(one)),
        phase_sum=freeze(sums) if known else None,
        major=freeze(major_orders(angles, orders), dtype=bool) if known else None,
        engine_amplitude=freeze(np.abs(np.sum(total, axis=1))),
        relative_amplitude_sums=None if rel is None else freeze(rel),
        modes=None if mode_numbers is None else freeze(mode_numbers, dtype=int),
        speed=float(speed),
        cylinders=excitation.cylinder_count,
        firing_angles=freeze(angles),
        source=excitation.description,
        notes=tuple(excitation.notes([speed])) or None,
    )


def cylinder_amplitudes(modes: ModalResult, model: TorsionModel, count: int) -> NDArray[np.float64]:
    """Mode-shape amplitude of the mass carrying each cylinder, each mode normalised to a
    largest absolute cylinder amplitude of 1 (0 for cylinders on no mass).

    Parameters
    ----------
    modes : crankdyn.torsion.modal.ModalResult
        The modes of ``model``.
    model : crankdyn.torsion.model.TorsionModel
        The model (its masses' ``cylinders``).
    count : int
        Number of cylinders.

    Returns
    -------
    numpy.ndarray
        Relative amplitudes beta (dimensionless), shape (modes, cylinders).
    """
    shapes = np.asarray(modes.mode_shapes)  # mode x mass
    out = np.zeros((shapes.shape[0], count))
    for i, m in enumerate(model.masses):
        for c in m.cylinders:
            if c <= count:
                out[:, c - 1] = shapes[:, i]
    peak = np.max(np.abs(out), axis=1, keepdims=True)
    return out / np.where(peak > 0.0, peak, 1.0)
