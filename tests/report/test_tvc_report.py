"""The TVC report (crankdyn tvc): folder, summary.json's verdicts and barred ranges, the PDF,
safety, and a real headless browser."""

from __future__ import annotations

import contextlib
import csv
import io
import json
import re
import shutil
import unicodedata

import pytest

from crankdyn.cli import main
from crankdyn.report.tvc import BARRED_FIELDS, VERDICT_FIELDS

pytestmark = pytest.mark.slow  # long: started first (tests/conftest.py)

HOSTILE = "<script>alert(1)</script>"


def _run(*args):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        status = main([str(a) for a in args])
    return status, out.getvalue(), err.getvalue()


@pytest.fixture(scope="module")
def marine(tmp_path_factory):
    target = tmp_path_factory.mktemp("tvc") / "marine"
    status, out, err = _run("tvc", "marine-propulsion", "--output", target)
    # one row fails by design: the reduction gear's torque reverses after the clutch-in's lock
    # (the engine on its governor; the clutch's torque rising in 0.5 s: docs/events.md): exit
    # status 1, the report written
    assert status == 1, err
    return target, out, err


@pytest.fixture(scope="module")
def hostile(tmp_path_factory):
    from pathlib import Path

    import crankdyn

    source = Path(crankdyn.__file__).parent / "examples" / "torsion" / "verdict-geared-line.toml"
    text = source.read_text(encoding="utf-8")
    text = re.sub(r'^name = ".*"$', f'name = "{HOSTILE}"', text, count=1, flags=re.M)
    folder = tmp_path_factory.mktemp("tvc-hostile")
    model = folder / "line.toml"
    model.write_text(text, encoding="utf-8")
    target = folder / "report"
    status, _out, err = _run("tvc", model, "--output", target, "--no-pdf", "--no-passage")
    assert status == 1, err  # the line's verdict fails by design: exit status 1, report written
    return target


def test_tvc_folder_and_summary_lists(marine):
    target, out, _err = marine
    for name in ("index.html", "summary.json", "data/verdicts.csv", "data/barred_speed_ranges.csv"):
        assert (target / name).is_file(), name
    summary = json.loads((target / "summary.json").read_text(encoding="utf-8"))
    verdicts = summary["verdicts"]
    assert verdicts and all(tuple(v) == VERDICT_FIELDS for v in verdicts)
    assert all(tuple(b) == BARRED_FIELDS for b in summary["barred_speed_ranges"])
    assert all(v["source"] for v in verdicts), "every row names the source of its limit"
    # the same rows in summary.json, the full result data and the CSV table
    full = summary["sections"]["passage"]["tvc"]["verdicts"]
    rows = list(csv.reader((target / "data" / "verdicts.csv").open(encoding="utf-8")))[1:]
    assert len(verdicts) == len(full) == len(rows)
    for v, f in zip(verdicts, full, strict=True):
        assert (v["component"], v["worst"], v["limit"]) == (f["component"], f["worst"], f["limit"])
    failed = [(v["component"], v["condition"]) for v in verdicts if not v["passed"]]
    assert failed == [("reduction gear", "clutch-in at 350 rpm")], failed
    conditions = {v["condition"] for v in verdicts}
    assert "normal firing" in conditions and "damper out of order" in conditions
    assert any(c.startswith("misfire cylinder") for c in conditions)
    components = {v["component"] for v in verdicts}
    for part in ("intermediate shaft", "crank span", "coupling", "gear", "damper"):
        assert any(c.startswith(part) or part in c for c in components), part
    # misfiring, the coupling's mode meets order 1 below rated speed: a permitted barred range
    # (Lloyd's Register margins, 2 % tachometer tolerance) and its passage in the time domain
    barred = summary["barred_speed_ranges"]
    assert any(b["component"] == "highly elastic coupling" and b["permitted"] for b in barred)
    assert any(v["quantity"].startswith("transient peak passing") for v in verdicts)
    assert "Verdict:" in out and "Report:" in out
    _check_pdf(target, out, rows)


