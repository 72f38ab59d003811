"""The harmonic torques of an event run (crankdyn.torsion.event_line.Harmonics), computed on
the degrees of freedom that carry one only: the same as the sum over orders written out for
every degree of freedom, Re sum_q F_q(Omega) e^{i q phi} with F interpolated linearly between
the grid's speeds; zero where no torque acts."""

from __future__ import annotations

import numpy as np

from crankdyn.torsion.event_line import Harmonics


def _written_out(grid, forcing, orders, speed, angle):
    out = np.zeros((speed.size, forcing.shape[2]))
    for i, (w, phi) in enumerate(zip(speed, angle, strict=True)):
        if grid.size == 1:
            f = forcing[0]
        else:
            c = min(int(np.searchsorted(grid, w, side="right")) - 1, grid.size - 2)
            c = max(c, 0)
            t = (w - grid[c]) / (grid[c + 1] - grid[c])
            f = (1.0 - t) * forcing[c] + t * forcing[c + 1]
        for q, row in zip(orders, f, strict=True):
            out[i] += (row * np.exp(1j * q * phi)).real
    return out


def test_only_the_excited_degrees_of_freedom_are_computed_and_the_torques_are_the_sum():
    rng = np.random.default_rng(4)
    grid, orders = np.linspace(20.0, 80.0, 7), np.arange(1, 13) * 0.5
    forcing = np.zeros((grid.size, orders.size, 40), dtype=complex)
    excited = [0, 5, 6, 39]
    forcing[:, :, excited] = rng.normal(size=(grid.size, orders.size, 4)) + 1j * rng.normal(
        size=(grid.size, orders.size, 4)
    )
    h = Harmonics(grid, forcing, orders)
    assert h.excited.tolist() == excited
    speed = rng.uniform(20.0, 80.0, 300)
    angle = rng.uniform(0.0, 40.0, 300)
    got = h(speed, angle)
    expected = _written_out(grid, forcing, orders, speed, angle)
    scale = np.abs(forcing).sum(axis=1).max()
    assert np.max(np.abs(got - expected)) <= 1e-13 * scale
    others = np.setdiff1d(np.arange(40), excited)
    assert np.all(got[:, others] == 0.0)


def test_one_speed():
    forcing = np.zeros((1, 2, 3), dtype=complex)
    forcing[0, :, 1] = [2.0, 1.0j]
    h = Harmonics(np.array([50.0]), forcing, np.array([1.0, 2.0]))
    got = h(np.array([50.0, 50.0]), np.array([0.0, np.pi / 4]))
    # 2 cos(phi) - sin(2 phi)
    assert np.allclose(got[:, 1], [2.0, 2.0 * np.cos(np.pi / 4) - 1.0], rtol=0, atol=1e-15)
    assert np.all(got[:, [0, 2]] == 0.0)
