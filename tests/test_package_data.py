"""Every file of the built-in examples ships in the wheel: pyproject's package-data patterns
cover each of them (the design examples and the builder's harmonic table were left out once,
so `crankdyn design --list` failed on an installed wheel)."""

from __future__ import annotations

import tomllib
from pathlib import Path, PurePosixPath

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "src" / "crankdyn"


def test_every_example_file_is_package_data():
    patterns = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["tool"][
        "setuptools"
    ]["package-data"]["crankdyn"]
    files = [
        p.relative_to(PACKAGE).as_posix()
        for p in (PACKAGE / "examples").rglob("*")
        if p.is_file() and "__pycache__" not in p.parts and p.suffix != ".py"
    ]
    assert files

    def covered(name: str, pattern: str) -> bool:  # setuptools' glob: "*" stays in a folder
        path = PurePosixPath(name)
        return len(path.parts) == len(PurePosixPath(pattern).parts) and path.match(pattern)

    missing = [f for f in files if not any(covered(f, pat) for pat in patterns)]
    assert not missing, missing
