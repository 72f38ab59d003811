"""``crankdyn measure`` and ``crankdyn analyze --measurement`` in process."""

import json
import math

import numpy as np
import pytest

from crankdyn.measure.synthetic import PrescribedMotion, synthetic_pulses

RPM = 30.0 / math.pi
ORDERS = np.array([1.5, 3.0, 4.5])
X = np.array([2e-3, 5e-3 * np.exp(1j), 1e-3 * np.exp(-2j)])


def _csv(path, train, reference=True):
    lines = ["time [s],reference [s]" if reference else "time [s]"]
    ref = list(train.reference) if reference and train.reference is not None else []
    for i, t in enumerate(train.times):
        cell = f"{ref[i]:.12f}" if i < len(ref) else ""
        lines.append(f"{t:.12f},{cell}" if reference else f"{t:.12f}")
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return str(path)


@pytest.fixture
def steady_csv(tmp_path):
    motion = PrescribedMotion(1800 / RPM, 0.0, ORDERS, X)
    return _csv(tmp_path / "steady.csv", synthetic_pulses(motion, 60, 1.0, reference_every=2))


@pytest.fixture
def runup_csv(tmp_path):
    motion = PrescribedMotion(1500 / RPM, 300 / RPM, ORDERS, X)
    return _csv(tmp_path / "runup.csv", synthetic_pulses(motion, 60, 2.0, reference_every=2))


def one_line_error(cli, *args):
    run = cli(*args)
    assert run.status == 2, run
    lines = run.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("crankdyn: error: "), run.err
    return lines[0]


def test_steady_json_has_the_issues_keys(cli, steady_csv):
    run = cli("measure", steady_csv, "--teeth", "60", "--orders", "1.5,3,4.5", "--format", "json")
    assert run.status == 0, run
    data = json.loads(run.out)
    assert data["speed_rpm"] == pytest.approx(1800.0, rel=1e-6)
    assert data["orders"] == [1.5, 3.0, 4.5]
    assert np.allclose(data["amplitude_rad"], np.abs(X), rtol=0.01)
    assert np.allclose(data["phase_deg"], np.degrees(np.angle(X)), atol=1.0)
    assert data["window"].startswith("uniform (rectangular) over 1 cycle")
    assert "complex (synchronous) average" in data["averaging"]


def test_tracking_json_per_speed_bin(cli, runup_csv):
    run = cli(
        "measure",
        runup_csv,
        "--teeth",
        "60",
        "--orders",
        "1.5,3,4.5",
        "--bin",
        "20",
        "--format",
        "json",
    )
    assert run.status == 0, run
    data = json.loads(run.out)
    assert data["kind"] == "run-up"
    speeds = np.array(data["speed_rpm"])
    amplitude = np.array(data["amplitude_rad"])
    assert amplitude.shape == (speeds.size, 3)
    assert np.all(np.diff(speeds) > 0)
    assert np.allclose(amplitude, np.abs(X), rtol=0.01)
    assert np.allclose(np.array(data["phase_deg"]), np.degrees(np.angle(X)), atol=1.0)
    assert data["bin_width_rpm"] == pytest.approx(20.0)
    assert data["window"].startswith("Hann over 4 cycles")


def test_table_and_csv(cli, runup_csv, steady_csv):
    run = cli("measure", runup_csv, "--teeth", "60")
    assert run.status == 0 and "Largest per order" in run.out
    assert "run-up 1615 - 2012" in run.out
    assert "Per speed bin" in run.out and "Hann over 4 cycles" in run.out
    run = cli("measure", steady_csv, "--teeth", "60", "--format", "csv")
    header = run.out.splitlines()[0]
    assert header == "orders,amplitude_rad,phase_deg,scatter_rad"
    run = cli("measure", runup_csv, "--teeth", "60", "--format", "csv", "--orders", "3")
    assert run.out.splitlines()[0] == (
        "speed_rpm,windows,synthesized_amplitude_rad,order_3_amplitude_rad,order_3_phase_deg"
    )


def test_plots_are_written(cli, steady_csv, runup_csv, tmp_path):
    paths = [tmp_path / n for n in ("t.svg", "m.png")]
    run = cli("measure", steady_csv, "--teeth", "60", "--plot-trace", paths[0])
    assert run.status == 0, run
    run = cli("measure", runup_csv, "--teeth", "60", "--plot-map", paths[1])
    assert run.status == 0, run
    assert all(p.stat().st_size > 1000 for p in paths)


