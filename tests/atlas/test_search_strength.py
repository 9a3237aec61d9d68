"""The curve index and the atlas search piece by piece: every stored curve swept again by the motion layer
and its coefficients fitted by least squares (not the index's FFT), the curve forms and alignments against
transformed curves sampled anew, the misfit against a projection on every shift, every refusal's sentence."""

from __future__ import annotations

import json
import math
import sqlite3

import numpy as np
import pytest

from synth.atlas import AtlasError, NoCurveIndex, index_curves, index_info, parse_grid, run_grid, search_atlas
from synth.atlas import curves
from synth.atlas.curves import (HARMONICS, STEPS, IndexResult, IndexSettings, _by_arc_length,
                                _slides_text, _turned, harmonics, index_units, slides_of, tracer_links, unblob,
                                untimed_parameter)
from synth.atlas.search import (SHIFTS, AtlasSearchResult, _form, _misfits, _refine, _variants, descriptor_of,
                                retrieve, sampled_starts)
from synth.dimension import PathTarget
from synth.errors import BadTarget, InvalidOption
from synth.motion import Linkage, sweep
from synth.structure.chain import Chain, Mechanism
from synth.synthesis.type_synthesis import mechanisms_of

from .helpers import sql

WATT = Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")
STEPHENSON = Chain.parse("0-1 1-2 2-3 3-0 1-4 4-5 5-3")


class _Terminal:
    """A terminal's stderr: progress draws its bar there (in a log it writes a line a minute instead)."""

    def __init__(self):
        import io

        self.text = io.StringIO()
        self.write, self.flush, self.getvalue = self.text.write, self.text.flush, self.text.getvalue

    def isatty(self):
        return True


@pytest.fixture
def terminal(monkeypatch):
    """A function that makes stderr a terminal and returns it (called in the test's body: pytest's capture
    puts its own stderr back after the fixtures), with tqdm's lock and monitor thread left out (mutmut forks)."""
    import sys
    import threading

    import tqdm

    monkeypatch.setattr(tqdm.tqdm, "_lock", threading.RLock(), raising=False)
    monkeypatch.setattr(tqdm.tqdm, "monitor_interval", 0)

    def attach() -> _Terminal:
        screen = _Terminal()
        monkeypatch.setattr(sys, "stderr", screen)
        return screen

    return attach


@pytest.fixture
def index(tmp_path):
    """The 1-DOF atlas of 4 and 6 links with 3 crank poses per mechanism (built for each test, 1.5 CPU s: a
    mutation run maps the index's code to every test that reads it, and each mutant's tests build it anew)."""
    db = tmp_path / "a.sqlite"
    run_grid(parse_grid('dof = 1\nlinks = "4..6"'), db, workers=1)
    result = index_curves(db, settings=IndexSettings(samples=3), workers=1)
    return db, result


# ------------------------------------------------------------------ the index
def test_settings_and_results_as_stored():
    assert IndexSettings().to_meta() == '{"harmonics": 12, "samples": 200, "seed": 0, "steps": 256, "triads": false}'
    assert json.loads(IndexSettings(5, 3, True, (0, 2)).to_meta()) == {
        "harmonics": 12, "samples": 5, "seed": 3, "steps": 256, "triads": True, "prismatic": [0, 2]}
    assert IndexResult(3, 2, 1, 40, 1.23456, "local 1").to_dict() == {
        "units_total": 3, "units_run": 2, "units_skipped": 1, "curves": 40, "seconds": 1.235, "executor": "local 1"}


def test_tracer_links_are_the_links_not_on_the_frame():
    assert tracer_links(Mechanism(WATT, 0)) == [2, 5]  # the frame 0 is jointed to 1, 3 and 4
    assert tracer_links(Mechanism(STEPHENSON, 0)) == [2, 4, 5]  # to 1 and 3
    assert tracer_links(Mechanism(STEPHENSON, 1)) == [3, 5]  # to 0, 2 and 4


