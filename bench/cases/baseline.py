"""Cases: the whole process against the version before issue 16 (old and new in one run).

Issue 16's report targets are ratios against the code of the day it was filed: ``crankdyn
analyze inline6-diesel`` (the demo engine's report: every analysis, the HTML page, its plots,
CSV and JSON) within 0.4x of the old version's whole process and under 250 MB, and ``crankdyn
study inline4-rod-and-firing`` (the built-in 30-case study with its HTML summary) within 0.5x.

The old version is main at :data:`BASELINE`, the commit main pointed to just before the first
of issue 16's speed work landed on it (main's reflog: ``b8f28ce``, the merge of the analysis
session, then ``cd14851``, the linkspeed merge; the start-up, large-model, forced-response and
report work, ``2ae2db5`` to ``63310b8``, landed after it). ``git log --first-parent main``
does not show that line: main was later fast-forwarded to a branch that had merged main into
itself, so its first parents run through that branch's commits; ``b8f28ce`` is an ancestor of
main all the same, so a clone of main has it. Its ``src`` is extracted once per run (``git
archive``) into a temporary folder and run as ``python -m crankdyn ...`` with ``PYTHONPATH``
set to that folder's ``src``, in the same environment as the new version (the bench's own:
numpy, scipy, matplotlib, pint, click, rich, and pyarrow and Dask from the ``studies`` extra,
which the old study needs as the new one does). Without git or without that commit (a shallow
clone, an unpacked sdist) the old side is reported as not measured.

Both sides are fresh processes (:func:`bench.cases.process.run_process`: peak RSS as VmHWM of
the command's own process; the plot pool's workers are separate processes and not included),
timed in turn (interleaved rounds, :class:`bench.harness.Case` ``interleave``), medians.

Agreement: both exit 0 and write their report (``index.html``, ``summary.json``) or study
(``results.csv``, ``summary/index.html``), and quantities whose meaning did not change between
the versions agree to 1e-9 relative: of the report's key figures the mean indicated torque, the
indicated work, the peak pressure, the largest gas force, the firing intervals and the firing
order's rank, the flywheel inertia and the first two natural frequencies (the old report's
other peaks were not resolved, so they may differ); of the study every case's figures in
``results.csv`` (mean torque, torque non-uniformity, largest main-bearing, crank-pin and side
force, largest piston acceleration), matched by case id.
"""

from __future__ import annotations

import atexit
import csv
import io
import json
import math
import shutil
import subprocess
import tarfile
import tempfile
from pathlib import Path

from bench.cases.process import ROOT, TITLE, _memory, run_process
from bench.harness import CRANKDYN, AgreementError, Case, Contender, Deviation, Target

KEY = "baseline"
BASELINE = "b8f28ce7306c2e1d8a77b04e224512c3a0b6d894"
"""main just before issue 16's speed work landed (module docstring)."""
OLD = f"crankdyn before issue 16 ({BASELINE[:7]})"
ENGINE = "inline6-diesel"
STUDY = "inline4-rod-and-firing"
REPORT_FIGURES = (
    "mean_torque_Nm",
    "indicated_work_J",
    "peak_pressure_Pa",
    "max_gas_force_N",
    "firing_intervals_deg",
    "firing_order_rank",
    "flywheel_inertia_kgm2",
    "natural_frequency_1_hz",
    "natural_frequency_2_hz",
)
"""Key figures of the report (summary.json) whose meaning is the same in both versions (by
their names in the old version: :data:`RENAMED`)."""
RENAMED = {"firing_order_rank": "engine_rank"}
"""Old key figure name -> its name now (issue 31's one summary renamed the engine's firing
order's rank; the same number)."""
STUDY_FIGURES = (
    "mean_torque_Nm",
    "torque_nonuniformity",
    "max_main_bearing_load_N",
    "max_crank_pin_load_N",
    "max_side_force_N",
    "max_piston_acceleration_m_s2",
)
"""Columns of the study's results.csv compared case by case."""
TOLERANCE = 1e-9


def extract_baseline(into: Path) -> tuple[Path | None, str | None]:
    """The old version's ``src`` folder, extracted from git into ``into``: (path, None), or
    (None, why not) when git or the commit is not available."""
    try:
        proc = subprocess.run(
            ["git", "-C", str(ROOT), "archive", "--format=tar", BASELINE, "src"],
            capture_output=True,
            check=False,
        )
    except OSError as exc:
        return None, f"git not available ({exc.strerror})"
    if proc.returncode != 0:
        return None, f"commit {BASELINE[:7]} not in this clone's history"
    with tarfile.open(fileobj=io.BytesIO(proc.stdout)) as archive:
        archive.extractall(into, filter="data")
    return into / "src", None