def _check_pdf(target, out, rows):
    """The PDF printed by headless Chromium (issue 32): page numbers and the running header on
    every page, the title block from the file's [project], a contents list with page numbers,
    the schematic, the mode tables with the vector sums, every verdict row; without a Chromium
    the command says why there is none."""
    if shutil.which("chromium") is None and shutil.which("chromium-browser") is None:
        assert "no PDF" in out and not (target / "report.pdf").exists()
        return
    from pypdf import PdfReader

    pdf = target / "report.pdf"
    assert pdf.read_bytes()[:5] == b"%PDF-" and "PDF:" in out
    pages = [p.extract_text() for p in PdfReader(pdf).pages]
    total = len(pages)
    # 22 pages for normal firing, misfire and damper out; the overspeed condition and the three
    # transient events (clutch-in, start, ice) add their plots: 27 pages
    assert total <= 28, f"the marine line's document runs to {total} pages"
    for n, text in enumerate(pages, start=1):
        squeezed = _squeeze(text)
        assert _squeeze(f"Page {n} of {total}") in squeezed, n
        assert _squeeze("TVC · TVC-EX-001") in squeezed, n  # the running header
        assert _squeeze("Rev. A · 2026-01-15") in squeezed, n
    title = _squeeze(pages[0])
    for words in (
        "Torsional vibration calculation",
        "Illustrative 6-cylinder propulsion line (crankdyn example)",
        "Example Shipyard / hull EX-1",
        "3000 kW at 750 rpm",
        "Revision",
        "First issue (illustrative example)",
        "Prepared",
        "Checked",
        "Approved",
        "Verdict:",
    ):
        assert _squeeze(words) in title, words
    contents = pages[1]
    assert "Contents" in contents
    entries = re.findall(r"^(\d+) (.+?) (\d+)$", contents, flags=re.M)
    assert len(entries) >= 9, contents
    numbers = [int(page) for _n, _title, page in entries]
    assert numbers == sorted(numbers) and numbers[-1] <= total, numbers
    for number, heading, page in entries:  # each heading is on the page the contents name
        assert _squeeze(f"{number} {heading}") in _squeeze(pages[int(page) - 1]), heading
    printed = _squeeze("\n".join(pages))
    for words in (
        "Schematic of the mass-elastic system",
        "Mode shapes",
        "Relative vector sums",
        "Campbell diagram",
        "forced response per order and synthesised",
        "Stiffness k (MN·m/rad)",
    ):
        assert _squeeze(words) in printed, words
    missing = [r for r in rows if _squeeze(r[0] + r[1]) not in printed]
    assert not missing, missing[:3]


def test_tvc_page_says_each_thing_once(marine):
    """Issue 32: the summary's table once (the verdict section repeats no key figures), no
    raw keys in the input, the misfire note under "Notes" (not "Not analysed"), a range's
    ends once (the barred-range table's columns; its "why" repeats no speeds)."""
    target, _out, _err = marine
    page = (target / "index.html").read_text(encoding="utf-8")
    assert page.count("<h3>Conditions</h3>") == 1
    assert page.count("Smallest margin of the verdict rows") == 1
    assert "Every check passed" not in page
    assert "Not analysed" not in page and "<h3>Notes</h3>" in page
    assert "Barred-range widening" not in page and "rules = " not in page
    assert "<th>Rule set</th><td class='text'>Lloyd&#x27;s Register</td>" in page
    assert "<th>Barred-range margins</th><td class='text'>least range 16 n_c/(18-λ_c)" in page
    barred = list(csv.DictReader((target / "data" / "barred_speed_ranges.csv").open()))
    assert barred and all(not re.search(r"(found|to) \d", r["reason"]) for r in barred)
    # one value per quantity: the conditions' smallest margins are the verdict rows' own
    rows = json.loads((target / "summary.json").read_text(encoding="utf-8"))["verdicts"]
    conditions = list(csv.DictReader((target / "data" / "conditions.csv").open()))
    for c in conditions:  # to the CSV's ten digits
        smallest = float(c["smallest_margin"])
        assert any(v["margin"] == pytest.approx(smallest, rel=1e-9) for v in rows), c


