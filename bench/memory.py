"""Peak memory of one analysis, measured in a fresh process.

``python -m bench.memory PROBE`` runs one probe (imports, then the analysis) and prints a JSON
line: the process's peak resident set size (``VmHWM`` of /proc/self/status, see
:mod:`bench.peak`: the interpreter, numpy, scipy and crankdyn's imports included), the same after
the imports alone, and the peak of Python-tracked allocations during the analysis
(``tracemalloc``, which numpy's array buffers report to). :func:`measure` runs a probe that way
from the benchmark.
"""

from __future__ import annotations

import json
import subprocess
import sys
import tracemalloc
from pathlib import Path

__all__ = ["PROBES", "measure"]


def _chain(n: int):
    from bench.cases.chain_modes import chain_values, crankdyn_modes

    inertia, stiffness = chain_values(n)
    return lambda: crankdyn_modes(inertia, stiffness)


def _sixbar(n: int):

    from bench.cases.sixbar import ALPHA, OMEGA, crank_angles, mechanism

    mech = mechanism()
    theta = crank_angles(n)
    return lambda: mech.motion(theta, OMEGA, ALPHA)


def _response(bare: bool, which: str | None = None, speeds: int = 20000, orders: int = 48):
    import numpy as np

    from bench.bare import thomas
    from bench.cases.forced_response import MODEL, limit_problem
    from crankdyn.torsion.solvers import steady_state

    model, omega, forcing = limit_problem(which or MODEL, speeds, orders)
    if bare:
        chain = model.chain
        flat = omega.reshape(-1)
        return lambda: thomas(
            chain.inertia, chain.stiffness, chain.damping, chain.ground_damping, flat, forcing
        )
    full = np.broadcast_to(forcing, (*omega.shape, forcing.size))
    return lambda: steady_state(model, omega, full)


PROBES = {
    "chain-1000": (
        "natural frequencies and mode shapes, free chain N = 1000",
        lambda: _chain(1000),
    ),
    "chain-40": ("natural frequencies and mode shapes, free chain N = 40", lambda: _chain(40)),
    "response-9x20000x48": (
        "forced response, 9 masses x 20000 speeds x 48 orders (crankdyn steady_state)",
        lambda: _response(False),
    ),
    "thomas-9x20000x48": (
        "the same by the bare in-place Thomas elimination (bench/bare.py)",
        lambda: _response(True),
    ),
    "response-200x5501x24": (
        "forced response, 200 masses x 5501 speeds x 24 orders (crankdyn steady_state)",
        lambda: _response(False, "chain-200", 5501, 24),
    ),
    "thomas-200x5501x24": (
        "the same by the bare in-place Thomas elimination (bench/bare.py)",
        lambda: _response(True, "chain-200", 5501, 24),
    ),
    "response-10000x101x12": (
        "forced response, 10,000 masses x 101 speeds x 12 orders (crankdyn steady_state)",
        lambda: _response(False, "chain-10000", 101, 12),
    ),
    "thomas-10000x101x12": (
        "the same by the bare in-place Thomas elimination (bench/bare.py)",
        lambda: _response(True, "chain-10000", 101, 12),
    ),
    "sixbar-360k": (
        "six-bar (conveyor-seed004) kinematics, 360,000 crank angles",
        lambda: _sixbar(360_000),
    ),
}


def _rss_mb() -> float:
    from bench.peak import peak_rss_mb

    return peak_rss_mb()


def main(argv: list[str]) -> int:
    name = argv[0]
    _what, prepare = PROBES[name]
    run = prepare()  # imports and inputs
    after_imports = _rss_mb()
    tracemalloc.start()
    result = run()
    _current, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    del result
    print(
        json.dumps(
            {
                "probe": name,
                "peak_rss_mb": _rss_mb(),
                "imports_rss_mb": after_imports,
                "traced_peak_mb": peak / 2**20,
            }
        )
    )
    return 0


def measure(name: str) -> dict:
    """Run probe ``name`` in a fresh interpreter; its figures (MB)."""
    proc = subprocess.run(
        [sys.executable, "-m", "bench.memory", name],
        capture_output=True,
        text=True,
        check=False,
        cwd=Path(__file__).resolve().parents[1],
    )
    if proc.returncode != 0:
        raise RuntimeError(f"memory probe {name} failed: {proc.stderr.strip()[-500:]}")
    figures = json.loads(proc.stdout.strip().splitlines()[-1])
    figures["what"] = PROBES[name][0]
    return figures


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
