"""The HTML report: contents, safety, and a real headless browser."""

from __future__ import annotations

import dataclasses
import json
import math
import re
import unicodedata

import pytest

import crankdyn.report.sections as sections
from crankdyn.engine.model import Engine
from crankdyn.io.catalogue import load_example
from crankdyn.report.build import build_report
from crankdyn.report.write import write_report

HOSTILE = "<script>alert(1)</script>"


@pytest.fixture(scope="module")
def demo_report(tmp_path_factory):
    out = tmp_path_factory.mktemp("report") / "demo"
    engine = load_example("inline6-diesel")
    write_report(build_report(engine), out)
    return out


@pytest.fixture(scope="module")
def hostile_report(tmp_path_factory):
    base = load_example("vaz2108")
    engine = Engine(
        name=HOSTILE,
        geometry=base.geometry,
        cylinders=base.cylinders,
        masses=base.masses,
        speed=base.speed,
        source="<b>file</b>.toml",
    )
    out = tmp_path_factory.mktemp("report") / "hostile"
    write_report(build_report(engine), out)
    return out


def test_report_folder_contents(demo_report):
    assert (demo_report / "index.html").stat().st_size > 10_000
    summary = json.loads((demo_report / "summary.json").read_text())
    figures = summary["key_figures"]
    assert figures["stroke_m"] == pytest.approx(0.137)
    assert figures["max_piston_acceleration_m_s2"] > 0
    # the Mendes 2008 9-mass model: first elastic mode 216.6 Hz (6th order at about 2166 rpm)
    assert figures["natural_frequency_1_hz"] == pytest.approx(216.58, abs=0.01)
    assert all(c["passed"] for c in summary["checks"])
    assert {"kinematics", "pressure", "forces", "torque", "torsion-modes"} <= set(
        summary["sections"]
    )
    assert len(summary["checks"]) >= 3
    # forced response: the 6th-order resonance of the first mode (2166 rpm) is flagged
    assert "torsion-response" in summary["sections"]
    crit = summary["sections"]["torsion-response"]["critical_speeds"]
    sixth = [c for c in crit if c["order"] == 6.0 and c["major"]]
    assert sixth and sixth[0]["speed_rpm"] == pytest.approx(2165.8, abs=1.0)
    assert summary["status"]["major_critical_speeds"] == "warn"
    # Mendes 2008 Fig. 31: about 9.5 kN m near 2150 rpm (tests/validation holds the tolerance):
    # the flywheel shaft's sum of order amplitudes in the response's table of shaft peaks
    rows = (demo_report / "data" / "shaft_peaks.csv").read_text().splitlines()
    flywheel = next(r for r in rows if r.startswith("cylinder 6 - flywheel,"))
    assert float(flywheel.split(",")[1]) == pytest.approx(9.49e3, rel=0.01)
    for png in (demo_report / "plots").glob("*.png"):
        assert (demo_report / "plots" / f"{png.stem}.svg").exists()
    assert (demo_report / "data" / "kinematics.csv").read_text().startswith("crank_angle_deg,")


def test_report_is_self_contained(demo_report):
    html = (demo_report / "index.html").read_text()
    assert "http://" not in html and "https://" not in html
    assert "<script" not in html.lower()
    assert "data:image/png;base64," in html


def test_user_text_is_escaped(hostile_report):
    html = (hostile_report / "index.html").read_text()
    assert HOSTILE not in html
    assert "&lt;script&gt;alert(1)&lt;/script&gt;" in html
    assert "<b>file</b>" not in html


def test_existing_report_not_overwritten(cli, demo_report):
    run = cli("analyze", "inline6-diesel", "--output", demo_report)
    assert run.status == 2 and "already exists" in run.err


@pytest.mark.browser
def test_report_in_browser(browser, demo_report):
    browser.get((demo_report / "index.html").as_uri())
    assert browser.title.startswith("crankdyn report")
    images = browser.execute_script(
        "return Array.from(document.images).map(i => [i.complete, i.naturalWidth, i.alt])"
    )
    assert images, "the report shows plots"
    for complete, width, alt in images:
        assert complete and width > 0, alt
    assert browser.find_element("css selector", "table.figures").is_displayed()
    rows = browser.find_elements("css selector", "#summary table.figures tbody tr")
    assert len(rows) >= 5
    errors = [e for e in browser.get_log("browser") if e["level"] == "SEVERE"]
    assert not errors, errors


@pytest.mark.browser
def test_escaped_name_shows_as_text_in_browser(browser, hostile_report):
    from selenium.common.exceptions import NoAlertPresentException

    browser.get((hostile_report / "index.html").as_uri())
    assert browser.find_element("css selector", "header h1").text == HOSTILE
    with pytest.raises(NoAlertPresentException):
        browser.switch_to.alert  # noqa: B018 - property access raises when no alert is open
    assert not [e for e in browser.get_log("browser") if e["level"] == "SEVERE"]


def _printed_text(browser) -> str:
    """The text of the open page printed by Chromium (CDP Page.printToPDF, A4, the print
    stylesheet), extracted with pypdf."""
    import base64
    import io

    from pypdf import PdfReader

    pdf = browser.execute_cdp_cmd(
        "Page.printToPDF", {"paperWidth": 8.27, "paperHeight": 11.69, "printBackground": True}
    )
    reader = PdfReader(io.BytesIO(base64.b64decode(pdf["data"])))
    return "\n".join(p.extract_text() for p in reader.pages)