def test_small_helpers_by_hand():
    x, y = _turned((1.0, 0.0), math.pi / 2)
    assert abs(x) < 1e-15 and y == pytest.approx(1.0)
    assert _turned((0.6, 0.8), math.pi) == pytest.approx((-0.6, -0.8))
    assert slides_of('{"3": [0.0, 1.0], "5": [0.6, -0.8]}') == {3: (0.0, 1.0), 5: (0.6, -0.8)}
    assert slides_of(None) == {}

    class Slid:
        slides = {2: (0.1234567890123456789, -1.0)}

    assert _slides_text(Slid()) == '{"2": [0.123456789012346, -1.0]}'
    Slid.slides = {}
    assert _slides_text(Slid()) is None
    c = np.array([1 + 2j, -3.5j])
    assert unblob(curves._blob(c)).tolist() == c.tolist() and len(curves._blob(c)) == 32
    # a 2 × 1 rectangle: perimeter 6, corners at arc lengths 0, 2, 3, 5
    assert untimed_parameter(np.array([0, 2, 2 + 1j, 1j])) == pytest.approx(
        [0, 2 * math.pi * 2 / 6, 2 * math.pi * 3 / 6, 2 * math.pi * 5 / 6])
    # resampled at as many points equally spaced along the closed polygon: a 2 × 1 rectangle's 6 points
    square = _by_arc_length(np.array([0, 2, 2 + 1j, 1j]))
    assert square == pytest.approx([0, 1.5, 2 + 1j, 0.5 + 1j])


def test_the_units_are_the_engines_mechanisms_with_input_links(index):
    db, result = index
    conn = sqlite3.connect(db)
    units = index_units(conn, IndexSettings(samples=3))
    chains = {cid: Chain.from_dict(json.loads(text)) for cid, text in conn.execute("SELECT id, chain FROM chains")}
    conn.close()
    expected = sorted((cid, m.frame, m.input_link) for cid, c in chains.items() for m in mechanisms_of(c, input_link=True))
    assert sorted((u.chain, u.frame, u.input_link) for u in units) == expected
    assert (result.units_total, result.units_run, result.executor) == (len(expected), len(expected), "local 1")
    assert [u for u in index_units(sqlite3.connect(db), IndexSettings(), links=(5, 5))] == []
    four = index_units(sqlite3.connect(db), IndexSettings(), links=(4, 4))
    assert [(u.frame, u.input_link) for u in four] == [(0, 1)]  # the four-bar: one crank up to symmetry


def _walked(z):
    """Points at equal arc lengths along the closed polygon through z, from z[0] (a walk, segment by segment)."""
    points = list(z) + [z[0]]
    lengths = [abs(b - a) for a, b in zip(points, points[1:])]
    total, out, k, done = sum(lengths), [], 0, 0.0
    for i in range(len(z)):
        s = total * i / len(z)
        while k < len(lengths) - 1 and done + lengths[k] < s:
            done += lengths[k]
            k += 1
        out.append(points[k] + (points[k + 1] - points[k]) * ((s - done) / lengths[k]))
    return np.array(out)


def test_every_stored_curve_is_its_linkage_swept_again(index):
    db, result = index
    rows = sql(db, "SELECT s.chain, s.frame, s.input_link, s.input_joint, s.tracer_link, s.points, s.tracer, "
                   "s.timed, s.untimed, s.slides, c.chain FROM curve_samples s JOIN chains c ON c.id = s.chain")
    assert len(rows) == result.curves
    units = sql(db, "SELECT chain, frame, input_link, status, samples FROM curve_units")
    # each done mechanism: 3 poses, each with a curve on every tracer link
    per = {(c, f, i): (s, n) for c, f, i, s, n in units}
    chains = {cid: Chain.from_dict(json.loads(text)) for cid, text in sql(db, "SELECT id, chain FROM chains")}
    assert result.curves == sum(3 * len(tracer_links(Mechanism(chains[c], f))) for (c, f, i), (s, _) in per.items()
                                if s == "done")
    assert result.units_skipped == sum(s == "skipped" for s, _ in per.values()) > 0
    assert all(n == 3 for s, n in per.values() if s == "done")
    for chain_id, frame, input_link, joint, tracer, points, at, timed, untimed, slides, text in rows[::5]:
        chain = chains[chain_id]
        assert chain.joints[joint] in {(frame, input_link), (input_link, frame)} or {frame, input_link} <= set(
            chain.joints[joint])
        linkage = Linkage(Mechanism(chain, frame, input_link), (joint,), json.loads(points), slides_of(slides),
                          tracers={"P": (tracer, tuple(json.loads(at)))})
        motion = sweep(linkage, steps=STEPS + 1)
        assert motion.stopped is None and motion.inputs[-1, 0] - motion.inputs[0, 0] == pytest.approx(2 * math.pi)
        xy = motion.tracers["P"][:STEPS]
        z = xy[:, 0] + 1j * xy[:, 1]
        phi = motion.inputs[:STEPS, 0]
        fitted = harmonics(z, phi, HARMONICS)  # in the absolute input angle, by least squares
        stored = unblob(timed)
        assert stored.shape == (2 * HARMONICS + 1,)
        assert np.abs(stored - fitted).max() <= 1e-9 * np.abs(fitted).max()
        assert abs(z[0] - complex(*json.loads(at))) <= 1e-9 * np.abs(fitted).max()  # the pose's point first
        # untimed: the polygon through the points walked at equal arc lengths from the pose's point, then
        # fitted in t = 2π s / L by least squares
        even = _walked(z)
        loose = harmonics(even, 2 * math.pi * np.arange(STEPS) / STEPS, HARMONICS)
        assert np.abs(unblob(untimed) - loose).max() <= 1e-9 * np.abs(loose).max()


