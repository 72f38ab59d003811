"""A marine driveline: the built-in medium-speed engine joined to its shaft line (elastic
coupling, 25:80 gearbox, distributed-mass shafts, four-blade propeller). Damped modes, the mean
torque along the line, the response at the propeller's blade orders, the Campbell diagram with
engine and propeller orders, and the mass-elastic table.

Run: python docs/examples/driveline.py [OUTPUT_FOLDER]
"""

import math
import sys
from pathlib import Path

import numpy as np

from crankdyn.engine.model import Engine
from crankdyn.io.mass_elastic import mass_elastic_csv
from crankdyn.torsion.campbell import campbell
from crankdyn.torsion.damped import damped_modes
from crankdyn.torsion.excitation import excitation_for
from crankdyn.torsion.sources import default_orders, mean_torques
from crankdyn.torsion.sweep import forced_response

RPM = math.pi / 30

engine = Engine.example("marine-propulsion")
model = engine.torsion  # the engine's crank train + torsion/marine-shaft-line.toml
print(f"{model.name}: {model.mass_count} masses, {model.dof_count} degrees of freedom")

damped = damped_modes(model)  # numbered as the undamped modes: rigid-body mode 0, elastic from 1
for r in range(1, 4):
    print(
        f"mode {damped.mode[r]}: {damped.damped_frequency[r] / (2 * math.pi):.2f} Hz, "
        f"damping ratio {damped.damping_ratio[r]:.3f}, log. decrement {damped.log_decrement[r]:.3f}"
    )

speeds = np.arange(300, 751, 10) * RPM
loads = mean_torques(model, speeds)
coupling = next(i for i, s in enumerate(model.shafts) if s.kind == "coupling")
print(f"coupling mean torque at 750 rpm: {loads.mean_torque[-1, coupling] / 1e3:.1f} kN·m")

excitation = excitation_for(model, engine)
orders = default_orders(model, excitation.cycle)  # 0.5 ... 12 and the blade orders 1.25, 2.5
# resolved: the critical speeds added, the resonances sampled where the coupling's load puts
# them and every peak refined to 0.1 %
result = forced_response(model, excitation, speeds, orders)
peak = result.peak("amplitude", "propeller", order=1.25)
print(f"blade order 1.25 at the propeller: {peak.describe(1e3, 'mrad')}")
top = result.peak("order_shaft_torque", ("stern tube flange", "propeller shaft 1/14"), order=2.5)
print(f"blade order 2 (2.5) in the propeller shaft: {top.describe(1e-3, 'kN·m')}")
print(f"{result.added_speeds.size} speeds added to the 10 rpm grid")
for c in campbell(model, orders, excitation=excitation).critical_speeds[:5]:
    print(
        f"critical speed {c.speed / RPM:.0f} rpm: mode {c.mode}, order {c.order:g} ({c.excited_by})"
    )

out = Path(sys.argv[1] if len(sys.argv) > 1 else "driveline")
out.mkdir(parents=True, exist_ok=True)
(out / "marine-mass-elastic.csv").write_text(mass_elastic_csv(model), encoding="utf-8")
print(f"mass-elastic table in {out}")
