"""``crankdyn demo``: the main job on the built-in inline-6 diesel."""

from __future__ import annotations

import math

import click
from rich.table import Table as RichTable

from crankdyn.bearings import bearing_loads
from crankdyn.cli.common import console, summary_table
from crankdyn.engine import Engine
from crankdyn.forces import cylinder_forces
from crankdyn.indicated import pressure_analysis
from crankdyn.io.engine_file import load_example
from crankdyn.io.output import atomic_directory
from crankdyn.kinematics import piston_kinematics
from crankdyn.pressure_model import default_pressure
from crankdyn.torque import engine_torque

DEMO_ENGINE = "inline6-diesel"


def engine_table(engine: Engine) -> RichTable:
    """The engine's main data as a rich table."""
    g, c = engine.geometry, engine.cylinders
    table = RichTable(title=engine.name, header_style="bold")
    table.add_column("Input")
    table.add_column("Value", justify="right")
    rows = [
        ("Cycle", engine.cycle),
        (
            "Cylinders",
            f"{c.count} {c.layout}"
            + (f" {math.degrees(c.bank_angle):g}°" if c.layout == "V" else ""),
        ),
        ("Firing order", "-".join(str(i) for i in c.firing_order)),
        ("Bore", f"{g.bore * 1e3:g} mm"),
        ("Stroke", f"{g.stroke * 1e3:.6g} mm"),
        ("Rod length", f"{g.rod_length * 1e3:.6g} mm (λ = {g.lam:.4f})"),
        ("Offset", f"{g.offset * 1e3:g} mm"),
        ("Displacement", f"{engine.displacement * 1e3:.4g} L"),
    ]
    if engine.speed:
        rows.append(("Speed", f"{engine.speed * 30 / math.pi:.0f} rpm"))
    if engine.pressure is not None:
        peak, at = engine.pressure.peak
        rows.append(
            (
                "Pressure trace",
                f"{engine.pressure.source}, peak {peak / 1e6:.3g} MPa at "
                f"{math.degrees(at):.1f}° after firing TDC",
            )
        )
    for label, value in rows:
        table.add_row(label, value)
    return table


@click.command("demo")
@click.option(
    "--out",
    default="crankdyn-demo",
    show_default=True,
    metavar="DIR",
    help="Folder to write the outputs to.",
)
@click.option("--force", is_flag=True, help="Replace an existing DIR.")
def demo_command(out: str, force: bool) -> int:
    """Analyse the built-in inline-6 diesel: summary tables, CSV, JSON and plots in DIR."""
    engine = load_example(DEMO_ENGINE)
    con = console()
    con.print(engine_table(engine))
    kin = piston_kinematics(engine.geometry, engine.speed)
    con.print(summary_table(kin.summary, "Kinematics"))
    pressure = pressure_analysis(default_pressure(engine), engine.geometry)
    forces = cylinder_forces(engine, engine.speed)
    bearings = bearing_loads(engine, engine.speed)
    torque = engine_torque(engine, engine.speed)
    con.print(summary_table(torque, "Torque and power"))
    results = {
        "kinematics": kin,
        "pressure": pressure,
        "forces": forces,
        "bearings": bearings,
        "torque": torque,
    }
    figures = {
        "kinematics": kin.plot,
        "pressure": pressure.plot,
        "forces": forces.plot,
        "crank_pin_polar": forces.plot_pin_polar,
        "bearings": bearings.plot,
        "torque": torque.plot,
    }
    with atomic_directory(out, force=force) as tmp:
        (tmp / "data").mkdir()
        (tmp / "plots").mkdir()
        for name, result in results.items():
            (tmp / "data" / f"{name}.csv").write_text(result.to_csv(), encoding="utf-8")
            (tmp / f"{name}.json").write_text(result.to_json() + "\n", encoding="utf-8")
        for name, make in figures.items():
            fig = make()
            fig.savefig(tmp / "plots" / f"{name}.png", dpi=110)
            fig.savefig(tmp / "plots" / f"{name}.svg")
    con.print(
        f"Wrote {out}/: {', '.join(f'{n}.json' for n in results)}; data/*.csv; "
        f"plots/{{{','.join(figures)}}}.png/.svg"
    )
    return 0


def register(group: click.Group) -> None:
    group.add_command(demo_command)