def test_the_skipped_mechanisms_say_why(index):
    db, _ = index
    notes = {note for (note,) in sql(db, "SELECT note FROM curve_units WHERE status = 'skipped'")}
    assert notes == {"moved by Newton's method (a triad or higher group): index it with triads"}
    assert sql(db, "SELECT COUNT(*) FROM curve_units WHERE status = 'done' AND note IS NOT NULL") == [(0,)]


def test_index_info_and_its_refusals(index, tmp_path):
    db, result = index
    info = index_info(db)
    skipped = sql(db, "SELECT COUNT(*) FROM curve_units WHERE status = 'skipped'")[0][0]
    assert info == {"settings": json.loads(IndexSettings(samples=3).to_meta()),
                    "mechanisms": result.units_total - skipped, "skipped": skipped, "curves": result.curves}
    bare = tmp_path / "bare.sqlite"
    run_grid(parse_grid("dof = 1\nlinks = 4"), bare, workers=1)
    with pytest.raises(NoCurveIndex) as e:
        index_info(bare)
    assert str(e.value) == f"the atlas {bare} has no curve index: build it with 'mechsynth atlas --db {bare} --index-curves'"
    with sqlite3.connect(bare) as conn:
        conn.execute("INSERT INTO meta VALUES ('curve_index_version', '7')")
    conn.close()
    with pytest.raises(NoCurveIndex) as e:
        index_info(bare)
    assert str(e.value) == (f"the atlas {bare} has a curve index of version 7, but this mechsynth reads version 1: "
                            "rebuild it in a fresh copy of the atlas")
    with pytest.raises(NoCurveIndex) as e:
        index_curves(bare, settings=IndexSettings(samples=1), workers=1)
    assert str(e.value) == (f"the atlas {bare} has a curve index of version 7; this mechsynth writes version 1: build "
                            "the index in a fresh copy of the atlas")


@pytest.mark.parametrize("options, sentence", [
    (dict(workers=0), "workers must be a whole number ≥ 1, not 0"),
    (dict(workers=True), "workers must be a whole number ≥ 1, not True"),
    (dict(settings=IndexSettings(samples=0)), "samples must be a whole number 1 … 100 000 per mechanism, not 0"),
    (dict(settings=IndexSettings(samples=100_001)), "samples must be a whole number 1 … 100 000 per mechanism, not 100001"),
    (dict(settings=IndexSettings(samples=2.0)), "samples must be a whole number 1 … 100 000 per mechanism, not 2.0"),
    (dict(settings=IndexSettings(samples=True)), "samples must be a whole number 1 … 100 000 per mechanism, not True"),
    (dict(settings=IndexSettings(prismatic=(2, 1))), "prismatic must be a range of whole numbers of prismatic pairs, "
                                                     "low to high, not (2, 1)"),
    (dict(settings=IndexSettings(prismatic=(-1, 0))), "prismatic must be a range of whole numbers of prismatic pairs, "
                                                      "low to high, not (-1, 0)"),
    (dict(settings=IndexSettings(prismatic=(0, 1.0))), "prismatic must be a range of whole numbers of prismatic "
                                                       "pairs, low to high, not (0, 1.0)"),
])
def test_index_options_are_refused_with_their_sentence(tmp_path, options, sentence):
    db = tmp_path / "a.sqlite"
    run_grid(parse_grid("dof = 1\nlinks = 4"), db, workers=1)
    before = db.read_bytes()
    with pytest.raises(InvalidOption) as e:
        index_curves(db, **options)
    assert str(e.value) == sentence
    assert db.read_bytes() == before


