"""``crankdyn torsion modes --damped`` above its bounds (issue 33): refused in one line, exit
status 2, naming the key and the value, before the damped modes are computed; at the bound the
command runs."""

from __future__ import annotations

import json

import numpy as np

import crankdyn.torsion.damped as damped


def _chain_file(tmp_path, n):
    rng = np.random.default_rng(7)
    masses = ",\n".join(
        f'{{name="m{i}",inertia={j!r},damping=2.0}}'
        for i, j in enumerate(rng.uniform(0.05, 2, n).tolist())
    )
    shafts = ",\n".join(
        f'{{between=["m{i}","m{i + 1}"],stiffness={k!r},loss_factor=0.05}}'
        for i, k in enumerate(rng.uniform(2e5, 5e6, n - 1).tolist())
    )
    path = tmp_path / f"chain-{n}.toml"
    path.write_text(f'name = "chain"\nmass = [\n{masses}\n]\nshaft = [\n{shafts}\n]\n', "utf-8")
    return path


def test_a_chain_above_the_bound_is_refused_in_one_line(cli, tmp_path, monkeypatch):
    monkeypatch.setattr(damped, "CHAIN_MAX_DOF", 50)
    computed = []
    monkeypatch.setattr(damped, "_per_mode", lambda *a: computed.append(a))  # never reached
    r = cli("torsion", "modes", _chain_file(tmp_path, 60), "--damped")
    assert r.status == 2 and not computed
    assert r.err.count("\n") == 1 and "degrees of freedom = 60" in r.err
    assert "at most 50 degrees of freedom" in r.err


def test_the_json_bound(cli, tmp_path, monkeypatch):
    monkeypatch.setattr(damped, "JSON_MAX_DOF", 40)
    path = _chain_file(tmp_path, 41)
    r = cli("torsion", "modes", path, "--damped", "--format", "json")
    assert r.status == 2 and r.err.count("\n") == 1
    assert '--format = "json"' in r.err and "at most 40 degrees of freedom" in r.err
    r = cli("torsion", "modes", path, "--damped", "--format", "csv")  # no mode shapes: taken
    assert r.status == 0 and r.out.count("\n") == 42  # header and 41 modes
    monkeypatch.setattr(damped, "JSON_MAX_DOF", 41)
    r = cli("torsion", "modes", path, "--damped", "--format", "json")
    assert r.status == 0 and len(json.loads(r.out)["mode_shapes_real"]) == 41
