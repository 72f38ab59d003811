"""User text is shown as written wherever it is rendered (issue 17, point 4): rich markup in the
terminal (every console is plain, crankdyn.cli.common.console), matplotlib's mathtext in figures
(crankdyn.plots.style.Figure) and HTML in the report. Generated names full of markup, dollars,
backslashes and angle brackets; the only outcome allowed is the result, with the name in it."""

from __future__ import annotations

import html
import io
import json
import os
import re
import signal
import subprocess
import sys
from importlib import resources

import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from crankdyn.plots.style import new_figure
from tests.conftest import fuzz_examples

EXAMPLES = resources.files("crankdyn") / "examples"
NASTY = [
    "x [/] y",
    "[bold]not bold[/bold]",
    "[link=https://example.com]a[/link]",
    "$\\undefinedcmd$",
    "$x$ and $y$",
    "a\\b$c",
    "<script>alert(1)</script> & co",
    ":smile: 100% {0} %s",
    "[torsion]",
]

# printable text, heavy in the characters that markup languages give a meaning to
names = st.one_of(
    st.sampled_from(NASTY),
    st.text(alphabet=st.sampled_from("[]/$\\<>&:{}%_^#'\"ab 1"), min_size=1, max_size=24),
).filter(lambda s: s.strip() and s == s.strip())


def toml_string(text: str) -> str:
    """A TOML basic string holding ``text``."""
    return json.dumps(text, ensure_ascii=False).replace("\x7f", "\\u007f")


def engine_file(folder, name: str, example: str = "vaz2108"):
    text = (EXAMPLES / f"{example}.toml").read_text(encoding="utf-8")
    text = re.sub(r'(?m)^name = ".*"$', lambda _m: f"name = {toml_string(name)}", text, count=1)
    path = folder / "engine.toml"
    path.write_text(text, encoding="utf-8")
    return path


def shown(name: str, out: str) -> bool:
    """Whether ``name`` appears literally in a table's text (rich pads titles with spaces)."""
    return name in out


@settings(
    max_examples=fuzz_examples(12),
    # the cli fixture reads what each run printed: it is reused safely across examples
    suppress_health_check=[HealthCheck.function_scoped_fixture],
)
@given(name=names)
@example(name="x [/] y")
@example(name="$\\undefinedcmd$")
def test_names_in_the_terminal(cli, tmp_path_factory, name):
    """balance, firing-orders and flywheel print the engine's name in their titles; forces and
    kinematics print tables of it: exit 0 and the name as written."""
    engine = engine_file(tmp_path_factory.mktemp("text"), name)
    for args, titled in (
        (("balance", engine), True),
        (("firing-orders", engine), True),
        (("flywheel", engine, "--delta", "0.01"), True),
        (("kinematics", engine), False),
    ):
        run = cli(*args)
        assert run.status == 0, (args, run)
        assert "Traceback" not in run.err
        if titled:
            assert shown(name, run.out), (name, run.out[:400])


@settings(max_examples=fuzz_examples(8))
@given(name=names, log=st.booleans())
@example(name="$\\undefinedcmd$", log=True)
def test_names_in_figures(name, log):
    """Titles, axis labels, legends, annotations and text tick labels draw a name literally;
    numeric tick labels keep matplotlib's mathtext (log axes)."""
    fig, axes = new_figure(1, 2)
    left, right = axes[0]
    left.plot([1, 2, 3], [1, 10, 100], label=f"line {name}")
    left.set_title(name)
    left.set_xlabel(name)
    left.legend(title=name)
    left.annotate(name, (2, 10))
    if log:
        left.set_yscale("log")
    right.bar([0, 1], [1, 2])
    right.set_xticks([0, 1], labels=[name, name + "2"])
    fig.suptitle(name)
    fig.savefig(io.BytesIO(), format="png", dpi=40)
    assert left.get_title() == name and not left.title.get_parse_math()
    if log:
        assert left.get_yticklabels()[0].get_parse_math()  # powers of ten in mathtext


