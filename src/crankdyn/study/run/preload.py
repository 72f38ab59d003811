"""Warm-up for the local pool's fork server: imported by the server before it forks the
workers, so that each worker starts with the analyses imported and the unit registry built (a
second and more of work that every worker would otherwise repeat)."""

from __future__ import annotations

from crankdyn.io.units import registry

registry()
