"""Number synthesis lists small problems directly, without CP-SAT: the same codes as the CP-SAT
model, problem by problem, for every query the project states (the benchmarks' queries by code, the
scenes, the README's and the docs' ``codes`` commands) and for a grid of options around them."""

from __future__ import annotations

import dataclasses
import itertools
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

import synth.synthesis.number_synthesis as ns
from synth import ChainQuery, SynthesisError, number_synthesis
from synth.synthesis.number_synthesis import _direct_codes, _solve_model, make_problem

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture
def problems(monkeypatch):
    """Every problem number synthesis solves while the test runs, by its repr."""
    seen: dict[str, ns.Problem] = {}
    solve = ns._solve

    def recorded(problem, tick=None):
        seen[repr(problem)] = problem
        return solve(problem, tick)

    monkeypatch.setattr(ns, "_solve", recorded)
    return seen


def _same_both_ways(problems) -> int:
    """The direct listing and the model agree on every problem; the codes compared."""
    compared = 0
    for problem in problems:
        direct = list(_direct_codes(problem))
        assert len(direct) == len(set(direct)), problem  # each code once
        assert set(direct) == set(_solve_model(problem)), problem
        compared += len(direct)
    return compared


def test_every_query_of_the_benchmarks_by_code(problems):
    """The 163 queries whose counts by code benchmarks/bycode.py keeps, through the planning of
    type synthesis (joint compositions, multiplicity limits, open chains, prismatic skeletons)."""
    sys.path.insert(0, str(ROOT / "benchmarks"))
    try:
        from bycode import QUERIES
    finally:
        sys.path.remove(str(ROOT / "benchmarks"))
    from synth.synthesis.type_synthesis import plan_jobs

    for q in QUERIES:
        options = dict(q)
        try:
            plan_jobs(ChainQuery.of(options.pop("dof"), options.pop("links"), **options))
        except SynthesisError:
            pass  # a size no chain has (an odd count of links where h − 1 = 2 …): no problem solved
    assert len(QUERIES) == 163 and len(problems) > 100
    assert _same_both_ways(problems.values()) > 2000


def _documented_codes_commands() -> list[list[str]]:
    """The arguments of every ``mechsynth codes …`` line in README.md and docs/*.md."""
    commands = []
    for path in [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]:
        for line in path.read_text().splitlines():
            m = re.match(r"\s*(?:\$ )?mechsynth codes (.*)", line)
            if m:
                words = shlex.split(m.group(1).split(" #")[0])
                commands.append(["codes", *[w for w in words if not w.startswith(">")]])
    return commands


def test_every_documented_codes_command(problems, capsys):
    from mechsynth.cli import main

    commands = _documented_codes_commands()
    assert len(commands) >= 6
    for argv in commands:
        main(argv)
    capsys.readouterr()
    assert len(problems) >= 10
    _same_both_ways(problems.values())


def test_every_scene_that_lists_codes(problems):
    from mechsynth.scene import load_scene, run_scene

    scenes = [p for p in sorted((ROOT / "models").glob("*.toml")) if re.search(r'compute\s*=.*"codes"', p.read_text())]
    assert len(scenes) >= 10
    for path in scenes:
        scene = load_scene(path)
        run_scene(dataclasses.replace(scene, compute=("codes",), expect={}))
    _same_both_ways(problems.values())


_GRID = [dict(dof=dof, loops=k) for dof in range(6) for k in range(1, 7)] + [
    dict(dof=dof, loops=k, compositions=True, **extra)
    for dof in (0, 1, 3) for k in range(1, 6) for extra in ({}, {"max_multiplicity": 3}, {"max_multiplicity": 2})
] + [
    dict(dof=dof, loops=k, n1=n1, compositions=c)
    for dof in (1, 2, 4) for k in (0, 1, 2, 3, 4) for n1 in ("0..3", "1..4", "2") for c in (False, True)
] + [
    dict(dof=1, loops=k, h=h) for h in (1, 2, 4, 5, 6) for k in (1, 2, 3, 4)
] + [
    dict(dof=1, loops=k, f=f) for f in (1, 2) for k in (2, 3, 4)
] + [
    dict(dof=1, loops=4, require=r, max_link_degree=d, v=v)
    for r, d, v in itertools.product((None, ["5=1.."], ["2=..3"], ["3=2..4", "4=0"], ["1=0"]),
                                     (None, "K+W", 3, 7), (None, "0", "1..3", "4.."))
] + [
    dict(dof=1, loop_classes={3: 4, 5: 1}, v=6), dict(dof=1, loop_classes={3: 1, 5: 1}),
    dict(dof=2, loop_classes={2: 2, 3: 2}, compositions=True), dict(dof=0, links=9, v="0..3"),
]


def test_a_grid_of_options_around_them():
    """W 0…5, K up to 6, every h, f, open chains, compositions and multiplicity limits,
    requirements with both ends, link-degree bounds and ranges of v."""
    compared, solved = 0, 0
    for options in _GRID:
        try:
            problem = make_problem(**options)
        except SynthesisError:
            continue  # an impossible combination (a requirement above the degree bound …)
        compared += _same_both_ways([problem])
        solved += 1
    assert solved > 250 and compared > 2000


def test_a_problem_beyond_the_direct_listing_goes_to_the_model(monkeypatch):
    """Above the bound the model lists the codes (and a run reads none from the direct listing)."""
    monkeypatch.setattr(ns, "_DIRECT_CODES", 10)
    monkeypatch.setattr(ns, "_direct_codes", lambda problem: pytest.fail("listed directly"))
    assert [str(c) for c in number_synthesis(1, loops=4, require=["5=1.."])] == [
        "6301/0", "7111/0", "8002/0", "7201/1", "8011/1", "8101/2", "9001/3"]


def test_a_query_of_codes_loads_no_solver():
    """Table 1 (K = 1 … 5) and the 12-link problem of the main query are listed without OR-Tools."""
    code = ("import sys, synth; c = synth.number_synthesis(1, loops='1..5'); d = synth.number_synthesis(1, links=12, "
            "compositions=True); print(len(c), len(d), any(m.startswith('ortools') for m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=120,
                         env={"MECHSYNTH_CACHE": "off", "PATH": "/usr/bin:/bin"})
    assert out.stdout.split() == ["89", str(len(number_synthesis(1, links=12, compositions=True))), "False"], out
