"""Write pytest's assertion-rewritten bytecode of the test modules once, on every core, before
the suite runs (`make test`).

pytest rewrites the assert statements of every test module and conftest.py it imports and
caches the result in __pycache__ only where bytecode may be written (not where
PYTHONDONTWRITEBYTECODE is set); each of `pytest -n 2`'s workers then rewrites all of them
again at collection (about 10 s of each worker's time on this suite). It reads the cached
files whatever that setting (checked against the source's hash and pytest's version), so they
are written here, as pytest writes them (its own functions, no configuration: the suite does
not enable the assertion pass hook). An optimisation only: where pytest's internals differ
(another version), nothing is written and the workers rewrite as before.

Usage: python scripts/rewrite-tests.py [FOLDER ...]  (default: tests)
"""

from __future__ import annotations

import os
import sys
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path


class _Quiet:
    """The assertion state's trace pytest's writer calls on a failure: ignored."""

    @staticmethod
    def trace(*_args: object) -> None:
        return None


def _write(path: str) -> bool:
    """Rewrite one module and write its cached bytecode where pytest looks for it."""
    try:
        from _pytest.assertion.rewrite import PYC_TAIL, _rewrite_test, _write_pyc, get_cache_dir
    except ImportError:
        return False
    fn = Path(os.path.abspath(path))  # as the import system names it (the code's file name)
    try:
        cache = get_cache_dir(fn)
        cache.mkdir(parents=True, exist_ok=True)
        source_hash, code = _rewrite_test(fn, None)  # no configuration: the defaults
        pyc = cache / (fn.name[:-3] + PYC_TAIL)
        return bool(_write_pyc(_Quiet(), code, source_hash, pyc))
    except (OSError, SyntaxError, TypeError, ValueError):
        return False


def main(folders: list[str]) -> int:
    files = sorted(
        str(p)
        for folder in folders
        for pattern in ("test_*.py", "*_test.py", "conftest.py")
        for p in Path(folder).rglob(pattern)
    )
    if not files:
        return 0
    with ProcessPoolExecutor(max_workers=min(len(files), os.cpu_count() or 1)) as pool:
        list(pool.map(_write, files, chunksize=8))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:] or ["tests"]))
