"""The post-processing of a chain's modes (issue 16: vectorised, node counts without locating the
nodes, positions located on demand) against a plain reference written here element by element
from the definitions of the module docstrings of crankdyn.torsion.modal and
crankdyn.torsion.nodes: the shapes normalised (largest amplitude 1, first amplitude above 1e-9
of it positive, below 1e-14 set to 0), a component resolved where |phi_i| sqrt(J_i) > tau_r
sqrt(J_r) (tau_r = 10 eps ||A|| / gap_r), a located node between resolved neighbours of opposite
sign at t = theta_a / (theta_a - theta_b), one undetermined node across a round-off run between
resolved components of opposite sign. Both start from the same eigenvectors (``eigen_modes``),
so the shapes, counts, flags, positions and regions must agree exactly."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from crankdyn.torsion import TorsionModel
from crankdyn.torsion.modal import eigen_modes, natural_modes

EPS = float(np.finfo(float).eps)


def _reference(model: TorsionModel, modal_inertia=None):
    """(shapes, node counts, resolved flags, located nodes (mode, first dof, fraction), nodes
    in round-off runs (mode, first, last), round-off regions per mode, modal inertias);
    ``modal_inertia``: the J_r for the thresholds (the code's, checked against the sum here to
    round-off: a BLAS may sum in another order)."""
    lam, phi = eigen_modes(model)
    omega = np.sqrt(lam)
    omega2 = [float(w) * float(w) for w in omega]
    n = len(omega2)
    J = [float(j) for j in model.dof_inertia]
    norm = max(abs(v) for v in omega2)
    shapes, counts, flags, located, loose, regions, inertias = [], [], [], [], [], [], []
    for r in range(n):
        x = [float(v) for v in phi[:, r]]
        peak = max(abs(v) for v in x)
        if not peak > 0.0:
            peak = 1.0
        size = [abs(v) / peak for v in x]
        first = next((i for i, s in enumerate(size) if s > 1e-9), 0)
        sign = math.copysign(1.0, x[first]) if x[first] != 0.0 else 1.0
        shape = [0.0 if s < 1e-14 else v / (peak * sign) for v, s in zip(x, size, strict=True)]
        shapes.append(shape)
        # the thresholds (omega_r^2 ascending)
        gaps = []
        if r + 1 < n:
            gaps.append(omega2[r + 1] - omega2[r])
        if r > 0:
            gaps.append(omega2[r] - omega2[r - 1])
        gap = min(gaps) if gaps else math.inf
        tau = 10.0 * EPS * norm / gap if gap > 0.0 else math.inf
        if n < 2:
            tau = 0.0
        jr = sum(j * v * v for j, v in zip(J, shape, strict=True))
        inertias.append(jr)
        if modal_inertia is not None:
            jr = float(modal_inertia[r])
        limit = tau * math.sqrt(jr)
        ok = [abs(v) * math.sqrt(j) > limit for v, j in zip(shape, J, strict=True)]
        if model.is_free and r == 0:
            ok = [True] * n
        # regions: maximal runs of unresolved components
        i = 0
        mode_regions = []
        while i < n:
            if ok[i]:
                i += 1
                continue
            k = i
            while k + 1 < n and not ok[k + 1]:
                k += 1
            mode_regions.append((i, k))
            i = k + 1
        regions.append(mode_regions)
        flags.append(not mode_regions)
        # nodes: sign changes between consecutive resolved components
        count = 0
        previous = None
        for q in range(n):
            if not ok[q]:
                continue
            if previous is not None and math.copysign(1.0, shape[previous]) != math.copysign(
                1.0, shape[q]
            ):
                count += 1
                if q == previous + 1:
                    a, b = shape[previous], shape[q]
                    located.append((r, previous, a / (a - b)))
                else:
                    loose.append((r, previous + 1, q - 1))
            previous = q
        counts.append(count)
    return shapes, counts, flags, located, loose, regions, inertias


def _chain(n: int, seed: int, kind: str, ground: str) -> TorsionModel:
    rng = np.random.default_rng(seed)
    if kind == "wide":  # ill-conditioned: localised high modes with round-off stretches
        inertia, stiffness = 10 ** rng.uniform(-4, 2, n), 10 ** rng.uniform(3, 9, n - 1)
    elif kind == "uniform":  # nodes at masses (round-off components in the middle)
        inertia, stiffness = np.ones(n), np.full(n - 1, 1e5)
    else:
        inertia, stiffness = rng.uniform(0.05, 2.0, n), rng.uniform(2e5, 5e6, n - 1)
    return TorsionModel.chain_of(
        inertia,
        stiffness,
        ground_left=3e5 if ground in ("left", "both") else None,
        ground_right=1e7 if ground == "both" else None,
    )


CASES = [
    (n, seed, kind, ground)
    for n, seed, kind, ground in [
        (1, 0, "random", "none"),
        (2, 1, "random", "none"),
        (3, 2, "wide", "left"),
        (7, 3, "uniform", "none"),
        (9, 4, "uniform", "left"),
        (12, 5, "random", "both"),
        (40, 6, "wide", "none"),
        (60, 7, "wide", "left"),
        (80, 8, "wide", "both"),
        (100, 9, "random", "none"),
        (120, 10, "wide", "none"),
        (300, 11, "wide", "left"),  # beyond _FLAT_COUNTS: the whole-array count
    ]
]


def test_the_reference_sees_round_off_runs_and_their_nodes():
    """The cases exercise what the vectorised code handles specially."""
    runs = nodes_in_runs = 0
    for case in CASES:
        *_, loose, regions, _ = _reference(_chain(*case))
        runs += sum(len(r) for r in regions)
        nodes_in_runs += len(loose)
    assert runs > 50 and nodes_in_runs > 10


@pytest.mark.parametrize(("n", "seed", "kind", "ground"), CASES)
def test_chain_post_processing_equals_the_reference(n, seed, kind, ground):
    model = _chain(n, seed, kind, ground)
    r = natural_modes(model)
    shapes, counts, flags, located, loose, regions, inertias = _reference(model, r.modal_inertia)
    np.testing.assert_allclose(r.modal_inertia, inertias, rtol=1e-13)
    got = np.asarray(r.mode_shapes)
    want = np.array(shapes)
    assert np.array_equal(got, want)
    assert np.array_equal(np.signbit(got), np.signbit(want))  # no negative zeros
    assert r.node_count.tolist() == counts
    assert r.nodes_resolved.tolist() == flags
    a = r.node_arrays
    assert a is not None
    shaft_first = [int(model.shaft_dofs[s].min()) for s in a.shaft]
    assert list(zip(a.shaft_mode.tolist(), shaft_first, a.fraction.tolist(), strict=True)) == [
        (m, i, t) for m, i, t in located
    ]
    assert (
        list(zip(a.open_mode.tolist(), a.open_first.tolist(), a.open_last.tolist(), strict=True))
        == loose
    )
    assert [
        [
            (f, z)
            for m, f, z in zip(a.region_mode, a.region_first, a.region_last, strict=True)
            if m == k
        ]
        for k in range(n)
    ] == regions
    assert [len(x) for x in r.nodes] == counts


@pytest.mark.parametrize("n", [1, 2, 5, 40, 91, 100, 150, 300])
def test_node_counts_of_any_resolved_pattern_equal_the_definition(n):
    """The counts (each way chain_node_counts takes: by rows found by division, by sums per row
    (reduceat), by whole-array passes) on random shapes and random resolved patterns, with rows
    that have no resolved component at all (a repeated eigenvalue: tau = inf), first, last or
    every row, and rows with a single resolved component, against the definition:
    the sign changes between a mode's consecutive resolved components."""
    from crankdyn.torsion.nodes import chain_node_counts

    rng = np.random.default_rng(n)
    for k in range(12):
        shapes = rng.standard_normal((n, n))
        shapes[rng.random((n, n)) < 0.2] = -0.0 if k % 2 else 0.0
        resolved = rng.random((n, n)) < rng.uniform(0.05, 1.0)
        resolved[rng.integers(0, n)] = False
        if k == 3:
            resolved[-1] = False  # the last rows with none: the sums end past every component
        if k == 5:
            resolved[:] = False
        if k == 7:
            resolved[0] = False  # the first row with none: its sum would start in the next row
        if k == 9:  # a single resolved component in every row, ending the last row
            resolved[:] = False
            resolved[np.arange(n), rng.integers(0, n, n)] = True
            resolved[-1, -1] = True
        counts, whole = chain_node_counts(shapes, resolved)
        want = []
        for row, keep in zip(shapes, resolved, strict=True):
            signs = [math.copysign(1.0, v) < 0 for v, ok in zip(row, keep, strict=True) if ok]
            want.append(sum(a != b for a, b in itertools.pairwise(signs)))
        assert counts.tolist() == want
        assert whole.tolist() == resolved.all(axis=1).tolist()


