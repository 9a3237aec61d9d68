"""identify round trip: every chain of the 1-DOF 8- and 10-link atlases, its links renumbered at
random and written in every format, is identified back to its id and to its row in its code's
listing; the listing order is the same for any number of workers and for the whole query."""

from __future__ import annotations

import io
import json
import random

import networkx as nx
import pytest

import synth
from synth import exchange
from synth.analysis.identify import chain_id
from synth.exchange.identify import identify
from tests.load import allowed_seconds

FORMATS = ("text", "json", "graphml", "gml", "dot", "edgelist", "adjacency", "incidence")


def _rows_by_code(chains):
    """Each chain's row in its code's listing, counted in the listing of the whole query."""
    seen: dict[str, int] = {}
    rows = {}
    for chain in chains:
        seen[str(chain.code)] = seen.get(str(chain.code), 0) + 1
        rows[chain.certificate] = seen[str(chain.code)]
    return rows


def _written(chain, fmt: str) -> str:
    if fmt == "text":
        return chain.compact()
    if fmt == "json":
        return json.dumps(chain.to_dict())
    out = io.StringIO()
    exchange.write([chain], fmt, out)
    return out.getvalue()


def _link_graph_of_another_tool(chain, rng) -> str:
    """GraphML of the link graph with names another tool would use (no link/joint attributes)."""
    names = [f"body{x}" for x in rng.sample(range(100), chain.links)]
    g = nx.relabel_nodes(chain.link_graph(), dict(enumerate(names)))
    out = io.BytesIO()
    nx.write_graphml(g, out)
    return out.getvalue().decode()


@pytest.mark.parametrize("links", [8, pytest.param(10, marks=pytest.mark.slow)])  # 10: 230 chains, 12 s
def test_every_chain_comes_back_to_its_id_and_row(links):
    chains = list(synth.type_synthesis(1, links, workers=1))
    assert len(chains) == {8: 16, 10: 230}[links]
    rows = _rows_by_code(chains)
    rng = random.Random(links)
    checked = 0
    for chain in chains:
        want = (chain_id(chain.certificate), rows[chain.certificate])
        perm = list(range(chain.links))
        rng.shuffle(perm)
        renumbered = chain.relabel(perm)
        texts = [_written(renumbered, fmt) for fmt in FORMATS] + [_link_graph_of_another_tool(chain, rng)]
        sources = texts + [renumbered.to_networkx()]
        for source in sources:
            found = identify(source)
            assert (found.id, found.index) == want, (chain.compact(), source if isinstance(source, str) else "graph")
            assert found.listing == f"mechsynth chains --code {chain.code}" and found.subchains == "none"
            checked += 1
    assert checked == len(chains) * (len(FORMATS) + 2)


def test_the_listing_order_does_not_depend_on_workers_or_the_query():
    """The row of a chain is a property of the chain: the per-code listing, the whole query's
    listing and a listing on two workers give the same order."""
    one = [c.certificate for c in synth.type_synthesis(1, 10, workers=1)]
    two = [c.certificate for c in synth.type_synthesis(1, 10, workers=2)]
    assert one == two
    by_code: dict[str, list] = {}
    for c in synth.type_synthesis(1, 10, workers=1):
        by_code.setdefault(str(c.code), []).append(c.certificate)
    for code, certificates in by_code.items():
        assert [c.certificate for c in synth.type_synthesis(1, code=code, workers=1)] == certificates


def test_multiple_joints_prismatic_pairs_and_mechanisms_round_trip():
    """Formats that hold multiple joints and kinds keep them; a mechanism keeps its frame."""
    chain = synth.Chain.parse("0-1-2 2=3 3-0 0-4 4-5 5-1")
    mech = synth.Mechanism(chain, 3)
    for fmt in ("text", "json", "graphml", "gml", "dot", "edgelist", "incidence"):
        text = exchange.text_of([mech], fmt)
        (entry,) = exchange.read_text(text)
        assert entry.chain.certificate == chain.certificate and entry.frame == 3, fmt
    with pytest.raises(synth.InvalidOption, match="simple joints only"):
        exchange.text_of([chain], "adjacency")


