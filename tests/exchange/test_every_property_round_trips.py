"""Every format a command writes carries every property of a chain — its motion space h, its joint
kinds, its multiple joints, a mechanism's frame and input link — and every reader gives it back:
``read``/``identify``/``compare`` for files, ``analyze``/``draw --chain``/``chains --chain``
(:func:`synth.exchange.read_chain`) for a chain on the command line (issue 37, item 7).

Where a format cannot hold a property (an adjacency matrix holds no multiple joint), the writer
refuses the chain; a source that states no h is read in the plane unless told, and a source that
states another h than ``--h`` is refused — never a silent planar default."""

from __future__ import annotations

import json

import pytest

import synth
from mechsynth.cli import main
from mechsynth.commands.chains import write_items
from synth import Chain, Mechanism, MalformedChain
from synth.analysis.identify import chain_id
from synth.exchange.identify import identify
from synth.exchange import WRITTEN, in_motion_space, read_chain, read_text


def _first(h: int, dof: int = 1, loops: int = 2):
    """The first chain type synthesis lists in motion space h (K loops, W = dof)."""
    return next(iter(synth.type_synthesis(synth.ChainQuery(dof, dof + 1 + (h - 1) * loops, h=h), workers=1)))


WATT = Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")
CHAINS = {
    **{f"h = {h}": _first(h) for h in (2, 4, 5, 6)},
    "watt (h = 3)": WATT,
    "slider-crank": Chain.parse("0-1 1=2 2-3 3-0"),
    "wedge loop": Chain.parse("0=1 1=2 2=3 3=0"),
    "gear mesh": Chain.parse("0-1 0-2 1~2"),
    "double joint": Chain.parse("0-1-2 2-3 3-0 0-4 4-5 5-1"),
    "double joint and slider": Chain.parse("0-1-2 2=3 3-0 0-4 4-5 5-1"),
    "open chain": Chain.parse("0-1 1-2 2-3 3-0 3-4"),
    "h = 5 open chain": Chain(7, Chain.parse("0-1 1-2 2-3 3-4 4-5 5-0 5-6").joints, h=5),
}
MECHANISMS = {
    "watt I": Mechanism(WATT, 3),
    "four-bar with input": Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0, 1),
    "slider-crank with input": Mechanism(CHAINS["slider-crank"], 0, 1),
    "bricard with input": Mechanism(Chain(6, Chain.parse("0-1 1-2 2-3 3-4 4-5 5-0").joints, h=5), 2, 3),
}
ITEMS = {**CHAINS, **MECHANISMS}


def _chain(item) -> Chain:
    return item.chain if isinstance(item, Mechanism) else item


def _listing(item, fmt: str, capsys) -> str:
    """What ``chains``/``mechanisms --format FMT`` print for this one item."""
    chain = _chain(item)
    what = "mechanisms" if isinstance(item, Mechanism) else "chains"
    assert write_items([item], what, fmt=fmt, kinds=not chain.all_revolute, h=chain.h) == 0
    return capsys.readouterr().out


def _written(item, fmt: str, capsys) -> str | None:
    """The item in a format, as a command writes it; None where the format refuses it."""
    if fmt in ("jsonl", "json", "csv", "table") + WRITTEN:
        if fmt == "adjacency" and any(len(j) > 2 for j in _chain(item).joints):
            with pytest.raises(synth.InvalidOption, match="simple joints only"):
                _listing(item, fmt, capsys)
            return None
        return _listing(item, fmt, capsys)
    return synth.exchange.text_of([item], fmt)  # text: the joint list with its settings comment


FORMATS = ("text", "jsonl", "json", "csv", "table") + WRITTEN


def _same(entry, item, fmt):
    chain = _chain(item)
    assert entry.chain.certificate == chain.certificate, (fmt, entry.chain, chain)
    assert entry.chain.h == chain.h and entry.chain.kinds == chain.kinds and entry.chain.joints == chain.joints, fmt
    # every format states h; a planar joint list leaves it out (a joint list is planar unless told)
    assert entry.h == chain.h or (fmt == "text" and chain.h == 3 and entry.h is None), f"{fmt} does not state h"
    if isinstance(item, Mechanism):
        assert entry.item.certificate == item.certificate, fmt
        assert (entry.frame, entry.input_link) == (item.frame, item.input_link), fmt
    else:
        assert entry.frame is None and entry.input_link is None, fmt


@pytest.mark.parametrize("name", ITEMS)
def test_every_format_carries_every_property_and_every_reader_gives_it_back(name, capsys):
    item = ITEMS[name]
    chain = _chain(item)
    checked = 0
    for fmt in FORMATS:
        text = _written(item, fmt, capsys)
        if text is None:
            continue
        (entry,) = read_text(text)  # the format told from the text, as identify and compare do
        _same(entry, item, fmt)
        found = identify(text, index=False)
        assert (found.id, found.h, found.certificate) == (chain_id(chain.certificate), chain.h, chain.certificate), fmt
        if isinstance(item, Mechanism):
            assert found.mechanism_certificate == item.certificate, fmt
        if fmt in ("text", "jsonl"):  # what a command line holds: analyze, draw --chain, chains --chain
            given = read_chain(text.strip())
            _same(given, item, fmt)
            analysed = synth.analyze_chain(given.chain)
            assert (analysed.h, analysed.dof, analysed.certificate) == (chain.h, found.dof, chain.certificate), fmt
        checked += 1
    assert checked == len(FORMATS) - (1 if any(len(j) > 2 for j in chain.joints) else 0)


