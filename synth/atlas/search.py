"""Type and dimensional synthesis over an atlas: which mechanism, with which dimensions, traces a
path — retrieval from the atlas's curve index, then the polish of :func:`synth.dimension.synthesize`.

1. The target's points are reduced to Fourier coefficients t_n, n = −h … h, as the index's curves are
   (:mod:`synth.atlas.curves`): in its input values when it has a timing (only their differences
   count), in the arc length of the closed polygon through its points when it has none.
2. Every indexed curve is aligned to it: t_n ≈ λ·u_n·e^{inτ}, u the curve's coefficients or those of
   its mirror image (and, without timing, of the curve run backwards), λ = scale·e^{iα} and τ the
   start point or input offset.  For each τ the best λ is a projection, so the shape's misfit
   ‖t − λ u e^{inτ}‖ / ‖t‖ (n ≠ 0: translation left out) depends on τ alone, and |Σ ū_n t_n e^{−inτ}|
   is a trigonometric polynomial in τ, evaluated by one FFT on 512 shifts and refined by a scalar search.
3. The best few samples of each topology (chain, frame, input; 3 per drawing of the index) are turned
   into start linkages in the target's frame (mirrored, turned, scaled, moved, posed at the first target
   point) and polished by :func:`synth.dimension.synthesize` within half the topology's share of the time
   budget, each for an equal slice of it, the best then going on; a topology
   none of whose polishes meets the target exactly spends the rest in synthesize's global stage
   (differential evolution seeded from its best polished linkage and samples).  The answer is the best
   mechanism of each topology, errors re-checked by the motion layer.

Retrieval can miss: a topology whose samples are all far from the target's shape (the samples are a
few hundred random poses, not every dimension), curves of rockers (only cranks are indexed), of
mechanisms moved by Newton's method unless the index holds them, of prismatic chains unless the index
holds them, of geared chains, and open paths (the descriptors are of closed curves).
"""

from __future__ import annotations

import json
import math
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from scipy.optimize import minimize_scalar

from ..errors import BadTarget, InvalidOption, SynthesisError, option
from ..structure.chain import Chain, Mechanism
from .curves import HARMONICS, _info, harmonics, slides_of, unblob, untimed_parameter
from .database import open_atlas

__all__ = ["Candidate", "AtlasMatch", "AtlasSearchResult", "descriptor_of", "retrieve", "sampled_starts",
           "search_atlas"]

#: shifts τ on which the alignment is evaluated before it is refined
SHIFTS = 512
#: the largest gap between a timed target's inputs (around the turn) the index can serve
MAX_INPUT_GAP = math.pi / 4
#: a target without timing is a closed curve when its ends are at most this many median spacings apart
CLOSING = 3.0


@dataclass(frozen=True)
class Candidate:
    """An indexed curve aligned to the target: its row, topology, misfit and the alignment."""

    row: int
    chain: int
    frame: int
    input_link: int
    input_joint: int
    tracer_link: int
    links: int
    misfit: float
    mirror: bool
    reverse: bool
    shift: float
    scale: complex
    offset: complex

    @property
    def topology(self) -> tuple[int, int, int]:
        return self.chain, self.frame, self.input_link


@dataclass
class AtlasMatch:
    """The best mechanism found for one topology: the polished result and where it started."""

    candidate: Candidate
    mechanism: Mechanism
    result: object  # synth.dimension.DimensionalResult
    tried: int
    seconds: float  # CPU seconds of this topology's polishes

    def row(self) -> dict:
        """One JSON-able row: the topology, its errors (target units and relative), where it started."""
        r = self.result
        return {"chain": self.mechanism.chain.compact(), "chain_id": _chain_id(self.mechanism.chain),
                "frame": self.mechanism.frame, "input": r.linkage.to_dict()["inputs"][0],
                "tracer_link": self.candidate.tracer_link,
                "links": self.candidate.links, "error_max": r.error_max, "error_rms": r.error_rms,
                "relative_max": r.relative_max, "relative_rms": r.relative_rms, "misfit": self.candidate.misfit,
                "met": r.met, "tried": self.tried, "seconds": round(self.seconds, 3)}


def _chain_id(chain: Chain) -> str:
    from .database import chain_id

    return chain_id(chain.certificate)


