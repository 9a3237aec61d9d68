"""Scene computations for dimensioned mechanisms: ``motion`` and ``closed form``.

``[linkage]`` is a linkage as :meth:`synth.motion.Linkage.from_dict` reads it (chain, frame,
inputs, points, slides, meshes, tracers); ``[sweep]`` optionally sets the steps.  ``motion``
sweeps it and finds its range: crank or rocker and limits, Grashof's class, the worst transmission
angle, and the *rigidity error* — how far any two pins of one link drift from their distance in the
pose, over every step (a loop that does not close shows here).  ``closed form`` checks the
solver against the textbook's formulas, written here independently of :mod:`synth.motion`:

``dyads``
    every joint rebuilt step by step from circle–circle intersections (RRR dyads) and rigid
    transfers, driven by the solver's angle of one crank (``driver``, default the input); for a
    four-bar also the residual of Freudenstein's equation.  Driven by another crank than the input,
    it checks a class III group (a triad) against the dyads of another inversion of its chain.
``slider-crank``
    the slider's pin on its line (circle–line intersection); stroke and quick-return ratio
    measured on the solver's own positions (each dead centre refined between steps, :mod:`mechsynth._slider_stroke`).
``slotted-lever``
    the crank-and-slotted-lever (an inverted slider-crank): the lever's angle and the slide; the
    lever's swing and the slide's extremes measured on the solver.
``willis``
    a planetary train: each gear's rotation against Willis' equations from its tooth numbers.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from pydantic import StrictStr

from mechbase import Row
from mechbase.schema import Table

from .._slider_stroke import dead_centres, slider_stroke
from .registry import ComputeKind, Expectation, Family, Run, SceneTable
from .results import SceneError
from .types import Count, Flag, Number, Numbers, NumberTable, Text

__all__ = ["Sweep", "ClosedForm", "MotionSummary", "DyadCheck", "SliderCrankCheck", "SlottedLeverCheck",
           "WillisCheck"]

# ``balance linkage``: the linkage's counterweights (balance.LinkageProblem, moved by synth.motion), from
# [linkage] and [linkage_balance] (masses per link or a density, the options of ``mechsynth balance linkage``)


class Sweep(Table):
    """The ``[sweep]`` table: how many input values the sweep visits."""

    steps: Count = 360


class ClosedForm(Table):
    """The ``[closed_form]`` table: which textbook formula checks the solver."""

    kind: Text
    driver: StrictStr | None = None
    teeth: NumberTable | None = None


_CLOSED_FORMS = ("dyads", "slider-crank", "slotted-lever", "willis")


def _read_linkage(raw, path: str, compute) -> object:
    from synth import MotionError
    from synth.motion import Linkage

    try:
        return Linkage.from_dict(dict(raw))
    except MotionError as exc:
        raise SceneError(f"{path}: [linkage] {exc}.") from None


def _read_closed_form(raw, path: str, compute) -> ClosedForm:
    table = ClosedForm.read(raw, source=path, where="[closed_form]", error=SceneError)
    if table.kind not in _CLOSED_FORMS:
        raise SceneError(f"{path}: [closed_form] kind must be one of {', '.join(_CLOSED_FORMS)}, not {table.kind!r}.")
    if table.kind == "willis" and not table.teeth:
        raise SceneError(f"{path}: [closed_form] kind 'willis' needs teeth = {{ LINK = z, … }} for every gear.")
    return table


FAMILY = Family("motion")  # its tables and computations, registered by mechsynth.scene

FAMILY.table(SceneTable("linkage", _read_linkage, "the linkage: chain, frame, inputs, points (slides, meshes, tracers)"))
FAMILY.table(SceneTable.typed("sweep", Sweep, "the number of steps"))
FAMILY.table(SceneTable("closed_form", _read_closed_form, "the formula that checks the solver (kind = …)"))


def _read_linkage_balance(raw, path: str, compute):
    from balance import BalanceError, linkage_table

    try:
        table = linkage_table({"linkage_balance": raw}, path)
    except BalanceError as exc:
        raise SceneError(str(exc)) from None
    if table.file is not None:
        raise SceneError(f"{path}: [linkage_balance] 'file' has no place in a scene: its linkage is the [linkage] table.")
    return table


FAMILY.table(SceneTable("linkage_balance", _read_linkage_balance,
                        "the links' masses (links = [{link, mass, centre}] or density), the counterweights they carry "
                        "(counterweights = [{link, mass, at}]) and the options of those to add"))


# --------------------------------------------------------------------------- motion
def _steps(run: Run) -> int:
    table = run.scene.tables.get("sweep")
    return table.steps if table is not None else 360


def _rigidity_error(linkage, joints: np.ndarray) -> float:
    """The largest change, over the steps, of the distance between two revolute joints of one link."""
    from synth import JointKind

    worst = 0.0
    for link in range(linkage.chain.links):
        pins = [k for k in linkage.joints_of(link) if linkage.kind(k) == JointKind.REVOLUTE]
        for i, a in enumerate(pins):
            for b in pins[i + 1:]:
                pose = math.dist(linkage.points[a], linkage.points[b])
                now = np.hypot(*(joints[:, a] - joints[:, b]).T)
                worst = max(worst, float(np.nanmax(np.abs(now - pose))))
    return worst


@dataclass(frozen=True)
class MotionSummary(Row):
    """``motion``: crank or rocker, the input's limits (degrees for a revolute input), Grashof class,
    dead positions, worst transmission angle (degrees), rigidity error and the sweep's extent."""

    full_rotation: bool
    input_limits: tuple[float, float] | None
    grashof: str | None
    dead_positions: int
    min_transmission_angle: float | None
    rigidity_error: float
    steps: int
    stopped: bool
    extent: dict


