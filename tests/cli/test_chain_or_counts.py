"""One reading of ``a=b`` words everywhere (issue 37, item 6): ``analyze``, ``identify``,
``draw --chain`` and ``chains --chain`` read ``0=1 1=2 2=3 3=0`` as the wedge loop of four
prismatic pairs; ``analyze`` reads ``2=4,3=2`` as link counts; a text both readings fit is
refused with how to write each."""

from __future__ import annotations

import itertools
import json

import pytest

from mechsynth.cli import main
from synth import Chain, MalformedChain


def _analyze(capsys, *words) -> tuple[int, dict | str]:
    status = main(["analyze", *words, "--format", "json"])
    out, err = capsys.readouterr()
    return status, (json.loads(out) if status == 0 else err.strip())


def test_a_wedge_loop_is_a_chain_in_every_command(capsys, tmp_path, monkeypatch):
    status, result = _analyze(capsys, "0=1 1=2 2=3 3=0")
    wedge = Chain.parse("0=1 1=2 2=3 3=0")
    assert status == 0 and (result["certificate"], result["dof"], result["prismatic"]) == (wedge.certificate, 2, 4)
    assert main(["identify", "0=1 1=2 2=3 3=0", "--format", "json", "--no-index"]) == 0
    assert json.loads(capsys.readouterr().out)["certificate"] == wedge.certificate
    assert main(["chains", "--chain", "0=1 1=2 2=3 3=0", "--format", "jsonl"]) == 0
    assert json.loads(capsys.readouterr().out)["certificate"] == wedge.certificate
    monkeypatch.chdir(tmp_path)
    assert main(["draw", "--chain", "0=1 1=2 2=3 3=0", "--out", "wedge.svg"]) == 0 and (tmp_path / "wedge.svg").exists()


@pytest.mark.parametrize("text, links", [("2=4", 4), ("2=4,3=2", 6), ("2=4 3=2", 6), ("1=2,2=3", 5), ("2=4,3=0", 4)])
def test_counts_stay_counts(text, links, capsys):
    status, result = _analyze(capsys, text)
    assert status == 0 and result["links"] == links and "certificate" not in result


def test_an_open_chains_code_is_a_code(capsys):
    """``2|5/2`` (an open chain: two single-joint links and five binary links, v = 2) is a code, not a chain whose
    loop classes follow a '|'; for W = 3 its nearest repair adds a binary link (``2|42/2``, as in the repair tests)."""
    status, result = _analyze(capsys, "2|5/2", "--dof", "3", "--repairs", "1")
    assert status == 0 and result["code"] == "2|5/2" and (result["links"], result["loops"]) == (7, 1)
    assert [r["code"] for r in result["repairs"]] == ["2|42/2"]


@pytest.mark.parametrize("text, counts, chain", [
    ("1=0,2=1", "'2=1'", "'0=1,2=1'"),
    ("1=0 2=1", "'2=1'", "'0=1 2=1'"),
    ("2=1 1=0 3=2", "'2=1,3=2'", "'2=1 0=1 3=2'"),
])
def test_a_text_both_readings_fit_says_how_to_write_each(text, counts, chain, capsys):
    status, message = _analyze(capsys, text)
    assert status == 2 and "reads both as link counts" in message and "\n" not in message
    assert f"without their zero counts ({counts})" in message and f"link 0 first in its joint ({chain})" in message
    for rewritten, kind in ((counts.strip("'"), "counts"), (chain.strip("'"), "chain")):
        status, result = _analyze(capsys, rewritten)  # each way of writing it reads one way only
        assert status == 0 and ("certificate" in result) == (kind == "chain")


def test_the_rule_against_both_readers_on_every_short_text():
    """Brute force over every text of one to three words a=b (a, b ≤ 3): analyze's reading is the
    chain exactly when the text parses as a chain and not as counts (I ≥ 1, each I once), counts
    in the other case, and a refusal when both or neither parse."""
    from mechsynth.commands.codes import _subject
    from synth import InvalidOption

    words = [f"{a}={b}" for a in range(4) for b in range(4)]
    for size in (1, 2, 3):
        for chosen in itertools.permutations(words, size):
            text = " ".join(chosen)
            try:
                Chain.parse(text)
                chain = True
            except MalformedChain:
                chain = False
            keys = [int(w.split("=")[0]) for w in chosen]
            counts = min(keys) >= 1 and len(set(keys)) == len(keys)
            try:
                said = _subject(text)
            except InvalidOption:
                said = None
            assert said == ("chain" if chain and not counts else "counts" if counts and not chain else None), text
