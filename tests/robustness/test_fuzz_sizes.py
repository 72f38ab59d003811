"""Every size bounded before it is allocated (issue 33, "Sizes nothing bounds"): NumPy signal
files whose headers claim any shape and type, archives that unpack far beyond their bytes, and
the options and keys that set the size of a grid (``--teeth``, ``[tvc] speed_step``). The only
outcomes allowed are a result or the one-line InputError, within a bounded memory."""

from __future__ import annotations

import io
import math
import tracemalloc
import zipfile
from importlib import resources

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from numpy.lib import format as npy

from crankdyn.errors import InputError
from crankdyn.io.files import MAX_ARRAY_BYTES, MAX_ARRAY_VALUES, read_numpy
from crankdyn.io.signals import read_signal
from tests.conftest import fuzz_examples

LIMIT = 4 * MAX_ARRAY_BYTES
"""The most memory (bytes, by tracemalloc) reading one NumPy signal file may take: the file's
bytes, one float copy of its arrays and change."""


def npy_bytes(shape: tuple[int, ...], dtype: str, data: bytes, version=(1, 0)) -> bytes:
    """A .npy file whose header claims ``shape`` and ``dtype``, followed by ``data``."""
    out = io.BytesIO()
    header = {"descr": np.dtype(dtype).str, "fortran_order": False, "shape": shape}
    if version == (1, 0):
        npy.write_array_header_1_0(out, header)
    else:
        npy.write_array_header_2_0(out, header)
    return out.getvalue() + data


def npz_bytes(members: dict[str, bytes]) -> bytes:
    out = io.BytesIO()
    with zipfile.ZipFile(out, "w", compression=zipfile.ZIP_DEFLATED) as archive:
        for name, data in members.items():
            archive.writestr(f"{name}.npy", data)
    return out.getvalue()


def bounded(path, teeth=36):
    """Read the signal within :data:`LIMIT` bytes of memory: the signal or the InputError."""
    tracemalloc.start()
    try:
        try:
            outcome = read_signal(path, teeth)
        except InputError as exc:
            outcome = exc
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < LIMIT, f"{peak / 2**20:.0f} MiB"
    if isinstance(outcome, InputError):
        assert "\n" not in str(outcome)
    return outcome


@pytest.mark.parametrize("shape", [(10**12,), (10**6, 10**6), (2**62, 4), (MAX_ARRAY_VALUES + 1,)])
def test_a_header_claiming_a_huge_shape_is_refused(tmp_path, shape):
    """A .npy (and an archive member) whose header claims 10**12 values ended in numpy's
    _ArrayMemoryError: now one line naming the file, the array and the claim. Pulse times (one
    column) are read in chunks, of any length (issue 37): their claim is held against the data
    the file holds; a speed signal (two columns) is read whole, at most 4,194,304 values."""
    path = tmp_path / "claim.npy"
    path.write_bytes(npy_bytes(shape, "<f8", b"\0" * 64))
    error = bounded(path)
    assert isinstance(error, InputError)
    assert str(error).startswith(f"{path}: array: the header claims shape {shape}")
    size = math.prod(shape) * 8
    if len(shape) == 1:
        assert str(error).endswith(f"({size:,} bytes of data) and the file holds 64 (truncated?)")
    else:
        assert f"crankdyn reads at most {MAX_ARRAY_VALUES:,} values (32 MiB)" in str(error)
    archive = tmp_path / "claim.npz"
    archive.write_bytes(npz_bytes({"time": npy_bytes(shape, "<f8", b"\0" * 64)}))
    error = bounded(archive)
    assert str(error).startswith(f"{archive}: time: the header claims shape {shape}")


