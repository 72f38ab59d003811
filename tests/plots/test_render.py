"""Figures written on every core (issue 16): the pool writes what one process writes."""

from __future__ import annotations

import contextlib
import sys

import numpy as np
import pytest
from matplotlib.figure import Figure

from crankdyn.plots.render import render_figures, workers_for


def _figures(n: int = 3) -> list[Figure]:
    out = []
    for k in range(n):
        fig = Figure(figsize=(3.0, 2.0), layout="constrained")
        ax = fig.add_subplot()
        x = np.linspace(0.0, 6.0, 50)
        ax.plot(x, np.sin((k + 1) * x))
        ax.set_title(f"figure {k}")
        out.append(fig)
    return out


def test_the_pool_writes_what_one_process_writes(tmp_path):
    serial = render_figures([(f, None, None) for f in _figures()], workers=1)
    jobs = [(f, tmp_path / f"{i}.png", tmp_path / f"{i}.svg") for i, f in enumerate(_figures())]
    seen = []
    pooled = render_figures(jobs, workers=2, progress=seen.append)
    assert pooled == serial and all(png.startswith(b"\x89PNG") for png in pooled)
    assert sorted(seen) == [0, 1, 2]
    for i, png in enumerate(pooled):
        assert (tmp_path / f"{i}.png").read_bytes() == png
        assert (tmp_path / f"{i}.svg").read_text(encoding="utf-8").lstrip().startswith("<?xml")


def test_workers_never_exceed_the_figures():
    assert workers_for(1) == 1 and 1 <= workers_for(50) <= 50


def _without_ids(svg: str) -> str:
    """An SVG file with matplotlib's random element ids (clip paths, markers) and its date
    left out."""
    import re

    svg = re.sub(r"<dc:date>.*?</dc:date>", "", svg, flags=re.S)
    return re.sub(r"\b([pm])[0-9a-f]{10}\b", r"\1", svg)


def test_one_figure_drawn_as_png_and_svg_by_two_workers_is_what_one_process_writes(tmp_path):
    """Fewer figures than cores (a study summary): the PNG and the SVG of a figure are drawn
    by workers of their own, the SVG's laid out again; the files are those of one process."""
    fig = _figures(1)[0]
    fig.subplots(1, 3)  # more axes: a layout with something to lay out
    one = tmp_path / "one"
    two = tmp_path / "two"
    one.mkdir()
    two.mkdir()
    serial = render_figures([(fig, one / "f.png", one / "f.svg")], workers=1)
    fig = _figures(1)[0]
    fig.subplots(1, 3)
    seen = []
    split = render_figures([(fig, two / "f.png", two / "f.svg")], progress=seen.append)
    assert split == serial and seen == [0]
    assert (two / "f.png").read_bytes() == serial[0]
    svg = [_without_ids((d / "f.svg").read_text(encoding="utf-8")) for d in (one, two)]
    assert svg[0] == svg[1]


def test_the_svg_writes_its_words_as_text_in_a_font_stack(tmp_path):
    """The SVG's words are text (searchable, escaped), not glyph outlines; the PNG is a PNG."""
    fig = _figures(1)[0]
    fig.axes[0].set_xlabel("Crank angle <&> (deg)")
    (png,) = render_figures([(fig, None, tmp_path / "f.svg")], workers=1)
    svg = (tmp_path / "f.svg").read_text(encoding="utf-8")
    assert png.startswith(b"\x89PNG")
    assert "Crank angle &lt;&amp;&gt; (deg)</text>" in svg and "figure 0</text>" in svg
    assert "font-family: 'DejaVu Sans'" in svg and "sans-serif" in svg
    assert "DejaVuSans-" not in svg  # no glyph definitions


def _report_like_figure(title: str = "Bearing loads") -> Figure:
    """A crankdyn figure with constrained layout, a suptitle, legends outside their axes and
    axes of different label widths: something for the layout to do."""
    from crankdyn.plots.style import legend_outside, new_figure

    fig, axes = new_figure(2, 2, width=8.0)
    x = np.linspace(0.0, 720.0, 200)
    for k, ax in enumerate(axes.flat):
        ax.plot(x, (10.0 ** (2 * k)) * np.sin(np.radians(x)), label=f"{title} {k}")
        ax.set_ylabel(f"load {k} (N)" * (k + 1))
        legend_outside(ax)
    fig.suptitle(title)
    return fig