def test_errors_are_one_line(cli, steady_csv, tmp_path, write):
    line = one_line_error(cli, "measure", steady_csv)
    assert "pulse times need --teeth N" in line and "steady.csv" in line
    line = one_line_error(cli, "measure", steady_csv, "--teeth", "60", "--model", "inline6-diesel")
    assert "--model and --at go together" in line
    line = one_line_error(
        cli, "measure", steady_csv, "--teeth", "60", "--model", "inline6-diesel", "--at", "puley"
    )
    assert '--at = "puley": no mass named "puley" (did you mean "pulley"?)' in line
    line = one_line_error(cli, "measure", steady_csv, "--teeth", "60", "--plot", "x.gif")
    assert "--plot" in line and ".png" in line
    line = one_line_error(
        cli, "measure", steady_csv, "--teeth", "60", "--plot-fit", str(tmp_path / "f.png")
    )
    assert "needs a run-up or run-down" in line
    line = one_line_error(cli, "measure", steady_csv, "--teeth", "2")
    assert "--teeth = 2: at least 4 pulses per revolution" in line
    line = one_line_error(cli, "measure", steady_csv, "--teeth", "60", "--orders", "31")
    assert "--orders" in line and "Nyquist order 30" in line
    line = one_line_error(cli, "measure", steady_csv, "--teeth", "60", "--bin", "-5")
    assert "--bin" in line
    line = one_line_error(
        cli, "measure", steady_csv, "--teeth", "60", "--window", "uniform", "--window-cycles", "0"
    )
    assert "--window-cycles" in line
    bad = write("bad.csv", "time [s]\n0.0\n0.2\n0.1\n")
    line = one_line_error(cli, "measure", bad, "--teeth", "60")
    assert "bad.csv" in line and "line 4 has 0.1 s after 0.2 s" in line
    out = tmp_path / "out.json"
    out.write_text("x")
    line = one_line_error(cli, "measure", steady_csv, "--teeth", "60", "-o", out)
    assert "already exists" in line
    line = one_line_error(cli, "measure", "inline6-runup", "--teeth", "36")
    assert "measured with 60 teeth" in line


def test_cycle_must_match_the_model(cli, steady_csv):
    line = one_line_error(
        cli,
        "measure",
        steady_csv,
        "--teeth",
        "60",
        "--cycle",
        "two-stroke",
        "--model",
        "inline6-diesel",
        "--at",
        "pulley",
    )
    assert "--cycle" in line and "four-stroke" in line


def test_done_when_the_built_in_run_up(cli, tmp_path):
    """Issue 20's "done when": the simulated run-up through a 60-tooth wheel, analysed by
    ``crankdyn measure``, gives the prescribed order amplitudes, the model's prediction beside
    them and the fitted damping; the loss factor written back is the one the simulated engine
    was built with."""
    from crankdyn.measure.examples import TRUE_LOSS_FACTOR, example_motion

    fit = tmp_path / "fit.png"
    run = cli(
        "measure",
        "inline6-runup",
        "--teeth",
        "60",
        "--model",
        "inline6-diesel",
        "--at",
        "pulley",
        "--format",
        "json",
        "--plot-fit",
        fit,
    )
    assert run.status == 0, run
    assert fit.stat().st_size > 1000
    data = json.loads(run.out)
    speeds = np.array(data["speed_rpm"]) / RPM
    amplitude = np.array(data["amplitude_rad"])
    phase = np.radians(np.array(data["phase_deg"]))
    prescribed = example_motion("inline6-runup").coefficients(speeds)
    big = np.abs(prescribed) > 5e-4  # orders above 0.5 mrad (the noise floor is ~1e-6 rad)
    rel = np.abs(amplitude - np.abs(prescribed)) / np.abs(prescribed)
    assert np.max(rel[big]) < 0.01
    assert np.max(np.degrees(np.abs(np.angle(np.exp(1j * phase) / prescribed)))[big]) < 1.0
    model = data["model"]
    assert model["mass"] == "pulley"
    assert np.array(model["amplitude_rad"]).shape == amplitude.shape
    peaks = {p["order"]: p for p in model["resonances"]}
    assert peaks[6.0]["measured_amplitude_rad"] < 0.85 * peaks[6.0]["model_amplitude_rad"]
    damping = model["damping"]
    assert damping["order"] == 6.0 and damping["mode_nodes"] == 1
    assert damping["loss_factor"] == pytest.approx(TRUE_LOSS_FACTOR, rel=0.02)
    assert damping["corrected_model_peak_rad"] == pytest.approx(
        damping["measured_peak_rad"], rel=0.01
    )
    assert f"loss_factor = {damping['loss_factor']:.4g}" in damping["apply"]


def test_analyze_measurement_options_checked_first(cli, tmp_path):
    line = one_line_error(
        cli, "analyze", "inline6-diesel", "--measurement", "inline6-runup", "-o", tmp_path / "r"
    )
    assert "--at MASS" in line
    line = one_line_error(cli, "analyze", "inline6-diesel", "--teeth", "60", "-o", tmp_path / "r")
    assert "go with --measurement" in line
    line = one_line_error(
        cli,
        "analyze",
        "inline6-diesel",
        "--measurement",
        "inline6-runup",
        "--at",
        "flywhel",
        "-o",
        tmp_path / "r",
    )
    assert 'did you mean "flywheel"' in line
    assert not (tmp_path / "r").exists()


# ---- issue 33: --teeth against the record, errors naming the file, the documented keys --------


def _speed_csv(path, seconds=2.0):
    """A sampled speed signal: 2000 rpm with 1 % of order 3, sampled at 10 kHz."""
    t = np.arange(0.0, seconds, 1e-4)
    omega = 2000 / RPM * (1 + 0.01 * np.sin(3 * 2000 / RPM * t))
    rows = "\n".join(f"{a:.6f},{w * RPM:.6f}" for a, w in zip(t, omega, strict=True))
    path.write_text("time [s],speed [rpm]\n" + rows + "\n", encoding="utf-8")
    return str(path)


