"""Fuzzing torsional model files and the free-vibration solvers: the only outcomes allowed are a
result with finite frequencies or the one-line InputError."""

from __future__ import annotations

import copy
import math
import tomllib
from importlib import resources

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from crankdyn.errors import InputError
from crankdyn.io.examples import example_names
from crankdyn.io.torsion_file import parse_torsion_model
from crankdyn.torsion.holzer import holzer_table
from crankdyn.torsion.modal import natural_modes
from tests.conftest import fuzz_examples
from tests.robustness.strategies import values

EXAMPLES = resources.files("crankdyn") / "examples" / "torsion"
BASES = [
    tomllib.loads((EXAMPLES / f"{name}.toml").read_text(encoding="utf-8"))
    for name in example_names("model")
]
KEYS = ["name", "inertia", "damping", "cylinders", "between", "stiffness", "length"]
KEYS += ["outer_diameter", "inner_diameter", "shear_modulus", "loss_factor", "ratio", "ground"]


@st.composite
def mutated_model(draw):
    doc = copy.deepcopy(draw(st.sampled_from(BASES)))
    for _ in range(draw(st.integers(1, 4))):
        table = draw(st.sampled_from(["mass", "shaft", "gear"]))
        entries = doc.setdefault(table, [])
        action = draw(st.sampled_from(["replace", "delete", "add", "drop", "copy", "magnitude"]))
        if action == "add" or not entries:
            entries.append({draw(st.sampled_from(KEYS)): draw(values) for _ in range(2)})
            continue
        entry = draw(st.sampled_from(entries))
        key = draw(st.sampled_from([*entry, *KEYS]))
        if action == "replace":
            entry[key] = draw(values)
        elif action == "delete":
            entry.pop(key, None)
        elif action == "drop":
            entries.remove(entry)
        elif action == "copy":
            entries.append(copy.deepcopy(entry))
        else:  # extreme but valid-looking magnitudes
            exponent = draw(st.integers(-300, 300))
            entry[key] = f"1e{exponent} {draw(st.sampled_from(['kg*m^2', 'N*m/rad', 'm', 'Pa']))}"
    return doc


def _solve(doc):
    try:
        model = parse_torsion_model(doc, file="fuzz.toml")
    except InputError as exc:
        text = str(exc)
        assert text.startswith("fuzz.toml") and "\n" not in text, text
        return
    for solver in ("eigen", "holzer", "transfer"):
        try:
            result = natural_modes(model, solver)
        except InputError as exc:
            assert "\n" not in str(exc)
            continue
        assert np.all(np.isfinite(result.natural_frequency))
        assert np.all(np.diff(result.natural_frequency) >= 0.0)
    try:
        holzer_table(model, 2 * math.pi * 100.0)
    except InputError as exc:
        assert "\n" not in str(exc)


@settings(max_examples=fuzz_examples(80))
@given(mutated_model())
def test_fuzz_torsion_model_documents(doc):
    _solve(doc)


# ---- drivelines: couplings, gears, distributed shafts, excitation sources ---------------------
LINES = [
    tomllib.loads((EXAMPLES / f"{name}.toml").read_text(encoding="utf-8"))
    for name in ("marine-shaft-line", "genset-line")
]
LINE_KEYS = [
    "kind",
    "dynamic_stiffness",
    "stiffness_table",
    "relative_damping",
    "damping_ratio",
    "temperature_factor",
    "reference_torque",
    "nominal_torque",
    "maximum_torque",
    "vibratory_torque",
    "power_loss",
    "density",
    "inertia",
    "elements",
    "max_frequency",
    "teeth",
    "ratio",
    "direction",
    "mesh_stiffness",
    "base_diameter",
    "role",
    "blades",
    "fractions",
    "torques",
    "phases",
    "power",
    "mean_torque",
    "speed",
    "exponent",
    "pole_pairs",
    "harmonics",
    "orders",
    "at",
]


def _entries(doc, table):
    if table.startswith("excitation."):
        ex = doc.setdefault("excitation", {})
        if not isinstance(ex, dict):
            return []
        return ex.setdefault(table.split(".", 1)[1], [])
    return doc.setdefault(table, [])


@st.composite
def mutated_line(draw):
    doc = copy.deepcopy(draw(st.sampled_from(LINES)))
    for _ in range(draw(st.integers(1, 3))):
        table = draw(
            st.sampled_from(["mass", "shaft", "gear", "excitation.propeller", "excitation.machine"])
        )
        entries = _entries(doc, table)
        if not isinstance(entries, list):
            continue
        if not entries or (draw(st.booleans()) and draw(st.booleans())):
            entries.append({draw(st.sampled_from(LINE_KEYS)): draw(values) for _ in range(2)})
            continue
        entry = draw(st.sampled_from(entries))
        if not isinstance(entry, dict):
            continue
        key = draw(st.sampled_from([*entry, *LINE_KEYS]))
        if draw(st.booleans()):
            entry[key] = draw(values)
        else:
            entry.pop(key, None)
    return doc


@settings(max_examples=fuzz_examples(60), deadline=None)
@given(mutated_line())
def test_fuzz_driveline_documents(doc):
    """Mutated shaft lines: a model whose modes, damped modes, mean torque and forced response
    are finite, or the one-line InputError."""
    from crankdyn.torsion.damped import damped_modes
    from crankdyn.torsion.excitation import excitation_for
    from crankdyn.torsion.sources import default_orders, mean_torques
    from crankdyn.torsion.sweep import forced_response

    try:
        model = parse_torsion_model(doc, file="line.toml")
    except InputError as exc:
        text = str(exc)
        assert text.startswith("line.toml") and "\n" not in text, text
        return
    if model.dof_count > 200:  # a subdivision the mutation made huge: valid, not for a test
        return
    modes = natural_modes(model)
    assert np.all(np.isfinite(modes.natural_frequency))
    try:
        damped = damped_modes(model)
        assert np.all(np.isfinite(damped.damped_frequency))
        ex = excitation_for(model)
        orders = default_orders(model, ex.cycle, engine=ex.cylinder_count > 0)
        r = forced_response(model, ex, [50.0, 120.0], orders[:6])
        # resolved: the two grid speeds and those added at the resonances between them
        assert int(np.sum(r.on_grid)) == 2 and r.amplitude.shape[1] == min(6, orders.size)
        if any(getattr(s, "load", None) is not None for s in model.sources):
            mean_torques(model, [50.0, 120.0])
    except InputError as exc:
        assert "\n" not in str(exc)
