"""crankdyn from Python: a short tour (run: python docs/examples/quickstart.py [OUTDIR]).

Every object here is a plain Python object with SI values: the engine, the result, its summary.
In a notebook the results show an HTML summary; plots are matplotlib Figures.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import crankdyn
from crankdyn.crank.kinematics import coefficient_table, piston_kinematics
from crankdyn.engine.model import Engine


def main(out: Path) -> None:
    out.mkdir(parents=True, exist_ok=True)

    # 1. An engine: a built-in example, or Engine.from_file("my-engine.toml")
    engine = Engine.example("vaz2108")
    g = engine.geometry
    print(f"{engine.name}: bore {g.bore * 1e3:g} mm, stroke {g.stroke * 1e3:g} mm, λ = {g.lam:.3f}")

    # 2. Kinematics at 4900 rpm (speeds in rad/s inside crankdyn)
    speed = 4900 * math.pi / 30
    kin = piston_kinematics(g, speed)
    s = kin.extrema  # the figures of the motion (kin.summary() gives every front end's view)
    print(
        f"mean piston speed {s.mean_piston_speed:.2f} m/s ({s.speed_class}), "
        f"v_max {s.max_velocity:.2f} m/s at {math.degrees(s.crank_angle_at_max_velocity):.1f} deg"
    )
    for x in s.acceleration_extrema:
        print(
            f"  acceleration {x.kind} {x.acceleration:9.1f} m/s² at "
            f"{math.degrees(x.crank_angle):6.1f} deg"
        )

    # 3. The seeds' second-order formula and the λ-series, against the exact motion
    approx = piston_kinematics(g, speed, method="approx")
    series = piston_kinematics(g, speed, method="series", order=8)
    err_a = max(abs(approx.acceleration - kin.acceleration))
    err_s = max(abs(series.acceleration - kin.acceleration))
    print(f"largest acceleration error: second order {err_a:.1f} m/s², order 8 {err_s:.2e} m/s²")

    # 4. Export and plot
    (out / "kinematics.csv").write_text(kin.to_csv(), encoding="utf-8")
    kin.plot().savefig(out / "kinematics.png", dpi=100)

    # 5. The seed 002 coefficient table for a few rod ratios
    table = coefficient_table([1 / 3.8, 0.26, 0.3], [math.radians(a) for a in range(0, 181, 30)])
    print("A = x/R at 90 deg:", [round(float(row[3]), 4) for row in table.displacement])

    # 6. Every analysis of an engine from one session, each computed once, with the defaults
    #    (and so the numbers) of the command line, the report and the parameter studies
    a = crankdyn.Analysis(Engine.example("inline6-diesel"))
    print(
        f"mean torque {a.torque.mean_torque:.1f} N m, max gas force "
        f"{a.forces().max_gas_force / 1e3:.2f} kN, first elastic mode "
        f"{a.modes.frequencies_hz[1]:.1f} Hz, "
        f"most loaded shaft {' - '.join(a.response().most_loaded_shaft())}"
    )
    a.forces().plot().savefig(out / "forces.png", dpi=100)
    for label, value, unit in a.bearings().summary().rows()[-4:]:  # its declared key figures
        print(f"  {label}: {value} {unit}")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path("quickstart-output"))