def test_teeth_checked_against_the_record_for_every_signal_kind(cli, steady_csv, tmp_path):
    """``--teeth 100000000`` on a sampled speed signal allocated 4.97 GiB (a traceback): now one
    line naming the file, --teeth, the pulses it would make, the bound (4,194,304) and the
    largest --teeth the record takes; a pulse file with a wheel larger than the record, one
    line too (it named neither the file nor --teeth)."""
    speed = _speed_csv(tmp_path / "speed.csv")
    # the revolutions of the record, the closed-form integral of its speed over 0..1.9999 s
    w0, end = 2000 / RPM, 1.9999
    revolutions = (w0 * end + 0.01 * (1 - math.cos(3 * w0 * end)) / 3) / (2 * math.pi)
    largest = math.floor((4_194_304 - 1) / revolutions)
    line = one_line_error(cli, "measure", speed, "--teeth", "100000000")
    assert line.startswith(
        f"crankdyn: error: {speed}: --teeth = 100000000: the record's {revolutions:.4g} "
        f"revolutions at 100,000,000 angle samples each make {revolutions * 1e8:,.0f} pulses; "
        f"crankdyn resamples a speed signal to at most 4,194,304 (this record takes at most "
        f"{largest:,} per revolution)"
    )
    assert cli("measure", speed, "--teeth", "64", "--orders", "3").status == 0
    line = one_line_error(cli, "measure", steady_csv, "--teeth", "100000000")
    assert line.startswith(f"crankdyn: error: {steady_csv}: --teeth = 100000000: the record ")
    assert "less than one revolution of a wheel with 100,000,000 pulses" in line
    np.save(tmp_path / "speed.npy", np.column_stack([np.arange(0, 2, 1e-4), np.full(20000, 200.0)]))
    line = one_line_error(cli, "measure", str(tmp_path / "speed.npy"), "--teeth", "10000000")
    revolutions = 200 * 1.9999 / (2 * math.pi)
    assert f"--teeth = 10000000: the record's {revolutions:.4g} revolutions" in line


def test_a_short_record_names_its_file(cli, steady_csv, tmp_path):
    """``measure`` on a record shorter than it needs named no file (issue 33)."""
    with open(steady_csv, encoding="utf-8") as handle:
        lines = handle.read().splitlines()
    short = tmp_path / "short.csv"
    short.write_text("\n".join(lines[:400]) + "\n", encoding="utf-8")
    line = one_line_error(cli, "measure", str(short), "--teeth", "60")
    assert line.startswith(f"crankdyn: error: {short}: time: the record holds 3.3 working cycles")
    line = one_line_error(
        cli, "measure", steady_csv, "--teeth", "60", "--analysis", "tracking", "--window-cycles",
        "90",
    )  # fmt: skip
    assert line.startswith(f"crankdyn: error: {steady_csv}: --window-cycles: the record holds ")


def test_json_keys_the_docs_list_are_always_present(cli, steady_csv, runup_csv):
    """``measure --format json`` omitted ``notes`` when there were none (issue 33): every key
    docs/measurement.md lists for a steady record is there, ``notes`` an empty list or not."""
    listed = [
        "speed_rpm",
        "orders",
        "amplitude_rad",
        "phase_deg",
        "scatter_rad",
        "synthesized_amplitude_rad",
        "cycles",
        "speed_min_rpm",
        "speed_max_rpm",
        "window",
        "averaging",
        "reference",
        "tooth_correction",
        "cycle_angle_deg",
        "cycle_vibration_rad",
        "cycle_speed_rpm",
        "notes",
    ]
    run = cli("measure", steady_csv, "--teeth", "60", "--format", "json")
    data = json.loads(run.out)
    assert set(listed) <= set(data), set(listed) - set(data)
    assert data["notes"] == []
    tracking = [
        "kind",
        "speed_rpm",
        "windows",
        "amplitude_rad",
        "phase_deg",
        "synthesized_amplitude_rad",
    ]
    tracking += ["window_speed_rpm", "window_cycles", "bin_width_rpm", "resonances", "notes"]
    data = json.loads(cli("measure", runup_csv, "--teeth", "60", "--format", "json").out)
    assert set(tracking) <= set(data), set(tracking) - set(data)


def test_largest_per_order_is_the_results_table(cli, runup_csv):
    """The terminal's "Largest per order" is the result's summary table: each order's largest
    speed bin as the exported amplitudes give it."""
    from crankdyn.display import column_text

    data = json.loads(cli("measure", runup_csv, "--teeth", "60", "--format", "json").out)
    amplitude = np.array(data["amplitude_rad"])
    text = cli("measure", runup_csv, "--teeth", "60").out
    part = " ".join(text[text.index("Largest per order") : text.index("Per speed bin")].split())
    cells, unit = column_text(list(amplitude.max(axis=0)), "rad")
    assert f"({unit})" in part and all(cell in part for cell in cells)
