"""The second count of issue 41 (``--method tight-reverse``, :func:`synth.synthesis.stage_b.count_reversed`):
the counting programme over the bundles of parallel strings in the reverse of the first count's order,
Burnside's lemma over the bundle group read off nauty's group of H on its strings, each bundle's ways
listed — against the first count (the kernel forced on every code, so that it is the programme too),
unit by unit on the 13 queries of the programme's own tests; each check shown able to fail (a fault
put into either count is caught by the other); the command line, its refusals and its checkpoint.

Faults put by hand into the compiled kernel (numba: not patchable from a test), each caught by the
comparison of the two counts on every unit of 10 and 12 links (1-DOF), 11 links h = 4, 9 links W = 0
and 12 links W = 3 (220 units), or of 7 links h = 2, 8 links h = 2 W = 0 and 9 links W = 2 rigid:

* first count only, ``_bundle_deficits`` letting a bundle's deficits rise by one
  (``min(v + 1, C − lows[x])``): 98 of 220 units differ;
* shared programme ``tight_count``, the floor raised two levels too high (``+ 1`` for ``− 1``):
  4 units of 9 links W = 0 differ (the order of the bundles changes which states it merges);
* second count only, each bundle's least weights without the parallel strings' (two empty
  parallel strings allowed): no unit differs where h + threshold > 2 (the pair's rule refuses them
  anyway), 90 of 117 units differ at 6 links h = 2 W = 0 (hence that query below), 8 057 of 11 469
  at 8 links.
"""

from __future__ import annotations

import numpy as np
import pytest

import synth
from synth.synthesis import stage_a, stage_b

from .test_count_search import QUERIES, _ids


@pytest.fixture
def kernel_everywhere(monkeypatch):
    monkeypatch.setattr(stage_a, "_KERNEL_LOOPS", {None: 0})


def _units(query):
    return [(u.key, (u.code, u.contracted, u.conventions)) for u in synth.plan_units(**query, workers=1)
            if u.contracted is not None]


def _both(query, stats=None):
    """Per unit of ``query``: its key, the first count's and the second's."""
    return [(key, stage_b.count_realised(*args), stage_b.count_reversed(*args, stats)) for key, args in _units(query)]


# the 13 queries, and W = 0 in the plane of wedges (h = 2), where h + threshold = 2: only the bundles'
# least weights keep two parallel strings from both being empty
@pytest.mark.parametrize("query", QUERIES + [dict(dof=0, links=6, h=2)], ids=_ids)
def test_the_second_count_equals_the_first_on_every_unit(query, kernel_everywhere):
    """Unit by unit, the same count; no unit of the 13 queries counted as the first count counts it
    (every one by the reversed programme or by orbits; at W = 0, h = 2, the few the kernel does not
    take), and the programme counts units wherever the first does."""
    stats = {}
    pairs = _both(query, stats)
    assert pairs
    assert [(key, first) for key, first, _ in pairs] == [(key, second) for key, _, second in pairs]
    assert stats.get("shared", 0) == 0 if query in QUERIES else stats.get("shared", 0) < stats["reversed"] / 4
    if query.get("fractionated", True) and not query.get("rigid_subchains"):  # (else every unit may carry excess)
        assert stats["reversed"] and any(first > 1 for _, first, _ in pairs)


def test_the_second_count_meets_automorphisms_and_bundles():
    """The 12-link units the comparison passes through include units with several permutations of
    the bundles and bundles of several strings, so both of its changes are at work."""
    units = _units(dict(dof=1, links=12))
    assert sum(len(stage_b._bundle_closure(g)) > 2 for _, (_, g, _) in units) > 10
    assert sum(not stage_b._bundle_starts(g.edges).all() for _, (_, g, _) in units) > 10


@pytest.mark.parametrize("C", [1, 2, 3, 4, 5])
def test_the_bundles_ways_listed_equal_the_kernels_programme(C):
    """Every bundle of one to five strings, the least weight of each string 0 … C + 1 (non-decreasing
    after the first), an excess bound of 0 … 2, strings the game sees or not, the links brought in one class
    or three (multiple joints): the ways listed from the weights and the kernel's programme over the deficits,
    excess and links."""
    from itertools import product

    from synth.synthesis._stage_b_kernel import _bundle_deficits

    checked = 0
    for r in range(1, 6 if C < 4 else 5):
        for lows in product(range(C + 2), repeat=r):
            if list(lows[1:]) != sorted(lows[1:]):
                continue
            for x_most, game, classes in product(range(3), (True, False), (1, 3)):
                ways = np.zeros((C * r + 1, x_most + 1, classes), dtype=np.int64)
                _bundle_deficits(C, np.array(lows, dtype=np.int64), game, x_most, ways)
                listed = stage_b._bundle_ways(C, lows, x_most, game, classes)
                assert listed == tuple(tuple(map(tuple, row)) for row in ways.tolist()), (C, lows, classes)
                checked += 1
    assert checked > 30


