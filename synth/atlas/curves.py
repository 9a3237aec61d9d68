"""The curve index of an atlas: coupler curves of every 1-DOF planar mechanism, sampled and reduced
to normalised Fourier descriptors, stored in the atlas's SQLite file for the atlas-wide search.

A *unit* of the index is one mechanism of the atlas with its input (a chain, its frame, its input
link up to symmetry).  Its linkage is posed by its drawing (:func:`synth.motion_draw.linkage_from_layout`)
and, on request, by the drawings of ``drawings − 1`` more labellings of its chain picked at random (the
drawing of a chain depends on how its links are numbered, and a mechanism a designer dimensions near
one drawing traces curves the poses near another do not reach); a seeded random generator then moves
every joint by 5 … 35 % of the mechanism's size around each drawing, and a pose is kept only when its
input turns fully (a crank: the coupler curves are closed and periodic in the input).  On every moving link not jointed to the frame (a coupler, a *tracer link*) a tracer point is
put at random near the link's joints, and its curve is swept at :data:`STEPS` inputs over one turn.
Each curve is stored as two sets of Fourier coefficients c_n, n = −H … H (:data:`HARMONICS`):

* ``timed``: z(φ) = Σ c_n e^{inφ} in the absolute input angle φ — the curve with its timing;
* ``untimed``: the same series in t = 2π s / L, s the arc length from the pose's point and L the
  curve's length — the curve alone.

The coefficients themselves are stored (not only invariants), so the search can align a target
to each sample (rotation, scale, translation, start point or input offset, direction, mirror image)
and turn the sample into a start linkage in the target's frame (:mod:`synth.atlas.search`).
A unit commits in one transaction with its ``done`` row, so an interrupted build resumes where it
stopped; the index's settings (samples, harmonics, steps, seed) are kept in ``meta`` and a build
with other settings is refused (an index of one drawing per mechanism keeps the settings it always had).  Mechanisms moved by Newton's method (triads and higher groups,
about a second a sample) are left out unless asked for; chains with prismatic pairs (slider-cranks,
six-bars with sliders: the atlas's variants of a grid with ``prismatic``) are indexed on request, their
sliding lines turned at random with the joints and stored with each sample; geared chains are not indexed.

Example
-------
>>> import numpy as np
>>> t = np.linspace(0, 2 * np.pi, 64, endpoint=False)
>>> c = harmonics(np.exp(1j * t) + 0.5 * np.exp(-2j * t), t, 3)
>>> [round(float(abs(x)), 9) for x in c]   # c_-3 … c_3: c_-2 = 0.5, c_1 = 1
[0.0, 0.5, 0.0, 0.0, 1.0, 0.0, 0.0]
"""

from __future__ import annotations

import json
import math
import sqlite3
import time
import zlib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from mechbase import Row

from ..errors import InvalidOption, MotionError, SynthesisError
from ..structure.chain import Chain, Mechanism
from ..structure.joints import PRISMATIC
from .database import AtlasError, open_atlas, refuse_unwritable, transaction

__all__ = ["INDEX_VERSION", "HARMONICS", "STEPS", "IndexSettings", "IndexResult", "CurveUnit", "harmonics",
           "untimed_parameter", "periodic_harmonics", "tracer_links", "index_curves", "index_units", "sample_unit", "index_info", "index_gap", "NoCurveIndex"]

#: version of the curve index's tables (``meta.curve_index_version``)
INDEX_VERSION = 1
#: Fourier harmonics kept each side of the mean: c_-H … c_H
HARMONICS = 12
#: inputs at which each sampled curve is swept over one turn
STEPS = 256