def _relative(a, b) -> float:
    """Largest relative difference of two numbers or lists of numbers."""
    a = a if isinstance(a, list) else [a]
    b = b if isinstance(b, list) else [b]
    if len(a) != len(b):
        return math.inf
    return max(
        (abs(float(x) - float(y)) / (abs(float(y)) or 1.0) for x, y in zip(a, b, strict=True)),
        default=0.0,
    )


def report_deviation(new: Path, old: Path) -> float:
    """Largest relative difference of :data:`REPORT_FIGURES` between two report folders."""
    figures = []
    for folder in (new, old):
        path = folder / "summary.json"
        if not (folder / "index.html").is_file() or not path.is_file():
            raise AgreementError(f"{folder}: no index.html or summary.json")
        figures.append(json.loads(path.read_text(encoding="utf-8"))["key_figures"])
    mine, theirs = figures
    pairs = [(RENAMED.get(k, k), k) for k in REPORT_FIGURES]
    missing = [k for k, t in pairs if k not in mine or t not in theirs]
    if missing:
        raise AgreementError(f"key figures missing from a summary.json: {', '.join(missing)}")
    return max(_relative(mine[k], theirs[t]) for k, t in pairs)


def study_deviation(new: Path, old: Path) -> float:
    """Largest relative difference of :data:`STUDY_FIGURES` between two study folders, case
    by case."""
    tables = []
    for folder in (new, old):
        path = folder / "results.csv"
        if not path.is_file() or not (folder / "summary" / "index.html").is_file():
            raise AgreementError(f"{folder}: no results.csv or summary/index.html")
        with path.open(encoding="utf-8", newline="") as f:
            tables.append({row["case_id"]: row for row in csv.DictReader(f)})
    mine, theirs = tables
    if set(mine) != set(theirs) or not mine:
        raise AgreementError("the two studies ran different cases")
    if any(row["status"] != "ok" for table in tables for row in table.values()):
        raise AgreementError("a study case failed")
    return max(
        _relative(float(mine[c][k]), float(theirs[c][k])) for c in mine for k in STUDY_FIGURES
    )


def cases(size: str = "full") -> list[Case]:
    scratch = Path(tempfile.mkdtemp(prefix="crankdyn-bench-baseline-"))
    atexit.register(shutil.rmtree, scratch, True)
    old_src, missing = extract_baseline(scratch / "baseline")
    old_env = None if old_src is None else {"PYTHONPATH": str(old_src)}
    full = size == "full"
    out = []

    def pair(label: str, command: list[str], compare, target: Target, memory: float | None):
        runs: list[dict] = []
        old_runs: list[dict] = []
        new_dir, old_dir = scratch / f"{label}-new", scratch / f"{label}-old"

        def check(_outputs) -> dict[str, Deviation]:
            for r in runs + old_runs:
                if r["status"] != 0:
                    raise AgreementError(
                        f"{label} failed (status {r['status']}): {r['err'].strip()[-400:]}"
                    )
            if not old_runs:
                return {}
            if compare is None:
                return {OLD: Deviation(0.0, 0.0, "both processes exit 0")}
            return {OLD: Deviation(compare(new_dir, old_dir), TOLERANCE, "relative, key figures")}

        def extra(_output) -> dict:
            figures = {} if memory is None else _memory(runs, memory)(None)
            if old_runs:
                figures["peer_peak_rss_mb"] = {OLD: max(r["rss_mb"] for r in old_runs)}
            return figures

        def args(folder: Path) -> list[str]:
            written = [] if compare is None else ["-o", str(folder), "--force"]
            return ["crankdyn", *command, *written]

        def new_run() -> dict:
            return run_process(args(new_dir), runs)

        def old_run() -> dict:
            return run_process(args(old_dir), old_runs, env=old_env)

        return Case(
            key=KEY,
            title=TITLE,
            size=f"crankdyn {' '.join(command)}, against the version before issue 16",
            contenders=(
                Contender(CRANKDYN, new_run),
                Contender(OLD, None if missing else old_run, missing=missing),
            ),
            check=check,
            targets=(target,),
            repeats=5 if full else 0,
            extra=extra,
            interleave=True,
        )

    if full:
        out.append(
            pair(
                "analyze",
                ["analyze", ENGINE],
                report_deviation,
                Target(OLD, 2.5, "<= 0.4x of the baseline (and < 250 MB)"),
                250.0,
            )
        )
        out.append(
            pair(
                "study",
                ["study", STUDY],
                study_deviation,
                Target(OLD, 2.0, "<= 0.5x of the baseline"),
                None,
            )
        )
    else:  # the tests' smoke run: the extraction and both versions' start, on a quick command
        out.append(
            pair(
                "kinematics",
                ["kinematics", "vaz2108"],
                None,
                Target(OLD, 0.0, "runs"),
                None,
            )
        )
    return out
