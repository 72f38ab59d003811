"""Cases: long torsiograph records, the whole process (issue 37, item 5).

A steady 1500 rpm record of a 60-tooth wheel (orders 1.5, 3 and 6 of 1, 2 and 0.5 mrad, 20 ns
of timing jitter, no reference mark), written as CSV (``time [s]``, nine decimals) by
:func:`write_record` before the clock starts.

- ``crankdyn measure`` of 10^6 pulses (as JSON) against :mod:`bench.bare_measure`, a plain
  numpy/scipy script of the same formulas reading the file with :func:`numpy.loadtxt`: both
  fresh processes (``python -m bench.peak``), timed in turn; target within 1.5x. The two JSON
  files agree to 1e-6 of the largest order in every amplitude (the script analyses the record
  whole, crankdyn block by block: both round the running sums of the mean-rotation filter,
  to some 1e-8);
- ``crankdyn measure`` of 10^7 pulses: no peer (the script would hold some 2.5 GB); target:
  the peak memory within 1.25x of the 10^6 record's, the memory bound not growing with the
  record.
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

KEY = "records"
TITLE = "Long measurement records (crankdyn measure, CSV)"
BARE = "plain numpy/scipy script (bench/bare_measure.py)"
TEETH = 60
SPEED = 1500.0 * math.pi / 30.0  # rad/s
ORDERS = np.array([1.5, 3.0, 6.0])
AMPLITUDES = np.array([1e-3, 2e-3j, 5e-4])
SIZES = {"full": (1_000_000, 10_000_000), "tiny": (40_000, 300_000)}


def write_record(path: Path, pulses: int) -> Path:
    """The benchmark's record of ``pulses`` pulses as CSV (module docstring), written in chunks."""
    from crankdyn.measure.synthetic import PrescribedMotion, synthetic_record

    motion = PrescribedMotion(SPEED, 0.0, ORDERS, AMPLITUDES)
    duration = (pulses - 0.5) * 2.0 * math.pi / TEETH / SPEED
    record = synthetic_record(motion, TEETH, duration, jitter=2e-8, seed=1)
    with open(path, "w", encoding="utf-8") as handle:
        handle.write("time [s]\n")
        for chunk in record.chunks():
            np.savetxt(handle, chunk.times, fmt="%.9f")
    return path


def _agreement(runs: list[dict], peer_runs: list[dict], mine: Path, theirs: Path) -> dict:
    for r in runs + peer_runs:
        if r["status"] != 0:
            raise AgreementError(f"measure failed (status {r['status']}): {r['err'][-400:]}")
    a = json.loads(mine.read_text(encoding="utf-8"))
    b = json.loads(theirs.read_text(encoding="utf-8"))
    amp_a, amp_b = np.asarray(a["amplitude_rad"]), np.asarray(b["amplitude_rad"])
    if a["orders"] != b["orders"]:
        raise AgreementError("the orders differ")
    x = amp_a * np.exp(1j * np.radians(a["phase_deg"]))
    y = amp_b * np.exp(1j * np.radians(b["phase_deg"]))
    dev = float(np.max(np.abs(x - y)) / np.max(amp_b))
    found = amp_a[np.searchsorted(a["orders"], ORDERS)]  # (no reference mark: no phases)
    if np.max(np.abs(found - np.abs(AMPLITUDES))) > 0.01 * np.max(np.abs(AMPLITUDES)):
        raise AgreementError(f"crankdyn's orders are not the record's: {found}")
    return {BARE: Deviation(dev, 1e-6, "complex orders, of the largest")}


def cases(size: str = "full") -> list[Case]:
    scratch = Path(tempfile.mkdtemp(prefix="crankdyn-bench-records-"))
    atexit.register(shutil.rmtree, scratch, True)
    short, long = SIZES[size]
    repeats = 5 if size == "full" else 0
    out = []

    record = write_record(scratch / "record.csv", short)
    mine_json, bare_json = scratch / "crankdyn.json", scratch / "bare.json"
    mine: list[dict] = []
    peer: list[dict] = []
    args = ["crankdyn", "measure", str(record), "--teeth", str(TEETH), "--analysis", "steady"]
    args += ["--format", "json", "-o", str(mine_json), "--force"]

    def peaks(_output) -> dict:
        peak = max(r["rss_mb"] for r in mine)
        return {
            "peak_rss_mb": peak,
            "memory_target_mb": math.inf,
            "memory_ok": True,
            "peer_peak_rss_mb": {BARE: max(r["rss_mb"] for r in peer)},
        }

    out.append(
        Case(
            key=KEY,
            title=TITLE,
            size=f"{short:,} pulses ({record.stat().st_size / 2**20:.0f} MiB)",
            contenders=(
                Contender(CRANKDYN, lambda: run_process(args, mine)),
                Contender(
                    BARE,
                    lambda: run_process(
                        ["bench.bare_measure", str(record), str(TEETH), str(bare_json)], peer
                    ),
                ),
            ),
            check=lambda _o: _agreement(mine, peer, mine_json, bare_json),
            targets=(Target(BARE, 1 / 1.5, "within 1.5x of it"),),
            repeats=repeats,
            interleave=True,  # a ratio to the bare script: both under the same load
            extra=peaks,
        )
    )

    big = write_record(scratch / "long.csv", long)
    big_json = scratch / "long.json"
    big_runs: list[dict] = []
    big_args = [*args[:2], str(big), *args[3:]]
    big_args[big_args.index(str(mine_json))] = str(big_json)

    def bounded(_output) -> dict:
        peak = max(r["rss_mb"] for r in big_runs)
        target = 1.25 * max(r["rss_mb"] for r in mine)
        return {"peak_rss_mb": peak, "memory_target_mb": target, "memory_ok": peak < target}

    def big_check(_outputs) -> dict:
        for r in big_runs:
            if r["status"] != 0:
                raise AgreementError(f"measure failed: {r['err'][-400:]}")
        data = json.loads(big_json.read_text(encoding="utf-8"))
        found = np.asarray(data["amplitude_rad"])[np.searchsorted(data["orders"], ORDERS)]
        if np.max(np.abs(found - np.abs(AMPLITUDES))) > 0.01 * np.max(np.abs(AMPLITUDES)):
            raise AgreementError(f"the long record's orders are not the record's: {found}")
        return {}

    out.append(
        Case(
            key=KEY,
            title=TITLE,
            size=f"{long:,} pulses ({big.stat().st_size / 2**20:.0f} MiB), memory",
            contenders=(Contender(CRANKDYN, lambda: run_process(big_args, big_runs)),),
            check=big_check,
            targets=(Target(None, 0.0, "finishes, memory < 1.25x the short record's", 3600.0),),
            repeats=1 if size == "full" else 0,
            extra=bounded,
        )
    )
    return out
