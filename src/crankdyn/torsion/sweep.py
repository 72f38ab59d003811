"""The forced torsional response over a speed range: the sweep and its resolution (analysis).

:func:`forced_response` gives the steady-state response of a model to its excitation at every
speed of the user's grid and every order: the dynamic-stiffness equation D(q Omega) X = F
(seed 003, the V6 paper's eqs. 1, 2 and 6; :mod:`crankdyn.torsion.solvers`), its synthesis over
the orders and the shafts' torques and nominal stresses
(:class:`~crankdyn.torsion.response.ResponseResult`).

The path of a speed runs one way: the grid is checked here; at each speed the harmonic torques
of the cylinders and of the model's sources (:func:`crankdyn.torsion.sources.assemble_forcing`)
and the change of the load-dependent couplings' stiffness (:func:`crankdyn.torsion.loaded.
load_change`) are found, the solver (:mod:`crankdyn.torsion.solvers`) takes all speeds x orders
at once and the response goes into the result (:mod:`crankdyn.torsion.response`). The response
judges nothing: the installation's checks (:mod:`crankdyn.tvc.checks`) are evaluated in one
place (:func:`crankdyn.tvc.evaluate.evaluate_condition`) by ``crankdyn torsion response`` and
``crankdyn tvc`` alike (:meth:`crankdyn.session.Analysis.judged`).

Forcing and drivelines. F holds the cylinders' harmonic torques and those of the model's sources
(propellers, electric machines, tabulated sources and further engines at any mass, at orders of
that mass's own speed: :func:`crankdyn.torsion.sources.assemble_forcing`). Couplings whose
stiffness depends on the mean torque take each speed's stiffness
(:func:`crankdyn.torsion.loaded.load_change`, still one batched solve:
:meth:`crankdyn.torsion.solvers.LinearSystem.solve_with_change`); modal damping ratios add
C_modal to C (:mod:`crankdyn.torsion.damped`).

Resolution. By default a sweep is *resolved* (:mod:`crankdyn.torsion.resolve`): the critical
speeds inside the grid's range are added, every damped resonance is sampled across its width
(with the damping, modal damping and, for load-dependent couplings, the stiffness at the
resonance's own speed) and every peak is refined until it is resolved to 0.1 %; each round is
one batched evaluation of the new speeds.
"""

from __future__ import annotations

import math
from collections import OrderedDict
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.constants import RPM
from crankdyn.defaults import RESPONSE_BLOCK_MEMORY
from crankdyn.errors import InputError, did_you_mean
from crankdyn.results import freeze, frozen
from crankdyn.torsion.dampers import Damper
from crankdyn.torsion.loaded import load_change, stiffness_change
from crankdyn.torsion.model import TorsionModel
from crankdyn.torsion.resolve import (
    MAX_ROUNDS,
    TOLERANCE,
    Refiner,
    damped_frequency_rows,
    merge_speeds,
    modal_pole_rows,
    seed_speeds,
)
from crankdyn.torsion.response import ResponseResult
from crankdyn.torsion.solvers import change_matrix, linear_system
from crankdyn.torsion.sources import (
    assemble_forcing,
    check_model_orders,
    forcing_notes,
    line_major,
    source_breakpoints,
    synthesis_index,
    synthesize_at,
)

if TYPE_CHECKING:
    from crankdyn.torsion.excitation import Excitation

__all__ = ["forced_response"]


def _check_speeds(speeds: ArrayLike) -> NDArray[np.float64]:
    s = np.atleast_1d(np.asarray(speeds, dtype=float))
    if s.ndim != 1 or s.size == 0:
        raise InputError("the speed range is empty", key="speeds")
    if not np.all(np.isfinite(s)) or np.any(s <= 0.0):
        bad = s[~(np.isfinite(s) & (s > 0.0))][0]
        raise InputError("speeds must be positive", key="speeds", value=float(bad) * RPM)
    return s


# ---- the sweep: the response at any speeds -------------------------------------------------
@dataclass(frozen=True, eq=False)
class _Block:
    """The response at a set of speeds (rows)."""

    speed: np.ndarray  # (S,) rad/s
    x: np.ndarray  # (S, Q, N) complex actual angles of the listed masses
    torque: np.ndarray  # (S, Q, E) complex element torques
    power: np.ndarray | None  # (S, D)
    top: np.ndarray  # (S, N + E + P) largest value over the cycle: masses, elements, pairs
    low: np.ndarray  # (S, N + E + P) smallest

    @staticmethod
    def joined(blocks: Sequence[_Block]) -> tuple[_Block, np.ndarray]:
        """The blocks' rows in ascending speed (a speed in several once: the first block's)
        and the row of the concatenation each row came from: one copy of every array, however
        many blocks (the rounds of a resolution)."""
        speed, first = merge_speeds(*(b.speed for b in blocks))
        # every row of the result: which block it comes from and its row there
        offsets = np.cumsum([0] + [b.speed.size for b in blocks])
        which = np.searchsorted(offsets, first, side="right") - 1
        rows = [(k, np.flatnonzero(which == k)) for k in range(len(blocks))]

        def cat(arrays: list[np.ndarray]) -> np.ndarray:
            """The rows ``first`` of the concatenation, filled block by block (one copy of
            the result, not the concatenation and then its rows)."""
            out = np.empty((first.size, *arrays[0].shape[1:]), dtype=arrays[0].dtype)
            for k, at in rows:  # the rounds (a few dozen at most), not the speeds
                if at.size:
                    out[at] = arrays[k][first[at] - offsets[k]]
            return out

        powers = [b.power for b in blocks]
        return (
            _Block(
                speed=speed,
                x=cat([b.x for b in blocks]),
                torque=cat([b.torque for b in blocks]),
                power=None
                if any(p is None for p in powers)
                else cat([p for p in powers if p is not None]),
                top=cat([b.top for b in blocks]),
                low=cat([b.low for b in blocks]),
            ),
            first,
        )


