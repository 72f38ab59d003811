"""Cases: what a user runs, the whole process (issue 16).

Every contender is a fresh process (``python -m bench.peak FILE MODULE ARGS``, which records the
process's peak resident set size, see :mod:`bench.peak`): interpreter start-up, imports, the
work and the writing are all inside the wall time. The bytecode cache is on (as in an
installed package), warmed by the warm-up call.

- ``crankdyn --help`` against ``python -c "import numpy, click"``: the start-up (target within
  3x);
- ``crankdyn kinematics vaz2108`` against a process importing numpy and click and running the
  same analysis without the command line (target within 2x);
- ``crankdyn torsion modes`` of a free chain of 1000 masses (the chain of the modes case), as a
  table and as JSON, against :mod:`bench.opentorsion_modes` (openTorsion parsing the same
  file, solving and writing compact JSON; target 2x faster, crankdyn under 300 MB); the JSON
  files agree to 1e-9 in the elastic frequencies;
- ``crankdyn torsion modes`` of a 10,000-mass chain, the table (it lists the lowest modes and
  says what it leaves out) against a bare process reading the file with tomllib and solving
  the 20 lowest modes by bisection (issue 37 item 4: within 3x), under 1 GB; the table's
  frequencies agree with the bare solve's to its five digits.
"""

from __future__ import annotations

import atexit
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from bench.harness import CRANKDYN, AgreementError, Case, Contender, Deviation, Target

KEY = "process"
TITLE = "Whole process"
ROOT = Path(__file__).resolve().parents[2]
IMPORTS = "python -c 'import numpy, click'"
KINEMATICS_BARE = "import numpy, click + the analysis"
OPENTORSION = "openTorsion script (parse, solve, write JSON)"
ANALYSIS = (
    "import numpy, click\n"
    "from crankdyn.io.catalogue import resolve_engine\n"
    "from crankdyn.session import Analysis\n"
    "result = Analysis(resolve_engine('vaz2108')).kinematics()\n"
    "print(len(result.columns()))\n"
)


def run_process(
    module_args: list[str], runs: list[dict] | None = None, *, env: dict[str, str] | None = None
) -> dict:
    """One fresh process ``python -m bench.peak <file> *module_args``: wall time (s), peak RSS
    (MB), status, standard output and error; ``env`` is added to the environment (e.g. a
    ``PYTHONPATH`` that puts another version of crankdyn first)."""
    with tempfile.TemporaryDirectory() as scratch:
        peak_file = Path(scratch) / "peak"
        argv = [sys.executable, "-m", "bench.peak", str(peak_file), *module_args]
        env = {**os.environ, "COLUMNS": "120", **(env or {})}
        env.pop("PYTHONDONTWRITEBYTECODE", None)  # as installed: bytecode cached
        start = time.perf_counter()
        proc = subprocess.run(argv, capture_output=True, text=True, env=env, cwd=ROOT, check=False)
        wall = time.perf_counter() - start
        peak = float(peak_file.read_text()) if peak_file.exists() else float("nan")
    out = {"wall": wall, "rss_mb": peak, "status": proc.returncode, "out": proc.stdout}
    out["err"] = proc.stderr
    if runs is not None:
        runs.append(out)
    return out


def _python(code: str) -> list[str]:
    """module_args running ``code`` (``python -c`` through runpy: a module of our own)."""
    return ["bench.cases.process", code]


def write_chain(path: Path, n: int) -> Path:
    """The modes case's free chain of ``n`` masses as a crankdyn model file (compact TOML)."""
    from bench.cases.chain_modes import chain_values

    inertia, stiffness = chain_values(n)
    masses = ",\n".join(f'{{name="m{i}",inertia={j!r}}}' for i, j in enumerate(inertia.tolist()))
    shafts = ",\n".join(
        f'{{between=["m{i}","m{i + 1}"],stiffness={k!r}}}' for i, k in enumerate(stiffness.tolist())
    )
    path.write_text(
        f'name = "chain {n}"\nmass = [\n{masses}\n]\nshaft = [\n{shafts}\n]\n', encoding="utf-8"
    )
    return path


