"""Design files and coupling catalogues: what they become, and one-line errors naming file, key
and value; the TOML writer of best.toml; a bundle that removes a key."""

from __future__ import annotations

import copy
import shutil
import tomllib
from pathlib import Path

import pytest

from crankdyn.errors import InputError
from crankdyn.io.design_file import load_design, read_coupling_catalogue
from crankdyn.io.engine_file import parse_engine
from crankdyn.io.examples import example_path
from crankdyn.io.files import load_toml
from crankdyn.io.toml_text import dumps
from crankdyn.session import Analysis
from crankdyn.study.docpath import apply_values, parse_path

DATA = Path(__file__).resolve().parents[1] / "validation" / "data"


@pytest.fixture
def space_file(tmp_path):
    for name in ("small_coupling_line.toml", "small_couplings.csv", "small_coupling_design.toml"):
        shutil.copy(DATA / name, tmp_path / name)
    return tmp_path / "small_coupling_design.toml"


def edit(path: Path, old: str, new: str) -> Path:
    text = path.read_text(encoding="utf-8")
    assert old in text
    path.write_text(text.replace(old, new), encoding="utf-8")
    return path


def test_a_catalogue_row_is_the_coupling_keys_in_si(tmp_path):
    sizes, rows, costs, unit = read_coupling_catalogue(DATA / "small_couplings.csv", "c.csv")
    assert sizes[:2] == ["S-10", "S-16"] and costs == [900, 1100, 1400, 1900, 1000, 1300]
    assert unit == "EUR"
    first = rows[0]
    assert first["dynamic_stiffness"] == "10000.0 N*m/rad" and first["stiffness_table"] is None
    assert first["nominal_torque"] == "1000.0 N*m" and first["vibratory_torque"] == "250.0 N*m"
    assert first["power_loss"] == "200.0 W" and first["J_primary"] == "0.2 kg*m^2"


def test_c_tdyn_at_percentages_of_t_kn_is_a_stiffness_table(tmp_path):
    path = tmp_path / "c.csv"
    path.write_text(
        "size,C_Tdyn_50 [kN*m/rad],C_Tdyn_100 [kN*m/rad],psi,T_KN [kN*m],"
        "J_primary [kg*m^2],J_secondary [kg*m^2]\nA,100,150,1.1,20,1,2\n",
        encoding="utf-8",
    )
    _, rows, costs, _ = read_coupling_catalogue(path, "c.csv")
    assert costs is None
    assert rows[0]["stiffness_table"] == [
        ["0.0 N*m", "100000.0 N*m/rad"],
        ["10000.0 N*m", "100000.0 N*m/rad"],
        ["20000.0 N*m", "150000.0 N*m/rad"],
    ]
    assert rows[0]["dynamic_stiffness"] is None


@pytest.mark.parametrize(
    ("header", "message"),
    [
        ("size,C_Tdyn,psi,T_KN [kN*m],J_primary [kg*m^2],J_secondary [kg*m^2]", "header"),
        ("size,C_Tdyn [kN*m/rad],psi,T_KN [kg],J_primary [kg*m^2],J_secondary [kg*m^2]", "T_KN"),
        ("size,C_Tdyn [kN*m/rad],psy,T_KN [kN*m],J_primary [kg*m^2],J_secondary [kg*m^2]", "psi"),
    ],
)
def test_catalogue_errors_name_the_file_and_the_cell(tmp_path, header, message):
    path = tmp_path / "c.csv"
    path.write_text(header + "\nA,1,1,1,1,1\n", encoding="utf-8")
    with pytest.raises(InputError) as info:
        read_coupling_catalogue(path, "c.csv")
    text = str(info.value)
    assert text.startswith("c.csv: ") and "\n" not in text and message in text


def test_the_small_design_space(space_file):
    space = load_design(space_file)
    assert space.method() == "exhaustive" and space.discrete_count == 12
    assert [c.figure for c in space.constraints] == ["condition_passed"]
    assert [(o.name, o.sense) for o in space.objectives] == [("condition_worst_margin", "max")]
    coupling = space.parameter(space.choices[0])
    assert coupling.bundle and coupling.names == ("S-10", "S-16", "S-25", "S-40", "H-16", "H-25")
    paths = {p.text for p in coupling.paths}
    assert {"shaft[5].dynamic_stiffness", "mass[5].inertia", "mass[6].inertia"} <= paths