_TABLES = """
CREATE TABLE IF NOT EXISTS curve_units (
    chain INTEGER NOT NULL REFERENCES chains, frame INTEGER NOT NULL, input_link INTEGER NOT NULL,
    input_joint INTEGER, status TEXT NOT NULL CHECK (status IN ('done', 'skipped')), note TEXT,
    samples INTEGER NOT NULL, tries INTEGER NOT NULL, seconds REAL NOT NULL,
    PRIMARY KEY (chain, frame, input_link)
) WITHOUT ROWID;
CREATE TABLE IF NOT EXISTS curve_samples (
    id INTEGER PRIMARY KEY, chain INTEGER NOT NULL REFERENCES chains, frame INTEGER NOT NULL,
    input_link INTEGER NOT NULL, input_joint INTEGER NOT NULL, sample INTEGER NOT NULL,
    tracer_link INTEGER NOT NULL, points TEXT NOT NULL, tracer TEXT NOT NULL,
    timed BLOB NOT NULL, untimed BLOB NOT NULL, slides TEXT,
    UNIQUE (chain, frame, input_link, sample, tracer_link)
);
"""


class NoCurveIndex(AtlasError):
    """The atlas has no curve index (or one of another version)."""


@dataclass(frozen=True)
class IndexSettings:
    """How an index is sampled: poses kept per mechanism, the seed, and whether triads are included.

    Parameters
    ----------
    samples : int
        Poses kept per mechanism and drawing (each gives one curve per tracer link).
    seed : int
        Seeds every mechanism's random poses (with the mechanism's identity).
    triads : bool
        Also index the mechanisms moved by Newton's method (about a second a sample).
    prismatic : (int, int)
        Index the atlas's chains with this many prismatic pairs (default (0, 0): revolute chains only;
        (0, 2): slider-cranks and six-bars with one or two sliders too).  Only mechanisms whose input
        is a revolute joint are sampled (a crank: a slide's curves are not closed).
    drawings : int
        Drawings each mechanism's poses are sampled around, ``samples`` poses each: the atlas's
        drawing of the chain and ``drawings − 1`` drawings of it numbered at random (seeded).

    Examples
    --------
    >>> IndexSettings(samples=20, drawings=10).to_meta()
    '{"drawings": 10, "harmonics": 12, "samples": 20, "seed": 0, "steps": 256, "triads": false}'
    """

    samples: int = 200
    seed: int = 0
    triads: bool = False
    prismatic: tuple[int, int] = (0, 0)
    drawings: int = 1

    def to_meta(self) -> str:
        meta = {"samples": self.samples, "seed": self.seed, "triads": self.triads, "harmonics": HARMONICS,
                "steps": STEPS}
        if tuple(self.prismatic) != (0, 0):  # (an index of revolute chains keeps the settings it always had)
            meta["prismatic"] = list(self.prismatic)
        if self.drawings != 1:  # (nor does an index of one drawing per mechanism)
            meta["drawings"] = self.drawings
        return json.dumps(meta, sort_keys=True)


@dataclass(frozen=True)
class CurveUnit:
    """One mechanism of the atlas to sample: its chain (atlas row and JSON), frame and input link."""

    chain: int
    chain_json: str
    frame: int
    input_link: int
    settings: IndexSettings


@dataclass
class _UnitRows:
    unit: CurveUnit
    input_joint: int | None
    status: str
    note: str | None
    rows: list = field(default_factory=list)
    tries: int = 0
    seconds: float = 0.0


@dataclass(frozen=True)
class IndexResult(Row):
    """What a build did: mechanisms in the index, how many this run sampled, curves stored, time."""

    units_total: int
    units_run: int
    units_skipped: int
    curves: int
    seconds: float
    executor: str

    row_keys = ("units_total", "units_run", "units_skipped", "curves", "seconds=seconds_rounded", "executor")

    @property
    def seconds_rounded(self) -> float:
        return round(self.seconds, 3)


# ------------------------------------------------------------------ descriptors
def harmonics(z: np.ndarray, t: np.ndarray, count: int) -> np.ndarray:
    """Fourier coefficients c_-count … c_count of a closed curve z(t) (complex) sampled at t (rad).

    A least-squares fit of the truncated series Σ c_n e^{int} to the samples: for equally spaced
    samples of one period it is the discrete Fourier transform; for unequal spacing (a target's
    points) it is the closest truncated series.

    Parameters
    ----------
    z : ndarray (N,) complex
    t : ndarray (N,)
        The parameter of each sample, one period being 2π.
    count : int
        Harmonics each side of the mean, at most (N − 1) // 2.

    Returns
    -------
    ndarray (2·count + 1,) complex, c_-count first.

    Examples
    --------
    >>> t = np.linspace(0, 2 * np.pi, 16, endpoint=False)
    >>> [round(float(abs(x)), 12) for x in harmonics(3 + np.exp(-1j * t), t, 2)]
    [0.0, 1.0, 3.0, 0.0, 0.0]
    """
    n = np.arange(-count, count + 1)
    basis = np.exp(1j * np.outer(t, n))
    return np.linalg.lstsq(basis, z, rcond=None)[0]


