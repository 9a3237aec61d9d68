"""The gear-train enumerator's parts by hand: every refusal's sentence, the trees, the pruning table of a star,
the lowering of its levels, a permutation group's closure, and the size estimate extrapolated from counts given
to it (the exact counts it would otherwise make), with the sentences of the size check."""

from __future__ import annotations

import math

import pytest

from synth.errors import InvalidOption, QueryTooLarge, flag
from synth.gears import enumeration
from synth.gears.enumeration import (Census, _closure, _lowered, _Tree, census, check_query, estimate_trains,
                                     link_axis_trees, size_check_trains)


@pytest.mark.parametrize("call,sentence", [
    (lambda: check_query(0, 4), "a gear train that moves has F ≥ 1 degrees of freedom, not 0"),
    (lambda: check_query(1, 1), "a gear train has at least 2 links (a frame and a gear), not 1"),
    (lambda: check_query(1, 13), "gear trains are enumerated up to 12 links, not 13"),
    (lambda: check_query(True, 4), "the degrees of freedom F must be a whole number, not True"),
    (lambda: check_query(1, 4.0), "the number of links must be a whole number, not 4.0"),
    (lambda: check_query(1, "4"), "the number of links must be a whole number, not '4'"),
    (lambda: check_query(1, 4, "rot"), "a gear train is listed by its displacement or its rotation graph, not 'rot'"),
    (lambda: census(1, 4, method="x"), "the method is auto, orderly or augmentation, not 'x'"),
])
def test_refusals_in_full(call, sentence):
    with pytest.raises(InvalidOption) as refused:
        call()
    assert str(refused.value) == sentence


def test_check_query_takes_the_bounds_themselves():
    for dof, links in ((1, 2), (1, 12), (5, 12)):
        check_query(dof, links, "rotation")  # no refusal


def test_the_smallest_trees_by_hand():
    """One link: no axis; two: one axis; three: a path of two axes or one axis of three."""
    assert link_axis_trees(0) == () and link_axis_trees(1) == ((),) and link_axis_trees(2) == (((0, 1),),)
    assert link_axis_trees(3) == (((0, 1), (0, 2)), ((0, 1, 2),))


def test_the_pruning_table_of_a_star():
    """Frame 0 with links 1, 2, 3 each on an axis of its own: the candidate meshes are the pairs of 1, 2, 3, all
    held by the frame.  For two meshes, the sets that can refuse one are those of slack
    3(|S| − 1) − 2p(S) − 1 below 2 holding a pair: {0, 1, 2}, {0, 1, 3}, {0, 2, 3} (slack 6 − 4 − 1 = 1); none
    has slack 0, and each holds one pair."""
    tree = _Tree(4, ((0, 1), (0, 2), (0, 3)))
    assert tree.pairs == [(1, 2), (1, 3), (2, 3)] and tree.carriers == [0, 0, 0]
    assert tree.triples == [(1, 2, 0), (1, 3, 0), (2, 3, 0)]
    assert tree.order == 6 and len(tree.group) == 6 and tree.group[0] == (0, 1, 2)
    assert tree.table(2) == ([0, 0b111], [0b001, 0b010, 0b100])
    assert list(tree.mesh_sets(2)) == [(0, 1)] == list(tree.mesh_sets(2, "augmentation"))
    assert list(tree.mesh_sets(4)) == []  # more meshes than candidates


def test_lowering_the_slack_levels():
    """A mesh held by the sets 0b0011: those move one level down, the others stay; the top level goes."""
    assert _lowered([0b1010, 0b0110, 0b0001], 0b0011) == [(0b1010 & ~0b0011) | (0b0110 & 0b0011),
                                                           (0b0110 & ~0b0011) | (0b0001 & 0b0011)] == [0b1010, 0b0101]


def test_the_closure_of_generators():
    """A swap makes a group of two; a 3-cycle one of three; the identity first, the rest sorted."""
    assert _closure([(1, 0, 2)], 3) == [(0, 1, 2), (1, 0, 2)]
    assert _closure([(1, 2, 0)], 3) == [(0, 1, 2), (1, 2, 0), (2, 0, 1)]
    assert _closure([(1, 0, 2), (0, 2, 1), (0, 1, 2)], 3) == [(0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1),
                                                                 (2, 1, 0)]


def test_a_census_reads_as_its_json():
    found = Census(13, 6, {"521/0": 13}, {"521/0": 6})
    assert found["displacement"] == 13 and found["rotation"] == 6 and found["by_code"] == {"521/0": 13}


# ------------------------------------------------------------------ the size estimate, from counts given to it
#: (displacement, rotation, CPU seconds) per size, as the estimate would count them (1-DOF, the true counts)
_COUNTS = {3: (1, 1, 1e-4), 4: (3, 2, 1e-4), 5: (13, 6, 1e-4), 6: (81, 27, 8.1e-3), 7: (647, 152, 6.47e-3),
           8: (6360, 1070, 1e4)}


