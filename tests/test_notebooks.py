"""The notebooks in notebooks/ run from top to bottom (nbclient, a fresh kernel each), so the
worked examples never fall behind the code (issue 21 point 6)."""

from __future__ import annotations

from pathlib import Path

import nbclient
import nbformat
import pytest

pytestmark = pytest.mark.slow  # long: started first (tests/conftest.py)

NOTEBOOKS = sorted((Path(__file__).parents[1] / "notebooks").glob("*.ipynb"))


def test_the_notebooks_are_there():
    names = {p.stem for p in NOTEBOOKS}
    assert {"engine-to-report", "linkage", "marine-shaft-line"} <= names


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebook_runs(path, tmp_path, monkeypatch):
    monkeypatch.setenv("MPLBACKEND", "Agg")
    nb = nbformat.read(path, as_version=4)
    client = nbclient.NotebookClient(
        nb, timeout=600, kernel_name="python3", resources={"metadata": {"path": str(tmp_path)}}
    )
    client.execute()  # raises CellExecutionError, naming the cell, on any error
    errors = [
        out
        for cell in nb.cells
        if cell.cell_type == "code"
        for out in cell.get("outputs", ())
        if out.get("output_type") == "error"
    ]
    assert not errors
    assert any(cell.get("outputs") for cell in nb.cells if cell.cell_type == "code")
    # every cell that makes a figure shows it as an image, with no %matplotlib inline (the
    # notebooks hold none): a crankdyn figure has _repr_png_
    figure_cells = [
        cell
        for cell in nb.cells
        if cell.cell_type == "code"
        and any(line.startswith("fig = ") for line in cell.source.split("\n"))
    ]
    assert figure_cells
    assert all("%matplotlib" not in cell.source for cell in nb.cells if cell.cell_type == "code")
    for cell in figure_cells:
        images = [
            out
            for out in cell.get("outputs", ())
            if out.get("output_type") in ("execute_result", "display_data")
            and "image/png" in out.get("data", {})
        ]
        assert images, cell.source