@pytest.mark.parametrize("dof, links", [(1, 12), (2, 11), (0, 9)])
def test_the_closed_bundle_group_is_nautys_bundle_group(dof, links):
    """On every unit: the permutations of the bundles closed from nauty's group of H on its strings
    are the identity and those nauty lists for H with one vertex per bundle."""
    for key, (_, graph, _) in _units(dict(dof=dof, links=links)):
        perms, whole = graph.bundle_group()
        assert whole
        identity = [list(range(len(stage_b._bundle_closure(graph)[0])))]
        assert stage_b._bundle_closure(graph).tolist() == sorted(identity + [list(p) for p in perms]), key


def test_a_group_too_large_to_list_is_counted_as_the_first_count_does(monkeypatch):
    """Where the bundle group has more elements than are listed (forced: at most one), the unit is
    counted by orbits or as the first count does, and says so; the counts stay."""
    want = [first for _, first, _ in _both(dict(dof=1, links=10))]
    monkeypatch.setattr(stage_a, "_GROUP_LIMIT", 1)
    stats = {}
    assert [second for _, _, second in _both(dict(dof=1, links=10), stats)] == want
    assert stats.get("shared", 0) + stats.get("by_orbits", 0) > 0


def test_a_fault_in_the_second_count_is_caught_by_the_first(monkeypatch, kernel_everywhere):
    """A bundle's ways miscounted in the second count (its all-long weights left out) changes the
    count of some 12-link unit, which the first count then contradicts."""
    listed = stage_b._bundle_ways.__wrapped__

    def wrong(C, lows, x_most=0, game=True, classes=1):
        ways = [[list(z) for z in row] for row in listed(C, lows, x_most, game, classes)]
        ways[0][0][0] -= len(lows) > 1  # a bundle of parallel strings loses the placement with every string long
        return tuple(tuple(map(tuple, row)) for row in ways)

    monkeypatch.setattr(stage_b, "_bundle_ways", wrong)
    assert any(first != second for _, first, second in _both(dict(dof=1, links=12)))


def test_a_fault_in_the_first_count_is_caught_by_the_second(monkeypatch, kernel_everywhere):
    """nauty's bundle group losing a permutation in the first count (its last one left out, and the
    inverse with it where that is another) changes or stops the first count of some 12-link unit;
    the second count, which reads the group off the strings, contradicts it."""
    real = stage_a.Contracted.bundle_group

    def short(self):
        perms, whole = real(self)
        if perms:
            last = perms[-1]
            inverse = tuple(np.argsort(last).tolist())
            perms = [p for p in perms if p not in (last, inverse)]
        return perms, whole

    monkeypatch.setattr(stage_a.Contracted, "bundle_group", short)
    differ = 0
    for key, args in _units(dict(dof=1, links=12)):
        second = stage_b.count_reversed(*args)
        try:
            differ += stage_b.count_realised(*args) != second
        except RuntimeError:  # Burnside's sum not a multiple: the first count stops
            differ += 1
    assert differ


@pytest.mark.parametrize("links", [6, 8, 10])
def test_the_command_counts_by_the_second_method_as_by_the_first(capsys, links):
    import json

    from mechsynth.cli import main

    got = []
    for method in ("listing", "tight-reverse"):
        assert main(["chains", "--dof", "1", "--links", str(links), "--count", "--workers", "1",
                     "--method", method]) == 0
        got.append(json.loads(capsys.readouterr().out))
    assert got[0] == got[1] and got[0]["count"] == {6: 2, 8: 16, 10: 230}[links]


@pytest.mark.parametrize("argv", [["--dof", "1", "--links", "10", "--v", "0..8"], ["--dof", "2", "--links", "9", "--v", "1.."],
                                  ["--dof", "0", "--links", "9", "--v", "0..7"]])
def test_the_command_counts_multiple_joints_by_the_second_method_as_by_the_first(capsys, argv):
    """With multiple joints the second count runs the programme with the exact rule (or counts by orbits) and
    gives every code the count of the first."""
    import json

    from mechsynth.cli import main

    got = []
    for method in ("listing", "tight-reverse"):
        assert main(["chains", *argv, "--count", "--workers", "1", "--method", method]) == 0
        got.append(json.loads(capsys.readouterr().out))
    assert got[0] == got[1] and got[0]["count"] > 0


