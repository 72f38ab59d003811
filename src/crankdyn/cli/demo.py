"""``crankdyn demo``: the main job on the built-in inline-6 diesel."""

from __future__ import annotations

import math

import click
from rich.table import Table as RichTable

from crankdyn.cli.common import console, summary_table
from crankdyn.engine import Engine
from crankdyn.io.engine_file import load_example
from crankdyn.io.output import atomic_directory
from crankdyn.kinematics import piston_kinematics

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
    with atomic_directory(out, force=force) as tmp:
        (tmp / "data").mkdir()
        (tmp / "plots").mkdir()
        (tmp / "data" / "kinematics.csv").write_text(kin.to_csv(), encoding="utf-8")
        (tmp / "kinematics.json").write_text(kin.to_json() + "\n", encoding="utf-8")
        fig = kin.plot()
        fig.savefig(tmp / "plots" / "kinematics.png", dpi=110)
        fig.savefig(tmp / "plots" / "kinematics.svg")
    con.print(f"Wrote {out}/: kinematics.json, data/kinematics.csv, plots/kinematics.png/.svg")
    return 0


def register(group: click.Group) -> None:
    group.add_command(demo_command)
