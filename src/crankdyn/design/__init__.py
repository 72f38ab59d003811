"""The design search (``crankdyn design``, docs/design-file.md): choose the coupling, damper,
flywheel, shaft and firing order that pass the verdicts with the widest margin.

- :mod:`crankdyn.design.space`: the design space, its constraints and objectives;
- :mod:`crankdyn.design.search`: candidates, scoring, exhaustive search and differential
  evolution over the study runner's cases;
- :mod:`crankdyn.design.result`: :class:`~crankdyn.design.result.DesignResult`.

The design file is read by :func:`crankdyn.io.design_file.load_design`; the search runs on the
study runner with :func:`crankdyn.study.run.design.run_design`.
"""