@dataclass(frozen=True)
class DyadCheck(Row):
    """``closed form`` by dyads: the joints rebuilt dyad by dyad against the sweep, and Freudenstein's
    residual for a four-bar of revolute joints."""

    closed_form_error: float
    freudenstein_residual: float | None = None
    row_keys = ("closed_form_error", "freudenstein_residual?")


@dataclass(frozen=True)
class SliderCrankCheck(Row):
    """``closed form`` of a slider-crank: stroke and quick-return ratio, measured and by formula."""

    closed_form_error: float
    stroke: float
    stroke_formula: float
    quick_return_ratio: float
    quick_return_formula: float
    crank: float
    rod: float
    offset: float


@dataclass(frozen=True)
class SlottedLeverCheck(Row):
    """``closed form`` of a slotted lever: its swing, measured and by formula, and the slide's range."""

    closed_form_error: float
    lever_swing: float
    lever_swing_formula: float
    slide_range: tuple[float, float]
    crank: float
    centres: float
    offset: float


@dataclass(frozen=True)
class WillisCheck(Row):
    """``closed form`` of a planetary train: speed ratios measured against Willis's."""

    closed_form_error: float
    speed_ratios: dict
    willis: dict


def _motion(run: Run) -> MotionSummary:
    from synth.motion import motion_range, sweep
    from synth import JointKind

    linkage = run.scene.tables["linkage"]
    motion = run.shared("motion", lambda: sweep(linkage, steps=_steps(run), velocities=True))
    reach = motion_range(linkage)
    revolute = linkage.kind(linkage.inputs[0]) == JointKind.REVOLUTE
    worst = min([min(t["min"], math.pi - t["max"]) for t in motion.transmission.values()], default=None)
    return MotionSummary(
        reach.full_rotation, tuple(math.degrees(v) if revolute else v for v in reach.limits) if reach.limits else None,
        reach.grashof, len(reach.dead_positions), None if worst is None else math.degrees(worst),
        _rigidity_error(linkage, motion.joints), motion.steps, motion.stopped is not None,
        {n: list(e) for n, e in motion.extent().items()})