def periodic_harmonics(z: np.ndarray, count: int) -> np.ndarray:
    """The coefficients c_-count … c_count of z(t) sampled at t = 2πk/N, k = 0 … N − 1 (a discrete
    Fourier transform; the same as :func:`harmonics` for such samples, without a solve).

    >>> t = np.linspace(0, 2 * np.pi, 8, endpoint=False)
    >>> np.allclose(periodic_harmonics(np.exp(2j * t) - 1j, 2), harmonics(np.exp(2j * t) - 1j, t, 2))
    True
    """
    d = np.fft.fft(z) / len(z)
    return np.concatenate((d[len(z) - count:], d[:count + 1]))


def _by_arc_length(z: np.ndarray) -> np.ndarray:
    """The closed curve through the points z resampled at as many points equally spaced along it,
    starting at its first point (linear between the points)."""
    t = untimed_parameter(z)
    even = np.linspace(0, 2 * math.pi, len(z), endpoint=False)
    closed_t = np.append(t, 2 * math.pi)
    closed_z = np.append(z, z[0])
    return np.interp(even, closed_t, closed_z.real) + 1j * np.interp(even, closed_t, closed_z.imag)


def untimed_parameter(z: np.ndarray) -> np.ndarray:
    """The arc-length parameter t = 2π s / L of the points of a closed curve (the polygon through
    them, closed from the last back to the first), 0 at the first point.

    >>> untimed_parameter(np.array([0, 1, 1 + 1j, 1j])).tolist()
    [0.0, 1.5707963267948966, 3.141592653589793, 4.71238898038469]
    """
    seg = np.abs(np.diff(np.append(z, z[0])))
    s = np.concatenate(([0.0], np.cumsum(seg[:-1])))
    return 2 * math.pi * s / seg.sum()


def _blob(c: np.ndarray) -> bytes:
    return np.asarray(c, dtype=np.complex128).tobytes()


def unblob(data: bytes) -> np.ndarray:
    """Coefficients stored by the index (complex128)."""
    return np.frombuffer(data, dtype=np.complex128)


# ------------------------------------------------------------------ one mechanism
def tracer_links(mechanism: Mechanism) -> list[int]:
    """The moving links not jointed to the frame: the couplers, whose points trace coupler curves
    (a point of a link pivoted on the frame traces a circle).

    >>> tracer_links(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0))
    [2]
    """
    chain, frame = mechanism.chain, mechanism.frame
    touching = {link for j in chain.joints if frame in j for link in j}
    return [link for link in range(chain.links) if link not in touching]


def _unit_seed(unit: CurveUnit, certificate: str) -> np.random.Generator:
    key = zlib.crc32(f"{certificate}:{unit.frame}:{unit.input_link}".encode())
    return np.random.default_rng([unit.settings.seed, key])


