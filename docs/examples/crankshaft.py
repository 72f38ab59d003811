"""The crankshaft of the built-in marine engine: its fatigue strength by IACS UR M53 with the
nominal torsional stress from the forced torsional response, the coupled modes of its beam
model beside the lumped model's, and the beam model's axial vibration fed into the check.

Run: python docs/examples/crankshaft.py [OUTPUT_FOLDER]
"""

import math
import sys
from pathlib import Path

import crankdyn

session = crankdyn.Analysis(crankdyn.Engine.example("marine-propulsion"))

check = session.crankshaft()  # UR M53, M_TN of every throw from session.response()
q, where = check.smallest_q()
print(f"smallest Q {q:.3f} at {where} (at least {check.q_required})")
print(f"M_TN of throw 1: {check.torsion_torque[0] / 1e3:.1f} kN·m, {check.torsion_where[0]}")

modes = session.crankshaft_modes()  # the crankshaft as a 3-D beam structure
for m, f, motion, lumped in zip(
    modes.mode[:8],
    modes.frequencies_hz[:8],
    modes.motion[:8],
    modes.lumped_frequency[:8],
    strict=True,
):
    beside = "" if math.isnan(lumped) else f"  (lumped model {lumped / (2 * math.pi):.2f} Hz)"
    print(f"mode {m}: {f:8.2f} Hz {motion}{beside}")

response = session.crankshaft_response()
axial = response.summary().figure("max_free_end_axial_m")
print(f"free-end axial vibration: {axial.display()}")

beam = session.crankshaft(additional_stress="beam")  # sigma_add from the beam model
print(f"with the beam model's additional stress: Q {beam.smallest_q()[0]:.3f}")
print(f"  sigma_add from {beam.additional_source}")

out = Path(sys.argv[1] if len(sys.argv) > 1 else "crankshaft")
out.mkdir(parents=True, exist_ok=True)
(out / "m53-quantities.csv").write_text(check.quantities_table().csv_text(), encoding="utf-8")
modes.plot().savefig(out / "crankshaft-modes.png", dpi=80)
response.plot().savefig(out / "crankshaft-axial.png", dpi=80)
print(f"quantities and figures in {out}")