# ---- the one-pass path of a chain (natural_modes up to _ONE_PASS dofs) ---------------------------


def _one_pass_models() -> list[TorsionModel]:
    """Chains that take each branch of _chain_modes: every mode resolved; modes at rest in the
    first amplitude, with round-off amplitudes and round-off runs (wide); nodes at masses
    (uniform); inertias and stiffnesses over 14 decades (extreme); repeated eigenvalues (two
    equal halves joined by a shaft of 1e-12 N m/rad); grounded at either or both ends; masses
    listed out of chain order; rigid gear meshes (degrees of freedom not the masses)."""
    from crankdyn.torsion import Gear, Mass, Shaft

    out = []
    rng = np.random.default_rng(16)
    for n in (2, 3, 5, 10, 17, 33, 64, 100, 128, 150):
        for kind in ("random", "wide", "uniform", "extreme"):
            if kind == "extreme":
                inertia, stiffness = 10 ** rng.uniform(-8, 6, n), 10 ** rng.uniform(0, 12, n - 1)
            else:
                model = _chain(n, int(rng.integers(1 << 30)), kind, "none")
                inertia, stiffness = model.dof_inertia, model.chain.stiffness
            for ground in ("none", "left", "right", "both"):
                out.append(
                    TorsionModel.chain_of(
                        inertia,
                        stiffness,
                        ground_left=3e5 if ground in ("left", "both") else None,
                        ground_right=1e7 if ground in ("right", "both") else None,
                    )
                )
    out.append(TorsionModel.chain_of([1.0] * 4, [1e6, 1e-12, 1e6]))
    out.append(
        TorsionModel(
            masses=(Mass("a", 1.0), Mass("c", 0.3), Mass("d", 0.2), Mass("b", 0.5)),
            shafts=(
                Shaft(("c", "d"), 3e5),
                Shaft(("a", "b"), 1e5),
                Shaft(("b", "c"), 2e5),
                Shaft(("ground", "d"), 4e4),
            ),
        )
    )
    out.append(
        TorsionModel(
            masses=(
                Mass("engine", 0.5),
                Mass("pinion", 0.01),
                Mass("wheel", 0.05),
                Mass("load", 1),
            ),
            shafts=(Shaft(("engine", "pinion"), 2e5), Shaft(("wheel", "load"), 5e4)),
            gears=(Gear(("pinion", "wheel"), teeth=(20, 64)),),
        )
    )
    return out


