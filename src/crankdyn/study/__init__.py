"""Parameter studies: many variants of an engine (or model), each analysed, one table of
results (docs/study-file.md).

>>> from crankdyn.study import load_study, run_study
>>> spec = load_study("my-study.toml")                      # doctest: +SKIP
>>> run = run_study(spec, "my-study-results")               # doctest: +SKIP

Modules: :mod:`~crankdyn.study.spec` (the study), :mod:`~crankdyn.study.cases` (grid and Monte
Carlo expansion), :mod:`~crankdyn.study.figures` (the registry of figures kept per case),
:mod:`~crankdyn.study.runner` (local pool and Dask), :mod:`~crankdyn.study.journal` (the output
folder and its journal), :mod:`~crankdyn.study.results` (tables and HTML summary),
:mod:`~crankdyn.study.sensitivity` (main effects, rank correlation).
"""

from __future__ import annotations

__all__ = ["FIGURES", "load_study", "read_table", "run_study"]


def __getattr__(name: str):
    # lazy: importing crankdyn.study (e.g. for its numeric helpers) does not start pint, dask...
    if name == "load_study":
        from crankdyn.io.study_file import resolve_study

        return resolve_study
    if name == "run_study":
        from crankdyn.study.runner import run_study

        return run_study
    if name == "read_table":
        from crankdyn.study.results import read_table

        return read_table
    if name == "FIGURES":
        from crankdyn.study.figures import FIGURES

        return FIGURES
    raise AttributeError(name)
