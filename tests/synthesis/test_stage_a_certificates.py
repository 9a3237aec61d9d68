"""Stage A's nauty graphs are built without pynauty's per-vertex checks (PROFILE.md §29): the certificates
and automorphism groups of H are those of the checked ``pynauty.Graph`` on every H of codes with simple
and multiple joints, open chains and the plane motion space, and the stream of a count never runs the checks."""

from __future__ import annotations

import pynauty
import pytest

from synth.structure.code import Code
from synth.synthesis import stage_a
from synth.synthesis.stage_a import Contracted, Conventions, contracted_graphs, contracted_stream
from synth.synthesis.type_synthesis import plan_jobs
from synth import ChainQuery


def _checked(graph: pynauty.Graph) -> pynauty.Graph:
    """The same graph through pynauty's own constructor (with its checks)."""
    return pynauty.Graph(graph.number_of_vertices, adjacency_dict=graph.adjacency_dict,
                         vertex_coloring=graph.vertex_coloring)


def _jobs():
    jobs = plan_jobs(ChainQuery(1, 12))[:6]                      # simple joints (kernel's search and model)
    jobs += plan_jobs(ChainQuery(1, 10, v=(1, 3)))[:6]            # multiple joints
    jobs += plan_jobs(ChainQuery(4, 7, n1=2, v=2))                # an open chain: single-joint links
    jobs += plan_jobs(ChainQuery(1, 9, h=2))[:4]                  # the plane motion space
    return jobs


@pytest.mark.parametrize("code, conv", _jobs(), ids=lambda x: str(x) if isinstance(x, Code) else "")
def test_every_H_has_the_checked_graphs_certificate_and_group(code, conv):
    graphs = contracted_graphs(code, conv)
    assert graphs or not stage_a._branch_vertices(code)
    for H in graphs:
        fast = H._subdivided()
        assert pynauty.certificate(fast).hex() == pynauty.certificate(_checked(fast)).hex() == H.certificate
        assert pynauty.autgrp(fast) == pynauty.autgrp(_checked(fast))


def test_the_bundle_group_is_the_checked_graphs():
    H = Contracted((stage_a.Vertex(stage_a.LINK, 4),) * 2 + (stage_a.Vertex(stage_a.LINK, 3),) * 2,
                   ((0, 1), (0, 1), (0, 2), (1, 3), (2, 3), (2, 3)), "")
    seen = []
    real = stage_a._listed_group
    try:
        stage_a._listed_group = lambda graph, m, e: seen.append(graph) or real(graph, m, e)
        fast = H.bundle_group()
    finally:
        stage_a._listed_group = real
    [graph] = seen
    assert fast == real(_checked(graph), 4, graph.number_of_vertices - 4)
    assert fast[0]  # (the swap of the two 4-joint links with the two 3-joint ones: not trivial)


def test_the_stream_of_a_count_runs_no_pynauty_check(monkeypatch):
    def refuse(*_):
        raise AssertionError("pynauty's checks ran")

    code, conv = Code.parse("662000/0"), Conventions()
    expected = sorted(g.certificate for g in contracted_graphs(code, conv))
    monkeypatch.setattr(pynauty.Graph, "set_adjacency_dict", refuse)
    monkeypatch.setattr(pynauty.Graph, "set_vertex_coloring", refuse)
    assert sorted(g.certificate for g in contracted_stream(code, conv)) == expected
    assert len(expected) == 215
