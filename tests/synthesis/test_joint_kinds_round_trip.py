"""Joint kinds belong to the chain: a row any command prints, fed back to ``analyze``, ``draw
--chain``, ``chains --chain`` and ``mechanisms --chain``, is the same chain (certificate, W, kinds);
mechanisms name their prismatic pairs as guides and swinging or floating cylinders (checked on
hand-classified cases); refusals of malformed kinds are one sentence."""

from __future__ import annotations

import json
import random

import pytest

from mechsynth.cli import main
from synth import Chain, ChainQuery, MalformedChain, mechanisms_of, type_synthesis
from synth.structure.kinds import prismatic_roles

FIG6_DRIVE = "0-1 0-3 0-4 0-5 1-2 1-8-11 2-4 2-7 3-6 3-7 5-6 8-9 9-10 10-11"


def _cli(capsys, argv):
    code = main(argv)
    out, err = capsys.readouterr()
    return code, out, err


def _rows(capsys, argv):
    code, out, err = _cli(capsys, [*argv, "--format", "jsonl"])
    assert code == 0, err
    return [json.loads(line) for line in out.splitlines()]


def _six_bar_rows(capsys):
    return _rows(capsys, ["chains", "--dof", "1", "--links", "6", "--prismatic", "0..3", "--workers", "1"])


def _fig6_rows(capsys):
    rows = _rows(capsys, ["chains", "--chain", FIG6_DRIVE, "--prismatic", "3"])
    assert len(rows) == 221
    return random.Random(6).sample(rows, 12)


@pytest.mark.parametrize("source", [_six_bar_rows, _fig6_rows], ids=["six-bars", "Fig. 6 drive"])
def test_every_row_reads_back_as_the_same_chain(capsys, tmp_path, source):
    rows = source(capsys)
    assert rows and any(r.get("kinds") for r in rows)
    for row in rows:
        text = json.dumps(row)
        # analyze reads the row: the same certificate and W
        code, out, err = _cli(capsys, ["analyze", text, "--format", "json"])
        analysed = json.loads(out)
        assert code == 0 and (analysed["certificate"], analysed["dof"]) == (row["certificate"], row["dof"]), err
        # chains --chain gives the row back (the compact joint list too, '=' for a prismatic pair)
        (again,) = _rows(capsys, ["chains", "--chain", text])
        assert (again["certificate"], again["dof"], again.get("kinds")) == (row["certificate"], row["dof"], row.get("kinds"))
        compact = Chain.from_dict(row).compact()
        assert ("=" in compact) == ("prismatic" in (row.get("kinds") or ()))
        (from_text,) = _rows(capsys, ["chains", "--chain", compact])
        assert from_text["certificate"] == row["certificate"]
        # mechanisms --chain: one row per frame orbit, each with the chain's certificate
        mechs = _rows(capsys, ["mechanisms", "--chain", compact])
        assert {m["chain_certificate"] for m in mechs} == {row["certificate"]}
    # draw --chain draws it (one drawing of the last row is enough to see it read)
    out_file = tmp_path / "row.svg"
    code, _, err = _cli(capsys, ["draw", "--chain", json.dumps(rows[-1]), "--out", str(out_file)])
    assert code == 0 and out_file.stat().st_size > 1000, err


def _roles(text: str) -> list[tuple[int, dict]]:
    chain = Chain.parse(text)
    return [(m.frame, {k: v for k, v in prismatic_roles(chain, m.frame).items() if v}) for m in mechanisms_of(chain)]


def test_slider_crank_inversions():
    """The slider-crank 0=1 0-3 1-2 2-3 has two inversions up to symmetry: the frame one of the
    slider's links (0: the pair slides on the frame, a guide) or pinned to one (2: links 1 and 0
    are binary, 1 pinned to the frame: a swinging cylinder)."""
    assert _roles("0=1 0-3 1-2 2-3") == [(0, {"guide": 1}), (2, {"swinging": 1})]


def test_watt_and_stephenson_cylinders_by_hand():
    """Watt six-bar 0-1 1-2 2-3 3-0 0-4 4-5 5-1 (ternaries 0, 1 joined directly):
    * P on 4=5 (both binary): fixed 0 — 4 is pinned to 0: swinging; fixed 2 — 4 and 5 pinned to the
      moving ternaries 0 and 1: floating; fixed 4 or 5 itself: a guide.
    * P on 0=1 (two ternaries): a guide when 0 or 1 is fixed, else a slider (block on a moving link);
      the chain's symmetry swaps its two loops and 0 with 1, so links 2…5 are one orbit.
    * P on 2=3 and 4=5: see below.
    Stephenson six-bar 0-2 2-1 0-3 3-1 0-4 4-5 5-1 (ternaries 0, 1 apart), P on 4=5: fixed 0: swinging;
    fixed 2 (or 3, its mirror image): floating; fixed 4: guide."""
    assert _roles("0-1 1-2 2-3 3-0 0-4 4=5 5-1") == [(0, {"swinging": 1}), (2, {"floating": 1}),
                                                    (4, {"guide": 1})]
    assert _roles("0=1 1-2 2-3 3-0 0-4 4-5 5-1") == [(0, {"guide": 1}), (2, {"slider": 1})]
    assert _roles("0-2 2-1 0-3 3-1 0-4 4=5 5-1") == [(0, {"swinging": 1}), (2, {"floating": 1}), (4, {"guide": 1})]
    # two cylinders on the Watt chain, one on each loop: fixed 0, both pinned to it (swinging); fixed 2
    # (its orbit is 2…5), 2=3 slides on the frame (a guide) and 4=5 is pinned to 0 and 1 (floating)
    assert _roles("0-1 1-2 2=3 3-0 0-4 4=5 5-1") == [(0, {"swinging": 2}), (2, {"guide": 1, "floating": 1})]


def test_fig6_drive_with_one_floating_and_two_swinging_cylinders():
    """Fig. 6 of the source: three revolute pairs of an 8310/1 drive (W = 3) become one floating and
    two swinging hydraulic cylinders; found by a query over every 8310/1 chain."""
    query = ChainQuery(3, code="8310/1", prismatic=3, cylinders="floating=1,swinging=2")
    first = next(iter(type_synthesis(query, workers=1)))
    found = mechanisms_of(first, cylinders=query.cylinders)
    assert first.dof == 3 and found
    for m in found:
        roles = prismatic_roles(m.chain, m.frame)
        assert (roles["floating"], roles["swinging"], roles["guide"], roles["slider"]) == (1, 2, 0, 0)


@pytest.mark.parametrize("text, words", [
    ('{"joints": [[0, 1], [1, 2], [2, 0]], "kinds": ["revolute", "spring", "revolute"]}', "joint kind 'spring'"),
    ('{"joints": [[0, 1, 2], [2, 3], [3, 0]], "kinds": ["prismatic", "revolute", "revolute"]}', "a multiple joint is a pin"),
    ("0~1 1~0 1-2 2-0", "join the same links"),
    ("0=1-2 2-0", "cannot read joint '0=1-2'"),
])
def test_malformed_kinds_are_one_sentence(capsys, text, words):
    with pytest.raises(MalformedChain, match=words.replace("(", r"\(")):
        Chain.parse(text)
    code, out, err = _cli(capsys, ["analyze", text])
    assert code == 2 and out == "" and err.count("\n") == 1 and words in err
