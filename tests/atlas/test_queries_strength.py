"""The ``--where`` language against the rows themselves: every field and operator selects exactly the
rows whose own values (read from each exported row, not from SQL) satisfy it; every refusal's
sentence; the mechanism rows and the summary of a small atlas counted by hand."""

from __future__ import annotations

import operator

import pytest

import synth
from synth.atlas import export, parse_where, summary
from synth.errors import InvalidOption
from synth.structure.code import Code
from tests.refusals import refused

from .helpers import grid_atlas

# four-bars and Watt/Stephenson chains (v ≤ 1), slider four-bars (1 or 2 sliders), the ring of six in h = 5,
# five-link gear trains
# and the 2-DOF chains of 7 links (one of them fractionated: two loops on one link)
GRID = ('dof = 1\nlinks = "4..6"\nv = "0..1"\n[[block]]\n[[block]]\nprismatic = "1..2"\nlinks = "4"\n'
        '[[block]]\nh = 5\nlinks = 6\nv = 0\n[[block]]\ndof = 2\nlinks = 7\nv = 0\n[[gears]]\nlinks = 5\n')


@pytest.fixture(scope="module")
def atlas(tmp_path_factory):
    return grid_atlas(tmp_path_factory.mktemp("queries") / "a.sqlite", GRID)


@pytest.fixture
def rows(atlas):
    """Every chain row, exported anew in each test (a module fixture would export once, in the first test, and a
    mutation run maps the exporting code to that test alone)."""
    return list(export(atlas))


def _base(code: str) -> str:
    c = Code.parse(code)
    return str(Code(c.assortment, c.v))


#: each field's value read from an exported row (None: the row has none, as SQL's NULL)
VALUE = {
    "code": lambda r: r["code"].split()[0], "basecode": lambda r: _base(r["code"].split()[0]),
    "W": lambda r: r["dof"], "dof": lambda r: r["dof"], "h": lambda r: r.get("h", 3),
    "n": lambda r: r["links"], "links": lambda r: r["links"], "K": lambda r: r["loops"], "loops": lambda r: r["loops"],
    "v": lambda r: r["v"], "maxdeg": lambda r: max(r["degrees"]), "max_degree": lambda r: max(r["degrees"]),
    "fractionated": lambda r: int(r["fractionated"]),
    "P": lambda r: r.get("kinds", []).count("prismatic"), "prismatic": lambda r: r.get("kinds", []).count("prismatic"),
    "G": lambda r: r.get("kinds", []).count("mesh"), "meshes": lambda r: r.get("kinds", []).count("mesh"),
    "n2": lambda r: r["degrees"].count(2), "n3": lambda r: r["degrees"].count(3), "n4": lambda r: r["degrees"].count(4),
    "carriers": lambda r: len(set(r["carriers"])) if "carriers" in r else None,
    "id": lambda r: r["id"], "certificate": lambda r: r["certificate"],
    "lever": lambda r: r.get("lever_code"), "rotation": lambda r: r.get("rotation_id"),
}
OPS = {"=": operator.eq, "==": operator.eq, "!=": operator.ne, "<": operator.lt, "<=": operator.le,
       ">": operator.gt, ">=": operator.ge}


def _ids(atlas, *where):
    return sorted(r["certificate"] for r in export(atlas, "chains", where=list(where)))


def _expected(rows, field, test):
    return sorted(r["certificate"] for r in rows if VALUE[field](r) is not None and test(VALUE[field](r)))


@pytest.mark.parametrize("field", ["W", "dof", "h", "n", "links", "K", "loops", "v", "maxdeg", "max_degree",
                                   "fractionated", "P", "prismatic", "G", "meshes", "n2", "n3", "n4", "carriers"])