# --------------------------------------------------------------------------- closed forms
def _rotate(v: np.ndarray, theta: np.ndarray) -> np.ndarray:
    """Vectors ``v`` (2,) or (S, 2) turned by ``theta`` (S,)."""
    c, s = np.cos(theta), np.sin(theta)
    v = np.broadcast_to(v, (len(theta), 2))
    return np.stack([c * v[:, 0] - s * v[:, 1], s * v[:, 0] + c * v[:, 1]], axis=-1)


def _angle(v: np.ndarray) -> np.ndarray:
    return np.arctan2(v[..., 1], v[..., 0])


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _circles(p: np.ndarray, r: float, q: np.ndarray, s: float, side: float) -> np.ndarray:
    """The intersection of the circles (p, r) and (q, s) on the ``side`` (±1) of the line p → q."""
    d = q - p
    e = np.hypot(d[:, 0], d[:, 1])
    x = (r * r - s * s + e * e) / (2 * e)
    h = np.sqrt(np.maximum(r * r - x * x, 0.0))
    u = d / e[:, None]
    n = np.stack([-u[:, 1], u[:, 0]], axis=-1)
    return p + x[:, None] * u + side * h[:, None] * n


def _by_dyads(linkage, motion, driver: int) -> np.ndarray:
    """Every joint at every step, rebuilt from the frame, the driver's angle (read from the solver)
    and RRR dyads; revolute joints only."""
    chain, pose = linkage.chain, linkage.points
    steps = motion.steps
    frame = linkage.frame
    link = next(x for x in chain.joints[driver] if x != frame)
    known: dict[int, np.ndarray] = {k: np.broadcast_to(pose[k], (steps, 2)) for k in linkage.joints_of(frame)}
    turned: dict[int, np.ndarray] = {frame: np.zeros(steps), link: motion.angles[:, link]}
    while len(known) < len(chain.joints):
        progress = False
        for x, theta in list(turned.items()):  # a link whose angle is known carries all its joints
            a = next((k for k in linkage.joints_of(x) if k in known), None)
            for k in linkage.joints_of(x):
                if k not in known and a is not None:
                    known[k] = known[a] + _rotate(pose[k] - pose[a], theta)
                    progress = True
        for x in range(chain.links):  # two known joints give a link's angle
            on = [k for k in linkage.joints_of(x) if k in known]
            if x not in turned and len(on) >= 2:
                a, b = on[:2]
                turned[x] = _angle(known[b] - known[a]) - math.atan2(*(pose[b] - pose[a])[::-1])
                progress = True
        for k, joint in enumerate(chain.joints):  # an RRR dyad: joint k of links x, y, each with one known pin
            if k in known or len(joint) != 2:
                continue
            x, y = joint
            px = [m for m in linkage.joints_of(x) if m in known]
            py = [m for m in linkage.joints_of(y) if m in known]
            if len(px) == 1 and len(py) == 1 and px != py:
                a, b = px[0], py[0]
                side = float(np.sign(_cross(pose[b] - pose[a], pose[k] - pose[a])))
                known[k] = _circles(known[a], math.dist(pose[a], pose[k]), known[b], math.dist(pose[b], pose[k]), side)
                progress = True
        if not progress:
            raise SceneError("the closed form 'dyads' cannot rebuild this mechanism from RRR dyads driven by joint "
                             f"{chain.joints[driver]}")
    return np.stack([known[k] for k in range(len(chain.joints))], axis=1)