def sample_unit(unit: CurveUnit) -> _UnitRows:
    """Sample one mechanism: ``settings.samples`` crank poses around each of its ``settings.drawings``
    drawings (:func:`drawings_of`), each pose with a tracer point on every tracer link, their curves and
    descriptors (the work of one unit; runs in a worker)."""
    from ..motion_draw import linkage_from_layout

    start = time.process_time()
    chain = Chain.from_dict(json.loads(unit.chain_json))
    mechanism = Mechanism(chain, unit.frame, None if unit.input_link < 0 else unit.input_link)
    links = tracer_links(mechanism)
    if not links:
        return _UnitRows(unit, None, "skipped", "no link carries a coupler curve (every moving link is jointed to "
                                                "the frame)", seconds=time.process_time() - start)
    if not unit.settings.triads:
        newton = _moved_by_newton(mechanism)
        if newton is not None:  # (known before a moving pose is searched for: that costs seconds with Newton)
            return _UnitRows(unit, newton, "skipped", _NEWTON_NOTE, seconds=time.process_time() - start)
    try:
        base = linkage_from_layout(mechanism)
    except MotionError as exc:
        return _UnitRows(unit, None, "skipped", f"no moving pose: {exc}", seconds=time.process_time() - start)
    joint = base.inputs[0]
    if base.kind(joint) == PRISMATIC:
        return _UnitRows(unit, joint, "skipped", "its input slides: only a crank's coupler curves are closed and "
                                                 "indexed", seconds=time.process_time() - start)
    if not unit.settings.triads and not _closed_form(base):
        return _UnitRows(unit, joint, "skipped", _NEWTON_NOTE, seconds=time.process_time() - start)
    rng = _unit_seed(unit, chain.certificate)
    out = _UnitRows(unit, joint, "done", None)
    groups = [[k for k, j in enumerate(chain.joints) if link in j] for link in links]
    # (the labellings drawn from a generator of their own: the atlas's drawing keeps its poses whatever the count)
    for drawn in drawings_of(base, unit.settings.drawings, rng.spawn(1)[0]):
        _sample_drawing(drawn, links, groups, unit.settings.samples, rng, out)
    out.seconds = time.process_time() - start
    if not out.rows:
        out.status, out.note = "skipped", (f"none of {out.tries} random poses near its drawing"
                                            f"{'s' * (unit.settings.drawings > 1)} turns its input fully")
    return out


def drawings_of(base, count: int, rng: np.random.Generator) -> list:
    """The linkage ``base`` (posed by the atlas's drawing of its mechanism) and up to ``count − 1``
    linkages of the same mechanism posed by the drawings of its chain with the links numbered at
    random: the centres the index samples poses around.

    The drawing of a chain (:func:`synth.draw.layout`) depends on how its links are numbered (which
    loop is drawn outside, how the embedding is shaped), so the same mechanism numbered otherwise is
    drawn with other proportions; each is posed as :func:`synth.motion_draw.linkage_from_layout`
    poses the atlas's (a moving pose near the drawing) and keeps ``base``'s joint numbers and input.
    A drawing is kept when its pose is a crank (the input of ``base`` turns fully: poses moved at
    random around a drawing that locks or rocks seldom turn) and is not one already kept (the same
    distances between its joints, to 1e-6 of its size: labellings related by a symmetry draw the same
    pose, turned or mirrored).  At most ``8·(count − 1)`` labellings are tried.

    Examples
    --------
    >>> from synth.motion_draw import linkage_from_layout
    >>> watt = Mechanism(Chain.parse("0-1 0-2 1-3 2-3 2-4 3-5 4-5"), 0, 1)
    >>> found = drawings_of(linkage_from_layout(watt), 3, np.random.default_rng(0))
    >>> len(found), all(d.inputs == found[0].inputs and d.points.shape == (7, 2) for d in found)
    (3, True)
    """
    from ..motion import Linkage, pose_branch
    from ..motion_draw import linkage_from_layout

    mechanism = base.mechanism
    found = [base]

    def shape(linkage) -> bytes:  # the joints' mutual distances: the pose up to a turn, a move or a mirror
        gaps = np.hypot(*(linkage.points[:, None] - linkage.points[None]).transpose(2, 0, 1))
        return np.round(gaps / base.scale, 6).tobytes()

    seen = {shape(base)}
    for _ in range(8 * (count - 1)):
        if len(found) == count:
            break
        order = [int(x) for x in rng.permutation(mechanism.chain.links)]  # link i is numbered order[i]
        renamed = Mechanism(mechanism.chain.relabel(order), order[mechanism.frame],
                            None if mechanism.input_link is None else order[mechanism.input_link])
        try:
            drawn = linkage_from_layout(renamed)  # (relabelling keeps the joints' order: its points are base's)
            posed = Linkage(mechanism, base.inputs, drawn.points * (base.scale / drawn.scale), drawn.slides)
            branch = pose_branch(posed)
        except SynthesisError:
            continue
        if math.isinf(branch.low) and math.isinf(branch.high) and shape(posed) not in seen:
            seen.add(shape(posed))
            found.append(posed)
    return found