@pytest.mark.parametrize(
    ("old", "new", "expected"),
    [
        ('key = "excitation.firing_order"', 'key = "excitation.firing_ordr"',
         '[[choice]] #2 key = "excitation.firing_ordr"'),
        ('base = "small_coupling_line.toml"', 'base = "nowhere.toml"',
         'base = "nowhere.toml": no such engine or model file'),
        ("[search]", "[search]\nmethod = \"exhaustiv\"", "[search] method"),
        ("[search]", '[[range]]\nkey = "shaft[1].stiffness"\nbounds = ["1 MN*m/rad", "2 kg"]\n'
         "[search]", "bounds"),
        ("[search]", '[[objective]]\nfigure = "max_shaft_torqe"\n[search]',
         'did you mean "max_shaft_torque"'),
        ('speed_step = "20 rpm"', 'speed_step = "20 rpm"\nspeed_stp = "5 rpm"',
         '[analysis] speed_stp = "5 rpm": unknown key'),
    ],
)  # fmt: skip
def test_errors_are_one_line_naming_file_key_and_value(space_file, old, new, expected):
    edit(space_file, old, new)
    with pytest.raises(InputError) as info:
        load_design(space_file)
    text = str(info.value)
    assert "\n" not in text and "small_coupling_design.toml: " in text, text
    assert expected in text, text


def test_a_cost_objective_and_a_pareto_front(space_file, cli, tmp_path):
    edit(space_file, "[search]", '[[objective]]\nfigure = "condition_worst_margin"\n'
         '[[objective]]\ncost = "coupling"\n[search]')  # fmt: skip
    result = cli("design", space_file, "-o", tmp_path / "out", "--workers", "1", "--no-report")
    assert result.status == 0, result
    assert "Pareto front" in result.out
    assert (tmp_path / "out" / "pareto.png").stat().st_size > 1000
    header = (tmp_path / "out" / "results.csv").read_text(encoding="utf-8").splitlines()[0]
    assert "objective_condition_worst_margin,cost_coupling" in header


def test_the_inline_shaft_line_reads_as_the_file():
    """An engine whose shaft line is written into [torsion.shaft_line] is the same installation
    as with the line's file: the same masses and the same verdict rows."""
    path = example_path("marine-propulsion", "engine")
    document = load_toml(path)
    inline = copy.deepcopy(document)
    inline["torsion"]["shaft_line"] = load_toml(path.parent / document["torsion"]["shaft_line"])
    a = parse_engine(document, file="a", base_dir=path.parent)
    b = parse_engine(inline, file="b", base_dir=path.parent)
    assert a.torsion.mass_names == b.torsion.mass_names
    ja, jb = Analysis(a).judged(), Analysis(b).judged()
    assert [v.margin for v in ja.verdicts] == [v.margin for v in jb.verdicts]


def test_toml_text_reads_back_and_a_bundle_may_remove_a_key():
    path = example_path("marine-propulsion", "engine")
    document = load_toml(path)
    assert tomllib.loads(dumps(document)) == document
    changed = apply_values(document, {parse_path("torsion.damper[1].permissible_power"): None})
    assert "permissible_power" not in changed["torsion"]["damper"][0]
    assert "permissible_power" in document["torsion"]["damper"][0]


def test_every_condition_a_barred_band_and_an_inertia_limit(space_file, tmp_path):
    """[constraints] verdicts = "all" (every row of crankdyn tvc), barred_band and
    max_added_inertia become constraints on the study figures failed_rows,
    barred_width_in_band and installation_inertia (the base's inertia plus the limit)."""
    from crankdyn.study.run.design import run_design

    limits = '[constraints]\nverdicts = "all"\nbarred_band = ["1700 rpm", "2000 rpm"]\n'
    edit(space_file, "[search]", limits + 'max_added_inertia = "0.05 kg*m^2"\n[search]')
    space = load_design(space_file)
    figures = [c.figure for c in space.constraints]
    assert figures == ["failed_rows", "barred_width_in_band", "installation_inertia"]
    base_inertia = 0.4 * 3 + 3 + 0.3 + 0.2 + 4  # kg m^2, the line's masses (no damper)
    assert space.constraints[2].high == pytest.approx(base_inertia + 0.05)
    assert space.objectives[0].name == "worst_margin"
    result = run_design(space, tmp_path / "out", workers=1)
    for c in (c for c in result.candidates if c.ok):
        inertia = c.figures["installation_inertia"]
        assert (inertia <= base_inertia + 0.05 + 1e-12) or not c.feasible
        assert c.figures["failed_rows"] == 0 or not c.feasible
    chosen = result.best
    assert chosen is not None and chosen.figures["barred_width_in_band"] == 0.0
    # S-10's halves (0.35 kg m^2) add none; S-40's (0.9 kg m^2) exceed the limit
    assert all(c.case.numbers[space.choices[0]] not in ("S-40", "H-25") for c in result.ranked(12))