def test_laid_out_once_the_files_are_those_of_matplotlibs_own_save(tmp_path):
    """Laying a figure out once (lay_out) and drawing it once per format writes the PNG that
    matplotlib's own savefig writes with constrained layout, and the SVG it writes with that
    layout kept (``set_layout_engine("none")``, which costs each save an extra undrawn pass)."""
    import matplotlib

    reference = _report_like_figure()
    reference.savefig(tmp_path / "ref.png", dpi=110, pil_kwargs={"compress_level": 1})
    reference.set_layout_engine("none")
    with matplotlib.rc_context({"svg.fonttype": "none"}):
        reference.savefig(tmp_path / "ref.svg", format="svg")
    fig = _report_like_figure()
    (png,) = render_figures([(fig, tmp_path / "f.png", tmp_path / "f.svg")], workers=1)
    assert fig.get_layout_engine() is None
    _same_pixels(png, (tmp_path / "ref.png").read_bytes())
    svg = [_without_ids((tmp_path / n).read_text(encoding="utf-8")) for n in ("f.svg", "ref.svg")]
    assert svg[0] == svg[1]


def _same_pixels(png: bytes, reference: bytes) -> None:
    """Two PNG files hold the same pixels (mode, size, every byte of every pixel) and the same
    resolution and ``Software`` text."""
    import io

    from PIL import Image

    a, b = (Image.open(io.BytesIO(data)) for data in (png, reference))
    assert (a.mode, a.size, a.info) == (b.mode, b.size, b.info)
    assert a.tobytes() == b.tobytes()


def test_the_png_holds_the_pixels_of_matplotlibs_own_png_unfiltered_at_zlib_level_1():
    """The PNG is written from Agg's raw pixels (png_file: no filter per row, zlib at
    PNG_COMPRESSION) instead of by Pillow, whose choice of a filter for every row took as long
    as the compression: the same pixels, resolution and Software text as matplotlib's PNG."""
    import io
    import zlib

    from crankdyn.plots.render import PNG_COMPRESSION, PNG_DPI, _png, lay_out

    reference = _report_like_figure()
    lay_out(reference)
    buffer = io.BytesIO()
    reference.savefig(buffer, format="png", dpi=PNG_DPI, pil_kwargs={"compress_level": 1})
    fig = _report_like_figure()
    lay_out(fig)
    canvas = fig.canvas
    png = _png(fig)
    assert fig.canvas is canvas  # an Agg canvas made for the draw is not left behind
    _same_pixels(png, buffer.getvalue())
    # one IDAT chunk: every row starts with filter type 0, compressed at level 1
    start = png.index(b"IDAT") + 4
    size = int.from_bytes(png[start - 8 : start - 4], "big")
    raw = zlib.decompress(png[start : start + size])
    from PIL import Image

    width, height = Image.open(buffer).size  # matplotlib's own PNG's (its rounding)
    assert len(raw) == height * (4 * width + 1)
    assert set(raw[:: 4 * width + 1]) == {0}
    assert PNG_COMPRESSION == 1 and png[start + 1] >> 6 == 0  # zlib header: fastest level


def test_png_file_refuses_pixels_of_another_size():
    from crankdyn.plots.render import png_file

    with pytest.raises(ValueError, match="RGBA pixels"):
        png_file(bytes(4 * 5), 2, 2, dpi=110)