def _same(a, b) -> bool:
    a, b = np.asarray(a), np.asarray(b)
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


def test_the_one_pass_chain_modes_are_the_step_by_step_ones_to_the_bit():
    """_chain_modes (dstevd and the post-processing fused, the common case of each step in few
    numpy calls) against _modes (eigen_modes, _rows, _result: the general helpers, checked
    against the reference above): every array identical to the bit, nodes included, on 163
    chains that take every branch (counted here)."""
    from crankdyn.torsion.modal import _chain_modes, _modes
    from crankdyn.torsion.nodes import distinct_thresholds

    seen = {"at rest first": 0, "round-off zeros": 0, "unresolved": 0, "repeated": 0}
    models = _one_pass_models()
    for model in models:
        free = model.is_free
        one = _chain_modes(model, model.chain, free)
        steps = _modes(model, "eigen", None, False, free)
        for name in (
            "mode",
            "natural_frequency",
            "node_count",
            "nodes_resolved",
            "modal_inertia",
            "modal_stiffness",
            "mode_shapes",
            "shapes_dof",
        ):
            assert _same(getattr(one, name), getattr(steps, name)), name
            assert not getattr(one, name).flags.writeable, name
        for name in ("masses", "solver", "structure", "free", "model_name", "modes_of_the_model"):
            assert getattr(one, name) == getattr(steps, name), name
        for name in one.node_arrays.__dataclass_fields__:
            assert _same(getattr(one.node_arrays, name), getattr(steps.node_arrays, name)), name
        shapes = np.asarray(one.shapes_dof)
        seen["at rest first"] += bool((np.abs(shapes[:, 0]) <= 1e-9).any())
        seen["round-off zeros"] += bool((shapes == 0.0).any())
        seen["unresolved"] += not one.nodes_resolved.all()
        seen["repeated"] += distinct_thresholds(np.asarray(one.natural_frequency) ** 2) is None
    assert len(models) == 163
    assert min(seen.values()) >= 1, seen


