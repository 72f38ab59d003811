"""The TVC's progress: every step it begins is named (each condition computed here in order,
the work beside, the modes), the command line shows them beside its spinner, and telling them
changes no number."""

from __future__ import annotations

from crankdyn.cli import main
from crankdyn.io.catalogue import resolve_model_and_engine
from crankdyn.tvc.analysis import tvc


def test_every_step_is_named_and_changes_nothing():
    model, engine = resolve_model_and_engine("genset-1500")
    steps: list[str] = []
    told = tvc(model, engine, passage=False, beside=False, progress=steps.append)
    # one process: every condition here in order (normal firing, each cylinder misfiring,
    # the damper out of order), then the events, then the modes
    count = 2 + engine.cylinders.count
    names = ["normal firing"]
    names += [f"misfire cylinder {k}" for k in range(1, engine.cylinders.count + 1)]
    names += ["damper out of order"]
    expected = [f"condition {k + 1} of {count}, {n}" for k, n in enumerate(names)]
    expected += ["the transient events", "the Campbell diagram and the natural modes"]
    assert steps == expected
    assert told.events
    silent = tvc(model, engine, passage=False, beside=False)
    assert told.to_json() == silent.to_json()


def test_the_command_shows_the_steps(tmp_path, monkeypatch):
    from rich.status import Status

    shown: list[str] = []
    original = Status.update

    def update(self, status=None, **kwargs):
        if status is not None:
            shown.append(str(status))
        return original(self, status, **kwargs)

    monkeypatch.setattr(Status, "update", update)
    status = main(["tvc", "genset-1500", "--no-passage", "-o", str(tmp_path / "r")])
    assert status in (0, 1)
    title = "Torsional vibration calculation: "
    assert shown[0].startswith(f"{title}condition 1 of ")
    assert f"{title}the Campbell diagram and the natural modes" in shown
    assert shown.index(f"{title}the report") < shown.index(f"{title}the PDF")


def test_a_step_is_shown_as_text_not_markup(tmp_path, monkeypatch):
    """A step's words are shown as they are: square brackets are not rich's markup (a stray
    closing tag would otherwise end the command)."""
    from rich.status import Status

    from crankdyn.session.crankshaft import CrankshaftAnalyses

    shown: list[str] = []
    original_update, original_tvc = Status.update, CrankshaftAnalyses.tvc

    def update(self, status=None, **kwargs):
        if status is not None:
            shown.append(str(status))
        return original_update(self, status, **kwargs)

    def tvc_told(self, **kwargs):
        kwargs["progress"]("[/] [bold]x[/bold]")
        return original_tvc(self, **kwargs)

    monkeypatch.setattr(Status, "update", update)
    monkeypatch.setattr(CrankshaftAnalyses, "tvc", tvc_told)
    status = main(["tvc", "genset-1500", "--no-passage", "--no-pdf", "-o", str(tmp_path / "r")])
    assert status in (0, 1)
    assert shown[0] == "Torsional vibration calculation: [/] [bold]x[/bold]"