def test_a_listing_in_graphml_is_one_document_of_every_chain(capsys):
    from mechsynth.cli import main

    assert main(["chains", "--dof", "1", "--links", "8", "--format", "graphml"]) == 0
    text = capsys.readouterr().out
    entries = exchange.read_text(text)
    assert [e.chain.certificate for e in entries] == [c.certificate for c in synth.type_synthesis(1, 8, workers=1)]
    assert text.count("<key ") == len(set(line.strip() for line in text.splitlines() if "<key " in line))


def test_the_row_is_found_unasked_up_to_the_documented_size_and_not_beyond(monkeypatch):
    """The row is found by listing the code: unasked only where listing every chain of the link
    count is estimated within INDEX_SECONDS (the bound itself included), always with index=True."""
    from synth.analysis import identify as module

    chains = list(synth.type_synthesis(1, 10, workers=1))
    chain = chains[-1]
    query, _ = module.listing_query(chain, 1, None, False)
    size = module.index_size(chain, query)  # 10 links: from the exact counts at 4, 6 and 8
    assert size is not None and size.basis == "exact counts at 4, 6, 8 links" and 0 < size.seconds
    assert 0.5 * len(chains) < size.chains < 2 * len(chains)  # an estimate of the 230 chains
    row = _rows_by_code(chains)[chain.certificate]
    monkeypatch.setattr(module, "INDEX_SECONDS", size.seconds)
    assert identify(chain).index == row
    monkeypatch.setattr(module, "INDEX_SECONDS", size.seconds * (1 - 1e-9))
    found = identify(chain)
    assert found.index is None and found.listing == f"mechsynth chains --code {chain.code}"
    assert "not computed" in found.note and f"about {round(size.chains)} chains" in found.note
    assert "(exact counts at 4, 6, 8 links)" in found.note
    assert identify(chain, index=True).index == row and identify(chain, index=False).index is None


def test_a_large_code_is_not_listed_unasked():
    """Issue 37: a 16-link chain of W = 3 listed 2.4 million chains (90 s, 1.9 GB) to find its
    row; now it is sized first and the row left out with the estimate, in seconds."""
    import time

    start = time.perf_counter()
    found = identify("0-8 0-10 0-11 1-6 1-7 1-9 2-6 2-7 2-8 3-5 3-7 3-8 4-5 4-12 4-14 5-15 6-15 9-10 9-11 12-13 13-14")
    assert (found.dof, found.loops, found.index) == (3, 6, None) and time.perf_counter() - start < allowed_seconds(30)
    assert "not computed" in found.note and "16-link chain" in found.note and "ask for its index" in found.note


def test_a_mechanism_with_an_input_link_comes_back_to_its_row_in_the_input_link_listing():
    query = synth.ChainQuery(1, 6, prismatic=(1, 1))
    listed = list(synth.mechanisms(query, input_link=True, workers=1))
    rng = random.Random(6)
    for row, mech in enumerate(listed, start=1):
        perm = list(range(mech.chain.links))
        rng.shuffle(perm)
        moved = synth.Mechanism(mech.chain.relabel(perm), perm[mech.frame], perm[mech.input_link])
        found = identify(exchange.text_of([moved], "edgelist"))
        code = f"{mech.chain.code}"
        assert found.mechanism_listing == f"mechsynth mechanisms --code {code} --dof 1 --prismatic 1 --input-link"
        assert (found.input_link, found.mechanism_certificate) == (moved.input_link, moved.certificate)
        rows_of_code = [m.certificate for m in listed if str(m.chain.code) == code]
        assert found.mechanism_index == rows_of_code.index(mech.certificate) + 1
        assert found.mechanisms_listed == len(rows_of_code)