def test_analyze_with_markup_in_the_name(cli, tmp_path, monkeypatch):
    """The issue's case: an engine named `x [/] y $\\undefinedcmd$` in analyze (report written,
    then the summary printed); analyze's own `[torsion]` note is printed whole."""
    from crankdyn.report import build, sections

    everything = dict(sections.builders())
    keep = ("kinematics", "torsion_modes")
    monkeypatch.setattr(build, "builders", lambda: [(k, everything[k]) for k in keep])
    name = "x [/] y $\\undefinedcmd$ <b>"
    run = cli("analyze", engine_file(tmp_path, name), "--output", tmp_path / "rep")
    assert run.status == 0, run
    assert name in run.out
    assert "the engine file has no [torsion] model" in run.out
    page = (tmp_path / "rep" / "index.html").read_text(encoding="utf-8")
    assert html.escape(name) in page and name not in page


def test_linkage_and_torsion_names(cli, tmp_path):
    linkage = (EXAMPLES / "linkages" / "fourbar-seed004.toml").read_text(encoding="utf-8")
    linkage = linkage.replace('name = "Four-bar, seed 004 link set 1"', 'name = "four [/] bar $x"')
    linkage = linkage.replace('"crank"', '"[red]crank$\\\\oops$"')  # the link and its uses
    (tmp_path / "l.toml").write_text(linkage, encoding="utf-8")
    run = cli("linkage", "check", tmp_path / "l.toml")
    assert run.status == 0, run
    assert "four [/] bar $x" in run.out and "[red]crank$\\oops$" in run.out
    model = (EXAMPLES / "torsion" / "seed003-three-disc.toml").read_text(encoding="utf-8")
    model = model.replace('"disc 2"', '"disc [/] $\\\\undefinedcmd$"')
    (tmp_path / "m.toml").write_text(model, encoding="utf-8")
    run = cli("torsion", "modes", tmp_path / "m.toml", "--plot", tmp_path / "m.png")
    assert run.status == 0, run
    assert "disc [/] $\\undefinedcmd$" in run.out
    assert (tmp_path / "m.png").stat().st_size > 0


@pytest.mark.parametrize("kind", ["engine", "model", "linkage", "study"])
@settings(max_examples=fuzz_examples(6))
@given(depth=st.integers(33, 30_000), brackets=st.sampled_from(["[]", "{}"]))
@example(depth=20_000, brackets="[]")
def test_toml_nested_deep(tmp_path_factory, kind, depth, brackets):
    """A TOML nested 20,000 deep (RecursionError in the parser) or just past the bound: one
    line, for every file format."""
    from crankdyn.errors import InputError
    from crankdyn.io.catalogue import load_torsion_model as load_model
    from crankdyn.io.engine_file import load_engine
    from crankdyn.io.linkage_file import load_linkage
    from crankdyn.io.study_file import load_study

    open_, close = brackets
    value = (open_ if open_ == "[" else "{a = ") * depth + "1" + close * depth
    path = tmp_path_factory.mktemp("deep") / "deep.toml"
    path.write_text(f"x = {value}\n", encoding="utf-8")
    load = {"engine": load_engine, "model": load_model, "linkage": load_linkage}.get(
        kind, load_study
    )
    with pytest.raises(InputError) as info:
        load(path)
    assert str(info.value) == f"{path}: invalid TOML: arrays and tables nest deeper than 32 levels"


# ---- standard output full or closed --------------------------------------------------------------

posix = pytest.mark.skipif(not os.path.exists("/dev/full"), reason="needs /dev/full (Linux)")


def crankdyn(*args, stdout):
    """``crankdyn ARGS`` in a child process writing to ``stdout``: (status, stderr)."""
    process = subprocess.run(
        [sys.executable, "-m", "crankdyn", *args],
        stdout=stdout,
        stderr=subprocess.PIPE,
        text=True,
        timeout=300,
    )
    return process.returncode, process.stderr


