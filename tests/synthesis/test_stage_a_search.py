"""Stage A of a code of few branch vertices runs a plain search instead of the CP-SAT model: the same
branch multigraphs, with the same first representative of each class in the same order, for every
code that the queries of benchmarks/bycode.py (163 queries: every h, W, open chains, multiple joints,
prismatic skeletons, conventions) hand to the model."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from synth import ChainQuery, SynthesisError
from synth.synthesis import stage_a
from synth.synthesis.stage_a import Conventions, _branch_vertices, _contracted_by_model, _contracted_by_search
from synth.synthesis.type_synthesis import plan_jobs
from synth.structure.code import Code

ROOT = Path(__file__).resolve().parents[2]


def _model_jobs():
    """(code, conventions) of every stage A the bycode queries run by the model or the search."""
    sys.path.insert(0, str(ROOT / "benchmarks"))
    try:
        from bycode import QUERIES
    finally:
        sys.path.remove(str(ROOT / "benchmarks"))
    jobs = {}
    for q in QUERIES:
        options = dict(q)
        try:
            planned = plan_jobs(ChainQuery.of(options.pop("dof"), options.pop("links"), **options))
        except SynthesisError:
            continue  # a size no chain has
        for code, conv in planned:
            if _branch_vertices(code) and not (stage_a.uses_kernel(code, conv) and stage_a._stage_a_kernel_applies(code, conv)):
                jobs[code, conv] = None
    return list(jobs)


def _same_both_ways(jobs) -> int:
    graphs = 0
    for code, conv in jobs:
        searched = _contracted_by_search(code, conv)
        assert searched == _contracted_by_model(code, conv), (str(code), conv)
        graphs += len(searched)
    return graphs


def test_the_search_finds_what_the_model_finds_for_the_codes_of_the_benchmark_queries():
    """Every code of up to 7 branch vertices (1 365 codes, 20 461 H; those of 5 loops or more with multiple
    joints go to the kernel)."""
    jobs = [job for job in _model_jobs() if len(_branch_vertices(job[0])) <= 7]
    assert len(jobs) > 1300
    assert _same_both_ways(jobs) > 5000


@pytest.mark.slow
def test_the_search_finds_what_the_model_finds_for_every_code_it_runs():
    """… and every code the search runs (8 branch vertices too: 1 420 codes)."""
    jobs = [job for job in _model_jobs() if stage_a._searched(*job)]
    assert len(jobs) > 1400
    assert _same_both_ways(jobs) > 5000


@pytest.mark.parametrize("code, conv", [
    ("48000/0", Conventions()), ("4.10.0/0", Conventions()),
    ("6301/0", Conventions(fractionated=False)), ("6301/0", Conventions(planar_only=True)),
    ("740/0", Conventions(h=4)), ("821/0", Conventions(h=4)), ("2|5/2", Conventions()),
])
def test_the_search_and_the_model_on_codes_the_queries_do_not_reach(code, conv):
    """Larger or other codes than the benchmark's, whatever the policy chooses for them."""
    code = Code.parse(code)
    assert _contracted_by_search(code, conv) == _contracted_by_model(code, conv)


def test_a_count_of_12_links_loads_no_solver(tmp_path):
    """The main query, with an empty store of solver results, never imports OR-Tools."""
    probe = ("import sys, synth; c = synth.count_chains(1, 12, workers=1); "
             "print(c['count'], any(m.startswith('ortools') for m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", probe], cwd=ROOT, capture_output=True, text=True, timeout=300,
                         env={"MECHSYNTH_CACHE": str(tmp_path), "PATH": "/usr/bin:/bin"})
    assert out.stdout.split() == ["6856", "False"], out
