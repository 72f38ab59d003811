"""The engineering report: every analysis that applies to an engine, as one HTML page with its
data (``crankdyn analyze``, ``crankdyn demo``).

- :mod:`crankdyn.report.model`: the report's parts (sections, key figures, plots, tables, checks);
- :mod:`crankdyn.report.sections`: one builder per analysis, each returning a section or None;
- :mod:`crankdyn.report.build`: runs the builders;
- :mod:`crankdyn.report.html`: renders the self-contained page (user text escaped);
- :mod:`crankdyn.report.write`: writes the folder atomically.
"""