def _shared_axes_figure() -> Figure:
    """Panels of different heights sharing their x axes (one ticker: the formatter is shared),
    a log axis, words as tick labels, a legend outside: what the report's figures have."""
    from crankdyn.plots.style import legend_outside

    fig = _figures(1)[0]
    fig.clear()
    fig.set_size_inches(6.0, 5.0)
    axes = fig.subplots(3, 1, sharex=True, height_ratios=[3, 1, 2])
    x = np.linspace(1.0, 2000.0, 300)
    axes[0].plot(x, 1e5 * np.sin(x / 300.0), label="large")
    axes[1].semilogy(x, x**2, label="log")
    axes[2].bar(["cyl 1", "cyl 2", "cyl 3"], [3.0, 1.0, 2.0])
    for ax in axes[:2]:
        legend_outside(ax)
    return fig


def test_ticks_kept_changes_no_byte_and_makes_the_ticks_fewer_times():
    """Inside ticks_kept each axis makes its ticks once per state (not at every question the
    layout and the draw ask); the PNG and the SVG are those drawn without it, and the axes'
    own methods are back afterwards."""
    import io

    from matplotlib.axis import Axis

    from crankdyn.plots import render
    from crankdyn.plots.render import _png, _svg, lay_out

    if not render._checked_matplotlib():
        pytest.skip("ticks_kept is checked with matplotlib 3.8-3.11 and draws plainly otherwise")
    ticks_kept = render.ticks_kept
    made = []
    original = Axis._update_ticks

    def counting(self):
        made.append(self)
        return original(self)

    files = []
    Axis._update_ticks = counting
    try:
        for kept in (False, True):
            for make in (_report_like_figure, _shared_axes_figure):
                fig = make()
                made.clear()
                # without it: not even the blocks lay_out, _png and _svg open of their own
                render.ticks_kept = ticks_kept if kept else lambda fig: contextlib.nullcontext()
                with render.ticks_kept(fig):
                    lay_out(fig, keep_canvas=True)
                    png = _png(fig)
                    svg = io.BytesIO()
                    _svg(fig, svg)
                files.append((png, _without_ids(svg.getvalue().decode("utf-8")), len(made)))
                axis = fig.axes[0].xaxis
                assert "_update_ticks" not in vars(axis)
                assert "_get_ticklabel_bboxes" not in vars(axis)
    finally:
        Axis._update_ticks = original
        render.ticks_kept = ticks_kept
    for plain, kept in zip(files[:2], files[2:], strict=True):
        assert kept[:2] == plain[:2]
        assert kept[2] * 3 < plain[2]


def test_ticks_kept_stands_in_for_nothing_under_a_matplotlib_it_was_not_checked_with(
    monkeypatch,
):
    """Under another matplotlib than 3.8-3.11 (its private tick methods may differ) the figure
    is drawn as matplotlib draws it: nothing stands in for the axes' methods."""
    import matplotlib

    from crankdyn.plots import render

    for version, checked in (
        ("3.7.5", False),
        ("3.8.0", True),
        ("3.11.2", True),
        ("3.12.0", False),
    ):
        render._checked_matplotlib.cache_clear()
        monkeypatch.setattr(matplotlib, "__version__", version)
        assert render._checked_matplotlib() is checked
        fig = _report_like_figure()
        with render.ticks_kept(fig):
            assert ("_update_ticks" in vars(fig.axes[0].xaxis)) is checked
    render._checked_matplotlib.cache_clear()


def test_laid_out_on_a_kept_canvas_the_files_are_the_same_and_no_word_is_measured_again(
    tmp_path,
):
    """A renderer's child keeps the Agg canvas the layout was measured on (``keep_canvas``):
    the PNG is drawn by that renderer, whose cache holds every word's size, so no word is
    measured again, and the PNG and SVG are those of a figure laid out without it."""
    import io

    from matplotlib.backends.backend_agg import RendererAgg

    from crankdyn.plots.render import _png, _svg, lay_out

    files = []
    measured = []
    original = RendererAgg.get_text_width_height_descent

    def counting(self, *args, **kwargs):
        measured[-1] += 1
        return original(self, *args, **kwargs)

    RendererAgg.get_text_width_height_descent = counting
    try:
        for keep in (False, True):
            fig = _report_like_figure()
            measured.append(0)
            lay_out(fig, keep_canvas=keep)
            measured[-1] = 0  # the words measured by the PNG's draw only
            png = _png(fig)
            svg = io.BytesIO()
            _svg(fig, svg)
            files.append((png, _without_ids(svg.getvalue().decode("utf-8"))))
    finally:
        RendererAgg.get_text_width_height_descent = original
    assert files[0] == files[1]
    assert measured[0] > 0
    assert measured[1] == 0