@pytest.mark.parametrize("short", [True, False])
def test_an_archive_that_unpacks_to_gigabytes_is_refused_unread(tmp_path, short):
    """A 0.8 MB .npz of 1e8 zeros reached 3.1 GB before its error (the 32 MiB limit applied to
    the compressed bytes). Pulse times are now read in chunks (issue 37): a member holding less
    than its header claims is refused before anything is unpacked; one holding it all is read
    a chunk at a time and refused at its second pulse, in bounded memory."""
    out = io.BytesIO()
    block = bytes(1 << 20)
    zeros = 800_000_000 // len(block) * len(block) if short else 800_000_000
    with (
        zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED, compresslevel=1) as archive,
        archive.open("time.npy", "w", force_zip64=True) as member,
    ):
        member.write(npy_bytes((10**8,), "<f8", b""))
        for _ in range(zeros // len(block)):
            member.write(block)
        member.write(bytes(zeros % len(block)))
    path = tmp_path / "zeros.npz"
    path.write_bytes(out.getvalue())
    assert path.stat().st_size < 4_000_000  # a few MB (0.8 MB at zip's best compression)
    error = bounded(path)
    assert isinstance(error, InputError)
    if short:
        assert str(error) == (
            f"{path}: time: the header claims shape (100000000,) (800,000,000 bytes of data) "
            f"and the file holds {zeros:,} (truncated?)"
        )
    else:
        assert str(error) == (
            f"{path}: time = 0.0: times must increase: sample 2 has 0 s after 0 s"
        )


def test_a_truncated_file_and_objects_are_refused(tmp_path):
    path = tmp_path / "short.npy"
    path.write_bytes(npy_bytes((1000,), "<f8", b"\0" * 80))
    assert "the header claims shape (1000,) (8,000 bytes of data) and the file holds 80" in str(
        bounded(path)
    )
    path.write_bytes(npy_bytes((3,), "|O", b"\0" * 24))
    assert str(bounded(path)) == f'{path}: array = "object": expected numbers'


def test_the_largest_file_accepted_is_read(tmp_path):
    """MAX_ARRAY_VALUES pulse times (the bound before pulse records were read in chunks) are
    read whole by read_signal within the memory bound (and the result is right)."""
    times = np.linspace(0.0, 100.0, MAX_ARRAY_VALUES)
    path = tmp_path / "big.npy"
    np.save(path, times)
    train = bounded(path, teeth=60)
    assert not isinstance(train, InputError)
    assert train.times.size == MAX_ARRAY_VALUES and train.times[-1] == 100.0


def test_read_numpy_gives_the_arrays(tmp_path):
    path = tmp_path / "a.npz"
    np.savez_compressed(path, time=np.arange(5.0), speed=np.full(5, 2.0))
    arrays = read_numpy(path, names=("time", "speed"))
    assert isinstance(arrays, dict) and sorted(arrays) == ["speed", "time"]
    np.testing.assert_array_equal(arrays["time"], np.arange(5.0))


shapes = st.lists(
    st.one_of(st.integers(0, 8), st.integers(0, 2**40), st.integers(0, 2**63 - 1)),
    min_size=0,
    max_size=4,
).map(tuple)
dtypes = st.sampled_from(["<f8", ">f8", "<f4", "<i8", "|u1", "<f2", "<c16", "|b1", "<U3", "|O"])


@settings(max_examples=fuzz_examples(60))
@given(
    shape=shapes,
    dtype=dtypes,
    data=st.binary(max_size=256),
    archive=st.booleans(),
    version=st.sampled_from([(1, 0), (2, 0)]),
)
@example(shape=(10**12,), dtype="<f8", data=b"", archive=False, version=(1, 0))
@example(shape=(10**6, 10**6), dtype="<f8", data=b"", archive=True, version=(2, 0))
def test_fuzz_numpy_headers(tmp_path_factory, shape, dtype, data, archive, version):
    """Any shape and type a header may claim, any data after it: a signal or one line, in
    bounded memory."""
    folder = tmp_path_factory.mktemp("npy")
    content = npy_bytes(shape, dtype, data, version)
    if archive:
        path = folder / "s.npz"
        path.write_bytes(npz_bytes({"time": content}))
    else:
        path = folder / "s.npy"
        path.write_bytes(content)
    bounded(path)


# ---- --teeth against the record ---------------------------------------------------------------


def _records(folder):
    """A sampled speed signal (CSV) and a pulse record (60 teeth), both about 13 revolutions."""
    import math

    t = np.arange(0.0, 0.4, 1e-4)
    speed = folder / "speed.csv"
    speed.write_text(
        "time [s],speed [rpm]\n" + "".join(f"{a:.6f},2000\n" for a in t), encoding="utf-8"
    )
    pulses = folder / "pulses.csv"
    pitch = 2 * math.pi / 60 / (2000 * math.pi / 30)
    pulses.write_text(
        "time [s]\n" + "".join(f"{k * pitch:.9f}\n" for k in range(800)), encoding="utf-8"
    )
    return {"speed": str(speed), "pulses": str(pulses)}


@settings(max_examples=fuzz_examples(12))
@given(
    teeth=st.one_of(st.integers(-3, 512), st.integers(10**6, 10**15)),
    kind=st.sampled_from(["speed", "pulses"]),
)
@example(teeth=100_000_000, kind="speed")
@example(teeth=100_000_000, kind="pulses")
def test_fuzz_teeth(tmp_path_factory, teeth, kind):
    """Any --teeth on either kind of record: the analysis, or one line naming the file or
    --teeth, never an allocation beyond the stated bound (4,194,304 pulses)."""
    from crankdyn.cli.measure import load_measurement

    path = _records(tmp_path_factory.mktemp("teeth"))[kind]
    tracemalloc.start()
    try:
        try:
            load_measurement(path, teeth, cycle="four-stroke", orders=[1.0])
        except InputError as exc:
            assert "\n" not in str(exc)
            assert str(exc).startswith((f"{path}:", "--teeth")), str(exc)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < LIMIT, f"{peak / 2**20:.0f} MiB"


# ---- [tvc] speed_step, capped like --speeds ------------------------------------------------

EXAMPLE_LINE = resources.files("crankdyn") / "examples" / "torsion" / "verdict-geared-line.toml"
LINE = EXAMPLE_LINE.read_text(encoding="utf-8")


def test_speed_step_capped_like_speeds(tmp_path, capsys):
    """``[tvc] speed_step = "0.0001 rpm"`` made a 6-million-speed grid and a 6.44 GiB traceback:
    refused at the key, before the work, with the bound of --speeds (100,000 speeds) and the
    least step the range takes; a range too wide for the default step names the range."""
    from crankdyn.cli import main

    path = tmp_path / "line.toml"
    path.write_text(LINE + '\n[tvc]\nspeed_step = "0.0001 rpm"\n', encoding="utf-8")
    for args in (["tvc", str(path)], ["torsion", "response", str(path)]):
        assert main(args) == 2
        assert capsys.readouterr().err == (
            f'crankdyn: error: {path}: [tvc] speed_step = "0.0001 rpm": makes 6,000,001 speeds '
            "over 400 to 1000 rpm ([operating] speed_range); at most 100,000, as --speeds (a "
            "step of at least 0.006 rpm)\n"
        )
    path.write_text(LINE + '\n[tvc]\nspeed_range = ["1 rpm", "1e7 rpm"]\n', encoding="utf-8")
    assert main(["tvc", str(path)]) == 2
    assert capsys.readouterr().err == (
        f'crankdyn: error: {path}: [tvc] speed_range = ["1 rpm", "1e7 rpm"]: 1 to 1e+07 rpm at '
        "the default step of 10 rpm makes 1,000,001 speeds; at most 100,000: give a coarser "
        "speed_step\n"
    )


@settings(max_examples=fuzz_examples(40))
@example(step=1e-05, low=1.0, span=1.0)  # 100,000 steps to the bit: found by the campaign
@given(
    step=st.floats(1e-9, 1e6, allow_nan=False),
    low=st.floats(1.0, 1e5),
    span=st.floats(0.001, 1e7),
)
def test_fuzz_speed_step(tmp_path_factory, step, low, span):
    """Any step over any range: read (its grid at most 100,000 speeds) or one line."""
    from crankdyn.torsion.model import TorsionModel

    path = tmp_path_factory.mktemp("step") / "line.toml"
    path.write_text(
        LINE + f'\n[tvc]\nspeed_step = "{step!r} rpm"\n'
        f'speed_range = ["{low!r} rpm", "{low + span!r} rpm"]\n',
        encoding="utf-8",
    )
    try:
        model = TorsionModel.from_file(path)
    except InputError as exc:
        assert "\n" not in str(exc)
        return
    low_w, high_w = model.tvc.speed_range
    # the speeds of the grid the TVC makes (tvc.analysis._grid: the steps from the start, and
    # the range's end when they stop short of it)
    step = model.tvc.step
    count = math.floor((high_w - low_w) / step * (1 + 1e-12)) + 1
    grid = low_w + step * np.arange(count)
    assert np.unique(np.concatenate([grid[grid < high_w], [high_w]])).size <= 100_000