def _sample_drawing(base, links: list, groups: list, samples: int, rng: np.random.Generator, out: _UnitRows) -> None:
    """``samples`` crank poses of ``base`` with its joints moved at random, the curves of a tracer point
    put at random on each of ``links`` (their joints ``groups``), appended to ``out.rows`` (at most 40
    tries a pose kept)."""
    from ..motion import Linkage, sweep

    size = base.scale
    kept = tries = 0
    while kept < samples and tries < 40 * samples:
        tries += 1
        out.tries += 1
        spread = rng.uniform(0.05, 0.35) * size
        points = base.points + rng.normal(size=base.points.shape) * spread
        slides = {k: _turned(u, rng.normal() * spread / size) for k, u in base.slides.items()}
        tracers = {}
        for link, ks in zip(links, groups):
            centre = points[ks].mean(axis=0)
            reach = max(float(np.hypot(*(points[ks] - centre).T).max()), 0.05 * size)
            tracers[f"T{link}"] = (link, tuple(centre + rng.normal(size=2) * 0.6 * reach))
        try:
            linkage = Linkage(base.mechanism, base.inputs, points, slides, tracers=tracers)
            motion = sweep(linkage, steps=STEPS + 1)  # a crank turns once from its pose; a rocker does not
        except SynthesisError:
            continue
        phi = motion.inputs[:, 0]
        if motion.stopped is not None or abs(phi[-1] - phi[0] - 2 * math.pi) > 1e-9 \
                or abs(phi[0] - linkage.pose_inputs[0]) > 1e-12:
            continue
        curves = []
        for link in links:
            xy = motion.tracers[f"T{link}"][:STEPS]
            z = xy[:, 0] + 1j * xy[:, 1]
            if not np.isfinite(z).all() or np.ptp(xy, axis=0).max() < 1e-3 * size:
                break
            curves.append((link, z))
        else:
            kept += 1
            for link, z in curves:
                timed = periodic_harmonics(z, HARMONICS) * np.exp(-1j * np.arange(-HARMONICS, HARMONICS + 1) * phi[0])
                untimed = periodic_harmonics(_by_arc_length(z), HARMONICS)
                at = tracers[f"T{link}"][1]
                out.rows.append((out.tries, link, json.dumps(np.round(points, 12).tolist()),
                                 json.dumps([round(float(at[0]), 12), round(float(at[1]), 12)]),
                                 _blob(timed), _blob(untimed), _slides_text(linkage)))


def _turned(u, angle: float) -> tuple[float, float]:
    """The direction u turned by ``angle`` (rad)."""
    c, s = math.cos(angle), math.sin(angle)
    return c * u[0] - s * u[1], s * u[0] + c * u[1]


def _slides_text(linkage) -> str | None:
    """A sample's sliding directions as JSON {joint index: [x, y]} (None for a revolute chain)."""
    if not linkage.slides:
        return None
    return json.dumps({str(k): [round(float(x), 15), round(float(y), 15)] for k, (x, y) in linkage.slides.items()})


def slides_of(text: str | None) -> dict:
    """The sliding directions a sample stored (:func:`_slides_text`), by joint index.

    >>> slides_of('{"3": [0.0, 1.0]}'), slides_of(None)
    ({3: (0.0, 1.0)}, {})
    """
    return {} if text is None else {int(k): (float(x), float(y)) for k, (x, y) in json.loads(text).items()}


_NEWTON_NOTE = "moved by Newton's method (a triad or higher group): index it with triads"


def _moved_by_newton(mechanism: Mechanism) -> int | None:
    """The input joint of a mechanism the motion layer moves by Newton's method (its groups after the
    input are not all dyads: a fact of the chain, frame and input, not of the dimensions), found on
    its drawing's pose without moving it; None when it decomposes into dyads or the drawing cannot
    be posed (the full posing then decides)."""
    from ..draw import layout
    from ..motion import link_poses, linkage_from_pose

    try:
        drawn = linkage_from_pose(mechanism, layout(mechanism.chain).joints, nudge=True)
        return drawn.inputs[0] if link_poses(drawn, [0.0]).discriminants is None else None
    except MotionError:
        return None


