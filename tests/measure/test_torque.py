"""Measured shaft torques (crankdyn.measure.torque; seed 003, the V6 paper's strain-gauge journal
torques): a synthetic record made from a known model response plus noise is analysed by order and
held against the model; the time- and angle-domain records, the reader and the command line.

The record is the model's own torque at the span between cylinder 6 and the flywheel of the
inline-6 diesel (the forced response at 1800 rpm, orders 0.5 to 12) plus a mean torque and white
noise of standard deviation sigma = 2 % of the largest order's amplitude, sampled at 20 kHz over
24 cycles. The complex mean over the cycles of each order's DFT has a noise of about
sigma sqrt(2 / N) (N samples in all); the tolerance is five times that, plus 1e-4 of the order's
amplitude for the resampling spline."""

import math

import numpy as np
import pytest

import crankdyn
from crankdyn.errors import InputError
from crankdyn.io.signals import read_torque_record
from crankdyn.measure.torque import TorqueRecord, compare_torque, torque_orders
from crankdyn.torsion.sweep import forced_response

SPEED = 1800.0 * math.pi / 30.0  # rad/s
ORDERS = np.arange(1, 25) * 0.5
SPAN = ("cylinder 6", "flywheel")
MEAN = 850.0  # N m


@pytest.fixture(scope="module")
def model_torque():
    analysis = crankdyn.Analysis(crankdyn.Engine.example("inline6-diesel"))
    excitation = analysis.excitation()
    response = forced_response(analysis.model, excitation, [SPEED], ORDERS, resolve=False)
    k = response.shaft_index(SPAN)
    return analysis, excitation, np.asarray(response.shaft_response[0, :, k])


def _record(torque, cycles=24, rate=20_000.0, sigma_share=0.02, seed=3):
    theta = 4 * math.pi
    t = np.arange(0.0, cycles * theta / SPEED + 0.01, 1.0 / rate)
    psi = SPEED * t
    signal = MEAN + np.real(np.exp(1j * np.outer(psi, ORDERS)) @ torque)
    sigma = sigma_share * float(np.max(np.abs(torque)))
    noisy = signal + np.random.default_rng(seed).normal(0.0, sigma, t.size)
    marks = np.arange(cycles + 1) * theta / SPEED
    return t, psi, noisy, marks, sigma


def test_synthetic_record_gives_back_the_models_orders(model_torque):
    analysis, excitation, torque = model_torque
    t, _psi, noisy, marks, sigma = _record(torque)
    spectrum = torque_orders(TorqueRecord(noisy, time=t, reference=marks), orders=ORDERS)
    assert spectrum.cycles == 24
    assert spectrum.speed == pytest.approx(SPEED, rel=1e-9)
    n = np.count_nonzero(t <= marks[-1])
    tolerance = 5.0 * sigma * math.sqrt(2.0 / n) + 1e-4 * np.abs(torque)
    assert np.all(np.abs(spectrum.coefficients - torque) <= tolerance)
    assert spectrum.mean_torque == pytest.approx(MEAN, abs=5.0 * sigma / math.sqrt(n))
    # held against the model: measured / model is 1 within the noise where the order matters
    cmp = compare_torque(spectrum, analysis.model, excitation, SPAN)
    assert cmp.span == "cylinder 6 - flywheel"
    big = np.abs(torque) > 0.05 * np.max(np.abs(torque))
    assert np.allclose(cmp.ratio[big], 1.0, atol=0.01)
    assert np.allclose(np.angle(np.exp(1j * (cmp.model_phase - spectrum.phase)))[big], 0.0,
                       atol=0.01)  # fmt: skip
    assert cmp.synthesized_ratio == pytest.approx(1.0, abs=0.01)


def test_angle_domain_record_and_its_speed(model_torque):
    _analysis, _excitation, torque = model_torque
    _t, psi, noisy, _marks, _sigma = _record(torque, cycles=6, sigma_share=0.0)
    record = TorqueRecord(noisy, crank_angle=psi + 0.3, speed=SPEED)  # starts 0.3 rad late
    # the record's angle 0 lies 0.3 rad before cylinder 1's firing TDC
    spectrum = torque_orders(record, orders=ORDERS, reference_angle=-0.3)
    assert np.allclose(spectrum.coefficients, torque, atol=1e-4 * np.max(np.abs(torque)))
    with pytest.raises(InputError, match="mean speed"):
        torque_orders(TorqueRecord(noisy, crank_angle=psi), orders=ORDERS)


def test_errors():
    psi = np.linspace(0.0, 3 * math.pi, 200)
    with pytest.raises(InputError, match="less than one"):
        torque_orders(TorqueRecord(np.cos(psi), crank_angle=psi, speed=100.0))
    psi = np.linspace(0.0, 8 * math.pi, 40)
    with pytest.raises(InputError, match="cannot follow order 12"):
        torque_orders(TorqueRecord(np.cos(psi), crank_angle=psi, speed=100.0))
    with pytest.raises(InputError, match="once-per-cycle mark"):
        TorqueRecord(np.zeros(10), time=np.arange(10.0))


def _write_csv(path, t, torque, marks):
    lines = ["time [s],torque [N*m],reference [s]"]
    for i, (ti, qi) in enumerate(zip(t, torque, strict=True)):
        mark = f"{float(marks[i])!r}" if i < marks.size else ""
        lines.append(f"{float(ti)!r},{float(qi)!r},{mark}")
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")


def test_reader_and_command_line(model_torque, cli, tmp_path):
    _analysis, _excitation, torque = model_torque
    t, _psi, noisy, marks, _sigma = _record(torque, cycles=8, sigma_share=0.0)
    path = tmp_path / "journal.csv"
    _write_csv(path, t, noisy, marks)
    record = read_torque_record(path)
    assert record.domain == "time" and record.reference.size == marks.size
    run = cli("measure", path, "--torque", "--model", "inline6-diesel", "--span",
              "cylinder 6,flywheel", "--format", "json", "--plot", tmp_path / "t.png")  # fmt: skip
    assert run.status == 0, run
    import json

    data = json.loads(run.out)
    assert data["mean_torque_Nm"] == pytest.approx(MEAN, rel=1e-6)
    assert data["model"]["span"] == "cylinder 6 - flywheel"
    ratio = np.array(data["model"]["measured_over_model"], dtype=float)
    big = np.abs(torque) > 0.05 * np.max(np.abs(torque))
    assert np.allclose(ratio[big], 1.0, atol=1e-3)
    assert (tmp_path / "t.png").stat().st_size > 0
    table = cli("measure", path, "--torque")
    assert table.status == 0 and "Measured torque orders" in table.out
    for args, text in (
        (("--at", "flywheel"), "--span MASS,MASS"),
        (("--span", "a,b"), "go together"),
        (("--teeth", "60"), "torsiograph"),
        (("--model", "inline6-diesel", "--span", "pulley,flywheel"), "no shaft joins"),
    ):
        bad = cli("measure", path, "--torque", *args)
        assert bad.status == 2 and text in bad.err, (args, bad)
    wrong = cli("measure", path, "--span", "a,b")
    assert wrong.status == 2 and "--torque" in wrong.err