def test_an_index_is_resumed_only_with_its_settings(tmp_path):
    db = tmp_path / "a.sqlite"
    with pytest.raises(AtlasError) as e:
        index_curves(db, settings=IndexSettings(samples=1), workers=1)
    assert str(e.value) == f"no atlas at {db} (run 'mechsynth grid GRID.toml --db {db}' first)"
    run_grid(parse_grid('dof = 1\nlinks = 4\nprismatic = "0..1"'), db, workers=1)
    first = index_curves(db, settings=IndexSettings(samples=1, prismatic=(0, 1)), workers=1)
    assert first.units_run == first.units_total > 1
    for settings, said in ((IndexSettings(samples=2, prismatic=(0, 1)), "2 samples per mechanism, seed 0, without "
                                                                        "triads, 0..1 prismatic pairs"),
                           (IndexSettings(samples=1, seed=4, triads=True), "1 samples per mechanism, seed 4, triads")):
        with pytest.raises(AtlasError) as e:
            index_curves(db, settings=settings, workers=1)
        assert str(e.value) == (f"the curve index of {db} was built with 1 samples per mechanism, seed 0, without "
                                f"triads, 0..1 prismatic pairs; resume it with the same settings, not {said}")
    again = index_curves(db, settings=IndexSettings(samples=1, prismatic=(0, 1)), workers=1)
    assert (again.units_total, again.units_run, again.curves) == (first.units_total, 0, first.curves)
    # the slider-crank's samples keep their sliding line; the four-bar's have none
    assert {s is None for (s,) in sql(db, "SELECT slides FROM curve_samples")} == {True, False}


# ------------------------------------------------------------------ the search's pieces
def test_the_forms_of_a_curve_are_the_transformed_curves_sampled_anew():
    rng = np.random.default_rng(4)
    h = 4
    c = rng.normal(size=2 * h + 1) + 1j * rng.normal(size=2 * h + 1)
    t = np.linspace(0, 2 * math.pi, 64, endpoint=False)
    n = np.arange(-h, h + 1)

    def curve(x):
        return np.exp(1j * np.outer(x, n)) @ c

    forms = {(False, False): curve(t), (True, False): np.conj(curve(-t)),   # mirrored, the crank's angle with it
             (False, True): curve(-t), (True, True): np.conj(curve(t))}     # run backwards; both
    for (mirror, reverse), z in forms.items():
        assert np.abs(_form(c, mirror, reverse) - harmonics(z, t, h)).max() < 1e-12, (mirror, reverse)
    assert _form(np.stack([c, 2 * c]), True, False)[1] == pytest.approx(2 * np.conj(c))  # row by row
    assert _variants(True) == ((False, False), (True, False))
    assert _variants(False) == ((False, False), (False, True), (True, False), (True, True))


def _projection_misfit(t, u, tau):
    """min over λ of ‖t − λ·u·e^{inτ}‖ / ‖t‖ without the mean, λ by least squares."""
    h = (len(t) - 1) // 2
    n = np.arange(-h, h + 1)
    keep = n != 0
    v = (u * np.exp(1j * n * tau))[keep]
    lam = np.linalg.lstsq(v[:, None], t[keep], rcond=None)[0][0]
    return np.linalg.norm(t[keep] - lam * v) / np.linalg.norm(t[keep]), lam


def test_the_misfit_on_the_shift_grid_is_the_best_projection_on_every_shift():
    rng = np.random.default_rng(8)
    h = 5
    t = rng.normal(size=2 * h + 1) + 1j * rng.normal(size=2 * h + 1)
    u = rng.normal(size=(3, 2 * h + 1)) + 1j * rng.normal(size=(3, 2 * h + 1))
    u[2] = 0
    u[2, h] = 5  # only a mean: no shape at all
    misfit, shift = _misfits(t, u)
    taus = 2 * math.pi * np.arange(SHIFTS) / SHIFTS
    for row in range(2):
        slow = [_projection_misfit(t, u[row], tau)[0] for tau in taus]
        assert misfit[row] == pytest.approx(min(slow), abs=1e-12)
        assert shift[row] == pytest.approx(taus[int(np.argmin(slow))])
    assert misfit[2] == math.inf


def test_an_aligned_copy_fits_exactly_and_its_shift_is_refined_between_the_grid():
    rng = np.random.default_rng(9)
    h = 6
    n = np.arange(-h, h + 1)
    u = rng.normal(size=2 * h + 1) + 1j * rng.normal(size=2 * h + 1)
    lam, tau = 0.4 * np.exp(2.1j), 2 * math.pi * 100.37 / SHIFTS  # between grid shifts 100 and 101
    t = lam * u * np.exp(1j * n * tau)
    t[h] = 7 - 3j  # another mean: the translation is left out
    misfit, shift = _misfits(t, u[None])
    assert misfit[0] < 0.02 and shift[0] == pytest.approx(2 * math.pi * 100 / SHIFTS)
    value, refined, scale = _refine(t, u, float(shift[0]))
    assert value < 1e-7 and refined == pytest.approx(tau, abs=1e-7) and scale == pytest.approx(lam, abs=1e-7)
    # a shift that is already the best is kept
    exact = lam * u * np.exp(1j * n * shift[0])
    value, kept, _ = _refine(exact, u, float(shift[0]))
    assert value < 1e-12 and kept == pytest.approx(shift[0], abs=1e-9)