def _squeeze(text: str) -> str:
    """Text without white space or soft hyphens (the PDF breaks lines where the page does),
    ligatures spelt out (NFKC: the PDF's "ﬀ" is "ff")."""
    return re.sub(r"[\s\u00ad]+", "", unicodedata.normalize("NFKC", text))


@pytest.mark.browser
def test_printed_report_holds_every_table_row(browser, demo_report):
    browser.get((demo_report / "index.html").as_uri())
    rows = browser.execute_script(
        "return Array.from(document.querySelectorAll('table tbody tr'))"
        ".map(r => Array.from(r.cells).map(c => c.innerText))"
    )
    printed = _squeeze(_printed_text(browser))
    assert len(rows) > 60
    missing = [row for row in rows if _squeeze("".join(row)) not in printed]
    assert not missing, missing[:5]
    # the demo's own order-6 resonance of the first elastic mode (2166 rpm), a row of the
    # critical-speed table, once cut off by a scroll box
    # (critical speed, mode, nodes, order, frequency, major, relative amplitude sum)
    crit = [r for r in rows if len(r) == 7 and r[3] == "6" and r[5] == "yes"]
    assert crit and crit[0][0].startswith("2165.8")


@pytest.mark.browser
def test_report_tables_are_whole_and_readable(browser, demo_report):
    browser.get((demo_report / "index.html").as_uri())
    # nothing scrolls inside the page: every table shows all its rows
    clipped = browser.execute_script(
        "return Array.from(document.querySelectorAll('table')).map(t => t.parentElement)"
        ".filter(e => e.scrollHeight > e.clientHeight + 1 && getComputedStyle(e).overflowY != "
        "'visible').length"
    )
    assert clipped == 0
    # text cells are left-aligned and wrap; numbers are right-aligned
    styles = browser.execute_script(
        "return Array.from(document.querySelectorAll('td.text')).map(c => "
        "[getComputedStyle(c).textAlign, getComputedStyle(c).whiteSpace])"
    )
    assert styles and all(a in ("left", "start") and w == "normal" for a, w in styles)
    nodes = browser.execute_script(
        "const h = Array.from(document.querySelectorAll('#torsion-modes th'))"
        ".map(th => th.innerText); return h;"
    )
    assert "Node positions" in nodes and all("_" not in h for h in nodes)


def test_cut_tables_say_where_the_rest_is(tmp_path):
    from crankdyn.report.html import render_html
    from crankdyn.report.model import Report, Section, Table

    rows = [[str(i), f"{i * 1.5:g}"] for i in range(30)]
    table = Table("many", "Many rows", header=["No.", "Value (N)"], rows=rows, limit=10)
    report = Report(title="t", inputs=[], sections=[Section("s", "S", tables=[table])])
    html = render_html(report, {})
    assert "The first 10 of 30 rows; all 30 in" in html and "data/many.csv" in html
    assert "\n".join(table.csv_text().splitlines()[1:]).count("\n") == 29  # the CSV has all


def test_cut_tables_take_their_units_from_the_shown_rows():
    from crankdyn.report.model import Table
    from crankdyn.summary import SummaryColumn, SummaryTable

    # 36 modes up to 12 kHz: the eight the page shows (4-230 Hz) read in Hz, not 0.004 kHz
    hz = [4.0597, 15.718, 84.666, 98.848, 136.49, 228.43, 230.67, 231.0, *[12000.0] * 28]
    columns = (SummaryColumn("mode", "Mode"), SummaryColumn("f_Hz", "Natural frequency", "Hz"))
    source = SummaryTable(
        "natural_frequencies",
        "Natural frequencies",
        columns,
        tuple((i, f) for i, f in enumerate(hz)),
    )
    table = Table.of(source, 8)
    assert table.header == ["Mode", "Natural frequency (Hz)"]
    assert table.rows[0] == ["0", "4.0597"] and len(table.rows) == 36
    assert "12000" in table.csv_text()  # the CSV keeps every row in SI
    assert Table.of(source).header[1] == "Natural frequency (kHz)"  # uncut: one unit for all


def _fast(name="vaz2108", rpm=11000.0):
    """A plausible engine driven too fast: mean piston speed 26 m/s, 2700 g."""
    return dataclasses.replace(load_example(name), speed=rpm * math.pi / 30.0)


def test_report_summary_shows_warnings(tmp_path, monkeypatch):
    monkeypatch.setattr(sections, "BUILDERS", ("kinematics", "pressure"))
    out = write_report(build_report(_fast()), tmp_path / "r")
    summary = json.loads((out / "summary.json").read_text())
    assert {w["check"] for w in summary["warnings"]} == {"mean_piston_speed", "piston_acceleration"}
    assert summary["status"]["max_piston_acceleration_m_s2"] == "warn"
    assert summary["status"]["mean_piston_speed_m_s"] == "warn"
    html = (out / "index.html").read_text()
    summary_part = html[html.index("id='summary'") : html.index("id='inputs'")]
    assert "Plausibility: Mean piston speed" in summary_part
    assert summary_part.count('<span class="badge warn">warn</span>') >= 2
