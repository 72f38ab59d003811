"""Case: the whole torsional vibration calculation as the number of masses grows (issue 37).

``crankdyn tvc FILE --no-pdf`` in a fresh process (:func:`bench.cases.process.run_process`: wall
time and peak resident set size) on the marine example (38 masses) and on the same line with its
two distributed shafts subdivided further (:mod:`bench.tvc_line`: 100, 300 and 1000 masses), each
timed in turn with the 38-mass line (interleaved: both under the same load). Targets: the time
grows no faster than N^1.2 from 38 to N masses (crankdyn at N within (N / 38)^1.2 times the
38-mass run), 1000 masses under 60 s; the peak memory is reported beside it (linear in N: within
N / 38 times the 38-mass run's). Each row notes the exponent of its pair, ln(t_N / t_38) /
ln(N / 38), and the exponent fitted by least squares to ln t against ln N over every size timed
so far (the last row: 38 to 1000 masses).

Agreement: every run exits 0 and writes summary.json with a verdict; the finer line's
natural frequencies converge to the coarse line's (the subdivision refines the shafts' own
modes, not the engine's): not checked here, the distributed shafts are tested in
tests/torsion. At the tiny size (the suite's run of the cases) there is no case: two whole
TVCs take longer than a test may; the command is tested in tests/cli and tests/tvc, the line
generator in tests/bench.
"""

from __future__ import annotations

import atexit
import json
import math
import shutil
import tempfile
from pathlib import Path

import numpy as np

from bench.cases.process import run_process
from bench.harness import CRANKDYN, AgreementError, Case, Contender, Deviation, Target
from bench.tvc_line import write_line

KEY = "tvc_scaling"
TITLE = "TVC (crankdyn tvc --no-pdf) against the number of masses"
SIZES: dict[str, tuple[int, ...]] = {"full": (100, 300, 1000), "tiny": ()}  # tiny: none
BASE = 38
EXPONENT = 1.2


def _runs_ok(runs: list[dict], folders: list[Path]) -> None:
    for r in runs:
        if r["status"] != 0:
            raise AgreementError(f"crankdyn tvc failed (status {r['status']}): {r['err'][-400:]}")
    for folder in folders:
        summary = json.loads((folder / "summary.json").read_text(encoding="utf-8"))
        if "status" not in summary:
            raise AgreementError(f"{folder}: summary.json has no status")


def exponents(times: dict[int, list[float]], base: int, big: int) -> tuple[float, float]:
    """(exponent of the pair base-big, exponent fitted to every size) of the median wall times
    ``times`` {masses: [s, ...]}: ln(t_big / t_base) / ln(big / base), and the slope of the
    least-squares line through (ln N, ln median t)."""
    median = {n: float(np.median(t)) for n, t in times.items() if t}
    pair = math.log(median[big] / median[base]) / math.log(big / base)
    sizes = sorted(median)
    slope = float(np.polyfit(np.log(sizes), np.log([median[n] for n in sizes]), 1)[0])
    return pair, slope


def cases(size: str = "full") -> list[Case]:
    scratch = Path(tempfile.mkdtemp(prefix="crankdyn-bench-tvc-"))
    atexit.register(shutil.rmtree, scratch, True)
    base_file, base_n = write_line(scratch / "base", BASE)
    times: dict[int, list[float]] = {}  # masses -> wall times of every run (the exponent fit)
    out = []
    for n in SIZES[size]:
        big_file, big_n = write_line(scratch / f"n{n}", n)
        base_label = f"crankdyn tvc, {base_n}-mass line"
        mine: list[dict] = []
        base: list[dict] = []
        folders = [scratch / f"out{n}", scratch / f"out{n}-base"]

        def run(file: Path, folder: Path, runs: list[dict], masses: int) -> dict:
            # --no-fail: the marine line fails its clutch-in by design (exit 1, report written)
            args = ["crankdyn", "tvc", str(file), "--no-pdf", "--no-fail", "-o", str(folder)]
            args.append("--force")
            found = run_process(args, runs)
            times.setdefault(masses, []).append(found["wall"])
            return found

        def check(
            _outputs, mine=mine, base=base, folders=folders, label=base_label
        ) -> dict[str, Deviation]:
            _runs_ok(mine + base, folders)
            return {label: Deviation(0.0, 0.0, "both exit 0 with a verdict")}

        def memory(_output, mine=mine, base=base, big_n=big_n) -> dict:
            peak, peak_base = max(r["rss_mb"] for r in mine), max(r["rss_mb"] for r in base)
            limit = peak_base * big_n / base_n
            pair, fitted = exponents(times, base_n, big_n)
            sizes = sorted(times)
            note = f"exponent {pair:.2f}; fitted {sizes[0]}-{sizes[-1]}: {fitted:.2f}"
            return {
                "peak_rss_mb": peak,
                "memory_target_mb": limit,
                "memory_ok": peak < limit,
                "exponent": pair,
                "fitted_exponent": fitted,
                "note": note,
            }

        targets = [
            Target(base_label, (base_n / big_n) ** EXPONENT, f"time within (N/{base_n})^1.2")
        ]
        if big_n >= 1000:
            targets.append(Target(None, 0.0, "under 60 s", 60.0))
        out.append(
            Case(
                key=KEY,
                title=TITLE,
                size=f"{big_n} masses against {base_n}",
                contenders=(
                    Contender(
                        CRANKDYN,
                        lambda f=big_file, o=folders[0], r=mine, k=big_n: run(f, o, r, k),
                    ),
                    Contender(
                        base_label, lambda o=folders[1], r=base: run(base_file, o, r, base_n)
                    ),
                ),
                check=check,
                targets=tuple(targets),
                repeats=1 if size == "full" else 0,
                extra=memory,
                interleave=True,
            )
        )
    return out