def _ellipse(count, timed=True, start=0.0):
    t = start + np.linspace(0, 2 * math.pi, count, endpoint=False)
    return PathTarget(np.c_[2 * np.cos(t), np.sin(t)], inputs=t if timed else None)


def test_a_targets_descriptor():
    c, h, timed = descriptor_of(_ellipse(30))
    # 2 cos t + i sin t = 1.5 e^{it} + 0.5 e^{−it}
    assert (h, timed) == (12, True) and c[h + 1] == pytest.approx(1.5) and c[h - 1] == pytest.approx(0.5)
    assert np.abs(np.delete(c, [h - 1, h + 1])).max() < 1e-12
    assert descriptor_of(_ellipse(7, timed=False))[1] == 3 and descriptor_of(_ellipse(24))[1] == 11
    assert descriptor_of(_ellipse(25))[1] == 12 and descriptor_of(_ellipse(26))[1] == 12
    c, h, timed = descriptor_of(_ellipse(40, timed=False))
    points = _ellipse(40).points
    z = points[:, 0] + 1j * points[:, 1]
    assert not timed and np.abs(c - harmonics(z, untimed_parameter(z), 12)).max() < 1e-12


def test_targets_the_index_cannot_serve_are_refused_with_their_sentence():
    with pytest.raises(BadTarget) as e:
        descriptor_of(_ellipse(6, timed=False))
    assert str(e.value) == "the atlas search needs at least 7 target points to describe a closed curve, not 6"
    t = np.linspace(0, 2 * math.pi, 8, endpoint=False)  # a gap of exactly 45° between inputs is served
    assert descriptor_of(PathTarget(np.c_[np.cos(t), np.sin(t)], inputs=t))[2]
    wide = np.append(t[:-1], t[-1] - 0.02)  # the last gap 45° + 1.1°
    with pytest.raises(BadTarget) as e:
        descriptor_of(PathTarget(np.c_[np.cos(wide), np.sin(wide)], inputs=wide))
    assert str(e.value) == ("the atlas's curves are indexed over a full turn of a crank: this timing leaves a gap of 46° "
                            "(at most 45°) — search a given topology instead (--mechanism)")
    # five unit steps along a line, then a last point at distance d from the first: served while d ≤ 3 median steps
    for d, served in ((2.999, True), (3.01, False)):
        target = PathTarget([[0.0, 0.0], [1, 0], [2, 0], [3, 0], [4, 0], [5, 0], [0, d]])
        if served:
            assert not descriptor_of(target)[2]
        else:
            with pytest.raises(BadTarget) as e:
                descriptor_of(target)
            assert str(e.value) == ("the atlas's curves are closed and this path is open (its ends are 3.01 apart, "
                                    "3.0 times its median spacing): search a given topology instead (--mechanism), or "
                                    "give points all round a closed curve")


def test_retrieval_keeps_the_best_of_each_topology(index):
    db, _ = index
    target = _ellipse(36)
    found, size = retrieve(db, target, per_topology=2)
    assert size == sql(db, "SELECT COUNT(*) FROM curve_samples")[0][0]
    topologies = {}
    for c in found:
        topologies.setdefault(c.topology, []).append(c)
    assert all(len(group) <= 2 for group in topologies.values())
    done = sql(db, "SELECT COUNT(*) FROM curve_units WHERE status = 'done'")[0][0]
    assert len(topologies) == done  # no limit on topologies: every indexed one
    t, h, _ = descriptor_of(target)
    for c in found:  # each candidate's misfit is its stored curve's, aligned anew
        (coefficients,) = sql(db, "SELECT timed FROM curve_samples WHERE id = ?", c.row)[0]
        u = _form(unblob(coefficients)[HARMONICS - h:HARMONICS + h + 1], c.mirror, c.reverse)
        assert c.misfit == pytest.approx(_projection_misfit(t, u, c.shift)[0], abs=1e-9)
        assert not c.reverse  # a timed target is never run backwards
    one, _ = retrieve(db, target, per_topology=1, topologies=1)
    links = {c.links for c in found}
    assert len(one) == len(links)  # at least the best topology of every link count
    best = {}
    for c in sorted(found, key=lambda c: c.misfit):
        best.setdefault(c.links, c)
    assert sorted(c.row for c in one) == sorted(c.row for c in best.values())
    only_four, size = retrieve(db, target, links=(4, 4))
    assert {c.links for c in only_four} == {4} and size == sql(
        db, "SELECT COUNT(*) FROM curve_samples s JOIN chains c ON c.id = s.chain WHERE c.links = 4")[0][0]