def _closed_form(linkage) -> bool:
    """Whether the motion layer moves the linkage by the dyads' closed forms (else Newton)."""
    from ..motion import sweep

    return bool(sweep(linkage, steps=2).transmission)  # (a transmission angle per closed-form dyad)


def _expand(unit: CurveUnit) -> list:
    return [unit]


# ------------------------------------------------------------------ the index in the atlas
def _settings_of(conn: sqlite3.Connection) -> dict | None:
    row = conn.execute("SELECT value FROM meta WHERE key = 'curve_index'").fetchone()
    return None if row is None else json.loads(row[0])


def index_info(db: str | Path) -> dict:
    """What the atlas's curve index holds: its settings, mechanisms done and skipped, curves.

    Raises
    ------
    NoCurveIndex
        The atlas has no curve index, or one of another version.
    """
    conn = open_atlas(db)
    try:
        return _info(conn, db)
    finally:
        conn.close()


def _info(conn: sqlite3.Connection, db) -> dict:
    version = conn.execute("SELECT value FROM meta WHERE key = 'curve_index_version'").fetchone()
    if version is None:
        raise NoCurveIndex(f"the atlas {db} has no curve index: build it with "
                           f"'mechsynth atlas --db {db} --index-curves'")
    if version[0] != str(INDEX_VERSION):
        raise NoCurveIndex(f"the atlas {db} has a curve index of version {version[0]}, but this mechsynth reads "
                           f"version {INDEX_VERSION}: rebuild it in a fresh copy of the atlas")
    by_status = dict(conn.execute("SELECT status, COUNT(*) FROM curve_units GROUP BY status").fetchall())
    curves = conn.execute("SELECT COUNT(*) FROM curve_samples").fetchone()[0]
    return {"settings": _settings_of(conn), "mechanisms": by_status.get("done", 0),
            "skipped": by_status.get("skipped", 0), "curves": curves}


def index_units(conn: sqlite3.Connection, settings: IndexSettings, links: tuple[int, int] | None = None) -> list:
    """Every mechanism (with its input link, up to symmetry) of the atlas's planar 1-DOF chains without
    gears, with ``links`` in the given range and as many prismatic pairs as ``settings.prismatic``
    allows: the units of the index, in the atlas's order."""
    from ..synthesis.type_synthesis import mechanisms_of

    lo, hi = links or (0, 10 ** 9)
    p_lo, p_hi = settings.prismatic
    units = []
    for chain_id_, text in conn.execute(
            "SELECT id, chain FROM chains WHERE dof = 1 AND h = 3 AND prismatic BETWEEN ? AND ? AND meshes = 0 "
            "AND links BETWEEN ? AND ? ORDER BY links, prismatic, v, code, certificate", (p_lo, p_hi, lo, hi)):
        chain = Chain.from_dict(json.loads(text))
        for m in mechanisms_of(chain, input_link=True):
            units.append(CurveUnit(chain_id_, text, m.frame, -1 if m.input_link is None else m.input_link, settings))
    return units