def test_every_number_field_and_operator_selects_the_rows_that_satisfy_it(atlas, rows, field):
    values = sorted({VALUE[field](r) for r in rows if VALUE[field](r) is not None})
    for value in sorted({values[0], values[len(values) // 2], values[-1]}):
        for op, test in OPS.items():
            assert _ids(atlas, f"{field} {op} {value}") == _expected(rows, field, lambda x: test(x, value)), (field, op)
    low, high = values[0], values[-1]
    assert _ids(atlas, f"{field}={low}..{high}") == _expected(rows, field, lambda x: low <= x <= high)
    assert _ids(atlas, f"{field}=..{low}") == _expected(rows, field, lambda x: x <= low)
    assert _ids(atlas, f"{field}={high}..") == _expected(rows, field, lambda x: x >= high)


@pytest.mark.parametrize("field", ["code", "basecode", "lever", "rotation", "id", "certificate"])
def test_every_text_field_selects_the_rows_that_have_it(atlas, rows, field):
    values = sorted({VALUE[field](r) for r in rows if VALUE[field](r) is not None})
    assert len(values) >= 2
    for value in (values[0], values[-1]):
        assert _ids(atlas, f"{field}={value}") == _expected(rows, field, lambda x: x == value) != []
        assert _ids(atlas, f"{field} != {value}") == _expected(rows, field, lambda x: x != value) != []
    if field in ("id", "rotation", "certificate"):  # written in capitals, read in any case
        assert _ids(atlas, f"{field}={values[0].upper()}") == _expected(rows, field, lambda x: x == values[0])


def test_a_composed_code_and_its_base_code(atlas, rows):
    """A code with a joint composition (401/0-1: one joint of four links) and its base code (v counted:
    401/2), which every composition of it shares."""
    composed = sorted({VALUE["code"](r) for r in rows if "-" in r["code"]})
    assert composed
    base = _base(composed[0])
    assert _ids(atlas, f"basecode={base}") == _expected(rows, "basecode", lambda x: x == base)
    assert len(_ids(atlas, f"basecode={composed[0]}")) == len(_ids(atlas, f"basecode={base}"))
    assert base != composed[0] and _ids(atlas, f"code={base}") == []  # no chain has the base code itself


def test_kind_cell_and_fractionated_words(atlas, rows):
    gears = sorted(r["certificate"] for r in rows if r.get("kind") == "gears")
    others = sorted(r["certificate"] for r in rows if r.get("kind") != "gears")
    assert gears and others
    assert _ids(atlas, "kind=gears") == _ids(atlas, "kind != chains") == _ids(atlas, "KIND = Gears") == gears
    assert _ids(atlas, "kind=chains") == _ids(atlas, "kind!=gears") == others
    for cell in summary(atlas)["cells"]:
        assert _ids(atlas, f"cell={cell['cell']}") == sorted(r["certificate"] for r in rows if cell["cell"] in r["cells"])
    assert _ids(atlas, "fractionated=true") == _ids(atlas, "fractionated=1")
    assert _ids(atlas, "fractionated=FALSE") == _ids(atlas, "fractionated=0") == _expected(
        rows, "fractionated", lambda x: x == 0)
    assert _ids(atlas, "n=4", "v=0", "P=0", "G=0") == _expected(rows, "n", lambda x: x == 4)[:0] + sorted(
        r["certificate"] for r in rows if r["links"] == 4 and r["v"] == 0 and "kinds" not in r)
    assert len(_ids(atlas)) == len(rows) == summary(atlas)["chains"]


def test_mechanism_rows_are_those_of_each_chain(atlas, rows):
    """Four-bar: one mechanism; Watt and Stephenson: 2 and 3 (their frames up to symmetry)."""
    mechanisms = list(export(atlas, "mechanisms", where=["n=6", "v=0", "h=3"]))
    assert len(mechanisms) == 5 == sum(1 for r in rows if r["links"] == 6 and r["v"] == 0 and r.get("h", 3) == 3) + 3
    for m in mechanisms:
        chain = synth.Chain.from_dict(m)
        assert m["certificate"] == synth.Mechanism(chain, m["frame"]).certificate
        assert m["chain_id"] == synth.atlas.chain_id(m["chain_certificate"]) and "input_link" not in m
        assert m["chain_certificate"] == chain.certificate
    assert sorted(m["frame"] for m in export(atlas, "mechanisms", where=["n=4", "P=0", "G=0"])) == [0]
    with pytest.raises(InvalidOption) as info:
        export(atlas, "links")
    assert str(info.value) == "export 'chains' or 'mechanisms', not 'links'"


def test_gear_rows_carry_their_train(atlas, rows):
    for r in (r for r in rows if r.get("kind") == "gears"):
        train = synth.gears.GearTrain.parse(r["train"])
        assert r["carriers"] == list(train.carriers) and r["rotation_id"] == synth.atlas.chain_id(
            r["rotation_certificate"])
        assert r["kinds"].count("mesh") == r["meshes"] and r["lever_code"]


def test_the_summary_counts_by_hand(atlas, rows):
    info = summary(atlas)
    assert info["chains"] == len(rows) and info["units"]["done"] == info["units"]["total"] > 0
    assert info["by_code"]["4/0"] == 1 and info["by_code"]["4/0 P1"] == 1 and info["by_code"]["4/0 P2"] == 2
    assert info["by_code"]["42/0"] == 2 and info["mechanisms_by_code"]["42/0"] == 5
    assert sum(info["by_code"].values()) == len(rows)
    assert info["mechanisms"] == sum(1 for _ in export(atlas, "mechanisms")) and info["mechanisms_with_input"] == 0
    assert info["locked_by"] is None and [r["status"] for r in info["runs"]] == ["done"]
    assert {c["code"]: (c["dof"], c["h"], c["links"]) for c in info["codes"]}["42/0"] == (1, 3, 6)
    assert info["by_code"]["6/0 h=5"] == 1 and info["mechanisms_by_code"]["6/0 h=5"] == 1  # the ring: one orbit
    gears = sum(1 for r in rows if r.get("kind") == "gears")
    assert gears == sum(n for code, n in info["by_code"].items() if code.endswith(" G3")) > 0
    four = next(c for c in info["cells"] if c["cell"].endswith("p=1..2"))
    assert (four["links"], four["chains"], four["by_code"]) == (4, 3, {"4/0 P1": 1, "4/0 P2": 2})


@pytest.mark.parametrize("bad, said", [
    ("n", "cannot read the condition 'n': write FIELD OP VALUE, e.g. n=10, v<=1, code=6301/0"),
    (7, "cannot read the condition 7: write FIELD OP VALUE, e.g. n=10, v<=1, code=6301/0"),
    ("code<4/0", "a code is compared with = or != only, not '<'"),
    ("lever>=4/0", "a code is compared with = or != only, not '>='"),
    ("code=4/x", None),
    ("kind<gears", "in the condition 'kind<gears': kind is gears or chains (with = or !=)"),
    ("kind=wheels", "in the condition 'kind=wheels': kind is gears or chains (with = or !=)"),
    ("id>abc", "a chain's id is compared with = or != only, not '>'"),
    ("id=abc", "in the condition 'id=abc': a chain id is 12 hex digits (the 'id' column of a listing), not 'abc'"),
    ("rotation=xyz", "in the condition 'rotation=xyz': a rotation graph id is 12 hex digits (the 'rotation_id' "
                     "column of a listing), not 'xyz'"),
    ("cell!=a", "a cell is selected with = only"),
    ("colour=1", "unknown field 'colour' in the condition 'colour=1' (fields: code, W, h, n, K, v, P, maxdeg, "
                 "fractionated, nI such as n3, basecode, cell, id, certificate; gear trains: kind, meshes, carriers, "
                 "lever, rotation)"),
    ("n>4..6", "a range A..B goes with '=' only, not '>' (in 'n>4..6')"),
    ("n=6..4", "in the condition 'n=6..4': the range 6..4 is empty (write the smaller end first)"),
    ("n=1..9223372036854775808", "in the condition 'n=1..9223372036854775808': 1..9223372036854775808 is beyond any "
                                 "count an atlas holds (|x| < 2^63)"),
    ("n=-9223372036854775808", "in the condition 'n=-9223372036854775808': -9223372036854775808 is beyond any count "
                               "an atlas holds (|x| < 2^63)"),
    ("n=x", "in the condition 'n=x': 'x' is not a whole number or a range A..B"),
])
def test_every_refusal_says_what_is_wrong(bad, said):
    sentence = refused(InvalidOption, parse_where, [bad])
    if said is None:
        assert sentence.startswith("in the condition 'code=4/x': ")
    else:
        assert sentence == said


def test_the_largest_counts_an_atlas_holds_are_read():
    assert parse_where(["n=9223372036854775807", "v=-9223372036854775807..9223372036854775807"]) == (
        "c.links = ? AND c.v >= ? AND c.v <= ?", [2**63 - 1, -(2**63 - 1), 2**63 - 1])
    assert parse_where([]) == ("1", [])


def test_rows_say_what_each_chain_is(atlas, rows):
    assert rows == list(export(atlas, "chains"))  # chains unless asked otherwise
    two_loops = synth.Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-6 6-0")
    split = [r for r in rows if r["certificate"] == two_loops.certificate]
    assert len(split) == 1 and split[0]["fractionated"] is True
    assert all(r["fractionated"] is synth.Chain.from_dict(r).is_fractionated() for r in rows)
    assert sum(r["fractionated"] for r in rows) == 1
    info = summary(atlas)
    assert info["db"] == str(atlas) and [set(r) for r in info["runs"]] == [
        {"id", "status", "executor", "units_run", "started", "finished"}]
    assert info["runs"][0]["id"] == 1 and info["runs"][0]["started"] is not None
    ring = next(c for c in info["cells"] if c["h"] == 5)
    assert (ring["dof"], ring["links"], ring["chains"]) == (1, 6, 1) and ring["units_done"] == ring["units_total"] >= 1
    assert {c["dof"] for c in info["cells"]} == {1, 2}


def test_mechanism_rows_with_their_input_links(tmp_path):
    """The four-bar: one frame up to symmetry, and one input link for it (its two neighbours are mirror images)."""
    db = grid_atlas(tmp_path / "inputs.sqlite", "input_link = true\ndof = 1\nlinks = 4\n")
    rows = list(export(db, "mechanisms"))
    chain = synth.Chain.parse("0-1 1-2 2-3 3-0")
    assert len(rows) == len(synth.mechanisms_of(chain)) + len(synth.mechanisms_of(chain, input_link=True)) == 2
    plain, moved = rows
    assert "input_link" not in plain and moved["input_link"] in (0, 1, 2, 3) and moved["input_link"] != moved["frame"]
    m = synth.Mechanism(synth.Chain.from_dict(moved), moved["frame"], moved["input_link"])
    assert moved["certificate"] == m.certificate != plain["certificate"]
    assert summary(db)["mechanisms_with_input"] == 1