def test_lay_out_measures_a_hostile_title_as_written(tmp_path):
    """A name that matplotlib's math parser rejects is laid out and drawn literally."""
    fig = _report_like_figure(r"$\undefinedcmd{x}$ & <b>")
    (png,) = render_figures([(fig, None, tmp_path / "f.svg")], workers=1)
    assert png.startswith(b"\x89PNG")
    assert r"$\undefinedcmd{x}$ &amp; &lt;b&gt;" in (tmp_path / "f.svg").read_text("utf-8")


def _temp_folders() -> set[str]:
    import tempfile
    from pathlib import Path

    return {p.name for p in Path(tempfile.gettempdir()).glob("crankdyn-plots-*")}


@pytest.fixture
def own_temp(tmp_path, monkeypatch):
    """The temporary folders of this test only: another test's or process's renderer (a test
    worker running `analyze` at the same moment) makes its folders in the shared one."""
    import tempfile

    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    return tmp_path


def test_a_renderer_draws_figures_submitted_while_busy_as_one_process_does(own_temp):
    """Figures submitted one by one while this process is busy (a report's sections) come back
    as one process draws them, in the order submitted, each reported done once; the children's
    folder is gone afterwards."""
    from crankdyn.plots.render import Renderer

    before = _temp_folders()
    with Renderer(1) as here:
        for fig in _figures(4):
            here.submit(fig)
        serial = here.results()
    seen: list[int] = []
    with Renderer(2) as renderer:
        renderer.busy()
        figures = _figures(4)
        for fig in figures:
            renderer.submit(fig)
        assert renderer.submit(figures[0]) == 0 and figures[2] in renderer
        pooled = renderer.results(progress=seen.append)
    assert sorted(seen) == [0, 1, 2, 3]
    assert [png for png, _ in pooled] == [png for png, _ in serial]
    for (_, a), (_, b) in zip(pooled, serial, strict=True):
        assert a is not None and b is not None
        assert _without_ids(a.decode("utf-8")) == _without_ids(b.decode("utf-8"))
    assert _temp_folders() <= before


class _Fails(Exception):
    pass


def _failing_figure() -> Figure:
    from matplotlib.artist import Artist

    class Broken(Artist):
        def draw(self, renderer):
            raise _Fails("drawn")

    fig = _figures(1)[0]
    fig.axes[0].add_artist(Broken())
    return fig


def test_a_figure_that_fails_in_its_child_is_drawn_here_and_its_error_raised_here(own_temp):
    """A child that fails leaves no file; the figure is then drawn in this process, where the
    error is raised as it would be without children, and no child is left behind."""
    import pytest

    from crankdyn.plots.render import Renderer

    before = _temp_folders()
    with Renderer(2) as renderer:
        renderer.submit(_figures(1)[0])
        renderer.submit(_failing_figure())
        with pytest.raises(_Fails):
            renderer.results()
    assert _temp_folders() <= before


def test_closing_a_renderer_stops_its_children(own_temp):
    """Leaving the block early (an error in the analyses) stops the children still drawing and
    removes their folder."""
    import os

    from crankdyn.plots.render import Renderer

    before = _temp_folders()
    with Renderer(2) as renderer:
        for fig in _figures(3):
            renderer.submit(fig)
        pids = [pid for pid, _, _ in renderer._running.values()]
    for pid in pids:  # reaped: no such child any more
        try:
            os.waitpid(pid, os.WNOHANG)
        except ChildProcessError:
            continue
        raise AssertionError(f"child {pid} left behind")
    assert _temp_folders() <= before