def index_curves(db: str | Path, *, settings: IndexSettings = IndexSettings(), links: tuple[int, int] | None = None,
                 workers: int | None = None, scheduler: str | None = None, progress: bool = False,
                 connect_timeout: float = 5.0) -> IndexResult:
    """Build (or resume) the curve index of an atlas.

    Parameters
    ----------
    db : path
        An atlas written by ``mechsynth grid``; the index is added to it (its other tables untouched).
    settings : IndexSettings
    links : (int, int), optional
        Index only the mechanisms with this many links (default: every planar 1-DOF chain).
    workers : int, optional
        Local processes (default: all cores; 1 runs inline).
    scheduler : str, optional
        A Dask scheduler's address: the mechanisms are sampled there.
    progress : bool
        Progress on stderr (mechanisms, curves): a bar on a terminal, a line a minute in a log.

    Returns
    -------
    IndexResult

    Raises
    ------
    AtlasError
        The file is missing, not an atlas, read-only; the index was built with other settings.

    Examples
    --------
    >>> import tempfile, os
    >>> from synth.atlas import parse_grid, run_grid
    >>> db = os.path.join(tempfile.mkdtemp(), "a.sqlite")
    >>> _ = run_grid(parse_grid('dof = 1\\nlinks = 4'), db, workers=1)
    >>> index_curves(db, settings=IndexSettings(samples=3), workers=1).curves
    3
    """
    import os

    from ..execution.executor import Executor, run_plan

    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise InvalidOption(f"workers must be a whole number ≥ 1, not {workers!r}")
    if isinstance(settings.samples, bool) or not isinstance(settings.samples, int) or not 1 <= settings.samples <= 100_000:
        raise InvalidOption(f"samples must be a whole number 1 … 100 000 per mechanism, not {settings.samples!r}")
    if isinstance(settings.drawings, bool) or not isinstance(settings.drawings, int) or not 1 <= settings.drawings <= 1000:
        raise InvalidOption(f"drawings must be a whole number 1 … 1000 per mechanism, not {settings.drawings!r}")
    p_lo, p_hi = settings.prismatic
    if not (isinstance(p_lo, int) and isinstance(p_hi, int) and 0 <= p_lo <= p_hi):
        raise InvalidOption(f"prismatic must be a range of whole numbers of prismatic pairs, low to high, not "
                            f"{settings.prismatic!r}")
    path = Path(db)
    if not path.is_file():
        raise AtlasError(f"no atlas at {path} (run 'mechsynth grid GRID.toml --db {path}' first)")
    refuse_unwritable(path)
    conn = open_atlas(path, write=True)
    client = None
    try:
        with transaction(conn):
            found = _settings_of(conn)
            version = conn.execute("SELECT value FROM meta WHERE key = 'curve_index_version'").fetchone()
            if version is not None and version[0] != str(INDEX_VERSION):
                raise NoCurveIndex(f"the atlas {path} has a curve index of version {version[0]}; this mechsynth "
                                   f"writes version {INDEX_VERSION}: build the index in a fresh copy of the atlas")
            if found is not None and found != json.loads(settings.to_meta()):
                raise AtlasError(f"the curve index of {path} was built with {_said(found)}; resume it with the same "
                                 f"settings, not {_said(json.loads(settings.to_meta()))}")
            for statement in _TABLES.split(";"):
                if statement.strip():
                    conn.execute(statement)
            if "slides" not in {row[1] for row in conn.execute("PRAGMA table_info(curve_samples)")}:
                conn.execute("ALTER TABLE curve_samples ADD COLUMN slides TEXT")  # (an index built before sliders)
            conn.execute("INSERT OR IGNORE INTO meta VALUES ('curve_index_version', ?)", (str(INDEX_VERSION),))
            conn.execute("INSERT OR IGNORE INTO meta VALUES ('curve_index', ?)", (settings.to_meta(),))
        units = index_units(conn, settings, links)
        done = {tuple(r) for r in conn.execute("SELECT chain, frame, input_link FROM curve_units")}
        todo = [u for u in units if (u.chain, u.frame, u.input_link) not in done]
        if scheduler:
            from ..execution.scheduler import connect

            client = connect(scheduler, connect_timeout)
        workers = workers or os.cpu_count() or 1
        executor = f"dask {scheduler}" if scheduler else f"local {workers}"
        start = time.perf_counter()
        bar = None
        if progress and todo:
            from ..execution.progress import Progress

            bar = Progress(len(todo), "mechanisms", desc="curve index")
        run = skipped = 0
        runner = Executor(workers, client)
        try:
            for _, unit, result in run_plan(todo, _expand, sample_unit, executor=runner,
                                             inline_seconds=0 if workers > 1 else 0.25, ordered=False):
                if unit is None:
                    continue
                _commit(conn, result)
                run += 1
                skipped += result.status == "skipped"
                if bar is not None:
                    bar.update(1, curves=len(result.rows))
        finally:
            runner.close()  # no worker outlives the index
            if bar is not None:
                bar.close()
        curves = conn.execute("SELECT COUNT(*) FROM curve_samples").fetchone()[0]
        return IndexResult(len(units), run, skipped, curves, time.perf_counter() - start, executor)
    finally:
        if client is not None:
            client.close()
        conn.close()