def test_natural_modes_takes_the_one_pass_path_for_chains_up_to_its_size(monkeypatch):
    from crankdyn.torsion import modal

    calls = []
    monkeypatch.setattr(modal, "_chain_modes", lambda *a: calls.append(a[0]) or "one pass")
    small = _chain(modal._ONE_PASS, 1, "random", "none")
    assert natural_modes(small) == "one pass"
    assert natural_modes(small, count=modal._ONE_PASS) == "one pass"  # all of them: the same
    for model, kw in [
        (_chain(modal._ONE_PASS + 1, 1, "random", "none"), {}),
        (small, {"count": 3}),
        (small, {"solver": "transfer"}),
        (_chain(1, 1, "random", "none"), {}),
    ]:
        assert natural_modes(model, **kw) != "one pass"
    assert len(calls) == 2


def test_a_result_assembled_without_init_is_the_one_init_makes():
    from crankdyn.torsion.modal import ModalResult

    r = natural_modes(_chain(5, 1, "random", "left"))
    values = {name: getattr(r, name) for name in ModalResult.__dataclass_fields__}
    assert ModalResult._assembled(**values).__dict__ == ModalResult(**values).__dict__
    assert not hasattr(ModalResult, "__post_init__")  # nothing checked there to skip
    del values["solver"]
    with pytest.raises(TypeError, match="every field"):
        ModalResult._assembled(**values)


def test_shapes_normalised_in_one_division_follow_the_rule_row_by_row():
    """normalise_shapes (each row divided once by its largest amplitude signed as its first, rows at
    rest in the first amplitude negated where needed) against _normalise_rows (the rule row by
    row: the sign of the first amplitude above 1e-9 of the largest) on random rows with
    amplitudes at rest first, round-off amplitudes, zeros of both signs and scales of 1e+-200,
    few and many rows at rest (both branches of each), to the bit; rows of zeros, inf or NaN go
    to the rule itself."""
    from crankdyn.torsion.nodes import _normalise_rows, normalise_shapes

    rng = np.random.default_rng(1616)
    for count, n in [(1, 1), (3, 4), (10, 10), (40, 40), (100, 100), (64, 300)]:
        for k in range(12):
            x = rng.standard_normal((count, n)) * 10.0 ** rng.uniform(-200, 200, (count, 1))
            x[rng.random((count, n)) < 0.1] *= 1e-16  # round-off amplitudes
            x[rng.random((count, n)) < 0.05] = -0.0 if k % 2 else 0.0
            rest = rng.random(count) < (0.9 if k % 3 == 0 else 0.1)  # many / few rows at rest
            x[rest, : rng.integers(1, n + 1)] *= 1e-12
            if k == 5:
                x[0] = 0.0  # a row of zeros: the rule itself
            if k == 7:
                x[-1, -1] = np.nan
            shapes, size, least = normalise_shapes(x.copy())
            want, want_size = _normalise_rows(x.copy())
            assert _same(shapes, want)
            assert _same(size, want_size)
            if least is not None:
                assert _same(least, size.min(axis=1))


def test_thresholds_of_distinct_eigenvalues_follow_their_definition_to_the_bit():
    """distinct_thresholds (on a list up to 32 eigenvalues, by numpy beyond) against the
    definition written out mode by mode: tau_r = 10 eps max|lambda| / gap_r, gap_r the distance
    to the nearer neighbour (LAPACK Users' Guide section 4.7.1), to the bit, for spectra of 2-40
    values at scales of 1e-300 to 1e+300; repeated, NaN or inf spectra give None."""
    from crankdyn.torsion.nodes import distinct_thresholds

    eps = np.finfo(float).eps
    rng = np.random.default_rng(4711)
    for n in [*range(2, 41), 64]:
        for scale in (1e-300, 1.0, 1e8, 1e300):
            lam = np.sort(rng.uniform(0.0, 1.0, n)) * scale
            if np.any(np.diff(lam) <= 0.0):
                continue
            got = distinct_thresholds(lam)
            assert got is not None
            values = lam.tolist()
            norm = max(abs(values[0]), abs(values[-1]))
            want = []
            for r in range(n):
                gaps = [values[r + 1] - values[r]] if r < n - 1 else []
                gaps += [values[r] - values[r - 1]] if r > 0 else []
                want.append(10.0 * eps * norm / min(gaps))
            assert got[0].tolist() == want
            assert got[1] == max(want)
        for bad in (np.nan, np.inf):
            lam = np.sort(rng.uniform(0.0, 1.0, n))
            lam[n // 2] = bad
            with np.errstate(invalid="ignore"):  # numpy's reductions over NaN say so
                assert distinct_thresholds(lam) is None
        assert distinct_thresholds(np.zeros(n)) is None
