"""``crankdyn torsion modes --format json/csv`` of a large chain, block by block (issue 17
point 5): the same keys and layout as the whole-array path, every mode or the lowest --modes,
atomic with -o (nothing left on failure), streamed to standard output."""

from __future__ import annotations

import json

import numpy as np
import pytest

import crankdyn.cli.torsion as torsion_cli
from crankdyn.cli import main
from crankdyn.errors import InputError


def run(capsys, *args):
    status = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return status, out, err


def _chain_file(tmp_path, n=60):
    rng = np.random.default_rng(5)
    masses = ",\n".join(
        f'{{name="m{i}",inertia={j!r}}}' for i, j in enumerate(rng.uniform(0.05, 2, n).tolist())
    )
    shafts = ",\n".join(
        f'{{between=["m{i}","m{i + 1}"],stiffness={k!r}}}'
        for i, k in enumerate(rng.uniform(2e5, 5e6, n - 1).tolist())
    )
    path = tmp_path / "chain.toml"
    path.write_text(f'name = "chain"\nmass = [\n{masses}\n]\nshaft = [\n{shafts}\n]\n', "utf-8")
    return path


def _close(a, b, tol=1e-9):
    """JSON-equal: the same keys, layout, integers, booleans and text; floats to ``tol``. A
    node's position t = ta / (ta - tb) moves by 2 d / |ta - tb| when the amplitudes move by d
    (1e-9 here): near small amplitudes by more, hence 1e-6 for the nodes."""
    if isinstance(a, dict):
        assert list(a) == list(b)
        for k in a:
            _close(a[k], b[k], 1e-6 if k == "nodes" else tol)
    elif isinstance(a, list):
        assert len(a) == len(b)
        for x, y in zip(a, b, strict=True):
            _close(x, y, tol)
    elif isinstance(a, float):
        assert a == pytest.approx(b, rel=tol, abs=tol)
    else:
        assert a == b and type(a) is type(b)


@pytest.fixture
def streamed(monkeypatch):
    """Every chain streamed (the threshold is a million amplitudes: a small chain here)."""
    monkeypatch.setattr(torsion_cli, "STREAMED_SIZE", 0)


def test_streamed_json_is_the_whole_array_json(tmp_path, capsys, monkeypatch):
    path = _chain_file(tmp_path)
    status, whole, _ = run(capsys, "torsion", "modes", path, "--format", "json")
    assert status == 0
    monkeypatch.setattr(torsion_cli, "STREAMED_SIZE", 0)
    status, out, _ = run(capsys, "torsion", "modes", path, "--format", "json")
    assert status == 0 and out.endswith("}\n")
    _close(json.loads(out), json.loads(whole))
    data = json.loads(out)
    assert len(data["mode_shapes"]) == 60 and [len(m) for m in data["nodes"]] == data["node_counts"]


def test_streamed_csv_and_the_lowest_modes(tmp_path, capsys, streamed):
    path = _chain_file(tmp_path)
    status, out, _ = run(capsys, "torsion", "modes", path, "--format", "csv")
    lines = out.splitlines()
    assert status == 0 and len(lines) == 61
    assert lines[0].split(",")[:7] == [
        "mode",
        "natural_frequencies_hz",
        "node_counts",
        "nodes_resolved",
        "modal_inertias_kg_m2",
        "modal_stiffnesses_Nm_per_rad",
        "amplitude_1",
    ]
    assert lines[0].endswith(",amplitude_60")
    status, out, _ = run(capsys, "torsion", "modes", path, "--format", "json", "--modes", "7")
    data = json.loads(out)
    assert data["mode"] == list(range(7)) and data["modes_of_the_model"] == 60
    status, out, _ = run(capsys, "torsion", "modes", path, "--format", "csv", "--modes", "7")
    assert len(out.splitlines()) == 8


def test_the_lowest_modes_in_json_without_streaming(tmp_path, capsys):
    path = _chain_file(tmp_path)
    status, out, _ = run(capsys, "torsion", "modes", path, "--format", "json", "--modes", "5")
    data = json.loads(out)
    assert status == 0 and data["mode"] == [0, 1, 2, 3, 4] and data["modes_of_the_model"] == 60


def test_streamed_file_is_atomic(tmp_path, capsys, streamed, monkeypatch):
    path = _chain_file(tmp_path)
    target = tmp_path / "modes.json"
    status, out, err = run(capsys, "torsion", "modes", path, "--format", "json", "-o", target)
    assert status == 0 and out == "" and f"wrote {target}" in err
    assert json.loads(target.read_text())["model"] == "chain"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["chain.toml", "modes.json"]
    # an existing file without --force: refused before the work
    status, out, err = run(capsys, "torsion", "modes", path, "--format", "json", "-o", target)
    assert status == 2 and "already exists" in err

    # a failure half-way leaves nothing behind (no target, no temporary or spool file)
    def failing(*_args, **_kw):
        yield "{"
        raise InputError("stopped half-way")

    monkeypatch.setattr(torsion_cli, "modes_json_chunks", failing)
    other = tmp_path / "other.json"
    status, _, err = run(capsys, "torsion", "modes", path, "--format", "json", "-o", other)
    assert status == 2 and "stopped half-way" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["chain.toml", "modes.json"]


def test_streamed_with_a_plot(tmp_path, capsys, streamed):
    path = _chain_file(tmp_path)
    figure = tmp_path / "shapes.png"
    status, out, _ = run(
        capsys, "torsion", "modes", path, "--format", "csv", "--plot", figure, "--plot-modes", "1,2"
    )
    assert status == 0 and figure.exists() and len(out.splitlines()) == 61
    status, _, err = run(capsys, "torsion", "modes", path, "--format", "csv", "--plot-modes", "99")
    assert status == 2 and "--plot-modes" in err