def index_gap(db: str | Path, links: tuple[int, int] | None = None) -> str | None:
    """A sentence naming the atlas's chains its curve index does not cover — added by a grid run after the
    index was built, or left out by ``links`` when it was — and the command that indexes them; None when it
    covers every chain it could (with ``links`` in the given range), or the atlas has no index.

    The atlas search sees only indexed chains; a chain is covered when the index has sampled (or skipped)
    any of its mechanisms, so a build interrupted within a chain is not named (resuming it finishes it).

    Examples
    --------
    >>> import tempfile, os
    >>> from synth.atlas import parse_grid, run_grid
    >>> db = os.path.join(tempfile.mkdtemp(), "a.sqlite")
    >>> _ = run_grid(parse_grid('dof = 1\\nlinks = "4..6"'), db, workers=1)
    >>> _ = index_curves(db, settings=IndexSettings(samples=3), links=(4, 4), workers=1)
    >>> print(index_gap(db).replace(db, "a.sqlite"))
    the curve index of a.sqlite does not cover 2 chains of the atlas (with 6 links): the atlas search does not see them until 'mechsynth atlas --db a.sqlite --index-curves --samples 3' indexes them
    >>> index_gap(db, links=(4, 5)) is None
    True
    """
    conn = open_atlas(db)
    try:
        if conn.execute("SELECT value FROM meta WHERE key = 'curve_index_version'").fetchone() is None:
            return None
        settings = _settings_of(conn)
        p_lo, p_hi = settings.get("prismatic", (0, 0))
        lo, hi = links or (0, 10 ** 9)
        missing = conn.execute(
            "SELECT links, COUNT(*) FROM chains WHERE dof = 1 AND h = 3 AND prismatic BETWEEN ? AND ? AND meshes = 0 "
            "AND links BETWEEN ? AND ? AND id NOT IN (SELECT chain FROM curve_units) GROUP BY links ORDER BY links",
            (p_lo, p_hi, lo, hi)).fetchall()
    finally:
        conn.close()
    if not missing:
        return None
    count = sum(n for _, n in missing)
    sizes = ", ".join(str(n) for n, _ in missing)
    return (f"the curve index of {db} does not cover {count} chain{'s' * (count > 1)} of the atlas (with {sizes} "
            f"links): the atlas search does not see them until '{_index_command(db, settings)}' indexes them")


def _index_command(db, settings: dict) -> str:
    """The command that resumes the index of ``db`` with its own settings (a build with others is refused)."""
    lo, hi = settings.get("prismatic", (0, 0))
    drawings = settings.get("drawings", 1)
    return (f"mechsynth atlas --db {db} --index-curves --samples {settings['samples']}"
            + (f" --drawings {drawings}" if drawings > 1 else "")
            + (f" --seed {settings['seed']}" if settings["seed"] else "")
            + (" --triads" if settings.get("triads") else "")
            + (f" --prismatic {lo}..{hi}" if (lo, hi) != (0, 0) else ""))


def _said(settings: dict) -> str:
    lo, hi = settings.get("prismatic", (0, 0))
    drawings = settings.get("drawings", 1)
    return (f"{settings['samples']} samples per mechanism" + (f" and drawing, {drawings} drawings" if drawings > 1 else "")
            + f", seed {settings['seed']}"
            + (", triads" if settings.get("triads") else ", without triads")
            + (f", {lo}..{hi} prismatic pairs" if (lo, hi) != (0, 0) else ""))


def _commit(conn: sqlite3.Connection, result: _UnitRows) -> None:
    """One mechanism's curves and its ``curve_units`` row in one transaction."""
    u = result.unit
    with transaction(conn):
        conn.executemany(
            "INSERT OR IGNORE INTO curve_samples (chain, frame, input_link, input_joint, sample, tracer_link, points, "
            "tracer, timed, untimed, slides) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
            [(u.chain, u.frame, u.input_link, result.input_joint, *row) for row in result.rows])
        conn.execute("INSERT OR REPLACE INTO curve_units VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?)",
                     (u.chain, u.frame, u.input_link, result.input_joint, result.status, result.note,
                      len({row[0] for row in result.rows}), result.tries, round(result.seconds, 4)))