class Sweep:
    """Everything of a forced response that does not depend on the speed, and its evaluation
    at any speeds (one batched solve): the ``evaluator`` of a
    :class:`~crankdyn.torsion.response.ResponseResult` (not part of the API)."""

    def __init__(
        self,
        model: TorsionModel,
        excitation: Excitation,
        orders: NDArray[np.float64],
        dampers: Iterable[Damper],
        hysteretic_frequency: float | None,
        pairs: Iterable[tuple[int, int]],
        modal_damping: ArrayLike | None = None,
        block_memory: float = RESPONSE_BLOCK_MEMORY,
    ) -> None:
        self.model = model
        self.block_memory = float(block_memory)
        self.excitation = excitation
        self.orders = orders
        self.hysteretic_frequency = hysteretic_frequency
        self.system = system = linear_system(model, dampers, modal_damping)
        # harmonic indices over the orders' common period (None: none short enough, the
        # synthesis is the sum of the amplitudes; crankdyn.torsion.sources.synthesize)
        self.synthesis = synthesis_index(orders, excitation.cycle)
        self.n_shafts = len(model.shafts)
        modulus = np.full(len(system.element_labels), np.nan)
        for s, shaft in enumerate(model.shafts):
            if shaft.geometry is not None:
                modulus[s] = shaft.geometry.section_modulus
        self.modulus = modulus
        self.pairs = tuple(pairs)
        self.major = line_major(excitation, orders)
        # (mode, order, critical speed) of the undamped resonances in the range (:meth:`seeds`)
        self.unbounded: list[tuple[int, float, float]] = []
        self._at: OrderedDict[bytes, ResponseResult] = OrderedDict()  # :meth:`at`'s last ones

    # ---- evaluation ---------------------------------------------------------------------------
    def block_size(self) -> int:
        """Speeds per block of :meth:`evaluate`: as many as the memory budget
        ``block_memory`` (bytes; :data:`crankdyn.defaults.RESPONSE_BLOCK_MEMORY`) holds at
        :data:`WORKING_BYTES` per speed, order and item (degree of freedom, listed mass,
        element, tracked pair), at least one."""
        system = self.system
        items = system.size + system.mass_dof.size + len(system.element_labels) + len(self.pairs)
        per_speed = WORKING_BYTES * max(self.orders.size, 1) * max(items, 1)
        return max(1, int(self.block_memory // per_speed))

    def evaluate(self, speeds: ArrayLike) -> _Block:
        """The response at ``speeds`` (rad/s): batched solves over speeds x orders, in blocks of
        :meth:`block_size` speeds written into arrays of all of them (the working arrays of one
        block at a time; every speed is solved and synthesised on its own, so the block size
        changes no number)."""
        speeds = np.asarray(speeds, dtype=float)
        rows = self.block_size()
        if speeds.size <= rows:
            return self._evaluate(speeds)
        first = self._evaluate(speeds[:rows])

        def room(a: np.ndarray) -> np.ndarray:
            out = np.empty((speeds.size, *a.shape[1:]), dtype=a.dtype)
            out[:rows] = a
            return out

        x, torque, top, low = room(first.x), room(first.torque), room(first.top), room(first.low)
        power = None if first.power is None else room(first.power)
        del first
        for start in range(rows, speeds.size, rows):  # blocks of speeds, not a loop per speed
            part = self._evaluate(speeds[start : start + rows])
            end = start + part.speed.size
            x[start:end], torque[start:end] = part.x, part.torque
            top[start:end], low[start:end] = part.top, part.low
            if power is not None and part.power is not None:
                power[start:end] = part.power
        return _Block(speed=speeds, x=x, torque=torque, power=power, top=top, low=low)

    def _evaluate(self, speeds: NDArray[np.float64]) -> _Block:
        """The response at one block of speeds (rad/s): one batched solve over speeds x
        orders."""
        system = self.system
        orders = self.orders
        # harmonic torques of the cylinders and of the model's sources (crankdyn.torsion.sources)
        forcing, _ = assemble_forcing(self.model, system, self.excitation, speeds, orders)
        omega = speeds[:, None] * orders[None, :]
        x_dof, k = self._solve(speeds, omega, forcing)
        # actual angles of the listed masses (signed speed ratios: the sense of rotation)
        x = x_dof[:, :, system.mass_dof] * system.mass_ratio[None, None, :]
        # element torques: k_actual (theta_b - theta_a)_actual = k_ref/r (dX_ref)
        ends = system.element_dofs
        xa = np.where(ends[:, 0] >= 0, x_dof[:, :, np.maximum(ends[:, 0], 0)], 0.0)
        xb = np.where(ends[:, 1] >= 0, x_dof[:, :, np.maximum(ends[:, 1], 0)], 0.0)
        twist = xb - xa
        torque = k * twist
        n_shafts = self.n_shafts
        power = None
        if system.dampers:
            ratio = system.element_ratio[n_shafts:]
            coupling = np.stack([d.complex_stiffness(omega) for d in system.dampers], axis=-1) * (
                ratio**2 / ratio
            )
            torque[:, :, n_shafts:] = coupling * twist[:, :, n_shafts:]
            actual_twist = twist[:, :, n_shafts:] * ratio
            power = np.sum(
                np.stack(
                    [d.power(omega, actual_twist[:, :, j]) for j, d in enumerate(system.dampers)],
                    axis=-1,
                ),
                axis=1,
            )
        parts = [x, torque]
        if self.pairs:
            i = np.array([p[0] for p in self.pairs])
            j = np.array([p[1] for p in self.pairs])
            parts.append(x[:, :, i] - x[:, :, j])
        top, low = synthesize_at(np.moveaxis(np.concatenate(parts, axis=2), 1, -1), self.synthesis)
        return _Block(speed=speeds, x=x, torque=torque, power=power, top=top, low=low)

    def _solve(
        self, speeds: np.ndarray, omega: np.ndarray, forcing: np.ndarray
    ) -> tuple[NDArray[np.complexfloating], NDArray[np.float64]]:
        """(x, k): the reflected amplitudes of the degrees of freedom (S, Q, n) and the elements'
        actual stiffness, each speed with its couplings' stiffness at that speed's mean torque
        where it depends on it (:func:`crankdyn.torsion.loaded.load_change`, solved by
        :meth:`~crankdyn.torsion.solvers.LinearSystem.solve_with_change`), otherwise the
        model's (:meth:`~crankdyn.torsion.solvers.LinearSystem.solve`)."""
        system = self.system
        base_k = system.element_stiffness / system.element_ratio
        found = load_change(self.model, system, speeds, omega, self.hysteretic_frequency)
        if found is None:
            return system.solve(omega, forcing, self.hysteretic_frequency), base_k
        ends, change, k = found
        if system.chain is None:
            x = system.solve_with_change(omega, forcing, ends, change, self.hysteretic_frequency)
        else:
            x = low_rank_solve(system, omega, forcing, ends, change, self.hysteretic_frequency)
        return x, k

    def at(self, speeds: ArrayLike) -> ResponseResult:
        """The response at exactly ``speeds`` (rad/s, checked positive), in their order, without
        resolution or rule check (:meth:`crankdyn.torsion.response.ResponseResult.at`). The
        last :data:`AT_KEPT` answers of at most :data:`AT_SPEEDS` speeds are kept (immutable
        results): the TVC's checks of one condition each ask for the range's ends and the
        barred ranges' ends."""
        checked = _check_speeds(speeds)
        if checked.size > AT_SPEEDS:  # a long grid: not kept
            return self.result(self.evaluate(checked))
        key = checked.tobytes()
        found = self._at.get(key)
        if found is None:
            found = self._at[key] = self.result(self.evaluate(checked))
            if len(self._at) > AT_KEPT:
                self._at.popitem(last=False)
        else:
            self._at.move_to_end(key)
        return found

    # ---- the curves whose peaks are resolved ----------------------------------------------------
    def tracked(self, block: _Block) -> tuple[np.ndarray, np.ndarray]:
        """(values (S, C), scale (C,)): every reported curve (per order, summed, synthesised:
        mass amplitudes, element torques (the stresses are proportional), damper power, the
        tracked relative angles) and the value each one's tolerance is relative to
        (:meth:`scale`)."""
        values, bounds = self._values(block)
        return values, self.scale(values, bounds)

    @staticmethod
    def scale(values: np.ndarray, bounds: np.ndarray) -> np.ndarray:
        """Per curve its largest value, at least 1e-9 of its family's largest (columns
        ``bounds[k]:bounds[k+1]``), so that curves at round-off level ask for no refinement."""
        top = np.max(values, axis=0) if values.shape[0] else np.zeros(values.shape[1])
        return Sweep.scale_of(top, bounds)

    @staticmethod
    def scale_of(top: np.ndarray, bounds: np.ndarray) -> np.ndarray:
        """:meth:`scale` from every curve's largest value ``top`` (C,)."""
        family = np.maximum.reduceat(top, bounds[:-1]) if top.size else top
        floor = np.repeat(1e-9 * family, np.diff(bounds))
        return np.maximum(top, floor)

    def _values(self, block: _Block) -> tuple[np.ndarray, np.ndarray]:
        """The tracked curves (S, C) and the column bounds of their families."""
        s = block.speed.size
        n, e = block.x.shape[2], block.torque.shape[2]
        ax = np.abs(block.x)
        at = np.abs(block.torque)
        half = 0.5 * (block.top - block.low)
        families = [
            ax.reshape(s, -1),
            ax.sum(axis=1),
            half[:, :n],
            at.reshape(s, -1),
            at.sum(axis=1),
            half[:, n : n + e],
        ]
        if block.power is not None:
            families.append(block.power)
        if self.pairs:
            i = np.array([p[0] for p in self.pairs])
            j = np.array([p[1] for p in self.pairs])
            rel = np.abs(block.x[:, :, i] - block.x[:, :, j])
            families += [rel.reshape(s, -1), rel.sum(axis=1), half[:, n + e :]]
        families = [f for f in families if f.shape[1]]
        bounds = np.concatenate([[0], np.cumsum([f.shape[1] for f in families])])
        return np.concatenate(families, axis=1), bounds

    def describe(self, column: int, block: _Block) -> str:
        """Which curve a column of :meth:`tracked` is (for the added speeds' reasons)."""
        q_count = self.orders.size
        n, e = block.x.shape[2], block.torque.shape[2]
        names = self.system.mass_names
        elements = [f"{a} - {b}" for a, b in self.system.element_labels]
        dampers = [d.name for d in self.system.dampers]
        pairs = [f"{names[i]} - {names[j]}" for i, j in self.pairs]
        layout = [
            ("angular amplitude", q_count * n, lambda k: _per_order(k, n, names, self.orders)),
            ("sum of order amplitudes", n, lambda k: names[k]),
            ("synthesised amplitude", n, lambda k: names[k]),
            ("torque", q_count * e, lambda k: _per_order(k, e, elements, self.orders)),
            ("vibratory torque (sum of orders)", e, lambda k: elements[k]),
            ("synthesised torque", e, lambda k: elements[k]),
        ]
        if block.power is not None:
            layout.append(("damper power", len(dampers), lambda k: dampers[k]))
        if self.pairs:
            p = len(pairs)
            layout += [
                ("relative angle", q_count * p, lambda k: _per_order(k, p, pairs, self.orders)),
                ("relative angle, sum of orders", p, lambda k: pairs[k]),
                ("relative angle, synthesised", p, lambda k: pairs[k]),
            ]
        for label, size, name in layout:
            if column < size:
                return f"{label}, {name(column)}"
            column -= size
        return "response"  # pragma: no cover

    # ---- resonances ----------------------------------------------------------------------------
    def _rigid_count(self) -> int:
        """Zero natural frequencies of the system: the rigid-body mode of a free model and one
        per damper ring joined by a viscous film only."""
        viscous = sum(1 for d in self.system.dampers if d.stiffness == 0.0)
        return (1 if self.model.is_free else 0) + viscous

    def undamped(self) -> np.ndarray:
        """The elastic undamped natural frequencies (rad/s) of the system with its damper
        rings, ascending: mode r is row r - 1 (docs/conventions.md)."""
        import scipy.linalg  # here, not at start-up (the command line's help imports this module)

        system = self.system
        if system.chain is not None and system.size > 1:
            kb, _, _, kg, _, _ = system.chain
            diag = np.array(kg, dtype=float)
            diag[:-1] += kb
            diag[1:] += kb
            j = system.inertia
            lam = scipy.linalg.eigvalsh_tridiagonal(diag / j, -kb / np.sqrt(j[:-1] * j[1:]))
        else:
            lam = scipy.linalg.eigh(system.stiffness, np.diag(system.inertia), eigvals_only=True)
        lam = np.sort(lam)[self._rigid_count() :]
        return np.sqrt(np.maximum(lam, 0.0))

    def _damping(self) -> tuple[np.ndarray, np.ndarray]:
        """(C, H) of the poles: the system's viscous and hysteretic damping matrices, the loss
        factors as viscous eta k / omega_h when the sweep freezes them at omega_h."""
        system = self.system
        c, h = system.damping, system.hysteretic
        if self.hysteretic_frequency is not None:
            c = c + h / self.hysteretic_frequency
            h = np.zeros_like(h)
        return c, h

    def poles(self, top: float) -> np.ndarray:
        """Damped natural frequencies a + i b (rad/s) with a <= top (module
        :mod:`crankdyn.torsion.resolve`), with the model's stiffness (load-dependent couplings
        at their reference torque): the quadratic eigenproblem for systems of up to
        :data:`POLE_LIMIT` degrees of freedom, else the undamped modes up to ``top`` with the
        modal damping of their shapes (b_r = phi^T (H + omega_r C) phi / (2 omega_r phi^T M
        phi); :func:`crankdyn.torsion.resolve.modal_pole_rows` for a chain)."""
        w = self._pole_rows(None, top)
        w = w[np.isfinite(w)]
        return np.sort_complex(w[w.real <= top])

    def _pole_rows(
        self, change: tuple[np.ndarray, np.ndarray, np.ndarray] | None, top: float
    ) -> np.ndarray:
        """Damped natural frequencies of the system with the stiffness changes ``change`` =
        (ends, delta (S, count), eta (count,)) of the load-dependent couplings at S speeds
        (:meth:`loaded_poles`), or of the model's own (None): (S or 1, P) complex, ascending in
        the real part, NaN-padded (:meth:`poles`); above :data:`POLE_LIMIT` degrees of freedom
        (:data:`TRACK_POLE_LIMIT` with changes) the undamped modes with their modal damping, a
        chain's up to ``top`` (rad/s) only."""
        system = self.system
        size = system.size
        limit = POLE_LIMIT if change is None else TRACK_POLE_LIMIT
        if system.chain is not None and size > limit:
            return self._chain_pole_rows(change, top)
        c0, h0 = self._damping()
        if change is None:
            return self._dense_pole_rows(system.stiffness, c0, h0, size <= limit)
        ends, delta, eta = change
        delta = np.asarray(delta, dtype=float)
        rows = max(1, POLE_BLOCK // (size * size))  # speeds per block: bounded memory
        parts = []
        for s0 in range(0, delta.shape[0], rows):
            d = delta[s0 : s0 + rows]
            k = system.stiffness + change_matrix(ends, d, size)
            c, h = c0, h0
            if self.hysteretic_frequency is None:
                h = h0 + change_matrix(ends, d * eta, size)
            else:
                c = c0 + change_matrix(ends, d * eta / self.hysteretic_frequency, size)
            parts.append(self._dense_pole_rows(k, c, h, size <= limit))
        width = max(p.shape[-1] for p in parts)
        out = np.full((delta.shape[0], width), np.nan, dtype=complex)
        for s0, part in zip(range(0, delta.shape[0], rows), parts, strict=True):
            out[s0 : s0 + part.shape[0], : part.shape[-1]] = part
        return out

    def _dense_pole_rows(
        self, k: np.ndarray, c: np.ndarray, h: np.ndarray, exact: bool
    ) -> np.ndarray:
        """:meth:`_pole_rows` of dense matrices (..., n, n): the quadratic eigenproblem
        (``exact``) or the undamped modes with their modal damping."""
        system = self.system
        if exact:
            return damped_frequency_rows(system.inertia, k, c, h)
        j = np.sqrt(system.inertia)
        lam, psi = np.linalg.eigh(k / j[:, None] / j[None, :])
        lam, psi = lam[..., self._rigid_count() :], psi[..., self._rigid_count() :]
        phi = psi / j[:, None]  # mass-normalised mode shapes
        omega = np.sqrt(np.maximum(lam, 0.0))
        modal_h = np.sum(phi * (h @ phi), axis=-2)
        modal_c = np.sum(phi * (c @ phi), axis=-2)
        with np.errstate(divide="ignore", invalid="ignore"):
            b = (modal_h + omega * modal_c) / (2.0 * np.maximum(omega, 1e-300))
        return np.where(omega > 0.0, omega + 1j * np.abs(b), np.nan)

    def _chain_pole_rows(
        self, change: tuple[np.ndarray, np.ndarray, np.ndarray] | None, top: float
    ) -> np.ndarray:
        """:meth:`_pole_rows` of a large chain (:func:`crankdyn.torsion.resolve.
        modal_pole_rows`): the changed couplings are links of the chain."""
        chain = self.system.chain
        assert chain is not None  # called for chains only
        kb, cb, hb, kg, cg, hg = chain
        k_link, c_link, h_link = kb[None, :], cb[None, :], hb[None, :]
        if change is not None:
            ends, delta, eta = change
            rows = np.asarray(delta).shape[0]
            k_link = np.repeat(k_link, rows, axis=0)
            h_link = np.repeat(h_link, rows, axis=0)
            for j, (a, b) in enumerate(np.asarray(ends).tolist()):  # the couplings (a few)
                k_link[:, min(a, b)] += delta[:, j]
                h_link[:, min(a, b)] += delta[:, j] * eta[j]
        if self.hysteretic_frequency is not None:  # the loss factors as viscous damping
            c_link = c_link + h_link / self.hysteretic_frequency
            cg = cg + hg / self.hysteretic_frequency
            h_link, hg = np.zeros_like(h_link), np.zeros_like(hg)
        return modal_pole_rows(
            self.system.inertia, (k_link, c_link, h_link), (kg, cg, hg), self._rigid_count(), top
        )

    def _loaded_change(self, speeds: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
        """(ends, delta, eta) of the load-dependent couplings at reference speeds (rad/s)
        (:func:`crankdyn.torsion.loaded.stiffness_change`), or None."""
        found = stiffness_change(self.model, self.system, speeds)
        return None if found is None else found[:3]

    def loaded_poles(self, speeds: ArrayLike, top: float = math.inf) -> np.ndarray:
        """Damped natural frequencies (rad/s) with the load-dependent couplings' stiffness at
        the mean torque of every speed (rad/s): (S, P), NaN-padded, ascending (:meth:`poles`;
        the forced response takes the same stiffness at that speed); above
        :data:`POLE_LIMIT` degrees of freedom those up to ``top`` (rad/s) only. Equal speeds
        are one eigenproblem (the resonances followed beyond the range all sit at its ends)."""
        speeds = np.asarray(speeds, dtype=float)
        distinct, where = np.unique(speeds, return_inverse=True)
        found = self._loaded_change(distinct)
        if found is None:  # pragma: no cover - called only with load-dependent couplings
            raise ValueError("no coupling of the model depends on the load")
        return self._pole_rows(found, top)[where.reshape(speeds.shape)]

    def _tracked_resonances(
        self, poles: np.ndarray, orders: np.ndarray, low: float, high: float
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The resonances of the damped modes with the load-dependent couplings' stiffness at
        the resonance's own speed: for every pole p (at the reference torque) and order q, the
        speed n with Re a_p(n) = q n, a_p(n) the pole at the stiffness of speed n (clipped to
        the range, beyond which the load laws give no stiffness), found by the secant method
        from the fixed-point step n = Re a_p(n0) / q, all pairs at once, each iteration one
        batched eigenproblem; the pole followed from speed to speed as the one nearest in
        frequency. Returns (centre (rad/s), half width (rad/s), pole frequency (rad/s), order
        index) of the pairs whose resonance lies within two half widths of the range."""
        top = 2.0 * float(np.max(orders)) * high * 1.5  # beyond the poles that matter (seeds)
        rows = self.loaded_poles([low, high], top)  # (2, P)

        def follow(rows_at: np.ndarray, previous: np.ndarray) -> np.ndarray:
            gap = np.abs(rows_at.real - previous[:, None])
            k = np.argmin(np.where(np.isnan(gap), np.inf, gap), axis=1)
            return rows_at[np.arange(k.size), k]  # NaN where there is no pole at all

        # candidates: a pole p at the reference torque, followed to both ends of the range
        p_ref = poles
        at_low = follow(np.broadcast_to(rows[0], (p_ref.size, rows.shape[1])), p_ref.real)
        at_high = follow(np.broadcast_to(rows[1], (p_ref.size, rows.shape[1])), p_ref.real)
        q = orders[None, :]
        g_low = at_low.real[:, None] - q * low + 2.0 * np.abs(at_low.imag)[:, None]
        g_high = at_high.real[:, None] - q * high - 2.0 * np.abs(at_high.imag)[:, None]
        with np.errstate(invalid="ignore"):
            p_idx, q_idx = np.nonzero((g_low >= 0.0) & (g_high <= 0.0))
        if p_idx.size == 0:
            return np.zeros(0), np.zeros(0), np.zeros(0), np.zeros(0, dtype=int)
        q_sel = orders[q_idx]
        # start: the resonance interpolated between the ends, then one fixed-point step
        lo_f, hi_f = at_low.real[p_idx], at_high.real[p_idx]
        gl, gh = lo_f - q_sel * low, hi_f - q_sel * high
        with np.errstate(divide="ignore", invalid="ignore"):
            t = np.clip(np.where(gl != gh, gl / (gl - gh), 0.5), 0.0, 1.0)
        n0 = low + t * (high - low)
        track = lo_f + t * (hi_f - lo_f)

        def step(
            n: np.ndarray, track: np.ndarray, which: np.ndarray
        ) -> tuple[np.ndarray, np.ndarray]:
            """The followed poles and g = Re a - q n at speeds n of the pairs ``which``."""
            at = np.clip(np.where(np.isfinite(n), n, low), low, high)
            a = follow(self.loaded_poles(at, top), track)
            return a, a.real - q_sel[which] * n

        every = np.arange(q_sel.size)
        a0, g0 = step(n0, track, every)
        n1 = a0.real / q_sel
        a1, g1 = step(n1, a0.real, every)
        for _ in range(TRACK_ITERATIONS):
            # converged, or lost (no pole to follow): no further evaluation
            active = np.flatnonzero(
                np.isfinite(n1) & np.isfinite(g1) & (np.abs(n1 - n0) > 1e-9 * np.abs(n1))
            )
            if active.size == 0:
                break
            m0, m1, h0, h1 = n0[active], n1[active], g0[active], g1[active]
            with np.errstate(divide="ignore", invalid="ignore"):
                secant = m1 - h1 * (m1 - m0) / (h1 - h0)
            # a secant step that fails (flat or non-finite) falls back to the fixed point
            fixed = a1.real[active] / q_sel[active]
            m2 = np.where(np.isfinite(secant) & (h1 != h0), secant, fixed)
            a2, h2 = step(m2, a1.real[active], active)
            n0, g0 = n1.copy(), g1.copy()
            n1[active], g1[active], a1[active] = m2, h2, a2
        centre = a1.real / q_sel
        width = np.maximum(np.abs(a1.imag), 1e-6 * a1.real) / q_sel
        with np.errstate(invalid="ignore"):
            near = (centre + 2.0 * width >= low) & (centre - 2.0 * width <= high)
        return centre[near], width[near], a1.real[near], q_idx[near]

    def seeds(self, grid: np.ndarray, low: float, high: float) -> tuple[np.ndarray, list[str]]:
        """The critical speeds (undamped modes x orders) inside [low, high] and the speeds
        that sample every damped resonance across its width (resolve module, step 1), with a
        reason for each: (speeds (rad/s), reasons). The critical speeds are the Campbell
        diagram's (the model's stiffness: load-dependent couplings at their reference torque);
        with load-dependent couplings the damped resonances are followed to the coupling
        stiffness at their own speed (:meth:`_tracked_resonances`), where the forced response
        has them."""
        orders = self.orders
        omega = self.undamped()
        poles = self.poles(float(np.max(orders)) * high * 1.5)
        # a mode without damping (its pole on the real axis) has an unbounded resonance: its
        # critical speeds are not evaluated (the solve would be singular) but noted
        free = poles.real[np.abs(poles.imag) <= 1e-9 * poles.real]
        undamped = np.zeros(omega.size, dtype=bool)
        if free.size and omega.size:
            gap = np.min(np.abs(omega[:, None] - free[None, :]), axis=1)
            undamped = gap <= 1e-6 * omega
        crit = omega[:, None] / orders[None, :]
        inside = (crit >= low) & (crit <= high)
        self.unbounded = [
            (int(a) + 1, float(orders[b]), float(crit[a, b]))
            for a, b in zip(*np.nonzero(inside & undamped[:, None]), strict=True)
        ]
        r, q = np.nonzero(inside & ~undamped[:, None])
        crit_speeds = crit[r, q]
        crit_reasons = [
            f"critical speed: mode {int(a) + 1} x order {orders[b]:g}"
            for a, b in zip(r, q, strict=True)
        ]
        poles = poles[np.abs(poles.imag) > 1e-9 * poles.real]
        if self._loaded_change([low]) is None:
            centre = poles.real[:, None] / orders[None, :]
            width = np.maximum(np.abs(poles.imag), 1e-6 * poles.real)[:, None] / orders[None, :]
            near = (centre + 2.0 * width >= low) & (centre - 2.0 * width <= high)
            p, q2 = np.nonzero(near)
            centre, width, frequency = centre[p, q2], width[p, q2], poles.real[p]
            loaded = ""
        else:
            centre, width, frequency, q2 = self._tracked_resonances(poles, orders, low, high)
            loaded = ", couplings at that speed's mean torque"
        points, which = seed_speeds(np.concatenate([grid, crit_speeds]), centre, width, low, high)
        seed_reasons = [
            f"resonance sampling: {frequency[k] / (2 * math.pi):.4g} Hz x order "
            f"{orders[q2[k]]:g}{loaded}"
            for k in which
        ]
        kinks = np.concatenate(
            [
                np.asarray(getattr(self.excitation, "breakpoints", lambda: ())(), dtype=float),
                source_breakpoints(self.model),
            ]
        )
        kinks = kinks[(kinks > low) & (kinks < high)]
        return (
            np.concatenate([crit_speeds, points, kinks]),
            crit_reasons
            + seed_reasons
            + ["excitation breakpoint (a point of a load curve, trace or source table)"]
            * kinks.size,
        )

    # ---- results ------------------------------------------------------------------------------
    def result(self, block: _Block, **extra: Any) -> ResponseResult:
        """The ResponseResult of a block (``extra``: the resolution fields and notes)."""
        n, e = block.x.shape[2], block.torque.shape[2]
        x, torque = block.x, block.torque
        shaft_torque = np.sum(np.abs(torque), axis=1)
        synth_torque = 0.5 * (block.top[:, n : n + e] - block.low[:, n : n + e])
        ptp = block.top[:, :n] - block.low[:, :n]
        system = self.system
        return ResponseResult(
            speed=freeze(block.speed),
            orders=freeze(self.orders),
            major=None if self.major is None else freeze(self.major, dtype=bool),
            masses=system.mass_names,
            shafts=system.element_labels,
            # the arrays computed here for the result: made read-only, not copied again
            amplitude=frozen(np.abs(x)),
            synthesized_amplitude=frozen(0.5 * ptp),
            peak_to_peak=frozen(ptp),
            order_sum_amplitude=frozen(np.sum(np.abs(x), axis=1)),
            order_shaft_torque=frozen(np.abs(torque)),
            shaft_torque=frozen(shaft_torque),
            synthesized_shaft_torque=frozen(synth_torque),
            shaft_stress=frozen(shaft_torque / self.modulus),
            synthesized_shaft_stress=frozen(synth_torque / self.modulus),
            damper_power=None if block.power is None else freeze(block.power),
            dampers=tuple(d.name for d in system.dampers) or None,
            model_name=self.model.name,
            excitation="; ".join(
                [self.excitation.description] + [src.describe() for src in self.model.sources]
            ),
            cycle=self.excitation.cycle,
            mass_response=x,
            shaft_response=torque,
            section_modulus=self.modulus,
            evaluator=self,
            **extra,
        )


def low_rank_solve(
    system: Any,
    omega: NDArray[np.float64],
    forcing: NDArray[np.complexfloating],
    ends: NDArray[np.int_],
    change: NDArray[np.complexfloating],
    hysteretic_frequency: float | None,
) -> NDArray[np.complexfloating]:
    """X with (D(omega) + sum_j c_j u_j u_j^T) X = F, u_j = e_a - e_b the ends of the changed
    elements (the load-dependent couplings at each speed), by the Sherman-Morrison-Woodbury
    identity (G. H. Golub and C. F. Van Loan, *Matrix Computations*, 4th ed., 2013, sec.
    2.1.4): one elimination of the model's own D(omega) per frequency with the forcing and the
    u_j as right-hand sides (:meth:`crankdyn.torsion.solvers.LinearSystem.solve`, the chain's
    fast path), then X = X_0 - Z (C^-1 + U^T Z)^-1 U^T X_0 with D Z = U, a (count x count)
    system per frequency.

    Parameters
    ----------
    system : crankdyn.torsion.solvers.LinearSystem
        The model's linear system.
    omega : numpy.ndarray
        (S, Q) frequencies (rad/s).
    forcing : numpy.ndarray
        (S, Q, n) harmonic torques (N m).
    ends : numpy.ndarray
        (count, 2) the changed elements' degrees of freedom.
    change : numpy.ndarray
        (S, Q, count) their dynamic stiffness changes (N m/rad).
    hysteretic_frequency : float or None
        As :meth:`~crankdyn.torsion.solvers.LinearSystem.solve`.

    Returns
    -------
    numpy.ndarray
        (S, Q, n) complex angles (rad).
    """
    n = system.size
    count = len(ends)
    rhs = np.empty((*forcing.shape[:-1], n, 1 + count), dtype=complex)
    rhs[..., 0] = forcing
    u = np.zeros((n, count))
    for j, (a, b) in enumerate(np.asarray(ends).tolist()):  # the couplings (a few)
        u[a, j] += 1.0
        u[b, j] -= 1.0
    rhs[..., 1:] = u
    solved = system.solve(omega, rhs, hysteretic_frequency)  # (S, Q, n, 1 + count)
    del rhs
    x0, z = solved[..., 0], solved[..., 1:]
    # U^T X: each column of U is e_a - e_b (a coupling's two ends), so U^T X is X_a - X_b,
    # read at the ends instead of a product over every degree of freedom
    a, b = np.asarray(ends)[:, 0], np.asarray(ends)[:, 1]
    ux = x0[..., a] - x0[..., b]  # (S, Q, count)
    uz = z[..., a, :] - z[..., b, :]  # (S, Q, count, count)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        small = np.eye(count) + change[..., :, None] * uz  # C (U^T Z) + I, times C^-1 of Woodbury
        y = np.linalg.solve(small, (change * ux)[..., None])[..., 0]
    out = x0.copy()
    for j in range(count):  # the couplings (a few): X_0 - Z y, a column at a time
        out -= z[..., j] * y[..., None, j]
    return out


AT_KEPT = 64
"""How many answers of :meth:`Sweep.at` a sweep keeps."""
AT_SPEEDS = 8
"""The most speeds of an answer of :meth:`Sweep.at` that is kept."""
WORKING_BYTES = 160
"""Bytes of working arrays per speed, order and item (degree of freedom, listed mass, element,
tracked pair) of one block of an evaluation (:meth:`Sweep.evaluate`: the forcing, the solve
with the load-dependent couplings' right-hand sides, the angles, twists and torques, the
coefficients of the synthesis): tracemalloc's peak less the kept arrays measured 59 for blocks
of many speeds and 138-147 for blocks of a few (the chain solve's and the synthesis's own
buffers), on chains of 150 and 600 masses and the marine example's line subdivided to 100 and
300 masses, with margin. Beyond the budget an evaluation holds the synthesis's block buffers
(:data:`SYNTHESIS_BUFFERS`)."""

SYNTHESIS_BUFFERS = 2 * 2**20
"""Bytes of the synthesis's own buffers (a block of 256 rows of the cycle's grid,
:mod:`crankdyn.torsion.synthesis`) and of the bookkeeping of one evaluation, whatever its
size: part of the stated bound (docs/benchmarks.md), not of the budget."""

TRACK_ITERATIONS = 30
"""Secant iterations at most when following a resonance to its load-dependent coupling
stiffness (each one batched eigenproblem; they converge superlinearly, in a few)."""

POLE_LIMIT = 200
"""Largest system (degrees of freedom) whose damped natural frequencies are found by the
quadratic eigenproblem; above it the undamped modes with modal damping are used."""

POLE_BLOCK = 1 << 22
"""Elements of the (speeds, n, n) matrices of :meth:`Sweep.loaded_poles` per block of speeds
(32 MiB of each): the memory of following the poles is bounded by a block, not by the number
of speeds (at least one speed per block)."""

TRACK_POLE_LIMIT = 64
"""The same limit for the poles followed to the load-dependent couplings' stiffness
(:meth:`Sweep.loaded_poles`: one eigenproblem per resonance and secant iteration): the
quadratic eigenproblem's (2n)^3 work there took 91 % of a whole TVC of a 200-mass line
(sampled profile, bench/tvc_line.py), the undamped modes' n^3 a sixtieth of it; the poles only
place the seed speeds, the forced response and its peaks are exact either way."""


def _per_order(k: int, count: int, names: Sequence[str], orders: np.ndarray) -> str:
    return f"{names[k % count]}, order {orders[k // count]:g}"


def forced_response(
    model: TorsionModel,
    excitation: Excitation,
    speeds: ArrayLike,
    orders: ArrayLike,
    *,
    dampers: Sequence[Damper] | None = None,
    hysteretic_frequency: float | None = None,
    resolve: bool = True,
    tolerance: float = TOLERANCE,
    relative: Iterable[tuple[str, str]] | None = None,
    modal_damping: ArrayLike | None = None,
    block_memory: float | None = None,
) -> ResponseResult:
    """Steady-state forced response of ``model`` to ``excitation`` over a speed range.

    The dynamic-stiffness equation D(q Omega) X = F for every speed and order (seed 003, the
    V6 paper's eqs. 1, 2 and 6), its synthesis over the orders and the shafts' torques and
    nominal stresses (:mod:`crankdyn.torsion.response`); the peaks resolved by
    :mod:`crankdyn.torsion.resolve`.

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The torsional model (masses carrying cylinders are the excitation points).
    excitation : EngineExcitation or UniformExcitation
        :class:`~crankdyn.torsion.excitation.EngineExcitation` or
        :class:`~crankdyn.torsion.excitation.UniformExcitation` (see
        :func:`~crankdyn.torsion.excitation.excitation_for`).
    speeds : array_like
        Crankshaft speeds (rad/s), > 0: the user's grid.
    orders : array_like
        Orders to solve (multiples of the cycle's fundamental order, or orders of the model's
        sources).
    dampers : sequence of Damper or None
        Dampers to add (:class:`~crankdyn.torsion.dampers.Damper`); None: the model's own
        (``model.dampers``); ``()``: none (the response without them).
    hysteretic_frequency : float or None
        None (default): loss factors as exact hysteretic damping. A frequency omega_h (rad/s):
        loss factors as viscous damping eta k / omega_h (the time-domain equivalent).
    resolve : bool
        True (default): add the critical speeds inside the grid's range and refine around
        every resonance until the peak of every reported quantity is resolved to
        ``tolerance`` (:mod:`crankdyn.torsion.resolve`); the result's speeds are the sorted
        union of the grid and the added speeds. False: exactly the given speeds, in their
        order (for comparisons on a fixed grid).
    tolerance : float
        Relative change of a peak below which it counts as resolved (dimensionless, default
        0.1 %), 0 < tolerance < 1.
    relative : iterable of (str, str) or None
        Pairs of masses (a, b) whose relative angle is resolved with the rest (in the same
        batched rounds); any other pair is resolved when asked for
        (:meth:`~crankdyn.torsion.response.ResponseResult.relative_angle`).
    modal_damping : float, array_like or None
        Damping ratios of the elastic modes (one for all, or one per mode) added to the model's
        damping as C_modal (:mod:`crankdyn.torsion.damped`, as openTorsion's ``C_modal``), or
        None. The damped-resonance sampling of a resolved sweep includes it.
    block_memory : float or None
        Memory budget (bytes) of the working arrays of one block of speeds
        (:meth:`Sweep.block_size`); None: :data:`crankdyn.defaults.RESPONSE_BLOCK_MEMORY`
        (256 MiB). The speeds are solved and synthesised block by block; the block size
        changes no number.

    Returns
    -------
    crankdyn.torsion.response.ResponseResult
        Amplitudes (rad), torques (N m), stresses (Pa) and damper power (W) per speed
        (rad/s); ``speed``, ``on_grid``, ``added_speeds`` and ``added_reasons``;
        :meth:`~crankdyn.torsion.response.ResponseResult.peak` for the largest value of any
        quantity (the response judges nothing: :func:`crankdyn.tvc.analysis.judge` does).

    Raises
    ------
    InputError
        Naming the key and value: an empty speed range or a speed that is not positive
        (``speeds``), orders the model cannot take (``orders``), a tolerance outside (0, 1),
        an unknown mass in ``relative``, a ``block_memory`` that is not positive, excitation
        points the model lacks, dampers and modal damping as
        :func:`~crankdyn.torsion.solvers.linear_system`.

    Examples
    --------
    One damped mass on a grounded shaft swept on a 130 rad/s grid: the peak of the resolved
    response is the single damped mass's, T / (c sqrt(k/J - (c/2J)^2)) (seed 003), to the
    tolerance; the grid alone misses it by more than half.

    >>> from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
    >>> from crankdyn.torsion.excitation import UniformExcitation
    >>> model = TorsionModel(
    ...     masses=(Mass("m", 1.0, damping=20.0, cylinders=(1,)),),
    ...     shafts=(Shaft(("ground", "m"), 1e6, geometry=ShaftGeometry(0.05)),),
    ... )
    >>> excitation = UniformExcitation(100.0, [0.0], "two-stroke")
    >>> grid = np.arange(500.0, 1500.0, 130.0)
    >>> exact = 100.0 / (20.0 * math.sqrt(1e6 - 100.0))
    >>> resolved = forced_response(model, excitation, grid, [1.0])
    >>> abs(resolved.peak("amplitude").value / exact - 1.0) < 1e-3
    True
    >>> on_grid = forced_response(model, excitation, grid, [1.0], resolve=False)
    >>> round(on_grid.peak("amplitude").value / exact, 2)
    0.44
    """
    speeds = _check_speeds(speeds)
    orders = check_model_orders(model, excitation, orders)
    if not (math.isfinite(tolerance) and 0.0 < tolerance < 1.0):
        raise InputError("the tolerance must lie between 0 and 1", key="tolerance", value=tolerance)
    if dampers is None:
        dampers = getattr(model, "dampers", ()) or ()
    system_names = list(model.mass_names) + [d.name for d in dampers]
    pairs: list[tuple[int, int]]
    if relative is None:
        pairs = []
    else:
        pairs = []
        for a, b in relative:
            for name in (a, b):
                if name not in system_names:
                    raise InputError(
                        f'no mass named "{name}"{did_you_mean(name, system_names)}',
                        key="relative",
                        value=name,
                    )
            pairs.append((system_names.index(a), system_names.index(b)))
    # the excitation points are checked (cylinders on the masses, sources) before any solve
    forcing_notes(model, excitation, speeds[:1], orders)
    budget = RESPONSE_BLOCK_MEMORY if block_memory is None else block_memory
    if not (math.isfinite(budget) and budget > 0.0):
        raise InputError("the memory budget must be positive", key="block_memory", value=budget)
    sweep = Sweep(
        model, excitation, orders, dampers, hysteretic_frequency, pairs, modal_damping, budget
    )
    extra: dict[str, Any]
    notes: list[str]
    if not resolve:
        block = sweep.evaluate(speeds)
        extra = {"on_grid": freeze(np.ones(speeds.size), dtype=bool)}
        notes = []
    else:
        block, extra, notes = _resolved(sweep, speeds, tolerance)
    # notes of the cylinders' and sources' excitation over every evaluated speed
    notes = list(forcing_notes(model, excitation, block.speed, orders)) + notes
    result = sweep.result(block, notes=tuple(notes) or None, **extra)
    return result


def _resolved(
    sweep: Sweep, speeds: np.ndarray, tolerance: float
) -> tuple[_Block, dict[str, Any], list[str]]:
    """Evaluate the grid, the critical speeds and the resonance seeds, then refine until every
    peak is resolved (module :mod:`crankdyn.torsion.resolve`): (block, resolution fields,
    notes)."""
    grid, _ = merge_speeds(speeds)
    low, high = float(grid[0]), float(grid[-1])
    seeds, seed_reasons = (np.zeros(0), []) if grid.size < 2 else sweep.seeds(grid, low, high)
    start, first = merge_speeds(grid, seeds)
    reasons_all = [""] * grid.size + seed_reasons
    reason = [reasons_all[k] for k in first]
    block = sweep.evaluate(start)
    values, bounds = sweep._values(block)
    notes = []
    unbounded = getattr(sweep, "unbounded", [])
    if unbounded:
        listed = ", ".join(f"mode {r} x order {q:g} at {w * RPM:.1f} rpm" for r, q, w in unbounded)
        notes.append(
            f"undamped resonances (no damping acts on the mode: the steady response is unbounded "
            f"there; the peaks next to them are not refined): {listed}"
        )
    refiner = Refiner(
        block.speed,
        values,
        lambda top: sweep.scale_of(top, bounds),
        tolerance,
        exclude=[w for _, _, w in unbounded],
    )
    del values
    blocks = [block]
    reasons = list(reason)
    for _ in range(MAX_ROUNDS):
        new, column = refiner.request()
        if new.size == 0:
            break
        reasons += [f"refinement: peak of {sweep.describe(int(c), block)}" for c in column]
        more = sweep.evaluate(new)
        refiner.add(more.speed, sweep._values(more)[0])
        blocks.append(more)
    else:
        notes.append(
            f"the peaks were refined {MAX_ROUNDS} times and some are still not resolved to "
            f"{tolerance * 100:g} %"
        )
    del refiner
    block, first = _Block.joined(blocks)
    reason = [reasons[k] for k in first]
    on_grid = np.isin(block.speed, grid)
    added = np.flatnonzero(~on_grid)
    if added.size:
        notes.append(
            f"{added.size} speeds added to the grid (critical speeds and refinement around the "
            f"resonances) so that every peak is resolved to {tolerance * 100:g} %: see "
            "added_speeds"
        )
    extra = {
        "on_grid": freeze(on_grid, dtype=bool),
        "added_speeds": freeze(block.speed[added]),
        "added_reasons": tuple(reason[k] for k in added),
        "resolved": True,
        "tolerance": float(tolerance),
    }
    return block, extra, notes