def test_dampers_from_a_list_are_bundles_of_their_keys(tmp_path):
    """``key = "damper[1]"`` with a list of tables: each a damper (its keys set together). On
    the Lanchester system the best of three is the one nearest the optimum damping, as the
    closed-form receptance ranks them (independent of crankdyn's solver)."""
    import numpy as np

    from crankdyn.design.search import run_search
    from crankdyn.study.run.runner import CaseRunner

    shutil.copy(DATA / "lanchester_single_mass.toml", tmp_path / "line.toml")
    space_file = tmp_path / "dampers.toml"
    space_file.write_text(
        'base = "line.toml"\n[[choice]]\nname = "damper"\nkey = "damper[1]"\n'
        'names = ["small", "medium", "large"]\n'
        'values = [{inertia = "0.1 kg*m^2", damping = "3 N*m*s/rad"},\n'
        '          {inertia = "0.1 kg*m^2", damping = "6 N*m*s/rad"},\n'
        '          {inertia = "0.1 kg*m^2", damping = "12 N*m*s/rad"}]\n'
        '[constraints]\nverdicts = "none"\n[[objective]]\nfigure = "max_free_end_amplitude"\n'
        '[analysis]\nmax_order = 1\nspeed_step = "5 rpm"\n',
        encoding="utf-8",
    )
    space = load_design(space_file)
    p = space.parameter(space.choices[0])
    assert p.bundle and {q.text for q in p.paths} == {"damper[1].inertia", "damper[1].damping"}
    with CaseRunner(space.study, tmp_path / "out", workers=1) as runner:
        method, candidates, _ = run_search(space, runner.run)
    assert method == "exhaustive"
    omega_n, j = 2 * np.pi * 10.0, 0.1
    w = np.linspace(0.3, 1.5, 200_001) * omega_n

    def peak(c: float) -> float:
        icw = 1j * c * w
        return float(np.abs(1 / (omega_n**2 - w**2 + icw * (-j * w**2) / (icw - j * w**2))).max())

    by_hand = sorted(
        ("small", "medium", "large"), key=lambda n: peak({"small": 3, "medium": 6, "large": 12}[n])
    )
    assert [c.case.numbers[space.choices[0]] for c in candidates] == by_hand


def test_a_shaft_diameter_range_moves_the_stiffness_the_reader_derives(tmp_path):
    """A range over a shaft's diameter: the file reader derives the stiffness
    k = G pi d^4 / (32 L) from each candidate's diameter, so the two-disc system's natural
    frequency (1/2 pi) sqrt(k (J1 + J2) / (J1 J2)) follows it (closed form, exact)."""
    import math

    from crankdyn.design.search import run_search
    from crankdyn.study.run.runner import CaseRunner

    (tmp_path / "discs.toml").write_text(
        '[[mass]]\nname = "a"\ninertia = "2 kg*m^2"\n[[mass]]\nname = "b"\ninertia = "3 kg*m^2"\n'
        '[[shaft]]\nbetween = ["a", "b"]\nlength = "1 m"\nouter_diameter = "60 mm"\n'
        'shear_modulus = "80 GPa"\n',
        encoding="utf-8",
    )
    (tmp_path / "space.toml").write_text(
        'base = "discs.toml"\n[[range]]\nname = "diameter"\nkey = "shaft[1].outer_diameter"\n'
        'bounds = ["40 mm", "80 mm"]\n[constraints]\nverdicts = "none"\n'
        '[[objective]]\nfigure = "natural_frequency_1"\nsense = "max"\n'
        "[search]\nmax_candidates = 10\npopulation = 5\n",
        encoding="utf-8",
    )
    space = load_design(tmp_path / "space.toml")
    with CaseRunner(space.study, tmp_path / "out", workers=1) as runner:
        _, candidates, _ = run_search(space, runner.run)
    assert len(candidates) >= 5
    for c in candidates:
        d = c.case.numbers["shaft[1].outer_diameter"] * 1e-3  # m (the range's unit: mm)
        k = 80e9 * math.pi * d**4 / 32.0
        expected = math.sqrt(k * 5.0 / 6.0) / (2.0 * math.pi)
        assert c.objectives[0] == pytest.approx(expected, rel=1e-9)