@posix
def test_standard_output_full():
    """A rich table into a full disk (`> /dev/full`)."""
    with open("/dev/full", "w") as full:
        status, err = crankdyn("kinematics", "vaz2108", stdout=full)
    assert (status, err) == (
        2,
        "crankdyn: error: cannot write to standard output: No space left on device\n",
    )


def _small_files():
    """In the child: files may not grow past 20 kB (RLIMIT_FSIZE, SIGXFSZ ignored), so a
    write that crosses it fails with EFBIG and no file name, as a full disk's does."""
    import resource

    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    resource.setrlimit(resource.RLIMIT_FSIZE, (20_000, 20_000))


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX resource limits")
@pytest.mark.parametrize(
    ("args", "target"),
    [
        (("analyze", "vaz2108"), "rep"),
        # no PDF, no passage: the failed write is the point, not the browser's print
        (("tvc", "verdict-geared-line", "--no-pdf", "--no-passage"), "tvc"),
        (("forces", "vaz2108", "--format", "json"), "f.json"),
    ],
)
def test_a_failed_write_names_its_target(tmp_path, args, target):
    """A write that fails for want of room (``analyze -o``, ``tvc -o`` said "cannot write to
    standard output: No space left on device", issue 33) names the folder or file being
    written, and leaves nothing behind."""
    process = subprocess.run(
        [sys.executable, "-m", "crankdyn", *args, "-o", target],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=300,
        preexec_fn=_small_files,
    )
    assert process.returncode == 2
    assert process.stderr.strip().splitlines()[-1] == (
        f"crankdyn: error: {target}: cannot write: File too large"
    )
    assert list(tmp_path.iterdir()) == []


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX pipes")
@pytest.mark.parametrize(
    "args",
    [
        ("forces", "vaz2108", "--format", "json"),
        ("examples",),
        ("kinematics", "vaz2108"),
        ("kinematics", "vaz2108", "--format", "csv"),
        ("docs", "cli"),
        ("torsion", "modes", "inline6-diesel"),
    ],
)
def test_standard_output_closed(args):
    """Output into a pipe whose reader is gone before anything is written (``| head`` that
    quit): the write fails with EPIPE at once, deterministically; a closed pipe is not an
    error (issue 33): the command ends quietly with status 0, as other command-line tools
    do."""
    read, write = os.pipe()
    os.close(read)
    try:
        status, err = crankdyn(*args, stdout=write)
    finally:
        os.close(write)
    assert (status, err) == (0, "")


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX pipes")
def test_reader_that_quits_after_two_lines():
    """``crankdyn examples | head -2``: head reads two lines and quits; crankdyn ends quietly
    with status 0 whenever its next write meets the closed pipe (issue 33)."""
    producer = subprocess.Popen(
        [sys.executable, "-m", "crankdyn", "examples"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )
    assert producer.stdout is not None and producer.stderr is not None
    producer.stdout.readline()
    producer.stdout.readline()
    producer.stdout.close()  # head quits
    err = producer.stderr.read()
    assert producer.wait(timeout=300) == 0
    assert err == b""


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX descriptors")
def test_started_with_standard_output_closed(tmp_path):
    """``crankdyn ... >&-`` (Python sets sys.stdout to None): a command that prints ends in one
    line and status 2, no traceback; one that writes only a file runs and writes it."""

    def closed(*args):
        process = subprocess.run(
            [sys.executable, "-m", "crankdyn", *args],
            stdin=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            text=True,
            timeout=300,
            preexec_fn=lambda: os.close(1),
        )
        return process.returncode, process.stderr

    message = "crankdyn: error: cannot write to standard output: standard output is closed\n"
    assert closed("kinematics", "vaz2108") == (2, message)
    assert closed("kinematics", "vaz2108", "--format", "json") == (2, message)
    target = tmp_path / "k.csv"
    status, err = closed("kinematics", "vaz2108", "--format", "csv", "-o", str(target))
    assert status == 0, err
    assert "Traceback" not in err
    assert target.read_text().startswith("crank_angle")
