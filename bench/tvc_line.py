"""The marine example's TVC input scaled to N masses (the benchmark's TVC cases).

The example (``crankdyn example marine-propulsion``: engine, damper, elastic coupling, gearbox,
subdivided intermediate and propeller shafts) is copied into a folder with its shaft line's
``max_frequency`` (the frequency up to which the two distributed shafts are subdivided, to
0.1 %: :func:`crankdyn.torsion.distributed.element_count`) raised until the line has the
number of masses asked for, so that the line grows where a finer model of a real line grows:
in its shafts, the engine, couplings and checks unchanged.
"""

from __future__ import annotations

import re
from importlib import resources
from pathlib import Path

__all__ = ["mass_count", "write_line"]

SHAFT_LINE = "marine-shaft-line.toml"


def _copy(folder: Path, frequency_hz: float) -> Path:
    examples = resources.files("crankdyn.examples")
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "torsion").mkdir(exist_ok=True)
    for name in ("marine-propulsion.toml", "marine-propeller-law-load.csv"):
        (folder / name).write_bytes(examples.joinpath(name).read_bytes())
    text = examples.joinpath("torsion").joinpath(SHAFT_LINE).read_text(encoding="utf-8")
    text = re.sub(r'max_frequency = "[^"]*"', f'max_frequency = "{frequency_hz:.6g} Hz"', text)
    (folder / "torsion" / SHAFT_LINE).write_text(text, encoding="utf-8")
    return folder / "marine-propulsion.toml"


def mass_count(path: Path) -> int:
    """The number of masses of the TVC's model of the engine file ``path``."""
    from crankdyn.io.catalogue import resolve_model_and_engine

    model, _ = resolve_model_and_engine(str(path))
    return len(model.masses)


def write_line(folder: Path, masses: int) -> tuple[Path, int]:
    """The engine file of the marine example with ``masses`` to ``masses + 2`` masses (the
    subdivision frequency found by bisection on the count, which grows with it) and its mass
    count."""
    low, high = 1.0, 150.0
    count = mass_count(_copy(folder, high))
    while count < masses:
        low, high = high, high * 2.0
        count = mass_count(_copy(folder, high))
    while count > masses + 2 and high - low > 1e-3 * high:  # within a few masses
        mid = 0.5 * (low + high)
        found = mass_count(_copy(folder, mid))
        if found >= masses:
            high, count = mid, found
        else:
            low = mid
    path = _copy(folder, high)
    return path, mass_count(path)


if __name__ == "__main__":  # pragma: no cover - a helper for trying sizes by hand
    import sys

    out, count = write_line(Path(sys.argv[1]), int(sys.argv[2]))
    print(out, count)