@pytest.fixture
def counted(monkeypatch):
    """The exact counts below ``links`` handed to the estimate; census itself must not run."""
    def given(*sizes):
        for m in sizes:
            monkeypatch.setitem(enumeration._CALIBRATED, (1, m), _COUNTS[m])

    def refuse(*args, **kwargs):
        raise AssertionError(f"census{args} was run")

    monkeypatch.setattr(enumeration, "census", refuse)
    return given


def test_the_estimate_extrapolates_the_growth_ratio(counted):
    """Counts 3, 13, 81 at 4, 5, 6 links: r = 81/13, r grows by 81/13 − 13/3 a link, so 7 links have
    81·(2·81/13 − 13/3) trains; the time is that times the CPU time a train at 6 links (8.1 ms / 81)."""
    counted(3, 4, 5, 6)
    e = estimate_trains(1, 7)
    count = 81 * (2 * 81 / 13 - 13 / 3)
    assert e.chains == pytest.approx(count, rel=1e-12) and e.seconds == pytest.approx(count * 1e-4, rel=1e-12)
    assert e.units == 59 and e.basis == "exact counts at 4, 5, 6 links"
    assert (e.log10_chains, e.log10_units, e.log10_seconds) == pytest.approx(
        (math.log10(count), math.log10(59), math.log10(count * 1e-4)))
    rotation = estimate_trains(1, 7, "rotation")  # 2, 6, 27: r = 4.5 growing by 1.5; times the 81/27 of 6 links
    assert rotation.chains == pytest.approx(27 * 6.0) and rotation.seconds == pytest.approx(27 * 6.0 * 81 / 27 * 1e-4)


def test_the_estimate_stops_counting_within_its_budget(counted):
    """With 6 links counted, 7 links would take about 81²/13 times 0.1 ms: more than a budget of 0.05 s leaves, so
    8 links are extrapolated from 4, 5, 6 in two steps (census is never called)."""
    counted(3, 4, 5, 6)
    e = estimate_trains(1, 8, budget=0.05)
    r, step = 81 / 13, 81 / 13 - 13 / 3
    assert e.chains == pytest.approx(81 * (r + step) * (r + 2 * step)) and e.units == 165
    assert e.basis == "exact counts at 4, 5, 6 links"


def test_a_falling_growth_ratio_is_not_extrapolated_down(counted, monkeypatch):
    """Counts 10, 40, 100: the ratio falls from 4 to 2.5; the next ratio is taken as 2.5, not lower."""
    monkeypatch.setitem(enumeration._CALIBRATED, (1, 3), (0, 0, 1e-4))
    for m, d in ((4, 10), (5, 40), (6, 100)):
        monkeypatch.setitem(enumeration._CALIBRATED, (1, m), (d, d, 1e-3))
    assert estimate_trains(1, 7).chains == pytest.approx(250)


def test_too_few_counts_give_no_estimate(counted, monkeypatch):
    """Trains at two sizes below 6 links only (none at 3): no extrapolation, None."""
    for m, d in ((3, 0), (4, 60), (5, 600)):
        monkeypatch.setitem(enumeration._CALIBRATED, (1, m), (d, d, 1e-4))
    assert estimate_trains(1, 6) is None


def test_the_size_check_in_words(counted, monkeypatch):
    """9 links from the counts at 6, 7, 8 (10 s a train at 8 links): about 74 236 trains, 32.4 hours: refused
    on one worker, a note on two; a table of more rows than allowed is refused even with force."""
    counted(3, 4, 5, 6, 7, 8)
    count = 6360 * (2 * 6360 / 647 - 647 / 81)
    assert round(count) == 74236 and count * 10000 / 6360 / 3600 == pytest.approx(32.42, abs=0.01)
    size = ("about 74 236 displacement graphs from 496 link–axis trees, about {} on {} (extrapolated from the exact "
            "counts at 6, 7, 8 links)")
    with pytest.raises(QueryTooLarge) as refused:
        size_check_trains(1, 9)
    assert str(refused.value) == ("this query (9 links) is too large to run unasked: " + size.format("32.4 h", "1 worker")
                                  + "; give force=True to run it anyway")
    assert refused.value.text(flag).endswith("; give --force to run it anyway")
    assert size_check_trains(1, 9, processes=2) == "a long query: " + size.format("16.2 h", "2 workers")
    assert size_check_trains(1, 9, force=True) == "a long query: " + size.format("32.4 h", "1 worker")
    import synth.synthesis.estimate as estimate

    monkeypatch.setattr(estimate, "TABLE_ROWS", 70000)
    with pytest.raises(QueryTooLarge) as refused:
        size_check_trains(1, 9, table=True, force=True)
    assert str(refused.value) == ("a table is held in memory to align it and this listing (9 links) is too large for one ("
                                  + size.format("32.4 h", "1 worker") + "); use format=jsonl or csv (streamed), or count=True")
    assert size_check_trains(1, 8) is None  # below the sized links: no estimate at all


