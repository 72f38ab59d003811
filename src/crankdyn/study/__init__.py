"""Parameter studies: many variants of an engine (or model), each analysed, one table of
results (docs/study-file.md).

>>> from crankdyn.study import load_study, run_study
>>> spec = load_study("my-study.toml")                      # doctest: +SKIP
>>> run = run_study(spec, "my-study-results")               # doctest: +SKIP

The numeric part: :mod:`~crankdyn.study.spec` (the study), :mod:`~crankdyn.study.cases` (grid
and Monte Carlo expansion), :mod:`~crankdyn.study.docpath` (key paths into the base document),
:mod:`~crankdyn.study.figures` (the registry of figures kept per case, each taken from the
analysis session :class:`crankdyn.session.Analysis`), :mod:`~crankdyn.study.sensitivity`
(main effects, rank correlation). The boundary part, :mod:`crankdyn.study.run`: the local pool
and Dask (:mod:`~crankdyn.study.run.runner`), the output folder and its journal
(:mod:`~crankdyn.study.run.journal`), the tables and HTML summary
(:mod:`~crankdyn.study.run.results`).
"""

from __future__ import annotations

from typing import Any

__all__ = ["FIGURES", "load_study", "read_table", "run_study"]


def __getattr__(name: str) -> Any:
    # lazy: importing crankdyn.study (e.g. for its numeric helpers) does not start pint, dask...
    if name == "load_study":
        from crankdyn.io.catalogue import resolve_study

        return resolve_study
    if name == "run_study":
        from crankdyn.study.run.runner import run_study

        return run_study
    if name == "read_table":
        from crankdyn.study.run.results import read_table

        return read_table
    if name == "FIGURES":
        from crankdyn.study.figures import FIGURES

        return FIGURES
    raise AttributeError(name)
