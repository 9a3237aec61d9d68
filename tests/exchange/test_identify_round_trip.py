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


@pytest.mark.parametrize("classes, code, loops, indexed", [
    ("3=3,5=1", "10.0.0.2/0", 4, True),     # the documented limit: 4 loops of simple joints
    ("3=4,5=1", "12.0.0.0.2/0", 5, False),  # one loop more
    ("3=2,5=1", "811/1", 3, True),          # with a multiple joint the limit is one loop lower
    ("3=3,5=1", "10.0.1.1/1", 4, False),
])
def test_a_heterogeneous_row_is_found_unasked_up_to_the_documented_loops(capsys, classes, code, loops, indexed):
    """A heterogeneous listing is not sized: identify lists it unasked up to 4 loops (3 with a multiple
    joint); each row read back names its own row number in the listing the command printed."""
    from mechsynth.cli import main

    assert main(["chains", "--dof", "1", "--loop-classes", classes, "--code", code, "--format", "jsonl"]) == 0
    rows = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    assert rows and all(r["loops"] == loops for r in rows)
    for number in sorted({1, len(rows) // 2 + 1, len(rows)}):
        found = identify(json.dumps(rows[number - 1]))
        assert found.listing == f"mechsynth chains --dof 1 --loop-classes {classes} --code {code}"
        if indexed:
            assert (found.index, found.listed, found.note) == (number, len(rows), "")
        else:
            assert (found.index, found.listed) == (None, None)
            assert found.note == (f"its place in the listing was not computed: the code has {loops} loops and its "
                                  "heterogeneous listing is built whole to find it (ask for its index to have it "
                                  "computed)")
            assert identify(json.dumps(rows[number - 1]), index=True).index == number


@pytest.mark.parametrize("text", [
    "0-1 1-2 2-3 3-4 4-5 5-0 0-6 6-3 | h2: 0 1 2 3 4 5",          # a base of a lower class than the chain's
    "0-1 1-2 2-3 3-0 | h5: 0 1 2 3",                              # no loop of the chain's own class
    "0-1 1-2 2-3 3-0 4-5 5-6 6-7 7-4 0-4 2-6 | h5: 0 1 2 3; h4: 4 5 6 7",  # three classes
])
def test_a_heterogeneous_chain_no_listing_holds_says_why(text):
    found = identify(text)
    assert (found.listing, found.index) == (None, None)
    assert found.note == ("heterogeneous chains are listed with two loop classes, a base of the higher class on a "
                          "chain of the lower one")


def test_a_heterogeneous_chain_with_a_rigid_sub_chain_is_in_the_rigid_listing(capsys):
    """Chains of K3 = 2, K5 = 1 that only --rigid-subchains lists: each is found there, at its row; one
    more joint inside its rigid sub-chain over-constrains it, and no listing holds it."""
    from mechsynth.cli import main

    def listing(*extra):
        assert main(["chains", "--dof", "1", "--loop-classes", "3=2,5=1", "--code", "640/0", "--format", "jsonl",
                     *extra]) == 0
        return [json.loads(line) for line in capsys.readouterr().out.splitlines()]

    plain = {r["certificate"] for r in listing()}
    rigid = listing("--rigid-subchains")
    only = [(number, r) for number, r in enumerate(rigid, start=1) if r["certificate"] not in plain]
    assert len(only) > 3
    for number, row in only[:: len(only) // 3]:
        found = identify(json.dumps(row))
        assert found.listing == "mechsynth chains --dof 1 --loop-classes 3=2,5=1 --code 640/0 --rigid-subchains"
        assert (found.index, found.listed, found.worst_mobility) == (number, len(rigid), 0)
    # links 0, 2, 3, 4, 5 of this chain are rigid (5 links, 6 pins: 3·4 − 2·6 = 0); a pin 2-4 makes them −2
    text = "0-2 0-4 0-5 1-2 1-6 1-9 2-3 3-4 3-5 6-7 7-8 8-9 | h5: 1 6 7 8 9"
    assert identify(text).worst_subchain == [0, 2, 3, 4, 5]
    over = identify(text.replace("2-3 ", "2-3 2-4 "))
    assert (over.listing, over.index, over.worst_mobility) == (None, None, -2)
    assert over.note == "an over-constrained chain (a sub-chain with W(S) < 0) is in no listing"


def test_a_heterogeneous_truss_is_in_the_plain_listing(capsys):
    """W = 0: the chain itself is rigid, which every truss listing allows (no --rigid-subchains)."""
    from mechsynth.cli import main

    assert main(["chains", "--dof", "0", "--loop-classes", "3=2,5=1", "--code", "702/0", "--format", "jsonl"]) == 0
    rows = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    for number, row in enumerate(rows, start=1):
        found = identify(json.dumps(row))
        assert found.listing == "mechsynth chains --dof 0 --loop-classes 3=2,5=1 --code 702/0"
        assert (found.dof, found.index, found.listed) == (0, number, len(rows))
        assert found.subchains == "none"  # judged with rigid sub-chains allowed, as a truss is


def test_a_rigid_sub_chain_or_a_gear_mesh_chooses_the_listing():
    """A rigid triangle in a 1-DOF chain: the --rigid-subchains listing, at the row that listing gives
    it; a gear mesh: no listing of type synthesis."""
    text = "0-1 1-2 2-0 0-3 3-4 4-5 5-1"
    listed = list(synth.type_synthesis(synth.ChainQuery(1, code="42/0", rigid_subchains=True), workers=1))
    found = identify(text)
    assert found.listing == "mechsynth chains --code 42/0 --rigid-subchains" and found.worst_mobility == 0
    assert listed[found.index - 1].certificate == found.certificate and found.listed == len(listed)
    gears = identify("0-1 0-2 1~2")
    assert (gears.listing, gears.index) == (None, None)
    assert gears.note == ("type synthesis lists revolute and prismatic chains, not gear meshes (gear trains are "
                          "listed by 'mechsynth gears')")


def test_the_size_of_a_mechanism_listing_counts_mechanisms():
    """A 10-link chain: its listing sized as chains (230 chains of 10 links) and, with a frame, as
    mechanisms (1 834): each estimate within a factor of two of its exact count."""
    from synth.analysis import identify as module

    chain = list(synth.type_synthesis(1, 10, workers=1))[-1]
    query, _ = module.listing_query(chain, 1, None, False)
    assert 115 < module.index_size(chain, query).chains < 460
    assert 917 < module.index_size(chain, query, mechanisms=True).chains < 3668
