"""Case: ``crankdyn analyze`` on the demo engine, the whole process.

``python -m crankdyn analyze inline6-diesel --out <temporary folder> --force`` (the built-in
inline-6 diesel of ``crankdyn demo``: every analysis that applies, the HTML report with its plots,
CSV and JSON data) in a fresh process each time: interpreter start-up, imports, analyses, plots
and writing are all inside the wall time. Peak memory is the process's maximum resident set
size (VmHWM, written by :mod:`bench.peak` as the process ends). Targets: under
10 s and under 500 MB. No peer: crankdyn's report has no counterpart in the peer libraries.
"""

from __future__ import annotations

import atexit
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from bench.harness import CRANKDYN, AgreementError, Case, Contender, Target

KEY = "analyze"
TITLE = "crankdyn analyze on the demo engine (whole process)"
ENGINE = "inline6-diesel"
SECONDS = 10.0
MEGABYTES = 500.0


def analyze_once(out_dir: Path, command: tuple[str, ...] | None = None) -> dict:
    """One whole-process run of ``crankdyn analyze`` (or of ``crankdyn *command``): wall time
    (s), peak RSS (MB), status.

    The process is ``python -m bench.peak <file> crankdyn analyze ...``: ``python -m crankdyn``
    with its peak resident set size (VmHWM) written to a file at exit (:mod:`bench.peak`)."""
    root = Path(__file__).resolve().parents[2]
    with tempfile.TemporaryDirectory() as scratch:
        peak_file = Path(scratch) / "peak"
        argv = [
            sys.executable,
            "-m",
            "bench.peak",
            str(peak_file),
            "crankdyn",
            *(command or ("analyze", ENGINE, "--out", str(out_dir), "--force")),
        ]
        env = {**os.environ, "COLUMNS": "120"}
        start = time.perf_counter()
        proc = subprocess.run(argv, capture_output=True, text=True, env=env, cwd=root, check=False)
        wall = time.perf_counter() - start
        peak = float(peak_file.read_text()) if peak_file.exists() else float("nan")
    return {
        "wall": wall,
        "rss_mb": peak,
        "status": proc.returncode,
        "err": proc.stderr,
        "index": command is not None or (out_dir / "index.html").is_file(),
    }


def cases(size: str = "full") -> list[Case]:
    scratch = Path(tempfile.mkdtemp(prefix="crankdyn-bench-"))
    atexit.register(shutil.rmtree, scratch, True)
    runs: list[dict] = []

    # the tests' smoke run checks the plumbing on a quick command (the report itself is tested
    # in tests/report); the benchmark runs the analysis
    command = ("examples",) if size == "tiny" else None

    def run():
        result = analyze_once(scratch / "report", command)
        runs.append(result)
        return result

    def check(outputs: dict) -> dict:
        for r in runs:
            if r["status"] != 0 or not r["index"]:
                raise AgreementError(
                    f"crankdyn analyze failed (status {r['status']}): {r['err'].strip()[-500:]}"
                )
        return {}

    def extra(_output) -> dict:
        peak = max(r["rss_mb"] for r in runs)
        return {"peak_rss_mb": peak, "memory_target_mb": MEGABYTES, "memory_ok": peak < MEGABYTES}

    return [
        Case(
            key=KEY,
            title=TITLE,
            size=ENGINE if size == "full" else "crankdyn examples (smoke run)",
            contenders=(Contender(CRANKDYN, run),),
            check=check,
            targets=(Target(None, 0.0, f"< {SECONDS:g} s (and < {MEGABYTES:g} MB)", SECONDS),),
            repeats=3 if size == "full" else 1,
            extra=extra,
        )
    ]
