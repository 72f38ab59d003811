"""The done-criterion of issue 32, item 2, on the command line: a bare 180 for a shaft diameter
or a bare speed cannot end in "passed". A bare speed (or a torque unit for a stiffness) ends in
one error line and status 2; a bare 180 for a diameter runs, warns on standard error, lists the
warning before the verdict and says "passed, with 1 input warning" in the terminal, the JSON,
the report and its PDF (never a clean "passed")."""

from __future__ import annotations

import json
import re
import shutil

import pytest

from crankdyn.io.examples import example_path
from crankdyn.io.units import BARE_SPEED

DIAMETER = 'outer_diameter = "330 mm"'  # the thrust shaft's, the first of the file
WARNING = "[[shaft]] #3 outer_diameter = 180: 180 m is outside the 0.003-3 m of shaft diameters"


def _line(folder, old: str = DIAMETER, new: str = "outer_diameter = 180"):
    """The built-in marine shaft line (it passes its checks) with one value changed."""
    text = example_path("marine-shaft-line", "model").read_text(encoding="utf-8")
    assert old in text
    path = folder / "line.toml"
    path.write_text(text.replace(old, new, 1), encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def line180(tmp_path_factory):
    return _line(tmp_path_factory.mktemp("line180"))


def _no_clean_pass(text: str) -> None:
    assert not re.search(r"Verdict: passed\s*$", text, flags=re.M), text[-400:]


def test_response_lists_the_warning_first_and_never_says_passed_alone(cli, line180):
    run = cli("torsion", "response", line180)
    assert run.status == 0, run
    assert run.err.count("crankdyn: warning: ") == 1 and WARNING in run.err
    out = run.out
    assert out.index("Input warning: ") < out.index("Verdicts") < out.index("Verdict: ")
    assert "Verdict: passed, with 1 input warning" in out
    assert "yes, with 1 input warning" in out  # the figure "Every check passed"
    _no_clean_pass(out)


def test_response_json_lists_the_input_warnings(cli, line180):
    run = cli("torsion", "response", line180, "--format", "json")
    assert run.status == 0, run
    data = json.loads(run.out)
    (w,) = data["input_warnings"]
    assert (w["file"], w["key"], w["value_as_written"], w["check"]) == (
        str(line180) if "/" in w["file"] else "line.toml",
        "[[shaft]] #3 outer_diameter",
        180,
        "input",
    )
    assert (w["value"], w["unit"], w["plausible_low"], w["plausible_high"]) == (180, "m", 0.003, 3)
    assert "warnings" not in data  # the analyses' own warnings: none
    judged = data["judged"]
    assert judged["verdict"] == "passed, with 1 input warning" and judged["input_warnings"]


def test_tvc_says_passed_with_the_warning_everywhere(cli, line180, tmp_path):
    target = tmp_path / "tvc"
    run = cli("tvc", line180, "--output", target, "--no-passage")
    assert run.status == 0, run  # a warned TVC that passes keeps status 0
    assert WARNING in run.err
    assert run.out.index("Input warning: ") < run.out.index("Verdict: passed, with 1 input")
    _no_clean_pass(run.out)
    summary = json.loads((target / "summary.json").read_text(encoding="utf-8"))
    assert summary["key_figures"]["verdict"] == "passed, with 1 input warning"
    assert summary["status"]["verdict"] == "warn"
    assert "pass" not in summary["status"].values()
    assert [w["key"] for w in summary["input_warnings"]] == ["[[shaft]] #3 outer_diameter"]
    page = (target / "index.html").read_text(encoding="utf-8")
    verdict = page.index("Verdict: passed, with 1 input warning")
    assert page.index("input-warnings") < verdict
    assert "badge pass" not in page
    if shutil.which("chromium") is None and shutil.which("chromium-browser") is None:
        return
    from pypdf import PdfReader

    text = " ".join(p.extract_text() for p in PdfReader(target / "report.pdf").pages)
    text = " ".join(text.split())
    assert "Verdict: passed, with 1 input warning" in text
    assert text.index("outer_diameter = 180") < text.index("Verdict: passed, with 1 input")


@pytest.mark.parametrize(
    "old, new, fragment",
    [
        (
            'speed_range = ["300 rpm", "750 rpm"]',
            'speed_range = ["350", "1000"]',
            f'line.toml: [operating] speed_range = "350": {BARE_SPEED}',
        ),
        (
            'stiffness = "95 MN*m/rad"',
            'stiffness = "95 MN*m"',
            'line.toml: [[shaft]] #3 stiffness = "95 MN*m": expected a torsional stiffness '
            '(e.g. "160 kN*m/rad"), got a torque',
        ),
    ],
)
def test_a_bare_speed_or_a_torque_as_stiffness_is_one_error_line(cli, tmp_path, old, new, fragment):
    path = _line(tmp_path, old, new)
    for args in (("torsion", "response", path), ("tvc", path, "--output", tmp_path / "r")):
        run = cli(*args)
        assert run.status == 2, run
        assert run.err.count("\n") == 1 and run.err.startswith("crankdyn: error: ")
        assert run.err.rstrip().endswith(fragment), run.err
        assert "Verdict" not in run.out
    assert not (tmp_path / "r").exists()


def test_a_loss_factor_of_2_is_warned(cli, tmp_path):
    path = _line(
        tmp_path,
        'stiffness = "14 MN*m/rad"\nloss_factor = 0.01',
        'stiffness = "14 MN*m/rad"\nloss_factor = 2',
    )
    run = cli("torsion", "modes", path)
    assert run.status == 0, run
    assert "[[shaft]] #2 loss_factor = 2: 2 is outside the 0-0.5 of loss factors" in run.err


def test_the_command_line_keeps_rpm_for_a_bare_speed(cli):
    """One vocabulary: a bare speed is rpm where an option implies it, refused in a file."""
    run = cli("torsion", "response", "marine-shaft-line", "--speeds", "300:750:50")
    assert run.status == 0, run
    assert "warning" not in run.err
    assert re.search(r"Verdict: passed\s*$", run.out, flags=re.M)  # clean inputs: clean pass