@pytest.mark.parametrize("options, sentence", [
    (dict(top=0), "top must be a whole number ≥ 1, not 0"),
    (dict(per_topology=True), "per_topology must be a whole number ≥ 1, not True"),
    (dict(workers=1.5), "workers must be a whole number ≥ 1, not 1.5"),
    (dict(budget=0), "the budget must be a positive number of seconds, not 0"),
    (dict(budget=math.inf), "the budget must be a positive number of seconds, not inf"),
    (dict(budget="5"), "the budget must be a positive number of seconds, not '5'"),
])
def test_search_options_are_refused_with_their_sentence(tmp_path, options, sentence):
    db = _four_bar_index(tmp_path, 1)
    with pytest.raises(InvalidOption) as e:
        search_atlas(db, _ellipse(30), **options)
    assert str(e.value) == sentence


def _four_bar_index(folder, samples: int, seed: int = 0):
    db = folder / "four.sqlite"
    run_grid(parse_grid("dof = 1\nlinks = 4"), db, workers=1)
    index_curves(db, settings=IndexSettings(samples=samples, seed=seed), workers=1)
    return db


def _stored_curve(db, row: int, steps: int):
    """The stored sample's linkage swept by the motion layer: (its mechanism, tracer link, the linkage,
    steps + 1 tracer points and crank angles over a full turn)."""
    ((chain_json, frame, input_link, joint, tracer, points, at),) = sql(
        db, "SELECT c.chain, s.frame, s.input_link, s.input_joint, s.tracer_link, s.points, s.tracer "
            "FROM curve_samples s JOIN chains c ON c.id = s.chain WHERE s.id = ?", row)
    mechanism = Mechanism(Chain.from_dict(json.loads(chain_json)), frame, input_link)
    linkage = Linkage(mechanism, (joint,), json.loads(points), tracers={"P": (tracer, tuple(json.loads(at)))})
    motion = sweep(linkage, steps=steps + 1)
    return mechanism, tracer, motion.tracers["P"], motion.inputs[:, 0]


@pytest.mark.parametrize("timed", [True, False])
def test_a_stored_curve_moved_and_mirrored_is_found_exactly(tmp_path, timed, terminal):
    db = _four_bar_index(tmp_path, 4)
    screen = terminal()
    size = sql(db, "SELECT COUNT(*) FROM curve_samples")[0][0]
    row = sql(db, "SELECT id FROM curve_samples ORDER BY id")[2][0]
    mechanism, tracer, xy, phi = _stored_curve(db, row, 36)
    # the curve mirrored in the x axis, turned by 40°, halved and moved: a four-bar of the same topology traces it
    turn = 0.5 * np.exp(0.7j)
    z = turn * (xy[:36, 0] - 1j * xy[:36, 1]) + (3 - 2j)
    target = PathTarget(np.c_[z.real, z.imag], inputs=-phi[:36] if timed else None)  # the mirror's crank turns back
    found = search_atlas(db, target, per_topology=2, budget=3, progress=timed)
    assert (found.index_curves, found.topologies, found.timed, found.notes) == (size, 1, timed, [])
    bar = screen.getvalue()  # a bar of the topologies polished, when asked for
    assert ("polish" in bar and "/1 [" in bar and "topologies" in bar) if timed else bar == ""
    best = found.best
    # (without timing the target's 36-gon is walked by arc length, not the index's 256 steps: close, not exact)
    assert best.candidate.mirror and best.candidate.misfit < (1e-6 if timed else 1e-3) and best.candidate.row == row
    # the mirror image z̄ in the sample's order: timed, its crank turns back (z̄(−ψ), the mirror's own form); untimed,
    # the mirror image run in the order it was sampled is the mirrored form run backwards (z̄(t))
    assert best.candidate.reverse is (not timed)
    assert best.result.met and best.result.relative_max < 1e-8 and best.tried == 1
    assert best.mechanism.chain.certificate == mechanism.chain.certificate
    assert (best.mechanism.frame, best.mechanism.input_link) == (mechanism.frame, mechanism.input_link)
    # polished from the sample alone, no global search: the dimensional synthesis says how it got there
    assert best.result.method == "bounded least squares (trf) from a given start, " + (
        "timed" if timed else "inputs as unknowns, in order")
    # its row: the topology and the errors of the polished result, the candidate it started from
    from synth.atlas.database import chain_id

    r = best.row()
    assert r["chain"] == best.mechanism.chain.compact() and r["chain_id"] == chain_id(mechanism.chain.certificate)
    assert (r["frame"], r["tracer_link"], r["links"], r["tried"]) == (mechanism.frame, tracer, 4, 1)
    assert r["input"] == best.result.linkage.to_dict()["inputs"][0]
    assert (r["error_max"], r["relative_max"], r["met"]) == (best.result.error_max, best.result.relative_max, True)
    assert (r["error_rms"], r["relative_rms"], r["misfit"]) == (best.result.error_rms, best.result.relative_rms,
                                                                best.candidate.misfit)
    assert r["seconds"] == round(best.seconds, 3) and 0 < best.seconds <= found.seconds
    # the polished linkage traces the target: moved again to each target point's input
    assert best.result.error_max <= 1e-8 * target.size