def _freudenstein(linkage, motion) -> float | None:
    """The residual of Freudenstein's equation K1 cos θ4 − K2 cos θ2 + K3 = cos(θ2 − θ4) over the
    sweep, angles from the ground line; None unless the linkage is a four-bar of revolute joints."""
    from synth import JointKind

    chain = linkage.chain
    if chain.links != 4 or len(chain.joints) != 4 or any(linkage.kind(k) != JointKind.REVOLUTE for k in range(4)):
        return None
    frame = linkage.frame
    o2 = linkage.inputs[0]
    crank = next(x for x in chain.joints[o2] if x != frame)
    o4 = next(k for k in linkage.joints_of(frame) if k != o2)
    rocker = next(x for x in chain.joints[o4] if x != frame)
    a_pin = next(k for k in linkage.joints_of(crank) if k != o2)
    b_pin = next(k for k in linkage.joints_of(rocker) if k != o4)
    p, j = linkage.points, motion.joints
    a, b = math.dist(p[o2], p[a_pin]), math.dist(p[a_pin], p[b_pin])
    c, d = math.dist(p[o4], p[b_pin]), math.dist(p[o2], p[o4])
    ground = math.atan2(*(p[o4] - p[o2])[::-1])
    t2 = _angle(j[:, a_pin] - p[o2]) - ground
    t4 = _angle(j[:, b_pin] - p[o4]) - ground
    k1, k2, k3 = d / a, d / c, (a * a - b * b + c * c + d * d) / (2 * a * c)
    return float(np.nanmax(np.abs(k1 * np.cos(t4) - k2 * np.cos(t2) + k3 - np.cos(t2 - t4))))


def _slider_crank(linkage, motion) -> SliderCrankCheck:
    """Roles: the input crank O–A, the rod A–B, the slider's pin B on the line along the slide of the
    slider–frame prismatic pair (through B as posed)."""
    chain, p, j = linkage.chain, linkage.points, motion.joints
    o = linkage.inputs[0]
    crank = linkage.input_link(0)
    a_pin = next(k for k in linkage.joints_of(crank) if k != o)
    rod = next(x for x in chain.joints[a_pin] if x != crank)
    b_pin = next(k for k in linkage.joints_of(rod) if k != a_pin)
    guide = next(k for k in linkage.slides)
    u = np.array(linkage.slides[guide])
    n = np.array([-u[1], u[0]])
    r, l = math.dist(p[o], p[a_pin]), math.dist(p[a_pin], p[b_pin])
    e = abs(float((p[o] - p[b_pin]) @ n))
    a_cf = p[o] + _rotate(p[a_pin] - p[o], motion.inputs[:, 0] - linkage.pose_inputs[0])
    w = a_cf - p[b_pin]
    side = -1.0 if float((p[a_pin] - p[b_pin]) @ u) > 0 else 1.0
    s = w @ u + side * np.sqrt(l * l - (w @ n) ** 2)
    b_cf = p[b_pin] + s[:, None] * u
    error = max(float(np.nanmax(np.hypot(*(j[:, a_pin] - a_cf).T))), float(np.nanmax(np.hypot(*(j[:, b_pin] - b_cf).T))))

    measured = slider_stroke(linkage, motion, b_pin, u)
    stroke = math.sqrt((l + r) ** 2 - e * e) - math.sqrt((l - r) ** 2 - e * e)
    delta = math.asin(e / (l - r)) - math.asin(e / (l + r))
    return SliderCrankCheck(error, measured.length, stroke, measured.quick_return_ratio,
                            (math.pi + delta) / (math.pi - delta), r, l, e)


