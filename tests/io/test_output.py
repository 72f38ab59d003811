"""Outputs are written atomically, checked before the work, and never over what was not checked
(crankdyn.io.output; docs/robustness.md, "No data loss")."""

from __future__ import annotations

import errno
import os
import signal
import stat
import sys

import pytest

from crankdyn.errors import InputError
from crankdyn.io import output
from crankdyn.io.output import (
    atomic_directory,
    check_output_dir,
    check_writable,
    deferred_signals,
    rename_noreplace,
    write_text,
)

posix = pytest.mark.skipif(os.name != "posix", reason="POSIX file semantics")


@pytest.fixture(params=["renameat2", "portable"])
def moves(request, monkeypatch):
    """Both ways of a no-replace move: Linux's renameat2 and the portable fallback (link and
    unlink for a file, mkdir of the target as a lock for a folder)."""
    if request.param == "portable":
        monkeypatch.setattr(output, "_renameat2", lambda: None)
    elif output._renameat2() is None:
        pytest.skip("no renameat2 on this system")
    return request.param


def listing(folder):
    """The files and folders under ``folder``, crankdyn's marker (:data:`output.MARKER`, in
    every folder crankdyn writes) left out."""
    return sorted(
        p.relative_to(folder).as_posix() for p in folder.rglob("*") if p.name != output.MARKER
    )


def test_write_text_refuses_to_overwrite(tmp_path):
    path = tmp_path / "a.txt"
    write_text(path, "one")
    with pytest.raises(InputError, match="already exists"):
        write_text(path, "two")
    assert path.read_text() == "one"
    write_text(path, "two", force=True)
    assert path.read_text() == "two"
    assert [p.name for p in tmp_path.iterdir()] == ["a.txt"]


def test_write_into_missing_folder(tmp_path):
    with pytest.raises(InputError, match="does not exist"):
        write_text(tmp_path / "no" / "a.txt", "x")


def test_atomic_directory_interrupted_leaves_nothing(tmp_path):
    target = tmp_path / "report"
    with pytest.raises(KeyboardInterrupt), atomic_directory(target) as tmp:
        (tmp / "half.txt").write_text("half")
        raise KeyboardInterrupt
    assert list(tmp_path.iterdir()) == []


def test_atomic_directory_replaces_only_when_complete(tmp_path, moves):
    target = tmp_path / "report"
    with atomic_directory(target) as tmp:
        (tmp / "v1.txt").write_text("1")
    with pytest.raises(InputError, match="already exists"), atomic_directory(target):
        pass
    with pytest.raises(RuntimeError), atomic_directory(target, force=True) as tmp:
        (tmp / "v2.txt").write_text("2")
        raise RuntimeError("boom")
    assert sorted(p.name for p in target.iterdir()) == [output.MARKER, "v1.txt"]
    with atomic_directory(target, force=True) as tmp:
        (tmp / "v2.txt").write_text("2")
    assert sorted(p.name for p in target.iterdir()) == [output.MARKER, "v2.txt"]
    assert [p.name for p in tmp_path.iterdir()] == ["report"]


# ---- the target appears between the check and the move (issue 17, point 1) -----------------------


def test_a_folder_that_appeared_meanwhile_is_kept(tmp_path, capsys, moves):
    """The issue's reproduction: while the report is written, the user makes the folder and
    puts notes in it. The notes stay; the report goes to rep.2, said on stderr."""
    target = tmp_path / "rep"
    folder = atomic_directory(target)
    with folder as tmp:
        (tmp / "index.html").write_text("report")
        target.mkdir()
        (target / "my-notes.txt").write_text("notes")
    assert (target / "my-notes.txt").read_text() == "notes"
    assert listing(target) == ["my-notes.txt"]
    assert folder.path == tmp_path / "rep.2"
    assert (tmp_path / "rep.2" / "index.html").read_text() == "report"
    err = capsys.readouterr().err
    assert f"{target} appeared while the output was being written" in err
    assert str(tmp_path / "rep.2") in err and err.count("\n") == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rep", "rep.2"]


def test_an_empty_folder_that_appeared_meanwhile_is_kept(tmp_path, moves):
    """An empty folder is not ours to replace either (a plain rename would replace it)."""
    target = tmp_path / "rep"
    (tmp_path / "rep.2").mkdir()  # taken as well: the next free name is used
    folder = atomic_directory(target)
    with folder as tmp:
        (tmp / "a").write_text("1")
        target.mkdir()
    assert listing(target) == []
    assert folder.path == tmp_path / "rep.3" and listing(folder.path) == ["a"]