def test_a_result_without_matches_has_no_best():
    assert AtlasSearchResult([], 10, 0, 0.1, True).best is None
    assert AtlasSearchResult(["a", "b"], 10, 2, 0.1, True).best == "a"


@pytest.mark.parametrize("seed", [0, 5])
def test_sampled_starts_are_the_index_samples_posed_on_the_target(tmp_path, seed):
    db = _four_bar_index(tmp_path, 4, seed)
    row = sql(db, "SELECT id FROM curve_samples ORDER BY id")[2][0]
    mechanism, tracer, xy, phi = _stored_curve(db, row, 36)
    z = 0.5 * np.exp(0.7j) * (xy[:36, 0] - 1j * xy[:36, 1]) + (3 - 2j)
    target = PathTarget(np.c_[z.real, z.imag], inputs=-phi[:36])
    # the index's own 4 samples of the mechanism (same seed): the nearest is the one that traced the target
    starts = sampled_starts(mechanism, tracer, target, seed, samples=4, count=2)
    assert len(starts) == 2 and len(sampled_starts(mechanism, tracer, target, seed, samples=4)) == 4
    first = starts[0]
    assert first.tracers["P"][0] == tracer and first.mechanism.chain.certificate == mechanism.chain.certificate
    assert (first.mechanism.frame, first.mechanism.input_link) == (mechanism.frame, mechanism.input_link)
    # posed at the target's first point, and it traces the target: swept from there, its curve is the target's
    assert np.hypot(*(np.asarray(first.tracers["P"][1]) - target.points[0])) < 1e-9 * target.size
    # (the sweep turns its crank forward; the mirror's target inputs run backward: the points in reverse order)
    motion = sweep(first, steps=37)
    traced = motion.tracers["P"][:36, 0] + 1j * motion.tracers["P"][:36, 1]
    assert np.abs(traced - z[(-np.arange(36)) % 36]).max() < 1e-8 * target.size
    # what the index cannot serve gives no start: no path, a target too short, the frame as tracer
    assert sampled_starts(mechanism, tracer, PathTarget(target.points[:6], inputs=target.inputs[:6]), samples=4) == []
    assert sampled_starts(mechanism, mechanism.frame, target, samples=4) == []

    class NotAPath:
        kind = "function"

    assert sampled_starts(mechanism, tracer, NotAPath(), samples=4) == []


def test_an_index_of_some_link_counts_and_its_columns_as_stored(tmp_path, terminal):
    db = tmp_path / "a.sqlite"
    run_grid(parse_grid('dof = 1\nlinks = "4..6"'), db, workers=1)
    screen = terminal()
    result = index_curves(db, settings=IndexSettings(samples=2), links=(4, 4), workers=1, progress=True)
    # only the four-bar's one mechanism with an input link, sampled twice with a curve of its coupler each
    assert (result.units_total, result.units_run, result.units_skipped, result.curves) == (1, 1, 0, 2)
    bar = screen.getvalue()
    assert "curve index" in bar and "/1 [" in bar and "mechanisms" in bar  # (a bar of 1 step, cleared at its end)
    ((chain, links, frame, input_link, joint, status, note, samples, tries, seconds),) = sql(
        db, "SELECT u.chain, c.links, u.frame, u.input_link, u.input_joint, u.status, u.note, u.samples, u.tries, "
            "u.seconds FROM curve_units u JOIN chains c ON c.id = u.chain")
    four_bar = Chain.from_dict(json.loads(sql(db, "SELECT chain FROM chains WHERE id = ?", chain)[0][0]))
    assert (links, frame, input_link, status, note, samples) == (4, 0, 1, "done", None, 2)
    assert set(four_bar.joints[joint]) == {0, 1}  # the input joint: the crank's pivot on the frame
    assert 2 <= tries <= 80 and seconds >= 0 and round(seconds, 4) == seconds
    rows = sql(db, "SELECT sample, tracer_link, points, tracer FROM curve_samples ORDER BY sample")
    assert len({s for s, *_ in rows}) == 2 and all(1 <= s <= tries for s, *_ in rows) and rows[-1][0] == tries
    for _, tracer, points, at in rows:
        assert [tracer] == tracer_links(Mechanism(four_bar, frame))  # the coupler: the link off the frame
        for value in [v for p in json.loads(points) for v in p] + json.loads(at):  # kept to 12 decimals
            assert abs(value * 1e12 - round(value * 1e12)) < 1e-3
    assert index_info(db)["mechanisms"] == 1