def _slotted_lever(linkage, motion) -> SlottedLeverCheck:
    """Roles: the input crank O–B, the block pinned at B sliding on the lever, the lever pivoted at C.
    The lever's angle ψ solves (B − C)·n(ψ) = e, with e the pin's distance from the parallel to the
    slide through C in the pose; the slide is (B − C)·u(ψ)."""
    from synth import JointKind

    chain, p, j = linkage.chain, linkage.points, motion.joints
    o = linkage.inputs[0]
    crank = linkage.input_link(0)
    b_pin = next(k for k in linkage.joints_of(crank) if k != o)
    block = next(x for x in chain.joints[b_pin] if x != crank)
    pair = next(k for k in linkage.slides)
    lever = next(x for x in chain.joints[pair] if x != block)
    c = next(k for k in linkage.joints_of(lever)
             if linkage.kind(k) == JointKind.REVOLUTE and linkage.frame in chain.joints[k])
    u0 = np.array(linkage.slides[pair])
    n0 = np.array([-u0[1], u0[0]])
    e = float((p[b_pin] - p[c]) @ n0)
    b_cf = p[o] + _rotate(p[b_pin] - p[o], motion.inputs[:, 0] - linkage.pose_inputs[0])
    w = b_cf - p[c]
    rho = np.hypot(w[:, 0], w[:, 1])
    # (B − C)·n(ψ) = ρ cos(β − ψ − ν) = e with β the angle of B − C and ν that of n0
    beta, nu = _angle(w), math.atan2(n0[1], n0[0])
    side = math.copysign(1.0, float(_cross(n0, p[b_pin] - p[c])))
    psi = beta - nu - side * np.arccos(np.clip(e / rho, -1, 1))
    psi = (psi - psi[0] + math.pi) % (2 * math.pi) - math.pi + psi[0]
    lever_angle = motion.angles[:, lever]
    error = float(np.nanmax(np.abs((lever_angle - psi + math.pi) % (2 * math.pi) - math.pi)))
    error = max(error, float(np.nanmax(np.hypot(*(j[:, b_pin] - b_cf).T))))

    def slide(m):
        u = _rotate(u0, m.angles[:, lever])
        return np.einsum("ij,ij->i", m.joints[:, b_pin] - p[c], u)

    def turned(m):
        return m.angles[:, lever]

    (_, psi_hi), (_, psi_lo) = dead_centres(linkage, motion, turned)
    (_, s_hi), (_, s_lo) = dead_centres(linkage, motion, slide)
    r, d = math.dist(p[o], p[b_pin]), math.dist(p[o], p[c])
    return SlottedLeverCheck(error, math.degrees(psi_hi - psi_lo),
                             math.degrees(math.acos((e - r) / d) - math.acos((e + r) / d)), (s_lo, s_hi), r, d, abs(e))


def _willis(linkage, motion, teeth: dict) -> WillisCheck:
    """Each gear's speed relative to the input (the carrier), from Willis' equation of each mesh
    z_a(ω_a − ω_t) = ∓ z_b(ω_b − ω_t) (− external, + internal: the ring's radius is written negative
    in the pose, so the sign follows from the pitch point lying beyond or between the axes)."""
    from synth import JointKind

    chain = linkage.chain
    carrier = linkage.input_link(0)
    z = {int(k): float(v) for k, v in teeth.items()}
    speed = {linkage.frame: 0.0, carrier: 1.0}
    while True:
        grown = False
        for k in range(len(chain.joints)):
            if linkage.kind(k) != JointKind.MESH:
                continue
            a, b = chain.joints[k]
            t = linkage.carrier(k)
            if t not in speed or (a in speed) == (b in speed):
                continue
            if a not in z or b not in z:
                raise SceneError(f"[closed_form] teeth needs the tooth numbers of links {a} and {b}")
            pa = linkage.points[k] - linkage.points[linkage.axis(a, t)]
            pb = linkage.points[k] - linkage.points[linkage.axis(b, t)]
            internal = float(pa @ pb) > 0  # the pitch point beyond both axes: a ring and its planet
            sign = 1.0 if internal else -1.0
            if a in speed:
                speed[b] = speed[t] + sign * z[a] / z[b] * (speed[a] - speed[t])
            else:
                speed[a] = speed[t] + sign * z[b] / z[a] * (speed[b] - speed[t])
            grown = True
        if not grown:
            break
    phi = motion.inputs[:, 0] - linkage.pose_inputs[0]
    error = max(float(np.nanmax(np.abs(motion.angles[:, x] - w * phi))) for x, w in speed.items())
    measured = {str(x): float((motion.angles[-1, x] - motion.angles[0, x]) / (phi[-1] - phi[0])) for x in speed}
    return WillisCheck(error, measured, {str(x): w for x, w in speed.items()})


