"""A parameter study from Python (run: python docs/examples/study_api.py [OUTDIR]).

The built-in study ``inline4-rod-and-firing`` with a smaller grid, run in this process, then
the results table read back and its best case printed. `crankdyn study` does the same from the
command line (docs/study-file.md).
"""

from __future__ import annotations

import sys
from dataclasses import replace
from pathlib import Path

from crankdyn.study import load_study, read_table, run_study


def main(out: Path) -> None:
    out.mkdir(parents=True, exist_ok=True)

    # 1. A study: a study file, or a built-in example study by name
    spec = load_study("inline4-rod-and-firing")
    print(f"{spec.name}: {spec.case_count} cases, figures {', '.join(spec.figures)}")

    # 2. Keep the first two rod ratios only (a StudySpec is an immutable dataclass)
    ratio = spec.parameters[0]
    small = replace(ratio, values=ratio.values[:2], numbers=ratio.numbers[:2])
    spec = replace(spec, parameters=(small, *spec.parameters[1:]))

    # 3. Run it: workers=1 in this process; the default is a process per core, and
    #    scheduler="tcp://host:8786" runs on a Dask cluster. A second call resumes.
    run = run_study(spec, out / "study", workers=1, summary=False)
    print(f"{run.ok} cases with results, {run.failed} failed, {run.rate:.1f} cases/s")

    # 4. The table (pyarrow; .to_pandas() with pandas installed)
    table = read_table(out / "study" / "results.parquet").to_pydict()
    loads = table["max_main_bearing_load_N"]
    best = min(range(len(loads)), key=loads.__getitem__)
    print(
        f"lowest main-bearing load {loads[best] / 1e3:.2f} kN in case {table['case'][best]}: "
        f"rod ratio {table['geometry.rod_ratio'][best]}, piston group "
        f"{table['masses.piston_group_kg'][best]} kg, firing order "
        f"{table['cylinders.firing_order'][best]}"
    )


if __name__ == "__main__":
    main(Path(sys.argv[1] if len(sys.argv) > 1 else "crankdyn-study-example"))