@pytest.mark.parametrize("argv, words", [
    (["--dof", "1", "--links", "8", "--prismatic", "0..2"], "prismatic"),
    (["--dof", "1", "--links", "8", "--cranks", "2=2"], "crank")])
def test_the_command_refuses_what_the_second_count_does_not_cover(capsys, argv, words):
    from mechsynth.cli import main

    assert main(["chains", *argv, "--count", "--method", "tight-reverse"]) == 2
    err = capsys.readouterr().err
    assert words in err and "tight-reverse" in err and err.count("\n") == 1


def test_the_second_count_keeps_its_own_checkpoint(tmp_path):
    """A checkpoint of the first count is refused to the second and the second's to the first (the
    plan identity differs); benchmarks/checkpoints.py reads the second's and compares the two code by
    code; the second resumes from its own."""
    import json
    import subprocess
    import sys
    from pathlib import Path

    first, second = tmp_path / "first.sqlite", tmp_path / "second.sqlite"
    assert synth.count_chains(1, 10, workers=1, checkpoint=first).count == 230
    assert synth.count_chains(1, 10, workers=1, checkpoint=second, method="tight-reverse").count == 230
    script = Path(__file__).resolve().parents[2] / "benchmarks" / "checkpoints.py"
    run = [subprocess.run([sys.executable, str(script), *args], capture_output=True, text=True, timeout=300)
           for args in (["status", str(second)], ["compare", str(first), str(second)])]
    assert [r.returncode for r in run] == [0, 0], [r.stderr for r in run]
    assert json.loads(run[0].stdout)["codes_in_plan"] == 7
    found = json.loads(run[1].stdout)
    assert found["verdict"] == "equal" and found["codes_equal"] == 7 and found["chains_compared"] == 230
    with pytest.raises(synth.SynthesisError, match="belongs to another query"):
        synth.count_chains(1, 10, workers=1, checkpoint=first, method="tight-reverse")
    with pytest.raises(synth.SynthesisError, match="belongs to another query"):
        synth.count_chains(1, 10, workers=1, checkpoint=second)
    assert synth.count_chains(1, 10, workers=1, checkpoint=second, method="tight-reverse").count == 230


def test_the_units_the_second_count_shares_with_the_first_are_said(tmp_path, capsys):
    """At W = 0 in the plane of wedges (6 links, h = 2) some units are neither tight nor countable by
    orbits, and the second count counts them by the first count's own path: the result, the command's
    stderr, the checkpoint and benchmarks/checkpoints.py's comparison say how many (it was silent),
    the same number as the units' own figures."""
    import json
    import sqlite3
    import subprocess
    import sys
    from pathlib import Path

    from mechsynth.cli import main
    from synth.execution.checkpoint import read_checkpoint

    query = dict(dof=0, links=6, h=2)
    stats: dict = {}
    for _, args in _units(query):
        stage_b.count_reversed(*args, stats)
    shared = stats["shared"]
    assert 0 < shared < len(_units(query))
    second = synth.count_chains(**query, workers=1, method="tight-reverse", checkpoint=tmp_path / "second.sqlite")
    first = synth.count_chains(**query, workers=1, checkpoint=tmp_path / "first.sqlite")
    assert (first.shared_units, second.shared_units, first.shared_note) == (0, shared, None)
    assert second.shared_note.startswith(f"{shared} of the {second.units_run} units run were counted by the first count's")
    assert read_checkpoint(tmp_path / "second.sqlite").shared_units == shared
    assert main(["chains", "--dof", "0", "--links", "6", "--h", "2", "--count", "--workers", "1", "--force",
                 "--method", "tight-reverse"]) == 0
    assert f"mechsynth: {second.shared_note}\n" in capsys.readouterr().err
    script = Path(__file__).resolve().parents[2] / "benchmarks" / "checkpoints.py"
    done = subprocess.run([sys.executable, str(script), "compare", str(tmp_path / "first.sqlite"),
                           str(tmp_path / "second.sqlite")], capture_output=True, text=True, timeout=300)
    found = json.loads(done.stdout)
    assert found["verdict"] == "equal" and found["shared_path_units"] == {"a": 0, "b": shared}
    # a checkpoint written before the units were recorded is still read (as 0)
    with sqlite3.connect(tmp_path / "second.sqlite") as conn:
        conn.execute("DROP TABLE shared_units")
    assert read_checkpoint(tmp_path / "second.sqlite").shared_units == 0
