"""crankdyn firing-orders, balance and flywheel from the command line, in process."""

from __future__ import annotations

import json
import math

import pytest


def test_firing_orders_json_table_csv(cli):
    run = cli("firing-orders", "inline6-diesel", "--format", "json")
    assert run.status == 0, run
    data = json.loads(run.out)
    assert len(data) == 4
    for d in data:
        assert isinstance(d["firing_order"], list) and isinstance(d["adjacent_consecutive"], int)
        assert d["interval_deviation_deg"] == 0.0
        assert d["firing_intervals_deg"] == [120.0] * 6
    run = cli("firing-orders", "inline6-diesel")
    assert run.status == 0 and "1-5-3-6-2-4" in run.out and "ranks" in run.out
    run = cli("firing-orders", "inline6-diesel", "--format", "csv")
    assert run.status == 0 and run.out.startswith("rank,firing_order")


def test_firing_orders_options(cli, tmp_path):
    plot = tmp_path / "arrangement.png"
    run = cli(
        "firing-orders",
        "inline6-diesel",
        "--any-crankshaft",
        "--mode-shape",
        "1,0.9,0.78,0.64,0.48,0.3",
        "--torsion-orders",
        "1.5,4.5",
        "--exhaust-groups",
        "1,2,3;4,5,6",
        "--rank-by",
        "exhaust_min_interval_deg,torsional_vector_sum",
        "--top",
        "3",
        "--format",
        "json",
        "--plot",
        plot,
    )
    assert run.status == 0, run
    data = json.loads(run.out)
    assert len(data) == 3
    assert data[0]["exhaust_min_interval_deg"] == pytest.approx(240.0)
    assert set(data[0]["torsional_vector_sums"]) >= {"1.5", "4.5"}
    assert plot.read_bytes()[:4] == b"\x89PNG"


def test_firing_orders_uneven_v6(cli, write):
    path = write(
        "v6.toml",
        """
name = "90 deg V6, common pins"
[geometry]
bore = "96 mm"
stroke = "86 mm"
rod_length = "150 mm"
[cylinders]
count = 6
layout = "V"
bank_angle = "90 deg"
firing_order = [1, 4, 2, 5, 3, 6]
throw_positions = ["0 deg", "120 deg", "240 deg"]
pitch = "110 mm"
""",
    )
    run = cli("firing-orders", path, "--format", "json", "--top", "1")
    assert run.status == 0, run
    best = json.loads(run.out)[0]
    assert best["firing_order"] == [1, 4, 2, 5, 3, 6]
    assert best["firing_intervals_deg"] == [90.0, 150.0, 90.0, 150.0, 90.0, 150.0]
    assert best["v_scheme"] == "alternating"
    assert best["crank_end_view_deg"] == [0.0, 120.0, 240.0]


def test_balance_json(cli):
    run = cli("balance", "v8-crossplane", "--speed", "3000", "--format", "json")
    assert run.status == 0, run
    data = json.loads(run.out)
    assert [o["order"] for o in data["orders"]] == [1, 2, 4, 6]
    first = data["orders"][0]
    for key in (
        "free_force_N",
        "free_moment_Nm",
        "free_force_vertical_N",
        "free_force_horizontal_N",
        "free_moment_vertical_plane_Nm",
        "free_moment_horizontal_plane_Nm",
    ):
        assert key in first
    assert first["free_moment_coefficient"] == pytest.approx(math.sqrt(10))
    assert {"free_force_N", "free_moment_Nm"} <= set(data["rotating"])
    assert data["speed_rpm"] == pytest.approx(3000)
    assert data["overturning"]["mean_overturning_moment_Nm"] < 0


def test_balance_table_csv_options(cli, tmp_path):
    run = cli(
        "balance",
        "v8-flatplane",
        "--orders",
        "1,2",
        "--method",
        "approx",
        "--counterweight-ratio",
        "1",
        "--reciprocating-balance-ratio",
        "0",
        "--rod-offset",
        "0",
        "--power",
        "350",
        "--no-torque",
    )
    assert run.status == 0, run
    assert "power" in run.out and "(N·m/kW)" in run.out and "1 (rotating)" in run.out
    out = tmp_path / "b.csv"
    run = cli(
        "balance", "inline3-petrol", "--format", "csv", "-o", out, "--plot", tmp_path / "b.svg"
    )
    assert run.status == 0, run
    assert out.read_text().startswith("order,source")
    assert (tmp_path / "b.svg").read_text().lstrip().startswith("<?xml")
    run = cli("balance", "inline3-petrol", "--format", "csv", "-o", out)
    assert run.status == 2 and "--force" in run.err