def _ok(runs: list[dict], what: str, peer: str | None = None) -> dict[str, Deviation]:
    """Every run exited 0 (else AgreementError); the peer's 'deviation': none, both ran."""
    for r in runs:
        if r["status"] != 0:
            raise AgreementError(f"{what} failed (status {r['status']}): {r['err'].strip()[-400:]}")
    return {} if peer is None else {peer: Deviation(0.0, 0.0, "both processes exit 0")}


def _memory(runs: list[dict], target: float):
    def extra(_output) -> dict:
        peak = max(r["rss_mb"] for r in runs)
        return {"peak_rss_mb": peak, "memory_target_mb": target, "memory_ok": peak < target}

    return extra


def cases(size: str = "full") -> list[Case]:
    scratch = Path(tempfile.mkdtemp(prefix="crankdyn-bench-process-"))
    atexit.register(shutil.rmtree, scratch, True)
    repeats = 5 if size == "full" else 0
    out = []

    mine: list[dict] = []
    peer: list[dict] = []
    out.append(
        Case(
            key=KEY,
            title=TITLE,
            size="crankdyn --help",
            contenders=(
                Contender(CRANKDYN, lambda: run_process(["crankdyn", "--help"], mine)),
                Contender(IMPORTS, lambda: run_process(_python("import numpy, click"), peer)),
            ),
            check=lambda _o: _ok(mine + peer, "crankdyn --help", IMPORTS),
            targets=(Target(IMPORTS, 1 / 3, "within 3x of it"),),
            repeats=repeats,
            interleave=True,  # a ratio to the bare start-up: both under the same load
        )
    )

    mine_k: list[dict] = []
    peer_k: list[dict] = []
    out.append(
        Case(
            key=KEY,
            title=TITLE,
            size="crankdyn kinematics vaz2108",
            contenders=(
                Contender(
                    CRANKDYN, lambda: run_process(["crankdyn", "kinematics", "vaz2108"], mine_k)
                ),
                Contender(KINEMATICS_BARE, lambda: run_process(_python(ANALYSIS), peer_k)),
            ),
            check=lambda _o: _ok(mine_k + peer_k, "crankdyn kinematics", KINEMATICS_BARE),
            targets=(Target(KINEMATICS_BARE, 0.5, "within 2x of it"),),
            repeats=repeats,
            interleave=True,  # a ratio to the bare analysis: both under the same load
        )
    )

    n = 1000 if size == "full" else 40
    model = write_chain(scratch / f"chain{n}.toml", n)
    ot_json = scratch / "opentorsion.json"
    try:
        import opentorsion  # noqa: F401

        ot_missing = None
    except ImportError:
        ot_missing = "opentorsion not installed"
    for fmt in ("table", "json"):
        runs: list[dict] = []
        ot_runs: list[dict] = []
        mine_json = scratch / f"crankdyn-{fmt}.out"
        args = ["crankdyn", "torsion", "modes", str(model), "--format", fmt, "-o", str(mine_json)]

        def check(_outputs, fmt=fmt, runs=runs, ot_runs=ot_runs, mine_json=mine_json) -> dict:
            both = _ok(runs + ot_runs, f"torsion modes --format {fmt}", OPENTORSION)
            if not ot_runs:
                return {}
            if fmt != "json":
                return both
            a = np.asarray(json.loads(mine_json.read_text())["natural_frequencies_hz"])
            b = np.asarray(json.loads(ot_json.read_text())["natural_frequencies_hz"])
            dev = float(np.max(np.abs(a[1:] - b[1:]) / a[1:]))
            return {OPENTORSION: Deviation(dev, 1e-9, "relative, natural frequencies")}

        out.append(
            Case(
                key=KEY,
                title=TITLE,
                size=f"crankdyn torsion modes, {n}-mass chain, --format {fmt}",
                contenders=(
                    Contender(CRANKDYN, lambda a=args, r=runs: run_process([*a, "--force"], r)),
                    Contender(
                        OPENTORSION,
                        None
                        if ot_missing
                        else lambda r=ot_runs: run_process(
                            ["bench.opentorsion_modes", str(model), str(ot_json)], r
                        ),
                        missing=ot_missing,
                    ),
                ),
                check=check,
                targets=(Target(OPENTORSION, 2.0, ">= 2x faster (and < 300 MB)"),),
                repeats=3 if size == "full" else 0,
                extra=_memory(runs, 300.0),
            )
        )

    big = 10_000 if size == "full" else 60
    big_model = write_chain(scratch / f"chain{big}.toml", big)
    big_runs: list[dict] = []
    bare_runs: list[dict] = []

    def big_check(_outputs) -> dict:
        _ok(big_runs + bare_runs, "torsion modes (large chain)")
        if not all("are not listed" in " ".join(r["out"].split()) for r in big_runs):
            raise AgreementError("the large chain's table does not say what it leaves out")
        if not bare_runs:
            return {}
        theirs = np.array(json.loads(bare_runs[-1]["out"]))
        mine = _table_frequencies(big_runs[-1]["out"], theirs.size)
        dev = float(np.max(np.abs(mine[1:] - theirs[1:]) / theirs[1:]))
        return {PARTIAL_BARE: Deviation(dev, 1e-4, "relative, the table's 5 digits")}

    out.append(
        Case(
            key=KEY,
            title=TITLE,
            size=f"crankdyn torsion modes, {big}-mass chain, table",
            contenders=(
                Contender(
                    CRANKDYN,
                    lambda: run_process(["crankdyn", "torsion", "modes", str(big_model)], big_runs),
                ),
                Contender(
                    PARTIAL_BARE,
                    lambda: run_process(
                        _python(PARTIAL_SOLVE.format(path=str(big_model))), bare_runs
                    ),
                ),
            ),
            check=big_check,
            targets=(Target(PARTIAL_BARE, 1 / 3, "within 3x of it (and < 1 GB)"),),
            repeats=3 if size == "full" else 0,
            extra=_memory(big_runs, 1024.0),
            interleave=True,  # a ratio to the bare process: both under the same load
        )
    )
    return out


