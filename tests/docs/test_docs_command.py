"""`crankdyn docs`: the user documentation shipped with the package, offline."""

from __future__ import annotations

import ast
import re
import subprocess
import sys
from pathlib import Path

import pytest

from crankdyn import docs
from crankdyn.cli import main
from crankdyn.cli.docs import terminal_markdown

ROOT = Path(__file__).resolve().parents[2]
PAGES = sorted(p.stem for p in (ROOT / "docs").glob("*.md") if p.stem not in docs.SITE_ONLY)


def test_every_page_of_docs_is_a_topic():
    assert docs.topic_names() == tuple(PAGES)
    assert "engine-file" in PAGES
    for t in docs.topics():
        assert t.title and not t.title.startswith("#"), t


def test_list(capsys):
    assert main(["docs"]) == 0
    out = capsys.readouterr().out
    for name in PAGES:
        assert name in out
    assert "The engine description file" in out


def test_show_a_topic_rendered(capsys):
    assert main(["docs", "engine-file"]) == 0
    out = capsys.readouterr().out
    assert "The engine description file" in out
    assert "# The engine description file" not in out  # rendered, not the source
    assert "\x1b[" not in out  # no colours when stdout is not a terminal


def test_show_accepts_the_file_name(capsys):
    assert main(["docs", "docs/errors.md"]) == 0
    assert "InputError" in capsys.readouterr().out


def test_raw_prints_the_markdown_source(capsys):
    assert main(["docs", "conventions", "--raw"]) == 0
    assert capsys.readouterr().out == (ROOT / "docs" / "conventions.md").read_text(encoding="utf-8")


def test_unknown_topic_is_one_line_with_a_suggestion(capsys):
    assert main(["docs", "engine-fil"]) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1
    assert 'TOPIC = "engine-fil"' in lines[0]
    assert 'did you mean "engine-file"?' in lines[0]


def test_hostile_topic_name_stays_one_line(capsys):
    assert main(["docs", "x\n[bold]y"]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1


def test_links_between_pages_become_commands():
    text = "See [the engine file](engine-file.md#pressure), [errors.md](errors.md) and [x](x.md)."
    assert terminal_markdown(text) == (
        "See the engine file (`crankdyn docs engine-file`), `crankdyn docs errors` and [x](x.md)."
    )


def test_html_not_built_says_how_to_build_it(capsys, monkeypatch, tmp_path):
    monkeypatch.setattr(docs, "html_dirs", lambda: (tmp_path / "none",))
    assert main(["docs", "--html"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1
    assert "make docs" in err


def test_html_opens_the_page_of_a_topic(capsys, monkeypatch, tmp_path):
    site = tmp_path / "html"
    site.mkdir()
    for page in ("index", "engine-file"):
        (site / f"{page}.html").write_text("<html></html>", encoding="utf-8")
    opened = []
    monkeypatch.setattr(docs, "html_dirs", lambda: (tmp_path / "none", site))
    monkeypatch.setattr("webbrowser.open", lambda uri: opened.append(uri) or True)
    assert main(["docs", "--html", "engine-file"]) == 0
    assert main(["docs", "--html"]) == 0
    assert opened == [(site / "engine-file.html").as_uri(), (site / "index.html").as_uri()]


def test_ref_points_to_the_command():
    assert docs.ref("torsion-file") == "crankdyn docs torsion-file"
    with pytest.raises(ValueError, match="no documentation topic"):
        docs.ref("torsion_file")


DYNAMIC_REF = {"cli/docs.py"}  # calls ref() on names it took from docs.topic_names()


def _ref_calls(path: Path):
    tree = ast.parse(path.read_text(encoding="utf-8"))
    for node in ast.walk(tree):
        if (
            isinstance(node, ast.Call)
            and getattr(node.func, "attr", getattr(node.func, "id", None)) == "ref"
            and node.args
        ):
            arg = node.args[0]
            if isinstance(arg, ast.Constant):
                yield node.lineno, arg.value
            else:
                rel = path.relative_to(ROOT / "src" / "crankdyn").as_posix()
                assert rel in DYNAMIC_REF, f"{path}:{node.lineno}: ref() of a non-literal"


def test_every_topic_pointed_to_exists():
    """Every ``ref("topic")`` call and every "crankdyn docs TOPIC" written in the package, the
    README and the pages names a page that exists."""
    names = set(docs.topic_names())
    bad = []
    sources = sorted((ROOT / "src" / "crankdyn").rglob("*.py"))
    for path in sources:
        bad += [f"{path}:{line}: {t}" for line, t in _ref_calls(path) if t not in names]
    mention = re.compile(r"crankdyn docs ([a-z0-9][a-z0-9_.-]*[a-z0-9])")
    for path in [*sources, ROOT / "README.md", *(ROOT / "docs").glob("*.md")]:
        for m in mention.finditer(path.read_text(encoding="utf-8")):
            if m.group(1) not in names and m.group(1) not in {"TOPIC"}:
                bad.append(f"{path}: crankdyn docs {m.group(1)}")
    assert not bad, bad


def test_the_built_package_carries_the_pages(tmp_path):
    """setup.py's build step copies docs/*.md into the package; crankdyn.docs reads them there."""
    lib = tmp_path / "lib"
    subprocess.run(
        [sys.executable, "setup.py", "-q", "build_py", "--build-lib", str(lib)],
        cwd=ROOT,
        check=True,
        capture_output=True,
    )
    shipped = sorted(p.stem for p in (lib / "crankdyn" / "docs").glob("*.md"))
    assert set(PAGES) <= set(shipped)
    assert (lib / "crankdyn" / "py.typed").is_file()
    probe = (
        "import crankdyn.docs as d; print(d.pages_dir()); print(d.read('errors').splitlines()[0])"
    )
    out = subprocess.run(
        [sys.executable, "-c", probe],
        cwd=tmp_path,
        env={"PYTHONPATH": str(lib), "PATH": ""},
        check=True,
        capture_output=True,
        text=True,
    ).stdout.splitlines()
    assert out == [str(lib / "crankdyn" / "docs"), "# Errors"]


REPOSITORY_PATH = re.compile(r"docs/[A-Za-z0-9_-]+\.md|the docs/ folder")


def _user_text_with_repository_paths() -> list[str]:
    """Help texts of the commands and options, and the strings of the package that are not
    docstrings (messages, report text), that name a repository path such as docs/engine-file.md."""
    import click

    from crankdyn.cli import cli

    found = []

    def walk(command: click.Command, path: str) -> None:
        texts = [command.help or "", *(getattr(p, "help", None) or "" for p in command.params)]
        found.extend(f"{path} --help: {m}" for t in texts for m in REPOSITORY_PATH.findall(t))
        for name, sub in getattr(command, "commands", {}).items():
            walk(sub, f"{path} {name}")

    walk(cli, "crankdyn")
    for path in sorted((ROOT / "src" / "crankdyn").rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        docstrings = {  # and attribute docstrings: every string that is a statement of its own
            id(node.value)
            for node in ast.walk(tree)
            if isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant)
        }
        for node in ast.walk(tree):
            if (
                isinstance(node, ast.Constant)
                and isinstance(node.value, str)
                and id(node) not in docstrings
            ):
                rel = path.relative_to(ROOT / "src").as_posix()
                found += [f"{rel}:{node.lineno}: {m}" for m in REPOSITORY_PATH.findall(node.value)]
    return found


def test_user_text_points_to_crankdyn_docs_not_to_repository_paths():
    found = _user_text_with_repository_paths()
    assert not found, "\n".join(found)