def test_flywheel_json_and_table(cli, tmp_path):
    run = cli("flywheel", "vaz2108", "--delta", "0.01", "--format", "json", "--step", "1")
    assert run.status == 0, run
    data = json.loads(run.out)
    for key in (
        "torque_nonuniformity",
        "excess_work_J",
        "excess_work_coefficient",
        "required_inertia_kgm2",
        "flywheel_inertia_kgm2",
        "gd2_Nm2",
        "speed_fluctuation",
    ):
        assert isinstance(data[key], float), key
    assert data["speed_fluctuation"] == pytest.approx(0.01, abs=1e-4)
    assert len(data["crank_speed_rpm"]) == 720
    run = cli("flywheel", "inline3-petrol", "--delta", "1/200", "--plot", tmp_path / "f.png")
    assert run.status == 0, run
    assert "Rim: width" in run.out
    run = cli("flywheel", "vaz2108", "--inertia", "0.1 kg*m^2", "--format", "csv", "--speed", "900")
    assert run.status == 0 and run.out.startswith("crank_angle_deg,torque_Nm")


@pytest.mark.parametrize(
    ("args", "fragment"),
    [
        (("flywheel", "vaz2108", "--delta", "2"), "--delta"),
        (("flywheel", "vaz2108", "--delta", "x"), "fraction"),
        (("flywheel", "vaz2108", "--inertia", "-1"), "--inertia"),
        (("flywheel", "vaz2108", "--delta", "0.01", "--step", "7"), "--step"),
        (("balance", "vaz2108", "--orders", "0,2"), "--orders"),
        (("balance", "vaz2108", "--orders", "a"), "--orders"),
        (("balance", "vaz2108", "--counterweight-ratio", "-1"), "--counterweight-ratio"),
        (("balance", "vaz2108", "--power", "0"), "--power"),
        (("balance", "vaz2108", "--rod-offset", "3 kg"), "--rod-offset"),
        (("balance", "vaz2108", "--plot", "x.gif", "--no-torque"), "--plot"),
        (("firing-orders", "vaz2108", "--rank-by", "speed"), "--rank-by"),
        (("firing-orders", "vaz2108", "--mode-shape", "1,2"), "--mode-shape"),
        (("firing-orders", "vaz2108", "--exhaust-groups", "1;2"), "--exhaust-groups"),
        (("firing-orders", "vaz2108", "--top", "0"), "--top"),
    ],
)
def test_errors_one_line_status_2(cli, args, fragment):
    run = cli(*args)
    assert run.status == 2, run
    assert fragment in run.err and run.err.count("\n") == 1 and "Traceback" not in run.err


def test_flywheel_default_target(cli):
    """Without a target δ or a flywheel the session's default δ = 0.01 is used, and said."""
    run = cli("flywheel", "vaz2108")
    assert run.status == 0, run
    assert "default 0.01" in run.out


def test_balance_needs_masses(cli, write):
    path = write(
        "bare.toml",
        """
name = "bare"
[geometry]
bore = "80 mm"
stroke = "80 mm"
rod_length = "150 mm"
""",
    )
    run = cli("balance", path, "--speed", "3000")
    assert run.status == 2 and "[masses]" in run.err
    run = cli("flywheel", path, "--speed", "3000", "--delta", "0.01")
    assert run.status == 2 and "[masses]" in run.err


def test_too_many_to_enumerate(cli, write):
    path = write(
        "i12.toml",
        """
name = "in-line twelve"
[geometry]
bore = "100 mm"
stroke = "100 mm"
rod_length = "200 mm"
[cylinders]
count = 12
firing_order = [1, 12, 5, 8, 3, 10, 6, 7, 2, 11, 4, 9]
""",
    )
    run = cli("firing-orders", path, "--any-crankshaft")
    assert run.status == 2 and "--any-crankshaft" in run.err and "more than the" in run.err
    # six pairs of cylinders share a TDC angle: the two of a pair must fire 360 deg apart, so of
    # the 2^11 choices of firing TDC only 2^5 (cylinder 1's pair fixed) avoid firing together
    run = cli("firing-orders", path, "--all", "--format", "json")
    assert run.status == 0 and len(json.loads(run.out)) == 2**5
