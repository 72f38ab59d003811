"""The documentation site: `make docs` builds it with no warnings, and it renders in a browser.

One test, so that the suite builds the site once (about half a minute on one core): the build
with warnings as errors (the worked examples are not run here; tests/test_docs_examples.py runs
them, and `make docs` runs them into the site), then the pages a reader lands on, in a headless
Chromium when there is one.
"""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def build_site(out: Path) -> subprocess.CompletedProcess:
    """Run the build of `make docs` into ``out`` (without running the worked examples)."""
    return subprocess.run(
        [
            sys.executable,
            "-m",
            "sphinx",
            "-W",
            "--keep-going",
            "-q",
            "-b",
            "html",
            "-D",
            "crankdyn_run_examples=0",
            "-d",
            str(out / "doctrees"),
            str(ROOT / "docs"),
            str(out / "html"),
        ],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )


@pytest.mark.slow
@pytest.mark.browser
def test_docs_site_builds_without_warnings_and_renders(tmp_path, request):
    built = build_site(tmp_path)
    assert built.returncode == 0 and not built.stderr.strip(), built.stderr
    site = tmp_path / "html"
    for page in (
        "index",
        "engine-file",
        "theory-torsion",
        "reference/cli",
        "reference/api",
        "reference/validation",
        "reference/api/crankdyn.crank.kinematics",
        "examples/index",
    ):
        assert (site / f"{page}.html").is_file(), page
    cli = (site / "reference" / "cli.html").read_text(encoding="utf-8")
    headings = set(re.findall(r"<h[2-4][^>]*>([a-z-]+)<", cli))
    assert {"crankdyn", "docs", "study", "torsion", "response", "fourbar"} <= headings, headings
    validation = (site / "reference" / "validation.html").read_text(encoding="utf-8")
    assert "test_seed002_vaz2108_table3_with_source_pi" in validation
    assert "Mendes" in validation

    browser = request.getfixturevalue("browser")
    browser.get((site / "index.html").as_uri())
    assert browser.title.startswith("crankdyn")
    assert browser.find_element("css selector", "article h1").text.startswith("crankdyn")
    links = browser.find_elements("css selector", "article a[href$='reference/cli.html']")
    assert links and links[0].is_displayed()
    links[0].click()
    assert browser.title.startswith("Command reference")
    headings = [h.text for h in browser.find_elements("css selector", "article h2, article h3")]
    assert any(h.startswith("docs") for h in headings), headings
    browser.get((site / "reference" / "api" / "crankdyn.crank.kinematics.html").as_uri())
    assert browser.find_element("css selector", "dl.py.function").is_displayed()
    errors = [e for e in browser.get_log("browser") if e["level"] == "SEVERE"]
    assert not errors, errors