PARTIAL_BARE = "tomllib + the 20 lowest modes by bisection (bare)"
PARTIAL_SOLVE = (
    "import json, tomllib\n"
    "import numpy as np, scipy.linalg\n"
    "with open({path!r}, 'rb') as f:\n"
    "    data = tomllib.load(f)\n"
    "j = np.array([m['inertia'] for m in data['mass']], dtype=float)\n"
    "k = np.array([s['stiffness'] for s in data['shaft']], dtype=float)\n"
    "s = np.sqrt(j)\n"
    "d = np.zeros(j.size)\n"
    "d[:-1] += k\n"
    "d[1:] += k\n"
    "lam, u = scipy.linalg.eigh_tridiagonal(d / j, -k / (s[:-1] * s[1:]), select='i',\n"
    "    select_range=(0, 19), lapack_driver='stebz')\n"
    "u /= s[:, None]\n"
    "u /= np.max(np.abs(u), axis=0)\n"
    "print(json.dumps((np.sqrt(np.abs(lam)) / (2 * np.pi)).tolist()))\n"
)
"""The least a program does for the lowest modes of a chain model file: read it (tomllib), the
mass-normalised tridiagonal matrix, the 20 lowest eigenpairs by bisection and inverse iteration
(LAPACK ``dstebz`` and ``dstein``), the shapes normalised, the frequencies printed."""


def _table_frequencies(text: str, count: int) -> np.ndarray:
    """The first ``count`` frequencies (Hz) of the modes table in ``crankdyn torsion modes``'s
    output (the rows numbered 0, 1, ...: the second column, its unit in the header)."""
    scale = 1.0
    values: list[float] = []
    for line in text.splitlines():
        if "Frequency (" in line and not values:
            unit = line.split("Frequency (", 1)[1].split(")", 1)[0]
            scale = {"Hz": 1.0, "mHz": 1e-3, "kHz": 1e3}.get(unit, 1.0)
        cells = [c.strip() for c in line.strip("│").split("│")]
        if len(cells) > 2 and cells[0].isdigit() and int(cells[0]) == len(values):
            values.append(float(cells[1]) * scale)
        if len(values) == count:
            break
    return np.array(values)


if __name__ == "__main__":  # the peer processes: ``python -m bench.cases.process CODE``
    exec(compile(sys.argv[1], "<bench>", "exec"))
