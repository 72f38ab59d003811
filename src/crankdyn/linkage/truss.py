"""Statically determinate plane trusses: member forces by the method of joints and by the method
of sections, each checked against the other (domain, analysis and result; seed 004).

Seed 004 sec. 3.4 ("静定平面桁架"): an ideal truss has smooth pin joints (结点都是光滑的铰结点),
straight members whose axes pass through the pins, and loads and reactions at the joints only, so
that every member is a two-force member carrying an axial force alone. A member's force N is
positive in tension (拉力, pointing away from the joint on a joint's free body) and negative in
compression; unknown forces are first taken as tension (seed 004 sec. 3.4.2).

Equilibrium of a joint n with members k to joints b(k), unit vectors e_k = (r_b - r_n)/|r_b - r_n|,
reaction components R_c along u_c and the applied load F_n::

    sum_k N_k e_k + sum_c R_c u_c + F_n = 0                        (two equations per joint)

A truss of j joints, m members and r reaction components is statically determinate when
m + r = 2 j and the 2 j equations are independent (else it is a mechanism, m + r < 2 j or the
equations singular, or statically indeterminate, m + r > 2 j); the seed's simple trusses (a
triangle to which each new joint is added by two members, 简单桁架) are.

**Method of joints** (结点法, seed 004 sec. 3.4.2): the reactions from the equilibrium of the whole
truss (sum F_x = sum F_y = 0 and the moments about the first support, when the supports give
exactly three components), then joint after joint, always one at which at most two forces are
still unknown, solving its two equations; the joints left over check the result (their
out-of-balance is reported). A compound or complex truss reaches a point where every joint has
three or more unknowns: the joints left are then solved together (the seed's combined method,
联合法, as one linear system), which the result says.

**Method of sections** (截面法): for each member a section that cuts it and at most two other
members and parts the truss in two; the three equilibrium equations of one part (sum F_x,
sum F_y, sum of moments, M = (x - x_0) F_y - (y - y_0) F_x, seed 004 eq. (1)), with that part's
loads and the reactions from the whole truss, give the cut members' forces: for three cut members
this is the seed's moment about the point where the other two meet (Ritter's method). The part
without supports is taken when there is one. A member that no section of three members isolates
(the inner members of some complex trusses) is found by joints only.

**Zero-force members by inspection** (seed 004 sec. 3.4.2, the three cases of 图 3-15): at an
unloaded, unsupported joint of two members that are not in line, both carry no force; at such a
joint of three members of which two are in line, the third carries none (and the two in line carry
the same force); at such a "K" joint of four members, two in line and the other two on one side of
that line at equal angles to it, those two carry equal and opposite forces. The first two rules
name zero-force members (listed in the result); all three hold in the solution (tested).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from crankdyn.crank.geometry import check_finite
from crankdyn.errors import InputError, did_you_mean
from crankdyn.results import Result, column, freeze, scalar

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = [
    "SUPPORT_KINDS",
    "Truss",
    "TrussLoad",
    "TrussReactions",
    "TrussResult",
    "TrussSupport",
    "member_forces",
    "truss_analysis",
]

SUPPORT_KINDS = ("pin", "roller")
"""A pin holds its joint in both directions (two reaction components), a roller in one."""
_PARALLEL = 1e-9
"""|sin| of the angle between two unknown forces at a joint below which they count as in line."""
_RANK = 1e-10
"""Singular value (relative to the largest) below which a system of equilibrium counts as
singular: a geometrically unstable truss."""


@dataclass(frozen=True)
class TrussSupport:
    """A support of a truss joint.

    Parameters
    ----------
    node : str
        The supported joint.
    kind : str
        ``"pin"`` (reactions R_x and R_y) or ``"roller"`` (one reaction along ``direction``).
    direction : float
        Direction of a roller's reaction (rad, counter-clockwise from the x axis); default
        pi / 2 (a roller on a horizontal surface). Ignored for a pin.

    Raises
    ------
    crankdyn.errors.InputError
        An unknown kind or a direction that is not finite (names the key and value).

    Examples
    --------
    >>> TrussSupport("J", "roller").components()
    (('J', (0.0, 1.0)),)
    """

    node: str
    kind: str = "pin"
    direction: float = math.pi / 2.0

    def __post_init__(self) -> None:
        if self.kind not in SUPPORT_KINDS:
            raise InputError(
                f"expected one of {', '.join(SUPPORT_KINDS)}"
                f"{did_you_mean(self.kind, SUPPORT_KINDS)}",
                key="kind",
                value=self.kind,
            )
        object.__setattr__(self, "direction", check_finite("direction", self.direction))

    def components(self) -> tuple[tuple[str, tuple[float, float]], ...]:
        """The reaction components: a name and a unit vector each.

        Returns
        -------
        tuple of (str, (float, float))
            ``(node + " x", (1, 0))`` and ``(node + " y", (0, 1))`` for a pin; ``(node,
            (cos a, sin a))`` for a roller (dimensionless unit vectors).
        """
        if self.kind == "pin":
            return ((f"{self.node} x", (1.0, 0.0)), (f"{self.node} y", (0.0, 1.0)))
        c, s = math.cos(self.direction), math.sin(self.direction)
        return ((self.node, (round(c, 15) + 0.0, round(s, 15) + 0.0)),)


@dataclass(frozen=True)
class TrussLoad:
    """A force applied at a truss joint.

    Parameters
    ----------
    node : str
        The loaded joint.
    force : tuple of float
        (F_x, F_y) (N).

    Raises
    ------
    crankdyn.errors.InputError
        A component that is not finite (key ``force``).
    """

    node: str
    force: tuple[float, float]

    def __post_init__(self) -> None:
        fx, fy = (check_finite("force", v) for v in self.force)
        object.__setattr__(self, "force", (fx, fy))


@dataclass(frozen=True, eq=False)
class Truss:
    """A plane pin-jointed truss: joints, members, supports and joint loads (module docstring).

    Parameters
    ----------
    nodes : tuple of str
        The joints' names.
    coordinates : array_like
        (j, 2) joint coordinates (m), in the order of ``nodes``; held as a read-only array.
    members : tuple of (str, str)
        The members, each by its two joints.
    supports : tuple of TrussSupport
        The supports.
    loads : tuple of TrussLoad
        The applied joint loads (N); default none.
    name : str
        The truss's name, for outputs.
    member_names : tuple of str or None
        The members' names; default ``"A-B"`` from their joints.
    source : str or None
        The file it came from, for messages.

    Raises
    ------
    crankdyn.errors.InputError
        Duplicate or unknown joint names, a member of zero length or given twice, two supports
        at one joint, coordinates not finite, or m + r other than 2 j (statically indeterminate
        or a mechanism); names the key and value.

    Examples
    --------
    A triangle on a pin and a roller, loaded at its apex:

    >>> truss = Truss(
    ...     ("A", "B", "C"), [(0.0, 0.0), (4.0, 0.0), (2.0, 1.5)],
    ...     (("A", "B"), ("A", "C"), ("B", "C")),
    ...     (TrussSupport("A"), TrussSupport("B", "roller")),
    ...     (TrussLoad("C", (0.0, -600.0)),),
    ... )
    >>> truss.member_names, truss.reaction_names
    (('A-B', 'A-C', 'B-C'), ('A x', 'A y', 'B'))
    """

    nodes: tuple[str, ...]
    coordinates: NDArray[np.float64]  # array_like accepted (frozen in __post_init__)
    members: tuple[tuple[str, str], ...]
    supports: tuple[TrussSupport, ...]
    loads: tuple[TrussLoad, ...] = ()
    name: str = "truss"
    member_names: tuple[str, ...] = None  # type: ignore[assignment]  # None: derived
    source: str | None = None
    _index: dict[str, int] = field(default_factory=dict, init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        nodes = tuple(str(n) for n in self.nodes)
        if len(set(nodes)) != len(nodes):
            same = next(n for n in nodes if nodes.count(n) > 1)
            raise InputError("two joints have the same name", key="nodes", value=same)
        xy = np.asarray(self.coordinates, dtype=float)
        if xy.shape != (len(nodes), 2) or not np.all(np.isfinite(xy)):
            raise InputError(
                "expected a finite (x, y) pair for every joint", key="coordinates", value=xy.shape
            )
        index = {n: i for i, n in enumerate(nodes)}
        members = tuple((str(a), str(b)) for a, b in self.members)
        for pair in members:
            for end in pair:
                if end not in index:
                    raise InputError(
                        f'no joint named "{end}"{did_you_mean(end, nodes)}',
                        key="members",
                        value=list(pair),
                    )
            if pair[0] == pair[1] or np.allclose(xy[index[pair[0]]], xy[index[pair[1]]]):
                raise InputError("a member joins two distinct points", key="members", value=pair)
        keys = [frozenset(p) for p in members]
        if len(set(keys)) != len(keys):
            twice = next(p for p, k in zip(members, keys, strict=True) if keys.count(k) > 1)
            raise InputError("a member is given twice", key="members", value=list(twice))
        names = (
            tuple(f"{a}-{b}" for a, b in members)
            if self.member_names is None
            else tuple(str(n) for n in self.member_names)
        )
        if len(names) != len(members) or len(set(names)) != len(names):
            raise InputError("expected one distinct name per member", key="name")
        supported = [s.node for s in self.supports]
        for s in self.supports:
            if s.node not in index:
                raise InputError(
                    f'no joint named "{s.node}"{did_you_mean(s.node, nodes)}',
                    key="supports",
                    value=s.node,
                )
        if len(set(supported)) != len(supported):
            raise InputError("a joint has two supports", key="supports", value=supported)
        for load in self.loads:
            if load.node not in index:
                raise InputError(
                    f'no joint named "{load.node}"{did_you_mean(load.node, nodes)}',
                    key="loads",
                    value=load.node,
                )
        r = sum(len(s.components()) for s in self.supports)
        m, j = len(members), len(nodes)
        if m + r != 2 * j:
            what = "statically indeterminate" if m + r > 2 * j else "a mechanism"
            raise InputError(
                f"{m} members and {r} reaction components against {j} joints: m + r = {m + r}, "
                f"not 2 j = {2 * j}; the truss is {what} (the methods of joints and sections "
                "need a statically determinate truss, seed 004 sec. 3.4)",
                key="members",
                value=m,
            )
        object.__setattr__(self, "nodes", nodes)
        object.__setattr__(self, "coordinates", freeze(xy))
        object.__setattr__(self, "members", members)
        object.__setattr__(self, "member_names", names)
        object.__setattr__(self, "supports", tuple(self.supports))
        object.__setattr__(self, "loads", tuple(self.loads))
        object.__setattr__(self, "_index", index)

    # ---- derived ------------------------------------------------------------------------------
    def index(self, node: str) -> int:
        """Position of a joint in :attr:`nodes`.

        Parameters
        ----------
        node : str
            The joint's name.

        Returns
        -------
        int
            Its index.

        Raises
        ------
        crankdyn.errors.InputError
            No such joint (key ``node``).
        """
        try:
            return self._index[node]
        except KeyError:
            raise InputError(
                f'no joint named "{node}"{did_you_mean(node, self.nodes)}', key="node", value=node
            ) from None

    @property
    def reaction_names(self) -> tuple[str, ...]:
        """The names of the reaction components, support by support."""
        return tuple(name for s in self.supports for name, _ in s.components())

    @property
    def member_ends(self) -> NDArray[np.int64]:
        """(m, 2) joint indices of every member."""
        return np.array([[self._index[a], self._index[b]] for a, b in self.members], dtype=int)

    @property
    def unit_vectors(self) -> NDArray[np.float64]:
        """(m, 2) unit vectors from each member's first joint to its second (dimensionless)."""
        ends = self.member_ends
        d = self.coordinates[ends[:, 1]] - self.coordinates[ends[:, 0]]
        return d / np.hypot(d[:, 0], d[:, 1])[:, None]

    @property
    def load_vector(self) -> NDArray[np.float64]:
        """(2 j,) applied loads, F_x and F_y of every joint in turn (N)."""
        f = np.zeros(2 * len(self.nodes))
        for load in self.loads:
            i = self._index[load.node]
            f[2 * i] += load.force[0]
            f[2 * i + 1] += load.force[1]
        return f

    def equilibrium_matrix(self) -> NDArray[np.float64]:
        """The joints' equilibrium equations A {N, R} = -F (module docstring).

        Returns
        -------
        numpy.ndarray
            (2 j, m + r): rows F_x and F_y of every joint in turn, columns the member forces
            (tension positive) then the reaction components (dimensionless).
        """
        j, m = len(self.nodes), len(self.members)
        comps = [(self._index[s.node], u) for s in self.supports for _, u in s.components()]
        a = np.zeros((2 * j, m + len(comps)))
        e = self.unit_vectors
        for k, (p, q) in enumerate(self.member_ends):
            a[2 * p : 2 * p + 2, k] += e[k]
            a[2 * q : 2 * q + 2, k] -= e[k]
        for c, (n, u) in enumerate(comps):
            a[2 * n : 2 * n + 2, m + c] = u
        return a

    def plot(self, result: TrussResult | None = None, fig: Figure | None = None) -> Figure:
        """The truss drawn, with its member forces when a result is given.

        Parameters
        ----------
        result : TrussResult or None
            Its analysis (tension and compression coloured, forces written on the members).
        fig : matplotlib.figure.Figure or None
            A figure to draw into; default a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.linkage_statics import plot_truss

        return plot_truss(self, result, fig=fig)


@dataclass(frozen=True)
class TrussReactions(Result):
    """The support reactions of a truss (:func:`truss_analysis`): as the method of joints used
    them (from the whole truss's equilibrium when the supports give three components), and from
    every joint's equations solved at once (:func:`member_forces`), an independent check."""

    title = "Support reactions"
    component: NDArray[np.str_] = column("component", "Reaction", "")
    joints: NDArray[np.float64] = column("reaction_N", "Reaction", "N")
    all_at_once: NDArray[np.float64] = column(
        "reaction_all_joints_N", "Reaction, every joint's equations solved at once", "N"
    )


@dataclass(frozen=True)
class TrussResult(Result):
    """Member forces of a plane truss by the methods of joints and of sections
    (:func:`truss_analysis`; module docstring). Tension positive.

    Parameters
    ----------
    truss : Truss or None
        The truss analysed (not exported), for the figure.
    """

    title = "Truss member forces"
    truss_name: str = scalar("truss", "Truss", "")
    member: NDArray[np.str_] = column("member", "Member", "")
    force: NDArray[np.float64] = column("force_N", "Force, method of joints", "N")
    force_sections: NDArray[np.float64] = column(
        "force_sections_N", "Force, method of sections", "N"
    )
    state: NDArray[np.str_] = column("state", "Tension / compression", "")
    section: NDArray[np.str_] = column("section", "Section through", "")
    max_tension: float = scalar("max_tension_N", "Largest tension", "N")
    max_compression: float = scalar("max_compression_N", "Largest compression", "N")
    method_difference: float = scalar(
        "method_difference_N", "Largest difference, joints against sections", "N"
    )
    closure: float = scalar(
        "closure_N", "Largest out-of-balance force at the joints used as checks", "N"
    )
    joint_order: str = scalar("joint_order", "Joints in the order solved", "")
    zero_force_members: tuple[str, ...] = scalar(
        "zero_force_members", "Zero-force members by inspection", ""
    )
    reactions: TrussReactions = scalar("reactions", "Support reactions", "")
    notes: tuple[str, ...] | None = scalar("notes", "Notes", "", default=None)
    truss: Truss | None = field(default=None, repr=False, compare=False)

    def plot(self, fig: Figure | None = None) -> Figure:
        """The truss with its member forces (:func:`crankdyn.plots.linkage_statics.plot_truss`).

        Parameters
        ----------
        fig : matplotlib.figure.Figure or None
            A figure to draw into; default a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.linkage_statics import plot_truss

        assert self.truss is not None  # truss_analysis keeps it
        return plot_truss(self.truss, self, fig=fig)


# ---- the analysis -----------------------------------------------------------------------------
def _rank_solve(a: NDArray[np.float64], b: NDArray[np.float64]) -> NDArray[np.float64] | None:
    """x with a x = b when a has full column rank and the system is consistent, else None."""
    if a.shape[1] == 0:
        return np.zeros(0)
    s = np.linalg.svd(a, compute_uv=False)
    if s.size < a.shape[1] or s[-1] <= _RANK * max(s[0], 1.0):
        return None
    x = np.linalg.lstsq(a, b, rcond=None)[0]
    scale = max(float(np.max(np.abs(b), initial=0.0)), float(np.max(np.abs(a @ x), initial=0.0)))
    if np.max(np.abs(a @ x - b), initial=0.0) > 1e-9 * max(scale, 1.0):
        return None
    return np.asarray(x, dtype=float)


def _whole_truss(truss: Truss) -> NDArray[np.float64] | None:
    """The reaction components from the whole truss's three equations (sum F_x, sum F_y, moments
    about the origin, seed 004 eq. (1)), when the supports give exactly three; else None."""
    comps = [(truss.index(s.node), u) for s in truss.supports for _, u in s.components()]
    if len(comps) != 3:
        return None
    xy = truss.coordinates
    a = np.zeros((3, 3))
    for c, (n, (ux, uy)) in enumerate(comps):
        a[:, c] = (ux, uy, xy[n, 0] * uy - xy[n, 1] * ux)
    f = truss.load_vector.reshape(-1, 2)
    b = -np.array([f[:, 0].sum(), f[:, 1].sum(), np.sum(xy[:, 0] * f[:, 1] - xy[:, 1] * f[:, 0])])
    return _rank_solve(a, b)


def _by_joints(
    truss: Truss, whole: NDArray[np.float64] | None
) -> tuple[NDArray[np.float64], list[str], float, list[str]]:
    """The method of joints: reactions from the whole truss, then joint by joint (module
    docstring). Returns the unknowns {N, R}, the joints in order, the closure and notes."""
    a = truss.equilibrium_matrix()
    rhs = -truss.load_vector
    m = len(truss.members)
    unknowns = a.shape[1]
    x = np.zeros(unknowns)
    known = np.zeros(unknowns, dtype=bool)
    if whole is not None:
        x[m:] = whole
        known[m:] = True
    j = len(truss.nodes)
    used = np.zeros(j, dtype=bool)
    order: list[str] = []
    notes: list[str] = []
    cols_at = [np.flatnonzero(np.any(a[2 * n : 2 * n + 2] != 0.0, axis=0)) for n in range(j)]
    progress = True
    while progress and not known.all():
        progress = False
        for n in range(j):
            if used[n]:
                continue
            free = [c for c in cols_at[n] if not known[c]]
            if not 1 <= len(free) <= 2:
                continue
            block = a[2 * n : 2 * n + 2]
            sub = block[:, free]
            if len(free) == 2 and abs(np.linalg.det(sub)) < _PARALLEL:
                continue  # two unknown forces in line: not from this joint
            b = rhs[2 * n : 2 * n + 2] - block[:, known] @ x[known]
            sol = _rank_solve(sub, b)
            if sol is None:
                continue
            x[free] = sol
            known[free] = True
            used[n] = True
            order.append(truss.nodes[n])
            progress = True
    if not known.all():
        rest = np.flatnonzero(~used)
        rows = np.concatenate([[2 * n, 2 * n + 1] for n in rest]).astype(int)
        free_cols = np.flatnonzero(~known)
        b = rhs[rows] - a[np.ix_(rows, known)] @ x[known]
        sol = _rank_solve(a[np.ix_(rows, free_cols)], b)
        if sol is None:
            raise InputError(
                "the truss is geometrically unstable: its joints' equations of equilibrium are "
                "singular (members in line at a joint, or a part that can move)",
                file=truss.source,
                key="members",
            )
        x[free_cols] = sol
        together = [truss.nodes[n] for n in rest]
        used[rest] = True
        order.append("(" + ", ".join(together) + " together)")
        notes.append(
            f"no joint with at most two unknown forces was left after {len(order) - 1} joints: "
            f"joints {', '.join(together)} were solved together (a compound or complex truss, "
            "seed 004's combined method)"
        )
    residual = a @ x - rhs
    closure = float(np.max(np.abs(residual), initial=0.0))
    checks = [truss.nodes[n] for n in range(j) if not used[n]]
    if checks and order:
        order[-1] += "; checks: " + ", ".join(checks)
    elif checks:
        order.append("checks: " + ", ".join(checks))
    return x, order, closure, notes


def _components(edges: NDArray[np.int64], keep: NDArray[np.bool_], j: int) -> NDArray[np.int64]:
    """Connected-component label of every joint over the kept members (union-find)."""
    parent = np.arange(j)

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = int(parent[i])
        return i

    for (p, q), k in zip(edges, keep, strict=True):
        if k:
            rp, rq = root(int(p)), root(int(q))
            if rp != rq:
                parent[rp] = rq
    return np.array([root(i) for i in range(j)])


def _section(truss: Truss, target: int, whole: NDArray[np.float64]) -> tuple[float, str] | None:
    """The force in member ``target`` by a section of at most three members (module docstring),
    and the section's description; None when no such section isolates it."""
    edges = truss.member_ends
    m, j = len(edges), len(truss.nodes)
    xy = truss.coordinates
    e = truss.unit_vectors
    loads = truss.load_vector.reshape(-1, 2)
    comps = [(truss.index(s.node), u) for s in truss.supports for _, u in s.components()]
    others = [k for k in range(m) if k != target]
    candidates: list[tuple[int, ...]] = [(target,)]
    candidates += [(target, k) for k in others]
    candidates += [(target, k, l) for i, k in enumerate(others) for l in others[i + 1 :]]
    for cut in candidates:
        keep = np.ones(m, dtype=bool)
        keep[list(cut)] = False
        label = _components(edges, keep, j)
        parts = np.unique(label)
        if parts.size != 2:
            continue
        if any(label[edges[k, 0]] == label[edges[k, 1]] for k in cut):
            continue  # a cut member inside one part: not a section
        supported = [label[n] for n, _ in comps]
        side = next((p for p in parts if p not in supported), None)
        if side is None:
            side = min(parts, key=lambda p: int(np.sum(label == p)))
        inside = label == side
        x0, y0 = xy[inside].mean(axis=0)
        a = np.zeros((3, len(cut)))
        for c, k in enumerate(cut):
            p, q = edges[k]
            n, sign = (p, 1.0) if inside[p] else (q, -1.0)  # tension pulls the part's joint out
            fx, fy = sign * e[k]
            a[:, c] = (fx, fy, (xy[n, 0] - x0) * fy - (xy[n, 1] - y0) * fx)
        f = loads.copy()
        for c, (n, (ux, uy)) in enumerate(comps):
            f[n] += whole[c] * np.array([ux, uy])
        fi, pi = f[inside], xy[inside]
        b = -np.array(
            [
                fi[:, 0].sum(),
                fi[:, 1].sum(),
                np.sum((pi[:, 0] - x0) * fi[:, 1] - (pi[:, 1] - y0) * fi[:, 0]),
            ]
        )
        sol = _rank_solve(a, b)
        if sol is None:
            continue
        names = [truss.member_names[k] for k in cut]
        part = [n for n, i in zip(truss.nodes, inside, strict=True) if i]
        return float(sol[0]), f"{', '.join(names)} (part {', '.join(part)})"
    return None