def test_tvc_existing_folder_not_overwritten(hostile, cli):
    run = cli("tvc", "verdict-geared-line", "--output", hostile)
    assert run.status == 2 and "already exists" in run.err


def test_tvc_bad_input_is_one_line(cli, tmp_path):
    run = cli("tvc", "no-such-line", "--output", tmp_path / "x")
    assert run.status == 2 and run.err.count("\n") == 1 and "crankdyn: error:" in run.err
    assert not (tmp_path / "x").exists()


def test_tvc_without_a_browser_says_so(monkeypatch, cli, tmp_path):
    import crankdyn.report.pdf as pdf

    monkeypatch.setattr(pdf, "find_browser", lambda: None)
    target = tmp_path / "r"
    run = cli("tvc", "verdict-geared-line", "--out", target, "--no-passage")
    assert run.status == 1, run.err  # the line fails by design (exit status 1)
    assert "no PDF: no Chromium found" in run.out
    assert "--out is deprecated" in run.err
    assert (target / "index.html").is_file() and not (target / "report.pdf").exists()


def test_tvc_user_text_is_escaped(hostile):
    page = (hostile / "index.html").read_text(encoding="utf-8")
    assert HOSTILE not in page and "&lt;script&gt;" in page


def _squeeze(text: str) -> str:
    return re.sub(r"[\s\u00ad]+", "", unicodedata.normalize("NFKC", text))


@pytest.mark.browser
def test_tvc_report_in_browser(browser, hostile):
    target = hostile
    browser.get((target / "index.html").as_uri())
    assert browser.title.startswith("crankdyn report")
    images = browser.execute_script(
        "return Array.from(document.images).map(i => [i.complete, i.naturalWidth, i.alt])"
    )
    assert len(images) >= 3  # modes, Campbell, the condition
    for complete, width, alt in images:
        assert complete and width > 0, alt
    rows = browser.find_elements("css selector", "#verdicts #table-verdicts tbody tr")
    summary = json.loads((target / "summary.json").read_text(encoding="utf-8"))
    assert len(rows) == len(summary["verdicts"])
    assert not [e for e in browser.get_log("browser") if e["level"] == "SEVERE"]


@pytest.mark.browser
def test_tvc_pdf_pages_in_browser(browser, marine, tmp_path):
    """The marine line's PDF: every page holds text (pypdf), and its first, middle and last
    pages shown by Chromium's PDF viewer are three different pictures with ink, kept as PNG
    (look at them: tmp_path/page-N.png). Each page is a fresh load: a new ``#page=`` fragment on
    the document already shown does not move the viewer (every shot was then page 1)."""
    import time

    from pypdf import PdfReader

    target, _out, _err = marine
    pdf = target / "report.pdf"
    if not pdf.exists():
        pytest.skip("no PDF (no Chromium)")
    pages = PdfReader(pdf).pages
    assert all(page.extract_text().strip() for page in pages)
    shots: dict[int, bytes] = {}
    for n in sorted({1, (len(pages) + 1) // 2, len(pages)}):
        browser.get("about:blank")
        browser.get(f"{pdf.as_uri()}#page={n}")
        png = tmp_path / f"page-{n}.png"
        waited = time.monotonic() + 30.0  # the viewer draws the page, then moves to it, some
        image = b""  # seconds after the load (slower on a busy machine): taken as shown once
        while time.monotonic() < waited:  # two shots 0.4 s apart are the same picture
            time.sleep(0.4)
            before, image = image, browser.get_screenshot_as_png()
            if image == before and len(image) > 20_000:
                break
        png.write_bytes(image)
        assert image[:8] == b"\x89PNG\r\n\x1a\n" and len(image) > 20_000, n
        shots[n] = image
    assert len(set(shots.values())) == len(shots) == min(3, len(pages))


@pytest.mark.browser
def test_tvc_hostile_name_in_browser(browser, hostile):
    from selenium.common.exceptions import NoAlertPresentException

    browser.get((hostile / "index.html").as_uri())
    assert HOSTILE in browser.find_element("css selector", "header h1").text
    with pytest.raises(NoAlertPresentException):
        browser.switch_to.alert  # noqa: B018