class _Clock:
    """A CPU clock for the search: starts at ``start`` seconds and moves ``step`` seconds a reading."""

    def __init__(self, start: float, step: float):
        self.now, self.step = start, step

    def __call__(self) -> float:
        self.now += self.step
        return self.now


def test_the_budget_is_counted_from_the_searchs_start_whatever_the_clock_reads(tmp_path, monkeypatch):
    import time

    db = _four_bar_index(tmp_path, 4)
    row = sql(db, "SELECT id FROM curve_samples ORDER BY id")[2][0]
    _, _, xy, phi = _stored_curve(db, row, 36)
    target = PathTarget(xy[:36], inputs=phi[:36])
    # a process that has run for hours already: the budget is the time spent since the search began
    monkeypatch.setattr(time, "process_time", _Clock(1e4, 1e-6))
    found = search_atlas(db, target, budget=3)
    assert found.notes == [] and found.best.result.relative_max < 1e-8 and found.best.tried == 1
    # a clock that jumps 10 s a reading spends a budget of 3 s before the first polish: the note says so
    monkeypatch.setattr(time, "process_time", _Clock(0.0, 10.0))
    found = search_atlas(db, target, budget=3, per_topology=1)
    chain = Chain.from_dict(json.loads(sql(db, "SELECT chain FROM chains")[0][0]))
    assert found.matches == [] and [str(note) for note in found.notes] == [
        f"{chain.compact()} (frame 0, input 0-1): no polish reached the target (its share of the time budget was "
        "spent before a polish began)"]


def test_a_share_spent_while_a_start_is_placed_is_said_as_spent_not_as_a_negative_budget(tmp_path, monkeypatch):
    # a clock of 1 s a reading: the polishing share (1.5 s of 3) is left at the loop's check and spent by the
    # polish's; it read "(the budget must be a positive number of seconds, not -0.5)", for every topology
    import time

    db = _four_bar_index(tmp_path, 4)
    row = sql(db, "SELECT id FROM curve_samples ORDER BY id")[2][0]
    _, _, xy, phi = _stored_curve(db, row, 36)
    monkeypatch.setattr(time, "process_time", _Clock(0.0, 1.0))
    found = search_atlas(db, PathTarget(xy[:36], inputs=phi[:36]), budget=3, per_topology=1)
    chain = Chain.from_dict(json.loads(sql(db, "SELECT chain FROM chains")[0][0]))
    assert found.matches == [] and [str(note) for note in found.notes] == [
        f"{chain.compact()} (frame 0, input 0-1): no polish reached the target (its share of the time budget was "
        "spent before a polish began)"]


def test_a_curve_no_four_bar_traces_is_polished_again_from_the_best(tmp_path):
    # a timed ellipse: the first polish stops short of it, and the search goes on from its best while that halves
    # the error and time is left; what it returns is a four-bar the motion layer moves along its reported curve
    db = _four_bar_index(tmp_path, 4)
    found = search_atlas(db, _ellipse(30), per_topology=1, budget=1.5)
    assert found.notes == [] and len(found.matches) == 1
    best = found.best
    assert best.tried == 1 and best.result.relative_max > 1e-9 and best.candidate.links == 4
    assert best.result.error_rms <= best.result.error_max


def test_a_result_the_motion_layer_cannot_move_to_an_input_is_infinitely_far_from_its_curve():
    # the README's slider-crank search was refused (CannotAssemble, exit 2) when the global stage's answer
    # for another topology could not be moved to one of its inputs: now that answer is not kept, and the
    # re-check reads such a gap as infinite instead of raising
    from types import SimpleNamespace

    from synth.atlas.search import _rechecked
    from tests.motion.helpers import four_bar

    rocker = four_bar(2.5, 3.2, 3.0, 4.0, phi=0.5, tracer=(1, 1))  # a rocker: no assembly at 3.0 rad
    result = SimpleNamespace(linkage=rocker, inputs=np.array([0.5, 3.0]), traced=np.zeros((2, 2)))
    assert _rechecked(result, SimpleNamespace(size=1.0)) == math.inf
    inside = SimpleNamespace(linkage=rocker, inputs=np.array([0.5]), traced=np.zeros((1, 2)))
    assert math.isfinite(_rechecked(inside, SimpleNamespace(size=1.0)))