def test_the_collector_paused_for_the_figures_resumes_as_it_was_and_frees_them_later():
    """No collector passes while a report's figures are made (issue 16's process speed); after
    the block the collector is on again (or still off, when it was), what was made meanwhile is
    in the oldest generation, not frozen, and a full pass frees its cycles."""
    import gc
    import weakref

    from crankdyn.plots.render import collector_paused

    class Node:
        pass

    assert gc.isenabled()
    with collector_paused():
        assert not gc.isenabled()
        node = Node()
        node.me = node  # a cycle only the collector frees
        alive = weakref.ref(node)
        del node
        assert gc.get_count()[0] >= 1  # young objects counted, not collected
    assert gc.isenabled()
    assert gc.get_freeze_count() == 0
    assert alive() is not None
    gc.collect()
    assert alive() is None

    gc.disable()
    try:
        with collector_paused():
            pass
        assert not gc.isenabled()  # a caller's choice is kept
    finally:
        gc.enable()


def test_the_collector_stays_on_for_a_caller_that_froze_objects():
    """With objects frozen by the caller (a pre-fork server) the pause leaves them frozen."""
    import gc

    from crankdyn.plots.render import collector_paused

    gc.freeze()
    try:
        frozen = gc.get_freeze_count()
        with collector_paused():
            pass
        assert gc.get_freeze_count() == frozen
        assert gc.isenabled()
    finally:
        gc.unfreeze()


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="forks (Linux)")
def test_a_child_forked_after_preparing_loads_no_writer_of_its_own():
    """The backends, Pillow's PNG writer and the image plugins Pillow loads at its first save
    are loaded once before the children fork (issue 16's process speed), not in each child."""
    import io
    import os

    from crankdyn.plots.render import _png, _svg, lay_out, prepare_children

    prepare_children()
    prepare_children()  # once per process
    fig = _figures(1)[0]
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:  # the child: draw, say which modules it loaded, exit
        code = 1
        try:
            os.close(read)
            before = set(sys.modules)
            lay_out(fig)
            _png(fig)
            _svg(fig, io.BytesIO())
            loaded = sorted(set(sys.modules) - before)
            os.write(write, "\n".join(loaded).encode())
            code = 0
        finally:
            os._exit(code)
    os.close(write)
    with os.fdopen(read, "rb") as pipe:
        loaded = pipe.read().decode().split()
    _, status = os.waitpid(pid, 0)
    assert status == 0
    assert [m for m in loaded if m.startswith(("PIL", "matplotlib.backends"))] == []


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals and fork")
def test_a_signal_as_a_child_is_forked_ends_the_child_not_a_copy_of_this_process(
    tmp_path, monkeypatch
):
    """A SIGTERM that reaches a drawing child at once after the fork (close() sends one to the
    children still drawing when an analysis is interrupted) ends that child by its default
    action. It was handled by this process's handler (the command line's raises) before the
    child entered its try, and the child ran on as a copy of this process (under pytest: a
    second worker waiting for tests, and close() waiting for it for ever). The child here
    signals itself before returning from the fork; were the signal handled, the exception
    would reach this test in the child, which leaves a mark and exits."""
    import os
    import signal

    from crankdyn.plots import render

    class _Handled(Exception):
        pass

    def handler(signum, frame):
        raise _Handled

    parent = os.getpid()
    mark = tmp_path / "escaped"
    real_fork = os.fork

    def fork():
        pid = real_fork()
        if pid == 0:
            os.kill(os.getpid(), signal.SIGTERM)
        return pid

    before = signal.signal(signal.SIGTERM, handler)
    monkeypatch.setattr(os, "fork", fork)
    try:
        with render.Renderer(2) as renderer:
            renderer.submit(_figures(1)[0])
            ((png, _),) = renderer.results()
    except BaseException:
        if os.getpid() != parent:
            mark.write_text("the child ran on")
            os._exit(3)
        raise
    finally:
        if os.getpid() != parent:  # pragma: no cover - the child escaped its try
            mark.write_text("the child ran on")
            os._exit(3)
        signal.signal(signal.SIGTERM, before)
    assert not mark.exists()
    assert png.startswith(b"\x89PNG")  # the figure drawn here, the child having died