def test_a_source_without_h_takes_the_h_asked_for_and_one_with_another_is_refused():
    bricard = "0-1 1-2 2-3 3-4 4-5 5-0"
    assert read_chain(bricard, 5).chain.dof == 1 and read_chain(bricard).chain.h == 3
    row = json.dumps(Chain(6, Chain.parse(bricard).joints, h=5).to_dict())
    assert read_chain(row).chain.h == 5 and read_chain(row, 5).chain.h == 5
    with pytest.raises(MalformedChain, match="states motion space h = 5, and --h 3 was given"):
        read_chain(row, 3)
    with pytest.raises(MalformedChain, match="states motion space h = 4"):
        identify(_graph_text(4), h=6)
    (entry,) = read_text(_graph_text(4))
    assert in_motion_space(entry, 4) is entry
    with pytest.raises(MalformedChain, match="planar"):  # a prismatic pair has no place in h = 4
        read_chain("0-1 1=2 2-3 3-0", 4)


def _graph_text(h: int) -> str:
    return synth.exchange.text_of([_first(h)], "graphml")


@pytest.mark.parametrize("fmt", ("jsonl", "json", "csv", "table") + WRITTEN)
def test_identify_and_compare_read_the_listing_of_another_motion_space_back(fmt, capsys, tmp_path):
    """The issue's case: the 1-DOF 8-link chains of h = 4 written in each format come back as
    themselves: identify gives the engine's ids, compare matches all three."""
    engine = list(synth.type_synthesis(synth.ChainQuery(1, 8, h=4), workers=1))
    assert main(["chains", "--dof", "1", "--links", "8", "--h", "4", "--format", fmt, "--workers", "1"]) == 0
    path = tmp_path / f"h4.{ {'jsonl': 'jsonl', 'json': 'json', 'csv': 'csv'}.get(fmt, 'txt') }"
    path.write_text(capsys.readouterr().out)
    form = [] if fmt in ("jsonl", "json", "csv", "table") else ["--input-format", fmt]
    assert main(["identify", str(path), "--format", "jsonl", *form]) == 0
    rows = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    assert [(r["id"], r["h"], r["dof"], r["index"]) for r in rows] == [
        (chain_id(c.certificate), 4, 1, i) for i, c in enumerate(engine, start=1)]
    assert main(["compare", str(path), "--dof", "1", "--links", "8", "--h", "4", "--format", "json", *form]) == 0
    result = json.loads(capsys.readouterr().out)
    assert (result["matched"], len(result["findings"])) == (3, 0)
    assert main(["compare", str(path), "--dof", "1", "--links", "8", "--format", "json", *form]) == 0
    result = json.loads(capsys.readouterr().out)  # the same file against the plane: three extra chains, by h
    extra = [f for f in result["findings"] if f["kind"] == "extra"]
    assert len(extra) == 3 and all(f["reason"] == "loops in motion space h = 4, not 3" for f in extra)


def test_compare_reads_a_foreign_file_without_h_in_the_query_space(tmp_path, capsys):
    engine = list(synth.type_synthesis(synth.ChainQuery(1, 8, h=4), workers=1))
    path = tmp_path / "plain.txt"
    path.write_text("".join(c.compact() + "\n" for c in engine))  # joint lists state no h
    assert main(["compare", str(path), "--dof", "1", "--links", "8", "--h", "4", "--format", "json"]) == 0
    assert json.loads(capsys.readouterr().out)["matched"] == 3


def test_analyze_of_a_row_of_another_space_keeps_it(capsys):
    assert main(["chains", "--dof", "1", "--links", "8", "--h", "4", "--format", "jsonl", "--workers", "1"]) == 0
    row = capsys.readouterr().out.splitlines()[0]
    assert main(["analyze", row, "--format", "json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert (result["h"], result["dof"], result["certificate"]) == (4, 1, json.loads(row)["certificate"])
    assert main(["analyze", row, "--h", "3"]) == 2
    assert "states motion space h = 4, and --h 3 was given" in capsys.readouterr().err


@pytest.mark.parametrize("command", [["draw", "--out", "x.svg"], ["chains"]])
def test_draw_and_chains_read_a_chain_as_analyze_does(command, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    row = json.dumps(Chain(6, Chain.parse("0-1 1-2 2-3 3-4 4-5 5-0").joints, h=5).to_dict())
    assert main([*command, "--chain", row, "--h", "4"]) == 2
    assert "states motion space h = 5, and --h 4 was given" in capsys.readouterr().err
    if command == ["chains"]:
        assert main(["chains", "--chain", row, "--format", "jsonl"]) == 0
        assert json.loads(capsys.readouterr().out)["h"] == 5