def _cross(u: NDArray[np.float64], v: NDArray[np.float64]) -> float:
    """z component of the cross product of two plane vectors."""
    return float(u[0] * v[1] - u[1] * v[0])


def _zero_by_inspection(truss: Truss) -> tuple[str, ...]:
    """Zero-force members by the seed's first two rules (module docstring)."""
    e = truss.unit_vectors
    edges = truss.member_ends
    loaded = {truss.index(f.node) for f in truss.loads if any(v != 0.0 for v in f.force)}
    supported = {truss.index(s.node) for s in truss.supports}
    zero: set[int] = set()
    for n in range(len(truss.nodes)):
        if n in loaded or n in supported:
            continue
        at = [k for k in range(len(edges)) if n in edges[k]]
        if len(at) == 2 and abs(_cross(e[at[0]], e[at[1]])) > _PARALLEL:
            zero.update(at)
        elif len(at) == 3:
            for i in range(3):
                p, q = (at[(i + 1) % 3], at[(i + 2) % 3])
                if abs(_cross(e[p], e[q])) <= _PARALLEL < abs(_cross(e[p], e[at[i]])):
                    zero.add(at[i])
    return tuple(truss.member_names[k] for k in sorted(zero))


def truss_analysis(truss: Truss) -> TrussResult:
    """Member forces of a statically determinate plane truss by the method of joints and by
    the method of sections, checked against each other (seed 004 sec. 3.4; module docstring).

    Parameters
    ----------
    truss : Truss
        The truss (m), its supports and joint loads (N).

    Returns
    -------
    TrussResult
        Member forces by both methods (N, tension positive), the reactions (N), the joints
        in the order solved, the out-of-balance at the joints used as checks (N), the zero-force
        members by inspection.

    Raises
    ------
    crankdyn.errors.InputError
        A geometrically unstable truss (singular equations of equilibrium).

    Examples
    --------
    A 3-4-5 triangle: the apex load 600 N down is carried by two struts of 500 N each
    and a tie of 400 N.

    >>> truss = Truss(
    ...     ("A", "B", "C"), [(0.0, 0.0), (8.0, 0.0), (4.0, 3.0)],
    ...     (("A", "B"), ("A", "C"), ("B", "C")),
    ...     (TrussSupport("A"), TrussSupport("B", "roller")),
    ...     (TrussLoad("C", (0.0, -600.0)),),
    ... )
    >>> result = truss_analysis(truss)
    >>> [round(float(f), 6) for f in result.force]
    [400.0, -500.0, -500.0]
    >>> [round(float(f), 6) for f in result.force_sections]
    [400.0, -500.0, -500.0]
    >>> [str(s) for s in result.state], result.joint_order
    (['tension', 'compression', 'compression'], 'A, B; checks: C')
    """
    whole = _whole_truss(truss)
    x, order, closure, notes = _by_joints(truss, whole)
    m = len(truss.members)
    force = x[:m]
    sections = np.full(m, np.nan)
    described: list[str] = []
    if whole is None:
        described = ["-"] * m
        notes.append(
            "the supports give more or fewer than three reaction components: the whole truss's "
            "equilibrium does not fix them, so no section check (the method of joints alone)"
        )
    else:
        for k in range(m):
            found = _section(truss, k, whole)
            if found is None:
                described.append("-")
                continue
            sections[k], text = found
            described.append(text)
        missing = [truss.member_names[k] for k in range(m) if np.isnan(sections[k])]
        if missing:
            notes.append(
                f"no section through at most three members isolates {', '.join(missing)}: "
                "found by joints only"
            )
    scale = max(float(np.max(np.abs(force), initial=0.0)), 1.0)
    tiny = 1e-9 * scale
    state = ["zero" if abs(f) <= tiny else "tension" if f > 0 else "compression" for f in force]
    checked = ~np.isnan(sections)
    difference = float(np.max(np.abs(force[checked] - sections[checked]), initial=0.0))
    reactions = TrussReactions(
        component=freeze(np.array(truss.reaction_names, dtype=str), dtype=str),
        joints=freeze(x[m:]),
        all_at_once=freeze(member_forces(truss)[m:]),
    )
    return TrussResult(
        truss_name=truss.name,
        member=freeze(np.array(truss.member_names, dtype=str), dtype=str),
        force=freeze(np.where(np.abs(force) <= tiny, 0.0, force)),
        force_sections=freeze(np.where(np.abs(sections) <= tiny, 0.0, sections)),
        state=freeze(np.array(state, dtype=str), dtype=str),
        section=freeze(np.array(described, dtype=str), dtype=str),
        max_tension=float(max(np.max(force, initial=0.0), 0.0)),
        max_compression=float(max(-np.min(force, initial=0.0), 0.0)),
        method_difference=difference,
        closure=closure,
        joint_order=", ".join(order),
        zero_force_members=_zero_by_inspection(truss),
        reactions=reactions,
        notes=tuple(notes) or None,
        truss=truss,
    )


def member_forces(truss: Truss) -> NDArray[np.float64]:
    """Member forces of all joints' equations solved at once (the matrix form), an independent
    check of :func:`truss_analysis`.

    Parameters
    ----------
    truss : Truss
        The truss.

    Returns
    -------
    numpy.ndarray
        (m + r,) member forces then reaction components (N).

    Raises
    ------
    crankdyn.errors.InputError
        A geometrically unstable truss.
    """
    sol = _rank_solve(truss.equilibrium_matrix(), -truss.load_vector)
    if sol is None:
        raise InputError("the truss is geometrically unstable", file=truss.source, key="members")
    return sol