def test_a_file_that_appeared_meanwhile_is_kept(tmp_path, monkeypatch, capsys, moves):
    target = tmp_path / "forces.json"
    real = output._sync

    def meanwhile(handle):
        real(handle)
        target.write_text("someone else's")

    monkeypatch.setattr(output, "_sync", meanwhile)
    written = write_text(target, "ours")
    assert target.read_text() == "someone else's"
    assert written == tmp_path / "forces.2.json" and written.read_text() == "ours"
    assert "forces.2.json" in capsys.readouterr().err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["forces.2.json", "forces.json"]


def test_force_replaces_at_the_very_end(tmp_path, moves):
    """With --force the target is replaced only when the new folder is complete; whatever
    crankdyn output appeared meanwhile is what --force agreed to replace."""
    target = tmp_path / "rep"
    with atomic_directory(target) as tmp:
        (tmp / "old.txt").write_text("old")
    with atomic_directory(target, force=True) as tmp:
        (tmp / "new.txt").write_text("new")
        assert listing(target) == ["old.txt"]  # untouched while the work runs
    assert listing(target) == ["new.txt"]
    assert [p.name for p in tmp_path.iterdir()] == ["rep"]


def test_two_analyze_runs_into_one_folder(cli, tmp_path, monkeypatch):
    """Two `crankdyn analyze --out rep` runs, the second started while the first writes: the
    first to finish takes rep, the other goes to rep.2 and says so; neither replaces the
    other. (The second run is started from inside the first one's writing step: no timing.)"""
    from crankdyn.report import build, sections
    from crankdyn.report import write as write_module

    everything = sections.builders
    monkeypatch.setattr(build, "builders", lambda: everything()[:1])  # a short report
    out = tmp_path / "rep"
    real = write_module.render_html
    runs = []

    def second_run_meanwhile(report, images):
        if not runs:
            runs.append(None)  # the second run's own writing step does not start a third
            runs[0] = cli("analyze", "single-cylinder", "--output", out)
        return real(report, images)

    monkeypatch.setattr(write_module, "render_html", second_run_meanwhile)
    first = cli("analyze", "vaz2108", "--output", out)
    (second,) = runs
    assert second.status == 0 and first.status == 0
    assert "Single-cylinder" in (out / "index.html").read_text(encoding="utf-8")
    assert "VAZ" in (tmp_path / "rep.2" / "index.html").read_text(encoding="utf-8")
    assert f"{out} appeared while the output was being written" in first.err
    assert f"Report: {tmp_path / 'rep.2' / 'index.html'}" in first.out
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rep", "rep.2"]


def test_rename_noreplace(tmp_path, moves):
    a, b = tmp_path / "a", tmp_path / "b"
    a.write_text("a")
    b.write_text("b")
    with pytest.raises(FileExistsError):
        rename_noreplace(a, b)
    assert a.read_text() == "a" and b.read_text() == "b"
    (tmp_path / "dangling").symlink_to(tmp_path / "nowhere")
    with pytest.raises(FileExistsError):
        rename_noreplace(a, tmp_path / "dangling")
    rename_noreplace(a, tmp_path / "c")
    assert not a.exists() and (tmp_path / "c").read_text() == "a"
    d = tmp_path / "d"
    d.mkdir()
    (d / "x").write_text("x")
    (tmp_path / "e").mkdir()
    with pytest.raises(FileExistsError):
        rename_noreplace(d, tmp_path / "e")
    rename_noreplace(d, tmp_path / "f")
    assert listing(tmp_path / "f") == ["x"]


# ---- checks before the work (issue 17, point 4) --------------------------------------------------


@posix
def test_a_dangling_symlink_is_refused_before_the_work(tmp_path):
    link = tmp_path / "rep"
    link.symlink_to(tmp_path / "gone")
    for check in (check_output_dir, check_writable):
        with pytest.raises(InputError) as info:
            check(link, force=True)
        assert str(info.value) == (
            f"{link}: is a symbolic link to {tmp_path / 'gone'}, which does not exist; remove "
            "the link or choose another name"
        )


