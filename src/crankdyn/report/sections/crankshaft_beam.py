"""Report section: the crankshaft as a beam structure, its coupled modes beside the lumped
model's and its forced response (:meth:`crankdyn.session.Analysis.crankshaft_modes`,
:meth:`~crankdyn.session.Analysis.crankshaft_response`)."""

from __future__ import annotations

from crankdyn.errors import InputError
from crankdyn.report.model import Plot, Section, Table
from crankdyn.report.sections import Context, NotApplicable, NotRequested


def build(ctx: Context) -> Section:
    """The beam model's section: the coupled modes classified by type, the torsional ones
    beside the lumped model's (how well it holds), a throw's stiffness, and the forced
    response (axial vibration at the free end, the webs' bending from vibration).

    Parameters
    ----------
    ctx : crankdyn.report.sections.Context
        The analysis session (SI units) and the optional inputs of the report.

    Returns
    -------
    crankdyn.report.model.Section
        The section: the results' key figures, tables, notes and plots.

    Raises
    ------
    NotRequested
        The engine file has no ``[crankshaft]`` section.
    NotApplicable
        The beam model cannot be made (no masses, no speed range for the response...).
    """
    if ctx.engine.crankshaft is None:
        raise NotRequested("the engine file has no [crankshaft] section")
    try:
        modes = ctx.analysis.crankshaft_modes()
        response = ctx.analysis.crankshaft_response()
    except InputError as exc:
        raise NotApplicable(f"no beam model of the crankshaft: {exc}") from None
    return Section.of(
        "crankshaft-beam",
        "The crankshaft as a beam structure",
        [modes, response],
        intro=(
            f"Journals, webs and pins as 3-D beam elements ({modes.mesh}), the rods' and "
            "pistons' masses at the pins, main bearings as springs, the flywheel, damper and "
            "shaft line attached: coupled modes classified by their kinetic energy, the "
            "torsional ones beside the lumped model's, and the forced response to the pins' "
            "gas and inertia forces over the speed range (crankdyn docs crankshaft)."
        ),
        plots=[
            Plot(
                "crankshaft_mode_shapes",
                "Mode shapes of the beam model",
                modes.plot(),
                "The first elastic modes in side, top and end views; grey the centre lines at "
                "rest.",
            ),
            Plot(
                "crankshaft_axial_response",
                "Axial vibration and web bending against speed",
                response.plot(),
                "The free end's axial vibration (synthesised and its largest orders) and the "
                "largest web bending stress, nominal and from vibration.",
            ),
        ],
        tables=[
            Table("crankshaft_beam_modes", "Beam model modes", result=modes, show=False),
            Table("crankshaft_beam_response", "Beam model response", result=response, show=False),
        ],
        json={"crankshaft_modes": modes.to_dict(), "crankshaft_response": response.to_dict()},
    )