@dataclass
class AtlasSearchResult:
    """Best mechanism per topology, best first; what was searched and how long it took."""

    matches: list
    index_curves: int
    topologies: int
    seconds: float
    timed: bool
    #: what the search could not do, a :class:`synth.SynthesisError` each: ``str(note)`` is its sentence,
    #: naming an option as a keyword (``underdetermined=True``); the command line writes it as a flag
    notes: list = field(default_factory=list)
    #: CPU seconds of the topologies' polishes wherever they ran (``seconds`` is this process's alone: with
    #: ``workers`` > 1 or a scheduler the polishes ran elsewhere)
    polish_seconds: float = 0.0

    @property
    def best(self) -> AtlasMatch | None:
        return self.matches[0] if self.matches else None


# ------------------------------------------------------------------ the target's descriptor
def _path_only(target) -> None:
    """Refuse a target the index cannot serve by its kind: it holds coupler curves, not functions or poses."""
    kind = getattr(target, "kind", None)
    if kind != "path":
        raise BadTarget(f"the atlas search looks for paths (its index holds coupler curves), not "
                        f"{'a ' + kind if isinstance(kind, str) else type(target).__name__}: give the topology with "
                        f"{option('mechanism', 'CHAIN')} or {option('linkage', 'FILE')}")


def descriptor_of(target) -> tuple[np.ndarray, int, bool]:
    """The target's Fourier coefficients (c_-h … c_h), h, and whether they are timed.

    Raises
    ------
    BadTarget
        A target the index cannot serve: a function or a motion (the index holds coupler curves), a timing
        that leaves a gap of more than 45° around the turn, an open path without timing, too few points for
        three harmonics.

    Examples
    --------
    >>> from synth.dimension import PathTarget
    >>> t = np.linspace(0, 2 * np.pi, 40, endpoint=False)
    >>> c, h, timed = descriptor_of(PathTarget(np.c_[np.cos(t), np.sin(t)], inputs=t))
    >>> h, timed, round(float(abs(c[h + 1])), 9)
    (12, True, 1.0)
    """
    _path_only(target)
    points = np.asarray(target.points, dtype=float)
    z = points[:, 0] + 1j * points[:, 1]
    h = min(HARMONICS, (len(z) - 1) // 2)
    if h < 3:
        raise BadTarget(f"the atlas search needs at least 7 target points to describe a closed curve, not {len(z)}")
    if target.inputs is not None:
        values = np.sort(np.asarray(target.inputs, dtype=float))
        gaps = np.append(np.diff(values), 2 * math.pi - (values[-1] - values[0]))
        if gaps.max() > MAX_INPUT_GAP:
            raise BadTarget(f"the atlas's curves are indexed over a full turn of a crank: this timing leaves a gap of "
                            f"{math.degrees(gaps.max()):.0f}° (at most {math.degrees(MAX_INPUT_GAP):.0f}°) — search "
                            "a given topology instead (--mechanism)")
        return harmonics(z, np.asarray(target.inputs, dtype=float), h), h, True
    steps = np.abs(np.diff(z))
    closing = abs(z[-1] - z[0])
    if closing > CLOSING * float(np.median(steps)):
        raise BadTarget(f"the atlas's curves are closed and this path is open (its ends are {closing:.6g} apart, "
                        f"{closing / float(np.median(steps)):.1f} times its median spacing): search a given topology "
                        "instead (--mechanism), or give points all round a closed curve")
    return harmonics(z, untimed_parameter(z), h), h, False


# ------------------------------------------------------------------ alignment
def _variants(timed: bool):
    """(mirror, reverse) of the forms of a curve the target may be: timed, the mirror image only
    (a crank's timing fixes the direction); untimed, also either direction."""
    return ((False, False), (True, False)) if timed else ((False, False), (False, True), (True, False), (True, True))


def _form(s: np.ndarray, mirror: bool, reverse: bool) -> np.ndarray:
    """Coefficients (…, 2h+1) of the curve mirrored (z → z̄, the crank angle negated with it) and / or
    run backwards (t → −t)."""
    if mirror:
        s = np.conj(s[..., ::-1])  # z̄(t) = Σ c̄_n e^{−int}
        if not reverse:
            s = s[..., ::-1]  # the mirrored crank's own angle runs the other way: z̄(−ψ)
    elif reverse:
        s = s[..., ::-1]
    return s


def _misfits(t: np.ndarray, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Best misfit of each row of u (R, 2h+1) to t over the shift grid, and the best grid shift."""
    h = (t.shape[-1] - 1) // 2
    n = np.arange(-h, h + 1)
    keep = n != 0
    a = np.zeros((u.shape[0], SHIFTS), dtype=complex)
    a[:, n[keep] % SHIFTS] = np.conj(u[:, keep]) * t[keep]
    f = np.abs(np.fft.fft(a, axis=1))  # |F(τ_j)|, τ_j = 2πj/SHIFTS
    j = np.argmax(f, axis=1)
    tt = float(np.sum(np.abs(t[keep]) ** 2))
    uu = np.sum(np.abs(u[:, keep]) ** 2, axis=1)
    best = f[np.arange(len(j)), j]
    with np.errstate(invalid="ignore", divide="ignore"):
        misfit = np.sqrt(np.maximum(tt - best ** 2 / uu, 0.0) / tt)
    return np.where(uu > 0, misfit, np.inf), 2 * math.pi * j / SHIFTS


def _refine(t: np.ndarray, u: np.ndarray, shift: float) -> tuple[float, float, complex]:
    """The misfit, shift τ and λ of one curve's alignment, refined between grid shifts."""
    h = (t.shape[-1] - 1) // 2
    n = np.arange(-h, h + 1)
    keep = n != 0

    def misfit(tau):
        v = u[keep] * np.exp(1j * n[keep] * tau)
        lam = np.vdot(v, t[keep]) / np.vdot(v, v).real
        return float(np.linalg.norm(t[keep] - lam * v) / np.linalg.norm(t[keep])), lam

    step = 2 * math.pi / SHIFTS
    found = minimize_scalar(lambda x: misfit(x)[0], bounds=(shift - step, shift + step), method="bounded",
                            options={"xatol": 1e-10})
    tau = float(found.x) if found.fun <= misfit(shift)[0] else shift
    value, lam = misfit(tau)
    return value, tau, complex(lam)


# ------------------------------------------------------------------ retrieval
def _load(conn, links: tuple[int, int] | None, h: int):
    lo, hi = links or (0, 10 ** 9)
    rows = conn.execute(
        "SELECT s.id, s.chain, s.frame, s.input_link, s.input_joint, s.tracer_link, c.links, s.timed, s.untimed "
        "FROM curve_samples s JOIN chains c ON c.id = s.chain WHERE c.links BETWEEN ? AND ? ORDER BY s.id",
        (lo, hi)).fetchall()
    meta = np.array([r[:7] for r in rows], dtype=np.int64).reshape(-1, 7)
    cut = slice(HARMONICS - h, HARMONICS + h + 1)
    timed = np.array([unblob(r[7])[cut] for r in rows]).reshape(-1, 2 * h + 1)
    untimed = np.array([unblob(r[8])[cut] for r in rows]).reshape(-1, 2 * h + 1)
    return meta, timed, untimed


def retrieve(db: str | Path, target, *, links: tuple[int, int] | None = None, per_topology: int = 3,
             topologies: int | None = None) -> tuple[list[Candidate], int]:
    """The indexed curves nearest the target: the best ``per_topology`` of each topology, for the
    best-fitting topology of every link count and then the others by their best misfit (at most
    ``topologies`` in all, or one per link count if that is more); and the index's size.

    Brute force over the whole index with numpy (the alignment of every curve to the target is one
    FFT of 512 shifts per form of the curve).

    Raises
    ------
    NoCurveIndex
        The atlas has no curve index.
    BadTarget
        A target the index cannot serve (see :func:`descriptor_of`).
    """
    conn = open_atlas(db)
    try:
        _info(conn, db)  # an atlas without an index is refused first, whatever the target
        t, h, timed = descriptor_of(target)
        meta, timed_c, untimed_c = _load(conn, links, h)
    finally:
        conn.close()
    coefficients = timed_c if timed else untimed_c
    best, form, shift = _aligned_all(t, coefficients, timed)
    variants = _variants(timed)
    order = np.argsort(best, kind="stable")
    chosen: dict[tuple, list] = {}
    # the best topology of every link count first (the answer is error against complexity), then the rest
    simplest = {}
    for i in order:
        if math.isfinite(best[i]):
            simplest.setdefault(int(meta[i, 6]), tuple(int(v) for v in meta[i, 1:4]))
    for key in simplest.values():
        chosen[key] = []
    for i in order:
        if not math.isfinite(best[i]):
            break
        key = tuple(int(v) for v in meta[i, 1:4])
        if key not in chosen and (topologies is None or len(chosen) < max(topologies, len(simplest))):
            chosen[key] = []
        if key in chosen and len(chosen[key]) < per_topology:
            chosen[key].append(int(i))
    out = []
    for key, rows in chosen.items():
        for i in rows:
            out.append(_candidate(t, coefficients[i], variants[form[i]], float(shift[i]), meta[i]))
    return out, len(meta)


def _aligned_all(t: np.ndarray, coefficients: np.ndarray, timed: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Every curve's (row of ``coefficients``) best misfit to the target's t over its forms, the form
    (an index of :func:`_variants`) and the grid shift where it is reached."""
    best = np.full(len(coefficients), np.inf)
    form = np.zeros(len(coefficients), dtype=int)
    shift = np.zeros(len(coefficients))
    for start in range(0, len(coefficients), 4096):
        block = slice(start, start + 4096)
        for k, (mirror, reverse) in enumerate(_variants(timed)):
            m, s = _misfits(t, _form(coefficients[block], mirror, reverse))
            better = m < best[block]
            best[block] = np.where(better, m, best[block])
            form[block] = np.where(better, k, form[block])
            shift[block] = np.where(better, s, shift[block])
    return best, form, shift


def _candidate(t: np.ndarray, u: np.ndarray, variant: tuple[bool, bool], shift: float, meta) -> Candidate:
    """The curve u (its coefficients) in the form ``variant`` aligned to t, refined from the grid
    shift; ``meta`` its (row, chain, frame, input link, input joint, tracer link, links)."""
    h = (t.shape[-1] - 1) // 2
    mirror, reverse = variant
    u = _form(u, mirror, reverse)
    misfit, tau, lam = _refine(t, u, shift)
    row_id, chain, frame, input_link, input_joint, tracer, n = (int(v) for v in meta)
    return Candidate(row_id, chain, frame, input_link, input_joint, tracer, n, misfit, mirror, reverse, tau, lam,
                     complex(t[h] - lam * u[h]))


def sampled_starts(mechanism: Mechanism, tracer_link: int, target, seed: int = 0, *, samples: int = 100,
                   count: int | None = None, drawings: int = 1) -> list:
    """Start linkages for a path target from the mechanism's own curves sampled at random as an atlas
    index samples them (``samples`` crank poses near each of its ``drawings`` drawings, seeded): the
    ``count`` (default all) curves of the tracer link nearest the target's shape, each turned, scaled and posed on the target
    as the atlas search poses its candidates (:func:`start_linkage`), nearest first.  Empty where the
    index could not serve the target (not a path, an open path, a timing with a gap, a mechanism whose
    input does not turn fully, a tracer link that traces a circle).  The ``starts`` of
    :func:`synth.dimension.synthesize`.

    Examples
    --------
    >>> from synth.dimension import PathTarget
    >>> t = np.linspace(0, 2 * np.pi, 12, endpoint=False)
    >>> four_bar = Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0, 1)
    >>> starts = sampled_starts(four_bar, 2, PathTarget(np.c_[np.cos(t), 0.6 * np.sin(t)]), samples=20, count=3)
    >>> len(starts), starts[0].tracers["P"][0]
    (3, 2)
    """
    starts = []
    for candidate, points, at, slides in sampled_candidates(mechanism, tracer_link, target, seed, samples=samples,
                                                            count=count, drawings=drawings):
        try:
            starts.append(start_linkage(candidate, mechanism.chain, points, at, target, slides))
        except SynthesisError:
            continue
    return starts


def sampled_candidates(mechanism: Mechanism, tracer_link: int, target, seed: int = 0, *, samples: int = 100,
                       count: int | None = None, drawings: int = 1) -> list:
    """The samples of :func:`sampled_starts` before they are posed: (candidate, points, tracer point,
    slides) of each, nearest first, as the atlas search hands a topology's samples to its polish
    (``TopologyPolish.candidates``).

    Examples
    --------
    >>> from synth.dimension import PathTarget
    >>> t = np.linspace(0, 2 * np.pi, 12, endpoint=False)
    >>> four_bar = Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0, 1)
    >>> rows = sampled_candidates(four_bar, 2, PathTarget(np.c_[np.cos(t), 0.6 * np.sin(t)]), samples=20, count=3)
    >>> len(rows), rows[0][0].tracer_link, rows[0][0].misfit <= rows[1][0].misfit
    (3, 2, True)
    """
    from .curves import CurveUnit, IndexSettings, sample_unit

    if getattr(target, "kind", None) != "path":
        return []
    try:
        t, h, timed = descriptor_of(target)
    except BadTarget:
        return []
    unit = CurveUnit(0, json.dumps(mechanism.chain.to_dict()), mechanism.frame,
                     -1 if mechanism.input_link is None else mechanism.input_link,
                     IndexSettings(samples=samples, seed=seed, drawings=drawings))
    sampled = sample_unit(unit)
    rows = [row for row in sampled.rows if row[1] == tracer_link]
    if not rows:
        return []
    cut = slice(HARMONICS - h, HARMONICS + h + 1)
    coefficients = np.array([unblob(row[5 if not timed else 4])[cut] for row in rows])
    best, form, shift = _aligned_all(t, coefficients, timed)
    variants = _variants(timed)
    out = []
    for i in np.argsort(best, kind="stable")[:count or len(rows)]:
        if not math.isfinite(best[i]):
            break
        meta = (i, 0, mechanism.frame, unit.input_link, sampled.input_joint, tracer_link, mechanism.chain.links)
        out.append((_candidate(t, coefficients[i], variants[form[i]], float(shift[i]), meta),
                    json.loads(rows[i][2]), json.loads(rows[i][3]), slides_of(rows[i][6])))
    return out


# ------------------------------------------------------------------ from a sample to a start linkage
def start_linkage(candidate: Candidate, chain: Chain, points: np.ndarray, tracer_at, target, slides=None):
    """The candidate's sample as a linkage in the target's frame, posed at the first target point:
    mirrored if its mirror image fits, turned and scaled by λ, moved so its curve's centre is the
    target's, its input set where its tracer point meets the target's first point (timed: the
    input the alignment gives; untimed: the nearest point of its curve).  Its tracer point is "P";
    its sliding directions (``slides``, by joint index) are mirrored and turned with it.
    """
    from ..motion import Linkage, assemble, sweep

    flip = np.array([1.0, -1.0]) if candidate.mirror else np.ones(2)
    pts = np.asarray(points, dtype=float) * flip
    at = np.asarray(tracer_at, dtype=float) * flip
    lam, delta = candidate.scale, candidate.offset

    def moved(p):
        z = lam * (p[..., 0] + 1j * p[..., 1]) + delta
        return np.stack((z.real, z.imag), axis=-1)

    turn = lam / abs(lam)
    lines = {}
    for k, (ux, uy) in (slides or {}).items():
        u = turn * complex(ux * flip[0], uy * flip[1])
        lines[k] = (u.real, u.imag)
    mechanism = Mechanism(chain, candidate.frame, None if candidate.input_link < 0 else candidate.input_link)
    linkage = Linkage(mechanism, (candidate.input_joint,), moved(pts), lines,
                      tracers={"P": (candidate.tracer_link, tuple(moved(at)))})
    first = np.asarray(target.points[0], dtype=float)
    if target.inputs is not None:
        value = float(target.inputs[0]) + candidate.shift + math.atan2(lam.imag, lam.real)
    else:
        motion = sweep(linkage, steps=721)
        k = int(np.argmin(np.hypot(*(motion.tracers["P"] - first).T)))
        value = float(motion.inputs[k, 0])
    return assemble(linkage, value)


# ------------------------------------------------------------------ polish, per topology
@dataclass(frozen=True)
class TopologyPolish:
    """One topology's candidates as a worker receives them (picklable): the task of
    :func:`polish_topology`, one a topology of the atlas search."""

    chain_json: str
    candidates: tuple  # (Candidate, points, tracer_at, slides), best misfit first
    target: object
    constraints: object
    budget: float
    seed: int
    underdetermined: bool = False


def _expand(task: TopologyPolish) -> list:
    return [task]


def polish_topology(task: TopologyPolish):
    """A topology's search within its share of the budget: its candidates polished in turn, each from
    its start linkage and for at most an equal slice of :data:`POLISH_SHARE` of the share, until one
    meets the target exactly; then the best goes on while the polishing share lasts and each polish
    halves its error (a polish that slides along a valley of near-equal curves, as an eight-bar's do,
    would otherwise spend the whole share on the first candidate); then, if none met the target exactly, the
    global stage of :func:`synth.dimension.synthesize` (differential evolution, its first population
    seeded from the best polished linkage and the samples) for the rest of the share.  Returns (best
    result or None, its candidate, candidates polished, why the last failed (a sentence whose options
    are marked as :func:`synth.errors.option` marks them), CPU seconds)."""
    from dataclasses import replace

    from ..dimension import synthesize

    chain = Chain.from_dict(json.loads(task.chain_json))
    clock = time.process_time()
    best, best_candidate, tried, why = None, None, 0, "its share of the time budget was spent before a polish began"
    centre = (np.min(task.target.points, axis=0) + np.max(task.target.points, axis=0)) / 2
    polishing = POLISH_SHARE * task.budget

    def widened(starts):  # the search box holds every start (a tighter box held every start at one false minimum)
        far = max(float(np.hypot(*(np.vstack((s.points, s.tracers["P"][1])) - centre).T).max()) for s in starts)
        return replace(task.constraints, reach=max(task.constraints.reach or 0.0, 3.0 * far / task.target.size))

    def polish(start, tracer_link, budget):  # None once the polishing share is spent
        left = min(budget, polishing - (time.process_time() - clock))
        if left <= 0:  # (a start's placing may take the last of it: a search of no budget said "the budget must be
            return None  # a positive number of seconds, not -0.0018" for every topology)
        return synthesize(start, task.target, tracer_link=tracer_link, constraints=widened([start]),
                          budget=left, seed=task.seed, underdetermined=task.underdetermined, polish_only=True)

    starts = []
    piece = polishing / max(len(task.candidates), 1)  # each candidate's first polish at most
    for candidate, points, at, slides in task.candidates:
        if time.process_time() - clock >= polishing:
            break
        tried += 1
        try:
            start = start_linkage(candidate, chain, points, at, task.target, slides)
            result = polish(start, candidate.tracer_link, piece)
        except SynthesisError as exc:
            why = exc.args[0]  # its options still marked: the note names them as the caller writes them
            continue
        if result is None:
            break
        starts.append((candidate.tracer_link, start))
        if best is None or (result.met, -result.error_rms) > (best.met, -best.error_rms):
            best, best_candidate = result, candidate
        if result.met and result.relative_max <= EXACT:
            break
    # the least squares stop at their slice or evaluation limit (long untimed problems): go on from the
    # best while the polishing share lasts and each polish at least halves its error
    while best is not None and best.relative_max > EXACT and time.process_time() - clock < polishing:
        try:
            again = polish(best.linkage, best_candidate.tracer_link, polishing)
        except SynthesisError:
            break
        if again is None or not again.error_rms < 0.5 * best.error_rms:
            break
        best = again
    # no sample lay in the target's basin (eight links: a few random poses of twenty dimensions): the global
    # stage, from the best polished linkage and the samples of the best one's tracer link
    left = task.budget - (time.process_time() - clock)
    if best is not None and best.relative_max > EXACT and left > 0:
        tracer = best_candidate.tracer_link
        seeds = [best.linkage] + [start for link, start in starts if link == tracer]
        try:
            found = synthesize(best.linkage.mechanism, task.target, tracer_link=tracer, constraints=widened(seeds),
                               budget=left, seed=task.seed, underdetermined=task.underdetermined,
                               starts=lambda *_: seeds)
        except SynthesisError:
            found = None
        if found is not None and (found.met, -found.error_rms) > (best.met, -best.error_rms) \
                and _rechecked(found, task.target) <= EXACT:  # (kept only if the motion layer moves it again)
            best = found
    return best, best_candidate, tried, why, time.process_time() - clock


#: the share of a topology's budget its samples' polishes may take before the global stage
POLISH_SHARE = 0.5
#: samples of a topology polished per drawing of the index (an index of K drawings: K times as many)
PER_DRAWING = 3
#: a polished mechanism meets the target exactly when its largest error is below this × the target's size
EXACT = 1e-9


def _rechecked(result, target) -> float:
    """The largest distance between the reported curve and the returned linkage moved by the motion
    layer to each reported input (:func:`synth.motion.assemble`), over the target's size; infinite
    where the branch of its pose does not reach one of the inputs."""
    from ..motion import assemble

    try:
        moved = np.array([assemble(result.linkage, float(v)).tracers["P"][1] for v in result.inputs])
    except SynthesisError:  # (CannotAssemble: a dead position between the pose and an input)
        return math.inf
    return float(np.hypot(*(moved - result.traced).T).max() / target.size)


def _refuse_underdetermined_without_use(tasks: list[TopologyPolish], target) -> None:
    """Refuse ``underdetermined`` when no topology the search polishes has fewer target equations than
    unknowns (a topology none of whose samples can be posed counts as one that might)."""
    from ..dimension import equations_and_unknowns

    unknowns = []
    for task in tasks:
        chain = Chain.from_dict(json.loads(task.chain_json))
        for candidate, points, at, slides in task.candidates:
            try:
                start = start_linkage(candidate, chain, points, at, target, slides)
                equations, count = equations_and_unknowns(start, target, tracer_link=candidate.tracer_link,
                                                          constraints=task.constraints)
            except SynthesisError:
                continue
            if equations < count:
                return
            unknowns.append(count)
            break
        else:
            return
    raise InvalidOption(f"{option('underdetermined')} allows fewer target equations than unknowns, and the "
                        f"target's {equations} equations are at least the unknowns of each topology this search "
                        f"polishes ({len(tasks)} topolog{'y' if len(tasks) == 1 else 'ies'}, at most "
                        f"{max(unknowns)} unknowns): drop it")


def search_atlas(db: str | Path, target, *, links: tuple[int, int] | None = None, top: int = 5,
                 per_topology: int | None = None, budget: float = 60.0, constraints=None, seed: int = 0,
                 underdetermined: bool = False, workers: int = 1, scheduler: str | None = None,
                 progress: bool = False, connect_timeout: float = 5.0) -> AtlasSearchResult:
    """Which mechanisms of the atlas trace the target path, and with which dimensions.

    Parameters
    ----------
    db : path
        An atlas with a curve index (``mechsynth atlas --db F --index-curves``).
    target : synth.dimension.PathTarget
        Points round a closed curve, with a timing over a full turn or without one.
    links : (int, int), optional
        Search only mechanisms with this many links.
    top : int
        Topologies (chain, frame, input) polished: those whose nearest samples fit best.
    per_topology : int, optional
        Samples of each topology polished at most (nearest first; default :data:`PER_DRAWING` for each
        drawing the index samples a mechanism around).
    budget : float
        CPU seconds of polishing and global search in all, shared equally by the topologies (a topology
        met exactly stops early).
    constraints : synth.dimension.Constraints, optional
        What the answer must also meet (the search box grows to hold each start).
    underdetermined : bool
        Polish topologies with more unknowns than the target gives equations (a six-bar through nine
        points: one of infinitely many exact answers), as :func:`synth.dimension.synthesize` does.
    workers, scheduler
        Topologies are polished on the project's executor: local processes or a Dask cluster.

    Returns
    -------
    AtlasSearchResult
        The best mechanism of each topology polished, ordered by met constraints, then error.

    Raises
    ------
    NoCurveIndex, BadTarget, InvalidOption

    Examples
    --------
    >>> import tempfile, os
    >>> from synth.atlas import parse_grid, run_grid
    >>> from synth.atlas.curves import index_curves, IndexSettings
    >>> from synth.dimension import PathTarget
    >>> db = os.path.join(tempfile.mkdtemp(), "a.sqlite")
    >>> _ = run_grid(parse_grid('dof = 1\\nlinks = 4'), db, workers=1)
    >>> _ = index_curves(db, settings=IndexSettings(samples=30), workers=1)
    >>> t = np.linspace(0, 2 * np.pi, 30, endpoint=False)
    >>> found = search_atlas(db, PathTarget(np.c_[np.cos(t), 0.6 * np.sin(t)]), budget=5)
    >>> found.best.candidate.links, found.best.result.relative_max < 0.05
    (4, True)
    """
    from ..dimension import Constraints
    from .curves import index_gap, index_info

    given = [("top", top), ("workers", workers)]
    for name, value in given + ([("per_topology", per_topology)] if per_topology is not None else []):
        if isinstance(value, bool) or not isinstance(value, int) or value < 1:
            raise InvalidOption(f"{name} must be a whole number ≥ 1, not {value!r}")
    if not (isinstance(budget, (int, float)) and math.isfinite(budget) and budget > 0):
        raise InvalidOption(f"the budget must be a positive number of seconds, not {budget!r}")
    _path_only(target)
    constraints = constraints or Constraints()
    clock = time.process_time()
    if per_topology is None:
        per_topology = PER_DRAWING * index_info(db)["settings"].get("drawings", 1)
    candidates, size = retrieve(db, target, links=links, per_topology=per_topology, topologies=top)
    conn = open_atlas(db)
    try:
        stored = {row[1] for row in conn.execute("PRAGMA table_info(curve_samples)")}
        slides_column = "slides" if "slides" in stored else "NULL"  # (an index built before sliders were indexed)
        tasks = []
        by_topology: dict[tuple, list] = {}
        for c in candidates:
            by_topology.setdefault(c.topology, []).append(c)
        for key, group in by_topology.items():
            chain_json = conn.execute("SELECT chain FROM chains WHERE id = ?", (key[0],)).fetchone()[0]
            rows = []
            for c in sorted(group, key=lambda c: c.misfit):
                points, at, slides = conn.execute(f"SELECT points, tracer, {slides_column} FROM curve_samples "
                                                  "WHERE id = ?", (c.row,)).fetchone()
                rows.append((c, json.loads(points), json.loads(at), slides_of(slides)))
            tasks.append(TopologyPolish(chain_json, tuple(rows), target, constraints, budget / max(len(by_topology), 1),
                                        seed, underdetermined))
    finally:
        conn.close()
    if underdetermined and tasks:
        _refuse_underdetermined_without_use(tasks, target)
    client = None
    if scheduler:
        from ..execution.scheduler import connect

        client = connect(scheduler, connect_timeout)
    matches, polish_seconds = [], 0.0
    gap = index_gap(db, links)
    notes = [SynthesisError(gap)] if gap else []
    bar = executor = None
    if progress and tasks:
        from ..execution.progress import Progress

        bar = Progress(len(tasks), "topologies", desc="polish")
    try:
        from ..execution.executor import Executor, run_plan

        executor = Executor(workers, client)
        for _, task, found in run_plan(tasks, _expand, polish_topology, executor=executor,
                                       inline_seconds=0 if workers > 1 else 0.25):
            if task is None:
                continue
            if bar is not None:
                bar.update()
            result, candidate, tried, why, spent = found
            polish_seconds += spent
            chain = Chain.from_dict(json.loads(task.chain_json))
            if result is None:
                from ..motion import joint_name

                first = task.candidates[0][0]
                notes.append(SynthesisError(f"{chain.compact()} (frame {first.frame}, input "
                                            f"{joint_name(chain, first.input_joint)}): no polish reached the "
                                            f"target ({why})"))
                continue
            gap = _rechecked(result, target)
            if gap > EXACT:
                notes.append(SynthesisError(
                    f"{chain.compact()}: the linkage moved again departs from the reported curve by "
                    f"{gap:.2g} of the target's size" if math.isfinite(gap) else
                    f"{chain.compact()}: the linkage cannot be moved again to every reported input"))
            matches.append(AtlasMatch(candidate, result.linkage.mechanism, result, tried, spent))
    finally:
        if bar is not None:
            bar.close()
        if executor is not None:
            executor.close()  # no worker outlives the search
        if client is not None:
            client.close()
    matches.sort(key=lambda m: (not m.result.met, m.result.error_rms, m.candidate.links))
    return AtlasSearchResult(matches, size, len(tasks), time.process_time() - clock, target.inputs is not None, notes,
                             polish_seconds)