@posix
def test_force_never_replaces_a_linked_folder(tmp_path):
    """``-o LINK --force``, LINK a symbolic link to a folder: refused before the work, in one
    line naming the link (issue 33: the linked folder was replaced and its files deleted),
    even when the folder it points to is crankdyn's; without --force it exists."""
    real = tmp_path / "real"
    with atomic_directory(real) as tmp:
        (tmp / "old").write_text("old")
    link = tmp_path / "rep"
    link.symlink_to(real)
    with pytest.raises(InputError) as info:
        atomic_directory(link, force=True)
    assert str(info.value) == (
        f"{link}: is a symbolic link to the folder {real}; --force does not replace a linked "
        "folder (it would delete the files where the link points): remove the link or choose "
        "another name"
    )
    with pytest.raises(InputError, match="already exists; not overwritten without --force"):
        check_output_dir(link, force=False)
    assert link.is_symlink() and listing(real) == ["old"]


def test_force_never_replaces_a_folder_crankdyn_did_not_write(tmp_path, capsys):
    """``-o DIR --force`` where DIR holds the user's files and no marker: refused before the
    work in one line naming the folder and what it holds (issue 33); its files stay."""
    target = tmp_path / "notes"
    target.mkdir()
    for name in ("b.txt", "a.txt", "c", "d.csv"):
        (target / name).write_text(name)
    with pytest.raises(InputError) as info:
        atomic_directory(target, force=True)
    assert str(info.value) == (
        f"{target}: holds 4 entries (a.txt, b.txt, c, ...) and no .crankdyn-output, the marker "
        "of a folder crankdyn wrote; --force replaces only crankdyn's own output folders: "
        "remove it yourself or choose another name"
    )
    assert listing(target) == ["a.txt", "b.txt", "c", "d.csv"]
    # the same through the command line: analyze and tvc, before any work
    from crankdyn.cli import main

    for args in (["analyze", "vaz2108"], ["tvc", "verdict-geared-line"]):
        assert main([*args, "-o", str(target), "--force"]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "and no .crankdyn-output" in err
    assert listing(target) == ["a.txt", "b.txt", "c", "d.csv"]


def test_force_replaces_an_empty_folder(tmp_path):
    """An empty folder holds nothing to lose: --force replaces it (no marker needed)."""
    target = tmp_path / "rep"
    target.mkdir()
    with atomic_directory(target, force=True) as tmp:
        (tmp / "new").write_text("new")
    assert listing(target) == ["new"] and (target / output.MARKER).is_file()


def test_every_output_folder_holds_the_marker(tmp_path):
    """The marker is a regular file written with every folder; a folder holding it is
    replaced by --force, and a marker that is not a regular file does not count."""
    target = tmp_path / "rep"
    with atomic_directory(target) as tmp:
        (tmp / "a").write_text("a")
    assert "written by crankdyn" in (target / output.MARKER).read_text(encoding="utf-8")
    (target / output.MARKER).unlink()
    (target / output.MARKER).mkdir()
    with pytest.raises(InputError, match=r"no \.crankdyn-output"):
        check_output_dir(target, force=True)


def test_a_folder_that_stopped_being_crankdyns_is_kept(tmp_path, capsys, moves):
    """--force agreed to replace crankdyn's folder; if, while the work ran, its marker went
    and the user's files came, it is kept and the output goes to a numbered sibling: the
    check is repeated on the very folder that would be removed."""
    target = tmp_path / "rep"
    with atomic_directory(target) as tmp:
        (tmp / "old").write_text("old")
    folder = atomic_directory(target, force=True)
    with folder as tmp:
        (tmp / "new").write_text("new")
        (target / output.MARKER).unlink()
        (target / "mine.txt").write_text("mine")
    assert listing(target) == ["mine.txt", "old"]
    assert folder.path == tmp_path / "rep.2" and listing(folder.path) == ["new"]
    assert f"{target} is no longer a folder crankdyn wrote" in capsys.readouterr().err


def test_a_write_into_the_folder_that_names_no_file_names_the_folder(tmp_path):
    """A full disk under ``Path.write_bytes`` raises an OSError without a file name: it is an
    error of the folder being written (issue 33: it was reported as standard output's)."""
    target = tmp_path / "rep"
    with pytest.raises(InputError) as info, atomic_directory(target):
        raise OSError(errno.ENOSPC, "No space left on device")
    assert str(info.value) == f"{target}: cannot write: No space left on device"
    assert list(tmp_path.iterdir()) == []


def test_targets_of_the_wrong_kind(tmp_path):
    (tmp_path / "file").write_text("x")
    (tmp_path / "folder").mkdir()
    with pytest.raises(InputError, match="exists and is not a folder"):
        check_output_dir(tmp_path / "file", force=True)
    with pytest.raises(InputError, match="is a folder; give a file name"):
        check_writable(tmp_path / "folder", force=True)
    with pytest.raises(InputError, match="file is not a folder"):
        check_writable(tmp_path / "file" / "x.json", force=False)


@posix
def test_a_device_is_never_replaced(tmp_path):
    with pytest.raises(InputError, match="is not a regular file"):
        write_text("/dev/null", "x", force=True)
    assert stat.S_ISCHR(os.stat("/dev/null").st_mode)


@posix
@pytest.mark.skipif(os.name == "posix" and os.geteuid() == 0, reason="root may write anywhere")
def test_an_unwritable_folder_is_refused_before_the_work(tmp_path):
    locked = tmp_path / "locked"
    locked.mkdir(mode=0o500)
    try:
        with pytest.raises(InputError, match="permission denied"):
            check_output_dir(locked / "rep", force=False)
    finally:
        locked.chmod(0o700)


@pytest.mark.parametrize(
    "code", [errno.ENOSPC, errno.EACCES, errno.EROFS, errno.EDQUOT], ids=errno.errorcode.get
)
def test_os_errors_while_writing_are_one_line(tmp_path, monkeypatch, code):
    """A full disk, a permission or a read-only file system met while writing (also as root,
    for whom the checks before the work pass): one line naming the target, nothing left."""

    def fail(*args, **kwargs):
        raise OSError(code, os.strerror(code))

    monkeypatch.setattr(output, "_sync", fail)
    with pytest.raises(InputError) as info:
        write_text(tmp_path / "a.json", "x")
    assert str(info.value) == f"{tmp_path / 'a.json'}: cannot write: {os.strerror(code)}"
    with pytest.raises(InputError) as info, atomic_directory(tmp_path / "rep") as tmp:
        (tmp / "x").write_text("x")
        raise OSError(code, os.strerror(code), str(tmp / "y"))
    assert str(info.value) == f"{tmp_path / 'rep'}: cannot write: {os.strerror(code)}"
    assert list(tmp_path.iterdir()) == []


# ---- permissions (issue 17, point 6) -------------------------------------------------------------


@posix
@pytest.mark.parametrize("umask", [0o022, 0o077, 0o002])
def test_outputs_take_the_umask(tmp_path, umask):
    old = os.umask(umask)
    try:
        path = write_text(tmp_path / "a.json", "x")
        with atomic_directory(tmp_path / "rep") as tmp:
            (tmp / "f").write_text("f")
    finally:
        os.umask(old)
    assert stat.S_IMODE(path.stat().st_mode) == 0o666 & ~umask
    assert stat.S_IMODE((tmp_path / "rep").stat().st_mode) == 0o777 & ~umask


# ---- signals -------------------------------------------------------------------------------------


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
def test_signals_are_held_during_a_move(tmp_path):
    """A SIGTERM (or SIGINT) that arrives during a move is delivered after it."""
    seen = []
    previous = signal.signal(signal.SIGTERM, lambda s, f: seen.append(("handler", s)))
    # the test sets the disposition it tests (a background job starts with SIGINT ignored)
    previous_int = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        with deferred_signals():
            os.kill(os.getpid(), signal.SIGTERM)
            seen.append("moved")
        assert seen == ["moved", ("handler", signal.SIGTERM)]
        with pytest.raises(KeyboardInterrupt), deferred_signals():
            os.kill(os.getpid(), signal.SIGINT)
            seen.append("second")
        assert seen[-1] == "second"
    finally:
        signal.signal(signal.SIGTERM, previous)
        signal.signal(signal.SIGINT, previous_int)


@posix
def test_commands_check_their_targets_before_the_work(cli, tmp_path, monkeypatch):
    """The issue's `analyze --out` a dangling symlink failed with NotADirectoryError after the
    whole analysis; every writing command now checks its target first (the analysis would
    raise here)."""
    from crankdyn.report import build

    def no_work(*args, **kwargs):
        raise AssertionError("the work started")

    monkeypatch.setattr(build, "builders", no_work)
    link = tmp_path / "rep"
    link.symlink_to(tmp_path / "gone")
    message = (
        f"is a symbolic link to {tmp_path / 'gone'}, which does not exist; remove the link or "
        "choose another name"
    )
    for args in (
        ("analyze", "vaz2108", "--output", link),
        ("forces", "vaz2108", "-o", link),
        ("balance", "vaz2108", "--plot", tmp_path / "nowhere" / "b.png"),
        ("study", "inline4-rod-and-firing", "--output", link),
    ):
        run = cli(*args)
        assert run.status == 2, (args, run)
        assert run.err.count("\n") == 1
        assert message in run.err or "the folder" in run.err, (args, run.err)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rep"]