def test_a_size_that_cannot_be_estimated_is_refused_unless_forced(counted, monkeypatch):
    for m in range(3, 9):
        monkeypatch.setitem(enumeration._CALIBRATED, (1, m), (0, 0, 1e-4))
    with pytest.raises(QueryTooLarge) as refused:
        size_check_trains(1, 9)
    assert str(refused.value) == ("this query (9 links) is large and its size cannot be estimated (fewer than three "
                                  "smaller sizes have trains); give force=True to run it anyway")
    assert size_check_trains(1, 9, force=True) is None


def test_a_trees_census_with_its_rotation_graphs():
    """The star (frame 0, links 1, 2, 3 on axes of their own) holds one train, 1~2 and 1~3 held by the frame: its
    census names its code and its one rotation graph, under the canonical key of its triples."""
    from synth.gears.enumeration import _rotation_key, tree_census

    star = ((0, 1), (0, 2), (0, 3))
    assert tree_census(1, 4, star) == (1, {"42/0": 1}, {_rotation_key(4, [(1, 2, 0), (1, 3, 0)]): "42/0"})


@pytest.mark.parametrize("dof,links", [(1, 6), (2, 6), (1, 7)])
def test_the_census_codes_are_those_of_the_trains_lever_analogues(dof, links):
    """The census finds each code from the links' degrees (remembered per shape); the slow way builds every listed
    train's lever analogue."""
    from collections import Counter

    from synth.gears.enumeration import trains

    listed = Counter(str(t.lever_analogue().code) for t in trains(dof, links))
    assert census(dof, links).by_code == dict(sorted(listed.items()))


def test_bars_only_when_asked(monkeypatch):
    """census and count_trains show a bar of the trees on stderr only when asked, rotation graphs included."""
    asked = []
    real = enumeration._bar

    def bar(total, progress):
        asked.append(progress)
        return real(total, False)

    monkeypatch.setattr(enumeration, "_bar", bar)
    census(1, 4)
    enumeration.count_trains(1, 4, "rotation", progress=True)
    enumeration.count_trains(1, 4)
    assert asked == [False, True, False]
    with pytest.raises(InvalidOption) as refused:
        enumeration.count_trains(1, 4, "rot")
    assert str(refused.value) == "a gear train is listed by its displacement or its rotation graph, not 'rot'"


def test_the_default_budget_is_two_seconds(counted, monkeypatch):
    """With 6 links counted in 0.405 s (5 ms a train), 7 links would take 81²/13 · 5 ms = 2.5 s more: past the
    default budget of 2 s, so 8 links are extrapolated from 4, 5, 6 (census is never called)."""
    counted(3, 4, 5)
    monkeypatch.setitem(enumeration._CALIBRATED, (1, 6), (81, 27, 0.405))
    assert estimate_trains(1, 8).basis == "exact counts at 4, 5, 6 links"


def test_the_next_size_is_predicted_from_the_displacement_counts(counted):
    """7 links are predicted at 81²/13 · 0.1 ms = 0.05 s (not 81²/6 with the rotation count, 0.11 s): within a
    budget of 0.08 s, so 7 links are counted too."""
    counted(3, 4, 5, 6, 7)
    assert estimate_trains(1, 8, budget=0.08).basis == "exact counts at 5, 6, 7 links"


def test_the_budget_doubles_until_three_sizes_have_trains(counted, monkeypatch):
    """Counts 1, 10, 100 at 3, 4, 5 links.  Before 5 links only two sizes have trains: 5 links are predicted at ten
    times the 0.15 s of 4 links, within twice a budget of 1 s, so they are counted (growth 10, no change: 1 000 at
    6 links).  With three sizes counted the budget is itself again: 6 links, predicted at 5 s, are not counted
    within 3 s (10 000 at 7 links, extrapolated twice)."""
    for m, row in ((3, (1, 1, 1e-4)), (4, (10, 5, 0.15)), (5, (100, 40, 0.01))):
        monkeypatch.setitem(enumeration._CALIBRATED, (1, m), row)
    assert estimate_trains(1, 6, budget=1.0).chains == pytest.approx(1000)
    monkeypatch.setitem(enumeration._CALIBRATED, (1, 5), (100, 40, 0.5))
    assert estimate_trains(1, 7, budget=3.0).chains == pytest.approx(10000)


def test_a_query_of_exactly_the_notes_time_has_no_note(counted, monkeypatch):
    import synth.synthesis.estimate as estimate

    counted(3, 4, 5, 6, 7, 8)
    monkeypatch.setattr(estimate, "NOTE_SECONDS", estimate_trains(1, 9).seconds / 20)
    assert size_check_trains(1, 9, processes=20) is None
    assert size_check_trains(1, 9, processes=19).startswith("a long query: ")