def _closed_form(run: Run) -> Row:
    from synth.motion import sweep

    linkage = run.scene.tables["linkage"]
    table = run.scene.tables["closed_form"]
    motion = run.shared("motion", lambda: sweep(linkage, steps=_steps(run), velocities=True))
    if table.kind == "dyads":
        driver = linkage.inputs[0] if table.driver is None else linkage.chain.joint_index(table.driver, "driver")
        rebuilt = _by_dyads(linkage, motion, driver)
        return DyadCheck(float(np.nanmax(np.hypot(*(rebuilt - motion.joints).reshape(-1, 2).T))),
                         _freudenstein(linkage, motion))
    if table.kind == "slider-crank":
        return _slider_crank(linkage, motion)
    if table.kind == "slotted-lever":
        return _slotted_lever(linkage, motion)
    return _willis(linkage, motion, table.teeth)


def _report_motion(r: dict) -> list[str]:
    limits = "turns fully" if r["full_rotation"] else f"rocks {r['input_limits']}"
    worst = "" if r["min_transmission_angle"] is None else f", worst transmission {r['min_transmission_angle']:.4g}°"
    return [f"input {limits}{', ' + r['grashof'] if r['grashof'] else ''}{worst}, "
            f"rigidity error {r['rigidity_error']:.2e} over {r['steps']} steps"]


def _report_closed_form(r: dict) -> list[str]:
    extra = "".join(f", {k} {v:.10g}" for k, v in r.items() if k != "closed_form_error" and isinstance(v, float))
    return [f"closed form error {r['closed_form_error']:.2e}{extra}"]


FAMILY.kind(ComputeKind(
    "motion", "sweep a linkage: crank or rocker, limits, Grashof, worst transmission angle, rigidity error", "linkage",
    _motion, reads=("sweep",),
    expect={"full_rotation": Expectation(Flag), "input_limits": Expectation(Numbers), "grashof": Expectation(Text),
            "min_transmission_angle": Expectation(Number), "rigidity_error": Expectation(Number, below=True),
            "dead_positions": Expectation(Number)},
    report=_report_motion))
def _balance_linkage(run: Run):
    from mechbase.errors import ProjectError

    from .._linkage_balance import OPTIONS, linkage_problem

    table = run.scene.tables["linkage_balance"]
    try:
        return linkage_problem(run.scene.tables["linkage"], {k: getattr(table, k) for k in OPTIONS}, table.links,
                               run.scene.name, run.scene.path, table.counterweights).solve()
    except ProjectError as exc:  # the balance's or the motion layer's one sentence
        raise SceneError(f"{run.scene.path}: [linkage_balance] {str(exc).rstrip('.')}.") from None


def _report_balance(r: dict) -> list[str]:
    weights = ", ".join(f"link {c['link']} {c['mass']:.6g} kg at {c['distance']:.6g} m from {c['joint']}"
                        for c in r["counterweights"] if c["mass"] > 0)
    state = "full balance" if r["full_balance"] else f"{100 * r['residual_share']:.3g}% of the excursion left"
    carried = ", ".join(f"link {b['link']} {b['mass']:.6g} kg" for b in r["carried"])
    return [(f"carried: {carried}; " if carried else "") + f"counterweights: {weights or 'none'}; {state}"]


FAMILY.kind(ComputeKind(
    "balance linkage", "counterweights that make a linkage's first moment of mass constant (shaking force, gravity)",
    "linkage_balance", _balance_linkage, reads=("linkage",),
    expect={"full_balance": Expectation(Flag), "residual_share": Expectation(Number, below=True),
            "added_mass": Expectation(Number),
            "shaking_force_after": Expectation(Number, ("after", "shaking_force"), below=True)},
    report=_report_balance))
FAMILY.kind(ComputeKind(
    "closed form", "the solver against a textbook formula (dyads, slider-crank, slotted-lever, willis)", "closed_form",
    _closed_form, reads=("linkage", "sweep"),
    expect={"closed_form_error": Expectation(Number, below=True),
            "freudenstein_residual": Expectation(Number, below=True),
            "stroke": Expectation(Number), "quick_return_ratio": Expectation(Number),
            "lever_swing": Expectation(Number), "slide_range": Expectation(Numbers),
            "speed_ratios": Expectation(NumberTable)},
    report=_report_closed_form))
